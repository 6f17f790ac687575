"""Set ZC body effects (new physics, not in sets A-ZB): the arm on a tall six-strut (hexapod) pedestal whose struts are
softer in tension than in compression; a mobile carrier whose active counterweight cancels the arm's moment only within
its stroke; a tool boom hinged at the flange on a rubber torsion bush that stiffens as it turns; and a tool boom bent by
a hose that it lifts off the floor, the hanging length growing with the boom tip's height. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* hexapod mount: the arm stands on the top plate of a six-strut space frame (a hexapod pedestal, struts 0.9-1.5 m
  between ball-ended rod ends on a base and a top circle); each strut is an axial spring, so the plate's stiffness is K
  = sum k_i s_i s_i^T, s_i = (u_i, r_i x u_i) its Pluecker coordinates (Merlet, *Parallel Robots*, 2nd ed., 2006, ch. 8,
  stiffness; Gosselin, "Stiffness mapping for parallel manipulators", IEEE Trans. Robot. Autom. 6, 1990). A strut bears
  in compression on its tube's shoulder (k) and in tension through its rod end's thread and jam nut, beta k with beta
  0.05-0.2 (bilinear: the struts' states iterated to agree with their forces). The plate moves by K^-1 (0, 0, -W, M): it
  sinks, tilts, slides and turns together. Sized so that the target's largest move about its mean is 0.3-0.6 mm (its
  sink under the arm's constant weight adds up to about 0.5 mm more on tool_changer, absorbed by the geometry). First
  short (height 0.35-0.65 m) with equal struts: ZC06 (ur10) ambiguous with the joint and link models at 0.99x; then tall
  (the struts steeper, the plate swaying more): 1.00-1.14x on ur10 in trial draws, and with the struts' tension softness
  still 1.11-1.16x in two of four: now on the heavier arms only. Unlike the bases on springs, pads or wheels of sets
  A-ZB (a tilt about a fixed pivot), the support is a parallel frame whose compliance couples tilt with translation and
  switches with its struts' forces. Driven by the pose and the payload (logged). The true structure: one column,
  amplitude 1 / k [mm/N].
* counterweight base: a mobile manipulator whose carrier keeps its zero-moment point centred with an active
  counterweight on an x-y table (stability compensation of mobile manipulators: Huang, Sugano & Tanie, "Stability
  compensation of a mobile manipulator by manipulator motion", Adv. Robotics 13, 1999; the variable counterweights of
  mobile cranes); the counterweight cancels each axis' gravity moment M_x, M_y only within its stroke, +-L (45-70 % of
  the session's largest), and the carrier's suspension takes the rest, tilting about its roll centre at the wheels'
  contact, h 400-900 mm (the deck's height) below the base (first 200-600 mm: ZC22's joint model at 1.25x): tilt = c (M
  - clip(M, -L, L)), a dead zone. Sized so that the target moves 0.3-0.6 mm at the largest. First a counterweight set
  per block against the block's mean part moment (ZC06, ZC12: ambiguous, gains 5-20 %: a moment-linear tilt is nearly
  absorbed by the geometry and mimicked by the joints); now the stroke-limited dead zone; with a stroke of 30-60 % still
  1.06-1.23x; on ur10 (light, its base moment made by the same links whose joints twist) 1.11x in two of three trial
  draws with the final stroke, so on the heavier arms only. Unlike set V's jacks or set E's soft foot (a support
  switched by block or by the load's side), the support sees only the moment an actuator could not cancel. Driven by the
  pose and the payload (logged). The true structure: one column, amplitude c [rad/(N m)].
* rubber bush: a light tool boom (500 mm along the tool's x, the part and the target at its tip) is hinged at the flange
  on a rubber torsion bush (a bonded rubber-metal bush about the tool's y, isolating the tool's vibration); the bush's
  torque-angle curve is progressive, M = k0 phi (1 + gamma phi^2) (rubber springs: Goebel, *Gummifedern*, 1969; Gent,
  *Engineering with Rubber*, 3rd ed., 2012, ch. 10), so phi = M / k0 - gamma (M / k0)^3 to first order, M the part's and
  boom's weight moment about the bush. Sized so that the tip moves 0.2-0.5 mm, the cubic term 15-35 % of it. Unlike set
  ZB's insulating flange (a layer in bending and torsion) or set M's wire-rope mounts, the tool turns about one hinge
  axis on a stiffening rubber spring. Driven by the pose and the payload (logged). The true structure: two columns (the
  linear and the cubic turn), amplitudes 1 / k0 and -gamma / k0^3.
* floor hose: a suction or supply hose lies on the floor and rises to a clamp at the tip of a light tool boom (450 mm
  along the tool's x, the target at its tip); the boom carries the hanging length of hose, w (z_tip - z_floor) (a chain
  or hose lifted off a pile: its hanging weight grows with the height, the catenary's horizontal pull nil at the pile;
  Irvine, *Cable Structures*, 1981, ch. 1), w 0.5-1.5 kg/m, the floor 100-400 mm below the session's lowest tip; its
  share across the boom bends it as a cantilever, F L^3 / (3 EI) (Roark, table 8.1, case 1a). Sized so that the tip
  moves 0.2-0.5 mm. Replaces a first kind (the upper arm bent by its balancer's force, ZC13 and ZC22: gains 7-10 %,
  ambiguous with the transmission model -- a bend that follows axis 2 alone is a joint-2 error as a function of its
  angle, and a nearly constant force is a link-length error). Unlike the hose kinds of sets D-ZB (a hose's pull or
  weight twisting the joints), the end-of-arm boom bends under a load that grows with its height. Driven by the pose
  (logged) and the hose's weight (not logged). The true structure: one column, amplitude w / EI.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import GRAVITY_N, mount_moment
from sim2real_indep.effects_u_joint import block_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _weight_N(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * np.linalg.norm(GRAVITY_N)


# ------------------------------------------------------------------------------------------------ hexapod mount
HEXAPOD_MM = {"ur10": (350.0, 250.0, 900.0), "kr16_like": (550.0, 400.0, 1200.0),
              "tool_changer": (800.0, 600.0, 1500.0)}   # base radius, top radius, height: a tall six-strut pedestal


def hexapod_legs(p):
    """(6, 3) the legs' unit vectors (base to top) and (6, 3) their top joints (the top plate's centre at 0): base
    joints in pairs at 120 i +- a, top joints at 60 + 120 i +- a, each leg from a base joint to the nearer top joint of
    the next pair (the usual 6-6 layout)."""
    Rb, Rt, H = p["geom_mm"]
    a = p["half_deg"]
    ang_b = np.deg2rad(np.array([120.0 * i + s * a for i in range(3) for s in (-1, 1)]))
    ang_t = np.deg2rad(np.array([60.0 + 120.0 * i + s * a for i in range(3) for s in (-1, 1)]))
    base = np.c_[Rb * np.cos(ang_b), Rb * np.sin(ang_b), np.full(6, -H)]
    top = np.c_[Rt * np.cos(ang_t), Rt * np.sin(ang_t), np.zeros(6)]
    base = np.roll(base, -1, axis=0)                               # leg k: base joint k + 1 to top joint k
    u = top - base
    return u / np.linalg.norm(u, axis=1, keepdims=True), top


def hexapod_unit(p, ctx):
    """(P, 3) the target's displacement per unit strut compliance 1 / k [per N/mm]: a strut in tension at beta k (its
    rod end's thread), in compression at k (its shoulder); the struts' states iterated to agree with their forces."""
    u, r = hexapod_legs(p)
    S = np.c_[u, np.cross(r, u)]                                   # (6, 6) Pluecker rows
    w = np.c_[np.zeros((len(ctx.q), 2)), -_weight_N(ctx), mount_moment(ctx) * 1000.0]   # [N, N mm]
    f = w @ np.linalg.inv(S)                                        # the struts' forces (rigid: S^T f = w), + tension
    x = np.zeros((len(w), 6))
    for i in range(len(w)):
        k = np.ones(6)
        for _ in range(8):
            kk = np.where(f[i] > 0, p["beta"], 1.0)
            if np.array_equal(kk, k):
                break
            k = kk
            x[i] = np.linalg.solve(S.T @ (k[:, None] * S), w[i])
            f[i] = k * (S @ x[i])
        x[i] = np.linalg.solve(S.T @ (k[:, None] * S), w[i])
    return x[:, :3] + np.cross(x[:, 3:], ctx.target)


def hexapod_draw(ctx, hw, rng):
    p = {"geom_mm": HEXAPOD_MM[ctx.chain.name], "half_deg": rng.uniform(8.0, 20.0), "beta": rng.uniform(0.05, 0.2)}
    unit = hexapod_unit(p, ctx)
    p["inv_k"] = rng.uniform(0.3, 0.6) / max(np.linalg.norm(unit - unit.mean(axis=0), axis=1).max(), 1e-12)
    return p


def hexapod_features(p, ctx, hw):
    return hexapod_unit(p, ctx)[None]


def hexapod_apply(p, ctx, hw):
    return _amp_apply([p["inv_k"]], hexapod_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------- counterweight base
def counterweight_unit(p, ctx):
    """(P, 3) the target's displacement per unit tilt compliance [per N m]: the carrier tilting about its roll centre
    h below the base under the moment its counterweight could not cancel (each axis' moment beyond the counterweight's
    stroke, +-L_x, +-L_y about the carrier's centre: a dead zone)."""
    M = mount_moment(ctx)
    net = np.zeros_like(M)
    for i in (0, 1):
        net[:, i] = M[:, i] - np.clip(M[:, i], -p["L_Nm"][i], p["L_Nm"][i])
    return np.cross(net, ctx.target - [0.0, 0.0, -p["h_mm"]])


def counterweight_draw(ctx, hw, rng):
    M = np.abs(mount_moment(ctx)[:, :2]).max(axis=0)
    p = {"h_mm": rng.uniform(400.0, 900.0), "L_Nm": M * rng.uniform(0.45, 0.7, 2)}
    unit = counterweight_unit(p, ctx)
    p["c"] = rng.uniform(0.3, 0.6) / max(np.linalg.norm(unit, axis=1).max(), 1e-12)
    return p


def counterweight_features(p, ctx, hw):
    return counterweight_unit(p, ctx)[None]


def counterweight_apply(p, ctx, hw):
    return _amp_apply([p["c"]], counterweight_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- rubber bush
BUSH_BOOM_MM = 500.0
BUSH_KG = 1.2
BUSH_PIVOT_MM = np.array([0.0, 0.0, 40.0])     # the bush's axis crosses the tool's z 40 mm out (along the tool's y)


def bush_moment(ctx):
    """(P,) the weight moment about the bush's axis (tool y) [N mm]: the part at the tip and half the boom."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N)                       # gravity per kg, tool frame
    mass = ctx.session.payload_kg[:, None]
    arm_p = ctx.payload_com_mm - BUSH_PIVOT_MM
    arm_b = np.array([0.5 * BUSH_BOOM_MM, 0.0, 0.0])
    return (np.cross(arm_p, g * mass) + np.cross(arm_b, g * BUSH_KG))[:, 1]


def bush_parts(p, ctx):
    """(2, P, 3) the target's displacement per unit of the linear and the cubic turn (base frame)."""
    pf, Rt = kin.flange(ctx.chain, ctx.q)
    M = bush_moment(ctx)
    pivot = pf + Rt @ BUSH_PIVOT_MM
    lever = np.cross(Rt[:, :, 1], ctx.target - pivot)
    return np.array([lever * M[:, None], lever * (M ** 3)[:, None]])


def bush_draw(ctx, hw, rng):
    parts = bush_parts({}, ctx)
    tot, share = rng.uniform(0.2, 0.5), rng.uniform(0.15, 0.35)
    Mmax = np.abs(bush_moment(ctx)).max()
    inv_k0 = tot / (1 - share) / max(np.linalg.norm(parts[0], axis=1).max(), 1e-12)
    cubic = share * tot / (1 - share) / max(np.linalg.norm(parts[1], axis=1).max(), 1e-12)
    return {"inv_k0": inv_k0, "cubic": -cubic, "gamma": cubic / max(inv_k0, 1e-30) ** 3, "M_max": Mmax}


def bush_features(p, ctx, hw):
    return bush_parts(p, ctx)


def bush_apply(p, ctx, hw):
    return _amp_apply([p["inv_k0"], p["cubic"]], bush_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- floor hose
HOSE_BOOM_MM = 450.0


def floor_hose_unit(p, ctx):
    """(P, 3) the boom tip's deflection per unit w / EI [mm per (N/mm / N mm^2)]: the hose's hanging weight w (z_tip -
    z_floor) at the tip, its share across the boom bending it as a cantilever (F L^3 / 3)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    hang = np.clip(ctx.target[:, 2] - p["floor_mm"], 0.0, None)           # the hanging length [mm]
    down = np.array([0.0, 0.0, -1.0])
    along = Rt[:, :, 0]                                                    # the boom along the tool's x
    across = down - np.einsum("pi,i->p", along, down)[:, None] * along    # the weight's share across the boom
    return across * (hang * HOSE_BOOM_MM ** 3 / 3.0)[:, None]


def floor_hose_draw(ctx, hw, rng):
    p = {"floor_mm": float(ctx.target[:, 2].min()) - rng.uniform(100.0, 400.0), "w_N_mm": rng.uniform(0.005, 0.015)}
    unit = floor_hose_unit(p, ctx)
    p["w_EI"] = rng.uniform(0.2, 0.5) / max(np.linalg.norm(unit, axis=1).max(), 1e-12)
    p["EI"] = p["w_N_mm"] / p["w_EI"]
    return p


def floor_hose_features(p, ctx, hw):
    return floor_hose_unit(p, ctx)[None]


def floor_hose_apply(p, ctx, hw):
    return _amp_apply([p["w_EI"]], floor_hose_features(p, ctx, hw))
