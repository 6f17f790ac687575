"""Set ZL joint effects (new physics, not in sets A-ZK): stepper wrists whose drivers cut the holding current at
standstill; current-based wrist control whose motors' torque constant saturates at high currents; Hall-effect
current sensors left magnetised by the last move's current peaks under current-based joint control; a single-acting
gripper's pressurised hose choosing a wrist roll's flank; output-side magnetic encoders misread by their motor's
stator leakage field; and stepper wrists commanded by truncated relative step counts. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* idle current (``idle_current``): a hybrid stepper holds its rotor by the static torque curve T = -T_H sin(N_r
  theta_m) (N_r = 50 rotor teeth for 1.8 deg motors: Kenjo & Sugawara, *Stepping Motors and Their Microprocessor
  Controls*, 2nd ed., 1994, ch. 2; Acarnley, *Stepping Motors: A Guide to Theory and Practice*, 4th ed., 2002, ch. 2);
  stepper drivers cut the phase current to 30-70 % a fraction of a second after the last step ("automatic current
  reduction" / "idle current", driver manuals, as recalled), and the rotor's load angle under the gravity torque grows
  from asin(u) to asin(u / r), u = tau / T_H, r the kept share of the current (the holding torque about in proportion
  at these currents). Behind a gear head of ratio N_g the wrist joint sags by (asin(u / r) - asin(u)) / (N_r N_g).
  Wrist axes 4 and 5 of ur10 and kr16_like (assumed stepper builds, as set ZJ's stepper wrists); r 0.5-0.7, the
  session's largest u 0.2-0.4 (so u / r < 0.8: no lost step); parts of 1-8 / 2-14 kg changed between blocks; sized
  to 0.25-0.6 mm (N_g some 5-20). Unlike set ZJ's stepper stall (whole steps lost in loaded fast moves) or the
  controllers' stiffness kinds (impedance presets, clamped integrators), the sag is the drivers' current cut at
  standstill, softening towards the pull-out. Driven by the pose and the payload (logged). The true structure: one
  column per axis (asin(u / r) - asin(u)), amplitudes 1 / (N_r N_g).
* torque-constant saturation (``kt_saturation``): under current-based (soft-servo) joint control the controller feeds
  the gravity torque forward as a current i = tau / K_t0 and leaves the rest to a low position gain K (soft-float
  modes of industrial controllers; Wensing et al., IEEE T-RO 33, 2017); a permanent-magnet motor's torque per amp
  falls at high currents as its stator iron saturates, K_t(i) = K_t0 (1 - s (i / i_pk)^2) to first order
  (Hendershot & Miller, *Design of Brushless Permanent-Magnet Machines*, 2010, ch. on saturation and the torque
  constant's linearity; Krishnan, *Permanent Magnet Synchronous and Brushless DC Motor Drives*, 2010, ch. 9), so the
  joint sags by s tau^3 / (tau_pk^2 K): nothing at light loads, the cube at heavy ones. The wrist bends (axes 4 and 5;
  tool_changer's axis 5), s 5-15 % at the peak current, holding torques up to 40-80 % of tau_pk (assumed); parts of
  1-8 / 2-14 / 10-60 kg changed between blocks; sized to 0.25-0.6 mm. (First ``preload_release``, a helical pinion's
  preloaded bearing pair letting go under the mesh's thrust on axes 2 and 3: absorbed on tool_changer (ZL09, 1.2 %),
  the link model at 1.07-1.08x on kr16_like (ZL18) with a release at 30-70 % and 15-35 % of the largest torque and on
  axis 3 alone in trial draws -- a nearly linear gravity twist of the main axes is the long links' bending; replaced.)
  Unlike set ZK's magnet warming (the whole gravity torque times a drifting K_t, following the time), set A's
  hardening (a stiffening gear) or this set's idle current (a stepper's current cut), the sag is the iron's
  saturation, cubic in the load. Driven by the pose and the payload (logged). The true structure: one column per axis
  (tau^3 / tau_max^2), amplitudes s tau_max^2 / (tau_pk^2 K).
* current remanence (``current_remanence``): open-loop Hall-effect current transducers keep a magnetic offset after
  a large current, of the sign of the last excursion beyond their core's coercive level and growing with it (LEM
  data sheets: "magnetic offset current after an overload", as recalled; Ripka, *Magnetic Sensors and
  Magnetometers*, 2001, ch. 4). Under current-based (proprioceptive) joint control -- the gravity torque fed forward
  as a current, a low position gain K taking the rest (Wensing et al., IEEE T-RO 33, 2017) -- an offset i_0 leaves
  K_t i_0 / K to the position loop. The drives auto-zero their current channels at each servo enable (the session's
  start and each pause), so the error is the core's state minus its state then. Each move's currents: the
  acceleration's tau + d J a, the deceleration's tau - d J a and the hold's tau (J the inertia beyond the joint,
  :func:`effects_c_thermal.inertia_about_joints`, a the mean speed over the 0.5 s ramps); an excursion past I_c
  (30-60 % of the session's largest) sets the core to sign(x) tanh(|x| / I_s) unless it already holds more of that
  sign. Axes 2 and 3 of ur10 (assumed current-based); sized to 0.25-0.6 mm. Unlike set ZG's coast flank (lost motion
  crossed by inertia), set ZK's torque-sensor hysteresis (a play operator of the gravity load) or set ZJ's gauge
  drift (temperature), the error is the current sensor's magnetic memory of the last large current, reset at each
  enable. Driven by the pose sequence, the speeds and the payload (logged). The true structure: one column per axis
  (core state minus its state at the last enable), amplitudes K_t i_s / K.
* hose Bourdon flank (``hose_bourdon``): a curved pressurised hose tends to straighten (the Bourdon-tube effect:
  Timoshenko, *Strength of Materials* II, 1956, on curved tubes under pressure; hose makers' notes on hose
  twisting under pressure), so a single-acting gripper's supply line, coiled round a wrist roll axis, puts a torque
  T_h on it while it is pressurised -- while a part is held (the blocks with a logged payload). A roll axis' gear
  lash (flank selection by the load above the mesh's friction, Nordin & Gutman, Automatica 38, 2002) then has its
  flank chosen by sign(tau + T_h) where |tau + T_h| beats the friction f (5-15 % of the session's largest |tau|),
  by the last motion otherwise; T_h 1.5-3 f of a fixed sense (the coil's hand). Roll axes 4 and 6 of kr16_like,
  axis 6 of tool_changer; parts of 2-14 / 10-60 kg in some blocks, none in others; sized to 0.25-0.6 mm. Unlike set
  N's harness lash or set ZI's dog play (the dress pack's torsion with the angle), set ZC's air preload (a cylinder
  closing the lash) or set Q's gooseneck (the tube's own bending), the hose's pressure picks the flank only while a
  part is held. Driven by the pose, the payload and the last motion (logged). The true structure: one column per
  axis (the flank), amplitudes the half lash.
* stator leakage (``stator_leakage``): off-axis magnetic output encoders in compact joint modules read the angle of
  a magnetised ring; a stray field B_s at an angle phi_s to the ring's field B_m turns the reading by (B_s / B_m)
  sin(phi_s - theta) (magnetic angle sensors' stray-field sensitivity: AMS / iC-Haus application notes, as
  recalled; Lenz & Edelstein, IEEE Sensors J. 6, 2006). The motor's stator leakage flux is proportional to the phase
  current -- at standstill the gravity torque's -- and turns with the electrical angle p N q (p pole pairs, N the
  gear ratio), so the output reads an error c tau sin(K q + phi), K = p N - 1. Axes 2 and 3 of ur10 (strain-wave,
  N 100-160) and kr16_like (cycloid, 101-161), p 4-8; sized to 0.25-0.6 mm. Unlike set P's stray field (the next
  axis' brake magnet, a fixed field), set N's magnetic drift (warming) or set A's gear orders, the error follows the
  motor's current and its electrical angle. Driven by the pose and the payload (logged). The true structure: two
  columns per axis (tau / tau_max times sin, cos K q).
* step truncation (``step_truncation``): an open-loop stepper wrist commanded by relative moves whose step counts the
  controller truncates towards zero (a floating-point count cast to an integer truncates: ISO/IEC 9899, 6.3.1.4),
  so each move falls short by the fraction of a step and the shortfalls add up along the session: the joint lags
  its logged target by sum_k (trunc(dq_k / s) s - dq_k). s = 2 pi / (200 mu N_g), mu 8 or 16 microsteps, N_g 5-20
  (0.006-0.045 deg). Wrist axes 4-6 of kr16_like (assumed stepper wrists); the size is what the counts give. Unlike
  set ZB's fieldbus rounding (each target rounded, no memory), set ZE's reversal counts (one count per reversal) or
  set ZJ's stepper stall (steps lost under load), the error is the running sum of truncated fractions. Driven by the
  pose sequence (logged). The true structure: one column per axis (the running sum), amplitudes 1.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_c_thermal import inertia_about_joints
from sim2real_indep.effects_zi_joint import _size_cols, loaded_joints

N_R = 50           # rotor teeth of a 1.8 deg hybrid stepper
RAMP_S = 0.5       # the session's acceleration ramps


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def wrist_bends(chain):
    return [j for j in (3, 4) if j < chain.n and chain.revolute[j]]


def wrist_joints(chain):
    return [j for j in (3, 4, 5) if j < chain.n and chain.revolute[j]]


def roll_joints(chain):
    """Wrist roll axes: 4 and 6 where 4 is a roll (kr16_like), else 6."""
    return [5] if chain.name in ("ur10", "tool_changer") else [j for j in (3, 5) if chain.revolute[j]]


# ---------------------------------------------------------------------------------------------------- idle current
def idle_sag(p, ctx, j):
    """(P,) asin(u / r) - asin(u), u = tau / T_H of axis j."""
    u = ctx.loads[:, j] / p["T_H"][j]
    return np.arcsin(np.clip(u / p["r"], -1, 1)) - np.arcsin(np.clip(u, -1, 1))


def idle_draw(ctx, hw, rng):
    js = wrist_bends(ctx.chain)
    p = {"r": float(rng.uniform(0.5, 0.7)),
         "T_H": {j: float(np.abs(ctx.loads[:, j]).max() / rng.uniform(0.2, 0.4)) + 1e-9 for j in js}}
    p["c"] = _size_cols(idle_features(p, ctx, hw), rng)
    return p


def idle_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, idle_sag(p, ctx, j)) for j in wrist_bends(ctx.chain)])


def idle_apply(p, ctx, hw):
    return _amp_apply(p["c"], idle_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- Kt saturation
def saturation_sag(ctx, j):
    """(P,) tau^3 / tau_max^2 of axis j (tau_max the session's largest |tau|)."""
    tau = ctx.loads[:, j]
    return tau ** 3 / max(float(np.abs(tau).max()), 1e-9) ** 2


def saturation_draw(ctx, hw, rng):
    return {"c": _size_cols(saturation_features({}, ctx, hw), rng)}


def saturation_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, saturation_sag(ctx, j)) for j in wrist_bends(ctx.chain)])


