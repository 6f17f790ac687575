"""Set ZG thermal effects (new physics, not in sets A-ZF): an arm still wet from a wash or a coolant mist, held below
the air by the evaporation of its film until the film dries; and a tool bracket warmed by the seals of the rotary union
that axis 6 turns. Same protocol as :mod:`effects_joint`.

Sources:

* drying film: a wet surface evaporating into the air sits near the wet-bulb temperature, 2-6 K below the dry air at
  the shop's humidity (psychrometry: ASHRAE *Handbook -- Fundamentals*, 2017, ch. 1); as the film thins the wetted
  share falls, linearly to zero at the drying time t_d (the constant-rate period of drying: Mujumdar, *Handbook of
  Industrial Drying*, 4th ed., 2014, ch. 1), 0.4-0.9 of the session; the links follow the surface with a first-order
  lag of 10-30 min, all links by one aluminium CTE. Unlike set X's washdown (a hot rinse cooling off) or set Q's
  draught (a cold air stream), the links start *below* the air and recover as the film dries, the logged air
  unchanged. Driven by time (logged); the film is not. The true structure: one column, amplitude CTE dT_wb.
* rotary union: a tool bracket (aluminium, 450 mm, carrying the target) holds a rotary union that feeds the tool's
  air and coolant through axis 6; its lip seals rub on the rotating shaft and turn their friction torque into heat
  in proportion to the angle turned (seal friction heating: Flitney, *Seals and Sealing Handbook*, 6th ed., 2014,
  ch. 3, rotary lip seals' power loss = friction torque x speed, so the heat per move = torque x |dq6|); the bracket
  takes each move's heat and loses it to the air with a time constant tau 5-15 min (lumped capacitance): T_k =
  (T_{k-1} + |dq6_k|) exp(-(t_k - t_{k-1}) / tau), normalised to its peak dT 10-25 K. Unlike set ZF's marking pulses
  (heat at each dwell), set D's tool heat or sets A-ZF's drive losses (heat from the drives' currents), the heat
  follows axis 6's travel alone. Driven by axis 6's motion and time (logged); the seals are not. The true structure:
  one column, amplitude CTE dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

BRACKET_MM = 450.0
CTE = 23e-6


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- drying film
def film_temperature(p, t_s):
    """(P,) the links' temperature below the air per unit wet-bulb depression (negative while wet)."""
    t = np.asarray(t_s, float) - t_s[0]
    wet = -np.maximum(1.0 - t / p["t_dry_s"], 0.0)
    return ph.first_order_zoh(t, wet, p["tau_s"], x0=-1.0)


def film_draw(ctx, hw, rng):
    t = ctx.session.time_s
    dT = rng.uniform(2.0, 6.0)
    return {"t_dry_s": (t[-1] - t[0]) * rng.uniform(0.4, 0.9), "tau_s": 60.0 * rng.uniform(10.0, 30.0),
            "dT_K": dT, "amp": CTE * dT}


def film_features(p, ctx, hw):
    uniform = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))
    return (uniform * film_temperature(p, ctx.session.time_s)[:, None])[None]


def film_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], film_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- rotary union
def union_temperature(p, q6, time_s):
    """(P,) the bracket's rise per unit peak: each move's heat (|dq6|) decayed to each pose, over its max."""
    t = np.asarray(time_s, float)
    heat = np.abs(np.diff(np.asarray(q6, float), prepend=q6[0]))
    T = np.zeros(len(t))
    for k in range(1, len(t)):
        T[k] = (T[k - 1] + heat[k]) * np.exp(-(t[k] - t[k - 1]) / p["tau_s"])
    return T / max(T.max(), 1e-12)


def union_draw(ctx, hw, rng):
    dT = rng.uniform(10.0, 25.0)
    return {"tau_s": 60.0 * rng.uniform(5.0, 15.0), "dT_K": dT, "amp": CTE * dT}


def union_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    T = union_temperature(p, ctx.q[:, ctx.chain.n - 1], ctx.session.time_s)
    return (Rt[:, :, 2] * (BRACKET_MM * T)[:, None])[None]


def union_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], union_features(p, ctx, hw))
