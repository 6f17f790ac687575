"""Set ZN joint effects (new physics, not in sets A-ZM): polymer gear stages softened by the moisture they take up
after the cell's washdown; a cobot's on-line payload identification lagging each part change; a hydraulic boom's
load-holding valves letting it drop as they close after a lowering move; a roll bearing's axial end play crossed by
the axial weight; a capstan (rope) stage's rope-lay waviness; and a telescopic stage read by a magnetostrictive
position sensor. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* moisture-softened gears (``hygro_gear``): polyamide and acetal gears take up water from humid air; PA66's modulus
  falls from ~3 GPa dry to ~1.2-1.8 GPa conditioned (Kohan, *Nylon Plastics Handbook*, 1995; BASF Ultramid data, as
  recalled), the tooth stiffness with it. The uptake of a tooth (a plate of half-thickness l) after a step in the
  humidity follows Fick's law, M(t) = 1 - sum 8 / ((2n+1)^2 pi^2) exp(-(2n+1)^2 t / tau_d), tau_d = 4 l^2 / (pi^2 D)
  1-4 h (Crank, *The Mathematics of Diffusion*, 2nd ed., 1975, ch. 4). A cell hosed down 5-20 min before the session
  (a food or washdown cell; the wet floor keeps the air humid) softens the wrist's polymer stages (assumed builds, as
  sets L and ZM assume polymer and stepper wrists) as twist = tau (1 + a M(t)), a 0.3-0.8. Wrist bends (ur10's axes
  4 and 5, the others' axis 5); hours of blocks with pauses. Unlike set L's polymer heat (the drives' warmth) or set
  V's moisture swell (a boom's length), the stiffness falls with the water the teeth absorb, whatever the arm does.
  Driven by the pose and the time since the washdown (the humidity is not logged). The true structure: one column
  per joint, amplitudes 1 / K0.
* payload identification lag (``payload_estimator``): a torque-controlled cobot identifies its payload on line from
  the joint torques of its moves (recursive least squares: Kubus, Kroeger & Wahl, ICRA 2008; Swevers et al., IEEE T-RA
  13, 1997, exciting moves), each move pulling the estimate towards the true mass by 1 - exp(-t_move / tau_e), tau_e
  20-60 s of excitation (a forgetting factor slow enough to reject the torque readings' noise; first 5-20 s: the
  estimate caught up within a few moves and ur10's mixture ZN08 lost under 5 % without it). After each part change the gravity compensation carries the old estimate; the residual
  (m - m_est) g r twists the joints through the controller's joint stiffness until the estimate catches up; before
  the session it had converged on an earlier part. ur10 and kr16_like, 3-5 blocks, a new part in each. Unlike set
  ZG's declared load (a fixed wrong value) or set H's load data, the error is the estimator's lag behind each part
  change. Driven by the logged payload and the moves (their durations follow from the time stamps). The true
  structure: one column per loaded joint, amplitudes the compliances.
* load-holding valves (``load_holding_valve``): a hydraulic boom's cylinders are held by pilot-operated check or
  counterbalance valves; when a lowering move stops, the pilot pressure decays and the poppet closes late, letting
  the load push out the oil of its closing stroke (0.05-0.2 cm^3), a drop of the boom; after a lifting move the check
  closes on the stopped flow with no load drop (Watton, *Fundamentals of Fluid Power Control*, 2009, ch. 4;
  valve makers' application notes on load-holding valves, as recalled). tool_changer's axes 2 and 3 (hydraulic, as
  set M's oil columns assume). The drop follows the last motion that moved the axis (its direction against the
  gravity load). Unlike set L's valve lap (a dead band drifting by leakage), set S's oil shrink or set M's oil columns,
  the error is a fixed drop after lowering, none after lifting. Driven by the last motion (logged directions). The
  true structure: one column per axis (lowered last), amplitude the drop angle.
* roll end play (``roll_endplay``): a roll axis on a pair of angular-contact or tapered bearings set with axial end
  play (worn, or set loose: Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. 1 and 5, axial
  clearance) lets everything beyond it slide along the axis by the play, to the side the axial weight pushes it where
  that beats the seals' and cage's friction (10-30 % of its largest), staying put otherwise. kr16_like's axis 4, ur10's
  axis 5, tool_changer's axis 6; sized to 0.25-0.6 mm. Unlike set G's axial float (a helical shaft's float turning
  the output) or set G's bearing clearance (radial play), the body beyond translates along the roll axis. Driven by
  the pose and the payload (logged). The true structure: one column, amplitude half the end play.
* rope lay (``rope_lay``): a capstan-driven joint (a steel rope wrapped on a motor capstan and anchored on the output
  drum: Townsend, MIT PhD thesis, 1988, the WAM arm's cable drives) rolls the rope on its crowns: the pitch radius
  ripples with the strands' crowns (n_s 6-8 per lay length) and once per lay length with the core's ovality (Feyrer,
  *Wire Ropes*, 2nd ed., 2015, ch. 1: lay length 6-8 rope diameters), so the output lags and leads the capstan
  periodically in the rope's travel, at 2 pi R / L and n_s times that per output radian (drum radius R 40-80 mm, rope
  1.5-3 mm). ur10's and kr16_like's axes 1 and 4 (assumed capstan stages, as set ZK's capstan spans). Unlike set ZK's
  capstan spans (the free spans' compliance), set O's mesh error or set M's rope creep, the error is periodic in the
  rope's travel. Driven by the joint angles (logged). The true structure: sin / cos columns per axis and period,
  amplitudes the harmonics.
* magnetostrictive sensor (``magnetostrictive_rod``): tool_changer's telescopic stage read by a magnetostrictive
  (Wiedemann-effect) waveguide sensor: a torsional strain pulse's travel time from the position magnet (MTS
  Temposonics / Balluff data, as recalled: linearity +-0.01-0.05 % FS; Lenz & Edelstein, IEEE Sensors J. 6, 2006,
  magnetic sensors) -- a gradient (pulse speed) set off the rod's (a scale error) and the waveguide's non-uniform
  tension (a smooth bow) give an error e(s) = sum c_n P_n(x) (Legendre polynomials of the stroke, n = 1-3),
  0.1-0.5 mm over 500 mm. Unlike set Q's draw wire, set T's rangefinder (cyclic errors) or set S's potentiometers,
  the error is the waveguide's travel-time law. Driven by the stroke (logged). The true structure: three columns,
  amplitudes c_n.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_joint import _size_cols
from sim2real_indep.effects_zm_joint import wrist_bends
from sim2real_indep.session import BOXES


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- moisture
def moisture(p, session):
    """(P,) the teeth's moisture uptake M(t) (0 dry, 1 saturated) since the washdown (Fick, a plate)."""
    t = session.time_s - session.time_s[0] + p["t_w"]
    n = 2 * np.arange(200)[:, None] + 1
    return 1 - (8 / (n ** 2 * np.pi ** 2) * np.exp(-n ** 2 * t[None] / p["tau_d"])).sum(axis=0)


