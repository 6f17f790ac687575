"""Standard values a tolerance may take, and manufacturing processes, as read from the costs file.

Every allocatable parameter gets a :class:`DiscreteSpec`: the standard half-widths it may take in a
drawing. Link lengths take ISO 286 IT grades (``grades = "IT5-IT12"``, the default: ``±IT/2`` at the
link's nominal length); other parameters take a catalogue of standard classes
(``classes_deg = { P5 = 0.002, P4 = 0.001 }``, half-widths) or, without one, any multiple of a resolution
step (``step_deg``, ``step_mm``; default 1 arcsec and 0.001 mm). Keys in ``[kinds.*]`` and
``[parameters.*]`` as for the cost laws.

Processes (optional)::

    [processes.grinding]
    applies_to = ["link_length"]     # kinds or parameter names (default: link_length)
    grades = "IT5-IT7"               # attainable grade range (graded lengths) ...
    cost = { IT5 = 6.0, IT6 = 4.5, IT7 = 3.5 }   # cost per grade (or per class) ...
    setup = 1.0                      # paid once per part (link or joint) that uses the process

    [processes.milling]
    grades = "IT8-IT11"
    model = "reciprocal"             # ... or a cost law of t = IT/2 (keys as [kinds.*])
    a = 0.5
    b = 1.0
    t_ref_mm = 0.1

``applies_to`` names kinds as the ``[kinds.*]`` tables do (``joint_drive``: the revolute drives,
``joint_drive_prismatic``: the prismatic ones) or parameters. For parameters without grades the attainable range
is ``t_min_<unit>`` / ``t_max_<unit>`` (default: the parameter's process limits) and the cost a law (or a
``cost`` table over the parameter's classes). A parameter that some process applies to chooses among those processes (one per
part: all parameters of a link or joint under processes share it); its kind's cost law then only drives the
continuous design.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from tolalloc.errormodel.model import KINDS
from tolalloc.exceptions import TolallocError
from tolalloc.units import ANGLE_UNITS, LENGTH_UNITS

__all__ = ["DiscreteSpec", "ProcessOption", "parse_grades", "discrete_spec", "read_processes", "DEFAULT_GRADES",
           "DISCRETE_KEYS"]

#: IT grades a link length may take when the costs file says nothing (IT5-IT12).
DEFAULT_GRADES = (5, 12)
#: Keys of ``[kinds.*]`` / ``[parameters.*]`` entries read here (``step_<unit>``, ``classes_<unit>``, ``grades``).
DISCRETE_KEYS = ("grades",)
_PROCESS_KEYS = {"applies_to", "grades", "cost", "setup", "model", "a", "b", "k"}
_GRADE = re.compile(r"^IT(\d+)$")


@dataclass(frozen=True)
class ProcessOption:
    """One process available to one parameter.

    Attributes
    ----------
    name : str
    grades : (int, int) or None
        Attainable IT grades (graded lengths), inclusive.
    t_lo, t_hi : float
        Attainable half-widths [mm or rad] (parameters without grades; 0 and inf for graded ones).
    cost_table : tuple of (label, cost) or None
        Cost per grade (``"IT7"``) or per class label.
    law : CostModel or None
        Cost law of the half-width (when there is no table).
    setup : float
        Cost paid once per part that uses the process.
    """

    name: str
    grades: tuple | None
    t_lo: float
    t_hi: float
    cost_table: tuple | None
    law: object | None
    setup: float = 0.0

    def cost(self, t: float, label: str) -> float:
        """Cost of a candidate of half-width ``t`` [mm or rad] and label ``label`` (NaN: not attainable)."""
        if self.cost_table is not None:
            return float(dict(self.cost_table).get(label, np.nan))
        return float(self.law.cost(t))

    def attains(self, t: float, label: str) -> bool:
        if self.grades is not None:
            m = _GRADE.match(label)
            return m is not None and self.grades[0] <= int(m.group(1)) <= self.grades[1]
        return self.t_lo * (1 - 1e-12) <= t <= self.t_hi * (1 + 1e-12) and np.isfinite(self.cost(t, label))


@dataclass(frozen=True)
class DiscreteSpec:
    """Standard values one parameter may take.

    Attributes
    ----------
    grades : (int, int) or None
        IT grade range (link lengths; used when the link's nominal length is in ISO 286's 0-3150 mm).
    classes : tuple of (label, half-width [mm or rad]) or None
        Standard classes; replaces the step.
    step : float or None
        Resolution of the value [mm or rad]; None: the allocation's default (1 arcsec, 0.001 mm).
    processes : tuple of ProcessOption
    """

    grades: tuple | None = None
    classes: tuple | None = None
    step: float | None = None
    processes: tuple = ()


def parse_grades(value, where: str) -> tuple[int, int]:
    """``"IT5-IT12"``, ``"IT7"`` or ``["IT5", "IT12"]`` -> ``(5, 12)``; TolallocError naming ``where``."""
    if isinstance(value, str):
        parts = [s.strip() for s in re.split(r"\s*(?:-|\.\.)\s*", value.strip())]
    elif isinstance(value, (list, tuple)):
        parts = list(value)
    else:
        parts = [value]
    nums = []
    for g in parts:
        m = _GRADE.match(g) if isinstance(g, str) else None
        if m is None or not 1 <= int(m.group(1)) <= 18:
            raise TolallocError(f"{where}: unknown grade {g!r}; expected ISO 286 grades IT1..IT18, e.g. "
                                "grades = \"IT5-IT12\" or grades = [\"IT5\", \"IT12\"].")
        nums.append(int(m.group(1)))
    if len(nums) not in (1, 2):
        raise TolallocError(f"{where}: expected one grade or a range of two (\"IT5-IT12\"), got {value!r}.")
    lo, hi = nums[0], nums[-1]
    if lo > hi:
        raise TolallocError(f"{where}: the grade range {value!r} is empty (IT{lo} is coarser than IT{hi}); "
                            f"give the finer grade first, e.g. \"IT{hi}-IT{lo}\".")
    return lo, hi


def _unit_items(entry: dict, base: str, unit: str, where: str):
    """``(key, value, factor)`` of ``base_<suffix>`` in ``entry``; the suffix must fit ``unit`` (mm or rad)."""
    table = LENGTH_UNITS if unit == "mm" else ANGLE_UNITS
    found = [k for k in entry if k.startswith(base + "_") and k[len(base) + 1:] in {**LENGTH_UNITS, **ANGLE_UNITS}]
    if len(found) > 1:
        raise TolallocError(f"{where}: give {base} once, got {found}.")
    if not found:
        return None
    key = found[0]
    suffix = key[len(base) + 1:]
    if suffix not in table:
        raise TolallocError(f"{where}: {key} has the wrong unit for a parameter in {unit}; use {base}_"
                            f"{'mm' if unit == 'mm' else 'deg'}.")
    return key, entry[key], table[suffix]


def _positive(v, key: str, where: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v <= 0:
        raise TolallocError(f"{where}: {key} expected a finite number > 0, got {v!r}.")
    return float(v)


def discrete_spec(entry: dict, p, where: str) -> DiscreteSpec:
    """The grades / classes / step of one parameter's merged costs entry (processes are added later)."""
    grades = None
    if "grades" in entry:
        if p.kind != "link_length":
            raise TolallocError(f"{where}: grades (ISO 286) apply to link_length parameters only, not to "
                                f"{p.kind}; use classes_{'mm' if p.unit == 'mm' else 'deg'} or step_"
                                f"{'mm' if p.unit == 'mm' else 'deg'} instead.")
        grades = parse_grades(entry["grades"], f"{where} grades")
    elif p.kind == "link_length":
        grades = DEFAULT_GRADES
    step = None
    item = _unit_items(entry, "step", p.unit, where)
    if item is not None:
        step = _positive(item[1], item[0], where) * item[2]
    classes = None
    item = _unit_items(entry, "classes", p.unit, where)
    if item is not None:
        key, raw, f = item
        if isinstance(raw, dict):
            pairs = [(str(lab), _positive(v, f"{key}.{lab}", where) * f) for lab, v in raw.items()]
        elif isinstance(raw, (list, tuple)):
            pairs = [("", _positive(v, f"{key}[{i}]", where) * f) for i, v in enumerate(raw)]
        else:
            raise TolallocError(f"{where}: {key} expected a table of class = half-width or a list of half-widths, "
                                f"got {raw!r}.")
        if not pairs:
            raise TolallocError(f"{where}: {key} is empty; give at least one class or leave the key out.")
        classes = tuple(sorted(pairs, key=lambda x: x[1]))
    return DiscreteSpec(grades, classes, step)


