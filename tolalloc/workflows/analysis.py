"""Linear analysis in one call: :func:`analyze_errors` (variance map, probabilities, error budget)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import json_native, write_json
from tolalloc.workflows import defaults as D
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult
from tolalloc.workflows.settings import ErrorModelOptions, as_settings

__all__ = ["analyze_errors", "ErrorAnalysis"]


@inputs.job_entry
def analyze_errors(robot="tool_changer", *, q_deg_mm=None, poses: str | None = None, radius_mm=(), prob=(),
                   error_model=None, top: int = D.TOP, sobol_n: int = 0, seed: int = D.SEED, tool: str | None = None,
                   trust_units: bool = False) -> "ErrorAnalysis":
    """First-order tool-position error of a robot's error model: covariance, probabilities, error budget.

    Parameters
    ----------
    robot : Robot, str or path
    q_deg_mm : array, shape (n,) or (P, n), or DataFrame with q1..qN, optional
        Joint values [deg for revolute, mm for prismatic joints]; default the pose set ``poses`` (or nominal).
    poses : str, optional
        A pose set of the robot (``working``) or ``nominal``.
    radius_mm : float or sequence of float
        Radii r for ``P(|dP| < r)`` [mm].
    prob : float or sequence of float
        Probabilities in (0, 1) for the radius with ``P(|dP| < r) = p`` [mm].
    error_model : ErrorModelOptions, optional
        Sigma set, sigma overrides (mm or deg), link / deflection model, clearance, exclusions
        (:class:`~tolalloc.workflows.ErrorModelOptions`; default: the robot file's first sigma set).
    top : int
        Budget rows in :meth:`ErrorAnalysis.text` and the budget figure.
    sobol_n : int
        With ``sobol_n >= 16``: Sobol' first-order and total indices of ``|dP|`` (and of the pass / fail indicator
        for the first ``radius_mm``) at the worst pose from the nonlinear model (Saltelli sampling, Jansen
        estimators, ``sobol_n (K + 2)`` chain evaluations, ``seed``), beside the linear variance shares; factors
        whose nonlinear total index differs from the linear one by more than 0.05 are flagged.
    seed : int
        Seed of the Sobol' samples.

    Returns
    -------
    ErrorAnalysis

    Examples
    --------
    >>> import tolalloc
    >>> a = tolalloc.analyze_errors("tool_changer", radius_mm=0.25)
    >>> a.linear.std_mm.shape
    (1, 3)
    """
    model_options = as_settings(error_model, ErrorModelOptions, "error_model")
    radii = inputs.check_values(radius_mm, "radius_mm", inputs.check_positive, "mm", "0.25")
    probs = inputs.check_values(prob, "prob", inputs.check_probability)
    top = inputs.check_count(top, "top", example="10")
    sobol_n = inputs.check_count(sobol_n, "sobol_n", minimum=0, example="4096")
    if 0 < sobol_n < 16:
        raise ArgumentError("sobol_n", f"expected 0 (no Sobol' indices) or a base sample size >= 16 (e.g. 4096), got "
                            f"{sobol_n}.")
    seed = inputs.check_seed(seed)
    inputs.check_name(poses, "poses", "the name of a pose set of the robot")
    inputs.check_one_pose_source(q_deg_mm, poses)
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    model = inputs.error_model(rob, **model_options.keywords())
    if sobol_n:  # its memory (the samples are held) and time, before any work
        from tolalloc.montecarlo.sobol import check_sobol_budget

        check_sobol_budget(model, sobol_n, argument="sobol_n", announce=True)
    _, q = inputs.resolve_poses(rob, q_deg_mm, poses)
    from tolalloc.linear.covariance import budget, linear_map

    res = linear_map(model, q)
    b = budget(res)
    sobol = None
    if sobol_n:
        from tolalloc.montecarlo.sobol import sobol_indices

        sobol = sobol_indices(model, q[b.worst_pose], sobol_n, seed, radius_mm=radii[0] if radii else None)
    return ErrorAnalysis(res, b, tuple(radii), tuple(probs), bool(model_options.clearance), top, sobol)


@dataclass(frozen=True, eq=False, repr=False)
class ErrorAnalysis(JobResult):
    """Linear variance map at one or more poses, with the error budget.

    Attributes
    ----------
    linear : LinearResult
        Covariance ``J Sigma J^T`` per pose [mm^2, rad^2], standard deviations, ``P(|dP| < r)``.
    budget : ErrorBudget
        Each parameter's and kind's share of the variance of x, y, z and ``|dP|^2``.
    radii_mm, probs : tuple of float
    clearance : bool
    top : int
    sobol : SobolResult or None
        Nonlinear Sobol' indices at the worst pose beside the linear shares (``sobol_n > 0``).
    """

    linear: object
    budget: object
    radii_mm: tuple = ()
    probs: tuple = ()
    clearance: bool = False
    top: int = 10
    sobol: object = None
    inputs: dict = field(default_factory=dict)

    @property
    def model(self):
        return self.linear.model

    @property
    def robot(self):
        return self.linear.model.robot

    @property
    def ok(self) -> bool:
        return True

    def headline(self) -> list[str]:
        b = self.budget
        w = b.worst_pose
        top = b.to_frame(pose=w).iloc[0]
        return [f"robot: {self.robot.name}   linear map at {self.linear.n_poses} pose(s)",
                f"worst pose {w + 1}: RMS position error {self.linear.rms_mm[w]:.4g} mm, largest share "
                f"{top['parameter']}"]

    def to_frame(self) -> pd.DataFrame:
        """Per pose: standard deviations of x, y, z [mm], RMS and rotation standard deviations."""
        return self.linear.to_frame()

    def budget_frame(self, pose="worst", by: str = "parameter") -> pd.DataFrame:
        """The error budget at a pose (``"worst"`` or a 0-based index), per ``parameter`` or ``kind``."""
        return self.budget.to_frame(pose="worst" if isinstance(pose, str) and pose == "worst" else pose, by=by)

    def summary(self) -> dict:
        """The content of ``analyze.json``: the worst pose's values at top level, every pose under ``poses``."""
        from tolalloc.workflows.analysis_text import analyze_dict

        out = analyze_dict(self.linear, self.budget, list(self.radii_mm), list(self.probs))
        out["labels"] = {**out["labels"], "clearance": self.clearance}
        if self.sobol is not None:
            # an index is undefined (null) where its output did not vary over the samples (every sample passed)
            rows = [{k: None if isinstance(v, float) and not np.isfinite(v) else v for k, v in row.items()}
                    for row in self.sobol.to_frame().to_dict(orient="records")]
            out["sobol"] = {"pose": self.budget.worst_pose + 1, "n": self.sobol.n, "radius_mm": self.sobol.radius_mm,
                            "flag_diff": self.sobol.flag_diff, "message": self.sobol.message(), "factors": rows,
                            "null": "an index whose output (|dP| or the pass / fail indicator) did not vary over the "
                                    "samples is undefined"}
        return json_native(out)

    def text(self) -> str:
        """What the command line prints."""
        from tolalloc.workflows.base import format_labels

        res, b = self.linear, self.budget
        out = [f"robot {self.robot.name}, {format_labels(self.model.labels)}, clearance={self.clearance}; linear "
               "map, Gaussian approximation", res.to_frame().to_string(index=False, float_format=lambda x: f"{x:.5g}")]
        def per_pose(values, fmt, unit=""):
            if len(values) == 1:
                return f"{values[0]:{fmt}}{unit}"
            return "per pose " + ", ".join(f"{i + 1}: {v:{fmt}}{unit}" for i, v in enumerate(values))

        for r in self.radii_mm:
            out.append(f"P(|dp| < {r:g} mm) = " + per_pose(res.p_within(r), ".6g"))
        for p in self.probs:
            out.append(f"radius for P = {p:g}: " + per_pose(res.radius_for(p), ".5g", " mm"))
        out.append(f"\nerror budget at the worst pose ({b.worst_pose + 1}), top {self.top}:")
        out.append(b.to_markdown(pose="worst", top=self.top))
        if self.sobol is not None:
            out.append(f"\nSobol' indices at the worst pose ({b.worst_pose + 1}), nonlinear model beside the linear "
                       f"variance share: {self.sobol.message()}")
            top = self.sobol.to_frame().sort_values("ST_norm", ascending=False).head(self.top)
            out.append(top.to_string(index=False, float_format=lambda x: f"{x:.4f}"))
        return "\n".join(out)

    def plot_budget(self, ax=None, *, pose="worst", by: str = "parameter"):
        """Bar chart of the variance shares at a pose; draws into ``ax`` or a new figure and returns the Axes."""
        from tolalloc.report.plots.linear import budget_bars
        from tolalloc.workflows.base import axes_of

        inputs.check_axes(ax, "ax")
        fig = budget_bars(self.budget, None, pose=pose, by=by, top=self.top, ax=ax)
        return axes_of(fig) if ax is None else ax

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write ``linear_table.csv``, ``budget.csv``, ``budget_kinds.csv``, ``budget.md``, ``budget.png``,
        ``analyze.json`` (and ``sobol.csv``) into an existing ``folder`` (not atomic; :meth:`save` stages through
        this); returns the file names."""
        from pathlib import Path

        import matplotlib.pyplot as plt

        from tolalloc.workflows.base import format_labels

        folder = Path(folder)
        b, robot = self.budget, self.robot
        self.linear.to_frame().to_csv(folder / "linear_table.csv", index=False, float_format="%.6g")
        b.write_csv(folder / "budget.csv")
        b.write_csv(folder / "budget_kinds.csv", by="kind")
        with open(folder / "budget.md", "w") as fh:
            fh.write(f"# Error budget of {robot.name} (worst pose {b.worst_pose + 1}), {format_labels(self.model.labels)}\n\n")
            fh.write(b.to_markdown(pose="worst", by="kind") + "\n\n" + b.to_markdown(pose="worst") + "\n")
        fig = self.plot_budget().figure
        fig.savefig(folder / "budget.png", dpi=110)
        plt.close(fig)
        write_json(self.summary(), folder / "analyze.json")
        names = ["linear_table.csv", "budget.csv", "budget_kinds.csv", "budget.md", "budget.png", "analyze.json"]
        if self.sobol is not None:
            self.sobol.to_frame().to_csv(folder / "sobol.csv", index=False, float_format="%.6g")
            names.append("sobol.csv")
        return names
