"""Set P body effects (new physics, not in sets A-O): a tool changer whose tools are re-seated at every change, their
locating pins landing anywhere in their bushes' clearance; a portable arm held to the floor by three vacuum cups on
elastomer support pads; an arm on an injection moulding machine's fixed platen, which the mould's clamping force bends.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* quick change: an automatic tool changer locates the tool plate on the master by two pins in bushes (or a pin and a
  diamond pin) and a locking piston; the fit's clearance, 0.03-0.10 mm radial on worn or low-cost changers, sets the
  repeatability (ISO 9409-1 flanges with a locating pin; tool changers' data sheets give +-0.01-0.05 mm; ISO 286 fits
  H7/g6 at 10-16 mm: 6-35 um), and each pick lands the pins anywhere inside it (Slocum, *Precision Machine Design*,
  1992, ch. 7 on pinned joints: a pin in a hole locates to its clearance). The plate translates by the pins' mean
  landing and turns about the tool axis by their difference over the pins' spacing (pins at 25-40 mm from the
  axis). The tool is changed between the session's 4-7 blocks (pauses of 1-3 min), each tool its own weight (logged as
  the payload); the target on the tool, 120-250 mm from the plate (:func:`effects_p.probe_hook`). The true structure:
  one column (the landings its shape), amplitude the clearance.
* vacuum feet: portable machining and drilling robots hold themselves to a floor or a part by vacuum cups (e.g. the
  vacuum-cup "flex track" drilling machines; Schmalz / Piab cup data: holding force dp A); with support pads the
  vacuum's force F_v = dp A presses each pad and the arm's weight and moments add to it. Three cups carry the base
  statically determinately (the vertical force and the two moments fix their forces); an elastomer pad compresses as
  delta = delta_r (C / C_r)^n with n 0.5-0.8 (hardening under compression: Gent, *Engineering with Rubber*, 3rd ed.,
  2012, ch. 8, bonded blocks' compression stiffness growing with the strain, as recalled), and the three compressions
  set the base's sink and tilt. Cups at 300-450 mm from the base's axis 50-120 mm below it, sized (their diameter at
  dp 60-80 kPa) so that the least-pressed pad keeps 10-30 % of its vacuum force; hard pads compressing delta_r 0.1-0.3
  mm at the vacuum force (assumed; first cups of 150-250 mm whatever the load, pads of 0.5-1.2 mm: nearly linear, the
  joint model within 1.06x on ur10, the link model within 1.23x on kr16_like); ur10 and kr16_like. The payload changes
  between blocks. The true structure: one column, amplitude delta_r.
* platen clamp: an arm mounted on the fixed platen of an injection moulding machine (EUROMAP 18 gives the mounting
  face for handling devices) tends the mould; the clamping force (hundreds of kN to MN) stretches the tie bars and
  bends the platen (Johannaber, *Injection Molding Machines*, 4th ed., 2008, ch. on clamping units: platen deflection),
  and the platen's top face, carrying the arm, turns by 1-3e-4 rad about a horizontal axis through a point 300-700 mm
  below it while the mould is clamped (assumed, a mid-size machine). The machine cycles while the arm is measured; the
  mould is clamped during 60-85 % of its cycle (injection, holding, cooling), and each measurement falls at a random
  moment of it (the machine's signal, not logged). ur10 and kr16_like. The true structure: one column (the clamp's
  states its shape), amplitude the rotation.
* vacuum plate: a vacuum gripper's box (a plenum behind a perforated or foam-faced plate) carries the pressure
  difference on its face plate while the vacuum holds a part; a clamped circular plate under a uniform pressure p
  bows by w0 = p a^4 / (64 D), D = E t^3 / (12 (1 - nu^2)), w = w0 (1 - (r / a)^2)^2 at radius r (Timoshenko &
  Woinowsky-Krieger, *Theory of Plates and Shells*, 2nd ed., 1959, ch. 3; Roark's *Formulas for Stress and Strain*,
  ch. 11). Aluminium face plates of 4-6 mm, an equivalent radius of 100-150 mm, 55-80 kPa of vacuum (ejectors'
  data); the target on the face, within half the radius of its centre, 60-120 mm from the flange
  (:func:`effects_p.probe_hook`) (assumed). The vacuum is on while a part is held (pick and place: the payload
  logged). The true structure: one column (the held poses along the tool axis), amplitude the centre's bow.
* hose lance: a sealing or dispensing nozzle on a slender steel lance (a tube cantilevered from the flange along
  the tool axis, 250-400 mm, 16-22 mm outer diameter, 1.5-2.5 mm wall; first 10-14 mm of 1-2 mm: 2-5 mm at the
  nozzle) whose supply hose is clipped to the nozzle and
  runs to a fixed outlet on the forearm; the hose's bending stiffness pulls the nozzle towards the outlet like a
  spring, F = k (p_outlet - p_nozzle), k 0.02-0.06 N/mm for a reinforced 6-10 mm hose over a 0.4-0.8 m loop
  (assumed), and the lance's tip moves by the pull across it, F L^3 / (3 E I) (Timoshenko & Gere, *Mechanics of
  Materials*, cantilever with an end load). The wrist's angles set the pull (not logged). The target at the nozzle.
  ur10 and kr16_like. The true structure: one column (the pull at k = 1 over E I), amplitude k / (E I).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_m_joint import block_index

Z = np.array([0.0, 0.0, 1.0])


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------------- quick change
QC_PIN_R_MM, QC_TOOL_MM = (25.0, 40.0), (120.0, 250.0)


def _disc(rng, n):
    """n points uniform in the unit disc (n, 2)."""
    r, a = np.sqrt(rng.uniform(0, 1, n)), rng.uniform(0, 2 * np.pi, n)
    return np.c_[r * np.cos(a), r * np.sin(a)]


def qc_draw(ctx, hw, rng):
    B = int(block_index(ctx.session)[-1]) + 1
    return {"c_mm": rng.uniform(0.03, 0.1), "R_pin_mm": rng.uniform(*QC_PIN_R_MM), "a": _disc(rng, B),
            "b": _disc(rng, B), "pin_az": rng.uniform(0, 2 * np.pi)}


def qc_local(p, probe_mm, blk):
    """(P, 3): the target's displacement in the tool frame per unit clearance: the plate's translation by the pins'
    mean landing and its turn about the tool axis by their difference across the pins' spacing 2 R."""
    a, b = p["a"][blk], p["b"][blk]
    e = np.array([np.cos(p["pin_az"]), np.sin(p["pin_az"])])          # pin A at +R e, pin B at -R e
    n = np.array([-e[1], e[0]])
    t = 0.5 * (a + b)
    w = ((a - b) @ n) / (2 * p["R_pin_mm"])
    rot = np.c_[-w * probe_mm[1], w * probe_mm[0]]
    return np.c_[t + rot, np.zeros(len(t))]


