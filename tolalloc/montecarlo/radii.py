"""The probabilities of a Monte Carlo result by radius: :class:`RadiusTable` and :func:`probability_frame`.

``McResult.p_within`` (radius [mm] -> ``P(|dP| < r)`` per pose with its interval), ``p_within_angle`` (radius
[rad]) and ``p_estimates`` / ``p_estimates_angle`` are :class:`RadiusTable` dicts: looking up a radius that was
not simulated raises :class:`RadiusNotSimulated` naming the simulated radii and how to ask for another one (a
radius equal to a simulated one up to rounding, ``0.1 + 0.2`` for ``0.3``, finds it).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, describe

__all__ = ["RadiusNotSimulated", "RadiusTable", "probability_frame"]

#: relative difference under which a looked-up radius is the simulated one
RADIUS_RTOL = 1e-9


class RadiusNotSimulated(TolallocError, KeyError):
    """A radius looked up in a :class:`RadiusTable` that the Monte Carlo did not simulate (also a ``KeyError``)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class RadiusTable(dict):
    """Radius -> value (an array ``(P, 3)`` of p, CI low, CI high, or a ``ProbabilityEstimate``).

    ``angle=True``: the radii are rotation-error radii [rad]; else position-error radii [mm].
    """

    def __init__(self, items=(), *, angle: bool = False):
        super().__init__(items)
        self.angle = angle

    def _radius(self, r) -> str:
        return f"{r:g} rad ({np.rad2deg(r):.4g} deg)" if self.angle else f"{r:g} mm"

    def __missing__(self, key):
        radii = [f"{r:g}" for r in self]
        if isinstance(key, (int, float, np.integer, np.floating)) and not isinstance(key, (bool, np.bool_)):
            for r in self:
                if abs(r - key) <= RADIUS_RTOL * max(abs(r), abs(key)):
                    return self[r]
            what, radii = self._radius(float(key)), [*radii, f"{float(key):g}"]
        else:
            what = f"{describe(key)} (expected a number in {'rad' if self.angle else 'mm'})"
        done = ", ".join(self._radius(r) for r in self) or "none"
        ask = (f"angle_radius_rad=[{', '.join(radii)}] (simulate_errors; or angle_radius_deg, --angle-radius-deg)"
               if self.angle else f"radius_mm=[{', '.join(radii)}] (simulate_errors; --radius-mm)")
        raise RadiusNotSimulated(f"radius {what} was not simulated; simulated radii: {done}. Simulate it with "
                                 f"{ask}: the same seed gives the same samples.")


def probability_frame(mc) -> pd.DataFrame:
    """One row per pose and radius of ``mc`` (an :class:`~tolalloc.montecarlo.McResult`), read, not recomputed.

    Columns ``pose`` (from 1), ``error`` (``position`` or ``rotation``), ``radius_mm`` / ``radius_deg`` (the row's
    unit filled, the other empty), ``p``, ``ci_low``, ``ci_high`` (the interval of ``mc.ci``, 95 %).
    """
    rows = []
    for error, table, unit in (("position", mc.p_within, "mm"), ("rotation", mc.p_within_angle, "deg")):
        for r, v in table.items():
            radius = {"radius_mm": r, "radius_deg": np.nan} if unit == "mm" else \
                {"radius_mm": np.nan, "radius_deg": float(np.rad2deg(r))}
            rows += [{"pose": i + 1, "error": error, **radius, "p": p, "ci_low": lo, "ci_high": hi}
                     for i, (p, lo, hi) in enumerate(np.asarray(v))]
    return pd.DataFrame(rows, columns=["pose", "error", "radius_mm", "radius_deg", "p", "ci_low", "ci_high"])
