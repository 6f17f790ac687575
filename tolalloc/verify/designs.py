"""Nonlinear Monte Carlo verification of an allocated design at every pose.

The design's error model (``sigma = t / z``) is sampled and evaluated with the exact perturbed
kinematics; ``P(|dP| < r)`` is estimated at every pose with an interval and set beside the linear (Gaussian)
prediction. The intervals of all poses and requirements are simultaneous: ``m`` = poses x requirements intervals
(plus the possible second looks, :func:`~tolalloc.verify.verdicts.verification_family`), each at level
``1 - (1 - level) / m`` (Bonferroni), hold together with probability at least ``level`` (0.95), so
the verdict over all poses is a joint claim at that level. The estimator (``estimator=``, :mod:`tolalloc.montecarlo.paired`): by default the paired
one -- the exact linear P plus the mean difference of the nonlinear and linear indicators on the same draws,
Tango's interval -- where the parameters are Gaussian, plain Monte Carlo (Wilson) elsewhere, importance
sampling where the tail is too thin for the sample size. With an orientation requirement ``P(|dw| < a) >= p_a``
its probability is estimated on the same draws. Criteria (:mod:`tolalloc.verify.verdicts`), for each requirement
against its own ``p``:

* a pose is **demonstrated** when the whole interval of every requirement is at or above its ``p`` (lower bounds
  ``>= p``);
* it **failed** when the whole interval of any requirement lies below its ``p``;
* it is **consistent** otherwise (every interval reaches its ``p``, some lower bound is below).

A **certified** design passes a pose only when every requirement is demonstrated there; an **exact** design passes
a consistent pose (no fixed allowance: a design whose interval lies below ``p`` fails).

A pose whose position interval straddles ``p`` (undecided) is looked at again with ``n_max`` samples -- for a
certified design by any estimator (pooled with the first look, or importance sampling under ``auto``), and under
``estimator="auto"`` on a Gaussian model whatever the criterion, by importance sampling, which resolves the thin shell
where the nonlinear and linear indicators disagree that the paired estimator's few discordant draws cannot -- and is
judged on that look. So with ``n_max > n_mc`` every position interval has a possible second look, counted in the
family (Bonferroni: the family's alpha spent equally on every possible look): ``m`` = poses x requirements + poses
(:func:`tolalloc.verify.verdicts.verification_family`).
Failing poses are named with the reason: *under-specified* (the linear prediction itself is below
``p``), *non-Gaussian* parameters (ring clearances, uniform) carrying a sizeable share of the variance,
*inconclusive* (the interval contains ``p`` at the largest sample size: more samples are needed, whatever
``P_hat``) or *nonlinearity* (the whole interval lies below ``p`` although the linear prediction meets it); the
orientation requirement's as *orientation under-specified*, *orientation inconclusive* or below ``p_a``
(:func:`tolalloc.verify.verdicts.failure_reasons`).

This module holds the result, :class:`Verification`, and the driver, :func:`verify_design`; the Monte Carlo runs at
the poses (first look, and the second look of undecided poses) are in
:mod:`tolalloc.verify.pose_estimates`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, whole_number
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Design
from tolalloc.montecarlo.intervals import simultaneous_level
from tolalloc.montecarlo.estimate import ProbabilityEstimate, fallback_text
from tolalloc.montecarlo.paired import check_estimator, control_fallback_reason
from tolalloc.verify.pose_estimates import _estimate, _redo
from tolalloc.verify.resolution import check_resolvable, choose_estimator
from tolalloc.verify.verdicts import (RequirementCheck, failure_reasons, family_text, interval_words, limiting,
                                      orientation_check, overall_verdict, pose_verdicts, shortfall_text,
                                      verification_family, weakest)

__all__ = ["Verification", "verify_design", "pose_verdicts", "overall_verdict", "check_resolvable"]


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
        Linear prediction, Monte Carlo estimate and its interval (one of ``n_intervals`` simultaneous intervals,
        each at :attr:`level_per_interval`).
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
        Orientation check when the problem has an orientation requirement: ``prob`` (its ``p``), ``p_linear``,
        ``p_mc``, ``ci_low``, ``ci_high``, ``passed`` and ``estimator`` (arrays, shape (P,)).
    estimate : ProbabilityEstimate or None
        The position estimate behind ``p_mc`` / ``ci_*``: estimator per pose, discordant counts, variance
        reduction, plain estimate of the same draws, fallback reasons (:mod:`tolalloc.montecarlo.paired`).
    family_level : float
        Level at which all the intervals (every pose, every requirement) hold together (0.95).
    n_intervals : int
        Intervals in the Bonferroni family: poses x requirements, plus :attr:`second_looks` (1: a single interval at
        ``family_level``).
    second_looks : int
        Possible second looks in ``n_intervals``: one per pose when ``n_max > n_mc`` and the design is certified or
        ``auto`` runs on a Gaussian model, else 0.
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
    estimate: ProbabilityEstimate | None = field(default=None, repr=False)
    family_level: float = 0.95
    n_intervals: int = 1
    second_looks: int = 0

    @property
    def level_per_interval(self) -> float:
        """Level of each interval (Bonferroni): ``1 - (1 - family_level) / n_intervals``."""
        return simultaneous_level(self.family_level, self.n_intervals)

    def interval_label(self) -> str:
        """The intervals' name for tables and figures: ``simultaneous 95% interval`` (``95% interval`` when single)."""
        return f"{interval_words(self.family_level, self.n_intervals)} interval"

    def interval_text(self) -> str:
        """What the intervals are, e.g. ``95% simultaneous over the 18 poses (Bonferroni: 18 intervals at 99.72%
        each)`` (``36 intervals at 99.86% each, a possible second look at each position interval counted`` when
        undecided poses may be re-run)."""
        return family_text(self.family_level, self.n_intervals, len(self.p_mc), 1 + (self.angle is not None),
                           self.second_looks)

    def all_poses_text(self) -> str:
        """``all 18 poses`` (``the 1 pose`` for a single pose)."""
        P = len(self.p_mc)
        return "the 1 pose" if P == 1 else f"all {P} poses"

    @property
    def estimator(self) -> np.ndarray:
        """Estimator that ran at each pose (``plain``, ``paired`` or ``importance``), shape (P,)."""
        return np.full(len(self.p_mc), "plain") if self.estimate is None else self.estimate.estimator

    @property
    def n_discordant(self) -> np.ndarray:
        """Samples on which the nonlinear chain and the linear map disagree, shape (P,) (effective counts for
        importance sampling; 0 where plain Monte Carlo ran)."""
        if self.estimate is None:
            return np.zeros(len(self.p_mc))
        return np.where(self.estimator == "plain", 0.0, self.estimate.n_discordant)

    @property
    def variance_reduction(self) -> np.ndarray:
        """Variance of plain Monte Carlo over the estimator's at the same sample size, shape (P,) (1: plain)."""
        return np.ones(len(self.p_mc)) if self.estimate is None else self.estimate.variance_reduction

    @property
    def fallback_reason(self) -> str:
        """Why plain Monte Carlo ran where a paired estimator was requested ("" if it did not)."""
        return "" if self.estimate is None else fallback_text(self.estimate.fallback)

    def estimator_summary(self) -> dict:
        """JSON-ready estimator block for summary.json's ``verification`` (per-pose lists, poses in order)."""
        vr = [float(x) if np.isfinite(x) else None for x in self.variance_reduction]
        return {"estimator_requested": "plain" if self.estimate is None else self.estimate.requested,
                "estimator": [str(e) for e in self.estimator], "n_discordant": [float(x) for x in self.n_discordant],
                "variance_reduction": vr, "fallback_reason": self.fallback_reason,
                "estimator_message": self.estimator_message()}

    def estimator_message(self) -> str:
        """One line: the estimator(s), discordant samples, variance reduction, fallback reason."""
        if self.estimate is None:
            return "estimator: plain"
        return self.estimate.message()

    @property
    def ok(self) -> bool:
        return bool(np.all(self.passed))

    def requirements(self) -> tuple:
        """The stated requirements' intervals: position, then orientation when the problem has one.

        Returns
        -------
        tuple of :class:`~tolalloc.verify.verdicts.RequirementCheck`
        """
        fam = (self.family_level, self.n_intervals)
        out = [RequirementCheck("position", self.prob, self.p_linear, self.p_mc, self.ci_low, self.ci_high, *fam)]
        if self.angle is not None:
            out.append(orientation_check(self.angle, len(self.p_mc), *fam))
        return tuple(out)

    @property
    def verdicts(self) -> np.ndarray:
        """Per-pose ``demonstrated | consistent | failed`` over every stated requirement, shape (P,).

        Demonstrated only where every requirement's lower (simultaneous) bound is at or above its ``p``; failed where any
        requirement's upper bound is below its ``p``; consistent otherwise (:mod:`tolalloc.verify.verdicts`).
        """
        return weakest(*(c.verdicts for c in self.requirements()))

    @property
    def verdict(self) -> str:
        """Overall verdict: the weakest pose's."""
        return overall_verdict(self.verdicts)

    @property
    def limited_by(self) -> str:
        """The requirement (``position`` or ``orientation``) that sets the overall verdict (least margin)."""
        return limiting(self.requirements()).name

    def requirements_summary(self) -> dict:
        """JSON-ready ``limited_by`` and, per requirement, its verdict and the margin of its deciding bound."""
        return {"limited_by": self.limited_by, "requirements": [c.to_dict() for c in self.requirements()]}

    @property
    def failing(self) -> list:
        """``[(pose number (1-based), reason), ...]``."""
        return [(i + 1, self.reason[i]) for i in np.flatnonzero(~self.passed)]

    def message(self) -> str:
        """One line: the verdict, the criterion, the requirement that limits it and by how much, the failing poses,
        what the intervals are (simultaneous over the poses and requirements)."""
        words = interval_words(self.family_level, self.n_intervals)
        rule = (f"pass: whole {words} interval >= p" if self.criterion == "certified" else
                f"pass: upper {words} bound >= p")
        family = "" if self.n_intervals <= 1 else f"; intervals: {self.interval_text()}"
        checks = self.requirements()
        short = shortfall_text(checks)
        if self.ok:
            angle = ("" if self.angle is None else
                     f"; orientation: lowest P_hat = {self.angle['p_mc'].min():.4f} at pose "
                     f"{int(np.argmin(self.angle['p_mc'])) + 1}")
            both = "" if len(checks) == 1 else " for position and orientation"
            meaning = (f"lower {words} bound >= p at every pose{both}" if self.verdict == "demonstrated" else
                       f"{rule}; not demonstrated at {int(np.sum(self.verdicts != 'demonstrated'))} pose(s): {short}")
            least = "" if short else f"; least margin: {limiting(checks).margin_text()}"
            return (f"verified: {self.verdict} by nonlinear Monte Carlo at {self.all_poses_text()} ({meaning}); "
                    f"lowest P_hat = {self.p_mc.min():.4f} at pose {self.worst_pose + 1}{angle}{least}{family}")
        head = "failed" if self.verdict == "failed" else f"{self.verdict}, criterion not met"
        return (f"verified: {head} ({rule}" + (f"; {short}" if short else "") + ") at "
                + "; ".join(f"pose {i}: {r}" for i, r in self.failing) + family)

    def to_frame(self) -> pd.DataFrame:
        """One row per pose: p_linear, p_mc, ci_low, ci_high, n, passed, reason.

        With an orientation requirement also ``p_linear_angle, p_mc_angle, ci_low_angle, ci_high_angle``;
        ``passed`` and ``verdict`` cover both requirements. ``level_per_interval`` is the level of each interval and
        ``family_level`` the level at which all of them (every pose and requirement) hold together.
        """
        cols = {"pose": np.arange(1, len(self.p_mc) + 1), "p_linear": self.p_linear, "p_mc": self.p_mc,
                "ci_low": self.ci_low, "ci_high": self.ci_high}
        if self.angle is not None:
            nan = np.full(len(self.p_mc), np.nan)
            cols.update({"p_linear_angle": nan if self.angle["p_linear"] is None else self.angle["p_linear"],
                         "p_mc_angle": self.angle["p_mc"], "ci_low_angle": self.angle["ci_low"],
                         "ci_high_angle": self.angle["ci_high"]})
        cols.update({"level_per_interval": self.level_per_interval, "family_level": self.family_level})
        cols.update({"n": self.n, "estimator": self.estimator, "n_discordant": self.n_discordant,
                     "variance_reduction": self.variance_reduction, "passed": self.passed, "verdict": self.verdicts,
                     "reason": list(self.reason)})
        return pd.DataFrame(cols)


