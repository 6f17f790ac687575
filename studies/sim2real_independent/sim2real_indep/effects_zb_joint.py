"""Set ZB joint effects (new physics, not in sets A-ZA): a torque-controlled arm in joint-impedance mode whose stiffness
preset is changed for each block; a process hose wrapped round the wrist by axis 6 and pulling the flange towards the
elbow once it is taut; positive-locking (notched) holding brakes that let a gravity-loaded axis settle onto the next
notch; a friction-compensation pulse left over after each reversal of a main axis; a two-track (nonius) absolute
encoder decoding one fine period wrong where its tracks' phase error is largest; and joint targets sent over a
fieldbus as integers of 0.01 deg. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* impedance preset: torque-controlled arms (KUKA LBR iiwa, Franka) hold a pose in joint-impedance control, tau = K (q_d
  - q) + g_model(q) (Albu-Schaeffer, Ott & Hirzinger, "A unified passivity-based control framework for position, torque
  and impedance control of flexible joint robots", IJRR 26, 2007): the joint settles off its target by the model's
  gravity error over the set stiffness. The application's presets soften the wrist (axes 4-6, for compliant assembly)
  and keep the main axes at their stiff default. The controller's load data hold the arm but not the part (the payload
  is changed per block, logged; the load data are not updated) and the arm's model is off by e 3-8 % of its own load
  (assumed): dq_j = (tau_part + e tau_arm)_j / K_j. The preset ("soft" / "medium" / "stiff", set over more than an order
  of magnitude) is chosen per block, s_b log-uniform 0.2-5 times a reference K_j proportional to the joint's gear
  stiffness (unlogged). Sized so that the session's largest target offset is 0.25-0.6 mm. First on all six axes with
  0.15-0.4 mm and s_b 0.3-3 (ZB01: a gain of 19 %, the link model at 1.09x), then 0.25-0.6 mm and s_b 0.2-5 (the link
  model still at 1.20-1.24x: the main axes' twist under the part looks like a beam's sag), now the wrist alone. Unlike
  the gear compliances of sets A-ZA (the hardware's stiffness), the stiffness is a control setting changed per block.
  Driven by the pose and the payload (logged) and the preset (not logged). The true structure: one column per block (the
  block's residual torque through the reference compliance), amplitudes A / s_b.
* hose wrap: a process hose (welding, dispensing) clamped on the forearm at the elbow and on the tool at radius r from
  axis 6 lies slack around its neutral angle; turned further, it wraps round the flange and, once its slack s is used
  up, stretches: T = k_h (r |q6 - q6_0| - s)+, pulling the flange towards the elbow clamp (dress-pack design: hose
  stretch and wrap limits of axis 6 in the makers' dress-pack manuals, as recalled; the hose as a linear spring). The
  joints yield by their compliance: dq = C J_f^T T u (Craig, *Introduction to Robotics*, ch. 5, static forces). Slack
  50-100 deg of axis 6, sized so that the largest pull moves the target 0.2-0.5 mm (a pressurised welding package; first
  0.1-0.35 mm: ZB09 gained 20 %, the transmission model at 1.25x). Unlike set V's coiled cord or set T's capstan-held
  hose (a pull set by the clamp's position or the guide's friction), the pull follows axis 6's wrap. Driven by q6 and
  the pose (logged). The true structure: one column, amplitude k_h [N/mm].
* pawl notch: a positive-locking holding brake (a solenoid pin dropping into a notched ring on the motor shaft; a
  toothed brake) engages at each dwell with the servo off (energy-saving standstill, as set F's brake hub); a
  gravity-loaded axis turns from its target until the pin meets the next notch wall in the load's direction, so the
  output stands off by the fraction of a notch pitch 2 pi / (Z i) the pin still had to go (ratchet-and-pawl kinematics:
  Shigley, *Mechanical Engineering Design*, brakes and clutches, as recalled); an axis whose load is below the motor's
  drag (5-10 % of the session's largest) stays. Z 150-300 notches (a face-toothed locking ring), ratio 100-160, axes 2
  and 3 (first Z 60-120: up to 1.7-1.8 mm at the tool on ZB08 and ZB10, beyond the set's range). Unlike set F's brake
  hub (a friction disc's play on its hub: a fixed half-play by load sign), the offset is a sawtooth of the joint's
  angle. Driven by the joint angles and the load (logged). The true structure: one column per axis (the fraction of a
  pitch with its sign), amplitudes the pitches [rad].
* reversal pulse: controllers add a friction-compensation pulse (a "quadrant glitch" compensation) to the command each
  time an axis reverses (Tung, Anwar & Tomizuka, "Low velocity friction compensation and feedforward solution based on
  repetitive control", ASME J. Dyn. Syst. 115, 1993; SINUMERIK "friction compensation with adaptive characteristic");
  mistuned, it leaves the axis e_j past its target in the new direction after a reversal, while a move in the same
  direction as the last leaves none. e_j 0.05-0.3 mrad on axes 1-3 (assumed). Unlike set Q's backlash compensation (a
  shift in the motion's direction whatever came before), the error needs a reversal. Driven by the directions of the
  last two moves (logged: ``dir1``...). The true structure: one column per axis, amplitudes e_j [rad].
* nonius slip: a multi-track absolute encoder finds its position from the phase difference of two tracks (the nonius
  principle; HEIDENHAIN, *Angle encoders with integral bearing*, absolute tracks, as recalled); a slow phase error e
  cos(q - c) between the tracks (an eccentricity of one, in fine periods) beyond half a period makes the decoder pick
  the neighbouring fine period: the reading jumps by 2 pi / N inside a window of angles. N 8192 or 16384 fine periods
  (tool_changer's larger rings 16384 or 32768; first 16384 or 32768 on every arm: ZB02 gained 23 %, the joint model at
  1.24x; 8192 on tool_changer moved its target 1.9 mm on a trial seed), e 0.55-0.8, the window's centre at 30-70 % of
  the session's range of an axis 1-3. Unlike set ZA's scratch (a step at one angle) or set T's soiled disc (a smooth
  error), the error is one period inside a window. Driven by the joint's angle (logged). The true structure: one column,
  amplitude the signed period [rad].
* fieldbus rounding: a cell PLC sends the joint targets to the robot as 16-bit integers of 0.01 deg (0.01 mm for a
  prismatic axis), converted by REAL_TO_INT (rounding) or TRUNC (towards zero) (IEC 61131-3 type conversions); the
  cell's log holds the planner's full-precision targets. Unlike set G's ratio rounding or set O's encoder counts (the
  drive's own quantisation), the command is quantised before the robot sees it. Driven by the joint angles (logged). The
  true structure: one column (the quantisation residual of every joint), amplitude 1.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import _features_of_dq


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ----------------------------------------------------------------------------------------------- impedance preset
def residual_torque(p, ctx):
    """(P, n) the gravity-model error the impedance holds: the part's load and e of the arm's own [N m / N]."""
    m, pos, body = ctx.mass_state
    part = np.zeros_like(m)
    part[:, -1] = m[:, -1]
    tau_part = kin.gravity_loads(ctx.chain, ctx.q, part, pos, body)
    return tau_part + p["e"] * (ctx.loads - tau_part)


IMPEDANCE_JOINTS = (3, 4, 5)   # the wrist, softened by the presets (the main axes stay at their stiff default)


def impedance_features(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    on = [j for j in IMPEDANCE_JOINTS if ctx.chain.revolute[j]]
    dq[:, on] = (compliance(hw)[None] * residual_torque(p, ctx))[:, on]
    b = np.minimum(block_index(ctx.session), len(p["s"]) - 1)
    return np.array([_features_of_dq(ctx, dq * (b == k)[:, None]) for k in range(len(p["s"]))])


def impedance_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"e": rng.uniform(0.03, 0.08), "s": np.exp(rng.uniform(np.log(0.2), np.log(5.0), nb))}
    F = impedance_features(p, ctx, hw)
    size = np.linalg.norm(np.einsum("k,kpi->pi", 1 / p["s"], F), axis=1).max()
    p["A"] = rng.uniform(0.25, 0.6) / max(size, 1e-12)
    p["amp"] = p["A"] / p["s"]
    return p


def impedance_apply(p, ctx, hw):
    return _amp_apply(p["amp"], impedance_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- hose wrap
WRAP_JOINT = 5


def hose_stretch(p, ctx):
    """(P,) the hose's stretch beyond its slack [mm]."""
    return np.clip(p["r_mm"] * np.abs(ctx.q[:, WRAP_JOINT] - p["q0"]) - p["slack_mm"], 0.0, None)


