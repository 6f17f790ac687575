"""The calibration fit at scale: chunked normal equations, vectorised kinematics, subsampling.

The measurement model of :mod:`.calibrate` (``x_i = R (T(q_i + dq; delta) [t; 1] + B_i beta + extra_i) + p``)
is fitted by a Levenberg-Marquardt iteration on the stacked residuals that never holds the ``3P x m``
Jacobian: every pass walks the poses in chunks of :data:`CHUNK_ROWS`, evaluates the exact perturbed
forward kinematics of the chunk (closed-form joint exponentials, :func:`point_kinematics`) and the
analytic Jacobian of the chunk, and accumulates ``J^T J``, ``J^T r`` and the cost. Memory is the data plus
the residuals (linear in the poses) and one chunk's Jacobian (constant). Small problems are one chunk;
the same code fits them, so there is one implementation of the fit.

Robust loss: with ``f_scale > 0`` the data rows are robust. ``loss="soft_l1"`` (per coordinate): SciPy's
``soft_l1`` loss ``f^2 rho((r/f)^2)``, ``rho(z) = 2 (sqrt(1 + z) - 1)``, on transformed residuals
``r' = sign(r) f sqrt(rho)`` with weights ``d r'/d r`` on the Jacobian rows (the normal equations of
``least_squares(loss="soft_l1")``). ``loss="huber"`` / ``"tukey"`` (per pose, on the 3-D residual norm ``s``,
:func:`m_rho`): M-estimators solved by iteratively reweighted least squares -- every pass weights a pose's three
rows by ``w(s) = rho'(s) / (2 s)`` (Huber: ``min(1, c / s)``; Tukey's biweight: ``(1 - (s/c)^2)^2`` inside ``c``,
0 beyond: a gross outlier has no influence at all) and the Levenberg-Marquardt step accepts on ``sum rho(s)``.
The prior rows (MAP prior on the geometric parameters, optional Gaussian priors on the target offset and on
effect parameters, :meth:`Problem.set_priors`) are never weighted. The rotation is updated on the right, ``R <- R exp([dw])``, so its Jacobian columns
``-R [y]`` are exact at every iterate. The geometric columns use the first-order error Jacobian of the
nominal model (as :mod:`.calibrate` documents); the fixed point therefore is that of the former
``scipy.optimize.least_squares`` fit with the same Jacobian (tests/test_diagnose_scale.py compares them).

Large training files: cross-validation, effect selection and the identifiability analysis run on a seeded
random subsample of at most :data:`SUBSAMPLE_ROWS` rows (:func:`subsample_index`); the final fits use every
row. Fits of at least :data:`PROGRESS_MIN_ROWS` rows show their passes on a bar (in a log: one line each, with
the passes and the time) when progress is on (:func:`tolalloc.progress.progress_scope`, which the pipeline opens).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from tolalloc.engine import resolve_engine
from tolalloc.diagnose.losses import LOSSES, m_rho, m_weight, norm_scale
from tolalloc.progress import NoBar, progress_bar
from tolalloc.robot.kinematics import poe_prefix_rp

__all__ = ["CHUNK_ROWS", "SUBSAMPLE_ROWS", "PROGRESS_MIN_ROWS", "Problem", "solve", "point_kinematics",
           "subsample_index", "robust_scale", "LOSSES", "m_rho", "m_weight", "norm_scale"]

#: Poses per chunk of a pass over the data (one chunk's Jacobian: 3 x CHUNK_ROWS x m floats).
CHUNK_ROWS = 20_000
#: Training files with more rows cross-validate and select effects on a seeded subsample of this size.
SUBSAMPLE_ROWS = 10_000
#: Fits on at least this many rows show their own progress bar (when progress is on).
PROGRESS_MIN_ROWS = 50_000


def subsample_index(n: int, max_rows: int = SUBSAMPLE_ROWS, seed: int = 0) -> np.ndarray | None:
    """Sorted seeded random subset of ``max_rows`` of ``range(n)``, or None when ``n <= max_rows``."""
    if n <= max_rows:
        return None
    return np.sort(np.random.default_rng(seed).choice(n, max_rows, replace=False))


def point_kinematics(screws: np.ndarray, home: np.ndarray, q: np.ndarray, t_mm: np.ndarray,
                     chunk_rows: int = CHUNK_ROWS) -> tuple[np.ndarray, np.ndarray]:
    """Target points ``T(q) [t; 1]`` and flange rotations of one chain at many poses, chunk by chunk.

    Parameters
    ----------
    screws : array, shape (n, 6); home : array, shape (4, 4); q : array, shape (P, n) [rad, mm]
    t_mm : array, shape (3,)

    Returns
    -------
    points : array, shape (P, 3) [mm]; rotations : array, shape (P, 3, 3)
    """
    P = len(q)
    pts, rots = np.empty((P, 3)), np.empty((P, 3, 3))
    w2 = np.sum(screws[:, :3] ** 2, axis=1)
    if resolve_engine() == "numba" and np.all((np.abs(w2 - 1.0) < 1e-12) | (w2 == 0.0)):
        from tolalloc.diagnose import _scale_nb

        f = np.ascontiguousarray
        _scale_nb.point_kinematics(f(screws, dtype=float), f(home, dtype=float), f(q, dtype=float),
                                   f(t_mm, dtype=float), pts, rots)
        return pts, rots
    for a in range(0, P, chunk_rows):
        R, p = poe_prefix_rp(screws, q[a:a + chunk_rows])
        Rf = R[:, -1] @ home[:3, :3]
        rots[a:a + chunk_rows] = Rf
        pts[a:a + chunk_rows] = R[:, -1] @ home[:3, 3] + p[:, -1] + Rf @ t_mm
    return pts, rots


def robust_scale(res: np.ndarray) -> float:
    """Scale of the robust loss: 3 robust standard deviations (1.4826 MAD) of the residual entries, >= 1e-4 mm."""
    return float(max(3.0 * 1.4826 * np.median(np.abs(res - np.median(res))), 1e-4))


class Problem:
    """Residual, Jacobian and normal equations of the measurement model for a fixed set of fitted columns.

    Parameter vector ``x = [w (3), p (3), t (3), delta[geo_index], beta]``, the rotation ``R = R0 exp([w])``.
    ``B`` is an array (P, 3, M) or a callable ``B(slice) -> (rows, 3, M)`` (computed chunk by chunk);
    ``n_effects`` gives M for a callable. With ``prior_w`` the residual ends with the prior rows
    ``prior_w * delta[geo_index]``; with ``f_scale > 0`` the data rows are robust (module docstring).
    """

    def __init__(self, model, R0, p0, t0, delta0, q, xyz, geo_index, B=None, extra=None, *, n_effects=None,
                 chunk_rows: int = CHUNK_ROWS):
        self.model, self.q, self.xyz, self.extra = model, q, xyz, extra
        self.R0, self.p0, self.t0, self.delta0 = R0, np.asarray(p0, float), np.asarray(t0, float), delta0
        self.geo = np.asarray(geo_index, int)
        self.B = B
        self.M = (B.shape[-1] if B is not None and not callable(B) else 0) if n_effects is None else n_effects
        self.chunk_rows = max(1, int(chunk_rows))
        self.prior_w = np.zeros(len(self.geo))
        self.t_prior = None  # (mean (3,), weight (3,)) of the target offset
        self.beta_prior_w = None  # weight (M,) of a zero-mean prior on the effect parameters
        self.f_scale = 0.0
        self.loss = "soft_l1"
        self.fixed_w = None  # (P,) pose weights held fixed (loss "fixed": weighted least squares)
        self._rot_key, self._rot = None, None  # last (w, R0) of _rotation and its matrix
        self._static = self._static_of(slice(0, len(q))) if len(q) <= self.chunk_rows else None

    # --------------------------------------------------------------- parameters
    @property
    def n_rows(self) -> int:
        return len(self.q)

    def x0(self) -> np.ndarray:
        return np.concatenate([np.zeros(3), self.p0, self.t0, self.delta0[self.geo], np.zeros(self.M)])

    def unpack(self, x):
        """``R, p, t, delta (all K), beta`` of ``x``."""
        k = len(self.geo)
        delta = self.delta0.copy()
        delta[self.geo] = x[9:9 + k]
        return self._rotation(x[:3]), x[3:6], x[6:9], delta, x[9 + k:]

    def _rotation(self, w) -> np.ndarray:
        """``R0 exp([w])``, remembered for the last ``(w, R0)`` (a pass asks for it once per chunk and more)."""
        key = (np.asarray(w, dtype=float).tobytes(), self.R0.tobytes())
        if self._rot_key != key:
            self._rot_key, self._rot = key, self.R0 @ Rotation.from_rotvec(w).as_matrix()
        return self._rot.copy()

    def rebase(self, x) -> np.ndarray:
        """Move the rotation of ``x`` into ``R0``; returns ``x`` with ``w = 0`` (same model)."""
        self.R0 = self.unpack(x)[0]
        x = np.array(x, dtype=float)
        x[:3] = 0.0
        return x

    def slices(self):
        return [slice(a, min(a + self.chunk_rows, self.n_rows)) for a in range(0, self.n_rows, self.chunk_rows)]

    # --------------------------------------------------------------- one chunk
    def _static_of(self, sl):
        """Per-pose quantities independent of the parameters, coordinate-major: nominal geometric point Jacobian
        ``Jp, Jw`` (3, rows, k) and flange rotation ``Rfl`` (3, rows, 3) (``Rfl[b, i, c] = R_flange,i[b, c]``)."""
        q = self.q[sl]
        J = self.model.jacobian(q)[:, :, self.geo] if len(self.geo) else np.zeros((len(q), 6, 0))
        robot = self.model.robot
        _, Rfl = point_kinematics(robot.screws, robot.home, q, np.zeros(3), self.chunk_rows)
        tr = lambda a: np.ascontiguousarray(a.transpose(1, 0, 2))  # noqa: E731
        return tr(J[:, :3, :]), tr(J[:, 3:, :]), tr(Rfl)

    def _B(self, sl):
        if self.B is None or self.M == 0:
            return None
        return self.B(sl) if callable(self.B) else self.B[sl]

    def chunk(self, x, sl, chain, want_jac: bool = True):
        """Data residual predicted - measured (rows, 3) [mm] on poses ``sl`` and its Jacobian in the robot base
        frame, coordinate-major ``A`` (3, rows, m) (or None); the tracker-frame Jacobian of coordinate ``a`` is
        ``sum_b R[a, b] A[b]`` (:meth:`tracker_rows`)."""
        R, p, t, delta, beta = self.unpack(x)
        screws, home, dq = chain
        y, _ = point_kinematics(screws, home, self.q[sl] + dq, t, self.chunk_rows)
        B = self._B(sl)
        if B is not None:
            y = y + B @ beta
        if self.extra is not None:
            y = y + self.extra[sl]
        r = y @ R.T + p - self.xyz[sl]
        if not want_jac:
            return r, None
        Jp, Jw, Rfl = self._static if self._static is not None else self._static_of(sl)
        C, k = len(y), Jp.shape[2]
        A = np.zeros((3, C, 9 + k + self.M))
        # rotation (right perturbation): -[y] dw ; translation: R^T dp (tracker frame -> base frame)
        for b, (c1, c2) in enumerate(((1, 2), (2, 0), (0, 1))):  # -[y] row b: (y x .)_b columns
            A[b, :, c1] = y[:, c2]
            A[b, :, c2] = -y[:, c1]
        A[:, :, 3:6] = R.T[:, None, :]
        A[:, :, 6:9] = Rfl
        arm = np.einsum("bic,c->bi", Rfl, t)  # flange-rotated offset, (3, rows)
        for b, (c1, c2) in enumerate(((1, 2), (2, 0), (0, 1))):  # Jp + Jw x arm
            A[b, :, 9:9 + k] = Jp[b] + Jw[c1] * arm[c2][:, None] - Jw[c2] * arm[c1][:, None]
        if B is not None:
            A[:, :, 9 + k:] = B.transpose(1, 0, 2)
        return r, A

    @staticmethod
    def tracker_rows(A, R):
        """Tracker-frame Jacobian rows of each coordinate, a list of three (rows, m) arrays."""
        return list((R @ A.reshape(3, -1)).reshape(A.shape))  # one GEMM for the whole chunk

    def set_priors(self, t_prior=None, beta_w=None) -> None:
        """Gaussian prior rows beside the geometric MAP prior ``prior_w``: ``t_prior = (mean (3,), weight (3,))`` on
        the target offset (weight = noise sd / prior sd), ``beta_w`` (M,) on the effect parameters (mean 0)."""
        self.t_prior = None if t_prior is None else (np.asarray(t_prior[0], float), np.asarray(t_prior[1], float))
        self.beta_prior_w = None if beta_w is None or not len(beta_w) else np.asarray(beta_w, float)

    def _prior_terms(self, x):
        """Prior rows as (parameter index, weight, mean) triples with nonzero weights."""
        k = len(self.geo)
        out = []
        if self.prior_w.any():
            out.append((np.arange(9, 9 + k), self.prior_w, np.zeros(k)))
        if self.t_prior is not None and np.any(self.t_prior[1] > 0):
            out.append((np.arange(6, 9), self.t_prior[1], self.t_prior[0]))
        if self.beta_prior_w is not None and np.any(self.beta_prior_w > 0):
            out.append((np.arange(9 + k, 9 + k + self.M), self.beta_prior_w, np.zeros(self.M)))
        return out

    @property
    def per_pose(self) -> bool:
        """True for the M-estimators on the 3-D residual norm (``huber``, ``tukey``) and fixed pose weights."""
        return (self.f_scale > 0 and self.loss in ("huber", "tukey")) or self.loss == "fixed"

    def _weights(self, s: np.ndarray, sl: slice | None = None) -> np.ndarray:
        """Per-pose weights of the residual norms ``s`` of the poses ``sl`` (all poses when None)."""
        if self.loss == "fixed":
            return self.fixed_w if sl is None else self.fixed_w[sl]
        return m_weight(s, self.loss, self.f_scale)

    def _rho(self, s: np.ndarray, sl: slice | None = None) -> np.ndarray:
        if self.loss == "fixed":
            return self._weights(s, sl) * s * s
        return m_rho(s, self.loss, self.f_scale)

    def pose_weights(self, raw: np.ndarray, sl: slice | None = None) -> np.ndarray:
        """IRLS weight of every pose (P,) for residuals ``raw`` (P, 3) under the current loss (``sl``: the poses of a
        chunk, for fixed weights)."""
        s = np.linalg.norm(raw, axis=1)
        if self.per_pose:
            return self._weights(s, sl)
        if self.f_scale > 0:  # soft_l1 on the norm (per coordinate in the fit)
            return 1.0 / np.sqrt(1.0 + (s / self.f_scale) ** 2)
        return np.ones(len(s))

    def _robust(self, r):
        """Transformed residual and its derivative d r' / d r (soft_l1); identity when ``f_scale`` is 0."""
        if self.f_scale <= 0 or self.loss != "soft_l1":
            return r, np.ones_like(r)
        f = self.f_scale
        root = np.sqrt(1.0 + (r / f) ** 2)
        rt = np.sign(r) * f * np.sqrt(2.0 * (root - 1.0))
        ratio = np.divide(r, rt, out=np.ones_like(r), where=np.abs(rt) > 1e-12 * f)
        return rt, ratio / root

    def chain(self, x):
        """The perturbed chain (screws, home, dq) of the geometric values in ``x``."""
        screws, home, dq = self.model.perturbed_chain(self.unpack(x)[3][None, :])
        return screws[0], home[0], dq[0]

    # --------------------------------------------------------------- stacked (small data, tests)
    def raw(self, x) -> np.ndarray:
        """Data residual predicted - measured, shape (3P,) [mm], without robust transform or prior rows."""
        ch = self.chain(x)
        return np.concatenate([self.chunk(x, sl, ch, False)[0].ravel() for sl in self.slices()])

    def fun(self, x) -> np.ndarray:
        """Stacked residual (robust data rows, then prior rows when set); ``|fun|^2`` is the cost."""
        raw = self.raw(x)
        if self.per_pose:
            s = np.linalg.norm(raw.reshape(-1, 3), axis=1)
            f = np.sqrt(self._rho(s) / np.maximum(s * s, 1e-300))
            res = (raw.reshape(-1, 3) * f[:, None]).ravel()
        else:
            res = self._robust(raw)[0]
        pri = [w * (x[i] - mu) for i, w, mu in self._prior_terms(x)]
        return np.concatenate([res, *pri]) if pri else res

    def jac(self, x) -> np.ndarray:
        """Stacked Jacobian of :meth:`fun` (holds 3P x m numbers: small problems only)."""
        ch = self.chain(x)
        R = self.unpack(x)[0]
        parts = []
        for sl in self.slices():
            r, A = self.chunk(x, sl, ch)
            J = np.stack(self.tracker_rows(A, R), axis=1).reshape(3 * len(r), -1)
            if self.per_pose:
                w = np.repeat(np.sqrt(self.pose_weights(r, sl)), 3)
            else:
                w = self._robust(r.ravel())[1]
            parts.append(J * w[:, None])
        J = np.concatenate(parts)
        for i, w, _ in self._prior_terms(x):
            Jp = np.zeros((len(i), J.shape[1]))
            Jp[np.arange(len(i)), i] = w
            J = np.concatenate([J, Jp])
        return J

    # --------------------------------------------------------------- normal equations
    def normal(self, x):
        """Cost ``|fun(x)|^2``, ``H = J^T J``, ``g = J^T fun(x)`` accumulated chunk by chunk, and the raw residual (P, 3)."""
        ch = self.chain(x)
        m = len(x)
        H, g, cost = np.zeros((m, m)), np.zeros(m), 0.0
        raw = np.empty((self.n_rows, 3))
        R = self.unpack(x)[0]
        for sl in self.slices():
            r, A = self.chunk(x, sl, ch)
            raw[sl] = r
            if self.per_pose:  # IRLS: one weight per pose from its 3-D residual norm
                nrm = np.linalg.norm(r, axis=1)
                sw = np.sqrt(self._weights(nrm, sl))
                cost += float(np.sum(self._rho(nrm, sl)))
            for a, Ja in enumerate(self.tracker_rows(A, R)):
                if self.per_pose:
                    Js, rt = Ja * sw[:, None], r[:, a] * sw
                else:
                    rt, s = self._robust(r[:, a])
                    Js = Ja * s[:, None] if self.f_scale > 0 and self.loss == "soft_l1" else Ja
                    cost += float(rt @ rt)
                H += Js.T @ Js
                g += Js.T @ rt
        for i, w, mu in self._prior_terms(x):
            d, w2 = x[i] - mu, w ** 2
            H[i, i] += w2
            g[i] += w2 * d
            cost += float(np.sum(w2 * d * d))
        return cost, H, g, raw


