"""Set O joint effects (new physics, not in sets A-N): the joints twisted by a milling spindle's cutting force and
torque; the joints twisted by a nutrunner's reaction moment while it holds a bolt's torque; the lost motion of the
axes that carry little gravity torque, whose flank the cutting load chooses; the hysteresis band of output-side
encoders that close the position loop; the count quantisation of such encoders and their stopping dead band; and the
static transmission error of a ring-gear axis at its tooth-mesh frequency. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* cutting force: the mechanistic model of peripheral milling (Altintas, *Manufacturing Automation*, 2nd ed., 2012, ch.
  2; Budak, Altintas & Armarego, "Prediction of milling force coefficients from orthogonal cutting data", J. Manuf. Sci.
  Eng. 118, 1996): a tooth at immersion phi cuts a chip h = f_z sin(phi) and takes the tangential, radial and axial
  forces K_tc a_p h + K_te a_p, K_rc a_p h + K_re a_p, K_ac a_p h; averaged over the spindle's turn (N teeth, the cutter
  in cut from phi_st to phi_ex: slotting, up- or down-milling at half immersion) they give the mean feed, normal and
  axial forces and the torque (D / 2) x mean tangential force. Aluminium alloys: K_tc 600-900 N/mm^2, K_rc 0.3-0.45
  K_tc, K_ac 0.1-0.25 K_tc, edge coefficients 15-30 / 20-40 N/mm (Altintas' tables, as recalled). The feed direction
  changes along the contour, so each measured pose (an in-process measurement, as in robotic machining with a tracker's
  feedback: Nikon / Metris "Adaptive Robot Control") sees its own direction across the tool axis. Robots milling deflect
  by tenths of a millimetre under such forces (Abele, Weigold & Rothenbucher, "Modeling and identification of an
  industrial robot for machining applications", CIRP Annals 56(1), 2007; Pan & Zhang, "Robotic machining from
  programming to process control", RCIM 25, 2009). A deburring spindle on ur10 (2-3 teeth, 6-12 mm, a_p 0.5-1.5 mm, f_z
  0.02-0.05 mm) and a finishing cut on kr16_like (2-3 teeth, 8-16 mm, a_p 0.3-1 mm, f_z 0.03-0.06 mm; assumed; first a
  roughing cut of 2-4 teeth, 10-20 mm, a_p 1.5-4 mm, f_z 0.05-0.12 mm -- up to 9 mm at the tool, the wrist's strain-wave
  gears loaded past their rating --, then a_p 0.5-1.5 mm, f_z 0.03-0.08 mm: 1.9 mm). The spindle sits on a bracket
  across the flange (:func:`effects_o.probe_hook`); the joints carry tau = J^T F + w . M (Craig, *Introduction to
  Robotics*, ch. 5) and twist with the linear gear stiffness of :mod:`hardware`; the spindle's weight is set A's
  compliance and left out. Cases with several set-O cutting kinds share one cut (``hw["cut"]``).
* nutrunner reaction: a robot-held nutrunner without a reaction arm passes the tightening torque's reaction to the
  flange (light screwdriving cells; the nutrunner's torque-hold step while the tracker measures; ISO 5393 on the
  reaction of rotary tools, as recalled); a bolt's breakaway torque on removal is 0.7-0.9 of its tightening torque
  (Bickford, *An Introduction to the Design and Behavior of Bolted Joints*, 4th ed., 2008, ch. 5, as recalled). Blocks
  alternate removing (loosening) and fitting (tightening) fasteners. M8-M12 screws, 15-60 N m on kr16_like; the
  tunnel machine's cutter-housing wedge bolts, 200-450 N m on tool_changer (assumed). The joints carry w_j . M (the
  moment about each revolute axis) and twist with the linear gear stiffness.
* cut flank: axes 1, 4 and 6 carry little gravity torque, so their drag keeps them on the flank of their last motion
  (the output trails by b / 2; Nordin & Gutman, "Controlling mechanical systems with backlash -- a survey", Automatica
  38, 2002) unless a torque beats the drag: here the cutting load's torque on the axis, with the gravity torque
  (:func:`physics.backlash_offset`). Lost motion 0.8-2 arcmin of a worn strain-wave gear, 0.6-1.5 arcmin of a cycloid
  axis 1 (catalogue 1 arcmin), drag 0.5-1.5 % of the rated torque; the flank at each pose is computed once from the
  true loads (a shape parameter, as set N's counterbalanced lash). The gears' twist under the cut is milling_force's.
* encoder hysteresis: an output-side absolute encoder closing the position loop (dual-encoder joints) reports a new
  value only after the angle has moved past a hysteresis band -- the digital hysteresis its interface applies against
  flicker (ams AS5047P / iC-Haus iC-MU data sheets, configurable 0-3 LSB) and the magnetic hysteresis of
  magnetoresistive sensors -- so its reading trails the motion by h / 2; the controller servoes the reading, and the
  joint overshoots by h / 2 in the direction of its last motion (a play operator on the reading: Krasnosel'skii &
  Pokrovskii, *Systems with Hysteresis*, 1989). 15-bit readings with 1-3 LSB on ur10 and kr16_like, 16-bit with 1-3 LSB
  on tool_changer's hydraulic axes (axes 1-3; assumed).
* quantisation stop: a position loop closed on a quantised output reading cannot settle between counts; drives stop
  at the first count inside their in-position band (a dead band against hunting; Ellis, *Control System Design
  Guide*, 4th ed., 2012, ch. 14 on resolution and limit cycles), so an axis approaching from below stops at the lower
  edge of the target count, from above at its upper edge: e = Delta (1/2 - frac(q / Delta - phi0)) - d Delta / 2,
  Delta = 2 pi / 2^bits, phi0 the count grid's phase against the joint's zero (its calibration). 14-15 bits on ur10's
  axes 1-3 (a low-cost output encoder), 15-16 bits on kr16_like's (its secondary encoders, as set N's magnetic
  encoders) and tool_changer's (assumed).
* mesh transmission error: a pinion on a ring gear (axis 1; set E's ring gear, set K's thermal backlash) has a static
  transmission error at the tooth-mesh frequency and its harmonic from the teeth's profile deviations (Welbourn,
  "Fundamental knowledge of gear noise -- a survey", IMechE Conf. Noise and Vibration of Engines and Transmissions,
  1979; Smith, *Gear Noise and Vibration*, 2nd ed., 2003, ch. 2; ISO 1328-1 profile form and slope deviations of
  20-50 um for hobbed, unground ring gears of modules 4-10, grades 9-11, as recalled; first 15-45 um: a trial draw at
  another seed gained 20 %, the link model at 1.24x): TE = sum_h A_h sin(h Z q + phi_h) at the pitch radius, h = 1,
  2, A_2 0.3-0.6 A_1 -- a different source from set E's cumulative pitch deviation
  (long-wave) and set L's pin spacing. Z 100-140 teeth at 250-350 mm pitch radius on kr16_like, 140-200 at 500-700 mm
  on tool_changer (assumed); the motor side holds its angle, so the output is off by TE / r.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_f_joint as fj
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all
from sim2real_indep.effects_m_joint import block_index

Z = np.array([0.0, 0.0, 1.0])


def moment_loads(ctx, M):
    """Joint loads (P, n) [N m] of moments M (P, 3) [N m] on the last body: the moment about each revolute axis."""
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    return np.where(ctx.chain.revolute, np.einsum("pji,pi->pj", w, M), 0.0)


# -------------------------------------------------------------------------------------------------- the cutting
#: per arm: teeth, cutter diameter [mm], axial depth a_p [mm], feed per tooth f_z [mm] (assumed)
MILL = {"ur10": ((2, 4), (6.0, 12.0), (0.5, 1.5), (0.02, 0.05)),
        "kr16_like": ((2, 4), (8.0, 16.0), (0.3, 1.0), (0.03, 0.06))}
IMMERSION = {"slot": (0.0, np.pi), "up": (0.0, np.pi / 2), "down": (np.pi / 2, np.pi)}


def mean_cut(c, n=400):
    """Mean feed, normal and axial force [N] and the spindle torque [N m] over a turn (Altintas, ch. 2)."""
    phi = np.linspace(*IMMERSION[c["mode"]], n)
    h = c["fz_mm"] * np.sin(phi)
    Ft = c["Ktc"] * c["ap_mm"] * h + c["Kte"] * c["ap_mm"]
    Fr = c["Krc"] * c["ap_mm"] * h + c["Kre"] * c["ap_mm"]
    Fa = c["Kac"] * c["ap_mm"] * h
    mean = lambda f: c["N"] / (2 * np.pi) * np.trapezoid(f, phi)                                  # noqa: E731
    F = np.array([mean(-Ft * np.cos(phi) - Fr * np.sin(phi)), mean(Ft * np.sin(phi) - Fr * np.cos(phi)), -mean(Fa)])
    return F, c["D_mm"] / 2000.0 * mean(Ft)


def cut_draw(ctx, hw, rng):
    """The cut's parameters (drawn once per case and shared by its set-O cutting kinds through ``hw["cut"]``)."""
    if "cut" in hw:
        return hw["cut"]
    (n0, n1), D, ap, fz = MILL[ctx.chain.name]
    Ktc = rng.uniform(600.0, 900.0)
    c = {"N": int(rng.integers(n0, n1)), "D_mm": rng.uniform(*D), "ap_mm": rng.uniform(*ap), "fz_mm": rng.uniform(*fz),
         "Ktc": Ktc, "Krc": rng.uniform(0.3, 0.45) * Ktc, "Kac": rng.uniform(0.1, 0.25) * Ktc,
         "Kte": rng.uniform(15.0, 30.0), "Kre": rng.uniform(20.0, 40.0),
         "mode": str(rng.choice(list(IMMERSION))), "psi": rng.uniform(0, 2 * np.pi, len(ctx.q))}
    hw["cut"] = c
    return c


