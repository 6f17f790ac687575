"""Nonlinear Monte Carlo: exact forward kinematics of sampled perturbed chains, streamed.

Every sample is a robot built with random errors; its tool pose is computed exactly (no
linearisation, :class:`~tolalloc.errormodel.chain.FastChain`) at one or several joint configurations and
compared with the nominal pose.

Reproducibility
---------------
Random numbers are drawn per block of :data:`BLOCK_SIZE` samples, block ``b`` with its own generator
``SeedSequence(seed).spawn`` child ``b``; a block is processed in sub-blocks of :data:`SUB_BLOCK`
samples whose statistics are merged in order, and blocks are merged in block order (Chan et al.'s
parallel update, :mod:`tolalloc.montecarlo.streaming`). So the same seed gives the same numbers whatever
``chunk_size``, thread count or scheduler (local threads, Dask processes, a Dask cluster).

Memory
------
Statistics (moments, extrema, probabilities, fixed-range 2-D histograms) are streamed: memory is a
few blocks per worker plus ``keep_samples`` (10^8 samples run in well under 1 GB).
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, raise_if_interrupted, whole_number
from tolalloc.errormodel.model import ErrorModel
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.features import N_BUF, ErrorFeatures, features_to_dict
from tolalloc.engine import resolve_engine
from tolalloc.progress import new_bar, show_progress
from tolalloc.errormodel.sampling import sample_values
from tolalloc.montecarlo.blocks import BLOCK_SIZE, SUB_BLOCK, McSpec, run_blocks
from tolalloc.montecarlo.parallel import check_scheduler, default_jobs, ordered_map
from tolalloc.montecarlo.streaming import HistSpec, McHistogram, Moments, proportion_ci
from tolalloc.montecarlo.radii import RadiusTable
from tolalloc.units import unit_columns

__all__ = ["BLOCK_SIZE", "SUB_BLOCK", "FastChain", "pose_errors", "McResult", "run_mc", "proportion_ci",
           "sample_values", "generic_pose_errors", "McHistogram", "sample_work", "check_samples_budget"]

#: Runs of at least this many samples show their progress by default (progress=None).
PROGRESS_MIN_N = 10**7


# ----------------------------------------------------------------- per-sample errors
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


def _errors_from_X(X: np.ndarray, T0: np.ndarray) -> dict:
    X = np.ascontiguousarray(X)
    N = X.shape[2]
    buf = np.empty((N_BUF, N))
    return features_to_dict(ErrorFeatures(T0).compute(X, buf, np.empty((2, N))))


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
        X-Y-Z fixed Euler-angle errors ``euler(R') - euler(R)`` (wrapped to (-pi, pi]);
        ``rotvec_rad`` (N, 3) rotation vector of ``R' R^T`` (space frame).
    """
    q = model.robot.check_q(q, "q")
    if q.ndim != 1:
        raise TolallocError(f"q: expected one pose of shape ({model.robot.n_joints},), got {q.shape}.")
    values = _check_values(model, values)
    chain = chain or FastChain(model)
    return _errors_from_X(chain.pose(q, values), model.robot.fk_internal(q))


def generic_pose_errors(model: ErrorModel, q: np.ndarray, values: np.ndarray) -> dict[str, np.ndarray]:
    """Reference implementation of :func:`pose_errors` through ``perturbed_chain`` + ``fk_poe`` (slow; the numpy walk
    over the chain program, so that no compiled code is on the reference's side)."""
    from tolalloc.robot.kinematics import fk_poe

    values = _check_values(model, values)
    screws, home, dq = model.perturbed_chain(values, engine="numpy")
    T = fk_poe(screws, home, np.asarray(q, float) + dq)
    X = np.moveaxis(T[:, :3, :], 0, -1)
    return _errors_from_X(X, model.robot.fk_internal(q))


