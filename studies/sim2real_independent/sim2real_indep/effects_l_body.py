"""Set L body effects (new physics, not in sets A-K): a palletising cell whose robot and pallet stand on one base frame
on levelling feet, the pallet growing as the robot stacks; anchor nuts that loosen under the production cycles, so the
base plate opens at ever smaller moments; a parallel gripper whose fingers, carrying the target, the grip force and the
part's weight spread; a tool on a preloaded radially compliant holder; the guideway of a telescopic stage, whose
straightness and angular error motions follow the stroke. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* pallet on the base frame: compact palletising cells put the robot's column and the pallet places on one welded base
  frame standing on four levelling feet (forkliftable cells, as recalled from cobot-palletiser brochures); a rigid frame
  on four equal feet of stiffness k at (+-a, +-b) sinks by W / 4k and tilts by M_x / 4 k b^2, M_y / 4 k a^2 under the
  weight and moment about its centre (statics of a rigid plate on springs: Timoshenko & Young, *Engineering Mechanics*;
  set G's jacks and set H's platform use the same statics for other loads). The robot's weight and moment and the
  pallet's weight at its place load it; the pallet grows by the boxes stacked during production (4-8 / 6-12 picks a
  minute of the session's mean box, as recalled from palletiser cycle rates) and is taken away full (200-600 / 400-1000
  kg). Feet on rubber pads of log-U(1e6, 1e7) / (3e6, 3e7) N/m, at +-0.4-0.6 x +-0.35-0.5 / +-0.6-0.9 x +-0.5-0.7 m, the
  column 0.2-0.45 / 0.3-0.6 m off the centre and 0.3-0.8 / 0.3-0.6 m high, the pallet 0.6-0.9 / 0.9-1.3 m off the centre
  on the far side (ur10 / kr16_like; assumed). Production between all blocks (the stacking). First drawn with stiffer
  feet (2e6-2e7 / 5e6-4e7 N/m) and smaller pallets (150-350 / 300-700 kg): absorbed or gains below 15 % in trial draws
  on ur10. None on tool_changer.
* anchor self-loosening: transverse micro-slip under each load reversal turns a nut back a little, so an anchor's clamp
  load falls with the number of load cycles (Junker, "New criteria for self-loosening of fasteners under vibration", SAE
  690055, 1969; Jiang, Zhang & Lee, "Study of early stages of self-loosening of bolted joints", J. Mech. Des. 126, 2004:
  a fall roughly linear in log N), here F / F_0 = max(0.2, 1 - s log10(1 + N / N_0)), s 0.2-0.4, N_0 2-10, one cycle per
  20-60 s of production, the anchors re-tightened before the session (assumed). The base plate stays closed until the
  horizontal moment passes the decompression moment, the arm's weight times the plate's half width plus the anchors'
  share, then rocks about its compressed edge at the anchors' compliance (VDI 2230 Part 1 on the opening limit; the
  column-base component method of EN 1993-1-8 6.2.8, as set D's loose anchor); the opening is isotropic (six or more
  anchors on a circle) and its threshold falls as the anchors loosen. Decompression at 0.6-0.9 of the session's largest
  moment at the start, the open compliance 1-4 / the plate stiffness of :mod:`hardware` (as set D), the plate's half
  width 0.35-0.5 m; the tool_changer of a tunnel-boring machine (its heavy overhung cutter loads the base most). The
  plate's elastic tilt is set A's mount and left out: the case isolates the opening. First drawn on all three arms
  (decompression at 0.6-1.0 of the largest moment, s 0.15-0.35, N_0 5-30, 0-300 cycles before the session): on ur10 and
  kr16_like the arm's own weight over the plate's half width holds the plate closed at almost every pose (absorbed or
  ambiguous with the joint model in trial draws); with a lower threshold (0.4-0.7) the opening was nearly linear in the
  moment and the link model (the base column's bending) came within 1.25x; with cycles before the session the loosening
  hardly changed over it (the set's case first had the joint model at 1.19x).
* gripper fingers: a pneumatic or hydraulic parallel gripper presses the part between two fingers with a constant force
  F_g; each finger is a cantilever from its jaw loaded at the contact point a from the root, its tip (where the target
  sits, :func:`effects_l.probe_hook`) moving by F a^2 (3 L - a) / 6 E I (Roark's *Formulas for Stress and Strain*,
  7th ed., Table 8.1, case 1a). While a part is held the grip force spreads the fingers; the part's weight adds half its
  component along the closing axis to the target's finger and bends both, half each, across it. Aluminium fingers of
  15-25 x 8-12 mm with 100-450 N (ur10: the grip forces of cobot grippers, as recalled from their data sheets), steel
  30-40 x 15-22 mm with 300-900 N (kr16_like), steel prongs 60-90 x 25-35 mm with 8-20 kN (tool_changer's hydraulic
  cutter gripper); the finger's length grows with the tip's height (:data:`FINGER_MM`), the contact at 75-95 % of it
  (assumed). First drawn with the prongs 30-50 mm thick (absorbed in a trial draw), then 25-40 mm with 5-15 kN (the
  set's case absorbed, 0.06 mm, once the fingers' length followed the tip's height); kr16_like's fingers, made longer
  for the hot parts (:mod:`effects_l_thermal`), first 20-30 x 10-16 mm; ur10's grip first 100-300 N.
* radially compliant holder: deburring spindles and floating grippers sit on holders that centre the tool with
  preloaded springs and let it move sideways once the side force passes the preload, up to the holder's stroke end
  (radially compliant tool holders, as recalled from ATI / SCHUNK compensation-unit data); a preloaded spring gives no
  motion below its preload and moves at its rate beyond it (Shigley's *Mechanical Engineering Design*, preloaded
  springs): delta = min((|F| - F_p)+ / k, s) along the side force F = m g across the tool axis. Tools of 2-4 / 5-12 kg,
  preload 50-85 % of their weight, rate 20-60 / 40-120 N/mm, stroke end 0.3-0.8 mm on ur10 / kr16_like (assumed). First
  drawn with a preload of 30-70 %, no stroke end and 50-150 / 100-300 N/mm: nearly linear in the side force, which the
  joint model's wrist compliance matched (ambiguous in a trial draw). Scored as link deflection (the end-of-arm
  structure carrying the target, as set K's RCC). None on tool_changer.
* guideway error motions: a linear axis moves with straightness errors across its axis and angular errors (roll, pitch,
  yaw) that are functions of its position (ISO 230-1:2012, the error motions of linear axes; Slocum, *Precision Machine
  Design*, 1992, ch. 2); a welded telescopic section on bolted, shimmed slide pads has straightness deviations of
  0.1-0.3 mm over its stroke and angular deviations of 0.2-0.5 mrad (assumed, heavy-machinery tolerances; first drawn at
  0.05-0.15 mm and 0.1-0.3 mrad: ambiguous with the mount model in a trial draw). Smooth curves over the guide's length:
  Legendre orders 2-4 for the straightness (orders 0-1 are a shift and a tilt of the axis, the geometry's), 1-3 for the
  angles; the distal body turns about the outer section's mouth. The prismatic stage of tool_changer (none on the
  others). Scored as transmission: the joint's motion errors as a function of its own position, as set C's bearing
  runout.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import legendre

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_g_body import _plate_motion
from sim2real_indep.effects_j_body import _logu
from sim2real_indep.effects_l_joint import production_time

Z = np.array([0.0, 0.0, 1.0])


def _gravity_tool(ctx):
    """Gravity (P, 3) [m/s^2] in the tool frame and the tool rotation (P, 3, 3)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return np.einsum("pji,j->pi", Rt, -kin.G * Z), Rt


