"""Set L joint effects (new physics, not in sets A-K): polymer strain-wave gears whose stiffness falls as their drives
warm them; a dispensing gun's sealant cartridge, an unlogged mass at the tool that empties while the robot works; the
secondary encoder of axis 1 driven by a measuring pinion whose backlash the encoder's drag keeps on the trailing flank;
axis 2 of a hydraulic arm positioned through a proportional valve whose overlap leaves a dead band, across which the
cylinder's leakage lets the load drift during the dwell; axis 1 driven through a pin (lantern) ring whose pins sit off
their pitch positions one by one. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* polymer gear softening: the modulus of the semi-crystalline thermoplastics of polymer gears (POM, PA-based tribo
  polymers) falls steadily above room temperature -- POM from about 3 GPa at 23 degC to 2 GPa at 60 degC, PA faster
  near its glass transition (Crawford, *Plastics Engineering*, 3rd ed., 1998, ch. 2; Menges, Haberstroh, Michaeli &
  Schmachtenberg, *Werkstoffkunde Kunststoffe*, 6th ed., 2011, modulus-temperature curves; igus iglidur data sheets,
  as recalled): E(T) = E0 exp(-beta dT), beta 0.008-0.015 /K, so the gear's twist under a held torque grows by
  exp(beta dT) - 1 as it warms. Polymer strain-wave gears on all joints of ur10 (the igus-ReBeL-like arm of set H's
  gear creep), their room-temperature compliance 2-4x the metal gear's of :mod:`hardware` (a polymer flexspline's
  modulus is some 1/70 of steel's, in a thicker section; assumed; first drawn at 1-2x, set H's short-term stiffness: the
  set's case had the link model at 1.25x); each gear warms
  with its drive's losses through one lumped node (:func:`effects_k_thermal.node_rise`; 15-35 K under the production
  cycle, 15-40 min, a cold start; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5). The twist at
  room temperature is set A's compliance and left out: the case isolates the thermal softening. None on the others.
* sealant cartridge: robot-mounted dispensing guns fed from an on-board cartridge or pressure pot (310 ml to 2.5 l, as
  recalled from dispensing-equipment catalogues) carry a mass the controller's load data do not follow: it falls at the
  dispensing rate while the robot works (production periods, a duty of 40-80 %), and a full cartridge replaces the
  empty one. The joints carry its weight (tau = J^T F, statics: Craig, *Introduction to Robotics*, ch. 5) and twist with
  the linear gear stiffness of :mod:`hardware`. Full cartridges or pots of 1.5-4 / 3-8 kg (1-2.5 / 2-5 l of sealant),
  0.5-2 / 1-4 g/s on ur10 / kr16_like, the cartridge's centre of mass 40-100 mm off the tool axis and 30-120 mm along it
  (assumed); production between all blocks. First drawn at 0.8-2.5 / 2-5 kg and 0.3-1.5 / 0.8-3 g/s with production
  between some blocks only: the link model (the tubes' bending under a tool load) within 1.22-1.27x in trial draws on
  ur10. None on tool_changer.
* measuring pinion: a secondary (absolute) encoder on a large axis is often driven by a pinion meshing with the axis's
  ring gear (slewing-ring encoders of heavy machinery; geared encoders, as recalled from Kuebler / Baumer application
  notes, which recommend spring-loaded anti-backlash pinions); without one, the encoder's bearing and seal drag keeps
  the pinion on its trailing flank, so the reading lags the joint by half the backlash j_n / (2 R) against the last
  motion (Nordin & Gutman, "Controlling mechanical systems with backlash -- a survey", Automatica 38, 2002, for the
  dead zone; backlash of a gear pair: ISO 21771 / AGMA 2002-B88). The controller servoes the reading: the joint leads
  its command by j_n / (2 R) in the direction of its last motion -- the sign opposite to a drive's lost motion. j_n
  0.05-0.2 mm (a module 2-4 pair, worn), ring pitch radius 0.25-0.38 / 0.42-0.55 m on kr16_like / tool_changer
  (assumed; the axis-1 ring gear of sets E and K). None on ur10.
* valve overlap: a proportional valve with positive overlap passes no flow for spool strokes inside its overlap, so a
  proportional position loop stops the cylinder anywhere within a band +-e_db of its target, short of it on the side of
  the approach; under load the cylinder's and the valve's laminar leakage, Q = C_l dp (Merritt, *Hydraulic Control
  Systems*, 1967, ch. 5; Jelali & Kroll, *Hydraulic Servo-systems*, 2003, on dead zones), lets the piston drift towards
  the load at v = C_l F / A^2 until the valve opens at the band's load-side edge. The measurement at the end of the
  dwell sees the stop position moved by the drift: e = clip(-e_db d + v t_dwell s_F, -e_db, e_db) (d the last motion's
  sign along the stroke, s_F the load's). Axis 2 of tool_changer driven by a hydraulic boom cylinder (set K's side
  cylinder; pivot r1 0.25-0.4 m, rod eye r2 0.5-0.8 m, included angle 70-110 deg at mid-range, the law of cosines of
  set F's levers), e_db 0.01-0.05 mm of stroke, the drift over a mean dwell at the session's largest load 0.5-4 e_db
  (assumed); the joint is off by e / a, a the lever's moment arm. None on the other arms.
* pin ring: a pin (lantern) ring -- cylindrical pins pressed into a drilled ring, meshing with a pinion -- drives
  slewing axes of heavy machinery (the rotation drives of tunnel-boring machines' segment erectors, as recalled); one
  or two pins carry the load at a time, so each pin's position off its pitch position (the hole's position tolerance
  and the pin's diameter, ISO 2768 / ISO 286, 0.03-0.1 mm rms; assumed) turns the ring by e_k / R while it meshes, with
  a linear handover to the next pin (the pin gearing of Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed.,
  2004, ch. on cycloidal gearing). Unlike a hobbed ring's smooth cumulative pitch error (set E's ring gear), the pins'
  errors are independent: a random staircase in the axis angle. 48-96 pins on R 0.42-0.55 m; axis 1 of tool_changer
  (none on the others).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_f_joint as fj
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all
from sim2real_indep.effects_k_thermal import _heat_params, node_rise

TWO_PI = 2 * np.pi
DOWN = np.array([0.0, 0.0, -1.0])


# --------------------------------------------------------------------------------------- polymer gear softening
#: arms built with polymer strain-wave gears
POLYMER_ARMS = {"ur10"}


def soft_draw(ctx, hw, rng):
    if ctx.chain.name not in POLYMER_ARMS:
        return {}
    joints = [int(j) for j in np.flatnonzero(ctx.chain.revolute)]
    m = len(joints)
    c0 = np.array([hwm.torsion(hw["drives"][j], 1.0, False) for j in joints]) * rng.uniform(2.0, 4.0, m)
    return {"joints": joints, "c0_rad_per_Nm": c0, "beta_per_K": rng.uniform(0.008, 0.015, m),
            "rise_K": rng.uniform(15, 35, m), "tau_s": rng.uniform(15, 40, m) * 60, **_heat_params(ctx, rng)}


def soft_rise(p, ctx, hw):
    """Gear temperature rises (P, joints) [K] at the measurements."""
    return node_rise(ctx, hw, p["joints"], p["rise_K"], p["tau_s"], p["accel_s"], p["duty"])


def softening(beta_per_K, dT):
    """The twist's growth under a held torque, E0 / E(T) - 1 = exp(beta dT) - 1, of a modulus E0 exp(-beta dT)."""
    return np.expm1(np.asarray(beta_per_K) * dT)


