"""Decision rules with the measurement uncertainty (ISO 14253-1).

ISO 14253-1:1998 (Geometrical Product Specifications -- Inspection by measurement of workpieces and measuring
equipment -- Part 1: Decision rules for proving conformance or nonconformance with specifications), 5.2 and 5.3:
the measurement uncertainty counts against whoever proves. For an upper specification limit ``L`` (the statistics
of ISO 9283 are non-negative), a measured value ``y`` of expanded uncertainty ``U``:

* **conformance demonstrated** when ``y + U <= L`` (``y`` in the specification zone reduced by ``U``, 5.2);
* **nonconformance demonstrated** when ``y - U > L`` (``y`` outside the zone enlarged by ``U``, 5.3);
* otherwise neither is demonstrated: ``y`` lies in the uncertainty range around ``L`` -- inside the limit but
  within ``U`` of it (the guard band), or above it by less than ``U``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["Decision", "decide", "CONFORMANCE", "NONCONFORMANCE", "INSIDE_GUARD_BAND", "ABOVE_LIMIT"]

CONFORMANCE = "conformance demonstrated"
NONCONFORMANCE = "nonconformance demonstrated"
INSIDE_GUARD_BAND = "not demonstrated: inside the limit, within U of it"
ABOVE_LIMIT = "not demonstrated: above the limit by less than U"


@dataclass(frozen=True)
class Decision:
    """The ISO 14253-1 verdict on one value.

    Attributes
    ----------
    outcome : str
        :data:`CONFORMANCE`, :data:`NONCONFORMANCE`, :data:`INSIDE_GUARD_BAND` or :data:`ABOVE_LIMIT`.
    value, limit, U : float
        Measured (or predicted measured) value, specification limit and expanded uncertainty [one unit].
    """

    outcome: str
    value: float
    limit: float
    U: float

    @property
    def demonstrated(self) -> bool:
        """Conformance demonstrated."""
        return self.outcome == CONFORMANCE

    @property
    def margin(self) -> float:
        """``L - (y + U)``: how far inside the reduced zone (> 0 demonstrated) or outside it (< 0)."""
        return float(self.limit - self.value - self.U)

    def text(self, unit: str = "mm", scale: float = 1.0) -> str:
        """One sentence: the verdict, the numbers and, short of a demonstration, by how much it missed."""
        y, L, U = self.value * scale, self.limit * scale, self.U * scale
        f = (lambda v: f"{v:.4g} {unit}")
        if self.outcome == CONFORMANCE:
            return f"{self.outcome}: {f(y)} + U {f(U)} = {f(y + U)} <= {f(L)} (margin {f(L - y - U)})"
        if self.outcome == NONCONFORMANCE:
            return f"{self.outcome}: {f(y)} - U {f(U)} = {f(y - U)} > {f(L)}"
        if self.outcome == INSIDE_GUARD_BAND:
            return (f"{self.outcome}: {f(y)} is {f(L - y)} below the limit {f(L)} but U = {f(U)}; conformance "
                    f"needs the value {f(y + U - L)} lower, or U <= {f(L - y)}")
        return (f"{self.outcome}: {f(y)} is {f(y - L)} above the limit {f(L)}, less than U = {f(U)}; "
                f"nonconformance is not proven either")


def decide(value, limit, U) -> Decision:
    """ISO 14253-1 verdict on ``value`` against the upper limit ``limit`` with expanded uncertainty ``U``."""
    y, L, u = float(value), float(limit), float(U)
    if not (np.isfinite(y) and np.isfinite(L) and np.isfinite(u)) or u < 0:
        raise TolallocError(f"decide: expected a finite value, limit and U >= 0, got {value!r}, {limit!r}, {U!r}.")
    if y + u <= L:
        out = CONFORMANCE
    elif y - u > L:
        out = NONCONFORMANCE
    elif y <= L:
        out = INSIDE_GUARD_BAND
    else:
        out = ABOVE_LIMIT
    return Decision(out, y, L, u)