# --------------------------------------------------------------------------------------------- pallet on frame
#: per arm: feet half-spacings a, b [m], feet stiffness [N/m], column offset and height [m], pallet offset [m], full
#: pallet [kg], picks per minute (assumed)
PALLET = {"ur10": ((0.4, 0.6), (0.35, 0.5), (1e6, 1e7), (0.2, 0.45), (0.3, 0.8), (0.6, 0.9), (200, 600), (4, 8)),
          "kr16_like": ((0.6, 0.9), (0.5, 0.7), (3e6, 3e7), (0.3, 0.6), (0.3, 0.6), (0.9, 1.3), (400, 1000), (6, 12))}


def pallet_draw(ctx, hw, rng):
    if ctx.chain.name not in PALLET:
        return {}
    a, b, k, c, h, d, cap, picks = PALLET[ctx.chain.name]
    phi = rng.uniform(0, 2 * np.pi)
    psi = phi + np.pi + rng.uniform(-np.pi / 4, np.pi / 4)
    box = ctx.session.payload_kg[ctx.session.payload_kg > 0]
    box = box.mean() if len(box) else 5.0
    full = rng.uniform(*cap)
    return {"a_m": rng.uniform(*a), "b_m": rng.uniform(*b), "k_N_per_m": _logu(rng, *k),
            "base_m": np.r_[rng.uniform(*c) * np.array([np.cos(phi), np.sin(phi)]), rng.uniform(*h)],
            "pallet_m": rng.uniform(*d) * np.array([np.cos(psi), np.sin(psi), 0.0]), "full_kg": full,
            "start_kg": rng.uniform(0, 1) * full, "rate_kg_s": box * rng.uniform(*picks) / 60}


