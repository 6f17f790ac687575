"""Product-of-exponentials kinematics of serial chains: prefix products, forward kinematics, Jacobians.

Plain functions on arrays (screw axes ``(omega, v)`` in the space frame, one per row; joint values
[rad, mm]); everything broadcasts over leading dimensions, so one chain at many configurations and a
stack of perturbed chains (Monte Carlo) go through the same code. :class:`tolalloc.robot.model.Robot` wraps
them for a robot's own screws and home pose.
"""

from __future__ import annotations

import numpy as np

from tolalloc.engine import resolve_engine
from tolalloc.exceptions import TolallocError, describe
from tolalloc.robot.lie import _rodrigues, adjoint, cross, exp_se3, exp_se3_rp, inv_transform

__all__ = [
    "fk_poe",
    "poe_prefix",
    "poe_prefix_rp",
    "space_jacobian",
    "body_jacobian",
    "JAC_KERNEL_MIN_POSES",
    "prefix_lists",
    "jacobian_kernel",
    "compiled_prefix",
]


def _floats(value):
    """``value`` as a float array, or None when it is not numbers (bools and strings are not)."""
    if value is None or isinstance(value, (str, bytes, dict)):
        return None
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        return None
    kind = np.asarray(value).dtype.kind if not isinstance(value, np.ndarray) else value.dtype.kind
    if kind in "bSU" or (kind == "O" and any(isinstance(v, (bool, np.bool_, str, bytes))
                                             for v in np.asarray(value, dtype=object).ravel()[:10**5])):
        return None
    return arr


def _screws_and_q(screws, q) -> tuple[np.ndarray, np.ndarray]:
    """``screws`` (..., n, 6) and ``q`` (..., n) as finite float arrays whose stacks broadcast; anything else is
    refused with what was expected."""
    S, Q = _floats(screws), _floats(q)
    n = S.shape[-2] if S is not None and S.ndim >= 2 else "n"
    shapes = f"q of shape {None if Q is None else Q.shape} and screws of shape {None if S is None else S.shape}"
    if S is None or Q is None or S.ndim < 2 or S.shape[-1] != 6 or Q.ndim == 0 or Q.shape[-1] != S.shape[-2] \
            or not _broadcast(S.shape[:-2], Q.shape[:-1]):
        raise TolallocError(f"q: expected shape (..., {n}) with joint screws of shape (..., {n}, 6), got {shapes}; one "
                            "joint value per screw, in rad and mm (numbers; the stacks must broadcast)")
    if not (np.all(np.isfinite(S)) and np.all(np.isfinite(Q))):
        raise TolallocError(f"q: expected finite joint values and screws, got NaN or inf in {shapes}.")
    return S, Q


def _broadcast(*shapes) -> bool:
    try:
        np.broadcast_shapes(*shapes)
    except ValueError:
        return False
    return True


def _home(home, batch: tuple) -> np.ndarray:
    """``home`` (..., 4, 4): a finite homogeneous transform (stack) whose stack broadcasts with ``batch``."""
    M = _floats(home)
    if M is None or M.ndim < 2 or M.shape[-2:] != (4, 4) or not np.all(np.isfinite(M)) \
            or not _broadcast(M.shape[:-2], batch):
        raise TolallocError(f"home: expected a finite homogeneous transform of shape (..., 4, 4) whose stack "
                            f"broadcasts with the joint values' {batch}, got {describe(home)}.")
    return M


def _joint_exp_rp(screws: np.ndarray, q: np.ndarray):
    """``exp([S] q)`` as (R, p) for joint screws, shapes (..., n, 3, 3) and (..., n, 3).

    Joint screws have a unit (revolute) or zero (prismatic) angular part, which allows the closed form
    ``R = cos q I + sin q [w] + (1 - cos q) w w^T``, ``p = (I - R)(w x v) + w (w . v) q`` (prismatic:
    ``R = I``, ``p = v q``) without the small-angle series of a general twist; other screws take
    :func:`~tolalloc.robot.lie.exp_se3_rp`.
    """
    w, v = screws[..., :3], screws[..., 3:]
    w2 = np.sum(w * w, axis=-1)
    if not np.all((np.abs(w2 - 1.0) < 1e-12) | (w2 == 0.0)):
        return exp_se3_rp(screws * q[..., None])
    th = q * np.sqrt(w2)
    s, c = np.sin(th), np.cos(th)
    R = _rodrigues(w, np.sqrt(w2), s, 1.0 - c)  # c I + s [w] + (1 - c) w w^T for |w| = 1; I for w = 0
    u = cross(w, v)
    p = ((1.0 - c)[..., None] * u - s[..., None] * cross(w, u)
         + (np.sum(w * v, axis=-1) * q)[..., None] * w + ((1.0 - w2) * q)[..., None] * v)
    return R, p


def prefix_lists(screws, q):
    """Cumulative products as lists of contiguous arrays: ``R[j]`` (..., 3, 3), ``p[j]`` (..., 3), j = 0..n."""
    screws, q = _screws_and_q(screws, q)
    ER, Ep = _joint_exp_rp(screws, q)  # (..., n, 3, 3), (..., n, 3)
    batch = ER.shape[:-3]
    R = [np.broadcast_to(np.eye(3), batch + (3, 3))]
    p = [np.zeros(batch + (3,))]
    for j in range(ER.shape[-3]):
        R.append(R[j] @ ER[..., j, :, :])
        p.append((R[j] @ Ep[..., j, :, None])[..., 0] + p[j])
    return R, p


