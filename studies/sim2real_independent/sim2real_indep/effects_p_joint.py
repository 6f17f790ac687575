"""Set P joint effects (new physics, not in sets A-O): the wrist axes of a hygienic (sealed) arm driven through
permanent-magnet couplings across their housings' walls, whose torque-angle law is a sine; a wrist axis whose last
stage is a toothed belt that an under-tensioned slack span lets go soft; the output lip seals' viscoelastic drag, whose wind-up
of the gear relaxes through the dwell; the accumulated pole-pitch errors of magnetised output encoder rings; and the
stray field of the neighbouring axis' permanent-magnet brake on a magnetic output encoder. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* magnetic coupling: a coaxial synchronous permanent-magnet coupling of p pole pairs transmits T = T_max sin(p dphi)
  at a slip angle dphi between its hubs (Furlani, *Permanent Magnet and Electromechanical Devices*, 2001, ch. 5 on
  couplings; makers' catalogues of coaxial magnetic couplings show the same sine curve, slipping past T_max). Sealed
  (wash-down, vacuum, Ex) joints drive the gear's input through such a coupling across a containment can, so the
  gear's input lags the motor by arcsin(tau / (N T_max)) / p and the output by that over N (N the gear ratio). The
  coupling sized at 1.4-2.2 times the session's largest motor-side load (a service factor, as the catalogues advise),
  4-8 pole pairs, ratios of 80-120; the wrist axes 4-6 of ur10 and kr16_like, whose motors sit in the dry forearm and
  drive the wash-down wrist across its wall (assumed; first axes 2 and 3 with 6-12 pole pairs, ratios of 100-160: the
  link model mimicked their twist under gravity, 1.04x on ur10, 1.12x on kr16_like). The true structure: a column per
  axis, arcsin(tau / (N T_max)) (the sizing its shape), amplitude 1 / (p N).
* slack belt: a toothed belt's two spans share a torque while both carry tension; once the torque exceeds 2 T0 r (T0
  the installation tension, r the pulley's radius) the slack span goes slack and the tight span alone carries it, so
  the stage's torsional stiffness falls from 2 k r^2 to k r^2, k = EA / L of a span (Gates, *Design Manual for
  synchronous belt drives*, installation tension; Childs, *Mechanical Design Engineering Handbook*, 2014, ch. 12 on
  belt drives: F1 - F2 = T / r, F1 + F2 = 2 T0 while both are taut). Steel- or aramid-cord belts, EA 0.3-1.0 MN (a 20-
  30 mm wide belt; 0.5-1.5 MN on kr16_like, first 0.3-1.0: up to 2.3 mm at the tool), spans of 150-300 mm, output
  pulleys of 30-45 mm (kr16_like's axis 5) and 60-90 mm (tool_changer's; EA 1.5-4 MN); the tension relaxed to 30-60 %
  of the largest span force of the session (assumed). The true structure:
  one column, tau + sign(tau) (|tau| - 2 T0 r)+, amplitude 1 / (2 k r^2).
* seal relaxation: the output's lip seals and bearing drag (5-12 % of the rated torque: double-lip wash-down seals
  before their run-in; first 3-8 %, ur10's 45-pose case gained 15 %, the mount model at 1.16x) wind the compliant gear
  against
  the motion while the joint moves; an elastomer's drag relaxes like a standard linear solid (Ferry, *Viscoelastic
  Properties of Polymers*, 3rd ed., 1980, ch. 1; seal friction: Mueller & Nau, *Fluid Sealing Technology*, 1998, ch. on
  radial lip seals), so after the stop the wind-up falls from C T_s to rho C T_s (rho 0.2-0.5) with a time constant of
  1.5-5 s: at the measurement, the end of the dwell, the output trails by C T_s (rho + (1 - rho) exp(-t_dwell / tau)).
  Every revolute axis. The true structure: a column per axis, amplitude C T_s.
* pole pitch: a magnetised encoder ring's poles are each a little long or short; the reading's error is their
  accumulated deviation, a random walk closed around the ring (its Fourier coefficients fall as 1 / k; e.g. the
  system accuracy of magnetic ring encoders is +-0.01-0.05 deg against their sub-divisional error of some arcsec:
  RLS / Renishaw, AMO and SIKO ring-encoder data sheets, as recalled). Output rings on axes 1-3, a peak error of 0.01-
  0.03 deg, harmonics 1-24 (assumed). The true structure: a column per axis (the drawn walk its shape), amplitude its
  peak error.
* stray field: a magnetic angle sensor reads the direction of the field in its plane; an added stray field B_s turns
  it by (B_s perpendicular to the magnet's field) / B0 (stray-field robustness of magnetic angle sensors: ISO 11452-8
  and the sensor makers' notes, as recalled). The permanent-magnet holding brake or the rotor of the next axis' motor,
  a dipole m rotating with that axis (field mu0 / 4 pi (3 (m.r) r - m) / r^3: Jackson, *Classical Electrodynamics*,
  3rd ed., ch. 5), sits 70-120 mm from the encoder of axes 1 and 2 (and 5: tool_changer and kr16_like, whose axes 2-3
  turn through 70-130 deg only: tool_changer's case gained 7 %, the mount model at 1.05x, with axes 1-2 alone); both
  the sensor's magnet and the dipole's housing
  turn with the axis the sensor reads, so the error is a function of the next axis' angle alone: c0 + c1 cos q_{j+1} +
  c2 sin q_{j+1}. Leakage dipoles of 0.05-0.2 A m^2 on ur10, 0.1-0.4 on the heavier arms' larger brakes, magnets
  giving 40-80 mT at the sensor (assumed; first 0.05-0.3 at 60-120 mm on every arm, then 0.03-0.15 at 80-140 mm: gains
  of 14 % on ur10 and 20 % on kr16_like). The true
  structure: two columns per axis (cos and sin of the next axis' angle).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep.context import Contribution

MU0_4PI = 1e-7          # [T m / A]


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _basis(w):
    u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return u, np.cross(w, u)


# ------------------------------------------------------------------------------------------ magnetic coupling
COUPLED = {"ur10": (3, 4, 5), "kr16_like": (3, 4, 5)}


def coupling_draw(ctx, hw, rng):
    if ctx.chain.name not in COUPLED:
        return {}
    js = list(COUPLED[ctx.chain.name])
    N = rng.uniform(80.0, 120.0, len(js))
    tmax = rng.uniform(1.4, 2.2, len(js)) * np.abs(ctx.loads[:, js]).max(axis=0) / N
    return {"joints": js, "N": N, "T_max": tmax, "p": rng.integers(4, 9, len(js)).astype(float)}


def coupling_signals(p, ctx):
    """(m, P): arcsin of each coupled axis' motor-side load over its coupling's pull-out torque."""
    return np.arcsin(np.clip(ctx.loads[:, p["joints"]] / (p["N"] * p["T_max"]), -1.0, 1.0)).T


def coupling_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = (coupling_signals(p, ctx) / (p["p"] * p["N"])[:, None]).T
    return Contribution(dq=dq)


def coupling_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], coupling_signals(p, ctx))])


# ------------------------------------------------------------------------------------------------ slack belt
#: per arm: belted axis, pulley radius [mm], EA [N], span [mm] (assumed)
BELT = {"kr16_like": (4, (30.0, 45.0), (0.5e6, 1.5e6), (150.0, 300.0)),
        "tool_changer": (4, (60.0, 90.0), (1.5e6, 4.0e6), (150.0, 300.0))}


def belt_draw(ctx, hw, rng):
    if ctx.chain.name not in BELT:
        return {}
    j, r, EA, L = BELT[ctx.chain.name]
    r, EA, L = rng.uniform(*r), rng.uniform(*EA), rng.uniform(*L)
    Fmax = np.abs(ctx.loads[:, j]).max() / (r * 1e-3)                   # the largest span force [N]
    T0 = rng.uniform(0.3, 0.6) * Fmax
    k = EA / (L * 1e-3)                                                 # [N/m]
    return {"joint": j, "r_mm": r, "EA_N": EA, "L_mm": L, "T0_N": T0, "tau_s": 2 * T0 * r * 1e-3,
            "c_rad_Nm": 1.0 / (2 * k * (r * 1e-3) ** 2)}


def belt_signal(p, tau):
    """tau + sign(tau) (|tau| - tau_s)+ [N m]: the torque the stage's compliance 1 / (2 k r^2) turns into twist."""
    return tau + np.sign(tau) * np.maximum(np.abs(tau) - p["tau_s"], 0.0)


