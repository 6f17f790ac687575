"""The component catalogue: the parts a robot's joints can be *bought* with, their figures and costs.

Not to be confused with :mod:`tolalloc.allocate.catalogue`, the standard values (ISO 286 grades, classes) a
*machined* tolerance can take. This catalogue lists purchasable parts, one TOML table each, every figure with its unit
in the key (the keys of :mod:`tolalloc.robot.components`)::

    [reducers."HD-CSG-32-100"]            # a part's name, unique within its kind
    family = "HD-CSG-32-100"              # parts of one family fit the same joint; they differ in grade
    grade = "standard"
    motion = "rotary"                     # rotary (revolute joints; the default) or linear (prismatic joints)
    type = "strain_wave"
    ratio = 100
    stiffness_Nm_per_rad = [6.7e4, 1.1e5, 1.2e5]
    torque_bands_Nm = [29, 108]
    transmission_accuracy_arcmin = 1.0
    lost_motion_arcmin = 1.0
    repeatability_arcsec = 6
    stiffness_sd_pct = 10
    rated_torque_Nm = 178
    cost = 40                             # relative cost units of the costs file
    cost_source = "assumed"
    source = "Harmonic Drive ..."

    [encoders."RING-100-STD"]             # side, accuracy_arcsec (peak-to-peak), eccentricity_um, scale_radius_mm
    [bearings."ISO492-P5"]                # an ISO 492 class: radial runout Kia per bore range
    precision_class = "P5"
    bore_limits_mm = [18, 30, 50, 80, 120, 180, 250]
    radial_runout_um = [4, 5, 5, 6, 8, 10]
    [motors."SERVO-750W"]                 # thermal figures (components.Motor)

The built-in catalogue is ``tolalloc/data/part_catalogue.toml`` (public catalogue figures with their source named;
costs ``assumed``). A user catalogue -- a file, or the ``[components.catalogue]`` tables and ``catalogue_file`` of a
robot file -- is merged over it: an entry of the same kind and name replaces the built-in one, a new name adds one.

A robot file's joint names a **slot** instead of figures (:func:`parse_slot`)::

    [components.joints.shoulder_lift_joint]
    reducer = { family = "HD-CSG-40-100" }                     # the design picks a grade of the family
    encoder = { part = "MOTOR-ENC-STD" }                       # a fixed catalogue part
    bearing = { options = ["ISO492-P0", "ISO492-P5"], bore_mm = 100, span_mm = 60 }

Bad entries are one clear error naming the entry: a figure without its unit, a stiffness curve that softens with
torque, a cost that is not a number >= 0, a slot naming no part of its kind or a part of the wrong motion.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.robot.components import _LENGTH, Bearing
from tolalloc.robot.components_io import (DATUM_KEYS, _positive_in, _text, datum_letter, read_encoder, read_motor,
                                          read_reducer, read_table)

__all__ = ["Part", "BearingClass", "PartCatalogue", "Slot", "KINDS", "BUILTIN_CATALOGUE", "load_part_catalogue",
           "builtin_catalogue", "robot_catalogue", "parse_slot"]

#: Part kinds, as the catalogue's top-level tables and a joint's part keys.
KINDS = {"reducers": "reducer", "encoders": "encoder", "bearings": "bearing", "motors": "motor"}
#: The built-in catalogue file.
BUILTIN_CATALOGUE = Path(__file__).resolve().parent.parent / "data" / "part_catalogue.toml"
_COMMON = ("family", "grade", "motion", "cost", "cost_source", "source")


@dataclass(frozen=True)
class BearingClass:
    """An ISO 492 tolerance class of radial bearings: the inner ring's radial runout Kia [mm] per bore range.

    ``bore_limits_mm`` (B + 1,): the range limits (a bore ``d`` is in range ``b`` for ``limit[b] < d <= limit[b+1]``);
    ``radial_runout`` (B,) [mm]."""

    precision_class: str
    bore_limits_mm: tuple
    radial_runout: tuple
    source: str = ""

    def runout_at(self, bore_mm: float, where: str = "bearing") -> float:
        """Kia [mm] of a bearing of bore ``bore_mm``; raises ValueError outside the table's bore ranges."""
        lim = self.bore_limits_mm
        if not lim[0] < bore_mm <= lim[-1]:
            raise ValueError(f"{where}: bore_mm = {bore_mm:g} lies outside the bore ranges of class "
                             f"{self.precision_class} ({lim[0]:g} < d <= {lim[-1]:g} mm); give a bore within them "
                             "or a catalogue entry whose table covers it")
        return float(self.radial_runout[int(np.searchsorted(lim, bore_mm)) - 1])


