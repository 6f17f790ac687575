"""ISO 286 fits: the limit deviations of the common hole and shaft tolerance classes, and the clearance of a fit.

A tolerance class is a fundamental deviation (a letter: the position of the zone) and a standard tolerance grade
(``IT``: its width, :mod:`tolalloc.allocate.standards`). ISO 286-1:2010 gives the fundamental deviations (its
Tables 2 and 3); ISO 286-2 tabulates the resulting limit deviations per class and size. This module implements the
rules of ISO 286-1 for nominal sizes up to 500 mm and the letters a robot joint's seats use:

- shafts ``d e f g h`` (upper deviation ``es`` from the table, ``ei = es - IT``), ``js`` (``±IT/2``) and
  ``k m n p`` (lower deviation ``ei`` from the table, ``es = ei + IT``; ``k``: the table's value for IT4 to IT7,
  0 for the other grades);
- holes ``D E F G H`` (``EI = -es`` of the shaft letter), ``JS`` (``±IT/2``) and ``K M N P`` (``ES = -ei + Delta``
  with ``Delta = IT_n - IT_(n-1)`` for K, M, N up to IT8 and P up to IT7; ``ES = -ei`` for M and P above, 0 for
  K and N above; sizes up to 3 mm without ``Delta`` and at every grade K 0, M -2, N -4, P -6 um, ISO 286-2's N9
  at 2 mm being -4/-29 um; the standard's special case M6 over 250 up to 315 mm, ``ES = -9 um``).

The tests check the limit deviations against ISO 286-2's tabulated values. A fit ``H7/g6`` is a hole class and a
shaft class at one nominal size: its clearance ranges from ``EI - es`` (minimum) to ``ES - ei`` (maximum), a
negative value being an interference.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.standards import IT_TABLE_UM, is_real_number, it_row
from tolalloc.exceptions import TolallocError

__all__ = ["ToleranceClass", "Fit", "tolerance_class", "parse_fit", "clearance_fits", "SHAFT_LETTERS", "HOLE_LETTERS",
           "PREFERRED_CLEARANCE_FITS", "FIT_MAX_SIZE_MM", "check_clearance_fits"]

#: Largest nominal size the fundamental deviations here cover [mm].
FIT_MAX_SIZE_MM = 500.0

# Fundamental deviations of the shafts [um] over the main size ranges up to 3, 6, 10, 18, 30, 50, 80, 120, 180,
# 250, 315, 400, 500 mm (ISO 286-1:2010, Tables 2 and 3): es for d..g, ei for k (IT4-IT7), m, n, p.
_SHAFT_ES = {
    "d": (-20, -30, -40, -50, -65, -80, -100, -120, -145, -170, -190, -210, -230),
    "e": (-14, -20, -25, -32, -40, -50, -60, -72, -85, -100, -110, -125, -135),
    "f": (-6, -10, -13, -16, -20, -25, -30, -36, -43, -50, -56, -62, -68),
    "g": (-2, -4, -5, -6, -7, -9, -10, -12, -14, -15, -17, -18, -20),
    "h": (0,) * 13,
}
_SHAFT_EI = {
    "k": (0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 4, 4, 5),
    "m": (2, 4, 6, 7, 8, 9, 11, 13, 15, 17, 20, 21, 23),
    "n": (4, 8, 10, 12, 15, 17, 20, 23, 27, 31, 34, 37, 40),
    "p": (6, 12, 15, 18, 22, 26, 32, 37, 43, 50, 56, 62, 68),
}
SHAFT_LETTERS = (*_SHAFT_ES, "js", *_SHAFT_EI)
HOLE_LETTERS = tuple(x.upper() for x in SHAFT_LETTERS)
#: Clearance fits of the hole-basis system a joint seat may take, finest first (ISO 286-1, preferred fits).
PREFERRED_CLEARANCE_FITS = ("H6/h5", "H6/g5", "H7/h6", "H7/g6", "H8/h7", "H7/f7", "H8/f7", "H8/e8", "H9/e9",
                            "H9/d9")
_CLASS = re.compile(r"^([A-Za-z]{1,2})(\d{1,2})$")
#: Upper ends of ISO 286's size ranges up to 500 mm (one nominal size per range checks a fit at every size).
_SIZES_MM = (3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500)


@dataclass(frozen=True)
class ToleranceClass:
    """One tolerance class at one nominal size.

    Attributes
    ----------
    name : str
        ``"H7"`` (hole, upper case) or ``"g6"`` (shaft, lower case).
    size_mm : float
        Nominal size [mm].
    upper_um, lower_um : float
        Upper and lower limit deviation [um] (``ES, EI`` of a hole, ``es, ei`` of a shaft).
    """

    name: str
    size_mm: float
    upper_um: float
    lower_um: float

    @property
    def is_hole(self) -> bool:
        return self.name[0].isupper()

    @property
    def grade(self) -> int:
        """The standard tolerance grade (7 for H7)."""
        return int(re.sub(r"\D", "", self.name))

    @property
    def width_um(self) -> float:
        """Width of the zone (the IT value) [um]."""
        return self.upper_um - self.lower_um


@dataclass(frozen=True)
class Fit:
    """A hole class and a shaft class at one nominal size.

    Attributes
    ----------
    hole, shaft : ToleranceClass
    """

    hole: ToleranceClass
    shaft: ToleranceClass

    @property
    def name(self) -> str:
        return f"{self.hole.name}/{self.shaft.name}"

    @property
    def size_mm(self) -> float:
        return self.hole.size_mm

    @property
    def clearance_min_um(self) -> float:
        """Smallest diametral clearance ``EI - es`` [um] (negative: an interference)."""
        return self.hole.lower_um - self.shaft.upper_um

    @property
    def clearance_max_um(self) -> float:
        """Largest diametral clearance ``ES - ei`` [um] (negative: an interference)."""
        return self.hole.upper_um - self.shaft.lower_um

    @property
    def kind(self) -> str:
        """``clearance`` (never an interference), ``interference`` (never a clearance) or ``transition``."""
        if self.clearance_min_um >= 0:
            return "clearance"
        return "interference" if self.clearance_max_um <= 0 else "transition"

    @property
    def radial_play_max_mm(self) -> float:
        """Largest radial displacement of the shaft centre in the hole, half the largest clearance [mm] (0 for a
        fit that is never a clearance)."""
        return max(self.clearance_max_um, 0.0) / 2000.0


def _it_um(row: int, grade: int) -> float:
    return float(IT_TABLE_UM[row, grade - 1])


def tolerance_class(name: str, size_mm: float, *, where: str = "tolerance class") -> ToleranceClass:
    """The limit deviations of class ``name`` (``"H7"``, ``"g6"``) at nominal size ``size_mm`` [mm].

    Raises TolallocError naming ``where`` for a class this module does not implement (letter or grade) or a size
    outside 0 < D <= 500 mm.
    """
    m = _CLASS.match(name.strip()) if isinstance(name, str) else None
    letters = ", ".join(SHAFT_LETTERS) + " (shafts) and " + ", ".join(HOLE_LETTERS) + " (holes)"
    if m is None or not (m.group(1).islower() or m.group(1).isupper()):
        raise TolallocError(f"{where}: {name!r} is not an ISO 286 tolerance class; expected a fundamental deviation "
                            f"and a grade such as H7 (hole) or g6 (shaft); implemented letters: {letters}.")
    letter, grade = m.group(1), int(m.group(2))
    if letter.lower() not in SHAFT_LETTERS:
        raise TolallocError(f"{where}: {name!r}: the fundamental deviation {letter!r} is not implemented; use one of "
                            f"{letters}.")
    if not 1 <= grade <= 18:
        raise TolallocError(f"{where}: {name!r}: grade IT{grade} is not an ISO 286 grade (IT1..IT18).")
    if not (is_real_number(size_mm) and np.isfinite(size_mm) and 0 < size_mm <= FIT_MAX_SIZE_MM):
        raise TolallocError(f"{where}: {name} size_mm: expected a nominal size 0 < D <= {FIT_MAX_SIZE_MM:g} mm (a "
                            f"number; the fundamental deviations here cover these sizes), got {size_mm!r} "
                            f"({type(size_mm).__name__}).")
    row = it_row(size_mm)
    it = _it_um(row, grade)
    if letter.islower():
        lo, hi = _shaft(letter, grade, row, it)
    else:
        lo, hi = _hole(letter.lower(), grade, row, it, size_mm)
    return ToleranceClass(name.strip(), float(size_mm), float(hi), float(lo))


def _shaft(letter: str, grade: int, row: int, it: float):
    if letter == "js":
        return -it / 2.0, it / 2.0
    if letter in _SHAFT_ES:
        es = _SHAFT_ES[letter][row]
        return es - it, es
    ei = _SHAFT_EI[letter][row]
    if letter == "k" and not 4 <= grade <= 7:
        ei = 0
    return ei, ei + it


def _hole(letter: str, grade: int, row: int, it: float, size_mm: float):
    if letter == "js":
        return -it / 2.0, it / 2.0
    if letter in _SHAFT_ES:
        ei = -_SHAFT_ES[letter][row]
        return ei, ei + it
    small = size_mm <= 3.0
    delta = 0.0 if grade < 2 else _it_um(row, grade) - _it_um(row, grade - 1)
    ei_shaft = _SHAFT_EI[letter][row]  # k: the table's value for IT4 to IT7
    if small:  # up to 3 mm one value for every grade: K 0, M -2, N -4, P -6 um (ISO 286-1, Table 3)
        es = 0.0 if letter == "k" else -ei_shaft
    elif grade <= (7 if letter == "p" else 8):
        if letter == "m" and grade == 6 and 250 < size_mm <= 315:
            es = -9.0  # ISO 286-1's special case
        else:
            es = -ei_shaft + delta
    elif letter in ("m", "p"):
        es = -ei_shaft
    else:  # K and N above IT8
        es = 0.0
    return es - it, es


def parse_fit(text: str, size_mm: float, *, where: str = "fit") -> Fit:
    """A fit ``"H7/g6"`` (hole class / shaft class) at nominal size ``size_mm`` [mm]; TolallocError naming ``where``
    for anything else."""
    parts = text.split("/") if isinstance(text, str) else []
    if len(parts) != 2:
        raise TolallocError(f"{where}: {text!r} is not an ISO 286 fit; expected hole class / shaft class such as "
                            "H7/g6.")
    hole, shaft = (p.strip() for p in parts)
    if not hole[:1].isupper() or not shaft[:1].islower():
        raise TolallocError(f"{where}: {text!r}: expected the hole class first (upper case, e.g. H7) and the shaft "
                            "class second (lower case, e.g. g6).")
    return Fit(tolerance_class(hole, size_mm, where=where), tolerance_class(shaft, size_mm, where=where))


def clearance_fits(size_mm: float, names=PREFERRED_CLEARANCE_FITS, *, where: str = "fit") -> list[Fit]:
    """The fits ``names`` at nominal size ``size_mm`` [mm], ordered by their largest clearance (finest first);
    TolallocError naming ``where`` for a bad fit or size."""
    fits = [parse_fit(n, size_mm, where=where) for n in names]
    return sorted(fits, key=lambda f: f.clearance_max_um)


def check_clearance_fits(names, *, where: str = "fits") -> tuple:
    """``names`` as a tuple of ISO 286 fits that are clearance fits at every nominal size up to 500 mm (the
    candidates of a radial clearance); TolallocError naming ``where``, the fit and the size otherwise."""
    if isinstance(names, str) or not isinstance(names, (tuple, list)) or not names:
        raise TolallocError(f"{where}: expected a non-empty tuple of ISO 286 fits such as ('H7/g6', 'H8/f7'), got "
                            f"{names!r}.")
    for name in names:
        for size in _SIZES_MM:
            fit = parse_fit(name, size, where=f"{where}: {name!r}")
            if fit.kind != "clearance":
                raise TolallocError(f"{where}: {name!r} is not a clearance fit ({fit.kind} at Ø{size:g} mm: smallest "
                                    f"clearance {fit.clearance_min_um:g} um); a radial clearance needs a clearance "
                                    "fit such as H7/g6.")
    return tuple(names)
