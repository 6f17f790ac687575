"""Set I joint effects (new physics, not in sets A-H): an arm installed on an inclined base, so that gravity acts
obliquely in its base frame; a hydropneumatic balancer on axis 2 whose gas charge heats on compression and relaxes
to the wall temperature during the dwell; lost motion whose flank after a stop is chosen by the load's inertia
(overrun); the axial play of a non-preloaded ball-screw nut on a prismatic stage, the flank set by the axial
gravity force against a guide friction that grows with the transverse loads; the runout of an idler bevel gear in
a coupled wrist train, which turns with the train's angle; the transmission error of the reducer of a
parallelogram-driven axis 3, which turns with the forearm's absolute angle. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* inclined base: robot makers permit floor, wall, ceiling and inclined installation (KUKA KR 16 / UR10 data sheets,
  "mounting position: any angle", as recalled); the joints then carry the static loads of gravity acting at the
  mounting angle in the base frame (statics of point masses: Craig, *Introduction to Robotics*, ch. 5), axis 1
  included, and twist through the linear gear stiffness of :mod:`hardware`. Angles 8-20 deg (ur10, kr16_like) and
  4-12 deg (tool_changer; a tool changer in a tunnel-boring machine on a gradient), any azimuth (assumed).
* balancer charge relaxation: a gas spring's charge heats on compression and cools back to the wall temperature
  with a thermal time constant (Pourmovahed & Otis, "An experimental thermal time-constant correlation for
  hydraulic accumulators", J. Dyn. Syst. Meas. Control 112(1), 1990: tau of a few to tens of seconds; Otis &
  Pourmovahed, J. Dyn. Syst. Meas. Control 107, 1985, the energy equation of the charge). Linearised energy
  balance of an ideal gas with Newtonian heat transfer: d(theta)/dt = -(gamma - 1) d(ln V)/dt - theta / tau_th,
  theta = T / T_wall - 1, p = p_iso (1 + theta); ln V taken linear in time over each move (exact first-order
  solution), the charge back at the wall temperature after production periods. Nitrogen gamma = 1.4, tau_th
  8-40 s, volume ratio over the session's stroke 1.3-1.8, the isothermal force carrying 50-90 % of the mean gravity
  torque of axis 2 (assumed); cylinder between a pivot at r1 on the proximal body and a rod eye at r2 on the upper
  arm: L^2 = r1^2 + r2^2 - 2 r1 r2 cos(psi), moment arm r1 r2 sin(psi) / L (law of cosines). The heavy arms only
  (tool_changer, kr16_like; none on ur10). Every joint twists with its linear gear stiffness under gravity, axis 2
  under gravity plus the balancer.
* overrun lash: while a joint moves, the motor drives the load on one tooth flank (the output trails by b / 2);
  at the stop the motor decelerates the output through the gear, and if the load's inertia torque J alpha plus its
  gravity torque along the motion beats the output-side friction, the output leaves the driving flank, crosses the
  gap and is stopped on the other one (it then leads by b / 2) -- the impact / dead-zone phases of backlash
  (Nordin & Gutman, "Controlling mechanical systems with backlash -- a survey", Automatica 38, 2002); a gravity
  torque above the friction then holds it on its gravity flank (:func:`physics.backlash_offset`). J of the point
  masses beyond the joint (:func:`effects_c_thermal.inertia_about_joints`), the deceleration of the session's
  trapezoidal moves (0.5 s ramps), output-side friction 2-6 % of the rated torque (as set E's friction wind-up),
  lost motion 0.3-1 arcmin on strain-wave joints, 0.5-1.5 arcmin on cycloid joints (worn; assumed).
* ball-screw nut play: a single nut without preload has an axial clearance (THK / NSK ball-screw catalogues:
  rolled screws up to 0.05-0.2 mm, as recalled; here 0.1-0.3 mm, worn); the ram rests on the flank the axial
  gravity force pushes it to when that force beats the friction of its guide (LM blocks: mu = 0.003-0.006 of the
  block loads plus 20-80 N of seals, THK catalogue values as recalled); the block loads follow from the ram's
  transverse force and moment on two blocks 0.25-0.45 m apart (statics). Below that the ram stays on the flank of
  its last motion (trailing). The prismatic stage of tool_changer (none on the others).
* wrist-train idler: in a wrist whose motors sit in the forearm, an intermediate (idler) bevel gear of a joint's
  train turns relative to its housing by i_g (q_j + sum_k c_jk q_k) (the coupled actuation of Craig, ch. 8, as set
  H's wrist coupling); its eccentricity e (half the runout; ISO 17485 / AGMA 2009 bevel accuracy: runout tolerances
  of some 15-60 um for gears of 30-60 mm in grades 9-10, as recalled) gives a transmission error e / R once per idler
  turn (and a second harmonic of 10-30 % of it) at the joint, divided by the ratio after it: 1.5-3.5 arcmin at the
  joint (assumed). The coupled wrists (kr16_like axes 5-6; tool_changer axis 6, whose small lever to the target
  leaves it weak there; none on ur10).
* parallelogram axis 3: the reducer of axis 3 sits on the base side and turns the forearm through a link bar, so it
  turns with the forearm's absolute angle q2 + q3 (set E's parallelogram); its transmission error (the RV spectrum
  of set C: crank order Z_p, 2 Z_p, once per turn and the input order R; Blanche & Yang, ASME JMTAD 111(3), 1989)
  repeats in q2 + q3, not in q3. 1-2 arcmin peak to peak (a worn reducer; assumed). tool_changer and kr16_like.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import effects_g_joint as gj
from sim2real_indep import effects_h_joint as hj
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

RAMP_S = 0.5  # the session's acceleration / deceleration ramps [s] (session.make_session)


def _stack(cols, P):
    return np.array(cols) if cols else np.zeros((0, P, 3))


def _torsion_all(ctx, hw, loads):
    """Linear gear torsion (P, n) [rad / mm] of every joint under ``loads`` (P, n)."""
    return np.array([hwm.torsion(d, loads[:, j], False) for j, d in enumerate(hw["drives"])]).T


def _load_cols(ctx, loads):
    return [ctx.joint_feature(j, loads[:, j]) for j in range(ctx.chain.n) if np.abs(loads[:, j]).max() > 1e-9]


# ------------------------------------------------------------------------------------------- inclined base
TILT_DEG = {"ur10": (8.0, 20.0), "kr16_like": (8.0, 20.0), "tool_changer": (4.0, 12.0)}


def tilt_draw(ctx, hw, rng):
    lo, hi = TILT_DEG[ctx.chain.name]
    return {"tilt_rad": np.deg2rad(rng.uniform(lo, hi)), "azimuth_rad": rng.uniform(0, 2 * np.pi)}


def tilt_gravity(p):
    """Unit gravity (3,) in the base frame of a base inclined by ``tilt_rad`` towards ``azimuth_rad``."""
    t, a = p["tilt_rad"], p["azimuth_rad"]
    return -np.array([np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)])


def tilt_loads(p, ctx):
    """Static joint loads (P, n) [N m / N] of the masses and payload under the inclined gravity."""
    m, pos, body = ctx.mass_state
    return kin.gravity_loads(ctx.chain, ctx.q, m, pos, body, gravity=tilt_gravity(p))


def tilt_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, tilt_loads(p, ctx)))


def tilt_features(p, ctx, hw):
    return _stack(_load_cols(ctx, tilt_loads(p, ctx)), len(ctx.q))


# ------------------------------------------------------------------------------------ balancer relaxation
#: pivot radius on the proximal body r1 and rod-eye radius on the upper arm r2 [m] (assumed)
BALANCER_M = {"kr16_like": ((0.30, 0.45), (0.15, 0.25)), "tool_changer": ((0.50, 0.80), (0.25, 0.40))}


def bal_draw(ctx, hw, rng):
    if ctx.chain.name not in BALANCER_M:
        return {}
    (a0, a1), (b0, b1) = BALANCER_M[ctx.chain.name]
    q2, tau2 = ctx.q[:, 1], ctx.loads[:, 1]
    p = {"r1": rng.uniform(a0, a1), "r2": rng.uniform(b0, b1), "psi_mid": np.deg2rad(rng.uniform(80, 110)),
         "q_mid": 0.5 * (q2.min() + q2.max()), "sign": -1.0 if tau2.mean() > 0 else 1.0, "gamma": 1.4,
         "rho": rng.uniform(1.3, 1.8), "tau_th_s": rng.uniform(8, 40)}
    L, _ = bal_geometry(p, q2)
    p.update(L_lo=L.min(), L_hi=L.max())
    _, a = bal_geometry(p, q2)
    p["F0_N"] = rng.uniform(0.5, 0.9) * abs(tau2.mean()) / np.mean(a / bal_volume(p, L))
    return p


def bal_geometry(p, q2):
    """Cylinder length L (P,) [m] and moment arm dL/dpsi (P,) [m] at joint-2 angles ``q2`` [rad]."""
    psi = p["psi_mid"] + p["sign"] * (q2 - p["q_mid"])
    L = np.sqrt(p["r1"] ** 2 + p["r2"] ** 2 - 2 * p["r1"] * p["r2"] * np.cos(psi))
    return L, p["r1"] * p["r2"] * np.sin(psi) / L


def bal_volume(p, L):
    """Gas volume (P,) relative to the smallest of the session (the ratio ``rho`` over its stroke)."""
    return 1.0 + (p["rho"] - 1.0) * (L - p["L_lo"]) / max(p["L_hi"] - p["L_lo"], 1e-12)


def bal_theta(p, ctx):
    """Relative gas temperature theta (P,) at the measurements: exact first-order response to ln V changing
    linearly over each move, decaying over dwells and pauses, reset to the wall temperature by production."""
    s = ctx.session
    lnv = np.log(bal_volume(p, bal_geometry(p, ctx.q[:, 1])[0]))
    tau, g1 = p["tau_th_s"], p["gamma"] - 1.0
    th, out = 0.0, np.zeros(len(lnv))
    for k in range(len(lnv)):
        if k > 0:
            th = 0.0 if s.gap_s[k] > 0 else th * np.exp(-abs(s.gap_s[k]) / tau)
            T = s.move_s[k]
            if T > 0:
                e = np.exp(-T / tau)
                th = th * e - g1 * (lnv[k] - lnv[k - 1]) / T * tau * (1 - e)
        th *= np.exp(-s.dwell_s[k] / tau)
        out[k] = th
    return out


def bal_torque_shapes(p, ctx):
    """Balancer torque on axis 2 per unit F0 (P,): isothermal part and its relaxing (theta) part."""
    L, a = bal_geometry(p, ctx.q[:, 1])
    iso = p["sign"] * a / bal_volume(p, L)
    return iso, iso * bal_theta(p, ctx)


def bal_apply(p, ctx, hw):
    if not p:
        return Contribution()
    loads = ctx.loads.copy()
    iso, rel = bal_torque_shapes(p, ctx)
    loads[:, 1] += p["F0_N"] * (iso + rel)
    return Contribution(dq=_torsion_all(ctx, hw, loads))


def bal_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return _stack(_load_cols(ctx, ctx.loads) + [ctx.joint_feature(1, s) for s in bal_torque_shapes(p, ctx)],
                  len(ctx.q))


# ------------------------------------------------------------------------------------------- overrun lash
def overrun_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        d = hw["drives"][j]
        b = rng.uniform(0.3, 1.0) if d["kind"] == "HD" else rng.uniform(0.5, 1.5)
        out.append({"joint": int(j), "b_rad": b * ph.ARCMIN, "T_f_Nm": rng.uniform(0.02, 0.06) * d["T_rated"]})
    return out


def stop_deceleration(session):
    """Deceleration (P, n) [rad/s^2 or mm/s^2] at the end of the move into each pose: trapezoidal moves with ramps
    of RAMP_S at each end cover |dq| = v_peak (move - RAMP_S)."""
    dq = np.abs(np.diff(np.vstack([session.q[:1], session.q]), axis=0))
    cruise = np.maximum(session.move_s - RAMP_S, RAMP_S)[:, None]
    return np.where(session.move_s[:, None] > 0, dq / cruise / RAMP_S, 0.0)


def overrun_flank(g, ctx, J=None, alpha=None):
    """Flank (P,) +-1: the gravity torque's above the friction; else leading the last motion (+d) where the stop
    threw the output across the gap (J alpha + d tau > T_f), trailing it (-d) otherwise."""
    J = ct.inertia_about_joints(ctx) if J is None else J
    alpha = stop_deceleration(ctx.session) if alpha is None else alpha
    j, d, tau = g["joint"], ctx.session.direction[:, g["joint"]], ctx.loads[:, g["joint"]]
    over = J[:, j] * alpha[:, j] + d * tau > g["T_f_Nm"]
    return np.where(np.abs(tau) > g["T_f_Nm"], np.sign(tau), np.where(over, d, -d))


def overrun_apply(p, ctx, hw):
    J, alpha = ct.inertia_about_joints(ctx), stop_deceleration(ctx.session)
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["b_rad"] / 2 * overrun_flank(g, ctx, J, alpha)
    return Contribution(dq=dq)


def overrun_features(p, ctx, hw):
    J, alpha = ct.inertia_about_joints(ctx), stop_deceleration(ctx.session)
    return _stack([ctx.joint_feature(g["joint"], overrun_flank(g, ctx, J, alpha)) for g in p], len(ctx.q))


# ----------------------------------------------------------------------------------------- ball-screw nut
def nut_draw(ctx, hw, rng):
    return [{"joint": int(j), "c_mm": rng.uniform(0.1, 0.3), "mu": rng.uniform(0.003, 0.006),
             "F_seal_N": rng.uniform(20, 80), "s_m": rng.uniform(0.25, 0.45)}
            for j in np.flatnonzero(~ctx.chain.revolute)]


def guide_friction(g, ctx):
    """Friction (P,) [N] of the ram's guide: seals plus mu times the two blocks' loads |F_perp| + 2 |M_perp| / s
    (the ram's transverse force and moment about the front block, at the joint's axis point)."""
    F, M, w, _ = gj.joint_wrench(ctx)
    j = g["joint"]
    Fp = F[:, j] - np.einsum("pi,pi->p", F[:, j], w[:, j])[:, None] * w[:, j]
    Mp = M[:, j] - np.einsum("pi,pi->p", M[:, j], w[:, j])[:, None] * w[:, j]
    return g["F_seal_N"] + g["mu"] * (np.linalg.norm(Fp, axis=1) + 2 * np.linalg.norm(Mp, axis=1) / g["s_m"])


def nut_flank(g, ctx):
    """Flank (P,) +-1 of the nut: the axial gravity force's above the guide friction, else trailing the last
    motion."""
    return ph.backlash_offset(ctx.session.direction[:, g["joint"]], ctx.loads[:, g["joint"]],
                              guide_friction(g, ctx), 2.0, 0.0)


def nut_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["c_mm"] / 2 * nut_flank(g, ctx)
    return Contribution(dq=dq)


def nut_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], nut_flank(g, ctx)) for g in p], len(ctx.q))


# ------------------------------------------------------------------------------------- wrist-train idler
def _tooth_ratio(rng):
    return int(rng.integers(17, 61)) / int(rng.integers(17, 61))


def idler_draw(ctx, hw, rng):
    out = {}
    for j, k in hj.wrist_pairs(ctx.chain):
        g = out.setdefault(j, {"joint": j, "c": {}, "i_g": rng.uniform(1.0, 2.5),
                               "amp_rad": rng.uniform(1.5, 3.5) * ph.ARCMIN * np.array([1.0, rng.uniform(0.1, 0.3)]),
                               "phase": rng.uniform(0, 2 * np.pi, 2)})
        g["c"][k] = _tooth_ratio(rng) * rng.choice([-1, 1])
    return list(out.values())


def idler_angle(g, q):
    """The idler's turn (P,) [rad] relative to its housing: i_g times the train angle q_j + sum_k c_jk q_k."""
    return g["i_g"] * (q[:, g["joint"]] + sum(c * q[:, k] for k, c in g["c"].items()))