def saturation_apply(p, ctx, hw):
    return _amp_apply(p["c"], saturation_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- current remanence
def move_currents(ctx, j):
    """(P, 3) joint j's torque-current excursions of the move into each pose: acceleration, deceleration, hold
    [N m]."""
    s = ctx.session
    tau = ctx.loads[:, j]
    Ja = inertia_about_joints(ctx)[:, j] * s.speed[:, j] / RAMP_S * s.direction[:, j]
    return np.stack([tau + Ja, tau - Ja, tau], axis=1)


def core_state(x, I_c, I_s, reset):
    """(P,) the core's state after each move's excursions x (P, 3), relative to its state at the last enable
    (``reset``: the poses after a servo enable)."""
    m, ref, out = 0.0, 0.0, np.empty(len(x))
    for k in range(len(x)):
        if reset[k]:
            ref = m
        for v in (x[k] if k else x[k, 2:]):
            if abs(v) >= I_c:
                g = np.sign(v) * np.tanh(abs(v) / I_s)
                if np.sign(m) != np.sign(v) or abs(g) > abs(m):
                    m = g
        out[k] = m - ref
    return out


def remanence_error(p, ctx, j):
    s = ctx.session
    reset = np.r_[True, s.gap_s[1:] < 0]  # the session's start and each pause: the drives auto-zero
    return core_state(move_currents(ctx, j), p["I_c"][j], p["I_s"][j], reset)


def remanence_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    big = {j: float(np.abs(move_currents(ctx, j)).max()) + 1e-9 for j in js}
    p = {"I_c": {j: big[j] * float(rng.uniform(0.3, 0.6)) for j in js}, "I_s": big}
    p["a"] = _size_cols(remanence_features(p, ctx, hw), rng, rng.uniform(0.5, 1.5, len(js)) * rng.choice([-1, 1]))
    return p


def remanence_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, remanence_error(p, ctx, j)) for j in loaded_joints(ctx.chain)])