@dataclass(frozen=True)
class Part:
    """One catalogue entry.

    Attributes
    ----------
    name, kind : str              the entry's name and its kind (``reducer``, ``encoder``, ``bearing``, ``motor``)
    family, grade : str
    motion : {"rotary", "linear"}
    spec : Reducer, Encoder, BearingClass or Motor    its figures in internal units
    cost : float or None          relative cost units (None: not priced)
    cost_source, source : str     where the cost and the figures come from
    """

    name: str
    kind: str
    family: str
    grade: str
    motion: str
    spec: object
    cost: float | None
    cost_source: str
    source: str


@dataclass(frozen=True)
class PartCatalogue:
    """Parts by kind: ``parts[kind][name]``; ``origins``: the files (or tables) merged, built-in first."""

    parts: dict
    origins: tuple = ()

    def get(self, kind: str, name: str, where: str = "catalogue") -> Part:
        """The part ``name`` of ``kind``; ValueError listing the kind's families when it is not there."""
        if name not in self.parts.get(kind, {}):
            raise ValueError(f"{where}: no {kind} named {name!r} in the component catalogue; {self._listing(kind)}")
        return self.parts[kind][name]

    def family(self, kind: str, family: str, where: str = "catalogue") -> tuple:
        """The parts of ``family`` (cheapest first); ValueError when the family is empty."""
        out = [p for p in self.parts.get(kind, {}).values() if p.family == family]
        if not out:
            raise ValueError(f"{where}: the catalogue has no {kind} of family {family!r} (an empty slot); "
                             f"{self._listing(kind)}")
        return tuple(sorted(out, key=lambda p: (np.inf if p.cost is None else p.cost, p.name)))

    def _listing(self, kind: str) -> str:
        fams = sorted({p.family for p in self.parts.get(kind, {}).values()})
        return f"{kind} families: {', '.join(fams) or 'none'}" + (
            f" (add entries with a user catalogue: [{kind}s.NAME] tables)" if not fams else "")

    def to_frame(self) -> pd.DataFrame:
        """One row per part: kind, name, family, grade, motion, cost, cost_source, source."""
        rows = [{"kind": p.kind, "name": p.name, "family": p.family, "grade": p.grade, "motion": p.motion,
                 "cost": p.cost, "cost_source": p.cost_source, "source": p.source}
                for kind in KINDS.values() for p in self.parts.get(kind, {}).values()]
        return pd.DataFrame(rows, columns=["kind", "name", "family", "grade", "motion", "cost", "cost_source", "source"])


def _entry(kind: str, name: str, table: dict, where: str, default_cost_source: str) -> Part:
    if not isinstance(table, dict):
        raise ValueError(f"{where}: expected a table of figures, got {table!r}")
    motion = _text(table, "motion", where, "rotary", ("rotary", "linear"))
    rev = motion == "rotary"
    if kind == "reducer":
        spec = read_reducer(table, where, rev, extra_keys=_COMMON)
    elif kind == "encoder":
        spec = read_encoder(table, where, rev, extra_keys=_COMMON)
    elif kind == "motor":
        spec = read_motor(table, where, extra_keys=_COMMON)
    else:
        spec = _bearing_class(table, where)
    cost = table.get("cost")
    if cost is not None and (isinstance(cost, bool) or not isinstance(cost, (int, float)) or not np.isfinite(cost)
                             or cost < 0):
        raise ValueError(f"{where}.cost: expected a number >= 0 (relative cost units of the costs file), got {cost!r}")
    src = _text(table, "source", where, "") or getattr(spec, "source", "")
    return Part(name, kind, _text(table, "family", where, name), _text(table, "grade", where, ""), motion, spec,
                None if cost is None else float(cost), _text(table, "cost_source", where, default_cost_source), src)


