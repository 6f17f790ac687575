"""Set H warm-up effects (new physics, not in sets A-G): a laser tracker measuring before it has warmed up, its
angles and distance drifting; the helical output stages of a wrist whose motor shafts grow with their drive heat and
push the pinions along the helix; and the output-side grease friction of cold joints, which winds the gears against
the last motion and fades as the joints warm. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* tracker warm-up: trackers specify a warm-up time after power-on before their accuracy holds (Leica AT960 / FARO
  Vantage manuals, as recalled; ASME B89.4.19-2006 tests a warmed-up instrument); the head's temperature settles
  as a lumped first-order node (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5), and with it
  the beam's pointing (azimuth and elevation offsets) and the distance meter's zero drift (error sources of
  trackers: Muralikrishnan, Phillips & Sawyer, "Laser trackers for large-scale dimensional metrology: a review",
  Precis. Eng. 44, 2016). Here drifts of 15-50 urad in azimuth and elevation and 5-20 um in distance over the
  warm-up, tau 20-60 min, the first point measured 0-5 min after power-on (assumed). The tracker reports
  r, az, el: a point moves by daz r cos(el) e_az + del r e_el + dr e_r in the tracker's frame (a measurement
  effect: needs the tracker's frame).
* helical shift: a helical pinion displaced axially by delta turns its wheel by delta tan(beta) / r (ISO 21771
  helical geometry; set G's axial float); a motor shaft located at its B-side bearing grows towards the pinion by
  alpha L dT (steel 11.7e-6 /K, L 100-180 mm) as its drive heats (copper and friction losses as
  :func:`effects_c_thermal.drive_heat`; one lumped node, tau 15-40 min, 15-35 K above ambient under the exercise
  cycle; assumed), beta 20-30 deg, r 25-50 mm (assumed): the joint is off by alpha L dT tan(beta) / r, its sign
  set by the helix hand. The wrist axes of the arms given helical (positioner-type) output stages (tool_changer,
  kr16_like; none on ur10).
* cold grease: the output-side friction (output bearing and seals) winds the compliant gear while the joint moves
  and static friction keeps the wind-up after the stop: the output trails by c T_f against the last motion (set E's
  friction wind-up). The viscous part of bearing friction grows as (nu n)^(2/3) (Palmgren; SKF rolling-bearing
  friction model, as recalled) and the base oil's viscosity falls about exponentially with temperature
  (ASTM D341 / Walther viscosity-temperature relation; 3-5 % per K near 20-50 degC), so
  T_f = T_s + T_v exp(-k dT) with k = 0.02-0.035 /K; cold friction 4-10 % of the rated torque, its viscous share
  50-80 % (assumed); the joint temperature dT from its drive's heat as above, a cold start at the first pose.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import hardware as hwm
from sim2real_indep.context import Contribution


# ------------------------------------------------------------------------------------------ tracker warm-up
def warm_draw(ctx, hw, rng):
    return {"tau_s": rng.uniform(20, 60) * 60, "t_on_s": rng.uniform(0, 5) * 60,
            "d_angle_rad": rng.uniform(15, 50, 2) * 1e-6 * rng.choice([-1, 1], 2),
            "d_range_mm": rng.uniform(0.005, 0.02) * rng.choice([-1, 1])}


def warm_signal(p, ctx):
    """Share (P,) of the warm-up drift reached at each measurement."""
    t = ctx.session.time_s - ctx.session.time_s[0] + p["t_on_s"]
    return 1.0 - np.exp(-t / p["tau_s"])


def warm_parts(ctx, hw):
    """Displacement (3, P, 3) [mm, base frame] of the measured points per unit azimuth and elevation drift [rad]
    and per mm of distance drift."""
    R, t = hw["tracker"]["R"], hw["tracker"]["t"]
    p = ctx.target @ R.T + t                         # tracker frame [mm]
    r = np.linalg.norm(p, axis=1)
    rho = np.hypot(p[:, 0], p[:, 1])
    az, el = np.arctan2(p[:, 1], p[:, 0]), np.arctan2(p[:, 2], rho)
    e_az = np.c_[-np.sin(az), np.cos(az), np.zeros(len(p))]
    e_el = np.c_[-np.sin(el) * np.cos(az), -np.sin(el) * np.sin(az), np.cos(el)]
    parts = [rho[:, None] * e_az, r[:, None] * e_el, p / r[:, None]]
    return np.array([d @ R for d in parts])          # back to base axes: R^T d


def warm_apply(p, ctx, hw):
    amp = np.r_[p["d_angle_rad"], p["d_range_mm"]]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, warm_parts(ctx, hw)) * warm_signal(p, ctx)[:, None])


def warm_features(p, ctx, hw):
    return warm_parts(ctx, hw) * warm_signal(p, ctx)[None, :, None]


# --------------------------------------------------------------------------------------------- drive node
def _node_draw(ctx, hw, rng, joints):
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    ex_w = ct.drive_heat(ctx, hw, accel, duty, exercise_only=True)
    rise = rng.uniform(15.0, 35.0, len(joints))
    return {"joints": list(joints), "accel_s": accel, "duty": duty, "tau_s": rng.uniform(15, 40, len(joints)) * 60,
            "R_K_per_W": rise / np.maximum(ex_w[list(joints)], 1e-3)}


def drive_rise(p, ctx, hw):
    """Temperature rise (P, len(joints)) [K] of the drives of ``p['joints']`` at the measurements: one lumped node
    per drive heated by its losses over the gaps, moves and dwells (cold start)."""
    pw = ct.drive_heat(ctx, hw, p["accel_s"], p["duty"])
    dur = ct._segment_times(ctx.session)
    out = np.zeros((len(ctx.q), len(p["joints"])))
    for k, j in enumerate(p["joints"]):
        u, x, xs = pw[:, :, j].ravel() * p["R_K_per_W"][k], 0.0, np.zeros(len(dur))
        for i, (dt, ui) in enumerate(zip(dur, u)):
            x = ui + (x - ui) * np.exp(-dt / p["tau_s"][k])
            xs[i] = x
        out[:, k] = xs[2::3]
    return out


# ------------------------------------------------------------------------------------------- helical shift
def helix_draw(ctx, hw, rng):
    if ctx.chain.name == "ur10":
        return {"joints": []}
    joints = [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j >= 3]
    p = _node_draw(ctx, hw, rng, joints)
    m = len(joints)
    p["k_rad_per_K"] = (11.7e-6 * rng.uniform(100, 180, m) * np.tan(np.deg2rad(rng.uniform(20, 30, m)))
                        / rng.uniform(25, 50, m) * rng.choice([-1, 1], m))
    return p


def helix_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p["joints"]:
        dq[:, p["joints"]] = drive_rise(p, ctx, hw) * p["k_rad_per_K"]
    return Contribution(dq=dq)


def helix_features(p, ctx, hw):
    if not p["joints"]:
        return np.zeros((0, len(ctx.q), 3))
    T = drive_rise(p, ctx, hw)
    return np.array([ctx.joint_feature(j, T[:, k]) for k, j in enumerate(p["joints"])])


# --------------------------------------------------------------------------------------------- cold grease
def grease_draw(ctx, hw, rng):
    joints = [int(j) for j in np.flatnonzero(ctx.chain.revolute)]
    p = _node_draw(ctx, hw, rng, joints)
    T_cold = np.array([rng.uniform(0.04, 0.10) * hw["drives"][j]["T_rated"] for j in joints])
    visc = rng.uniform(0.5, 0.8, len(joints))
    p.update(T_static_Nm=T_cold * (1 - visc), T_visc_Nm=T_cold * visc, k_per_K=rng.uniform(0.02, 0.035))
    return p


def grease_signals(p, ctx, hw):
    """Per joint the wind-up torque shapes (2, P, len(joints)): -direction (static part) and -direction
    exp(-k dT) (viscous part)."""
    d = -ctx.session.direction[:, p["joints"]]
    return np.array([d, d * np.exp(-p["k_per_K"] * drive_rise(p, ctx, hw))])


def grease_apply(p, ctx, hw):
    s = grease_signals(p, ctx, hw)
    dq = np.zeros_like(ctx.q)
    for k, j in enumerate(p["joints"]):
        d = hw["drives"][j]
        dq[:, j] = hwm.torsion(d, p["T_static_Nm"][k] * s[0, :, k] + p["T_visc_Nm"][k] * s[1, :, k], False)
    return Contribution(dq=dq)


def grease_features(p, ctx, hw):
    s = grease_signals(p, ctx, hw)
    return np.array([ctx.joint_feature(j, s[i, :, k]) for k, j in enumerate(p["joints"]) for i in range(2)])
