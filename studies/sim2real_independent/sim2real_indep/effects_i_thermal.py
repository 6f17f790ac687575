"""Set I thermal effects (new physics, not in sets A-H): an end-of-arm boom of aluminium profile carrying a steel
linear rail on one face, which bows like a bimetal strip as the hall's air warms it; and the joint housings growing
along their own axes with their drives' heat, so that every body beyond a joint shifts along that joint's axis.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* bimetal boom: two bars joined along their length (axial rigidities E1 A1, E2 A2, bending E1 I1, E2 I2, centroids
  d apart) under a uniform temperature change dT take the curvature kappa = (alpha2 - alpha1) dT d / (d^2 +
  (E1 I1 + E2 I2)(1 / E1 A1 + 1 / E2 A2)) (Timoshenko, "Analysis of bi-metal thermostats", J. Opt. Soc. Am. 11,
  1925, in its general form for bars of any section), the side of lower expansion concave; bar 1's centroid
  strains by alpha1 dT + (E1 I1 + E2 I2) kappa / (d E1 A1). The boom (a square aluminium profile of 40-70 mm,
  wall 3-5 mm, 400-900 mm long; alpha 23e-6 /K, E 70 GPa) carries a steel rail of 20-30 mm square (11.7e-6 /K, 210
  GPa) on one face (a servo slide or gripper stroke on the tool; assumed); cantilevered from the flange, its end
  (the target, see :func:`effects_i.probe_hook`) moves by the growth along the boom and kappa L^2 / 2 towards the
  rail. The profile follows the hall air through a lumped lag of 5-20 min (tau = rho c t / h, Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 5); sessions in a hall whose air drifts by 3-6 K.
* housing growth: a joint housing between its stator flange and its output flange grows along the axis by
  alpha L_h dT as its drive heats it (handbook CTEs as :mod:`hardware`), shifting the distal chain along the joint's
  current axis (an axis-point shift the uniform link expansion of set A does not contain; the thermal behaviour of
  robot joints: Heisel, Richter & Wurst, CIRP Annals 46(1), 1997). Housing lengths 120-180 / 100-150 mm (main /
  wrist axes of ur10), 150-250 / 60-120 mm (kr16_like), 200-300 / 80-150 mm (tool_changer), the output flange on
  either side (assumed); the drive heat of :func:`effects_c_thermal.drive_heat` into one lumped node per drive (15-45
  min, 20-35 K above ambient under the exercise cycle -- housings of 40-60 degC --, cold start; assumed, as set H's
  helical shift). The links' own expansion is set
  A's heat and left out: the case isolates the axis shift.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import effects_h_thermal as ht
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

ALUMINIUM = (70e9, 23e-6)
STEEL = (210e9, 11.7e-6)


# ------------------------------------------------------------------------------------------ bimetal boom
def bimetal(E1, A1, I1, a1, E2, A2, I2, a2, d):
    """Curvature [1/m per K] (positive: bar 2's side convex) and bar 1's centroid strain [1/K] of two joined bars,
    bar 2's centroid at +d [m] from bar 1's."""
    S = E1 * I1 + E2 * I2
    kappa = (a2 - a1) * d / (d * d + S * (1 / (E1 * A1) + 1 / (E2 * A2)))
    return kappa, a1 + S * kappa / (d * E1 * A1)


def boom_draw(ctx, hw, rng):
    a, t, r = rng.uniform(0.04, 0.07), rng.uniform(0.003, 0.005), rng.uniform(0.02, 0.03)
    A1, I1 = a * a - (a - 2 * t) ** 2, (a ** 4 - (a - 2 * t) ** 4) / 12
    kappa, eps = bimetal(ALUMINIUM[0], A1, I1, ALUMINIUM[1], STEEL[0], r * r, r ** 4 / 12, STEEL[1], (a + r) / 2)
    e = ctx.probe_mm / np.linalg.norm(ctx.probe_mm)
    u = np.cross(e, [1.0, 0, 0] if abs(e[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    ang = rng.uniform(0, 2 * np.pi)
    return {"kappa_per_K": kappa, "eps_per_K": eps, "rail_dir": np.cos(ang) * u + np.sin(ang) * np.cross(e, u),
            "tau_s": rng.uniform(5, 20) * 60}


def boom_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per K of the boom: its growth along its axis and its bow (towards the
    rail for kappa < 0), times the boom's temperature change since the session start."""
    L = np.linalg.norm(ctx.probe_mm)                                     # [mm]
    e = ctx.probe_mm / L
    _, Rt = kin.flange(ctx.chain, ctx.q)
    dT = eb.structure_temperature(p, ctx)[:, None]
    grow = (Rt @ (p["eps_per_K"] * L * e)) * dT
    bow = (Rt @ (-p["kappa_per_K"] * (L / 1000.0) ** 2 / 2 * 1000.0 * p["rail_dir"])) * dT
    return np.array([grow, bow])


def boom_apply(p, ctx, hw):
    return Contribution(displace=boom_parts(p, ctx).sum(axis=0))


def boom_features(p, ctx, hw):
    return boom_parts(p, ctx)


# ----------------------------------------------------------------------------------------- housing growth
#: housing length along the axis [m]: main axes 1-3, wrist axes (assumed)
HOUSING_M = {"ur10": ((0.12, 0.18), (0.10, 0.15)), "kr16_like": ((0.15, 0.25), (0.06, 0.12)),
             "tool_changer": ((0.20, 0.30), (0.08, 0.15))}


def housing_draw(ctx, hw, rng):
    joints = [int(j) for j in np.flatnonzero(ctx.chain.revolute)]
    n = ctx.chain.n
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    ex_w = ct.drive_heat(ctx, hw, accel, duty, exercise_only=True)
    main, wrist = HOUSING_M[ctx.chain.name]
    L = np.array([rng.uniform(*(main if j < 3 else wrist)) for j in joints])
    return {"joints": joints, "accel_s": accel, "duty": duty, "tau_s": rng.uniform(15, 45, len(joints)) * 60,
            "R_K_per_W": rng.uniform(20, 35, len(joints)) / np.maximum(ex_w[joints], 1e-3),
            "grow_mm_per_K": 1000.0 * hw["material"]["cte"] * L * rng.choice([-1, 1], len(joints))}


def housing_parts(p, ctx, hw):
    """Target displacement (m, P, 3) [mm] per mm of growth of each housing: the current axis times its drive's
    temperature rise [K]."""
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    dT = ht.drive_rise(p, ctx, hw)
    return np.array([w[:, j] * dT[:, k:k + 1] for k, j in enumerate(p["joints"])])


def housing_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["grow_mm_per_K"], housing_parts(p, ctx, hw)))


def housing_features(p, ctx, hw):
    return housing_parts(p, ctx, hw)