def belt_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["c_rad_Nm"] * belt_signal(p, ctx.loads[:, p["joint"]])
    return Contribution(dq=dq)


def belt_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    return ctx.joint_feature(p["joint"], belt_signal(p, ctx.loads[:, p["joint"]]))[None]


# ---------------------------------------------------------------------------------------------- seal relaxation
def seal_draw(ctx, hw, rng):
    js = [int(j) for j in np.flatnonzero(ctx.chain.revolute)]
    T = np.array([rng.uniform(0.05, 0.12) * hw["drives"][j]["T_rated"] for j in js])
    return {"joints": js, "T_s": T, "C": np.array([hwm.torsion(hw["drives"][j], 1.0, False) for j in js]),
            "rho": rng.uniform(0.2, 0.5, len(js)), "tau_s": rng.uniform(1.5, 5.0, len(js))}


def seal_signals(p, ctx):
    """(m, P): -direction (rho + (1 - rho) exp(-t_dwell / tau)), the wind-up left at the measurement per C T_s."""
    s = ctx.session
    left = p["rho"][:, None] + (1 - p["rho"][:, None]) * np.exp(-s.dwell_s[None] / p["tau_s"][:, None])
    return -s.direction[:, p["joints"]].T * left


def seal_amplitudes(p):
    return p["C"] * p["T_s"]


