"""Set K thermal effects (new physics, not in sets A-J): the backlash of an axis-1 pinion and ring-gear stage opening
as the housing between them warms; the read heads of output-side encoders drifting on their warming brackets; a
controller's thermal compensation that takes the links' growth from the drives' winding temperatures. Same protocol
as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* thermal backlash: the backlash of a gear pair changes with the centre distance, j = 2 tan(alpha_n) da, and a
  housing warmer than its gears, or of a larger expansion coefficient, moves the centre distance by alpha_h a dT_h
  (AGMA 2002-B88, *Tooth Thickness Specification and Measurement*, the change of backlash with temperature; ISO/TR
  10064-2 on backlash and centre distance, as recalled). Axis 1 driven through a pinion on a ring gear (set E's ring
  gear; pitch radius R 0.25-0.38 / 0.42-0.55 m, centre distance a 0.30-0.45 / 0.50-0.65 m on kr16_like /
  tool_changer), the pinion's housing on the base casting (aluminium 23e-6 / steel 11.7e-6 /K) warmed by the axis-1
  drive through one lumped node (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5; tau 20-60 min,
  8-20 K above the air under the production cycle, a cold start; the gears follow the air; assumed), the pair set at
  0.5-1.5 arcmin cold. Axis 1 carries no gravity torque, so its drag keeps it on the flank of its last motion: the
  output trails by b / 2 (Nordin & Gutman, Automatica 38, 2002). None on ur10 (strain-wave joints).
* read-head drift: an output-side encoder's read head sits on a bracket at h = 30-80 mm from its fixing; the bracket's
  thermal growth alpha h dT has a part tangential to the scale (the bracket at gamma to the tangent, |sin gamma|
  0.3-1), read as an angle alpha h dT sin(gamma) / R_e (HEIDENHAIN mounting instructions for modular angle encoders
  on the thermal stability of the scanning head's mounting, as recalled; Bryan, "International status of thermal
  error research", CIRP Annals 39(2), 1990). The controller holds the reading, so the joint is off by as much.
  Scale radii R_e 25-50 / 50-100 / 80-160 mm on ur10 / kr16_like / tool_changer; every joint of ur10 (its joints read
  their outputs), axes 1-3 of the others (secondary encoders, an accuracy option; assumed). The housing warms with
  its drive's heat (:func:`effects_c_thermal.drive_heat`) through one lumped node (tau 15-45 min, 15-30 K under the
  production cycle, a cold start; sessions with production periods between all blocks; assumed; first drawn with h
  20-60 mm, R_e 30-60 / 60-120 mm, 10-25 K and pauses between some blocks: absorbed or gains below 10 % in some trial
  draws, where the housings hardly warmed).
* compensation from winding temperatures: machine-tool controllers correct thermal growth from temperature sensors
  with gains identified at the steady state of a warm-up test (Bryan 1990; Mayr et al., "Thermal issues in machine
  tools", CIRP Annals 61(2), 2012; ISO 230-3 warm-up tests), and robot drives report their windings' temperatures;
  a correction alpha kappa dT_w of each link body, kappa = dT_l / dT_w at the production cycle's steady state. The
  winding follows its copper loss (:func:`copper_heat`; tau 2-6 min, 50-90 K under the production cycle), the link
  its drive's whole loss, copper and friction (tau 60-150 min, 10-25 K): the winding leads, so the arm is
  over-corrected while it warms and under-corrected while it cools, and the measurement blocks, holding torque with
  little motion, heat the winding more for the link's share than the production cycle did (assumed: the drive of the
  joint before each body heats it, the arm's expansion coefficient of :mod:`hardware`). The true structure: one
  column, the lags and kappa its shape. First drawn with both nodes on the whole loss (5-15 / 40-80 K, tau 30-90 /
  3-10 min) and a column per node and body: the set's ur10 case, split by time, extrapolated the twelve free columns
  badly (gain -83 %) and its kr16_like case gained 14 %.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_i_joint import _stack


def copper_heat(ctx, hw, accel_s, ex_duty):
    """The copper part of :func:`effects_c_thermal.drive_heat`: (P, 3, n) [W] per segment (gap, move, dwell) and the
    production cycle's (n,) -- P_cu,rated times the mean square torque over the rated torque squared (the same
    gravity and acceleration torques)."""
    s, tau = ctx.session, ctx.loads
    J = ct.inertia_about_joints(ctx)
    prev = np.vstack([tau[:1], tau[:-1]])
    out, ex = np.zeros((len(s.q), 3, ctx.chain.n)), np.zeros(ctx.chain.n)
    for j, d in enumerate(hw["drives"]):
        unit = 1.0 if ctx.chain.kinds[j] == "R" else 1e-3
        t_acc = J[:, j] * unit * s.speed[:, j] / accel_s[j]
        frac = np.where(s.move_s > 0, np.minimum(2 * accel_s[j] / np.maximum(s.move_s, 1e-9), 1.0), 0.0)
        ex_acc = J[:, j].mean() * unit * s.exercise_speed[j] / accel_s[j]
        cu = d["P_cu_rated_W"] / d["T_rated"] ** 2
        ex[j] = cu * ((tau[:, j] ** 2).mean() + ex_duty[j] * ex_acc ** 2)
        out[:, 0, j] = np.where(s.gap_s > 0, ex[j], 0.0)
        out[:, 1, j] = cu * ((prev[:, j] ** 2 + tau[:, j] ** 2) / 2 + frac * t_acc ** 2)
        out[:, 2, j] = cu * tau[:, j] ** 2
    return out, ex


def node_rise(ctx, hw, joints, rise_K, tau_s, accel_s, duty, copper_only=False):
    """Temperature rise (P, m) [K] at the measurements of one lumped node per drive in ``joints``, heated by that
    drive's losses (:func:`effects_c_thermal.drive_heat`; ``copper_only``: its copper loss alone, :func:`copper_heat`)
    scaled to ``rise_K`` (m,) at the production cycle's steady state, time constants ``tau_s`` (m,); a cold start; exact
    for the heat held over each segment."""
    if copper_only:
        heat, ex_w = copper_heat(ctx, hw, accel_s, duty)
        heat, ex_w = heat[:, :, joints], ex_w[joints]
    else:
        heat = ct.drive_heat(ctx, hw, accel_s, duty)[:, :, joints]
        ex_w = ct.drive_heat(ctx, hw, accel_s, duty, exercise_only=True)[joints]
    u = (heat * (np.asarray(rise_K) / ex_w)).reshape(-1, len(joints))
    x, out = np.zeros(len(joints)), np.zeros(u.shape)
    for i, (dt, ui) in enumerate(zip(ct._segment_times(ctx.session), u)):
        x = ui + (x - ui) * np.exp(-dt / np.asarray(tau_s))
        out[i] = x
    return out[2::3]


def _heat_params(ctx, rng):
    n = ctx.chain.n
    return {"accel_s": rng.uniform(0.2, 0.6, n), "duty": rng.uniform(0.2, 0.5, n)}


# -------------------------------------------------------------------------------------------- thermal backlash
#: per arm: housing CTE [1/K], centre distance a [m], ring pitch radius R [m] (assumed)
LASH = {"kr16_like": (23e-6, (0.30, 0.45), (0.25, 0.38)), "tool_changer": (11.7e-6, (0.50, 0.65), (0.42, 0.55))}
ALPHA_N = np.deg2rad(20.0)


def lash_draw(ctx, hw, rng):
    if ctx.chain.name not in LASH:
        return {}
    cte, a, R = LASH[ctx.chain.name]
    a, R = rng.uniform(*a), rng.uniform(*R)
    return {"joint": 0, "b0_rad": rng.uniform(0.5, 1.5) * ph.ARCMIN, "rise_K": rng.uniform(8, 20),
            "tau_s": rng.uniform(20, 60) * 60, "k_rad_per_K": 2 * np.tan(ALPHA_N) * cte * a / R,
            **_heat_params(ctx, rng)}


def lash_signals(p, ctx, hw):
    """(2, P): the flank (-1 trailing the last motion) alone and times the housing's rise [K]."""
    j = p["joint"]
    flank = -ctx.session.direction[:, j]
    dT = node_rise(ctx, hw, [j], [p["rise_K"]], [p["tau_s"]], p["accel_s"], p["duty"])[:, 0]
    return np.array([flank, flank * dT])


