"""Set E thermal effects (new physics, not in sets A-D): sunlight through the hall's windows warming the arm's
tubes on the side facing the sun, which moves with the time of day; and main-axis motors whose cooling fan is
switched by a thermostat, so that their housings warm, overshoot and settle (a non-monotonic transient after
power-on). Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* sun: solar position from the hour angle (15 deg per hour; Duffie & Beckman, *Solar Engineering of Thermal
  Processes*, 4th ed., 2013, ch. 1), simplified here to an elevation e_max sin(pi (h - 6) / 12) (e_max 30-60 deg)
  and an azimuth turning 15 deg/h; beam irradiance taken as sqrt(sin(elevation)) of its noon value (assumed).
  A thin-walled tube lit from one side: the circumferential conduction time r^2 / (pi^2 a) is seconds for
  aluminium and tens of seconds for steel, so the temperature difference across it follows the light
  quasi-statically and points at the sun (its size ~ the projected flux: |s_perp|); the tube bows away from the
  warm side with curvature alpha dT / D (Timoshenko & Goodier, *Theory of Elasticity*; Roark). The mean
  temperature follows the absorbed flux through a lumped lag of 15-60 min (Incropera & DeWitt, *Fundamentals of
  Heat and Mass Transfer*, ch. 5). dT across 0.5-2.5 K, mean rise 2-6 K at full sun (assumed); the logged air
  stays still (the sun heats the robot, not the hall's air).
* thermostat fan: natural convection h ~ 5-25 W/m^2 K against forced 25-250 W/m^2 K (Incropera & DeWitt,
  ch. 7-9): the fan cuts the housing's thermal resistance to 0.35-0.6x (forced-ventilation ratings of servo
  motors, e.g. Siemens 1FT7 / 1PH8 catalogues, as recalled), at the same heat capacity (so tau scales with R).
  A snap-action thermostat switches the fan on at T_on (35-60 % of the fan-less steady rise under the exercise
  cycle) and off 2-5 K lower (switching differential, as recalled from bimetal thermostat data). Heat from the
  drive losses along the session (:func:`effects_c_thermal.drive_heat`), fan-less rise 15-35 K, tau 20-60 min
  (assumed); each main-axis link body expands with its drive's housing temperature.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


# --------------------------------------------------------------------------------------------------- sunlight
def sun_draw(ctx, hw, rng):
    """Session start at 8-12 h solar time; the sun's noon azimuth in the base frame U(0, 360) deg."""
    links = {}
    for name, tb in hw["tubes"].items():
        links[name] = {"D_mm": 1000 * np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2),
                       "dT_across": rng.uniform(0.5, 2.5), "dT_mean": rng.uniform(2.0, 6.0)}
    return {"h0": rng.uniform(8.0, 12.0), "az_noon": rng.uniform(0, 2 * np.pi),
            "e_max": np.deg2rad(rng.uniform(30, 60)), "tau_s": rng.uniform(15, 60) * 60, "links": links,
            "cte": hw["material"]["cte"]}


def sun_state(p, t_s, t0):
    """Unit direction to the sun (K, 3) and relative irradiance (K,) at times ``t_s`` [s] (t0: session start)."""
    h = p["h0"] + (np.asarray(t_s, float) - t0) / 3600.0
    elev = p["e_max"] * np.sin(np.pi * (h - 6.0) / 12.0)
    az = p["az_noon"] + np.deg2rad(15.0) * (h - 12.0)
    s = np.stack([np.cos(elev) * np.cos(az), np.cos(elev) * np.sin(az), np.sin(elev)], axis=-1)
    return s, np.sqrt(np.clip(np.sin(elev), 0.0, 1.0))


def sun_mean(p, ctx):
    """Lagged relative irradiance (P,) at the measurement instants (the arm in the hall's temperature at the
    session start), from a minute grid."""
    s = ctx.session
    grid = np.arange(s.time_s[0], s.time_s[-1] + 60.0, 60.0)
    _, I = sun_state(p, grid, s.time_s[0])
    x = ph.first_order_foh(grid, I, p["tau_s"], x0=0.0)
    return np.interp(s.time_s, grid, x)


