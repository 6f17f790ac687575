"""Set ZA joint effects (new physics, not in sets A-Z): gears whose two tooth flanks differ in stiffness; tool_changer's
boom luffed by a rope tackle whose free length and lever change with the luff angle; the telescopic stage's sliding
guides holding its drive's wind-up against the last stroke with a friction that follows the stage's inclination; a
tool on viscoelastic mounts still creeping back from the last stop's deceleration; an incremental ring scale that
loses counts at a scratch; and a wrist belt that jumped a tooth in the production between two blocks. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* flank stiffness: gears with asymmetric teeth (a drive flank of a high pressure angle, a coast flank of a low one:
  Kapelevich, *Asymmetric Gearing*, CRC Press, 2018; Litvin et al., "Design and investigation of gear drives with
  non-symmetric profiles", Comput. Methods Appl. Mech. Eng. 196, 2007) mesh with a stiffness that differs between the
  flanks (the tooth's bending and contact compliance grow as its pressure angle falls; ISO 6336-1's single-tooth
  stiffness, as recalled); gravity-loaded axis 3 (given the asymmetric stage) runs on the drive flank one way and on the
  coast flank the other. The twist is c tau on one side and c (1 + r) tau on the other, c the joint's catalogue
  compliance (:mod:`hardware`), scaled by s 0.8-1.2 (the catalogue's spread), r 0.3-0.8 (assumed); the soft side's sign
  drawn. First on axes 2 and 3 (up to 2.3 mm on ur10 and kr16_like, 4.9 mm on tool_changer: beyond the set's 0.05-1 mm),
  now on axis 3 alone. Unlike set A's hardening (the curve's knee, symmetric), set C's hysteresis or set E's stiffness
  varying along the turn, the stiffness depends on the sign of the load. Driven by the pose and the payload (logged).
  The true structure: two columns (the twist per unit compliance, and its part on the soft side), amplitudes s and s r.
* luff rope: tool_changer's boom (axis 2) luffed by a wire-rope tackle of n falls between a sheave block on a mast above
  the column (r1 from axis 2) and one on the boom (r2 along it), like a crane's luffing gear: the tackle's free length L
  = (r1^2 + r2^2 - 2 r1 r2 cos g)^(1/2) and its lever r1 r2 sin g / L change with the angle g between the mast and the
  boom, so the rope force is tau / lever and the boom turns by tau L / (n^2 E A lever^2) (the stretch of a tackle of n
  falls: Feyrer, *Wire Ropes*, 2nd ed., 2015, ch. 3; the lever: statics, Craig, *Introduction to Robotics*, ch. 5). The
  mast stands so that g is 50-60 deg in the middle of the session's luffing range (a short mast close behind the column:
  the lever shrinks fast as the boom comes up), sized so that the session's largest twist is 0.3-0.6 mrad (a 10-12 mm
  rope in 4 falls). First g about 90 deg mid-range and 0.1-0.3 mrad (ZA09: a gain of 14 %, the link model at 1.06x -- a
  lever that hardly changes leaves a twist in proportion to the gravity load). Unlike set K's extension ropes (the
  telescope's axial force) or set Z's balancers (a force beside the drive), the rope is the drive and its compliance
  follows the luff angle. Driven by the pose and the payload (logged). Only tool_changer has the boom (inert elsewhere).
  The true structure: one column (axis 2 turned by tau L / lever^2), amplitude 1 / (n^2 E A) [1/N].
* guide drag: tool_changer's telescopic stage slides on plastic guide shoes (Coulomb friction mu 0.1-0.2 of their
  normal load: polymer slide bearings' catalogue values, e.g. igus iglidur, as recalled); at a stop the friction holds
  the drive's (rack and pinion, belt) elastic wind-up against the last stroke (a friction-held spring: Al-Bender &
  Swevers, IEEE Control Syst. Mag. 28(6), 2008). The shoes' normal load is their preload plus the stage's and the
  part's weight across the stage, sin(theta) g (m_stage + k_m m_part), theta the stage's angle from the vertical, k_m
  2-4 the overhang's lever on the shoes (assumed); the held wind-up at the session's largest load 0.08-0.25 mm, the
  preload's share 20-40 %. Unlike set I's nut play or set K's ram roll (clearances), or set E's friction wind-up (a
  revolute output's bearing), the prismatic stage's guide friction follows its inclination. Driven by q4's direction
  (``dir4``), the pose and the payload (logged). Inert without the stage. The true structure: two columns (q4 held back
  by its direction, and that times the normal load per its largest), amplitudes the two wind-ups [mm].
* tool recoil: a camera or dispensing head on elastomer anti-vibration mounts (a standard linear solid: Findley, Lai &
  Onaran, *Creep and Relaxation of Nonlinear Viscoelastic Materials*, 1976, ch. 5) is loaded by its inertia over the
  0.5 s deceleration at the end of each move; the mount's retarded (creep) compliance takes up c_r m a (1 -
  exp(-0.5 / tau)) and recovers as exp(-t_d / tau) over the dwell t_d, tau 2-8 s (assumed), so the target stands
  ahead along the last move's end velocity. The end velocity is J(q) dq / t_move (synchronous point-to-point moves:
  all joints finish together). Sized so that the 90th percentile of the session's residual is 0.1-0.25 mm. Unlike set
  Q's servo tail (the loop's overshoot), set W's stable probe (the trigger) or set X's part slide (a clearance),
  the tool's mount creeps. Driven by the last move (the logged joint angles and time stamps; the dwell is not
  logged). The true structure: one column, amplitude c_r m (1 - exp(-0.5 / tau)) [s^2].
* scratch count: an incremental output-side ring scale (18000-36000 lines) with a scratch across its graduation: the
  counter misses the lines under the scratch each time the head passes it, in either direction, so beyond it (seen
  from where the session started) the reading is short by the lost lines (HEIDENHAIN, *Angle encoders*, and ISO
  230-2 on incremental scales' contamination, as recalled): the joint stands off by delta on the far side. delta 0.4-1
  arcmin (1-2 lines), the scratch at 30-70 % of the session's range of an axis 1-3 (drawn). Unlike set T's soiled disc
  (a smooth error) or set M's dropped counts (a speed limit), the error is a step at one angle. Driven by the joint's
  angle (logged). The true structure: one column (the step on that joint), amplitude delta [rad].
* tooth skip: a wrist axis driven by a toothed belt before its reducer (Z 24-40 teeth on the motor pulley, ratio
  80-160) jumps a tooth when an overload in the production (a light collision, an emergency stop) exceeds the belt's
  ratcheting torque (ISO 13050 / belt makers' ratcheting data, as recalled), and the joint's zero moves by 2 pi / (Z
  i) after that block. Unlike set R's rehoming (each power-up's scatter) or set V's hub slip (friction), the step is
  one quantised tooth at one boundary. Driven by the production's events (not logged). The true structure: one column
  (the step on that joint after the boundary), amplitude the step [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import _features_of_dq
from sim2real_indep.effects_z_joint import upright_angle

ARCMIN = np.pi / (180 * 60)


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _dq_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ------------------------------------------------------------------------------------------------ flank stiffness
FLANK_JOINTS = (2,)   # axis 3


def flank_features(p, ctx, hw):
    c, tau = compliance(hw), ctx.loads
    a, b = np.zeros_like(ctx.q), np.zeros_like(ctx.q)
    for j in FLANK_JOINTS:
        a[:, j] = c[j] * tau[:, j]
        b[:, j] = c[j] * tau[:, j] * (np.sign(tau[:, j]) == p["soft_sign"])
    return np.array([_features_of_dq(ctx, a), _features_of_dq(ctx, b)])


def flank_draw(ctx, hw, rng):
    s, r = rng.uniform(0.8, 1.2), rng.uniform(0.3, 0.8)
    return {"s": s, "r": r, "soft_sign": float(rng.choice([-1.0, 1.0])), "amp": np.array([s, s * r])}


def flank_apply(p, ctx, hw):
    return _dq_apply(p["amp"], flank_features(p, ctx, hw))


# ----------------------------------------------------------------------------------------------------- luff rope
LUFF_JOINT = 1


def luff_geometry(p, ctx):
    """(P,) the tackle's free length [m] and lever [m]."""
    g = upright_angle(ctx) - p["gamma"]
    r1, r2 = p["r1_m"], p["r2_m"]
    L = np.sqrt(r1 ** 2 + r2 ** 2 - 2 * r1 * r2 * np.cos(g))
    return L, r1 * r2 * np.sin(g) / L


