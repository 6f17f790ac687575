"""Paired (control-variate) Monte Carlo of ``P(|dP| < r)``: the nonlinear chain and the linear map on the same draws.

For Gaussian error parameters the linear prediction ``P_lin = P(|J e| < r)`` is known exactly
(:func:`tolalloc.linear.probability.p_within_radius`). On every sampled robot both indicators are evaluated,
``1{|dP_nonlinear| < r}`` by the exact perturbed chain and ``1{|J e| < r}`` by the linear map, and

    P_hat = P_lin + (b - c) / n,

``b`` (``c``) the samples inside by the nonlinear chain (the linear map) only. The two indicators disagree only
on the thin shell where the nonlinearity moves a sample across the sphere, so ``b + c`` is tiny and the variance
``((b + c) / n - D^2) / n`` is thousands of times below plain Monte Carlo's ``P (1 - P) / n``. The interval is
Tango's score interval of the paired difference (:mod:`tolalloc.montecarlo.intervals`).

The draws are those of :func:`tolalloc.montecarlo.run.run_mc` (same blocks, same generators), so the plain
estimate carried alongside equals ``run_mc``'s for the same seed. Memory is bounded (blocks streamed through
:func:`tolalloc.montecarlo.parallel.ordered_map`); the scheduler never changes the numbers.

When the linear probability is not the exact mean of the linear indicator -- a non-normal parameter with
non-zero sigma (ring clearances, uniform or truncated errors) -- the paired estimator would be biased and
``estimator="auto"`` falls back to plain Monte Carlo of the same draws, saying why; so it does at a pose where
the control is poor (variance reduction below 1, with discordant draws to show it).
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.features import N_BUF, ErrorFeatures
from tolalloc.errormodel.sampling import draw_rows
from tolalloc.linear.probability import p_within_radius
from tolalloc.montecarlo.blocks import BLOCK_SIZE, SUB_BLOCK, KernelSpec
from tolalloc.montecarlo.estimate import ProbabilityEstimate, variance_reduction
from tolalloc.montecarlo.intervals import paired_difference_ci
from tolalloc.montecarlo.parallel import check_scheduler, default_jobs, ordered_map
from tolalloc.montecarlo.streaming import proportion_ci

__all__ = ["ESTIMATORS", "check_estimator", "control_fallback_reason", "ProbabilityEstimate", "paired_counts",
           "estimate_probabilities", "estimate_radii", "estimate_from_counts", "PairedCounts"]

#: Estimators of a verified probability.
ESTIMATORS = ("auto", "plain", "paired", "importance")


def check_estimator(estimator, allowed=ESTIMATORS) -> str:
    """Validate an ``estimator`` keyword; returns it."""
    if estimator not in allowed:
        raise TolallocError(f"estimator: expected one of {', '.join(repr(a) for a in allowed)}, got {estimator!r}; "
                            "'auto' uses the paired estimator where the linear map is an exact control (Gaussian "
                            "parameters) and plain Monte Carlo elsewhere.")
    return estimator


def control_fallback_reason(model) -> str:
    """Why the linear map is not an exact control for ``model`` ("" when it is: every varying parameter normal)."""
    sig = model.sigma
    bad = sorted({p.distribution for p, s in zip(model.params, sig) if s > 0 and p.distribution != "normal"})
    if not bad:
        return ""
    names = [p.name for p, s in zip(model.params, sig) if s > 0 and p.distribution != "normal"]
    more = f" ({', '.join(names[:4])}{', ...' if len(names) > 4 else ''})"
    return (f"non-Gaussian parameters ({', '.join(bad)}){more}: the linear probability is not exact for them, "
            "so plain Monte Carlo was used")


# ----------------------------------------------------------------- block task
class _PairSpec(KernelSpec):
    """What a block needs: model, poses, radii; the prepared chain programs are built once per process."""

    def __init__(self, model, q, n, seed, radii, aradii, keep):
        self.model, self.q, self.n, self.seed = model, q, int(n), int(seed)
        self.radii, self.aradii, self.keep = list(radii), list(aradii), int(keep)
        self._lock = threading.Lock()

    def _build(self):
        chain, mult, progs = self._chain_and_programs()
        feats = [ErrorFeatures(self.model.robot.fk_internal(qi)) for qi in self.q]
        A = self.model.jacobian(self.q) * mult  # (P, 6, K): linear map of the drawn rows
        return chain, progs, feats, np.ascontiguousarray(A)


def _pair_block(spec: _PairSpec, b: int):
    """Counts of block ``b``: (P, R, 3) int64 ``[nonlinear inside, linear inside, both]`` and kept samples."""
    chain, progs, feats, A = spec.kernel()
    K = len(spec.model.params)
    m = min(BLOCK_SIZE, spec.n - b * BLOCK_SIZE)
    V = np.empty((K, m))
    draw_rows(spec.model, m, np.random.default_rng(np.random.SeedSequence(spec.seed, spawn_key=(b,))), V)
    R = len(spec.radii) + len(spec.aradii)
    counts = np.zeros((len(progs), R, 3), np.int64)
    dev = np.zeros(len(progs))
    keep = max(0, min(m, spec.keep - b * BLOCK_SIZE))
    kept = []
    work = FastChain.workspace(SUB_BLOCK)
    X = np.empty((3, 4, SUB_BLOCK))
    buf, tmp = np.empty((N_BUF, SUB_BLOCK)), np.empty((2, SUB_BLOCK))
    for i, prog in enumerate(progs):
        for s0 in range(0, m, SUB_BLOCK):
            s1 = min(m, s0 + SUB_BLOCK)
            N = s1 - s0
            Xs = X[:, :, :N]
            chain.run(prog, V[:, s0:s1], Xs, work)
            F = feats[i].compute(Xs, buf, tmp)
            nl_pos, nl_ang = F[6].copy(), ErrorFeatures.angle_row(buf, N).copy()
            lin = A[i] @ V[:, s0:s1]
            lin_pos = np.sqrt(np.einsum("in,in->n", lin[:3], lin[:3]))
            lin_ang = np.sqrt(np.einsum("in,in->n", lin[3:], lin[3:]))
            dev[i] = max(dev[i], float(np.abs(nl_pos - lin_pos).max()))
            for j, (r, a, la) in enumerate([(r, nl_pos, lin_pos) for r in spec.radii]
                                           + [(r, nl_ang, lin_ang) for r in spec.aradii]):
                ni, li = a < r, la < r
                counts[i, j] += (np.count_nonzero(ni), np.count_nonzero(li), np.count_nonzero(ni & li))
            if i == 0 and s0 < keep:
                kept.append(F[0:3, : keep - s0].T.copy())
    return m, counts, dev, kept


def _pair_blocks(spec: _PairSpec, blocks: tuple[int, int]):
    out = None
    for b in range(*blocks):
        r = _pair_block(spec, b)
        out = r if out is None else (out[0] + r[0], out[1] + r[1], np.maximum(out[2], r[2]), out[3] + r[3])
    return out


@dataclass(frozen=True)
class PairedCounts:
    """Raw counts of a paired run.

    Attributes
    ----------
    n, seed : int
    counts : array of int, shape (P, R, 3)
        Per pose and radius (position radii first, then angles): nonlinear inside, linear inside, both inside.
    max_deviation_mm : array, shape (P,)
        Largest ``| |dP_nonlinear| - |J e| |`` seen [mm].
    kept_mm : array, shape (k, 3) or None
        Nonlinear position errors of the first ``keep`` samples at pose 0 [mm].
    """

    n: int | np.ndarray
    seed: int
    counts: np.ndarray
    max_deviation_mm: np.ndarray
    kept_mm: np.ndarray | None = None


def paired_counts(model, q, n: int, seed: int = 0, *, radii_mm=(), angle_radii_rad=(), keep_samples: int = 0,
                  scheduler=None, n_jobs: int | None = None) -> PairedCounts:
    """Nonlinear and linear indicators on the same draws (those of :func:`run_mc` for ``seed``), streamed.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (P, n_joints) [rad, mm]
    n : int
    radii_mm, angle_radii_rad : sequences of float
    keep_samples : int
        Nonlinear position errors kept at pose 0.
    scheduler, n_jobs
        Where the blocks run (:func:`~tolalloc.montecarlo.parallel.ordered_map`); never changes the numbers.
    """
    from threadpoolctl import threadpool_limits

    from tolalloc.exceptions import raise_if_interrupted

    q = np.atleast_2d(model.robot.check_q(q, "q"))
    _check_budget(model, len(q), n, "paired", n_jobs)
    spec = _PairSpec(model, q, n, seed, radii_mm, angle_radii_rad, keep_samples)
    n_blocks = -(-int(n) // BLOCK_SIZE)
    tasks = ((b, b + 1) for b in range(n_blocks))
    counts = np.zeros((len(q), len(spec.radii) + len(spec.aradii), 3), np.int64)
    dev, kept = np.zeros(len(q)), []
    with threadpool_limits(limits=1, user_api="blas"):
        for _, c, d, k in ordered_map(_pair_blocks, tasks, spec, scheduler=check_scheduler(scheduler),
                                      n_jobs=n_jobs or default_jobs()):
            raise_if_interrupted()
            counts += c
            np.maximum(dev, d, out=dev)
            kept += k
    return PairedCounts(int(n), int(seed), counts, dev, np.concatenate(kept) if kept else None)


def _check_budget(model, n_poses: int, n, kind: str, n_jobs) -> None:
    """Refuse ``n`` samples at ``n_poses`` poses that cannot run within the time budget (:mod:`tolalloc.budget`)."""
    from tolalloc.budget import chain_scale, check_count
    from tolalloc.exceptions import whole_number

    count = whole_number(n)
    if count is None or count < 1:
        raise TolallocError(f"n: expected a whole number of samples >= 1, got {n!r}.")
    check_count(count, "n", f"samples at {n_poses} pose{'s' if n_poses != 1 else ''}", {kind: n_poses},
                scale=chain_scale(len(model.params), model.robot.n_joints), threads=n_jobs or default_jobs(),
                example="1000000", announce=False)


# ----------------------------------------------------------------- estimate
def estimate_from_counts(pc: PairedCounts, j: int, radius: float, p_linear, *, quantity: str = "position",
                         estimator: str = "auto", model_reason: str = "", level: float = 0.95,
                         details: dict | None = None) -> ProbabilityEstimate:
    """The estimate of radius column ``j`` of a paired run, with the ``auto`` choice made per pose."""
    c = pc.counts[:, j, :].astype(float)
    n = np.broadcast_to(np.asarray(pc.n), (len(c),)).astype(float)
    nl, li, both = c[:, 0], c[:, 1], c[:, 2]
    b, cc = nl - both, li - both
    plain = proportion_ci(nl, n, "wilson", level)
    d = paired_difference_ci(b, cc, n, level)
    p_lin = np.asarray(p_linear, float)
    paired = np.stack([p_lin + d[:, 0], np.clip(p_lin + d[:, 1], 0, 1), np.clip(p_lin + d[:, 2], 0, 1)], axis=1)
    var_paired = (np.maximum(b + cc, 1.0) / n - d[:, 0] ** 2) / n
    vr = variance_reduction(paired[:, 0], n, var_paired)
    use_plain = np.full(len(c), estimator == "plain" or bool(model_reason))
    fallback = [model_reason if (model_reason and estimator != "plain") else "" for _ in range(len(c))]
    if estimator == "auto" and not model_reason:
        # a poor control shows in its discordant draws; with none, both intervals are the zero-count one (+-z^2 / n)
        poor = (vr < 1.0) & (b + cc > 0)
        use_plain |= poor
        for i in np.flatnonzero(poor):
            fallback[i] = f"poor control: variance reduction x{vr[i]:.2g} < 1, so plain Monte Carlo"
    est = np.where(use_plain[:, None], plain, paired)
    return ProbabilityEstimate(quantity, float(radius), estimator, np.where(use_plain, "plain", "paired"),
                               tuple(fallback), n.astype(int), p_lin, est[:, 0], est[:, 1], est[:, 2], plain[:, 0], plain[:, 1],
                               plain[:, 2], b, cc, np.where(use_plain, 1.0, vr), level, dict(details or {}))


def estimate_radii(model, q, n: int, seed: int = 0, *, radii_mm=(), angle_radii_rad=(), estimator: str = "auto",
                   level: float = 0.95, keep_samples: int = 0, scheduler=None, n_jobs: int | None = None):
    """Estimates of ``P(|dP| < r)`` and ``P(|rotvec| < a)`` for several radii from one paired run.

    Returns
    -------
    position : dict float -> ProbabilityEstimate
        Radius [mm] -> estimate (``details``: ``kept_mm``, ``max_deviation_mm``).
    orientation : dict float -> ProbabilityEstimate
        Angle [rad] -> estimate.
    """
    check_estimator(estimator, ("auto", "plain", "paired"))
    q = np.atleast_2d(model.robot.check_q(q, "q"))
    reason = control_fallback_reason(model)
    if estimator == "paired" and reason:
        raise ArgumentError("estimator", f"'paired' needs Gaussian parameters; {reason.split(':')[0]}. Use "
                            "estimator='auto' (plain Monte Carlo for this model) or 'plain'.")
    radii, aradii = [float(r) for r in radii_mm], [float(a) for a in angle_radii_rad]
    pc = paired_counts(model, q, n, seed, radii_mm=radii, angle_radii_rad=aradii, keep_samples=keep_samples,
                       scheduler=scheduler, n_jobs=n_jobs)
    J = model.jacobian(q)
    s2 = model.sigma**2
    cov = {k: np.einsum("pik,k,pjk->pij", J[:, rows], s2, J[:, rows]) for k, rows in (("position", slice(0, 3)),
                                                                                     ("orientation", slice(3, 6)))}
    pos, ang = {}, {}
    for j, (name, rad) in enumerate([("position", r) for r in radii] + [("orientation", a) for a in aradii]):
        det = {"kept_mm": pc.kept_mm, "max_deviation_mm": pc.max_deviation_mm} if name == "position" else {}
        e = estimate_from_counts(pc, j, rad, p_within_radius(cov[name], rad), quantity=name, estimator=estimator,
                                 model_reason=reason, level=level, details=det)
        (pos if name == "position" else ang)[rad] = e
    return pos, ang


def estimate_probabilities(model, q, n: int, seed: int = 0, *, radius_mm: float | None = None,
                           angle_radius_rad: float | None = None, estimator: str = "auto", level: float = 0.95,
                           keep_samples: int = 0, scheduler=None, n_jobs: int | None = None):
    """Position (and orientation) probability estimates at every pose from one paired run.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (P, n_joints) [rad, mm]
    n : int
        Samples (the same sampled robots at every pose).
    seed : int
    radius_mm : float, optional
        Position requirement radius [mm].
    angle_radius_rad : float, optional
        Orientation requirement radius [rad].
    estimator : {"auto", "plain", "paired"}
        ``paired`` on a model with non-Gaussian parameters is refused (the control would be biased); ``auto``
        falls back to plain there and at poses with a poor control.
    level : float
    keep_samples : int
        Nonlinear position errors kept at pose 0 (``details["kept_mm"]`` of the position estimate).

    Returns
    -------
    dict with ``"position"`` and/or ``"orientation"`` -> :class:`ProbabilityEstimate`
    """
    pos, ang = estimate_radii(model, q, n, seed, radii_mm=() if radius_mm is None else (radius_mm,),
                              angle_radii_rad=() if angle_radius_rad is None else (angle_radius_rad,),
                              estimator=estimator, level=level, keep_samples=keep_samples, scheduler=scheduler,
                              n_jobs=n_jobs)
    out = {}
    if pos:
        out["position"] = next(iter(pos.values()))
    if ang:
        out["orientation"] = next(iter(ang.values()))
    return out
