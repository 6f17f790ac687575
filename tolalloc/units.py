"""Unit suffixes of input keys (``vector_mm``, ``limits_deg``, ``t_ref_mm`` ...) and unit plausibility guards.

Every user-facing key carries its unit; :func:`unit_value` is the one parser of ``base_<unit>``
keys (robot files, DH tables, costs files, sigma sets) and converts to the internal units mm / rad.

Plausibility guards catch the common unit slips and say how to proceed: a length under ``_m``
above :data:`MAX_PLAUSIBLE_M` (millimetres under a metre key), a robot whose lengths given in mm
all together are under :data:`MIN_PLAUSIBLE_REACH_MM` or one of which is tiny next to the longest
(metres under a mm key), an angle under
``_deg`` beyond +-360 deg or under ``_rad`` beyond +-2 pi (degrees under a radian key). A robot built in
Python from ``Link`` / ``Joint`` objects (internal units mm / rad) gets the same rules
(:func:`check_chain_units`): lengths that look like metres, and revolute limits beyond two turns or a nominal
value beyond one turn each way (degrees given for radians). A file or robot that really is that way is accepted
inside :func:`trusting_units` (the CLI's ``--trust-units``, ``trust_units=True`` in Python).

A table whose rows mix lengths and angles (tolerances, sigmas) shows each such quantity in a ``<name>_mm`` /
``<name>_deg`` column pair, the row's own unit filled and the other one empty (:func:`unit_columns`,
:func:`in_row_unit`).
"""

from __future__ import annotations

import contextlib
import contextvars

import numpy as np

from tolalloc.exceptions import ArgumentError, TolallocError, describe

__all__ = ["LENGTH_UNITS", "ANGLE_UNITS", "ALL_UNITS", "unit_key", "unit_value", "check_plausible", "trusting_units",
           "units_trusted", "check_reach", "MAX_PLAUSIBLE_M", "MIN_PLAUSIBLE_REACH_MM", "MAX_TINY_LINK_MM",
           "TINY_LINK_RATIO", "TRUST_HINT", "PYTHON_TRUST_HINT", "radians_fix", "check_joint_units",
           "check_chain_units", "PLAUSIBLE_MAX", "MAX_LIMIT_TURNS", "unit_columns", "in_row_unit", "number",
           "check_positive", "check_probability", "RANGES"]

#: factor from the suffix to the internal unit
LENGTH_UNITS = {"mm": 1.0, "m": 1000.0}
ANGLE_UNITS = {"deg": np.pi / 180.0, "rad": 1.0}
ALL_UNITS = {**LENGTH_UNITS, **ANGLE_UNITS}

#: a single length under a ``_m`` key above this many metres looks like millimetres
MAX_PLAUSIBLE_M = 20.0
#: a chain whose link lengths add up to less than this [mm] looks like it was written in metres
MIN_PLAUSIBLE_REACH_MM = 10.0
#: a link shorter than this [mm] and TINY_LINK_RATIO times shorter than the longest one looks like metres
MAX_TINY_LINK_MM = 2.0
TINY_LINK_RATIO = 200.0
TRUST_HINT = "if the values really are meant so, pass --trust-units (trust_units=True in Python)"
#: the same, for what only Python can give (a Robot built from Link / Joint objects)
PYTHON_TRUST_HINT = "if the values really are meant so, pass trust_units=True"
#: largest plausible magnitude of a value under each unit suffix: a length under ``_m`` (millimetres beyond),
#: an angle under ``_deg`` or ``_rad`` (one turn each way; degrees under a radian key beyond)
PLAUSIBLE_MAX = {"m": MAX_PLAUSIBLE_M, "deg": 360.0, "rad": 2 * np.pi}
#: turns each way a revolute joint's limits may span (a continuous joint: +-720 deg, the robot files' and
#: URDF's default); its nominal value stays within one turn
MAX_LIMIT_TURNS = 2
#: joint values in deg whose revolute entries all lie within +-2 pi, while a joint's limits span at least this many
#: degrees and this many times the values' range, read as radians
MIN_SPAN_FOR_RADIANS_DEG = 90.0
SPAN_RATIO_FOR_RADIANS = 10.0
#: prismatic values in mm all within +-this while the stroke spans at least MIN_STROKE_FOR_METRES_MM read as metres
MAX_METRES_LIKE = 2.0
MIN_STROKE_FOR_METRES_MM = 100.0

_TRUST = contextvars.ContextVar("tolalloc_trust_units", default=False)


@contextlib.contextmanager
def trusting_units(trust: bool = True):
    """Within the block, the plausibility guards are off (``trust=True``)."""
    token = _TRUST.set(bool(trust))
    try:
        yield
    finally:
        _TRUST.reset(token)


