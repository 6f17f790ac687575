"""Set ZG joint effects (new physics, not in sets A-ZF): a torque-controlled arm whose gravity compensation carries a
declared tool load other than the one it holds; axis 1 twisted by its supply bundle once the bundle's slack is taken
up; axis 1's lost motion whose flank an inclined installation's gravity torque chooses; the main axes' lost motion
crossed by the arm's own inertia at a fast move's end; a chipped pinion tooth on axis 1; and an RV reducer on axis 2
with a broken ring pin. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* gravity-compensation payload mismatch: a joint-impedance (torque-controlled) arm compensates its gravity with a model
  of the arm plus the *declared* tool load; the joint-impedance law then yields to the rest, tau_err = tau_pay(m) -
  tau_pay(m_d), by K^-1 (Albu-Schaeffer, Ott & Hirzinger, "A unified passivity-based control framework for position,
  torque and impedance control of flexible joint robots", IJRR 26(1), 2007: gravity compensation with the model's
  load). The arm's own weight is compensated and deflects nothing; the part's weight beyond (or short of) the declared
  load does. m_d inside the session's part range (the operator declared one typical part). Unlike set ZB's impedance
  preset (a stiffness per block) or sets A-ZF's compliances (the whole gravity torque), only the payload mismatch acts.
  Sized to 0.25-0.6 mm. Driven by the payload (logged) and the pose. The true structure: one column per main loaded
  axis, amplitudes the compliances [rad / (N m)].
* taut harness: axis 1's supply bundle (a dress pack clamped to the base and the turret) has a slack of some tens of
  degrees; past q_t its sag is pulled out and its tension rises progressively (an elastic catenary straightening:
  Irvine, *Cable Structures*, 1981, ch. 2), taken here as k (q1 - q_t)^2, twisting axis 1's gear (compliance c): dq1 =
  -c k max(q1 - q_t, 0)^2 (Craig, *Introduction to Robotics*, ch. 5, static torque to joint deflection). q_t at the
  80-90 % quantile of the session's axis-1 angles (first a linear pull past the 70-85 % quantile: ZG17 on kr16_like let
  the transmission model's once- and twice-per-turn terms within 1.15x -- over axis 1's +-90 deg a long linear ramp is
  nearly a sine; a bundle laid with slack for most of the range and straightening progressively is not). Unlike
  set S's wall bellows (spring rates at every pose) or set N's harness (a flank choice) the
  bundle acts only past its slack, a hinge in angle. Sized to 0.25-0.6 mm. Driven by axis 1's angle (logged); the
  bundle is not logged. The true structure: one column, amplitude c k [1 / rad].
* tilt flank: an arm installed on an inclined wedge (5-20 deg; inclined installations: ISO 9946 mounting positions)
  sees a gravity torque on axis 1, which a level arm does not; axis 1's lost motion rests on the flank that torque
  chooses where it exceeds the output's friction T_f (30-60 % of its largest) and trails the last motion elsewhere
  (Nordin & Gutman, "Controlling mechanical systems with backlash -- a survey", Automatica 38, 2002). Unlike set I's
  tilted base (the gears' elastic twist) the effect is a lost motion. Half-play sized to 0.25-0.6 mm at the target.
  Driven by the pose and the motion (logged); the wedge's inclination is not. The true structure: one column, the
  half-play [rad].
* coast flank: at a move's end the decelerating link's inertia drives the output across its lash towards the motion
  where the inertial torque J v / t_r (v the move's mean speed, t_r 0.5 s ramp) exceeds the gravity torque and the
  output's friction; the output stays on that leading flank if the gravity torque afterwards is below the friction,
  else falls to the gravity flank (Nordin & Gutman 2002; lash crossing by inertia, Tao & Kokotovic, *Adaptive Control
  of Systems with Actuator and Sensor Nonlinearities*, 1996, ch. 2). flank = sign(tau) where |tau| > T_f; else +d if
  v > v_c (the 35-65 % quantile of the speeds), -d otherwise. Unlike set S's overshoot lash (the position loop's
  overshoot on gravity-free axes 1, 4, 6), the inertial coast acts on the loaded axes 2 and 3, with the gravity flank
  beyond the friction. Sized to 0.25-0.6 mm. Driven by the poses and time stamps (logged). The true structure: one
  column per axis, amplitudes the half-plays [rad].
* chipped pinion: axis 1 driven by a pinion (z_p 9-12 teeth, profile-shifted) on a large ring (6-10 times as many
  teeth) one of whose teeth has chipped (tooth-surface damage: ISO 10825-1:2022, chipping / breakage at the tip); while
  the chipped tooth and its neighbours hand the load over -- 1.5-2 base pitches, once per pinion turn (first 1.3-1.8
  pitches of a 12-17-tooth pinion: ZG18 on kr16_like gained 17 %, the thermal model at 1.19x -- so narrow a dip,
  ~10 % of the pinion's turn, met too few held-out poses) -- the mesh loses conjugate
  contact and the ring lags by the missing profile, a transmission-error dip per pinion turn (gear-damage signatures
  in the transmission error: Smith, *Gear Noise and Vibration*, 2nd ed., 2003, ch. 9; Randall, *Vibration-based
  Condition Monitoring*, 2011, ch. 5: a local fault gives an impulse once per turn of the faulty gear): e
  cos^2(pi psi / (2 h)) for |psi| < h, psi the pinion's angle from the chip's mesh (wrapped), h half the mesh span.
  Unlike set ZF's repaired sector on the ring (one bump per output turn), the periodic errors of sets A-ZF (smooth
  harmonics) or set C's RV error, the error is a narrow dip repeating at the pinion's turn. Sized to 0.25-0.6 mm. (Set
  first as a segmented ring gear -- a staircase of segment placement errors -- and withdrawn: set V's rack segments
  already carry that mechanism on a linear axis.) Driven by axis 1's angle (logged). The true structure: one column.
* missing pin: an RV (cycloidal) reducer on axis 2 with one broken ring pin; each time the load zone of the cycloid
  disc (turning once per crank turn, z_p - 1 times per output turn) passes the missing pin, fewer pins share the
  load and the output yields further in the torque's direction (cycloid load sharing: Blanche & Yang, "Cycloid drives
  with machining tolerances", ASME JMTAD 111(3), 1989; Gorla et al., "Theoretical and experimental analysis of a
  cycloidal speed reducer", ASME JMD 130, 2008): dq2 = k tau2 b(psi), b = exp((cos psi - 1) / w^2), psi = (z_p - 1)
  q2 + phi, z_p 30-40, w 0.3-0.6 rad. Unlike set C's RV error (lost motion and a clearance's periodic error) or set
  E's varying stiffness (a smooth modulation of every load), the yield is a narrow pulse per crank turn. Sized to
  0.25-0.6 mm. Driven by the pose and payload (logged). The true structure: one column, amplitude k [rad / (N m)].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def loaded_joints(chain):
    return [j for j in (1, 2) if chain.revolute[j]]


# ---------------------------------------------------------------------------------------------------- gravcomp payload
def payload_torque_per_kg(ctx):
    """(P, n) the joint torques [N m / kg] of 1 kg at the payload's centre of mass."""
    m, pos, body = ctx.mass_state
    unit = np.zeros_like(m)
    unit[:, -1] = 1.0
    return kin.gravity_loads(ctx.chain, ctx.q, unit, pos, body)