def luff_signal(p, ctx):
    L, lever = luff_geometry(p, ctx)
    return ctx.loads[:, LUFF_JOINT] * L / lever ** 2


def luff_draw(ctx, hw, rng):
    p = {"active": bool(ctx.chain.name == "tool_changer"), "r1_m": rng.uniform(0.8, 1.2), "r2_m": rng.uniform(0.9, 1.4)}
    psi = upright_angle(ctx)
    p["gamma"] = 0.5 * (psi.min() + psi.max()) - np.deg2rad(rng.uniform(50.0, 60.0))  # g 50-60 deg mid-range
    twist = rng.uniform(0.3e-3, 0.6e-3)
    p["inv_nEA"] = twist / max(np.abs(luff_signal(p, ctx)).max(), 1e-9)
    return p


def luff_features(p, ctx, hw):
    if not p["active"]:
        return _empty(ctx)
    return ctx.joint_feature(LUFF_JOINT, luff_signal(p, ctx))[None]


def luff_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p["active"]:
        dq[:, LUFF_JOINT] = p["inv_nEA"] * luff_signal(p, ctx)
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------------- guide drag
STAGE_JOINT = 3
STAGE_KG = 40.0


def guide_load(p, ctx):
    """(P,) the shoes' weight-borne normal load per its session maximum."""
    u = ctx.jac[:, :, STAGE_JOINT]
    u = u / np.linalg.norm(u, axis=1, keepdims=True)
    s = np.sqrt(np.clip(1 - u[:, 2] ** 2, 0.0, 1.0))
    n = s * (STAGE_KG + p["k_m"] * ctx.session.payload_kg)
    return n / max(n.max(), 1e-9)


