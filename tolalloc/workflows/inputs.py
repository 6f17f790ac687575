"""What the workflow functions accept, turned into the library's objects, checked once at the entry point.

Robots come as a :class:`~tolalloc.robot.Robot`, a built-in name or a robot file; joint values in interface units
(deg for revolute joints, mm for prismatic ones); measurements as a CSV path or a DataFrame. Every refusal is an
:class:`~tolalloc.exceptions.ArgumentError` naming the keyword argument (the command line shows its flag instead).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError
from tolalloc.robot.io import load_robot
from tolalloc.robot.model import Robot
from tolalloc.units import trusting_units

__all__ = ["trusting_units", "honours_trust_units", "as_robot", "check_probability", "check_positive", "check_count", "check_seed", "check_choice",
           "joint_values", "resolve_poses", "error_model", "sigma_overrides", "resolve_region", "trajectory",
           "as_measurements", "default_pose_set"]


def honours_trust_units(fn):
    """Run workflow ``fn`` with the unit-plausibility guards off when it is called with ``trust_units=True``
    (robot files, joint values, costs files: :mod:`tolalloc.units`)."""
    import functools

    @functools.wraps(fn)
    def run(*args, trust_units: bool = False, **kwargs):
        with trusting_units(bool(trust_units)):
            return fn(*args, trust_units=trust_units, **kwargs)

    return run


def as_robot(robot, *, tool: str | None = None, trust_units: bool = False) -> Robot:
    """A :class:`Robot` from a Robot, a built-in name (``"tool_changer"``, ``"ur10"``) or a robot-file path.

    ``trust_units`` accepts robot-file values that look like a unit slip (see :mod:`tolalloc.units`).
    """
    if not isinstance(robot, (Robot, str, Path)):
        raise ArgumentError("robot", f"expected a Robot, a built-in robot name or a path to a robot file (.toml, DH "
                            f".csv, .urdf), got {type(robot).__name__} {robot!r}.")
    with trusting_units(bool(trust_units)):
        return load_robot(robot, tool=tool)


def _number(value, argument: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ArgumentError(argument, f"expected a number, got {type(value).__name__} {value!r}.")
    return float(value)


def check_probability(value, argument: str, *, example: str = "0.95") -> float:
    """A probability strictly between 0 and 1."""
    x = _number(value, argument)
    if not (np.isfinite(x) and 0 < x < 1):
        raise ArgumentError(argument, f"expected a probability strictly between 0 and 1 (e.g. {example}), got {value!r}.")
    return x


def check_positive(value, argument: str, unit: str, example: str) -> float:
    """A finite number > 0 in ``unit``."""
    x = _number(value, argument)
    if not (np.isfinite(x) and x > 0):
        raise ArgumentError(argument, f"expected a finite number > 0 [{unit}] (e.g. {example}), got {value!r}.")
    return x


def check_count(value, argument: str, *, minimum: int = 1, example: str = "1000000") -> int:
    """A whole number >= ``minimum`` (``1e6`` as a float is accepted when it is whole)."""
    if isinstance(value, (bool, np.bool_)):
        raise ArgumentError(argument, f"expected a whole number >= {minimum} (e.g. {example}), got {value!r}.")
    try:
        whole = float(value) == int(value)
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole or int(value) < minimum:
        raise ArgumentError(argument, f"expected a whole number >= {minimum} (e.g. {example}), got {value!r}.")
    return int(value)


def check_seed(value, argument: str = "seed") -> int:
    """A random seed: a whole number >= 0."""
    return check_count(value, argument, minimum=0, example="0 or 42")


def check_choice(value, argument: str, choices) -> str:
    """One of ``choices``."""
    if value not in choices:
        raise ArgumentError(argument, f"expected one of {', '.join(repr(c) for c in choices)}, got {value!r}.")
    return value


def joint_values(robot: Robot, q_deg_mm, argument: str = "q_deg_mm") -> np.ndarray:
    """Joint values in interface units (deg / mm), shape (n,) or (P, n) or a DataFrame with columns q1..qN,
    checked against count, finiteness and the joint limits; returned in internal units [rad, mm], shape (P, n)."""
    if isinstance(q_deg_mm, pd.DataFrame):
        cols = [f"q{j + 1}" for j in range(robot.n_joints)]
        missing = [c for c in cols if c not in q_deg_mm.columns]
        if missing:
            raise ArgumentError(argument, f"expected a DataFrame with columns {', '.join(cols)} (deg / mm), got "
                                f"columns {list(map(str, q_deg_mm.columns))} (missing {missing}).")
        q_deg_mm = q_deg_mm[cols].to_numpy()
    arr = np.asarray(q_deg_mm, dtype=object)
    if arr.size == 0:
        raise ArgumentError(argument, f"expected joint values of robot {robot.name!r} ({robot.n_joints} per pose, deg "
                            "/ mm), got none.")
    try:
        q = robot.check_q(q_deg_mm, argument, interface=True)
    except ArgumentError:
        raise
    except TolallocError as exc:
        text = str(exc)
        detail = text[len(argument) + 2:] if text.startswith(f"{argument}: ") else text
        raise ArgumentError(argument, detail) from None
    return np.atleast_2d(q)


def default_pose_set(robot: Robot) -> str:
    """``working`` if the robot defines it, else ``nominal``."""
    return "working" if "working" in robot.pose_sets else "nominal"


def resolve_poses(robot: Robot, q_deg_mm=None, poses: str | None = None, *,
                  q_argument: str = "q_deg_mm", poses_argument: str = "poses") -> tuple[str, np.ndarray]:
    """``(label, q (P, n) [rad, mm])`` from explicit joint values or a pose-set name (default: nominal)."""
    if q_deg_mm is not None and poses is not None:
        raise ArgumentError(q_argument, f"give joint values or a pose set ({poses_argument}), not both.")
    if q_deg_mm is not None:
        return "given", joint_values(robot, q_deg_mm, q_argument)
    name = poses or "nominal"
    if not isinstance(name, str):
        raise ArgumentError(poses_argument, f"expected the name of a pose set of robot {robot.name!r} "
                            f"({', '.join(['nominal', *robot.pose_sets])}), got {name!r}.")
    if name != "nominal" and name not in robot.pose_sets:
        raise ArgumentError(poses_argument, f"pose set {name!r} is not defined for robot {robot.name!r}; known sets: "
                            f"{', '.join(['nominal', *robot.pose_sets])}.")
    return name, robot.poses(name)


def sigma_overrides(params, sigma) -> dict:
    """``{parameter or kind: sigma in mm (lengths) or deg (angles)}`` -> ``{parameter: sigma [mm or rad]}``.

    A kind (``joint_drive``) sets every parameter of that kind, each in its own unit; a parameter named as well
    wins over its kind.
    """
    if sigma is None:
        return {}
    if not isinstance(sigma, dict):
        raise ArgumentError("sigma", f"expected a dict {{parameter or kind: sigma in mm or deg}}, got {sigma!r}.")
    by_kind, by_name = {}, {}
    for name, val in sigma.items():
        hits = [p for p in params if name in (p.name, p.kind)]
        if not hits:
            known = ", ".join(sorted({p.name for p in params} | {p.kind for p in params}))
            raise ArgumentError("sigma", f"unknown parameter or kind {name!r}; known: {known}.")
        units = " / ".join(sorted({p.interface_unit for p in hits}))
        try:
            v = float(val)
        except (TypeError, ValueError):
            v = np.nan
        if not np.isfinite(v) or v < 0:
            raise ArgumentError("sigma", f"{name}: expected a finite sigma >= 0 in {units}, got {val!r}.")
        target = by_name if any(p.name == name for p in hits) else by_kind
        for p in hits:
            target[p.name] = v if p.interface_unit == "mm" else np.deg2rad(v)
    return {**by_kind, **by_name}


def error_model(robot: Robot, *, sigma_set=None, link_mode="consistent", deflection_mode="screw", clearance=False,
                exclude=(), sigma=None, clearance_tilt_literal=False):
    """The error model of the workflow options (sigma set, modes, clearance, sigma overrides, exclusions)."""
    from tolalloc.errormodel import build_error_model
    from tolalloc.errormodel.model import CLEARANCE_TILT_LITERAL_RAD

    check_choice(link_mode, "link_mode", ("consistent", "axes_only"))
    check_choice(deflection_mode, "deflection_mode", ("screw", "tilt"))
    if clearance_tilt_literal and not clearance:
        raise ArgumentError("clearance_tilt_literal", "changes the clearance tilt sigma, but clearance is off; add "
                            "`clearance` (or leave out `clearance_tilt_literal`).")
    if isinstance(exclude, str):
        exclude = (exclude,)
    opts = dict(link_mode=link_mode, deflection_mode=deflection_mode, clearance=bool(clearance))
    if sigma is None and not clearance_tilt_literal:
        return build_error_model(robot, sigma_set, **opts, exclude=tuple(exclude))
    base = build_error_model(robot, sigma_set, **opts)
    cs = {"tilt_rad": CLEARANCE_TILT_LITERAL_RAD} if clearance_tilt_literal else None
    return build_error_model(robot, sigma_set, **opts, clearance_sigma=cs,
                             sigma=sigma_overrides(base.params, sigma) or None, exclude=tuple(exclude))


def resolve_region(robot: Robot, region=None, poses: str | None = None):
    """Where an allocation's requirement must hold: ``(label, box Region or None, q (P, n) or None)``.

    ``region``: a pose set of the robot, ``"limits"``, a box of the robot file (``[regions.NAME]``), a
    trajectory CSV path (q1..qN per row, deg / mm) or an array / DataFrame of joint values (deg / mm). Default:
    the robot's ``working`` box if it has one and no ``poses`` are given, else the pose set ``poses``.
    """
    from tolalloc.allocate.region import box_region

    regions = robot.regions
    if region is None:
        if poses is None and "working" in regions:
            region = "working"
        else:
            name = poses if poses is not None else default_pose_set(robot)
            return resolve_poses(robot, None, name)[0], None, resolve_poses(robot, None, name)[1]
    if not isinstance(region, (str, Path)):
        return "trajectory", None, joint_values(robot, region, "region")
    spec = str(region)
    if spec == "limits":
        return spec, box_region(robot, robot.lower, robot.upper, "limits", "region 'limits'"), None
    if spec in regions:
        lo, hi = regions[spec]
        return spec, box_region(robot, lo, hi, spec, f"region {spec!r}"), None
    if spec in robot.pose_sets or spec == "nominal":
        return spec, None, robot.poses(spec)
    if spec.lower().endswith(".csv") or Path(spec).is_file():
        return spec, None, trajectory(robot, spec)
    known = ", ".join(dict.fromkeys(["limits", *regions, "nominal", *robot.pose_sets]))
    raise ArgumentError("region", f"{spec!r} is neither a region, a pose set nor a trajectory CSV file; known: "
                        f"{known}, or give a path to a .csv file.")


def trajectory(robot: Robot, path) -> np.ndarray:
    """Rows q1..qN [deg / mm] of a CSV file (header line optional) -> (P, n) [rad, mm]."""
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"region {str(path)!r}: no such trajectory file; give a CSV with one pose (q1..qN, "
                             "deg / mm) per row.")
    try:
        rows = np.genfromtxt(p, delimiter=",", dtype=float, skip_header=0)
    except ValueError as exc:
        raise ArgumentError("region", f"{str(path)!r}: cannot read the trajectory ({exc}); expected "
                            f"{robot.n_joints} comma-separated numbers per row.") from None
    rows = np.atleast_2d(rows)
    if rows.size and np.all(np.isnan(rows[0])):  # a header line
        rows = rows[1:]
    if rows.ndim != 2 or rows.shape[0] == 0 or rows.shape[1] != robot.n_joints:
        raise ArgumentError("region", f"{str(path)!r}: expected rows of {robot.n_joints} joint values (deg / mm), "
                            f"got shape {rows.shape}.")
    if not np.all(np.isfinite(rows)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(rows), axis=1))[0]) + 1
        raise ArgumentError("region", f"{str(path)!r}: row {bad} has a missing or non-finite value; every joint "
                            "value must be a finite number (deg / mm).")
    return robot.check_q(rows, f"region {str(path)!r}", interface=True)


def as_measurements(data, robot: Robot, argument: str):
    """Measurements from a CSV path or a DataFrame (columns q1..qN in deg / mm, x_mm, y_mm, z_mm, optional ones)."""
    from tolalloc.diagnose import measurements_from_frame, read_measurements

    if isinstance(data, pd.DataFrame):
        return measurements_from_frame(data, robot, f"{argument} (DataFrame)")
    if isinstance(data, (str, Path)):
        if not Path(data).exists():
            raise InputFileError(f"measurement file {str(data)!r} does not exist; expected a CSV with columns "
                                 "q1..qN, x_mm, y_mm, z_mm.")
        return read_measurements(data, robot)
    raise ArgumentError(argument, f"expected a CSV path or a pandas DataFrame with columns q1..qN (deg / mm), x_mm, "
                        f"y_mm, z_mm, got {type(data).__name__}.")