def pallet_mass(p, session):
    """The pallet's mass (P,) [kg] at each measurement: stacked during production, taken away when full."""
    return np.mod(p["start_kg"] + p["rate_kg_s"] * production_time(session), p["full_kg"])


def pallet_part(p, ctx):
    """Target displacement (P, 3) [mm] per unit foot compliance [m/N]: the frame's tilt and sink under the robot's and
    the pallet's weight and moments about its centre."""
    m, _, _ = ctx.mass_state
    W = m.sum(axis=1) * kin.G
    Wp = pallet_mass(p, ctx.session) * kin.G
    down = np.c_[np.zeros((len(W), 2)), -np.ones(len(W))]
    M = (eb.mount_moment(ctx) + np.cross(p["base_m"], down * W[:, None])
         + np.cross(p["pallet_m"], down * Wp[:, None]))
    tilt = np.c_[M[:, 0] / (4 * p["b_m"] ** 2), M[:, 1] / (4 * p["a_m"] ** 2)]
    return _plate_motion(ctx, tilt, 1000.0 * (W + Wp) / 4, -1000.0 * p["base_m"])


def pallet_apply(p, ctx, hw):
    return Contribution(displace=pallet_part(p, ctx) / p["k_N_per_m"] if p else None)


def pallet_features(p, ctx, hw):
    return pallet_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------ anchor loosening
#: per arm: the base plate's half width [m] (assumed)
PLATE_HALF_M = {"tool_changer": (0.35, 0.50)}


def loose_draw(ctx, hw, rng):
    if ctx.chain.name not in PLATE_HALF_M:
        return {}
    M = np.linalg.norm(eb.mount_moment(ctx)[:, :2], axis=1)
    m, _, _ = ctx.mass_state
    R = rng.uniform(*PLATE_HALF_M[ctx.chain.name])
    M_w = (m.sum(axis=1) * kin.G).min() * R
    return {"R_m": R, "M_anchor_Nm": max(rng.uniform(0.6, 0.9) * M.max() - M_w, 0.0),
            "s": rng.uniform(0.2, 0.4), "N0": rng.uniform(2, 10), "cycle_s": rng.uniform(20, 60),
            "c_open": rng.uniform(1.0, 4.0) / min(hw["mount"]["k_plate"]),
            "h_mm": hw["mount"]["height_mm"]}


def clamp_share(p, session):
    """The anchors' clamp load (P,) as a share of the first: Junker's fall, linear in log N of the cycles."""
    N = production_time(session) / p["cycle_s"]
    return np.maximum(0.2, 1 - p["s"] * np.log10(1 + N / p["N0"]))


def decompression(p, ctx):
    """Decompression moment (P,) [N m]: the weight's about the plate's edge and the loosening anchors' share."""
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G * p["R_m"] + p["M_anchor_Nm"] * clamp_share(p, ctx.session)


