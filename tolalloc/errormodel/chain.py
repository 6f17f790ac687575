"""Fast exact perturbed-chain kinematics and per-sample tool-pose error features.

The perturbed chain of :meth:`ErrorModel.perturbed_chain` is the product
``G_0 E_1 G_1 ... E_n G_n M`` of error displacements ``G_s`` (exponentials of
the parameters' twists) and joint exponentials ``E_j = exp([S_j](q_j + dq_j))``.
:class:`FastChain` evaluates it right to left, in place, on a structure-of-arrays
``(3, 4, N)`` block (rows of ``[R | p]``) with closed-form exponentials: a rotation
about a base axis mixes only the two rows it touches, a pure translation only adds
to ``p``, a factor whose amount is a constant is applied with scalars (and skipped
when it is the identity). ``cos`` is taken as ``sqrt(1 - sin^2)`` when every angle
of the block lies in ``[-1, 1]`` rad (exact to rounding, a third of the cost).
It equals the generic ``fk_poe`` path to rounding (tested to 1e-9).

:class:`ErrorFeatures` turns chain outputs into the Monte Carlo features with one
small matrix product (every feature's linear part) and a few element-wise passes;
Euler-angle errors are taken as ``atan2`` of the rotated pair, which wraps the
difference to ``(-pi, pi]`` without a modulo.
"""

from __future__ import annotations

import numpy as np

from tolalloc.errormodel.model import ErrorModel
from tolalloc.robot.lie import euler_xyz_fixed, hat

__all__ = ["FastChain", "ErrorFeatures", "FEATURES"]

#: Rows of the feature matrix returned by :meth:`ErrorFeatures.compute` [mm, rad].
FEATURES = ("dx", "dy", "dz", "rvx", "rvy", "rvz", "norm", "reach", "alpha", "beta", "gamma")
_FIRST = 7  # feature rows start here in the work buffer (rows 0-6 are intermediate)
N_BUF = _FIRST + len(FEATURES)


