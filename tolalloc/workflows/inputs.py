"""What the workflow functions accept, turned into the library's objects, checked once at the entry point.

Robots come as a :class:`~tolalloc.robot.Robot`, a built-in name or a robot file; joint values in interface units
(deg for revolute joints, mm for prismatic ones); measurements as a CSV path or a DataFrame. Every refusal is an
:class:`~tolalloc.exceptions.ArgumentError` naming the keyword argument (the command line shows its flag instead).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError, describe, known_names, whole_number
from tolalloc.robot.io import load_robot
from tolalloc.robot.model import Robot

__all__ = ["honours_trust_units", "as_robot", "check_probability", "check_positive", "check_count", "check_seed",
           "check_choice", "check_flag", "check_optional_flag", "check_name", "check_names", "check_path",
           "check_scheduler", "check_model_options", "check_values", "check_z", "check_costs_file", "Z_RANGE", "shown", "RANGES", "joint_values", "resolve_poses", "error_model", "sigma_overrides", "resolve_region", "trajectory",
           "as_measurements", "default_pose_set"]


def honours_trust_units(fn):
    """Run workflow ``fn`` with the unit-plausibility guards off when it is called with ``trust_units=True``
    (robot files, joint values, costs files: :mod:`tolalloc.units`)."""
    import functools

    from tolalloc.units import trusting_units

    @functools.wraps(fn)
    def run(*args, trust_units: bool = False, **kwargs):
        check_flag(trust_units, "trust_units")
        with trusting_units(bool(trust_units)):
            return fn(*args, trust_units=trust_units, **kwargs)

    return run


def shown(value, limit: int = 60) -> str:
    """What arrived, for a message (see :func:`tolalloc.exceptions.describe`)."""
    return describe(value, limit)


def as_robot(robot, *, tool: str | None = None, trust_units: bool = False) -> Robot:
    """A :class:`Robot` from a Robot, a built-in name (``"tool_changer"``, ``"ur10"``) or a robot-file path.

    ``trust_units`` accepts robot-file values that look like a unit slip (see :mod:`tolalloc.units`).
    """
    from tolalloc.units import trusting_units

    if not isinstance(robot, (Robot, str, os.PathLike)) or (isinstance(robot, str) and not robot.strip()):
        raise ArgumentError("robot", f"expected a Robot, a built-in robot name or a path to a robot file (.toml, DH "
                            f".csv, .urdf), got {shown(robot)}.")
    if "\0" in str(robot if not isinstance(robot, Robot) else ""):
        raise ArgumentError("robot", f"expected a built-in robot name or a path to a robot file, got {shown(robot)} "
                            "(it holds a NUL character).")
    check_name(tool, "tool", "the URDF tool link (a link name of the URDF file)")
    check_flag(trust_units, "trust_units")
    with trusting_units(bool(trust_units)):
        return load_robot(robot, tool=tool)


def _number(value, argument: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ArgumentError(argument, f"expected a number, got {shown(value)}.")
    try:
        return float(value)
    except OverflowError:  # an int beyond the float range
        return float("inf") if value > 0 else float("-inf")


def check_values(value, argument: str, check, *args, **kwargs) -> list:
    """A number or a flat sequence of numbers, each checked by ``check(x, argument, *args, **kwargs)``."""
    if isinstance(value, (list, tuple, np.ndarray, pd.Series)):
        items = list(np.ravel(np.asarray(value, dtype=object))) if not isinstance(value, (list, tuple)) else list(value)
        if any(isinstance(v, (list, tuple, np.ndarray, pd.Series, dict)) for v in items):
            raise ArgumentError(argument, f"expected a number or a flat list of numbers, got {shown(value)}.")
        return [check(v, argument, *args, **kwargs) for v in items]
    return [check(value, argument, *args, **kwargs)]


def check_probability(value, argument: str, *, example: str = "0.95") -> float:
    """A probability strictly between 0 and 1."""
    x = _number(value, argument)
    if not (np.isfinite(x) and 0 < x < 1):
        raise ArgumentError(argument, f"expected a probability strictly between 0 and 1 (e.g. {example}), got {value!r}.")
    return x


#: Ranges of radii, noise levels and steps ``(smallest, largest)`` in each unit: beyond them a tolerance problem
#: is not physical (a nanometre .. a kilometre, a nano-degree .. one turn) and its squares under- or overflow.
RANGES = {"mm": (1e-6, 1e6), "deg": (1e-9, 360.0), "rad": (np.deg2rad(1e-9), 2 * np.pi)}


def check_positive(value, argument: str, unit: str, example: str) -> float:
    """A finite number > 0 in ``unit`` (``mm``, ``deg`` or ``rad``), within that unit's :data:`RANGES`."""
    x = _number(value, argument)
    if not (np.isfinite(x) and x > 0):
        raise ArgumentError(argument, f"expected a finite number > 0 [{unit}] (e.g. {example}), got {value!r}.")
    lo, hi = RANGES.get(unit, (0.0, np.inf))
    if not lo <= x <= hi:
        raise ArgumentError(argument, f"expected a number between {lo:.3g} and {hi:.3g} {unit} (e.g. {example}), got "
                            f"{value!r}.")
    return x


