"""Set M body effects (new physics, not in sets A-K nor L): a mobile robot cart re-docked between the production runs,
landing each time elsewhere inside its docking pins' clearance; the robot on a track carriage whose worn cam-follower
rollers let it rock across the rail by their clearance as the arm's moment about the rail changes sign; a tool on
wire-rope isolators, whose strands slide on each other beyond a slip force; a long gripper bar stiffened by a tie rod
that carries tension only; a parallel gripper whose jaw rocks in the clearance of its guide. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* cart docking: mobile robot carts (a cobot on a wheeled table moved between machines) are located at each station by
  a docking plate with two pins, one round and one diamond, in bushes with a clearance (the 3-2-1 / pin-and-slot
  location of fixture design: Rong & Zhu, *Computer-Aided Fixture Design*, 1999; ISO 286 fits H7/g6 to H8/f7 worn),
  and clamped; each docking lands at random inside the clearance, c 0.1-0.3 mm over a pin spacing of 0.3-0.6 m (first
  0.05-0.2 mm over 0.4-0.8 m: a gain of 24 % in a trial draw), the
  locating pin 0.2-0.5 m from the robot's base (assumed): a translation of +-c/2 and a yaw of +-c / s per docking,
  fixed until the cart leaves. The cart leaves for production between all blocks (5-8 blocks); the first docking is
  the reference. ur10 and kr16_like (a cobot cart and a heavier mobile cell; none on tool_changer).
* carriage play: track carriages run on cam followers (eccentric-bush rollers) on both sides of the rails; worn or
  badly adjusted rollers leave a clearance across the rail, and the carriage rocks about the rail's axis from one pair
  of rollers to the other when the moment about that axis changes sign, friction holding it while the moment stays
  inside a band (Slocum, *Precision Machine Design*, 1992, on kinematic and elastically averaged bearings; roller guide
  data as recalled from Hepco / Rollon catalogues). Clearance 0.02-0.08 mm over a roller base of 0.15-0.3 m, the rail
  0.1-0.3 m below the robot's base, friction band 2-8 % of the arm's largest moment about the rail (assumed); the
  elastic tilt of the carriage is set C's track and left out. ur10 and kr16_like (none on tool_changer).
* wire-rope mount: tools that must not pass vibration to the arm (grinding and polishing spindles, cameras) sit on
  wire-rope isolators -- helical stranded steel cables between two bars; the strands slide on each other, so the mount
  deflects elastically plus a friction slip that follows the load only beyond a slip force and otherwise stays
  (Demetriades, Constantinou & Reinhorn, "Study of wire rope systems for seismic protection of equipment in
  buildings", Eng. Struct. 15, 1993; a play operator in parallel with a spring, the Masing model of dry-friction
  hysteresis: Brokate & Sprekels 1996). The side weight of the tool and its held part, across the tool axis, loads
  it. Tools 1-3 / 4-10 kg, elastic compliance 2-5e-3 / 1-3e-3 mm/N, friction compliance 4-10e-3 / 2-6e-3 mm/N, slip
  force 2-6 / 8-20 N (ur10 / kr16_like; assumed, catalogue-like isolators); the target on the tool. Scored as link
  deflection (the end-of-arm structure carrying the target). None on tool_changer.
* tie-rod bar: long gripper bars (press-line crossbars, sheet-handling booms) are stiffened by a tie rod or a cable
  over a king post on one side: the rod carries tension only, so the bar bends at the stiff truss's rate when its load
  pulls the rod and at the bare beam's when it pushes (a slack cable; tension-only members, e.g. Hibbeler, *Structural
  Analysis*, ch. on cables). The bar carries its own weight and the part's, uniformly (tip deflection w L^4 / 8EI,
  Roark's *Formulas for Stress and Strain*, Table 8.1, case 2a); across the truss's plane it bends as the bare beam.
  Aluminium tube bars of 0.4-0.6 / 0.6-0.9 m, EI 4e3-1e4 / 6e3-1.5e4 N m^2 (kr16_like's first 0.5-0.8 m of
  1e4-3e4 N m^2: a gain of 21 %, the thermal model within 1.26x), 1-2 / 2-4 kg with their cups, the truss
  5-15x stiffer (ur10 / kr16_like; assumed); the target on the bar's end, the part's centre at its middle.
* jaw guide play: a parallel gripper's jaws slide in guides with a clearance; the jaw rocks in it when the moment on it
  changes sign -- the grip's reaction at the finger tips always opens it while a part is held, the part's and the
  finger's weight along the closing axis decide otherwise, and across the closing axis the weight alone, friction
  holding the jaw while the weight's component stays within 5-15 % of g (the play of
  a sliding guide, Slocum 1992, ch. 8). Clearance 0.02-0.08 mm over a guide of 20-60 mm, the target on a finger tip
  (:func:`effects_m.probe_hook`); ur10 and tool_changer (a cobot's gripper and the cutter gripper; none on kr16_like).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_m_joint import block_index

Z = np.array([0.0, 0.0, 1.0])


def _tool_gravity(ctx):
    """Gravity (P, 3) [m/s^2] in the tool frame and the tool rotation (P, 3, 3)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return np.einsum("pji,j->pi", Rt, -kin.G * Z), Rt


