"""Calibration-plan design in one call: :func:`plan_calibration`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, check_memory, known_names
from tolalloc.outputs import atomic_output
from tolalloc.progress import StageBar, show_progress
from tolalloc.workflows import defaults as D
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult
from tolalloc.workflows.settings import Costs, ErrorModelOptions, Measurement, as_settings

__all__ = ["plan_calibration", "CalibrationPlanDesign"]

#: memory of one candidate pose in the design [bytes]: its information block, the relaxation's share and the
#: solver's (about 30 kB measured with tracemalloc on the tool_changer, doubled for what it does not see)
CANDIDATE_BYTES = 65536
#: tracker noise sigma: 0.1 um .. 1 m and 1e-6 .. 10 deg. Below, the posterior of the candidates is conditioned
#: beyond what the design's factorizations resolve (the all-candidates floor drifts above a plan's score at
#: 1e-5 mm); no tracker comes near (typical: 0.005 .. 0.05 mm)
NOISE_MM_RANGE = Measurement.NOISE_MM_RANGE
NOISE_DEG_RANGE = Measurement.NOISE_DEG_RANGE


def _check_tool_moves(model, q_eval, rob, ev: str) -> None:
    """Refuse a robot whose tool point no error parameter moves at the evaluation poses (nothing to calibrate)."""
    if not np.any(np.abs(model.jacobian(q_eval)[:, :3, :]) > 1e-9):
        raise ArgumentError("robot", f"{rob.name!r}: no error parameter moves the tool point at the {ev} poses (the "
                            "tool lies on every joint axis), so a calibration has nothing to reduce; expected a robot "
                            "whose tool point is off its joint axes (a tool offset or links), or other eval_poses.")


@inputs.job_entry
def plan_calibration(robot="tool_changer", n_poses: int = D.N_POSES, *, region: str = "limits",
                     eval_poses: str | None = None, n_candidates: int = D.N_CANDIDATES, measurement="position",
                     costs=None, error_model=None, seed: int = D.SEED, for_allocation=False,
                     random_plans: int = D.RANDOM_PLANS, progress: bool | None = None, tool: str | None = None,
                     trust_units: bool = False) -> "CalibrationPlanDesign":
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
    n_candidates : int
        Candidate poses (default 2000).
    measurement : {"position", "pose"} or Measurement
        What the tracker measures, with its noise and whether the registration is estimated
        (:class:`~tolalloc.workflows.Measurement`; a string is its ``kind``).
    costs : str, path or Costs, optional
        Costs file whose ``[calibration]`` table overrides the systematic / random split (and, with
        ``for_allocation``, the cost laws of the allocation).
    error_model : ErrorModelOptions, optional
        Its ``sigma_set``: the manufacturing sigma set of the robot file (the prior); the other options are not read.
    seed : int
        Seed of the candidates and the random comparison plans.
    for_allocation : bool or PositionRequirement
        Design the plan for the calibration-aware allocation it serves (``True``: for ``P(|dP| < 0.25 mm) >= 0.95``;
        a :class:`~tolalloc.workflows.PositionRequirement`: for that): starting from the A-optimal plan, alternate the
        allocation (over the robot's ``working`` box if it has one, else at the evaluation poses) and a re-design
        that maximises the worst post-calibration P at the design's binding poses, keeping a plan only when the
        allocation gets cheaper; then compare the plan with ``random_plans`` random plans of the same size (median,
        10th and 90th percentile of their worst-pose P). Position measurements only.
    random_plans : int
        Random plans compared with a plan designed for an allocation (read only with ``for_allocation``).
    progress : bool, optional
        The job's stage on stderr (candidates, design, allocation rounds); default: in a terminal or notebook.

    Returns
    -------
    CalibrationPlanDesign
        ``.save(directory)`` writes ``plan.csv`` (the file ``allocate_tolerances(calibration=...)`` reads) and
        ``summary.json``; ``allocate_tolerances(calibration=result)`` takes the result itself.

    Examples
    --------
    >>> import tolalloc
    >>> d = tolalloc.plan_calibration("tool_changer", 8, n_candidates=64)
    >>> d.plan.n_poses, d.design.score_mm2 < d.design.random_score_mm2
    (8, True)
    """
    n_cand = inputs.check_count(n_candidates, "n_candidates", example="2000")
    check_memory(n_cand, CANDIDATE_BYTES, "n_candidates", "candidate poses", "2000")
    n_poses = inputs.check_count(n_poses, "n_poses", example="30")
    if n_poses > n_cand:
        raise ArgumentError("n_poses", f"expected a whole number between 1 and the {n_cand} candidates, got {n_poses}.")
    meas = as_settings(measurement, Measurement, "measurement", lambda v: Measurement(kind=v))
    cost = as_settings(costs, Costs, "costs", lambda v: Costs(file=v))
    options = as_settings(error_model, ErrorModelOptions, "error_model")
    target, random_plans = _target(for_allocation, random_plans, meas, cost, options)
    inputs.check_optional_flag(progress, "progress")
    seed = inputs.check_seed(seed)
    inputs.check_name(region, "region", "'limits' or the name of a pose set of the robot")
    inputs.check_name(eval_poses, "eval_poses", "the name of a pose set of the robot")
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    _check_region(rob, region)
    with StageBar(show_progress(progress), f"plan_calibration {rob.name}") as bar:
        return _design(rob, n_poses, n_cand, region, eval_poses, meas, cost, options, target, random_plans, seed, bar)


