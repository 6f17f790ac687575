"""Set T thermal effects (new physics, not in sets A-S): an arm brought cold into the hall (from an unheated store or a
truck) and measured while it warms, each body and the pedestal through its own lag, faster at first while dew condenses
on the parts below the air's dew point (the latent heat of condensation); and tool_changer's console on the bulkhead of
a tunnel-boring machine, warmed on its upper side by the main drive, bowing back as the main drive cools after the
machine stopped for the cutter change and warms again at each inching of the cutterhead. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* dew warming: a body's lumped temperature (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5)
  follows the air with its time constant, plus, while its surface is below the air's dew point, the latent heat of the
  vapour condensing on it: by the heat and mass transfer analogy the condensation flux adds h (w_air - w_s(T)) h_fg /
  (c_p Le^(2/3)) to the convective h (T_air - T) (Incropera & DeWitt, ch. 6, the Chilton-Colburn analogy; Threlkeld,
  *Thermal Environmental Engineering*, 1970, on wet coils), w_s the saturation humidity ratio by the Magnus formula
  (Alduchov & Eskridge, J. Appl. Meteor. 35(4), 1996). The arm came in 0-15 min before the session 10-25 K colder than
  the hall, whose air (logged) stays near its start (a still shop), at a relative humidity of 40-70 %; link bodies of
  25-60 / 60-150 min (thin tubes with joint housings / cast links), the steel pedestal of :mod:`hardware` 40-90 /
  90-180 min (ur10 / kr16_like; assumed; first 15-40 min on ur10, 8-20 K and an arrival up to 30 min before the
  session: gain 12 % in a trial draw). Unlike set A's heat and ambient kinds, no heat source and no logged air change
  drives it: the arm's own cold start does. The true structure: one column, amplitude the links' expansion
  coefficient (the pedestal's steel in proportion).
* main drive: a shield machine's main drive (motors, gearbox and main bearing behind the bulkhead) runs 20-40 K above
  the shield while boring (as recalled from TBM main-drive cooling data) and cools, once the cutterhead stops, with a
  lumped time constant of 1.5-4 h (Incropera & DeWitt, ch. 5); the crew inches the cutterhead at the start of each pause
  to bring the next cutters to the changing position, a load of 0.5-1.5 times the boring's steady heat for 2-5 min
  that warms it again. The robot's console, a steel box 0.25-0.4 m deep cantilevered 1-2 m from the bulkhead, takes a
  top-bottom difference of 15-35 % of the drive's excess (its top flange nearer the drive's flange) and a mean excess
  of 20-60 % of that difference through its own lag of 20-60 min (two first-order nodes in series). The console bows
  down by alpha dT L^2 / 2d at its tip, turning by alpha dT L / d (Timoshenko & Goodier, *Theory of Elasticity*,
  thermal bending of beams), and grows by alpha dT_mean L along its axis (the tunnel's, +-10 deg off the arm's reach),
  carrying the arm. The session starts 0.3-2 h after the stop (assumed; first a plain cooling curve without the
  inching with 0.6-1.2 m consoles 0.3-0.5 m deep, 15-35 K and a share of 10-25 %: the random-split case absorbed, then
  with 20-40 K and 15-35 % a gain of 20 % with the mount model at 1.26x; the inching, a part of the intervention the
  first version left out, and consoles of 1-2 m made it clean). tool_changer only. The true structure: one column,
  amplitude dT_0 (the drive's excess at the stop).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

Z = np.array([0.0, 0.0, 1.0])


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# --------------------------------------------------------------------------------------------------- dew warming
DEW = {"ur10": ((25.0, 60.0), (40.0, 90.0)), "kr16_like": ((60.0, 150.0), (90.0, 180.0))}
STEP_S = 30.0
GRID_S = 10.0
STEEL_CTE = 11.7e-6
#: h_fg / (c_p Le^(2/3)) [K per kg/kg]: 2.45e6 J/kg over 1006 J/kg K times 0.87
LATENT_K = 2.45e6 / (1006.0 * 0.87)


def saturation_ratio(T_c, p_pa=101325.0):
    """Saturation humidity ratio [kg/kg] at ``T_c`` [degC] (Magnus: p_s = 610.94 exp(17.625 T / (T + 243.04)) Pa)."""
    ps = 610.94 * np.exp(17.625 * np.asarray(T_c, float) / (np.asarray(T_c, float) + 243.04))
    return 0.622 * ps / (p_pa - ps)


def dew_draw(ctx, hw, rng):
    if ctx.chain.name not in DEW:
        return {}
    (lo, hi), (plo, phi) = DEW[ctx.chain.name]
    bodies = sorted(set(int(b) for b in ctx.chain.link_body if b >= 1))
    T0 = air_temperature(ctx.session, ctx.session.time_s[:1])[0]
    return {"bodies": bodies, "tau_s": {b: rng.uniform(lo, hi) * 60 for b in bodies},
            "tau_ped": rng.uniform(plo, phi) * 60, "dT0": rng.uniform(10.0, 25.0),
            "w_air": rng.uniform(0.4, 0.7) * saturation_ratio(T0), "t_in": rng.uniform(0.0, 0.25) * 3600,
            "h_ped": hw["mount"]["height_mm"], "cte": hw["material"]["cte"]}


def dew_temperatures(p, ctx):
    """(P, bodies + 1): each body's (and the pedestal's) temperature change [K] since the first pose: lumped nodes, cold
    by dT0 when the arm came in (t_in before the session), warmed by the air (logged) and, while a node is below the dew
    point, by the latent heat of the dew condensing on it, L_e (w_air - w_s(T)) with L_e = h_fg / (c_p Le^(2/3)) (the
    Chilton-Colburn analogy); explicit steps of 30 s."""
    s = ctx.session
    taus = [p["tau_s"][b] for b in p["bodies"]] + [p["tau_ped"]]
    grid = np.arange(s.time_s[0] - p["t_in"], s.time_s[-1] + STEP_S, STEP_S)
    Ta = air_temperature(s, grid)
    T = np.full(len(taus), Ta[0] - p["dT0"])
    out = np.empty((len(grid), len(taus)))
    for i, ta in enumerate(Ta):
        out[i] = T
        latent = LATENT_K * np.maximum(p["w_air"] - saturation_ratio(T), 0.0)
        T = T + STEP_S / np.array(taus) * (ta - T + latent)
    x = np.array([np.interp(s.time_s, grid, out[:, k]) for k in range(len(taus))]).T
    return x - x[0]


def dew_shape(p, ctx):
    """(P, 3): the target's displacement [mm] per unit CTE of the links (the steel pedestal at its own)."""
    dT = dew_temperatures(p, ctx)
    out = np.zeros((len(ctx.q), 3))
    for k, b in enumerate(p["bodies"]):
        out += ctx.link_scale_feature(ctx.chain.link_body == b) * dT[:, k:k + 1]
    return out + (STEEL_CTE / p["cte"]) * p["h_ped"] * dT[:, -1:] * Z