def soft_signals(p, ctx, hw):
    """(joints, P): the load times exp(beta dT) - 1 [N m], the twist's growth per unit room-temperature compliance."""
    return (ctx.loads[:, p["joints"]] * softening(p["beta_per_K"], soft_rise(p, ctx, hw))).T


def soft_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = (p["c0_rad_per_Nm"][:, None] * soft_signals(p, ctx, hw)).T
    return Contribution(dq=dq)


def soft_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    sig = soft_signals(p, ctx, hw)
    return _stack([ctx.joint_feature(j, s) for j, s in zip(p["joints"], sig) if np.abs(s).max() > 1e-12],
                  len(ctx.q))


# ------------------------------------------------------------------------------------------ sealant cartridge
#: per arm: full cartridge [kg], dispensing rate [g/s] (assumed)
DRAIN = {"ur10": ((1.5, 4.0), (0.5, 2.0)), "kr16_like": ((3.0, 8.0), (1.0, 4.0))}
EMPTY = 0.05   # the share left when the cartridge is changed


def drain_draw(ctx, hw, rng):
    if ctx.chain.name not in DRAIN:
        return {}
    (m0, m1), (r0, r1) = DRAIN[ctx.chain.name]
    full, b = rng.uniform(m0, m1), rng.uniform(0, TWO_PI)
    r = rng.uniform(40, 100)
    return {"full_kg": full, "start_kg": rng.uniform(0.2, 1.0) * full,
            "rate_kg_s": rng.uniform(r0, r1) * 1e-3 * rng.uniform(0.4, 0.8),
            "com_mm": np.array([r * np.cos(b), r * np.sin(b), rng.uniform(30, 120)])}


def production_time(session):
    """Production time (P,) [s] before each measurement (the production periods between the blocks)."""
    return np.cumsum(np.where(session.gap_s > 0, session.gap_s, 0.0))


def cartridge_mass(p, session):
    """Mass (P,) [kg] in the cartridge at each measurement: the start mass less the dispensed one, a full cartridge
    fitted whenever the last one is down to its empty share."""
    used = p["rate_kg_s"] * production_time(session)
    usable = (1 - EMPTY) * p["full_kg"]
    over = used - (p["start_kg"] - EMPTY * p["full_kg"])
    return np.where(over <= 0, p["start_kg"] - used, p["full_kg"] - np.mod(over, usable))


def drain_unit_loads(p, ctx):
    """Joint loads (P, n) [N m / N per kg] of a unit mass at the cartridge's centre of mass."""
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    return fj.point_loads(ctx, ctx.chain.n, fl + Rt @ p["com_mm"], np.broadcast_to(kin.G * DOWN, fl.shape))


