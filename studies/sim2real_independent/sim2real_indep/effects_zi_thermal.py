"""Set ZI thermal effects (new physics, not in sets A-ZH): a forearm cooled by a gravity-driven heat pipe
(thermosyphon) that works only while its wrist end hangs below its elbow end; and an upper arm and forearm heated by
their joint electronics and cooled by the air they move through, faster the faster they move. Same protocol as
:mod:`effects_joint`.

Sources:

* thermosyphon: a sealed (wash-down) arm whose wrist motors in the forearm's far end have no fan carries their heat to
  fins at the elbow through a two-phase closed thermosyphon (a wickless heat pipe): its condensate returns by gravity,
  so it conducts only while the evaporator (the wrist end) is lower than the condenser (Faghri, *Heat Pipe Science and
  Technology*, 1995, ch. 5 and 7; Reay, Kew & McGlen, *Heat Pipes*, 6th ed., 2014, ch. 2: a thermosyphon's limits
  and tilt). The forearm is a lumped node (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) with
  the wrist motors' heat P while the servo is on and a conductance G0 (1 + r w), w 0-1 the share of the pipe working
  (from 3 deg of the wrist end's drop to full at 8-12 deg), r 3-8 (the fins against the bare tube): it settles at
  P / (G0 (1 + r w)) with the time constant tau0 / (1 + r w), tau0 10-25 min; in the pauses (20-60 min) the servo is
  off (no heat), in the production between blocks the pipe works for a share w_p 0.3-0.7 of the time. The rise without
  the pipe, P / G0, 25-45 K (first r 2-5, 15-35 K, pauses of 10-30 min: on tool_changer's steel forearm absorbed, 2.4 %,
  on kr16_like 3-23 % in trial draws; now the aluminium arms only); the forearm's length grows by CTE L T. Unlike set
  A's drive heat or set ZH's wrist conduction (heat with a fixed path), the forearm's cooling switches with its
  attitude. Driven by the pose sequence and time (logged); the motors' heat is not. The true structure: one column,
  amplitude CTE x P / G0.
* motion cooling: a cobot's upper arm and forearm warmed by the joint electronics and brakes at their ends (a constant
  heat Q while the servo is on, none in the pauses; the two tubes taken as one node) and cooled by the air: natural
  convection at rest, forced convection while they move through the air, h = h0 (1 + b (v / v0)^0.8), v the upper
  arm's mean far-end speed over each move (the Churchill-Bernstein / Hilpert correlations for a cylinder in cross flow,
  Nu ~ Re^0.6-0.8 at these Reynolds numbers; Incropera & DeWitt, ch. 7), b 1-3 at v0 = 1 m/s; each interval's
  conductance is the time average over its move and dwell, the production between blocks at the production's speeds,
  pauses of 20-60 min. The tubes settle at Q / (h A) with the time constant C / (h A), tau0 10-25 min at rest; the rise
  at rest 15-35 K from a start 0-50 % warm. (First the upper arm alone, 10-25 K from a start 30-80 % warm: ZI05 14.5 %,
  the link model at 1.18x; with production alone between the blocks 0.3-23 % on ur10.) Unlike set A's drive heat
  (losses that grow with the motion) or set ZA's AC jet (an outside air stream), the arm warms in the slow measuring and
  cools in the fast production. Driven by the motion and time (logged); the electronics' heat is not. The true
  structure: one column, amplitude CTE x Q / (h0 A).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zh_thermal import forearm_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def upper_arm_index(chain):
    """The longest link on body 2 (carried by joint 2)."""
    body = np.asarray(chain.link_body)
    norms = np.linalg.norm(chain.links, axis=1) * (body == 2)
    return int(np.argmax(norms))


def _relax(x, target, rate, dt):
    return target + (x - target) * np.exp(-max(dt, 0.0) * rate)


# ---------------------------------------------------------------------------------------------------- thermosyphon
def syphon_share(p, ctx):
    """(P,) the share of the heat pipe working: 0 with the wrist end level or above, 1 once it is 3-12 deg below."""
    li = forearm_index(ctx.chain)
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    d = np.einsum("pij,j->pi", R[:, ctx.chain.link_body[li]], ctx.chain.links[li])
    down = -d[:, 2] / np.linalg.norm(d, axis=1)  # sine of the wrist end's drop
    return np.clip((down - np.sin(np.deg2rad(3.0))) / (np.sin(np.deg2rad(p["full_deg"])) - np.sin(np.deg2rad(3.0))),
                   0.0, 1.0)


def syphon_temperature(p, ctx):
    """(P,) the forearm's rise per unit P / G0."""
    s = ctx.session
    w = syphon_share(p, ctx)
    T = np.empty(len(w))
    x = p["T0"]
    T[0] = x
    for k in range(1, len(w)):
        dt = s.time_s[k] - s.time_s[k - 1]
        g = abs(s.gap_s[k])
        if s.gap_s[k] > 0:  # production: the pipe working for a share w_p of the time
            Gp = 1 + p["r"] * p["w_prod"]
            x = _relax(x, 1 / Gp, Gp / p["tau0_s"], g)
        elif s.gap_s[k] < 0:  # a pause: servo off, the node cools through the pipe's idle conductance
            x = _relax(x, 0.0, 1 / p["tau0_s"], g)
        Gk = 1 + p["r"] * w[k]
        x = _relax(x, 1 / Gk, Gk / p["tau0_s"], dt - g)
        T[k] = x
    return T


