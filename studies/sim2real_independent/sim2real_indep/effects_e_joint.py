"""Set E joint effects (new physics, not in sets A-D): the coupled compliance of a parallelogram-driven axis 3;
a gear stiffness that varies along the output turn; output-side friction that winds the compliant gear and stays
locked after each stop; an anti-backlash (scissor) gear whose spring preload the load overcomes in one direction;
the sub-divisional error of an off-axis magnetic ring encoder; the cumulative pitch error of an open ring-gear
stage on axis 1. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* parallelogram drive: axis 3's gear sits on the base side and turns the forearm through a link bar, so it sets
  the forearm's absolute angle q2 + q3 (palletising and heavy-duty arms: ABB IRB 460 / 660, KUKA KR QUANTEC PA,
  FANUC M-410). Virtual work with the shaft map s = G q gives the joint-space compliance G^-1 diag(c) G^-T: gear 2
  carries tau2 - tau3, gear 3 tau3 (Craig, *Introduction to Robotics*, ch. 5 statics and ch. 8 actuation
  schemes; off-diagonal joint stiffness identified on real arms: Alici & Shirinzadeh, IEEE Trans. Robot. 21(4),
  2005). The bar's axial compliance adds 10-40 % to gear 3's (assumed).
* stiffness varying along the turn: the mesh stiffness of a gear pair varies with the mesh position (ISO 6336-1
  mesh stiffness; time-varying mesh stiffness, Kahraman & Singh, J. Sound Vib. 146(1), 1991); in a cycloid
  drive the number of lobes in contact changes with the crank angle (Blanche & Yang, ASME JMTAD 111(3), 1989),
  in a strain-wave gear with the wave generator (twice per its turn); an eccentric assembly modulates the contact
  once per output turn. C(theta) = C0 (1 + e1 cos(theta + p1) + ek cos(k theta + pk)), e1 0.1-0.3, ek 0.05-0.2
  (assumed).
* friction wind-up: friction at the output side of the gear's compliance (output bearing, seals) opposes the
  motion, so the gear is wound by T_f / K while moving; after the stop static friction holds the wind-up (it is
  below the breakaway torque): the output trails by C T_f, against the last motion. Crossed-roller bearing
  friction grows with the tilting moment and the loads, M_R = mu (2.2 M_k + d_M / 2 (F_a + 2.2 F_r)) (after the
  INA / Schaeffler catalogue formula for crossed-roller bearings, as recalled; mu = 0.003-0.006); seal and
  remaining output-side friction 2-6 % of the rated torque (assumed).
* scissor gear: an anti-backlash split gear holds both flanks with a spring; a load against the spring half
  beyond its preload T_p turns the output through the backlash b at the spring rate until the solid half's
  flank is reached; loads the other way are carried by the solid half (Michalec, *Precision Gearing: Theory and
  Practice*, 1966, anti-backlash gears). Here a spring that does not cover the session's loads (worn or
  undersized): T_p 20-60 % of the largest load against it, b 1-4 arcmin taken up over 30-100 % of the rest.
* magnetic ring encoder: the sub-divisional (interpolation) error repeats with each signal period: an offset of
  the sine / cosine signals gives one cycle, an amplitude or phase mismatch two cycles per period (HEIDENHAIN,
  "Angle Encoders" brochure, interpolation error; RLS / Renishaw magnetic ring data sheets: pole pitch 1-5 mm).
  P = pi D / pitch periods per turn on a ring of D = 60-150 mm; 1-6 um on the ring each (assumed).
* ring gear: a pinion (15-25 teeth) on a large ring gear (axis 1 of heavy arms, positioners): the cumulative
  pitch deviation F_p of ISO 1328-1 (its tolerance formula, classes 7-9 of a cut, unground ring) is a
  smooth periodic curve, modelled by the harmonics 1-10 of the output turn with amplitudes ~k^-1.5 (transmission
  error spectra: Smith, *Gear Noise and Vibration*, 2003); the pinion's runout F_r 10-25 um repeats Z / z times,
  the single pitch deviation 3-8 um at the tooth order Z.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_joint as ej
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


def _compliance(drive):
    """Linear output-referred compliance of a drive [rad/N m or mm/N]."""
    return hwm.torsion(drive, 1.0, False)


def _harmonic_cols(ctx, j, orders):
    th = ctx.q[:, j]
    return [c for f in orders for c in (ctx.joint_feature(j, np.sin(f * th)), ctx.joint_feature(j, np.cos(f * th)))]


def _harmonic_dq(params, ctx, sign=1.0):
    dq = np.zeros_like(ctx.q)
    for g in params:
        th = ctx.q[:, g["joint"]]
        dq[:, g["joint"]] += sign * (g["amp"] * np.sin(np.multiply.outer(th, g["orders"]) + g["phase"])).sum(axis=1)
    return dq


# ------------------------------------------------------------------------------------- parallelogram drive
def para_draw(ctx, hw, rng):
    """Joints 2 and 3 (indices 1, 2), parallel axes; ``sgn`` +1 if they point the same way."""
    sgn = float(np.sign(ctx.chain.axes[1] @ ctx.chain.axes[2]) or 1.0)
    return {"sgn": sgn, "bar": rng.uniform(0.1, 0.4)}


def para_shaft_torques(p, ctx):
    """Torques on gear 2 and gear 3 (P,), (P,) [N m]: tau_s = G^-T tau with s2 = q2, s3 = sgn q2 + q3."""
    tau = ctx.loads
    return tau[:, 1] - p["sgn"] * tau[:, 2], tau[:, 2]


def para_apply(p, ctx, hw):
    dq = np.array([hwm.torsion(d, ctx.loads[:, j], False) for j, d in enumerate(hw["drives"])]).T
    t2, t3 = para_shaft_torques(p, ctx)
    ds2 = hwm.torsion(hw["drives"][1], t2, False)
    ds3 = hwm.torsion(hw["drives"][2], t3, False) * (1 + p["bar"])
    dq[:, 1], dq[:, 2] = ds2, ds3 - p["sgn"] * ds2          # dq = G^-1 ds
    return Contribution(dq=dq)


def para_features(p, ctx, hw):
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n) if j not in (1, 2)]
    t2, t3 = para_shaft_torques(p, ctx)
    cols.append(ctx.joint_feature(1, t2) - p["sgn"] * ctx.joint_feature(2, t2))
    cols.append(ctx.joint_feature(2, t3))
    return np.array(cols)


# ---------------------------------------------------------------------------- stiffness varying along the turn
def varstiff_draw(ctx, hw, rng):
    out = []
    for j, d in enumerate(hw["drives"]):
        if not ctx.chain.revolute[j]:
            continue
        k = 2 * int(rng.choice([80, 100, 120, 160])) if d["kind"] == "HD" else int(rng.choice([30, 36, 40]))
        out.append({"joint": j, "k": float(k), "e": np.array([rng.uniform(0.1, 0.3), rng.uniform(0.05, 0.2)]),
                    "phase": rng.uniform(0, 2 * np.pi, 2)})
    return out


def _varstiff_mod(v, ctx):
    th = ctx.q[:, v["joint"]]
    return 1 + v["e"][0] * np.cos(th + v["phase"][0]) + v["e"][1] * np.cos(v["k"] * th + v["phase"][1])


def varstiff_apply(p, ctx, hw):
    dq = np.array([hwm.torsion(d, ctx.loads[:, j], False) for j, d in enumerate(hw["drives"])]).T
    for v in p:
        dq[:, v["joint"]] *= _varstiff_mod(v, ctx)
    return Contribution(dq=dq)


def varstiff_features(p, ctx, hw):
    mod = {v["joint"]: v for v in p}
    cols = []
    for j in range(ctx.chain.n):
        tau = ctx.loads[:, j]
        cols.append(ctx.joint_feature(j, tau))
        if j in mod:
            th, k = ctx.q[:, j], mod[j]["k"]
            cols += [ctx.joint_feature(j, tau * s) for s in (np.cos(th), np.sin(th), np.cos(k * th), np.sin(k * th))]
    return np.array(cols)


# ------------------------------------------------------------------------------------------- friction wind-up
#: bearing pitch diameter range per arm [m] (assumed from the gear sizes)
BEARING_DM = {"ur10": (0.06, 0.12), "kr16_like": (0.12, 0.25), "tool_changer": (0.2, 0.35)}


def windup_draw(ctx, hw, rng):
    return [{"joint": int(j), "mu": rng.uniform(0.003, 0.006), "d_M": rng.uniform(*BEARING_DM[ctx.chain.name]),
             "T0": rng.uniform(0.02, 0.06) * hw["drives"][j]["T_rated"]} for j in np.flatnonzero(ctx.chain.revolute)]


def bearing_load_term(w, ctx):
    """2.2 M_k + d_M / 2 (F_a + 2.2 F_r) (P,) [N m] of joint w["joint"]'s output bearing under gravity."""
    j = w["joint"]
    m, pos, body = ctx.mass_state
    F = m[..., None] * kin.G * np.array([0, 0, -1.0])
    ax, c = kin.joint_frames(ctx.chain, ctx.q)
    on = body >= j + 1
    M = np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F[:, on]).sum(axis=1)
    Ft = F[:, on].sum(axis=1)
    a = ax[:, j]
    Mk = np.linalg.norm(M - np.sum(M * a, axis=1, keepdims=True) * a, axis=1)
    Fa = np.abs(np.sum(Ft * a, axis=1))
    Fr = np.linalg.norm(Ft - np.sum(Ft * a, axis=1, keepdims=True) * a, axis=1)
    return 2.2 * Mk + w["d_M"] / 2 * (Fa + 2.2 * Fr)


