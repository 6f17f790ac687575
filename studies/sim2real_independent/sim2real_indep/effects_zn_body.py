"""Set ZN body effects (new physics, not in sets A-ZM): the arm's base on wire-rope isolators, softening when pressed and
stiffening when pulled; its base on inclined (focalised) elastomer mounts that turn it about a point above their
plane; a tool-side dovetail slide whose gib side is softer than its solid flank; and a tool hung on a metal bellows
coupling. Same protocol as :mod:`effects_joint`.

Sources:

* wire-rope isolators (``wire_rope_isolators``): helical steel-cable isolators soften in compression as their loops
  flatten and roll, and stiffen in tension as the cable strands straighten (Demetriades, Constantinou & Reinhorn, Eng.
  Struct. 15, 1993; makers' load-deflection curves, e.g. Enidine / ITT wire-rope isolators, as recalled). Written as a
  deflection d = (R / k0)(1 + s R / F0) pressed and (R / k0) / (1 + h |R| / F0) pulled, F0 a mount's share of the
  arm's weight, s 0.3-0.8, h 0.5-1.5. Four isolators at the corners of a narrow stand (half sides 0.35-0.5 and
  0.15-0.25 m, heading at random: the narrow stand turns the tilt away from the moment, see set ZM's cone mounts) take
  W / 4 plus their share of the moment; the plate follows the least-squares plane of their deflections, 60-120 mm
  below the base frame. Parts of up to the rated payload changed between blocks; sized to 0.25-0.6 mm. Unlike set
  ZM's cone mounts (hardening rubber) or rail blocks (softer pulled than pressed, linear each way), set ZC's hexapod
  or set Q's disc springs, the supports soften as they are pressed and harden as they are pulled. Driven by the pose
  and the payload (logged). The true structure: one column, amplitude 1 / k0.
* focalised mounts (``focalised_mounts``): elastomer mounts set inclined by gamma 30-45 deg in pairs (a chevron
  along the stand's long side) so that their lines of action meet at a focal point h_f = a / tan(gamma) above their
  plane (Harris & Piersol, *Shock and Vibration Handbook*, 5th ed., 2002, ch. 30, focalised isolators and the
  elastic centre; Rivin, *Stiffness and Damping in Mechanical Design*, 1999): about the stand's short axis the base
  turns about that focal point with the mounts' shear stiffness, 1 / (4 rho k (a^2 + h_f^2)), rho = k_s / k_c
  0.2-0.5; about its long axis it rocks on the mounts' vertical stiffness k_v = k (cos^2 gamma + rho sin^2 gamma)
  about their plane, 1 / (4 k_v b^2); and it sinks by W / (4 k_v). Half sides 0.35-0.5 / 0.15-0.25 m, the plane 60-120
  mm below the base frame; parts of up to the rated payload changed between blocks; sized to 0.25-0.6 mm. Unlike
  every vertical support of sets A-ZM (a tilt about a point in or below the support plane), the turn is about a point
  above it. Driven by the pose and the payload (logged). The true structure: one column, amplitude 1 / k.
* dovetail slide (``dovetail_gib``): the target's part sits on a hand-set dovetail slide (a gripper's stroke
  adjustment) running along the tool's y and clamped by its gib screw; the moment about the slide's axis presses
  either the solid dovetail flank or the gib strip, whose contact is 2-4 times softer (Slocum, *Precision Machine
  Design*, 1992, ch. 8, dovetail slides and gibs; Rivin 1999, ch. 4, contact stiffness of joints), the moment across
  it (about the tool's x) bears on the slide's length (2-4 times stiffer). The slide 70 mm down the tool axis, the
  part's centre 40-100 mm below it, the target on the part 190 mm down the tool axis. Parts of 1-8 / 2-14 / 10-60 kg
  changed between blocks; sized to 0.25-0.6 mm. Unlike set ZM's jaw guides (rolling guides, symmetric) or set M's jaw
  play (a clearance), the slide turns elastically, softer to the gib's side. Driven by the attitude and the payload
  (logged). The true structure: one column, amplitude 1 / K.
* bellows coupling (``bellows_coupling``): the tool hangs on a metal bellows coupling (for a misalignment-tolerant
  tool: torsionally stiff, axially and angularly soft); a bellows' angular rate is its axial rate times D_m^2 / 8 (EJMA
  *Standards of the Expansion Joint Manufacturers Association*, 10th ed., 2015, bellows spring rates; D_m its mean
  diameter, 30-60 mm), so the part's weight stretches it along the tool axis and its moment tilts it about the
  bellows' centre (50 mm down the tool axis; the part's centre 40-100 mm below, the target 160 mm down). Parts of
  1-8 / 2-14 / 10-60 kg changed between blocks; sized to 0.25-0.6 mm. Unlike set S's diaphragm (membrane stiffening)
  or set W's air bellows (a pneumatic spring), the tool moves along its axis by the weight's axial part and tilts in
  the proportion the bellows' geometry sets. Driven by the attitude and the payload (logged). The true structure: one
  column, amplitude 1 / K_ax.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zm_body import _axes, _plate, _to_world, mount_loads, part_loads, total_weight

Z = np.array([0.0, 0.0, 1.0])
SLIDE_MM = 70.0         # the dovetail slide down the tool axis
SLIDE_TARGET_MM = 190.0
BELLOWS_MM = 50.0       # the bellows' centre down the tool axis
BELLOWS_TARGET_MM = 160.0


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _stand(rng):
    return {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.35, 0.5)), "b": float(rng.uniform(0.15, 0.25)),
            "pivot_mm": float(rng.uniform(60.0, 120.0))}


# ---------------------------------------------------------------------------------------------------- wire-rope isolators
def isolator_deflection(p, R):
    """(P, 4) the isolators' deflections per unit 1 / k0 [N]: softening pressed (R > 0), stiffening pulled."""
    x = np.abs(R) / p["F0"]
    return np.where(R >= 0, R * (1 + p["s"] * x), R / (1 + p["h"] * x))