def spindle_tip(probe_mm):
    """The cutter's tip (3,) in the tool frame for a target on the spindle's nose (:func:`effects_o.probe_hook`)."""
    from sim2real_indep.effects_o_body import SPINDLE_NOSE_MM, spindle_axis
    d, a, _ = spindle_axis(probe_mm)
    return a * d + (probe_mm[2] + SPINDLE_NOSE_MM) * Z


def cut_loads_tool(c):
    """The cutting force (P, 3) [N] and moment (P, 3) [N m] on the tool, tool frame: the feed frame turned by psi."""
    F, T = mean_cut(c)
    cs, sn = np.cos(c["psi"]), np.sin(c["psi"])
    Ft = np.stack([F[0] * cs - F[1] * sn, F[0] * sn + F[1] * cs, np.full_like(cs, F[2])], axis=1)
    return Ft, np.broadcast_to(-T * Z, Ft.shape)


def cut_joint_loads(c, ctx):
    """Joint loads (P, n) of the cut: the force at the cutter's tip and the spindle's reaction torque."""
    p, Rt = kin.flange(ctx.chain, ctx.q)
    Ft, Mt = cut_loads_tool(c)
    tip = p + Rt @ spindle_tip(ctx.probe_mm)
    F, M = np.einsum("pij,pj->pi", Rt, Ft), np.einsum("pij,pj->pi", Rt, Mt)
    return fj.point_loads(ctx, ctx.chain.n, tip, F) + moment_loads(ctx, M)


