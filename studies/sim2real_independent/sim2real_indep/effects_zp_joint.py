"""Set ZP joint effects (new physics, not in sets A-ZO): a washdown-soaked protective jacket drying on the arm; the arm
on a vessel that lists as its ballast is shifted; the boom cylinders' eye pins' clearances taken up by the cylinders'
force through their varying lever arm; a spiral-spring anti-backlash preload on the wrist rolls; a polyester code
strip on axis 1's drum swelling with the hall's humidity; and boom axes whose position is integrated from analogue
tachogenerators. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* soaked jacket (``soaked_jacket``): a food-grade protective jacket (a coated polyester / PVC robot suit, as used in
  washdown and foundry cells) on the upper arm and forearm takes up water in the cell's hose-down; the textile and its
  seams hold 0.3-1.5 kg, which drains and evaporates in the falling-rate period of drying, m(t) = m0 exp(-t / tau_d),
  tau_d 30-90 min (Keey, *Drying of Loose and Particulate Materials*, 1992, ch. 1 and 6; Mujumdar (ed.), *Handbook of
  Industrial Drying*, 3rd ed., 2006, ch. 1), the session beginning 2-10 min after the rinse. The water's weight, spread
  over the upper arm (60 %) and the forearm (40 %) like the links' own masses, twists the gears of axes 2 and 3 (their
  compliance). Blocks with pauses of 15-45 min. Unlike set Y's frost load (ice accreting from the air), set W's swarf
  shroud or set L's emptying cartridge (masses at the tool), the jacket's water leaves the links' covers as they dry.
  Driven by the time since the rinse and the pose; nothing of the water is logged. The true structure: one column per
  axis, amplitudes m0 times the gear's compliance.
* vessel list (``vessel_list``): the arm works on a barge or a ship's deck (offshore and shipyard robotics), the tracker
  on the same deck; as ballast water is pumped across to trim the vessel, the deck lists steadily by 0.1-0.4 deg over
  the session about an axis of any heading (hydrostatics of list: Biran & Lopez-Pulido, *Ship Hydrostatics and
  Stability*, 2nd ed., 2014, ch. 2 and 6: tan(phi) = w d / (Delta GM)). The tracker turns with the deck, so the list is
  invisible except through gravity's direction in the base frame: the gravity loads change by phi (e x g) and the gears
  of axes 1-3 twist by their compliance (axis 1, whose gravity torque is zero on a level floor, is loaded too). Unlike
  set I's tilted base (a fixed inclination), set O's pontoon (a float tilted by the arm's own moment) or set ZE's
  slewing rock, the tilt grows in time, whatever the arm does. Driven by the time (the list is not logged). The true
  structure: one column per axis (1-3), amplitudes phi_max times the compliance.
* clevis clearance (``clevis_clearance``): tool_changer's boom axes 2 and 3 are driven by hydraulic cylinders pinned at
  both ends (base eye and rod eye; the geometry of set D's gas spring: length L = sqrt(r1^2 + r2^2 - 2 r1 r2 cos psi),
  moment arm h = r1 r2 sin psi / L); a constant-torque hydropneumatic counterbalance set to 80-120 % of the
  median gravity torque carries the rest, so the cylinders push or pull by the pose. Each eye pin has a diametral clearance (ISO 286 clearance fits of worn pins,
  0.1-0.4 mm); the cylinder's force, which carries the joint's gravity torque, takes the clearances up on its side, so
  the joint turns by c / h(q) one way or the other
  (with the cylinder's net force's sign); within a friction band f (5-20 % of the largest torque) the pins
  stay where the last larger load left them (Shigley's *Mechanical Engineering Design*, 10th ed., ch. 7 on fits; pin
  joints' lost motion: Slocum, *Precision Machine Design*, 1992, ch. 7). Unlike set V's journal climb (the boom's pins
  at the joints, climbing against the last rotation) or set F's clevis stiffness, the play lies along the cylinder and
  is seen through its varying lever arm. Driven by the pose and the payload (logged). The true structure: one column
  per axis, amplitude the clearance.
* spiral-spring preload (``clock_spring_flank``): the wrist rolls (axes 4 and 6) are preloaded against one flank of
  their gear's lost motion by a spiral (clock) spring between the output and the housing (an anti-backlash device:
  Slocum, ch. 7; spiral springs' linear torque k (q - q_s): Wahl, *Mechanical Springs*, 2nd ed., 1963, ch. 15). The
  spring winds as the joint turns, so the output leans on the flank that the sum of the spring's torque and gravity's
  chooses; within a friction band it stays on its last flank. The spring's torque at the range's ends 0.5-1.5 times the
  largest gravity torque. Unlike set ZF's centring spring (a spring holding the output mid-clearance), set S's overshoot
  lash or the gravity-chosen flanks of sets A-ZO, the flank changes at a joint angle that the spring's wind-up sets.
  Driven by the pose and the payload (logged). The true structure: one column per axis, amplitude the lost motion.
* polyester code strip (``mylar_strip``): axis 1 read by a reflective code strip of polyester (PET) film glued around
  a drum (low-cost large-diameter encoders), referenced at its index mark q_ref. PET swells with the water it takes up,
  beta_h 0.7-1.1e-5 per % RH (DuPont Teijin Films, *Mylar* physical-properties bulletin, as recalled), through its
  thickness with a lag tau 10-40 min (Crank, *The Mathematics of Diffusion*, 1975, a thin film); the strip's marks move
  apart and the reading errs by -eps (q - q_ref). The hall's humidity is off the strip's calibration by -8..8 % RH and
  drifts by 10-25 % RH over the session (unlogged). Unlike set F's tape scale (a steel tape's temperature), set ZN's
  moisture-softened gears or set V's swelling boom, a scale of axis 1's reading follows the humidity. Driven by the
  time and axis 1's angle. The true structure: two columns (the standing and the drifting strain).
* tachogenerator position (``tacho_integration``): tool_changer's boom axes 2 and 3 take their position by integrating
  an analogue tachogenerator's voltage from the homing at the lower limit (older heavy hydraulic manipulators; the
  integrator's drift: D'Azzo & Houpis, *Linear Control System Analysis and Design*, 4th ed., 1995, ch. on integral
  control; tachogenerator gain tolerance +-0.1-0.5 %, makers' data as recalled). The gain error gives an error
  g (q - q_home); the amplifier's offset integrates to b t while the position loop holds the integrated value. Unlike
  set U's dropped counts or set W's miscounts (an incremental encoder's counts), the reading is an integral of an
  analogue speed; the offset's drift outweighs the gain error over a session (weights
  1-1.5 against 0.05-0.15; a working day's blocks with pauses of 30-90 min). Driven by the pose and the time. The true structure: two columns per axis, amplitudes g and b.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zi_joint import _size_cols
from sim2real_indep.effects_zm_thermal import _grid, _lag


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _t(session):
    return session.time_s - session.time_s[0]


def _hold_flank(x, f, s0):
    """(P,) sign(x) where |x| > f, else the last such sign (s0 before the first)."""
    out, s = np.empty(len(x)), s0
    for i, v in enumerate(x):
        if abs(v) > f:
            s = float(np.sign(v))
        out[i] = s
    return out


# ---------------------------------------------------------------------------------------------------- soaked jacket
JACKET_J = (1, 2)


def jacket_torque(ctx):
    """(P, 2) gravity torque [N m] on axes 2 and 3 of 1 kg of water spread 60 / 40 over the upper arm and forearm (at
    their links' centres of mass)."""
    m, pos, body = ctx.mass_state
    out = np.zeros((len(ctx.q), 2))
    for b, share in ((2, 0.6), (3, 0.4)):
        sel = np.flatnonzero(body[:-1] == b)
        if not len(sel):
            continue
        w = m[:, sel] / m[:, sel].sum(axis=1, keepdims=True) * share
        out += kin.gravity_loads(ctx.chain, ctx.q, w, pos[:, sel], body[sel])[:, list(JACKET_J)]
    return out


def jacket_features(p, ctx, hw):
    tau = jacket_torque(ctx) * np.exp(-(_t(ctx.session) + p["t_w"]) / p["tau_d"])[:, None]
    return np.array([ctx.joint_feature(j, tau[:, k]) for k, j in enumerate(JACKET_J)])


def jacket_draw(ctx, hw, rng):
    p = {"t_w": 60 * float(rng.uniform(2.0, 10.0)), "tau_d": 60 * float(rng.uniform(30.0, 90.0))}
    p["c"] = _size_cols(jacket_features(p, ctx, hw), rng).tolist()
    return p


def jacket_apply(p, ctx, hw):
    return _amp_apply(p["c"], jacket_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- vessel list
LIST_J = (0, 1, 2)


def list_torque(p, ctx):
    """(P, n) the gravity loads' change per radian of list about the deck's axis e (psi)."""
    e = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    m, pos, body = ctx.mass_state
    return kin.gravity_loads(ctx.chain, ctx.q, m, pos, body, gravity=np.cross(e, [0.0, 0.0, -1.0]))


def list_features(p, ctx, hw):
    t = _t(ctx.session)
    ramp = t / max(t[-1], 1.0)
    dtau = list_torque(p, ctx) * ramp[:, None]
    return np.array([ctx.joint_feature(j, dtau[:, j]) for j in LIST_J])


def list_draw(ctx, hw, rng):
    p = {"psi": float(rng.uniform(0, 2 * np.pi))}
    p["c"] = _size_cols(list_features(p, ctx, hw), rng).tolist()
    return p


def list_apply(p, ctx, hw):
    return _amp_apply(p["c"], list_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- clevis clearance
CLEVIS_J = (1, 2)  # tool_changer's boom axes 2 and 3


def lever_arm(g, q):
    """(P,) the cylinder's moment arm [m] at joint angle q."""
    psi = g["psi0"] + q
    L = np.sqrt(g["r1"] ** 2 + g["r2"] ** 2 - 2 * g["r1"] * g["r2"] * np.cos(psi))
    return g["r1"] * g["r2"] * np.sin(psi) / L


def clevis_flanks(p, ctx):
    """(P, 2) the side the cylinders' net force (gravity less the boom's counterbalance) takes the clearances up on."""
    return np.stack([_hold_flank(ctx.loads[:, j] - p["bal"][k], p["f"][k], p["s0"][k])
                     for k, j in enumerate(CLEVIS_J)], axis=1)


def clevis_features(p, ctx, hw):
    """(2, P, 3) per mm of clearance: the joint turned by flank / (1000 h(q)) [rad]."""
    s = clevis_flanks(p, ctx)
    return np.array([ctx.joint_feature(j, s[:, k] / (1000.0 * lever_arm(p["geo"][k], ctx.q[:, j])))
                     for k, j in enumerate(CLEVIS_J)])


def clevis_draw(ctx, hw, rng):
    geo = []
    for j in CLEVIS_J:
        lo, hi = ctx.chain.lower[j], ctx.chain.upper[j]
        mid = np.deg2rad(rng.uniform(75.0, 105.0))  # psi at mid-range: the arm near its largest
        geo.append({"r1": float(rng.uniform(0.3, 0.5)), "r2": float(rng.uniform(0.4, 0.7)),
                    "psi0": float(mid - (lo + hi) / 2)})
    T = np.abs(ctx.loads[:, list(CLEVIS_J)]).max(axis=0)
    bal = np.median(ctx.loads[:, list(CLEVIS_J)], axis=0) * rng.uniform(0.8, 1.2, 2)
    p = {"geo": geo, "f": (T * rng.uniform(0.05, 0.2, 2)).tolist(), "s0": rng.choice([-1.0, 1.0], 2).tolist(),
         "bal": bal.tolist()}
    p["c"] = _size_cols(clevis_features(p, ctx, hw), rng).tolist()
    return p


def clevis_apply(p, ctx, hw):
    return _amp_apply(p["c"], clevis_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- spiral spring
SPRING_J = (3, 5)  # the wrist rolls, axes 4 and 6


def spring_torque(p, ctx, k, j):
    return p["k_s"][k] * (ctx.q[:, j] - p["q_s"][k])


def spring_flanks(p, ctx):
    return np.stack([_hold_flank(ctx.loads[:, j] + spring_torque(p, ctx, k, j), p["f"][k], p["s0"][k])
                     for k, j in enumerate(SPRING_J)], axis=1)


def spring_features(p, ctx, hw):
    s = spring_flanks(p, ctx)
    return np.array([ctx.joint_feature(j, s[:, k] / 2) for k, j in enumerate(SPRING_J)])


def spring_draw(ctx, hw, rng):
    q = ctx.q[:, list(SPRING_J)]
    T = np.maximum(np.abs(ctx.loads[:, list(SPRING_J)]).max(axis=0), 0.2)
    lo, hi = q.min(axis=0), q.max(axis=0)
    q_s = lo + (hi - lo) * rng.uniform(0.3, 0.7, 2)
    k_s = T * rng.uniform(0.5, 1.5, 2) / np.maximum(np.maximum(hi - q_s, q_s - lo), 1e-3)
    p = {"q_s": q_s.tolist(), "k_s": k_s.tolist(), "f": (T * rng.uniform(0.05, 0.15, 2)).tolist(),
         "s0": rng.choice([-1.0, 1.0], 2).tolist()}
    p["b"] = _size_cols(spring_features(p, ctx, hw), rng).tolist()
    return p


def spring_apply(p, ctx, hw):
    return _amp_apply(p["b"], spring_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- code strip
def strip_humidity(p, session):
    """(P,) the strip's humidity change [fraction of the session's drift]: a ramp lagged by the film's tau."""
    tg = _grid(session)
    t0, span = session.time_s[0], max(session.time_s[-1] - session.time_s[0], 1.0)
    ramp = np.clip((tg - t0) / span, 0.0, 1.0)
    return np.interp(session.time_s, tg, _lag(ramp, p["tau"], 0.0))


def strip_features(p, ctx, hw):
    """(2, P, 3): axis 1's error per unit standing strain and per unit drifting strain."""
    d = -(ctx.q[:, 0] - p["q_ref"])
    return np.array([ctx.joint_feature(0, d), ctx.joint_feature(0, d * strip_humidity(p, ctx.session))])


def strip_draw(ctx, hw, rng):
    lo, hi = ctx.q[:, 0].min(), ctx.q[:, 0].max()
    beta = float(rng.uniform(0.7e-5, 1.1e-5))
    p = {"tau": 60 * float(rng.uniform(10.0, 40.0)), "q_ref": float(lo + (hi - lo) * rng.uniform(0.0, 0.3)),
         "beta": beta, "rh0": float(rng.uniform(-8.0, 8.0)),
         "drh": float(rng.choice([-1.0, 1.0]) * rng.uniform(10.0, 25.0))}
    p["amp"] = [beta * p["rh0"], beta * p["drh"]]
    return p


def strip_apply(p, ctx, hw):
    return _amp_apply(p["amp"], strip_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- tachogenerators
TACHO_J = (1, 2)


def tacho_features(p, ctx, hw):
    """(4, P, 3): per axis, the error per unit gain error (q - q_home) and per unit offset rate [rad/s] (t)."""
    t = _t(ctx.session) + p["t_h"]
    cols = []
    for j in TACHO_J:
        cols += [ctx.joint_feature(j, ctx.q[:, j] - ctx.chain.lower[j]), ctx.joint_feature(j, t)]
    return np.array(cols)


def tacho_draw(ctx, hw, rng):
    p = {"t_h": 60 * float(rng.uniform(2.0, 10.0))}
    F = tacho_features(p, ctx, hw)
    rel = rng.choice([-1.0, 1.0], 4) * np.tile([rng.uniform(0.05, 0.15), rng.uniform(1.0, 1.5)], 2)
    p["amp"] = _size_cols(F, rng, rel).tolist()
    return p


def tacho_apply(p, ctx, hw):
    return _amp_apply(p["amp"], tacho_features(p, ctx, hw))
