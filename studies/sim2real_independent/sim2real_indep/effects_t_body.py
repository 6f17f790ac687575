"""Set T body effects (new physics, not in sets A-S): the arm on a bracket of a hall column that also carries an
overhead crane's runway, bent by the crane's wheel loads on its corbel as the crane travels and lifts; the arm on a
console in a tunnel-boring machine's shield that squeezing rock ovalises during the standstill for the cutter change;
a tool on a lateral compliance unit that is locked (and centred) while the gripper holds a part and floats under the
tool's weight while it is empty; and a tool on an axial compliance plunger, centred by two springs, whose guide friction
keeps it wherever it last stuck (a play operator of the weight along the tool axis). Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* crane runway: a hall column of a rolled H section (HE 240-300 B, EN 10365), fixed at its foot and held laterally by
  the roof bracing at H = 7-9 m, carries the crane runway girder on a corbel 0.8-2 m below its top, eccentric by e =
  0.25-0.5 m; a wheel load R makes the couple R e (crane runways: EN 1993-6, as recalled; superposition for a propped
  cantilever, Timoshenko & Gere, *Mechanics of Materials*: the couple M0 at height a, the prop force P = -3 M0 a (H -
  a / 2) / H^3, below a the slope M0 z / EI + P z (2H - z) / 2EI and the deflection M0 z^2 / 2EI + P z^2 (3H - z) /
  6EI). The arm's base plate sits on a bracket of the column 1.5-3 m above the floor (over a machine), 0.3-0.6 m from
  its axis on the corbel's side, so the base turns and shifts with the column there. R follows the crane: simply
  supported runway girders of 5-7 m spans give the column the reaction of each wheel within a span, R = W (1 - |x| /
  L_s) (influence line), per wheel a quarter of the bridge plus half the trolley and hook load in the lever rule across
  the span; bridges of 2-5 / 3-8 t, trolleys of 0.3-1 t, hooks lifting 0.3-1 of 3-8 / 3-10 t half the time (ur10 /
  kr16_like halls), two wheels 2-3 m apart per end carriage, the crane moving to a new place every 1-5 min along 30 m
  of runway (assumed; first a bracket at 0.8-1.6 m and lighter cranes: 0.05 mm rms on ur10, gain 11 %). Nothing of the
  crane is logged. The true structure: one column, amplitude e / EI.
* shield squeeze: in squeezing rock a shield machine's convergence goes on during a standstill, by a law of the form
  C(t) = C_inf (1 - (T / (T + t))^n) (Sulem, Panet & Guenot, "An analytical solution for time-dependent displacements in
  a circular tunnel", Int. J. Rock Mech. Min. Sci. 24(3), 1987); the uneven rock pressure ovalises the shield, an
  inextensional ring mode u_r = delta cos 2(phi - phi_p), u_phi = -(delta / 2) sin 2(phi - phi_p), the section turning
  by (u_phi - du_r / dphi) / R (thin rings: Timoshenko, *Strength of Materials* II, deformation of rings). The robot's
  console, welded to the skin of a shield of radius 2.5-4.5 m at its side (60-120 deg from the crown, either side),
  moves with it; the tunnel's axis along the arm's reach (+-10 deg), the principal axis phi_p anywhere (bedded rock),
  delta_inf 2-6 mm, T 2-10 h, n 0.2-0.4, the session starting 0.5-4 h into the standstill (assumed; first a console near
  the invert and delta_inf 0.5-2 mm: the vertical shift was the thermal model's per-body drift of the column link,
  ambiguous with it at 1.00x in a random-split case). tool_changer (the tunnelling robot) and kr16_like (a handling arm
  in the same shield). The true structure: one column, amplitude delta_inf.
* lockable float: lateral compliance units carry a tool on centring springs and lock it with a pneumatic cone piston
  (compensation units with locking, as recalled from SCHUNK AGE-XY / ATI compliance-device data): locked and centred
  while the gripper holds a part (the cell locks before it moves the part), free while it is empty, when the tool's
  weight across its axis moves it by m g_perp / k. Tools of 1-3 / 3-8 kg, 0.2-0.6 mm at a full g across (ur10 /
  kr16_like; assumed); the gripper alternately empty and holding a part from block to block. Unlike set L's preloaded
  holder (always free, a dead zone), this one has no preload and is locked by the logged payload. The true structure:
  one column, amplitude 1 / k.
* plunger stiction: an axial compliance plunger centred by two opposed springs (net rate k) slides in a guide bushing
  with Coulomb friction F_f; at rest it holds wherever the spring force, the weight along the tool axis (tool and part)
  and friction balance, within F_f / k of the frictionless place, and moves only when the load passes that band: a play
  operator of (m g_axial) / k of half-width F_f / k (Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989;
  Prandtl's elastic-plastic element), taken from pose to pose. Tools of 1-3 / 2-6 kg, 0.2-0.5 mm at a full g along the
  axis, friction 25-40 % of the tool's weight (so that the moves' accelerations, below 0.25 g, do not shift it), the
  start anywhere in the band (ur10 / kr16_like; assumed). Unlike set S's diaphragm flexure (frictionless, hardening),
  this one is linear with memory. The true structure: one column, amplitude 1 / k.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_body import _gravity_tool

Z = np.array([0.0, 0.0, 1.0])
COLUMN_I_M4 = np.array([1.126e-4, 1.492e-4, 1.924e-4, 2.517e-4])  # HE 240 B, 260 B, 280 B, 300 B (EN 10365)
STEEL_E_PA = 210e9


def _zero(ctx):
    return np.zeros((len(ctx.q), 3))


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# ----------------------------------------------------------------------------------------------- crane runway
CRANE = {"ur10": ((2000.0, 5000.0), (3000.0, 8000.0)), "kr16_like": ((3000.0, 8000.0), (3000.0, 10000.0))}


def crane_schedule(p, t):
    """(P,) the corbel's wheel load R [N] at times ``t`` [s] (the crane's state of the last event before each)."""
    k = np.searchsorted(p["t_event"], np.asarray(t, float), side="right") - 1
    return p["R_event"][np.clip(k, 0, len(p["R_event"]) - 1)]


def crane_draw(ctx, hw, rng):
    if ctx.chain.name not in CRANE:
        return {}
    (b_lo, b_hi), (c_lo, c_hi) = CRANE[ctx.chain.name]
    az = rng.uniform(0, 2 * np.pi)
    H = rng.uniform(7.0, 9.0)
    p = {"e_c": np.array([np.cos(az), np.sin(az), 0.0]), "l_b": rng.uniform(300.0, 600.0),
         "I": float(rng.choice(COLUMN_I_M4)), "H": H, "a": H - rng.uniform(0.8, 2.0), "z_b": rng.uniform(1.5, 3.0),
         "e": rng.uniform(0.25, 0.5)}
    W_b, W_t, cap = rng.uniform(b_lo, b_hi), rng.uniform(300.0, 1000.0), rng.uniform(c_lo, c_hi)
    S, s_w, L_s = rng.uniform(12.0, 20.0), rng.uniform(2.0, 3.0), rng.uniform(5.0, 7.0)
    t0, t1 = ctx.session.time_s[0] - 600.0, ctx.session.time_s[-1] + 60.0
    gaps = rng.uniform(60.0, 300.0, int((t1 - t0) / 60.0) + 2)
    te = t0 + np.r_[0.0, np.cumsum(gaps)]
    te = te[te < t1]
    x = rng.uniform(-15.0, 15.0, len(te))                               # the bridge's place along the runway [m]
    y = rng.uniform(0.0, 1.0, len(te))                                  # the trolley's place across, 0 at our side
    hook = np.where(rng.random(len(te)) < 0.5, rng.uniform(0.3, 1.0, len(te)) * cap, 0.0)
    wheel = kin.G * (W_b / 4 + (W_t + hook) * (1 - y) / 2)          # [N]
    eta = sum(np.clip(1 - np.abs(x + s) / L_s, 0.0, None) for s in (-s_w / 2, s_w / 2))
    p.update(t_event=te, R_event=wheel * eta)
    return p


def crane_shape(p, ctx):
    """(P, 3): the target's displacement [mm] per unit e / EI [1 / (N m)]: the column's slope and deflection at the
    bracket under the couple R e (propped cantilever), carried to the arm as a rigid motion about the column's axis."""
    H, a, z = p["H"], p["a"], p["z_b"]
    pp = -3 * a * (H - a / 2) / H ** 3                                  # prop force per unit couple [1/m]
    theta = z * (1 + pp * (2 * H - z) / 2)                              # slope per unit M0 / EI [rad m]
    v = z ** 2 * (0.5 + pp * (3 * H - z) / 6) * 1000.0                 # deflection per unit M0 / EI [mm m]
    R = crane_schedule(p, ctx.session.time_s)[:, None]
    n = np.cross(Z, p["e_c"])
    col = -p["l_b"] * p["e_c"]
    return R * (v * p["e_c"] + theta * np.cross(n, ctx.target - col))


