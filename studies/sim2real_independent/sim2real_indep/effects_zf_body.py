"""Set ZF body effects (new physics, not in sets A-ZE): the arm on a shelf bracket cantilevered from a wall or a machine,
bent by the weight and the moment the arm puts on its tip; the arm's base on a shim stack whose friction lets it slip
back and forth as the moment changes; a 3-D-printed polymer tool boom whose modulus falls as the shop's air warms; and a
tool flange whose bolted joint opens once the tool's moment exceeds its preload. Same protocol as :mod:`effects_joint`.

Sources:

* shelf bracket: the arm's base on the tip of a steel shelf bracket of length L 300-600 mm cantilevered horizontally
  from a wall at heading psi; the tip under the vertical load W and the moment M_u about the bracket's bending axis
  turns by (W L^2 / 2 + M_u L) / EI and drops by (W L^3 / 3 + M_u L^2 / 2) / EI (Roark's *Formulas for Stress and
  Strain*, 7th ed., table 8.1, cases 1a and 3a). Unlike the mounts of sets A-ZE (a tilt following the moment, or a
  column's P-delta about a vertical axis) the tilt follows the weight on the bracket (the logged part, new each block)
  as well as the moment, about a fixed axis. Sized to 0.3-0.7 mm. Driven by the pose and the payload (logged). The true
  structure: one column, amplitude 1 / EI.
* shim friction: the base bolted through a stack of shims and slotted holes whose faying surfaces slip in micro-slip
  (Iwan's model of a bolted joint: Iwan, "A distributed-element model for hysteresis", ASME J. Appl. Mech. 33, 1966;
  Segalman, ASME J. Appl. Mech. 72, 2005): each change of the overturning moment tips the base by +-f about the
  moment's axis, by the sign of the change since the last pose (the friction's hysteresis), about a pivot h 0-200 mm
  below the base. Unlike the elastic (linear, saturating, P-delta) mounts of sets A-ZE, the tilt follows the sign of
  the moment's last change. Sized to 0.25-0.6 mm. Driven by the pose sequence (logged). The true structure: two columns
  (about x and y), amplitudes f_x, f_y [rad].
* polymer boom: a 3-D-printed PA12 tool boom (L 400 mm along the tool's x, the target at its tip) sagging under its
  own and the tool's weight, W_perp L^3 / (3 E I), whose modulus falls by kappa 1.5-3 %/K as the air warms (PA12's
  modulus roughly halves between 23 and 60 C: Ashby, *Materials Selection in Mechanical Design*, 4th ed., 2011, ch. 4;
  supplier data sheets, as recalled): 1 / E(T) = (1 + kappa (T - T_0)) / E_0. The shop's air drifts by 3-6 K over the
  session (logged). Unlike sets A-ZE's booms (fixed stiffness; set ZC's curing bond stiffening with time) the sag follows
  the logged air temperature. Sized to 0.3-0.7 mm. Driven by the pose and the air temperature (logged). The true
  structure: one column, amplitude W L^3 / (3 E_0 I).
* flange gapping: the tool (m 3-10 kg at the middle of a 400 mm boom along the tool's x) on a bolted flange: below the
  decompression moment M_0 the preloaded joint is stiff; beyond, the joint opens on one side and its rotational
  stiffness drops (VDI 2230 Part 1, 2015: the opening limit of an eccentrically loaded bolted joint), so the flange turns
  by c max(|M| - M_0, 0) about the moment's axis, M_0 30-60 % of the largest moment. Unlike sets A-ZE's tool mounts
  (linear, bush, insulating flange) the joint's rotation starts at a threshold of the tool's moment. Sized to 0.25-0.6
  mm. Driven by the pose (logged) and the tool's mass (not logged). The true structure: one column, amplitude c.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_body import total_weight_N
from sim2real_indep.effects_ze_joint import _size

G = kin.G
BOOM_MM = 400.0


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- shelf bracket
def shelf_turn_drop(p, ctx):
    """(P,), (P,) the bracket tip's turn and drop per unit 1 / EI [N mm^2, N mm^3] / 1e9."""
    e = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    u = np.cross([0.0, 0.0, 1.0], e)
    W, L = total_weight_N(ctx), p["L_mm"]
    Mu = (mount_moment(ctx) @ u) * 1000.0
    return (W * L ** 2 / 2 + Mu * L) / 1e9, (W * L ** 3 / 3 + Mu * L ** 2 / 2) / 1e9


