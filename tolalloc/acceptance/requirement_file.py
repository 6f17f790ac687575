"""Requirement files (TOML): the requirements of a job and, optionally, the acceptance test that judges them.

Schema (``examples/requirements_iso9283.toml`` is a complete example)::

    [[requirement]]               # one table per requirement; `kind` says which
    kind = "pose_repeatability"   # position, orientation, pose_accuracy, pose_repeatability, orientation_accuracy,
                                  # orientation_repeatability, multidirectional_accuracy,
                                  # multidirectional_orientation, distance_accuracy, path_accuracy
    limit_mm = 0.05               # the limit, its unit in the key: limit_mm / limit_um (lengths),
                                  # limit_deg / limit_arcsec / limit_rad (orientation statistics)
    share = 0.95                  # share of the built robots meeting it (optional, default 0.95)
    population = "fleet"          # "fleet" or "robot" (optional)
    load_pct = 100                # test load, % of the rated load (optional, default 100)
    speed_pct = 100               # test velocity, % of the rated velocity (optional, default 100)
    guard_band = false            # allocate for conformance demonstrated by the test (ISO 14253-1; optional)
    poses = [2, 4]                # distance_accuracy: the two test poses (default P2, P4); multidirectional_*: the
                                  # poses approached from three directions (default [1, 2, 4])
    approach = ["-x", "-y", "-z"] # multidirectional_* only: the tool's motion into the pose, one per base axis
    points = 11                   # path_accuracy only: command points along the path (default 11)

    [[requirement]]
    kind = "position"             # the ball of the working poses: radius_mm (or radius_um) and prob
    radius_mm = 0.25
    prob = 0.95

    [[requirement]]
    kind = "orientation"          # radius_deg (or radius_arcsec, radius_rad) and prob (default: the position's)
    radius_deg = 0.02

    [test]                        # the acceptance test (optional; defaults of the standard)
    cycles = 30                   # cycles per test pose (>= 2)
    path_cycles = 10              # cycles of the test path (>= 2)
    cube_edge_mm = 200            # a given cube (optional; default the largest found in the working region)
    cube_centre_mm = [0, 900, 1200]
    plane = 1                     # diagonal plane 1-4 of P1-P5
    orientation = "auto"          # "auto", "fixed" or "free"
    registration = "corners"      # "corners" or "none"
    registration_visits = 1
    tracker_mpe_a_mm = 0.015      # MPE = A + B L of the laser tracker (or tracker_mpe_a_um = 15)
    tracker_mpe_b_mm_per_m = 0.006  # (or tracker_mpe_b_um_per_m = 6)
    tracker_distance_m = 2.0
    tracker_angle_mpe_deg = 0.01
    coverage_factor_k = 2

Every value needs its unit in its key: a bare ``limit = 0.05`` or ``radius = 0.25`` is refused, naming the keys
that would work.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tolalloc.exceptions import InputFileError, TolallocError
from tolalloc.acceptance.instrument import Tracker
from tolalloc.acceptance.requirements import REQUIREMENT_KINDS, Conditions, IsoRequirement, check_requirements

__all__ = ["RequirementFile", "read_requirement_file", "parse_requirements", "TEST_KEYS"]

#: unit suffixes accepted per quantity: suffix -> factor to the class's unit
_LENGTH = {"mm": 1.0, "um": 1e-3}
_ANGLE = {"deg": 1.0, "arcsec": 1 / 3600, "rad": 180 / np.pi}
_COMMON = ("share", "population", "load_pct", "speed_pct", "guard_band")
#: keys of the [test] table and the argument of tolalloc.acceptance.acceptance_test each feeds
TEST_KEYS = ("cycles", "path_cycles", "cube_edge_mm", "cube_centre_mm", "plane", "orientation", "registration",
             "registration_visits", "tracker_mpe_a_mm", "tracker_mpe_a_um", "tracker_mpe_b_mm_per_m",
             "tracker_mpe_b_um_per_m", "tracker_distance_m", "tracker_angle_mpe_deg", "coverage_factor_k")


@dataclass(frozen=True)
class RequirementFile:
    """A parsed requirement file.

    Attributes
    ----------
    requirements : tuple of Requirement
    test : dict
        Keyword arguments of :func:`tolalloc.acceptance.acceptance_test` from the ``[test]`` table (``tracker`` a
        :class:`~tolalloc.acceptance.Tracker`).
    source : str
    """

    requirements: tuple
    test: dict = field(default_factory=dict)
    source: str = "<dict>"

    @property
    def iso(self) -> tuple:
        """The ISO 9283 requirements."""
        return tuple(r for r in self.requirements if isinstance(r, IsoRequirement))


def read_requirement_file(path) -> RequirementFile:
    """Read and check a requirement file (module docstring)."""
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"requirement file {str(path)!r} does not exist; give the path of a TOML file (see "
                             "examples/requirements_iso9283.toml).")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise TolallocError(f"requirement file {p}: not valid TOML ({exc}).") from None
    return parse_requirements(data, str(p))


def parse_requirements(data: dict, source: str = "<dict>") -> RequirementFile:
    """Check a parsed requirement file (a dict of its TOML) into a :class:`RequirementFile`."""
    bad = set(data) - {"requirement", "test"}
    if bad:
        raise TolallocError(f"{source}: unknown top-level key(s) {', '.join(sorted(bad))}; expected [[requirement]] "
                            "tables and an optional [test] table.")
    items = data.get("requirement")
    if not isinstance(items, list) or not items or not all(isinstance(t, dict) for t in items):
        raise TolallocError(f"{source}: expected at least one [[requirement]] table (kind = \"pose_accuracy\", "
                            f"limit_mm = 0.5, ...), got {items!r}.")
    reqs = tuple(_requirement(t, f"{source}: requirement[{i + 1}]") for i, t in enumerate(items))
    try:
        reqs = check_requirements(reqs)
    except TolallocError as exc:
        raise TolallocError(f"{source}: {exc}") from None
    return RequirementFile(reqs, _test(data.get("test", {}), f"{source}: [test]"), source)


def _value(table: dict, base: str, units: dict, where: str, unit_to: str):
    """The value of ``base_<unit>`` converted to ``unit_to``; a bare ``base`` is refused (None if absent)."""
    keys = [f"{base}_{u}" for u in units]
    if base in table:
        raise TolallocError(f"{where}.{base}: a value needs its unit in its key; write {' or '.join(keys)} = "
                            f"{table[base]!r} (in {unit_to} the library's unit).")
    given = [k for k in keys if k in table]
    if len(given) > 1:
        raise TolallocError(f"{where}: give {base} once, got {', '.join(given)}.")
    if not given:
        return None
    k = given[0]
    v = table[k]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise TolallocError(f"{where}.{k}: expected a number, got {v!r}.")
    return float(v) * units[k[len(base) + 1:]]


def _requirement(t: dict, where: str):
    kind = t.get("kind")
    if kind not in REQUIREMENT_KINDS:
        raise TolallocError(f"{where}.kind: unknown kind {kind!r}; known: {', '.join(REQUIREMENT_KINDS)}.")
    cls = REQUIREMENT_KINDS[kind]
    if kind in ("position", "orientation"):
        units, unit = (_LENGTH, "mm") if kind == "position" else (_ANGLE, "deg")
        allowed = {"kind", "prob"} | {f"radius_{u}" for u in units}
        _unknown(t, allowed | {"radius"}, where)
        r = _value(t, "radius", units, where, unit)
        if r is None:
            raise TolallocError(f"{where}: kind {kind!r} needs radius_{unit} = ...")
        kw = {f"radius_{unit}": r}
        if "prob" in t:
            kw["prob"] = t["prob"]
        return _build(cls, kw, where)
    units, unit = (_ANGLE, "deg") if cls.unit == "deg" else (_LENGTH, "mm")
    extra = {"distance_accuracy": ("poses",), "path_accuracy": ("points",),
             "multidirectional_accuracy": ("poses", "approach"),
             "multidirectional_orientation": ("poses", "approach")}.get(kind, ())
    _unknown(t, {"kind", *_COMMON, *extra, "limit"} | {f"limit_{u}" for u in units}, where)
    lim = _value(t, "limit", units, where, unit)
    if lim is None:
        raise TolallocError(f"{where}: kind {kind!r} needs its limit, limit_{unit} = ... "
                            f"(or {', '.join(f'limit_{u}' for u in units if u != unit)}).")
    kw = {f"limit_{unit}": lim, **{k: t[k] for k in ("share", "population", "guard_band") if k in t}}
    kw.update({k: (tuple(t[k]) if isinstance(t[k], list) else t[k]) for k in extra if k in t})
    cond = {k: t[k] for k in ("load_pct", "speed_pct") if k in t}
    if cond:
        kw["conditions"] = _build(Conditions, cond, where)
    return _build(cls, kw, where)


def _unknown(t: dict, allowed: set, where: str) -> None:
    bad = set(t) - allowed
    if bad:
        raise TolallocError(f"{where}: unknown key(s) {', '.join(sorted(bad))} for kind {t.get('kind')!r}; expected "
                            f"{', '.join(sorted(allowed - {'limit', 'radius'}))}.")


def _build(cls, kw: dict, where: str):
    try:
        return cls(**kw)
    except TolallocError as exc:  # name the file's table, not the Python field
        raise TolallocError(f"{where}: {exc}") from None


def _test(t: dict, where: str) -> dict:
    if not isinstance(t, dict):
        raise TolallocError(f"{where}: expected a table, got {t!r}.")
    bad = set(t) - set(TEST_KEYS)
    if bad:
        hint = ("; a value needs its unit in its key (tracker_mpe_a_mm, cube_edge_mm ...)"
                if any(k in ("cube_edge", "tracker_mpe_a", "tracker_mpe_b", "tracker_distance") for k in bad) else "")
        raise TolallocError(f"{where}: unknown key(s) {', '.join(sorted(bad))}; expected {', '.join(TEST_KEYS)}{hint}.")
    out = {k: t[k] for k in ("cycles", "path_cycles", "cube_edge_mm", "cube_centre_mm", "plane", "orientation",
                             "registration", "registration_visits") if k in t}
    tr = {}
    for base, name, units in (("tracker_mpe_a", "mpe_a_mm", {"mm": 1.0, "um": 1e-3}),
                              ("tracker_mpe_b", "mpe_b_mm_per_m", {"mm_per_m": 1.0, "um_per_m": 1e-3})):
        v = _value(t, base, units, where, "mm")
        if v is not None:
            tr[name] = v
    for key, name in (("tracker_distance_m", "distance_m"), ("tracker_angle_mpe_deg", "angle_mpe_deg"),
                      ("coverage_factor_k", "k")):
        if key in t:
            tr[name] = t[key]
    if tr:
        out["tracker"] = _build(Tracker, tr, where)
    return out
