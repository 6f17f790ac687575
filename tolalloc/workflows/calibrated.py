"""Calibration-aware allocation (``allocate_tolerances(..., calibration=PLAN)``) and its result.

What runs: the certified calibration-aware design (eigenvalue rule on the post-calibration covariance), then the
exact stage on the post-calibration probability (``solver="exact"``; skipped with ``"certified"``), over the pose set
or the box; then the standard grades (``Solver.snap``); then the end-to-end Monte Carlo of the design to build
(unless ``verification=False``; position plans; ``Verification.n_mc`` simulated calibrations clipped to
:data:`N_ROBOTS_RANGE`, estimator ``auto``, ``plain`` or ``paired``). Position requirement only. There is no correction
loop and the end-to-end Monte Carlo runs in this process, so :func:`~tolalloc.workflows.allocate_tolerances` refuses
a ``Verification`` with ``correction=True``, ``correction_rounds``, ``scheduler`` or ``estimator="importance"``, and
an ``OrientationRequirement``, with ``calibration``.

The result's tolerance table is built in :mod:`.calibrated_table`, its printed text in :mod:`.calibrated_text`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tolalloc.outputs import write_json
from tolalloc.workflows.base import AllocationJobResult

__all__ = ["CalibratedToleranceAllocation", "calibrated_allocation", "split_from_costs", "N_ROBOTS_RANGE",
           "PLAN_IN_MEMORY"]

#: simulated calibrations of the end-to-end Monte Carlo: ``n_mc`` clipped to this range (each is a nonlinear fit)
N_ROBOTS_RANGE = (200, 4000)
#: ``plan_source`` of a plan given as the result of :func:`~tolalloc.workflows.plan_calibration` (not a file)
PLAN_IN_MEMORY = "plan_calibration result (not saved)"


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


def calibrated_allocation(model, label, box, q, plan, plan_source: str, *, costs_path, verify, n_mc, seed, estimator,
                          coverage_n, inputs_record, exact: bool = True, snap: bool = True,
                          angle_step_deg: float | None = None, **kw):
    """Calibration-aware allocation after the :class:`~tolalloc.calibration.plan.CalibrationPlan` ``plan`` (for
    ``model.robot``; ``plan_source``: its file, or :data:`PLAN_IN_MEMORY`): certified, then (``exact``) exact, at the poses
    ``q`` (P, n) [rad, mm] or over the box ``box`` (cutting planes, coverage); with ``snap`` the standard-grade design
    (ISO 286 grades, classes, ``angle_step_deg`` steps) chosen over the same poses or box
    (:func:`tolalloc.allocate.calibrated.standard.standardize_calibrated`), the design to build; the end-to-end Monte
    Carlo (``n_mc`` simulated robots within :data:`N_ROBOTS_RANGE`, each calibrated nonlinearly, at the built design's
    worst poses; ``estimator`` auto, plain or paired) when ``verify`` and the plan measures positions."""
    from tolalloc.allocate import build_problem
    from tolalloc.allocate.calibrated.design import allocate_with_calibration
    from tolalloc.verify.cost import check_allocation_budgets
    from tolalloc.workflows.inputs import default_pose_set, resolve_poses

    check_allocation_budgets(model, box is not None, q, n_mc=None, estimator=estimator, coverage_n=coverage_n,
                             rounds=1 if snap else 0)  # coverage of the continuous and the standard design
    if box is not None:  # the initial active set: the robot's pose set (the poses inside the box are kept)
        q = resolve_poses(model.robot, None, default_pose_set(model.robot))[1]
    problem = build_problem(model, q, **kw)
    split = split_from_costs(model, costs_path)
    res = allocate_with_calibration(problem, plan, split=split, region=box, exact=exact, coverage_n=coverage_n,
                                    seed=seed)
    std = None
    if res.design.ok and snap:
        from tolalloc.allocate.calibrated.standard import standardize_calibrated

        std = standardize_calibrated(res, angle_step_deg=angle_step_deg, coverage_n=coverage_n, seed=seed)
    chk, n = None, None
    if res.design.ok and verify and plan.measurement == "position":
        from tolalloc.verify.calibrated_worst import verify_calibrated_design

        n = int(np.clip(int(n_mc), *N_ROBOTS_RANGE))
        built = std if std is not None and std.design.ok else None
        chk = verify_calibrated_design(res, standard=built, n_robots=n, seed=seed, estimator=estimator)
    return CalibratedToleranceAllocation(res, plan, plan_source, label, chk, n, inputs_record, std)


@dataclass(frozen=True, eq=False, repr=False)
class CalibratedToleranceAllocation(AllocationJobResult):
    """Tolerances for the accuracy after a calibration plan: per parameter 'calibrated away', 'loose (at t_max)' or
    'must be held'.

    The same interface as :class:`ToleranceAllocation` where it applies: ``ok``, ``status``, ``cost``,
    :meth:`to_frame` (the same core columns), :meth:`verification_frame`, :meth:`summary`, :meth:`text` and
    :meth:`save` (``tolerances.csv``/``.md``/``.tex``, ``summary.json``, ``verification.csv``, ``report.html``).

    Attributes
    ----------
    result : tolalloc.allocate.calibrated.design.CalibratedDesign
        The certified and (``solver="exact"``) exact calibration-aware designs (the exact one chosen when accepted),
        the region search and its coverage, the designs without calibration, the post-calibration statistics.
    plan : CalibrationPlan
    plan_source : str
        The plan's file, or :data:`PLAN_IN_MEMORY` for a plan given as a :func:`plan_calibration` result.
    label : str
        Where the requirement holds: the region or pose-set name.
    end_to_end : EndToEnd or None
        Simulated robots, each calibrated nonlinearly at the plan's poses, then checked at the built design's worst
        poses (per-pose verdicts demonstrated / consistent / failed).
    n_robots : int or None
    inputs : dict
    standard : CalibratedStandard or None
        The standard-grade design (ISO 286 grades, classes, steps) chosen over the same poses or box: the design to
        build when it was found (``tol_mm`` / ``tol_deg``, ``grade`` in the table); None when not asked for
        (``snap``).
    """

    result: object
    plan: object
    plan_source: str
    label: str
    end_to_end: object
    n_robots: int | None
    inputs: dict = field(default_factory=dict)
    standard: object = None


    @property
    def plan_file(self) -> str | None:
        """The plan's file; None for a plan given as a :func:`plan_calibration` result."""
        return None if self.plan_source == PLAN_IN_MEMORY else self.plan_source

    @property
    def built(self):
        """The standard-grade design when one was found (the design to build, the one checked end to end), else
        None (the continuous design is built)."""
        std = self.standard
        return std if std is not None and std.design.ok else None

    @property
    def cost(self) -> float:
        """Cost of the design to build: the standard one when found, else the continuous one."""
        return float(self.built.cost if self.built is not None else self.result.cost)

    @property
    def continuous_cost(self) -> float:
        return float(self.result.cost)

    @property
    def region(self):
        """The box searched (``None`` for a pose set or a trajectory)."""
        return self.result.region

    @property
    def certified(self) -> bool:
        return bool(self.result.certified.certified)

    @property
    def status(self) -> str:
        """``optimal``, ``infeasible`` or ``not_converged``: the status of the continuous calibration-aware design
        (exact when accepted, else certified)."""
        return str(self.result.design.status)

    @property
    def ok(self) -> bool:
        """The design to build (standard when found, else continuous) meets the requirement wherever checked, and its
        end-to-end Monte Carlo passed (if run)."""
        if not self.result.design.ok or not self.result.ok:
            return False
        if self.built is not None and not self.standard.ok:  # the standard design to build falls short somewhere
            return False
        return self.end_to_end is None or self.end_to_end.passed

    @property
    def verified(self) -> bool:
        """Whether the design to build passed the end-to-end Monte Carlo (simulated robots, each calibrated at the
        plan's poses): it ran and :attr:`ok`, as :attr:`ToleranceAllocation.verified`; False when it did not run
        (``verification=False``, a pose-measurement plan or no design).

        Passed (:attr:`~tolalloc.verify.calibrated_worst.EndToEnd.passed`) means: for the exact or standard design
        every checked pose is ``demonstrated`` (the interval of ``P_hat`` lies at or above p) or ``consistent``
        (the interval reaches p: the Monte Carlo cannot tell the design from one that meets p exactly, which is
        what an exact design, built to meet p with equality at its worst poses, is expected to show); the certified
        design needs ``demonstrated`` at every pose. In both cases the linear prediction must lie nowhere above the
        interval."""
        return self.end_to_end is not None and self.ok

    @property
    def writable(self) -> bool:
        """Whether :meth:`save` has something to write (an infeasible calibration-aware problem has not)."""
        return bool(self.result.design.ok)

    def stages(self) -> str:
        """The stages that ran, in order: ``certified -> exact -> standard grades``, with ``exact (not run:
        solver='certified')`` or ``exact (not used)`` where the exact stage gave no design."""
        res = self.result
        ex = ("exact" if res.exact_accepted else "exact (not run: solver='certified')" if res.exact is None
              else "exact (not used)")
        std = [] if self.standard is None else ["standard grades" + ("" if self.built is not None else " (none found)")]
        return " -> ".join(["certified", ex, *std])

    def headline(self) -> list[str]:
        pr = self.problem
        lines = [f"robot: {self.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
                 f"calibration ({self.plan.n_poses}-pose plan) over {self.label}"]
        if not self.result.design.ok:
            return lines + [f"status: {self.status} ({self.result.design.message})"]
        s = self.result.summary()
        lines.append(f"status: {self.status}   stages: {self.stages()}")
        lines.append(f"cost: {self.continuous_cost:.4f} ({s['design']})" + (
            "" if s.get("saving_pct") is None else f", {s['saving_pct']:.1f}% below no calibration"))
        if self.built is not None:
            b = self.built
            lines.append(f"design to build: standard grades, cost {b.cost:.4f} ({b.premium_pct:+.2f} % over the "
                         f"continuous design; rounding down {b.rounded_premium_pct:+.2f} %)")
        lines.append(f"end-to-end Monte Carlo: {self.end_to_end.verdict}" if self.end_to_end is not None else
                     f"end-to-end Monte Carlo: not run ({self._no_end_to_end()})")
        return lines

    def _no_end_to_end(self) -> str:
        """Why the end-to-end Monte Carlo did not run."""
        if self.inputs.get("n_mc", 0) is None:
            return "verification=False"
        if self.plan.measurement != "position":
            return "the plan measures poses; the end-to-end simulation handles position measurements only"
        return "no design to check"

    def grade_note(self) -> str:
        """What the tolerance table says about standard grades: the design to build, where it holds, its premium."""
        std, b = self.standard, self.built
        if std is None:
            return "The calibration-aware design was not made standard (snap=False): its tolerances are continuous."
        if b is None:
            return (f"No standard-grade design was found ({std.design.message}); the continuous design is the one "
                    "shown and checked.")
        if std.ok:
            where = ("holds at p over the region (worst-pose search and coverage on its post-calibration covariance)"
                     if std.region_kind == "box" else "holds at p at every pose")
        else:
            where = f"does NOT hold where checked (worst post-calibration P found {std.worst_p():.5f})"
        split = ("" if not np.isfinite(b.relaxed_cost) else
                 f" Within the catalogue's range the continuous design costs {b.relaxed_cost:.4f}: "
                 f"{b.range_premium_pct:+.2f} % is the range"
                 + (f" ({', '.join(b.range_limited)} above their coarsest standard value)" if b.range_limited else "")
                 + f", {b.step_premium_pct:+.2f} % the steps between standard values.")
        check = " The end-to-end Monte Carlo checks the standard design." if self.end_to_end is not None else ""
        return (f"The design to build carries standard values (tol_mm / tol_deg, grade: ISO 286 grades for link lengths), "
                f"rounded down from the continuous {b.continuous_label} design and improved by a local search under "
                f"the exact post-calibration probability; it {where}. It costs {b.cost:.4f}, {b.premium_pct:+.2f} % "
                f"over the continuous design ({b.continuous_cost:.4f}); rounding down alone would cost "
                f"{b.rounded_cost:.4f} ({b.rounded_premium_pct:+.2f} %).{split} The search ends at a local optimum, "
                "not a proven one." + check)

    def to_frame(self):
        """The tolerance table: the core columns of :meth:`ToleranceAllocation.to_frame` for the design to build
        (``tol_mm`` / ``tol_deg``, ``grade``, cost, variance share of the post-calibration ``tr Sigma`` at the worst
        pose, process limits; ``tol_continuous_*`` the continuous design, exact when accepted, else certified), then
        ``status``, ``tol_no_calibration_*``, ``sigma_post_calibration_*``, ``sigma_random_*`` (see
        :mod:`tolalloc.workflows.calibrated_table`)."""
        from tolalloc.workflows.calibrated_table import calibrated_frame

        return calibrated_frame(self)

    def verification_frame(self):
        """Per pose of the end-to-end Monte Carlo: the joint values (deg / mm), the linear post-calibration P, the
        Monte Carlo P_hat with its simultaneous interval, the simulated robots ``n``, the estimator, whether the linear
        prediction lies in the interval (``agree``) and the verdict; None when it did not run."""
        if self.end_to_end is None:
            return None
        chk = self.end_to_end.check
        frame = self.end_to_end.to_frame()
        qi = np.atleast_2d(self.robot.q_to_interface(chk.q))
        for k, j in enumerate(self.robot.joints):
            frame.insert(1 + k, f"{j.name}_{j.unit}", qi[:, k])
        frame.insert(list(frame.columns).index("family_level") + 1, "n", chk.n_robots)
        return frame

    def _table_note(self, frame) -> str:
        """What the tolerance table holds, and which parameters the calibration removes (the .md / .tex line)."""
        from tolalloc.workflows.calibrated_table import status_groups

        b = self.built
        if b is not None:
            note = (f"design to build: standard grades ({b.design.label}) in tol_mm / tol_deg and grade; the continuous "
                    f"{self.result.design.label} calibration-aware design in tol_continuous_mm / _deg of tolerances.csv "
                    f"(stages: {self.stages()})")
        else:
            note = (f"design to build: the continuous {self.result.design.label} calibration-aware design in tol_mm / "
                    f"tol_deg (stages: {self.stages()})")
        groups = "; ".join(f"{status}: {', '.join(names)}" for status, names in status_groups(frame).items())
        return f"{note}. Status after the plan -- {groups}."

    def _table_legend(self) -> str:
        """What the columns of the tolerance table hold (below the ``.md`` / ``.tex`` table)."""
        from tolalloc.report.tables import UNIT_PAIRS_LEGEND

        return (f"Tolerances are symmetric ± half-widths of the design to build. {UNIT_PAIRS_LEGEND} sigma: the "
                f"manufactured standard deviation, tol / {self.problem.costs.z:.4g}. cost: relative cost units. variance_share_pct: share of "
                "tr(Sigma) of the position error after calibration at the worst pose, in % (slightly negative where the "
                "calibration leaves estimates correlated). status: calibrated away (the plan's calibration removes the "
                "error), loose (at t_max: the process's loosest tolerance suffices; coarsest grade: the coarsest "
                "standard grade suffices) or must be held (allocated tight; random: a part no calibration removes).")

    def summary(self) -> dict:
        """The content of ``summary.json``."""
        from tolalloc.workflows.calibrated_table import unidentifiable_fractions, unidentifiable_groups

        s = self.result.summary()
        cert = self.result.certified
        if cert.grade_t is not None:  # the repeatability of the parts a calibration cannot remove, priced
            s.update(cost_parts=float(cert.design.cost), cost_repeatability_grades=float(cert.grade_cost),
                     cost_repeatability_grades_loosest=float(cert.grade_cost_loosest))
        s["end_to_end"] = None if self.end_to_end is None else self.end_to_end.to_dict()
        std, b = self.standard, self.built
        s["standard"] = None if std is None else std.to_dict()
        s.update(cost_continuous=s["cost"], cost_standard=None if b is None else b.cost,
                 cost_rounded=None if std is None else std.rounded_cost,
                 standard_premium_pct=None if b is None else b.premium_pct,
                 rounded_premium_pct=None if std is None else std.rounded_premium_pct)
        s["built"] = {"design": "standard" if b is not None else s["design"], "cost": self.cost if s["cost"] is not None
                      else None, "standard": b is not None}
        s["cost"] = s["built"]["cost"]  # as in the plain allocation's summary: the cost of the design to build
        held, loose, frac = [], [], {}
        if self.result.design.ok and s["unidentifiable"]:
            held, loose, _ = unidentifiable_groups(self.to_frame(), s["unidentifiable"])
            frac = unidentifiable_fractions(self)
        s.update(unidentifiable_held=held, unidentifiable_loose=loose, unidentifiable_sigma_fraction=frac,
                 continuous_ok=s["ok"], ok=self.ok)
        return {**s, "solver_requested": self.inputs.get("solver", "exact"), "pose_set": self.label,
                "plan_file": self.plan_file}

    def text(self) -> str:
        """What the command line prints (:func:`tolalloc.workflows.calibrated_text.report_text`)."""
        from tolalloc.workflows.calibrated_text import report_text

        return report_text(self)

    has_report = True

    def check_savable(self) -> None:
        from tolalloc.exceptions import TolallocError

        if not self.result.design.ok:
            raise TolallocError(f"save: nothing to save, the calibration-aware allocation is infeasible "
                                f"({self.result.design.message}).")

    def card_frame(self):
        """The key columns of the tolerance table (the card of a notebook); None when infeasible."""
        if not self.result.design.ok:
            return None
        frame = self.to_frame()
        keep = ["parameter", "kind", "unit", "status", "tol_mm", "tol_deg", "grade", "cost", "variance_share_pct"]
        return frame[[c for c in keep if c in frame.columns]]

    def plot_budget(self, ax=None, *, title: str | None = None):
        """Tolerance and post-calibration variance share per parameter of the design to build, side by side; draws
        into ``ax`` (a pair of Axes) or a new figure and returns the pair."""
        from tolalloc.report.plots.allocate import plot_budget
        from tolalloc.workflows.base import axes_of

        self.check_savable()
        t = f"{self.robot.name}: after the {self.plan.n_poses}-pose calibration plan" if title is None else title
        fig = plot_budget(self.to_frame(), None, title=t, axes=ax)
        return axes_of(fig) if ax is None else axes_of(list(ax))

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write the output files into an existing ``folder`` (not atomic; :meth:`save` stages through this); returns
        the file names."""
        from pathlib import Path

        from tolalloc.report.tables import write_tables

        folder = Path(folder)
        pr, frame = self.problem, self.to_frame()
        write_tables(frame, folder, caption=f"Tolerances of {self.robot.name}: P(|dP| < {pr.radius_mm:g} mm) >= "
                     f"{pr.prob:g} after the {self.plan.n_poses}-pose calibration plan, over {self.label}",
                     note=self._table_note(frame), legend=self._table_legend())
        write_json(self.summary(), folder / "summary.json")
        names = ["tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json"]
        ver = self.verification_frame()
        if ver is not None:
            ver.to_csv(folder / "verification.csv", index=False, float_format="%.8g")
            names.append("verification.csv")
        if report:
            from tolalloc.report.html_calibrated import write_calibrated_report

            write_calibrated_report(self, folder)
            names.append("report.html")
        return names
