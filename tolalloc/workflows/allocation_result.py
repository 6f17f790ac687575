"""The result of :func:`tolalloc.allocate_tolerances`: tables, summary, text, figures, files."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.outputs import atomic_output, write_json
from tolalloc.workflows.base import JobResult

__all__ = ["ToleranceAllocation"]

#: files written by :meth:`ToleranceAllocation.save` (those after the marker only with a verification)
ALLOCATION_FILES = ("tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json", "error_budget.png")


@dataclass(frozen=True, eq=False, repr=False)
class ToleranceAllocation(JobResult):
    """Tolerances allocated for a requirement over a region, with their checks.

    Attributes
    ----------
    result : AllocationResult
        The final allocation (the corrected one when the correction loop re-solved): certified, exact and
        standard-grade designs, the problem (poses, requirement, costs).
    label : str
        Where the requirement holds: the region or pose-set name.
    region : Region or None
        The box region, if one was searched.
    region_search : RegionAllocation or None
        The cutting-plane search over the box (rounds, active poses, worst P found).
    coverage : Coverage or None
        The final design's linear P on a fresh sample of the box.
    verification : Verification or None
        Nonlinear Monte Carlo at every active pose (and the coverage's worst poses).
    correction : Correction or None
        The correction loop, when a pose was not demonstrated.
    inputs : dict
        The call's inputs that decide the numbers (robot, requirement, region, costs source, seed, n_mc).
    infeasible : str or None
        Set when the region cannot be covered even at the tightest process limits (no design to use).
    built : Design or None
        The design that will be built, the one verified and covered: the standard design chosen by the optimiser
        (grades, classes, resolution steps) when it was asked for and meets the requirement, else the continuous
        one (``result.design``).

    Examples
    --------
    >>> import tolalloc
    >>> res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=2000)
    >>> res.ok, res.status
    (True, 'optimal')
    >>> res.to_frame().loc[0, ["parameter", "unit", "grade"]].tolist()
    ['dl1', 'mm', 'IT10']
    """

    result: object
    label: str
    region: object
    region_search: object
    coverage: object
    verification: object
    correction: object
    inputs: dict = field(default_factory=dict)
    infeasible: str | None = None
    built: object = None

    # ------------------------------------------------------------------ the headline numbers
    @property
    def robot(self):
        return self.result.problem.model.robot

    @property
    def problem(self):
        return self.result.problem

    @property
    def design(self):
        """The design that will be built (verified, covered): the standard one, or the continuous one."""
        return self.built if self.built is not None else self.result.design

    @property
    def continuous_design(self):
        """The continuous optimum (``result.design``; ``tolerance`` in the table)."""
        return self.result.design

    @property
    def standard(self) -> bool:
        """Whether the design to build is the standard one (``tolerance_std``, ``grade`` in the table)."""
        return self.design is not self.result.design

    @property
    def status(self) -> str:
        """``optimal``, ``infeasible`` or ``not_converged`` (the allocation's)."""
        return self.result.status

    @property
    def cost(self) -> float:
        return float(self.design.cost)

    @property
    def verdict(self) -> str | None:
        """``demonstrated``, ``consistent`` or ``failed`` (the Monte Carlo verification), None without one."""
        return None if self.verification is None else self.verification.verdict

    @property
    def ok(self) -> bool:
        """An optimal design, covering the region, that passed its verification (if one ran)."""
        if self.infeasible is not None or self.status != "optimal":
            return False
        if self.coverage is not None and not self.coverage.ok:
            return False
        return self.verification is None or bool(self.verification.ok)

    @property
    def writable(self) -> bool:
        """Whether :meth:`save` has something to write (a region no design can cover has not)."""
        return self.infeasible is None

    def design_note(self) -> str:
        """What the tables hold: the design's label, and whether it is the corrected one."""
        res, corr = self.result, self.correction
        note = f"{res.design.label}"
        if self.standard:
            note = (f"standard grades ({self.design.label}) in tolerance_std / grade: verified, to be built; the "
                    f"continuous {res.design.label} optimum in tolerance")
        if corr is not None and corr.rounds:
            note += (f", corrected for the nonlinear Monte Carlo ({corr.rounds} round(s), poses "
                     f"{', '.join(str(i + 1) for i in corr.tightened)} tightened, {corr.premium_pct:+.3g}% cost)")
        return note

    def requirement(self) -> str:
        pr = self.problem
        text = f"P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g}"
        if pr.angle_radius_rad is not None:
            text += f", P(|dw| < {np.rad2deg(pr.angle_radius_rad):g} deg) >= {pr.angle_prob:g}"
        return text

    def headline(self) -> list[str]:
        where = (f"region {self.label!r}" if self.region is not None else f"{self.problem.n_poses} {self.label} pose(s)")
        lines = [f"robot: {self.robot.name}   requirement: {self.requirement()} over {where}"]
        if self.infeasible is not None:
            return lines + ["status: infeasible over the region (no design): " + self.infeasible]
        extra = (f" (continuous optimum {self.continuous_design.cost:.4f}, "
                 f"{100 * (self.cost / self.continuous_design.cost - 1):+.2f} %)" if self.standard else "")
        lines.append(f"status: {self.status}   design to build: {self.design.label}   cost: {self.cost:.4f}{extra}")
        if self.verification is not None:
            v = self.verification
            lines.append(f"verification: {self.verdict} (lowest P_hat {v.p_mc.min():.5f}, n = {int(v.n.min())} per "
                         f"pose, {', '.join(sorted(set(map(str, v.estimator))))} estimator)")
        else:
            lines.append("verification: not run")
        return lines

    # ------------------------------------------------------------------ tables
    def to_frame(self) -> pd.DataFrame:
        """The tolerance table: one row per parameter (tolerance and sigma in mm or deg, standard grade, cost,
        variance share at the worst pose, process limits) and the ``design`` it holds."""
        table = self.result.to_frame()
        table["design"] = self.design_note()
        return table

    def verification_frame(self) -> pd.DataFrame | None:
        """Per pose: linear P, Monte Carlo P_hat with its 95 % interval, samples, verdict, reason."""
        return None if self.verification is None else self.verification.to_frame()

    def summary(self) -> dict:
        """The content of ``summary.json``: allocation, region search, coverage, verification, correction."""
        from tolalloc.workflows.allocation_text import summary_dict

        return summary_dict(self)

    def text(self) -> str:
        """What the command line prints (for a region no design can cover, why: the command's error line)."""
        from tolalloc.workflows.allocation_text import report_text

        if self.infeasible is not None:
            return "status: infeasible over the region (no design): " + self.infeasible
        return report_text(self)

    # ------------------------------------------------------------------ figures
    def plot_budget(self, axes=None, *, title: str | None = None):
        """Tolerance and variance share per parameter at the worst pose; returns the figure."""
        from tolalloc.report.plots.allocate import plot_budget

        t = (f"{self.robot.name}: {self.design.label} design, worst pose {self.result.worst_pose + 1}"
             if title is None else title)
        fig = plot_budget(self.to_frame(), None, title=t, axes=axes)
        return fig

    def plot_pose_probabilities(self, ax=None):
        """Linear P and Monte Carlo P_hat (95 % interval) per pose against p; returns the figure."""
        from tolalloc.report.plots.allocate import plot_pose_probabilities

        self._need_verification("plot_pose_probabilities")
        return plot_pose_probabilities(self.verification, None, ax=ax)

    def plot_cloud(self, axes=None):
        """Kept Monte Carlo position errors at the worst linear pose, three projections; returns the figure."""
        from tolalloc.report.plots.allocate import plot_cloud

        self._need_verification("plot_cloud")
        return plot_cloud(self.verification, None, axes=axes)

    def _need_verification(self, what: str) -> None:
        from tolalloc.exceptions import TolallocError

        if self.verification is None:
            raise TolallocError(f"{what}: this allocation was not verified (verify=False or no design); run "
                                "allocate_tolerances(..., verify=True).")

    # ------------------------------------------------------------------ files
    def save(self, out, *, report: bool = False) -> list[str]:
        """Write the tables, ``summary.json``, ``verification.csv`` and the figures into directory ``out``.

        All files appear together or none (staged, then published in one step). ``report=True`` also writes
        ``report.html``. Returns the names of the files written.
        """
        from tolalloc.exceptions import TolallocError

        if self.infeasible is not None:
            raise TolallocError(f"save: nothing to save, {self.infeasible}")
        self.check_out(out, "out", required=True)
        if not isinstance(report, (bool, np.bool_)):
            from tolalloc.exceptions import ArgumentError

            raise ArgumentError("report", f"expected True or False, got {report!r}.")
        with atomic_output(out, directory=True) as tmp:
            names = self.write_files(tmp, report=report)
        return names

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write the output files into an existing ``folder`` (not atomic; :meth:`save` stages through this)."""
        from tolalloc.report.tables import write_tables

        robot, pr = self.robot, self.problem
        write_tables(self.to_frame(), folder, caption=f"Tolerances of {robot.name}: P(|dP| < {pr.radius_mm:g} mm) >= "
                     f"{pr.prob:g} at the {self.label} poses", note=f"design: {self.design_note()}")
        write_json(self.summary(), folder / "summary.json")
        names = list(ALLOCATION_FILES)
        _save_figure(self.plot_budget(), folder / "error_budget.png")
        ver = self.verification
        if ver is not None:
            ver.to_frame().to_csv(folder / "verification.csv", index=False, float_format="%.8g")
            _save_figure(self.plot_pose_probabilities(), folder / "pose_probabilities.png")
            names += ["verification.csv", "pose_probabilities.png"]
            if ver.samples_mm is not None:
                _save_figure(self.plot_cloud(), folder / "error_cloud.png")
                names.append("error_cloud.png")
        if report:
            from tolalloc.workflows.html import write_allocation_report

            write_allocation_report(self, folder)
            names.append("report.html")
        return names


def _save_figure(fig, path, dpi: int = 100) -> None:
    import matplotlib.pyplot as plt

    fig.savefig(path, dpi=dpi)
    plt.close(fig)