def poe_prefix_rp(screws, q) -> tuple[np.ndarray, np.ndarray]:
    """Rotations and translations of the cumulative products ``P_j`` of :func:`poe_prefix`.

    Returns
    -------
    R : array, shape (..., n + 1, 3, 3)
    p : array, shape (..., n + 1, 3)  [mm]
    """
    R, p = prefix_lists(screws, q)
    return np.stack(R, axis=-3), np.stack(p, axis=-2)


def poe_prefix(screws, q) -> np.ndarray:
    """Cumulative products ``P_j = exp([S_1]q_1) ... exp([S_j]q_j)`` for ``j = 0..n``.

    Parameters
    ----------
    screws : array, shape (..., n, 6)
        Space screw axes (a stack of perturbed chains is allowed).
    q : array, shape (..., n)  [rad, mm]

    Returns
    -------
    P : array, shape (..., n + 1, 4, 4), ``P[..., 0] = I``.
    """
    R, p = poe_prefix_rp(screws, q)
    P = np.zeros(R.shape[:-2] + (4, 4))
    P[..., :3, :3] = R
    P[..., :3, 3] = p
    P[..., 3, 3] = 1.0
    return P


def fk_poe(screws, home, q) -> np.ndarray:
    """Space-frame POE forward kinematics ``T = exp([S1]q1) ... exp([Sn]qn) M``.

    Everything broadcasts: one chain at many configurations, or ``N`` perturbed
    chains (per-sample screws and home poses) at one or ``N`` configurations.

    Parameters
    ----------
    screws : array, shape (..., n, 6)
    home : array, shape (..., 4, 4)
    q : array, shape (..., n)  [rad, mm]

    Returns
    -------
    T : array, shape (..., 4, 4)
    """
    screws, q = _screws_and_q(screws, q)
    batch = np.broadcast_shapes(screws.shape[:-2], q.shape[:-1])
    home = _home(home, batch)
    if screws.shape[-2] == 0:  # a chain without joints: the home pose
        return np.array(np.broadcast_to(home, np.broadcast_shapes(batch, home.shape[:-2]) + (4, 4)))
    E = exp_se3(screws * q[..., None])
    T = E[..., 0, :, :]
    for j in range(1, E.shape[-3]):
        T = T @ E[..., j, :, :]
    return T @ home


#: Poses from which the default engine uses the compiled Jacobian kernels (below: numpy, no JIT-call overhead).
JAC_KERNEL_MIN_POSES = 64


def compiled_prefix():
    """The compiled (numba) prefix products, for other compiled kernels to call (imports numba):
    ``prefix(S (n, 6), q (n,), R (n + 1, 3, 3), p (n + 1, 3))`` fills ``R[j]``, ``p[j]`` of :func:`poe_prefix_rp`
    at one pose, for screws with unit or zero angular parts (the closed form of the numpy path, same operations)."""
    from tolalloc.robot import _jacobian_nb

    return _jacobian_nb._prefix


def jacobian_kernel(screws: np.ndarray, q: np.ndarray, engine: str | None):
    """:mod:`tolalloc.robot._jacobian_nb` when ``engine`` resolves to numba, ``screws`` is one chain (n, 6) with unit
    or zero angular parts and ``q`` is (P, n) with P >= :data:`JAC_KERNEL_MIN_POSES` (any P for
    ``engine="numba"``); else ``None`` (numpy path)."""
    if resolve_engine(engine) != "numba" or screws.ndim != 2 or screws.shape[1] != 6 or q.ndim != 2:
        return None
    if q.shape[1] != screws.shape[0] or (engine != "numba" and q.shape[0] < JAC_KERNEL_MIN_POSES):
        return None
    w2 = np.sum(screws[:, :3] * screws[:, :3], axis=-1)
    if not np.all((np.abs(w2 - 1.0) < 1e-12) | (w2 == 0.0)):  # as _joint_exp_rp's closed form
        return None
    from tolalloc.robot import _jacobian_nb

    return _jacobian_nb


def space_jacobian(screws, q, *, engine: str | None = None) -> np.ndarray:
    """Space Jacobian ``J_s`` with columns ``Ad_{P_{j-1}} S_j``.

    Parameters
    ----------
    screws : array, shape (..., n, 6)
    q : array, shape (..., n)
    engine : {None, "auto", "numba", "numpy"}
        As :func:`tolalloc.engine.resolve_engine`; the compiled kernel runs for one chain (n, 6) of joint
        screws at many poses (P, n), P >= :data:`JAC_KERNEL_MIN_POSES` unless ``engine="numba"``.

    Returns
    -------
    J : array, shape (..., 6, n); the spatial twist of the end effector is ``J @ qdot``.
    """
    screws, q = _screws_and_q(screws, q)
    nb = jacobian_kernel(screws, q, engine)
    if nb is not None:
        return nb.space_jacobian(screws, q)
    R, p = prefix_lists(screws, q)
    if screws.shape[-2] == 0:  # a chain without joints: no column
        return np.zeros(np.broadcast_shapes(screws.shape[:-2], q.shape[:-1]) + (6, 0))
    cols = []
    for j in range(screws.shape[-2]):  # Ad_{P_j} S_j = (R w, R v + p x R w)
        rw = (R[j] @ screws[..., j, :3, None])[..., 0]
        rv = (R[j] @ screws[..., j, 3:, None])[..., 0]
        cols.append(np.concatenate([rw, rv + np.cross(p[j], rw)], axis=-1))
    return np.stack(cols, axis=-1)


def body_jacobian(screws, home, q) -> np.ndarray:
    """Body Jacobian ``J_b = Ad_{T^-1} J_s``, shape (..., 6, n)."""
    T = fk_poe(screws, home, q)
    return adjoint(inv_transform(T)) @ space_jacobian(screws, q)