def qc_part(p, ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    local = qc_local(p, np.asarray(ctx.probe_mm, float), block_index(ctx.session))
    return np.einsum("pij,pj->pi", Rt, local)


def qc_apply(p, ctx, hw):
    return Contribution(displace=p["c_mm"] * qc_part(p, ctx))


def qc_features(p, ctx, hw):
    return qc_part(p, ctx)[None]


# ------------------------------------------------------------------------------------------------- vacuum feet
VACUUM_ARMS = {"ur10", "kr16_like"}


def vac_draw(ctx, hw, rng):
    if ctx.chain.name not in VACUUM_ARMS:
        return {}
    R, az = rng.uniform(300.0, 450.0), rng.uniform(0, 2 * np.pi)
    ang = az + 2 * np.pi * np.arange(3) / 3
    p = {"F_v": 0.0, "R_mm": R, "cups": np.c_[R * np.cos(ang), R * np.sin(ang)], "h_mm": rng.uniform(50.0, 120.0),
         "n": rng.uniform(0.5, 0.8), "delta_r": rng.uniform(0.1, 0.3)}
    # the cups sized (their diameter at dp 60-80 kPa) so that the least-pressed pad keeps 10-30 % of its vacuum force
    p["F_v"] = -vac_forces(p, ctx).min() / (1 - rng.uniform(0.1, 0.3))
    p["C_r"] = p["F_v"]
    return p


def vac_forces(p, ctx):
    """(P, 3): the pads' forces [N]: the vacuum's preload plus the three that carry the weights' force and moments."""
    O = -p["h_mm"] * Z
    m, pos, _ = ctx.mass_state
    W = kin.G * m.sum(axis=1)
    M = np.cross(pos - O, -kin.G * m[..., None] * Z).sum(axis=1)     # [N mm]
    c = p["cups"]
    # sum C = W; sum (c_i x C_i e_z) = -M (the pads' reactions balance the weights' moment): x: y_i C_i, y: -x_i C_i
    A = np.array([np.ones(3), c[:, 1], -c[:, 0]])
    rhs = np.c_[W, -M[:, 0], -M[:, 1]]
    return p["F_v"] + np.linalg.solve(A, rhs.T).T


def vac_shape(p, ctx):
    """(P, 3): the target's displacement per unit delta_r: the base sinking and tilting to the pads' compressions."""
    d = (vac_forces(p, ctx) / p["C_r"]) ** p["n"]                      # (P, 3) compressions per delta_r
    c = p["cups"]
    # the base's vertical motion w0 + wx y - wy x at the cups equals -d (rotation (wx, wy) about O)
    A = np.c_[np.ones(3), c[:, 1], -c[:, 0]]
    sol = np.linalg.solve(A, -d.T).T                                   # (P, 3): w0, wx, wy
    r = ctx.target + p["h_mm"] * Z
    w = np.c_[sol[:, 1], sol[:, 2], np.zeros(len(sol))]
    return sol[:, :1] * Z + np.cross(w, r)


def vac_apply(p, ctx, hw):
    return Contribution(displace=p["delta_r"] * vac_shape(p, ctx) if p else None)


def vac_features(p, ctx, hw):
    return vac_shape(p, ctx)[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------- platen clamp
PLATEN_ARMS = {"ur10", "kr16_like"}


def platen_draw(ctx, hw, rng):
    if ctx.chain.name not in PLATEN_ARMS:
        return {}
    az = rng.uniform(0, 2 * np.pi)
    closed = rng.uniform(0.6, 0.85)
    return {"theta_rad": rng.uniform(1e-4, 3e-4), "axis": np.array([np.cos(az), np.sin(az), 0.0]),
            "h_mm": rng.uniform(300.0, 700.0), "closed": closed,
            "state": (rng.uniform(0, 1, len(ctx.q)) < closed).astype(float)}


def platen_shape(p, ctx):
    """(P, 3): the target's displacement per unit rotation of the platen's top face while the mould is clamped."""
    return p["state"][:, None] * np.cross(p["axis"], ctx.target + p["h_mm"] * Z)


def platen_apply(p, ctx, hw):
    return Contribution(displace=p["theta_rad"] * platen_shape(p, ctx) if p else None)


def platen_features(p, ctx, hw):
    return platen_shape(p, ctx)[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------ vacuum plate
VPLATE_FACE_MM, VPLATE_R_MM = (60.0, 120.0), (100.0, 150.0)


def vplate_draw(ctx, hw, rng):
    a, t, dp = rng.uniform(*VPLATE_R_MM), rng.uniform(4.0, 6.0), rng.uniform(55e3, 80e3) * 1e-6   # [mm], [N/mm^2]
    D = 70e3 * t ** 3 / (12 * (1 - 0.33 ** 2))
    r = float(np.linalg.norm(np.asarray(ctx.probe_mm, float)[:2]))
    return {"a_mm": a, "t_mm": t, "dp": dp, "w0_mm": dp * a ** 4 / (64 * D), "shape": (1 - min(r / a, 1.0) ** 2) ** 2}


def vplate_part(p, ctx):
    """(P, 3): the target's displacement per unit bow: inwards along the tool axis while a part is held."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    held = (ctx.session.payload_kg > 0).astype(float)
    return -(held * p["shape"])[:, None] * Rt[:, :, 2]


def vplate_apply(p, ctx, hw):
    return Contribution(displace=p["w0_mm"] * vplate_part(p, ctx))


def vplate_features(p, ctx, hw):
    return vplate_part(p, ctx)[None]


# -------------------------------------------------------------------------------------------------- hose lance
LANCE_ARMS = {"ur10": 3, "kr16_like": 3}        # the body carrying the hose's outlet (the forearm)
LANCE_MM = (250.0, 400.0)


def lance_draw(ctx, hw, rng):
    if ctx.chain.name not in LANCE_ARMS:
        return {}
    D, t = rng.uniform(16.0, 22.0), rng.uniform(1.5, 2.5)
    EI = 210e3 * np.pi / 64 * (D ** 4 - (D - 2 * t) ** 4)                # [N mm^2]
    ch, b = ctx.chain, LANCE_ARMS[ctx.chain.name]
    start = np.cumsum(ch.links, axis=0)[np.flatnonzero(ch.link_body == b)[-1]]   # the forearm's end at home
    outlet = start * rng.uniform(0.5, 0.8) + rng.uniform(80.0, 200.0) * _unit3(rng)
    return {"L_mm": float(np.linalg.norm(ctx.probe_mm)), "EI": EI, "k_N_mm": rng.uniform(0.02, 0.06),
            "body": b, "outlet_home": outlet}


def _unit3(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def lance_part(p, ctx):
    """(P, 3): the nozzle's displacement per unit k / (E I): the hose's pull across the lance times L^3 / 3."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    outlet = np.einsum("pij,j->pi", R[:, p["body"]], p["outlet_home"]) + t[:, p["body"]]
    _, Rt = kin.flange(ctx.chain, ctx.q)
    pull = outlet - ctx.target
    z = Rt[:, :, 2]
    across = pull - np.sum(pull * z, axis=1, keepdims=True) * z
    return across * p["L_mm"] ** 3 / 3


def lance_apply(p, ctx, hw):
    return Contribution(displace=p["k_N_mm"] / p["EI"] * lance_part(p, ctx) if p else None)


def lance_features(p, ctx, hw):
    return lance_part(p, ctx)[None] if p else _empty(ctx)
