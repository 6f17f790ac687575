"""Building an :class:`~tolalloc.errormodel.model.ErrorModel` from a robot: parameter list, sigma sets, distributions."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.units import ALL_UNITS, LENGTH_UNITS
from tolalloc.robot.model import Robot
from tolalloc.errormodel.model import (CLEARANCE_SIGMA, GENERIC_SIGMA, KINDS, ErrorModel, ErrorParameter,
                                       perpendicular_axes)

__all__ = ["build_error_model"]


def build_error_model(
    robot: Robot,
    sigma_set: str | None = None,
    *,
    link_mode: str = "consistent",
    deflection_mode: str = "screw",
    clearance: bool = False,
    clearance_sigma: dict | None = None,
    sigma: dict | None = None,
    exclude: tuple = (),
    distribution: str | dict = "normal",
) -> ErrorModel:
    """Build the error model of a robot.

    Parameters
    ----------
    robot : Robot
    sigma_set : str, optional
        A set from the robot file (``table2`` is the tool_changer's default) or ``generic``;
        default: the robot file's first set, else ``generic``.
    link_mode : {"consistent", "axes_only"}
        ``axes_only`` is the paper-literal Eq. 24.
    deflection_mode : {"screw", "tilt"}
        ``tilt`` is the paper's Eqs. 32/37 reading.
    clearance : bool
        Add joint clearance parameters (axial, radial ring, tilt) to every revolute joint.
    clearance_sigma : dict, optional
        Keys ``axial_mm``, ``radial_mm``, ``tilt_rad`` (default :data:`CLEARANCE_SIGMA`).
    sigma : dict, optional
        Overrides: parameter name or kind -> sigma [mm or rad].
    exclude : tuple of str
        Parameter names or kinds to leave out.
    distribution : str or dict
        ``normal`` (default), ``uniform`` or ``truncnormal``; a dict maps names or kinds to one.
    """
    if link_mode not in ("consistent", "axes_only"):
        raise TolallocError(f"link_mode: expected 'consistent' or 'axes_only' (paper-literal), got {link_mode!r}.")
    if deflection_mode not in ("screw", "tilt"):
        raise TolallocError(f"deflection_mode: expected 'screw' or 'tilt', got {deflection_mode!r}.")
    params = _geometric_params(robot, link_mode, deflection_mode)
    if clearance:
        params += _clearance_params(robot, {**CLEARANCE_SIGMA, **(clearance_sigma or {})})
    names = [p.name for p in params]
    dup = sorted({x for x in names if names.count(x) > 1})
    if dup:
        raise TolallocError(f"robot {robot.name!r}: error parameter names clash ({dup}); rename the links so that 'd'+link name differs from the drive names dth<j>/dd<j>.")
    for item in exclude:
        if item not in names and item not in KINDS:
            raise TolallocError(f"exclude: {item!r} is neither a parameter ({', '.join(names)}) nor a kind ({', '.join(KINDS)}).")
    if sigma_set is None:
        sigma_set = next(iter(robot.sigma_sets), "generic")
    # sigma of the full parameter list first, so that a set naming an excluded parameter stays valid
    geo = [p for p in params if not p.kind.startswith("clearance")]
    geo_sigma = dict(zip([p.name for p in geo], _sigma_from_set(robot, geo, sigma_set)))
    params = [p for p in params if p.name not in exclude and p.kind not in exclude]
    if not params:
        raise TolallocError(f"exclude: {', '.join(exclude)} leaves no error parameter of robot {robot.name!r}; "
                            "expected at least one left: exclude fewer parameters or kinds.")
    out = [_with_sigma_and_distribution(p, geo_sigma.get(p.name, p.sigma), sigma, distribution) for p in params]
    if sigma:
        unknown = [k for k in sigma if k not in names and k not in KINDS]
        if unknown:
            raise TolallocError(f"sigma: unknown parameter or kind {unknown}; known parameters: {', '.join(names)}.")
    return ErrorModel(robot, tuple(out), link_mode, deflection_mode, sigma_set)


def _geometric_params(robot: Robot, link_mode: str, deflection_mode: str) -> list[ErrorParameter]:
    """Link-length, joint-drive and axis-deflection parameters (sigma not yet set), in the model's order."""
    n = robot.n_joints
    params: list[ErrorParameter] = []
    for link, site in zip(robot.links, robot.link_sites):
        if link.length_mm == 0:
            continue
        twist = np.concatenate([np.zeros(3), link.direction])
        undo = n if link_mode == "axes_only" else None
        params.append(ErrorParameter(f"d{link.name}", "link_length", link.name, "mm", int(site), twist, undo))
    for j, joint in enumerate(robot.joints):
        tag = f"dth{j + 1}" if joint.is_revolute else f"dd{j + 1}"
        params.append(ErrorParameter(tag, "joint_drive", joint.name, "rad" if joint.is_revolute else "mm", j,
                                     robot.screws[j].copy(), joint_index=j))
    for j, joint in enumerate(robot.joints):
        if not joint.is_revolute:
            continue
        pt = robot.joint_points_mm[j]
        for letter, e in perpendicular_axes(joint.axis):
            twist = np.concatenate([e, -np.cross(e, pt)])
            undo = j + 1 if deflection_mode == "tilt" else None
            params.append(ErrorParameter(f"e{j + 1}{letter}", "axis_deflection", joint.name, "rad", j, twist, undo))
    return params


def _clearance_params(robot: Robot, cs: dict) -> list[ErrorParameter]:
    """Clearance parameters of every revolute joint: axial slip, radial ring pair, tilt pair (sigma from ``cs``)."""
    params = []
    for j, joint in enumerate(robot.joints):
        if not joint.is_revolute:
            continue
        pt = robot.joint_points_mm[j]
        w = joint.axis
        params.append(ErrorParameter(f"ca{j + 1}", "clearance_axial", joint.name, "mm", j,
                                     np.concatenate([np.zeros(3), w]), sigma=cs["axial_mm"]))
        perp = perpendicular_axes(w)
        for letter, e in perp:
            params.append(ErrorParameter(f"cr{j + 1}{letter}", "clearance_radial", joint.name, "mm", j,
                                         np.concatenate([np.zeros(3), e]), sigma=cs["radial_mm"] / np.sqrt(2),
                                         distribution="ring", group=f"cr{j + 1}"))
        for letter, e in perp:
            params.append(ErrorParameter(f"cw{j + 1}{letter}", "clearance_tilt", joint.name, "rad", j,
                                         np.concatenate([e, -np.cross(e, pt)]), sigma=cs["tilt_rad"]))
    return params


def _with_sigma_and_distribution(p: ErrorParameter, s, sigma: dict | None, distribution: str | dict) -> ErrorParameter:
    """``p`` with its final sigma (default ``s``, overridden by kind then name in ``sigma``) and distribution."""
    if sigma:
        for key in (p.kind, p.name):
            if key in sigma:
                s = sigma[key]
    try:
        s = float(s)
    except (TypeError, ValueError):
        raise TolallocError(f"sigma of {p.name}: expected a number, got {s!r}.") from None
    if not np.isfinite(s) or s < 0:
        raise TolallocError(f"sigma of {p.name}: expected a finite value >= 0 [{p.unit}], got {s!r}.")
    dist = p.distribution
    if p.distribution != "ring":
        dist = distribution if isinstance(distribution, str) else distribution.get(p.name, distribution.get(p.kind, "normal"))
        if dist not in ("normal", "uniform", "truncnormal"):
            raise TolallocError(f"distribution of {p.name}: expected normal, uniform or truncnormal, got {dist!r}.")
    return replace(p, sigma=s, distribution=dist)


def _sigma_from_set(robot: Robot, params: list, sigma_set: str) -> np.ndarray:
    """Standard deviations [internal units] of ``params`` from a named set of the robot file or ``generic``."""
    names = [p.name for p in params]
    if sigma_set == "generic":
        out = []
        for p in params:
            if p.kind == "joint_drive":
                key = "joint_drive_" + ("revolute" if p.unit == "rad" else "prismatic")
                out.append(GENERIC_SIGMA[key])
            else:
                out.append(GENERIC_SIGMA.get(p.kind, 0.0))
        return np.array(out)
    if sigma_set not in robot.sigma_sets:
        known = ", ".join(["generic", *robot.sigma_sets])
        raise TolallocError(f"unknown sigma set {sigma_set!r} for robot {robot.name!r}; known: {known}.")
    entry = robot.sigma_sets[sigma_set]
    factors = {f"sigma_{u}": ("mm" if u in LENGTH_UNITS else "rad", f) for u, f in ALL_UNITS.items()}
    where = f"sigma set {sigma_set!r}"
    sigma = np.full(len(params), np.nan)
    for key, table in entry.items():
        if key == "description":
            continue
        if key not in factors:
            raise TolallocError(f"{where}: unknown key {key!r}; expected {', '.join(factors)}.")
        if not isinstance(table, dict):
            raise TolallocError(f"{where}: {key} expected a table {{ name = sigma, ... }} such as "
                                f"{key} = {{ {names[0]} = 0.01 }}, got {table!r}.")
        unit, f = factors[key]
        for name, value in table.items():
            if name not in names:
                raise TolallocError(f"{where}: unknown error parameter {name!r}; known: {', '.join(names)}.")
            p = params[names.index(name)]
            if p.unit != unit:
                raise TolallocError(f"{where}: {name} is in {p.interface_unit}, but was given under {key}.")
            try:
                v = float(value)
            except (TypeError, ValueError):
                v = np.nan
            if isinstance(value, bool) or not np.isfinite(v) or v < 0:
                raise TolallocError(f"{where}: {key}.{name} expected a finite sigma >= 0 in {key[6:]}, got {value!r}.")
            sigma[names.index(name)] = v * f
    missing = [nm for nm, s in zip(names, sigma) if np.isnan(s)]
    if missing:
        raise TolallocError(f"{where} has no sigma for {', '.join(missing)}; give one for each "
                            "(sigma_mm for lengths, sigma_deg for angles).")
    return sigma
