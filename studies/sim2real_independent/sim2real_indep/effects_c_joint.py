"""Set C joint effects (new physics, not in sets A / B): RV (cycloid) reducer transmission error; a motor-side
encoder error plus output-side gear eccentricity and ovality; radial runout of the output bearings; joint
stiffness with friction hysteresis (Prandtl-Ishlinskii play operators); cross-coupled joint compliance (the output
bearing tilting under the moment perpendicular to the axis); lost motion with a dead band and Dahl / LuGre-type
friction that depends on the approach travel and speed. Same protocol as :mod:`effects_joint`.

Sources:

* RV reducer: ratio R = 1 + (Z2 / Z1) Z_p (spur stage Z2 / Z1, Z_p ring pins); the crankshafts turn Z_p times
  relative to the carrier (the output) per output turn, the input (motor) R times. Transmission error components
  at the crank-rotation order and its harmonic, once per output turn (carrier / output bearing runout) and at the
  input order: Blanche & Yang, "Cycloid drives with machining tolerances", ASME J. Mech. Transm. Autom. Des.
  111(3), 1989 (error periodic with the crank rotation); Nabtesco RV catalogues (angular transmission error of
  the order of 1 arcmin; the ratios of the RV-E series lie between 57 and 185). Peak-to-peak 0.6-1.5 arcmin
  and the split between orders are this study's assumptions.
* encoder / gear eccentricity: HEIDENHAIN "Angle Encoders" (eccentricity e on diameter D: 2e/D); a motor-side
  encoder's error is divided by the ratio N and repeats N times per output turn; strain-wave kinematic error
  contains once- and twice-per-output-turn terms from eccentricity and ovality of the assembly (Ghorbel, Gandhi
  & Alpeter, J. Mech. Des. 123(1), 2001).
* bearing runout: crossed-roller bearing radial runout of 4-12 um (precision classes of THK RU / IKO CRBH
  catalogues, as recalled).
* hysteresis of the torsion curve: Ruderman, Hoffmann & Bertram, "Modeling and identification of elastic robot
  joints with hysteresis and backlash", IEEE Trans. Ind. Electron. 56(10), 2009; Prandtl-Ishlinskii / Iwan
  play-operator models (Iwan, J. Appl. Mech. 33, 1966); the loop width is the catalogue "hysteresis loss"
  (Harmonic Drive: about 1 arcmin). Quasi-static: the load path between two poses is taken as monotonic.
* bearing tilt: moment rigidity of the reducer's main bearing (Nabtesco RV catalogues list it in N m/arcmin:
  of the order of 1.5-4 x the rated torque per arcmin, as recalled; strain-wave units with a crossed-roller
  bearing: 2-5 x the gear's K3, assumed; main axes 1-3 only).
* lost motion: dead zone b between the flanks (Nordin & Gutman, Automatica 38, 2002); Dahl's friction model in
  the space domain (Dahl, Aerospace Corp. TOR-0158, 1968): the state approaches its limit exponentially in the
  travel since the last reversal; LuGre steady state with a Stribeck curve g(v) = Fc + (Fs - Fc) exp(-(v/vs)^2)
  (Canudas de Wit, Olsson, Astrom & Lischinsky, IEEE Trans. Autom. Control 40(3), 1995).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_joint as ej
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


def _harmonics(ctx, j, orders):
    th = ctx.q[:, j]
    cols = []
    for f in orders:
        cols += [ctx.joint_feature(j, np.sin(f * th)), ctx.joint_feature(j, np.cos(f * th))]
    return cols


def _apply_harmonics(params, ctx):
    dq = np.zeros_like(ctx.q)
    for g in params:
        th = ctx.q[:, g["joint"]]
        dq[:, g["joint"]] += (g["amp"] * np.sin(np.multiply.outer(th, g["orders"]) + g["phase"])).sum(axis=1)
    return Contribution(dq=dq)


def _harmonic_features(params, ctx, hw):
    return np.array([c for g in params for c in _harmonics(ctx, g["joint"], g["orders"])])


# ------------------------------------------------------------------------------------------- RV reducer
def rv_draw(ctx, hw, rng):
    out = []
    for j, d in enumerate(hw["drives"]):
        if d["kind"] != "RV":
            continue
        zp = int(rng.choice([30, 36, 40]))
        stages = [i for i in np.arange(2.5, 7.01, 0.5) if 100 <= 1 + i * zp <= 200]
        ratio = int(round(1 + rng.choice(stages) * zp))
        w = np.array([rng.uniform(0.4, 0.6), rng.uniform(0.1, 0.2), rng.uniform(0.1, 0.3), rng.uniform(0.05, 0.15)])
        pp = rng.uniform(0.6, 1.5) * ph.ARCMIN
        out.append({"joint": j, "pins": zp, "ratio": ratio, "orders": np.array([zp, 2 * zp, 1, ratio], float),
                    "amp": pp / 2 * w / w.sum(), "phase": rng.uniform(0, 2 * np.pi, 4)})
    return out


rv_apply, rv_features = (lambda p, ctx, hw: _apply_harmonics(p, ctx)), _harmonic_features


# ---------------------------------------------------------------------- motor encoder + output eccentricity
def dual_encoder_draw(ctx, hw, rng):
    out = []
    for j in ej._joints(ctx, rng, 2, 4):
        N = int(rng.choice([80, 100, 120, 160]))
        motor = 2e-3 * rng.uniform(5, 20) / rng.uniform(20, 40) / N      # motor disc eccentricity, output rad
        gear = rng.uniform(5, 20) * 1e-3 / rng.uniform(30, 80)           # output eccentricity on the pitch radius
        amp = np.array([gear, gear * rng.uniform(0.2, 0.5), motor, motor * rng.uniform(0.3, 0.7)])
        out.append({"joint": j, "ratio": N, "orders": np.array([1, 2, N, 2 * N], float), "amp": amp,
                    "phase": rng.uniform(0, 2 * np.pi, 4)})
    return out


dual_encoder_apply, dual_encoder_features = rv_apply, _harmonic_features


# ------------------------------------------------------------------------------------ bearing radial runout
def _perp_basis(w):
    u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return u, np.cross(w, u)


def runout_draw(ctx, hw, rng):
    return [{"joint": int(j), "e_mm": rng.uniform(4, 12) * 1e-3, "phase": rng.uniform(0, 2 * np.pi)}
            for j in np.flatnonzero(ctx.chain.revolute)]


def _runout_parts(p, ctx):
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    cols = []
    for r in p:
        j = r["joint"]
        u, v = _perp_basis(ctx.chain.axes[j])
        uc, vc = R[:, j] @ u, R[:, j] @ v  # in the proximal body, current orientation
        th = ctx.q[:, j, None] + r["phase"]
        cols.append((np.cos(th) * uc + np.sin(th) * vc, -np.sin(th) * uc + np.cos(th) * vc))
    return cols


def runout_apply(p, ctx, hw):
    disp = sum(r["e_mm"] * c for r, (c, _) in zip(p, _runout_parts(p, ctx)))
    return Contribution(displace=disp)


def runout_features(p, ctx, hw):
    return np.array([c for pair in _runout_parts(p, ctx) for c in pair])


# --------------------------------------------------------------------------------- stiffness with hysteresis
def play_operator(x, r, x0=None):
    """Prandtl-Ishlinskii play operator of radius r along the sequence x (P,): w follows x with a lag of r."""
    w = np.empty_like(x)
    prev = x[0] if x0 is None else x0
    for i, xi in enumerate(x):
        prev = min(max(prev, xi - r), xi + r)
        w[i] = prev
    return w


def hysteresis_signal(tau, r):
    """Mean of three play operators (radii r/3, 2r/3, r) minus the load, normalised: in [-1, 1], -1 on a long
    loading branch, +1 on a long unloading branch."""
    return np.mean([(play_operator(tau, rk) - tau) / rk for rk in (r / 3, 2 * r / 3, r)], axis=0)


def hyst_draw(ctx, hw, rng):
    return [{"joint": int(j), "r": rng.uniform(0.03, 0.10) * hw["drives"][j]["T_rated"],
             "H": rng.uniform(0.25, 0.75) * ph.ARCMIN} for j in np.flatnonzero(ctx.chain.revolute)]


def hyst_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for j, d in enumerate(hw["drives"]):
        dq[:, j] = hwm.torsion(d, ctx.loads[:, j], False)
    for h in p:
        dq[:, h["joint"]] += h["H"] * hysteresis_signal(ctx.loads[:, h["joint"]], h["r"])
    return Contribution(dq=dq)


def hyst_features(p, ctx, hw):
    cols = list(ej.compliance_features(p, ctx, hw))
    cols += [ctx.joint_feature(h["joint"], hysteresis_signal(ctx.loads[:, h["joint"]], h["r"])) for h in p]
    return np.array(cols)


# --------------------------------------------------------------------------------------- bearing tilt
def tilt_draw(ctx, hw, rng):
    """The main axes' bearings (revolute joints 1-3); a wrist's tilt is carried by the forearm's bearing pair (not
    modelled). The linear torsion of every joint (as in set A's ``compliance``) acts as well."""
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[:3]):
        d = hw["drives"][j]
        K = (rng.uniform(1.5, 4.0) * d["T_rated"] / ph.ARCMIN if d["kind"] == "RV"
             else rng.uniform(2.0, 5.0) * d["K3"])
        out.append({"joint": int(j), "K_tilt": K})
    return out


