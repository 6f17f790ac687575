"""The test conditions of ISO 9283 requirements: load (6.6) and velocity (6.7)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import ArgumentError

__all__ = ["Conditions"]


@dataclass(frozen=True)
class Conditions:
    """Test conditions of ISO 9283: load (6.6) and velocity (6.7), in percent of the rated values.

    Attributes
    ----------
    load_pct : float
        Load on the mechanical interface, % of the rated load (the standard tests at 100 %, and optionally at
        10 %); 0 to 100.
    speed_pct : float
        Velocity, % of the rated velocity (100, 50 or 10 in the standard); > 0 to 100.
    """

    load_pct: float = 100.0
    speed_pct: float = 100.0

    def __post_init__(self):
        for name, lo in (("load_pct", 0.0), ("speed_pct", 0.0)):
            v = getattr(self, name)
            ok = not isinstance(v, bool) and isinstance(v, (int, float, np.floating)) and np.isfinite(v)
            if not ok or not (lo <= v <= 100) or (name == "speed_pct" and v == 0):
                raise ArgumentError(f"Conditions.{name}", f"expected a percentage of the rated value in "
                                    f"{'[0, 100]' if name == 'load_pct' else '(0, 100]'} (ISO 9283 tests at 100 "
                                    f"and {'10' if name == 'load_pct' else '50, 10'}), got {v!r}.")
            object.__setattr__(self, name, float(v))

    def text(self) -> str:
        return f"{self.load_pct:g} % rated load, {self.speed_pct:g} % rated velocity"