def shelf_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi), "L_mm": rng.uniform(300.0, 600.0)}
    p["c"] = _size(shelf_features(p, ctx, hw), [1.0], rng, 0.3, 0.7)
    return p


def shelf_features(p, ctx, hw):
    e = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    u = np.cross([0.0, 0.0, 1.0], e)
    th, dr = shelf_turn_drop(p, ctx)
    return (np.cross(th[:, None] * u, ctx.target) - dr[:, None] * np.array([0.0, 0.0, 1.0]))[None]


def shelf_apply(p, ctx, hw):
    return _amp_apply(p["c"], shelf_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- shim friction
def slip_sign(ctx):
    """(P, 2) the sign of the change of the moment's x and y components since the last pose (the first: its own)."""
    M = mount_moment(ctx)[:, :2]
    dM = np.vstack([M[:1], np.diff(M, axis=0)])
    return np.sign(dM)


def shim_draw(ctx, hw, rng):
    p = {"h_mm": rng.uniform(0.0, 200.0)}
    p["f"] = _size(shim_features(p, ctx, hw), rng.uniform(0.5, 1.5, 2), rng)
    return p


def shim_features(p, ctx, hw):
    s = slip_sign(ctx)
    r = ctx.target - np.array([0.0, 0.0, -p["h_mm"]])
    return np.array([np.cross(s[:, k:k + 1] * np.eye(3)[k], r) for k in range(2)])


def shim_apply(p, ctx, hw):
    return _amp_apply(p["f"], shim_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- polymer boom
def modulus_factor(p, session):
    """(P,) E_0 / E(T) = 1 + kappa (T - T_0), T the logged air, T_0 the session's first."""
    return 1.0 + p["kappa"] * (session.air_c - session.air_c[0])


def polymer_draw(ctx, hw, rng):
    p = {"kappa": rng.uniform(0.015, 0.03)}
    p["amp"] = _size(polymer_features(p, ctx, hw), [1.0], rng, 0.3, 0.7)
    return p


def polymer_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    e = Rt[:, :, 0]
    g = np.array([0.0, 0.0, -1.0])
    perp = g - e * (e @ g)[:, None]
    return (perp * modulus_factor(p, ctx.session)[:, None])[None]


def polymer_apply(p, ctx, hw):
    return _amp_apply(p["amp"], polymer_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- flange gapping
def flange_moment(ctx, m_kg=1.0):
    """(P, 3) the tool's gravity moment [N m] about the flange (its mass at the boom's middle)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    r = Rt[:, :, 0] * BOOM_MM / 2000.0
    return np.cross(r, np.array([0.0, 0.0, -m_kg * G]))


def gap_rotation(p, ctx):
    """(P, 3) the opened joint's rotation per unit c: the moment's axis times max(|M| - M_0, 0)."""
    M = flange_moment(ctx, p["m_kg"])
    n = np.linalg.norm(M, axis=1, keepdims=True)
    return M / np.maximum(n, 1e-12) * np.maximum(n - p["M0"], 0.0)


def gap_draw(ctx, hw, rng):
    p = {"m_kg": rng.uniform(3.0, 10.0)}
    p["M0"] = float(np.linalg.norm(flange_moment(ctx, p["m_kg"]), axis=1).max() * rng.uniform(0.3, 0.6))
    p["c"] = _size(gap_features(p, ctx, hw), [1.0], rng)
    return p


def gap_features(p, ctx, hw):
    fl, _ = kin.flange(ctx.chain, ctx.q)
    return np.cross(gap_rotation(p, ctx), ctx.target - fl)[None]


def gap_apply(p, ctx, hw):
    return _amp_apply(p["c"], gap_features(p, ctx, hw))
