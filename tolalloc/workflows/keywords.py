"""The keywords a job took before its settings objects: accepted for one more release with a ``DeprecationWarning``
and folded into the objects that now hold them (``allocate_tolerances(seed=3)`` ->
``verification=Verification(seed=3)``), and the reverse, a job's call written with the objects
(:func:`grouped_call`, for a report's "command to reproduce").

``MOVED[job]`` maps each old keyword to ``(new keyword, field)``; a field of None renames the keyword
(``simulate_errors(n=...)`` -> ``n_mc``).
"""

from __future__ import annotations

import warnings
from dataclasses import fields as dataclass_fields

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.workflows import defaults as D
from tolalloc.workflows.checks import check_flag, check_positive, check_values, shown
from tolalloc.workflows.settings import Settings, named_fields

__all__ = ["MOVED", "CLASSES", "SHORT_FIELD", "fold_moved", "field_sources", "grouped_call"]

_MODEL = {k: ("error_model", k) for k in ("sigma_set", "link_mode", "deflection_mode", "clearance",
                                          "clearance_tilt_literal", "sigma", "exclude")}
_ALLOCATION_MODEL = {k: v for k, v in _MODEL.items() if k not in ("sigma", "clearance_tilt_literal")}
#: job -> {old keyword: (keyword that holds it now, its field; None: the keyword renamed)}
MOVED = {
    "allocate_tolerances": {
        "angle_radius_deg": ("requirement", "radius_deg"), "angle_prob": ("requirement", "prob"),
        "poses": ("region", "poses"), "coverage_n": ("region", "coverage_n"),
        "z": ("costs", "z"), "uniform": ("costs", "uniform"), **_ALLOCATION_MODEL,
        "snap": ("solver", "snap"), "angle_step_deg": ("solver", "angle_step_deg"),
        **{k: ("verification", k) for k in ("verify", "seed", "estimator", "correction", "correction_rounds",
                                             "scheduler")}},
    "simulate_errors": {
        "n": ("n_mc", None), "angle_radius_rad": ("angle_radius_deg", None), **_MODEL,
        **{k: ("monte_carlo", k) for k in ("ci", "estimator", "keep_samples", "hist_bins", "hist_range_mm",
                                            "scheduler", "jobs", "chunk_size")}},
    "analyze_errors": dict(_MODEL),
    "plan_calibration": {
        "sigma_set": ("error_model", "sigma_set"),
        **{k: ("measurement", k) for k in ("noise_mm", "noise_deg", "registration")},
        "radius_mm": ("for_allocation", "radius_mm"), "prob": ("for_allocation", "prob")},
    "diagnose_measurements": {
        "register_n": ("test_frame", "register_n"), "register_rows": ("test_frame", "register_rows"),
        "register_update": ("test_frame", "update"),
        **{k: ("fit", k) for k in ("robust_loss", "target_offset_mm", "target_offset_sd_mm",
                                    "instrument_noise_mm")}},
}
#: the object each keyword takes (its class name in tolalloc)
CLASSES = {"requirement": "OrientationRequirement", "region": "Region", "costs": "Costs",
           "error_model": "ErrorModelOptions", "solver": "Solver", "verification": "Verification",
           "monte_carlo": "MonteCarlo", "measurement": "Measurement", "for_allocation": "PositionRequirement",
           "test_frame": "Refit", "fit": "FitOptions"}
#: the field a keyword's short form sets (``region="limits"`` is ``Region(where="limits")``)
SHORT_FIELD = {"region": "where", "costs": "file", "solver": "method", "measurement": "kind"}


def _classes():
    import tolalloc.workflows as W

    return {k: getattr(W, v) for k, v in CLASSES.items()}


def fold_moved(job: str, kwargs: dict) -> dict:
    """``kwargs`` of a call to ``job`` with its old keywords folded into their objects (one ``DeprecationWarning``
    naming them and what replaces them); errors of a folded value name the old keyword."""
    moved = MOVED.get(job, {})
    old = [k for k in kwargs if k in moved]
    if not old:
        return kwargs
    kwargs = dict(kwargs)
    _warn(job, old, moved)
    groups: dict = {}
    for k in old:
        target, field = moved[k]
        value = kwargs.pop(k)
        if field is None:
            if kwargs.get(target) is not None:
                what = ("both give the radii of the rotation error" if k == "angle_radius_rad" else
                        f"both given ({k} is the old name of {target})")
                raise ArgumentError(k, f"{shown(value)} and `{target}` {shown(kwargs[target])} {what}; give {target} "
                                    "only.")
            kwargs[target] = _angle_deg(value) if k == "angle_radius_rad" else value
        else:
            groups.setdefault(target, {})[field] = (k, value)
    for target, items in groups.items():
        fields = {f: v for f, (_, v) in items.items()}
        rename = {f: k for f, (k, _) in items.items()}
        if target in SHORT_FIELD:
            rename.setdefault(SHORT_FIELD[target], target)
        with named_fields("", rename):
            kwargs[target] = _FOLD.get(target, _fold_object)(target, kwargs, fields, rename)
    return kwargs