def lash_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = np.array([p["b0_rad"], p["k_rad_per_K"]]) / 2 @ lash_signals(p, ctx, hw)
    return Contribution(dq=dq)


def lash_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], s) for s in lash_signals(p, ctx, hw)] if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------- read-head drift
#: per arm: scale radius R_e [m], the joints read at their outputs (assumed)
READ_HEAD = {"ur10": ((0.025, 0.05), 6), "kr16_like": ((0.05, 0.10), 3), "tool_changer": ((0.08, 0.16), 3)}


def head_draw(ctx, hw, rng):
    R, n = READ_HEAD[ctx.chain.name]
    joints = [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j < n]
    m = len(joints)
    k = (hw["material"]["cte"] * rng.uniform(0.03, 0.08, m) * rng.uniform(0.3, 1.0, m) * rng.choice([-1, 1], m)
         / rng.uniform(*R, m))
    return {"joints": joints, "k_rad_per_K": k, "rise_K": rng.uniform(15, 30, m), "tau_s": rng.uniform(15, 45, m) * 60,
            **_heat_params(ctx, rng)}


def head_rise(p, ctx, hw):
    return node_rise(ctx, hw, p["joints"], p["rise_K"], p["tau_s"], p["accel_s"], p["duty"])


def head_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = head_rise(p, ctx, hw) * p["k_rad_per_K"]
    return Contribution(dq=dq)


