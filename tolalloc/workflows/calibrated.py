"""Calibration-aware allocation (``allocate_tolerances(..., calibration=PLAN)``) and its result."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tolalloc.outputs import atomic_output, write_json
from tolalloc.workflows.base import JobResult

__all__ = ["CalibratedToleranceAllocation", "calibrated_allocation", "split_from_costs"]


def split_from_costs(model, path):
    """The systematic / random error split with the costs file's ``[calibration]`` overrides (defaults without)."""
    from tolalloc.calibration.split import split_errors

    if path is None:
        return split_errors(model)
    from tolalloc.allocate.costs import cost_set, read_costs_file

    from tolalloc.exceptions import ArgumentError, TolallocError

    data = read_costs_file(path)
    cost_set(model, data, source=str(path))  # the whole file is checked, not only its [calibration] table
    try:
        return split_errors(model, data.get("calibration"))
    except TolallocError as exc:  # its messages name the key; the file is named here
        raise ArgumentError("costs", f"{path}: {exc}") from None


def calibrated_allocation(model, label, box, q, plan_path, *, region_given, costs_path, verify, n_mc, seed, estimator,
                          inputs_record, **kw):
    """Certified calibration-aware design at the poses ``q`` (P, n) [rad, mm] after the plan in ``plan_path``,
    with the end-to-end Monte Carlo (simulated robots, each calibrated nonlinearly) when ``verify``."""
    from tolalloc.allocate import build_problem
    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows.inputs import default_pose_set, resolve_poses

    if box is not None:
        if region_given:
            raise ArgumentError("calibration", f"the calibration-aware allocation works on a pose set, got the box "
                                f"region {label!r}; give `poses` SET (or `region` SET with a pose set).")
        label, q = resolve_poses(model.robot, None, default_pose_set(model.robot))
    from tolalloc.allocate.calibrated import allocate_calibrated
    from tolalloc.calibration.plan import read_plan

    problem = build_problem(model, q, **kw)
    plan = read_plan(plan_path, model.robot)
    split = split_from_costs(model, costs_path)
    res = allocate_calibrated(problem, plan, split=split)
    chk, n = None, None
    if res.design.ok and verify and plan.measurement == "position":
        from tolalloc.verify.calibrated import verify_calibration

        n = max(200, min(int(n_mc), 4000))
        # the end-to-end check has no importance sampler: its rare tails take the paired estimator
        est = "paired" if estimator == "importance" else estimator
        chk = verify_calibration(res.post.split, plan, problem.q, problem.radius_mm, n_robots=n, seed=seed,
                                 estimator=est)
    return CalibratedToleranceAllocation(res, plan, str(plan_path), label, chk, n, inputs_record)


