"""Calibration-aware allocation (``allocate_tolerances(..., calibration=PLAN)``) and its result."""

from __future__ import annotations

from dataclasses import dataclass, field


from tolalloc.outputs import atomic_output, write_json
from tolalloc.workflows.base import JobResult

__all__ = ["CalibratedToleranceAllocation", "calibrated_allocation", "split_from_costs"]


def split_from_costs(model, path):
    """The systematic / random error split with the costs file's ``[calibration]`` overrides (defaults without)."""
    from tolalloc.calibration.split import split_errors

    if path is None:
        return split_errors(model)
    from tolalloc.allocate.costs import cost_set, read_costs_file

    data = read_costs_file(path)
    cost_set(model, data, source=str(path))  # the whole file is checked, not only its [calibration] table
    return split_errors(model, data.get("calibration"))


def calibrated_allocation(model, label, box, q, plan_path, *, costs_path, verify, n_mc, seed, estimator, coverage_n,
                          inputs_record, **kw):
    """Calibration-aware allocation after the plan in ``plan_path``: certified, then exact, at the poses ``q``
    (P, n) [rad, mm] or over the box ``box`` (cutting planes, coverage), with the end-to-end Monte Carlo (simulated
    robots, each calibrated nonlinearly, at the design's worst poses) when ``verify``."""
    from tolalloc.allocate import build_problem
    from tolalloc.allocate.calibrated_design import allocate_with_calibration
    from tolalloc.calibration.plan import read_plan
    from tolalloc.workflows.inputs import default_pose_set, resolve_poses

    if box is not None:  # the initial active set: the robot's pose set (the poses inside the box are kept)
        q = resolve_poses(model.robot, None, default_pose_set(model.robot))[1]
    problem = build_problem(model, q, **kw)
    plan = read_plan(plan_path, model.robot)
    split = split_from_costs(model, costs_path)
    res = allocate_with_calibration(problem, plan, split=split, region=box, coverage_n=coverage_n, seed=seed)
    chk, n = None, None
    if res.design.ok and verify and plan.measurement == "position":
        from tolalloc.verify.calibrated_worst import verify_calibrated_design

        n = max(200, min(int(n_mc), 4000))
        # the end-to-end check has no importance sampler: its rare tails take the paired estimator
        est = "paired" if estimator == "importance" else estimator
        chk = verify_calibrated_design(res, n_robots=n, seed=seed, estimator=est)
    return CalibratedToleranceAllocation(res, plan, str(plan_path), label, chk, n, inputs_record)


@dataclass(frozen=True, eq=False, repr=False)
class CalibratedToleranceAllocation(JobResult):
    """Tolerances for the accuracy after a calibration plan: per parameter 'calibrated away' or 'must be held'.

    Attributes
    ----------
    result : tolalloc.allocate.calibrated_design.CalibratedDesign
        The certified and exact calibration-aware designs (the exact one chosen when accepted), the region search
        and its coverage, the designs without calibration, the post-calibration statistics.
    plan : CalibrationPlan
    plan_source : str
    label : str
        Where the requirement holds: the region or pose-set name.
    end_to_end : EndToEnd or None
        Simulated robots, each calibrated nonlinearly at the plan's poses, then checked at the design's worst poses
        (per-pose verdicts demonstrated / consistent / failed).
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
        return float(self.result.cost)

    @property
    def region(self):
        """The box searched (``None`` for a pose set or a trajectory)."""
        return self.result.region

    @property
    def certified(self) -> bool:
        return bool(self.result.certified.certified)

    @property
    def ok(self) -> bool:
        """A design meeting the requirement wherever checked, and its end-to-end Monte Carlo passed (if run)."""
        if not self.result.design.ok or not self.result.ok:
            return False
        return self.end_to_end is None or self.end_to_end.passed

    @property
    def writable(self) -> bool:
        """Whether :meth:`save` has something to write (an infeasible calibration-aware problem has not)."""
        return bool(self.result.design.ok)

    def headline(self) -> list[str]:
        pr = self.problem
        lines = [f"robot: {self.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
                 f"calibration ({self.plan.n_poses}-pose plan) over {self.label}"]
        if not self.result.design.ok:
            return lines + [f"status: infeasible ({self.result.design.message})"]
        s = self.result.summary()
        lines.append(f"cost: {self.cost:.4f} ({s['design']})" + ("" if s.get("saving_pct") is None else
                                                               f", {s['saving_pct']:.1f}% below no calibration"))
        if self.end_to_end is not None:
            lines.append(f"end-to-end Monte Carlo: {self.end_to_end.verdict}")
        return lines

    def to_frame(self):
        """Per parameter: ``tolerance``, ``status`` and ``cost`` of the chosen design (exact when accepted, else
        certified), the certified and exact tolerances, the tolerance without calibration, manufactured /
        post-calibration / random sigma."""
        df = self.result.to_frame()
        exact = self.result.exact_accepted
        df.insert(2, "tolerance", df["tolerance_exact"] if exact else df["tolerance_certified"])
        df["cost"] = df["cost_exact"] if exact else df["cost_certified"]
        if exact:
            df["status"] = df["status_exact"]
        return df

    def summary(self) -> dict:
        """The content of ``summary.json``."""
        s = self.result.summary()
        cert = self.result.certified
        if cert.grade_t is not None:  # the repeatability of the parts a calibration cannot remove, priced
            s.update(cost_parts=float(cert.design.cost), cost_repeatability_grades=float(cert.grade_cost),
                     cost_repeatability_grades_loosest=float(cert.grade_cost_loosest))
        if self.end_to_end is not None:
            s["end_to_end"] = self.end_to_end.to_dict()
        return {**s, "pose_set": self.label, "plan_file": self.plan_source}

    def text(self) -> str:
        """What the command line prints."""
        res, pr, plan = self.result, self.problem, self.plan
        out = [f"robot: {self.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
               f"calibration over {self.label}; plan {self.plan_source}: {plan.n_poses} {plan.measurement} "
               f"measurements, noise {plan.noise_mm:g} mm", res.message()]
        if not res.design.ok:
            return "\n".join(out)
        cert = res.certified
        if cert.grade_t is not None:
            out.append(f"  certified design: of which repeatability grades {cert.grade_cost:.4f} (parts "
                       f"{cert.design.cost:.4f}); without calibration: the loosest grades, {cert.grade_cost_loosest:.4f}")
        out += ["", self.to_frame().to_string(index=False, float_format=lambda x: f"{x:.5g}")]
        unid = res.summary().get("unidentifiable") or []
        if unid:
            out.append(f"\nnot identifiable by the plan (must be held in manufacturing): {', '.join(unid)}")
        if self.end_to_end is not None:
            out.append("\n" + self.end_to_end.message())
        return "\n".join(out)

    def save(self, out, *, report: bool = False) -> list[str]:
        """Write ``calibrated_tolerances.csv``, ``summary.json`` and ``end_to_end.csv`` into directory ``out``
        (all together or none); ``report=True`` adds ``report.html``. Returns the file names."""
        from tolalloc.exceptions import TolallocError

        if not self.result.design.ok:
            raise TolallocError(f"save: nothing to save, the calibration-aware allocation is infeasible "
                                f"({self.result.design.message}).")
        self.check_out(out, "out")
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
