"""Set U body effects (new physics, not in sets A-T): the arm on the table of a tilting (trunnion) positioner held by
its worm drive; the arm's base plate straddling a sawn contraction joint of the floor slab, whose two sides carry the
tilting moment unequally; a light sandwich boom across the tool, carrying the part and the target, deflecting in the
bending of its faces and the shear of its foam core; and the target on a telescopic sleeve extension that rocks across
the clearance of its overlap towards the side gravity pulls it. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* trunnion positioner: the arm stands on the table of a one-axis tilting positioner (welding and machining cells), the
  table held about its horizontal trunnion axis by a self-locking worm stage; the worm's and the wheel's teeth, the worm
  shaft's thrust bearings and the trunnion bearings give a torsional stiffness k_t about that axis only (worm gear
  stiffness: Niemann & Winter, *Maschinenelemente* III, 1983; positioner data sheets give tilting torques of 1-20 kN m,
  as recalled). The arm's gravity moment about the axis, M_a = a . M (M about the base origin: the axis lies below it,
  and a vertical load's moment about a point straight below is the same), tilts the table by M_a / k_t about the axis,
  150-600 mm below the base (assumed). k_t 0.2-0.8e6 / 2-8e6 / 1-4e7 N m/rad (ur10 / kr16_like / tool_changer; assumed;
  first 0.4-1.5e6 on ur10: 0.03 mm, absorbed in a trial draw), the axis' azimuth uniform. The true structure: one
  column, amplitude 1 / k_t.
* slab joint: a slab on grade is weakest at its joints: a load at a joint deflects the slab some 1.5-3 times as much as
  the same load inside the panel when the joint transfers little shear (Westergaard, "Stresses in concrete pavements
  computed by theoretical analysis", Public Roads 7, 1926: edge against interior loading; load transfer efficiency of
  sawn joints: Huang, *Pavement Analysis and Design*, 2004, ch. 4). A base plate straddling a sawn joint tilts about the
  joint's line, by c_s M_a when the moment presses the plate's edge on the weaker side and c_i M_a the other way (c_s /
  c_i 2-5). c_i from the plate stiffness range of :mod:`hardware` (1 / k, k 2-20e6 / 0.5-5e6 N m/rad), the joint line
  0-150 mm off the base's centre, its azimuth uniform (assumed). The pivot is the slab's surface on the joint line, the
  pedestal's height below the base. The true structure: two columns (the moment's two signs), amplitudes c_s and c_i.
* sandwich boom: light gripper booms are foam- or honeycomb-core sandwich beams; a sandwich cantilever of faces' bending
  stiffness D and core shear stiffness S = G_c b c^2 / t_c deflects at its tip by F (L^3 / (3 D) + L / S) under a tip
  load F across its faces, the core's shear as large as the faces' bending in short foam-core booms (Allen, *Analysis
  and Design of Structural Sandwich Panels*, 1969, ch. 2; Zenkert, *An Introduction to Sandwich Construction*, 1995).
  The boom lies across the tool axis at the flange (along the tool's x), its faces normal to the tool axis, 400 mm long,
  the part (the logged payload) and a 1-3 kg gripper at its tip with the target (:func:`effects_u.probe_hook`), and its
  own weight w L; the weight's component along the faces' normal deflects it along that normal. Core: PMI foam G_c 20-60
  MPa (Rohacell data sheets, as recalled), b 80-150 mm, c 20-40 mm, faces 1-2 mm aluminium (assumed). The true
  structure: two columns (the part's weight and the boom's own), amplitudes the tip load's compliance and the own
  weight's deflection.
* sleeve clearance: a target carried on a telescopic extension -- an inner tube in a clamped outer sleeve -- rocks in
  the overlap by its radial clearance c over the overlap length l (the tilt c / l of a shaft in a bushing: ISO 286
  clearance fits; a worn sliding fit), towards the side the weight across the tube pulls it, so the tip throws by c L /
  l in the direction of gravity's component across the tube whatever its size; near a vertical tube the friction in the
  overlap holds it part way: the throw scales by |g_perp| / sqrt(|g_perp|^2 + g_f^2). c 0.03-0.12 mm, l 40-80 mm, the
  target 250 mm beyond the overlap along the tool axis (:func:`effects_u.probe_hook`), g_f 0.5-2 m/s^2 (assumed). The
  true structure: one column, amplitude the throw c L / l.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment

Z = np.array([0.0, 0.0, 1.0])


def _gravity_tool(ctx):
    """(P, 3, 3) tool rotations and (P, 3) the gravity vector [m/s^2] in the tool frame."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt, np.einsum("pji,j->pi", Rt, -kin.G * Z)


def _tilt(axis, M_a, target, pivot):
    """(P, 3) displacement [mm] of the target for a rotation M_a (P,) [rad per unit compliance] about ``axis``
    through ``pivot``."""
    return np.cross(axis[None] * M_a[:, None], target - pivot)


# ------------------------------------------------------------------------------------------------ trunnion
TRUNNION_K = {"ur10": (0.2e6, 0.8e6), "kr16_like": (2e6, 8e6), "tool_changer": (1e7, 4e7)}


def trunnion_draw(ctx, hw, rng):
    psi = rng.uniform(0, np.pi)
    return {"axis": np.array([np.cos(psi), np.sin(psi), 0.0]), "h_mm": rng.uniform(150.0, 600.0),
            "k_t": rng.uniform(*TRUNNION_K[ctx.chain.name])}


