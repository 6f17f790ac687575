"""Rigid-body algebra: SO(3)/SE(3) hats, exponentials, adjoints, Euler angles.

Conventions (as in Lynch & Park, *Modern Robotics*):

* a twist or screw is ``(omega, v)`` -- angular part first -- shape ``(..., 6)``;
* lengths are in mm, angles in rad;
* every function broadcasts over leading dimensions, so a stack of ``N``
  twists or transforms is processed without a Python loop.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = [
    "cross",
    "hat",
    "exp_so3",
    "exp_se3",
    "exp_se3_rp",
    "adjoint",
    "inv_transform",
    "euler_xyz_fixed",
    "rotvec",
    "rot_x",
    "rot_y",
    "rot_z",
    "transform",
]


def cross(a: np.ndarray, b: np.ndarray, axis: int = -1) -> np.ndarray:
    """``a x b`` over the 3-vector axis ``axis`` (negative: counted from the end), broadcasting as :func:`numpy.cross`.

    Parameters
    ----------
    a, b : array, shape (..., 3) for ``axis=-1``; (..., 3, K) for ``axis=-2`` (K vectors as columns)
    axis : int, negative

    Returns
    -------
    array, the broadcast shape with the 3-vector at ``axis``

    The kinematics, error and load models call it many thousand times on small stacks, where :func:`numpy.cross`'s
    axis handling costs about twice the arithmetic.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    tail = (slice(None),) * (-axis - 1)
    a0, a1, a2 = (a[(Ellipsis, i) + tail] for i in range(3))
    b0, b1, b2 = (b[(Ellipsis, i) + tail] for i in range(3))
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=axis)


def hat(w: np.ndarray) -> np.ndarray:
    """Skew-symmetric matrix ``[w]`` of a 3-vector.

    Parameters
    ----------
    w : array, shape (..., 3)

    Returns
    -------
    W : array, shape (..., 3, 3), with ``W @ x == cross(w, x)``.
    """
    w = np.asarray(w, dtype=float)
    W = np.zeros(w.shape[:-1] + (3, 3))
    W[..., 0, 1] = -w[..., 2]
    W[..., 0, 2] = w[..., 1]
    W[..., 1, 0] = w[..., 2]
    W[..., 1, 2] = -w[..., 0]
    W[..., 2, 0] = -w[..., 1]
    W[..., 2, 1] = w[..., 0]
    return W


def _sinc_terms(theta: np.ndarray):
    """Return ``sin(t)/t``, ``(1-cos t)/t^2`` and ``(t - sin t)/t^3``, safe near 0."""
    small = theta < 1e-4
    t = np.where(small, 1.0, theta)
    t2 = theta * theta
    a = np.where(small, 1.0 - t2 / 6.0 + t2 * t2 / 120.0, np.sin(t) / t)
    b = np.where(small, 0.5 - t2 / 24.0 + t2 * t2 / 720.0, (1.0 - np.cos(t)) / (t * t))
    c = np.where(small, 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0, (t - np.sin(t)) / (t * t * t))
    return a, b, c