def sun_bow(p, lk, li, ctx):
    """Target displacement (P, 3) [mm] per unit alpha dT_across of link ``li`` (quasi-static bow away from
    the sun)."""
    s_dir, I = sun_state(p, ctx.session.time_s, ctx.session.time_s[0])
    e, tip, L = eb._beam_state(ctx, li)
    L = 1000.0 * L
    s_perp = (s_dir - np.sum(s_dir * e, axis=1, keepdims=True) * e) * I[:, None]
    kappa = s_perp / lk["D_mm"]                      # warm side towards the sun, per unit alpha dT [1/mm]
    shift = -kappa * L ** 2 / 2
    rot = -L * np.cross(e, kappa)
    return shift + np.cross(rot, ctx.target - tip)


def sun_apply(p, ctx, hw):
    disp = np.zeros((len(ctx.q), 3))
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    m = sun_mean(p, ctx)
    for name, lk in p["links"].items():
        li = ctx.chain.link_names.index(name)
        disp += p["cte"] * lk["dT_across"] * sun_bow(p, lk, li, ctx)
        strain[:, li] += p["cte"] * lk["dT_mean"] * m
    return Contribution(strain=strain, displace=disp)


def sun_features(p, ctx, hw):
    m = sun_mean(p, ctx)
    cols = []
    for name, lk in p["links"].items():
        li = ctx.chain.link_names.index(name)
        cols += [sun_bow(p, lk, li, ctx), ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li) * m[:, None]]
    return np.array(cols)


# --------------------------------------------------------------------------------------------- thermostat fan
def fan_draw(ctx, hw, rng):
    """The drives of axes 1-3; each link body 1-3 heated by the drive at its root (weight U(0.5, 1))."""
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    ex_w = ct.drive_heat(ctx, hw, accel, duty, exercise_only=True)
    out = []
    for j in range(3):
        T_ss = rng.uniform(15, 35)
        T_on = rng.uniform(0.35, 0.6) * T_ss
        out.append({"joint": j, "R": T_ss / max(ex_w[j], 1e-3), "tau_s": rng.uniform(20, 60) * 60,
                    "fan": rng.uniform(0.35, 0.6), "T_on": T_on, "T_off": T_on - rng.uniform(2, 5),
                    "w": rng.uniform(0.5, 1.0)})
    return {"drives": out, "accel_s": accel, "duty": duty, "cte": hw["material"]["cte"]}


def thermostat_response(dur, power, d, max_step=20.0):
    """Housing temperature rise (K,) at the end of each segment (cold start, fan off), heat ``power`` (K,) [W]
    held over ``dur`` (K,) [s]; the fan state is decided at sub-steps of at most ``max_step`` s."""
    T, on = 0.0, False
    out = np.zeros(len(dur))
    for k, (dt, pw) in enumerate(zip(dur, power)):
        n = max(int(np.ceil(dt / max_step)), 1)
        for _ in range(n):
            R = d["R"] * (d["fan"] if on else 1.0)
            tau = d["tau_s"] * (d["fan"] if on else 1.0)
            T = R * pw + (T - R * pw) * np.exp(-dt / n / tau)
            on = T >= d["T_on"] or (on and T > d["T_off"])
        out[k] = T
    return out


def fan_temperatures(p, ctx, hw):
    """Housing temperature rise (P, 3) [K] of the drives of axes 1-3 at the measurement instants."""
    pw = ct.drive_heat(ctx, hw, p["accel_s"], p["duty"])
    dur = ct._segment_times(ctx.session)
    return np.array([thermostat_response(dur, pw[:, :, d["joint"]].ravel(), d)[2::3] for d in p["drives"]]).T


def _fan_bodies(p, ctx):
    """(drive, body mask over the links) for each heated body that carries links."""
    out = []
    for k, d in enumerate(p["drives"]):
        mask = ctx.chain.link_body == d["joint"] + 1
        if mask.any():
            out.append((k, mask))
    return out


def fan_apply(p, ctx, hw):
    T = fan_temperatures(p, ctx, hw)
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    for k, mask in _fan_bodies(p, ctx):
        strain[:, mask] += p["cte"] * p["drives"][k]["w"] * T[:, k:k + 1]
    return Contribution(strain=strain)


def fan_features(p, ctx, hw):
    T = fan_temperatures(p, ctx, hw)
    return np.array([ctx.link_scale_feature(mask) * T[:, k:k + 1] for k, mask in _fan_bodies(p, ctx)])
