"""Set R body effects (new physics, not in sets A-Q): the arm on a slab on grade that a loaded forklift, parked at a
nearby dock at unlogged moments, dishes into its deflection basin; the arm on a sprayer vehicle's sprung chassis, which
rises and tilts as the vehicle's tank drains and sinks back when it is refilled; a thin-webbed sheet-metal bracket
carrying the target, whose web buckles in shear and goes on as a tension field; and a tool on a swing-away mount,
preloaded against its stop, that its own weight swings off the stop in some orientations. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* forklift slab: a concentrated load P on a slab on grade (a plate of rigidity D on a Winkler foundation of modulus
  k) dishes it into the basin w(r) = -(P l^2 / (2 pi D)) kei(r / l), l = (D / k)^(1/4) the radius of relative
  stiffness, w(0) = P / (8 k l^2) (Westergaard, "Stresses in concrete pavements computed by theoretical analysis",
  Public Roads 7, 1926; Hetenyi, *Beams on Elastic Foundation*, 1946, ch. on plates; Kelvin function kei). The arm's
  base, a small rigid footprint r from the load, sinks by w(r) and tilts towards the load by dw/dr. A loaded forklift's
  front axle (40-80 kN) stops at a dock 1.2-2.5 m from the base, arriving at random (Poisson, 4-10 an hour) and staying
  1-4 min; slab of l = 0.7-1 m on a subgrade of k = 27-55 MPa/m (industrial ground floors, Concrete Society TR 34, as
  recalled), the base's foot the pedestal's height below it (assumed). The truck is not logged; the tracker stands
  beyond the basin's reach. The true structure: one column (the basin's sink and slope times the truck's presence),
  amplitude P / (k l^2).
* sprayer tank: the arm rides on a vehicle's chassis on four linear springs (a sprung rigid body: the springs' forces
  balance the loads' force and moments, K u = f, K = k sum a a^T, a = (1, y, -x): statics of a rigid body on elastic
  supports, Timoshenko & Young, *Engineering Mechanics*); the loads are the arm's weights and the vehicle's tank, which
  a boom sprayer empties at a steady rate while it works and which is refilled in each pause. Springs at +-500-800 /
  +-350-550 mm from the base's axis on a plane 300-600 mm below it, 750-1500 / 1500-3000 / 5000-10000 N/mm each (ur10 /
  kr16_like / tool_changer: rubber torsion axles of compact carriers), a tank of 30-60 / 50-120 / 150-300 kg full (first
  150-300 / 300-600 / 1000-2000 N/mm, 60-120 / 100-200 / 300-600 kg: 6-8 mm at the tool, a truck's leaf springs rather
  than a compact carrier's) 500-900 mm from the base, 40-80 % of it sprayed over a block (assumed; nothing of the
  vehicle is logged). The true structure: one column (the chassis' sink and tilt under every load per unit spring
  compliance), amplitude 1 / k.
* web buckling: a thin web in shear buckles at tau_cr = k_s pi^2 E / (12 (1 - nu^2)) (t / b)^2 and carries further shear
  as a diagonal tension field at a lower stiffness (Wagner, "Ebene Blechwandtraeger mit sehr duennem Stegblech", Z.
  Flugtechnik 20, 1929; Kuhn, *Stresses in Aircraft and Shell Structures*, 1956, ch. 2): the bracket's deflection is
  bilinear in its shear force, V / k1 up to V_cr, then (V - V_cr) / k2 more with k2 = 0.25-0.45 k1. A sheet-metal
  bracket (a web of 1-1.5 mm between two flanges) reaches 120-220 mm across the tool axis and carries a sensor of 1-3 /
  2-6 / 5-15 kg with the target at its tip (:func:`effects_r.probe_hook`); its web lies along the tool axis, so the
  shear is the sensor's weight along the tool axis; V_cr at 30-60 % of the session's largest shear, which would deflect
  the tip by 0.08-0.2 mm with k1 alone (assumed). The true structure: two columns (the shear up to V_cr and beyond it),
  amplitudes 1 / k1 and 1 / k2.
* swing mount: dispensing valves, torches and knives are carried on swing-away (breakaway) mounts: a hinge with a spring
  that preloads the tool against a stop, so that a collision swings it away; the tool's own weight moment about the
  hinge, when it pushes away from the stop and exceeds the spring's preload, swings it off by (M - M_pre) / k (a
  preloaded torsion spring: Wahl, *Mechanical Springs*, 2nd ed., 1963). Hinge 20-40 mm out on the tool axis, across the
  line to the target 150-250 mm out (:func:`effects_r.probe_hook`), a tool of 2-6 / 4-12 / 15-40 kg with its centre of
  mass 40-70 % of the way to the target, preload 30-60 % of the largest moment off the stop over the session, the target
  swung 0.2-0.5 mm at that moment (a spring sized to release at a light collision; first 0.1-0.3 mm: R21 gained 10 %
  with the transmission model at 1.11x) (assumed). The true structure: one column (the excess moment), amplitude 1 / k.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np
from scipy.special import kei, keip

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])


def _unit(v):
    return v / np.linalg.norm(v)


def _gravity_tool(ctx):
    """(P, 3, 3) tool rotations and (P, 3) gravity [m/s^2] in the tool frame."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt, np.einsum("pji,j->pi", Rt, -kin.G * Z)