def head_features(p, ctx, hw):
    dT = head_rise(p, ctx, hw)
    return _stack([ctx.joint_feature(j, dT[:, i]) for i, j in enumerate(p["joints"])], len(ctx.q))


# --------------------------------------------------------------------------------- compensation from windings
def comp_draw(ctx, hw, rng):
    ch = ctx.chain
    bodies = [int(b) for b in sorted(set(ch.link_body)) if b >= 1 and np.abs(ch.links[ch.link_body == b]).max() > 1.0]
    m = len(bodies)
    dT_w, dT_l = rng.uniform(50, 90, m), rng.uniform(10, 25, m)
    return {"bodies": bodies, "cte": hw["material"]["cte"], "kappa": dT_l / dT_w, "rise_w": dT_w, "rise_l": dT_l,
            "tau_w": rng.uniform(2, 6, m) * 60, "tau_l": rng.uniform(60, 150, m) * 60, **_heat_params(ctx, rng)}


def comp_rises(p, ctx, hw):
    """Winding and link rises (2, P, bodies) [K], each body heated by the drive of the joint before it."""
    joints = [b - 1 for b in p["bodies"]]
    return np.array([node_rise(ctx, hw, joints, p[f"rise_{k}"], p[f"tau_{k}"], p["accel_s"], p["duty"], k == "w")
                     for k in ("w", "l")])


def comp_strain(p, ctx, hw):
    """Net thermal strain (P, bodies) of each body's links per unit expansion coefficient [K]: the link's rise minus
    the correction kappa times the winding's."""
    dTw, dTl = comp_rises(p, ctx, hw)
    return dTl - p["kappa"] * dTw


def comp_apply(p, ctx, hw):
    net = comp_strain(p, ctx, hw)
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    for i, b in enumerate(p["bodies"]):
        strain[:, ctx.chain.link_body == b] += p["cte"] * net[:, i:i + 1]
    return Contribution(strain=strain)


def comp_features(p, ctx, hw):
    """One column: the target's displacement per unit expansion coefficient (kappa and the lags are the shape)."""
    net = comp_strain(p, ctx, hw)
    return sum(ctx.link_scale_feature(ctx.chain.link_body == b) * net[:, i:i + 1]
               for i, b in enumerate(p["bodies"]))[None]
