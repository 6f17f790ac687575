"""Set N thermal effects (new physics, not in sets A-M): the laser tracker's tripod warmed on one side by a heater, its
legs growing unequally so that the head carrying the tracker tilts; the elastomer pads of the arm's levelling mounts
warmed unequally by a heater beside the cell, so that the base plate rises and tilts; and the output-side magnetic angle
encoders of the main axes, whose sine and cosine channels' offsets and gains drift as their joints warm, so that their
once- and twice-per-turn errors grow with the temperature. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* tripod tilt: a tripod's legs (aluminium 23e-6 /K) are hinged to its head and stand on spikes; the head is carried like
  the platform of a 3-RPS parallel mechanism (Lee & Shah, "Kinematic analysis of a three-degrees-of-freedom in-parallel
  actuated manipulator", IEEE J. Robot. Autom. 4(3), 1988): each hinge moves in its leg's vertical plane, by the leg's
  growth along it, so a leg grown by dL more than the others tilts the head by about dL / (1.5 r_h), r_h the hinges'
  radius -- the reason tracker stands are shielded from one-sided heat and sun (the thermal drift of the metrology
  frame: Bryan, "International status of thermal error research", CIRP Annals 39(2), 1990; Estler et al., "Large-scale
  metrology -- an update", CIRP Annals 51, 2002, on instrument stands). A radiant heater (or a patch of sun through a
  door) on one side, on for 30-60 % of the session (switched on 0-40 % into it), warms the legs facing it through a
  lumped lag of 5-20 min (thin tubes: Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) by up to
  0.4-1.5 K, each leg by 0.1 + 0.9 max(0, cos) of its angle to the heater. Legs of 1.2-1.9 m height spread to 0.6-0.9 m,
  hinges at 80-140 mm from the head's axis, 100-200 mm below the tracker's origin (assumed). The tracker reports a fixed
  point displaced by minus its head's motion (a measurement effect: needs the tracker's frame). All arms.
* elastomer pads: levelling mounts with elastomer pads (anti-vibration mounts under machine bases) expand some
  1.5-2.5e-4 /K, ten to twenty times steel (natural rubber and neoprene: Gent, *Engineering with Rubber*, 3rd ed., 2012,
  ch. 1; ASM data, as recalled); a radiant heater beside the cell, 0.7-1.5 m from the base's centre, switched on 10-50 %
  into the session as the hall cooled and left on, warms the pads it faces more: each pad's rise falls with the square
  of its distance from the source (irradiance), up to 15-30 K at the nearest, through a lag of 15-45 min (a 40-80 mm
  rubber pad: t^2 / a of half an hour and more). A rigid plate on four equal pads at (+-a, +-b) takes the least-squares
  plane through their growths (equal springs), so the arm rises by their mean and tilts by their differences. Pads 40-80
  mm thick (anti-vibration levelling mounts) at a half spacing of 0.15-0.3 / 0.25-0.45 m (ur10 / kr16_like; assumed),
  the plate's top 20-60 mm below the base frame's origin. None on tool_changer. First drawn with the heater 1.2-2.5 m
  away, on for 30-60 % of the session, pads of 20-50 mm and 10-25 K (gains of 3-20 % in trial draws), then 0.7-1.5 m
  away with thicker pads (a time split's test part saw the pads cooling: absorbed in a trial draw).
* magnetic encoder drift: an output-side absolute encoder with Hall or magnetoresistive sensors on a diametrically
  magnetised ring reads the angle atan2 of a sine and a cosine channel; an offset o in a channel errs once per turn by o
  / A, a gain mismatch twice per turn (the interpolation errors of HEIDENHAIN's "Angle encoders" brochure; sensor data
  sheets, e.g. ams AS5047 / iC-Haus iC-MU, specify the offsets' and gains' temperature drift and the magnet's remanence
  falls by 0.1-0.12 %/K for NdFeB), so the errors grow with the sensor's temperature. Here 6-16 urad/K once per turn and
  3-8 urad/K twice per turn, at random phases (assumed; first 2-8 and 1-4 urad/K: gains of 6-30 % in trial draws), the
  phases the sensor's (shape parameters; first free sine and cosine columns: the set's case split by time extrapolated
  its twelve columns, gain -43 %), the sensor next to the drive warming with it through one lumped node
  (:func:`effects_k_thermal.node_rise`; 15-35 K under the production cycle, 15-40 min, a cold start); the controller
  servoes the reading (dual-encoder joints), so the joint is off by minus the error. Axes 1-3 of ur10 and kr16_like.
  Scored as transmission, the family whose model holds the shape (a joint's error as a function of its own angle; as set
  K's thermal backlash is backlash).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_k_thermal as kt
from sim2real_indep.context import Contribution
from sim2real_indep.effects_m_thermal import tracker_origin

Z = np.array([0.0, 0.0, 1.0])
ALUMINIUM_CTE = 23e-6


def heater_curve(p, t_s):
    """Lagged on/off heating (P,) in [0, 1]: the first-order response to a heater on over [t_on, t_off)."""
    t = np.asarray(t_s, float)
    on = 1 - np.exp(-np.clip(t - p["t_on"], 0.0, p["t_off"] - p["t_on"]) / p["tau_s"])
    return on * np.exp(-np.clip(t - p["t_off"], 0.0, None) / p["tau_s"])


def heater_times(ctx, rng):
    t0, t1 = ctx.session.time_s[0], ctx.session.time_s[-1]
    a = rng.uniform(0.0, 0.4)
    return t0 + a * (t1 - t0), t0 + (a + rng.uniform(0.3, 0.6)) * (t1 - t0)


# -------------------------------------------------------------------------------------------------- tripod tilt
def tripod_draw(ctx, hw, rng):
    t_on, t_off = heater_times(ctx, rng)
    return {"H_mm": rng.uniform(1200, 1900), "r_f_mm": rng.uniform(600, 900), "r_h_mm": rng.uniform(80, 140),
            "h_h_mm": rng.uniform(100, 200), "phi0": rng.uniform(0, 2 * np.pi), "src": rng.uniform(0, 2 * np.pi),
            "dT_K": rng.uniform(0.4, 1.5), "tau_s": rng.uniform(5, 20) * 60, "t_on": t_on, "t_off": t_off}


def tripod_legs(p, o):
    """Feet, hinges (3, 3) [mm] and leg lengths (3,) of the tripod under the tracker's origin ``o``."""
    phi = p["phi0"] + 2 * np.pi * np.arange(3) / 3
    rad = np.c_[np.cos(phi), np.sin(phi), np.zeros(3)]
    hinge = o + p["r_h_mm"] * rad - p["h_h_mm"] * Z
    foot = o + p["r_f_mm"] * rad - p["H_mm"] * Z
    return foot, hinge, np.linalg.norm(hinge - foot, axis=1), rad