def windup_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for w in p:
        j = w["joint"]
        Tf = w["T0"] + w["mu"] * bearing_load_term(w, ctx)
        dq[:, j] = -ctx.session.direction[:, j] * _compliance(hw["drives"][j]) * Tf
    return Contribution(dq=dq)


def windup_features(p, ctx, hw):
    cols = []
    for w in p:
        j, d = w["joint"], ctx.session.direction[:, w["joint"]]
        cols += [ctx.joint_feature(j, -d), ctx.joint_feature(j, -d * bearing_load_term(w, ctx))]
    return np.array(cols)


# ---------------------------------------------------------------------------------------------- scissor gear
def scissor_draw(ctx, hw, rng):
    """The wrist joints (revolute, index >= 3) whose gravity load reaches 1 N m; spring side +-1."""
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        tau = ctx.loads[:, j]
        if j < 3 or np.abs(tau).max() < 1.0:
            continue
        s = float(rng.choice([-1.0, 1.0]))
        if (s * tau).max() < 0.3 * np.abs(tau).max():
            s = -s
        top = (s * tau).max()
        Tp = rng.uniform(0.2, 0.6) * top
        out.append({"joint": int(j), "side": s, "T_p": Tp, "span": rng.uniform(0.3, 1.0) * (top - Tp),
                    "b": rng.uniform(1.0, 4.0) * ph.ARCMIN})
    return out