def _step(H, g, lam):
    """Levenberg-Marquardt step with Marquardt scaling: ``(H + lam diag(H)) dx = -g``."""
    d = np.sqrt(np.maximum(np.diag(H), 0.0))
    d = np.where(d > 0, d, 1.0)
    A = H / np.outer(d, d) + lam * np.eye(len(d))
    try:
        z = np.linalg.solve(A, -g / d)
    except np.linalg.LinAlgError:
        z = np.linalg.lstsq(A, -g / d, rcond=None)[0]
    return z / d


def solve(prob: Problem, x: np.ndarray, *, max_iter: int = 60, ftol: float = 1e-10, xtol: float = 1e-10,
          sd_tol: float = 0.01, label: str = "fit"):
    """Minimise ``|prob.fun(x)|^2`` by Levenberg-Marquardt on the chunked normal equations.

    Returns ``(x, raw)``: the solution (rotation moved into ``prob.R0``, ``x[:3] = 0``) and its raw data
    residual (P, 3). Stops when an accepted step lowers the cost by less than ``ftol`` of it or moves every
    parameter by less than ``xtol (xtol + |x|)``, after ``max_iter`` passes, when no step lowers the cost, or
    when a step is worth less than ``sd_tol`` standard errors: its decrease (accepted) or the next step's
    predicted decrease (quadratic model; saves a pass) is below ``sd_tol^2 s^2``, ``s^2 = cost / (3P - m)`` the
    residual variance. A move of ``d`` standard errors changes the cost by about ``d^2 s^2``, so the stop leaves
    the parameters within about ``sd_tol`` of their standard error of the optimum; without it, the robust
    losses' tail (weights that change with the residuals) can spend a dozen rejected passes on decreases of
    ``1e-8`` of the cost.
    """
    bar = progress_bar(f"{label} ({prob.n_rows:,} rows)", unit="pass") if prob.n_rows >= PROGRESS_MIN_ROWS \
        else NoBar()
    x = prob.rebase(x)
    cost, H, g, raw = prob.normal(x)
    bar.update()
    lam = 1e-6
    per_sd2 = sd_tol ** 2 / max(3 * prob.n_rows - len(x), 1)  # (sd_tol standard errors)^2 / cost
    for _ in range(max_iter):
        dx = _step(H, g, lam)
        if -(g @ dx + 0.5 * dx @ H @ dx) <= max(1e-4 * ftol, per_sd2) * cost:  # no useful decrease predicted
            break
        trial = prob.normal(x + dx)
        bar.update()
        if trial[0] <= cost:
            small = np.all(np.abs(dx) <= xtol * (xtol + np.abs(x)))
            done = cost - trial[0] <= max(ftol, per_sd2) * cost or small
            x = prob.rebase(x + dx)
            cost, H, g, raw = trial
            bar.set_postfix_str(f"cost {cost:.6g}")
            lam = max(lam / 10.0, 1e-12)
            if done:
                break
        else:
            lam *= 10.0
            if lam > 1e8:
                break
    bar.close()
    return x, raw