def _to_base(Rt, v):
    return np.einsum("pij,pj->pi", Rt, v)


# -------------------------------------------------------------------------------------------------- cart dock
DOCK_ARMS = {"ur10", "kr16_like"}


def dock_draw(ctx, hw, rng):
    if ctx.chain.name not in DOCK_ARMS:
        return {}
    B = int(block_index(ctx.session)[-1]) + 1
    c, s = rng.uniform(0.1, 0.3), rng.uniform(300, 600)
    a = rng.uniform(0, 2 * np.pi)
    pin = rng.uniform(200, 500) * np.array([np.cos(a), np.sin(a), 0.0])
    amp = np.c_[rng.uniform(-c / 2, c / 2, (B, 2)), rng.uniform(-c / s, c / s, B)]
    amp[0] = 0.0                                         # the first docking is the reference
    return {"pin_mm": pin, "amp": amp, "blocks": B}


def dock_parts(p, ctx):
    """(3 (B - 1), P, 3): per docking after the first, a unit shift along x, y and a unit yaw about the pin."""
    b = block_index(ctx.session)
    yaw = np.cross(Z, ctx.target - p["pin_mm"])
    cols = []
    for k in range(1, p["blocks"]):
        m = (b == k)[:, None].astype(float)
        cols += [m * np.eye(3)[0], m * np.eye(3)[1], m * yaw]
    return np.array(cols) if cols else np.zeros((0, len(ctx.q), 3))


def dock_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["amp"][1:].ravel(), dock_parts(p, ctx)) if p else None)


def dock_features(p, ctx, hw):
    return dock_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))


# ---------------------------------------------------------------------------------------------- carriage play
CARRIAGE_ARMS = {"ur10", "kr16_like"}


def carriage_draw(ctx, hw, rng):
    if ctx.chain.name not in CARRIAGE_ARMS:
        return {}
    a = rng.uniform(0, np.pi)
    u = np.array([np.cos(a), np.sin(a), 0.0])
    M = eb.mount_moment(ctx) @ u
    return {"rail": u, "theta_rad": rng.uniform(0.02, 0.08) / rng.uniform(150, 300), "h_mm": rng.uniform(100, 300),
            "band_Nm": rng.uniform(0.02, 0.08) * np.abs(M).max(), "start": float(rng.choice([-1.0, 1.0]))}


def carriage_side(p, ctx):
    """Roller pair (P,) the carriage rests on, +-1: the moment's sign about the rail, held while inside the band."""
    M = eb.mount_moment(ctx) @ p["rail"]
    side, out = p["start"], np.zeros(len(M))
    for i, m in enumerate(M):
        if abs(m) > p["band_Nm"]:
            side = np.sign(m)
        out[i] = side
    return out


def carriage_part(p, ctx):
    return np.cross(carriage_side(p, ctx)[:, None] * p["rail"], ctx.target + p["h_mm"] * Z)


def carriage_apply(p, ctx, hw):
    return Contribution(displace=p["theta_rad"] * carriage_part(p, ctx) if p else None)


def carriage_features(p, ctx, hw):
    return carriage_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------- wire-rope mount
#: per arm: tool mass [kg], the isolators' elastic and friction compliance [mm/N], the friction slip force [N] (assumed)
ROPE = {"ur10": ((1.0, 3.0), (2e-3, 5e-3), (4e-3, 1e-2), (2.0, 6.0)),
        "kr16_like": ((4.0, 10.0), (1e-3, 3e-3), (2e-3, 6e-3), (8.0, 20.0))}


def rope_draw(ctx, hw, rng):
    if ctx.chain.name not in ROPE:
        return {}
    (m0, m1), (e0, e1), (f0, f1), (r0, r1) = ROPE[ctx.chain.name]
    return {"m_kg": rng.uniform(m0, m1), "c_mm_per_N": np.array([rng.uniform(e0, e1), rng.uniform(f0, f1)]),
            "slip_N": rng.uniform(r0, r1)}


def play_operator(F, r, z0=None):
    """The play (backlash) operator's output (P, ...) for inputs F (P, ...) and half width r: it follows F at a lag of
    at most r and stays put while F turns back inside the band (Krasnosel'skii & Pokrovskii; Brokate & Sprekels,
    *Hysteresis and Phase Transitions*, 1996, ch. 2)."""
    F = np.asarray(F, float)
    z, out = (F[0] if z0 is None else z0), np.zeros_like(F)
    for k, f in enumerate(F):
        z = np.clip(z, f - r, f + r)
        out[k] = z
    return out


