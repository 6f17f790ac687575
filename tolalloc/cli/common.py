"""Helpers shared by the CLI commands: argument parsing and all-or-nothing output."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from .._validate import TolallocError
from ..robot import Robot
from ..robotfile import load_robot

__all__ = ["parse_q", "add_robot_arg", "robot_from_args", "atomic_output", "write_json", "json_default"]


def add_robot_arg(parser) -> None:
    parser.add_argument("robot", metavar="ROBOT",
                        help="built-in robot name (see `tolalloc robots`) or path to a robot file (.toml, DH .csv, .urdf)")
    parser.add_argument("--tool", metavar="LINK", default=None,
                        help="URDF only: the tool link (default: the last link of the chain; required if the URDF branches)")


def robot_from_args(args) -> Robot:
    return load_robot(args.robot, tool=getattr(args, "tool", None))


def parse_q(text: str, robot: Robot, flag: str = "--q") -> np.ndarray:
    """Parse ``"15,30,-10,0,-20,-5"`` (deg / mm) into internal joint values [rad, mm], checking count and limits."""
    try:
        values = [float(x) for x in text.replace(";", ",").split(",") if x.strip()]
    except ValueError:
        raise TolallocError(f"{flag}: expected comma-separated numbers in deg (revolute) / mm (prismatic), got {text!r}.") from None
    return robot.check_q(values, flag, interface=True)


def json_default(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    if isinstance(obj, np.bool_):
        return bool(obj)
    raise TypeError(f"not JSON serialisable: {type(obj)}")


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, *, directory: bool = False):
    """Yield a temporary path; move it to ``path`` only if the block finishes without error.

    For ``directory=True`` the temporary path is a fresh directory whose content
    replaces the files of the same name in ``path`` (other files there are kept).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if directory:
        tmp = Path(tempfile.mkdtemp(prefix=".tmp-", dir=path.parent))
        try:
            yield tmp
            path.mkdir(parents=True, exist_ok=True)
            for item in tmp.iterdir():
                target = path / item.name
                if target.is_dir():
                    shutil.rmtree(target)
                os.replace(item, target)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
    else:
        fd, tmp_name = tempfile.mkstemp(prefix=".tmp-", dir=path.parent)
        os.close(fd)
        tmp = Path(tmp_name)
        try:
            yield tmp
            os.replace(tmp, path)
        finally:
            if tmp.exists():
                tmp.unlink()


def write_json(obj, path) -> None:
    """Write ``obj`` as indented JSON to ``path`` atomically ('-' prints to stdout)."""
    text = json.dumps(obj, indent=2, default=json_default)
    if str(path) == "-":
        print(text)
        return
    with atomic_output(path) as tmp:
        tmp.write_text(text + "\n")
