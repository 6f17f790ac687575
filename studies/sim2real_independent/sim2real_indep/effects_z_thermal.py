"""Set Z thermal effects (new physics, not in sets A-Y): the arm's steel base plate curled by the underfloor heating
loop running beneath one edge of it, cooling after the heating was switched off for the shift; and the upper arm bowed
as the hall's air drifts because a cable duct bolted along one side of it insulates that side, which follows the air
more slowly than the bare side. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* floor heating: a hall heated through its floor (hydronic pipes in the screed); the loop is switched off at the shift's
  start, and the base plate (a steel plate 30-50 mm thick, 500-800 mm wide) lies with one edge over a pipe run: that
  edge's underside is warmer by dT_0 = 2-5 K, decaying as the screed cools with tau 1.5-4 h (a first-order cooling of
  the screed; Incropera & DeWitt, ch. 5; the time constants of heated screeds, EN 1264 design practice, as recalled). A
  gradient across a plate's thickness t curls it to the curvature alpha dT / t (thermal bowing; Timoshenko & Goodier,
  *Theory of Elasticity*, thermal stress in plates), which over the half-width w / 2 turns the base by alpha dT w / (2
  t) about the horizontal axis along the pipe run (drawn). The session: blocks with pauses of 30-80 min (a morning).
  Unlike set V's slab curl (the floor slab between the arm and the tracker curling with the air) or set Y's cabinet
  exhaust (a pedestal bowed by an exhaust), the base plate curls over a heat source decaying after its switch-off.
  Driven by the time (the ``time_s`` column); the screed's temperature is not logged. The true structure: one column
  (the turn per unit rotation times exp(-t / tau)), amplitude the turn at the session's start [rad].
* duct lag: a cable duct (a steel trunking with its cables) bolted along one side of the upper arm insulates that side
  from the air, so it follows the hall's air with a lag tau_s of 90-240 min while the bare side follows with tau_f of
  5-15 min (lumped, first-order nodes; Incropera & DeWitt, ch. 5); as the air drifts the difference between the two
  lags is a gradient across the tube of depth D that bows it to alpha dT / D away from the warm side (thermal bowing,
  as above), and their mean lengthens it. The share of the gradient that reaches the wall under the duct is 0.5-0.9
  (assumed). The session: a working morning in a hall that warms or cools by 8-14 K, with pauses. Unlike set C's two
  nodes (the links at two lags, lengthening) or set Y's vision lamp (a bow by a heat source), the air drives the bow
  through the two sides' different lags. Driven by the air temperature (the ``temperature_c`` column). The true
  structure: two columns (the link's growth times the mean of the two lagged temperatures less 20 degC, and its bow per
  unit curvature times their difference), amplitudes alpha and alpha share / D.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_y_thermal import STEEL_CTE, lamp_side, link_bow, upper_arm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# -------------------------------------------------------------------------------------------------- floor heating
def floor_decay(p, session):
    """(P,) exp(-t / tau), t from the session's first pose."""
    return np.exp(-(session.time_s - session.time_s[0]) / p["tau_s"])


def floor_draw(ctx, hw, rng):
    dT, t, w = rng.uniform(2.0, 5.0), rng.uniform(30.0, 50.0), rng.uniform(500.0, 800.0)
    return {"dT0": dT, "t_mm": t, "w_mm": w, "psi": rng.uniform(0, 2 * np.pi), "h_mm": rng.uniform(0.0, 50.0),
            "tau_s": 3600.0 * rng.uniform(1.5, 4.0), "turn": STEEL_CTE * dT * w / (2 * t)}


def floor_features(p, ctx, hw):
    a = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    rot = np.cross(a, ctx.target - np.array([0.0, 0.0, -p["h_mm"]]))
    return (rot * floor_decay(p, ctx.session)[:, None])[None]


def floor_apply(p, ctx, hw):
    return _amp_apply([p["turn"]], floor_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------------ duct lag
DUCT_D_MM = {"ur10": (85.0, 110.0), "kr16_like": (150.0, 220.0), "tool_changer": (200.0, 300.0)}


def duct_temperatures(p, session):
    """(2, P) the bare side's and the duct side's temperatures [degC] (the logged air through two lags)."""
    t, T = session.time_s, session.air_c
    return np.array([ph.first_order_foh(t, T, p["tau_f_s"]), ph.first_order_foh(t, T, p["tau_s_s"])])


def duct_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    D, share = rng.uniform(*DUCT_D_MM[ctx.chain.name]), rng.uniform(0.5, 0.9)
    return {"tau_f_s": 60.0 * rng.uniform(5.0, 15.0), "tau_s_s": 60.0 * rng.uniform(90.0, 240.0), "D_mm": D,
            "share": share, "psi": rng.uniform(0, 2 * np.pi), "amp": np.array([cte, cte * share / D])}


def duct_features(p, ctx, hw):
    li = upper_arm(ctx.chain)
    Tf, Ts = duct_temperatures(p, ctx.session)
    grow = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li)
    bow = link_bow(ctx, li, lamp_side(ctx.chain, li, p["psi"]))   # bowed away from the bare (warmer) side
    return np.array([grow * (0.5 * (Tf + Ts) - 20.0)[:, None], bow * (Tf - Ts)[:, None]])


def duct_apply(p, ctx, hw):
    return _amp_apply(p["amp"], duct_features(p, ctx, hw))