def _bearing_class(table: dict, where: str) -> BearingClass:
    v = read_table(table, {"bore_limits": (_LENGTH, None), "radial_runout": (_LENGTH, None)}, where,
                   text=("precision_class",) + _COMMON)
    lim, kia = v["bore_limits"], _positive_in(v, "radial_runout", where, allow_zero=True)
    if lim is None or kia is None:
        raise ValueError(f"{where}: a bearing class needs bore_limits_mm (B + 1 increasing limits) and "
                         "radial_runout_um (B values, Kia per bore range)")
    lim = (lim,) if isinstance(lim, float) else lim
    kia = (kia,) if isinstance(kia, float) else kia
    if len(lim) != len(kia) + 1 or any(b <= a for a, b in zip(lim, lim[1:])):
        raise ValueError(f"{where}: expected {len(kia) + 1} increasing bore_limits_mm for {len(kia)} radial_runout "
                         f"values, got {len(lim)} limits")
    cls = _text(table, "precision_class", where, None)
    if cls is None:
        raise ValueError(f"{where}: missing precision_class (the ISO 492 class, e.g. \"P5\")")
    return BearingClass(cls, tuple(lim), tuple(kia), _text(table, "source", where, ""))


def _merge(base: dict, data: dict, origin: str, default_cost_source: str) -> dict:
    """``base`` (``{kind: {name: Part}}``) with the entries of a parsed catalogue ``data`` merged over it."""
    if not isinstance(data, dict):
        raise ValueError(f"{origin}: expected tables of parts, got {data!r}")
    extra = [k for k in data if k not in KINDS and k not in ("schema", "cost_unit", "description")]
    if extra:
        raise ValueError(f"{origin}: unknown table {extra[0]!r}; expected {', '.join(KINDS)}")
    out = {k: dict(v) for k, v in base.items()}
    for table, kind in KINDS.items():
        entries = data.get(table) or {}
        if not isinstance(entries, dict):
            raise ValueError(f"{origin}: [{table}] expected tables of parts ([{table}.NAME]), got {entries!r}")
        for name, entry in entries.items():
            out.setdefault(kind, {})[name] = _entry(kind, name, entry, f"{origin}: {table}.{name}",
                                                    default_cost_source)
    return out


def _read(path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise ValueError(f"component catalogue {path}: cannot read it ({exc.strerror or exc})") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"component catalogue {path}: not valid TOML ({exc})") from None


@lru_cache(maxsize=1)
def builtin_catalogue() -> PartCatalogue:
    """The built-in catalogue (:data:`BUILTIN_CATALOGUE`), read once."""
    return PartCatalogue(_merge({}, _read(BUILTIN_CATALOGUE), "built-in component catalogue", "assumed"),
                         (str(BUILTIN_CATALOGUE),))


def load_part_catalogue(user=None, base: PartCatalogue | None = None) -> PartCatalogue:
    """The built-in catalogue (or ``base``) with a user catalogue merged over it.

    Parameters
    ----------
    user : str, path or dict, optional
        A catalogue file (TOML) or its parsed tables; its entries replace built-in ones of the same kind and name.
    base : PartCatalogue, optional
        What to merge over (default the built-in catalogue).

    Raises
    ------
    ValueError
        Naming the entry and key (the robot and workflow entry points turn it into a TolallocError).
    """
    base = builtin_catalogue() if base is None else base
    if user is None:
        return base
    if isinstance(user, dict):
        origin, data = "user catalogue", user
    else:
        origin, data = f"component catalogue {user}", _read(user)
    return PartCatalogue(_merge(base.parts, data, origin, f"given in {origin}"), base.origins + (origin,))


def robot_catalogue(components: dict, where: str, base_dir=None) -> PartCatalogue:
    """The catalogue a robot file's slots resolve against: built-in, then its ``catalogue_file`` (relative to
    ``base_dir``), then its inline ``[components.catalogue]`` tables."""
    cat = builtin_catalogue()
    f = components.get("catalogue_file")
    if f is not None:
        if not isinstance(f, str):
            raise ValueError(f"{where}.catalogue_file: expected a file name, got {f!r}")
        path = Path(f) if Path(f).is_absolute() or base_dir is None else Path(base_dir) / f
        cat = load_part_catalogue(path, cat)
    if "catalogue" in components:
        cat = PartCatalogue(_merge(cat.parts, components["catalogue"], f"{where}.catalogue", f"given in {where}"),
                            cat.origins + (f"{where}.catalogue",))
    return cat