def syphon_draw(ctx, hw, rng):
    dT = rng.uniform(25.0, 45.0)
    return {"r": rng.uniform(3.0, 8.0), "tau0_s": 60 * rng.uniform(10.0, 25.0), "full_deg": rng.uniform(8.0, 12.0),
            "w_prod": rng.uniform(0.3, 0.7), "T0": rng.uniform(0.0, 0.3), "dT_K": dT,
            "amp": float(hw["material"]["cte"]) * dT}


def syphon_features(p, ctx, hw):
    li = forearm_index(ctx.chain)
    u = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li)
    return (u * syphon_temperature(p, ctx)[:, None])[None]


def syphon_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], syphon_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- motion cooling
def link_speed(ctx):
    """(P,) the upper arm's mean far-end speed [m/s] over the move into each pose, from axes 1 and 2."""
    s = ctx.session
    L = np.linalg.norm(ctx.chain.links[upper_arm_index(ctx.chain)]) / 1000.0
    dq = np.abs(np.diff(ctx.q[:, :2], axis=0, prepend=ctx.q[:1, :2])).sum(axis=1)
    return np.where(s.move_s > 0, L * dq / np.maximum(s.move_s, 1e-9), 0.0)


def convection(p, v):
    return 1.0 + p["b"] * (np.asarray(v, float) / 1.0) ** 0.8


def cooling_temperature(p, ctx):
    """(P,) the tubes' rise per unit Q / (h0 A)."""
    s = ctx.session
    v = link_speed(ctx)
    L = np.linalg.norm(ctx.chain.links[upper_arm_index(ctx.chain)]) / 1000.0
    v_prod = L * (s.exercise_speed[0] + s.exercise_speed[1])
    T = np.empty(len(v))
    x = p["T0"]
    T[0] = x
    for k in range(1, len(v)):
        dt = s.time_s[k] - s.time_s[k - 1]
        g = abs(s.gap_s[k])
        if s.gap_s[k] > 0:
            Gp = convection(p, v_prod)
            x = _relax(x, 1 / Gp, Gp / p["tau0_s"], g)
        elif s.gap_s[k] < 0:
            x = _relax(x, 0.0, 1 / p["tau0_s"], g)
        span = max(dt - g, 1e-9)
        Gk = (s.move_s[k] * convection(p, v[k]) + (span - s.move_s[k]) * 1.0) / span
        x = _relax(x, 1 / Gk, Gk / p["tau0_s"], span)
        T[k] = x
    return T


def cooling_draw(ctx, hw, rng):
    dT = rng.uniform(15.0, 35.0)
    return {"b": rng.uniform(1.0, 3.0), "tau0_s": 60 * rng.uniform(10.0, 25.0), "T0": rng.uniform(0.0, 0.5),
            "dT_K": dT, "amp": float(hw["material"]["cte"]) * dT}


def cooling_features(p, ctx, hw):
    idx = np.arange(len(ctx.chain.links))
    u = ctx.link_scale_feature((idx == upper_arm_index(ctx.chain)) | (idx == forearm_index(ctx.chain)))
    return (u * cooling_temperature(p, ctx)[:, None])[None]


def cooling_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], cooling_features(p, ctx, hw))
