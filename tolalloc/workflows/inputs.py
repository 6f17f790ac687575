"""What the workflow functions accept, turned into the library's objects, checked once at the entry point.

Robots come as a :class:`~tolalloc.robot.Robot`, a built-in name or a robot file; joint values in interface units
(deg for revolute joints, mm for prismatic ones); measurements as a CSV path or a DataFrame. Every refusal is an
:class:`~tolalloc.exceptions.ArgumentError` naming the keyword argument (the command line shows its flag instead).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Callable, TypeVar

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError, UnknownArgumentError, known_names
from tolalloc.workflows.checks import (RANGES, Z_RANGE, check_axes, check_choice, check_costs_file,  # noqa: F401
                                       check_count, check_flag, check_model_options, check_name, check_names,
                                       check_optional_flag, check_not_both, check_path, check_positive,
                                       check_probability, check_scheduler, check_seed, check_text, check_values,
                                       check_z, number, shown)
from tolalloc.robot.columns import JOINT_COLUMNS_TEXT, find_joint_columns
from tolalloc.robot.io import load_robot
from tolalloc.robot.model import Robot
from tolalloc.units import trusting_units

#: the checks of :mod:`tolalloc.workflows.checks` are reachable here too (``inputs.check_count`` ...)
__all__ = ["trusting_units", "job_entry", "as_robot", "joint_values", "resolve_poses", "error_model",
           "sigma_overrides", "resolve_region", "check_one_pose_source", "trajectory", "as_measurements",
           "default_pose_set", "read_table", "check_choice", "check_costs_file", "check_count", "check_flag",
           "check_model_options", "check_name", "check_names", "check_not_both", "check_optional_flag", "check_path",
           "check_positive", "check_probability", "check_scheduler", "check_seed", "check_values", "check_z", "number",
           "shown", "check_axes", "check_text", "RANGES", "Z_RANGE"]


_Job = TypeVar("_Job", bound=Callable[..., Any])  # job_entry keeps the job's signature for type checkers


def job_entry(fn: _Job) -> _Job:
    """The entry point of workflow ``fn``: a keyword ``fn`` does not have is refused with the closest names
    (:class:`~tolalloc.exceptions.UnknownArgumentError`, a TypeError), a keyword it had before its settings objects
    is folded into them with a ``DeprecationWarning`` (:mod:`tolalloc.workflows.keywords`), and with
    ``trust_units=True`` the unit-plausibility guards are off during the call (robot files, joint values, costs
    files: :mod:`tolalloc.units`)."""
    import difflib
    import functools
    import inspect

    from tolalloc.workflows.keywords import MOVED, field_sources, fold_moved

    signature = inspect.signature(fn)
    keywords = [name for name, p in signature.parameters.items()
                if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
    moved = MOVED.get(fn.__name__, {})

    @functools.wraps(fn)
    def run(*args, trust_units: bool = False, **kwargs):
        for name in kwargs:
            if name not in keywords and name not in moved:
                close = difflib.get_close_matches(name, keywords, n=3, cutoff=0.7)
                # the name without its unit (radius for radius_mm), or with one the call's name has not (n_mc for n)
                close += [k for k in keywords if (k.startswith(name + "_") or name.startswith(k + "_"))
                          and k not in close][:3 - len(close)]
                hint = f"did you mean {' or '.join(close)}? " if close else ""
                raise UnknownArgumentError(name, f"{fn.__name__}() has no argument {name!r}; {hint}"
                                                 f"help(tolalloc.{fn.__name__}) lists them all.")
        # an old keyword renamed (simulate_errors' n is n_mc now): an error of its value names it as it was given;
        # a run-time error of a settings object's field names ClassName.field (or the old keyword that set it)
        renamed = {moved[k][0]: k for k in kwargs if k in moved and moved[k][1] is None}
        renamed.update(field_sources(signature, args, kwargs, moved))
        try:
            if any(name in moved for name in kwargs):  # positional arguments by name, so the old keywords meet them
                old = {k: kwargs.pop(k) for k in list(kwargs) if k in moved}
                kwargs = fold_moved(fn.__name__, {**signature.bind_partial(*args, **kwargs).arguments, **old})
                args = ()
            check_flag(trust_units, "trust_units")
            with trusting_units(bool(trust_units)):
                return fn(*args, trust_units=trust_units, **kwargs)
        except ArgumentError as exc:
            if exc.argument not in renamed:
                raise
            raise ArgumentError(renamed[exc.argument], exc.detail) from None

    return run  # type: ignore[return-value]  # the same signature as ``fn``


def as_robot(robot, *, tool: str | None = None, trust_units: bool = False) -> Robot:
    """A :class:`Robot` from a Robot, a built-in name (``"tool_changer"``, ``"ur10"``) or a robot-file path.

    ``trust_units`` accepts robot-file values that look like a unit slip (see :mod:`tolalloc.units`).
    """
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


def joint_values(robot: Robot, q_deg_mm, argument: str = "q_deg_mm") -> np.ndarray:
    """Joint values in interface units (deg / mm), shape (n,) or (P, n) or a DataFrame with one column per joint
    (:mod:`tolalloc.robot.columns`: ``q1_deg`` / ``q4_mm``, ``<joint name>_deg`` or ``q1..qN``), checked against
    count, finiteness, unit slips (:func:`tolalloc.units.check_joint_units`) and the joint limits; returned in
    internal units [rad, mm], shape (P, n)."""
    want = f"{robot.n_joints} per pose, deg / mm"
    if isinstance(q_deg_mm, pd.DataFrame):
        names = [str(c).strip() for c in q_deg_mm.columns]
        try:
            cols = find_joint_columns(robot, names, "DataFrame")
        except TolallocError as exc:
            raise ArgumentError(argument, str(exc)) from None
        q_deg_mm = q_deg_mm.set_axis(names, axis=1)[cols].to_numpy()
    elif isinstance(q_deg_mm, (str, bytes, dict)) or not hasattr(q_deg_mm, "__len__") and not np.isscalar(q_deg_mm) \
            and not isinstance(q_deg_mm, np.ndarray):
        raise ArgumentError(argument, f"expected joint values of robot {robot.name!r} ({want}): a list, an array of "
                            f"shape (n,) or (P, n) or a DataFrame with one column per joint (q1_deg ...), got "
                            f"{shown(q_deg_mm)}.")
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


def check_one_pose_source(q_deg_mm, poses, q_argument: str = "q_deg_mm", poses_argument: str = "poses") -> None:
    """Refuse joint values and a pose-set name given together (one would override the other); needs no robot."""
    check_not_both(q_deg_mm, q_argument, poses, poses_argument, "give the poses",
                   " (joint values in deg / mm, or the name of a pose set)")


def resolve_poses(robot: Robot, q_deg_mm=None, poses: str | None = None, *,
                  q_argument: str = "q_deg_mm", poses_argument: str = "poses") -> tuple[str, np.ndarray]:
    """``(label, q (P, n) [rad, mm])`` from explicit joint values or a pose-set name (default: nominal)."""
    check_one_pose_source(q_deg_mm, poses, q_argument, poses_argument)
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
    trajectory CSV path (a pose per row, deg / mm: :func:`trajectory`) or an array / DataFrame of joint values
    (deg / mm). Default: the robot's ``working`` box if it has one and no ``poses`` are given, else the pose set
    ``poses`` (default: ``working``, else the nominal pose, with a ``UserWarning`` that the requirement is then
    checked at one pose only). ``region`` and ``poses`` together are refused.
    """
    check_not_both(region, "region", poses, "poses", "say where the requirement holds",
                   " (`region` also takes a pose set name)")
    regions = robot.regions
    if region is None:
        if poses is None and "working" in regions:
            region = "working"
        else:
            name = poses if poses is not None else default_pose_set(robot)
            if poses is None and name == "nominal":
                _warn_nominal_only(robot)
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