def field_sources(signature, args: tuple, kwargs: dict, moved: dict) -> dict:
    """``{bare field: the name its refusal shows}`` for one call of a job: ``ClassName.field`` for every field of a
    settings object passed (alone or in a list), the old keyword for a field it set; a name passed as a keyword of
    its own, or a field two objects share, keeps its bare name."""
    try:
        given = signature.bind_partial(*args, **{k: v for k, v in kwargs.items() if k not in moved}).arguments
    except TypeError:  # the call itself fails the same way, with Python's message
        return {}
    owners: dict = {}
    for value in given.values():
        for obj in (value if isinstance(value, (list, tuple)) else [value]):
            if isinstance(obj, Settings):
                for f in dataclass_fields(obj):
                    owners.setdefault(f.name, set()).add(f"{type(obj).__name__}.{f.name}")
    for k in kwargs:
        if k in moved and moved[k][1] is not None:
            owners[moved[k][1]] = {k}
    return {f: next(iter(names)) for f, names in owners.items() if len(names) == 1 and f not in given}


def _warn(job: str, old: list, moved: dict) -> None:
    by_target: dict = {}
    for k in old:
        by_target.setdefault(moved[k][0], []).append(k)
    parts = []
    for target, names in by_target.items():
        fields = [moved[k][1] for k in names if k != "verify"]
        if moved[names[0]][1] is None:
            parts.append(f"{names[0]} -> {target}")
            continue
        if "verify" in names:
            parts.append("verify=False -> verification=False")
        if fields:
            parts.append(f"{', '.join(k for k in names if k != 'verify')} -> {target}=tolalloc.{CLASSES[target]}("
                         + ", ".join(f"{f}=..." for f in fields) + ")")
    warnings.warn(f"{job}(): the keyword(s) {', '.join(old)} are deprecated and go in the next release; use "
                  + "; ".join(parts) + f" (help(tolalloc.{job})).", DeprecationWarning, stacklevel=4)


def _angle_deg(value):
    """``angle_radius_rad`` values (checked as radians) in degrees."""
    rad = check_values(value, "angle_radius_rad", check_positive, "rad", "0.002")
    deg = [float(np.rad2deg(r)) for r in rad]
    return deg if isinstance(value, (list, tuple, np.ndarray)) else deg[0]


def _fold_object(target: str, kwargs: dict, fields: dict, rename: dict):
    """The object of keyword ``target`` (its short form, an object or nothing) with the folded ``fields``."""
    from tolalloc.workflows.settings import as_settings

    cls = _classes()[target]
    short = SHORT_FIELD.get(target)
    base = as_settings(kwargs.get(target), cls, target, None if short is None else (lambda v: cls(**{short: v})))
    return base.replace(**fields)


def _fold_requirement(target, kwargs, fields, rename):
    """The old orientation keywords beside ``radius_mm`` / ``prob``: a list of requirements."""
    from tolalloc.workflows.requirements import OrientationRequirement, PositionRequirement

    if kwargs.get("requirement") is not None:
        first = next(iter(rename.values()))
        raise ArgumentError(first, "and `requirement` both state requirements; give the orientation requirement in "
                            "the requirement list (OrientationRequirement(radius_deg=...)).")
    if "radius_deg" not in fields or fields["radius_deg"] is None:
        if fields.get("prob") is None:
            return None
        raise ArgumentError("angle_prob", f"{shown(fields['prob'])} needs an orientation requirement: add "
                            "`angle_radius_deg` A.")
    with named_fields("", {"radius_mm": "radius_mm", "prob": "prob"}):
        pos = PositionRequirement(*(d if kwargs.get(k) is None else kwargs[k]
                                    for k, d in (("radius_mm", D.RADIUS_MM), ("prob", D.PROB))))
    kwargs.pop("radius_mm", None)
    kwargs.pop("prob", None)
    return [pos, OrientationRequirement(**fields)]


