"""Candidate unmodelled effects, each a linear parametric correction to the calibrated model.

Every effect ``e`` contributes a displacement of the target point, linear in its parameters ``beta``::

    dx_i = B_e(q_i, covariates_i) @ beta      B_e : (P, 3, M) [mm per unit of beta], robot base frame

built to first order at the nominal geometry (effects are sub-millimetre; the second-order error is
~1e-3 mm). Joint-type effects move joint ``j`` by ``dq_j`` and displace the target by
``(v_j + omega_j x p) dq_j`` (space-Jacobian column ``j`` at the target point ``p``).

``joint_compliance``  ``dq_j = c_j tau_j(q)``, ``tau_j`` the gravity torque [N m] (force [N] for a
                      prismatic joint) of the robot's masses, or of the default mass model
                      (:data:`DEFAULT_KG_PER_M` kg per metre of link at the link midpoints) when the
                      robot file has none. Parameters ``c_j`` [rad/(N m)] or [mm/N].
``link_deflection``   cantilever bending of each arm segment between consecutive revolute joints
                      (spanning prismatic strokes) whose overhang can reach :data:`MIN_OVERHANG_MM`:
                      tip drop ``k h^3`` [mm] along gravity (``h`` the horizontal overhang [m]) and tip
                      slope ``1.5 k h^2 / 1000`` [rad]; parameter ``k`` [mm/m^3] per segment.
``backlash``          ``dq_j = b_j dir_j`` (half the backlash [rad or mm]); needs ``dir1..dirN``.
``thermal``           every link length grows by ``alpha (T - T_ref) L``; ``alpha`` [1e-6/K];
                      needs ``temperature_c`` varying by >= 0.05 K.
``transmission``      ``dq_j = a_j sin 2q_j + b_j cos 2q_j + c_j sin 3q_j + d_j cos 3q_j`` [rad] per
                      revolute joint.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.errormodel import build_error_model
from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Mass, Robot
from tolalloc.diagnose.measurements import Measurements

__all__ = ["EFFECTS", "EffectBasis", "effect_basis", "effect_reference", "applicable", "gravity_torques",
           "robot_masses", "deflection_segments", "joint_effect_dq", "target_points", "point_jacobian"]

EFFECTS = ("joint_compliance", "link_deflection", "backlash", "thermal", "transmission")
DEFAULT_KG_PER_M = 10.0
MIN_OVERHANG_MM = 200.0
G = 9.81


@dataclass(frozen=True, eq=False)
class EffectBasis:
    """The displacement basis of one effect on a pose set.

    Attributes
    ----------
    effect : str
    names : tuple of str
        Parameter names with their unit, e.g. ``c_j2 [rad/(N m)]``.
    B : array, shape (P, 3, M) [mm per unit parameter], robot base frame.
    """

    effect: str
    names: tuple
    B: np.ndarray


def target_points(robot: Robot, q: np.ndarray, t_mm: np.ndarray) -> np.ndarray:
    """Nominal target position ``T(q) [t; 1]`` in the base frame [mm], shape (P, 3)."""
    T = robot.fk(q)
    return T[:, :3, 3] + T[:, :3, :3] @ np.asarray(t_mm, dtype=float)


def point_jacobian(robot: Robot, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Velocity of the point ``p`` (P, 3) per unit joint rate, ``v_j + omega_j x p``, shape (P, 3, n)."""
    Js = robot.space_jacobian(q)
    return Js[:, 3:, :] + np.cross(Js[:, :3, :], p[:, :, None], axis=1)


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


def gravity_torques(robot: Robot, q: np.ndarray) -> np.ndarray:
    """Gravity load at every joint, shape (P, n): torque about the axis [N m] (revolute), force [N] (prismatic)."""
    q = np.atleast_2d(q)
    P = poe_prefix(robot.screws, q)  # (P, n+1, 4, 4)
    n = robot.n_joints
    tau = np.zeros((q.shape[0], n))
    g = np.asarray(robot.gravity, dtype=float)
    for m in robot_masses(robot):
        c = P[:, m.body, :3, :3] @ m.com_mm + P[:, m.body, :3, 3]
        F = m.mass_kg * G * g
        for j in range(min(m.body, n)):
            w = P[:, j, :3, :3] @ robot.joints[j].axis
            if robot.joints[j].is_revolute:
                pj = P[:, j, :3, :3] @ robot.joint_points_mm[j] + P[:, j, :3, 3]
                tau[:, j] += np.einsum("pi,pi->p", w, np.cross(c - pj, F)) / 1000.0
            else:
                tau[:, j] += w @ F
    return tau


def deflection_segments(robot: Robot) -> list:
    """Arm segments that may bend: ``(start_joint, end_joint or None for the flange, max overhang [mm])``.

    A segment runs from a revolute joint to the next revolute joint (spanning prismatic joints) or to the
    flange; it is kept when its horizontal overhang reaches :data:`MIN_OVERHANG_MM` on a fixed sample of
    400 poses within the joint limits (seed 0), so the list depends on the robot only.
    """
    rev = [j for j in range(robot.n_joints) if robot.joints[j].is_revolute]
    rng = np.random.default_rng(0)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    q = rng.uniform(lo, hi, (400, robot.n_joints))
    segs = []
    for a, j in enumerate(rev):
        k = rev[a + 1] if a + 1 < len(rev) else None
        h = _overhang(robot, q, j, k)[1]
        if h.max() >= MIN_OVERHANG_MM:
            segs.append((j, k, float(h.max())))
    return segs