def tilt_parts(p, ctx):
    """Target displacement (m, P, 3) per unit tilt compliance [rad / N m] of each listed joint's bearing."""
    m, pos, body = ctx.mass_state
    F = m[..., None] * kin.G * np.array([0, 0, -1.0])
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    cols = []
    for t in p:
        j = t["joint"]
        on = body >= j + 1
        M = np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F[:, on]).sum(axis=1)
        M_perp = M - np.einsum("pi,pi->p", M, w[:, j])[:, None] * w[:, j]
        cols.append(np.cross(M_perp, ctx.target - c[:, j]))
    return np.array(cols)


def tilt_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for j, d in enumerate(hw["drives"]):
        dq[:, j] = hwm.torsion(d, ctx.loads[:, j], False)
    amp = np.array([1 / t["K_tilt"] for t in p])
    return Contribution(dq=dq, displace=np.einsum("k,kpi->pi", amp, tilt_parts(p, ctx)))


def tilt_features(p, ctx, hw):
    return np.concatenate([ej.compliance_features(p, ctx, hw), tilt_parts(p, ctx)])


# ------------------------------------------------------------------------------ Dahl / LuGre lost motion
def dahl_draw(ctx, hw, rng):
    return [{"joint": int(j), "half_b": rng.uniform(0.5, 2.0) * ph.ARCMIN, "c": rng.uniform(0.2, 0.8) * ph.ARCMIN,
             "theta_c": np.deg2rad(rng.uniform(0.01, 0.1)), "v_s": np.deg2rad(rng.uniform(0.5, 5.0)),
             "fc_fs": rng.uniform(0.5, 0.8), "preload": rng.uniform(0.02, 0.08) * hw["drives"][j]["T_rated"]}
            for j in np.flatnonzero(ctx.chain.revolute)]


