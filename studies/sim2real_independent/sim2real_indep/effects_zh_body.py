"""Set ZH body effects (new physics, not in sets A-ZG): a thin-walled tubular pedestal softened by its section's
ovalisation (the Brazier effect); the base on a rim-clamped adapter plate that sinks under the vertical load and turns
under the moment; an inflated fabric boom that wrinkles beyond a moment; a boom held in a long clamp bush that gives as
an elastic foundation; and a target bracket swinging between the two stops of a loose pivot. Same protocol as
:mod:`effects_joint`.

Sources:

* Brazier pedestal: a thin-walled round tube bent by a moment flattens (its section ovalises), which lowers its
  bending stiffness progressively: M(kappa) = EI kappa (1 - 3/2 (1 - nu^2) (kappa r^2 / t)^2) (Brazier, "On the flexure
  of thin cylindrical shells and other thin sections", Proc. R. Soc. A 116, 1927; Calladine, *Theory of Shell
  Structures*, 1983, ch. 15), to first order kappa = M / EI (1 + (M / M_b)^2). A tall riser of thin sheet tube (H 1-2
  m) turns its head by kappa H and shifts it by kappa H^2 / 2, a rotation about a point H / 2 below the base. The riser
  also carries a side load (a cabinet or balancer console on its side: a bias moment M0 of 1-2 times the arm's largest,
  any direction), so the arm's moment acts on a pre-bent, pre-ovalised tube whose tangent compliance is about three
  times larger along M0 than across it; (|M0| / M_b)^2 0.8-1.5; the bias's own tilt belongs to the calibrated
  geometry. (First without the side load, (M_max / M_b)^2 0.3-0.8, H 1-2 m: on ur10 the link model at 1.09x, on
  kr16_like absorbed -- a tube bent only by the arm tilts along the moment nearly linearly, as an arm's sag or a
  joint-2 offset turns it.) Unlike set ZE's slender pedestal (the weight's P-delta amplification) and sets A-ZG's
  linear mounts, the compliance grows with the moment itself. Sized to 0.25-0.6 mm. Driven by the pose
  and payload (logged). The true structure: one column, amplitude 1 / EI.
* dished plate: the base bolted to the central boss of a thin steel adapter plate clamped at its rim (a plate bridging
  a pit or a machine's opening, a riser of h 300-800 mm standing on it): the boss sinks under the vertical load's
  change (its sink under the arm's own weight belongs to the calibrated geometry) and turns under the moment (annular
  plate, outer edge fixed, rigid central hub: Roark & Young, *Formulas for Stress and Strain*, 7th ed., table 11.2;
  Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, 1959, sec. 18-19), w = c_F dW and theta = c_M M about
  the plate's mid-plane, h below the base (first at the base itself and with the arm's whole weight sinking it:
  absorbed on tool_changer and kr16_like, the constant sink outweighing the rest; then on kr16_like the link model
  within 1.03x, the plate now on tool_changer alone); the parts change between blocks, so W does. Unlike sets A-ZG's
  mount tilts alone (a moment's rotation), the payload's weight also sinks the base. Sized to 0.25-0.6 mm. Driven by
  the pose and payload (logged). The true structure: two columns (c_F [mm / N], c_M [rad / (N m)]).
* inflated boom: an air-inflated fabric tube (a light boom on a soft-handling tool) bends as a beam until the bending
  stress cancels the pressure's axial prestress at its wall, at the wrinkling moment M_w = pi p r^3 / 2; beyond it the
  wrinkled side carries no load and the deflection grows progressively (Comer & Levy, "Deflections of an inflated
  circular-cylindrical cantilever beam", AIAA J. 1(7), 1963; Wielgosz & Thomas, "Deflections of inflatable fabric
  panels at high pressure", Thin-Walled Struct. 40, 2002): delta = delta_lin (1 + a (m - 1)^2) for m = M / M_w > 1, a
  1-3, M_w at the 40-70 % quantile of the session's root moments. Unlike the linear booms of sets A-ZG, set ZG's
  beam-column (amplified by the axial load) or set ZF's polymer boom, the stiffness falls past a moment that the
  pressure sets. Parts 0-3 kg changed between blocks. Sized to 0.3-0.7 mm. Driven by the pose and payload (logged). The
  true structure: one column, amplitude 1 / EI.
* collet root: a boom held in a long clamp bush (a collet or split bush of length >> 1 / beta) bears on the bush's
  wall as on an elastic foundation of modulus k; the root shifts and turns (semi-infinite beam on an elastic
  foundation loaded at its end by V and M: Hetenyi, *Beams on Elastic Foundation*, 1946, ch. 2): y0 = 2 beta (V - beta
  M) / k, theta0 = 2 beta^2 (2 beta M - V) / k, beta = (k / 4 EI)^(1/4), 1 / beta 15-40 mm; the tip moves by y0 +
  theta0 L. Unlike a boom's own bending (L^3 / 3 EI) or set Q's clamped ball joints, the give is the bush's contact
  foundation, whose shift and turn follow the shear and the moment in the ratio beta sets. Sized to 0.25-0.6 mm.
  Driven by the pose and payload (logged). The true structure: one column, amplitude 1 / k.
* loose pivot: a target bracket (length 150-250 mm, down the tool axis) hangs on a pin across the tool with an angular
  clearance +-delta between two stops; the bracket's weight rests it on the stop its moment about the pin chooses where
  that moment exceeds the pin's friction (10-30 % of the largest), and it stays where it was elsewhere (a mechanism
  with clearance: Flores et al., *Kinematics and Dynamics of Multibody Systems with Imperfect Joints*, 2008). Unlike the
  joints' lost motions of sets A-ZG, set K's ram roll or set P's quick change (a tool re-seated at each change), the
  clearance is about a tool-fixed pin and its side follows the tool's attitude, with memory. Sized to 0.25-0.6 mm.
  Driven by the pose sequence (logged). The true structure: one column, amplitude delta [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size

BOOM_MM = 400.0
PIVOT_MM = 200.0
G = kin.G


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- Brazier pedestal
def brazier_factor(p, M):
    """(P,) 1 + (|M_xy| / M_b)^2."""
    return 1.0 + (np.linalg.norm(M[:, :2], axis=1) / p["M_b"]) ** 2


def brazier_draw(ctx, hw, rng):
    M = mount_moment(ctx)
    big = float(np.linalg.norm(M[:, :2], axis=1).max())
    psi = rng.uniform(0, 2 * np.pi)
    p = {"H_mm": rng.uniform(1500.0, 2500.0)}
    p["M0"] = (big * rng.uniform(1.0, 2.0) * np.array([np.cos(psi), np.sin(psi)])).tolist()
    p["M_b"] = float(np.linalg.norm(p["M0"]) / np.sqrt(rng.uniform(0.8, 1.5)))
    p["inv_EI"] = _size(brazier_features(p, ctx, hw), [1.0], rng)
    return p


def brazier_curvature(p, M):
    """(P, 3) the curvature vector per unit 1 / EI [N m] under the arm's moment M on top of the bias M0, less the
    bias's own (part of the calibrated geometry)."""
    M0 = np.r_[p["M0"], 0.0]
    tot = M * np.array([1.0, 1.0, 0.0]) + M0
    return tot * brazier_factor(p, tot)[:, None] - M0 * brazier_factor(p, M0[None])[0]


