"""Calibration-plan design in one call: :func:`plan_calibration`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, check_memory, known_names
from tolalloc.outputs import atomic_output
from tolalloc.progress import StageBar, show_progress
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["plan_calibration", "CalibrationPlanDesign"]

#: memory of one candidate pose in the design [bytes]: its information block, the relaxation's share and the
#: solver's (about 30 kB measured with tracemalloc on the tool_changer, doubled for what it does not see)
CANDIDATE_BYTES = 65536
#: tracker noise sigma: 0.1 um .. 1 m and 1e-6 .. 10 deg. Below, the posterior of the candidates is conditioned
#: beyond what the design's factorizations resolve (the all-candidates floor drifts above a plan's score at
#: 1e-5 mm); no tracker comes near (typical: 0.005 .. 0.05 mm)
NOISE_MM_RANGE = (1e-4, 1e3)
NOISE_DEG_RANGE = (1e-6, 10.0)


def _check_tool_moves(model, q_eval, rob, ev: str) -> None:
    """Refuse a robot whose tool point no error parameter moves at the evaluation poses (nothing to calibrate)."""
    if not np.any(np.abs(model.jacobian(q_eval)[:, :3, :]) > 1e-9):
        raise ArgumentError("robot", f"{rob.name!r}: no error parameter moves the tool point at the {ev} poses (the "
                            "tool lies on every joint axis), so a calibration has nothing to reduce; expected a robot "
                            "whose tool point is off its joint axes (a tool offset or links), or other eval_poses.")


@inputs.job_entry
def plan_calibration(robot="tool_changer", n_poses: int = 30, *, region: str = "limits", eval_poses: str | None = None,
                     n_candidates: int = 2000, measurement: str = "position", noise_mm: float = 0.02,
                     noise_deg: float = 0.001, registration: bool = True, costs=None, sigma_set: str | None = None,
                     seed: int = 0, tool: str | None = None, trust_units: bool = False, for_allocation: bool = False,
                     radius_mm: float = 0.25, prob: float = 0.95, random_plans: int = 100,
                     progress: bool | None = None) -> "CalibrationPlanDesign":
    """Choose ``n_poses`` laser-tracker measurement poses that minimise the post-calibration error.

    Candidates are scrambled-Sobol poses in the joint limits (``region="limits"``) or in the box of a pose set; the
    plan minimises the mean post-calibration position variance of the systematic errors over the evaluation
    poses (task-weighted A-optimal design: a convex relaxation solved by SciPy's interior-point method, then
    rounding and exchange) and is compared with ``n_poses`` random candidates.

    Parameters
    ----------
    robot : Robot, str or path
    n_poses : int
        Measurement poses in the plan.
    region : str
        ``"limits"`` or a pose set whose box holds the candidates.
    eval_poses : str, optional
        Pose set where the accuracy matters (default ``working`` if defined, else nominal).
    measurement : {"position", "pose"}
    noise_mm, noise_deg : float
        Tracker noise sigma per coordinate [mm] and per axis [deg] (``noise_deg``: pose measurements only).
    registration : bool
        Estimate the tracker frame and tool offset too (False: they are known).
    costs : str or path, optional
        Costs file whose ``[calibration]`` table overrides the systematic / random split.
    sigma_set : str, optional
        Manufacturing sigma set of the robot file (the prior).
    for_allocation : bool
        Design the plan for the calibration-aware allocation it serves: starting from the A-optimal plan, alternate
        the allocation for ``P(|dP| < radius_mm) >= prob`` (over the robot's ``working`` box if it has one, else at
        the evaluation poses) and a re-design that maximises the worst post-calibration P at the design's binding
        poses, keeping a plan only when the allocation gets cheaper; then compare the plan with ``random_plans``
        random plans of the same size (median, 10th and 90th percentile of their worst-pose P). Position
        measurements only; ``radius_mm``, ``prob`` and ``random_plans`` are read only here (refused, away from their
        defaults, without it).
    progress : bool, optional
        The job's stages on stderr (:mod:`tolalloc.progress`: a status line on a terminal, a line per stage in a log).

    Returns
    -------
    CalibrationPlanDesign
        ``.save(path)`` writes the plan CSV that ``allocate_tolerances(calibration=path)`` reads;
        ``allocate_tolerances(calibration=result)`` takes the result itself.

    Examples
    --------
    >>> import tolalloc
    >>> d = tolalloc.plan_calibration("tool_changer", 8, n_candidates=64)
    >>> d.plan.n_poses, d.design.score_mm2 < d.design.random_score_mm2
    (8, True)
    """
    n_cand, n_poses = _check_design_args(n_candidates, n_poses, noise_mm, noise_deg, measurement, registration,
                                         for_allocation, progress)
    _check_unused(for_allocation, measurement, radius_mm=radius_mm, prob=prob, random_plans=random_plans,
                  noise_deg=noise_deg)
    seed = inputs.check_seed(seed)
    costs = inputs.check_costs_file(costs)
    inputs.check_name(region, "region", "'limits' or the name of a pose set of the robot")
    inputs.check_name(eval_poses, "eval_poses", "the name of a pose set of the robot")
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    _check_region(rob, region)
    from tolalloc.calibration.design import candidate_poses, design_plan
    from tolalloc.calibration.posterior import posterior
    from tolalloc.workflows.calibrated import split_from_costs

    model = inputs.error_model(rob, sigma_set=sigma_set)
    split = split_from_costs(model, costs)
    ev, q_eval = inputs.resolve_poses(rob, None, eval_poses or inputs.default_pose_set(rob), poses_argument="eval_poses")
    _check_tool_moves(model, q_eval, rob, ev)
    with StageBar(show_progress(progress), f"calplan {rob.name}") as bar:
        bar.stage(f"{n_cand:,} candidate poses")
        cand = candidate_poses(rob, n_cand, region, seed=seed)
        bar.stage(f"A-optimal design of {n_poses} poses")
        d = design_plan(split, n_poses, cand, q_eval, measurement=measurement, noise_mm=noise_mm, noise_deg=noise_deg,
                        registration=registration, seed=seed)
        alloc, comparison = None, None
        if for_allocation:
            bar.stage(f"plan for the allocation, compared with {random_plans} random plans")
            alloc, comparison = _for_allocation(model, split, d.plan, cand, q_eval, costs=costs, radius_mm=radius_mm,
                                                prob=prob, random_plans=random_plans, measurement=measurement,
                                                noise_mm=noise_mm, registration=registration, seed=seed)
    post = posterior(split, d.plan if alloc is None else alloc.plan)
    unid, frac = tuple(post.unidentifiable), dict(zip(model.names, post.sigma_fraction))
    return CalibrationPlanDesign(d, rob, region, ev, len(cand), unid, alloc, comparison,
                                 unidentifiable_sigma_fraction=tuple(float(frac[n]) for n in unid))


def _check_design_args(n_candidates, n_poses, noise_mm, noise_deg, measurement, registration, for_allocation,
                       progress) -> tuple[int, int]:
    """The counts ``(n_candidates, n_poses)``, checked with the noises and flags of :func:`plan_calibration`."""
    n_cand = inputs.check_count(n_candidates, "n_candidates", example="2000")
    check_memory(n_cand, CANDIDATE_BYTES, "n_candidates", "candidate poses", "2000")
    n_poses = inputs.check_count(n_poses, "n_poses", example="30")
    if n_poses > n_cand:
        raise ArgumentError("n_poses", f"expected a whole number between 1 and the {n_cand} candidates, got {n_poses}.")
    inputs.check_positive(noise_mm, "noise_mm", "mm", "0.02", NOISE_MM_RANGE)
    inputs.check_positive(noise_deg, "noise_deg", "deg", "0.001", NOISE_DEG_RANGE)
    inputs.check_choice(measurement, "measurement", ("position", "pose"))
    inputs.check_flag(registration, "registration")
    inputs.check_flag(for_allocation, "for_allocation")
    inputs.check_optional_flag(progress, "progress")
    return n_cand, n_poses


def _check_unused(for_allocation: bool, measurement: str, **given) -> None:
    """Refuse an option set away from its default where nothing reads it: the allocation's requirement and random
    plans without ``for_allocation``, an orientation noise with position measurements."""
    import inspect

    defaults = inspect.signature(plan_calibration).parameters
    for name, value in given.items():
        if np.ndim(value) == 0 and value == defaults[name].default:
            continue
        if name == "noise_deg" and measurement == "position":
            raise ArgumentError(name, f"{inputs.shown(value)} is the orientation noise of pose measurements, but "
                                "`measurement` is position; add `measurement` pose (or leave out `noise_deg`).")
        if name != "noise_deg" and not for_allocation:
            raise ArgumentError(name, f"{inputs.shown(value)} is read only for a plan designed for an allocation, but "
                                "`for_allocation` is off; add `for_allocation` (or leave out this option).")


def _check_region(rob, region: str) -> None:
    """``region`` is ``'limits'`` (then every joint limit is finite) or a pose set of ``rob``."""
    if region != "limits" and region not in rob.pose_sets:
        raise ArgumentError("region", f"expected 'limits' or a pose set of robot {rob.name!r}, got {region!r}; known: "
                            f"{known_names(['limits'], rob.pose_sets)}.")
    if region == "limits" and not np.all(np.isfinite(rob.lower) & np.isfinite(rob.upper)):
        loose = [j.name for j, lo, hi in zip(rob.joints, rob.lower, rob.upper) if not np.isfinite(lo + hi)]
        raise ArgumentError("region", f"'limits' needs finite joint limits to draw candidates, but joint(s) "
                            f"{', '.join(loose)} of robot {rob.name!r} have none; give them limits in the robot file or "
                            "use a pose set's box (region=SET).")


def _for_allocation(model, split, start, cand, q_eval, *, costs, radius_mm, prob, random_plans, measurement, noise_mm,
                    registration, seed):
    """The plan designed for the allocation it serves, and its comparison with random plans of its size."""
    from tolalloc.allocate import build_problem
    from tolalloc.allocate.calibrated.plan import compare_with_random_plans, design_plan_for_allocation
    from tolalloc.allocate.costs import cost_set, load_costs
    from tolalloc.allocate.region import box_region

    inputs.check_positive(radius_mm, "radius_mm", "mm", "0.25")
    inputs.check_probability(prob, "prob")
    count = inputs.check_count(random_plans, "random_plans", example="100")
    if measurement != "position":
        raise ArgumentError("for_allocation", "needs `measurement` position: the allocation's end-to-end check "
                            "simulates position measurements.")
    robot = model.robot
    box = None
    if "working" in robot.regions:
        box = box_region(robot, *robot.regions["working"], "working", "region 'working'")
    costs_set = cost_set(model, None) if costs is None else load_costs(costs, model)
    problem = build_problem(model, q_eval, radius_mm=float(radius_mm), prob=float(prob), costs=costs_set)
    alloc = design_plan_for_allocation(problem, start.n_poses, cand, split=split, region=box, start=start,
                                       coverage_n=0, baseline=False, seed=seed, noise_mm=noise_mm,
                                       registration=registration)
    return alloc, compare_with_random_plans(alloc.result, cand, count=count, seed=seed)


@dataclass(frozen=True, eq=False, repr=False)
class CalibrationPlanDesign(JobResult):
    """A designed calibration plan, compared with a random plan of the same size.

    Attributes
    ----------
    design : PlanDesign
        The plan, its score (mean post-calibration variance of the systematic part [mm^2]), the random plan's,
        the all-candidates floor and the relaxation's lower bound.
    robot : Robot
    region, eval_poses : str
    n_candidates : int
    unidentifiable : tuple of str
        Parameters the plan cannot identify individually (each enters a combination of parameters the plan cannot
        see, or no measurement sees it).
    for_allocation : PlanForAllocation or None
        With ``for_allocation=True``: the plan designed for the allocation (the one saved) and that allocation.
    comparison : PlanComparison or None
        Its worst-pose post-calibration P against random plans of the same size.
    unidentifiable_sigma_fraction : tuple of float
        Per parameter of ``unidentifiable``: its post-calibration sigma as a fraction of the manufactured one (1: the
        calibration leaves it as manufactured; below 1: reduced through the combinations the plan does see).

    Examples
    --------
    >>> import tolalloc
    >>> d = tolalloc.plan_calibration("tool_changer", 8, n_candidates=64)
    >>> list(d.to_frame().columns)
    ['j1_deg', 'j2_deg', 'j3_deg', 'j4_mm', 'j5_deg', 'j6_deg']
    """

    design: object
    robot: object
    region: str
    eval_poses: str
    n_candidates: int
    unidentifiable: tuple = ()
    for_allocation: object = None
    comparison: object = None
    inputs: dict = field(default_factory=dict)
    unidentifiable_sigma_fraction: tuple = ()

    @property
    def plan(self):
        """The plan to measure: designed for the allocation when asked, else the A-optimal one."""
        return self.design.plan if self.for_allocation is None else self.for_allocation.plan

    @property
    def ok(self) -> bool:
        return True

    def plan_for(self, robot):
        """The plan, checked for an allocation on ``robot``: designed for a robot of its name and joints, poses
        within its limits (``allocate_tolerances(calibration=design)``)."""
        if self.robot.name != robot.name or self.robot.n_joints != robot.n_joints:
            raise ArgumentError("calibration", f"the plan was designed for the robot {self.robot.name!r}, but the "
                                f"allocation is for {robot.name!r}; design a plan for this robot "
                                f"(tolalloc.plan_calibration({robot.name!r}, n_poses)) and give it as calibration.")
        robot.check_q(self.plan.q, "calibration plan poses")
        return self.plan

    def headline(self) -> list[str]:
        d = self.design
        return [f"robot: {self.robot.name}   {d.plan.n_poses}-pose plan of {self.n_candidates} candidates "
                f"({self.region}), evaluated at the {self.eval_poses} poses",
                f"mean post-calibration position variance (systematic part) [mm^2]: designed {d.score_mm2:.6g}, random "
                f"{d.random_score_mm2:.6g} ({self._lower_pct()}); no calibration {d.no_calibration_mm2:.6g}",
                self._floor_words()]

    def _lower_pct(self) -> str:
        """How much lower the designed plan's score is than the random plan's, in % of the random one's."""
        d = self.design
        pct = 100.0 * (d.random_score_mm2 - d.score_mm2) / d.random_score_mm2
        if abs(pct) < 1e-6:  # rounding level: e.g. too few poses to see past the registration, both plans see nothing
            return "the same"
        return f"designed {pct:.2g} % lower" if pct > 0 else f"designed {-pct:.2g} % higher"

    def _floor_words(self) -> str:
        """The floor, what it is, and the two plans above it [mm^2]."""
        d = self.design
        return (f"floor (all {self.n_candidates} candidates measured) {d.floor_mm2:#.6g} mm^2, of which "
                f"{d.floor_unidentifiable_mm2:#.6g} in parameter combinations no candidate identifies (the rest: "
                f"noise and repeatability); above the floor: designed {d.score_mm2 - d.floor_mm2:.4g}, random "
                f"{d.random_score_mm2 - d.floor_mm2:.4g} mm^2")

    def to_frame(self) -> pd.DataFrame:
        """The plan: one row per measurement pose, joint values in deg / mm."""
        return self.plan.to_frame(self.robot)

    def summary(self) -> dict:
        d = self.design
        return {"robot": self.robot.name, "n_poses": d.plan.n_poses, "n_candidates": self.n_candidates,
                "region": self.region, "eval_poses": self.eval_poses, "measurement": d.plan.measurement,
                "noise_mm": d.plan.noise_mm, "score_mm2": d.score_mm2, "random_score_mm2": d.random_score_mm2,
                "floor_mm2": d.floor_mm2, "relaxation_bound_mm2": d.relaxation_bound_mm2,
                "floor_unidentifiable_mm2": d.floor_unidentifiable_mm2, "no_calibration_mm2": d.no_calibration_mm2,
                "relaxation_method": d.relaxation_method, "unidentifiable": list(self.unidentifiable),
                "unidentifiable_sigma_fraction": dict(zip(self.unidentifiable, self.unidentifiable_sigma_fraction)),
                "for_allocation": None if self.for_allocation is None else {
                    "cost": float(self.for_allocation.result.cost), "start_cost": float(self.for_allocation.start_cost),
                    "rounds": len(self.for_allocation.history), "message": self.for_allocation.message()},
                "random_plans": None if self.comparison is None else self.comparison.to_dict()}

    def text(self) -> str:
        """What the command line prints."""
        d = self.design
        out = [f"robot: {self.robot.name}   {d.plan.n_poses} poses of {self.n_candidates} candidates ({self.region}), "
               f"evaluated at the {self.eval_poses} poses; {d.plan.measurement} measurement, noise {d.plan.noise_mm:g} mm",
               f"mean post-calibration position variance of the systematic part [mm^2]: designed {d.score_mm2:.6g}, "
               f"random {d.random_score_mm2:.6g} ({self._lower_pct()}); no calibration {d.no_calibration_mm2:.6g}; "
               f"relaxation lower bound {d.relaxation_bound_mm2:.6g}",
               f"relaxation: {d.relaxation_method} ({d.relaxation_note}); value {d.relaxation_value_mm2:.6g} mm^2",
               f"{self._floor_words()}   ({d.time_s:.2f} s)"]
        if self.for_allocation is not None:
            out.append(self.for_allocation.message())
        if self.comparison is not None:
            out.append(self.comparison.message())
        if self.unidentifiable:
            from tolalloc.workflows.calibrated_table import UNIDENTIFIABLE_NOTE, with_fractions

            frac = dict(zip(self.unidentifiable, self.unidentifiable_sigma_fraction))
            out.append(f"{UNIDENTIFIABLE_NOTE}: {with_fractions(self.unidentifiable, frac)}")
        return "\n".join(out)

    def save(self, path) -> list[str]:
        """Write the plan CSV (settings in ``#`` header lines) to file ``path``, atomically."""
        from tolalloc.calibration.plan import write_plan

        self.check_out(path, "path", directory=False, required=True)
        with atomic_output(path) as tmp:
            write_plan(self.plan, self.robot, tmp)
        return [str(path)]
