"""The checks of one section of a costs file (a kind's or a parameter's entry): keys, unit suffixes, values.

:func:`_check_entry` refuses unknown keys and non-boolean ``fixed`` / ``exclude``; :func:`_check_units` refuses a
``t_ref`` / ``t_min`` / ``t_max`` / ``tol`` / ``step`` / ``classes`` key whose unit suffix does not fit the
parameters' interface unit (mm or deg); :func:`_value` reads one such value in internal units (mm or rad);
:func:`_check_values` checks all the values of a section. :func:`tolalloc.allocate.costs.cost_set` runs them on
every section of a costs file, :mod:`tolalloc.allocate.calibrated.certified` on the calibration grades.
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.allocate.processes import DISCRETE_KEYS
from tolalloc.units import ANGLE_UNITS, LENGTH_UNITS, unit_value

__all__ = []

_LEN = LENGTH_UNITS
_ANG = ANGLE_UNITS
_ENTRY_KEYS = {"model", "a", "b", "k", "fixed", "exclude", *DISCRETE_KEYS}
_UNIT_BASES = ("t_ref", "t_min", "t_max", "tol", "step", "classes")


def _check_units(entry: dict, unit: str, what: str, where: str, bases=_UNIT_BASES) -> None:
    """Refuse a ``base_<suffix>`` key whose unit is not ``unit`` (the parameters' interface unit, mm or deg)."""
    table, other = (_LEN, "m") if unit == "mm" else (_ANG, "rad")
    for key in entry:
        for b in bases:
            suffix = key[len(b) + 1:] if key.startswith(b + "_") else None
            if suffix in {**_LEN, **_ANG} and suffix not in table:
                raise TolallocError(f"{where}: {key} has the wrong unit: {what} are in {unit}; use {b}_{unit} (or "
                                    f"{b}_{other}).")


def _value(entry: dict, base: str, unit: str, where: str, what: str = "the parameter's tolerances"):
    """Value of ``base_<unit suffix>`` in internal units (None if absent); the suffix must fit ``unit`` (the
    parameter's unit: mm, or rad / deg for angles)."""
    unit = "mm" if unit == "mm" else "deg"
    _check_units(entry, unit, what, where, (base,))
    try:
        value, suffix = unit_value({k: v for k, v in entry.items() if k != base}, base, _LEN if unit == "mm" else _ANG)
    except ValueError as exc:
        text = str(exc)
        raise TolallocError(f"{where}: {text}{'' if text.endswith('.') else '.'}") from None
    if suffix is None:
        return None
    key = f"{base}_{suffix}"
    if np.shape(value) != () or not np.isfinite(value) or value <= 0:
        raise TolallocError(f"{where}: {key} expected a finite number > 0, got {entry[key]!r}.")
    return float(value)


def _check_entry(entry, where: str) -> None:
    if not isinstance(entry, dict):
        raise TolallocError(f"{where}: expected a table of keys, got {entry!r}.")
    for key in ("fixed", "exclude"):
        if key in entry and not isinstance(entry[key], bool):
            raise TolallocError(f"{where}: {key} expected true or false, got {entry[key]!r}.")
    for key in entry:
        base_ok = any(key.startswith(b + "_") and key[len(b) + 1:] in {**_LEN, **_ANG} for b in _UNIT_BASES)
        if key not in _ENTRY_KEYS and not base_ok:
            raise TolallocError(f"{where}: unknown key {key!r}; expected model, a, b, k, fixed, exclude, "
                                "t_ref_<mm|deg>, t_min_<mm|deg>, t_max_<mm|deg>, tol_<mm|deg>, grades, "
                                "step_<mm|deg>, classes_<mm|deg>.")


def _check_values(entry: dict, unit: str, what: str, where: str) -> None:
    """The unit suffixes and the reference / limit / fixed values of one section, in the section's terms."""
    _check_units(entry, unit, what, where)
    for b in ("t_ref", "t_min", "t_max", "tol"):
        _value(entry, b, unit, where, what)
