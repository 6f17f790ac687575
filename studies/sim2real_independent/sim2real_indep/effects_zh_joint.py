"""Set ZH joint effects (new physics, not in sets A-ZG): axis 2's mesh softened where its flanks wore in the
production zone; axis 3's ring with a cracked tooth root; the loaded axes' lost motion held centred by gelled grease
after each pause; axis 1 driven by two torque-biased pinions that hand the drive over with the motion's direction; and
axis 2's final-stage profile errors polished away as the gears run in. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* worn mesh: mild sliding wear removes flank material where the gear pair works most (Archard's law applied to gear
  flanks: Flodin & Andersson, "Simulation of mild wear in spur gears", Wear 207, 1997); the thinned teeth bend more
  (the single-tooth stiffness falls with the tooth's thickness, ISO 6336-1:2019 clause 9), so the mesh is softer in the
  worn zone of the output's turn: dq2 = c tau2 exp(-(q2 - q_w)^2 / (2 s^2)), q_w the production zone's centre (the
  30-70 % quantile of the session's axis-2 angles), s 6-15 deg. Unlike set E's varying stiffness (a periodic mesh
  stiffness along every turn), set F's wear zones (lash opening in the worn zone) or set ZG's missing pin (a pulse per
  crank turn), the compliance itself grows in one broad zone of the output angle. Sized to 0.25-0.6 mm. Driven by the
  pose and payload (logged). The true structure: one column, amplitude c [rad / (N m)].
* tooth crack: a fatigue crack at one tooth root of axis 3's ring (z 50-70 teeth) lowers that tooth's bending
  stiffness (Chaari, Fakhfakh & Haddar, "Analytical modelling of spur gear tooth crack and influence on gearmesh
  stiffness", Eur. J. Mech. A/Solids 28, 2009: 10-40 % of the mesh stiffness lost while the cracked tooth carries
  load); the softening lasts while the cracked tooth and its neighbours share the load, 1.5-2.5 pitches, once per
  output turn: dq3 = c tau3 cos^2(pi psi / (2 h)) for |psi| < h, psi = q3 - q_c. Unlike the worn zone (a broad
  Gaussian of the production zone) the window is a narrow mesh span at one tooth; unlike set ZG's chipped pinion (a
  geometric dip, load-free) it scales with the torque. Sized to 0.25-0.6 mm. Driven by the pose and payload (logged).
  The true structure: one column, amplitude c.
* grease gel: a lithium-soap grease is thixotropic: at rest its structure rebuilds and it sets as a gel with a yield
  stress, sheared down again by motion (Barnes, "Thixotropy -- a review", J. Non-Newtonian Fluid Mech. 70, 1997;
  grease rheology: Lugt, *Grease Lubrication in Rolling Bearings*, Wiley, 2013, ch. 5). In a grease-filled spur stage
  the gel that set in the lash during a pause holds the output centred; each move shears it, so the output trails its
  motion across a growing share 1 - exp(-n / n0) of the lash, n the moves since the last pause, n0 2-6. Unlike set H's
  cold grease (friction lost motion fading with the joints' temperature), set ZF's viscous crossing (the dwell's oil
  film) or set Q's squeeze film, the lash opens with the count of moves after a rest. Half-plays sized to 0.25-0.6 mm.
  Driven by the motion and the pauses (logged). The true structure: one column per loaded axis, the half-plays [rad].
* pinion handover: a large slewing axis driven by two pinions under a torque bias (the master drives, the slave
  counter-torques; the roles swap with the commanded torque's sign: Gawronski et al., "Torque-bias profile for improved
  tracking of the Deep Space Network antennas", IEEE Antennas Propag. Mag. 42(6), 2000); each pinion has its own
  runout, a transmission error once per pinion turn (Smith, *Gear Noise and Vibration*, 2003, ch. 9), so the ring
  follows pinion A's runout after a positive move and pinion B's after a negative one: e = [d > 0] a_A sin(r q1 +
  phi_A) + [d < 0] a_B sin(r q1 + phi_B), r = z_ring / z_pinion (6-10, not an integer). Unlike set G's twin pinion
  (the preload's stiffness), set X's pinion runout (one pinion) or the lost motions of sets A-ZG, the periodic error
  itself switches with the last motion. Sized to 0.25-0.6 mm. Driven by axis 1's angle and direction (logged). The
  true structure: four columns (sin, cos per pinion).
* running-in TE: a new final stage (wheel of z 40-70 teeth) carries profile errors from its finishing that repeat at
  each tooth mesh; running in polishes them down, the profile deviation decaying with the sliding distance
  (Archard; the running-in of gear flanks: Sosa, Bjorklund, Sellgren & Olofsson, "In situ running-in of gears", Tribol.
  Int. 82, 2015): e = exp(-E / E0) (a sin(z q2) + b cos(z q2)), E the travel of axis 2 so far, E0 30-60 % of the
  session's. Unlike set F's wear zones or set Z's run-in wear (a lash opening) and the steady periodic errors of sets
  A-ZG, a tooth-mesh error fading with the travel. Sized to 0.25-0.6 mm. Driven by axis 2's angles (logged). The true
  structure: two columns.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def loaded_joints(chain):
    return [j for j in (1, 2) if chain.revolute[j]]


# ---------------------------------------------------------------------------------------------------- worn mesh
def wear_zone(p, q2):
    return np.exp(-0.5 * ((q2 - p["q_w"]) / p["s"]) ** 2)


def worn_draw(ctx, hw, rng):
    p = {"q_w": float(np.quantile(ctx.q[:, 1], rng.uniform(0.3, 0.7))), "s": float(np.deg2rad(rng.uniform(6, 15)))}
    p["c"] = _size(worn_features(p, ctx, hw), [1.0], rng)
    return p


def worn_features(p, ctx, hw):
    return ctx.joint_feature(1, ctx.loads[:, 1] * wear_zone(p, ctx.q[:, 1]))[None]


def worn_apply(p, ctx, hw):
    return _amp_apply(p["c"], worn_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- tooth crack
def crack_window(p, q3):
    psi = q3 - p["q_c"]
    return np.where(np.abs(psi) < p["h"], np.cos(np.pi * psi / (2 * p["h"])) ** 2, 0.0)


def crack_draw(ctx, hw, rng):
    z = int(rng.integers(50, 71))
    p = {"q_c": float(np.quantile(ctx.q[:, 2], rng.uniform(0.25, 0.75))), "h": rng.uniform(1.5, 2.5) * np.pi / z,
         "z": z}
    p["c"] = _size(crack_features(p, ctx, hw), [1.0], rng)
    return p


def crack_features(p, ctx, hw):
    return ctx.joint_feature(2, ctx.loads[:, 2] * crack_window(p, ctx.q[:, 2]))[None]


def crack_apply(p, ctx, hw):
    return _amp_apply(p["c"], crack_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- grease gel
def moves_since_pause(session):
    """(P,) the moves since the last pause (the first pose of a block after a pause: 1; the session's first: 0)."""
    n = np.zeros(len(session.time_s))
    for k in range(1, len(n)):
        n[k] = 1.0 if session.gap_s[k] < 0 else n[k - 1] + 1.0
    return n


def gel_share(p, session):
    return 1.0 - np.exp(-moves_since_pause(session) / p["n0"])


def gel_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    p = {"n0": rng.uniform(2.0, 6.0)}
    p["half"] = _size(gel_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(js)), rng)
    return p