def rope_parts(p, ctx):
    """(2, P, 3) [mm per mm/N]: the tool's side shift per unit elastic and per unit friction compliance -- the side
    weight (across the tool axis) and its play operator."""
    g, Rt = _tool_gravity(ctx)
    F = (p["m_kg"] + ctx.session.payload_kg)[:, None] * g * np.array([1.0, 1.0, 0.0])
    return np.array([_to_base(Rt, F), _to_base(Rt, play_operator(F, p["slip_N"]))])


def rope_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["c_mm_per_N"], rope_parts(p, ctx)) if p else None)


def rope_features(p, ctx, hw):
    return rope_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------------ tie-rod bar
#: per arm: bar length [mm], EI [N m^2], bar mass [kg] (assumed)
BAR = {"ur10": ((400.0, 600.0), (4e3, 1e4), (1.0, 2.0)), "kr16_like": ((600.0, 900.0), (6e3, 1.5e4), (2.0, 4.0))}


def bar_geometry(probe_mm):
    """The bar's direction d (3,) across the tool axis and its length [mm]: the target sits on its end
    (:func:`effects_m.probe_hook`)."""
    d = np.array([probe_mm[0], probe_mm[1], 0.0])
    return d / np.linalg.norm(d), float(np.linalg.norm(d))


def bar_draw(ctx, hw, rng):
    if ctx.chain.name not in BAR:
        return {}
    _, (e0, e1), (b0, b1) = BAR[ctx.chain.name]
    d, L = bar_geometry(ctx.probe_mm)
    EI, rod = rng.uniform(e0, e1), rng.uniform(5, 15)
    c = (L / 1000) ** 3 / (8 * EI) * 1000                # tip deflection per N of uniform load [mm/N]
    return {"d": d, "L_mm": L, "m_bar_kg": rng.uniform(b0, b1), "stay": float(rng.choice([-1.0, 1.0])),
            "c_mm_per_N": np.array([c / rod, c, c])}


def bar_parts(p, ctx):
    """(3, P, 3) [mm per mm/N]: the uniform load along the tool axis (the truss's plane) pulling the tie rod, pushing
    it, and the load across the plane."""
    g, Rt = _tool_gravity(ctx)
    W = (p["m_bar_kg"] + ctx.session.payload_kg)[:, None] * g
    e = np.cross(Z, p["d"])
    wz = W[:, 2] * p["stay"]                              # > 0: the load pulls the rod
    pull, push = np.maximum(wz, 0.0) * p["stay"], np.minimum(wz, 0.0) * p["stay"]
    return np.array([_to_base(Rt, pull[:, None] * Z), _to_base(Rt, push[:, None] * Z),
                     _to_base(Rt, (W @ e)[:, None] * e)])


def bar_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["c_mm_per_N"], bar_parts(p, ctx)) if p else None)


def bar_features(p, ctx, hw):
    return bar_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))


# --------------------------------------------------------------------------------------------- jaw guide play
#: per arm: the gripper's half opening at the finger [mm] and the finger tip's height [mm] (assumed)
JAW = {"ur10": ((20.0, 50.0), (120.0, 200.0)), "tool_changer": ((120.0, 200.0), (300.0, 450.0))}


def jaw_geometry(probe_mm):
    """The closing axis d (3,), the half opening and the tip's height [mm]: the target sits on the finger's tip
    (:func:`effects_m.probe_hook`)."""
    d = np.array([probe_mm[0], probe_mm[1], 0.0])
    return d / np.linalg.norm(d), float(np.linalg.norm(d)), float(probe_mm[2])


def jaw_draw(ctx, hw, rng):
    if ctx.chain.name not in JAW:
        return {}
    d, _, h = jaw_geometry(ctx.probe_mm)
    c, Lg = rng.uniform(0.02, 0.08, 2), rng.uniform(20.0, 60.0, 2)
    return {"d": d, "amp_mm": c / 2 + c / Lg * h, "band": rng.uniform(0.05, 0.15), "start": rng.choice([-1.0, 1.0], 2)}


def jaw_sides(p, ctx):
    """(2, P): the jaw's rest in its guide along the closing axis (+1 outwards: gripping) and across it, each held by
    friction while the weight's component stays inside ``band`` of g."""
    g, _ = _tool_gravity(ctx)
    held = ctx.session.payload_kg > 0
    comp = np.array([g @ p["d"], g @ np.cross(Z, p["d"])]) / kin.G
    side, out = np.array(p["start"], float), np.zeros((2, len(held)))
    for i in range(len(held)):
        side = np.where(np.abs(comp[:, i]) > p["band"], np.sign(comp[:, i]), side)
        if held[i]:
            side[0] = 1.0
        out[:, i] = side
    return out


def jaw_parts(p, ctx):
    _, Rt = _tool_gravity(ctx)
    s = jaw_sides(p, ctx)
    return np.array([_to_base(Rt, s[0][:, None] * p["d"]), _to_base(Rt, s[1][:, None] * np.cross(Z, p["d"]))])


def jaw_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["amp_mm"], jaw_parts(p, ctx)) if p else None)


def jaw_features(p, ctx, hw):
    return jaw_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))