class FastChain:
    """Exact perturbed-chain kinematics of an :class:`ErrorModel`, vectorised over samples.

    Parameters
    ----------
    model : ErrorModel
    """

    def __init__(self, model: ErrorModel):
        robot = model.robot
        n = robot.n_joints
        self.model = model
        self.K = len(model.params)
        drives = [[] for _ in range(n)]
        inserts = [[] for _ in range(n + 1)]  # same order as ErrorModel.perturbed_chain
        for k, p in enumerate(model.params):
            if p.kind == "joint_drive":
                drives[p.joint_index].append(k)
                continue
            inserts[p.site].append((np.asarray(p.twist, float), k, 1.0))
            if p.undo_site is not None:
                inserts[p.undo_site].insert(0, (np.asarray(p.twist, float), k, -1.0))
        factors = []  # left to right: (twist, joint index or None, [(k, sign), ...])
        for s in range(n + 1):
            for twist, k, sign in inserts[s]:
                factors.append((twist, None, [(k, sign)]))
            if s < n:
                factors.append((np.asarray(robot.screws[s], float), s, [(k, 1.0) for k in drives[s]]))
        self.factors = [self._prepare(*f) for f in factors]
        self.home = np.asarray(robot.home, float)

    @staticmethod
    def _prepare(twist, joint, sources):
        w, v = twist[:3], twist[3:]
        nw = float(np.linalg.norm(w))
        if nw < 1e-15:
            nv = float(np.linalg.norm(v))
            return {"kind": "trans", "v": v / nv if nv > 0 else v, "scale": nv, "joint": joint, "src": sources}
        w, v = w / nw, v / nw
        axis = None
        big = int(np.argmax(np.abs(w)))
        if abs(abs(w[big]) - 1.0) < 1e-15:  # base axis x, y or z (sign sg): rows (a, b) rotate
            axis = ((big + 1) % 3, (big + 2) % 3, 1.0 if w[big] > 0 else -1.0)
        return {"kind": "rot", "w": w, "r0": np.cross(w, v), "h": float(w @ v), "scale": nw,
                "A": hat(w), "joint": joint, "src": sources, "axis": axis}

    # ------------------------------------------------------------- programs
    def program(self, q: np.ndarray, mult: np.ndarray | None = None) -> list:
        """Factors right to left with their amounts ``const + sum(coef_k V[k])`` at pose ``q``.

        ``mult`` (K,) scales the value rows (e.g. sigma for standard-normal rows); a source
        with ``mult == 0`` is dropped, an identity factor is skipped.
        """
        prog = []
        for f in reversed(self.factors):
            const = float(q[f["joint"]]) * f["scale"] if f["joint"] is not None else 0.0
            coefs = []
            for k, sign in f["src"]:
                m = 1.0 if mult is None else float(mult[k])
                if m != 0.0:
                    coefs.append((k, sign * f["scale"] * m))
            if not coefs and const == 0.0:
                continue
            prog.append((f, const, tuple(coefs)))
        return prog

    @staticmethod
    def _amount(const, coefs, V, th):
        if len(coefs) == 1 and const == 0.0 and coefs[0][1] == 1.0:
            return V[coefs[0][0]]
        k, cf = coefs[0]
        np.multiply(V[k], cf, out=th)
        for k, cf in coefs[1:]:
            th += V[k] * cf
        if const != 0.0:
            th += const
        return th

    def run(self, prog: list, V: np.ndarray, X: np.ndarray, work: dict) -> np.ndarray:
        """Evaluate a :meth:`program` on values ``V`` (K, N) into ``X`` (3, 4, N), in place.

        ``work`` holds scratch arrays ``t1, t2`` (4, N) and ``th, s, c`` (N,) (see :meth:`workspace`).
        """
        N = X.shape[2]
        for i in range(3):
            X[i] = self.home[i, :, None]
        th_buf, s, c, t1, t2 = work["th"][:N], work["s"][:N], work["c"][:N], work["t1"][:, :N], work["t2"][:, :N]
        off = [0.0, 0.0, 0.0]  # lazy shift of p: the pose is X with off added to column 3
        for f, const, coefs in prog:
            if coefs:
                th = self._amount(const, coefs, V, th_buf)
            else:
                th = const
            if f["kind"] == "trans":
                for i in range(3):
                    vi = f["v"][i]
                    if vi == 0.0:
                        continue
                    if vi == 1.0 or not coefs:
                        X[i, 3] += th if vi == 1.0 else th * vi
                    else:
                        np.multiply(th, vi, out=c)
                        X[i, 3] += c
                continue
            if coefs:
                np.sin(th, out=s)
                if th.max() <= 1.0 and th.min() >= -1.0:
                    np.multiply(s, s, out=c)
                    np.subtract(1.0, c, out=c)
                    np.sqrt(c, out=c)
                else:
                    np.cos(th, out=c)
                ss, cc = s, c
            else:
                ss, cc = np.sin(th), np.cos(th)
            r0 = f["r0"]
            if f["axis"] is not None:
                a, b, sg = f["axis"]
                Xa, Xb = X[a], X[b]
                for r in (a, b):  # shift p so that it is relative to the axis point r0
                    if off[r] != r0[r]:
                        X[r, 3] += off[r] - r0[r]
                        off[r] = r0[r]
                np.multiply(Xa, ss, out=t1)
                np.multiply(Xb, ss, out=t2)
                Xa *= cc
                Xb *= cc
                if sg > 0:
                    Xa -= t2
                    Xb += t1
                else:
                    Xa += t2
                    Xb -= t1
            else:  # general axis: R = I + s A + (1 - c) A^2 applied to the rows, p about r0
                A = f["A"]
                B = A @ A
                Y = X.copy()
                for j in range(3):
                    Y[j, 3] += off[j] - r0[j]
                    off[j] = 0.0
                for i in range(3):
                    row = None
                    for j in range(3):
                        cij = (1.0 if i == j else 0.0) + B[i, j] + A[i, j] * ss - B[i, j] * cc
                        term = Y[j] * cij
                        row = term if row is None else row + term
                    X[i] = row
                    X[i, 3] += r0[i]
            if f["h"] != 0.0:
                for i in range(3):
                    if f["w"][i] != 0.0:
                        X[i, 3] += (f["h"] * f["w"][i]) * th
        for i in range(3):
            if off[i] != 0.0:
                X[i, 3] += off[i]
        return X

    @staticmethod
    def workspace(N: int) -> dict:
        """Scratch arrays for :meth:`run` on up to ``N`` samples."""
        return {"th": np.empty(N), "s": np.empty(N), "c": np.empty(N), "t1": np.empty((4, N)), "t2": np.empty((4, N))}

    def pose(self, q: np.ndarray, values: np.ndarray, *, transposed: bool = False) -> np.ndarray:
        """Perturbed tool poses as rows of ``[R | p]``.

        Parameters
        ----------
        q : array, shape (n,) [rad, mm]
        values : array, shape (N, K) [mm, rad], or (K, N) if ``transposed``

        Returns
        -------
        X : array, shape (3, 4, N); ``X[i, j, m]`` is ``T'[i, j]`` of sample ``m``.
        """
        V = values if transposed else np.ascontiguousarray(values.T)
        N = V.shape[1]
        X = np.empty((3, 4, N))
        return self.run(self.program(np.asarray(q, float)), V, X, self.workspace(N))


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