def read_processes(data: dict, model, names, entries: dict, cost_model, source: str) -> dict:
    """Process options per parameter name, from ``[processes.*]``.

    Parameters
    ----------
    data : dict
        The parsed costs file.
    model : ErrorModel
    names : sequence of str
        Parameters in the problem (excluded ones left out).
    entries : dict
        name -> the parameter's merged costs entry (its own process limits are the default range).
    cost_model : callable
        ``cost_model(entry, p, where) -> CostModel`` (the costs module's law parser).
    source : str

    Returns
    -------
    dict name -> tuple of ProcessOption
    """
    procs = data.get("processes") or {}
    if not isinstance(procs, dict):
        raise TolallocError(f"costs {source}: processes expected tables [processes.NAME], got {procs!r}.")
    out: dict = {nm: [] for nm in names}
    kinds = set(KINDS) | {"joint_drive_prismatic"}
    for pname, entry in procs.items():
        where = f"costs {source} [processes.{pname}]"
        if not isinstance(entry, dict):
            raise TolallocError(f"{where}: expected a table of keys, got {entry!r}.")
        for key in entry:
            if key not in _PROCESS_KEYS and not re.match(r"^(t_ref|t_min|t_max)_(mm|m|deg|rad)$", key):
                raise TolallocError(f"{where}: unknown key {key!r}; expected applies_to, grades, cost, setup, "
                                    "model, a, b, k, t_ref_<mm|deg>, t_min_<mm|deg>, t_max_<mm|deg>.")
        targets = entry.get("applies_to", ["link_length"])
        if isinstance(targets, str):
            targets = [targets]
        if not isinstance(targets, list) or not targets or not all(isinstance(t, str) for t in targets):
            raise TolallocError(f"{where}: applies_to expected a list of kinds or parameter names, got {targets!r}.")
        for t in targets:
            if t not in kinds and t not in model.names:
                raise TolallocError(f"{where}: applies_to: {t!r} is neither a kind ({', '.join(sorted(kinds))}) nor "
                                    f"a parameter of the error model.")
        setup = entry.get("setup", 0.0)
        if isinstance(setup, bool) or not isinstance(setup, (int, float)) or not np.isfinite(setup) or setup < 0:
            raise TolallocError(f"{where}: setup expected a finite cost >= 0, got {setup!r}.")
        table = _cost_table(entry, where)
        if table is None and "model" not in entry:
            raise TolallocError(f"{where}: give a cost per grade (cost = {{ IT7 = 2.0, ... }}) or a cost law "
                                "(model, a, b, t_ref_<unit>).")
        if table is not None and ("model" in entry or "a" in entry or "b" in entry):
            raise TolallocError(f"{where}: give either a cost table (cost = ...) or a cost law (model, a, b), not both.")
        used = False
        for nm in names:
            p = model.params[model.index(nm)]
            key = "joint_drive_prismatic" if p.kind == "joint_drive" and p.unit == "mm" else p.kind
            if nm in targets or key in targets:  # joint_drive: the revolute drives (as [kinds.joint_drive])
                out[nm].append(_option(pname, entry, p, entries[nm], table, float(setup), cost_model, where))
                used = True
        if not used:
            raise TolallocError(f"{where}: applies_to {targets} matches no parameter of this problem.")
    return {nm: tuple(v) for nm, v in out.items()}