def loose_part(p, ctx):
    """Target displacement (P, 3) [mm] per unit open compliance [rad/(N m)]: the plate rocking about its compressed
    edge by the moment in excess of the decompression moment, in the moment's direction."""
    M = eb.mount_moment(ctx) * np.array([1.0, 1.0, 0.0])
    n = np.linalg.norm(M, axis=1)
    u = M / np.maximum(n, 1e-12)[:, None]
    omega = u * np.maximum(n - decompression(p, ctx), 0.0)[:, None]
    edge = -1000.0 * p["R_m"] * np.cross(Z, u) - p["h_mm"] * Z
    return np.cross(omega, ctx.target - edge)


def loose_apply(p, ctx, hw):
    return Contribution(displace=p["c_open"] * loose_part(p, ctx) if p else None)


def loose_features(p, ctx, hw):
    return loose_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------- gripper fingers
#: per arm: finger section width b, thickness t [m] (along the closing axis), E [Pa], grip force [N] (assumed)
FINGER = {"ur10": ((0.015, 0.025), (0.008, 0.012), 70e9, (100, 450)),
          "kr16_like": ((0.030, 0.040), (0.015, 0.022), 210e9, (300, 900)),
          "tool_changer": ((0.060, 0.090), (0.025, 0.035), 210e9, (8e3, 20e3))}
#: per arm: the finger's length [mm] and the tip height beyond the flange [mm] (assumed); the finger the longer the
#: higher the tip (the gripper's body the rest), the target on the tip (:func:`effects_l.probe_hook`)
FINGER_MM = {"ur10": (60.0, 110.0), "kr16_like": (150.0, 250.0), "tool_changer": (150.0, 250.0)}
FINGER_TIP_MM = {"ur10": (130.0, 220.0), "kr16_like": (250.0, 400.0), "tool_changer": (300.0, 500.0)}


def finger_geometry(probe_mm):
    """Closing axis d (3,) (towards the target's finger), the target's half opening and tip height [mm]."""
    d = np.array([probe_mm[0], probe_mm[1], 0.0])
    w = np.linalg.norm(d)
    return d / w, w, float(probe_mm[2])


def finger_length(robot_key, z_tip):
    """The finger's length [mm] at tip height ``z_tip`` [mm]: the arm's range mapped onto its tip heights."""
    (L0, L1), (z0, z1) = FINGER_MM[robot_key], FINGER_TIP_MM[robot_key]
    return L0 + (L1 - L0) * float(np.clip((z_tip - z0) / (z1 - z0), 0.0, 1.0))


def tip_compliance(L, a, EI):
    """Tip deflection [m/N] of a cantilever of length L under a force at a from its root: a^2 (3 L - a) / 6 EI (Roark,
    Table 8.1, case 1a)."""
    return a * a * (3 * L - a) / (6 * EI)


def grip_draw(ctx, hw, rng):
    (b0, b1), (t0, t1), E, (f0, f1) = FINGER[ctx.chain.name]
    d, w, z_tip = finger_geometry(ctx.probe_mm)
    L = finger_length(ctx.chain.name, z_tip) / 1000
    a = rng.uniform(0.75, 0.95) * L
    b, t = rng.uniform(b0, b1), rng.uniform(t0, t1)
    return {"d": d, "F_g_N": rng.uniform(f0, f1), "L_m": L, "a_m": a, "b_m": b, "t_m": t, "E": E,
            "c_mm_per_N": 1000 * np.array([tip_compliance(L, a, E * b * t ** 3 / 12),
                                           tip_compliance(L, a, E * t * b ** 3 / 12)])}