def crane_apply(p, ctx, hw):
    return Contribution(displace=p["e"] / (STEEL_E_PA * p["I"]) * crane_shape(p, ctx) if p else _zero(ctx))


def crane_features(p, ctx, hw):
    return crane_shape(p, ctx)[None] if p else _empty(ctx)


# ---------------------------------------------------------------------------------------------- shield squeeze
SHIELD_ARMS = {"tool_changer", "kr16_like"}


def squeeze_draw(ctx, hw, rng):
    if ctx.chain.name not in SHIELD_ARMS:
        return {}
    g = np.deg2rad(rng.uniform(-10.0, 10.0))
    return {"axis": np.array([np.sin(g), np.cos(g), 0.0]), "R_mm": rng.uniform(2500.0, 4500.0),
            "phi_m": np.deg2rad(rng.uniform(60.0, 120.0) + rng.choice([0.0, 180.0])), "phi_p": rng.uniform(0, np.pi),
            "delta_inf": rng.uniform(2.0, 6.0), "T_s": rng.uniform(2.0, 10.0) * 3600, "n": rng.uniform(0.2, 0.4),
            "t_start": rng.uniform(0.5, 4.0) * 3600}


def squeeze_signal(p, session):
    """(P,): the ovalisation's growth since the session's first pose per unit delta_inf."""
    t = p["t_start"] + session.time_s - session.time_s[0]
    law = lambda tt: 1 - (p["T_s"] / (p["T_s"] + tt)) ** p["n"]  # noqa: E731
    return law(t) - law(p["t_start"])


