"""Gravity loads at the joints: the robot's mass model (:func:`robot_masses`: the robot file's masses, or
:data:`DEFAULT_KG_PER_M` kg per metre of link at the link midpoints), the load of point masses on the joints
before them and the gravity torques of the masses and a payload (:func:`gravity_torques`).

The gravity-driven effects of :mod:`.effects` (joint compliance, gravity-held backlash, the telescopic guide's
tilt) and the residual breakdown (:mod:`.where`) are built on them.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Mass, Robot

__all__ = ["G", "DEFAULT_KG_PER_M", "robot_masses", "gravity_torques"]

#: Standard gravity [m/s^2].
G = 9.81
#: Mass per metre of link [kg/m] of the default mass model (robots whose file gives no masses).
DEFAULT_KG_PER_M = 10.0


def robot_masses(robot: Robot) -> tuple:
    """The robot file's masses, or the default model (10 kg per metre of link, at link midpoints)."""
    if robot.masses:
        return robot.masses
    out, point = [], np.zeros(3)
    for link, site in zip(robot.links, robot.link_sites):
        if link.length_mm > 0:
            out.append(Mass(link.name, int(site), DEFAULT_KG_PER_M * link.length_mm / 1000.0, point + link.vector_mm / 2))
        point = point + link.vector_mm
    return tuple(out)


def _point_load(robot: Robot, P, c, F, below: int) -> np.ndarray:
    """Load of forces ``F`` (P, 3) [N] at points ``c`` (P, 3) [mm] on the joints ``j < below``, shape (P, n)."""
    tau = np.zeros((len(c), robot.n_joints))
    for j in range(min(below, robot.n_joints)):
        w = P[:, j, :3, :3] @ robot.joints[j].axis
        if robot.joints[j].is_revolute:
            pj = P[:, j, :3, :3] @ robot.joint_points_mm[j] + P[:, j, :3, 3]
            tau[:, j] = np.einsum("pi,pi->p", w, np.cross(c - pj, F)) / 1000.0
        else:
            tau[:, j] = np.einsum("pi,pi->p", w, F)
    return tau


def _tip_load(robot: Robot, q, tip_mm) -> np.ndarray:
    """Gravity load of a 1 kg point mass at ``tip_mm`` (P, 3) [mm] on every joint, shape (P, n) [N m / kg, N / kg]."""
    F = np.broadcast_to(G * np.asarray(robot.gravity, dtype=float), tip_mm.shape)
    return _point_load(robot, poe_prefix(robot.screws, np.atleast_2d(q)), tip_mm, F, robot.n_joints)


def gravity_torques(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None,
                    tip_kg: np.ndarray | float = 0.0) -> np.ndarray:
    """Gravity load at every joint, shape (P, n): torque about the axis [N m] (revolute), force [N] (prismatic).

    ``tip_mm`` (P, 3) [mm, base frame] and ``tip_kg`` (P,) or float: an extra point mass (the payload) at the target.
    """
    q = np.atleast_2d(q)
    P = poe_prefix(robot.screws, q)  # (P, n+1, 4, 4)
    g = np.asarray(robot.gravity, dtype=float)
    tau = np.zeros((q.shape[0], robot.n_joints))
    for m in robot_masses(robot):
        c = P[:, m.body, :3, :3] @ m.com_mm + P[:, m.body, :3, 3]
        tau += _point_load(robot, P, c, np.broadcast_to(m.mass_kg * G * g, c.shape), m.body)
    if tip_mm is not None:
        tau += np.broadcast_to(np.asarray(tip_kg, float), (len(q),))[:, None] * _tip_load(robot, q, tip_mm)
    return tau
