"""Helpers shared by the CLI commands: argument parsing and all-or-nothing output."""

from __future__ import annotations

import re

from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError
from tolalloc.outputs import (check_distinct_outputs, check_output, json_default, reserve_directory,
                              write_json)

__all__ = ["parse_q", "add_robot_arg", "robot_from_args", "write_json", "json_default", "check_output",
           "reserve_directory", "check_distinct_outputs", "add_error_model_args", "add_scheduler_arg", "sigma_items",
           "error_model_options",
           "robot_kwargs", "flag_map", "flag_text", "error_line"]

#: argparse (Python < 3.13) takes "-15,30,..." for an option; a joint list starting with a minus is a value
_NEGATIVE_VALUE = re.compile(r"^-\d+$|^-\d*\.\d+$|^-\.?\d[\d.eE+-]*([,;]\s*[-+]?[\d.eE+-]*)+$")


def add_robot_arg(parser) -> None:
    parser._negative_number_matcher = _NEGATIVE_VALUE  # --q "-15,30,-10,0,-20,-5" is a value, not an option
    parser.add_argument("robot", metavar="ROBOT",
                        help="built-in robot name (see `tolalloc robots`) or path to a robot file (.toml, DH .csv, .urdf)")
    parser.add_argument("--tool", metavar="LINK", default=None,
                        help="URDF only: the tool link (default: the leaf link with the most movable joints above it; "
                        "required where that is ambiguous: a tree that branches near its end, or a chain ending in a "
                        "gripper-like joint)")
    parser.add_argument("--trust-units", action="store_true",
                        help="accept values that look like a unit slip: in robot files (lengths under _m above 20 m, "
                        "a robot under 10 mm long, angles beyond one turn) and in joint values (--q, --pose, trajectory "
                        "CSVs, pose sets, measurement files: revolute values all within +-2 pi read as radians)")


def robot_from_args(args):
    """The robot of :func:`add_robot_arg`'s options (a built-in name or a robot file)."""
    from tolalloc.workflows.inputs import as_robot

    return as_robot(args.robot, **robot_kwargs(args))


def trusting(args):
    """The unit-plausibility guards off within the block when ``--trust-units`` was given."""
    from tolalloc.workflows.inputs import trusting_units

    return trusting_units(getattr(args, "trust_units", False))


def parse_q(text: str, flag: str = "--q") -> list:
    """Parse ``"15,30,-10,0,-20,-5"`` into joint values in interface units (deg / mm); the workflow checks them."""
    try:
        return [float(x) for x in text.replace(";", ",").split(",") if x.strip()]
    except ValueError:
        raise TolallocError(f"{flag}: expected comma-separated numbers in deg (revolute) / mm (prismatic), got {text!r}.") from None


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
    from tolalloc.workflows import defaults as D

    parser.add_argument("--link-mode", default=D.LINK_MODE, choices=["consistent", "axes_only"],
                        help="link errors move axes and tool (consistent, default) or axes only (paper-literal Eq. 24)")
    parser.add_argument("--deflection-mode", default=D.DEFLECTION_MODE, choices=["screw", "tilt"],
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


def sigma_items(items) -> dict:
    """``--sigma NAME=VALUE`` items -> ``{NAME: VALUE}`` (VALUE in mm or deg, checked by the workflow)."""
    out = {}
    for item in items:
        if "=" not in item:
            raise TolallocError(f"--sigma: expected NAME=VALUE (mm or deg), got {item!r}.")
        name, val = item.split("=", 1)
        try:
            out[name.strip()] = float(val)
        except ValueError:
            out[name.strip()] = val.strip()
    return out


def error_model_options(args):
    """The :class:`~tolalloc.workflows.ErrorModelOptions` of :func:`add_error_model_args`' options."""
    from tolalloc.workflows import ErrorModelOptions

    kw = dict(sigma_set=args.sigma_set, link_mode=args.link_mode, deflection_mode=args.deflection_mode,
              clearance=args.clearance, exclude=tuple(args.exclude))
    if hasattr(args, "sigma"):
        kw.update(sigma=sigma_items(args.sigma) or None, clearance_tilt_literal=args.clearance_tilt_literal)
    return ErrorModelOptions(**kw)


def robot_kwargs(args) -> dict:
    """``tool`` and ``trust_units`` of :func:`add_robot_arg`."""
    return dict(tool=getattr(args, "tool", None), trust_units=getattr(args, "trust_units", False))


#: workflow arguments whose flag is not their name with dashes (the flag switches the argument off, or is shorter):
#: (workflow argument, argparse dest); the flag shown is the dest's first spelling
_RENAMED = [("verify", "no_verify"), ("correction", "no_correction"), ("snap", "no_snap"),
            ("registration", "no_registration"), ("q_deg_mm", "pose"), ("q_deg_mm", "q"), ("path", "out"),
            ("directory", "out"), ("file", "costs"), ("where", "region"), ("method", "solver"),
            ("kind", "measurement"), ("update", "register_update"), ("n", "n_mc")]
#: settings fields whose flag is not the field's name (``OrientationRequirement.prob`` is ``--angle-prob``)
_FIELD_FLAGS = {"OrientationRequirement.prob": "angle_prob", "OrientationRequirement.radius_deg": "angle_radius_deg",
                "OrientationRequirement": "angle_radius_deg"}
#: a keyword with one value whose flag is a switch (`` `after='compensation'` `` is ``--after-compensation``)
_VALUE_FLAGS = {"after='compensation'": "after_compensation"}


def flag_map(parser) -> dict:
    """``{workflow argument: flag}`` of one command: argparse's ``dest`` names the workflow's keyword argument."""
    flags = {}
    for action in parser._actions:
        longs = [o for o in action.option_strings if o.startswith("--")]
        if longs and action.dest not in flags:
            flags[action.dest] = longs[0]
    if "pose_set" in flags:  # mc: --pose-set is the workflow's ``poses``
        flags["poses"] = flags["pose_set"]
    for name, dest in _RENAMED:
        if dest in flags:
            flags.setdefault(name, flags[dest])
    for name, dest in (*_FIELD_FLAGS.items(), *_VALUE_FLAGS.items()):
        if dest in flags:
            flags.setdefault(name, flags[dest])
    return flags


def _flag(flags: dict, name: str) -> str:
    """The flag of a workflow argument or a settings field (``Verification.n_mc`` -> ``--n-mc``), else the name."""
    return flags.get(name) or flags.get(name.rsplit(".", 1)[-1], name)


def flag_text(text: str, args) -> str:
    """A workflow message in command-line terms: `argument` and `argument='value'` references become their flags."""
    flags = getattr(args, "flags", {})
    return re.sub(r"`([A-Za-z_][A-Za-z0-9_.]*(?:='[A-Za-z_]+')?)`", lambda m: _flag(flags, m.group(1)), text)


def error_line(exc: TolallocError, args) -> str:
    """The ``error:`` line of a refused input: an :class:`ArgumentError` (an :class:`InputFileError` that names its
    argument) names its flag."""
    if isinstance(exc, ArgumentError) and args is not None:
        flags = getattr(args, "flags", {})
        return f"{_flag(flags, exc.argument)}{exc.sep}{flag_text(exc.detail, args)}"
    named = getattr(exc, "argument", "") if isinstance(exc, InputFileError) else ""
    if named and args is not None and str(exc).startswith(f"{named}: "):
        return f"{_flag(getattr(args, 'flags', {}), named)}: {flag_text(str(exc)[len(named) + 2:], args)}"
    return flag_text(str(exc), args)