# ------------------------------------------------------------------------------------------------ forklift slab
def slab_draw(ctx, hw, rng):
    t = ctx.session.time_s
    az = rng.uniform(0, 2 * np.pi)
    t0 = t[0] - 1200.0
    n = int(rng.poisson(rng.uniform(4.0, 10.0) / 3600 * (t[-1] - t0))) + 2
    starts = np.sort(rng.uniform(t0, t[-1], n))
    P, k, l = rng.uniform(40e3, 80e3), rng.uniform(0.027, 0.055), rng.uniform(700.0, 1000.0)
    return {"e_r": np.array([np.cos(az), np.sin(az), 0.0]), "r_mm": rng.uniform(1200.0, 2500.0), "l_mm": l,
            "A_mm": P / (k * l ** 2), "stays": np.c_[starts, starts + rng.uniform(1.0, 4.0, n) * 60],
            "O": -hw["mount"]["height_mm"] * Z}


def slab_present(p, t):
    t = np.asarray(t, float)
    return np.any((t[:, None] >= p["stays"][:, 0]) & (t[:, None] < p["stays"][:, 1]), axis=1).astype(float)


def slab_basin(p):
    """The sink [mm] and the slope [rad] of the basin at the base per unit P / (k l^2)."""
    x = p["r_mm"] / p["l_mm"]
    return -kei(x) / (2 * np.pi), -keip(x) / (2 * np.pi * p["l_mm"])


def slab_shape(p, ctx):
    """(P, 3): the target's displacement per unit P / (k l^2) while the truck stands: the base sinks by w and turns
    with the slab's surface, omega = w' z x e_r (e_r from the load to the base)."""
    w, dw = slab_basin(p)
    omega = dw * np.cross(Z, p["e_r"])
    one = -w * Z + np.cross(omega, ctx.target - p["O"])
    return slab_present(p, ctx.session.time_s)[:, None] * one


def slab_apply(p, ctx, hw):
    return Contribution(displace=p["A_mm"] * slab_shape(p, ctx))


def slab_features(p, ctx, hw):
    return slab_shape(p, ctx)[None]


# ------------------------------------------------------------------------------------------------ sprayer tank
SPRING_N_MM = {"ur10": (750.0, 1500.0), "kr16_like": (1500.0, 3000.0), "tool_changer": (5000.0, 10000.0)}
TANK_KG = {"ur10": (30.0, 60.0), "kr16_like": (50.0, 120.0), "tool_changer": (150.0, 300.0)}


def tank_draw(ctx, hw, rng):
    az = rng.uniform(0, 2 * np.pi)
    R = np.array([[np.cos(az), -np.sin(az)], [np.sin(az), np.cos(az)]])
    a, b = rng.uniform(500.0, 800.0), rng.uniform(350.0, 550.0)
    springs = np.array([[a, b], [a, -b], [-a, b], [-a, -b]]) @ R.T
    taz = rng.uniform(0, 2 * np.pi)
    return {"springs": springs, "O": -rng.uniform(300.0, 600.0) * Z,
            "k_N_mm": rng.uniform(*SPRING_N_MM[ctx.chain.name]),
            "tank": rng.uniform(500.0, 900.0) * np.array([np.cos(taz), np.sin(taz), 0.0]),
            "full_kg": rng.uniform(*TANK_KG[ctx.chain.name]), "drain": rng.uniform(0.4, 0.8)}


def tank_mass(p, session):
    """(P,): the tank's content [kg]: full at each block's start (refilled in the pause), sprayed at a steady rate."""
    t, block = session.time_s, np.cumsum(session.gap_s < 0)
    out = np.zeros(len(t))
    for b in np.unique(block):
        on = block == b
        t0 = t[on][0] - session.dwell_s[on][0] - session.move_s[on][0]
        span = max(t[on][-1] - t0, 1.0)
        out[on] = p["full_kg"] * (1 - p["drain"] * (t[on] - t0) / span)
    return out


