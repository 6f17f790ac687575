"""Set ZM body effects (new physics, not in sets A-ZL): the arm's base on progressive conical rubber mounts; its base on a
parked track carriage whose profile-rail blocks are softer pulled than pressed; a part held on an expanding mandrel's
elastomer sleeve; and a parallel gripper's jaws tilting in their preloaded miniature rail guides. Same protocol as
:mod:`effects_joint`.

Sources:

* conical mounts (``conical_mounts``): conical (cone-in-cup) rubber mounts stiffen as they are loaded -- the rubber
  is sheared at light loads and compressed against the cone at heavy ones (makers' load-deflection curves, e.g.
  Trelleborg / Continental cone mounts, as recalled; Gent, *Engineering with Rubber*, 3rd ed., 2012, ch. 10: the
  compression stiffness rising with the shape factor as the bulge is confined). Written as k = k0 (1 + F / F0), i.e.
  a deflection (F0 / k0) ln(1 + F / F0), F0 20-50 % of a mount's share of the arm's weight. Four mounts at the
  corners of a narrow stand (half sides 0.35-0.5 and 0.15-0.25 m, heading at random) each take W / 4 plus their share
  of the moment (a linear load distribution); the rigid plate follows the least-squares plane of the four
  deflections, about the mounts' top 60-120 mm below the base frame. Parts changed between blocks (the weight sets
  where on the curve each mount works); sized to 0.25-0.6 mm. (First on a near-square frame, half sides 0.3-0.45 and
  0.25-0.4 m, F0 30-100 %: ur10's ZM04 with the joint model at 1.12x -- a tilt along the moment about a point just
  below the shoulder is axis 2's compliance; the narrow stand turns the tilt away from the moment.) Unlike set Q's
  disc springs (degressive Belleville stacks), set G's air isolators, set S's Mullins softening or set Z's warm
  isolators, the mounts harden with their own load, so the arm's tilt per moment falls as the part gets heavier.
  Driven by the pose and the payload (logged). The true structure: one column, amplitude F0 / k0.
* rail blocks (``rail_blocks``): the arm stands on the carriage of a floor track (its seventh axis, parked at one
  station for the measurement and not logged), carried by four recirculating-ball profile-rail blocks (a light track's
  narrow carriage: rail spacing 0.15-0.3 m, block spacing along the rail 0.4-0.7 m, heading at random). A block is
  stiffer pressed (radial load) than pulled off its rail (reverse radial): its raceways' contact angles favour the
  radial direction (THK / Hiwin / Bosch Rexroth linear-guide catalogues, rigidity in the radial and reverse-radial
  directions, as recalled: reverse radial 50-75 % of radial, kappa 1.3-2.0 here). Each block takes W / 4 plus its
  share of the moment (a linear load distribution); where the moment lifts a side past its share of the weight its
  blocks are pulled and soften; the carriage plate follows the least-squares plane of the four deflections, about the
  blocks' top 60-120 mm below the base frame. Parts of up to the rated payload changed between blocks; sized to
  0.25-0.6 mm. Unlike set C's track (the track beam's torsion), set M's carriage play (cam followers' clearance), set
  ZC's hexapod (struts softer in tension: the nearest law) or this set's cone mounts, the supports are a carriage's
  rolling blocks, softer pulled than pressed. First with the rails 0.4-0.7 m apart and the blocks 0.3-0.6 m:
  kr16_like's ZM20 ambiguous (12 %), ur10 and tool_changer with the joint model at 1.04-1.08x in trials -- a
  near-square carriage tilts along the moment; the narrow carriage's blocks lift on its short side and turn the tilt;
  now on ur10 (ZM01). (The set's first second mount kind was ``pedestal_splice``, a riser's bolted splice opening past
  its decompression moment: the link model at 1.17-1.21x on kr16_like (ZM20), with the splice turning about its
  centre and then about its compressed edge, and ambiguous on ur10 in trials -- a tilt along the moment about a point
  below the base is the arm's own bending there; replaced.) Driven by the pose and the payload (logged). The true
  structure: one column, amplitude 1 / k_r.
* expanding mandrel (``mandrel_rock``): an internal gripper holds a ring part by its bore on an expanding
  polyurethane sleeve (length L 40-80 mm, 100 mm down the tool axis); the sleeve is an elastic foundation of modulus
  k_f (Winkler; Hetenyi, *Beams on Elastic Foundation*, 1946), so the rigid part shifts by F / (k_f L) across the
  axis and rocks by M / (k_f L^3 / 12) under its weight (centre 30-80 mm past the sleeve's), the target on the part 220
  mm down the tool axis (:func:`effects_zm.probe_hook`, :func:`effects_zm.payload_hook`). Parts of 1-8 / 2-14 / 10-60
  kg changed between blocks; sized to 0.25-0.6 mm. Unlike set ZL's finger pads (torsion of two pads about the closing
  axis), set Y's foam pad or set X's suction cup, the part rocks and shifts on a sleeve round its bore, in both
  directions across the axis. Driven by the attitude and the payload (logged). The true structure: one column,
  amplitude 1 / k_f.
* jaw guides (``jaw_guide_tilt``): a parallel gripper's jaws run on preloaded miniature profile-rail guides along the
  closing axis (the tool's y); the part's weight moment tilts the two carriages by M / (2 K) in pitch (about the
  tool's x), yaw (about its z) and roll (about the rail, y), with the catalogue's moment stiffnesses K_A : K_B : K_C
  (THK / Hiwin miniature guide catalogues, as recalled: yaw 0.9-1.2, roll 1.3-2.0 times the pitch stiffness). The guides
  60 mm down the tool axis, the part's centre 40-100 mm below them, the target on the part 180 mm down the tool axis.
  Parts of 1-8 / 2-14 / 10-60 kg changed between blocks; sized to 0.25-0.6 mm. Unlike set M's jaw play (a clearance),
  set L's grip spread (the grip force) or set ZL's pads, the jaws turn elastically in their rolling guides about three
  axes. Driven by the attitude and the payload (logged). The true structure: one column, amplitude 1 / K_A.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_body import gravity_in_tool, tool_frame

Z = np.array([0.0, 0.0, 1.0])
MANDREL_MM = 100.0      # the sleeve's centre down the tool axis
MANDREL_TARGET_MM = 220.0
JAW_MM = 60.0           # the jaw guides down the tool axis
JAW_TARGET_MM = 180.0


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def total_weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G


def _axes(psi):
    e1 = np.array([np.cos(psi), np.sin(psi), 0.0])
    return e1, np.cross(Z, e1)


def _to_world(ctx, local):
    return np.einsum("pij,pj->pi", tool_frame(ctx), local)


# ---------------------------------------------------------------------------------------------------- conical mounts
def mount_loads(p, ctx):
    """(P, 4) the mounts' loads [N] at (+-a, +-b) in the grid frame, and those positions (4, 2) [m]."""
    M, W = mount_moment(ctx), total_weight(ctx)
    e1, e2 = _axes(p["psi"])
    xy = np.array([[sx * p["a"], sy * p["b"]] for sx in (1, -1) for sy in (1, -1)])
    R = W[:, None] / 4 + np.outer(M @ e2, xy[:, 0]) / (4 * p["a"] ** 2) - np.outer(M @ e1, xy[:, 1]) / (4 * p["b"] ** 2)
    return R, xy


