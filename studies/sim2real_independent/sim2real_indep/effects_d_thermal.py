"""Set D thermal effects (new physics, not in sets A-C): thermal-gradient bending of links with a drive on one side;
a process tool at the flange (spindle / torch head) heating itself and the wrist while it works; and the laser
beam's refraction in a vertically stratified workshop air (a measurement error the tracker's weather station does
not compensate). Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* thermal bow of a link: a temperature difference dT across a beam of depth D bends it with curvature
  alpha dT / D (Timoshenko & Goodier, *Theory of Elasticity*, thermal stresses; Roark's *Formulas for Stress and
  Strain*, beams with a linear temperature gradient): the tip shifts by kappa L^2 / 2 away from the warm side and
  rotates by kappa L; the link grows by alpha dT_mean L. Robot arms with motors flanged to one side of a link
  warm asymmetrically (Heisel, Richter & Wurst, CIRP Annals 46(1), 1997; thermographies in Li et al. and Gong et
  al. on industrial-robot thermal errors, as recalled). dT across 1-4 K under the exercise cycle, mean 1-3x that,
  lag 15-60 min (assumed). Drive heat as :func:`effects_c_thermal.drive_heat` (copper + friction loss).
* process tool heat: a spindle or torch head dissipating while it works (production periods between the
  measurement blocks), idle 0-10 % while the robot is measured; lumped first-order nodes (Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 5): tool housing tau 5-20 min rising 10-40 K in continuous use,
  the wrist following it through 20-60 min, 3-10 K (assumed). The tool (150-300 mm along its axis, steel) grows
  alpha dT L; the wrist links expand with the wrist temperature.
* refraction: dn/dT ~ -0.93e-6 /K (Edlen, Metrologia 2, 1966; Birch & Downs, Metrologia 30, 1993); a ray in a
  uniform transverse index gradient bends with curvature |grad n|, deviating kappa L^2 / 2 at range L -- the
  target appears displaced away from the warm air; vertical gradients in halls of 0.2-1.5 K/m (Estler et al.,
  "Large-scale metrology -- an update", CIRP Annals 51(2), 2002, on refraction as a limit of tracker accuracy;
  the gradient's size is this study's assumption), growing by 0.1-0.3 K/m per K as the air warms (assumed).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

DN_DT = -0.93e-6  # [1/K]


# ------------------------------------------------------------------------------------------ thermal bending
def bend_draw(ctx, hw, rng):
    """One or two tube links, each warmed on one side (direction U(0, 360) deg normal to it) by the drive at its
    root or its tip."""
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    names = list(hw["tubes"])
    pick = sorted(rng.permutation(names)[:int(rng.integers(1, 3))])
    links = {}
    for name in pick:
        li = ctx.chain.link_names.index(name)
        b = int(ctx.chain.link_body[li])
        cand = [j for j in (b - 1, b) if 0 <= j < n]
        tb = hw["tubes"][name]
        e0 = ctx.chain.links[li] / np.linalg.norm(ctx.chain.links[li])
        u = np.cross(e0, [1.0, 0, 0] if abs(e0[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        a = rng.uniform(0, 2 * np.pi)
        links[name] = {"drive": int(rng.choice(cand)), "g_home": np.cos(a) * u + np.sin(a) * np.cross(e0, u),
                       "D_mm": 1000 * np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2),
                       "dT_across": rng.uniform(1.0, 4.0), "mean_ratio": rng.uniform(1.0, 3.0),
                       "tau_s": rng.uniform(15, 60) * 60}
    return {"links": links, "accel_s": accel, "duty": duty, "cte": hw["material"]["cte"]}


def bend_signal(p, lk, ctx, hw):
    """Temperature difference across the link (P,) [K]: its drive's heat through the lag, dT_across at the
    exercise cycle's heat."""
    j = lk["drive"]
    pw = ct.drive_heat(ctx, hw, p["accel_s"], p["duty"])[:, :, j]
    ref = max(ct.drive_heat(ctx, hw, p["accel_s"], p["duty"], exercise_only=True)[j], 1e-9)
    t = np.r_[0.0, np.cumsum(ct._segment_times(ctx.session))]
    x = ph.first_order_zoh(t, np.r_[pw.ravel() / ref, 0.0], lk["tau_s"], 0.0)
    return lk["dT_across"] * x[3::3]


