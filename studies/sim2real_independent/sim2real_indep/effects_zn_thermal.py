"""Set ZN thermal effects (new physics, not in sets A-ZM): the arm's links bowed by the gas-fired radiant tube heaters of
the hall's roof, cycling on the hall's thermostat; and axis 2's holding brake dragging (not fully released), its
friction heating the joint and the upper arm whenever the axis turns. Same protocol as :mod:`effects_joint`.

Sources:

* radiant tube heaters (``radiant_tube_heater``): halls are often heated by gas-fired radiant tubes under the roof
  that a thermostat switches on while the air is below its set point (EN 416-1 / EN 419 radiant heaters; ASHRAE
  Handbook -- HVAC Systems and Equipment, ch. 16, infrared radiant heaters). The infrared falls on the upward faces of
  the arm's tubes: a tube inclined at phi to the vertical takes a flux ~ sin phi on its top, so a gradient dT across
  its depth h bows it with the curvature alpha dT / h (a uniformly curved tube turns its far end by alpha dT L / h;
  Timoshenko & Goodier, *Theory of Elasticity*, ch. 13; Boley & Weiner, *Theory of Thermal Stresses*, 1960), the
  top side outward, about the horizontal axis normal to it. The gradient follows the heaters' on-state (on while the
  logged hall air is in its cool half-cycle, a duty set by the thermostat's offset) through the tubes' lag tau 5-15
  min; the air cycles by 0.3-0.8 K over 20-40 min (logged). Tubes of 200 mm or more; blocks with pauses of 10-30 min
  span several cycles. Unlike set E's sunlight (a side lit by the moving sun), set O's IR dryer (a panel facing the
  arm), set ZM's radiant envelope (the links' mean temperature) or set E's fan thermostat (motor housings), the
  gradient is across the tubes from above, switched by the hall's thermostat. Driven by the heaters' cycle (the
  logged air shows it) and the pose. The true structure: one column, amplitude alpha dT / h.
* dragging brake (``dragging_brake``): a spring-applied holding brake whose armature does not clear the friction
  disc (a worn lining shrinking the air gap, or a release voltage sagging on a long cable: Kendrion / Mayr ROBA-stop
  manuals on the air gap and the residual drag of a poorly released brake, as recalled) drags at 0.2-1 N m on the
  motor shaft; its heat, the drag times the motor's speed (tens to a hundred W), warms axis 2's joint housing and from
  it the upper arm (and half as much the link below), a lumped node of time constant 20-60 min (Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 5). The arm exercises between the blocks (10-30 min of production) and
  only moves between the poses during them. Unlike set A's activity heat (every drive's losses from its torque), set
  ZE's holding copper loss (the gravity torque at standstill) or set ZG's rotary union, the heat is the brake's
  friction, following axis 2's speed alone. Driven by axis 2's motion (its speeds follow from the logged angles and
  time stamps); no temperature of it is logged. The true structure: one column (the links' stretch times the node),
  amplitude alpha dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zm_thermal import _grid, _lag

Z = np.array([0.0, 0.0, 1.0])


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- radiant tubes
def heater_on(p, session, t_s):
    """The heaters' state (1 on) at times t_s: on while the hall's air cycle is below the thermostat's offset."""
    a = session.air
    t_h = (np.asarray(t_s, float) - session.time_s[0]) / 3600
    return (np.sin(2 * np.pi * t_h * 60 / a["period_min"] + a["phase"]) < p["offset"]).astype(float)


def gradient_node(p, session):
    """(P,) the tubes' top-to-bottom gradient per unit (the heaters' state lagged by tau), settled an hour before."""
    tg = _grid(session)
    return np.interp(session.time_s, tg, _lag(heater_on(p, session, tg), p["tau"], 0.0))


def tube_bows(ctx, node):
    """(P, 3) the target's displacement [mm] when every tube of 200 mm or more bows by node * L * sin(phi) about the
    horizontal axis normal to it (a turn about its mid-length)."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    start_home = np.cumsum(ch.links, axis=0) - ch.links
    out = np.zeros((len(ctx.q), 3))
    for li, v0 in enumerate(ch.links):
        L = np.linalg.norm(v0)
        if L < 200.0:
            continue
        b = ch.link_body[li]
        v = np.einsum("pij,j->pi", R[:, b], v0)
        mid = np.einsum("pij,j->pi", R[:, b], start_home[li] + v0 / 2) + t[:, b]
        u = np.cross(Z, v) / L                                   # |u| = sin(phi)
        out += np.cross(u * (node * L / 1000.0)[:, None], ctx.target - mid)
    return out


def radiant_draw(ctx, hw, rng):
    p = {"offset": float(rng.uniform(-0.3, 0.3)), "tau": 60 * float(rng.uniform(5.0, 15.0))}
    p["amp"] = float(_size(radiant_features(p, ctx, hw), [1.0], rng)[0])
    return p


def radiant_features(p, ctx, hw):
    return tube_bows(ctx, gradient_node(p, ctx.session))[None]


def radiant_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], radiant_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dragging brake
BRAKE_J = 1  # axis 2


def brake_speed(session, tg, j=BRAKE_J):
    """(T,) axis j's speed [rad/s] on the grid: the exercise's mean speed in the gaps before blocks, each move's mean
    speed during it, nothing in the dwells and pauses."""
    s = session
    u = np.zeros(len(tg))
    end_move = s.time_s - s.dwell_s
    start_move = end_move - s.move_s
    for i in range(len(s.time_s)):
        u[(tg >= start_move[i]) & (tg < end_move[i])] = s.speed[i, j]
        if s.gap_s[i] > 0:
            u[(tg >= start_move[i] - s.gap_s[i]) & (tg < start_move[i])] = s.exercise_speed[j]
    return u


def brake_node(p, session):
    """(P,) the joint's temperature rise per unit (heat proportional to the speed, lag tau; 1 = steady at the
    exercise's speed)."""
    tg = _grid(session)
    u = brake_speed(session, tg) / max(session.exercise_speed[BRAKE_J], 1e-9)
    return np.interp(session.time_s, tg, _lag(u, p["tau"], 0.0))


def brake_draw(ctx, hw, rng):
    p = {"tau": 60 * float(rng.uniform(20.0, 60.0))}
    p["amp"] = float(_size(brake_features(p, ctx, hw), [1.0], rng)[0])
    return p


def brake_features(p, ctx, hw):
    body = ctx.chain.link_body
    stretch = ctx.link_scale_feature(body == BRAKE_J + 1) + 0.5 * ctx.link_scale_feature(body == BRAKE_J)
    return (stretch * brake_node(p, ctx.session)[:, None])[None]


def brake_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], brake_features(p, ctx, hw))