def _warn_nominal_only(robot: Robot) -> None:
    """Warn that a robot without a working region or pose set is allocated at its nominal pose alone."""
    import warnings

    warnings.warn(f"robot {robot.name!r} has no working region or pose set: allocated at the nominal pose only "
                  "(1 pose); for the working region pass region='limits' (--region limits: the box of the joint "
                  "limits), a pose set or a trajectory, or add a [regions.working] box to the robot file.",
                  UserWarning, stacklevel=5)  # the caller of allocate_tolerances


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
    """Rows of joint values [deg / mm] of a CSV file -> (P, n) [rad, mm].

    With a header line, the joint columns are found by their names (:mod:`tolalloc.robot.columns`: ``q1_deg`` /
    ``q4_mm``, ``<joint name>_deg`` or ``q1..qN``; other columns are not read); without one, every row holds the
    ``n`` joint values in joint order.
    """
    p = Path(path)
    where = repr(str(path))
    if not p.is_file():
        raise InputFileError(f"region {where}: no such trajectory file; give a CSV with one pose per row ("
                             f"{JOINT_COLUMNS_TEXT}, or {robot.n_joints} values without a header).")
    try:
        frame = pd.read_csv(p, header=None, dtype=str, skipinitialspace=True, encoding="utf-8-sig",
                            skip_blank_lines=True)
    except (ValueError, OSError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        raise ArgumentError("region", f"{where}: cannot read the trajectory ({exc}); expected "
                            f"{robot.n_joints} comma-separated numbers per row.") from None
    cells = frame.fillna("").to_numpy(dtype=str)
    if len(cells) and not any(_is_number(c) for c in cells[0]):  # a header line
        try:
            cols = find_joint_columns(robot, cells[0], where)
        except TolallocError as exc:
            raise ArgumentError("region", str(exc)) from None
        names = [str(c).strip() for c in cells[0]]
        cells = cells[1:, [names.index(c) for c in cols]]
    rows = np.array([[float(c) if _is_number(c) else np.nan for c in row] for row in cells]).reshape(len(cells), -1)
    if rows.shape[0] == 0 or rows.shape[1] != robot.n_joints:
        raise ArgumentError("region", f"{where}: expected rows of {robot.n_joints} joint values (deg / mm), "
                            f"got shape {rows.shape}.")
    if not np.all(np.isfinite(rows)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(rows), axis=1))[0]) + 1
        raise ArgumentError("region", f"{where}: row {bad} has a missing or non-finite value; every joint "
                            "value must be a finite number (deg / mm).")
    try:
        return robot.check_q(rows, where, interface=True)
    except TolallocError as exc:
        raise ArgumentError("region", str(exc)) from None


