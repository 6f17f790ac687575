"""Set ZP body effects (new physics, not in sets A-ZO): the arm's base held on a steel floor plate by a switchable
permanent-magnet base, whose rough interface is stiffer the harder it is pressed; an unanchored, ballasted stand whose
feet lift off the floor; parts held by a needle gripper; and a deep, narrow gripper boom near lateral-torsional
buckling. Same protocol as :mod:`effects_joint`.

Sources:

* magnet base (``magnet_base``): portable arms are clamped to steel structures (hull blocks, fixtures) by switchable
  permanent-magnet bases (holding forces of 1.2-2.5 times the weight of the arm and its part); the base plate rests on the steel through a
  ground interface whose normal stiffness grows in proportion to the contact pressure (rough surfaces:
  Greenwood & Williamson, Proc. R. Soc. A 295, 1966; Johnson, *Contact Mechanics*, 1985, ch. 13: the real contact area
  and the stiffness go as the load), so each quarter of the interface closes by (1 / kappa) ln(p / p_ref) -- the magnet's
  pull sets p_ref and softens the law's curvature. The base's four quarters at (+-a, +-b), 0.06-0.12 m (a compact magnet base), any heading, the
  interface 20-60 mm below the base frame; parts of up to the rated payload changed between blocks. Unlike set P's
  vacuum feet (elastomer pads held by suction), set X's levelling foot or set ZM's cone mounts, the compliance is the
  magnetically pressed metal-to-metal joint's logarithmic law. Driven by the pose and the payload (logged). The true
  structure: one column, amplitude 1 / kappa [mm].
* ballasted stand (``ballast_stand``): an unanchored stand (trade-fair and temporary cells) on four levelling feet on
  rubber pads (linear, no tension), ballasted so that the heaviest overturning moments unload a foot: a foot that
  would go into tension lifts off and the stand rocks onto the other three (unilateral contact: Johnson, ch. 5;
  overturning of free-standing bodies: Housner, BSSA 53, 1963, statics). Feet at (+-a, +-b), 0.25-0.4 / 0.2-0.3 m,
  any heading, the pads 100-300 mm below the base frame; the ballast 0.05-0.4 times the weight of the arm and part, more
  where that would leave the stand on two feet (it would tip). Unlike set F's
  uplift (an anchored plate prying its bolts) or the plates of sets ZM-ZO (springs that carry tension), the support
  changes from four feet to three. Driven by the pose and the payload (logged). The true structure: one column,
  amplitude the pads' compliance [mm per N].
* needle gripper (``needle_gripper``): textile, foam and composite blanks are held by needle grippers, two rows of
  hardened needles (0.8-1.2 mm, 10-20 of them) driven into the part at +-alpha (30-45 deg) from the tool axis
  (Schmalz / Schunk needle grippers, as recalled); each needle is stiff along itself and a short cantilever across
  (3 E I / l^3, l 5-15 mm: Timoshenko & Gere, *Mechanics of Materials*), so the rows' stiffness in the tool frame is
  N k diag(cos^2 alpha, 1, sin^2 alpha) and the part, and the target on it, move by its inverse times the weight's
  components. Parts of 1-8 / 2-14 / 10-60 kg changed between blocks. Unlike set ZA's soft fingers, set ZJ's gecko pad
  or set X's suction cup, the compliance is the needles' anisotropic bending. Driven by the attitude and the payload
  (logged). The true structure: one column, amplitude 1 / (N k).
* lateral-torsional buckling (``ltb_boom``): a deep, narrow gripper boom (a flat bar on edge, 400 mm along the tool
  axis, the part at its tip) bends in its stiff plane under the weight's component across it; a small initial sweep
  a0 is amplified towards lateral-torsional buckling, u = a0 mu / (1 - mu^2), mu = M / M_cr (Timoshenko & Gere,
  *Theory of Elastic Stability*, 2nd ed., 1961, ch. 6; Trahair, *Flexural-Torsional Buckling of Structures*, 1993),
  with the largest moment at 40-70 % of M_cr. Parts of 1-8 / 2-14 / 10-60 kg changed between blocks. Unlike set ZG's
  beam-column (an axial force's P-delta) or set E's channel, the lateral move grows with the moment in the other plane.
  Driven by the attitude and the payload (logged). The true structure: one column, amplitude a0 [mm].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zm_body import _plate, _to_world, mount_loads, part_loads, total_weight

LTB_MM = 400.0  # the boom along the tool axis, the part and the target at its tip


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- magnet base
def magnet_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / kappa [mm]: the plate through the quarters' closures ln(p / p_ref)."""
    R, xy = mount_loads(p, ctx)
    R = R + p["F_m"] / 4
    return _plate(p, ctx, np.log(R / p["R_ref"]), xy)


