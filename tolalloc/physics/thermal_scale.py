"""Thermal scale error of a joint's own position measurement, for encoders the robot file declares a scale for.

A scale that grows with temperature relative to what it measures -- a linear axis' glass or steel scale on a frame
of another material, a measuring wheel on a slewing ring, a rack read by a pinion encoder -- reads every position
off by its relative growth times the distance from its reference mark (ISO 230-3, thermal effects on a machine's
axes: the scale's expansion against the structure's; Bryan, "International status of thermal error research",
CIRP Annals 39(2), 1990). With the reference mark at the joint's zero, joint ``j`` is off by::

    dq_j = c_j q_j dT        c_j: the scale's expansion less the structure's [1e-6 per K]

The robot file declares ``c_j`` on the joint's encoder (``scale_expansion_um_per_m_K``); only those joints get the
diagnosis's thermal variants ``scale`` (``dT`` the logged air less the training mean) and ``scale_lag_<tau>min``
(through a first-order lag: the scale's heat capacity), each with a coefficient per joint fitted (the declared value
is the design's). Undeclared, per-joint scale columns would copy any effect that grows with the joints' positions
while the air drifts over a session. The design's term is :func:`scale_error`.
"""

from __future__ import annotations

import numpy as np

from tolalloc.physics.loads import point_jacobian
from tolalloc.robot.model import Robot

__all__ = ["scale_joints", "joint_scale", "scale_error"]


def scale_joints(robot: Robot) -> np.ndarray:
    """Indices of the joints whose encoder declares a scale expansion, shape (k,)."""
    return robot.components.encoder_joints([jt.name for jt in robot.joints],
                                           lambda enc: enc.scale_expansion is not None)


def joint_scale(robot: Robot, q: np.ndarray, points_mm: np.ndarray) -> tuple:
    """Displacement of the points ``points_mm`` (P, 3) per 1e-6 of relative scale error of every joint of
    :func:`scale_joints`, shape (P, 3, k), and the columns' names (``scale_<joint> [1e-6/K]``)."""
    q = np.atleast_2d(np.asarray(q, float))
    js = scale_joints(robot)
    J = point_jacobian(robot, q, np.asarray(points_mm, float))
    return 1e-6 * J[:, :, js] * q[:, None, js], tuple(f"scale_{robot.joints[j].name} [1e-6/K]" for j in js)


def scale_error(expansion: float, q_j: np.ndarray, dT: np.ndarray) -> np.ndarray:
    """Joint error [rad or mm] of a scale of relative ``expansion`` [1 per K] at joint values ``q_j`` (P,) and
    temperatures ``dT`` (P,) [K] above the reference: ``expansion q_j dT``."""
    return expansion * np.asarray(q_j, float) * np.asarray(dT, float)