def milling_draw(ctx, hw, rng):
    return cut_draw(ctx, hw, rng) if ctx.chain.name in MILL else {}


def milling_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, cut_joint_loads(p, ctx)) if p else None)


def milling_features(p, ctx, hw):
    return _stack(_load_cols(ctx, cut_joint_loads(p, ctx)) if p else [], len(ctx.q))


# -------------------------------------------------------------------------------------------- nutrunner reaction
#: per arm: tightening torque [N m] (assumed)
BOLT_NM = {"kr16_like": (15.0, 60.0), "tool_changer": (200.0, 450.0)}


def bolt_draw(ctx, hw, rng):
    if ctx.chain.name not in BOLT_NM:
        return {}
    B = int(block_index(ctx.session)[-1]) + 1
    first = float(rng.choice([-1.0, 1.0]))
    sense = first * (-1.0) ** np.arange(B)                          # removing and fitting alternate
    return {"T_Nm": rng.uniform(*BOLT_NM[ctx.chain.name]), "k_loose": rng.uniform(0.7, 0.9), "sense": sense}


def bolt_moment(p, ctx):
    """The reaction moment (P, 3) [N m] on the flange: +T along the tool axis while fitting, -k T while removing."""
    s = p["sense"][block_index(ctx.session)]
    mag = p["T_Nm"] * np.where(s > 0, 1.0, p["k_loose"]) * s
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return mag[:, None] * Rt[:, :, 2]


def bolt_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, moment_loads(ctx, bolt_moment(p, ctx))) if p else None)