def grip_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per unit finger compliance [mm/N] along the closing axis (grip force while a
    part is held and half the part's weight along it) and across it (half the part's weight across)."""
    g, Rt = _gravity_tool(ctx)
    m = ctx.session.payload_kg
    held = (m > 0).astype(float)
    d = p["d"]
    e = np.cross(Z, d)
    along = (p["F_g_N"] * held + 0.5 * m * (g @ d))[:, None] * d
    across = (0.5 * m * (g @ e))[:, None] * e
    return np.array([np.einsum("pij,pj->pi", Rt, along), np.einsum("pij,pj->pi", Rt, across)])


def grip_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["c_mm_per_N"], grip_parts(p, ctx)))


def grip_features(p, ctx, hw):
    return grip_parts(p, ctx)


# --------------------------------------------------------------------------------------- compliant holder
#: per arm: tool mass [kg], spring rate beyond the preload [N/mm] (assumed)
FLOAT = {"ur10": ((2.0, 4.0), (20.0, 60.0)), "kr16_like": ((5.0, 12.0), (40.0, 120.0))}


def float_draw(ctx, hw, rng):
    if ctx.chain.name not in FLOAT:
        return {}
    (m0, m1), (k0, k1) = FLOAT[ctx.chain.name]
    m = rng.uniform(m0, m1)
    return {"m_tool_kg": m, "F_p_N": rng.uniform(0.5, 0.85) * m * kin.G, "k_N_per_mm": rng.uniform(k0, k1),
            "stroke_mm": rng.uniform(0.3, 0.8)}


def float_part(p, ctx):
    """Target displacement (P, 3) [mm]: the tool moved along the side force of its and the part's weight by its excess
    over the preload at the holder's rate, up to the holder's stroke end."""
    g, Rt = _gravity_tool(ctx)
    F = (p["m_tool_kg"] + ctx.session.payload_kg)[:, None] * g * np.array([1.0, 1.0, 0.0])
    n = np.linalg.norm(F, axis=1)
    move = np.minimum(np.maximum(n - p["F_p_N"], 0.0) / p["k_N_per_mm"], p["stroke_mm"])
    return np.einsum("pij,pj->pi", Rt, F * (move / np.maximum(n, 1e-12))[:, None])


def float_apply(p, ctx, hw):
    return Contribution(displace=float_part(p, ctx) if p else None)


def float_features(p, ctx, hw):
    return float_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))


# ---------------------------------------------------------------------------------------------- guideway
#: per arm: straightness [mm] and angular [rad] error scales (assumed)
GUIDE = {"tool_changer": ((0.1, 0.3), (2e-4, 5e-4))}
GUIDE_PARTS = ("vertical", "horizontal", "roll", "pitch", "yaw")


def guide_draw(ctx, hw, rng):
    idx = np.flatnonzero(~ctx.chain.revolute)
    if ctx.chain.name not in GUIDE or not len(idx):
        return {}
    j = int(idx[0])
    (s0, s1), (r0, r1) = GUIDE[ctx.chain.name]
    s_lin, s_ang = rng.uniform(s0, s1), rng.uniform(r0, r1)
    coef = {}
    for name in GUIDE_PARTS:
        lin = name in ("vertical", "horizontal")
        orders = (2, 3, 4) if lin else (1, 2, 3)
        c = np.zeros(5)
        for k in orders:
            c[k] = rng.uniform(-1, 1) * (s_lin / (k - 1) if lin else s_ang / k)
        coef[name] = c
    return {"joint": j, "lo": float(ctx.chain.lower[j]), "hi": float(ctx.chain.upper[j]), "coef": coef}


def guide_curves(p, u):
    """The error motions (5, P) at strokes ``u`` [mm]: straightness [mm] and angles [rad]."""
    xi = (2 * np.asarray(u) - p["lo"] - p["hi"]) / (p["hi"] - p["lo"])
    return np.array([legendre.legval(xi, p["coef"][name]) for name in GUIDE_PARTS])


def guide_parts(p, ctx):
    """Target displacement (5, P, 3) [mm] of each error motion's curve."""
    j, ch = p["joint"], ctx.chain
    R, _ = kin.body_transforms(ch, ctx.q)
    _, c = kin.joint_frames(ch, ctx.q)
    e_a = ch.axes[j]
    e_v = Z - (Z @ e_a) * e_a
    e_v = e_v / np.linalg.norm(e_v)
    e_h = np.cross(e_v, e_a)
    f = guide_curves(p, ctx.q[:, j])
    Rj = R[:, j + 1]
    ax = [np.einsum("pij,j->pi", Rj, v) for v in (e_v, e_h, e_a)]
    r = ctx.target - c[:, j]
    return np.array([ax[0] * f[0][:, None], ax[1] * f[1][:, None], np.cross(ax[2] * f[2][:, None], r),
                     np.cross(ax[1] * f[3][:, None], r), np.cross(ax[0] * f[4][:, None], r)])


def guide_apply(p, ctx, hw):
    return Contribution(displace=guide_parts(p, ctx).sum(axis=0) if p else None)


def guide_features(p, ctx, hw):
    return guide_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))