def hygro_draw(ctx, hw, rng):
    p = {"t_w": 60 * float(rng.uniform(5.0, 20.0)), "tau_d": 3600 * float(rng.uniform(1.0, 4.0)),
         "a": float(rng.uniform(0.3, 0.8))}
    p["c"] = _size_cols(hygro_features(p, ctx, hw), rng)
    return p


def hygro_features(p, ctx, hw):
    w = 1 + p["a"] * moisture(p, ctx.session)
    return np.array([ctx.joint_feature(j, ctx.loads[:, j] * w) for j in wrist_bends(ctx.chain)])


def hygro_apply(p, ctx, hw):
    return _amp_apply(p["c"], hygro_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- payload estimate
def payload_torque(ctx):
    """(P, n) the joint loads of 1 kg at the payload's centre of mass [N m / kg]."""
    m, pos, body = ctx.mass_state
    unit = np.zeros_like(m)
    unit[:, -1] = 1.0
    return kin.gravity_loads(ctx.chain, ctx.q, unit, pos, body)


def estimate(p, session):
    """(P,) the controller's payload estimate after each move into a pose [kg]."""
    out, m = np.empty(len(session.payload_kg)), p["m0"]
    for i, (mt, tm) in enumerate(zip(session.payload_kg, session.move_s)):
        m = m + (1 - np.exp(-tm / p["tau_e"])) * (mt - m)
        out[i] = m
    return out


def estimator_joints(ctx):
    T = np.abs(payload_torque(ctx)).max(axis=0)
    return [j for j in range(ctx.chain.n) if ctx.chain.revolute[j] and T[j] > 0.05 * T.max()]


def estimator_draw(ctx, hw, rng):
    pk = ctx.session.payload_kg
    p = {"tau_e": float(rng.uniform(20.0, 60.0)),
         "m0": float(rng.uniform(0.0, 1.2) * max(pk.max(), 1.0))}
    p["c"] = _size_cols(estimator_features(p, ctx, hw), rng)
    return p


def estimator_features(p, ctx, hw):
    r = ctx.session.payload_kg - estimate(p, ctx.session)
    T = payload_torque(ctx)
    return np.array([ctx.joint_feature(j, T[:, j] * r) for j in estimator_joints(ctx)])


def estimator_apply(p, ctx, hw):
    return _amp_apply(p["c"], estimator_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- holding valves
VALVE_JOINTS = (1, 2)  # tool_changer's axes 2 and 3


def lowered_last(ctx, j):
    """(P,) 1 where the last move of joint j went with its gravity load (a lowering), else 0."""
    s = ctx.session
    down = s.direction[:, j] == np.sign(ctx.loads[:, j])
    out, prev = np.empty(len(down)), float(down[0])
    for i in range(len(down)):
        if i == 0 or s.speed[i, j] > 0:
            prev = float(down[i])
        out[i] = prev
    return out


def valve_draw(ctx, hw, rng):
    p = {}
    p["d"] = _size_cols(valve_features(p, ctx, hw), rng).tolist()
    return p


def valve_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, lowered_last(ctx, j)) for j in VALVE_JOINTS])


