"""Loading a robot: a built-in name, a TOML robot file (chain or DH layout), a DH CSV table or a URDF."""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

from tolalloc.exceptions import InputFileError, TolallocError, describe, known_names
from tolalloc.robot.io.dh import load_dh_csv, robot_from_dh_dict
from tolalloc.robot.io.robotfile import robot_from_chain_dict
from tolalloc.robot.io.urdf import load_urdf
from tolalloc.robot.model import Robot

__all__ = ["load_robot", "builtin_robots", "robot_from_dict"]


def robot_from_dict(data: dict, source: str = "<dict>") -> Robot:
    """Build a :class:`Robot` from the parsed TOML of a robot file (chain or DH layout)."""
    if "dh" in data or "convention" in data:
        return robot_from_dh_dict(data, source)
    return robot_from_chain_dict(data, source)


def _builtin_dir():
    return resources.files("tolalloc") / "data" / "robots"


def builtin_robots() -> dict[str, str]:
    """Names and one-line descriptions of the built-in robots.

    Examples
    --------
    >>> import tolalloc
    >>> sorted(tolalloc.builtin_robots())
    ['tool_changer', 'ur10']
    """
    out = {}
    for f in sorted(_builtin_dir().iterdir(), key=lambda p: p.name):
        if f.name.endswith(".toml"):
            data = tomllib.loads(f.read_text())
            out[f.name[:-5]] = data.get("description", "").split("\n")[0]
    return out


def load_robot(robot: str | Path | Robot, tool: str | None = None) -> Robot:
    """Load a robot: a :class:`Robot` (returned as is), a built-in name, or a path to a robot file.

    Robot files: TOML (chain or DH layout), a DH table in CSV (``.csv``, see :mod:`tolalloc.robot.io.dh`) or a
    URDF (``.urdf``, see :mod:`tolalloc.robot.io.urdf`); ``tool`` names the URDF tool link (URDF only).

    Raises
    ------
    TolallocError
        Naming the file, the field and what was expected (a missing file: also a ``FileNotFoundError``).

    Examples
    --------
    >>> import tolalloc
    >>> tolalloc.load_robot("ur10")
    <Robot 'ur10': 6 joints (RRRRRR), 6 links, home tool point 1212 mm from the base; pose sets: working (6); regions: work_cell>
    """
    import os

    if not isinstance(robot, (Robot, str, os.PathLike)) or (not isinstance(robot, Robot) and
                                                           (not str(robot).strip() or "\0" in str(robot))):
        raise TolallocError(f"robot: expected a Robot, a built-in robot name ({known_names(builtin_robots())}) or the "
                            f"path to a robot file (.toml, DH .csv, .urdf), got {describe(robot)}.")
    if tool is not None and not (isinstance(tool, str) and tool.strip()):
        raise TolallocError(f"`tool`: expected the name of the URDF tool link (a string), got {describe(tool)}.")
    if tool is not None and (isinstance(robot, Robot) or not str(robot).lower().endswith(".urdf")):
        got = f"robot {robot.name!r}" if isinstance(robot, Robot) else repr(str(robot))
        raise TolallocError(f"`tool` {tool!r}: the tool link can only be chosen for a URDF robot file (*.urdf), got "
                            f"{got}; leave out the tool link (`tool`) or give a URDF file.")
    if isinstance(robot, Robot):
        return robot
    text_name = str(robot)
    builtin = _builtin_dir() / f"{text_name}.toml"
    if "/" not in text_name and not text_name.endswith((".toml", ".urdf", ".csv")) and builtin.is_file():
        source, text = f"built-in robot {text_name!r}", builtin.read_text()
    else:
        path = Path(text_name)
        if path.is_dir():
            raise TolallocError(f"robot {text_name!r} is a directory; expected a built-in robot name or a robot file "
                                "(.toml, DH .csv, .urdf).")
        if not path.is_file():
            known = known_names(builtin_robots())
            raise InputFileError(f"robot {text_name!r}: not a built-in robot ({known}) and no such file; give a "
                                 "built-in name or the path to a robot file (.toml, DH .csv, .urdf).")
        if path.suffix.lower() == ".urdf":
            return load_urdf(path, tool=tool)
        if path.suffix.lower() == ".csv":
            return load_dh_csv(path)
        source = f"robot file {str(path)!r}"
        try:
            text = path.read_text(encoding="utf-8-sig")  # a byte-order mark (Windows editors) is fine
        except (OSError, UnicodeDecodeError) as exc:
            raise TolallocError(f"{source}: cannot be read as text ({exc}); expected a TOML robot file.") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise TolallocError(f"{source}: not valid TOML ({exc}); see docs/howto/own-robot.md for the robot file format.") from None
    try:
        return robot_from_dict(data, source)
    except TolallocError as exc:
        raise TolallocError(f"{source}: {exc}") from None
