"""Joint clearance: the play of a joint's bearings (axial, radial, tilt), taken up on the side its load presses.

A joint's bearings leave the body beyond it free to move within a clearance in the five directions the joint does
not drive: along the axis (axial play), across it (radial play) and about the two axes across it (tilt play). Under
a static load the body rests against the clearance's side the load presses -- the gravity force and moment carried
through the joint (:func:`~.loads.joint_wrenches`) -- so it is displaced by half the clearance in the direction of
the force component (axial, radial) or turned by half the tilt clearance about the moment's component across the
axis::

    axial    d = (c_a / 2) sign(F . w) w
    radial   d = (c_r / 2) F_r / |F_r|                         F_r = F - (F . w) w
    tilt     d = (c_t / 2) M_t / |M_t| x (p - o)               M_t = M - (M . w) w

``w`` the joint's axis and ``o`` its point, ``F``, ``M`` the force and the moment about ``o`` that the masses beyond
the joint (and a payload at the target) put through it, ``p`` the target point. A prismatic joint's motion is along
``w`` (its drive's lost motion is the axial play, :mod:`~tolalloc.physics.lost_motion`); instead it has roll play,
a turn about ``w`` by the sign of the moment about it (a ram turning in its key's clearance). A revolute joint's turn
about ``w`` is the gear's lost motion, not a bearing's. The first joint's tilt turns the whole arm about the base as
a rocking mount does (:mod:`~.compliance`'s ``play``): it is left to the mount. Textbook forms: Harris & Kotzalas,
*Rolling Bearing Analysis* (2007), ch. 2 (internal clearance, axial and radial play, tilt), and the joint-clearance
error screws of the error model (:mod:`tolalloc.errormodel`), here set by the load instead of drawn.

:func:`clearance_columns` gives the target displacement per unit half-clearance, one column per joint and direction
whose side changes between the poses (a side that never changes is a constant offset, which the geometric
calibration takes).
"""

from __future__ import annotations

import numpy as np

from tolalloc.physics.loads import joint_wrenches, unit_along
from tolalloc.robot.model import Robot

__all__ = ["clearance_columns"]

#: A load component below this fraction of the whole load's largest value over the poses has no side (a bearing
#: loaded across it by rounding only).
NO_LOAD = 1e-6


def _side(v: np.ndarray, whole: np.ndarray) -> np.ndarray:
    """Unit vectors (P, 3) along the component ``v`` (P, 3) of a load; zero where ``|v|`` is below :data:`NO_LOAD` of
    the whole load ``whole`` (P, 3)'s largest size."""
    return unit_along(v, np.linalg.norm(whole, axis=1).max(initial=0.0), NO_LOAD)


def clearance_columns(robot: Robot, q: np.ndarray, p: np.ndarray, tip_mm: np.ndarray | None = None,
                      payload_kg=None) -> tuple:
    """Target displacement per unit half-clearance, ``B`` shape (P, 3, M) [mm per mm, mm per mrad], the column
    names (``ca_<joint> [mm]``, ``cr_<joint> [mm]``, ``ct_<joint> [mrad]``, ``cq_<joint> [mrad]`` for a prismatic
    joint's roll) and their prior groups (M,): ``2 j`` a joint's translations, ``2 j + 1`` its turns.

    ``p`` (P, 3): the target points [mm]; the payload ``payload_kg`` (P,) sits at ``tip_mm`` (P, 3).
    """
    p = np.asarray(p, dtype=float)
    F, M, o, w = joint_wrenches(robot, q, tip_mm, 0.0 if payload_kg is None else payload_kg)
    cols, names, groups = [], [], []

    def add(col, label, unit, group):
        # a column that does not change between the poses is a constant offset: the geometry's
        if np.abs(col - col.mean(axis=0)).max() > 1e-9 * max(np.abs(col).max(), 1e-300):
            cols.append(col)
            names.append(f"{label}_{jt.name} [{unit}]")
            groups.append(group)

    for j, jt in enumerate(robot.joints):
        wj = w[:, j]
        Fa = np.einsum("pi,pi->p", F[:, j], wj)
        Ma = np.einsum("pi,pi->p", M[:, j], wj)
        turn = lambda axis: 1e-3 * np.cross(axis, p - o[:, j])  # noqa: E731  (mm per mrad)
        if jt.is_revolute:
            add(_side(Fa[:, None], F[:, j]) * wj, "ca", "mm", 2 * j)
        add(_side(F[:, j] - Fa[:, None] * wj, F[:, j]), "cr", "mm", 2 * j)
        if j:  # the first joint's tilt turns the whole arm as a rocking base does: mount_compliance's play
            add(turn(_side(M[:, j] - Ma[:, None] * wj, M[:, j])), "ct", "mrad", 2 * j + 1)
        if not jt.is_revolute:
            add(turn(_side(Ma[:, None], M[:, j]) * wj), "cq", "mrad", 2 * j + 1)
    P = len(p)
    if not cols:
        return np.zeros((P, 3, 0)), [], np.zeros(0, int)
    return np.stack(cols, axis=-1), names, np.asarray(groups, int)
