"""Set ZO thermal effects (new physics, not in sets A-ZN): tool_changer's telescopic stage read by an ultrasonic
time-of-flight sensor whose speed-of-sound compensation lags the air; and a dry-ice blasting nozzle on the tool whose
bracket the sublimating pellets chill in the production between the blocks. Same protocol as :mod:`effects_joint`.

Sources:

* ultrasonic stroke sensor (``ultrasonic_ram``): tool_changer's telescopic stage read by an ultrasonic time-of-flight
  sensor on the outer section aimed at a reflector on the inner one, at a standoff D0 100-300 mm plus the stroke. Sound
  travels at c = 331.3 sqrt(1 + T / 273.15) m/s in air (Kinsler, Frey, Coppens & Sanders, *Fundamentals of Acoustics*,
  4th ed., 2000, ch. 5), 0.17 %/K near 20 degC; the sensor compensates with a thermistor inside its housing, which
  follows the air through the housing's lag tau 10-30 min (ultrasonic sensors' temperature compensation: makers'
  notes, e.g. Pepperl+Fuchs / Microsonic, as recalled; lumped capacitance: Incropera & DeWitt, ch. 5). The controller
  drives the reading to the target, so the stroke errs by (D0 + s) (T_air - T_sensor) / (2 T_K). A hall whose air
  drifts by 2-5 K over the session and cycles by 0.3-1 K over 40-120 min (logged); blocks with pauses of 20-60 min.
  Unlike set C's refraction or tracker scale (the tracker's beam), set T's rangefinder (a laser's cyclic errors) or set
  ZN's magnetostrictive rod, the stage's reading follows the speed of sound and its compensation's lag. Scored as
  thermal (a reading that follows the air, as set C's tracker scale). Driven by the logged air temperature and the
  stroke. The true structure: two columns (the standoff's and the stroke's), amplitudes D0 / (2 T_K) and 1 / (2 T_K).
* dry-ice nozzle (``dry_ice_nozzle``): a dry-ice blasting nozzle (CO2 pellets at -78.5 degC, sublimating on impact
  and in the nozzle, carried by expanding compressed air: Spur, Uhlmann & Elbing, "Dry-ice blasting for cleaning:
  process, optimization and application", Wear 233-235, 1999; makers' notes on nozzle icing, e.g. Cold Jet, as
  recalled) on an aluminium lance bracket 600 mm along the tool's z (the target at the nozzle; lances reach into the
  moulds) cleans moulds in the production between the blocks, at a duty of 50-90 %; the chilled nozzle cools the
  bracket 25-45 K below the air while blasting, and it warms back in still air during the measurement (lumped node,
  tau 5-15 min: Incropera & DeWitt, ch. 5), shortening it by alpha dT L (alpha 23e-6 /K). Production of 10-30 min
  between 4-6 blocks. Unlike set ZB's sonotrode or set D's process tool (heated in production), set Q's ejector chill
  (the vacuum's exhaust while a part is held) or set ZF's marking pulses, the bracket is chilled by subliming dry ice
  in the production and recovers while measured. Driven by the production between the blocks (the time stamps show the
  gaps; nothing of it is logged). The true structure: one column, amplitude alpha dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_zi_body import tool_frame
from sim2real_indep.effects_zm_thermal import _grid, _lag
from sim2real_indep.session import air_temperature

RAM_J = 3  # tool_changer's telescopic stage
NOZZLE_MM = 600.0
ALU_CTE = 23e-6


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- ultrasonic sensor
def sensor_lag(p, session):
    """(P,) the air's temperature less the sensor's thermistor's [K]: the air lagged by tau (settled an hour before)."""
    tg = _grid(session)
    air = air_temperature(session, np.maximum(tg, session.time_s[0]))
    lagged = _lag(air - air[0], p["tau"], 0.0) + air[0]
    return np.interp(session.time_s, tg, air - lagged)


def ultra_features(p, ctx, hw):
    """(2, P, 3): the stage's error per unit D0 / (2 T_K) [mm / K ...] and per unit 1 / (2 T_K) times the stroke."""
    u = sensor_lag(p, ctx.session)
    s = ctx.q[:, RAM_J]
    return np.array([ctx.joint_feature(RAM_J, u), ctx.joint_feature(RAM_J, s * u)])


def ultra_draw(ctx, hw, rng):
    T_K = 273.15 + float(ctx.session.air["T0"])
    p = {"tau": 60 * float(rng.uniform(10.0, 30.0)), "D0_mm": float(rng.uniform(100.0, 300.0))}
    p["amp"] = [p["D0_mm"] / (2 * T_K), 1 / (2 * T_K)]
    return p


def ultra_apply(p, ctx, hw):
    return _amp_apply(p["amp"], ultra_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dry-ice nozzle
def blasting(session, tg, duty):
    """(T,) the nozzle's duty on the grid: ``duty`` in the production before each block, 0 elsewhere."""
    s = session
    u = np.zeros(len(tg))
    start_move = s.time_s - s.dwell_s - s.move_s
    for i in np.flatnonzero(s.gap_s > 0):
        u[(tg >= start_move[i] - s.gap_s[i]) & (tg < start_move[i])] = duty
    return u


def ice_node(p, session):
    """(P,) the bracket's chill per unit dT (0 at the air, 1 fully chilled)."""
    tg = _grid(session)
    return np.interp(session.time_s, tg, _lag(blasting(session, tg, p["duty"]), p["tau"], 0.0))


def ice_features(p, ctx, hw):
    """(1, P, 3) per unit alpha dT: the bracket's shortening along the tool's z (the target moves towards the
    flange)."""
    return (-NOZZLE_MM * tool_frame(ctx)[:, :, 2] * ice_node(p, ctx.session)[:, None])[None]


def ice_draw(ctx, hw, rng):
    p = {"duty": float(rng.uniform(0.5, 0.9)), "tau": 60 * float(rng.uniform(5.0, 15.0)),
         "dT": float(rng.uniform(25.0, 45.0))}
    p["amp"] = ALU_CTE * p["dT"]
    return p


def ice_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], ice_features(p, ctx, hw))
