"""Nonlinear Monte Carlo verification of an allocated design at every pose.

The design's error model (``sigma = t / z``) is sampled and evaluated with the exact perturbed
kinematics (:func:`tolalloc.montecarlo.run.run_mc`); ``P(|dP| < r)`` is estimated at every pose with a
95 % Wilson interval and set beside the linear (Gaussian) prediction. Criteria (issue 5):

* a pose is **demonstrated** when the whole interval is at or above ``p`` (lower bound ``>= p``);
* it is **consistent** when the interval reaches ``p`` (upper bound ``>= p``) but its lower bound is below;
* it **failed** when the whole interval lies below ``p``.

A **certified** design passes a pose only when demonstrated; an **exact** design passes a consistent pose
(no fixed allowance: a design whose interval lies below ``p`` fails, issue 13).

A certified pose whose interval straddles ``p`` is re-run with more samples (up to ``n_max``, pooled).
Failing poses are named with the reason: *under-specified* (the linear prediction itself is below
``p``), *non-Gaussian* parameters (ring clearances, uniform) carrying a sizeable share of the variance,
*inconclusive* (the interval contains ``p`` at the largest sample size: more samples are needed, whatever
``P_hat``) or *nonlinearity* (the whole interval lies below ``p`` although the linear prediction meets it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Design
from tolalloc.linear.covariance import variance_share

__all__ = ["Verification", "verify_design", "pose_verdicts", "overall_verdict"]


def pose_verdicts(ci_low, ci_high, prob) -> np.ndarray:
    """Per-pose verdict from the 95 % interval of ``P_hat``.

    Parameters
    ----------
    ci_low, ci_high : array, shape (P,)
    prob : float

    Returns
    -------
    array of str, shape (P,)
        ``"demonstrated"`` (lower bound >= p), ``"consistent"`` (upper bound >= p) or ``"failed"``.
    """
    lo, hi = np.asarray(ci_low, float), np.asarray(ci_high, float)
    return np.where(lo >= prob, "demonstrated", np.where(hi >= prob, "consistent", "failed"))


def overall_verdict(verdicts) -> str:
    """The weakest per-pose verdict: ``failed`` < ``consistent`` < ``demonstrated``."""
    v = set(np.asarray(verdicts).tolist())
    return "failed" if "failed" in v else ("consistent" if "consistent" in v else "demonstrated")


@dataclass(frozen=True, eq=False)
class Verification:
    """Monte Carlo verification of one design.

    Attributes
    ----------
    criterion : {"certified", "exact"}
    radius_mm, prob : float
    n : array of int, shape (P,)
        Samples used per pose.
    seed : int
    p_linear, p_mc, ci_low, ci_high : arrays, shape (P,)
    passed : array of bool, shape (P,)
    reason : tuple of str
        Empty for passing poses.
    worst_pose : int
        Pose with the lowest ``p_mc``.
    samples_mm : array, shape (m, 3) or None
        Position errors of the first samples at ``samples_pose`` (for the error-cloud figure) [mm].
    samples_pose : int
        The pose of ``samples_mm``: the lowest linear prediction.
    angle : dict or None
        Orientation check (same keys as arrays) when the problem has an orientation requirement.
    """

    criterion: str
    radius_mm: float
    prob: float
    n: np.ndarray
    seed: int
    p_linear: np.ndarray
    p_mc: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    passed: np.ndarray
    reason: tuple
    worst_pose: int
    samples_mm: np.ndarray | None = field(default=None, repr=False)
    samples_pose: int = 0
    angle: dict | None = None

    @property
    def ok(self) -> bool:
        return bool(np.all(self.passed))

    @property
    def verdicts(self) -> np.ndarray:
        """Per-pose ``demonstrated | consistent | failed`` (position requirement), shape (P,)."""
        v = pose_verdicts(self.ci_low, self.ci_high, self.prob)
        if self.angle is not None:
            v = np.where(np.asarray(self.angle["passed"], bool), v, "failed")
        return v

    @property
    def verdict(self) -> str:
        """Overall verdict: the weakest pose's."""
        return overall_verdict(self.verdicts)

    @property
    def failing(self) -> list:
        """``[(pose number (1-based), reason), ...]``."""
        return [(i + 1, self.reason[i]) for i in np.flatnonzero(~self.passed)]

    def message(self) -> str:
        rule = ("pass: whole 95% interval >= p" if self.criterion == "certified" else "pass: upper 95% bound >= p")
        if self.ok:
            angle = ("" if self.angle is None else
                     f"; orientation: lowest P_hat = {self.angle['p_mc'].min():.4f} at pose "
                     f"{int(np.argmin(self.angle['p_mc'])) + 1}")
            meaning = ("lower 95% bound >= p at every pose" if self.verdict == "demonstrated" else
                       f"{rule}; at {int(np.sum(self.verdicts != 'demonstrated'))} pose(s) the interval also extends "
                       "below p")
            return (f"verified: {self.verdict} by nonlinear Monte Carlo at all {len(self.passed)} poses ({meaning}); "
                    f"lowest P_hat = {self.p_mc.min():.4f} at pose {self.worst_pose + 1}{angle}")
        head = "failed" if self.verdict == "failed" else f"{self.verdict}, criterion not met"
        return f"verified: {head} ({rule}) at " + "; ".join(f"pose {i}: {r}" for i, r in self.failing)

    def to_frame(self) -> pd.DataFrame:
        """One row per pose: p_linear, p_mc, ci_low, ci_high, n, passed, reason.

        With an orientation requirement also ``p_linear_angle, p_mc_angle, ci_low_angle, ci_high_angle`` and
        ``passed`` covers both requirements.
        """
        cols = {"pose": np.arange(1, len(self.p_mc) + 1), "p_linear": self.p_linear, "p_mc": self.p_mc,
                "ci_low": self.ci_low, "ci_high": self.ci_high}
        if self.angle is not None:
            nan = np.full(len(self.p_mc), np.nan)
            cols.update({"p_linear_angle": nan if self.angle["p_linear"] is None else self.angle["p_linear"],
                         "p_mc_angle": self.angle["p_mc"], "ci_low_angle": self.angle["ci_low"],
                         "ci_high_angle": self.angle["ci_high"]})
        cols.update({"n": self.n, "passed": self.passed, "verdict": self.verdicts, "reason": list(self.reason)})
        return pd.DataFrame(cols)