def dahl_states(b, ctx):
    """Lost-motion state per unit dead-band half width and per unit friction term (2, P) of joint b["joint"]:
    the output trails the motor by z, approaching +-(b/2 + c g(v)) exponentially in the travel (theta_c) of the
    main move and then of the final approach (travel and speed from the session's approach plan)."""
    s, j = ctx.session, b["joint"]
    ap = s.approach
    q, d, trav = ctx.q[:, j], s.direction[:, j], ap["travel"][:, j]
    g = lambda v: b["fc_fs"] + (1 - b["fc_fs"]) * np.exp(-(np.asarray(v) / b["v_s"]) ** 2)  # noqa: E731
    z = np.zeros(2)
    out = np.zeros((2, len(q)))
    for i in range(len(q)):
        start = q[i - 1] if i else q[0] - 2 * d[0] * trav[0]
        main = q[i] - d[i] * trav[i] - start
        sm = np.sign(main) if main != 0 else d[i]
        for sign, travel, v in ((sm, abs(main), s.speed[i, j]), (d[i], trav[i], ap["speed"][i, j])):
            lim = sign * np.array([1.0, g(v)])
            z = lim - (lim - z) * np.exp(-travel / b["theta_c"])
        out[:, i] = z
    return out


def _dahl_signals(b, ctx):
    tau = ctx.loads[:, b["joint"]]
    loaded = np.abs(tau) > b["preload"]
    z = dahl_states(b, ctx)
    return np.where(loaded, np.sign(tau), -z[0]), np.where(loaded, 0.0, -z[1])


def dahl_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for b in p:
        fb, fc = _dahl_signals(b, ctx)
        dq[:, b["joint"]] = b["half_b"] * fb + b["c"] * fc
    return Contribution(dq=dq)


def dahl_features(p, ctx, hw):
    return np.array([ctx.joint_feature(b["joint"], f) for b in p for f in _dahl_signals(b, ctx)])
