"""Generic parametric model of each effect family, for the oracle's (c) fits: what a diagnosis could fit knowing
only the robot file (its masses, payload at the tool point) and the logged columns -- never the case's truth.

Each family gives variants (name, features (m, P, 3) in the base frame); the oracle picks one by 3-fold
cross-validation on the training poses. Shape grids (fixed defaults, not tuned on any case):

* joint_compliance: linear d_q = c tau per loaded joint; + a hardening term tau |tau| (smooth law);
* backlash: flank = sign(tau) where |tau| > f max|tau| else -direction (f = 0.05, 0.2) and a hysteresis term
  (direction), per revolute joint; or direction only;
* transmission: harmonics once (and twice) per output turn of each revolute joint (no gear ratio is known);
* thermal: uniform expansion with the logged air temperature lagged by 0, 30, 90 min; or per-body warm-up curves
  1 - exp(-t / tau), tau = 15, 45 min, or a linear drift in time;
* mount_compliance: base tilt = C M (2 x 2 compliance, gravity moment M of the file's masses) about a pivot
  0, 400 or 800 mm below the base;
* link_deflection: cantilever bending (1/EI) and shear (1/kGA) of every link of 200 mm or more under the file's
  masses (the same beam law as the generator's, :func:`effects_body._beam_displacement`).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import physics as ph


def _stack(cols, P):
    return np.array(cols) if cols else np.zeros((0, P, 3))


def joint_compliance(ctx, data):
    tau = ctx.loads
    big = np.abs(tau).max(axis=0) > 1e-3 * np.abs(tau).max()
    lin = [ctx.joint_feature(j, tau[:, j]) for j in np.flatnonzero(big)]
    hard = [ctx.joint_feature(j, tau[:, j] * np.abs(tau[:, j]) / np.abs(tau[:, j]).max())
            for j in np.flatnonzero(big & ctx.chain.revolute)]
    P = len(ctx.q)
    return [("linear", _stack(lin, P)), ("linear+hardening", _stack(lin + hard, P))]


def backlash(ctx, data):
    tau, d, P = ctx.loads, data["direction"], len(ctx.q)
    out = [("direction", _stack([ctx.joint_feature(j, d[:, j]) for j in np.flatnonzero(ctx.chain.revolute)], P))]
    for f in (0.05, 0.2):
        cols = []
        for j in np.flatnonzero(ctx.chain.revolute):
            lim = f * np.abs(tau[:, j]).max()
            flank = np.where(np.abs(tau[:, j]) > lim, np.sign(tau[:, j]), -d[:, j])
            cols += [ctx.joint_feature(j, flank), ctx.joint_feature(j, d[:, j])]
        out.append((f"flank f={f}", _stack(cols, P)))
    return out


def transmission(ctx, data):
    P = len(ctx.q)
    once, twice = [], []
    for j in np.flatnonzero(ctx.chain.revolute):
        th = ctx.q[:, j]
        once += [ctx.joint_feature(j, np.sin(th)), ctx.joint_feature(j, np.cos(th))]
        twice += [ctx.joint_feature(j, np.sin(2 * th)), ctx.joint_feature(j, np.cos(2 * th))]
    return [("1/turn", _stack(once, P)), ("1,2/turn", _stack(once + twice, P))]


def thermal(ctx, data):
    t, T = data["time_s"], data["temperature_c"]
    P = len(ctx.q)
    out = []
    uniform = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))
    for lag in (0, 30, 90):
        Tl = T if lag == 0 else ph.first_order_foh(t, T, lag * 60.0)
        out.append((f"ambient lag {lag} min", (uniform * (Tl - Tl.mean())[:, None])[None]))
    bodies = sorted(set(int(b) for b in ctx.chain.link_body if b >= 1))
    el = t - t[0]
    for tau in (15, 45, None):
        w = el / el[-1] if tau is None else 1 - np.exp(-el / (tau * 60.0))
        cols = [ctx.link_scale_feature(ctx.chain.link_body == b) * w[:, None] for b in bodies]
        out.append(("linear drift" if tau is None else f"warm-up {tau} min", _stack(cols, P)))
    return out


def mount_compliance(ctx, data):
    M = eb.mount_moment(ctx)
    out = []
    ex, ey = np.eye(3)[0], np.eye(3)[1]
    for h in (0.0, 400.0, 800.0):
        root = np.array([0, 0, -h])
        cols = [np.cross(a * (M @ b)[:, None], ctx.target - root) for a in (ex, ey) for b in (ex, ey)]
        out.append((f"pivot {h:.0f} mm", np.array(cols)))
    return out


def link_deflection(ctx, data):
    cols = []
    for li, v in enumerate(ctx.chain.links):
        if np.linalg.norm(v) >= 200.0:
            cols.append(eb._beam_displacement(ctx, li, 1.0, np.inf, 1.0 / 1.3))
            cols.append(eb._beam_displacement(ctx, li, np.inf, 1.0, np.inf))
    return [("beams >= 200 mm", _stack(cols, len(ctx.q)))]


MODELS = {"joint_compliance": joint_compliance, "mount_compliance": mount_compliance,
          "link_deflection": link_deflection, "backlash": backlash, "thermal": thermal,
          "transmission": transmission}
