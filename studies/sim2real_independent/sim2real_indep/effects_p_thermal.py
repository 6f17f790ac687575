"""Set P thermal effects (new physics, not in sets A-O): the arm in a foundry's protective jacket, cooled by a vortex
cooler that a thermostat switches on and off, so that the jacket's air cycles through its switching band and the links
follow it; and a mobile robot's (AMR's) deck bowed by its battery's heat while it charges in the pauses, tilting the
arm's base. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* jacket cycle: robots in foundries and die-casting cells wear heat-protective jackets, some cooled by compressed-air
  vortex coolers whose thermostat switches the air on and off (makers' notes on jacket and cabinet coolers, as
  recalled: a switching band of several kelvin). An on-off (relay) loop settles into a limit cycle (Astrom & Murray,
  *Feedback Systems*, 2008, ch. 9 on relay feedback): the jacket's air falls while the cooler runs and rises while it
  is off, a sawtooth between the band's edges, here of half-width 5-10 K (first 4-8 K: 0.05 mm on ur10) with cooling
  runs of 6-15 min and pauses of
  8-20 min (assumed); the thin aluminium tubes follow through a lumped lag of 2-6 min (rho c t / h with walls of 3-5
  mm under the jacket's air flow; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5). The hall's air,
  which the frame logs, stays still. Links of 150 mm or more, ur10 and kr16_like (aluminium). The true structure: one
  column (the cycle and the lag its shape), amplitude the links' expansion coefficient.
* charging heat: an AMR charges in the pauses between its runs (opportunity charging); the pack's losses, I^2 R of
  some 100-300 W, warm the deck plate above it from below, and a plate with a temperature difference dT across its
  thickness t curls to a curvature alpha dT / t (Timoshenko & Goodier, *Theory of Elasticity*, ch. 14, thermal
  bending of plates); the arm's base, 50-150 mm off the bow's crest, tilts by alpha dT s / t. dT 1.5-4 K at the full
  charging heat (first 1-3 K: kr16_like's case gained 29 %), 15-30 % of it while driving and working, through a lag of
  6-15 min; aluminium decks of 12-20 mm, the
  tilt about a horizontal axis through the deck 80-200 mm below the base (assumed); a charge of 10-30 min before the
  first block, pauses of 10-25 min between 3-5 blocks. ur10 and kr16_like. The true structure: one column (the lag and
  the schedule its shape), amplitude the tilt at the full difference.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])
ALU_CTE = 23e-6


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# -------------------------------------------------------------------------------------------------- jacket cycle
JACKET_ARMS = {"ur10", "kr16_like"}
JACKET_MIN_MM = 150.0


def jacket_draw(ctx, hw, rng):
    if ctx.chain.name not in JACKET_ARMS:
        return {}
    length = np.linalg.norm(ctx.chain.links, axis=1)
    return {"links": [int(i) for i in np.flatnonzero(length >= JACKET_MIN_MM)], "A_K": rng.uniform(5.0, 10.0),
            "t_on_s": rng.uniform(6.0, 15.0) * 60, "t_off_s": rng.uniform(8.0, 20.0) * 60,
            "phase": rng.uniform(0, 1), "tau_s": rng.uniform(2.0, 6.0) * 60}


def jacket_air(p, t_s):
    """The jacket air's deviation [K] from the band's middle at times t_s: down from +A to -A while the cooler runs,
    back up while it is off."""
    period = p["t_on_s"] + p["t_off_s"]
    x = np.mod(np.asarray(t_s, float) / period + p["phase"], 1.0) * period
    return np.where(x < p["t_on_s"], p["A_K"] * (1 - 2 * x / p["t_on_s"]),
                    p["A_K"] * (-1 + 2 * (x - p["t_on_s"]) / p["t_off_s"]))


def jacket_signal(p, ctx):
    """The links' temperature deviation [K] at the poses: the jacket's air through the lag (exact for its piecewise-
    linear cycle, sampled every 10 s, from three lags before the first pose)."""
    t = ctx.session.time_s
    grid = np.arange(t[0] - 3 * p["tau_s"], t[-1] + 10.0, 10.0)
    x = ph.first_order_foh(grid, jacket_air(p, grid), p["tau_s"])
    return np.interp(t, grid, x)


def jacket_shape(p, ctx):
    mask = np.isin(np.arange(len(ctx.chain.links)), p["links"])
    return ctx.link_scale_feature(mask) * jacket_signal(p, ctx)[:, None]


def jacket_apply(p, ctx, hw):
    return Contribution(displace=ALU_CTE * jacket_shape(p, ctx) if p else None)


def jacket_features(p, ctx, hw):
    return jacket_shape(p, ctx)[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------ charging heat
CHARGE_ARMS = {"ur10", "kr16_like"}


def charge_draw(ctx, hw, rng):
    if ctx.chain.name not in CHARGE_ARMS:
        return {}
    az = rng.uniform(0, 2 * np.pi)
    dT, s, t = rng.uniform(1.5, 4.0), rng.uniform(50.0, 150.0), rng.uniform(12.0, 20.0)
    tau = rng.uniform(6.0, 15.0) * 60
    return {"tilt_rad": ALU_CTE * dT * s / t, "axis": np.array([np.cos(az), np.sin(az), 0.0]),
            "h_mm": rng.uniform(80.0, 200.0), "r_work": rng.uniform(0.15, 0.3), "tau_s": tau,
            "x0": 1 - np.exp(-rng.uniform(10.0, 30.0) * 60 / tau)}


def charge_signal(p, ctx):
    """(P,): the deck's temperature difference per its full value: charging (1) in the pauses, r_work in the blocks,
    the exact first-order lag of the schedule (pause, then move and dwell before each pose)."""
    s = ctx.session
    x, out = p["x0"], np.zeros(len(s.time_s))
    for k in range(len(out)):
        if s.gap_s[k] < 0:
            x = 1.0 + (x - 1.0) * np.exp(s.gap_s[k] / p["tau_s"])
        elif s.gap_s[k] > 0:
            x = p["r_work"] + (x - p["r_work"]) * np.exp(-s.gap_s[k] / p["tau_s"])
        x = p["r_work"] + (x - p["r_work"]) * np.exp(-(s.move_s[k] + s.dwell_s[k]) / p["tau_s"])
        out[k] = x
    return out


def charge_shape(p, ctx):
    return charge_signal(p, ctx)[:, None] * np.cross(p["axis"], ctx.target + p["h_mm"] * Z)


def charge_apply(p, ctx, hw):
    return Contribution(displace=p["tilt_rad"] * charge_shape(p, ctx) if p else None)


def charge_features(p, ctx, hw):
    return charge_shape(p, ctx)[None] if p else _empty(ctx)