def check_count(value, argument: str, *, minimum: int = 1, example: str = "1000000", maximum: int | None = None) -> int:
    """A whole number >= ``minimum`` (and <= ``maximum``); ``1e6`` as a float is accepted when it is whole."""
    want = f"a whole number >= {minimum}" + ("" if maximum is None else f" and <= {maximum}")
    n = whole_number(value)
    if n is None or n < minimum or (maximum is not None and n > maximum):
        raise ArgumentError(argument, f"expected {want} (e.g. {example}), got {shown(value)}.")
    return n


def check_seed(value, argument: str = "seed") -> int:
    """A random seed: a whole number >= 0 (numpy takes seeds below 2**128)."""
    return check_count(value, argument, minimum=0, example="0 or 42", maximum=2**128 - 1)


def check_choice(value, argument: str, choices) -> str:
    """One of ``choices`` (strings)."""
    if not isinstance(value, str) or value not in choices:
        raise ArgumentError(argument, f"expected one of {', '.join(repr(c) for c in choices)}, got {shown(value)}.")
    return str(value)


def check_flag(value, argument: str) -> bool:
    """``True`` or ``False`` (a numpy bool too); anything else is refused rather than read by its truth value."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ArgumentError(argument, f"expected True or False, got {shown(value)}.")


def check_optional_flag(value, argument: str) -> bool | None:
    """``None`` (automatic), ``True`` or ``False``."""
    return None if value is None else check_flag(value, argument)


def check_name(value, argument: str, what: str, known=None) -> str | None:
    """``None`` or a non-empty string (one of ``known`` if given: a list of names offered in the message)."""
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip():
        extra = f" ({known_names(known)})" if known else ""
        raise ArgumentError(argument, f"expected {what}{extra} as a string, got {shown(value)}.")
    if known is not None and value not in known:
        raise ArgumentError(argument, f"unknown {what} {value!r}; known: {known_names(known)}.")
    return str(value)


def check_names(value, argument: str, what: str) -> tuple:
    """A name or a list / tuple of names (strings) -> tuple of str."""
    if isinstance(value, str):
        value = (value,)
    if not isinstance(value, (list, tuple, set, frozenset)) or not all(isinstance(v, str) and v.strip() for v in value):
        raise ArgumentError(argument, f"expected {what}: a name or a list of names, e.g. ('dl1', 'axis_deflection'), "
                            f"got {shown(value)}.")
    return tuple(dict.fromkeys(value))


def check_path(value, argument: str, what: str) -> Path | None:
    """``None`` or a path (str or os.PathLike) to an input file."""
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)) or not str(value).strip() or "\0" in str(value):
        raise ArgumentError(argument, f"expected a path to {what} (a str or pathlib.Path), got {shown(value)}.")
    return Path(value)


#: sigma = t / z: smallest and largest z (a tolerance of 1/100 .. 100 standard deviations)
Z_RANGE = (1e-2, 1e2)


def check_z(value, argument: str = "z") -> float:
    """``z`` of sigma = t / z, a number within :data:`Z_RANGE`."""
    x = np.nan if isinstance(value, (bool, np.bool_)) else _number(value, argument)
    if not (np.isfinite(x) and Z_RANGE[0] <= x <= Z_RANGE[1]):
        raise ArgumentError(argument, f"expected a number > 0 (sigma = t / z, e.g. 3) between {Z_RANGE[0]:g} and "
                            f"{Z_RANGE[1]:g}, got {shown(value)}.")
    return x


def check_costs_file(path, argument: str = "costs") -> Path | None:
    """``None`` or the path of a readable TOML costs file whose ``z`` (if any) lies within :data:`Z_RANGE`; its
    other keys are checked by :func:`tolalloc.allocate.costs.load_costs`."""
    import tomllib

    path = check_path(path, argument, "a costs file (TOML)")
    if path is None or not path.is_file():
        return path  # a missing file or a directory: the costs loader says which
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError, OSError) as exc:
        raise ArgumentError(argument, f"{str(path)!r} is not a valid TOML costs file ({exc}); expected tables such as "
                            "[kinds.link_length] with a, b, t_ref_mm, t_min_mm, t_max_mm (see tolalloc.allocate.costs)."
                            ) from None
    z = data.get("z")
    if isinstance(z, (int, float)) and not isinstance(z, bool) and not Z_RANGE[0] <= z <= Z_RANGE[1]:
        raise ArgumentError(argument, f"{str(path)!r}: z = {z!r} (sigma = t / z) is outside {Z_RANGE[0]:g} .. "
                            f"{Z_RANGE[1]:g}; expected a number such as z = 3.")
    return path


def check_scheduler(value, argument: str = "scheduler"):
    """Where Monte Carlo samples run (see :func:`tolalloc.montecarlo.parallel.check_scheduler`)."""
    if value is not None and not isinstance(value, str) and not hasattr(value, "submit"):
        raise ArgumentError(argument, f"expected None (local threads), 'threads', 'processes', a Dask scheduler "
                            f"address such as 'tcp://10.0.0.5:8786' or a distributed.Client, got {shown(value)}.")
    from tolalloc.montecarlo.parallel import check_scheduler as check

    try:
        return check(value)
    except ArgumentError:
        raise
    except TolallocError as exc:
        text = str(exc)
        raise ArgumentError(argument, text[len(argument) + 2:] if text.startswith(argument + ": ") else text) from None


def joint_values(robot: Robot, q_deg_mm, argument: str = "q_deg_mm") -> np.ndarray:
    """Joint values in interface units (deg / mm), shape (n,) or (P, n) or a DataFrame with columns q1..qN,
    checked against count, finiteness, unit slips (:func:`tolalloc.units.check_joint_units`) and the joint limits;
    returned in internal units [rad, mm], shape (P, n)."""
    want = f"{robot.n_joints} per pose, deg / mm"
    if isinstance(q_deg_mm, pd.DataFrame):
        cols = [f"q{j + 1}" for j in range(robot.n_joints)]
        names = [str(c) for c in q_deg_mm.columns]
        missing = [c for c in cols if c not in names]
        repeated = sorted({c for c in cols if names.count(c) > 1})
        if missing or repeated:
            what = f"missing {missing}" if missing else f"repeated {repeated}"
            raise ArgumentError(argument, f"expected a DataFrame with columns {', '.join(cols)} (deg / mm), each "
                                f"once, got columns {names} ({what}).")
        q_deg_mm = q_deg_mm.set_axis(names, axis=1)[cols].to_numpy()
    elif isinstance(q_deg_mm, (str, bytes, dict)) or not hasattr(q_deg_mm, "__len__") and not np.isscalar(q_deg_mm) \
            and not isinstance(q_deg_mm, np.ndarray):
        raise ArgumentError(argument, f"expected joint values of robot {robot.name!r} ({want}): a list, an array of "
                            f"shape (n,) or (P, n) or a DataFrame with columns q1..qN, got {shown(q_deg_mm)}.")
    try:
        arr = np.asarray(q_deg_mm, dtype=object)
    except ValueError:
        arr = None
    if arr is None or arr.ndim > 2 or any(isinstance(v, (list, tuple, np.ndarray)) for v in np.ravel(arr)):
        raise ArgumentError(argument, f"expected joint values of robot {robot.name!r} ({want}) as a list or an "
                            f"array of shape (n,) or (P, n), got {shown(q_deg_mm)} (ragged or nested deeper).")
    if arr.size == 0:
        raise ArgumentError(argument, f"expected joint values of robot {robot.name!r} ({want}), got none.")
    if any(isinstance(v, (bool, np.bool_, str, bytes)) for v in np.ravel(arr)):
        raise ArgumentError(argument, f"expected numbers ({want}), got {shown(q_deg_mm)}.")
    try:
        q = robot.check_q(arr, argument, interface=True)
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
    known = known_names(["nominal"], robot.pose_sets)
    if poses is not None and (not isinstance(poses, str) or not poses):
        raise ArgumentError(poses_argument, f"expected the name of a pose set of robot {robot.name!r} ({known}), got "
                            f"{shown(poses)}.")
    name = poses or "nominal"
    if name != "nominal" and name not in robot.pose_sets:
        raise ArgumentError(poses_argument, f"pose set {name!r} is not defined for robot {robot.name!r}; known sets: "
                            f"{known}.")
    return name, robot.poses(name)


def sigma_overrides(params, sigma) -> dict:
    """``{parameter or kind: sigma in mm (lengths) or deg (angles)}`` -> ``{parameter: sigma [mm or rad]}``.

    A kind (``joint_drive``) sets every parameter of that kind, each in its own unit; a parameter named as well
    wins over its kind.
    """
    if sigma is None:
        return {}
    if not isinstance(sigma, dict):
        raise ArgumentError("sigma", f"expected a dict {{parameter or kind: sigma in mm or deg}}, got {shown(sigma)}.")
    by_kind, by_name = {}, {}
    for name, val in sigma.items():
        hits = [p for p in params if isinstance(name, str) and name in (p.name, p.kind)]
        if not hits:
            known = known_names([p.name for p in params], [p.kind for p in params])
            raise ArgumentError("sigma", f"unknown parameter or kind {name!r}; known: {known}.")
        units = " / ".join(sorted({p.interface_unit for p in hits}))
        try:
            v = np.nan if isinstance(val, (bool, np.bool_, str)) else float(val)
        except (TypeError, ValueError, OverflowError):
            v = np.nan
        if not np.isfinite(v) or v < 0:
            raise ArgumentError("sigma", f"{name}: expected a finite sigma >= 0 in {units}, got {val!r}.")
        target = by_name if any(p.name == name for p in hits) else by_kind
        for p in hits:
            target[p.name] = v if p.interface_unit == "mm" else np.deg2rad(v)
    return {**by_kind, **by_name}


def check_model_options(*, sigma_set=None, link_mode="consistent", deflection_mode="screw", clearance=False,
                        exclude=(), sigma=None, clearance_tilt_literal=False) -> tuple:
    """Check the error-model options that need no robot; returns ``exclude`` as a tuple of names."""
    check_name(sigma_set, "sigma_set", "the name of a sigma set of the robot file (or 'generic')")
    check_choice(link_mode, "link_mode", ("consistent", "axes_only"))
    check_choice(deflection_mode, "deflection_mode", ("screw", "tilt"))
    check_flag(clearance, "clearance")
    check_flag(clearance_tilt_literal, "clearance_tilt_literal")
    if clearance_tilt_literal and not clearance:
        raise ArgumentError("clearance_tilt_literal", "changes the clearance tilt sigma, but clearance is off; add "
                            "`clearance` (or leave out `clearance_tilt_literal`).")
    if sigma is not None and not isinstance(sigma, dict):
        raise ArgumentError("sigma", f"expected a dict {{parameter or kind: sigma in mm or deg}}, got {shown(sigma)}.")
    return check_names(exclude, "exclude", "parameters or kinds to leave out")


def error_model(robot: Robot, *, sigma_set=None, link_mode="consistent", deflection_mode="screw", clearance=False,
                exclude=(), sigma=None, clearance_tilt_literal=False):
    """The error model of the workflow options (sigma set, modes, clearance, sigma overrides, exclusions)."""
    from tolalloc.errormodel import build_error_model
    from tolalloc.errormodel.model import CLEARANCE_TILT_LITERAL_RAD

    exclude = check_model_options(sigma_set=sigma_set, link_mode=link_mode, deflection_mode=deflection_mode,
                                  clearance=clearance, exclude=exclude, sigma=sigma,
                                  clearance_tilt_literal=clearance_tilt_literal)
    check_name(sigma_set, "sigma_set", f"sigma set of robot {robot.name!r}",
               known=list(dict.fromkeys(["generic", *robot.sigma_sets])))
    opts = dict(link_mode=link_mode, deflection_mode=deflection_mode, clearance=bool(clearance))
    base = build_error_model(robot, sigma_set, **opts)
    known = [p.name for p in base.params] + list(dict.fromkeys(p.kind for p in base.params))
    unknown = [e for e in exclude if e not in known]
    if unknown:
        raise ArgumentError("exclude", f"{unknown[0]!r} is neither an error parameter nor a kind of robot "
                            f"{robot.name!r}; known: {known_names(known)}.")
    if all(p.name in exclude or p.kind in exclude for p in base.params):
        raise ArgumentError("exclude", f"{', '.join(exclude)} leaves no error parameter of robot {robot.name!r}; "
                            "expected at least one left: exclude fewer parameters or kinds.")
    if sigma is None and not clearance_tilt_literal:
        return base if not exclude else build_error_model(robot, sigma_set, **opts, exclude=exclude)
    cs = {"tilt_rad": CLEARANCE_TILT_LITERAL_RAD} if clearance_tilt_literal else None
    return build_error_model(robot, sigma_set, **opts, clearance_sigma=cs,
                             sigma=sigma_overrides(base.params, sigma) or None, exclude=exclude)


def resolve_region(robot: Robot, region=None, poses: str | None = None):
    """Where an allocation's requirement must hold: ``(label, box Region or None, q (P, n) or None)``.

    ``region``: a pose set of the robot, ``"limits"``, a box of the robot file (``[regions.NAME]``), a
    trajectory CSV path (q1..qN per row, deg / mm) or an array / DataFrame of joint values (deg / mm). Default:
    the robot's ``working`` box if it has one and no ``poses`` are given, else the pose set ``poses``.
    """
    regions = robot.regions
    if region is None:
        if poses is None and "working" in regions:
            region = "working"
        else:
            name = poses if poses is not None else default_pose_set(robot)
            return resolve_poses(robot, None, name)[0], None, resolve_poses(robot, None, name)[1]
    if not isinstance(region, (str, os.PathLike)):
        return "trajectory", None, joint_values(robot, region, "region")
    spec = str(region)
    if spec == "limits":
        return spec, _box(robot, robot.lower, robot.upper, spec), None
    if spec in regions:
        lo, hi = regions[spec]
        return spec, _box(robot, lo, hi, spec), None
    if spec in robot.pose_sets or spec == "nominal":
        return spec, None, robot.poses(spec)
    if spec.lower().endswith(".csv") or Path(spec).is_file():
        return spec, None, trajectory(robot, spec)
    known = known_names(["limits"], regions, ["nominal"], robot.pose_sets)
    raise ArgumentError("region", f"{spec!r} is neither a region, a pose set nor a trajectory CSV file; known: "
                        f"{known}, or give a path to a .csv file.")


def _box(robot: Robot, lo, hi, name: str):
    """A box region of the robot, its refusal an :class:`ArgumentError` of ``region``."""
    from tolalloc.allocate.region import box_region

    try:
        return box_region(robot, lo, hi, name, f"region {name!r}")
    except ArgumentError:
        raise
    except TolallocError as exc:
        raise ArgumentError("region", str(exc)[len("region "):]) from None


def trajectory(robot: Robot, path) -> np.ndarray:
    """Rows q1..qN [deg / mm] of a CSV file (header line optional) -> (P, n) [rad, mm]."""
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"region {str(path)!r}: no such trajectory file; give a CSV with one pose (q1..qN, "
                             "deg / mm) per row.")
    try:
        rows = np.genfromtxt(p, delimiter=",", dtype=float, skip_header=0)
    except (ValueError, OSError, UnicodeDecodeError) as exc:
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
    try:
        return robot.check_q(rows, f"{str(path)!r}", interface=True)
    except TolallocError as exc:
        raise ArgumentError("region", str(exc)) from None


def as_measurements(data, robot: Robot, argument: str):
    """Measurements from a CSV path or a DataFrame (columns q1..qN in deg / mm, x_mm, y_mm, z_mm, optional ones).

    The joint values are checked for unit slips first (:func:`tolalloc.units.check_joint_units`, the rule of every
    joint-value input), then read and checked by :mod:`tolalloc.diagnose.measurements`.
    """
    from tolalloc.diagnose import measurements_from_frame, read_measurements

    want = "a CSV path or a pandas DataFrame with columns q1..qN (deg / mm), x_mm, y_mm, z_mm"
    if isinstance(data, pd.DataFrame):
        names = [str(c).strip() for c in data.columns]
        repeated = sorted({c for c in names if names.count(c) > 1})
        if repeated:
            raise ArgumentError(argument, f"expected {want}, each column once, got the column(s) {repeated} more "
                                "than once; drop or rename the copies.")
        _measured_joint_units(data, robot, argument, "DataFrame")
        return measurements_from_frame(data, robot, f"{argument} (DataFrame)")
    if isinstance(data, (str, os.PathLike)) and str(data).strip() and "\0" not in str(data):
        if not Path(data).exists():
            raise InputFileError(f"measurement file {str(data)!r} does not exist; expected a CSV with columns "
                                 "q1..qN, x_mm, y_mm, z_mm.")
        cols = {f"q{j + 1}" for j in range(robot.n_joints)}
        try:  # the joint columns only; a file that cannot be read gets the reader's message below
            frame = pd.read_csv(data, usecols=lambda c: str(c).strip() in cols, skipinitialspace=True,
                                encoding="utf-8-sig")
        except (ValueError, OSError, UnicodeDecodeError):
            frame = None
        if frame is not None:
            _measured_joint_units(frame, robot, argument, repr(str(data)))
        return read_measurements(data, robot)
    raise ArgumentError(argument, f"expected {want}, got {shown(data)}.")


def _measured_joint_units(frame: pd.DataFrame, robot: Robot, argument: str, source: str) -> None:
    """:func:`~tolalloc.units.check_joint_units` on the rows of q1..qN that are all numbers (others are the
    reader's to refuse)."""
    from tolalloc.units import check_joint_units

    cols = [f"q{j + 1}" for j in range(robot.n_joints)]
    names = [str(c).strip() for c in frame.columns]
    if not all(c in names for c in cols):
        return
    Q = np.column_stack([pd.to_numeric(frame.iloc[:, names.index(c)], errors="coerce").to_numpy(dtype=float)
                         for c in cols])
    Q = Q[np.all(np.isfinite(Q), axis=1)]
    if len(Q):
        try:
            check_joint_units(Q, robot.revolute_mask, robot.q_to_interface(robot.lower),
                              robot.q_to_interface(robot.upper), f"{source} ({cols[0]}..{cols[-1]})")
        except TolallocError as exc:
            raise ArgumentError(argument, str(exc)) from None