def read_table(source, argument: str, expected: str, *, text: bool = False) -> pd.DataFrame | None:
    """A table a user gives: a DataFrame as it is, or a CSV file read (a byte-order mark and spaces after the commas
    allowed); the column names stripped of spaces. None for anything else (the caller says what it accepts).

    Parameters
    ----------
    source : str, os.PathLike or pandas.DataFrame
    argument : str      the argument's name in the errors
    expected : str      what the file should be, in words (``"the parts.csv of a design with bought parts"``)
    text : bool         every cell read as text, an empty cell as ``""`` (default: numbers parsed, empty cells NaN)

    Raises
    ------
    InputFileError  the path names nothing
    ArgumentError   the path names a folder, or a file that is not a readable CSV
    """
    if isinstance(source, pd.DataFrame):
        frame = source
    elif isinstance(source, (str, os.PathLike)) and str(source).strip():
        where = repr(str(source))
        if Path(source).is_dir():
            raise ArgumentError(argument, f"{where} is a folder; expected {expected}.")
        if not Path(source).is_file():
            raise InputFileError(f"{argument}: {where} does not exist; expected {expected}.", argument=argument)
        opts = {"dtype": str, "keep_default_na": False} if text else {}
        try:
            frame = pd.read_csv(source, skipinitialspace=True, encoding="utf-8-sig", **opts)
        except (ValueError, OSError, UnicodeDecodeError, pd.errors.ParserError) as exc:
            raise ArgumentError(argument, f"{where}: cannot read the CSV ({exc}); expected {expected}.") from None
    else:
        return None
    return frame.set_axis([str(c).strip() for c in frame.columns], axis=1)


def _is_number(text) -> bool:
    try:
        float(text)
    except (TypeError, ValueError):
        return False
    return True


def as_measurements(data, robot: Robot, argument: str):
    """Measurements from a CSV path or a DataFrame (a column per joint in deg / mm, x_mm, y_mm, z_mm, optional
    ones; :mod:`tolalloc.diagnose.measurements`).

    The joint values are checked for unit slips first (:func:`tolalloc.units.check_joint_units`, the rule of every
    joint-value input), then read and checked by :mod:`tolalloc.diagnose.measurements`.
    """
    from tolalloc.diagnose import measurements_from_frame, read_measurements
    from tolalloc.diagnose.measurements import comment_lines

    want = f"a CSV path or a pandas DataFrame with {JOINT_COLUMNS_TEXT} and x_mm, y_mm, z_mm"
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
            raise InputFileError(f"measurement file {str(data)!r} does not exist; expected a CSV with "
                                 f"{JOINT_COLUMNS_TEXT} and x_mm, y_mm, z_mm.")
        opts = dict(skipinitialspace=True, encoding="utf-8-sig", skiprows=comment_lines(data))
        try:  # the joint columns only; a file that cannot be read or named gets the reader's message below
            cols = find_joint_columns(robot, pd.read_csv(data, nrows=0, **opts).columns, "")
            frame = pd.read_csv(data, usecols=lambda c: str(c).strip() in cols, **opts)
        except (ValueError, OSError, UnicodeDecodeError):  # TolallocError and pandas' errors are ValueErrors
            frame = None
        if frame is not None:
            _measured_joint_units(frame, robot, argument, repr(str(data)))
        return read_measurements(data, robot)
    raise ArgumentError(argument, f"expected {want}, got {shown(data)}.")


def _measured_joint_units(frame: pd.DataFrame, robot: Robot, argument: str, source: str) -> None:
    """:func:`~tolalloc.units.check_joint_units` on the rows of the joint columns that are all numbers (others
    are the reader's to refuse)."""
    from tolalloc.units import check_joint_units

    names = [str(c).strip() for c in frame.columns]
    try:
        cols = find_joint_columns(robot, names, source)
    except TolallocError:
        return  # the reader refuses the columns with its own message
    Q = np.column_stack([pd.to_numeric(frame.iloc[:, names.index(c)], errors="coerce").to_numpy(dtype=float)
                         for c in cols])
    Q = Q[np.all(np.isfinite(Q), axis=1)]
    if len(Q):
        try:
            check_joint_units(Q, robot.revolute_mask, robot.q_to_interface(robot.lower),
                              robot.q_to_interface(robot.upper), f"{source} ({cols[0]}..{cols[-1]})")
        except TolallocError as exc:
            raise ArgumentError(argument, str(exc)) from None