def _run(model, q, n, seed, radius, angle, keep, scheduler=None):
    from tolalloc.montecarlo.run import run_mc

    res = run_mc(model, q, int(n), seed, radii_mm=(radius,), angle_radii_rad=() if angle is None else (angle,),
                 keep_samples=keep, scheduler=scheduler)
    pw = np.asarray(res.p_within[float(radius)] if float(radius) in res.p_within else next(iter(res.p_within.values())))
    pa = None
    if angle is not None:
        pa = np.asarray(next(iter(res.p_within_angle.values())))
    s = None
    if keep and res.samples:
        s = np.asarray(res.samples.get("dp_mm"))[:keep]
    return pw, pa, s


def verify_design(problem: AllocationProblem, design: Design, *, criterion: str | None = None, n_mc: int = 10**6,
                  n_max: int | None = None, seed: int = 0, keep_samples: int = 4000,
                  nongauss_share: float = 0.05, scheduler=None) -> Verification:
    """Verify a design by nonlinear Monte Carlo at every pose of ``problem``.

    Parameters
    ----------
    problem : AllocationProblem
    design : Design
        Must have half-widths ``t``.
    criterion : {"certified", "exact"}, optional
        Default: ``certified`` for designs of a certified rule (``Design.solver.certified``, a certified fallback
        of the exact solver included), else ``exact``.
    n_mc : int
        Samples per pose (the same sampled robots at every pose).
    n_max : int, optional
        Largest pooled sample size for poses whose interval straddles ``p`` (certified criterion);
        default ``4 n_mc``.
    seed : int
    keep_samples : int
        Position errors kept at the worst pose for figures.
    nongauss_share : float
        Variance share of non-normal parameters above which a failure is attributed to them.
    scheduler : str or dask.distributed.Client, optional
        Where the Monte Carlo runs (see :func:`tolalloc.montecarlo.parallel.ordered_map`); never changes the numbers.
    """
    from tolalloc.montecarlo.run import proportion_ci

    if design.t is None:
        raise TolallocError(f"verify: the design ({design.solver}) has no tolerances ({design.status}); nothing to verify.")
    if design.status == NOT_CONVERGED:
        raise TolallocError(f"verify: the design {design.label} did not converge ({design.message}); re-solve it "
                            "(or verify its tolerances as a design of their own) before calling it verified.")
    try:
        n_ok = int(n_mc) == n_mc and n_mc >= 100
    except (TypeError, ValueError, OverflowError):
        n_ok = False
    if not n_ok:
        raise TolallocError(f"n_mc: expected an integer number of samples >= 100, got {n_mc!r}.")
    crit = criterion or ("certified" if design.solver.certified else "exact")
    if crit not in ("certified", "exact"):
        raise TolallocError(f"criterion: expected 'certified' or 'exact', got {crit!r}.")
    n_max = 4 * int(n_mc) if n_max is None else int(n_max)
    model = problem.model_for(design.t)
    r, p = problem.radius_mm, problem.prob
    ang = problem.angle_radius_rad
    p_lin = design.p_linear["position"]
    order = np.argsort(p_lin)  # worst linear pose first: its samples are kept
    P = problem.n_poses
    pw, pa, samples = _run(model, problem.q[order], n_mc, seed, r, ang, keep_samples, scheduler)
    inv = np.argsort(order)
    pw, pa = pw[inv], None if pa is None else pa[inv]
    n = np.full(P, int(n_mc))
    k = np.rint(pw[:, 0] * n_mc)

    def passes(lo, hi):
        return lo >= p if crit == "certified" else hi >= p

    # more samples where a certified interval straddles p
    if crit == "certified" and n_max > n_mc:
        redo = np.flatnonzero((pw[:, 1] < p) & (pw[:, 2] >= p))
        if redo.size:
            extra = n_max - int(n_mc)
            pw2, _, _ = _run(model, problem.q[redo], extra, seed + 1, r, None, 0, scheduler)
            k[redo] += np.rint(pw2[:, 0] * extra)
            n[redo] += extra
    est = np.stack([np.asarray(proportion_ci(k[i], int(n[i]))).reshape(3) for i in range(P)])  # (P, 3)
    ok = passes(est[:, 1], est[:, 2])
    angle = None
    if pa is not None:
        ap = problem.angle_prob
        a_ok = pa[:, 1] >= ap if crit == "certified" else pa[:, 2] >= ap
        angle = {"p_linear": design.p_linear.get("orientation"), "p_mc": pa[:, 0], "ci_low": pa[:, 1],
                 "ci_high": pa[:, 2], "passed": a_ok}
    else:
        a_ok = np.ones(P, bool)
    reasons = _failure_reasons(problem, model, crit, p_lin, est, n, ok, a_ok, pa, nongauss_share)
    worst = int(np.argmin(est[:, 0]))
    return Verification(crit, r, p, n, int(seed), p_lin.copy(), est[:, 0], est[:, 1], est[:, 2], ok & a_ok,
                        reasons, worst, samples, int(order[0]), angle)


