"""Per-sample tool-pose error features of perturbed poses, for both Monte Carlo engines.

:class:`ErrorFeatures` turns chain outputs (rows of ``[R | p]``, shape (3, 4, N), as evaluated by
:class:`tolalloc.errormodel.chain.FastChain`) into the Monte Carlo features with one small matrix product
(every feature's linear part) and a few element-wise passes; Euler-angle errors are taken as ``atan2`` of the
rotated pair, which wraps the difference to ``(-pi, pi]`` without a modulo. :meth:`ErrorFeatures.constants` is
the same per-pose data as plain numbers for the compiled kernel of :mod:`tolalloc.montecarlo.engines`.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.lie import euler_xyz_fixed

__all__ = ["ErrorFeatures", "FEATURES", "N_BUF", "features_to_dict"]

#: Rows of the feature matrix returned by :meth:`ErrorFeatures.compute` [mm, rad].
FEATURES = ("dx", "dy", "dz", "rvx", "rvy", "rvz", "norm", "reach", "alpha", "beta", "gamma")
_FIRST = 7  # feature rows start here in the work buffer (rows 0-6 are intermediate)
N_BUF = _FIRST + len(FEATURES)


class ErrorFeatures:
    """Per-sample tool-pose error features of perturbed poses relative to a nominal pose.

    Parameters
    ----------
    T0 : array, shape (4, 4)
        Nominal tool pose [mm].

    Notes
    -----
    :meth:`compute` returns the rows of :data:`FEATURES`: ``dx, dy, dz`` = ``p' - p`` [mm]; the
    rotation vector of ``R' R^T`` [rad]; ``|p' - p|``; the reach change ``|p'| - |p|`` [mm]; and the
    X-Y-Z fixed Euler-angle errors ``euler(R') - euler(R)`` [rad] (alpha, gamma wrapped to (-pi, pi]).
    """

    def __init__(self, T0: np.ndarray):
        T0 = np.asarray(T0, float)
        R0, p0 = T0[:3, :3], T0[:3, 3]
        self.R0, self.p0 = R0, p0
        self.r0 = float(np.linalg.norm(p0))
        a0, self.b0, g0 = euler_xyz_fixed(R0)
        L = np.zeros((13, 3, 4))
        L[0, :, 3] = p0  # p0 . p'
        ca, sa, cg, sg = np.cos(a0), np.sin(a0), np.cos(g0), np.sin(g0)
        L[1, 2, 1], L[1, 2, 2] = ca, -sa  # cos(b) sin(a - a0)
        L[2, 2, 2], L[2, 2, 1] = ca, sa  # cos(b) cos(a - a0)
        L[3, 1, 0], L[3, 0, 0] = cg, -sg  # cos(b) sin(g - g0)
        L[4, 0, 0], L[4, 1, 0] = cg, sg  # cos(b) cos(g - g0)
        L[5, 2, 0] = -1.0  # sin(b)
        L[6, :, :3] = R0  # trace(R' R0^T)
        for i in range(3):
            L[7 + i, i, 3] = 1.0
        for row, (i, j) in zip((10, 11, 12), ((2, 1), (0, 2), (1, 0))):  # antisymmetric part of E = R' R0^T
            L[row, i, :3] += 0.5 * R0[j]
            L[row, j, :3] -= 0.5 * R0[i]
        self.L = L.reshape(13, 12)

    def constants(self) -> np.ndarray:
        """The nominal pose as the compiled kernel's constants, shape (20,).

        ``[p0 (3), r0^2, r0, R0 (9, row-major), cos a0, sin a0, cos g0, sin g0, b0, 0]`` with ``(a0, b0, g0)``
        the X-Y-Z fixed Euler angles of ``R0``.
        """
        a0, _, g0 = euler_xyz_fixed(self.R0)
        c = np.zeros(20)
        c[:3] = self.p0
        c[3], c[4] = self.r0**2, self.r0
        c[5:14] = self.R0.ravel()
        c[14:19] = (np.cos(a0), np.sin(a0), np.cos(g0), np.sin(g0), self.b0)
        return c

    def compute(self, X: np.ndarray, buf: np.ndarray, tmp: np.ndarray) -> np.ndarray:
        """Features of chain outputs ``X`` (3, 4, N), written into ``buf`` (N_BUF, >= N); returns the (11, N) view.

        ``tmp`` is scratch of shape (2, >= N).
        """
        N = X.shape[2]
        B = buf[:, :N]
        t, u = tmp[0, :N], tmp[1, :N]
        np.matmul(self.L, X.reshape(12, N), out=B[:13])
        for i in range(3):
            B[7 + i] -= self.p0[i]
        B[0] -= self.r0**2  # dp . p0
        n2 = B[13]
        np.multiply(B[7], B[7], out=n2)
        for i in (8, 9):
            np.multiply(B[i], B[i], out=t)
            n2 += t
        num = B[0]
        num *= 2.0
        num += n2  # |p'|^2 - |p|^2
        if self.r0 > 0:
            np.add(num, self.r0**2, out=t)
            np.sqrt(t, out=t)
            t += self.r0
            np.divide(num, t, out=B[14])
        else:
            np.sqrt(num, out=B[14])
        np.sqrt(n2, out=n2)
        np.arctan2(B[1], B[2], out=B[15])
        np.arctan2(B[3], B[4], out=B[17])
        np.multiply(B[3], B[3], out=t)
        np.multiply(B[4], B[4], out=u)
        t += u
        np.sqrt(t, out=t)
        np.arctan2(B[5], t, out=B[16])
        B[16] -= self.b0
        v = B[10:13]
        np.multiply(v[0], v[0], out=t)
        for i in (1, 2):
            np.multiply(v[i], v[i], out=u)
            t += u
        np.sqrt(t, out=t)  # sin(theta)
        cosv = B[5]
        np.subtract(B[6], 1.0, out=cosv)
        cosv *= 0.5
        theta = B[6]
        np.arctan2(t, cosv, out=theta)
        u.fill(1.0)
        np.divide(theta, t, out=u, where=t > 1e-300)
        v *= u
        if cosv.min() < -0.999:  # near pi the antisymmetric part loses the axis: use scipy there
            from scipy.spatial.transform import Rotation

            bad = np.flatnonzero(cosv < -0.999)
            E = np.einsum("ikn,jk->nij", X[:, :3, bad], self.R0)
            rv = Rotation.from_matrix(E).as_rotvec()
            v[:, bad] = rv.T
            theta[bad] = np.linalg.norm(rv, axis=1)
        return B[_FIRST:]

    @staticmethod
    def angle_row(buf: np.ndarray, N: int) -> np.ndarray:
        """``|rotation vector|`` [rad] of the last :meth:`compute` (valid until the buffer is reused)."""
        return buf[6, :N]


def features_to_dict(F: np.ndarray) -> dict[str, np.ndarray]:
    """Split a feature matrix (11, N) into the per-sample arrays of :func:`tolalloc.montecarlo.run.pose_errors`."""
    return {"dp_mm": F[0:3].T.copy(), "norm_mm": F[6].copy(), "reach_mm": F[7].copy(),
            "euler_rad": F[8:11].T.copy(), "rotvec_rad": F[3:6].T.copy()}
