"""Joint-value columns of CSV files and DataFrames: one naming rule for every reader.

The column of joint ``k`` (numbered from 1) of a robot, whose interface unit ``u`` is ``deg`` for a revolute
joint and ``mm`` for a prismatic one, may be named

* ``q<k>_<u>`` (``q1_deg``, ``q4_mm``): the unit-carrying form, written by the library's output files;
* ``<joint name>_<u>`` (``j1_deg``, ``shoulder_pan_joint_deg``): the form calibration plans are written with;
* ``q<k>_deg_mm``: the generic interface suffix (deg for revolute, mm for prismatic joints);
* ``q<k>``: an accepted alias, read in the joint's interface unit.

A name of the ``q<k>`` form is always read as joint ``k``, whatever the joints are called. Refused, each with a
message naming the column and what to do: a unit suffix that is not the joint's (``q1_mm`` for a revolute joint;
``q1_rad``: convert to degrees), a joint given in two columns, joint columns beyond the robot's joints (``q7`` for
a six-joint robot: a file of another robot?) and a joint without a column. The readers of measurement files
(:mod:`tolalloc.diagnose.measurements`), calibration plans (:mod:`tolalloc.calibration.plan`), trajectories and
joint-value DataFrames (:mod:`tolalloc.workflows.inputs`) all find their joint columns with
:func:`find_joint_columns`.
"""

from __future__ import annotations

import re

from tolalloc.exceptions import TolallocError

__all__ = ["find_joint_columns", "joint_column_names", "JOINT_COLUMNS_TEXT", "UNIT_SUFFIXES"]

#: unit suffixes a joint column may carry (the joint's own unit, or the generic deg_mm, is accepted)
UNIT_SUFFIXES = ("deg_mm", "deg", "rad", "mm", "m")
#: how the joint columns are described in messages
JOINT_COLUMNS_TEXT = "one column per joint named q<k>_deg / q<k>_mm (or q<k>, or <joint name>_deg / _mm; deg / mm)"

_Q = re.compile(r"^q(\d+)(?:_(" + "|".join(UNIT_SUFFIXES) + r"))?$")


def joint_column_names(robot) -> list[str]:
    """The unit-carrying column name of each joint, ``q<k>_deg`` / ``q<k>_mm`` (the form output files write)."""
    return [f"q{k + 1}_{j.unit}" for k, j in enumerate(robot.joints)]


def _parse(col: str, robot):
    """``(k (0-based), unit suffix or None)`` of a joint column, or None for another column."""
    m = _Q.match(col)
    if m:
        return int(m.group(1)) - 1, m.group(2)
    for k, j in enumerate(robot.joints):
        rest = col[len(j.name) + 1:] if col.startswith(f"{j.name}_") else None
        if rest in UNIT_SUFFIXES:
            return k, rest
    return None


def _unit_error(col: str, k: int, joint, suffix: str, source: str) -> TolallocError:
    """A joint column whose unit suffix is not the joint's: what to name it and how to convert it."""
    good = f"q{k + 1}_{joint.unit}"
    what = f"{source}: column {col!r}: joint {k + 1} ({joint.name}) is {joint.kind}, its values are read in {joint.unit}"
    if joint.is_revolute and suffix == "rad":
        return TolallocError(f"{what}: convert the column to degrees (numpy.degrees) and name it {good}.")
    if not joint.is_revolute and suffix == "m":
        return TolallocError(f"{what}: multiply the column by 1000 and name it {good}.")
    return TolallocError(f"{what}, not {suffix}: name the column {good} (with its values in {joint.unit}).")


def _span(indices) -> str:
    """``q1..q7`` for consecutive joint numbers (0-based in), else ``q1, q3, q9``."""
    ks = sorted(set(indices))
    if ks == list(range(ks[0], ks[-1] + 1)) and len(ks) > 2:
        return f"q{ks[0] + 1}..q{ks[-1] + 1}"
    return ", ".join(f"q{k + 1}" for k in ks)


def find_joint_columns(robot, columns, source: str) -> list[str]:
    """The column of each joint of ``robot``, in joint order, among ``columns`` (by the module's rule).

    Parameters
    ----------
    robot : Robot
    columns : iterable of str
        Column names of the file or DataFrame (surrounding spaces are ignored); other columns are left alone.
    source : str
        Prefix of the messages (the file or argument).

    Returns
    -------
    list of str
        ``n_joints`` column names (stripped), joint ``k``'s at index ``k``.

    Raises
    ------
    TolallocError
        A wrong unit suffix, a joint in two columns, joint columns beyond the robot's joints, or a joint without a
        column.
    """
    cols = [str(c).strip() for c in columns]
    n = robot.n_joints
    found: dict[int, list[str]] = {}
    numbered = set()  # joint numbers of q<k> columns, in and beyond the robot's joints
    for col in cols:
        hit = _parse(col, robot)
        if hit is None:
            continue
        k, suffix = hit
        if _Q.match(col):
            numbered.add(k)
        if not 0 <= k < n:
            continue
        joint = robot.joints[k]
        if suffix is not None and suffix not in (joint.unit, "deg_mm"):
            raise _unit_error(col, k, joint, suffix, source)
        found.setdefault(k, []).append(col)
    beyond = sorted(k for k in numbered if not 0 <= k < n)
    if beyond:
        raise TolallocError(f"{source}: the file has joint columns {_span(numbered)} but robot {robot.name!r} has {n} "
                            f"joints: is it a file of another robot? (expected {_span(range(n))})")
    twice = [k for k, c in found.items() if len(c) > 1]
    if twice:
        k = twice[0]
        raise TolallocError(f"{source}: joint {k + 1} ({robot.joints[k].name}) is given in {len(found[k])} columns, "
                            f"{', '.join(repr(c) for c in found[k])}; expected one column per joint: keep one.")
    missing = [k for k in range(n) if k not in found]
    if missing:
        raise TolallocError(_missing_message(robot, cols, missing, numbered, source))
    return [found[k][0] for k in range(n)]


def _missing_message(robot, cols, missing, numbered, source) -> str:
    n = robot.n_joints
    want = joint_column_names(robot)
    names = ", ".join(f"{want[k]} ({robot.joints[k].name})" for k in missing)
    text = (f"{source}: missing column(s) for joint(s) {names}; expected {JOINT_COLUMNS_TEXT}: {', '.join(want)}, "
            f"got columns {cols}.")
    if len(numbered) > 1 and max(numbered) < n and missing == list(range(max(numbered) + 1, n)):
        text += (f" The file has joint columns {_span(numbered)} but robot {robot.name!r} has {n} joints: is it a "
                 "file of another robot?")
    lower = {c.lower(): c for c in cols}
    hints = [f"{lower[c]!r} -> {c!r}" for k in missing for c in (want[k], f"q{k + 1}") if c in lower]
    if hints:
        text += f" Rename: {', '.join(hints)}."
    return text