def hose_unit(p, ctx, hw):
    """(P, 3) the target's displacement per unit hose stiffness [mm per N/mm]."""
    pf, _ = kin.flange(ctx.chain, ctx.q)
    _, c = kin.joint_frames(ctx.chain, ctx.q)
    u = c[:, 2] - pf
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    Jf = kin.position_jacobian(ctx.chain, ctx.q, pf)                       # (P, 3, n) [mm/rad, mm/mm]
    tau = np.einsum("pij,pi->pj", Jf, u) * hose_stretch(p, ctx)[:, None]  # [N mm per N/mm; N per N/mm]
    tau[:, ctx.chain.revolute] /= 1000.0                                   # revolute joints: [N m per N/mm]
    return _features_of_dq(ctx, compliance(hw)[None] * tau)


def hose_draw(ctx, hw, rng):
    q6 = ctx.q[:, WRAP_JOINT]
    p = {"r_mm": rng.uniform(60.0, 100.0), "q0": 0.5 * (q6.min() + q6.max()) + np.deg2rad(rng.uniform(-30, 30))}
    p["slack_mm"] = p["r_mm"] * np.deg2rad(rng.uniform(50.0, 100.0))
    size = np.linalg.norm(hose_unit(p, ctx, hw), axis=1).max()
    p["k_h"] = rng.uniform(0.2, 0.5) / max(size, 1e-12)
    return p


