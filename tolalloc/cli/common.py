"""Helpers shared by the CLI commands: argument parsing and all-or-nothing output."""

from __future__ import annotations

import re

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Robot
from tolalloc.robot.io import load_robot
from tolalloc.cli.output import atomic_output, check_distinct_outputs, check_output, json_default, write_json

__all__ = ["format_labels", "parse_q", "add_robot_arg", "robot_from_args", "atomic_output", "write_json", "json_default",
           "check_output", "check_distinct_outputs", "add_error_model_args", "sigma_overrides", "error_model_from_args"]

#: argparse (Python < 3.13) takes "-15,30,..." for an option; a joint list starting with a minus is a value
_NEGATIVE_VALUE = re.compile(r"^-\d+$|^-\d*\.\d+$|^-\.?\d[\d.eE+-]*([,;]\s*[-+]?[\d.eE+-]*)+$")


def add_robot_arg(parser) -> None:
    parser._negative_number_matcher = _NEGATIVE_VALUE  # --q "-15,30,-10,0,-20,-5" is a value, not an option
    parser.add_argument("robot", metavar="ROBOT",
                        help="built-in robot name (see `tolalloc robots`) or path to a robot file (.toml, DH .csv, .urdf)")
    parser.add_argument("--tool", metavar="LINK", default=None,
                        help="URDF only: the tool link (default: the last link of the chain; required if the URDF branches)")
    parser.add_argument("--trust-units", action="store_true",
                        help="accept robot-file values that look like a unit slip (lengths under _m above 20 m, a "
                        "robot under 10 mm long, angles beyond one turn)")


def robot_from_args(args) -> Robot:
    from tolalloc.units import trusting_units

    with trusting_units(getattr(args, "trust_units", False)):
        return load_robot(args.robot, tool=getattr(args, "tool", None))


def parse_q(text: str, robot: Robot, flag: str = "--q") -> np.ndarray:
    """Parse ``"15,30,-10,0,-20,-5"`` (deg / mm) into internal joint values [rad, mm], checking count and limits."""
    try:
        values = [float(x) for x in text.replace(";", ",").split(",") if x.strip()]
    except ValueError:
        raise TolallocError(f"{flag}: expected comma-separated numbers in deg (revolute) / mm (prismatic), got {text!r}.") from None
    return robot.check_q(values, flag, interface=True)


def format_labels(labels: dict) -> str:
    """Model options for a one-line header: ``sigma_set=table2, link_mode=consistent, ...``."""
    return ", ".join(f"{k}={v}" for k, v in labels.items() if v is not None)


def add_error_model_args(parser, *, allocation: bool = False) -> None:
    """The error-model options of every command (read back by :func:`error_model_from_args`).

    ``allocation``: the sigmas are what the allocation chooses, so the sigma overrides and the
    clearance-sigma choice are left out and ``--sigma-set`` only serves fixed parameters.
    """
    from tolalloc.errormodel.model import CLEARANCE_SIGMA, CLEARANCE_TILT_LITERAL_RAD

    parser.add_argument("--sigma-set", default=None,
                        help="sigma set used for fixed parameters without tol_mm/tol_deg (default: the robot file's "
                        "first)" if allocation else
                        "sigma set of the robot file (tool_changer: table2 (default), table1) or 'generic'")
    parser.add_argument("--link-mode", default="consistent", choices=["consistent", "axes_only"],
                        help="link errors move axes and tool (consistent, default) or axes only (paper-literal Eq. 24)")
    parser.add_argument("--deflection-mode", default="screw", choices=["screw", "tilt"],
                        help="axis deflection as error screws (default) or as a tilt of the axis (Eqs. 32/37)")
    parser.add_argument("--clearance", action="store_true",
                        help="add joint clearance (axial slip, radial ring, tilt) to every revolute joint"
                        + (" (allocated like the others)" if allocation else ""))
    parser.add_argument("--exclude", action="append", default=[], metavar="NAME",
                        help="leave out a parameter or kind; repeatable")
    if allocation:
        return
    parser.add_argument("--clearance-tilt-literal", action="store_true",
                        help=f"use Table 4's literal tilt sigma {CLEARANCE_TILT_LITERAL_RAD} rad instead of the "
                        f"corrected {CLEARANCE_SIGMA['tilt_rad']} rad")
    parser.add_argument("--sigma", action="append", default=[], metavar="NAME=VALUE",
                        help="override a parameter's or kind's sigma, in mm (lengths) or deg (angles); repeatable")


