"""Joint-space effects: gear transmission error, encoder eccentricity, joint stiffness (linear and hardening),
backlash. Each: ``draw(ctx, hw, rng)``, ``apply(params, ctx, hw) -> Contribution``, ``features(params, ctx, hw) ->
(m, P, 3)`` (target displacements, base frame, per unit amplitude of the true structure). Laws in :mod:`physics`,
hardware ranges in :mod:`hardware`. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


def _joints(ctx, rng, lo, hi, revolute_only=True):
    cand = np.flatnonzero(ctx.chain.revolute) if revolute_only else np.arange(ctx.chain.n)
    k = int(rng.integers(lo, min(hi, len(cand)) + 1))
    main = [j for j in cand if j < 3]
    rest = [j for j in cand if j >= 3]
    pick = list(rng.permutation(main))[:k] + list(rng.permutation(rest))
    return sorted(int(j) for j in pick[:k])


# ------------------------------------------------------------------------------------------ transmission
def gear_draw(ctx, hw, rng):
    joints = _joints(ctx, rng, 2, 4)
    out = []
    for j in joints:
        ratio = int(rng.choice([80, 100, 120, 160]))  # standard strain-wave / cycloid ratios
        acc = rng.uniform(0.5, 1.5) * ph.ARCMIN   # catalogue accuracy, peak to peak
        w = np.array([rng.uniform(0.4, 0.7), rng.uniform(0.1, 0.3), rng.uniform(0.1, 0.3)])
        out.append({"joint": j, "ratio": ratio, "amp": acc / 2 * w / w.sum(), "phase": rng.uniform(0, 2 * np.pi, 3)})
    return out


def gear_apply(params, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in params:
        dq[:, g["joint"]] += ph.harmonic_drive_error(ctx.q[:, g["joint"]], g["ratio"], g["amp"], g["phase"])
    return Contribution(dq=dq)


def gear_features(params, ctx, hw):
    cols = []
    for g in params:
        th = ctx.q[:, g["joint"]]
        for f in (2 * g["ratio"], g["ratio"], 1):
            cols += [ctx.joint_feature(g["joint"], np.sin(f * th)), ctx.joint_feature(g["joint"], np.cos(f * th))]
    return np.array(cols)


def encoder_draw(ctx, hw, rng):
    out = []
    for j in _joints(ctx, rng, 2, 4):
        motor_side = rng.random() < 0.3
        ratio = int(rng.choice([80, 100, 120, 160]))
        out.append({"joint": j, "ecc_um": rng.uniform(3, 20), "diameter_mm": rng.uniform(40, 120),
                    "phase": rng.uniform(0, 2 * np.pi), "cycles": ratio if motor_side else 1})
    return out


def encoder_apply(params, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for e in params:  # the controller servoes the reading, so the true angle is off by minus the reading error
        err = ph.encoder_eccentricity_error(ctx.q[:, e["joint"]], e["ecc_um"], e["diameter_mm"], e["phase"],
                                            e["cycles"])
        dq[:, e["joint"]] -= err / e["cycles"]
    return Contribution(dq=dq)


def encoder_features(params, ctx, hw):
    cols = []
    for e in params:
        th = ctx.q[:, e["joint"]] * e["cycles"]
        cols += [ctx.joint_feature(e["joint"], np.sin(th)), ctx.joint_feature(e["joint"], np.cos(th))]
    return np.array(cols)


# ---------------------------------------------------------------------------------------------- stiffness
def stiffness_draw(ctx, hw, rng):
    return {}


def stiffness_apply(hardening):
    def apply(params, ctx, hw):
        dq = np.zeros_like(ctx.q)
        for j, d in enumerate(hw["drives"]):
            dq[:, j] = hwm.torsion(d, ctx.loads[:, j], hardening)
        return Contribution(dq=dq)
    return apply


def compliance_features(params, ctx, hw):
    return np.array([ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)])


def hardening_features(params, ctx, hw):
    cols = []
    for j, d in enumerate(hw["drives"]):
        tau = ctx.loads[:, j]
        knots = hwm.torsion_knots(d)
        if knots is None:
            cols.append(ctx.joint_feature(j, tau))
            continue
        a, s = np.abs(tau), np.sign(tau)
        T1, T2 = knots
        for sig in (np.minimum(a, T1), np.clip(a - T1, 0, T2 - T1), np.maximum(a - T2, 0)):
            if np.abs(sig).max() > 1e-6 * max(T1, 1.0):
                cols.append(ctx.joint_feature(j, s * sig))
    return np.array(cols)


# ----------------------------------------------------------------------------------------------- backlash
def backlash_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        out.append({"joint": int(j), "b": rng.uniform(1.0, 4.0) * ph.ARCMIN, "h": rng.uniform(0.2, 1.0) * ph.ARCMIN,
                    "preload": rng.uniform(0.02, 0.08) * hw["drives"][j]["T_rated"]})
    return out


def backlash_apply(params, ctx, hw):
    dq = np.zeros_like(ctx.q)
    d = ctx.session.direction
    for b in params:
        j = b["joint"]
        dq[:, j] = ph.backlash_offset(d[:, j], ctx.loads[:, j], b["preload"], b["b"], b["h"])
    return Contribution(dq=dq)


def backlash_features(params, ctx, hw):
    cols = []
    d = ctx.session.direction
    for b in params:
        j = b["joint"]
        cols.append(ctx.joint_feature(j, ph.backlash_offset(d[:, j], ctx.loads[:, j], b["preload"], 2.0, 0.0)))
        cols.append(ctx.joint_feature(j, d[:, j]))
    return np.array(cols)
