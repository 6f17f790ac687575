"""Set S body effects (new physics, not in sets A-R): the arm's base located by two dowel pins with clearance, its
anchor bolts slack, yawed across the dowels' clearance by the reaction of axis 1's accelerations; the arm on a table it
shares with a twin robot that runs its production cycle while the first is measured; the base on new elastomer isolators
that soften (the Mullins effect) wherever a load passes its largest so far; a gripper frame of aluminium profiles whose
bracket joint carrying the target rotates by a semi-rigid (power-law) moment-rotation curve; and a tool on a
double-diaphragm axial flexure whose diaphragms stiffen by membrane action as they deflect. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* dowel yaw: a base located by two dowel pins in holes of diametral clearance c can turn by c / r_d (r_d the pins'
  radius from the axis) once its bolts' friction torque T_s gives way (VDI 2230 Part 1 on slip of preloaded joints; the
  bolts' preload lost by embedding and self-loosening: Junker, SAE 690055, 1969); the driving torque is the reaction of
  axis 1's drive, J alpha (Newton's third law on the base; J the arm's inertia about axis 1,
  :func:`effects_c_thermal.inertia_about_joints`, alpha the cruise speed over the 0.5 s ramps of :mod:`session`): the
  start of a move throws the base against its motion, the stop with it; where neither beats T_s the base stays (a
  non-ideal relay: Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989). c 0.02-0.06 mm (ISO 286 clearance fits
  of worn pins), r_d 100-180 / 150-300 mm (ur10 / the heavier arms), the pins' centre N(0, 20 mm) off axis 1, T_s 30-70
  % of the session's largest reaction at a stop (assumed). The state at each pose is computed once from the true
  inertias (a shape parameter). The true structure: one column (the yaw's lever), amplitude c / (2 r_d).
* twin robot: two arms on one welded table standing on four levelling feet: the table's top, a rigid body on four
  springs, heaves and tilts under every weight on it (statics of a rigid body on elastic supports, K u = f, K = k sum a
  a^T, a = (1, y, -x): Timoshenko & Young, *Engineering Mechanics*), so the twin's production cycle -- K poses of its
  own box, K 4-8, visited every 20-60 s, a part of 2-10 / 4-16 / 20-80 kg carried over half of the cycle -- tilts the
  measured arm's base. The twin is the same model with the file's masses, 1.0-1.4 / 1.3-1.6 / 1.4-1.8 m from the base,
  yawed at random; feet 0.8-1.3 m along and 0.35-0.6 m across the table from its centre, 200-600 / 2000-6000 /
  10000-30000 N/mm each (ur10 / kr16_like / tool_changer: rubber-padded levelling feet; assumed; ur10's first 300-1000,
  a trial draw at another seed gained 8 %). Nothing of the twin is logged; the measured arm's own weights' share is set
  A's mount and left out. The true structure: one column (the table's motion under the twin per unit foot compliance),
  amplitude 1 / k.
* Mullins isolators: filled elastomers soften on reloading below the largest strain they have seen and follow their
  virgin curve again beyond it (Mullins, "Softening of rubber by deformation", Rubber Chem. Technol. 42, 1969; Ogden &
  Roxburgh, "A pseudo-elastic model for the Mullins effect in filled rubber", Proc. R. Soc. A 455, 1999). Four bonded
  isolators under the base plate, virgin F = k_v c, reloading F = k_v c_m (|c| / c_m)^m sign(c) below the largest |c| so
  far, c_m, m 2-3.5 (highly filled compounds); new mounts whose commissioning left c_m at 100-110 % of the empty arm's
  static compression; the plate (a rigid body of 30-60 / 80-150 / 150-300 kg, its underside 20-60 mm below the base)
  solved for each pose by Newton's method, the maxima carried from pose to pose. Feet at +-150-250 / +-300-400 /
  +-350-450 mm, k_v 2300-4000 / 8000-16000 / 40000-80000 N/mm (ur10 / kr16_like / tool_changer; assumed; ur10's first
  3000-6000: a trial draw at another seed had the joint model at 1.10x); pick and place changes the payload between
  blocks. The solution scales with 1 / k_v. The true structure: one column (the base's motion per unit compliance),
  amplitude 1 / k_v.
* profile frame: a gripper frame of aluminium profiles joined by angle brackets and T-slot nuts; the bracket joint's
  moment-rotation curve is semi-rigid, M = R_ki theta / (1 + (theta / theta_0)^n)^(1/n), theta_0 = M_u / R_ki (the
  three-parameter power model of Kishi & Chen, "Moment-rotation relations of semirigid connections with angles", J.
  Struct. Eng. 116(7), 1990), so theta = M / R_ki / (1 - (M / M_u)^n)^(1/n). The member (the profile itself rigid)
  leaves the tool plate 30 mm out and runs 150-300 mm across the tool axis to a gripper module of 1-3 / 2-5 / 5-15 kg
  that holds the part and carries the target (:func:`effects_s.probe_hook`, :func:`effects_s.payload_hook`); the joint
  turns about the bending moment's direction (its torsion stiff: two bolts). n 1-2, the session's largest moment at
  60-85 % of M_u, the tip moved 0.2-0.5 mm there (assumed). The true structure: one column, amplitude 1 / R_ki.
* diaphragm flexure: an axial float of two clamped circular diaphragms (a double-diaphragm guide, stiff in tilt)
  carrying the tool and the target; a clamped plate with a rigid centre deflects by w with F a^2 / (16 pi D t) = w / t +
  beta (w / t)^3 per diaphragm, its membrane stretching stiffening it once w nears t (large-deflection plates:
  Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, 2nd ed., 1959, ch. 13, beta 0.44-0.49 as recalled; D =
  E t^3 / 12 (1 - nu^2), spring steel). The axial load is the tool's and the part's weight along the tool axis plus an
  assembly preload of 0-50 % of the largest; radii 35-50 / 40-55 mm, w / t 0.8-1.6 at the session's largest load (its
  thickness then follows), tools of 1-3 / 2-5 kg (ur10 / kr16_like; the heavier tools of tool_changer would need a
  stiffer guide: none there; assumed). The true structure: one column, amplitude one.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_c_thermal import inertia_about_joints
from sim2real_indep.effects_s_joint import RAMP_S, cruise_speed
from sim2real_indep.session import sample_poses

Z = np.array([0.0, 0.0, 1.0])


def _gravity_tool(ctx):
    """(P, 3, 3) tool rotations and (P, 3) the gravity vector [m/s^2] in the tool frame."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt, np.einsum("pji,j->pi", Rt, -kin.G * Z)