def _cost_table(entry: dict, where: str):
    if "cost" not in entry:
        return None
    raw = entry["cost"]
    if not isinstance(raw, dict) or not raw:
        raise TolallocError(f"{where}: cost expected a table of grade (or class) = cost, e.g. "
                            f"cost = {{ IT7 = 3.0, IT8 = 2.2 }}, got {raw!r}.")
    out = []
    for lab, v in raw.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v < 0:
            raise TolallocError(f"{where}: cost.{lab} expected a finite cost >= 0 (a part never costs less than "
                                f"nothing), got {v!r}.")
        out.append((str(lab), float(v)))
    return tuple(out)


def _option(pname, entry, p, own: dict, table, setup, cost_model, where) -> ProcessOption:
    """The process as seen by parameter ``p`` (its unit, its grades or range)."""
    here = f"{where} (for {p.name})"
    spec = discrete_spec(own, p, here)
    grades = None
    if p.kind == "link_length":
        grades = parse_grades(entry["grades"], f"{where} grades") if "grades" in entry else spec.grades
        if table is not None:
            for lab, _ in table:
                m = _GRADE.match(lab)
                if m is None or not grades[0] <= int(m.group(1)) <= grades[1]:
                    raise TolallocError(f"{where}: cost.{lab}: not a grade of the process range IT{grades[0]}-"
                                        f"IT{grades[1]}; give costs for grades of that range.")
    elif "grades" in entry:
        raise TolallocError(f"{where}: grades apply to link_length parameters only; {p.name} is {p.kind}; give "
                            f"t_min_{'mm' if p.unit == 'mm' else 'deg'} / t_max_... for its attainable range.")
    elif table is not None:
        labels = {lab for lab, _ in (spec.classes or ())}
        bad = [lab for lab, _ in table if lab not in labels]
        if bad:
            raise TolallocError(f"{where}: cost.{bad[0]}: {p.name} has no standard class {bad[0]!r} "
                                f"(its classes: {sorted(labels) or 'none'}); give a cost law for parameters "
                                "without classes.")
    lo_hi = []
    for base in ("t_min", "t_max"):
        item = _unit_items(entry, base, p.unit, here)
        lo_hi.append(None if item is None else _positive(item[1], item[0], here) * item[2])
    lo = lo_hi[0] if lo_hi[0] is not None else 0.0
    hi = lo_hi[1] if lo_hi[1] is not None else np.inf
    if lo > hi:
        raise TolallocError(f"{where}: the attainable range is empty (t_min > t_max for {p.name}); swap them.")
    law = None
    if table is None:
        law_entry = {k: v for k, v in entry.items() if k in ("model", "a", "b", "k") or k.startswith("t_ref_")}
        u = "mm" if p.unit == "mm" else "deg"
        f = 1.0 if p.unit == "mm" else 180.0 / np.pi
        # the law's own limits are not used (the grades or the range above decide); give it the parameter's
        law_entry.update({f"t_min_{u}": own_limit(own, "t_min", p) * f, f"t_max_{u}": own_limit(own, "t_max", p) * f})
        law = cost_model(law_entry, p, here)
    return ProcessOption(pname, grades, lo, hi, table, law, setup)


def own_limit(entry: dict, base: str, p) -> float:
    """A parameter's own limit ``base`` [mm or rad] from its merged entry."""
    item = _unit_items(entry, base, p.unit, base)
    return float(item[1]) * item[2]
