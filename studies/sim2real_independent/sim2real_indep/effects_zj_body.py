"""Set ZJ body effects (new physics, not in sets A-ZI): the arm's base on the carriage of a rail held by opposed
constant-flow hydrostatic pads; the base on a pair of short piers in soft clay whose lateral reaction follows
Matlock's p-y curve; a part held by a directional dry adhesive (gecko-like microwedges) whose stiffness grows with
the shear it carries in its preferred direction; a freshly moulded part creeping under its own weight while it is
still warm; and axis 1's lost motion whose flank a steady wind's torque on the arm chooses. Same protocol as
:mod:`effects_joint`.

Sources:

* hydrostatic rail: the base on a carriage that runs on one rail (a long linear axis, parked) held above and below the
  rail head by opposed constant-flow hydrostatic pads at +-s/2 across it (s 120-250 mm). A constant-flow pad carries W
  h^3 = const (Rowe, *Hydrostatic, Aerostatic and Hybrid Bearing Design*, 2012, ch. 3-5; Stansfield, *Hydrostatic
  Bearings for Machine Tools*, 1970), so an opposed pair under a net load F sits at the film change delta with F h0^3
  / C = (1 - d)^-3 - (1 + d)^-3, d = delta / h0 (it stiffens as the film closes). Each side carries half the weight
  (arm, part and a carriage of 0.3-1 times the arm) and the roll moment about the rail over s; the carriage rolls
  about the rail's axis (at 80-200 mm below the base) by the sides' difference and sinks by their mean. Load at the
  mean pose of 0.5-1.5 C / h0^3 per side; films h0 sized so that the target moves 0.25-0.6 mm (some 20-80 um,
  assumed). Unlike set C's track carriage (Hertzian ball guides) or set G's air isolators, the support is an oil film
  whose stiffness follows the cube law, about one fixed axis. Driven by the pose and the payload (logged). The true
  structure: one column, amplitude h0.
* soft-clay piers: the base on a cross-beam over a pair of short rigid concrete piers (a yard or quay installation)
  0.8-1.5 m apart along a horizontal line e of any heading, embedded 1-2 m in soft clay, their tops 0.2-0.6 m above
  the ground. Across e the pair resists by the piers' axial push and pull (stiff, left out); about e each pier turns
  in the clay about a point some 0.7 of its embedment down, and soft clay's lateral reaction follows p / p_u = 0.5 (y
  / y50)^(1/3) (Matlock, "Correlations for design of laterally loaded piles in soft clay", OTC 1204, 1970; API RP 2A),
  so the moment grows as the cube root of the turn: theta = c (M . e)^3 about e. Sized to 0.25-0.6 mm. (First a single
  pier turning about the moment's own axis: the link model at 1.04x on kr16_like and 1.17x on tool_changer -- a turn
  along the moment bends the arm's plane as the links' compliance does; now the pair's one axis.) Unlike set K's
  outriggers (an elastic half-space), set N's crawler (vertical pressure-sinkage), set ZG's settlement (consolidation
  in time) or set ZI's crowned sole (rocking against the weight), the soil yields laterally with the cube of the
  moment. Driven by the pose and the payload (logged). The true structure: one column, amplitude c.
* gecko pad: a gripper pad of directional dry adhesive (wedge-shaped microstructures that bend over and adhere when
  loaded in shear along their preferred direction: Autumn et al., "Frictional adhesion", J. Exp. Biol. 209, 2006;
  Parness et al., J. R. Soc. Interface 6, 2009; Hawkes et al., "Grasping without squeezing", IEEE/ASME TMech 20, 2015)
  holds a flat part on the tool's face; the wedges' contact area, and with it the pad's tilt stiffness, grows with the
  shear load along the preferred direction (the tool's x) and collapses against it, k = k0 (1 + kappa S+ / S_ref)
  (kappa 2-6, S_ref the session's largest), so the part tilts by its weight's moment about the pad (its centre of mass
  20-60 mm out) over k, about the face. Parts of 0.2-2 / 0.3-3 / 1-8 kg (ur10 / kr16_like / tool_changer) changed
  between blocks, the target on the part 40 mm beyond the face. Unlike set X's suction cup or set Y's foam pad (a
  fixed compliance), the stiffness is set by another component of the load. Driven by the tool's attitude and the
  payload (logged). The true structure: one column, amplitude 1 / k0.
* warm sag: a part taken from an injection moulding machine at 60-90 degC (near its heat-deflection temperature) is a
  thin panel (300 mm along the tool's x, held at one edge, the target at its tip) that creeps under the component of
  its weight across it at a rate following its fluidity, which falls as it cools (the viscosity's temperature law,
  Williams-Landel-Ferry / Arrhenius: Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., 1980, ch. 11; taken as
  exp(-t / tau_c) of the time since the pick, tau_c 3-10 min), so it sets in the shape its weight's history gave it:
  delta = A sum_i w_n,i exp(-t_i / tau_c) dt_i (the elastic sag of the ribbed part left out). A new part each block.
  Unlike set Y's sheet part (an elastic sag under the present weight) or set W's cooling part (thermal shrinkage), the
  deflection is the frozen-in creep of the attitude's history. Driven by the attitude, the payload and the time
  (logged); the part's temperature is not. The true structure: one column, amplitude A.
* wind flank: an arm working outdoors (a yard or quay) in a steady wind of any heading; the wind's drag on the links
  (the cross-flow part of each, 1/2 rho V^2 C_d D l_perp: Hoerner, *Fluid-Dynamic Drag*, 1965, ch. 3) has a torque
  about axis 1 that changes with the arm's azimuth and reach. Where it beats axis 1's drag (20-60 % of the session's
  largest wind torque) it pushes the output to that flank of its lost motion; elsewhere the drag keeps it on the flank
  of its last motion. The flank is found once from the true pose (a shape parameter). Unlike set N's wind on a panel
  (the gears twisted by the wind) or the flank choices of sets N-ZG (a harness, a cut, an inclined gravity), the wind
  chooses the flank. Driven by the pose and the last motion (logged) and the wind (not logged). The true structure:
  one column, amplitude the half lash.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_body import _block_starts, gravity_in_tool, tool_frame

G = kin.G
PART_MM = 40.0     # the gecko pad's part: the target 40 mm beyond the face, along the tool's z
PANEL_MM = 300.0   # the warm panel: the target at its tip, 300 mm along the tool's x


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- hydrostatic
def opposed_film(f):
    """The film change d = delta / h0 of an opposed constant-flow pair under the non-dimensional load f (bisection of
    (1 - d)^-3 - (1 + d)^-3 = f)."""
    f = np.asarray(f, float)
    lo, hi = np.full(f.shape, -0.999), np.full(f.shape, 0.999)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        up = (1 - mid) ** -3 - (1 + mid) ** -3 < f
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    return 0.5 * (lo + hi)


def rail_sides(p, ctx):
    """(P, 2) the non-dimensional loads of the two sides (+e_l, -e_l)."""
    m, _, _ = ctx.mass_state
    W = (m.sum(axis=1) + p["carriage_kg"]) * G
    e = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    Mr = mount_moment(ctx) @ e
    F = np.stack([W / 2 - Mr / (p["s_mm"] / 1000.0), W / 2 + Mr / (p["s_mm"] / 1000.0)], axis=1)
    return p["f_nom"] * F / p["F_ref"]


def hydro_draw(ctx, hw, rng):
    m, _, _ = ctx.mass_state
    p = {"psi": rng.uniform(0, np.pi), "s_mm": rng.uniform(120.0, 250.0), "depth_mm": rng.uniform(80.0, 200.0),
         "carriage_kg": float(np.sum(ctx.masses)) * rng.uniform(0.3, 1.0), "f_nom": rng.uniform(0.5, 1.5)}
    p["F_ref"] = float(((m.sum(axis=1) + p["carriage_kg"]) * G).mean() / 2)
    p["h0"] = float(_size(hydro_features(p, ctx, hw), [1.0], rng)[0])
    return p


def hydro_features(p, ctx, hw):
    d = opposed_film(rail_sides(p, ctx))      # per unit h0, downwards, sides +e_l and -e_l
    e = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    phi = (d[:, 1] - d[:, 0]) / p["s_mm"]     # roll about e [rad per unit h0 in mm]
    sink = (d[:, 0] + d[:, 1]) / 2
    pivot = np.array([0.0, 0.0, -p["depth_mm"]])
    return (np.cross(phi[:, None] * e, ctx.target - pivot) - sink[:, None] * np.array([0.0, 0.0, 1.0]))[None]


def hydro_apply(p, ctx, hw):
    return _amp_apply([p["h0"]], hydro_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- clay pier
def pier_axis(p):
    """The horizontal line through the two piers (the pair turns about it)."""
    return np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])


def pier_tilt(p, M):
    """(P, 3) the pair's turn per unit c: (M . e / M_ref)^3 about e."""
    e = pier_axis(p)
    return np.outer((M @ e / p["M_ref"]) ** 3, e)