def guide_active(ctx):
    return bool(ctx.chain.n > STAGE_JOINT and not ctx.chain.revolute[STAGE_JOINT])


def guide_features(p, ctx, hw):
    if not guide_active(ctx):
        return _empty(ctx)
    d = -ctx.session.direction[:, STAGE_JOINT]
    return np.array([ctx.joint_feature(STAGE_JOINT, d), ctx.joint_feature(STAGE_JOINT, d * guide_load(p, ctx))])


def guide_draw(ctx, hw, rng):
    w, pre = rng.uniform(0.08, 0.25), rng.uniform(0.2, 0.4)
    return {"k_m": rng.uniform(2.0, 4.0), "mu": rng.uniform(0.1, 0.2), "w_mm": w, "pre": pre,
            "amp": np.array([w * pre, w * (1 - pre)])}


def guide_apply(p, ctx, hw):
    if not guide_active(ctx):
        return Contribution(displace=np.zeros((len(ctx.q), 3)))
    return _dq_apply(p["amp"], guide_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- tool recoil
RAMP_S = 0.5


def recoil_signal(p, ctx):
    """(P, 3) the end-of-move deceleration [mm/s^2] times the creep's recovery over the dwell."""
    s = ctx.session
    dq = np.diff(np.vstack([ctx.q[:1], ctx.q]), axis=0)
    v = np.einsum("pij,pj->pi", ctx.jac, dq / np.maximum(s.move_s, 1e-9)[:, None])
    v[0] = 0.0
    return v / RAMP_S * np.exp(-s.dwell_s / p["tau_s"])[:, None]


def recoil_draw(ctx, hw, rng):
    tau = rng.uniform(2.0, 8.0)
    p = {"tau_s": tau}
    size = np.percentile(np.linalg.norm(recoil_signal(p, ctx), axis=1), 90)
    p["c"] = rng.uniform(0.1, 0.25) / max(size, 1e-9)
    return p


def recoil_features(p, ctx, hw):
    return recoil_signal(p, ctx)[None]


def recoil_apply(p, ctx, hw):
    return Contribution(displace=p["c"] * recoil_signal(p, ctx))


# ------------------------------------------------------------------------------------------------- scratch count
def scratch_signal(p, ctx):
    """(P,) +1 beyond the scratch (seen from the session's first pose), else 0."""
    side = ctx.q[:, p["joint"]] > p["q_s"]
    return (side != side[0]).astype(float)


def scratch_draw(ctx, hw, rng):
    j = int(rng.integers(0, 3))
    q = ctx.q[:, j]
    return {"joint": j, "q_s": q.min() + (q.max() - q.min()) * rng.uniform(0.3, 0.7),
            "delta": float(rng.choice([-1.0, 1.0])) * rng.uniform(0.4, 1.0) * ARCMIN}


def scratch_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], scratch_signal(p, ctx))[None]


def scratch_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = p["delta"] * scratch_signal(p, ctx)
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------------- tooth skip
SKIP_JOINTS = {"ur10": (3, 4), "kr16_like": (3, 4), "tool_changer": (4,)}


def skip_signal(p, session):
    return (block_index(session) >= p["block"]).astype(float)


def skip_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    z, i = int(rng.integers(24, 41)), rng.uniform(80.0, 160.0)
    return {"joint": int(rng.choice(SKIP_JOINTS[ctx.chain.name])), "block": int(rng.integers(1, max(nb, 2))),
            "Z": z, "ratio": i, "step": float(rng.choice([-1.0, 1.0])) * 2 * np.pi / (z * i)}


def skip_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], skip_signal(p, ctx.session))[None]


def skip_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = p["step"] * skip_signal(p, ctx.session)
    return Contribution(dq=dq)