def gravcomp_draw(ctx, hw, rng):
    pay = ctx.session.payload_kg
    js = loaded_joints(ctx.chain)
    p = {"m_decl_kg": float(np.quantile(pay, rng.uniform(0.3, 0.7)))}
    p["c"] = _size(gravcomp_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(js)), rng)
    return p


def gravcomp_features(p, ctx, hw):
    t = payload_torque_per_kg(ctx) * (ctx.session.payload_kg - p["m_decl_kg"])[:, None]
    return np.array([ctx.joint_feature(j, t[:, j]) for j in loaded_joints(ctx.chain)])


def gravcomp_apply(p, ctx, hw):
    return _amp_apply(p["c"], gravcomp_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- taut harness
def harness_stretch(p, q1):
    """(P,) the bundle's progressive pull past its slack, (q1 - q_t)^2 [rad^2] (the torque opposes it)."""
    return -np.maximum(q1 - p["q_t"], 0.0) ** 2


def harness_draw(ctx, hw, rng):
    p = {"q_t": float(np.quantile(ctx.q[:, 0], rng.uniform(0.8, 0.9)))}
    p["ck"] = _size(harness_features(p, ctx, hw), [1.0], rng)
    return p


def harness_features(p, ctx, hw):
    return ctx.joint_feature(0, harness_stretch(p, ctx.q[:, 0]))[None]


def harness_apply(p, ctx, hw):
    return _amp_apply(p["ck"], harness_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- tilt flank
def tilt_gravity(p):
    """The unit gravity in the base frame of an arm on a wedge inclined by alpha about the horizontal psi axis."""
    u = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    return kin._rot(u, p["alpha"]) @ np.array([0.0, 0.0, -1.0])


def tilt_torque(p, ctx):
    """(P,) axis 1's gravity torque [N m] on the inclined installation."""
    m, pos, body = ctx.mass_state
    return kin.gravity_loads(ctx.chain, ctx.q, m, pos, body, gravity=tilt_gravity(p))[:, 0]


def tilt_flank(p, ctx):
    tau, d = tilt_torque(p, ctx), ctx.session.direction[:, 0].astype(float)
    return np.where(np.abs(tau) > p["T_f"], np.sign(tau), -d)


def tilt_draw(ctx, hw, rng):
    p = {"alpha": float(np.deg2rad(rng.uniform(5.0, 20.0))), "psi": rng.uniform(0, 2 * np.pi)}
    p["T_f"] = float(np.abs(tilt_torque(p, ctx)).max() * rng.uniform(0.3, 0.6))
    p["half"] = _size(tilt_features(p, ctx, hw), [1.0], rng)
    return p


def tilt_features(p, ctx, hw):
    return ctx.joint_feature(0, tilt_flank(p, ctx))[None]


def tilt_apply(p, ctx, hw):
    return _amp_apply(p["half"], tilt_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- coast flank
def move_speed(session, j):
    """(P,) the mean |speed| of axis j in the move into each pose [rad/s] (the first pose: 0)."""
    dq = np.abs(np.diff(session.q[:, j], prepend=session.q[0, j]))
    return dq / np.maximum(session.move_s, 1e-9)


def coast_flank(ctx, j, T_f, v_c):
    tau, d = ctx.loads[:, j], ctx.session.direction[:, j].astype(float)
    band = np.where(move_speed(ctx.session, j) > v_c, d, -d)
    return np.where(np.abs(tau) > T_f, np.sign(tau), band)


def coast_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    p = {"T_f": [float(np.abs(ctx.loads[:, j]).max() * rng.uniform(0.3, 0.6)) for j in js],
         "v_c": [float(np.quantile(move_speed(ctx.session, j), rng.uniform(0.35, 0.65))) for j in js]}
    p["half"] = _size(coast_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(js)), rng)
    return p


def coast_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, coast_flank(ctx, j, T, v)) for j, T, v in
                     zip(loaded_joints(ctx.chain), p["T_f"], p["v_c"])])


