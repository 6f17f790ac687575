"""The result of :func:`tolalloc.allocate_tolerances`: tables, summary, text, figures, files."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.outputs import write_json
from tolalloc.workflows.base import AllocationJobResult, _old_axes, axes_of

__all__ = ["ToleranceAllocation"]

#: files written by :meth:`ToleranceAllocation.save` (those after the marker only with a verification)
ALLOCATION_FILES = ("tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json", "error_budget.png")


@dataclass(frozen=True, eq=False, repr=False)
class ToleranceAllocation(AllocationJobResult):
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
    >>> res.to_frame().loc[0, ["parameter", "unit", "grade"]].tolist(), float(res.to_frame().loc[0, "nominal_mm"])
    (['dl1', 'mm', 'IT10'], 315.0)
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
    def design(self):
        """The design that will be built (verified, covered): the standard one, or the continuous one."""
        return self.built if self.built is not None else self.result.design

    @property
    def continuous_design(self):
        """The continuous optimum (``result.design``; ``tol_continuous_mm`` / ``tol_continuous_deg`` in the table)."""
        return self.result.design

    @property
    def standard(self) -> bool:
        """Whether the design to build is the standard one (the table's ``tol_mm`` / ``tol_deg`` and ``grade``)."""
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
        """Whether the design to build meets the requirement as far as it was checked: an optimal design that covers
        the region (a box region) and passed its Monte Carlo verification -- or had none (``verification=False``: then
        only the linear prediction was checked, and :attr:`verified` is False)."""
        if self.infeasible is not None or self.status != "optimal":
            return False
        if self.coverage is not None and not self.coverage.ok:
            return False
        return self.verification is None or bool(self.verification.ok)

    @property
    def verified(self) -> bool:
        """Whether the design to build passed a nonlinear Monte Carlo verification (False when none ran)."""
        return self.verification is not None and self.ok

    @property
    def worst_pose(self) -> int:
        """Pose index (0-based) of the allocation's poses with the lowest linear P of the design to build."""
        return int(np.argmin(self.design.p_linear["position"]))

    @property
    def writable(self) -> bool:
        """Whether :meth:`save` has something to write (a region no design can cover has not)."""
        return self.infeasible is None

    def design_note(self) -> str:
        """Which design the tables hold and what was checked, in one sentence: the ``.md`` first line, the ``.tex``
        caption, ``tables_design`` in summary.json and a line of :meth:`text`."""
        res, d = self.result, self.design
        if res.status != "optimal":
            return (f"{d.label}: for reference only, it does not meet the requirement (status {res.status}); "
                    "not a design to build")
        if self.standard:
            what = f"standard grades ({d.label})"
        elif res.standard is None:
            what = f"the continuous {d.label} design (no standard values asked for)"
        else:
            what = f"the continuous {d.label} design (the standard design does not meet the requirement)"
        parts = [what + (", the design to build" if self.ok else ", NOT ready to build")] + self._checks()
        corr = self.correction
        if corr is not None and corr.rounds:
            which = [f"{what} at pose(s) {', '.join(str(i + 1) for i in idx)}" for what, idx in
                     (("position", corr.tightened), ("orientation", getattr(corr, "tightened_angle", ())))
                     if len(idx)]
            parts.append(f"corrected for the nonlinear Monte Carlo ({corr.rounds} round(s), {'; '.join(which)} "
                         f"tightened, {corr.premium_pct:+.3g} % cost)")
        if self.standard:
            c = res.design.cost
            parts.append(f"cost {d.cost:.4f}, {100 * (d.cost / c - 1):+.2f} % over the continuous {res.design.label} "
                         f"optimum ({c:.4f})")
        return "; ".join(parts)

    def _checks(self) -> list[str]:
        """What the coverage and the verification found for the design to build, in words."""
        cov, ver, out = self.coverage, self.verification, []
        if cov is not None and cov.angle_prob is None:
            out.append(f"covers the region (lowest linear P {cov.min_p:.4f} on {cov.n} fresh poses)" if cov.ok else
                       f"does NOT cover the region ({cov.n_below} of {cov.n} fresh poses below p, lowest linear P "
                       f"{cov.min_p:.4f})")
        elif cov is not None:
            low = (f"lowest linear P {cov.min_p:.4f} (position), {cov.min_p_angle:.4f} (orientation) on {cov.n} fresh "
                   "poses")
            out.append(f"covers the region ({low})" if cov.ok else
                       f"does NOT cover the region ({cov.n_below} position and {cov.n_below_angle} orientation "
                       f"pose(s) of {cov.n} fresh poses below p, {low})")
        if ver is None:
            out.append("NOT verified by Monte Carlo (verification not run; the linear prediction meets the "
                       "requirement at every pose of the allocation)")
        elif ver.ok:
            out.append(f"verified by nonlinear Monte Carlo: {ver.verdict} at {ver.all_poses_text()}")
        else:
            out.append(f"NOT verified: the nonlinear Monte Carlo is {ver.verdict} at pose(s) "
                       + ", ".join(str(i) for i, _ in ver.failing))
        return out

    def where(self) -> str:
        """Where the requirement holds, for captions: the box region or the pose set."""
        if self.region is not None:
            return f"over the box region {self.label!r}"
        return f"at the {self.problem.n_poses} pose(s) of {self.label!r}"

    def table_legend(self) -> str:
        """What the columns of the tolerance table hold, with their units (below the ``.md`` / ``.tex`` table)."""
        pr = self.problem
        dist = " (errors uniform over ±t)" if pr.costs.distribution == "uniform" else ""
        from tolalloc.report.tables import UNIT_PAIRS_LEGEND

        return (f"Tolerances are symmetric ± half-widths. {UNIT_PAIRS_LEGEND} grade: the ISO 286 IT grade of a link "
                "length, a class name, or empty (a multiple of the resolution step). "
                f"sigma = tol / {pr.costs.z:.4g}{dist}. cost: relative cost units of the cost laws. "
                "variance_share_pct: share of tr(Sigma) of the position error at the worst pose (pose "
                f"{self.worst_pose + 1}), in %. role: allocate, or fixed by the costs file. at_limit: t_min or t_max "
                "when the tolerance sits at a process limit (fixed: set by the costs file). process: the optimiser's "
                "(costs file [processes.*]) or the cheapest of the built-in table (assumed). callout: the row's drawing "
                "callout (ISO 1101 zone in mm | datum, over its length) or bought part (handover.md: sources and "
                "assumptions).")

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
        role = "design to build" if self.status == "optimal" else "design (for reference only, not to build)"
        lines.append(f"status: {self.status}   {role}: {self.design.label}   cost: {self.cost:.4f}{extra}")
        if self.verification is not None:
            v = self.verification
            angle = (f", orientation {v.angle['p_mc'].min():.5f}" if getattr(v, "angle", None) is not None else "")
            lines.append(f"verification: {self.verdict} (lowest P_hat {v.p_mc.min():.5f}{angle}, n = {int(v.n.min())} "
                         f"per pose, {', '.join(sorted(set(map(str, v.estimator))))} estimator)")
        elif self.status == "optimal":
            lines.append("verification: not run (NOT verified; linear prediction only)")
        else:
            lines.append("verification: not run (no design that meets the requirement)")
        return lines

    # ------------------------------------------------------------------ tables
    def to_frame(self) -> pd.DataFrame:
        """The tolerance table of the design to build: one row per parameter, tolerance and sigma in ``*_mm`` /
        ``*_deg`` columns, standard grade, cost, variance share at its worst pose, process limits, and the continuous
        optimum for comparison (:meth:`tolalloc.allocate.result.AllocationResult.to_frame`). Which design it is and
        what was checked: :meth:`design_note`. An empty ``process`` is filled from :meth:`handover` (the built-in
        table's process, ``purchased part`` for a joint drive); ``callout`` is the row's drawing callout or bought
        part and ``cost_source`` (last) where its cost comes from."""
        frame = self.result.to_frame(self.design)
        if self.infeasible is None and self.design.t is not None:
            h = self.handover()
            fill, callout, source = h.process_of(), h.callout_of(), h.cost_source_of()
            frame["process"] = [p or fill.get(n, "") for p, n in zip(frame["process"], frame["parameter"])]
            frame["callout"] = [callout.get(n, "") for n in frame["parameter"]]
            frame["cost_source"] = [source.get(n, "") for n in frame["parameter"]]
        return frame

    def handover(self, settings=None):
        """The drawing callouts, purchase list and assumptions of the design to build
        (:func:`tolalloc.allocate.handover.handover`; ``settings``: a
        :class:`~tolalloc.allocate.drawing.HandoverSettings`, default its stated defaults)."""
        from tolalloc.allocate.handover import handover

        if settings is not None:
            return handover(self.result, self.design, settings=settings)
        if "_handover" not in self.__dict__:
            object.__setattr__(self, "_handover", handover(self.result, self.design))
        return self.__dict__["_handover"]

    def card_lines(self) -> list[str]:
        """The headline and which design the table holds (the table's caption)."""
        return self.headline() + ([] if self.infeasible is not None else [f"table: {self.design_note()}"])

    def card_frame(self) -> pd.DataFrame | None:
        """The key columns of the tolerance table (the card of a notebook); None for a region no design covers."""
        from tolalloc.report.tables import TABLE_COLUMNS

        if self.infeasible is not None:
            return None
        frame = self.to_frame()
        cols = [c for c in TABLE_COLUMNS if c in frame.columns]
        return frame[cols[:2] + ["unit"] + cols[2:]]

    def error_model_options(self):
        """The design to build as an :class:`~tolalloc.workflows.ErrorModelOptions`: every parameter's sigma (mm or
        deg) overridden by the design's, the same link and deflection model and clearance, the parameters left out of
        the allocation left out; for ``simulate_errors(robot, error_model=res.error_model_options())``. The
        simulation draws Gaussian errors of these sigmas (``Costs(uniform=True)`` designs: same sigma, not uniform)."""
        from tolalloc.workflows.settings import ErrorModelOptions

        frame, model = self.to_frame(), self.problem.model
        sigma = dict(zip(frame["parameter"], frame["sigma_mm"].fillna(frame["sigma_deg"]).astype(float)))
        labels = model.labels
        return ErrorModelOptions(sigma_set=labels["sigma_set"], link_mode=labels["link_mode"],
                                 deflection_mode=labels["deflection_mode"],
                                 clearance=any(str(k).startswith("clearance") for k in model.kinds), sigma=sigma,
                                 exclude=tuple(self.inputs.get("exclude", [])) + tuple(self.problem.costs.excluded))

    def verification_frame(self) -> pd.DataFrame | None:
        """Per pose: linear P, Monte Carlo P_hat with its interval (95 % simultaneous over the poses and requirements,
        a certified pose's possible second look counted; ``level_per_interval``, ``family_level``), samples, verdict,
        reason."""
        return None if self.verification is None else self.verification.to_frame()

    def summary(self) -> dict:
        """The content of ``summary.json``: allocation, region search, coverage, verification, correction."""
        from tolalloc.outputs import json_native
        from tolalloc.workflows.allocation_text import summary_dict

        return json_native(summary_dict(self))

    def text(self) -> str:
        """What the command line prints (for a region no design can cover, why: the command's error line)."""
        from tolalloc.workflows.allocation_text import report_text

        if self.infeasible is not None:
            return "status: infeasible over the region (no design): " + self.infeasible
        return report_text(self)

    # ------------------------------------------------------------------ figures
    def plot_budget(self, ax=None, *, title: str | None = None, axes=None):
        """Tolerance and variance share per parameter at the worst pose, side by side; draws into ``ax`` (a pair of
        Axes) or a new figure and returns the pair."""
        from tolalloc.report.plots.allocate import plot_budget
        from tolalloc.workflows.checks import check_axes, check_text

        ax = _old_axes("plot_budget", ax, axes)
        check_axes(ax, "ax", 2)
        check_text(title, "title", "the figure's title")
        t = (f"{self.robot.name}: {self.design.label} design, worst pose {self.worst_pose + 1}"
             if title is None else title)
        fig = plot_budget(self.to_frame(), None, title=t, axes=ax)
        return axes_of(fig) if ax is None else axes_of(list(ax))

    def plot_pose_probabilities(self, ax=None):
        """Linear P and Monte Carlo P_hat (95 % simultaneous interval) per pose against p; returns the Axes."""
        from tolalloc.report.plots.allocate import plot_pose_probabilities
        from tolalloc.workflows.checks import check_axes

        check_axes(ax, "ax")
        self._need_verification("plot_pose_probabilities")
        fig = plot_pose_probabilities(self.verification, None, ax=ax)
        return axes_of(fig) if ax is None else ax

    def plot_cloud(self, ax=None, *, axes=None):
        """Kept Monte Carlo position errors at the worst linear pose, three projections; draws into ``ax`` (three
        Axes) or a new figure and returns the three."""
        from tolalloc.report.plots.allocate import plot_cloud
        from tolalloc.workflows.checks import check_axes

        ax = _old_axes("plot_cloud", ax, axes)
        check_axes(ax, "ax", 3)
        self._need_verification("plot_cloud")
        fig = plot_cloud(self.verification, None, axes=ax)
        return axes_of(fig) if ax is None else axes_of(list(ax))

    def _need_verification(self, what: str) -> None:
        from tolalloc.exceptions import TolallocError

        if self.verification is None:
            raise TolallocError(f"{what}: this allocation was not verified (verification=False or no design); expected "
                                "a verified allocation: run allocate_tolerances(...) with its verification on.")

    # ------------------------------------------------------------------ files
    has_report = True

    def check_savable(self) -> None:
        from tolalloc.exceptions import TolallocError

        if self.infeasible is not None:
            raise TolallocError(f"save: nothing to save, {self.infeasible}")

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write the tables, ``summary.json``, ``verification.csv``, the figures and (``report``) ``report.html``
        into an existing ``folder`` (not atomic; :meth:`save` stages through this); returns the file names."""
        from pathlib import Path

        from tolalloc.report.tables import write_tables

        folder = Path(folder)
        write_tables(self.to_frame(), folder, caption=f"Tolerances of {self.robot.name}: {self.requirement()} "
                     f"{self.where()}", note=f"design: {self.design_note()}", legend=self.table_legend())
        write_json(self.summary(), folder / "summary.json")
        names = list(ALLOCATION_FILES)
        from tolalloc.report.handover import write_handover

        names += write_handover(self.handover(), folder, f"Handover of {self.robot.name}: {self.requirement()} "
                                f"{self.where()}")
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
            from tolalloc.report.html_allocation import write_allocation_report

            write_allocation_report(self, folder)
            names.append("report.html")
        return names


def _save_figure(axes, path, dpi: int = 100) -> None:
    """Save the figure of ``axes`` (what a ``plot_*`` method returns) and close it."""
    import matplotlib.pyplot as plt

    fig = np.ravel(np.asarray(axes, dtype=object))[0].figure
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
