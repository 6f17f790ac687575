"""Gravity loads: the robot's mass model, the loads of point masses on the joints and on the base mount.

:func:`robot_masses`: the robot file's masses, or :data:`DEFAULT_KG_PER_M` kg per metre of link at the link
midpoints. :func:`gravity_torques`: the gravity load of every joint [N m about a revolute axis, N along a prismatic
one], from the robot's masses and a payload at the target point. :func:`base_moment`: the overturning moment of
all of them about the base origin [N m, base frame] -- what tilts a compliant mount. Every gravity-driven effect
(joint compliance, gravity-held lost motion, beam sag, the mount) is built on these.

Kinematic helpers shared by the effect models: :func:`target_points` (the measured point at a pose) and
:func:`point_jacobian` (its velocity per unit joint rate).
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.lie import cross
from tolalloc.robot.model import Mass, Robot

__all__ = ["G", "DEFAULT_KG_PER_M", "robot_masses", "gravity_torques", "tip_load", "base_moment", "joint_wrenches",
           "wrench_load", "wrench_moment", "point_at",
           "target_points", "point_jacobian", "mass_points", "across_axes", "unit_along"]

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


def target_points(robot: Robot, q: np.ndarray, t_mm: np.ndarray) -> np.ndarray:
    """Nominal target position ``T(q) [t; 1]`` in the base frame [mm], shape (P, 3); ``t_mm`` (3,) on the flange."""
    T = robot.fk_internal(q)
    return T[:, :3, 3] + T[:, :3, :3] @ np.asarray(t_mm, dtype=float)


def point_jacobian(robot: Robot, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Velocity of the point ``p`` (P, 3) per unit joint rate, ``v_j + omega_j x p``, shape (P, 3, n)."""
    Js = robot.space_jacobian_internal(q)
    return Js[:, 3:, :] + np.cross(Js[:, :3, :], p[:, :, None], axis=1)


def point_at(prefix: np.ndarray, p_home: np.ndarray) -> np.ndarray:
    """Where a point ``p_home`` (3,) of a body moves under the prefix transforms ``prefix`` (P, 4, 4), shape (P, 3)."""
    return prefix[:, :3, :3] @ p_home + prefix[:, :3, 3]


def mass_points(robot: Robot, q: np.ndarray, prefix: np.ndarray | None = None) -> list:
    """``[(Mass, centre of mass at each pose (P, 3) [mm])]`` of :func:`robot_masses`."""
    P = poe_prefix(robot.screws, np.atleast_2d(q)) if prefix is None else prefix
    return [(m, point_at(P[:, m.body], m.com_mm)) for m in robot_masses(robot)]


def _point_load(robot: Robot, P, c, F, below: int) -> np.ndarray:
    """Load of forces ``F`` (P, 3) [N] at points ``c`` (P, 3) [mm] on the joints ``j < below``, shape (P, n)."""
    tau = np.zeros((len(c), robot.n_joints))
    for j in range(min(below, robot.n_joints)):
        w = P[:, j, :3, :3] @ robot.joints[j].axis
        if robot.joints[j].is_revolute:
            pj = point_at(P[:, j], robot.joint_points_mm[j])
            tau[:, j] = np.einsum("pi,pi->p", w, cross(c - pj, F)) / 1000.0
        else:
            tau[:, j] = np.einsum("pi,pi->p", w, F)
    return tau


def tip_load(robot: Robot, q, tip_mm) -> np.ndarray:
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
    for m, c in mass_points(robot, q, P):
        tau += _point_load(robot, P, c, np.broadcast_to(m.mass_kg * G * g, c.shape), m.body)
    if tip_mm is not None:
        tau += np.broadcast_to(np.asarray(tip_kg, float), (len(q),))[:, None] * tip_load(robot, q, tip_mm)
    return tau


def base_moment(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None,
                tip_kg: np.ndarray | float = 0.0) -> np.ndarray:
    """Gravity moment of every moving mass (and a payload ``tip_kg`` at ``tip_mm``) about the base origin [N m],
    base frame, shape (P, 3): what the mount carries beside the robot's weight (its horizontal part tilts it).

    Masses fixed to the base (``body == 0``) are left out: their moment does not change with the pose.
    """
    q = np.atleast_2d(q)
    g = G * np.asarray(robot.gravity, dtype=float)
    M = np.zeros((len(q), 3))
    for m, c in mass_points(robot, q):
        if m.body > 0:
            M += np.cross(c / 1000.0, m.mass_kg * g)
    if tip_mm is not None:
        kg = np.broadcast_to(np.asarray(tip_kg, float), (len(q),))
        M += kg[:, None] * np.cross(np.asarray(tip_mm, float) / 1000.0, g)
    return M