def _fold_verification(target, kwargs, fields, rename):
    from tolalloc.workflows.allocation_settings import Verification

    verify = fields.pop("verify", True)
    check_flag(verify, "verify")
    base = kwargs.get("verification")
    if not verify:
        kwargs.pop("n_mc", None)
        fields["n_mc"] = None
    elif base is None and kwargs.get("n_mc") is not None:
        with named_fields("", {"n_mc": "n_mc"}):
            base = Verification(n_mc=kwargs.pop("n_mc"))
    if isinstance(base, (bool, np.bool_)):
        base = Verification() if base else Verification(n_mc=None)
    return _fold_object(target, {target: base}, fields, rename)


def _fold_monte_carlo(target, kwargs, fields, rename):
    for short in ("n_mc", "seed"):  # the short forms join the object the old keywords built
        if kwargs.get(short) is not None and kwargs.get(target) is None:
            fields[short] = kwargs.pop(short)
            rename[short] = short
    return _fold_object(target, kwargs, fields, rename)


def _fold_for_allocation(target, kwargs, fields, rename):
    """``for_allocation=True`` with the old ``radius_mm`` / ``prob``: a PositionRequirement; without it, values away
    from the defaults are refused (nothing would read them)."""
    from tolalloc.workflows.requirements import PositionRequirement

    value = kwargs.get(target)
    if value is None or value is False:
        for f, v in fields.items():
            if v != getattr(PositionRequirement(), f):
                raise ArgumentError(rename[f], f"{shown(v)} is read only for a plan designed for an allocation, but "
                                    "`for_allocation` is off; add `for_allocation` (or leave out this option).")
        return value
    base = PositionRequirement() if value is True else value
    return _fold_object(target, {target: base}, fields, rename)


def _fold_test_frame(target, kwargs, fields, rename):
    """``test_frame="refit"`` with the old registration keywords: a Refit."""
    from tolalloc.workflows.diagnosis_settings import Refit

    value = kwargs.get(target)
    if value in (None, "same"):
        first = next(iter(rename.values()))
        raise ArgumentError(first, "needs `test_frame` refit: only a test file in another frame is re-registered.")
    return _fold_object(target, {target: Refit() if value == "refit" else value}, fields, rename)


_FOLD = {"requirement": _fold_requirement, "verification": _fold_verification, "monte_carlo": _fold_monte_carlo,
         "for_allocation": _fold_for_allocation, "test_frame": _fold_test_frame}


def _py(v) -> str:
    return repr(float(v)) if isinstance(v, float) else repr(v)


def grouped_call(job: str, positional: list, kw: dict) -> str:
    """The call ``tolalloc.job(*positional, **kw)`` written with the settings objects: ``kw`` in the old flat keywords
    (``seed=3, snap=False``) becomes ``verification=tolalloc.Verification(seed=3), solver=tolalloc.Solver(...)``."""
    moved = MOVED.get(job, {})
    kw = dict(kw)
    groups: dict = {}
    for k in [k for k in kw if k in moved]:
        target, field = moved[k]
        groups.setdefault(target, {})[field] = kw.pop(k)
    args = [_py(v) for v in positional]
    if "requirement" in groups:
        o = groups.pop("requirement")
        req = [f"tolalloc.PositionRequirement(radius_mm={_py(kw.pop('radius_mm', D.RADIUS_MM))}, "
               f"prob={_py(kw.pop('prob', D.PROB))})",
               "tolalloc.OrientationRequirement(" + ", ".join(f"{f}={_py(v)}" for f, v in o.items()) + ")"]
        args.append("requirement=[" + ", ".join(req) + "]")
    verify = groups.get("verification", {}).pop("verify", True)
    if not verify:
        groups["verification"]["n_mc"] = None
        kw.pop("n_mc", None)
    elif "verification" in groups and "n_mc" in kw:
        groups["verification"] = {"n_mc": kw.pop("n_mc"), **groups["verification"]}
    for target in list(groups):
        if target in SHORT_FIELD and target in kw:
            groups[target] = {SHORT_FIELD[target]: kw.pop(target), **groups[target]}
        elif target in kw:  # the object implies its short form (test_frame="refit" for a Refit)
            kw.pop(target)
    for k, v in kw.items():
        args.append(f"{k}={_py(v)}")
    for target, fields in groups.items():
        if fields:
            args.append(f"{target}=tolalloc.{CLASSES[target]}(" + ", ".join(f"{f}={_py(v)}" for f, v in fields.items())
                        + ")")
    return f"tolalloc.{job}(\n    " + ",\n    ".join(args) + ")"
