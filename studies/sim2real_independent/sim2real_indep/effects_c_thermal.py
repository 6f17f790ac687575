"""Set C thermal effects (new physics, not in sets A / B): a two-node drive model with per-joint time constants and
heat from RMS (gravity + acceleration) torque; the thermal bow of a pedestal column under a temperature difference
across it; a workcell whose air drifts while the drives warm up; and the laser tracker's uncompensated
refractive-index scale error. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* two-node (winding -> housing -> ambient) lumped thermal network of a servo drive: Boglietti, Cavagnino,
  Staton, Shanel, Mueller & Mejuto, "Evolution and modern approaches for thermal analysis of electrical
  machines", IEEE Trans. Ind. Electron. 56(3), 2009 (lumped-parameter networks); the robot case (joint drives as the
  heat sources that expand the links): Heisel, Richter & Wurst, "Thermal behaviour of industrial robots and
  possibilities for error compensation", CIRP Annals 46(1), 1997. Copper loss ~ RMS torque squared (Mohan,
  *Electric Drives*); acceleration torque J alpha with J = sum m r^2 of the point masses about the joint axis.
  Ranges (time constants, the housing's rise under a continuous exercise cycle) are this study's assumptions.
* thermal bow of a beam with a linear temperature difference dT across its depth D: curvature alpha dT / D
  (Timoshenko & Goodier, *Theory of Elasticity*, thermal stress chapter; Roark's *Formulas for Stress and Strain*,
  thermal-gradient beam cases): the column top tilts by alpha dT h / D and shifts by alpha dT h^2 / (2 D); the
  column grows by alpha dT_mean h.
* air refractive index: dn/dT ~ -0.93e-6 /K near 20 degC, 1013 hPa (Edlen, Metrologia 2, 1966; Birch & Downs,
  Metrologia 30, 1993): a tracker whose weather compensation is frozen at the session start reads every distance
  short by ~0.93 ppm per K of warming (angles are unaffected: a scaling about the tracker's origin). Only the
  measurement is affected here (an idealisation: the case isolates the measurement error).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

N_PER_K_AIR = -0.93e-6  # relative change of the air's refractive index per K


# ------------------------------------------------------------------------------------ drive heat (RMS torque)
def inertia_about_joints(ctx):
    """J (P, n) [kg m^2] of the point masses beyond each revolute joint about its axis (prismatic: moving mass [kg])."""
    m, pos, body = ctx.mass_state
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    out = np.zeros(ctx.q.shape)
    for j in range(ctx.chain.n):
        on = body >= j + 1
        if not ctx.chain.revolute[j]:
            out[:, j] = m[:, on].sum(axis=1)
            continue
        r = (pos[:, on] - c[:, j, None]) / 1000.0
        r_perp = r - np.einsum("pbi,pi->pb", r, w[:, j])[..., None] * w[:, j, None]
        out[:, j] = (m[:, on] * np.sum(r_perp ** 2, axis=-1)).sum(axis=1)
    return out


def drive_heat(ctx, hw, accel_s, ex_duty, exercise_only=False):
    """Heat [W] of each drive per segment before each measurement, (P, 3, n): gap (exercise; pause = servo off),
    move, dwell (``exercise_only``: the exercise cycle's heat (n,) alone).
    Move: mean square torque = gravity^2 + (accel time / move time) (J alpha)^2 with alpha = v /
    ``accel_s``; exercise: the poses' mean square gravity load + a duty ``ex_duty`` of (J alpha)^2 at the exercise
    speed."""
    s, tau = ctx.session, ctx.loads
    J = inertia_about_joints(ctx)
    prev = np.vstack([tau[:1], tau[:-1]])
    out, ex_w = np.zeros((len(s.q), 3, ctx.chain.n)), np.zeros(ctx.chain.n)
    for j, d in enumerate(hw["drives"]):
        unit = 1.0 if ctx.chain.kinds[j] == "R" else 1e-3
        t_acc = J[:, j] * unit * s.speed[:, j] / accel_s[j]
        frac = np.where(s.move_s > 0, np.minimum(2 * accel_s[j] / np.maximum(s.move_s, 1e-9), 1.0), 0.0)
        mv2 = (prev[:, j] ** 2 + tau[:, j] ** 2) / 2 + frac * t_acc ** 2
        ex_acc = J[:, j].mean() * unit * s.exercise_speed[j] / accel_s[j]
        ex2 = (tau[:, j] ** 2).mean() + ex_duty[j] * ex_acc ** 2
        loss = lambda v, t2: ph.motor_losses(v, np.sqrt(t2), d["T_rated"], d["P_cu_rated_W"], d["friction_frac"])
        ex_w[j] = loss(unit * s.exercise_speed[j], ex2)
        out[:, 0, j] = np.where(s.gap_s > 0, ex_w[j], 0.0)
        out[:, 1, j] = loss(unit * s.speed[:, j], mv2)
        out[:, 2, j] = loss(0.0, tau[:, j] ** 2)
    return ex_w if exercise_only else out


def _segment_times(s):
    dur = np.stack([np.abs(s.gap_s), s.move_s, s.dwell_s], axis=1).ravel()
    return dur


def two_node_zoh(dur, power, tau_w, tau_h, R_wh, R_ha):
    """Housing temperature rise at the end of each segment of the two-node network (cold start), heat ``power``
    (K,) [W] held over segments of ``dur`` (K,) [s]. Winding C_w = tau_w / R_wh, housing C_h = tau_h / R_ha."""
    C_w, C_h = tau_w / R_wh, tau_h / R_ha
    A = np.array([[-1 / (R_wh * C_w), 1 / (R_wh * C_w)], [1 / (R_wh * C_h), -(1 / R_wh + 1 / R_ha) / C_h]])
    B = np.array([1 / C_w, 0.0])
    lam, V = np.linalg.eig(A)
    lam, V = lam.real, V.real
    Vi = np.linalg.inv(V)
    x, out = np.zeros(2), np.zeros(len(dur))
    for k, (dt, p) in enumerate(zip(dur, power)):
        e = np.exp(lam * dt)
        x = V @ (e * (Vi @ x)) + V @ (((e - 1) / lam) * (Vi @ (B * p)))
        out[k] = x[1]
    return out


def twonode_draw(ctx, hw, rng):
    """Per drive: winding time constant 3-15 min, housing 20-120 min (each joint its own), winding-to-housing
    resistance 0.5-1.5x housing-to-ambient; the housing would settle 8-20 K above ambient under the continuous
    exercise cycle (assumed). Each link body heated by its proximal and distal drive housings (weights U(0.3, 1)).
    Acceleration ramps 0.2-0.6 s, exercise acceleration duty 20-50 %."""
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    ex_w = drive_heat(ctx, hw, accel, duty, exercise_only=True)
    R_ha = rng.uniform(8.0, 20.0, n) / np.maximum(ex_w, 1e-3)
    bodies = sorted(set(int(b) for b in ctx.chain.link_body if b >= 1))
    return {"tau_w": rng.uniform(3, 15, n) * 60, "tau_h": rng.uniform(20, 120, n) * 60, "R_ha": R_ha,
            "R_wh": R_ha * rng.uniform(0.5, 1.5, n), "accel_s": accel, "duty": duty, "bodies": bodies,
            "w": {b: (rng.uniform(0.3, 1.0), rng.uniform(0.3, 1.0) if b < n else 0.0) for b in bodies},
            "cte": hw["material"]["cte"]}


def housing_temperatures(p, ctx, hw):
    """Housing temperature rise (P, n) [K] of each drive at the measurement instants."""
    pw = drive_heat(ctx, hw, p["accel_s"], p["duty"])
    dur = _segment_times(ctx.session)
    out = np.zeros(ctx.q.shape)
    for j in range(ctx.chain.n):
        x = two_node_zoh(dur, pw[:, :, j].ravel(), p["tau_w"][j], p["tau_h"][j], p["R_wh"][j], p["R_ha"][j])
        out[:, j] = x[2::3]
    return out


def _body_dT(p, ctx, hw):
    Th = housing_temperatures(p, ctx, hw)
    n = ctx.chain.n
    return {b: p["w"][b][0] * Th[:, b - 1] + (p["w"][b][1] * Th[:, b] if b < n else 0.0) for b in p["bodies"]}


def twonode_apply(p, ctx, hw):
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    for b, dT in _body_dT(p, ctx, hw).items():
        strain[:, ctx.chain.link_body == b] += p["cte"] * dT[:, None]
    return Contribution(strain=strain)


def twonode_features(p, ctx, hw):
    return np.array([ctx.link_scale_feature(ctx.chain.link_body == b) * dT[:, None]
                     for b, dT in _body_dT(p, ctx, hw).items()])


# ------------------------------------------------------------------------------------ workcell: air + warm-up
def workcell_draw(ctx, hw, rng):
    """The air drifts (logged; session options) and the structure follows it through a 20-90 min lag, while the
    drives warm up as in :func:`twonode_draw`."""
    return {"air_tau_s": rng.uniform(20, 90) * 60, "cte": hw["material"]["cte"], "drives": twonode_draw(ctx, hw, rng)}


def _air_structure(p, ctx):
    return eb.structure_temperature({"tau_s": p["air_tau_s"]}, ctx)


def workcell_apply(p, ctx, hw):
    c = twonode_apply(p["drives"], ctx, hw)
    return Contribution(strain=c.strain + p["cte"] * _air_structure(p, ctx)[:, None])


def workcell_features(p, ctx, hw):
    uni = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool)) * _air_structure(p, ctx)[:, None]
    return np.concatenate([uni[None], twonode_features(p["drives"], ctx, hw)])


# ------------------------------------------------------------------------------------------- column bow
def column_draw(ctx, hw, rng):
    """A steel riser column (height 400-1200 mm, depth 250-450 mm) under the base; the drives of axes 1 and 2 sit
    on one side of it (direction U(0, 360) deg) and heat it through a 20-60 min lag: the difference across it
    reaches 1-3 K, its mean 1-3x that, under the continuous exercise cycle (assumed ranges)."""
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    a = rng.uniform(0, 2 * np.pi)
    return {"h_mm": rng.uniform(400, 1200), "D_m": rng.uniform(0.25, 0.45), "dir": np.array([np.cos(a), np.sin(a), 0]),
            "tau_s": rng.uniform(20, 60) * 60, "dT_across": rng.uniform(1.0, 3.0), "mean_ratio": rng.uniform(1, 3),
            "accel_s": accel, "duty": duty, "cte": 11.7e-6}


def column_signal(p, ctx, hw):
    """Temperature difference across the column (P,) [K]: the lagged heat of drives 1-2, scaled to dT_across at
    the exercise cycle's heat."""
    pw = drive_heat(ctx, hw, p["accel_s"], p["duty"])[:, :, :2].sum(axis=2)
    ref = drive_heat(ctx, hw, p["accel_s"], p["duty"], exercise_only=True)[:2].sum()
    dur = _segment_times(ctx.session)
    t = np.r_[0.0, np.cumsum(dur)]
    x = ph.first_order_zoh(t, np.r_[pw.ravel() / ref, 0.0], p["tau_s"], 0.0)
    return p["dT_across"] * x[3::3]


def column_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per K across (bow) and per K mean (growth)."""
    h, g, z = p["h_mm"], p["dir"], np.array([0, 0, 1.0])
    kappa = p["cte"] / (p["D_m"] * 1000.0)           # [1/mm per K]
    top_shift = -g * kappa * h ** 2 / 2               # the column bows away from the warm side
    rot = np.cross(g, z) * kappa * h                  # the top tilts towards the cool side
    bow = top_shift + np.cross(rot, ctx.target)
    grow = np.broadcast_to(z * p["cte"] * h, bow.shape)
    return np.array([bow, grow])


def column_apply(p, ctx, hw):
    s = column_signal(p, ctx, hw)
    parts = column_parts(p, ctx)
    return Contribution(displace=parts[0] * s[:, None] + parts[1] * (p["mean_ratio"] * s)[:, None])


def column_features(p, ctx, hw):
    s = column_signal(p, ctx, hw)
    return column_parts(p, ctx) * s[None, :, None]


# ---------------------------------------------------------------------------------- tracker scale (air)
def scale_draw(ctx, hw, rng):
    return {"ppm_per_K": -N_PER_K_AIR * 1e6 * rng.uniform(0.9, 1.05)}  # distances read short as the air warms


def _scale_signal(p, ctx):
    s = ctx.session
    T = air_temperature(s, s.time_s)
    return -p["ppm_per_K"] * 1e-6 * (T - T[0])


def scale_parts(ctx, hw):
    tr = hw["tracker"]
    return ctx.target + tr["R"].T @ tr["t"]  # position relative to the tracker's origin, base axes


def scale_apply(p, ctx, hw):
    return Contribution(displace=scale_parts(ctx, hw) * _scale_signal(p, ctx)[:, None])


def scale_features(p, ctx, hw):
    return (scale_parts(ctx, hw) * _scale_signal(p, ctx)[:, None])[None]