def units_trusted() -> bool:
    """True inside :func:`trusting_units`."""
    return _TRUST.get()


def unit_key(data: dict, base: str, exclude: tuple[str, ...] = ()) -> str | None:
    """The one key ``base`` or ``base_<unit>`` of ``data`` (None if absent); ValueError if given twice."""
    present = [k for k in data if (k == base or (k.startswith(base + "_") and k[len(base) + 1:] in ALL_UNITS))
               and not any(k.startswith(e) for e in exclude)]
    if not present:
        return None
    if len(present) > 1:
        raise ValueError(f"give {base} once, got {present}")
    return present[0]


def unit_value(data: dict, base: str, allowed: dict, default=None, *, exclude: tuple[str, ...] = (),
               check: bool = True):
    """``(value in internal units, unit)`` of the key ``base_<unit>`` in ``data``; ``(default, None)`` if absent.

    Parameters
    ----------
    data : dict
    base : str
        Key without suffix (``vector``, ``limits``, ``t_ref``).
    allowed : dict
        Allowed suffixes -> factor to the internal unit (:data:`LENGTH_UNITS`, :data:`ANGLE_UNITS`).
    exclude : tuple of str
        Key prefixes that are other bases (``d_offset`` is not ``d``).
    check : bool
        Apply :func:`check_plausible` to the value as given.

    Raises
    ------
    ValueError
        Given twice, a suffix not in ``allowed``, not numbers, or implausible for its unit.
    """
    key = unit_key(data, base, exclude)
    if key is None:
        return default, None
    unit = key[len(base) + 1:] if key != base else ""
    if unit not in allowed:
        want = " or ".join(f"{base}_{u}" for u in allowed)
        raise ValueError(f"key {key!r} has unit {unit or 'none'!r}; expected {want}")
    try:
        raw = np.asarray(data[key], dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{key} expected numbers, got {data[key]!r}") from None
    if check:
        check_plausible(raw, key, unit)
    return raw * allowed[unit], unit


def check_plausible(raw, key: str, unit: str, *, error=ValueError) -> None:
    """Refuse a value that looks like it is in another unit than its suffix says (see the module docstring)."""
    if units_trusted():
        return
    big = _beyond(raw, PLAUSIBLE_MAX.get(unit, np.inf))
    if big is None:
        return
    if unit == "m":
        raise error(f"{key} = {_shown(raw)} is {big:g} m; that looks like millimetres: use the _mm key "
                    f"({key[:-2]}_mm) or divide by 1000 ({TRUST_HINT}).")
    if unit == "deg":
        raise error(f"{key} = {_shown(raw)} goes beyond +-360 deg; expected angles within one turn each way ({TRUST_HINT}).")
    raise error(f"{key} = {_shown(raw)} goes beyond +-2 pi rad; that looks like degrees: use the _deg key "
                f"({key[:-4]}_deg) ({TRUST_HINT}).")


def _beyond(raw, limit: float) -> float | None:
    """The largest finite magnitude in ``raw`` if it exceeds ``limit``, else None."""
    a = np.abs(np.asarray(raw, dtype=float))
    a = a[np.isfinite(a)]
    if a.size == 0 or float(a.max()) <= limit + 1e-9:
        return None
    return float(a.max())


def check_chain_units(lengths_mm: dict, revolute_joints: list, where: str) -> None:
    """The unit guards of a robot built in Python from ``Link`` / ``Joint`` objects (internal units mm / rad).

    The rules of the robot files (:data:`PLAUSIBLE_MAX`, :func:`check_reach`): a revolute joint whose limits go
    beyond :data:`MAX_LIMIT_TURNS` turns each way, or whose nominal value goes beyond one turn, was given in
    degrees; link lengths that look like metres (:func:`check_reach`, one-tiny-link rule included).

    Parameters
    ----------
    lengths_mm : dict
        Link name -> length [mm].
    revolute_joints : list of tuple
        ``(name, lower, upper, nominal)`` [rad] of each revolute joint.
    where : str
        Prefix of the message (``robot 'arm'``).
    """
    if units_trusted():
        return
    turn = PLAUSIBLE_MAX["rad"]
    for name, lower, upper, nominal in revolute_joints:
        if _beyond([lower, upper], MAX_LIMIT_TURNS * turn) is not None or _beyond(nominal, turn) is not None:
            raise TolallocError(
                f"{where}, joint {name}: limits [{lower:g}, {upper:g}] rad and nominal value {nominal:g} rad go beyond "
                f"{MAX_LIMIT_TURNS} turns (limits) or one turn (nominal value) each way; Joint takes rad for a "
                "revolute joint (mm for a prismatic one) and these look like degrees: convert them with "
                "numpy.deg2rad, or build the joint with Joint.from_interface(name, kind, axis, lower_deg_mm, "
                f"upper_deg_mm, nominal_deg_mm) ({PYTHON_TRUST_HINT}).")
    check_reach(lengths_mm, where, objects=True)


def _fractional(v: np.ndarray) -> np.ndarray:
    """Entries that are neither zero nor whole numbers (degrees are often whole; radians seldom are)."""
    return (np.abs(v) > 1e-2) & (np.abs(v - np.round(v)) > 1e-9)


def radians_fix(revolute) -> str:
    """What joint values in interface units are and how to get them from radians (the end of a message after
    ``expected``): ``numpy.degrees`` only when every joint is revolute (it would multiply a prismatic joint's mm
    by 57.3), else ``Robot.q_to_interface``.

    Parameters
    ----------
    revolute : array of bool, shape (n,)
    """
    rev = np.asarray(revolute, bool)
    if rev.all():
        return "degrees: convert with numpy.degrees or robot.q_to_interface(q)"
    prismatic = ", ".join(f"q{k + 1}" for k in np.flatnonzero(~rev))
    return (f"degrees for the revolute joints and mm for the prismatic {prismatic}: convert with "
            f"robot.q_to_interface(q) (rad to deg, {prismatic} left in mm; numpy.degrees would also multiply "
            f"{prismatic} by 57.3)")


def check_joint_units(q_deg_mm, revolute, lower_deg_mm, upper_deg_mm, where: str) -> None:
    """Refuse joint values in interface units (deg / mm) that read as radians (or warn where either reading fits).

    The one rule for every joint-value input (``q_deg_mm`` arguments, trajectories, pose sets, ``--q``):

    * **radians for degrees**: every revolute value within +-2 pi, at least two of them fractional, while some
      revolute joint's limits span at least :data:`MIN_SPAN_FOR_RADIANS_DEG` and
      :data:`SPAN_RATIO_FOR_RADIANS` times the values' range: refused with a hint;
    * **metres for millimetres**: every prismatic value within +-:data:`MAX_METRES_LIKE`, one fractional, while
      the stroke spans at least :data:`MIN_STROKE_FOR_METRES_MM`: a warning (small strokes are real);
    * a single fractional revolute value within +-2 pi among zeros: a warning.

    Parameters
    ----------
    q_deg_mm : array, shape (n,) or (P, n)
    revolute : array of bool, shape (n,)
    lower_deg_mm, upper_deg_mm : array, shape (n,)
        Joint limits in deg / mm.
    """
    import warnings

    if units_trusted():
        return
    q = np.atleast_2d(np.asarray(q_deg_mm, dtype=float))
    rev = np.asarray(revolute, bool)
    span = np.asarray(upper_deg_mm, float) - np.asarray(lower_deg_mm, float)
    if rev.any():
        v = q[:, rev]
        m = float(np.abs(v).max()) if v.size else 0.0
        n_frac = int(_fractional(v).sum())
        wide = float(np.max(np.where(np.isfinite(span[rev]), span[rev], 720.0)))
        if 0 < m <= 2 * np.pi + 1e-9 and wide >= max(MIN_SPAN_FOR_RADIANS_DEG, SPAN_RATIO_FOR_RADIANS * 2 * m):
            if n_frac >= 2:
                raise TolallocError(f"{where}: every revolute joint value lies within +-2 pi (largest {m:.4g}) while "
                                    f"the joint limits span up to {wide:.4g} deg: these look like radians; expected "
                                    f"{radians_fix(rev)} ({TRUST_HINT}).")
            if n_frac == 1:
                warnings.warn(f"{where}: the revolute joint values are all small (largest {m:.4g} deg); if they are "
                              f"radians, expected {radians_fix(rev)}.", UserWarning, stacklevel=3)
    if (~rev).any():
        d = q[:, ~rev]
        stroke = float(np.max(np.where(np.isfinite(span[~rev]), span[~rev], 0.0)))
        if (d.size and float(np.abs(d).max()) <= MAX_METRES_LIKE and _fractional(d).any()
                and stroke >= MIN_STROKE_FOR_METRES_MM):
            warnings.warn(f"{where}: the prismatic joint values are all within +-{MAX_METRES_LIKE:g} mm of a "
                          f"{stroke:g} mm stroke; if they are metres, multiply them by 1000.", UserWarning,
                          stacklevel=3)


def check_reach(lengths_mm: dict, where: str, *, tiny_links: bool = True, objects: bool = False) -> None:
    """Refuse link lengths [mm] that look like metres: all together under :data:`MIN_PLAUSIBLE_REACH_MM`, or
    one link under :data:`MAX_TINY_LINK_MM` that is over :data:`TINY_LINK_RATIO` times shorter than the longest.

    Parameters
    ----------
    lengths_mm : dict
        Link name -> length [mm].
    where : str
        Prefix of the message.
    tiny_links : bool
        Also apply the one-tiny-link rule (off for DH tables, whose small calibrated offsets are real).
    objects : bool
        The lengths are ``Link`` objects' vectors (a robot built in Python), not file keys: the messages say so.
    """
    if units_trusted() or not lengths_mm:
        return
    total = float(sum(abs(v) for v in lengths_mm.values()))
    if 0 < total < MIN_PLAUSIBLE_REACH_MM:
        fix = ("metres: Link vectors are in mm, multiply them by 1000" if objects else
               "metres given under _mm keys: multiply by 1000 or use the _m keys")
        raise TolallocError(f"{where}: the link lengths add up to {total:g} mm; that looks like {fix} "
                            f"({PYTHON_TRUST_HINT if objects else TRUST_HINT}).")
    if not tiny_links:
        return
    longest = max(lengths_mm, key=lambda k: abs(lengths_mm[k]))
    for name, v in lengths_mm.items():
        if 0 < abs(v) < MAX_TINY_LINK_MM and abs(v) * TINY_LINK_RATIO < abs(lengths_mm[longest]):
            fix = ("metres: Link vectors are in mm, multiply it by 1000" if objects else
                   "metres under a _mm key: multiply it by 1000 or use the _m key")
            raise TolallocError(f"{where}: link {name} is {abs(v):g} mm long while link {longest} is "
                                f"{abs(lengths_mm[longest]):g} mm; that looks like a length in {fix} "
                                f"({PYTHON_TRUST_HINT if objects else TRUST_HINT}).")


def unit_columns(name: str, values, is_mm) -> dict:
    """``{name_mm: values on length rows, name_deg: values on angle rows}`` (NaN on the other rows).

    The one way a table shows a quantity whose rows mix lengths and angles (a tolerance, a sigma): each column
    carries one unit, the other column of the pair is empty on that row.

    Parameters
    ----------
    name : str
        Column stem (``tol``, ``sigma``).
    values : array, shape (K,)
        Each row's value in its interface unit (mm or deg).
    is_mm : array of bool, shape (K,)
        Rows in mm (the others in deg).
    """
    v = np.asarray(values, float)
    return {f"{name}_mm": np.where(is_mm, v, np.nan), f"{name}_deg": np.where(is_mm, np.nan, v)}


def in_row_unit(frame, name: str):
    """The ``<name>_mm`` / ``<name>_deg`` pair of :func:`unit_columns` as one column (a ``pandas.Series``): each
    row's value in its own unit (the frame's ``unit``, mm or deg)."""
    return frame[f"{name}_mm"].where(frame["unit"] == "mm", frame[f"{name}_deg"])


def _shown(raw):
    a = np.asarray(raw, dtype=float)
    return a.tolist() if a.ndim else float(a)


# ---- numbers at the public entry points (re-exported by tolalloc.workflows.checks) -----------------------------

def number(value, argument: str) -> float:
    """A number (int, float or numpy scalar; not a bool or a string) as a float."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ArgumentError(argument, f"expected a number, got {describe(value)}.")
    try:
        return float(value)
    except OverflowError:  # an int beyond the float range
        return float("inf") if value > 0 else float("-inf")


def check_probability(value, argument: str, *, example: str = "0.95") -> float:
    """A probability strictly between 0 and 1."""
    x = number(value, argument)
    if not (np.isfinite(x) and 0 < x < 1):
        raise ArgumentError(argument, f"expected a probability strictly between 0 and 1 (e.g. {example}), got {value!r}.")
    return x


#: Ranges of radii, noise levels and steps ``(smallest, largest)`` in each unit: beyond them a tolerance problem
#: is not physical (a nanometre .. a kilometre, a nano-degree .. one turn) and its squares under- or overflow.
RANGES = {"mm": (1e-6, 1e6), "deg": (1e-9, 360.0), "rad": (np.deg2rad(1e-9), 2 * np.pi)}


def check_positive(value, argument: str, unit: str, example: str, bounds: tuple | None = None) -> float:
    """A finite number > 0 in ``unit`` (``mm``, ``deg`` or ``rad``), within ``bounds`` (default that unit's
    :data:`RANGES`)."""
    x = number(value, argument)
    if not (np.isfinite(x) and x > 0):
        raise ArgumentError(argument, f"expected a finite number > 0 [{unit}] (e.g. {example}), got {value!r}.")
    lo, hi = bounds or RANGES.get(unit, (0.0, np.inf))
    if not lo <= x <= hi:
        raise ArgumentError(argument, f"expected a number between {lo:.3g} and {hi:.3g} {unit} (e.g. {example}), got "
                            f"{value!r}.")
    return x