def wire_draw(ctx, hw, rng):
    p = _stand(rng) | {"s": float(rng.uniform(0.3, 0.8)), "h": float(rng.uniform(0.5, 1.5))}
    p["F0"] = float(total_weight(ctx).min() / 4)
    p["c"] = float(_size(wire_features(p, ctx, hw), [1.0], rng)[0])
    return p


def wire_features(p, ctx, hw):
    R, xy = mount_loads(p, ctx)
    return _plate(p, ctx, isolator_deflection(p, R), xy)


def wire_apply(p, ctx, hw):
    return _amp_apply([p["c"]], wire_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- focalised mounts
def focal_height_mm(p):
    return 1000.0 * p["a"] / np.tan(p["gamma"])


def focal_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / k [N/m]: the turn about the focal point (short axis), the rock about the mounts' plane
    (long axis) and the sink."""
    M, W = mount_moment(ctx), total_weight(ctx)
    e1, e2 = _axes(p["psi"])
    kv = np.cos(p["gamma"]) ** 2 + p["rho"] * np.sin(p["gamma"]) ** 2
    hf = focal_height_mm(p) / 1000.0
    th2 = (M @ e2) / (4 * p["rho"] * (p["a"] ** 2 + hf ** 2))     # about e2 (moment along e2), focal point [rad]
    th1 = (M @ e1) / (4 * kv * p["b"] ** 2)                        # about e1, the mounts' plane
    plane = np.array([0.0, 0.0, -p["pivot_mm"]])
    focus = plane + np.array([0.0, 0.0, focal_height_mm(p)])
    d = (np.cross(th2[:, None] * e2, ctx.target - focus) + np.cross(th1[:, None] * e1, ctx.target - plane)
         - 1000.0 * (W / (4 * kv))[:, None] * Z)
    return d[None]


def focal_draw(ctx, hw, rng):
    p = _stand(rng) | {"gamma": float(np.deg2rad(rng.uniform(30.0, 45.0))), "rho": float(rng.uniform(0.2, 0.5))}
    p["c"] = float(_size(focal_features(p, ctx, hw), [1.0], rng)[0])
    return p


def focal_apply(p, ctx, hw):
    return _amp_apply([p["c"]], focal_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dovetail slide
def dovetail_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / K: the slide's roll about the tool's y (softer, kappa, towards the gib) and its pitch
    about the tool's x (stiffer by beta)."""
    _, M = part_loads(ctx, SLIDE_MM)
    roll = M[:, 1] * np.where(M[:, 1] * p["gib"] > 0, p["kappa"], 1.0)
    theta = np.stack([M[:, 0] / p["beta"], roll, np.zeros(len(roll))], axis=1)
    arm = ctx.probe_mm - np.array([0.0, 0.0, SLIDE_MM])
    return _to_world(ctx, np.cross(theta, arm))[None]


def dovetail_draw(ctx, hw, rng):
    p = {"kappa": float(rng.uniform(2.0, 4.0)), "beta": float(rng.uniform(2.0, 4.0)),
         "gib": float(rng.choice([-1.0, 1.0]))}
    p["inv_K"] = float(_size(dovetail_features(p, ctx, hw), [1.0], rng)[0])
    return p


def dovetail_apply(p, ctx, hw):
    return _amp_apply([p["inv_K"]], dovetail_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- bellows coupling
def bellows_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / K_ax [m/N]: the stretch F_z along the tool axis and the tilt 8 M / D_m^2."""
    F, M = part_loads(ctx, BELLOWS_MM)
    theta = 8.0 * M * [1.0, 1.0, 0.0] / p["D_m"] ** 2
    arm = ctx.probe_mm - np.array([0.0, 0.0, BELLOWS_MM])
    local = np.cross(theta, arm) + 1000.0 * F * [0.0, 0.0, 1.0]
    return _to_world(ctx, local)[None]


def bellows_draw(ctx, hw, rng):
    p = {"D_m": float(rng.uniform(0.03, 0.06))}
    p["inv_Kax"] = float(_size(bellows_features(p, ctx, hw), [1.0], rng)[0])
    return p


def bellows_apply(p, ctx, hw):
    return _amp_apply([p["inv_Kax"]], bellows_features(p, ctx, hw))
