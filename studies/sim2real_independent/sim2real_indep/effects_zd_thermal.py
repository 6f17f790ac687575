"""Set ZD thermal effects (new physics, not in sets A-ZC): the arm inside a paint booth whose air is switched between
spraying and a warm flash-off by block while the logged air is the hall's outside it; and a hot-melt gun on the tool,
switched on at the session's start, warming its mounting bracket through the gun's own warm-up (two nodes in series).
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* bake booth: spray booths run a flash-off (or low-bake) phase between coats with the booth's air heated 15-30 K over
  the spraying air (first 10-20 K: ZD22 on kr16_like gained 14 %, its thick walls lagging) (paint-shop practice: flash-off at 30-45 degC; Goldschmidt & Streitberger, *BASF Handbook on
  Basics of Coating Technology*, 2007, ch. 7); the tracker stands outside the booth's window and logs the hall's air.
  Each block is run in one of the two modes (unlogged, both present), the pauses between blocks 5-15 min (first 3-10), the booth's
  air switching at the pause's start; the links follow through their wall's lag rho c t / h (Incropera & DeWitt, ch.
  5: 8-20 min for ur10's thin tubes, 15-40 min for the heavier arms) and grow uniformly by alpha dT. Unlike the hall's
  drifts of sets A-ZC (logged) or set Q's door draught (a Poisson opening), the air the arm sits in follows a booth
  schedule set by block and nobody logs it. Driven by the time (logged) and the booth's mode (not logged). The true
  structure: one column (every link's growth times the lagged schedule), amplitude alpha dT_booth.
* gun warm-up: a hot-melt gun (set point 150-180 degC) clamped to an aluminium bracket that carries the nozzle and the
  target 350 mm along the tool's z is switched on at the session's start; the gun's body heats with its own time
  constant tau_g 3-6 min and the bracket, fed through the clamp, follows with tau_b 10-20 min, a rise of 25-45 K (two
  first-order nodes in series: dT (1 - (tau_b exp(-t / tau_b) - tau_g exp(-t / tau_g)) / (tau_b - tau_g)); Incropera &
  DeWitt, ch. 5, lumped capacitances), 0-3 min before the first pose. The bracket grows by alpha L dT along the tool's z.
  Unlike the single-lag tool heating of sets D-ZC, the bracket's growth starts with zero slope (an S-curve: the gun
  warms first). Driven by the time (logged) and the switch-on time (not logged). The true structure: one column,
  amplitude alpha dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_za_thermal import lagged_source


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- bake booth
BOOTH_TAU_MIN = {"ur10": (8.0, 20.0), "kr16_like": (15.0, 40.0), "tool_changer": (15.0, 40.0)}


def booth_schedule(p, session):
    """A function of the time from the session's start [s]: 1 while the booth runs its flash-off, else 0 (the mode
    switched at the start of the pause before each block)."""
    b = block_index(session)
    t = session.time_s - session.time_s[0]
    nb = len(p["warm"])
    starts = np.array([0.0] + [t[np.argmax(b == k)] - abs(session.gap_s[np.argmax(b == k)])
                               for k in range(1, nb)])
    warm = np.asarray(p["warm"], float)

    def on(tt):
        k = np.clip(np.searchsorted(starts, tt, side="right") - 1, 0, nb - 1)
        return warm[k]
    return on


def booth_temperature(p, session):
    """(P,) the links' rise over the hall at unit booth rise."""
    return lagged_source(session.time_s, booth_schedule(p, session), p["tau_s"])


def booth_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    warm = rng.random(nb) < 0.5
    if nb > 1 and (warm.all() or not warm.any()):
        warm[int(rng.integers(nb))] = not warm[0]
    dT = rng.uniform(15.0, 30.0)
    return {"warm": warm.astype(int), "tau_s": 60.0 * rng.uniform(*BOOTH_TAU_MIN[ctx.chain.name]), "dT_K": dT,
            "cte": hw["material"]["cte"], "amp": hw["material"]["cte"] * dT}


def booth_features(p, ctx, hw):
    grow = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))
    return (grow * booth_temperature(p, ctx.session)[:, None])[None]


def booth_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], booth_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- gun warm-up
GUN_MM = 350.0
GUN_CTE = 23e-6


def gun_temperature(p, session):
    """(P,) the bracket's rise at unit dT: two first-order nodes in series from the switch-on."""
    t = session.time_s - session.time_s[0] + p["lead_s"]
    tg, tb = p["tau_g_s"], p["tau_b_s"]
    return 1.0 - (tb * np.exp(-t / tb) - tg * np.exp(-t / tg)) / (tb - tg)


def gun_draw(ctx, hw, rng):
    return {"lead_s": 60.0 * rng.uniform(0.0, 3.0), "tau_g_s": 60.0 * rng.uniform(3.0, 6.0),
            "tau_b_s": 60.0 * rng.uniform(10.0, 20.0), "dT_K": rng.uniform(25.0, 45.0), "cte": GUN_CTE}


def gun_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (Rt[:, :, 2] * (GUN_MM * p["dT_K"] * gun_temperature(p, ctx.session))[:, None])[None]


def gun_apply(p, ctx, hw):
    return _amp_apply([p["cte"]], gun_features(p, ctx, hw))
