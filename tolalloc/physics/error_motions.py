"""Error motions of a linear axis along its stroke.

A carriage travelling on its guideway neither moves on a straight line nor keeps its attitude: ISO 230-1:2012 (3.4)
names six error motions of a linear axis X, each a function of the position ``x`` along the stroke -- the
positioning error ``E_XX`` (a ball screw's or rack's cumulative lead error, a scale's graduation), the straightness
errors ``E_YX`` and ``E_ZX``, and the roll, pitch and yaw errors ``E_AX``, ``E_BX``, ``E_CX``. On a guideway they vary
smoothly over its length: a bent or twisted rail, a bed that sags between its supports, a screw's progressive lead
error (Slocum, *Precision Machine Design*, 1992, ch. 2; ISO 230-2 for the positioning error).

:func:`stroke_columns` is the basis the diagnosis fits for every prismatic joint: the six error motions as Legendre
polynomials of the normalised stroke ``s = 2 (q - lower) / (upper - lower) - 1``, orders 1 to :data:`STROKE_ORDER`,
in a frame carried by the axis (its direction ``u`` and two directions across it). The terms a complete geometric
model already holds are left out: constants (the next joint's place and attitude) and the linear straightness (the
axis' direction). A rotation turns the carriage about its own reference point (the joint point carried along the
stroke); translations are in mm, rotations in mrad, so the two groups of a joint's prior (one scale each) compare
like with like at a lever of a metre.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import legendre

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Robot
from tolalloc.physics.loads import across_axes, point_at

__all__ = ["STROKE_ORDER", "stroke_joints", "stroke_position", "stroke_columns"]

#: Highest Legendre order of the error motions along the stroke.
STROKE_ORDER = 3


def stroke_joints(robot: Robot) -> list:
    """The prismatic joints whose stroke is bounded (finite limits): those that get error motions."""
    return [j for j, jt in enumerate(robot.joints)
            if not jt.is_revolute and np.isfinite(robot.lower[j]) and np.isfinite(robot.upper[j])]


def stroke_position(robot: Robot, q: np.ndarray, j: int) -> np.ndarray:
    """The normalised stroke ``s`` (P,) of prismatic joint ``j``: -1 at its lower limit, +1 at its upper one."""
    lo, hi = float(robot.lower[j]), float(robot.upper[j])
    return 2.0 * (np.asarray(q, float)[:, j] - lo) / max(hi - lo, 1e-9) - 1.0


def stroke_columns(robot: Robot, q: np.ndarray, p_t: np.ndarray, order: int = STROKE_ORDER) -> tuple:
    """Displacement basis of the error motions of every prismatic joint with a bounded stroke along it (module
    docstring; :func:`stroke_joints`).

    Parameters
    ----------
    robot : Robot
    q : array, shape (P, n)  [rad, mm]
    p_t : array, shape (P, 3)  target points [mm], base frame
    order : int  highest Legendre order

    Returns
    -------
    B : array, shape (P, 3, M)  [mm per mm of translation amplitude, mm per mrad of rotation amplitude]
    names : list of str  ``e<motion><order>_<joint> [mm or mrad]``, motion ``u`` (along the axis), ``v``, ``w``
        (across it) for translations, ``ru``, ``rv``, ``rw`` for rotations
    groups : array of int, shape (M,)  one prior group per joint for its translations and one for its rotations
    """
    q = np.atleast_2d(np.asarray(q, float))
    Pm = poe_prefix(robot.screws, q)
    cols, names, groups = [], [], []
    for j in stroke_joints(robot):
        joint = robot.joints[j]
        R = Pm[:, j, :3, :3]
        axis = np.asarray(joint.axis, float) / np.linalg.norm(joint.axis)
        dirs = [R @ e for e in (axis, *across_axes(axis))]
        o = point_at(Pm[:, j + 1], robot.joint_points_mm[j])  # the carriage's reference point
        s = stroke_position(robot, q, j)
        for k in range(1, order + 1):
            pk = legendre.legval(s, np.eye(order + 1)[k])[:, None]
            for d, lab in zip(dirs, "uvw"):
                if lab == "u" or k >= 2:
                    cols.append(d * pk)
                    names.append(f"e{lab}{k}_{joint.name} [mm]")
                    groups.append(2 * j)
            for d, lab in zip(dirs, "uvw"):
                cols.append(1e-3 * np.cross(d, p_t - o) * pk)
                names.append(f"er{lab}{k}_{joint.name} [mrad]")
                groups.append(2 * j + 1)
    B = np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))
    return B, names, np.array(groups, int)
