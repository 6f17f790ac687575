"""Set ZG body effects (new physics, not in sets A-ZF): the arm's foundation still settling unevenly; the base's
anchor bolts relaxing through the session so that the base tilts more under the same moment; a slender tool boom whose
bending under the part's and its own weight the axial load amplifies or relieves (a beam-column); and a flat-bar tool
boom that bends towards its weak axis. Same protocol as :mod:`effects_joint`.

Sources:

* settlement tilt: a new or re-laid foundation block consolidating unevenly (Terzaghi consolidation: settlement
  growing as the pore water drains, its rate slow against a session, so the tilt grows at a near-constant rate over
  hours; differential settlement of machine foundations: Arya, O'Neill & Pincus, *Design of Structures and
  Foundations for Vibrating Machines*, 1979, ch. 1); the base turns about a horizontal axis (direction psi) at the
  footing's level h 0-300 mm below the base at a rate set by the soil, not by the arm. Unlike sets A-ZF's mount
  kinds (tilts following the arm's moment, its history, the support's load or an event) the tilt follows the time
  alone. Sized to 0.25-0.6 mm over the session. Driven by time (logged); the soil is not. The true structure: two
  columns (the tilt rate about x and y) [rad / s].
* bolt relaxation: the anchor bolts of a freshly tightened base plate lose preload by embedding and gasket creep,
  fast at first and then logarithmically in time (Bickford, *Introduction to the Design and Behavior of Bolted
  Joints*, 4th ed., 2008, ch. 10: short-term relaxation 5-20 %); the joint's rotational stiffness falls with the
  preload (contact stiffness of a preloaded interface), so the tilt under the moment grows: tilt = C M (1 + beta
  ln(1 + t / t0)), beta 0.8-1.5 (a plate on a soft grout or shim pad that the bolts embed into), t0 2-10 min, about a
  pivot 0-200 mm below the base; C anisotropic, the relaxed bolt row's axis (any direction) 1, the other 0.05-0.3.
  (First beta 0.2-0.5 and a near-isotropic C: ZG22 on kr16_like absorbed, 4.6 % -- an isotropic tilt following the
  moment turns the arm in its own plane as a joint-2 offset does, and so small a growth left little beyond it; ZG09 on
  tool_changer, 20 %, the thermal warm-up model at 1.14x -- its moment varies little, so the growth is a near-uniform
  drift in time; the kind now sits on ur10 (ZG08) and kr16_like (ZG22).) Unlike set ZA's/ZF's shim and
  set W's grout kinds (the support's own creep or slip under the moment) or set F's plate yield, the compliance grows
  with the bolts' relaxation in time under any moment. Sized to 0.3-0.7 mm. Driven by the pose, payload and time
  (logged). The true structure: four columns (C's entries) [rad / (N m)].
* beam-column boom: a slender tool boom (length 400 mm, a thin CFRP tube) carrying the part at its tip bends under the
  weight's component across it; the component along it compresses (boom up) or stretches (boom down) the boom, which
  amplifies the bending by 1 / (1 - P / P_cr) or relieves it (Timoshenko & Gere, *Theory of Elastic Stability*, 2nd
  ed., 1961, ch. 1, the amplification factor of a beam-column), P_cr = pi^2 EI / (4 L^2) for a cantilever; the
  largest part's P / P_cr 0.2-0.45. Unlike set ZF's polymer boom (stiffness following the air) or the bending of
  sets A-ZF's booms (linear in the load), the stiffness depends on the load's direction along the boom. Parts of
  0-10 kg changed between blocks. Sized to 0.3-0.7 mm. Driven by the pose and the payload (logged). The true
  structure: one column, amplitude 1 / EI.
* leaf boom: a flat-bar boom (width / thickness 3-7, so EI_strong / EI_weak 10-50; Roark's *Formulas for Stress and
  Strain*, 7th ed., table 8.1, unsymmetric bending about principal axes) bends by (g . n_k) / EI_k along each
  principal axis n_k: the tip deflects towards the weak axis, not along the weight's component. Unlike sets A-ZF's
  round booms (deflection along the weight's component) and set ZF's polymer boom, the deflection turns with the
  bar's roll. Principal axes at a roll angle chi about the boom. Sized to 0.3-0.7 mm. Driven by the pose (logged).
  The true structure: one column (the weak and strong parts in their known ratio), amplitude 1 / EI_weak.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size

BOOM_MM = 400.0
G = kin.G


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _elapsed(session):
    return session.time_s - session.time_s[0]


# ---------------------------------------------------------------------------------------------------- settlement tilt
def settle_draw(ctx, hw, rng):
    p = {"h_mm": rng.uniform(0.0, 300.0)}
    psi = rng.uniform(0, 2 * np.pi)
    p["rate"] = _size(settle_features(p, ctx, hw), [np.cos(psi), np.sin(psi)], rng)
    return p


def settle_features(p, ctx, hw):
    t = _elapsed(ctx.session)
    r = ctx.target - np.array([0.0, 0.0, -p["h_mm"]])
    return np.array([np.cross(np.eye(3)[k], r) * t[:, None] for k in range(2)])


def settle_apply(p, ctx, hw):
    return _amp_apply(p["rate"], settle_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- bolt relaxation
def relax_factor(p, session):
    """(P,) the compliance's growth 1 + beta ln(1 + t / t0)."""
    return 1.0 + p["beta"] * np.log1p(_elapsed(session) / p["t0_s"])