def idler_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        phi = idler_angle(g, ctx.q)
        dq[:, g["joint"]] = sum(a * np.sin(h * phi + f) for h, a, f in zip((1, 2), g["amp_rad"], g["phase"]))
    return Contribution(dq=dq)


def idler_features(p, ctx, hw):
    cols = []
    for g in p:
        phi = idler_angle(g, ctx.q)
        cols += [ctx.joint_feature(g["joint"], f(h * phi)) for h in (1, 2) for f in (np.sin, np.cos)]
    return _stack(cols, len(ctx.q))


# ------------------------------------------------------------------------------------- parallelogram axis 3
#: arms given a parallelogram-driven axis 3 with a cycloid reducer (axes 2 and 3 parallel)
PARA_ARMS = {"tool_changer", "kr16_like"}


def para_draw(ctx, hw, rng):
    if ctx.chain.name not in PARA_ARMS:
        return {}
    zp = int(rng.choice([30, 36, 40]))
    ratio = 1 + rng.uniform(2.5, 5.0) * zp
    w = np.array([rng.uniform(0.4, 0.6), rng.uniform(0.1, 0.2), rng.uniform(0.1, 0.3), rng.uniform(0.05, 0.15)])
    return {"orders": np.array([zp, 2 * zp, 1, ratio]), "amp": rng.uniform(1.0, 2.0) * ph.ARCMIN / 2 * w / w.sum(),
            "phase": rng.uniform(0, 2 * np.pi, 4)}


def para_angle(q):
    """The axis-3 reducer's turn (P,) [rad]: the forearm's absolute angle q2 + q3."""
    return q[:, 1] + q[:, 2]


def para_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        psi = para_angle(ctx.q)
        dq[:, 2] = np.sum(p["amp"] * np.sin(np.multiply.outer(psi, p["orders"]) + p["phase"]), axis=1)
    return Contribution(dq=dq)


def para_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    psi = para_angle(ctx.q)
    return np.array([ctx.joint_feature(2, f(k * psi)) for k in p["orders"] for f in (np.sin, np.cos)])