def _rigid_plate(points_xy, k=1.0):
    """(3, 3) the stiffness K = k sum a a^T of springs at ``points_xy`` (n, 2) [mm] on the plate's heave and tilts."""
    a = np.c_[np.ones(len(points_xy)), points_xy[:, 1], -points_xy[:, 0]]
    return k * a.T @ a, a


def _weights(m, pos):
    """(P, 3): the weights' resultant, the moment about x and minus the moment about y [N, N mm], base frame."""
    fz = -kin.G * m
    return np.stack([fz.sum(1), (fz * pos[..., 1]).sum(1), -(fz * pos[..., 0]).sum(1)], axis=1)


def _rigid_motion(u, target, origin):
    """(P, 3): the displacement of ``target`` for heave u[:, 0] and tilts u[:, 1:] about x and y through ``origin``."""
    omega = np.c_[u[:, 1], u[:, 2], np.zeros(len(u))]
    return u[:, :1] * Z + np.cross(omega, target - origin)


# -------------------------------------------------------------------------------------------------- dowel yaw
DOWEL_R = {"ur10": (100.0, 180.0), "kr16_like": (150.0, 300.0), "tool_changer": (150.0, 300.0)}


def dowel_torques(ctx):
    """(2, P): axis 1's inertial torque at the start (the previous pose's inertia) and at the stop of each move
    [N m]."""
    J = inertia_about_joints(ctx)[:, 0]
    alpha = cruise_speed(ctx.session)[:, 0] / RAMP_S
    return np.array([np.r_[J[0], J[:-1]] * alpha, J * alpha])


def dowel_state(torques, direction, T_s, y0):
    """(P,): the side (+-1) the base rests on: the stop's reaction throws it with the motion, the start's against it,
    else it stays."""
    y = np.empty(len(direction))
    prev = y0
    for i, (t_a, t_d, d) in enumerate(zip(torques[0], torques[1], direction)):
        if t_d > T_s:
            prev = d
        elif t_a > T_s:
            prev = -d
        y[i] = prev
    return y