def verify_design(problem: AllocationProblem, design: Design, *, criterion: str | None = None, n_mc: int = 10**6,
                  n_max: int | None = None, seed: int = 0, keep_samples: int = 4000,
                  nongauss_share: float = 0.05, scheduler=None, estimator: str = "auto",
                  level: float = 0.95) -> Verification:
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
        Sample size of the second look at poses whose position interval straddles ``p`` (certified criterion, or
        ``estimator="auto"`` on a Gaussian model); default ``4 n_mc``. Must be at least ``n_mc``; ``n_max = n_mc``
        means no second look (each pose judged once, at ``n_mc``).
    seed : int
    keep_samples : int
        Position errors kept at the worst pose for figures.
    nongauss_share : float
        Variance share of non-normal parameters above which a failure is attributed to them.
    scheduler : str or dask.distributed.Client, optional
        Where the Monte Carlo runs (see :func:`tolalloc.montecarlo.parallel.ordered_map`); never changes the numbers.
    estimator : {"auto", "plain", "paired", "importance"}
        How ``P(|dP| < r)`` is estimated (:mod:`tolalloc.montecarlo.paired`): ``paired`` is the exact linear P plus
        the mean difference of the nonlinear and linear indicators on the same draws; ``importance`` the same
        with importance sampling (position requirement; the orientation one is estimated as ``auto``); ``auto``
        is paired where the linear map is an exact control (Gaussian parameters), plain elsewhere (the reason is
        in ``Verification.fallback_reason``), and importance sampling for the second look at undecided poses
        (``n_max`` samples), for a rare-event tail (``1 - p <=`` :data:`~tolalloc.verify.resolution.RARE_TAIL`)
        and wherever ``n_mc`` is too small for the paired interval to resolve the tail ``1 - p``
        (:func:`~tolalloc.verify.resolution.resolvable_n`, at the level of each simultaneous interval); a tail
        that the estimator cannot resolve is refused with the samples needed -- the orientation requirement's
        included, by the same rule (:func:`~tolalloc.verify.resolution.choose_estimator`; importance sampling
        estimates the position requirement only).
    level : float
        Level at which the intervals of all poses and requirements hold together: each of the ``m`` intervals is at
        ``1 - (1 - level) / m`` (Bonferroni), so the verdict over all poses is a joint claim at ``level``. ``m`` =
        poses x requirements, plus one per pose for the certified criterion with ``n_max > n_mc`` (the possible
        second look at each position interval; :func:`~tolalloc.verify.verdicts.verification_family`).
    """
    crit, n_max = _check_args(design, n_mc, n_max, estimator, criterion, level)
    model = problem.model_for(design.t)
    r, p = problem.radius_mm, problem.prob
    ang = problem.angle_radius_rad
    P = problem.n_poses
    looks_by_is = estimator == "auto" and not control_fallback_reason(model)
    m, looks = verification_family(P, 1 if ang is None else 2, crit, n_mc, n_max, importance_look=looks_by_is)
    _check_budget(model, P, n_mc, n_max, looks, estimator)
    lvl = simultaneous_level(level, m)
    what = f"{interval_words(level, m)} interval" + ("" if m == 1 else f" (one of {m}, each at {100 * lvl:.4g}%"
                                                      + (", a possible second look counted)" if looks else ")"))
    reqs = [("position", p)] + ([] if ang is None else [("orientation", problem.angle_prob)])
    asked, estimator = estimator, choose_estimator(model, reqs, n_mc, n_max, looks > 0, estimator, lvl, what)
    p_lin = design.p_linear["position"]
    order = np.argsort(p_lin)  # worst linear pose first: its samples are kept
    est = _estimate(model, problem.q[order], n_mc, seed, r, ang, keep_samples, scheduler, estimator, lvl)
    inv = np.argsort(order)
    pos = replace(est["position"].take(inv), requested=asked)
    samples = pos.details.get("kept_mm")
    pa = None if "orientation" not in est else est["orientation"].take(inv)

    def passes(lo, hi):
        return lo >= p if crit == "certified" else hi >= p

    if looks:  # the second look, counted in the family: more samples where an interval straddles p
        redo = np.flatnonzero((pos.ci_low < p) & (pos.ci_high >= p))
        if redo.size:
            pos = _redo(model, problem, pos, redo, n_mc, n_max, seed, scheduler, estimator)
    est_arr = np.stack([pos.p_hat, pos.ci_low, pos.ci_high], axis=1)
    n = np.asarray(pos.n, int)
    ok = passes(est_arr[:, 1], est_arr[:, 2])
    angle, a_ok, a_check, a_n = None, np.ones(P, bool), None, None
    if pa is not None:
        ap = problem.angle_prob
        a_ok = pa.ci_low >= ap if crit == "certified" else pa.ci_high >= ap
        angle = {"prob": float(ap), "p_linear": design.p_linear.get("orientation"), "p_mc": pa.p_hat,
                 "ci_low": pa.ci_low, "ci_high": pa.ci_high, "passed": a_ok, "estimator": pa.estimator}
        a_check, a_n = orientation_check(angle, P, level, m), np.asarray(pa.n, int)
    reasons = failure_reasons(problem, model, p_lin, est_arr, n, ok, a_ok, a_check, a_n, nongauss_share)
    worst = int(np.argmin(est_arr[:, 0]))
    return Verification(crit, r, p, n, int(seed), p_lin.copy(), est_arr[:, 0], est_arr[:, 1], est_arr[:, 2], ok & a_ok,
                        reasons, worst, samples, int(order[0]), angle, pos, float(level), m, looks)


def _check_budget(model, n_poses: int, n_mc: int, n_max: int, looks: int, estimator: str) -> None:
    """Refuse sample sizes the verification cannot run within the time budget (:mod:`tolalloc.budget`): ``n_mc`` at
    every pose, and ``n_max`` at every pose when second looks are possible (importance sampling or pooled)."""
    from tolalloc.verify.cost import check_verification_budget

    check_verification_budget(model, n_poses, n_mc, estimator=estimator, announce=False)
    if looks:
        second = "importance" if estimator in ("auto", "importance") and not control_fallback_reason(model) \
            else estimator
        check_verification_budget(model, n_poses, n_max, estimator=second, argument="n_max", announce=False)


def _check_args(design, n_mc, n_max, estimator, criterion, level) -> tuple:
    """Refuse what :func:`verify_design` cannot verify; returns the criterion and ``n_max`` (default ``4 n_mc``)."""
    if design.t is None:
        raise TolallocError(f"verify: the design ({design.solver}) has no tolerances ({design.status}); nothing to verify.")
    if design.status == NOT_CONVERGED:
        raise TolallocError(f"verify: the design {design.label} did not converge ({design.message}); re-solve it "
                            "(or verify its tolerances as a design of their own) before calling it verified.")
    whole = whole_number(n_mc)
    if whole is None or whole < 100:
        raise TolallocError(f"n_mc: expected an integer number of samples >= 100, got {n_mc!r}.")
    most = 4 * whole if n_max is None else whole_number(n_max)
    if most is None or most < whole:
        raise TolallocError(f"n_max: expected a whole number n_max >= n_mc (the second look of a certified pose uses "
                            f"more samples), got n_max={n_max!r}, n_mc={whole}; give n_max >= n_mc (n_max = n_mc: no "
                            "second look), or leave it out (default 4 x n_mc).")
    if isinstance(level, bool) or not isinstance(level, (int, float, np.floating)) or not 0.5 <= level < 1:
        raise TolallocError(f"level: expected a confidence level in [0.5, 1) for the simultaneous intervals "
                            f"(e.g. 0.95), got {level!r}.")
    check_estimator(estimator)
    crit = criterion or ("certified" if design.solver.certified else "exact")
    if crit not in ("certified", "exact"):
        raise TolallocError(f"criterion: expected 'certified' or 'exact', got {crit!r}.")
    return crit, most