def conical_features(p, ctx, hw):
    """(1, P, 3) per unit F0 / k0 [mm]: the plate through the mounts' deflections ln(1 + F / F0)."""
    R, xy = mount_loads(p, ctx)
    return _plate(p, ctx, np.log1p(np.maximum(R, 0.0) / p["F0"]), xy)


def _plate(p, ctx, d, xy):
    """(1, P, 3) the target's displacement [mm] for support deflections d (P, 4) [mm, down] at xy (4, 2) [m]: the
    least-squares plane's tilt about the supports' top and its sink."""
    d0 = d.mean(axis=1)
    s1 = d @ xy[:, 0] / (4 * p["a"] ** 2) / 1000.0                 # [rad per unit]
    s2 = d @ xy[:, 1] / (4 * p["b"] ** 2) / 1000.0
    e1, e2 = _axes(p["psi"])
    w = -s2[:, None] * e1 + s1[:, None] * e2
    return (np.cross(w, ctx.target - np.array([0.0, 0.0, -p["pivot_mm"]])) - d0[:, None] * Z)[None]


def conical_draw(ctx, hw, rng):
    p = {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.35, 0.5)), "b": float(rng.uniform(0.15, 0.25)),
         "pivot_mm": float(rng.uniform(60.0, 120.0))}
    p["F0"] = float(rng.uniform(0.2, 0.5) * total_weight(ctx).min() / 4)
    p["c"] = float(_size(conical_features(p, ctx, hw), [1.0], rng)[0])
    return p