def seal_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = (seal_amplitudes(p)[:, None] * seal_signals(p, ctx)).T
    return Contribution(dq=dq)


def seal_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], seal_signals(p, ctx))])


# ------------------------------------------------------------------------------------------------- pole pitch
POLE_JOINTS, POLE_K = (0, 1, 2), 24


def pole_draw(ctx, hw, rng):
    js = [j for j in POLE_JOINTS if ctx.chain.revolute[j]]
    k = np.arange(1, POLE_K + 1)
    a = rng.normal(size=(len(js), POLE_K)) / k
    b = rng.normal(size=(len(js), POLE_K)) / k
    grid = np.linspace(0, 2 * np.pi, 2048, endpoint=False)
    peak = np.abs(np.cos(np.outer(grid, k)) @ a.T + np.sin(np.outer(grid, k)) @ b.T).max(axis=0)
    return {"joints": js, "a": a / peak[:, None], "b": b / peak[:, None],
            "peak_rad": np.deg2rad(rng.uniform(0.01, 0.03, len(js)))}


def pole_shapes(p, ctx):
    """(m, P): each ring's accumulated pitch error per unit peak at the axis' angle."""
    k = np.arange(1, POLE_K + 1)
    th = ctx.q[:, p["joints"]]
    return np.array([np.cos(np.outer(th[:, i], k)) @ p["a"][i] + np.sin(np.outer(th[:, i], k)) @ p["b"][i]
                     for i in range(len(p["joints"]))])


def pole_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = (p["peak_rad"][:, None] * pole_shapes(p, ctx)).T
    return Contribution(dq=dq)


def pole_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], pole_shapes(p, ctx))])


# ------------------------------------------------------------------------------------------------ stray field
#: per arm: (read axis, next axis) pairs
STRAY_PAIRS = {"ur10": ((0, 1), (1, 2)), "kr16_like": ((0, 1), (1, 2), (4, 5)),
               "tool_changer": ((0, 1), (1, 2), (4, 5))}
#: per arm: the leakage dipole [A m^2] (the heavier arms' larger brakes)
STRAY_M = {"ur10": (0.05, 0.2), "kr16_like": (0.1, 0.4), "tool_changer": (0.1, 0.4)}


def dipole_field(m, r):
    """Field [T] at offsets r (..., 3) [m] from dipoles m (..., 3) [A m^2]."""
    d = np.linalg.norm(r, axis=-1, keepdims=True)
    e = r / d
    return MU0_4PI * (3 * np.sum(m * e, axis=-1, keepdims=True) * e - m) / d ** 3


def stray_draw(ctx, hw, rng):
    ch = ctx.chain
    out = []
    for j, k in STRAY_PAIRS[ch.name]:
        u, v = _basis(ch.axes[k])
        out.append({"joint": j, "next": k, "m": rng.uniform(*STRAY_M[ch.name]),
                    "r_m": rng.uniform(0.07, 0.12) * _unit(rng),
                    "B0": rng.uniform(0.04, 0.08), "phi": rng.uniform(0, 2 * np.pi),
                    "t0": np.cos(a := rng.uniform(0, 2 * np.pi)) * _basis(ch.axes[j])[0]
                    + np.sin(a) * _basis(ch.axes[j])[1], "u": u, "v": v})
    return out


def _unit(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def stray_coeffs(s):
    """(c1, c2) [rad]: the reading's error c0 + c1 cos q + c2 sin q over the next axis' angle q (the dipole m (cos(q +
    phi) u + sin(q + phi) v) at -r from the sensor; the field's part along t0 over B0)."""
    q = np.array([0.0, np.pi / 2])
    m = s["m"] * (np.cos(q + s["phi"])[:, None] * s["u"] + np.sin(q + s["phi"])[:, None] * s["v"])
    B = dipole_field(m, np.broadcast_to(s["r_m"], m.shape)) @ s["t0"] / s["B0"]
    return B                                  # linear in m: B(0) = c1, B(pi / 2) = c2 (the dipole's mean is zero)


def stray_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for s in p:
        c1, c2 = stray_coeffs(s)
        q = ctx.q[:, s["next"]]
        dq[:, s["joint"]] -= c1 * np.cos(q) + c2 * np.sin(q)
    return Contribution(dq=dq)


def stray_features(p, ctx, hw):
    cols = []
    for s in p:
        q = ctx.q[:, s["next"]]
        cols += [ctx.joint_feature(s["joint"], np.cos(q)), ctx.joint_feature(s["joint"], np.sin(q))]
    return np.array(cols) if cols else _empty(ctx)