def magnet_draw(ctx, hw, rng):
    W = total_weight(ctx)
    p = {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.06, 0.12)), "b": float(rng.uniform(0.06, 0.12)),
         "pivot_mm": float(rng.uniform(20.0, 60.0)), "F_m": float(W.min() * rng.uniform(1.2, 2.5))}
    R, _ = mount_loads(p, ctx)
    if (R + p["F_m"] / 4).min() <= 0.05 * p["F_m"] / 4:  # the magnet must hold every quarter down
        p["F_m"] = float(4 * (0.05 * p["F_m"] / 4 - R.min()) + p["F_m"])
    p["R_ref"] = float(p["F_m"] / 4 + W.min() / 4)
    p["inv_kappa"] = float(_size(magnet_features(p, ctx, hw), [1.0], rng)[0])
    return p


def magnet_apply(p, ctx, hw):
    return _amp_apply([p["inv_kappa"]], magnet_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ballasted stand
def stand_loads(p, ctx, clip=True):
    """(P, 4) the feet's loads [N], none in tension: on four feet where they all press, else on the three whose
    statics hold (the foot that would pull lifts), and the feet's positions (4, 2) [m]."""
    R4, xy = mount_loads(p, ctx)
    R4 = R4 + p["W_b"] / 4
    W, Mx, My = R4.sum(axis=1), R4 @ xy[:, 0], R4 @ xy[:, 1]
    out = R4.copy()
    for i in np.flatnonzero(R4.min(axis=1) < 0):
        off = int(np.argmin(R4[i]))
        on = [k for k in range(4) if k != off]
        A = np.vstack([np.ones(3), xy[on, 0], xy[on, 1]])
        out[i] = 0.0
        out[i, on] = np.linalg.solve(A, [W[i], Mx[i], My[i]])
    return (np.maximum(out, 0.0) if clip else out), xy


def stand_features(p, ctx, hw):
    """(1, P, 3) per unit pad compliance [mm per N]: the plane through the pressed feet (a lifted foot's point on it)."""
    R, xy = stand_loads(p, ctx)
    d = R.copy()
    for i in np.flatnonzero((R <= 0).any(axis=1)):
        off = int(np.argmin(R[i]))
        opp = 3 - off  # corners (+a+b, +a-b, -a+b, -a-b): d0 + d3 = d1 + d2
        d[i, off] = d[i, 1] + d[i, 2] - d[i, opp] if off in (0, 3) else d[i, 0] + d[i, 3] - d[i, opp]
    return _plate(p, ctx, d, xy)


def stand_draw(ctx, hw, rng):
    W = total_weight(ctx)
    p = {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.25, 0.4)), "b": float(rng.uniform(0.2, 0.3)),
         "pivot_mm": float(rng.uniform(100.0, 300.0)), "W_b": float(W.min() * rng.uniform(0.05, 0.4))}
    while stand_loads(p, ctx, clip=False)[0].min() < 0:  # never on two feet: the stand would tip
        p["W_b"] *= 1.1
    p["C"] = float(_size(stand_features(p, ctx, hw), [1.0], rng)[0])
    return p


def stand_apply(p, ctx, hw):
    return _amp_apply([p["C"]], stand_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- needle gripper
def needle_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / (N k) [mm per N]: the part's move under its weight, tool frame to base."""
    F, _ = part_loads(ctx, 0.0)
    ca, sa = np.cos(p["alpha"]) ** 2, np.sin(p["alpha"]) ** 2
    local = F / np.array([ca, 1.0, sa])
    return _to_world(ctx, local)[None]


def needle_draw(ctx, hw, rng):
    p = {"alpha": float(np.deg2rad(rng.uniform(30.0, 45.0)))}
    p["inv_Nk"] = float(_size(needle_features(p, ctx, hw), [1.0], rng)[0])
    return p


def needle_apply(p, ctx, hw):
    return _amp_apply([p["inv_Nk"]], needle_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- LTB boom
def ltb_ratio(p, ctx):
    """(P,) mu = M / M_cr: the part's weight across the boom (tool x) times its length."""
    F, _ = part_loads(ctx, 0.0)
    return F[:, 0] * p["L_mm"] / 1000.0 / p["M_cr"]


def ltb_features(p, ctx, hw):
    """(1, P, 3) per unit a0 [mm]: the tip's lateral move (tool y) mu / (1 - mu^2)."""
    mu = ltb_ratio(p, ctx)
    local = np.zeros((len(mu), 3))
    local[:, 1] = mu / (1 - mu ** 2)
    return _to_world(ctx, local)[None]


def ltb_draw(ctx, hw, rng):
    F, _ = part_loads(ctx, 0.0)
    L = LTB_MM
    Mmax = max(float(np.abs(F[:, 0]).max()) * L / 1000.0, 1e-6)
    p = {"L_mm": L, "M_cr": float(Mmax / rng.uniform(0.4, 0.7))}
    p["a0"] = float(_size(ltb_features(p, ctx, hw), [1.0], rng)[0])
    return p


def ltb_apply(p, ctx, hw):
    return _amp_apply([p["a0"]], ltb_features(p, ctx, hw))
