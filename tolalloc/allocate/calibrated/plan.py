"""Plan and tolerances designed together: a calibration plan for the allocation that uses it.

:func:`design_plan_for_allocation` alternates

1. allocate with the current plan (:func:`tolalloc.allocate.calibrated.design.allocate_with_calibration`, over the
   poses or the region);
2. re-design the plan for that design: prior = the design's sigmas, evaluation poses = where its requirement binds
   (the allocation's final poses: the pose set, or the region's active set), criterion = the worst post-calibration
   probability there (:func:`tolalloc.calibration.design_worst.design_plan_worst`, started from the current plan
   and, in the first round, from the A-optimal plan for that prior);

and keeps a new plan only if the allocation with it is cheaper; it stops at the first round that does not lower the
cost (or after ``rounds``). The start is the task-weighted A-optimal plan of :func:`tolalloc.calibration.design.
design_plan` at the problem's poses under the robot file's sigmas (what ``tolalloc calplan`` writes).

:func:`compare_with_random_plans` states the designed plan against the distribution of random plans of the same size
from the same candidates, at the final design: worst-pose post-calibration ``P`` (median, 10th and 90th percentile)
and the bound that no plan from these candidates can pass (every candidate measured).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.calibrated.design import CalibratedDesign, allocate_with_calibration
from tolalloc.calibration.check import min_plan_poses
from tolalloc.calibration.design import design_plan
from tolalloc.calibration.design_worst import design_plan_worst, plan_worst_p, random_plan_worst_p
from tolalloc.calibration.plan import CalibrationPlan, make_plan
from tolalloc.calibration.split import split_errors
from tolalloc.exceptions import TolallocError

__all__ = ["PlanForAllocation", "design_plan_for_allocation", "PlanComparison", "compare_with_random_plans"]


@dataclass(frozen=True, eq=False)
class PlanForAllocation:
    """Result of :func:`design_plan_for_allocation`.

    Attributes
    ----------
    plan : CalibrationPlan
        The kept plan.
    result : CalibratedDesign
        The allocation with it (with the caller's coverage and baseline settings).
    start_plan : CalibrationPlan
    start_cost : float
        Cost of the allocation with the start plan.
    history : tuple of (round, cost, worst_p_at_binding_poses, kept)
    time_s : float
    """

    plan: CalibrationPlan
    result: CalibratedDesign
    start_plan: CalibrationPlan
    start_cost: float
    history: tuple
    time_s: float

    def message(self) -> str:
        r = self.result
        return (f"plan designed for the allocation: {self.plan.n_poses} poses, {len(self.history)} round(s); cost "
                f"{r.cost:.4f} (start plan {self.start_cost:.4f})")


def design_plan_for_allocation(problem, n_poses: int, candidates, *, split=None, region=None,
                               start: CalibrationPlan | None = None, rounds: int = 3, exact: bool = True,
                               baseline: bool = True, coverage_n: int = 100_000, seed: int = 0,
                               noise_mm: float = 0.02, registration: bool = True,
                               relaxation: str = "auto") -> PlanForAllocation:
    """Alternate plan design and allocation (module docstring); position measurements.

    Parameters
    ----------
    problem : AllocationProblem
    n_poses : int
        Plan size, at least :func:`tolalloc.calibration.check.min_plan_poses`.
    candidates : array, shape (C, n) [rad, mm]
        Candidate measurement poses (e.g. :func:`tolalloc.calibration.design.candidate_poses`).
    region, exact, baseline, coverage_n, seed
        As :func:`tolalloc.allocate.calibrated.design.allocate_with_calibration` (the intermediate allocations skip
        the coverage check and the baseline).
    start : CalibrationPlan, optional
        Default: the A-optimal plan at the problem's poses under the file's sigmas.
    rounds : int
        At most this many re-designs.
    relaxation : str
        Relaxation of the A-optimal plans (:func:`tolalloc.calibration.design.design_plan`).
    """
    t0 = time.perf_counter()
    split = split_errors(problem.model) if split is None else split
    robot = problem.model.robot
    candidates = np.asarray(candidates, float)
    if not isinstance(rounds, (int, np.integer)) or isinstance(rounds, bool) or rounds < 0:
        raise TolallocError(f"rounds: expected a whole number >= 0, got {rounds!r}.")
    like = make_plan(robot, candidates[:1], noise_mm=noise_mm, registration=registration)
    need = min_plan_poses(split, like)
    if not isinstance(n_poses, (int, np.integer)) or isinstance(n_poses, bool) or not need <= n_poses <= len(
            candidates):
        raise TolallocError(f"n_poses: expected a whole number between {need} (the fewest poses that identify what "
                            f"a calibration of {robot.name} can) and the {len(candidates)} candidates, got {n_poses!r}.")
    plan = start if start is not None else design_plan(split, int(n_poses), candidates, problem.q, noise_mm=noise_mm,
                                                       registration=registration, relaxation=relaxation).plan
    kw = dict(split=split, region=region, exact=exact, seed=seed)
    res = allocate_with_calibration(problem, plan, baseline=False, coverage_n=0, **kw)
    if not res.design.ok:
        raise TolallocError(f"problem: no calibration-aware design meets the requirement with the start plan "
                            f"({res.design.message}); relax the requirement or the process limits.")
    start_plan, start_cost = plan, res.cost
    hist = [(0, res.cost, float(plan_worst_p(res.post.split, plan, res.problem.q, problem.radius_mm).min()), True)]
    for rnd in range(1, rounds + 1):
        w = design_plan_worst(res.post.split, int(n_poses), candidates, res.problem.q, problem.radius_mm, start=plan,
                              noise_mm=noise_mm, registration=registration, a_optimal=rnd == 1,
                              relaxation=relaxation)
        new = allocate_with_calibration(problem, w.plan, baseline=False, coverage_n=0, **kw)
        kept = new.design.ok and new.cost < res.cost * (1 - 1e-7)
        hist.append((rnd, new.cost if new.design.ok else float("nan"), w.worst_p, kept))
        if not kept:
            break
        plan, res = w.plan, new
    final = allocate_with_calibration(problem, plan, baseline=baseline, coverage_n=coverage_n, **kw)
    return PlanForAllocation(plan, final, start_plan, start_cost, tuple(hist), time.perf_counter() - t0)


@dataclass(frozen=True, eq=False)
class PlanComparison:
    """Result of :func:`compare_with_random_plans` (worst-pose post-calibration ``P`` at one design).

    Attributes
    ----------
    designed : float
    random : array, shape (count,)
    all_candidates : float
        With every candidate measured: no plan from these candidates exceeds it.
    n_poses : int
    """

    designed: float
    random: np.ndarray
    all_candidates: float
    n_poses: int

    @property
    def better_than(self) -> float:
        """Share of the random plans the designed plan beats."""
        return float(np.mean(self.random < self.designed))

    def to_dict(self) -> dict:
        r = self.random
        return {"n_poses": self.n_poses, "designed_worst_p": self.designed, "random_median": float(np.median(r)),
                "random_p10": float(np.quantile(r, 0.1)), "random_p90": float(np.quantile(r, 0.9)),
                "random_max": float(r.max()), "n_random": len(r), "better_than_share": self.better_than,
                "all_candidates_worst_p": self.all_candidates}

    def message(self) -> str:
        d = self.to_dict()
        return (f"worst-pose post-calibration P at the design: designed plan {self.designed:.5f}; {len(self.random)} "
                f"random {self.n_poses}-pose plans: median {d['random_median']:.5f}, 10th percentile "
                f"{d['random_p10']:.5f}, 90th {d['random_p90']:.5f}; the designed plan beats "
                f"{100 * self.better_than:.1f} % of them; every candidate measured: {self.all_candidates:.5f}")


def compare_with_random_plans(res: CalibratedDesign, candidates, *, count: int = 200, seed: int = 0,
                              q_eval=None) -> PlanComparison:
    """Designed plan of ``res`` against ``count`` random plans of its size at ``res``'s design (module docstring).

    ``q_eval`` (default the design's poses: the pose set or the region's active set) [rad, mm].
    """
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise TolallocError(f"count: expected a whole number >= 1, got {count!r}.")
    sp, plan, r = res.post.split, res.plan, res.problem.radius_mm
    q = res.problem.q if q_eval is None else np.atleast_2d(np.asarray(q_eval, float))
    candidates = np.asarray(candidates, float)
    rnd = random_plan_worst_p(sp, candidates, plan.n_poses, q, r, count=count, seed=seed, like=plan)
    every = make_plan(sp.model.robot, candidates, measurement=plan.measurement, noise_mm=plan.noise_mm,
                      noise_deg=np.rad2deg(plan.noise_rad), registration=plan.registration)
    return PlanComparison(float(plan_worst_p(sp, plan, q, r).min()), rnd, float(plan_worst_p(sp, every, q, r).min()),
                          plan.n_poses)