def valve_apply(p, ctx, hw):
    return _amp_apply(p["d"], valve_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- roll end play
ENDPLAY_J = {"ur10": 4, "kr16_like": 3, "tool_changer": 5}


def axial_force(ctx, j):
    """(P,) the weight of everything beyond joint j along its axis [N]."""
    m, _, body = ctx.mass_state
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    W = m[:, body >= j + 1].sum(axis=1) * kin.G
    return -W * w[:, j, 2]


def endplay_side(p, ctx):
    j = ENDPLAY_J.get(ctx.chain.name, 4)
    F = axial_force(ctx, j)
    out, prev = np.empty(len(F)), p["s0"]
    for i, f in enumerate(F):
        if abs(f) > p["f"]:
            prev = float(np.sign(f))
        out[i] = prev
    return out


def endplay_draw(ctx, hw, rng):
    j = ENDPLAY_J.get(ctx.chain.name, 4)
    p = {"f": float(rng.uniform(0.1, 0.3) * np.abs(axial_force(ctx, j)).max()), "s0": float(rng.choice([-1.0, 1.0]))}
    p["e2"] = float(_size(endplay_features(p, ctx, hw), [1.0], rng)[0])
    return p


def endplay_features(p, ctx, hw):
    j = ENDPLAY_J.get(ctx.chain.name, 4)
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    return (w[:, j] * endplay_side(p, ctx)[:, None])[None]


def endplay_apply(p, ctx, hw):
    return _amp_apply([p["e2"]], endplay_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- rope lay
ROPE_JOINTS = (0, 3)  # axes 1 and 4


def rope_draw(ctx, hw, rng):
    p = {"k": {}}
    for j in ROPE_JOINTS:
        R, d = rng.uniform(40.0, 80.0), rng.uniform(1.5, 3.0)
        k1 = 2 * np.pi * R / (rng.uniform(6.0, 8.0) * d)
        p["k"][j] = [float(k1), float(k1 * rng.integers(6, 9))]
    F = rope_features(p, ctx, hw)
    ph = rng.uniform(0, 2 * np.pi, len(F) // 2)
    rel = np.repeat(rng.uniform(0.3, 1.0, len(F) // 2), 2) * np.ravel([[np.cos(a), np.sin(a)] for a in ph])
    p["amp"] = _size(F, rel, rng).tolist()
    return p


def rope_features(p, ctx, hw):
    cols = []
    for j in ROPE_JOINTS:
        for k in p["k"][j]:
            cols += [ctx.joint_feature(j, np.sin(k * ctx.q[:, j])), ctx.joint_feature(j, np.cos(k * ctx.q[:, j]))]
    return np.array(cols)


def rope_apply(p, ctx, hw):
    return _amp_apply(p["amp"], rope_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- magnetostrictive
STROKE_J = 3  # tool_changer's telescopic stage


def stroke_x(ctx):
    lo, hi = BOXES["tool_changer"][0][STROKE_J], BOXES["tool_changer"][1][STROKE_J]
    return 2 * (ctx.q[:, STROKE_J] - lo) / (hi - lo) - 1


def legendre(x):
    return [x, (3 * x ** 2 - 1) / 2, (5 * x ** 3 - 3 * x) / 2]


def rod_draw(ctx, hw, rng):
    c = rng.normal(0, 1, 3) * [1.0, 0.6, 0.4]
    e = np.polynomial.legendre.legval(np.linspace(-1, 1, 201), np.r_[0.0, c])
    p = {"c": (c * rng.uniform(0.1, 0.5) / np.abs(e).max()).tolist()}  # [mm]
    return p


def rod_features(p, ctx, hw):
    return np.array([ctx.joint_feature(STROKE_J, P) for P in legendre(stroke_x(ctx))])


def rod_apply(p, ctx, hw):
    return _amp_apply(p["c"], rod_features(p, ctx, hw))