@dataclass(frozen=True)
class Slot:
    """A joint's catalogue slot: the parts it may take (one: a fixed part) and, for a bearing, the seat geometry.

    Attributes
    ----------
    joint, kind : str
    options : tuple of Part        cheapest first (for a family) or as listed
    geometry : dict                bearing slots: ``bore_mm``, ``span_mm``, ``datum``, ``locating_datum``,
                                   ``shoulder_datum``, ``seat_diameter_mm``, ``tilt_stiffness``
    """

    joint: str
    kind: str
    options: tuple
    geometry: dict

    @property
    def names(self) -> tuple:
        return tuple(p.name for p in self.options)

    def part(self, name: str) -> Part:
        for p in self.options:
            if p.name == name:
                return p
        raise ValueError(f"components.joints.{self.joint}.{self.kind}: {name!r} is not an option of the slot; "
                         f"options: {', '.join(self.names)}")

    def resolve(self, name: str):
        """The component figures (Reducer, Encoder, Bearing or Motor) of option ``name`` at this joint."""
        p = self.part(name)
        if self.kind != "bearing":
            return replace(p.spec, source=p.source) if hasattr(p.spec, "source") else p.spec
        kia = p.spec.runout_at(self.geometry["bore_mm"], f"components.joints.{self.joint}.bearing ({p.name})")
        return replace(self.seat(), precision_class=p.spec.precision_class, source=p.source, radial_runout=kia)

    def seat(self) -> Bearing:
        """A bearing slot's seat geometry as a :class:`Bearing` with no class chosen (span, datum letters, bore, seat
        diameter, tilt stiffness, centre: the same for every option; precision class and runout None)."""
        g = self.geometry
        return Bearing(None, g.get("span_mm"), g.get("datum"), g.get("tilt_stiffness"), "", g["bore_mm"], None,
                       g.get("seat_diameter_mm"), g.get("centre_mm", 0.0), g.get("locating_datum"),
                       g.get("shoulder_datum"))


def parse_slot(table: dict, where: str, kind: str, joint: str, revolute: bool, catalogue: PartCatalogue) -> Slot:
    """A :class:`Slot` from a joint's part table with ``part``, ``family`` or ``options`` (module docstring)."""
    sel = [k for k in ("part", "family", "options") if k in table]
    if len(sel) != 1:
        raise ValueError(f"{where}: give one of part, family or options, got {sel}")
    geo_spec = {"bore": (_LENGTH, ((),)), "span": (_LENGTH, ((),)), "centre": (_LENGTH, ((),)),
                "seat_diameter": (_LENGTH, ((),)),
                "tilt_stiffness": ({"Nm_per_rad": 1.0}, ((),))} if kind == "bearing" else {}
    v = read_table(table, geo_spec, where, text=("part", "family", "options", "source")
                   + (DATUM_KEYS if kind == "bearing" else ()))
    key = sel[0]
    if key == "options":
        names = table["options"]
        if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
            raise ValueError(f"{where}.options: expected a non-empty list of part names (an empty slot cannot be "
                             f"bought), got {names!r}; {catalogue._listing(kind)}")
        opts = tuple(catalogue.get(kind, n, where) for n in names)
    elif not isinstance(table[key], str):
        raise ValueError(f"{where}.{key}: expected a name, got {table[key]!r}")
    elif key == "part":
        opts = (catalogue.get(kind, table["part"], where),)
    else:
        opts = catalogue.family(kind, table["family"], where)
    want = "rotary" if revolute else "linear"
    bad = [p.name for p in opts if p.motion != want and kind != "motor"]  # a motor turns whatever it drives
    if bad:
        raise ValueError(f"{where}: {', '.join(bad)} is a {'linear' if revolute else 'rotary'} part, but "
                         f"{joint} is a {'revolute' if revolute else 'prismatic'} joint; choose {want} parts")
    if len(opts) > 1:
        unpriced = [p.name for p in opts if p.cost is None]
        if unpriced:
            raise ValueError(f"{where}: the options {', '.join(unpriced)} have no cost; a choice needs every option "
                             "priced (cost = ... in the catalogue entry)")
    geometry = {}
    if kind == "bearing":
        if v["bore"] is None:
            raise ValueError(f"{where}: a bearing slot needs bore_mm (it selects the ISO 492 runout row)")
        geometry = {"bore_mm": v["bore"], "span_mm": _positive_in(v, "span", where),
                    "tilt_stiffness": _positive_in(v, "tilt_stiffness", where),
                    "seat_diameter_mm": _positive_in(v, "seat_diameter", where),
                    **{k: datum_letter(table, k, where) for k in DATUM_KEYS},
                    "centre_mm": float(v["centre"] or 0.0)}
        if geometry["span_mm"] is None:
            raise ValueError(f"{where}: a bearing slot needs span_mm (the distance between its two bearings: "
                             "runout over the span tilts the axis)")
        for p in opts:
            p.spec.runout_at(geometry["bore_mm"], f"{where} ({p.name})")
    return Slot(joint, kind, opts, geometry)
