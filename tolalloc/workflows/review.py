"""Design review of an existing drawing in one call: :func:`review_drawing`.

The drawing exchange file (:mod:`tolalloc.allocate.drawing_io`: zones, fits, grades, bought parts) -> sigma of every
error parameter -> ``P(|dP| < r)`` at the poses (and the worst pose of a box region) -> each feature's share of the
error variance at the worst pose (:func:`tolalloc.allocate.tolerance_analysis.analyze_drawing`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.outputs import write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["review_drawing", "DrawingReview"]


@inputs.job_entry
def review_drawing(robot="tool_changer", drawing=None, *, radius_mm: float = 0.25, prob: float = 0.95, region=None,
                   costs=None, error_model=None, others: str = "error", seed: int = 0, tool: str | None = None,
                   trust_units: bool = False):
    """``P(|dP| < radius_mm)`` that an existing drawing gives, at the worst pose of the region, with each
    feature's share.

    Parameters
    ----------
    robot : Robot, str or path
    drawing : path
        The drawing exchange CSV (the ``drawing.csv`` an allocation writes, or one made by hand in its schema).
    radius_mm, prob : float
        The requirement the drawing is reviewed against.
    region : str, array or Region, optional
        Where: as in :func:`tolalloc.allocate_tolerances` (a box is searched for its worst pose).
    costs : Costs, optional
        Only its ``z`` (sigma = t / z) or ``uniform`` (errors uniform over ±t) are read. A drawing file that
        records its design's z and distribution (columns ``z``, ``distribution``) is reviewed with them and a given
        value that disagrees is refused; a file without them (written before they were recorded, or by hand) is
        reviewed with the given z, else 3. The review's ``inputs`` name the z used and where it came from.
    error_model : ErrorModelOptions, optional
        Sigma set, link and deflection model (clearance parameters are included when the drawing bounds any).
    others : {"error", "model"}
        A parameter no row bounds: an error, or the error model's own sigma.
    seed : int
        Seed of the region's worst-pose search.
    """
    from tolalloc.workflows.allocation_settings import Region
    from tolalloc.workflows.settings import Costs, ErrorModelOptions, as_settings

    reg = region if isinstance(region, Region) else Region(where=region)
    region, poses = reg.where, reg.poses
    cost = as_settings(costs, Costs, "costs")
    em = as_settings(error_model, ErrorModelOptions, "error_model")
    z, uniform = cost.z, cost.uniform
    sigma_set, link_mode, deflection_mode = em.sigma_set, em.link_mode, em.deflection_mode
    from tolalloc.allocate.drawing_io import read_drawing, read_rows, recorded_z
    from tolalloc.allocate.tolerance_analysis import analyze_drawing
    from tolalloc.exceptions import ArgumentError

    if drawing is None or not isinstance(drawing, (str, os.PathLike)):
        raise ArgumentError("drawing", f"expected the path (str or pathlib.Path) of a drawing exchange CSV "
                            f"(drawing.csv), got {drawing!r} ({type(drawing).__name__}).")
    inputs.check_probability(prob, "prob")
    inputs.check_positive(radius_mm, "radius_mm", "mm", "0.25")
    inputs.check_seed(seed, "seed")
    rb = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    frame = read_rows(drawing)
    cells = frame["parameters"] if "parameters" in frame.columns else []  # a missing column: read_drawing says so
    clearance = any(str(p).startswith(("ca", "cr", "cw")) for p in " ".join(cells).split())
    model = inputs.error_model(rb, sigma_set=sigma_set, link_mode=link_mode, deflection_mode=deflection_mode,
                               clearance=clearance)
    given_z = None if z is None else inputs.check_z(z)
    fmap = read_drawing(frame, model, z=given_z, distribution="uniform" if uniform else None, name=str(drawing))
    zz, dist = fmap.z, fmap.distribution
    z_source = ("the drawing file" if recorded_z(frame)[0] is not None else
                "given (the drawing file records none)" if z is not None or uniform else
                "default (the drawing file records none)")
    label, box, q = inputs.resolve_region(rb, region, poses)
    if box is not None:
        q = box.sample(1, seed)
    analysis = analyze_drawing(model, fmap, q, radius_mm=radius_mm, prob=prob, region=box, others=others, seed=seed)
    return DrawingReview(analysis, label, rb, {"robot": rb.name, "drawing": str(drawing), "radius_mm": radius_mm,
                                           "prob": prob, "region": label, "z": zz, "distribution": dist,
                                           "z_source": z_source, "seed": seed})


@dataclass(frozen=True, eq=False, repr=False)
class DrawingReview(JobResult):
    """The review of a drawing: its ``P`` per pose, the worst pose, each feature's share.

    Attributes
    ----------
    analysis : DrawingAnalysis
    label : str
        The region or pose set.
    robot : Robot
    inputs : dict
    """

    analysis: object
    label: str
    robot: object
    inputs: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.analysis.ok

    def headline(self) -> list[str]:
        a = self.analysis
        q = ", ".join(f"{v:.4g}" for v in self.robot.q_to_interface(a.q[a.worst]))
        return [f"robot: {self.inputs.get('robot')}   drawing: {self.inputs.get('drawing')}",
                f"requirement: P(|dP| < {a.radius_mm:g} mm) >= {a.prob:g} over {self.label!r}; sigma = t / z with "
                f"z = {self.inputs.get('z', 3.0):.4g} ({self.inputs.get('distribution', 'normal')}, "
                f"{self.inputs.get('z_source', 'given')})",
                f"worst pose {a.worst + 1} (q = {q} deg / mm): P = {a.p_worst:.6f}"
                + (f", {a.shortfall:.2g} short" if a.shortfall > 0 else "") + f" (the drawing {a.verdict()})"
                ] + self._gap_lines()

    def _gap_lines(self) -> list[str]:
        """The callouts whose datum cannot bound their parameter: P above takes them as bounding it."""
        gaps = self.analysis.features.datum_gaps
        if not gaps:
            return []
        return ([f"P takes every callout as bounding its parameter; {len(gaps)} cannot as drawn, and the verdict "
                 "holds only once each has the datum it needs:"] + [f"DATUM NEEDED: {g}" for g in gaps])

    def to_frame(self) -> pd.DataFrame:
        """Each feature's share of the position-error variance at the worst pose."""
        return self.analysis.feature_frame()

    def pose_frame(self) -> pd.DataFrame:
        """Per pose: ``pose`` (from 1), ``p_linear``, ``meets``."""
        a = self.analysis
        return pd.DataFrame({"pose": np.arange(1, len(a.p) + 1), "p_linear": a.p, "meets": a.p >= a.prob})

    def summary(self) -> dict:
        from tolalloc.outputs import json_native

        a = self.analysis
        return json_native({"inputs": self.inputs, "ok": a.ok, "datum_gaps": list(a.features.datum_gaps),
                            "worst_pose": a.worst + 1, "p_worst": a.p_worst,
                            "q_worst_deg_mm": self.robot.q_to_interface(a.q[a.worst]).tolist(),
                            "p_linear": a.p.tolist(), "features": self.to_frame().to_dict("records")})

    def text(self) -> str:
        return "\n".join(self.headline()) + "\n" + self.analysis.text()

    def plot_shares(self, ax=None):
        """Each feature's share of the variance at the worst pose (bars, largest first); returns the axes."""
        from tolalloc.report.plots.acceptance import plot_feature_shares

        return plot_feature_shares(self.to_frame(), ax=ax)

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """``review_features.csv``, ``review_poses.csv`` and ``review.json`` into an existing ``folder`` (not atomic:
        :meth:`save` publishes them together)."""
        folder = Path(folder)
        self.to_frame().to_csv(folder / "review_features.csv", index=False, float_format="%.8g")
        self.pose_frame().to_csv(folder / "review_poses.csv", index=False, float_format="%.10g")
        write_json(self.summary(), folder / "review.json")
        return ["review_features.csv", "review_poses.csv", "review.json"]