def coast_apply(p, ctx, hw):
    return _amp_apply(p["half"], coast_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- chipped pinion
def chip_dip(p, q1):
    """(P,) the dip's shape while the chipped tooth is in mesh: cos^2 over the mesh span, 0 elsewhere."""
    psi = np.mod(q1 * p["ratio"] + p["phase"] + np.pi, 2 * np.pi) - np.pi
    return np.where(np.abs(psi) < p["h"], np.cos(np.pi * psi / (2 * p["h"])) ** 2, 0.0)


def chip_draw(ctx, hw, rng):
    z_p = int(rng.integers(9, 13))
    z_r = int(round(z_p * rng.uniform(6.0, 10.0)))
    p = {"ratio": z_r / z_p, "phase": rng.uniform(0, 2 * np.pi), "h": rng.uniform(1.5, 2.0) * np.pi / z_p}
    p["e"] = _size(chip_features(p, ctx, hw), [1.0], rng)
    return p


def chip_features(p, ctx, hw):
    return ctx.joint_feature(0, chip_dip(p, ctx.q[:, 0]))[None]


def chip_apply(p, ctx, hw):
    return _amp_apply(p["e"], chip_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- missing pin
def pin_pulse(p, q2):
    psi = (p["z_p"] - 1) * q2 + p["phi"]
    return np.exp((np.cos(psi) - 1.0) / p["w"] ** 2)


def pin_draw(ctx, hw, rng):
    p = {"z_p": int(rng.integers(30, 41)), "phi": rng.uniform(0, 2 * np.pi), "w": rng.uniform(0.3, 0.6)}
    p["k"] = _size(pin_features(p, ctx, hw), [1.0], rng)
    return p


def pin_features(p, ctx, hw):
    return ctx.joint_feature(1, ctx.loads[:, 1] * pin_pulse(p, ctx.q[:, 1]))[None]


def pin_apply(p, ctx, hw):
    return _amp_apply(p["k"], pin_features(p, ctx, hw))