def brazier_features(p, ctx, hw):
    kap = brazier_curvature(p, mount_moment(ctx))
    H = p["H_mm"]
    r = ctx.target - np.array([0.0, 0.0, -H / 2])
    return (np.cross(kap * H, r))[None] / 1e6


def brazier_apply(p, ctx, hw):
    return _amp_apply(p["inv_EI"], brazier_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dished plate
def total_weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * G


def plate_draw(ctx, hw, rng):
    p = {"h_mm": rng.uniform(300.0, 800.0)}
    rel = np.array([rng.uniform(1.0, 2.0), 1.0])
    F = plate_features(p, ctx, hw)
    s = [np.linalg.norm(F[k], axis=1).max() for k in range(2)]
    p["c"] = _size(F, rel / np.maximum(s, 1e-12), rng)
    return p


def plate_features(p, ctx, hw):
    W = total_weight(ctx)
    sink = np.zeros((len(W), 3))
    sink[:, 2] = -(W - W[0])  # the sink under the arm's own weight is part of its calibrated geometry
    M = mount_moment(ctx) * np.array([1.0, 1.0, 0.0])
    return np.array([sink, np.cross(M, ctx.target - np.array([0.0, 0.0, -p["h_mm"]]))])


def plate_apply(p, ctx, hw):
    return _amp_apply(p["c"], plate_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- inflated boom
def boom_frame(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt


def boom_load(p, ctx):
    """(P, 3) the weight's component across the boom [N] (part at the tip, half the boom's own) and (P,) its root
    moment [N m]."""
    e = boom_frame(ctx)[:, :, 0]
    g = np.array([0.0, 0.0, -1.0])
    perp = g - e * (e @ g)[:, None]
    w = (ctx.session.payload_kg + p["boom_kg"] / 2) * G
    return perp * w[:, None], np.linalg.norm(perp, axis=1) * w * BOOM_MM / 1000.0


def wrinkle_factor(p, m):
    return 1.0 + p["a"] * np.maximum(m / p["M_w"] - 1.0, 0.0) ** 2


def inflated_draw(ctx, hw, rng):
    p = {"boom_kg": rng.uniform(0.2, 0.6), "a": rng.uniform(1.0, 3.0)}
    _, M = boom_load(p, ctx)
    p["M_w"] = float(np.quantile(M, rng.uniform(0.4, 0.7)))
    p["inv_EI"] = _size(inflated_features(p, ctx, hw), [1.0], rng, 0.3, 0.7)
    return p


def inflated_features(p, ctx, hw):
    F, M = boom_load(p, ctx)
    return (F * (wrinkle_factor(p, M) * BOOM_MM ** 3 / 3)[:, None])[None] / 1e9


def inflated_apply(p, ctx, hw):
    return _amp_apply(p["inv_EI"], inflated_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- collet root
def collet_give(p, V, M_Nmm):
    """Root shift y0 [mm] and turn theta0 [rad] per unit 1 / k of shear V [N] and moment M [N mm]."""
    b = 1.0 / p["inv_beta_mm"]
    return 2 * b * (V - b * M_Nmm), 2 * b ** 2 * (2 * b * M_Nmm - V)


def collet_draw(ctx, hw, rng):
    p = {"boom_kg": rng.uniform(0.3, 1.0), "inv_beta_mm": rng.uniform(15.0, 40.0)}
    p["inv_k"] = _size(collet_features(p, ctx, hw), [1.0], rng)
    return p


def collet_features(p, ctx, hw):
    e = boom_frame(ctx)[:, :, 0]
    g = np.array([0.0, 0.0, -1.0])
    perp = g - e * (e @ g)[:, None]
    V = (ctx.session.payload_kg + p["boom_kg"]) * G
    M = (ctx.session.payload_kg + p["boom_kg"] / 2) * G * BOOM_MM
    y0, th0 = collet_give(p, V, M)
    return (perp * (y0 - th0 * BOOM_MM)[:, None])[None]


def collet_apply(p, ctx, hw):
    return _amp_apply(p["inv_k"], collet_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- loose pivot
def pivot_moment(ctx):
    """(P,) the bracket's gravity moment about the pin (tool y) per unit weight and half length: g's tool-x share."""
    Rt = boom_frame(ctx)
    return -Rt[:, 2, 0]  # gravity (0, 0, -1) in the tool frame, its x component


def pivot_side(p, ctx):
    mom = pivot_moment(ctx)
    side = np.zeros(len(mom))
    last = 1.0
    for k, m in enumerate(mom):
        if abs(m) > p["f"]:
            last = np.sign(m)
        side[k] = last
    return side


def pivot_draw(ctx, hw, rng):
    p = {"f": rng.uniform(0.1, 0.3), "L_mm": PIVOT_MM}
    p["delta"] = _size(pivot_features(p, ctx, hw), [1.0], rng)
    return p


def pivot_features(p, ctx, hw):
    Rt = boom_frame(ctx)
    arm = np.cross([0.0, 1.0, 0.0], [0.0, 0.0, p["L_mm"]])  # a pin along tool y, the target L down the tool axis
    return (np.einsum("pij,j->pi", Rt, arm) * pivot_side(p, ctx)[:, None])[None]


def pivot_apply(p, ctx, hw):
    return _amp_apply(p["delta"], pivot_features(p, ctx, hw))