def dew_apply(p, ctx, hw):
    return Contribution(displace=p["cte"] * dew_shape(p, ctx) if p else np.zeros((len(ctx.q), 3)))


def dew_features(p, ctx, hw):
    return dew_shape(p, ctx)[None] if p else _empty(ctx)


# -------------------------------------------------------------------------------------------------- main drive
def drive_draw(ctx, hw, rng):
    if ctx.chain.name != "tool_changer":
        return {}
    g = np.deg2rad(rng.uniform(-10.0, 10.0))
    return {"axis": -np.array([np.sin(g), np.cos(g), 0.0]), "L_mm": rng.uniform(1000.0, 2000.0),
            "d_mm": rng.uniform(250.0, 400.0), "grad": rng.uniform(0.15, 0.35), "mean": rng.uniform(0.2, 0.6),
            "tau_d": rng.uniform(1.5, 4.0) * 3600, "tau_c": rng.uniform(20.0, 60.0) * 60,
            "t_start": rng.uniform(0.3, 2.0) * 3600, "inch": rng.uniform(0.5, 1.5), "inch_s": rng.uniform(120.0, 300.0),
            "dT0": rng.uniform(20.0, 40.0), "cte": hw["material"]["cte"]}


def drive_node(p, session):
    """(P,): the console's gradient per unit drive excess at the stop, at the measurements: the drive node cooling from
    one (in equilibrium at the stop, t_start before the session), re-warmed while the cutterhead inches at the start of
    each pause (a load of ``inch`` times the boring's steady heat for ``inch_s``), the console node lagging it."""
    s = session
    t = s.time_s
    grid = np.arange(t[0] - p["t_start"], t[-1] + GRID_S, GRID_S)
    u = np.zeros(len(grid))
    starts = (t - s.dwell_s - s.move_s - np.abs(s.gap_s))[s.gap_s < 0]    # the pauses' starts
    for a in starts:
        u[(grid >= a) & (grid < a + p["inch_s"])] = p["inch"]
    y = ph.first_order_zoh(grid, u, p["tau_d"], 1.0)
    x = ph.first_order_zoh(grid, y, p["tau_c"], 1.0)
    return np.interp(t, grid, x)


def drive_shape(p, ctx):
    """(P, 3): the target's displacement [mm] per kelvin of the drive's excess at the stop."""
    node = drive_node(p, ctx.session)
    dT = (node - node[0])[:, None] * p["grad"]
    c, L, d = p["axis"], p["L_mm"], p["d_mm"]
    u = p["cte"] * (-Z * L ** 2 / (2 * d) + c * p["mean"] * L)          # the console's tip per kelvin of gradient
    rot = p["cte"] * L / d * np.cross(Z, c)                            # its turn (down at the tip) per kelvin
    return dT * (u + np.cross(rot, ctx.target))


def drive_apply(p, ctx, hw):
    return Contribution(displace=p["dT0"] * drive_shape(p, ctx) if p else np.zeros((len(ctx.q), 3)))


def drive_features(p, ctx, hw):
    return drive_shape(p, ctx)[None] if p else _empty(ctx)