def _design(rob, n_poses, n_cand, region, eval_poses, meas, cost, options, target, random_plans, seed, bar):
    """The plan of :func:`plan_calibration`, its inputs checked; ``bar`` names the stage."""
    from tolalloc.calibration.design import candidate_poses, design_plan
    from tolalloc.calibration.posterior import posterior
    from tolalloc.workflows.calibrated import split_from_costs

    model = inputs.error_model(rob, sigma_set=options.sigma_set)
    split = split_from_costs(model, cost.file)
    ev, q_eval = _eval_poses(model, eval_poses, random_plans if target is not None else None)
    bar.stage(f"{n_cand} candidate poses")
    cand = candidate_poses(rob, n_cand, region, seed=seed)
    bar.stage(f"A-optimal {n_poses}-pose plan")
    d = design_plan(split, n_poses, cand, q_eval, measurement=meas.kind, noise_mm=meas.noise_mm,
                    noise_deg=meas.noise_deg, registration=meas.registration, seed=seed)
    alloc, comparison = None, None
    if target is not None:
        bar.stage(f"plan for the allocation ({target.text()}) and {random_plans} random plans")
        alloc, comparison = _for_allocation(model, split, d.plan, cand, q_eval, costs=cost.file, target=target,
                                            random_plans=random_plans, measurement=meas, seed=seed)
    post = posterior(split, d.plan if alloc is None else alloc.plan)
    unid, frac = tuple(post.unidentifiable), dict(zip(model.names, post.sigma_fraction))
    return CalibrationPlanDesign(d, rob, region, ev, len(cand), unid, alloc, comparison,
                                 unidentifiable_sigma_fraction=tuple(float(frac[n]) for n in unid))


def _eval_poses(model, eval_poses, random_plans) -> tuple:
    """``(name, q (P, n))`` of the evaluation poses, where the tool moves with the errors; the count of random plans
    compared at them (None: no comparison) checked against the time budget before any work (it runs last)."""
    rob = model.robot
    ev, q_eval = inputs.resolve_poses(rob, None, eval_poses or inputs.default_pose_set(rob),
                                      poses_argument="eval_poses")
    _check_tool_moves(model, q_eval, rob, ev)
    if random_plans is not None:
        from tolalloc.calibration.design_worst import check_random_plans_budget

        check_random_plans_budget(random_plans, len(q_eval), announce=True)
    return ev, q_eval


def _target(for_allocation, random_plans, meas, cost, options) -> tuple:
    """``(requirement, random_plans)``: the requirement the plan serves (None: a plan for the A-optimal criterion
    alone) and the count of random plans, checked; refuses options nothing would read."""
    from tolalloc.workflows.requirements import PositionRequirement

    if isinstance(for_allocation, PositionRequirement):
        target = for_allocation
    else:
        target = PositionRequirement() if inputs.check_flag(for_allocation, "for_allocation") else None
    random_plans = inputs.check_count(random_plans, "random_plans", example="100")
    if target is None and random_plans != D.RANDOM_PLANS:
        raise ArgumentError("random_plans", f"{inputs.shown(random_plans)} is read only for a plan designed for an "
                            "allocation, but `for_allocation` is off; add `for_allocation` (or leave out this option).")
    if target is not None:
        if meas.kind != "position":
            raise ArgumentError("for_allocation", "needs `measurement` position: the allocation's end-to-end check "
                                "simulates position measurements.")
    if cost.z is not None or cost.uniform:
        raise ArgumentError("costs", "a plan reads the costs file only (its [calibration] split and, for an "
                            "allocation, its cost laws); leave out Costs.z and Costs.uniform.")
    unread = [f for f in options.changed() if f != "sigma_set"]
    if unread:
        raise ArgumentError("error_model", f"a plan reads only ErrorModelOptions.sigma_set (the prior), got "
                            f"{', '.join(unread)} too; leave them out.")
    return target, random_plans


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