def pier_draw(ctx, hw, rng):
    p = {"embed_mm": rng.uniform(1000.0, 2000.0), "top_mm": rng.uniform(200.0, 600.0),
         "psi": rng.uniform(0, np.pi), "M_ref": float(np.linalg.norm(mount_moment(ctx), axis=1).max())}
    p["c"] = float(_size(pier_features(p, ctx, hw), [1.0], rng)[0])
    return p


def pier_features(p, ctx, hw):
    pivot = np.array([0.0, 0.0, -(p["top_mm"] + 0.7 * p["embed_mm"])])
    return np.cross(pier_tilt(p, mount_moment(ctx)), ctx.target - pivot)[None]


def pier_apply(p, ctx, hw):
    return _amp_apply([p["c"]], pier_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- gecko pad
def gecko_tilt(p, ctx):
    """(P, 3) the part's tilt in the tool frame per unit 1 / k0 [rad per N m]: its weight's moment about the pad over
    (1 + kappa S+ / S_ref)."""
    w = ctx.session.payload_kg[:, None] * G * gravity_in_tool(tool_frame(ctx))
    M = np.cross([0.0, 0.0, p["d_mm"] / 1000.0], w)
    S = np.maximum(w[:, 0], 0.0)
    return M / (1.0 + p["kappa"] * S / p["S_ref"])[:, None]


def gecko_draw(ctx, hw, rng):
    w = ctx.session.payload_kg * G * gravity_in_tool(tool_frame(ctx))[:, 0]
    p = {"d_mm": rng.uniform(20.0, 60.0), "kappa": rng.uniform(2.0, 6.0), "S_ref": float(max(w.max(), 1e-6))}
    p["inv_k0"] = float(_size(gecko_features(p, ctx, hw), [1.0], rng)[0])
    return p


def gecko_features(p, ctx, hw):
    arm = np.array([0.0, 0.0, PART_MM])  # the target on the part, beyond the pad's face (the pivot)
    return np.einsum("pij,pj->pi", tool_frame(ctx), np.cross(gecko_tilt(p, ctx), arm))[None]


def gecko_apply(p, ctx, hw):
    return _amp_apply([p["inv_k0"]], gecko_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- warm sag
def creep_history(p, ctx):
    """(P,) the panel's frozen-in creep per unit A [N min]: the weight across it times its fluidity, summed over the
    block's intervals since the pick (a new part at each block's first pose)."""
    s = ctx.session
    wn = s.payload_kg * G * gravity_in_tool(tool_frame(ctx))[:, 2]
    start = _block_starts(s)
    out = np.zeros(len(wn))
    for k in range(1, len(wn)):
        if start[k] == k:
            continue
        dt = s.time_s[k] - s.time_s[k - 1] - abs(s.gap_s[k])
        age = s.time_s[k] - s.time_s[start[k]]
        out[k] = out[k - 1] + wn[k] * np.exp(-age / p["tau_c_s"]) * dt / 60.0
    return out


def sag_draw(ctx, hw, rng):
    p = {"tau_c_s": 60 * rng.uniform(3.0, 10.0)}
    p["A"] = float(_size(sag_features(p, ctx, hw), [1.0], rng)[0])
    return p


def sag_features(p, ctx, hw):
    return (tool_frame(ctx)[:, :, 2] * creep_history(p, ctx)[:, None])[None]


def sag_apply(p, ctx, hw):
    return _amp_apply([p["A"]], sag_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- wind flank
def wind_torque(chain, q, psi):
    """(P,) the wind's torque about axis 1 per unit drag per length [N m per N/m]: each link's cross-flow length
    (chain's link vectors at the pose, the last to the flange) at its midpoint."""
    R, t = kin.body_transforms(chain, q)
    u = np.array([np.cos(psi), np.sin(psi), 0.0])
    cum = np.cumsum(chain.links, axis=0)
    c1 = kin.joint_frames(chain, q)[1][:, 0]
    out = np.zeros(len(q))
    for li, b in enumerate(chain.link_body):
        a = np.einsum("pij,j->pi", R[:, b], cum[li] - chain.links[li]) + t[:, b]
        e = np.einsum("pij,j->pi", R[:, b], cum[li]) + t[:, b]
        ell = (e - a) / 1000.0
        perp = np.linalg.norm(ell - np.outer(ell @ u, u), axis=1)
        mid = (a + e) / 2000.0 - c1 / 1000.0
        out += np.cross(mid, u * perp[:, None])[:, 2]
    return out


def wind_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    T = wind_torque(ctx.chain, ctx.q, psi)
    lim = rng.uniform(0.2, 0.6) * np.abs(T).max()
    flank = np.where(np.abs(T) > lim, np.sign(T), -ctx.session.direction[:, 0])
    p = {"psi": psi, "share": float(lim / np.abs(T).max()), "flank": flank}
    p["b2"] = float(_size(wind_features(p, ctx, hw), [1.0], rng)[0])
    return p


def wind_features(p, ctx, hw):
    return ctx.joint_feature(0, np.asarray(p["flank"], float))[None]


def wind_apply(p, ctx, hw):
    return _amp_apply([p["b2"]], wind_features(p, ctx, hw))
