"""Correction loop: tighten the targets where the nonlinear Monte Carlo does not demonstrate a requirement.

After a design is verified, every requirement -- the position one and, when stated, the orientation one -- gets,
at every pose that lacks the margin, a new target ``p + max(0, P_lin - P_hat) + k_se se``: the measured shortfall
of the nonlinear estimate below the linear prediction plus ``k_se`` standard errors of ``P_hat`` (the estimator's:
paired and importance-sampling estimates resolve the nonlinearity itself, so the margin shrinks to it; never below
its previous target; never 1 or more: where the interval is too wide for any target below 1 to carry the margin, only
an estimate below ``p`` is tightened, and a pose whose estimate clears ``p`` is left to more samples,
:func:`needed_targets`). A pose lacks the margin where the lower bound of its interval (simultaneous over the poses
and requirements) lies below ``p +`` :data:`MARGIN_SE` standard errors: not *demonstrated*, or demonstrated on
these draws by too little to hold on fresh ones (a pose on ``p`` whose nonlinear estimate cleared it by chance). By default ``k_se = z +`` :data:`MARGIN_SE`
(3), ``z`` the normal quantile of each simultaneous interval (1.96 for a single 95 % interval, 2.99 for 18 poses,
3.20 for 18 certified poses with a possible second look at each: 36 intervals,
:func:`tolalloc.verify.verdicts.verification_family`): a re-solved pose sits about ``z + 3`` standard errors above
``p``; the corrected design is judged on fresh draws (below), whose estimate and the one that set the target each
carry about one standard error of noise, so the 3 are about two standard deviations of their difference. The
allocation is solved again with these per-pose targets (:func:`tolalloc.allocate.problem.build_problem`
``target=`` and ``angle_target=``) and re-verified against the requirements themselves (same seed, same poses), at
most ``max_rounds`` times; then the loop stops and says so.

The rounds re-use the draws that measured the shortfall (common random numbers: a round's change is not lost in
sampling noise), so a corrected design that they call *demonstrated* was tuned on those draws; the 95 % claim of a
verification holds for draws the design did not depend on. A corrected design is therefore judged once more on
fresh draws (seed ``seed +`` :data:`CONFIRM_SEED_OFFSET`), and that verification is the result: demonstrated
there, or stopped with what fell short. A design demonstrated at the first verification (no round) needs no
second run: nothing was tuned on its draws.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.problem import build_problem
from tolalloc.exceptions import ArgumentError
from tolalloc.verify.designs import Verification, verify_design
from tolalloc.verify.verdicts import shortfall_text

__all__ = ["Correction", "correct_design", "needed_targets", "imprecise_poses", "CONFIRM_SEED_OFFSET", "MARGIN_SE"]

#: Standard errors beyond the interval's half-width ``z`` that a tightened pose's target carries (``k_se = z + 3``).
MARGIN_SE = 3.0

#: Seed offset of the fresh draws a corrected design is judged on (apart from ``seed`` and ``seed + 1``, which a
#: verification's own second look uses).
CONFIRM_SEED_OFFSET = 1_000_000


@dataclass(frozen=True, eq=False)
class Correction:
    """Result of :func:`correct_design`.

    Attributes
    ----------
    result : AllocationResult
        The final allocation (the input one if no round was needed or none succeeded).
    verification : Verification
        Its verification against ``p`` (verdict per pose and overall); after a correction round (demonstrated or
        stopped), the one on fresh draws (:attr:`confirm_seed`).
    before : Verification
        The verification of the uncorrected design.
    rounds : int
        Correction rounds whose design was kept (0: nothing was re-solved).
    targets : array, shape (P,)
        The per-pose position probability target of the final design (``p`` where no pose was tightened).
    costs : tuple of float
        The design cost of each kept solve (first: the uncorrected design).
    stopped : bool
        True when the final design is still not demonstrated (round limit, or no further tightening possible).
    reason : str
        Why the loop ended.
    angle_targets : array, shape (P,) or None
        The same for the orientation requirement (``angle_prob`` where no pose was tightened); None without one.
    tuned : Verification or None
        The final design's verification on the draws the rounds were tuned on (None: no round ran).
    confirm_seed : int or None
        Seed of the fresh draws of :attr:`verification` (None when no fresh run was made).
    """

    result: object
    verification: Verification
    before: Verification
    rounds: int
    targets: np.ndarray
    costs: tuple
    stopped: bool
    reason: str = ""
    angle_targets: np.ndarray | None = None
    tuned: Verification | None = None
    confirm_seed: int | None = None

    @property
    def cost_of_correction(self) -> float:
        """Final cost minus the uncorrected cost."""
        return float(self.costs[-1] - self.costs[0])

    @property
    def premium_pct(self) -> float:
        """The cost of the correction in % of the uncorrected cost."""
        return 100.0 * self.cost_of_correction / self.costs[0] if self.costs[0] else float("nan")

    @property
    def tightened(self) -> np.ndarray:
        """Pose indices (0-based) whose position target was raised above ``p``."""
        return np.flatnonzero(self.targets > self.verification.prob)

    @property
    def tightened_angle(self) -> np.ndarray:
        """Pose indices (0-based) whose orientation target was raised above ``angle_prob`` (empty without one)."""
        if self.angle_targets is None:
            return np.zeros(0, int)
        return np.flatnonzero(self.angle_targets > self.verification.angle["prob"])

    def message(self) -> str:
        v = self.verification

        def listed(idx, tgt):
            return ", ".join(f"{i + 1} ({tgt[i]:.5f})" for i in idx) or "none"

        poses = listed(self.tightened, self.targets)
        if self.angle_targets is not None:
            poses += f"; orientation poses tightened (target): {listed(self.tightened_angle, self.angle_targets)}"
        fresh = ("" if self.confirm_seed is None else
                 f", judged on fresh draws (seed {self.confirm_seed}; on the draws the rounds were tuned on, seed "
                 f"{self.tuned.seed}, it was {self.tuned.verdict})")
        head = (f"verified: {v.verdict} after {self.rounds} correction round(s){fresh} "
                f"(before: {self.before.verdict}); poses tightened (target): {poses}; cost {self.costs[0]:.4f} -> {self.costs[-1]:.4f} "
                f"({self.cost_of_correction:+.4f}, {self.premium_pct:+.3g} %)")
        return head + (f"; stopped, not demonstrated: {self.reason}" if self.stopped else "")

    def to_dict(self) -> dict:
        """JSON-ready ``correction`` block of summary.json (poses 1-based)."""
        v = self.verification
        ang = self.angle_targets
        return {"rounds": self.rounds, "stopped": self.stopped, "reason": self.reason,
                "poses_tightened": [int(i) + 1 for i in self.tightened],
                "target_per_pose": [float(x) for x in self.targets],
                "poses_tightened_angle": [int(i) + 1 for i in self.tightened_angle],
                "angle_target_per_pose": None if ang is None else [float(x) for x in ang],
                "cost_before": float(self.costs[0]), "cost_after": float(self.costs[-1]),
                "cost_of_correction": self.cost_of_correction, "premium_pct": self.premium_pct,
                "costs_per_round": [float(c) for c in self.costs],
                "verdict_before": self.before.verdict, "verdicts_before": self.before.verdicts.tolist(),
                "verdict": v.verdict, "verdicts": v.verdicts.tolist(), "estimator": [str(e) for e in v.estimator],
                "confirm_seed": self.confirm_seed, "verdict_tuned": None if self.tuned is None else self.tuned.verdict,
                "message": self.message()}


def needed_targets(check, targets, k_se: float | None = None) -> np.ndarray:
    """Per-pose targets of one requirement for the next round, shape (P,); never 1 or more.

    ``max(target, p + max(0, P_lin - P_hat) + k_se se)`` at the poses whose lower bound lies below
    ``p + (k_se - z) se`` (not demonstrated, or by less than the margin beyond ``z``, :data:`MARGIN_SE` by
    default); unchanged elsewhere. ``se`` is the standard error implied by the pose's interval (half its
    width over ``z``, the normal quantile of the interval's own level -- for simultaneous intervals the Bonferroni
    one): ``sqrt(P_hat (1 - P_hat) / n)`` for plain Monte Carlo, the far smaller paired or importance-sampling one
    otherwise, so the margin is what the estimator can resolve, not what plain sampling could. ``k_se`` None:
    ``z +`` :data:`MARGIN_SE`. An unknown linear prediction (NaN) counts as no shortfall.

    Where that target would be 1 or more, the interval is too wide for any design to clear ``p`` by it (the
    imprecision, not the design, is short): such a pose is tightened only when its estimate itself is below ``p``,
    to the target halfway between ``p + max(0, P_lin - P_hat)`` and 1; a pose whose estimate is at or above ``p``
    keeps its target (more samples decide it: :func:`imprecise_poses`).

    Parameters
    ----------
    check : RequirementCheck or Verification
        One requirement's ``prob``, ``p_linear``, ``p_mc``, ``ci_low``, ``ci_high`` (a
        :class:`~tolalloc.verify.verdicts.RequirementCheck` of :meth:`Verification.requirements`; a
        :class:`~tolalloc.verify.designs.Verification` stands for its position requirement), with the level of its
        intervals.
    targets : array, shape (P,)
        This requirement's current targets.
    """
    check, targets, z, k_se, se = _margin_terms(check, targets, k_se)
    base = check.prob + np.nan_to_num(np.maximum(0.0, check.p_linear - check.p_mc), nan=0.0)
    need = base + k_se * se
    # not demonstrated by the margin beyond z (MARGIN_SE by default): fresh draws could still fail it (a pose on p
    # whose nonlinear estimate cleared it on these draws only)
    short = check.ci_low < check.prob + max(0.0, k_se - z) * se
    too_wide = need >= 1.0
    halfway = np.where(base < 1.0, 0.5 * (base + 1.0), targets)
    need = np.where(too_wide, np.where(check.p_mc < check.prob, halfway, targets), need)
    return np.where(short, np.maximum(targets, need), targets)


def imprecise_poses(check, targets, k_se: float | None = None) -> np.ndarray:
    """Poses (0-based) of one requirement that are short of the margin only for the imprecision of their interval:
    the estimate is at or above ``p``, but a target carrying ``k_se`` standard errors would be 1 or more
    (:func:`needed_targets` leaves them)."""
    check, targets, z, k_se, se = _margin_terms(check, targets, k_se)
    need = check.prob + np.nan_to_num(np.maximum(0.0, check.p_linear - check.p_mc), nan=0.0) + k_se * se
    short = check.ci_low < check.prob + max(0.0, k_se - z) * se
    return np.flatnonzero(short & (need >= 1.0) & (check.p_mc >= check.prob))


def _margin_terms(check, targets, k_se) -> tuple:
    """``(check, targets, z, k_se, se)`` of :func:`needed_targets`."""
    from tolalloc.montecarlo.intervals import z_of_level

    if isinstance(check, Verification):
        check = check.requirements()[0]
    z = z_of_level(check.level)
    k_se = z + MARGIN_SE if k_se is None else k_se
    se = np.maximum((check.ci_high - check.ci_low) / (2 * z), 1e-12)
    return check, np.asarray(targets, float), z, k_se, se


def correct_design(model, q, *, solver: str = "exact", n_mc: int = 10**5, seed: int = 0, k_se: float | None = None,
                   max_rounds: int = 2, result=None, verification: Verification | None = None, snap: bool = False,
                   angle_step_deg: float | None = None, scheduler=None, keep_samples: int = 0,
                   estimator: str = "auto", standard: bool = False, level: float | None = None,
                   **problem_kw) -> Correction:
    """Allocate, verify and, where the Monte Carlo falls short of a requirement, tighten those poses and re-solve.

    Every stated requirement (position, and orientation when ``angle_radius_deg`` is given) is tightened by the
    same rule (:func:`needed_targets`) at the poses where its lower bound (of the intervals simultaneous over the
    poses and requirements) is below its ``p`` plus :data:`MARGIN_SE` standard errors. A corrected design is judged
    on fresh draws (seed ``seed +`` :data:`CONFIRM_SEED_OFFSET`), whose verification is the result.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (P, n) [rad, mm]
        The poses that are verified (and tightened).
    solver : {"exact", "certified"}
    n_mc : int
        Monte Carlo samples per pose.
    seed : int
    k_se : float, optional
        Margin in standard errors added to the measured shortfall; default ``z + 3``, ``z`` the normal quantile of
        each simultaneous interval of the verification (so the margin outgrows the intervals' half-width).
    max_rounds : int
        Correction rounds before the loop stops.
    result : AllocationResult, optional
        An allocation already solved for ``p`` on ``q`` (saves the first solve).
    verification : Verification, optional
        Its verification on ``q`` (saves the first Monte Carlo run).
    snap, angle_step_deg
        Passed to :func:`tolalloc.allocate.solve.allocate` for the re-solved designs.
    scheduler
        Where the Monte Carlo runs (never changes the numbers).
    keep_samples : int
        Position errors kept at the worst linear pose of each re-verification (for figures).
    estimator : {"auto", "plain", "paired", "importance"}
        Estimator of every verification (:func:`~tolalloc.verify.designs.verify_design`); with ``paired`` or
        ``importance`` the targets carry the estimator's own (much smaller) standard error.
    standard : bool
        Verify (and cost) each round's standard design, the one that will be built (needs ``snap=True``), instead of
        its continuous design.
    level : float, optional
        Family level of every verification (the intervals of all poses and requirements hold together at it,
        :func:`~tolalloc.verify.designs.verify_design`); default: the given ``verification``'s
        ``family_level``, else 0.95. A ``level`` that differs from the given verification's is refused.
    problem_kw
        The requirement and costs, as :func:`tolalloc.allocate.problem.build_problem` (``radius_mm``, ``prob``,
        ``costs``, ``angle_radius_deg``, ``angle_prob``).
    """
    from tolalloc.allocate.solve import allocate
    from tolalloc.montecarlo.paired import check_estimator

    check_estimator(estimator)
    level = _family_level(level, verification, seed)

    def solve(targets=None):
        t = targets or {}
        problem = build_problem(model, q, target=t.get("position"), angle_target=t.get("orientation"), **problem_kw)
        return allocate(problem, solver=solver, snap=snap, angle_step_deg=angle_step_deg)

    def built(res):
        return res.standard if standard and res.standard is not None else res.design

    def check(res, draws=seed):  # against p itself (the problem's prob), with the design's own criterion
        return verify_design(res.problem, built(res), n_mc=n_mc, seed=draws, keep_samples=keep_samples,
                             scheduler=scheduler, estimator=estimator, level=level)

    res = result if result is not None else solve()
    before = ver = verification if verification is not None else check(res)
    targets = {c.name: np.full(len(c.p_mc), c.prob) for c in ver.requirements()}
    costs, rounds, cause = [float(built(res).cost)], 0, ""
    while ver.verdict != "demonstrated":
        if rounds >= max_rounds:
            cause = f"round limit ({max_rounds}) reached"
            break
        new = {c.name: needed_targets(c, targets[c.name], k_se) for c in ver.requirements()}
        cause = _cannot_tighten(new, targets, ver, k_se)
        if cause:
            break
        nxt = solve(new)
        if not built(nxt).ok or nxt.status != "optimal":
            cause = f"the tightened problem has no design ({nxt.status}: {built(nxt).message or nxt.message})"
            break
        res, targets, rounds = nxt, new, rounds + 1
        costs.append(float(built(res).cost))
        ver = check(res)
    ver, tuned, confirm_seed, reason = _on_fresh_draws(ver, rounds, max_rounds, lambda s: check(res, s), seed, cause)
    return Correction(res, ver, before, rounds, targets["position"], tuple(costs), ver.verdict != "demonstrated",
                      reason, targets.get("orientation"), tuned, confirm_seed)


def _on_fresh_draws(ver: Verification, rounds: int, max_rounds: int, check, seed: int, cause: str) -> tuple:
    """``(verification, tuned, confirm_seed, reason)`` of the loop's result: a design corrected in ``rounds`` > 0 is
    verified again on fresh draws (``check(seed + offset)``), which decide -- its verification on the tuning draws
    (``ver``) set its targets; with no round ``ver`` stands (``tuned``, ``confirm_seed`` None). ``cause``: why the
    loop stopped ("" when it ended demonstrated); stopped by the round limit ``max_rounds``, the reason also says
    what is still short."""
    at_limit = rounds >= max_rounds and ver.verdict != "demonstrated"  # the loop checks the limit first in a round
    if not rounds:
        return ver, None, None, cause + (f"; still short: {shortfall_text(ver.requirements())}" if at_limit else "")
    confirm_seed = int(seed) + CONFIRM_SEED_OFFSET
    fresh = check(confirm_seed)
    if fresh.verdict == "demonstrated":
        reason = ""
    elif ver.verdict == "demonstrated":
        reason = (f"demonstrated on the draws the rounds were tuned on (seed {seed}), not on fresh draws (seed "
                  f"{confirm_seed}): {shortfall_text(fresh.requirements())}")
    else:  # the loop stopped short: why, with the shortfall the fresh draws measure
        reason = f"{cause}; on fresh draws (seed {confirm_seed}) still short: {shortfall_text(fresh.requirements())}"
    return fresh, ver, confirm_seed, reason


def _family_level(level, verification, seed: int) -> float:
    """The family level of the loop's verifications: ``level``, else the given verification's, else 0.95; a given
    verification of other draws than ``seed``'s is refused (the rounds are tuned on its draws)."""
    if verification is None:
        return 0.95 if level is None else level
    if level is not None and level != verification.family_level:
        raise ArgumentError("level", f"{level!r} differs from the family level {verification.family_level:g} of the "
                            "given `verification`; leave `level` out (the verification's is used) or verify again "
                            "at the level wanted.")
    if verification.seed != seed:
        raise ArgumentError("seed", f"{seed!r} differs from the seed {verification.seed} of the given "
                            "`verification`, whose draws the rounds are tuned on; pass seed="
                            f"{verification.seed}, or verify again with seed={seed!r}.")
    return verification.family_level


def _cannot_tighten(new: dict, targets: dict, ver: Verification, k_se) -> str:
    """Why the next round cannot be solved ("" when it can): nothing raised -- every pose short of ``p`` already
    carries its measured shortfall and margin, or is short only for the imprecision of its interval."""
    if any(np.any(new[k] > targets[k]) for k in new):
        return ""
    wide = [(c, i) for c in ver.requirements() for i in imprecise_poses(c, targets[c.name], k_se)]
    if wide:
        c, i = wide[0]
        half = 0.5 * (c.ci_high[i] - c.ci_low[i])
        more = f" (and {len(wide) - 1} more)" if len(wide) > 1 else ""
        return (f"{c.name} pose {i + 1}{more}: the estimate {c.p_mc[i]:.8g} is at or above p = {c.prob:g}, but its "
                f"interval (half-width {half:.2g}) is too wide to demonstrate it, and a target carrying that "
                "imprecision would be 1 or more; more samples (`n_mc`) or importance sampling (`estimator`) would "
                "decide it, tightening cannot")
    return ("no pose short of p can be tightened further: every such target already covers the measured "
            "shortfall and margin")
