"""Checks of a robot at construction: numbers, names, the unit guards of a chain built in Python, reserved names.

:class:`~tolalloc.robot.model.Robot` runs :func:`check_chain` on every construction; the loaders of robot files,
DH tables and URDF files have checked the units in their own terms (keys with unit suffixes, metres) and build
the robot with the unit guards of :func:`check_chain` off. :func:`check_reserved_names` refuses a pose set, region
or sigma set named like one of the library's own (:data:`RESERVED_NAMES`), for the robot and the robot files.
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError, describe
from tolalloc.robot.elements import REVOLUTE, Joint, Link
from tolalloc.units import check_chain_units

__all__ = ["check_chain", "check_reserved_names", "check_fields", "check_named_sets", "joint_array", "RESERVED_NAMES"]

#: names the library gives a meaning of its own: the pose set of the nominal joint values, the box of the joint
#: limits, the generic sigma set; a robot file's set of the same name would never be used
RESERVED_NAMES = {"pose set": "nominal", "region": "limits", "sigma set": "generic"}


def _floats(value, what: str, shape: tuple, who: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.shape != shape or not np.all(np.isfinite(arr)):
        count = {(): "one finite number", (3,): "3 finite numbers"}.get(shape, "a 3 x 3 matrix of finite numbers")
        raise TolallocError(f"{who}, {what}: expected {count}, got {describe(value)}.")
    return arr


def _check_joint(e: Joint, who: str) -> None:
    try:
        np.asarray(e.axis, dtype=float)
    except (TypeError, ValueError):
        raise TolallocError(f"{who}, joint {e.name}: axis {describe(e.axis)} is not a finite unit "
                            "3-vector; expected e.g. [0, 0, 1].") from None
    _floats(e.nominal, f"joint {e.name}: the nominal value (a finite nominal value inside the limits)", (), who)
    try:
        vals = np.array([e.lower, e.upper], dtype=float)
    except (TypeError, ValueError):
        vals = np.array([np.nan, np.nan])
    if np.isnan(vals).any():
        raise TolallocError(f"{who}, joint {e.name}: limits [{e.lower}, {e.upper}]; expected numbers "
                            "(+-inf for no limit).")
    if not e.lower <= e.nominal <= e.upper:
        raise TolallocError(f"{who}, joint {e.name}: nominal value {e.nominal:g} outside its limits "
                            f"[{e.lower:g}, {e.upper:g}] [rad / mm]; expected a value inside the limits.")


def check_chain(chain, tool_offset_mm, tool_rotation, who: str, *, units: bool = True) -> None:
    """Refuse non-numbers, NaN / inf in links, axes, limits, nominal values and the tool frame, zero-length
    links and unnamed elements; with ``units``, also values that look like a unit slip
    (:func:`tolalloc.units.check_chain_units`: metres for mm, degrees for rad).

    Parameters
    ----------
    chain : tuple of Link and Joint
    tool_offset_mm : array, shape (3,)
    tool_rotation : array, shape (3, 3)
    who : str
        Prefix of the messages (``robot 'arm'``).
    units : bool
        Apply the unit guards (off for robots read from files, whose loaders check units in the file's terms).
    """
    for e in chain:
        if not isinstance(e, (Link, Joint)) or not isinstance(e.name, str) or not e.name:
            raise TolallocError(f"{who}: chain element {describe(e)}; expected Link and Joint elements with "
                                "names.")
        if isinstance(e, Link):
            v = _floats(e.vector_mm, f"link {e.name} vector [mm]", (3,), who)
            if not np.any(v):
                raise TolallocError(f"{who}, link {e.name}: zero length; a link needs a length > 0 (its "
                                    "tolerance has a direction); leave the entry out.")
        else:
            _check_joint(e, who)
    _floats(tool_offset_mm, "tool offset [mm] (tool offset_mm)", (3,), who)
    R = _floats(tool_rotation, "tool rotation", (3, 3), who)
    if not np.allclose(R @ R.T, np.eye(3), atol=1e-6):
        raise TolallocError(f"{who}: tool rotation is not a rotation matrix; expected finite tool rpy angles.")
    if units:
        check_chain_units({e.name: float(np.linalg.norm(e.vector_mm)) for e in chain if isinstance(e, Link)},
                          [(e.name, float(e.lower), float(e.upper), float(e.nominal)) for e in chain
                           if isinstance(e, Joint) and e.kind == REVOLUTE], who)


def check_reserved_names(who: str, *, pose_sets=(), regions=(), sigma_sets=()) -> None:
    """Refuse a pose set ``nominal``, a region ``limits`` or a sigma set ``generic`` defined by a robot file."""
    for what, names, key in (("pose set", pose_sets, "pose_sets"), ("region", regions, "regions"),
                             ("sigma set", sigma_sets, "sigma_sets")):
        if RESERVED_NAMES[what] in names:
            name = RESERVED_NAMES[what]
            raise TolallocError(f"{who + ': ' if who else ''}{key}.{name}: the {what} name {name!r} is built in ({_MEANING[what]}); "
                                f"expected another name for this {what}, e.g. {name}_2.")


_MEANING = {"pose set": "the nominal joint values", "region": "the box of the joint limits",
            "sigma set": "the library's generic sigmas"}


def check_fields(name, chain, description, masses, gravity, named: dict) -> tuple:
    """The plain fields of a robot, before its chain is read: ``(chain, masses, gravity)`` as a tuple of elements, a
    tuple of :class:`~tolalloc.robot.elements.Mass` and a unit 3-vector; ``named``: the fields
    ``pose_sets``, ``regions`` and ``sigma_sets``, each a dict keyed by names (their entries: :func:`check_named_sets`).
    """
    from tolalloc.robot.elements import Mass

    if not isinstance(name, str) or not name.strip():
        raise TolallocError(f"robot name: expected a non-empty string, got {describe(name)}.")
    who = f"robot {name!r}"
    if not isinstance(chain, (tuple, list)) or not chain:
        raise TolallocError(f"{who}: chain {describe(chain)}; expected a tuple of Link and Joint elements from the "
                            "base (at least one joint).")
    if not isinstance(description, str):
        raise TolallocError(f"{who}: description: expected a string, got {describe(description)}.")
    for field, value in named.items():  # pose_sets, regions, sigma_sets
        if not isinstance(value, dict) or not all(isinstance(k, str) and k.strip() for k in value):
            raise TolallocError(f"{who}: {field} {describe(value)}; expected a dict with names (strings) as keys.")
    if not isinstance(masses, (tuple, list)) or not all(isinstance(m, Mass) for m in masses):
        raise TolallocError(f"{who}: masses {describe(masses)}; expected a tuple of Mass elements (or none).")
    g = _floats(gravity, "gravity (a direction in the base frame)", (3,), who)
    norm = float(np.linalg.norm(g))
    if norm == 0:
        raise TolallocError(f"{who}: gravity [0, 0, 0] has no direction; expected e.g. [0, 0, -1].")
    return tuple(chain), tuple(masses), g / norm


def check_named_sets(robot) -> None:
    """The pose sets (finite joint values inside the limits, shape (P, n) [rad, mm]), regions (``(q_min, q_max)``,
    one value per joint each, ``q_min <= q_max``) and sigma sets (dicts) of ``robot``; masses carried by joints it
    has. The pose sets are stored as float arrays (P, n)."""
    who, n = f"robot {robot.name!r}", robot.n_joints
    sets = {}
    for key, q in robot.pose_sets.items():
        arr = robot.check_q(q, f"{who}, pose set {key!r}")
        sets[key] = np.atleast_2d(arr)
    object.__setattr__(robot, "pose_sets", sets)
    for key, box in robot.regions.items():
        try:
            lo_hi = np.array(box, dtype=float)
        except (TypeError, ValueError):
            lo_hi = None
        if lo_hi is None or lo_hi.shape != (2, n) or np.isnan(lo_hi).any() or np.any(lo_hi[0] > lo_hi[1]):
            raise TolallocError(f"{who}, region {key!r}: {describe(box)}; expected (q_min, q_max) with {n} joint "
                                "values each [rad, mm], q_min <= q_max.")
    for key, entry in robot.sigma_sets.items():
        if not isinstance(entry, dict):
            raise TolallocError(f"{who}, sigma set {key!r}: {describe(entry)}; expected a dict (as a robot file's "
                                "[sigma_sets.NAME] table).")
    for m in robot.masses:
        if m.body > n:
            raise TolallocError(f"{who}, mass {m.name}: body {m.body}; expected at most the robot's {n} joints.")


def joint_array(q, n: int, robot: str, name: str = "q", units: str = "rad / mm", finite: bool = True) -> np.ndarray:
    """``q`` as a float array of shape (..., n) for robot ``robot`` (its name): numbers (no bools or strings), one
    per joint in the last axis, no NaN (and, with ``finite``, no +-inf); refused by ``name`` with what was expected.
    No limits checked (:meth:`Robot.check_q <tolalloc.robot.model.Robot.check_q>` does)."""
    want = f"{n} joint value{'s' if n > 1 else ''} [{units}] in the last axis, shape ({n},) or (P, {n})"
    arr = None
    if not isinstance(q, (str, bytes, dict)) and q is not None:
        try:
            arr = np.asarray(q, dtype=float)
        except (TypeError, ValueError, OverflowError):
            arr = None
    # a numeric array holds no bool or string: only other inputs (lists, object arrays) are scanned value by value
    numeric = isinstance(q, np.ndarray) and q.dtype.kind in "fiu"
    kinds = np.asarray(q, dtype=object).ravel() if arr is not None and not numeric and 0 < arr.size < 10**5 else ()
    if arr is None or any(isinstance(v, (bool, np.bool_, str, bytes)) for v in kinds):
        raise TolallocError(f"{name}: expected numbers, {want}, got {describe(q)}.")
    if arr.ndim == 0 or arr.shape[-1] != n or arr.size == 0:
        raise TolallocError(f"{name}: expected {want}, got shape {arr.shape} for robot {robot!r}.")
    if np.isnan(arr).any() or (finite and np.isinf(arr).any()):
        raise TolallocError(f"{name}: expected {'finite ' if finite else ''}numbers (no NaN), {want}, got "
                            f"{describe(q)}.")
    return arr