def joint_wrenches(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None, tip_kg=0.0,
                   wrench: np.ndarray | None = None) -> tuple:
    """Force [N] and moment [N m] about each joint's point that the loads beyond it put through the joint -- the
    gravity of the masses it carries, a payload and a process wrench at the target -- base frame: ``F, M`` each shape
    (P, n, 3), and the joints' points ``o`` (P, n, 3) [mm] and axes ``w`` (P, n, 3). The part of ``M`` along a
    revolute axis is the joint's torque (:func:`gravity_torques`); the part across it is what the joint's bearings
    carry.

    ``tip_mm`` (P, 3) and ``tip_kg`` (P,) or float: an extra point mass (the payload) at the target; ``wrench``
    (P, 6): a process force [N] and moment [N m] applied there (:func:`wrench_load`). A payload or a wrench without
    ``tip_mm`` is refused (ValueError): it has no point to act at.
    """
    if tip_mm is None and (wrench is not None or np.any(np.asarray(tip_kg, float) != 0.0)):
        raise ValueError("joint_wrenches: a payload or a process wrench needs tip_mm, the point it acts at")
    q = np.atleast_2d(q)
    P, n = q.shape
    prefix = poe_prefix(robot.screws, q)
    o = np.stack([point_at(prefix[:, j], robot.joint_points_mm[j]) for j in range(n)], axis=1)
    w = np.stack([prefix[:, j, :3, :3] @ robot.joints[j].axis for j in range(n)], axis=1)
    g = G * np.asarray(robot.gravity, dtype=float)
    F, M = np.zeros((P, n, 3)), np.zeros((P, n, 3))
    loads = [(m.body, c, np.broadcast_to(m.mass_kg * g, c.shape)) for m, c in mass_points(robot, q, prefix)]
    if tip_mm is not None:
        kg = np.broadcast_to(np.asarray(tip_kg, float), (P,))
        loads.append((n, np.asarray(tip_mm, float), kg[:, None] * g))
        if wrench is not None:
            loads.append((n, np.asarray(tip_mm, float), np.asarray(wrench, float)[:, :3]))
            M += np.asarray(wrench, float)[:, None, 3:]
    for body, c, f in loads:
        for j in range(min(body, n)):
            F[:, j] += f
            M[:, j] += np.cross((c - o[:, j]) / 1000.0, f)
    return F, M, o, w


def wrench_load(robot: Robot, q: np.ndarray, tip_mm: np.ndarray, wrench: np.ndarray) -> np.ndarray:
    """Load on every joint of a wrench applied to the robot at the target points, shape (P, n) [N m, N].

    ``wrench`` (P, 6): the force [N] at ``tip_mm`` (P, 3) [mm] and the moment [N m], both in the base frame (what
    a process -- a cut, a press, a screwing reaction -- does to the tool). A joint carries the virtual work of the
    wrench per unit joint motion: ``w_j . (M + (c - p_j) x F)`` about a revolute axis, ``w_j . F`` along a prismatic
    one; a force ``m g`` at the target gives :func:`tip_load` times ``m``.
    """
    q = np.atleast_2d(q)
    wrench = np.asarray(wrench, dtype=float)
    P = poe_prefix(robot.screws, q)
    tau = _point_load(robot, P, np.asarray(tip_mm, dtype=float), wrench[:, :3], robot.n_joints)
    for j, joint in enumerate(robot.joints):
        if joint.is_revolute:
            tau[:, j] += np.einsum("pi,pi->p", P[:, j, :3, :3] @ joint.axis, wrench[:, 3:])
    return tau


def wrench_moment(tip_mm: np.ndarray, wrench: np.ndarray) -> np.ndarray:
    """Moment [N m] about the base origin of the wrench ``wrench`` (P, 6) applied at ``tip_mm`` (P, 3) [mm], base
    frame, shape (P, 3) (see :func:`wrench_load`): what it adds to :func:`base_moment`."""
    wrench = np.asarray(wrench, dtype=float)
    return np.cross(np.asarray(tip_mm, float) / 1000.0, wrench[:, :3]) + wrench[:, 3:]


def across_axes(e: np.ndarray) -> tuple:
    """Two unit axes across the unit direction ``e`` (3,), ``(u, e x u)``, ``u`` fixed by ``e`` alone."""
    u = np.cross(e, [1.0, 0.0, 0.0] if abs(e[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    return u, np.cross(e, u)


def unit_along(v: np.ndarray, scale: float, rel: float) -> np.ndarray:
    """Unit vectors (P, 3) along the loads ``v`` (P, 3) (the side a load presses a clearance or a play to); zero
    where ``|v|`` is at most ``rel`` times ``scale``, the size below which a load is rounding noise."""
    size = np.linalg.norm(v, axis=1)
    keep = size > rel * max(float(scale), 1e-300)
    return np.where(keep[:, None], v / np.where(keep, size, 1.0)[:, None], 0.0)
