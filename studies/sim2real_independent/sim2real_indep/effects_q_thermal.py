"""Set Q thermal effects (new physics, not in sets A-P): a vacuum gripper's boom chilled by its ejector's cold exhaust
while a part is held, shrinking and bowing; and the arm chilled by cold outside air let in by a hall door that opens at
random moments (forklift traffic), the hall's air sensor, away from the door, not seeing it. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* ejector chill: a vacuum ejector (a compressed-air venturi) expands its drive air to atmosphere; the exhaust leaves
  cooler than the supply (an expanding, accelerating jet: the static temperature falls by v^2 / (2 c_p); mixing recovers
  part of it) and blows along the gripper boom it is mounted on (makers' notes on ejector exhaust and silencers, as
  recalled; Shapiro, *The Dynamics and Thermodynamics of Compressible Fluid Flow*, 1953, ch. 4 on the static temperature
  of a jet). While a part is held the ejector runs (the payload logged), the boom's mean temperature falls by 4-10 K
  (first 3-8) and its exhaust side by 0.3-0.6 of that more than the far side, through a lag of 2-6 min (walls of 2-4 mm
  in the jet, Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5 on lumped capacitance); the boom (an
  aluminium extrusion of depth 30-50 mm (first 40-60), the target at its tip 400-700 mm along the tool axis:
  :func:`effects_q.probe_hook`) shrinks by alpha L dT and bows towards its exhaust side by alpha dT_g L^2 / (2 D)
  (Timoshenko & Goodier, *Theory of Elasticity*, ch. 13, thermal bending of a bar) (assumed). The true structure: one
  column (the held schedule through the lag its shape), amplitude the mean chill.
* door draught: a hall door opened for traffic lets cold outside air in; it spreads along the floor as a gravity current
  and mixes into the hall (Linden, "The fluid mechanics of natural ventilation", Annu. Rev. Fluid Mech. 31, 1999), so
  the air at an arm near the door falls by 5-12 K (first 3-8) while it is open (winter air some 10-20 K colder outside)
  and recovers with the hall's mixing time of 2-5 min (first 4-10); the links follow through their own lag (8-20 min for
  ur10's thin aluminium tubes, 15-40 min for the heavier arms' walls: rho c t / h) and shrink uniformly by alpha dT.
  Openings of 5-20 min (a loading door; first 1-3 min) as a Poisson process of 1-3 an hour (first 2-5) from 30 min
  before the session (assumed); the logged air is the hall's, measured away from the door. The true structure: one
  column (the openings through both lags its shape), amplitude the air's fall while open.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])
ALU_CTE = 23e-6
BOOM_MM = (400.0, 700.0)


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# ----------------------------------------------------------------------------------------------- ejector chill
def chill_draw(ctx, hw, rng):
    az = rng.uniform(0, 2 * np.pi)
    held0 = float(ctx.session.payload_kg[0] > 0)
    return {"L_mm": float(np.asarray(ctx.probe_mm, float)[2]), "D_mm": rng.uniform(30.0, 50.0),
            "dT_K": rng.uniform(4.0, 10.0), "r_g": rng.uniform(0.3, 0.6), "tau_s": rng.uniform(2.0, 6.0) * 60,
            "side": np.array([np.cos(az), np.sin(az), 0.0]), "x0": held0 * rng.uniform(0.3, 1.0)}


def chill_signal(p, ctx):
    """(P,): the boom's chill per its full value: the ejector running while a part is held (from the pick before the
    move into each pose), through the first-order lag."""
    s = ctx.session
    held = (s.payload_kg > 0).astype(float)
    x, out = p["x0"], np.zeros(len(held))
    for k in range(len(held)):
        if k:
            x = held[k] + (x - held[k]) * np.exp(-(s.time_s[k] - s.time_s[k - 1]) / p["tau_s"])
        out[k] = x
    return out


def chill_local(p):
    """(3,): the tip's displacement per kelvin of mean chill, tool frame: shrinking along the boom, bowing towards the
    exhaust side."""
    L = p["L_mm"]
    return ALU_CTE * (-L * Z + p["r_g"] * L ** 2 / (2 * p["D_mm"]) * p["side"])


def chill_shape(p, ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return chill_signal(p, ctx)[:, None] * (Rt @ chill_local(p))


def chill_apply(p, ctx, hw):
    return Contribution(displace=p["dT_K"] * chill_shape(p, ctx))


def chill_features(p, ctx, hw):
    return chill_shape(p, ctx)[None]


# ----------------------------------------------------------------------------------------------- door draught
DOOR_TAU_MIN = {"ur10": (8.0, 20.0), "kr16_like": (15.0, 40.0), "tool_changer": (15.0, 40.0)}
GRID_S = 10.0


def door_draw(ctx, hw, rng):
    t = ctx.session.time_s
    t0 = t[0] - 1800.0
    rate = rng.uniform(1.0, 3.0) / 3600
    n = int(rng.poisson(rate * (t[-1] - t0))) + 1                       # at least one opening
    starts = np.sort(rng.uniform(t0, t[-1], n))
    return {"open": np.c_[starts, starts + rng.uniform(5.0, 20.0, n) * 60], "dT_K": rng.uniform(5.0, 12.0),
            "tau_air_s": rng.uniform(2.0, 5.0) * 60, "tau_link_s": rng.uniform(*DOOR_TAU_MIN[ctx.chain.name]) * 60,
            "cte": hw["material"]["cte"]}


def door_signal(p, ctx):
    """(P,): the links' temperature per the air's fall while open (<= 0): the openings through the hall's mixing and
    the links' lag, on a 10 s grid from 30 min before the session."""
    t = ctx.session.time_s
    grid = np.arange(t[0] - 1800.0, t[-1] + GRID_S, GRID_S)
    mid = grid + GRID_S / 2
    u = -np.any((mid[:, None] >= p["open"][:, 0]) & (mid[:, None] < p["open"][:, 1]), axis=1).astype(float)
    air = ph.first_order_zoh(grid, u, p["tau_air_s"])
    link = ph.first_order_zoh(grid, air, p["tau_link_s"])
    return np.interp(t, grid, link)


def door_shape(p, ctx):
    every = np.ones(len(ctx.chain.links), bool)
    return p["cte"] * door_signal(p, ctx)[:, None] * ctx.link_scale_feature(every)


def door_apply(p, ctx, hw):
    return Contribution(displace=p["dT_K"] * door_shape(p, ctx))


def door_features(p, ctx, hw):
    return door_shape(p, ctx)[None]
