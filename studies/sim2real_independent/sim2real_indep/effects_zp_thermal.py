"""Set ZP thermal effects (new physics, not in sets A-ZO): the forearm warmed by a heated build bed below it, by how
long and how low the arm has worked over it; and an air-motor spindle's bracket following the supply air, whose
temperature a load / unload compressor cycles. Same protocol as :mod:`effects_joint`.

Sources:

* heated bed (``heated_bed``): an arm laying up or printing over a heated bed (60-120 degC, as in robotic additive
  manufacturing and thermoplastic tape placement) whose rising plume and radiation warm the forearm by a heat flux that
  falls with the flange's height above the bed, q ~ 1 / (1 + (z / h0)^2) (a disc's view factor to a point above its
  centre: Howell, *A Catalog of Radiation Heat Transfer Configuration Factors*, B-13; h0 0.2-0.4 m, the bed 0.2-0.5 m
  below the base frame, switched on as the session starts, the arm cold); the forearm follows the exposure of the poses it has held through a first-order lag, tau 2-5
  min (a 3-4 mm aluminium wall in the plume's convection, h 20-30 W/m^2K; lumped capacitance: Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5), and lengthens by
  alpha dT, dT 20-40 K settled at the session's lowest working height. Unlike set O's infrared dryer (a panel at a fixed place), set M's hot plume (the tracker's beam) or set
  ZB's air knife, the heat input follows where the arm has been. Driven by the pose history and the time (the bed's
  temperature is not logged). The true structure: one column (the forearm's strain per unit alpha dT_max).
* compressor-cycled supply air (``air_motor_heat``): an air-motor spindle on the tool idles during the measurement
  (a deburring spindle kept running) on supply air from a load / unload screw compressor whose aftercooler outlet
  temperature rises while it loads and falls while it idles (a 6-15 min cycle at 30-70 % duty; CAGI / Atlas Copco
  *Compressed Air Manual*, 8th ed., 2015, ch. 3, as recalled); the 5-15 l/s through the motor keep its aluminium
  lance (700 mm along the tool's z, the target at the spindle nose; lances reach into castings) following the air
  through a lag of 1-3 min (the air flowing through it), 10-20 K from load to idle. Unlike set R's line pressure (a balancer's force following the compressor's pressure cycle) or
  set Q's ejector chill, the bracket's temperature follows the compressor's cycle. Driven by the compressor's cycle
  (unlogged). The true structure: one column, amplitude alpha dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zi_body import tool_frame
from sim2real_indep.effects_zm_thermal import _grid, _lag

ALU_CTE = 23e-6
SPINDLE_MM = 700.0


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- heated bed
def bed_exposure(p, ctx):
    """(P,) the heat flux at each pose's flange height above the bed, 1 at the session's lowest pose."""
    z, _ = kin.flange(ctx.chain, ctx.q)
    h = np.maximum(z[:, 2] / 1000.0 + p["bed_m"], 0.0)
    e = 1 / (1 + (h / p["h0"]) ** 2)
    return e / e.max()


def bed_node(p, ctx):
    """(P,) the forearm's warming (0 cold, 1 settled at the bed's flux): the exposure of the pose held at each instant
    (none before the bed is switched on with the first pose), lagged by tau."""
    s = ctx.session
    tg = _grid(s)
    e = bed_exposure(p, ctx)
    held = np.where(tg < s.time_s[0] - s.dwell_s[0], 0.0, e[np.clip(np.searchsorted(s.time_s, tg), 0, len(e) - 1)])
    return np.interp(s.time_s, tg, _lag(held, p["tau"], p["x0"]))


def bed_features(p, ctx, hw):
    """(1, P, 3) per unit alpha dT_max: the forearm's links (body 3) stretched by the node."""
    mask = ctx.chain.link_body == 3
    return (ctx.link_scale_feature(mask) * bed_node(p, ctx)[:, None])[None]


def bed_draw(ctx, hw, rng):
    p = {"bed_m": float(rng.uniform(0.2, 0.5)), "h0": float(rng.uniform(0.2, 0.4)),
         "tau": 60 * float(rng.uniform(2.0, 5.0)), "x0": 0.0, "dT": float(rng.uniform(20.0, 40.0))}
    p["amp"] = ALU_CTE * p["dT"]
    return p


def bed_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], bed_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- compressor air
def compressor_cycle(p, tg):
    """(T,) 1 while the compressor loads, 0 while it idles."""
    return (((tg / p["period"]) + p["phase"]) % 1.0 < p["duty"]).astype(float)


def air_node(p, session):
    tg = _grid(session)
    return np.interp(session.time_s, tg, _lag(compressor_cycle(p, tg), p["tau"], p["duty"]))


def air_features(p, ctx, hw):
    """(1, P, 3) per unit alpha dT: the bracket's growth along the tool's z."""
    node = air_node(p, ctx.session)
    return (SPINDLE_MM * tool_frame(ctx)[:, :, 2] * (node - p["duty"])[:, None])[None]


def air_draw(ctx, hw, rng):
    p = {"period": 60 * float(rng.uniform(6.0, 15.0)), "duty": float(rng.uniform(0.3, 0.7)),
         "phase": float(rng.uniform(0.0, 1.0)), "tau": 60 * float(rng.uniform(1.0, 3.0)),
         "dT": float(rng.uniform(10.0, 20.0))}
    p["amp"] = ALU_CTE * p["dT"]
    return p


def air_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], air_features(p, ctx, hw))
