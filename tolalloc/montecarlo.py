"""Nonlinear Monte Carlo: exact forward kinematics of sampled perturbed chains.

Every sample is a robot built with random errors; its tool pose is computed
exactly (no linearisation) at one or several joint configurations and compared
with the nominal pose.

Fast exact path
---------------
The perturbed chain of :meth:`ErrorModel.perturbed_chain` is the product
``G_0 E_1 G_1 ... E_n G_n M`` of error displacements ``G_s`` (exponentials of
the parameters' twists) and joint exponentials ``E_j = exp([S_j](q_j + dq_j))``.
:class:`FastChain` evaluates it right to left on a structure-of-arrays ``(3, 4, N)``
block (rows of ``[R | p]``) with closed-form exponentials: a unit-rotation twist
only mixes the rows its rotation touches (two for an axis-aligned one), a pure
translation only adds to ``p``. It equals the generic ``fk_poe`` path to
rounding (tested to 1e-9).

Reproducibility
---------------
Random numbers are drawn per block of :data:`BLOCK_SIZE` samples, block ``b``
with its own generator ``SeedSequence(seed).spawn`` child ``b``; statistics are
computed per block and merged in block order (Chan et al.'s parallel update), so
the same seed gives the same numbers whatever ``chunk_size`` or thread count.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ._validate import TolallocError
from .errors import ErrorModel
from .lie import euler_xyz_fixed, hat

__all__ = ["BLOCK_SIZE", "FastChain", "pose_errors", "McResult", "run_mc", "proportion_ci", "sample_values", "generic_pose_errors"]

#: Samples per random-number block (the unit of reproducibility).
BLOCK_SIZE = 2**16
#: Per-sample features accumulated by :func:`run_mc`, in this order.
FEATURES = ("dx", "dy", "dz", "norm", "reach", "alpha", "beta", "gamma", "rvx", "rvy", "rvz")


# ----------------------------------------------------------------- fast chain
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
        # factors left to right: (twist, joint index or None, [(k, sign), ...])
        factors = []
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
        A = hat(w)
        B = A @ A
        I = np.eye(3)
        # R = I + s A + (1 - c) B = (I + B) + s A - c B
        coef = [[(I[i, j] + B[i, j], A[i, j], -B[i, j]) for j in range(3)] for i in range(3)]
        coef = [[tuple(0.0 if abs(x) < 1e-15 else x for x in c) for c in row] for row in coef]
        rows = [i for i in range(3) if any(abs(A[i, j]) > 0 or abs(B[i, j]) > 0 for j in range(3))]
        axis = None
        big = int(np.argmax(np.abs(w)))
        if abs(abs(w[big]) - 1.0) < 1e-15:  # base axis x, y or z (sign sg): rows (a, b) rotate
            a, b = (big + 1) % 3, (big + 2) % 3
            axis = (a, b, 1.0 if w[big] > 0 else -1.0)
        return {"kind": "rot", "w": w, "r0": np.cross(w, v), "h": float(w @ v), "scale": nw,
                "coef": coef, "rows": rows, "joint": joint, "src": sources, "axis": axis}

    def _amount(self, f, V, q):
        """Exponential coordinate of factor ``f`` per sample, shape (N,), from values ``V`` (K, N)."""
        base = float(q[f["joint"]]) if f["joint"] is not None else 0.0
        out = None
        for k, sign in f["src"]:
            term = V[k] if sign == 1.0 else -V[k]
            out = term.copy() if out is None else out + term
        if out is None:
            return np.full(V.shape[1], base * f["scale"])
        if base != 0.0:
            out += base
        if f["scale"] != 1.0:
            out *= f["scale"]
        return out

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
        rows = [np.repeat(self.home[i, :, None], N, axis=1) for i in range(3)]  # rows of [R | p], (4, N) each
        buf, spare = np.empty((4, N)), np.empty((4, N))
        s, c = np.empty(N), np.empty(N)
        for f in reversed(self.factors):
            th = self._amount(f, V, q)
            if f["kind"] == "trans":
                for i in range(3):
                    if f["v"][i] != 0.0:
                        rows[i][3] += th * f["v"][i] if f["v"][i] != 1.0 else th
                continue
            np.sin(th, out=s)
            np.cos(th, out=c)
            r0, w, h = f["r0"], f["w"], f["h"]
            if f["axis"] is not None:  # rotation about a base axis: rows a, b mix (no allocation)
                a, b, sg = f["axis"]
                if sg < 0:
                    np.negative(s, out=s)
                Xa, Xb = rows[a], rows[b]
                if r0[a] != 0.0:
                    Xa[3] -= r0[a]
                if r0[b] != 0.0:
                    Xb[3] -= r0[b]
                na = spare
                np.multiply(Xa, c, out=na)
                np.multiply(Xb, s, out=buf)
                na -= buf
                np.multiply(Xa, s, out=buf)
                Xb *= c
                Xb += buf
                rows[a], spare = na, Xa
                if r0[a] != 0.0:
                    na[3] += r0[a]
                if r0[b] != 0.0:
                    Xb[3] += r0[b]
            else:
                cache = {}
                s, c = s.copy(), c.copy()

                def coef_arr(a0, a1, a2):
                    key = (a0, a1, a2)
                    if key not in cache:
                        cache[key] = a0 + a1 * s + a2 * c
                    return cache[key]

                new = {}
                for i in f["rows"]:
                    row = None
                    t = np.full(N, r0[i]) if r0[i] != 0.0 else None
                    for j in range(3):
                        if f["coef"][i][j] == (0.0, 0.0, 0.0):
                            continue
                        cf = coef_arr(*f["coef"][i][j])
                        term = rows[j] * cf
                        row = term if row is None else np.add(row, term, out=row)
                        if r0[j] != 0.0:
                            t = -r0[j] * cf if t is None else t - r0[j] * cf
                    if t is not None:
                        row[3] += t
                    new[i] = row
                for i, row in new.items():
                    rows[i] = row
            if h != 0.0:
                for i in range(3):
                    if w[i] != 0.0:
                        rows[i][3] += (h * w[i]) * th
        return np.stack(rows)


# ----------------------------------------------------------------- per-sample errors
def _rotvec_rows(E) -> np.ndarray:
    """Rotation vectors of rotations given as nested rows ``E[i][j]`` of arrays (N,), shape (N, 3)."""
    v = np.stack([E[2][1] - E[1][2], E[0][2] - E[2][0], E[1][0] - E[0][1]], axis=-1) * 0.5
    cos = (E[0][0] + E[1][1] + E[2][2] - 1.0) * 0.5
    sin = np.linalg.norm(v, axis=-1)
    theta = np.arctan2(sin, cos)
    ratio = np.where(sin > 1e-300, theta / np.where(sin > 1e-300, sin, 1.0), 1.0)
    out = v * ratio[:, None]
    bad = cos < -0.999  # near pi: the antisymmetric part loses the axis; use scipy there
    if np.any(bad):
        from scipy.spatial.transform import Rotation

        M = np.stack([np.stack([E[i][j][bad] for j in range(3)], -1) for i in range(3)], -2)
        out[bad] = Rotation.from_matrix(M).as_rotvec()
    return out


def _errors_from_X(X: np.ndarray, T0: np.ndarray) -> dict:
    p0, R0 = T0[:3, 3], T0[:3, :3]
    dp = (X[:, 3] - p0[:, None]).T  # (N, 3)
    norm = np.sqrt(np.einsum("ij,ij->i", dp, dp))
    r0 = float(np.linalg.norm(p0))
    pn = np.sqrt(np.einsum("ij,ij->i", X[:, 3].T, X[:, 3].T))
    reach = (2.0 * dp @ p0 + norm**2) / (pn + r0) if r0 > 0 else pn
    e0 = euler_xyz_fixed(R0)
    R = X[:, :3]  # R[i, j] (N,)
    beta = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
    alpha = np.arctan2(R[2, 1], R[2, 2])
    gamma = np.arctan2(R[1, 0], R[0, 0])
    eul = np.stack([alpha, beta, gamma], axis=-1) - e0
    eul = (eul + np.pi) % (2 * np.pi) - np.pi
    E = [[sum(R[i, k] * R0[j, k] for k in range(3)) for j in range(3)] for i in range(3)]  # R' R0^T
    return {"dp_mm": dp, "norm_mm": norm, "reach_mm": reach, "euler_rad": eul, "rotvec_rad": _rotvec_rows(E)}


def _check_values(model: ErrorModel, values) -> np.ndarray:
    values = np.asarray(values, dtype=float)
    if values.ndim == 1:
        values = values[None, :]
    if values.ndim != 2 or values.shape[1] != len(model.params):
        raise TolallocError(f"values: expected shape (N, {len(model.params)}) (one column per error parameter "
                            f"{', '.join(model.names)}), got {values.shape}.")
    if not np.all(np.isfinite(values)):
        raise TolallocError("values: expected finite parameter values [mm, rad]; got NaN or inf.")
    return values


def pose_errors(model: ErrorModel, q: np.ndarray, values: np.ndarray, *, chain: FastChain | None = None) -> dict[str, np.ndarray]:
    """Exact nonlinear tool-pose errors of perturbed chains at one pose.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (n,) [rad, mm]
    values : array, shape (N, K) [mm, rad]
        Error parameter values (one row per sample, columns in ``model.names`` order).
    chain : FastChain, optional
        Reuse a prepared kernel.

    Returns
    -------
    dict with
        ``dp_mm`` (N, 3) position error ``p' - p``; ``norm_mm`` (N,) ``|p' - p|``;
        ``reach_mm`` (N,) ``|p'| - |p|`` (the paper's Table-3 "Δp"); ``euler_rad`` (N, 3)
        X-Y-Z fixed Euler-angle errors ``euler(R') - euler(R)`` (wrapped to [-pi, pi));
        ``rotvec_rad`` (N, 3) rotation vector of ``R' R^T`` (space frame).
    """
    q = model.robot.check_q(q, "q")
    if q.ndim != 1:
        raise TolallocError(f"q: expected one pose of shape ({model.robot.n_joints},), got {q.shape}.")
    values = _check_values(model, values)
    chain = chain or FastChain(model)
    return _errors_from_X(chain.pose(q, values), model.robot.fk(q))


def generic_pose_errors(model: ErrorModel, q: np.ndarray, values: np.ndarray) -> dict[str, np.ndarray]:
    """Reference implementation of :func:`pose_errors` through ``perturbed_chain`` + ``fk_poe`` (slow)."""
    from .robot import fk_poe

    values = _check_values(model, values)
    screws, home, dq = model.perturbed_chain(values)
    T = fk_poe(screws, home, np.asarray(q, float) + dq)
    X = np.moveaxis(T[:, :3, :], 0, -1)
    return _errors_from_X(np.ascontiguousarray(X), model.robot.fk(q))


def sample_values(model: ErrorModel, m: int, rng: np.random.Generator) -> np.ndarray:
    """Draw ``m`` samples of the parameter values, transposed: shape (K, m) [mm, rad].

    Same distributions as :meth:`ErrorModel.sample` (normal, uniform over ``±sqrt(3) sigma``,
    normal truncated at ``±3 sigma``, ring pairs ``s (cos t, sin t)``), drawn in bulk: all normal
    parameters with non-zero sigma in one call; zero-sigma parameters are exactly 0 and draw nothing.
    """
    params = model.params
    K = len(params)
    out = np.zeros((K, m))
    sig = model.sigma
    normal = [k for k, p in enumerate(params) if p.distribution == "normal" and sig[k] > 0]
    if normal:
        out[normal] = rng.standard_normal((len(normal), m)) * sig[normal, None]
    done = set()
    for k, p in enumerate(params):
        if sig[k] == 0 or p.distribution == "normal" or k in done:
            continue
        if p.distribution == "ring":
            k2 = next(i for i, o in enumerate(params) if o.group == p.group and i != k)
            s = rng.standard_normal(m) * (np.sqrt(2.0) * p.sigma)
            t = rng.uniform(0.0, 2 * np.pi, m)
            out[k], out[k2] = s * np.cos(t), s * np.sin(t)
            done.update((k, k2))
        elif p.distribution == "uniform":
            out[k] = rng.uniform(-np.sqrt(3.0) * p.sigma, np.sqrt(3.0) * p.sigma, m)
        elif p.distribution == "truncnormal":
            from scipy.stats import truncnorm

            out[k] = truncnorm.rvs(-3, 3, scale=p.sigma, size=m, random_state=rng)
    return out


# ----------------------------------------------------------------- statistics
def proportion_ci(k, n, ci: str = "wilson", level: float = 0.95) -> np.ndarray:
    """Point estimate and two-sided confidence interval of a binomial proportion.

    Parameters
    ----------
    k : array of int
        Successes.
    n : int
        Trials.
    ci : {"wilson", "exact"}
        Wilson score interval or Clopper-Pearson.

    Returns
    -------
    array, shape (..., 3): ``p, low, high``.
    """
    from scipy import stats

    k = np.asarray(k, dtype=float)
    p = k / n
    if ci == "wilson":
        z = stats.norm.ppf(0.5 + level / 2)
        den = 1 + z**2 / n
        centre = (p + z**2 / (2 * n)) / den
        half = z * np.sqrt(p * (1 - p) / n + z**2 / (4 * n**2)) / den
        lo, hi = np.clip(centre - half, 0, 1), np.clip(centre + half, 0, 1)
    elif ci in ("exact", "clopper-pearson"):
        a = (1 - level) / 2
        lo = np.where(k > 0, stats.beta.ppf(a, np.maximum(k, 1e-300), n - k + 1), 0.0)
        hi = np.where(k < n, stats.beta.ppf(1 - a, k + 1, np.maximum(n - k, 1e-300)), 1.0)
    else:
        raise TolallocError(f"ci: expected 'wilson' or 'exact' (Clopper-Pearson), got {ci!r}.")
    return np.stack([p, lo, hi], axis=-1)


@dataclass
class _Acc:
    """Running count, mean, co-moment matrix, max and min of a feature vector."""

    n: int = 0
    mean: np.ndarray | None = None
    M2: np.ndarray | None = None
    mx: np.ndarray | None = None
    mn: np.ndarray | None = None
    counts: np.ndarray | None = None

    def merge(self, n, mean, M2, mx, mn, counts):
        if self.n == 0:
            self.n, self.mean, self.M2, self.mx, self.mn, self.counts = n, mean, M2, mx, mn, counts
            return
        tot = self.n + n
        d = mean - self.mean
        self.mean = self.mean + d * (n / tot)
        self.M2 = self.M2 + M2 + np.outer(d, d) * (self.n * n / tot)
        self.mx, self.mn = np.maximum(self.mx, mx), np.minimum(self.mn, mn)
        self.counts = self.counts + counts
        self.n = tot


def _block_stats(err: dict, radii, angle_radii):
    F = np.column_stack([err["dp_mm"], err["norm_mm"], err["reach_mm"], err["euler_rad"], err["rotvec_rad"]])
    mean = F.mean(axis=0)
    C = F - mean
    ang = np.linalg.norm(err["rotvec_rad"], axis=1)
    counts = np.array([np.count_nonzero(err["norm_mm"] < r) for r in radii]
                      + [np.count_nonzero(ang < r) for r in angle_radii], dtype=np.int64)
    return F.shape[0], mean, C.T @ C, F.max(axis=0), F.min(axis=0), counts


@dataclass(frozen=True)
class McResult:
    """Monte Carlo summary, one entry per pose along axis 0 (``P`` poses).

    Attributes
    ----------
    n, seed : int
    q : array, shape (P, n_joints) [rad, mm]
    labels : dict
        Model options (``sigma_set``, ``link_mode``, ``deflection_mode``, ``clearance``).
    mean_mm, std_mm : array, shape (P, 3)
        Mean and standard deviation (ddof 1) of ``p' - p``.
    cov_mm2 : array, shape (P, 3, 3)
    norm_mm, reach_mm : array, shape (P, 4)
        Mean, std, max, min of ``|p' - p|`` and of ``|p'| - |p|`` (the paper's "Δp").
    angle_mean_rad, angle_std_rad : array, shape (P, 3)
        X-Y-Z fixed Euler-angle errors ``(alpha, beta, gamma)``.
    rotvec_std_rad : array, shape (P, 3)
    p_within : dict float -> array, shape (P, 3)
        Radius [mm] -> ``P(|p' - p| < r)``, CI low, CI high.
    p_within_angle : dict float -> array, shape (P, 3)
        Angle [rad] -> ``P(|rotvec| < r)`` with CI.
    samples : dict or None
        The first ``keep_samples`` per-sample arrays (keys of :func:`pose_errors`) at pose 0.
    dp_max_mm, dp_min_mm, angle_max_rad, angle_min_rad : array, shape (P, 3)
    ci : str
        Interval method (95 %).
    """

    n: int
    seed: int
    q: np.ndarray
    labels: dict
    mean_mm: np.ndarray
    std_mm: np.ndarray
    cov_mm2: np.ndarray
    norm_mm: np.ndarray
    reach_mm: np.ndarray
    angle_mean_rad: np.ndarray
    angle_std_rad: np.ndarray
    rotvec_std_rad: np.ndarray
    p_within: dict
    p_within_angle: dict
    samples: dict | None = None
    dp_max_mm: np.ndarray = field(default=None, repr=False)
    dp_min_mm: np.ndarray = field(default=None, repr=False)
    angle_max_rad: np.ndarray = field(default=None, repr=False)
    angle_min_rad: np.ndarray = field(default=None, repr=False)
    ci: str = "wilson"

    def to_frame(self) -> pd.DataFrame:
        """Table-3-style table: one row per pose and quantity with mean, std, max, min."""
        rows = []
        for i in range(self.q.shape[0]):
            items = [("dp_reach_mm", *self.reach_mm[i]), ("dp_norm_mm", *self.norm_mm[i])]
            for a, nm in enumerate(("dx_mm", "dy_mm", "dz_mm")):
                items.append((nm, self.mean_mm[i, a], self.std_mm[i, a], self.dp_max_mm[i, a], self.dp_min_mm[i, a]))
            for a, nm in enumerate(("dalpha_rad", "dbeta_rad", "dgamma_rad")):
                items.append((nm, self.angle_mean_rad[i, a], self.angle_std_rad[i, a],
                              self.angle_max_rad[i, a], self.angle_min_rad[i, a]))
            rows += [{"pose": i, "quantity": it[0], "mean": it[1], "std": it[2], "max": it[3], "min": it[4]} for it in items]
        return pd.DataFrame(rows)


def run_mc(model: ErrorModel, q, n: int, seed: int = 0, *, radii_mm=(), angle_radii_rad=(), chunk_size: int = 2**17,
           keep_samples: int = 0, ci: str = "wilson", n_jobs: int | None = None) -> McResult:
    """Nonlinear Monte Carlo of the tool-pose error at one or several poses.

    The same sampled robots (parameter values) are evaluated at every pose.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (n_joints,) or (P, n_joints) [rad, mm]
    n : int
        Number of samples (>= 1).
    seed : int
    radii_mm : sequence of float
        Radii for ``P(|p' - p| < r)``.
    angle_radii_rad : sequence of float
        Radii for ``P(|rotvec| < r)``.
    chunk_size : int
        Samples processed at once (rounded up to whole blocks of :data:`BLOCK_SIZE`); bounds memory,
        never changes the numbers.
    keep_samples : int
        Keep the first this many per-sample errors of pose 0 (for figures).
    ci : {"wilson", "exact"}
    n_jobs : int, optional
        Threads (default: the CPU count, at most 8); never changes the numbers.

    Returns
    -------
    McResult
    """
    q = np.atleast_2d(model.robot.check_q(q, "q"))
    try:
        n_ok = int(n) == n and n >= 1
    except (TypeError, ValueError, OverflowError):
        n_ok = False
    if not n_ok:
        raise TolallocError(f"n: expected an integer number of samples >= 1, got {n!r}.")
    n = int(n)
    sig = model.sigma
    if np.any(~np.isfinite(sig)) or np.any(sig < 0):
        raise TolallocError(f"sigma: expected finite values >= 0, got {sig}; fix the sigma set or overrides.")
    radii = [float(r) for r in radii_mm]
    aradii = [float(r) for r in angle_radii_rad]
    for r, nm in [(r, "radii_mm") for r in radii] + [(r, "angle_radii_rad") for r in aradii]:
        if not np.isfinite(r) or r <= 0:
            raise TolallocError(f"{nm}: expected finite radii > 0, got {r!r}.")
    if ci not in ("wilson", "exact", "clopper-pearson"):
        raise TolallocError(f"ci: expected 'wilson' or 'exact' (Clopper-Pearson), got {ci!r}.")
    chain = FastChain(model)
    T0 = [model.robot.fk(qi) for qi in q]
    n_blocks = -(-n // BLOCK_SIZE)
    per_chunk = max(1, -(-int(chunk_size) // BLOCK_SIZE))
    children = np.random.SeedSequence(int(seed)).spawn(n_blocks)
    accs = [_Acc() for _ in q]
    kept = []

    def work(b):
        m = min(BLOCK_SIZE, n - b * BLOCK_SIZE)
        values = sample_values(model, m, np.random.default_rng(children[b]))
        out = []
        for i, qi in enumerate(q):
            err = _errors_from_X(chain.pose(qi, values, transposed=True), T0[i])
            out.append((_block_stats(err, radii, aradii), err if (i == 0 and b * BLOCK_SIZE < keep_samples) else None))
        return out

    jobs = n_jobs or min(os.cpu_count() or 1, 8)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        for start in range(0, n_blocks, per_chunk):
            for b, res in zip(range(start, min(n_blocks, start + per_chunk)),
                              pool.map(work, range(start, min(n_blocks, start + per_chunk)))):
                for i, (st, err) in enumerate(res):
                    accs[i].merge(*st)
                    if err is not None:
                        kept.append({k: v[: keep_samples - b * BLOCK_SIZE] for k, v in err.items()})
    samples = {k: np.concatenate([d[k] for d in kept]) for k in kept[0]} if kept else None
    P = len(q)
    mean = np.array([a.mean for a in accs])
    ddof = 1 if n > 1 else 0
    cov = np.array([a.M2 / max(n - ddof, 1) for a in accs])
    std = np.sqrt(np.maximum(np.diagonal(cov, axis1=1, axis2=2), 0))
    mx, mn = np.array([a.mx for a in accs]), np.array([a.mn for a in accs])
    counts = np.array([a.counts for a in accs]).reshape(P, -1)

    def four(j):
        return np.stack([mean[:, j], std[:, j], mx[:, j], mn[:, j]], axis=1)

    pci = proportion_ci(counts, n, ci) if counts.size else np.zeros((P, 0, 3))
    labels = {**model.labels, "clearance": any(p.kind.startswith("clearance") for p in model.params)}
    return McResult(
        n=n, seed=int(seed), q=q, labels=labels,
        mean_mm=mean[:, 0:3], std_mm=std[:, 0:3], cov_mm2=cov[:, 0:3, 0:3],
        norm_mm=four(3), reach_mm=four(4),
        angle_mean_rad=mean[:, 5:8], angle_std_rad=std[:, 5:8], rotvec_std_rad=std[:, 8:11],
        p_within={r: pci[:, j] for j, r in enumerate(radii)},
        p_within_angle={r: pci[:, len(radii) + j] for j, r in enumerate(aradii)},
        samples=samples, dp_max_mm=mx[:, 0:3], dp_min_mm=mn[:, 0:3], angle_max_rad=mx[:, 5:8],
        angle_min_rad=mn[:, 5:8], ci="exact" if ci == "clopper-pearson" else ci,
    )