def dowel_draw(ctx, hw, rng):
    tq = dowel_torques(ctx)
    p = {"c_mm": rng.uniform(0.02, 0.06), "r_d": rng.uniform(*DOWEL_R[ctx.chain.name]),
         "centre": np.r_[rng.normal(0.0, 20.0, 2), 0.0], "T_s": rng.uniform(0.3, 0.7) * tq[1].max()}
    p["y"] = dowel_state(tq, ctx.session.direction[:, 0], p["T_s"], float(rng.choice([-1.0, 1.0])))
    return p


def dowel_shape(p, ctx):
    return p["y"][:, None] * np.cross(Z, ctx.target - p["centre"])


def dowel_apply(p, ctx, hw):
    return Contribution(displace=p["c_mm"] / (2 * p["r_d"]) * dowel_shape(p, ctx))


def dowel_features(p, ctx, hw):
    return dowel_shape(p, ctx)[None]


# ------------------------------------------------------------------------------------------------- twin robot
TWIN = {"ur10": ((1000.0, 1400.0), (200.0, 600.0)), "kr16_like": ((1300.0, 1600.0), (2000.0, 6000.0)),
        "tool_changer": ((1400.0, 1800.0), (10000.0, 30000.0))}
TWIN_PAYLOAD_KG = {"ur10": (2.0, 10.0), "kr16_like": (4.0, 16.0), "tool_changer": (20.0, 80.0)}