@dataclass(frozen=True, eq=False, repr=False)
class CalibratedToleranceAllocation(JobResult):
    """Tolerances for the accuracy after a calibration plan: per parameter 'calibrated away' or 'must be held'.

    Attributes
    ----------
    result : tolalloc.allocate.calibrated.CalibratedAllocation
        The certified calibration-aware design, the design without calibration, the post-calibration statistics.
    plan : CalibrationPlan
    plan_source : str
    label : str
        The pose set the requirement holds at.
    end_to_end : CalibrationCheck or None
        Simulated robots, each calibrated nonlinearly at the plan's poses, then checked at the working poses.
    n_robots : int or None
    inputs : dict
    """

    result: object
    plan: object
    plan_source: str
    label: str
    end_to_end: object
    n_robots: int | None
    inputs: dict = field(default_factory=dict)

    @property
    def robot(self):
        return self.result.problem.model.robot

    @property
    def problem(self):
        return self.result.problem

    @property
    def cost(self) -> float:
        return float(self.summary()["cost"])

    @property
    def certified(self) -> bool:
        return bool(self.result.certified)

    @property
    def ok(self) -> bool:
        """Feasible, certified, and the end-to-end Monte Carlo agrees with the linear prediction (if run)."""
        if not self.result.design.ok or not self.certified:
            return False
        return self.end_to_end is None or bool(np.all(self.end_to_end.agree))

    @property
    def writable(self) -> bool:
        """Whether :meth:`save` has something to write (an infeasible calibration-aware problem has not)."""
        return bool(self.result.design.ok)

    def headline(self) -> list[str]:
        pr = self.problem
        lines = [f"robot: {self.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
                 f"calibration ({self.plan.n_poses}-pose plan) at {pr.n_poses} {self.label} pose(s)"]
        if not self.result.design.ok:
            return lines + [f"status: infeasible ({self.result.design.message})"]
        s = self.result.summary()
        lines.append(f"cost: {s['cost']:.4f} ({'certified' if self.certified else 'NOT certified'})"
                     + ("" if s["saving_pct"] is None else f", {s['saving_pct']:.1f}% below no calibration"))
        if self.end_to_end is not None:
            lines.append(f"end-to-end Monte Carlo: {self.end_to_end.message()}")
        return lines

    def to_frame(self):
        """Per parameter: tolerance, tolerance without calibration, manufactured / post-calibration / random sigma,
        status (calibrated away, must be held, loose), cost."""
        return self.result.to_frame()

    def summary(self) -> dict:
        """The content of ``summary.json``."""
        s = self.result.summary() if self.result.design.ok else {"status": "infeasible",
                                                                    "message": self.result.design.message}
        chk = self.end_to_end
        if chk is not None:
            s["end_to_end"] = {"n_robots": self.n_robots, "agree": bool(np.all(chk.agree)),
                               "p_mc_min": float(chk.p_mc.min()), "p_linear_min": float(chk.p_linear.min())}
        return {**s, "pose_set": self.label, "plan": self.plan_source}

    def text(self) -> str:
        """What the command line prints."""
        res, pr, plan = self.result, self.problem, self.plan
        out = [f"robot: {self.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
               f"calibration at {pr.n_poses} {self.label} pose(s); plan {self.plan_source}: {plan.n_poses} "
               f"{plan.measurement} measurements, noise {plan.noise_mm:g} mm"]
        if not res.design.ok:
            return "\n".join(out + [f"status: INFEASIBLE. {res.design.message}"])
        s = res.summary()
        verdict = "certified" if res.certified else f"NOT certified (lambda_max / bound = {res.ratio:.6f} > 1)"
        base = "n/a" if s["cost_no_calibration"] is None else f"{s['cost_no_calibration']:.4f}"
        out.append(f"design: {res.design.solver} ({verdict}; {res.design.message})   cost {s['cost']:.4f}   "
                   f"without calibration {base}" + ("" if s["saving"] is None else
                                                    f"   saving {s['saving']:.4f} ({s['saving_pct']:.2f}%)"))
        if res.grade_t is not None:
            out.append(f"  of which repeatability grades {s['cost_repeatability_grades']:.4f} (parts "
                       f"{s['cost_parts']:.4f}); without calibration: the loosest grades, {res.grade_cost_loosest:.4f}")
        out += ["", self.to_frame().to_string(index=False, float_format=lambda x: f"{x:.5g}")]
        if s["unidentifiable"]:
            out.append(f"\nnot identifiable by the plan (must be held in manufacturing): {', '.join(s['unidentifiable'])}")
        chk = self.end_to_end
        if chk is not None:
            p_ok = bool(np.all(chk.ci_high >= pr.prob))
            out.append(f"\nend-to-end Monte Carlo ({self.n_robots} simulated robots, nonlinear calibration each): "
                       f"{chk.message()}; smallest P_hat {chk.p_mc.min():.4f}"
                       + ("" if p_ok else f" -- below p = {pr.prob:g} beyond its interval at some pose"))
        return "\n".join(out)

    def save(self, out, *, report: bool = False) -> list[str]:
        """Write ``calibrated_tolerances.csv``, ``summary.json`` and ``end_to_end.csv`` into directory ``out``
        (all together or none); ``report=True`` adds ``report.html``. Returns the file names."""
        from tolalloc.exceptions import TolallocError

        if not self.result.design.ok:
            raise TolallocError(f"save: nothing to save, the calibration-aware allocation is infeasible "
                                f"({self.result.design.message}).")
        self.check_out(out, "out", required=True)
        if not isinstance(report, (bool, np.bool_)):
            from tolalloc.exceptions import ArgumentError

            raise ArgumentError("report", f"expected True or False, got {report!r}.")
        with atomic_output(out, directory=True) as tmp:
            names = self.write_files(tmp, report=report)
        return names

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write the output files into an existing ``folder`` (not atomic; :meth:`save` stages through this)."""
        self.to_frame().to_csv(folder / "calibrated_tolerances.csv", index=False, float_format="%.8g")
        names = ["calibrated_tolerances.csv", "summary.json"]
        if self.end_to_end is not None:
            self.end_to_end.to_frame().to_csv(folder / "end_to_end.csv", index=False, float_format="%.8g")
            names.append("end_to_end.csv")
        write_json(self.summary(), folder / "summary.json")
        if report:
            from tolalloc.workflows.html import write_calibrated_report

            write_calibrated_report(self, folder)
            names.append("report.html")
        return names