def gel_features(p, ctx, hw):
    s = gel_share(p, ctx.session)
    return np.array([ctx.joint_feature(j, -ctx.session.direction[:, j] * s) for j in loaded_joints(ctx.chain)])


def gel_apply(p, ctx, hw):
    return _amp_apply(p["half"], gel_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- pinion handover
def handover_signals(p, q1, d1):
    a, b = (d1 > 0).astype(float), (d1 < 0).astype(float)
    x = p["ratio"] * q1
    return np.array([a * np.sin(x), a * np.cos(x), b * np.sin(x), b * np.cos(x)])


def handover_draw(ctx, hw, rng):
    z_p = int(rng.integers(12, 19))
    p = {"ratio": int(round(z_p * rng.uniform(6.0, 10.0))) / z_p}
    ph = rng.uniform(0, 2 * np.pi, 2)
    amp = rng.uniform(0.5, 1.5, 2)
    rel = [amp[0] * np.cos(ph[0]), amp[0] * np.sin(ph[0]), amp[1] * np.cos(ph[1]), amp[1] * np.sin(ph[1])]
    p["e"] = _size(handover_features(p, ctx, hw), rel, rng)
    return p


def handover_features(p, ctx, hw):
    sig = handover_signals(p, ctx.q[:, 0], ctx.session.direction[:, 0])
    return np.array([ctx.joint_feature(0, s) for s in sig])


def handover_apply(p, ctx, hw):
    return _amp_apply(p["e"], handover_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- running-in TE
def travel(session, j):
    """(P,) axis j's travel [rad] from the session's first pose to each pose."""
    return np.cumsum(np.abs(np.diff(session.q[:, j], prepend=session.q[0, j])))


def runin_draw(ctx, hw, rng):
    E = travel(ctx.session, 1)
    p = {"z": int(rng.integers(40, 71)), "E0": float(max(E[-1], 1e-9) * rng.uniform(0.3, 0.6))}
    ph = rng.uniform(0, 2 * np.pi)
    p["e"] = _size(runin_features(p, ctx, hw), [np.cos(ph), np.sin(ph)], rng)
    return p


def runin_features(p, ctx, hw):
    decay = np.exp(-travel(ctx.session, 1) / p["E0"])
    x = p["z"] * ctx.q[:, 1]
    return np.array([ctx.joint_feature(1, decay * np.sin(x)), ctx.joint_feature(1, decay * np.cos(x))])


def runin_apply(p, ctx, hw):
    return _amp_apply(p["e"], runin_features(p, ctx, hw))
