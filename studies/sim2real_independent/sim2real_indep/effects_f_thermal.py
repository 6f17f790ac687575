"""Set F thermal effects (new physics, not in sets A-E): a day / night cycle of the hall's air that the arm follows
through one lag and the concrete floor slab's top through a much longer one, so that the slab curls and tilts the
robot's base; and the ball screws of the cylinder-driven axes (and of a prismatic stage) growing with their own
friction heat through the duty cycle, so that the stroke read from the motor drifts. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* slab curling: a slab whose top is dT warmer than its bottom curls with curvature alpha dT / h (convex up, the
  edges lifting off their support less the restraint of its own weight): Westergaard, "Analysis of stresses in
  concrete pavements due to variations of temperature", Proc. Highway Research Board 6, 1926; Bradbury,
  *Reinforced Concrete Pavements*, 1938 (restraint coefficients); curling of industrial ground floors at their
  joints (Concrete Society TR 34, as recalled). Concrete alpha = 10e-6 /K (Neville, *Properties of Concrete*:
  6-13e-6), slab 0.15-0.3 m thick, restraint leaving 30-70 % of the free curvature, the robot 0.5-2.5 m from the
  panel's centre (assumed); the slab's top follows the hall air through a lag of 1-4 h, its bottom the ground
  (constant over a day); the base tilts by kappa r away from the panel's centre and sinks by kappa r^2 / 2 under its
  pedestal. The arm follows the air through 20-90 min (lumped capacitance: Incropera & DeWitt, *Fundamentals of
  Heat and Mass Transfer*, ch. 5) and expands uniformly. Sessions over a day and a night: the air cycles by +-1.5-3.5
  K over 24 h (a hall without air conditioning, assumed), blocks between pauses of 1-2.5 h.
* ball-screw growth: a screw warmed by its nut and support-bearing friction grows alpha dT over the length between
  its fixed bearing and the nut, and a semi-closed loop (motor encoder x nominal lead) does not see it -- the main
  thermal error of screw-driven axes (Bryan, "International status of thermal error research", CIRP Annals 39(2),
  1990; Ramesh, Mannan & Poo, Int. J. Mach. Tools Manuf. 40, 2000; Mayr et al., "Thermal issues in machine tools",
  CIRP Annals 61(2), 2012). Friction heat ~ |screw speed| (a constant drag torque), a lumped lag of 10-40 min,
  5-15 K above the air under the continuous exercise cycle (assumed); steel alpha 11.7e-6 /K. Sessions with
  production periods (exercise) between all blocks (with random pauses instead some sessions never warmed the
  screws: absorbed). The cylinder's
  stroke error dL turns the joint by dL / a (lever of :mod:`effects_f_joint`); the nut sits 0.05-0.15 m from the
  fixed bearing at the shortest length the session uses (assumed).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import effects_f_joint as xj
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

Z = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------------------------------- day and night
def daynight_draw(ctx, hw, rng):
    a = rng.uniform(0, 2 * np.pi)
    return {"tau_arm_s": rng.uniform(20, 90) * 60, "tau_slab_s": rng.uniform(60, 240) * 60,
            "h_slab_m": rng.uniform(0.15, 0.3), "restraint": rng.uniform(0.3, 0.7), "r_m": rng.uniform(0.5, 2.5),
            "dir": np.array([np.cos(a), np.sin(a), 0.0]), "alpha_c": 10e-6, "cte": hw["material"]["cte"],
            "h_ped_mm": hw["mount"]["height_mm"]}


def lagged_air(ctx, tau_s):
    """Temperature change (P,) [K] since the session start of a body following the air through a lag ``tau_s``
    (in its periodic state: the lag runs from 4 tau before the start, on a minute grid)."""
    s = ctx.session
    grid = np.arange(s.time_s[0] - 4 * tau_s, s.time_s[-1] + 60.0, 60.0)
    x = np.interp(s.time_s, grid, ph.first_order_foh(grid, air_temperature(s, grid), tau_s))
    return x - x[0]


def slab_part(p, ctx):
    """Target displacement (P, 3) [mm] per unit slab curvature [1/m]: tilt kappa r away from the panel's centre
    about the floor under the pedestal, and the sink kappa r^2 / 2."""
    omega = p["r_m"] * np.cross(Z, p["dir"])
    root = np.array([0.0, 0.0, -p["h_ped_mm"]])
    return np.cross(omega, ctx.target - root) - 1000.0 * p["r_m"] ** 2 / 2 * Z


def _daynight_parts(p, ctx):
    uni = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool)) * lagged_air(ctx, p["tau_arm_s"])[:, None]
    return np.array([uni, slab_part(p, ctx) * lagged_air(ctx, p["tau_slab_s"])[:, None]])


def _daynight_amp(p):
    return np.array([p["cte"], p["alpha_c"] * p["restraint"] / p["h_slab_m"]])


def daynight_apply(p, ctx, hw):
    T = lagged_air(ctx, p["tau_arm_s"])
    kappa = _daynight_amp(p)[1] * lagged_air(ctx, p["tau_slab_s"])
    return Contribution(strain=np.outer(p["cte"] * T, np.ones(len(ctx.chain.links))),
                        displace=slab_part(p, ctx) * kappa[:, None])


def daynight_features(p, ctx, hw):
    return _daynight_parts(p, ctx)


# ---------------------------------------------------------------------------------------- ball-screw growth
def screw_draw(ctx, hw, rng):
    """Every cylinder-driven joint's screw and every prismatic ball-screw stage (none on ur10)."""
    out = []
    for lv in xj.lever_geometry(ctx, hw, rng):
        _, L, _ = xj.lever_state(lv, ctx.q[:, lv["joint"]])
        lv.update(L_r=float(L.min()) - rng.uniform(0.0, 0.05), d0=rng.uniform(0.05, 0.15))
        out.append(lv)
    for j in np.flatnonzero(~ctx.chain.revolute):
        if hw["drives"][j]["kind"] == "screw":
            out.append({"joint": int(j), "s_min_mm": float(ctx.q[:, j].min()) - rng.uniform(50, 150)})
    for g in out:
        g.update(dT=rng.uniform(5, 15), tau_s=rng.uniform(10, 40) * 60, cte=11.7e-6)
    return out


def screw_temperature(g, ctx):
    """Screw temperature rise (P,) per unit dT at the measurement instants: heat ~ |speed| / exercise speed over
    the segments (exercise gap, move, dwell), cold start."""
    s, j = ctx.session, g["joint"]
    u = np.stack([(s.gap_s > 0).astype(float), s.speed[:, j] / s.exercise_speed[j], np.zeros(len(s.q))], axis=1)
    t = np.r_[0.0, np.cumsum(ct._segment_times(s))]
    return ph.first_order_zoh(t, np.r_[u.ravel(), 0.0], g["tau_s"], 0.0)[3::3]


def screw_signal(g, ctx):
    """Joint offset (P,) [rad or mm] per unit alpha dT."""
    q = ctx.q[:, g["joint"]]
    if "r1" not in g:                                          # a prismatic stage: the nut's travel itself
        return screw_temperature(g, ctx) * (q - g["s_min_mm"])
    _, L, a = xj.lever_state(g, q)
    return screw_temperature(g, ctx) * (L - g["L_r"] + g["d0"]) / a / g["s"]


def screw_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] += g["cte"] * g["dT"] * screw_signal(g, ctx)
    return Contribution(dq=dq)


def screw_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(g["joint"], screw_signal(g, ctx)) for g in p])
