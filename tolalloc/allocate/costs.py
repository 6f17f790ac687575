"""Cost-tolerance models, process limits and the costs file.

Every allocatable parameter ``k`` gets a symmetric tolerance ``±t_k`` and a cost
``c_k(t_k)``. All models are written with a *reference tolerance* ``t_ref`` (which
carries the unit, mm or deg at the interface) and two cost coefficients ``a`` and
``b`` in relative cost units; with ``tau = t / t_ref``:

``reciprocal``        ``c = a + b / tau``           (``A + B/t`` with ``A = a``, ``B = b t_ref``)
``reciprocal_power``  ``c = a + b / tau**k``        (``A + B t^-k``)
``exponential``       ``c = a + b exp(-tau)``       (``A' + A e^(-B t)`` with ``B = 1/t_ref``)
``michael_siddall``   ``c = a + b tau**-k exp(-tau)`` (``A' + A t^-k e^(-B t)``)

The published source of each form: :data:`tolalloc.allocate.process_table.COST_LAW_SOURCES`.

With ``sigma = t / z`` the allocation works in the scaled variance
``u = (t / t_ref)**2 = tau**2``; every model above is convex in ``u`` (``u**-1/2``,
``u**-k/2``, ``exp(-sqrt(u))`` and ``exp(-k/2 log u - sqrt(u))``), which is what the certified conic solver needs.

Costs file (TOML, units in the keys)::

    z = 3.0                       # sigma = t / z (3: a +-3 sigma process); distribution = "uniform" -> sqrt(3)

    [kinds.link_length]           # kinds: link_length, joint_drive (revolute),
    model = "reciprocal"          #   joint_drive_prismatic, axis_deflection, clearance_*
    a = 1.0
    b = 1.0
    t_ref_mm = 0.1
    t_min_mm = 0.005
    t_max_mm = 1.0

    [parameters.dl3]              # per-parameter overrides (merged over the kind's entry)
    t_min_mm = 0.01
    [parameters.e6x]
    fixed = true                  # keep at tol_deg (or at the error model's sigma * z)
    tol_deg = 0.01
    [parameters.dth6]
    exclude = true                # leave out of the problem entirely

Angles are given with ``_deg`` (or ``_rad``), lengths with ``_mm`` (or ``_m``).

Standard values for the drawing (``grades = "IT5-IT12"`` for link lengths, ``classes_<unit>``, ``step_<unit>``)
and manufacturing processes (``[processes.NAME]``) are described in :mod:`tolalloc.allocate.processes`.

This module holds the cost laws (:class:`CostModel`), the defaults (:data:`DEFAULT_COSTS`), the resolved set
(:class:`CostSet`, :func:`cost_set`) and the file reader (:func:`load_costs`, :func:`read_costs_file`); the checks of
one section's keys, unit suffixes and values are in :mod:`tolalloc.allocate.costs_entries`.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import ErrorModel
from tolalloc.allocate.costs_entries import _UNIT_BASES, _check_entry, _check_values, _value
from tolalloc.allocate.processes import DiscreteSpec, discrete_spec, parse_grades, read_processes

__all__ = ["CostModel", "CostSet", "DEFAULT_COSTS", "cost_set", "load_costs", "read_costs_file", "param_kind_key", "MODELS"]

MODELS = ("reciprocal", "reciprocal_power", "exponential", "michael_siddall")

#: Default cost-tolerance data for the tool_changer (and any robot without a costs file).
#: ASSUMPTIONS of this project, not measured data: relative cost 2 (= a + b) at the reference
#: tolerance, reciprocal law (Chase & Greenwood's classic form); references and process limits
#: chosen as typical for precision machining of ~0.2-0.8 m links (+-0.1 mm ordinary, +-5 um
#: the best process, about IT4 over 500 mm), servo drives with absolute encoders (+-0.01 deg
#: ordinary, +-0.0005 deg = 1.8 arcsec after calibration), and assembled bearing axes
#: (+-0.01 deg ordinary, +-0.001 deg = 3.6 arcsec with precision bearings and alignment).
DEFAULT_COSTS = {
    "z": 3.0,
    "kinds": {
        "link_length": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_mm": 0.1, "t_min_mm": 0.005, "t_max_mm": 1.0,
                        "grades": "IT5-IT12"},
        "joint_drive": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_deg": 0.01, "t_min_deg": 0.0005, "t_max_deg": 0.5},
        "joint_drive_prismatic": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_mm": 0.05, "t_min_mm": 0.002,
                                  "t_max_mm": 1.0},
        "axis_deflection": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_deg": 0.01, "t_min_deg": 0.001,
                            "t_max_deg": 0.5},
        "clearance_axial": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_mm": 0.05, "t_min_mm": 0.002, "t_max_mm": 1.0},
        "clearance_radial": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_mm": 0.05, "t_min_mm": 0.002,
                             "t_max_mm": 1.5},
        "clearance_tilt": {"model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_deg": 0.01, "t_min_deg": 0.001, "t_max_deg": 1.0},
    },
}


@dataclass(frozen=True)
class CostModel:
    """Cost-tolerance law and process limits of one parameter (internal units mm or rad).

    Attributes
    ----------
    model : {"reciprocal", "reciprocal_power", "exponential", "michael_siddall"}
    a, b : float
        Cost coefficients [relative cost units], ``b > 0``.
    t_ref : float
        Reference tolerance [mm or rad] (``tau = t / t_ref``).
    t_min, t_max : float
        Process limits on the half-width ``t`` [mm or rad], ``0 < t_min <= t_max``.
    k : float
        Exponent of ``reciprocal_power`` and ``michael_siddall``.
    """

    model: str
    a: float
    b: float
    t_ref: float
    t_min: float
    t_max: float
    k: float = 1.0

    def cost(self, t) -> np.ndarray:
        """Cost at half-width ``t`` [mm or rad] (array-like)."""
        tau = np.asarray(t, dtype=float) / self.t_ref
        with np.errstate(divide="ignore"):
            if self.model == "reciprocal":
                return self.a + self.b / tau
            if self.model == "reciprocal_power":
                return self.a + self.b / tau**self.k
            if self.model == "michael_siddall":
                return self.a + self.b * np.exp(-tau) / tau**self.k
            return self.a + self.b * np.exp(-tau)

    def cost_u(self, u, lib):
        """Cost as an expression of the scaled variance ``u = (t/t_ref)**2``.

        ``lib`` is ``"cvxpy"`` (a convex DCP expression) or ``"casadi"``; ``u`` is that library's variable.
        """
        if lib == "cvxpy":
            import cvxpy as cp

            if self.model == "reciprocal":
                return self.a + self.b * cp.power(u, -0.5)
            if self.model == "reciprocal_power":
                return self.a + self.b * cp.power(u, -self.k / 2.0)
            if self.model == "michael_siddall":
                return self.a + self.b * cp.exp(-self.k / 2.0 * cp.log(u) - cp.sqrt(u))
            return self.a + self.b * cp.exp(-cp.sqrt(u))
        import casadi as ca

        if self.model == "reciprocal":
            return self.a + self.b * u ** (-0.5)
        if self.model == "reciprocal_power":
            return self.a + self.b * u ** (-self.k / 2.0)
        if self.model == "michael_siddall":
            return self.a + self.b * u ** (-self.k / 2.0) * ca.exp(-ca.sqrt(u))
        return self.a + self.b * ca.exp(-ca.sqrt(u))


@dataclass(frozen=True)
class CostSet:
    """Cost models and roles of the parameters of an error model.

    Attributes
    ----------
    names : tuple of str
        Parameter names (the error model's order, excluded ones left out).
    role : tuple of str
        ``"allocate"`` or ``"fixed"`` per parameter.
    models : tuple of CostModel
    fixed_tol : tuple of float
        Half-width of fixed parameters [mm or rad] (NaN for allocatable ones).
    z : float
        ``sigma = t / z``.
    excluded : tuple of str
    source : str
        ``"defaults"`` or the costs file's path.
    distribution : {"normal", "uniform"}
        How a part's error is distributed within its tolerance: ``uniform`` over ``±t`` (``z = sqrt(3)``),
        else normal; the allocation's Monte Carlo verification samples it so.
    discrete : tuple of DiscreteSpec
        Standard values (grades, classes or step) and processes per parameter (empty: the defaults).
    """

    names: tuple
    role: tuple
    models: tuple
    fixed_tol: tuple
    z: float
    excluded: tuple = ()
    source: str = "defaults"
    distribution: str = "normal"
    discrete: tuple = ()

    def spec(self, k: int) -> DiscreteSpec:
        """The standard values of parameter ``k`` (defaults when the set carries none)."""
        return self.discrete[k] if self.discrete else DiscreteSpec()

    def to_frame(self, model: ErrorModel) -> pd.DataFrame:
        """One row per parameter: law, coefficients, and the reference tolerance, process limits and fixed
        tolerance (NaN for allocatable parameters) each as a ``<name>_mm`` / ``<name>_deg`` pair in the row's
        interface unit (:func:`tolalloc.units.unit_columns`)."""
        params = [model.params[model.index(nm)] for nm in self.names]
        frame = pd.DataFrame({"parameter": list(self.names), "kind": [p.kind for p in params],
                              "unit": [p.interface_unit for p in params], "role": list(self.role),
                              **{c: [getattr(cm, c) for cm in self.models] for c in ("model", "a", "b", "k")}})
        for name in ("t_ref", "t_min", "t_max"):
            values = [getattr(cm, name) for cm in self.models]
            frame = frame.assign(**model.interface_columns(name, values, self.names))
        return frame.assign(**model.interface_columns("fixed_tol", np.array(self.fixed_tol, float), self.names))


def param_kind_key(p) -> str:
    """The costs-file section a parameter falls under (``joint_drive_prismatic`` for prismatic drives)."""
    if p.kind == "joint_drive" and p.unit == "mm":
        return "joint_drive_prismatic"
    return p.kind


def _kind_unit(kind: str) -> str:
    """The interface unit (mm or deg) of the parameters of a costs-file kind."""
    return "mm" if any(k.endswith("_mm") for k in DEFAULT_COSTS["kinds"][kind]) else "deg"


def cost_set(model: ErrorModel, data: dict | None = None, *, z: float | None = None, source: str = "defaults",
             distribution: str | None = None) -> CostSet:
    """Resolve the cost model and role of every parameter of ``model``.

    Parameters
    ----------
    model : ErrorModel
    data : dict, optional
        Parsed costs file (see the module docstring); merged over :data:`DEFAULT_COSTS` per kind.
    z : float, optional
        Overrides the file's ``z`` (``sigma = t / z``) and its ``distribution`` (then normal).
    distribution : {"normal", "uniform"}, optional
        Overrides the file's ``distribution``; ``uniform`` means ``z = sqrt(3)``.
    """
    data = data or {}
    for key in data:
        if key not in ("z", "distribution", "kinds", "parameters", "processes", "calibration"):  # [calibration]: the split
            raise TolallocError(f"costs {source}: unknown top-level key {key!r}; expected z, distribution, [kinds.*], "
                                "[parameters.*], [processes.*].")
    zz, dist = _z_of(data, z, distribution, source)
    kinds, per = _entries(data, model, source)
    names, role, models, fixed, excluded, specs, merged = [], [], [], [], [], [], {}
    for p in model.params:
        # the section the parameter's entry comes from: its own, or its kind's
        where = (f"costs {source} [parameters.{p.name}]" if p.name in per else
                 f"costs {source} [kinds.{param_kind_key(p)}] ({p.name})")
        base = kinds[param_kind_key(p)]
        own = per.get(p.name, {})
        entry = {key: val for key, val in base.items()
                 if not any(key.startswith(b + "_") and any(x.startswith(b + "_") for x in own) for b in _UNIT_BASES)}
        entry.update(own)
        if entry.get("exclude", False):
            excluded.append(p.name)
            continue
        cm = _cost_model(entry, p, where)
        names.append(p.name)
        models.append(cm)
        specs.append(discrete_spec(entry, p, where))
        merged[p.name] = entry
        if entry.get("fixed", False):
            tol = _value(entry, "tol", p.unit, where)
            role.append("fixed")
            fixed.append(tol if tol is not None else p.sigma * zz)
        else:
            role.append("allocate")
            fixed.append(np.nan)
    if not any(r == "allocate" for r in role):
        raise TolallocError(f"costs {source}: no parameter is left to allocate; un-fix or un-exclude some.")
    procs = read_processes(data, model, names, merged, _cost_model, source)
    specs = [replace(s, processes=procs[nm]) for s, nm in zip(specs, names)]
    return CostSet(tuple(names), tuple(role), tuple(models), tuple(fixed), zz, tuple(excluded), source, dist,
                   tuple(specs))


def _z_of(data: dict, z, distribution, source: str):
    """``(z, distribution)`` from the file, overridden by the ``z`` / ``distribution`` arguments."""
    zz = data.get("z", DEFAULT_COSTS["z"])
    dist = distribution if distribution is not None else data.get("distribution")
    if dist is not None and dist not in ("normal", "uniform"):
        where = "distribution" if distribution is not None else f"costs {source}: distribution"
        raise TolallocError(f"{where} expected 'normal' or 'uniform', got {dist!r}.")
    dist = dist or "normal"
    if dist == "uniform":
        zz = np.sqrt(3.0)
    if z is not None:
        zz, dist = z, "normal"
    raw = zz
    try:
        zz = float(zz) if not isinstance(zz, (bool, str)) else np.nan
    except (TypeError, ValueError):
        zz = np.nan
    if not np.isfinite(zz) or zz <= 0:
        what = "not a number" if np.isnan(zz) else "not > 0" if np.isfinite(zz) else "not finite"
        raise TolallocError(f"costs {source}: z (sigma = t / z) expected a finite number > 0 (e.g. z = 3), got "
                            f"{raw!r} ({what}).")
    return zz, dist


def _entries(data: dict, model: ErrorModel, source: str):
    """Per-kind entries (defaults merged with the file's) and the file's per-parameter entries."""
    for key in ("kinds", "parameters"):
        if not isinstance(data.get(key) or {}, dict):
            raise TolallocError(f"costs {source}: {key} expected tables [{key}.NAME], got {key} = {data[key]!r}.")
    kinds = {k: dict(v) for k, v in DEFAULT_COSTS["kinds"].items()}
    for k, v in (data.get("kinds") or {}).items():
        _check_entry(v, f"costs {source} [kinds.{k}]")
        if k not in kinds:
            raise TolallocError(f"costs {source}: unknown kind [kinds.{k}]; expected one of {', '.join(kinds)}.")
        if "grades" in v:  # named at the kind, not at each parameter that inherits it
            if k != "link_length":
                raise TolallocError(f"costs {source} [kinds.{k}]: grades (ISO 286) apply to link_length parameters "
                                    "only; use classes_<unit> or step_<unit> instead.")
            parse_grades(v["grades"], f"costs {source} [kinds.{k}] grades")
        # a new reference/limit with another unit suffix replaces the default one
        base = {key: val for key, val in kinds[k].items()
                if not any(key.startswith(b + "_") and any(x.startswith(b + "_") for x in v) for b in _UNIT_BASES)}
        _check_values(v, _kind_unit(k), f"{k} tolerances", f"costs {source} [kinds.{k}]")
        kinds[k] = {**base, **v}
    per = data.get("parameters") or {}
    for nm, v in per.items():
        _check_entry(v, f"costs {source} [parameters.{nm}]")
        if nm not in model.names:
            raise TolallocError(f"costs {source} [parameters.{nm}]: unknown error parameter {nm!r}; "
                                f"known: {', '.join(model.names)}.")
        p = model.params[model.index(nm)]
        _check_values(v, p.interface_unit, f"{nm}'s tolerances", f"costs {source} [parameters.{nm}]")
    return kinds, per


def _cost_model(entry: dict, p, where: str) -> CostModel:
    """The cost law and process limits of one parameter's merged entry."""
    form = entry.get("model", "reciprocal")
    if form not in MODELS:
        raise TolallocError(f"{where}: model expected one of {', '.join(MODELS)}, got {form!r}.")
    vals = {k: entry.get(k, d) for k, d in (("a", 0.0), ("b", 1.0), ("k", 1.0))}
    for k, v in vals.items():
        if isinstance(v, (bool, str)) or not isinstance(v, (int, float)):
            raise TolallocError(f"{where}: {k} expected a number, got {v!r}.")
    a, b, kk = float(vals["a"]), float(vals["b"]), float(vals["k"])
    if not (np.isfinite(a) and a >= 0 and np.isfinite(b) and b > 0 and np.isfinite(kk) and kk > 0):
        raise TolallocError(f"{where}: expected a finite fixed cost a >= 0, b > 0 and k > 0 (a part never costs "
                            f"less than nothing), got a={a:g}, b={b:g}, k={kk:g}.")
    t_ref = _value(entry, "t_ref", p.unit, where)
    t_min = _value(entry, "t_min", p.unit, where)
    t_max = _value(entry, "t_max", p.unit, where)
    if t_ref is None or t_min is None or t_max is None:
        raise TolallocError(f"{where}: t_ref, t_min and t_max are required (in {p.interface_unit}).")
    if t_min > t_max:
        raise TolallocError(f"{where}: process limits t_min > t_max ({t_min * p.to_interface:g} > "
                            f"{t_max * p.to_interface:g} {p.interface_unit}); swap them.")
    return CostModel(form, a, b, t_ref, t_min, t_max, kk)


def load_costs(path, model: ErrorModel, *, z: float | None = None, distribution: str | None = None) -> CostSet:
    """Read a costs file (TOML) and resolve it against ``model`` (see :func:`cost_set`)."""
    return cost_set(model, read_costs_file(path), z=z, source=str(path), distribution=distribution)


def read_costs_file(path) -> dict:
    """The parsed TOML of a costs file (a byte-order mark is fine); clear errors for a missing or bad file."""
    path = Path(path)
    if path.is_dir():
        raise TolallocError(f"costs file {str(path)!r} is a directory; give a TOML file (its format: "
                            "docs/howto/costs-file.md).")
    if not path.is_file():
        raise TolallocError(f"costs file {str(path)!r} not found; give a TOML file (its format: docs/howto/costs-file.md).")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))  # a byte-order mark is fine
    except UnicodeDecodeError as exc:
        raise TolallocError(f"costs file {path}: cannot be read as text ({exc}); expected a TOML file.") from None
    except tomllib.TOMLDecodeError as exc:
        raise TolallocError(f"costs file {path}: not valid TOML ({exc}).") from None
    return data