def scissor_signal(g, ctx):
    """side * clip(side tau - T_p, 0, span) (P,) [N m]: the load taken by the yielding spring."""
    tau = ctx.loads[:, g["joint"]]
    return g["side"] * np.clip(g["side"] * tau - g["T_p"], 0.0, g["span"])


def scissor_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["b"] / g["span"] * scissor_signal(g, ctx)
    return Contribution(dq=dq)


def scissor_features(p, ctx, hw):
    return np.array([ctx.joint_feature(g["joint"], scissor_signal(g, ctx)) for g in p])


# -------------------------------------------------------------------------------------- magnetic ring encoder
def magring_draw(ctx, hw, rng):
    out = []
    for j in ej._joints(ctx, rng, 2, 4):
        pitch = float(rng.choice([1.0, 2.0, 5.0]))
        P = int(round(np.pi * rng.uniform(60, 150) / pitch))
        R = P * pitch / (2 * np.pi)                                   # ring radius [mm]
        amp = rng.uniform(1.0, 6.0, 2) * 1e-3 / R                     # [rad]
        out.append({"joint": int(j), "periods": P, "pitch_mm": pitch, "orders": np.array([P, 2 * P], float),
                    "amp": amp, "phase": rng.uniform(0, 2 * np.pi, 2)})
    return out


def magring_apply(p, ctx, hw):  # the controller servoes the reading: the true angle is off by minus its error
    return Contribution(dq=_harmonic_dq(p, ctx, -1.0))


def magring_features(p, ctx, hw):
    return np.array([c for g in p for c in _harmonic_cols(ctx, g["joint"], g["orders"])])


# ------------------------------------------------------------------------------------------ ring gear, axis 1
#: ring pitch diameter range per arm [m] (assumed)
RING_D = {"ur10": (0.3, 0.5), "kr16_like": (0.5, 0.8), "tool_changer": (0.8, 1.2)}


def iso1328_Fp_um(module_mm, d_mm, quality):
    """Total cumulative pitch deviation F_p [um] of ISO 1328-1:1995 (as recalled): class 5 value
    0.3 m + 1.25 sqrt(d) + 7, times sqrt(2) per class step."""
    return (0.3 * module_mm + 1.25 * np.sqrt(d_mm) + 7.0) * 2 ** ((quality - 5.0) / 2)


def ring_draw(ctx, hw, rng):
    D = rng.uniform(*RING_D[ctx.chain.name])
    module = rng.uniform(2.0, 4.0)
    Z = int(round(D * 1000 / module))
    z = int(rng.integers(15, 26))
    k = np.arange(1, 11, dtype=float)
    w = k ** -1.5 * rng.uniform(0.5, 1.5, 10)
    Fp = iso1328_Fp_um(module, D * 1000, rng.uniform(7.0, 9.0)) * 1e-3  # [mm] total cumulative pitch deviation
    amp_mm = np.r_[Fp / 2 * w / w.sum(), rng.uniform(10, 25) * 1e-3 / 2, rng.uniform(3, 8) * 1e-3]
    return [{"joint": 0, "Z": Z, "z": z, "D_m": D, "orders": np.r_[k, Z / z, Z], "amp": amp_mm / (D * 500.0),
             "phase": rng.uniform(0, 2 * np.pi, 12)}]


def ring_apply(p, ctx, hw):
    return Contribution(dq=_harmonic_dq(p, ctx))


def ring_features(p, ctx, hw):
    return np.array([c for g in p for c in _harmonic_cols(ctx, g["joint"], g["orders"])])