def remanence_apply(p, ctx, hw):
    return _amp_apply(p["a"], remanence_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- hose Bourdon flank
def bourdon_flank(p, ctx, j):
    """(P,) the flank of roll axis j: sign(tau + air T_h) beyond the friction f, else against the last motion."""
    air = (ctx.session.payload_kg > 0).astype(float)
    t = ctx.loads[:, j] + air * p["T_h"][j]
    return np.where(np.abs(t) > p["f"][j], np.sign(t), -ctx.session.direction[:, j])


def bourdon_draw(ctx, hw, rng):
    js = roll_joints(ctx.chain)
    sense = float(rng.choice([-1.0, 1.0]))
    f = {j: float(np.abs(ctx.loads[:, j]).max() * rng.uniform(0.05, 0.15)) + 1e-9 for j in js}
    p = {"f": f, "T_h": {j: sense * f[j] * float(rng.uniform(1.5, 3.0)) for j in js}}
    p["b"] = _size_cols(bourdon_features(p, ctx, hw), rng)
    return p


def bourdon_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, bourdon_flank(p, ctx, j)) for j in roll_joints(ctx.chain)])


def bourdon_apply(p, ctx, hw):
    return _amp_apply(p["b"], bourdon_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- stator leakage
def leakage_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    lo, hi = (100, 161) if ctx.chain.name == "ur10" else (101, 162)
    p = {"K": {j: int(rng.integers(4, 9)) * int(rng.integers(lo, hi)) - 1 for j in js},
         "tau_max": {j: float(np.abs(ctx.loads[:, j]).max()) + 1e-9 for j in js}}
    ph = rng.uniform(0, 2 * np.pi, len(js))
    w = rng.uniform(0.5, 1.5, len(js))
    rel = np.ravel([[wk * np.cos(a), wk * np.sin(a)] for wk, a in zip(w, ph)])
    p["e"] = _size_cols(leakage_features(p, ctx, hw), rng, rel)
    return p


def leakage_features(p, ctx, hw):
    cols = []
    for j in loaded_joints(ctx.chain):
        u = ctx.loads[:, j] / p["tau_max"][j]
        cols += [ctx.joint_feature(j, u * f(p["K"][j] * ctx.q[:, j])) for f in (np.sin, np.cos)]
    return np.array(cols)


def leakage_apply(p, ctx, hw):
    return _amp_apply(p["e"], leakage_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- step truncation
def truncation_lag(q, s):
    """(P,) the running sum of the truncated moves' shortfalls, sum_k (trunc(dq_k / s) s - dq_k), 0 at the first
    pose."""
    d = np.diff(q, prepend=q[0])
    return np.cumsum(np.trunc(d / s) * s - d)


def truncation_draw(ctx, hw, rng):
    js = wrist_joints(ctx.chain)
    return {"s": {j: float(2 * np.pi / (200 * rng.choice([8, 16]) * rng.integers(5, 21))) for j in js},
            "amp": [1.0] * len(js)}


def truncation_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, truncation_lag(ctx.q[:, j], p["s"][j])) for j in wrist_joints(ctx.chain)])


def truncation_apply(p, ctx, hw):
    return _amp_apply(p["amp"], truncation_features(p, ctx, hw))