def _failure_reasons(problem: AllocationProblem, model, crit: str, p_lin: np.ndarray, est: np.ndarray, n: np.ndarray,
                     ok: np.ndarray, a_ok: np.ndarray, pa, nongauss_share: float) -> tuple:
    """Per pose, why it failed ("" when it passed): under-specified, non-Gaussian, inconclusive or nonlinear.

    ``p_lin`` (P,): linear position probabilities; ``est`` (P, 3): position estimate and interval; ``n`` (P,) samples; ``ok`` / ``a_ok`` (P,) position /
    orientation verdicts; ``pa`` (P, 3) orientation estimate and interval or None.
    """
    p = problem.prob
    nongauss = np.array([prm.distribution != "normal" for prm in model.params])
    reasons = []
    for i in range(len(est)):
        if ok[i] and a_ok[i]:
            reasons.append("")
            continue
        share = float(variance_share(problem.J[i, :3, :], model.sigma**2)[nongauss].sum())
        bits = []
        if not ok[i]:
            if p_lin[i] < p - 1e-6:
                bits.append(f"under-specified: even the linear prediction P = {p_lin[i]:.4f} < {p:g}")
            elif share >= nongauss_share:
                kinds = sorted({prm.distribution for prm, g in zip(model.params, nongauss) if g})
                bits.append(f"non-Gaussian parameters ({', '.join(kinds)}) carry {share:.0%} of the variance: "
                            f"P_hat = {est[i, 0]:.4f} vs linear-Gaussian {p_lin[i]:.4f}")
            elif est[i, 1] < p <= est[i, 2]:  # the interval contains p: too few samples to tell, whatever P_hat
                bits.append(f"inconclusive: interval [{est[i, 1]:.4f}, {est[i, 2]:.4f}] contains {p:g} "
                            f"at n = {n[i]}; raise --n-mc")
            else:
                bits.append(f"nonlinearity: exact kinematics give P_hat = {est[i, 0]:.4f} "
                            f"[{est[i, 1]:.4f}, {est[i, 2]:.4f}] vs linear {p_lin[i]:.4f}")
        if not a_ok[i]:
            bits.append(f"orientation P_hat = {pa[i, 0]:.4f} below {problem.angle_prob:g}")
        reasons.append("; ".join(bits))
    return tuple(reasons)