def squeeze_shape(p, ctx):
    """(P, 3): the target's displacement [mm] per unit delta_inf [mm]: the console's translation with the skin and its
    turn about the tunnel's axis."""
    a = p["axis"]
    h = np.cross(a, Z)
    r_hat = np.cos(p["phi_m"]) * Z + np.sin(p["phi_m"]) * h            # from the shield's centre to the console
    t_hat = -np.sin(p["phi_m"]) * Z + np.cos(p["phi_m"]) * h
    psi = 2 * (p["phi_m"] - p["phi_p"])
    u = np.cos(psi) * r_hat - 0.5 * np.sin(psi) * t_hat                 # per unit delta [mm/mm]
    chi = 1.5 * np.sin(psi) / p["R_mm"]                                 # turn per unit delta [rad/mm]
    s = squeeze_signal(p, ctx.session)[:, None]
    return s * (u + chi * np.cross(a, ctx.target))


def squeeze_apply(p, ctx, hw):
    return Contribution(displace=p["delta_inf"] * squeeze_shape(p, ctx) if p else _zero(ctx))


def squeeze_features(p, ctx, hw):
    return squeeze_shape(p, ctx)[None] if p else _empty(ctx)


# ---------------------------------------------------------------------------------------------- lockable float
FLOAT_KG = {"ur10": (1.0, 3.0), "kr16_like": (3.0, 8.0)}


def float_draw(ctx, hw, rng):
    if ctx.chain.name not in FLOAT_KG:
        return {}
    m = rng.uniform(*FLOAT_KG[ctx.chain.name])
    return {"m_kg": m, "k_N_mm": m * kin.G / rng.uniform(0.2, 0.6)}


def float_shape(p, ctx):
    """(P, 3): the tool's float [mm per mm/N] while the gripper is empty (unlocked), none while it holds a part."""
    Rt, g_t = _gravity_tool(ctx)
    free = (ctx.session.payload_kg <= 0.0)[:, None]
    F = p["m_kg"] * g_t * np.array([1.0, 1.0, 0.0])
    return free * np.einsum("pij,pj->pi", Rt, F)


def float_apply(p, ctx, hw):
    return Contribution(displace=float_shape(p, ctx) / p["k_N_mm"] if p else _zero(ctx))


def float_features(p, ctx, hw):
    return float_shape(p, ctx)[None] if p else _empty(ctx)


# ---------------------------------------------------------------------------------------------- plunger stiction
PLUNGER_KG = {"ur10": (1.0, 3.0), "kr16_like": (2.0, 6.0)}


def plunger_draw(ctx, hw, rng):
    if ctx.chain.name not in PLUNGER_KG:
        return {}
    m = rng.uniform(*PLUNGER_KG[ctx.chain.name])
    return {"m_kg": m, "k_N_mm": m * kin.G / rng.uniform(0.2, 0.5), "F_f": rng.uniform(0.25, 0.4) * m * kin.G,
            "u0": rng.uniform(-1.0, 1.0)}


def plunger_state(p, ctx):
    """(P,): the plunger's place [N per unit rate, i.e. mm per mm/N]: a play operator of the axial weight."""
    _, g_t = _gravity_tool(ctx)
    x_eq = (p["m_kg"] + ctx.session.payload_kg) * g_t[:, 2]
    w = p["F_f"]
    x = np.empty(len(x_eq))
    prev = x_eq[0] + p["u0"] * w
    for i, e in enumerate(x_eq):
        prev = min(max(prev, e - w), e + w)
        x[i] = prev
    return x


def plunger_shape(p, ctx):
    Rt, _ = _gravity_tool(ctx)
    return plunger_state(p, ctx)[:, None] * Rt[:, :, 2]


def plunger_apply(p, ctx, hw):
    return Contribution(displace=plunger_shape(p, ctx) / p["k_N_mm"] if p else _zero(ctx))


def plunger_features(p, ctx, hw):
    return plunger_shape(p, ctx)[None] if p else _empty(ctx)