# ----------------------------------------------------------------- result
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
    p_within : RadiusTable, float -> array, shape (P, 3)
        Radius [mm] -> ``P(|p' - p| < r)``, CI low, CI high; a radius not simulated raises
        :class:`~tolalloc.montecarlo.radii.RadiusNotSimulated` naming the simulated ones
        (:func:`~tolalloc.montecarlo.radii.probability_frame`: all of them as a table).
    p_within_angle : RadiusTable, float -> array, shape (P, 3)
        Angle [rad] -> ``P(|rotvec| < r)`` with CI.
    samples : dict or None
        The first ``keep_samples`` per-sample arrays (keys of :func:`pose_errors`) at pose 0.
    dp_max_mm, dp_min_mm, angle_max_rad, angle_min_rad : array, shape (P, 3)
    ci : str
        Interval method (95 %).
    hist : McHistogram or None
        Fixed-range x-y, x-z, y-z histograms of ``p' - p`` over all samples (``hist_bins > 0``).
    p_estimates, p_estimates_angle : dict float -> ProbabilityEstimate, or None
        With ``estimator`` given: radius [mm] (angle [rad]) -> the estimate of ``P(|.| < r)`` by that estimator
        (:mod:`tolalloc.montecarlo.paired`; the plain columns equal ``p_within``).
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
    hist: McHistogram | None = field(default=None, repr=False)
    p_estimates: dict | None = field(default=None, repr=False)
    p_estimates_angle: dict | None = field(default=None, repr=False)

    def to_frame(self) -> pd.DataFrame:
        """Table-3-style table: one row per pose (from 1) and quantity (``dp_reach``, ``dp_norm``, ``dx``, ``dy``,
        ``dz``, then the X-Y-Z fixed Euler-angle errors ``dalpha``, ``dbeta``, ``dgamma``) with its ``unit`` and
        mean, std, max, min in the ``_mm`` / ``_deg`` column pair (:func:`tolalloc.units.unit_columns`: position
        rows in mm, angle rows in deg, the other column empty)."""
        stats = ("mean", "std", "max", "min")
        angles = ("dalpha", "dbeta", "dgamma")
        rows = []
        for i in range(self.q.shape[0]):
            rows += [(i + 1, "dp_reach", *self.reach_mm[i]), (i + 1, "dp_norm", *self.norm_mm[i])]
            for a, nm in enumerate(("dx", "dy", "dz")):
                rows.append((i + 1, nm, self.mean_mm[i, a], self.std_mm[i, a], self.dp_max_mm[i, a],
                             self.dp_min_mm[i, a]))
            for a, nm in enumerate(angles):
                rows.append((i + 1, nm, *np.rad2deg([self.angle_mean_rad[i, a], self.angle_std_rad[i, a],
                                                     self.angle_max_rad[i, a], self.angle_min_rad[i, a]])))
        df = pd.DataFrame(rows, columns=["pose", "quantity", *stats])
        length = ~df["quantity"].isin(angles).to_numpy()
        df["unit"] = np.where(length, "mm", "deg")
        for st in stats:
            df = df.assign(**unit_columns(st, df.pop(st).to_numpy(float), length))
        return df[["pose", "quantity", "unit"] + [f"{st}_{u}" for u in ("mm", "deg") for st in stats]]


# ----------------------------------------------------------------- driver
def _hist_spec(model, q, bins, hist_range_mm, hist_sigmas=6.0):
    P = len(q)
    if hist_range_mm is None:
        J = model.jacobian(q)[:, :3]  # (P, 3, K)
        sd = np.sqrt(np.einsum("pik,k->pi", J**2, model.sigma**2))
        half = np.where(sd > 0, hist_sigmas * sd, 1e-6)
    else:
        h = np.asarray(hist_range_mm, float)
        half = np.broadcast_to(h, (P, 3)) if h.ndim <= 1 else h
    return HistSpec.symmetric(np.array(half, float), bins)


def _checked_args(model: ErrorModel, q, n, radii_mm, angle_radii_rad, ci):
    """Validated ``(q (P, n_joints), n, radii, angle radii)`` of :func:`run_mc` (TolallocError naming the argument)."""
    q = np.atleast_2d(model.robot.check_q(q, "q"))
    whole = whole_number(n)
    if whole is None or whole < 1:
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
    return q, n, radii, aradii


def _tasks(n: int, scheduler, chunk_size: int):
    """Block ranges ``(b0, b1)`` of the run, generated lazily: memory does not grow with n (1e20 is fine)."""
    n_blocks = -(-n // BLOCK_SIZE)
    local = scheduler in (None, "local", "sync")
    per_task = 1 if local else max(1, -(-int(chunk_size) // BLOCK_SIZE))
    return ((b, min(n_blocks, b + per_task)) for b in range(0, n_blocks, per_task))


def run_mc(model: ErrorModel, q, n: int, seed: int = 0, *, radii_mm=(), angle_radii_rad=(), chunk_size: int = 2**17,
           keep_samples: int = 0, ci: str = "wilson", n_jobs: int | None = None, scheduler=None,
           progress: bool | None = None, hist_bins: int = 0, hist_range_mm=None, engine: str | None = None,
           estimator: str | None = None) -> McResult:
    """Nonlinear Monte Carlo of the tool-pose error at one or several poses (streamed, bounded memory).

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
        Samples per task on Dask schedulers (rounded up to whole blocks of :data:`BLOCK_SIZE`);
        never changes the numbers.
    keep_samples : int
        Keep the first this many per-sample errors of pose 0 (for figures).
    ci : {"wilson", "exact"}
    n_jobs : int, optional
        Local threads (default: the usable CPUs, at most 8); never changes the numbers.
    scheduler : None, "local", "sync", "threads", "processes", "distributed", "tcp://HOST:PORT" or a
        ``distributed.Client``
        Where blocks run (:mod:`tolalloc.montecarlo.parallel`); never changes the numbers.
    progress : bool, optional
        Progress on stderr (:mod:`tolalloc.progress`: a bar on a terminal, one line when done in a log); default:
        when ``n >= PROGRESS_MIN_N``.
    hist_bins : int
        If > 0, accumulate fixed-range ``hist_bins x hist_bins`` histograms of ``p' - p`` on the x-y,
        x-z and y-z planes over all samples (``McResult.hist``).
    hist_range_mm : float, array (3,) or (P, 3), optional
        Half-width of the histogram window per axis [mm]; default 6 linear standard deviations.
    engine : {None, "auto", "numba", "numpy"}
        Per-block computation: the compiled kernel of :mod:`tolalloc.montecarlo.engines.numba_engine` (default when numba is
        installed and ``TOLALLOC_NUMBA`` is not ``0``) or numpy. Same random numbers; results agree to
        rounding (about 1e-13 relative).
    estimator : {None, "auto", "plain", "paired", "importance"}
        Also estimate every probability with this estimator (``McResult.p_estimates``, see :func:`_estimates`).

    Returns
    -------
    McResult
    """
    q, n, radii, aradii = _checked_args(model, q, n, radii_mm, angle_radii_rad, ci)
    scheduler = check_scheduler(scheduler)
    _check_estimator_arg(estimator)
    check_samples_budget(model, len(q), n, estimator if (radii or aradii) else None, n_jobs)
    hist = _hist_spec(model, q, hist_bins, hist_range_mm) if hist_bins else None
    spec = McSpec(model, q, n, int(seed), radii, aradii, hist, int(keep_samples), resolve_engine(engine))
    tasks = _tasks(n, scheduler, chunk_size)
    show = show_progress(progress) and (progress is not None or n >= PROGRESS_MIN_N)
    bar = new_bar("Monte Carlo", total=n, unit="sample", unit_scale=True) if show else None
    P = len(q)
    moms = [Moments() for _ in range(P)]
    ext, kept = None, []
    from threadpoolctl import threadpool_limits

    try:
        with threadpool_limits(limits=1, user_api="blas"):
            results = ordered_map(run_blocks, tasks, spec, scheduler=scheduler, n_jobs=n_jobs or default_jobs())
            with contextlib.closing(results):  # an interrupt cancels the queued blocks at once
                for ns, block_moms, e, k in results:
                    raise_if_interrupted()  # a signal whose exception a worker library swallowed
                    for bm in block_moms:
                        for acc, mo in zip(moms, bm):
                            acc.merge(mo)
                    ext = e if ext is None else [a.merge(x) for a, x in zip(ext, e)]
                    kept += k
                    if bar is not None:
                        bar.update(sum(ns))
    finally:
        if bar is not None:
            bar.close()
    res = _result(model, spec, moms, ext, kept, ci)
    if estimator is None or not (radii or aradii):
        return res
    from dataclasses import replace

    return replace(res, **_estimates(model, q, n, int(seed), radii, aradii, estimator, scheduler, n_jobs))


def sample_work(model: ErrorModel, n_poses: int, estimator: str | None = None) -> tuple:
    """``(kinds, scale)`` of one sampled robot of :func:`run_mc` at ``n_poses`` poses for :mod:`tolalloc.budget`:
    the plain pass, plus the paired pass over the same draws and the importance-sampling draws of ``estimator``."""
    from tolalloc.budget import chain_scale

    kinds = {"mc": n_poses}
    if estimator is not None:
        kinds["paired"] = n_poses
    if estimator == "importance":
        kinds["importance"] = n_poses
    return kinds, chain_scale(len(model.params), model.robot.n_joints)


def check_samples_budget(model: ErrorModel, n_poses: int, n: int, estimator: str | None = None,
                         n_jobs: int | None = None, *, argument: str = "n", announce: bool = True):
    """Refuse ``n`` samples at ``n_poses`` poses that cannot finish within the time budget, announce a long run
    (:func:`tolalloc.budget.check_count`); returns the estimate."""
    from tolalloc.budget import check_count

    kinds, scale = sample_work(model, n_poses, estimator)
    what = f"samples at {n_poses} pose{'s' if n_poses != 1 else ''}"
    return check_count(n, argument, what, kinds, scale=scale, threads=n_jobs or default_jobs(), example="1000000",
                       announce=announce)


def _check_estimator_arg(estimator) -> None:
    if estimator is not None:
        from tolalloc.montecarlo.paired import check_estimator

        check_estimator(estimator)


def _estimates(model, q, n, seed, radii, aradii, estimator, scheduler, n_jobs) -> dict:
    """``p_estimates`` and ``p_estimates_angle`` of :func:`run_mc` with ``estimator``.

    Every ``P(|.| < r)`` of ``radii_mm`` / ``angle_radii_rad`` against the exact linear prediction: a second pass
    over the same draws (:func:`~tolalloc.montecarlo.paired.estimate_radii`), plus per-pose draws for
    ``importance`` (position radii; orientation as ``auto``).
    """
    from tolalloc.montecarlo.paired import estimate_radii

    other = "auto" if estimator == "importance" else estimator
    pos, ang = estimate_radii(model, q, n, seed, radii_mm=radii, angle_radii_rad=aradii, estimator=other,
                              scheduler=scheduler, n_jobs=n_jobs)
    if estimator == "importance":
        from tolalloc.montecarlo.importance import importance_probability

        pos = {r: importance_probability(model, q, n, seed, radius_mm=r, scheduler=scheduler, n_jobs=n_jobs)
               for r in radii}
    return {"p_estimates": RadiusTable(pos), "p_estimates_angle": RadiusTable(ang, angle=True)}


def _result(model, spec, moms, ext, kept, ci) -> McResult:
    n, q, radii, aradii = spec.n, spec.q, spec.radii, spec.aradii
    P = len(q)
    samples = {k: np.concatenate([d[k] for d in kept]) for k in kept[0]} if kept else None
    mean = np.array([a.mean for a in moms])
    ddof = 1 if n > 1 else 0
    cov = np.array([a.cov(ddof) for a in moms])
    std = np.sqrt(np.maximum(np.diagonal(cov, axis1=1, axis2=2), 0))
    mx, mn = np.array([e.mx for e in ext]), np.array([e.mn for e in ext])
    counts = np.array([e.counts for e in ext]).reshape(P, -1)

    def four(j):
        return np.stack([mean[:, j], std[:, j], mx[:, j], mn[:, j]], axis=1)

    pci = proportion_ci(counts, n, ci) if counts.size else np.zeros((P, 0, 3))
    hist = None
    if spec.hist is not None:
        H = np.array([e.hist for e in ext])  # (P, 3, b + 2, b + 2)
        inner = H[:, :, 1:-1, 1:-1]
        b = spec.hist.bins
        edges = spec.hist.lo_mm[:, :, None] + spec.hist.width_mm[:, :, None] * np.arange(b + 1)
        hist = McHistogram(n, edges, inner.copy(), n - inner.sum(axis=(2, 3)))
    labels = {**model.labels, "clearance": any(p.kind.startswith("clearance") for p in model.params)}
    # feature rows: dx dy dz rvx rvy rvz norm reach alpha beta gamma
    return McResult(
        n=n, seed=spec.seed, q=q, labels=labels,
        mean_mm=mean[:, 0:3], std_mm=std[:, 0:3], cov_mm2=cov[:, 0:3, 0:3],
        norm_mm=four(6), reach_mm=four(7),
        angle_mean_rad=mean[:, 8:11], angle_std_rad=std[:, 8:11], rotvec_std_rad=std[:, 3:6],
        p_within=RadiusTable({r: pci[:, j] for j, r in enumerate(radii)}),
        p_within_angle=RadiusTable({r: pci[:, len(radii) + j] for j, r in enumerate(aradii)}, angle=True),
        samples=samples, dp_max_mm=mx[:, 0:3], dp_min_mm=mn[:, 0:3], angle_max_rad=mx[:, 8:11],
        angle_min_rad=mn[:, 8:11], ci="exact" if ci == "clopper-pearson" else ci, hist=hist,
    )
