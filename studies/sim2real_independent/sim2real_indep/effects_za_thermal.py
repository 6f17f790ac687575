"""Set ZA thermal effects (new physics, not in sets A-Z): the upper arm bowed by the cold jet of a split air
conditioner whose compressor cycles on and off under its thermostat; and the forearm heated from one side by the hot
air let out each time a curing oven's door opens for a load. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* AC jet: a wall-mounted split unit's outlet blows its supply air, 8-12 K below the room, across the cell; the jet's
  core reaches the upper arm's one side 3-7 K colder than the hall (jet decay: Rajaratnam, *Turbulent Jets*, 1976, as
  recalled), only while the compressor runs: a fixed-speed unit cycles on and off under its thermostat's dead band,
  periods 10-25 min, on 30-60 % of the time (ASHRAE Handbook -- HVAC Systems and Equipment, cycling of unitary
  equipment, as recalled). The wall under the jet follows it through a first-order lag of 2-6 min (forced convection on
  a thin aluminium or cast wall; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5), the far side
  stays at the hall's air: the difference bows the tube by alpha share dT / D (thermal bowing: Timoshenko & Goodier,
  thermal stress), share 0.5-0.9 of it across the tube, and the mean shortens it by alpha dT / 2. Unlike set Y's vision
  lamp (a heater at the clamp lit with inspection) or set E's fan thermostat (the convection coefficient switching), a
  cold jet on one side cycles with the compressor; the logged air hardly moves. Driven by the compressor's cycle (not
  logged). The true structure: two columns (the link's growth times dT_j / 2 and its bow per unit curvature times dT_j),
  amplitudes alpha and alpha share / D.
* oven door: a curing oven (150-200 degC) opens its door beside the forearm's working area for 40-90 s every 8-15 min to
  change a load; the hot air that rolls out over the lintel (door-opening heat losses: ASHRAE Handbook -- Refrigeration,
  infiltration through doorways, as recalled) passes under the forearm, whose underside takes a heat pulse of 4-8 K rise
  per opening (a wall lag of 3-10 min through the pulse; first 2-5 K: gains of 24-28 %), relaxing with the same lag
  between openings, so the pulses ride on a rising, saw-toothed mean. The gradient bows the forearm by alpha share dT /
  D (share 0.5-0.9) and its mean grows it by alpha dT / 2. Unlike set Y's cabinet exhaust (a steady exhaust on the
  pedestal) or set M's hot plume (the tracker's beam), pulses from a door heat the forearm. Driven by the oven's door
  (not logged). The true structure: two columns, amplitudes alpha and alpha share / D.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_y_thermal import lamp_side, link_bow, upper_arm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def forearm(chain):
    """Index of the forearm: the longest link past joint 3 and before the wrist's bend (body 3 or 4: on kr16_like the
    forearm's tube follows its roll axis 4)."""
    body = np.asarray(chain.link_body)
    return int(np.argmax(np.linalg.norm(chain.links, axis=1) * np.isin(body, (3, 4))))


def lagged_source(t_s, on, tau_s, step_s=5.0):
    """(P,) a unit source switched by ``on(t)`` (t from the session's start [s]) through a first-order lag, sampled
    at ``t_s``; the wall at the hall's temperature at the start."""
    t = np.asarray(t_s, float) - t_s[0]
    grid = np.arange(0.0, t[-1] + 2 * step_s, step_s)
    u = on(grid).astype(float)
    x = np.zeros_like(grid)
    a = np.exp(-step_s / tau_s)
    for k in range(1, len(grid)):
        x[k] = a * x[k - 1] + (1 - a) * u[k - 1]
    return np.interp(t, grid, x)


def _bow_features(ctx, li, psi, dT):
    grow = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li)
    bow = link_bow(ctx, li, lamp_side(ctx.chain, li, psi))
    return np.array([grow * (0.5 * dT)[:, None], bow * dT[:, None]])


# --------------------------------------------------------------------------------------------------------- AC jet
JET_D_MM = {"ur10": (85.0, 110.0), "kr16_like": (150.0, 220.0), "tool_changer": (200.0, 300.0)}


def jet_temperature(p, session):
    """(P,) the jet side's temperature less the hall's [K] (negative)."""
    def on(t):
        return ((t / 60.0 + p["phase_min"]) % p["period_min"]) < p["duty"] * p["period_min"]
    return -p["dT_K"] * lagged_source(session.time_s, on, p["tau_s"])


def jet_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    D, share, period = rng.uniform(*JET_D_MM[ctx.chain.name]), rng.uniform(0.5, 0.9), rng.uniform(10.0, 25.0)
    return {"dT_K": rng.uniform(3.0, 7.0), "period_min": period, "duty": rng.uniform(0.3, 0.6),
            "phase_min": rng.uniform(0.0, period), "tau_s": 60.0 * rng.uniform(2.0, 6.0), "D_mm": D, "share": share,
            "psi": rng.uniform(0, 2 * np.pi), "amp": np.array([cte, cte * share / D])}


def jet_features(p, ctx, hw):
    return _bow_features(ctx, upper_arm(ctx.chain), p["psi"], jet_temperature(p, ctx.session))


def jet_apply(p, ctx, hw):
    return _amp_apply(p["amp"], jet_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------------- oven door
DOOR_D_MM = {"ur10": (75.0, 95.0), "kr16_like": (110.0, 160.0), "tool_changer": (150.0, 250.0)}


def door_temperature(p, session):
    """(P,) the forearm's underside less the hall's [K]: pulses of the open door through the wall's lag."""
    def on(t):
        return ((t / 60.0 + p["phase_min"]) % p["period_min"]) < p["open_s"] / 60.0
    a = p["tau_s"] / p["open_s"]                          # a pulse of length open_s raises the wall by about rise_K
    return p["rise_K"] * a * lagged_source(session.time_s, on, p["tau_s"])


def door_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    D, share, period = rng.uniform(*DOOR_D_MM[ctx.chain.name]), rng.uniform(0.5, 0.9), rng.uniform(8.0, 15.0)
    return {"rise_K": rng.uniform(4.0, 8.0), "period_min": period, "open_s": rng.uniform(40.0, 90.0),
            "phase_min": rng.uniform(0.0, period), "tau_s": 60.0 * rng.uniform(3.0, 10.0), "D_mm": D,
            "share": share, "psi": rng.uniform(0, 2 * np.pi), "amp": np.array([cte, cte * share / D])}


def door_features(p, ctx, hw):
    return _bow_features(ctx, forearm(ctx.chain), p["psi"], door_temperature(p, ctx.session))


def door_apply(p, ctx, hw):
    return _amp_apply(p["amp"], door_features(p, ctx, hw))