def relax_draw(ctx, hw, rng):
    p = {"beta": rng.uniform(0.8, 1.5), "t0_s": 60.0 * rng.uniform(2.0, 10.0), "h_mm": rng.uniform(0.0, 200.0)}
    psi, eps = rng.uniform(0, np.pi), rng.uniform(0.05, 0.3)  # the relaxed bolt row's axis; the other axis' share
    R = np.array([[np.cos(psi), -np.sin(psi)], [np.sin(psi), np.cos(psi)]])
    C = R @ np.diag([1.0, eps]) @ R.T
    p["C"] = _size(relax_features(p, ctx, hw), C.ravel(), rng, 0.3, 0.7)
    return p


def relax_features(p, ctx, hw):
    M = mount_moment(ctx) * relax_factor(p, ctx.session)[:, None]
    r = ctx.target - np.array([0.0, 0.0, -p["h_mm"]])
    e = np.eye(3)
    return np.array([np.cross(e[a] * M[:, b:b + 1], r) for a in range(2) for b in range(2)])


def relax_apply(p, ctx, hw):
    return _amp_apply(p["C"], relax_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- beam-column boom
def boom_axis(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt


def amplification(p, ctx):
    """(P,) 1 / (1 - P_ax / P_cr): P_ax the compression along the boom (negative: tension)."""
    e = boom_axis(ctx)[:, :, 0]
    m = ctx.session.payload_kg + p["boom_kg"] / 2
    comp = m * G * (-e[:, 2])  # the weight's component pushing the tip towards the root when the boom points up
    return 1.0 / (1.0 - comp / p["P_cr"])


def column_draw(ctx, hw, rng):
    p = {"boom_kg": rng.uniform(0.3, 1.0)}
    m_top = float(ctx.session.payload_kg.max()) + p["boom_kg"] / 2
    p["P_cr"] = m_top * G / rng.uniform(0.2, 0.45)
    p["inv_EI"] = _size(column_features(p, ctx, hw), [1.0], rng, 0.3, 0.7)
    return p


def column_features(p, ctx, hw):
    e = boom_axis(ctx)[:, :, 0]
    g = np.array([0.0, 0.0, -1.0])
    perp = g - e * (e @ g)[:, None]
    L = BOOM_MM
    load = ctx.session.payload_kg * G * L ** 3 / 3 + p["boom_kg"] * G * L ** 3 / 8  # tip + own weight [N mm^3]
    return (perp * (load * amplification(p, ctx))[:, None])[None] / 1e9


def column_apply(p, ctx, hw):
    return _amp_apply(p["inv_EI"], column_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- leaf boom
def leaf_axes(p, ctx):
    """(P, 3), (P, 3) the bar's weak and strong principal axes across the boom."""
    R = boom_axis(ctx)
    c, s = np.cos(p["chi"]), np.sin(p["chi"])
    return c * R[:, :, 1] + s * R[:, :, 2], -s * R[:, :, 1] + c * R[:, :, 2]


def leaf_draw(ctx, hw, rng):
    p = {"chi": rng.uniform(0, np.pi), "ratio": rng.uniform(10.0, 50.0)}
    p["inv_EI"] = _size(leaf_features(p, ctx, hw), [1.0], rng, 0.3, 0.7)
    return p


def leaf_features(p, ctx, hw):
    n_w, n_s = leaf_axes(p, ctx)
    g = np.array([0.0, 0.0, -1.0])
    return ((n_w * (n_w @ g)[:, None] + n_s * (n_s @ g)[:, None] / p["ratio"]) * BOOM_MM ** 4 / 8e9)[None]


def leaf_apply(p, ctx, hw):
    return _amp_apply(p["inv_EI"], leaf_features(p, ctx, hw))
