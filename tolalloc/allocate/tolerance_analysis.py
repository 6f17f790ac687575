"""Tolerance analysis of an existing drawing: zones, fits, grades and bought parts back to error-screw sigmas, and
the probability they give at every pose (the reverse of the handover, :mod:`tolalloc.allocate.handover`).

Every callout bounds its parameters' half-width ``t = zone / factor`` (:class:`~tolalloc.allocate.drawing.Callout`:
a size or position ``zone / 2``, an orientation zone in one direction ``zone / L``, a diameter zone ``zone / (L f)``
at the two-dimensional coverage, a fit ``c_max / (2 sqrt(2))``); a purchased part its stated half-width. Then
``sigma = t / z`` and the linear map gives ``P(|dP| < r)`` at every pose, the worst pose (of a region: found by
the allocation's worst-pose search), and each feature's share of the error variance there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.allocate.drawing import FeatureMap
from tolalloc.allocate.region import REGION_TOL
from tolalloc.exceptions import TolallocError
from tolalloc.linear.covariance import variance_share
from tolalloc.linear.probability import p_within_radius

__all__ = ["DrawingAnalysis", "halfwidths_from_drawing", "analyze_drawing"]


def halfwidths_from_drawing(model, fmap: FeatureMap, *, others: str = "error") -> np.ndarray:
    """Half-width of every parameter of ``model`` (K,) [mm or rad] that drawing ``fmap`` allows.

    ``others``: ``"error"`` refuses a parameter no row bounds (naming them); ``"model"`` keeps the error model's
    ``sigma * z`` for them. A parameter bounded by two rows takes the tighter.
    """
    if others not in ("error", "model"):
        raise TolallocError(f"others: expected 'error' or 'model', got {others!r}.")
    t = np.full(len(model.params), np.inf)
    idx = {nm: i for i, nm in enumerate(model.names)}
    for c in fmap.callouts:
        for p in c.parameters:
            t[idx[p]] = min(t[idx[p]], c.zone_mm / c.factor)
    for part in fmap.parts:
        for p in part.parameters:
            t[idx[p]] = min(t[idx[p]], part.required)
    free = np.isinf(t)
    if free.any():
        if others == "error":
            raise TolallocError(f"drawing: no callout or part bounds {', '.join(np.array(model.names)[free])}; add "
                                "rows for them, or keep the error model's sigma for them (others='model').")
        t[free] = np.array([p.sigma for p in model.params])[free] * fmap.z
    return t


@dataclass(frozen=True, eq=False)
class DrawingAnalysis:
    """``P(|dP| < r)`` of a drawing at every pose, its worst pose and each feature's share there.

    Attributes
    ----------
    features : FeatureMap
    names : tuple of str
        Error parameters (the model's order).
    t : array, shape (K,) [mm or rad]
    sigma : array, shape (K,) [mm or rad]
    q : array, shape (P, n) [rad, mm]
        The poses analysed (with the region's worst pose last when a region was searched).
    p : array, shape (P,)
    radius_mm, prob : float
    worst : int
        Index of the worst pose in ``q``.
    share : array, shape (K,)
        Each parameter's share of ``tr Sigma`` of the position error at the worst pose.
    """

    features: FeatureMap
    names: tuple
    t: np.ndarray
    sigma: np.ndarray
    q: np.ndarray
    p: np.ndarray
    radius_mm: float
    prob: float
    worst: int
    share: np.ndarray

    @property
    def p_worst(self) -> float:
        return float(self.p[self.worst])

    @property
    def shortfall(self) -> float:
        """How far the worst pose's ``P`` lies below ``prob`` (0 when it does not)."""
        return float(max(self.prob - self.p_worst, 0.0))

    @property
    def ok(self) -> bool:
        """Whether ``P >= prob`` at every pose analysed, to within the tolerance the allocation's region search
        accepts (:data:`~tolalloc.allocate.region.REGION_TOL` in ``P``): the review of a drawing holds it to the rule
        the design was allocated by."""
        return bool(np.all(self.p >= self.prob - REGION_TOL))

    def verdict(self) -> str:
        """``meets it``, ``meets it within the allocation's tolerance ...`` (short by less than it) or ``does NOT meet
        it``; the worst pose's shortfall is in :meth:`text`."""
        if self.shortfall == 0.0:
            return "meets it"
        return (f"meets it within the allocation's tolerance of {REGION_TOL:g} in P" if self.ok else
                "does NOT meet it")

    def feature_frame(self) -> pd.DataFrame:
        """One row per callout and part: ``feature, characteristic, parameters, variance_share_pct`` at the worst
        pose, largest first."""
        idx = {nm: i for i, nm in enumerate(self.names)}
        rows = [(c.feature, c.characteristic, c.parameters) for c in self.features.callouts]
        rows += [(p.part, "purchased_part", p.parameters) for p in self.features.parts]
        frame = pd.DataFrame({"feature": [r[0] for r in rows], "characteristic": [r[1] for r in rows],
                              "parameters": [" ".join(r[2]) for r in rows],
                              "variance_share_pct": [100.0 * sum(self.share[idx[p]] for p in r[2]) for r in rows]})
        return frame.sort_values("variance_share_pct", ascending=False, ignore_index=True)

    def text(self) -> str:
        short = f" ({self.shortfall:.2g} short)" if self.shortfall > 0 else ""
        lines = [f"drawing review: P(|dP| < {self.radius_mm:g} mm) >= {self.prob:g}: the drawing {self.verdict()} at "
                 f"{int(np.sum(self.p >= self.prob - REGION_TOL))} of {len(self.p)} pose(s); worst pose "
                 f"{self.worst + 1}: P = {self.p_worst:.6f}{short}",
                 "feature shares of the position-error variance at the worst pose:"]
        fr = self.feature_frame()
        lines += [f"  {r.variance_share_pct:6.2f} %  {r.characteristic:16s} {r.feature} ({r.parameters})"
                  for r in fr.itertuples()]
        return "\n".join(lines)


def analyze_drawing(model, fmap: FeatureMap, q, *, radius_mm: float, prob: float, region=None,
                    others: str = "error", seed: int = 0) -> DrawingAnalysis:
    """``P(|dP| < radius_mm)`` under drawing ``fmap`` at poses ``q`` (P, n) [rad, mm] and, with a ``region``
    (:class:`~tolalloc.allocate.region.Region`), at the region's worst pose (appended to the poses)."""
    q = np.atleast_2d(np.asarray(q, float))
    t = halfwidths_from_drawing(model, fmap, others=others)
    sigma = t / fmap.z
    if region is not None:
        from tolalloc.allocate.problem import build_problem
        from tolalloc.allocate.region import worst_pose

        problem = build_problem(model, q, radius_mm=radius_mm, prob=prob)
        qw, _, _ = worst_pose(problem, sigma * problem.costs.z, region, seed=seed)
        q = np.vstack([q, qw])
    J = model.jacobian(q)[:, :3, :]
    p = np.asarray(p_within_radius(np.einsum("pik,k,pjk->pij", J, sigma**2, J), radius_mm), float)
    w = int(np.argmin(p))
    return DrawingAnalysis(fmap, tuple(model.names), t, sigma, q, p, float(radius_mm), float(prob), w,
                           variance_share(J[w], sigma**2))