def conical_apply(p, ctx, hw):
    return _amp_apply([p["c"]], conical_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- rail blocks
def rail_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / k_r [mm/N]: the carriage plate through the blocks' deflections, R where a block is
    pressed (R >= 0), kappa R where it is pulled."""
    R, xy = mount_loads(p, ctx)
    d = np.where(R >= 0, R, p["kappa"] * R)
    return _plate(p, ctx, d, xy)


def rail_draw(ctx, hw, rng):
    p = {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.2, 0.35)), "b": float(rng.uniform(0.075, 0.15)),
         "pivot_mm": float(rng.uniform(60.0, 120.0)), "kappa": float(rng.uniform(1.3, 2.0))}
    p["c"] = float(_size(rail_features(p, ctx, hw), [1.0], rng)[0])
    return p


def rail_apply(p, ctx, hw):
    return _amp_apply([p["c"]], rail_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- expanding mandrel
def part_loads(ctx, centre_mm):
    """The part's weight (P, 3) [N] and its moment about the point ``centre_mm`` down the tool axis (P, 3) [N m],
    tool frame."""
    F = gravity_in_tool(tool_frame(ctx)) * kin.G * ctx.session.payload_kg[:, None]
    r = (np.asarray(ctx.payload_com_mm, float) - np.array([0.0, 0.0, centre_mm])) / 1000.0
    return F, np.cross(r, F)


def mandrel_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / k_f [m^2 / N]: the shift F / L and the rock 12 M / L^3 across the tool axis."""
    F, M = part_loads(ctx, MANDREL_MM)
    L = p["L_m"]
    u = 1000.0 * F * [1.0, 1.0, 0.0] / L
    theta = 12.0 * M * [1.0, 1.0, 0.0] / L ** 3
    arm = ctx.probe_mm - np.array([0.0, 0.0, MANDREL_MM])
    return _to_world(ctx, u + np.cross(theta, arm))[None]


def mandrel_draw(ctx, hw, rng):
    p = {"L_m": float(rng.uniform(0.04, 0.08))}
    p["inv_kf"] = float(_size(mandrel_features(p, ctx, hw), [1.0], rng)[0])
    return p


def mandrel_apply(p, ctx, hw):
    return _amp_apply([p["inv_kf"]], mandrel_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- jaw guides
def jaw_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / K_A: the jaws' tilt M / (2 K) about the tool's x (pitch), z (yaw) and y (roll)."""
    _, M = part_loads(ctx, JAW_MM)
    theta = M / (2.0 * np.array([1.0, p["roll"], p["yaw"]]))
    arm = ctx.probe_mm - np.array([0.0, 0.0, JAW_MM])
    return _to_world(ctx, np.cross(theta, arm))[None]


def jaw_draw(ctx, hw, rng):
    p = {"yaw": float(rng.uniform(0.9, 1.2)), "roll": float(rng.uniform(1.3, 2.0))}
    p["inv_KA"] = float(_size(jaw_features(p, ctx, hw), [1.0], rng)[0])
    return p


def jaw_apply(p, ctx, hw):
    return _amp_apply([p["inv_KA"]], jaw_features(p, ctx, hw))