def add_scheduler_arg(parser, what: str = "the samples") -> None:
    """``--scheduler WHERE``: local threads (default), Dask on this machine, or a Dask scheduler address."""
    parser.add_argument("--scheduler", default=None, metavar="WHERE",
                        help=f"where {what} run: local threads (default), 'threads' or 'processes' (Dask, this "
                        "machine), or a Dask scheduler address such as tcp://HOST:8786; never changes the numbers")


def sigma_overrides(model_params, items) -> dict:
    """Parse ``--sigma NAME=VALUE`` items into ``{parameter name: sigma [mm or rad]}``.

    VALUE is in mm for length parameters and in deg for angle parameters. A kind (``joint_drive``)
    sets every parameter of that kind, each in its own unit (a revolute drive in deg, a prismatic
    drive in mm); a parameter name given as well wins over its kind, whatever the order.

    Raises
    ------
    TolallocError
        Malformed item, unknown parameter or kind, or a value that is not a finite number >= 0.
    """
    by_kind, by_name = {}, {}
    for item in items:
        if "=" not in item:
            raise TolallocError(f"--sigma: expected NAME=VALUE (mm or deg), got {item!r}.")
        name, val = item.split("=", 1)
        name = name.strip()
        hits = [p for p in model_params if name in (p.name, p.kind)]
        if not hits:
            known = ", ".join(sorted({p.name for p in model_params} | {p.kind for p in model_params}))
            raise TolallocError(f"--sigma: unknown parameter or kind {name!r}; known: {known}.")
        units = " / ".join(sorted({p.interface_unit for p in hits}))
        try:
            v = float(val)
        except ValueError:
            v = np.nan
        if not np.isfinite(v) or v < 0:
            raise TolallocError(f"--sigma {name}: expected a finite sigma >= 0 in {units}, got {val.strip()!r}.")
        target = by_name if any(p.name == name for p in hits) else by_kind
        for p in hits:
            target[p.name] = v if p.interface_unit == "mm" else np.deg2rad(v)
    return {**by_kind, **by_name}


def error_model_from_args(robot: Robot, args):
    """The error model of :func:`add_error_model_args`' options (sigma set, modes, clearance, overrides, exclusions)."""
    from tolalloc.errormodel import build_error_model
    from tolalloc.errormodel.model import CLEARANCE_TILT_LITERAL_RAD

    if not hasattr(args, "sigma"):  # allocation options (add_error_model_args(allocation=True))
        return build_error_model(robot, args.sigma_set, link_mode=args.link_mode, deflection_mode=args.deflection_mode,
                                 clearance=args.clearance, exclude=tuple(args.exclude))
    if args.clearance_tilt_literal and not args.clearance:
        raise TolallocError("--clearance-tilt-literal changes the clearance tilt sigma, but clearance is off; "
                            "add --clearance (or leave out --clearance-tilt-literal).")
    opts = dict(link_mode=args.link_mode, deflection_mode=args.deflection_mode, clearance=args.clearance)
    base = build_error_model(robot, args.sigma_set, **opts)
    sigma = sigma_overrides(base.params, args.sigma)
    cs = {"tilt_rad": CLEARANCE_TILT_LITERAL_RAD} if args.clearance_tilt_literal else None
    return build_error_model(robot, args.sigma_set, **opts, clearance_sigma=cs, sigma=sigma or None,
                             exclude=tuple(args.exclude))