def tank_shape(p, ctx):
    """(P, 3): the target's displacement per unit spring compliance [mm per mm/N]: the chassis sinking and tilting under
    the arm's weights and the tank's."""
    m, pos, _ = ctx.mass_state
    pos = np.concatenate([pos, np.broadcast_to(p["tank"], (len(pos), 1, 3))], axis=1) - p["O"]
    m = np.c_[m, tank_mass(p, ctx.session)]
    fz = -kin.G * m                                                    # (P, B) [N]
    g = np.stack([fz.sum(1), (fz * pos[..., 1]).sum(1), -(fz * pos[..., 0]).sum(1)], axis=1)
    a = np.c_[np.ones(4), p["springs"][:, 1], -p["springs"][:, 0]]
    u = np.linalg.solve(a.T @ a, g.T).T                                # (w, theta_x, theta_y) per unit compliance
    omega = np.c_[u[:, 1], u[:, 2], np.zeros(len(u))]
    return u[:, :1] * Z + np.cross(omega, ctx.target - p["O"])


def tank_apply(p, ctx, hw):
    return Contribution(displace=tank_shape(p, ctx) / p["k_N_mm"])


def tank_features(p, ctx, hw):
    return tank_shape(p, ctx)[None]


# ------------------------------------------------------------------------------------------------- web buckling
BRACKET_MM = (120.0, 220.0)
SENSOR_KG = {"ur10": (1.0, 3.0), "kr16_like": (2.0, 6.0), "tool_changer": (5.0, 15.0)}


def web_draw(ctx, hw, rng):
    p = {"m_kg": rng.uniform(*SENSOR_KG[ctx.chain.name]), "V_cr": 1.0, "e_w": Z.copy()}
    V = web_shear(p, ctx)
    Vmax = np.abs(V).max()
    p["V_cr"] = rng.uniform(0.3, 0.6) * Vmax
    p["k1"] = Vmax / rng.uniform(0.08, 0.2)                            # [N/mm]
    p["k2"] = p["k1"] * rng.uniform(0.25, 0.45)
    return p


def web_shear(p, ctx):
    """(P,): the web's shear force [N]: the sensor's weight along the tool axis."""
    _, g_t = _gravity_tool(ctx)
    return p["m_kg"] * g_t @ p["e_w"]


def web_parts(p, ctx):
    """(2, P, 3): the tip's displacement per unit compliance [mm per mm/N] up to buckling and beyond, base frame."""
    Rt, _ = _gravity_tool(ctx)
    V = web_shear(p, ctx)
    Vc = np.clip(V, -p["V_cr"], p["V_cr"])
    d = Rt @ p["e_w"]
    return np.array([Vc[:, None] * d, (V - Vc)[:, None] * d])


def web_amplitudes(p):
    return np.array([1 / p["k1"], 1 / p["k2"]])


def web_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("m,mpi->pi", web_amplitudes(p), web_parts(p, ctx)))


def web_features(p, ctx, hw):
    return web_parts(p, ctx)


# --------------------------------------------------------------------------------------------------- swing mount
SWING_MM = (150.0, 250.0)
TOOL_KG = {"ur10": (2.0, 6.0), "kr16_like": (4.0, 12.0), "tool_changer": (15.0, 40.0)}


def swing_draw(ctx, hw, rng):
    T = np.asarray(ctx.probe_mm, float)
    H = rng.uniform(20.0, 40.0) * Z
    across = np.linalg.norm(np.cross(_unit(T - H), Z)) > 0.1
    axis = _unit(np.cross(T - H, Z) if across else np.cross(T - H, [1.0, 0, 0]))
    p = {"T": T, "H": H, "axis": axis, "c": H + rng.uniform(0.4, 0.7) * (T - H),
         "m_kg": rng.uniform(*TOOL_KG[ctx.chain.name]),
         "side": float(rng.choice([-1.0, 1.0])), "M_pre": 0.0}
    M = p["side"] * swing_moment(p, ctx)
    Mmax = max(M.max(), 1e-9)
    p["M_pre"] = rng.uniform(0.3, 0.6) * Mmax
    p["k_Nmm"] = (Mmax - p["M_pre"]) / (rng.uniform(0.2, 0.5) / np.linalg.norm(T - H))
    return p


def swing_moment(p, ctx):
    """(P,): the tool's weight moment about the hinge's axis [N mm]."""
    _, g_t = _gravity_tool(ctx)
    return np.cross(p["c"] - p["H"], p["m_kg"] * g_t) @ p["axis"]


def swing_shape(p, ctx):
    """(P, 3): the target's displacement per unit hinge compliance [mm per rad/(N mm)], base frame."""
    Rt, _ = _gravity_tool(ctx)
    excess = np.maximum(p["side"] * swing_moment(p, ctx) - p["M_pre"], 0.0) * p["side"]
    return excess[:, None] * (Rt @ np.cross(p["axis"], p["T"] - p["H"]))


def swing_apply(p, ctx, hw):
    return Contribution(displace=swing_shape(p, ctx) / p["k_Nmm"])


def swing_features(p, ctx, hw):
    return swing_shape(p, ctx)[None]
