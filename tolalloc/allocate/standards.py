"""Standard tolerance grades: ISO 286-1 IT grades for lengths, a fixed step for angles.

A symmetric tolerance ``±t`` is a tolerance zone of width ``2 t`` (deviations ``js``/``JS``:
``±IT/2``). Snapping takes, for a length of nominal size ``D``, the coarsest IT grade whose
zone is at or below the allocated width (``IT <= 2 t``) and sets ``t = IT / 2``; angles are
rounded down to a multiple of a stated step (default 1 arcsec). Snapping only tightens, so the
requirement can only get better -- but a snapped value may fall below the process limit
``t_min``; then the next coarser grade (or step) at or above ``t_min`` is taken and the
requirement must be re-checked (:func:`tolalloc.allocate.problem.recheck`).

Values: ISO 286-1:2010, Table 1 (standard tolerance grades IT1..IT18 for nominal sizes up to
3150 mm), in micrometres; checked in the tests against the standard's formulas
(``i = 0.45 D^(1/3) + 0.001 D`` up to 500 mm, ``I = 0.004 D + 2.1`` above, IT7 = 16 i).
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["IT_SIZES_MM", "IT_GRADES", "IT_TABLE_UM", "it_row", "it_value_mm", "snap_length", "snap_angle",
           "ANGLE_STEP_DEG", "is_real_number"]

#: Upper ends of the nominal size ranges [mm] ("over previous, up to and including this").
IT_SIZES_MM = np.array([3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500,
                        630, 800, 1000, 1250, 1600, 2000, 2500, 3150], dtype=float)
#: Grades in the columns of :data:`IT_TABLE_UM`.
IT_GRADES = tuple(f"IT{g}" for g in range(1, 19))
#: Standard tolerance values [um], rows: size ranges, columns: IT1..IT18.
IT_TABLE_UM = np.array([
    [0.8, 1.2, 2, 3, 4, 6, 10, 14, 25, 40, 60, 100, 140, 250, 400, 600, 1000, 1400],
    [1, 1.5, 2.5, 4, 5, 8, 12, 18, 30, 48, 75, 120, 180, 300, 480, 750, 1200, 1800],
    [1, 1.5, 2.5, 4, 6, 9, 15, 22, 36, 58, 90, 150, 220, 360, 580, 900, 1500, 2200],
    [1.2, 2, 3, 5, 8, 11, 18, 27, 43, 70, 110, 180, 270, 430, 700, 1100, 1800, 2700],
    [1.5, 2.5, 4, 6, 9, 13, 21, 33, 52, 84, 130, 210, 330, 520, 840, 1300, 2100, 3300],
    [1.5, 2.5, 4, 7, 11, 16, 25, 39, 62, 100, 160, 250, 390, 620, 1000, 1600, 2500, 3900],
    [2, 3, 5, 8, 13, 19, 30, 46, 74, 120, 190, 300, 460, 740, 1200, 1900, 3000, 4600],
    [2.5, 4, 6, 10, 15, 22, 35, 54, 87, 140, 220, 350, 540, 870, 1400, 2200, 3500, 5400],
    [3.5, 5, 8, 12, 18, 25, 40, 63, 100, 160, 250, 400, 630, 1000, 1600, 2500, 4000, 6300],
    [4.5, 7, 10, 14, 20, 29, 46, 72, 115, 185, 290, 460, 720, 1150, 1850, 2900, 4600, 7200],
    [6, 8, 12, 16, 23, 32, 52, 81, 130, 210, 320, 520, 810, 1300, 2100, 3200, 5200, 8100],
    [7, 9, 13, 18, 25, 36, 57, 89, 140, 230, 360, 570, 890, 1400, 2300, 3600, 5700, 8900],
    [8, 10, 15, 20, 27, 40, 63, 97, 155, 250, 400, 630, 970, 1550, 2500, 4000, 6300, 9700],
    [9, 11, 16, 22, 32, 44, 70, 110, 175, 280, 440, 700, 1100, 1750, 2800, 4400, 7000, 11000],
    [10, 13, 18, 25, 36, 50, 80, 125, 200, 320, 500, 800, 1250, 2000, 3200, 5000, 8000, 12500],
    [11, 15, 21, 28, 40, 56, 90, 140, 230, 360, 560, 900, 1400, 2300, 3600, 5600, 9000, 14000],
    [13, 18, 24, 33, 47, 66, 105, 165, 260, 420, 660, 1050, 1650, 2600, 4200, 6600, 10500, 16500],
    [15, 21, 29, 39, 55, 78, 125, 195, 310, 500, 780, 1250, 1950, 3100, 5000, 7800, 12500, 19500],
    [18, 25, 35, 46, 65, 92, 150, 230, 370, 600, 920, 1500, 2300, 3700, 6000, 9200, 15000, 23000],
    [22, 30, 41, 55, 78, 110, 175, 280, 440, 700, 1100, 1750, 2800, 4400, 7000, 11000, 17500, 28000],
    [26, 36, 50, 68, 96, 135, 210, 330, 540, 860, 1350, 2100, 3300, 5400, 8600, 13500, 21000, 33000],
])
#: Default angle step [deg] (1 arcsec).
ANGLE_STEP_DEG = 1.0 / 3600.0


def is_real_number(v) -> bool:
    """A real scalar (int, float, a numpy scalar or 0-d array), not a bool, a string or None."""
    if isinstance(v, np.ndarray):
        return v.ndim == 0 and np.issubdtype(v.dtype, np.number) and not np.issubdtype(v.dtype, np.complexfloating)
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def it_row(size_mm: float) -> int:
    """Row of :data:`IT_TABLE_UM` for nominal size ``size_mm`` [mm] (0 < D <= 3150)."""
    if not is_real_number(size_mm) or not np.isfinite(size_mm) or size_mm <= 0 or size_mm > IT_SIZES_MM[-1]:
        raise TolallocError(f"ISO 286 nominal size: expected 0 < D <= 3150 mm, got {size_mm!r} mm; "
                            "give the part a nominal size in range or set it to none (snap to a step).")
    return int(np.searchsorted(IT_SIZES_MM, size_mm - 1e-9))


def it_value_mm(size_mm: float, grade: str) -> float:
    """Tolerance zone width of grade ``grade`` (``"IT7"``) at nominal size ``size_mm`` [mm]."""
    if grade not in IT_GRADES:
        raise TolallocError(f"IT grade: expected one of IT1..IT18, got {grade!r}.")
    return float(IT_TABLE_UM[it_row(size_mm), IT_GRADES.index(grade)]) / 1000.0


def snap_length(t_mm: float, size_mm: float, t_min_mm: float = 0.0) -> tuple[float, str]:
    """Snap a length half-width to an ISO 286 grade at or below it (``±IT/2``).

    Parameters
    ----------
    t_mm : float
        Allocated half-width [mm].
    size_mm : float
        Nominal size [mm] (the link length).
    t_min_mm : float
        Process limit: a snapped half-width below it is replaced by the finest grade at or above it.

    Returns
    -------
    t_std_mm : float
        ``IT / 2`` [mm].
    grade : str
        ``"IT7"``; ``"<IT1"`` if even IT1 is wider than ``2 t`` (then ``t`` is kept unsnapped).

    Raises TolallocError for a half-width that is not a number > 0 or a process limit that is not a number >= 0.
    """
    if not (is_real_number(t_mm) and np.isfinite(t_mm) and t_mm > 0):
        raise TolallocError(f"snap_length: t_mm expected a half-width > 0 [mm] (a number), got {t_mm!r}.")
    if not (is_real_number(t_min_mm) and np.isfinite(t_min_mm) and t_min_mm >= 0):
        raise TolallocError(f"snap_length: t_min_mm expected a process limit >= 0 [mm] (a number), got "
                            f"{t_min_mm!r}.")
    widths = IT_TABLE_UM[it_row(size_mm)] / 1000.0
    ok = np.nonzero(widths <= 2.0 * t_mm * (1 + 1e-12))[0]
    if ok.size == 0:
        return float(t_mm), "<IT1"
    g = int(ok[-1])
    if widths[g] / 2.0 < t_min_mm * (1 - 1e-12):
        above = np.nonzero(widths / 2.0 >= t_min_mm * (1 - 1e-12))[0]
        if above.size:
            g = int(above[0])
    return float(widths[g] / 2.0), IT_GRADES[g]


def snap_angle(t_rad: float, step_deg: float = ANGLE_STEP_DEG, t_min_rad: float = 0.0) -> float:
    """Round an angle half-width down to a multiple of ``step_deg`` (up to ``t_min`` if below it) [rad]."""
    if not np.isfinite(step_deg) or step_deg <= 0:
        raise TolallocError(f"angle step: expected a number > 0 [deg], got {step_deg!r}.")
    step = np.deg2rad(step_deg)
    t = np.floor(t_rad / step * (1 + 1e-12)) * step
    if t < t_min_rad * (1 - 1e-12) or t <= 0:
        t = np.ceil(max(t_min_rad, 1e-300) / step * (1 - 1e-12)) * step
    return float(t)