def _for_allocation(model, split, start, cand, q_eval, *, costs, target, random_plans, measurement, seed):
    """The plan designed for the allocation it serves, and its comparison with random plans of its size."""
    from tolalloc.allocate import build_problem
    from tolalloc.allocate.calibrated.plan import compare_with_random_plans, design_plan_for_allocation
    from tolalloc.allocate.costs import cost_set, load_costs
    from tolalloc.allocate.region import box_region

    robot = model.robot
    box = None
    if "working" in robot.regions:
        box = box_region(robot, *robot.regions["working"], "working", "region 'working'")
    costs_set = cost_set(model, None) if costs is None else load_costs(costs, model)
    problem = build_problem(model, q_eval, **target.problem_arguments(), costs=costs_set)
    alloc = design_plan_for_allocation(problem, start.n_poses, cand, split=split, region=box, start=start,
                                       coverage_n=0, baseline=False, seed=seed, noise_mm=measurement.noise_mm,
                                       registration=measurement.registration)
    return alloc, compare_with_random_plans(alloc.result, cand, count=random_plans, seed=seed)


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
        within its limits (``allocate_tolerances(calibration=design)``); ``robot``: a Robot, a built-in name or a
        robot file."""
        robot = inputs.as_robot(robot)
        if self.robot.name != robot.name or self.robot.n_joints != robot.n_joints:
            raise ArgumentError("robot", f"the plan was designed for the robot {self.robot.name!r}, but the "
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

    def plot_scores(self, ax=None):
        """Mean post-calibration position variance of the systematic part [mm^2]: no calibration, the random plan,
        the designed plan and the floor of measuring every candidate; draws into ``ax`` or a new figure and returns
        the Axes."""
        import matplotlib.pyplot as plt

        from tolalloc.report.plots import fit_layout

        d = self.design
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 2.6))
        names = ["no calibration", f"random {d.plan.n_poses}-pose plan", f"designed {d.plan.n_poses}-pose plan",
                 f"all {self.n_candidates} candidates (floor)"]
        values = [d.no_calibration_mm2, d.random_score_mm2, d.score_mm2, d.floor_mm2]
        ax.barh(names[::-1], values[::-1], color=["#999999", "#4c72b0", "#c44e52", "#dddddd"][::-1])
        ax.set_xscale("log")
        ax.set_xlabel("mean post-calibration position variance (systematic part) [mm²]")
        ax.set_title(f"{self.robot.name}: calibration plan at the {self.eval_poses} poses", fontsize=9)
        fit_layout(ax.figure)
        return ax

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write ``plan.csv`` (settings in ``#`` header lines: the file ``allocate_tolerances(calibration=...)``
        reads) and ``summary.json`` into an existing ``folder`` (not atomic); returns the file names."""
        from pathlib import Path

        from tolalloc.calibration.plan import write_plan
        from tolalloc.outputs import json_native, write_json

        folder = Path(folder)
        write_plan(self.plan, self.robot, folder / "plan.csv")
        write_json(json_native(self.summary()), folder / "summary.json")
        return ["plan.csv", "summary.json"]

    def save_plan(self, path) -> list:
        """Write the plan CSV alone to file ``path`` (``str`` or ``os.PathLike``), atomically, as ``tolalloc calplan
        --out FILE`` does; returns ``[Path(path)]``."""
        from pathlib import Path

        from tolalloc.calibration.plan import write_plan

        path = self.check_out(path, "path", directory=False, required=True)
        with atomic_output(path) as tmp:
            write_plan(self.plan, self.robot, tmp)
        return [Path(path)]

    def save(self, directory=None, *, report: bool = False, json=None, **old) -> list:
        """Write ``plan.csv`` and ``summary.json`` into ``directory`` (the result protocol,
        :mod:`tolalloc.workflows.base`); ``save("plan.csv")`` (a path ending in ``.csv``), the former form, writes the
        plan file alone, with a DeprecationWarning (use :meth:`save_plan`)."""
        import warnings

        if directory is not None and str(directory).lower().endswith(".csv") and not old and json is None:
            warnings.warn("CalibrationPlanDesign.save(FILE.csv) is deprecated: save(directory) writes plan.csv and "
                          "summary.json into a directory, save_plan(FILE.csv) the plan file alone.",
                          DeprecationWarning, stacklevel=2)
            return self.save_plan(directory)
        return super().save(directory, report=report, json=json, **old)
