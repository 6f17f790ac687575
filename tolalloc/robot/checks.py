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

__all__ = ["check_chain", "check_reserved_names", "RESERVED_NAMES"]

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