def bolt_features(p, ctx, hw):
    return _stack(_load_cols(ctx, moment_loads(ctx, bolt_moment(p, ctx))) if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------------- cut flank
LASH_JOINTS = (0, 3, 5)


def flank_draw(ctx, hw, rng):
    if ctx.chain.name not in MILL:
        return {}
    c = dict(cut_draw(ctx, hw, rng))
    tau = cut_joint_loads(c, ctx) + ctx.loads
    b, side, drag = [], [], []
    for j in LASH_JOINTS:
        d = hw["drives"][j]
        b.append((rng.uniform(0.8, 2.0) if d["kind"] == "HD" else rng.uniform(0.6, 1.5)) * ph.ARCMIN)
        drag.append(rng.uniform(0.005, 0.015) * d["T_rated"])
        side.append(ph.backlash_offset(ctx.session.direction[:, j], tau[:, j], drag[-1], 2.0, 0.0))
    return {"cut": c, "b_rad": np.array(b), "drag_Nm": np.array(drag), "side": np.array(side)}


def flank_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, list(LASH_JOINTS)] = (p["b_rad"][:, None] / 2 * p["side"]).T
    return Contribution(dq=dq)


def flank_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(j, s) for j, s in zip(LASH_JOINTS, p["side"])])


# ---------------------------------------------------------------------------------------- encoder hysteresis
ENC_JOINTS = (0, 1, 2)
#: per arm: the output encoders' bits (assumed)
ENC_BITS = {"ur10": 15, "kr16_like": 15, "tool_changer": 16}


def hyst_draw(ctx, hw, rng):
    lsb = 2 * np.pi / 2 ** ENC_BITS[ctx.chain.name]
    return {"joints": list(ENC_JOINTS), "h_rad": rng.uniform(1.0, 3.0, len(ENC_JOINTS)) * lsb}


def hyst_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = p["h_rad"] / 2 * ctx.session.direction[:, p["joints"]]
    return Contribution(dq=dq)


def hyst_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, ctx.session.direction[:, j]) for j in p["joints"]])


# ---------------------------------------------------------------------------------------- quantisation stop
#: per arm: the output encoders' bits (assumed)
LSB_BITS = {"ur10": (14, 16), "kr16_like": (15, 17), "tool_changer": (15, 17)}


def lsb_draw(ctx, hw, rng):
    if ctx.chain.name not in LSB_BITS:
        return {}
    bits = rng.integers(*LSB_BITS[ctx.chain.name], len(ENC_JOINTS))
    return {"joints": list(ENC_JOINTS), "delta_rad": 2 * np.pi / 2.0 ** bits, "phi0": rng.uniform(0, 1, len(bits))}


def lsb_signals(p, ctx):
    """(m, P): the stopping error per count, 1/2 - frac(q / Delta - phi0) - d / 2."""
    q, d = ctx.q[:, p["joints"]], ctx.session.direction[:, p["joints"]]
    x = q / p["delta_rad"] - p["phi0"]
    return (0.5 - (x - np.floor(x)) - d / 2).T


def lsb_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = (p["delta_rad"][:, None] * lsb_signals(p, ctx)).T
    return Contribution(dq=dq)


def lsb_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], lsb_signals(p, ctx))])


# ------------------------------------------------------------------------------------ mesh transmission error
#: per arm: ring teeth, pitch radius [mm] (assumed)
MESH = {"kr16_like": ((100, 141), (250.0, 350.0)), "tool_changer": ((140, 201), (500.0, 700.0))}


def mesh_draw(ctx, hw, rng):
    if ctx.chain.name not in MESH:
        return {}
    (z0, z1), r = MESH[ctx.chain.name]
    A1 = rng.uniform(20e-3, 50e-3)
    return {"Z": int(rng.integers(z0, z1)), "r_mm": rng.uniform(*r), "A_mm": np.array([A1, rng.uniform(0.3, 0.6) * A1]),
            "phase": rng.uniform(0, 2 * np.pi, 2)}


def mesh_signals(p, ctx):
    q = ctx.q[:, 0]
    return np.array([np.sin(h * p["Z"] * q + p["phase"][h - 1]) for h in (1, 2)])


def mesh_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 0] = p["A_mm"] @ mesh_signals(p, ctx) / p["r_mm"]
    return Contribution(dq=dq)


def mesh_features(p, ctx, hw):
    return np.array([ctx.joint_feature(0, s) for s in mesh_signals(p, ctx)]) if p else np.zeros((0, len(ctx.q), 3))