def head_motion(p, o):
    """(3, 6): the head's translation and rotation (about ``o``) per unit growth [mm] of each leg: each hinge moves
    along its leg by the growth and not across the leg's vertical plane."""
    foot, hinge, L, rad = tripod_legs(p, o)
    u = (hinge - foot) / L[:, None]
    tang = np.cross(Z, rad)
    M = np.zeros((6, 6))
    for k in range(3):
        lever = hinge[k] - o
        for row, v in ((k, u[k]), (3 + k, tang[k])):
            M[row, :3], M[row, 3:] = v, np.cross(lever, v)       # v . (D + w x r) = v . D + (r x v) . w
    return np.linalg.solve(M, np.r_[np.eye(3), np.zeros((3, 3))]).T


def tripod_parts(p, ctx, hw):
    """(3, P, 3): each leg's share -- the apparent displacement of the targets per unit strain of that leg at the
    heater's full effect: minus the head's motion, times the leg's length, exposure and heating curve."""
    o = tracker_origin(hw)
    _, _, L, rad = tripod_legs(p, o)
    src = np.array([np.cos(p["src"]), np.sin(p["src"]), 0.0])
    w = 0.1 + 0.9 * np.maximum(rad @ src, 0.0)
    theta = heater_curve(p, ctx.session.time_s)
    out = []
    for k, x in enumerate(head_motion(p, o)):
        move = x[:3] + np.cross(x[3:], ctx.target - o)
        out.append(-(L[k] * w[k]) * theta[:, None] * move)
    return np.array(out)