def twin_draw(ctx, hw, rng):
    ch = ctx.chain
    (d_lo, d_hi), k = TWIN[ch.name]
    az, yaw = rng.uniform(0, 2 * np.pi, 2)
    e = np.array([np.cos(az), np.sin(az), 0.0])
    base = rng.uniform(d_lo, d_hi) * e
    K = int(rng.integers(4, 9))
    q = sample_poses(ch, ch.name, K, rng)
    m_part = rng.uniform(*TWIN_PAYLOAD_KG[ch.name])
    Rz = kin._rot(Z, yaw)
    pos = kin.mass_positions(ch, q) @ Rz.T + base                     # the twin's masses (K, B, 3)
    fl, Rt = kin.flange(ch, q)
    part = (fl + Rt @ np.array([0.0, 0.0, 50.0])) @ Rz.T + base
    held = (np.arange(K) < K // 2).astype(float)                      # picked at its first pose, placed half-way
    m = np.c_[np.broadcast_to(ch.masses, (K, len(ch.masses))), m_part * held]
    centre = 0.5 * base
    along, across = rng.uniform(800.0, 1300.0), rng.uniform(350.0, 600.0)
    ex, ey = e[:2], np.array([-e[1], e[0]])
    feet = np.array([s * along * ex + t * across * ey for s in (-1, 1) for t in (-1, 1)]) + centre[:2]
    return {"f_cycle": _weights(m, np.concatenate([pos, part[:, None]], axis=1) - centre), "centre": centre,
            "feet": feet - centre[:2], "T_c": rng.uniform(20.0, 60.0), "phase": rng.uniform(0.0, 1.0),
            "k_N_mm": rng.uniform(*k)}


def twin_index(p, t):
    """(P,): the twin's cycle pose at times ``t`` [s]."""
    K = len(p["f_cycle"])
    return np.floor(np.mod(np.asarray(t, float) / p["T_c"] + p["phase"], 1.0) * K).astype(int) % K


def twin_shape(p, ctx):
    """(P, 3): the target's displacement per unit foot compliance [mm per mm/N]."""
    Kmat, _ = _rigid_plate(p["feet"])
    u = np.linalg.solve(Kmat, p["f_cycle"][twin_index(p, ctx.session.time_s)].T).T
    return _rigid_motion(u, ctx.target, p["centre"])


def twin_apply(p, ctx, hw):
    return Contribution(displace=twin_shape(p, ctx) / p["k_N_mm"])


def twin_features(p, ctx, hw):
    return twin_shape(p, ctx)[None]


# --------------------------------------------------------------------------------------------- Mullins isolators
MULLINS = {"ur10": ((150.0, 250.0), (2300.0, 4000.0), (30.0, 60.0)),
           "kr16_like": ((300.0, 400.0), (8000.0, 16000.0), (80.0, 150.0)),
           "tool_changer": ((350.0, 450.0), (40000.0, 80000.0), (150.0, 300.0))}


def mullins_force(c, c_m, m):
    """Isolator force per unit virgin rate [mm] at compression ``c``: virgin beyond the largest |c| so far, ``c_m``,
    else the softened reloading curve."""
    a = np.abs(c)
    return np.sign(c) * np.where(a >= c_m, a, c_m * (a / np.maximum(c_m, 1e-12)) ** m)


def mullins_stiffness(c, c_m, m):
    a = np.abs(c)
    return np.where(a >= c_m, 1.0, m * (a / np.maximum(c_m, 1e-12)) ** (m - 1))


def mullins_solve(p, loads):
    """(P, 3): the plate's heave and tilts per unit virgin rate under the weights (P, 3) (:func:`_weights`) in visiting
    order, the isolators' maxima carried from pose to pose (compression c = -(heave + tilt_x y - tilt_y x))."""
    Kmat, a = _rigid_plate(p["feet"])
    c_m, out = p["c_m0"].copy(), np.zeros((len(loads), 3))
    for i, g in enumerate(loads):
        u = np.linalg.solve(Kmat, g)                                   # the linear (virgin) solution to start
        for _ in range(50):
            c = -a @ u
            r = a.T @ mullins_force(c, c_m, p["m"]) + g                  # the isolators' push plus the weights
            if np.abs(r).max() < 1e-10 * (1 + np.abs(g).max()):
                break
            u = u + np.linalg.solve(a.T @ (mullins_stiffness(c, c_m, p["m"])[:, None] * a), r)
        c_m = np.maximum(c_m, np.abs(a @ u))
        out[i] = u
    return out


def mullins_loads(p, ctx, payload=True):
    """(P, 3): the weights on the plate (arm, part, plate) about its centre, :func:`_weights`."""
    m, pos, _ = ctx.mass_state
    m = np.c_[m[:, :-1], m[:, -1] * payload, np.full(len(m), p["m_plate"])]
    pos = np.concatenate([pos, np.broadcast_to(p["origin"], (len(m), 1, 3))], axis=1)
    return _weights(m, pos - p["origin"])


def mullins_draw(ctx, hw, rng):
    (lo, hi), _, plate = MULLINS[ctx.chain.name]
    a_, b_ = rng.uniform(lo, hi, 2)
    yaw = rng.uniform(0, np.pi)
    Rz = kin._rot(Z, yaw)[:2, :2]
    feet = np.array([[a_, b_], [a_, -b_], [-a_, b_], [-a_, -b_]]) @ Rz.T
    p = {"feet": feet, "m": rng.uniform(2.0, 3.5), "m_plate": rng.uniform(*plate),
         "origin": -rng.uniform(20.0, 60.0) * Z, "k_v": rng.uniform(*MULLINS[ctx.chain.name][1])}
    Kmat, a = _rigid_plate(feet)                                       # set-up: the empty arm at the first pose
    p["c_m0"] = np.abs(a @ np.linalg.solve(Kmat, mullins_loads(p, ctx, payload=False)[0])) * rng.uniform(1.0, 1.1, 4)
    return p


def mullins_shape(p, ctx):
    return _rigid_motion(mullins_solve(p, mullins_loads(p, ctx)), ctx.target, p["origin"])


def mullins_apply(p, ctx, hw):
    return Contribution(displace=mullins_shape(p, ctx) / p["k_v"])


def mullins_features(p, ctx, hw):
    return mullins_shape(p, ctx)[None]


# ----------------------------------------------------------------------------------------------- profile frame
FRAME_MM = (150.0, 300.0)
PLATE_MM = 30.0
MODULE_KG = {"ur10": (1.0, 3.0), "kr16_like": (2.0, 5.0), "tool_changer": (5.0, 15.0)}


def frame_moment(p, ctx):
    """(P, 3): the bending moment at the bracket joint [N m], tool frame (the torsion about the member removed)."""
    _, g_t = _gravity_tool(ctx)
    mass = p["m_kg"] + ctx.session.payload_kg
    arm = (p["tip"] - p["root"]) / 1000.0
    M = np.cross(arm, mass[:, None] * g_t)
    e = arm / np.linalg.norm(arm)
    return M - np.outer(M @ e, e)


def frame_draw(ctx, hw, rng):
    T = np.asarray(ctx.probe_mm, float)
    p = {"root": np.array([0.0, 0.0, PLATE_MM]), "tip": T, "m_kg": rng.uniform(*MODULE_KG[ctx.chain.name]),
         "n": rng.uniform(1.0, 2.0), "M_u": 1.0}
    Mmax = np.linalg.norm(frame_moment(p, ctx), axis=1).max()
    p["M_u"] = Mmax / rng.uniform(0.6, 0.85)
    theta = rng.uniform(0.2, 0.5) / np.linalg.norm(T - p["root"])
    p["R_ki"] = Mmax / theta / (1 - (Mmax / p["M_u"]) ** p["n"]) ** (1 / p["n"])   # [N m/rad]
    return p


def frame_shape(p, ctx):
    """(P, 3): the target's displacement per unit joint compliance [mm per rad/(N m)], base frame."""
    Rt, _ = _gravity_tool(ctx)
    M = frame_moment(p, ctx)
    Mn = np.linalg.norm(M, axis=1)
    gain = 1 / (1 - np.minimum(Mn / p["M_u"], 0.999) ** p["n"]) ** (1 / p["n"])
    theta = M * gain[:, None]                                          # rotation vector x R_ki, tool frame
    return np.einsum("pij,pj->pi", Rt, np.cross(theta, p["tip"] - p["root"]))


def frame_apply(p, ctx, hw):
    return Contribution(displace=frame_shape(p, ctx) / p["R_ki"])


def frame_features(p, ctx, hw):
    return frame_shape(p, ctx)[None]


# -------------------------------------------------------------------------------------------------- diaphragm
DIAPHRAGM = {"ur10": ((35.0, 50.0), (1.0, 3.0)), "kr16_like": ((40.0, 55.0), (2.0, 5.0))}
STEEL_E, STEEL_NU = 200e3, 0.3                                         # [N/mm^2]


def diaphragm_draw(ctx, hw, rng):
    if ctx.chain.name not in DIAPHRAGM:
        return {}
    (a_lo, a_hi), (m_lo, m_hi) = DIAPHRAGM[ctx.chain.name]
    p = {"a": rng.uniform(a_lo, a_hi), "beta": rng.uniform(0.44, 0.49), "m_kg": rng.uniform(m_lo, m_hi)}
    Fmax = (p["m_kg"] + ctx.session.payload_kg.max()) * kin.G
    p["F_p"] = rng.uniform(0.0, 0.5) * Fmax
    u = rng.uniform(0.8, 1.6)                                          # w / t at the largest load
    K = 2 * 16 * np.pi * STEEL_E / (12 * (1 - STEEL_NU ** 2))          # two diaphragms
    p["t"] = ((Fmax + p["F_p"]) * p["a"] ** 2 / (K * u * (1 + p["beta"] * u ** 2))) ** 0.25
    return p


def diaphragm_w(p, F):
    """The hub's axial deflection [mm] under the axial force ``F`` [N]: the real root of u + beta u^3 = F a^2 / (2 16 pi
    D t) (Cardano), w = t u."""
    D = STEEL_E * p["t"] ** 3 / (12 * (1 - STEEL_NU ** 2))
    f = np.asarray(F, float) * p["a"] ** 2 / (2 * 16 * np.pi * D * p["t"])
    P_, Q = 1 / p["beta"], -f / p["beta"]
    s = np.sqrt(Q ** 2 / 4 + P_ ** 3 / 27)
    return p["t"] * (np.cbrt(-Q / 2 + s) + np.cbrt(-Q / 2 - s))


def diaphragm_shape(p, ctx):
    Rt, g_t = _gravity_tool(ctx)
    F = p["F_p"] + (p["m_kg"] + ctx.session.payload_kg) * g_t[:, 2]   # along the tool axis, outwards
    return diaphragm_w(p, F)[:, None] * Rt[:, :, 2]


def diaphragm_apply(p, ctx, hw):
    return Contribution(displace=diaphragm_shape(p, ctx) if p else np.zeros((len(ctx.q), 3)))


def diaphragm_features(p, ctx, hw):
    return diaphragm_shape(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))