def bend_parts(p, lk, li, ctx):
    """Target displacement (P, 3) [mm] per K across the link (its thermal bow)."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    e, tip, L = eb._beam_state(ctx, li)
    L = 1000.0 * L
    g = R[:, ctx.chain.link_body[li]] @ lk["g_home"]
    kappa = p["cte"] / lk["D_mm"]
    shift = -g * kappa * L ** 2 / 2
    rot = -kappa * L * np.cross(e, g)
    return shift + np.cross(rot, ctx.target - tip)


def bend_apply(p, ctx, hw):
    disp = np.zeros((len(ctx.q), 3))
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    for name, lk in p["links"].items():
        li = ctx.chain.link_names.index(name)
        s = bend_signal(p, lk, ctx, hw)
        disp += bend_parts(p, lk, li, ctx) * s[:, None]
        strain[:, li] += p["cte"] * lk["mean_ratio"] * s
    return Contribution(strain=strain, displace=disp)


def bend_features(p, ctx, hw):
    cols = []
    for name, lk in p["links"].items():
        li = ctx.chain.link_names.index(name)
        s = bend_signal(p, lk, ctx, hw)
        cols += [bend_parts(p, lk, li, ctx) * s[:, None],
                 ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li) * s[:, None]]
    return np.array(cols)


# ------------------------------------------------------------------------------------------- process tool heat
def toolheat_draw(ctx, hw, rng):
    return {"tau_tool_s": rng.uniform(5, 20) * 60, "tau_wrist_s": rng.uniform(20, 60) * 60,
            "dT_tool": rng.uniform(10, 40), "dT_wrist": rng.uniform(3, 10), "idle": rng.uniform(0.0, 0.1),
            "L_tool_mm": rng.uniform(150, 300), "cte_tool": 11.7e-6, "cte": hw["material"]["cte"]}


def toolheat_temperatures(p, ctx):
    """Tool and wrist temperature rises (2, P) [K] at the measurement instants (cold start)."""
    s = ctx.session
    on = np.stack([np.where(s.gap_s > 0, 1.0, p["idle"]), np.full(len(s.q), p["idle"]),
                   np.full(len(s.q), p["idle"])], axis=1).ravel()
    tool, wrist = series_lags(ct._segment_times(s), on, p["tau_tool_s"], p["tau_wrist_s"])
    return np.array([p["dT_tool"] * tool[2::3], p["dT_wrist"] * wrist[2::3]])


def series_lags(dur, u, tau1, tau2):
    """Exact end-of-segment states of tau1 x1' = u - x1, tau2 x2' = x1 - x2 (cold start) for an input held at
    u[k] over segments of dur[k] [s] (tau1 != tau2): x2 = u + c e1 + (x2_0 - u - c) e2, c = (x1_0 - u) tau1 /
    (tau1 - tau2)."""
    x1, x2 = 0.0, 0.0
    o1, o2 = np.zeros(len(dur)), np.zeros(len(dur))
    for k, (dt, uk) in enumerate(zip(dur, u)):
        e1, e2 = np.exp(-dt / tau1), np.exp(-dt / tau2)
        c = (x1 - uk) * tau1 / (tau1 - tau2)
        x1, x2 = uk + (x1 - uk) * e1, uk + c * e1 + (x2 - uk - c) * e2
        o1[k], o2[k] = x1, x2
    return o1, o2


def _wrist_mask(ctx):
    return (ctx.chain.link_body >= ctx.chain.n - 2) & (np.linalg.norm(ctx.chain.links, axis=1) > 0)


def _tool_axis(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt[:, :, 2]


def toolheat_apply(p, ctx, hw):
    T = toolheat_temperatures(p, ctx)
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    strain[:, _wrist_mask(ctx)] = p["cte"] * T[1][:, None]
    disp = _tool_axis(ctx) * (p["cte_tool"] * p["L_tool_mm"] * T[0])[:, None]
    return Contribution(strain=strain, displace=disp)


def toolheat_features(p, ctx, hw):
    T = toolheat_temperatures(p, ctx)
    return np.array([_tool_axis(ctx) * T[0][:, None], ctx.link_scale_feature(_wrist_mask(ctx)) * T[1][:, None]])


# ---------------------------------------------------------------------------------------------- refraction
def refraction_draw(ctx, hw, rng):
    return {"G0_K_per_m": rng.uniform(0.2, 1.5), "G1_per_K": rng.uniform(0.1, 0.3)}


def refraction_parts(ctx, hw):
    """Apparent target displacement (2, P, 3) [mm] per K/m of vertical gradient: constant and following the air's
    warming since the session start."""
    tr = hw["tracker"]
    rel = ctx.target + tr["R"].T @ tr["t"]       # from the tracker's origin, base axes [mm]
    L = np.linalg.norm(rel, axis=1, keepdims=True)
    e = rel / L
    z = np.array([0.0, 0.0, 1.0])
    z_perp = z - e[:, 2:3] * e
    shape = -DN_DT * (L / 1000.0) ** 2 / 2 * 1000.0 * z_perp   # warm air above: the target appears higher
    s = ctx.session
    T = air_temperature(s, s.time_s)
    return np.array([shape, shape * (T - T[0])[:, None]])


def refraction_apply(p, ctx, hw):
    parts = refraction_parts(ctx, hw)
    return Contribution(displace=p["G0_K_per_m"] * parts[0] + p["G1_per_K"] * parts[1])


def refraction_features(p, ctx, hw):
    return refraction_parts(ctx, hw)