def hose_features(p, ctx, hw):
    return hose_unit(p, ctx, hw)[None]


def hose_apply(p, ctx, hw):
    return _amp_apply([p["k_h"]], hose_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- pawl notch
PAWL_JOINTS = (1, 2)


def pawl_fraction(p, ctx):
    """(P, n) the signed fraction of a notch pitch each braked axis turns to its next notch wall."""
    out = np.zeros_like(ctx.q)
    tau = ctx.loads
    for k, j in enumerate(PAWL_JOINTS):
        x = np.mod(ctx.q[:, j] / p["pitch"][k] + p["phase"][k], 1.0)
        frac = np.where(tau[:, j] > 0, 1.0 - x, -x)
        out[:, j] = frac * (np.abs(tau[:, j]) > p["drag"] * np.abs(tau[:, j]).max())
    return out


def pawl_draw(ctx, hw, rng):
    Z, i = rng.integers(150, 301, 2), rng.uniform(100.0, 160.0, 2)
    return {"Z": Z, "ratio": i, "pitch": 2 * np.pi / (Z * i), "phase": rng.uniform(0, 1, 2),
            "drag": rng.uniform(0.05, 0.1)}


def pawl_features(p, ctx, hw):
    f = pawl_fraction(p, ctx)
    return np.array([ctx.joint_feature(j, f[:, j]) for j in PAWL_JOINTS])


def pawl_apply(p, ctx, hw):
    dq = pawl_fraction(p, ctx)
    for k, j in enumerate(PAWL_JOINTS):
        dq[:, j] *= p["pitch"][k]
    return Contribution(dq=dq)


# ----------------------------------------------------------------------------------------------- reversal pulse
PULSE_JOINTS = (0, 1, 2)


def reversal_signal(session):
    """(P, n) the new direction where the move into the pose reversed the axis, else 0 (0 at the first pose)."""
    d = session.direction
    rev = np.zeros_like(d)
    rev[1:] = d[1:] * (d[1:] != d[:-1])
    return rev


def pulse_draw(ctx, hw, rng):
    return {"e": rng.uniform(0.05e-3, 0.3e-3, len(PULSE_JOINTS))}


def pulse_features(p, ctx, hw):
    r = reversal_signal(ctx.session)
    return np.array([ctx.joint_feature(j, r[:, j]) for j in PULSE_JOINTS])


def pulse_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    r = reversal_signal(ctx.session)
    for k, j in enumerate(PULSE_JOINTS):
        dq[:, j] = p["e"][k] * r[:, j]
    return Contribution(dq=dq)


# -------------------------------------------------------------------------------------------------- nonius slip
NONIUS_N = {"ur10": (8192, 16384), "kr16_like": (8192, 16384), "tool_changer": (16384, 32768)}  # fine periods / turn


def nonius_signal(p, q):
    """(P,) the decoder's slip in fine periods: round(e cos(q - c)), -1, 0 or +1."""
    return np.round(p["e"] * np.cos(q - p["c"]))


def nonius_draw(ctx, hw, rng):
    j = int(rng.integers(0, 3))
    q = ctx.q[:, j]
    N = int(rng.choice(NONIUS_N[ctx.chain.name]))
    return {"joint": j, "N": N, "e": rng.uniform(0.55, 0.8), "c": q.min() + (q.max() - q.min()) * rng.uniform(0.3, 0.7),
            "delta": float(rng.choice([-1.0, 1.0])) * 2 * np.pi / N}


def nonius_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], nonius_signal(p, ctx.q[:, p["joint"]]))[None]


def nonius_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = p["delta"] * nonius_signal(p, ctx.q[:, p["joint"]])
    return Contribution(dq=dq)


# --------------------------------------------------------------------------------------------- fieldbus rounding
def fieldbus_residual(p, chain, q):
    """(P, n) the commanded less the logged joint values [rad, mm]: 0.01 deg / 0.01 mm integers."""
    step = np.where(chain.revolute, np.deg2rad(0.01), 0.01)
    x = q / step
    n = np.trunc(x) if p["mode"] == "trunc" else np.round(x)
    return n * step - q


def fieldbus_draw(ctx, hw, rng):
    return {"mode": str(rng.choice(["round", "trunc"]))}


def fieldbus_features(p, ctx, hw):
    return _features_of_dq(ctx, fieldbus_residual(p, ctx.chain, ctx.q))[None]


def fieldbus_apply(p, ctx, hw):
    return Contribution(dq=fieldbus_residual(p, ctx.chain, ctx.q))