def drain_loads(p, ctx):
    return drain_unit_loads(p, ctx) * cartridge_mass(p, ctx.session)[:, None]


def drain_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, drain_loads(p, ctx)) if p else None)


def drain_features(p, ctx, hw):
    return _stack(_load_cols(ctx, drain_loads(p, ctx)) if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------- measuring pinion
#: per arm: the axis-1 ring gear's pitch radius [m] (assumed)
GAUGE_R_M = {"kr16_like": (0.25, 0.38), "tool_changer": (0.42, 0.55)}


def gauge_draw(ctx, hw, rng):
    if ctx.chain.name not in GAUGE_R_M:
        return {}
    R, jn = rng.uniform(*GAUGE_R_M[ctx.chain.name]), rng.uniform(0.05, 0.2)
    return {"joint": 0, "R_m": R, "jn_mm": jn, "half_rad": jn / 2000 / R}


def gauge_signal(p, ctx):
    """+1 / -1 (P,): the joint leads its reading in the direction of its last motion."""
    return ctx.session.direction[:, p["joint"]]


def gauge_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["half_rad"] * gauge_signal(p, ctx)
    return Contribution(dq=dq)


def gauge_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], gauge_signal(p, ctx))] if p else [], len(ctx.q))


# ---------------------------------------------------------------------------------------------- valve overlap
#: per arm: pivot radius r1, rod-eye radius r2 [m], included angle at mid-range [deg] of the boom cylinder (assumed)
VALVE_LEVER = {"tool_changer": ((0.25, 0.40), (0.5, 0.8), (70.0, 110.0))}
VALVE_JOINT = 1  # axis 2


def valve_draw(ctx, hw, rng):
    if ctx.chain.name not in VALVE_LEVER:
        return {}
    (a0, a1), (b0, b1), (m0, m1) = VALVE_LEVER[ctx.chain.name]
    q = ctx.q[:, VALVE_JOINT]
    s = float(rng.choice([-1.0, 1.0]))
    p = {"joint": VALVE_JOINT, "r1": rng.uniform(a0, a1), "r2": rng.uniform(b0, b1), "s": s,
         "psi0": np.deg2rad(rng.uniform(m0, m1)) - s * 0.5 * (q.min() + q.max()), "e_db_mm": rng.uniform(0.01, 0.05)}
    _, _, a = fj.lever_state(p, q)
    F = np.abs(ctx.loads[:, VALVE_JOINT]) / a
    p["rho_per_Ns"] = rng.uniform(0.5, 4.0) / (F.max() * ctx.session.dwell_s.mean())
    return p


def valve_band(p, ctx):
    """Stroke error at the measurement in units of e_db (P,): stopped short of the target on the side of the approach,
    then drifted towards the load by the leakage over the dwell, inside [-1, 1]; the moment arm a (P,) [m]."""
    j = p["joint"]
    _, _, a = fj.lever_state(p, ctx.q[:, j])
    tau = ctx.loads[:, j]
    d_L = p["s"] * ctx.session.direction[:, j]          # dL = s a dq
    s_F = np.sign(p["s"] * tau)                          # the load's push along the stroke
    rho = p["rho_per_Ns"] * np.abs(tau) / a * ctx.session.dwell_s
    return np.clip(-d_L + s_F * rho, -1.0, 1.0), a


def valve_signal(p, ctx):
    """Joint offset (P,) [rad per mm of e_db]."""
    g, a = valve_band(p, ctx)
    return g * p["s"] / (1000 * a)


def valve_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["e_db_mm"] * valve_signal(p, ctx)
    return Contribution(dq=dq)


def valve_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], valve_signal(p, ctx))] if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------------- pin ring
#: per arm: pin count, pitch radius [m], rms pin position error [mm] (assumed)
PIN_RING = {"tool_changer": ((48, 97), (0.42, 0.55), (0.03, 0.10))}


def pin_draw(ctx, hw, rng):
    if ctx.chain.name not in PIN_RING:
        return {}
    (z0, z1), R, sig = PIN_RING[ctx.chain.name]
    Z = int(rng.integers(z0, z1))
    return {"joint": 0, "Z": Z, "R_m": rng.uniform(*R), "sigma_mm": rng.uniform(*sig), "e": rng.normal(0, 1, Z),
            "phase": rng.uniform(0, TWO_PI / Z)}


def pin_error(p, theta):
    """The meshing pins' position error (P,) in units of sigma at ring angles ``theta`` [rad]: pin k's error while it
    meshes, handed over linearly to pin k + 1 across the pitch."""
    x = (np.asarray(theta) + p["phase"]) * p["Z"] / TWO_PI
    k = np.floor(x).astype(int)
    f = x - k
    return p["e"][k % p["Z"]] * (1 - f) + p["e"][(k + 1) % p["Z"]] * f


def pin_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = -p["sigma_mm"] / (1000 * p["R_m"]) * pin_error(p, ctx.q[:, p["joint"]])
    return Contribution(dq=dq)


def pin_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], pin_error(p, ctx.q[:, p["joint"]]))] if p else [], len(ctx.q))