def tripod_apply(p, ctx, hw):
    return Contribution(displace=ALUMINIUM_CTE * p["dT_K"] * tripod_parts(p, ctx, hw).sum(axis=0))


def tripod_features(p, ctx, hw):
    return tripod_parts(p, ctx, hw)


# ---------------------------------------------------------------------------------------------- elastomer pads
#: per arm: the pads' half spacing [mm] (assumed)
PADS = {"ur10": (150.0, 300.0), "kr16_like": (250.0, 450.0)}


def pad_draw(ctx, hw, rng):
    if ctx.chain.name not in PADS:
        return {}
    t0, t1 = ctx.session.time_s[0], ctx.session.time_s[-1]
    t_on, t_off = t0 + rng.uniform(0.1, 0.5) * (t1 - t0), np.inf      # switched on as the cell cooled, left on
    a, b = rng.uniform(*PADS[ctx.chain.name], 2)
    yaw, az, D = rng.uniform(0, np.pi), rng.uniform(0, 2 * np.pi), rng.uniform(700, 1500)
    R = np.array([[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]])
    xy = np.array([[a, b], [-a, b], [-a, -b], [a, -b]]) @ R.T
    src = D * np.array([np.cos(az), np.sin(az)])
    r2 = np.sum((xy - src) ** 2, axis=1)
    return {"xy": xy, "w": r2.min() / r2, "t_mm": rng.uniform(40, 80), "alpha": rng.uniform(1.5e-4, 2.5e-4),
            "dT_K": rng.uniform(15, 30), "tau_s": rng.uniform(15, 45) * 60, "t_on": t_on, "t_off": t_off,
            "top_mm": rng.uniform(20, 60)}


def pad_part(p, ctx):
    """(P, 3): the target's displacement per mm of growth of the nearest pad at the heater's full effect: the plate's
    least-squares plane through the pads' growths, its rise and tilts about its centre."""
    c0, c1, c2 = np.linalg.lstsq(np.c_[np.ones(4), p["xy"]], p["w"], rcond=None)[0]   # growths per nearest pad's
    r = ctx.target + p["top_mm"] * Z
    theta = heater_curve(p, ctx.session.time_s)
    move = c0 * Z + np.cross(np.array([c2, -c1, 0.0]), r)
    return theta[:, None] * move


def pad_apply(p, ctx, hw):
    return Contribution(displace=p["alpha"] * p["t_mm"] * p["dT_K"] * pad_part(p, ctx) if p else None)


def pad_features(p, ctx, hw):
    return pad_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------ magnetic encoder drift
MAG_ARMS = {"ur10", "kr16_like"}
MAG_JOINTS = (0, 1, 2)


def mag_draw(ctx, hw, rng):
    if ctx.chain.name not in MAG_ARMS:
        return {}
    n = ctx.chain.n
    return {"joints": list(MAG_JOINTS), "rise_K": rng.uniform(15, 35, 3), "tau_s": rng.uniform(15, 40, 3) * 60,
            "accel_s": rng.uniform(0.2, 0.6, n), "duty": rng.uniform(0.2, 0.5, n),
            "amp": np.c_[rng.uniform(6e-6, 16e-6, 3), rng.uniform(3e-6, 8e-6, 3)],
            "phase": rng.uniform(0, 2 * np.pi, (3, 2))}


def mag_signals(p, ctx, hw):
    """(3, 2, P): per joint dT cos(q - phi_1) and dT cos(2 q - phi_2) [K] -- the once- and twice-per-turn errors per
    unit drift, their phases the sensor's (shape parameters)."""
    dT = kt.node_rise(ctx, hw, p["joints"], p["rise_K"], p["tau_s"], p["accel_s"], p["duty"])
    q = ctx.q[:, p["joints"]]
    S = np.stack([dT * np.cos(q - p["phase"][:, 0]), dT * np.cos(2 * q - p["phase"][:, 1])], axis=1)
    return S.transpose(2, 1, 0)


def mag_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = -np.einsum("jk,jkp->pj", p["amp"], mag_signals(p, ctx, hw))
    return Contribution(dq=dq)


def mag_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    S = mag_signals(p, ctx, hw)
    return np.array([ctx.joint_feature(j, s) for j, sj in zip(p["joints"], S) for s in sj])