def _overhang(robot: Robot, q, j, k):
    """Segment end points (P, 3) and horizontal overhang [mm] (P,) and unit direction (P, 3)."""
    P = poe_prefix(robot.screws, q)
    g = np.asarray(robot.gravity, dtype=float)
    start = _point_at(P[:, j], robot.joint_points_mm[j])
    end = _point_at(P[:, k], robot.joint_points_mm[k]) if k is not None else robot.fk(q)[:, :3, 3]
    L = end - start
    Lh = L - (L @ g)[:, None] * g
    h = np.linalg.norm(Lh, axis=1)
    return end, h, Lh / np.maximum(h, 1e-9)[:, None]


def _point_at(Pj, p_home):
    return Pj[:, :3, :3] @ p_home + Pj[:, :3, 3]


def _link_deflection(robot: Robot, q, p_t):
    g = np.asarray(robot.gravity, dtype=float)
    cols, names = [], []
    for j, k, _ in deflection_segments(robot):
        end, h, u = _overhang(robot, q, j, k)
        hm = h / 1000.0
        drop = hm ** 3  # mm per unit k
        slope = 1.5e-3 * hm ** 2  # rad per unit k
        axis = np.cross(u, g)
        cols.append(drop[:, None] * g + slope[:, None] * np.cross(axis, p_t - end))
        names.append(f"k_{robot.joints[j].name} [mm/m^3]")
    return np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0)), names


def joint_effect_dq(effect: str, robot: Robot, q, direction=None):
    """Joint-offset basis of a joint-type effect: ``dq = A @ beta``, ``A`` shape (P, n, M), with names."""
    n = robot.n_joints
    P = q.shape[0]
    cols, names = [], []
    if effect == "joint_compliance":
        tau = gravity_torques(robot, q)
        for j in range(n):
            if np.abs(tau[:, j]).max() > 1e-9:
                a = np.zeros((P, n))
                a[:, j] = tau[:, j]
                cols.append(a)
                names.append(f"c_{robot.joints[j].name} [{'rad/(N m)' if robot.joints[j].is_revolute else 'mm/N'}]")
    elif effect == "backlash":
        for j in range(n):
            a = np.zeros((P, n))
            a[:, j] = direction[:, j]
            cols.append(a)
            names.append(f"b_{robot.joints[j].name} [{'rad' if robot.joints[j].is_revolute else 'mm'}]")
    elif effect == "transmission":
        for j in range(n):
            if not robot.joints[j].is_revolute:
                continue
            for lab, f in (("s2", lambda x: np.sin(2 * x)), ("c2", lambda x: np.cos(2 * x)),
                           ("s3", lambda x: np.sin(3 * x)), ("c3", lambda x: np.cos(3 * x))):
                a = np.zeros((P, n))
                a[:, j] = f(q[:, j])
                cols.append(a)
                names.append(f"{lab}_{robot.joints[j].name} [rad]")
    else:
        raise ValueError(effect)
    return (np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))), names


def effect_reference(meas: Measurements) -> dict:
    """Reference values taken from the training set (kept fixed for held-out poses)."""
    T = meas.temperature_c
    return {"temperature_c": float(np.mean(T)) if T is not None else None}


def applicable(effect: str, meas: Measurements) -> tuple[bool, str]:
    """Whether the data can carry ``effect`` at all, with the reason when not."""
    if effect == "backlash" and meas.direction is None:
        return False, "no dir1..dirN columns"
    if effect == "backlash" and not np.any((meas.direction > 0).any(0) & (meas.direction < 0).any(0)):
        return False, "no joint approached from both directions"
    if effect == "thermal":
        if meas.temperature_c is None:
            return False, "no temperature_c column"
        if np.ptp(meas.temperature_c) < 0.05:
            return False, f"temperature varies by only {np.ptp(meas.temperature_c):.3g} K"
    return True, ""


def effect_basis(effect: str, robot: Robot, meas: Measurements, t_mm, ref: dict) -> EffectBasis:
    """Displacement basis of ``effect`` on the poses of ``meas`` (target offset ``t_mm`` on the flange)."""
    q = meas.q
    p_t = target_points(robot, q, t_mm)
    if effect in ("joint_compliance", "backlash", "transmission"):
        A, names = joint_effect_dq(effect, robot, q, meas.direction)
        B = np.einsum("pin,pnm->pim", point_jacobian(robot, q, p_t), A)
    elif effect == "link_deflection":
        B, names = _link_deflection(robot, q, p_t)
    elif effect == "thermal":
        model = build_error_model(robot, "generic", exclude=("joint_drive", "axis_deflection"))
        J = model.jacobian(q)[:, :3, :]  # (P, 3, L) per mm of each link
        L = np.array([lk.length_mm for lk in robot.links if lk.length_mm > 0])
        dT = meas.temperature_c - ref["temperature_c"]
        B = (J @ L * 1e-6 * dT[:, None])[:, :, None]
        names = ["alpha [1e-6/K]"]
    else:
        raise ValueError(f"unknown effect {effect!r}; known: {', '.join(EFFECTS)}")
    return EffectBasis(effect, tuple(names), np.asarray(B, dtype=float))
