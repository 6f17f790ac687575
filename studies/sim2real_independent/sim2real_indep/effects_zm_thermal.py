"""Set ZM thermal effects (new physics, not in sets A-ZL): an arm whose links settle at the operative temperature of
the drifting hall air and of the slowly following walls and roof they radiate to; and an arm inside a conditioned
enclosure whose door is opened at each part change. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* radiant exchange with the envelope (``mean_radiant``): a body exchanging heat by convection (h_c 2-5 W/m^2 K in
  still air) and by long-wave radiation (h_r = 4 eps sigma T^3, 3.5-5.5 W/m^2 K for eps 0.6-0.9) with surroundings at
  the mean radiant temperature settles at the operative temperature (h_c T_air + h_r T_mr) / (h_c + h_r) (ISO 7726:
  1998; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 1 and 13). A hall's walls, floor and roof
  follow its air by hours (heavy envelopes: tau_w 2-5 h, assumed), so while the air drifts by 3-8 K over a working
  morning (its logged sensor reads it) the links lag behind it by more than their own time constant (tau_l 15-40 min):
  they follow (1 - s) T_air + s T_wall, s = h_r / (h_c + h_r) 0.4-0.7. All links grow together (the arm's CTE);
  blocks with pauses of 30-90 min spread the session over hours. Unlike set A's ambient kind (the links following the
  air), set C's two-node drives or set V's restrained bar, the links follow the air only partly, the rest through the
  envelope's slow radiant temperature. kr16_like (ZM22; first on tool_changer, ZM14: its steel boom grew 0.065 mm,
  10 %, the mount model at 1.12x; on ur10 in a trial, ZM06: 0.075 mm, absorbed). Driven by the air (logged) and the
  time. The true structure: one column (the links' stretch times their temperature), amplitude the CTE.
* enclosure door (``enclosure_door``): a robot cell held at a set point 4-10 K from the hall (a cooled metrology or
  clean cell, or a heated one; the logged sensor hangs in the hall); at each part change the door stays open for the
  loading of a fixture or pallet (5-15 min) and the cell's air relaxes towards the hall's (tau_o 2-5 min, the door's
  air exchange: ASHRAE Handbook -- Fundamentals, ch. 16, infiltration through open doors), then back to the set point
  by the cell's conditioning (tau_c 5-15 min); the links follow the cell's air (tau_l 10-30 min, lumped: Incropera &
  DeWitt, ch. 5). 4-7 blocks, a new part in each (first 3-8 min loadings and 3-8 K: ur10's ZM06 gained 21.7 %, the
  joint model at 1.27x, the links catching little of the short pulses; tool_changer's steel arm 16.7 %, the mount model
  at 1.18x). Unlike set Q's hall door (a draught from the hall's own door at random times), set ZD's paint booth or set
  W's cooling part, the pulses are the enclosure's air exchanges at the loadings. ur10. Driven by the loadings (the
  logged payload's changes and the pauses); the cell's temperature is not logged. The true structure: one column (the
  links' stretch times the node), amplitude CTE dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

DT_S = 10.0  # the integration step [s]


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _lag(u, tau_s, x0):
    """(T,) a first-order lag of u (T,) sampled every DT_S (exact for u held over each step)."""
    a = np.exp(-DT_S / tau_s)
    out, x = np.empty(len(u)), x0
    for k, v in enumerate(u):
        x = v + (x - v) * a
        out[k] = x
    return out


def _grid(session):
    t = session.time_s
    return np.arange(t[0] - 3600.0, t[-1] + DT_S, DT_S)


def _stretch(ctx):
    return ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))


# ---------------------------------------------------------------------------------------------------- radiant envelope
def link_temperature(p, session):
    """(P,) the links' temperature [K above the air's at the start]: the operative temperature of the air and of the
    walls (the air lagged by tau_w), lagged by tau_l; everything settled an hour before the first pose."""
    tg = _grid(session)
    T0 = air_temperature(session, session.time_s[0])
    air = air_temperature(session, np.maximum(tg, session.time_s[0])) - T0
    wall = _lag(air, p["tau_w"], 0.0)
    link = _lag((1 - p["s"]) * air + p["s"] * wall, p["tau_l"], 0.0)
    return np.interp(session.time_s, tg, link)


def radiant_draw(ctx, hw, rng):
    return {"tau_w": 3600 * float(rng.uniform(2.0, 5.0)), "tau_l": 60 * float(rng.uniform(15.0, 40.0)),
            "s": float(rng.uniform(0.4, 0.7)), "cte": float(hw["material"]["cte"])}


def radiant_features(p, ctx, hw):
    return (_stretch(ctx) * link_temperature(p, ctx.session)[:, None])[None]


def radiant_apply(p, ctx, hw):
    return _amp_apply([p["cte"]], radiant_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- enclosure door
def door_open(session, tg):
    """(T,) True while the door is open: during each pause before a block (the loading)."""
    t, g = session.time_s, session.gap_s
    out = np.zeros(len(tg), bool)
    for k in np.flatnonzero(g < 0):
        out |= (tg >= t[k - 1]) & (tg < t[k - 1] - g[k])
    return out


def door_node(p, session):
    """(P,) the links' share of the cell-to-hall difference: the cell's air relaxing to the hall's while the door is
    open (tau_o) and back (tau_c), the links following it (tau_l)."""
    tg = _grid(session)
    op = door_open(session, tg)
    x, cell = 0.0, np.empty(len(tg))
    ao, ac = np.exp(-DT_S / p["tau_o"]), np.exp(-DT_S / p["tau_c"])
    for k, o in enumerate(op):
        x = 1.0 + (x - 1.0) * ao if o else x * ac
        cell[k] = x
    return np.interp(session.time_s, tg, _lag(cell, p["tau_l"], 0.0))


def door_draw(ctx, hw, rng):
    p = {"tau_o": 60 * float(rng.uniform(2.0, 5.0)), "tau_c": 60 * float(rng.uniform(5.0, 15.0)),
         "tau_l": 60 * float(rng.uniform(10.0, 30.0))}
    p["amp"] = float(hw["material"]["cte"] * rng.choice([-1.0, 1.0]) * rng.uniform(4.0, 10.0))
    return p


def door_features(p, ctx, hw):
    return (_stretch(ctx) * door_node(p, ctx.session)[:, None])[None]


def door_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], door_features(p, ctx, hw))