def trunnion_shape(p, ctx):
    M_a = mount_moment(ctx) @ p["axis"]
    return _tilt(p["axis"], M_a, ctx.target, np.array([0.0, 0.0, -p["h_mm"]]))


def trunnion_apply(p, ctx, hw):
    return Contribution(displace=trunnion_shape(p, ctx) / p["k_t"])


def trunnion_features(p, ctx, hw):
    return trunnion_shape(p, ctx)[None]


# ---------------------------------------------------------------------------------------------- slab joint
SLAB_K = {"ur10": (1e6, 5e6), "kr16_like": (5e6, 25e6), "tool_changer": (25e6, 120e6)}


def slab_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    a = np.array([np.cos(psi), np.sin(psi), 0.0])
    n = np.cross(Z, a)
    k = np.exp(rng.uniform(*np.log(SLAB_K[ctx.chain.name])))
    c_i = 1.0 / k
    return {"axis": a, "pivot": n * rng.uniform(0.0, 150.0) - Z * hw["mount"]["height_mm"],
            "c_i": c_i, "c_s": c_i * rng.uniform(2.0, 4.0)}


def slab_parts(p, ctx):
    """(2, P, 3): the tilt's displacement per unit compliance for the moment's positive and negative parts."""
    M_a = mount_moment(ctx) @ p["axis"]
    return np.array([_tilt(p["axis"], np.maximum(M_a, 0.0), ctx.target, p["pivot"]),
                     _tilt(p["axis"], np.minimum(M_a, 0.0), ctx.target, p["pivot"])])


def slab_apply(p, ctx, hw):
    pos, neg = slab_parts(p, ctx)
    return Contribution(displace=p["c_s"] * pos + p["c_i"] * neg)


def slab_features(p, ctx, hw):
    return slab_parts(p, ctx)


# -------------------------------------------------------------------------------------------- sandwich boom
BOOM_MM = 400.0   # the boom's length along the tool's x (the target's offset, effects_u.probe_hook)
#: per arm: the boom's width and core depth ranges [m] (sized for the arm's parts)
BOOM_SECTION = {"ur10": ((0.08, 0.15), (0.02, 0.04)), "kr16_like": ((0.15, 0.25), (0.03, 0.05)),
                "tool_changer": ((0.3, 0.5), (0.06, 0.1))}


def boom_draw(ctx, hw, rng):
    L = BOOM_MM / 1000.0
    (b_lo, b_hi), (c_lo, c_hi) = BOOM_SECTION.get(ctx.chain.name, BOOM_SECTION["ur10"])
    G_c, b, c = rng.uniform(20e6, 60e6), rng.uniform(b_lo, b_hi), rng.uniform(c_lo, c_hi)
    t_f, E_f = rng.uniform(0.001, 0.002), 70e9
    D = E_f * b * t_f * (c + t_f) ** 2 / 2                           # faces' bending stiffness [N m^2]
    S = G_c * b * (c + t_f) ** 2 / c                                  # core shear stiffness [N]
    w = (2 * t_f * 2700 + c * 75.0) * b * kin.G                       # own weight [N/m] (core 75 kg/m^3)
    p = {"L_m": L, "D": D, "S": S, "w_N_m": w, "m_tip": rng.uniform(1.0, 3.0)}
    p["c_tip"] = (L ** 3 / (3 * D) + L / S) * 1000.0                 # tip compliance [mm/N]
    p["d_own"] = (w * L ** 4 / (8 * D) + w * L ** 2 / (2 * S)) * 1000.0 / kin.G   # per unit g [mm s^2/m]
    return p


def boom_parts(p, ctx):
    """(2, P, 3): the tip's deflection along the faces' normal (the tool axis) per unit compliance of the tip load
    (part and gripper: (m_part + m_tip) g_n [N]) and per unit of the own weight's deflection (g_n [m/s^2])."""
    Rt, g_t = _gravity_tool(ctx)
    n = Rt[:, :, 2]
    g_n = g_t[:, 2]
    m = ctx.session.payload_kg + p["m_tip"]
    return np.array([n * (m * g_n)[:, None], n * g_n[:, None]])


def boom_apply(p, ctx, hw):
    tip, own = boom_parts(p, ctx)
    return Contribution(displace=p["c_tip"] * tip + p["d_own"] * own)


def boom_features(p, ctx, hw):
    return boom_parts(p, ctx)


# ------------------------------------------------------------------------------------------ sleeve clearance
SLEEVE_MM = 250.0  # the target's distance beyond the overlap, along the tool axis (effects_u.probe_hook)


def sleeve_draw(ctx, hw, rng):
    c, l = rng.uniform(0.03, 0.12), rng.uniform(40.0, 80.0)
    return {"c_mm": c, "l_mm": l, "throw_mm": c * SLEEVE_MM / l, "g_f": rng.uniform(0.5, 2.0)}


def sleeve_shape(p, ctx):
    """(P, 3): the throw's direction (base frame) times its friction share, gravity's component across the tube."""
    Rt, g_t = _gravity_tool(ctx)
    gp = g_t.copy()
    gp[:, 2] = 0.0
    mag = np.linalg.norm(gp, axis=1)
    u = gp / np.sqrt(mag ** 2 + p["g_f"] ** 2)[:, None]
    return np.einsum("pij,pj->pi", Rt, u)


def sleeve_apply(p, ctx, hw):
    return Contribution(displace=p["throw_mm"] * sleeve_shape(p, ctx))


def sleeve_features(p, ctx, hw):
    return sleeve_shape(p, ctx)[None]