def _rodrigues(w: np.ndarray, theta: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``I + a [w] + b [w]^2`` using ``[w]^2 = w w^T - |w|^2 I`` (no matrix products), shape (..., 3, 3)."""
    M = (b[..., None, None] * w[..., :, None]) * w[..., None, :]
    d = 1.0 - b * theta * theta
    M[..., 0, 0] += d
    M[..., 1, 1] += d
    M[..., 2, 2] += d
    aw = a[..., None] * w
    M[..., 0, 1] -= aw[..., 2]
    M[..., 0, 2] += aw[..., 1]
    M[..., 1, 0] += aw[..., 2]
    M[..., 1, 2] -= aw[..., 0]
    M[..., 2, 0] -= aw[..., 1]
    M[..., 2, 1] += aw[..., 0]
    return M


def exp_so3(w: np.ndarray) -> np.ndarray:
    """Rotation matrix ``exp([w])`` of a rotation vector (Rodrigues).

    Parameters
    ----------
    w : array, shape (..., 3)  [rad]

    Returns
    -------
    R : array, shape (..., 3, 3)
    """
    w = np.asarray(w, dtype=float)
    theta = np.linalg.norm(w, axis=-1)
    a, b, _ = _sinc_terms(theta)
    return _rodrigues(w, theta, a, b)


def exp_se3_rp(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotation and translation of ``exp([xi])`` for twists ``xi = (omega, v)``.

    Parameters
    ----------
    xi : array, shape (..., 6)  [rad, mm]

    Returns
    -------
    R : array, shape (..., 3, 3)
    p : array, shape (..., 3)  [mm], ``p = V v`` with ``V = I + b [w] + c [w]^2``.
    """
    xi = np.asarray(xi, dtype=float)
    w, v = xi[..., :3], xi[..., 3:]
    theta = np.linalg.norm(w, axis=-1)
    a, b, c = _sinc_terms(theta)
    R = _rodrigues(w, theta, a, b)
    wv = np.sum(w * v, axis=-1)
    p = (1.0 - c * theta * theta)[..., None] * v + b[..., None] * cross(w, v) + (c * wv)[..., None] * w
    return R, p


def exp_se3(xi: np.ndarray) -> np.ndarray:
    """Homogeneous transform ``exp([xi])`` of a twist ``xi = (omega, v)``.

    For a screw axis ``S`` and joint value ``q`` pass ``xi = S * q``.

    Parameters
    ----------
    xi : array, shape (..., 6)  [rad, mm]

    Returns
    -------
    T : array, shape (..., 4, 4)
    """
    xi = np.asarray(xi, dtype=float)
    R, p = exp_se3_rp(xi)
    T = np.zeros(xi.shape[:-1] + (4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = p
    T[..., 3, 3] = 1.0
    return T


def inv_transform(T: np.ndarray) -> np.ndarray:
    """Inverse of homogeneous transforms, shape (..., 4, 4)."""
    T = np.asarray(T, dtype=float)
    R = T[..., :3, :3]
    p = T[..., :3, 3]
    Ti = np.zeros_like(T)
    Rt = np.swapaxes(R, -1, -2)
    Ti[..., :3, :3] = Rt
    Ti[..., :3, 3] = -np.einsum("...ij,...j->...i", Rt, p)
    Ti[..., 3, 3] = 1.0
    return Ti


def adjoint(T: np.ndarray) -> np.ndarray:
    """Adjoint map ``Ad_T`` (6x6) acting on twists ``(omega, v)``.

    Parameters
    ----------
    T : array, shape (..., 4, 4)

    Returns
    -------
    Ad : array, shape (..., 6, 6), ``[[R, 0], [[p] R, R]]``.
    """
    T = np.asarray(T, dtype=float)
    R = T[..., :3, :3]
    p = T[..., :3, 3]
    Ad = np.zeros(T.shape[:-2] + (6, 6))
    Ad[..., :3, :3] = R
    Ad[..., 3:, 3:] = R
    Ad[..., 3:, :3] = hat(p) @ R
    return Ad


def transform(R: np.ndarray | None = None, p: np.ndarray | None = None) -> np.ndarray:
    """Build a 4x4 homogeneous transform from a rotation (3x3) and a translation (3,)."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if p is not None:
        T[:3, 3] = p
    return T


def rot_x(angle: float) -> np.ndarray:
    """Rotation by ``angle`` [rad] about x, shape (3, 3)."""
    return exp_so3(np.array([angle, 0.0, 0.0]))


def rot_y(angle: float) -> np.ndarray:
    """Rotation by ``angle`` [rad] about y, shape (3, 3)."""
    return exp_so3(np.array([0.0, angle, 0.0]))


def rot_z(angle: float) -> np.ndarray:
    """Rotation by ``angle`` [rad] about z, shape (3, 3)."""
    return exp_so3(np.array([0.0, 0.0, angle]))


def euler_xyz_fixed(R: np.ndarray) -> np.ndarray:
    """X-Y-Z fixed-axis Euler angles ``(alpha, beta, gamma)`` of rotations.

    ``R = Rz(gamma) @ Ry(beta) @ Rx(alpha)`` (rotate about the fixed x, then the
    fixed y, then the fixed z axis), the convention of the seed paper.

    Parameters
    ----------
    R : array, shape (..., 3, 3)

    Returns
    -------
    angles : array, shape (..., 3)  [rad]
    """
    R = np.asarray(R, dtype=float)
    beta = np.arctan2(-R[..., 2, 0], np.hypot(R[..., 0, 0], R[..., 1, 0]))
    alpha = np.arctan2(R[..., 2, 1], R[..., 2, 2])
    gamma = np.arctan2(R[..., 1, 0], R[..., 0, 0])
    return np.stack([alpha, beta, gamma], axis=-1)


def rotvec(R: np.ndarray) -> np.ndarray:
    """Rotation vector (axis times angle, [rad]) of rotations, shape (..., 3, 3) -> (..., 3)."""
    R = np.asarray(R, dtype=float)
    flat = R.reshape(-1, 3, 3)
    out = Rotation.from_matrix(flat).as_rotvec()
    return out.reshape(R.shape[:-2] + (3,))
