"""Set ZD body effects (new physics, not in sets A-ZC): the arm on three air mounts whose levelling valves re-level
each mount only once it leaves their dead band; the arm on a scissor lift table, heaved by its cylinder's oil column
under the load and its position; a tool boom whose root bond is still curing, stiffening through the session; and a
forearm bent by the wrist's drive tendons, which run off its neutral axis with tensions that follow the wrist's loads.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* levelling valves: air mounts (air springs) with mechanical height-control (levelling) valves hold the plate at its
  set height within the valve's dead band +-delta (0.1-0.5 mm): a load change first sinks or lifts a mount by dF / k,
  then the valve refills or vents it back to the band's edge within seconds (Rivin, *Passive Vibration Isolation*, 2003,
  ch. 4; pneumatic isolators with levelling valves, makers' data, as recalled). Each mount's height error is therefore
  a play operator of its load: e_i <- clip(e_i - dF_i / k, -delta, delta), from the first pose (the plate levelled).
  Three mounts at 120 deg on a circle (radius 1.8-2.5 times the largest moment over the weight, so none unloads); the
  plate follows their heights (heave and tilt). Sized so that the target's largest move is 0.2-0.5 mm. Unlike set G's
  air isolators or the mounts of sets A-ZC (elastic, creeping, clearance), the support's error is a valve's dead band,
  a memory of the loads' last changes. Driven by the pose sequence (logged). The true structure: one column (the
  mounts' play at unit band), amplitude delta [mm].
* scissor lift: the arm stands on a scissor lift table at working height; its cylinder carries the load with a
  mechanical advantage that changes with where the load stands along the table, F_c = a W + b M_t (the scissor's
  statics; lift-table makers' load diagrams, EN 1570-1, as recalled), and its oil column and hoses yield by F_c / k_oil
  (Merritt, *Hydraulic Control Systems*, 1967, the oil's bulk modulus); the platform and the arms' pins tilt the deck a
  little under the moment. The part's mass (logged) changes each block. Heave 75-90 % of the move (first 60-80 %:
  ZD21's link model at 1.18x -- a deck of welded box sections tilts little), sized so that the
  target moves 0.4-0.8 mm about its mean (the table at full height, its long hoses; first 0.3-0.6 mm: ZD21 at 1.24x). Unlike the tilting supports of sets A-ZC, the deck rises and sinks with the
  load and its position along the table. Driven by the pose and the payload (logged). The true structure: four columns
  (heave per weight, heave per moment along the table, tilt about the table's two axes), amplitudes [mm/N, mm/(N m),
  1/(N m), 1/(N m)].
* curing bond: a light tool boom (400 mm along the tool's x, the target at its tip, a 1-3 kg head there) bonded into its
  root fitting 10-30 min before the session with a room-temperature epoxy that is still curing: the adhesive's shear
  modulus rises with the conversion (Kamal & Sourour, Polym. Eng. Sci. 13, 1973; the modulus build-up after gelation),
  so the bonded joint's rotational compliance falls, c(t) = c_inf + (c_0 - c_inf) exp(-t_age / tau), tau 20-60 min,
  c_0 / c_inf 2-4; the boom turns at its root by c(t) M (the weight moment across the boom). Sized so that the tip moves
  0.2-0.5 mm at first. Unlike set H's bond creep (a compliance growing under the load), the joint stiffens as its
  adhesive cures, whatever the load. Driven by the pose and the time (logged) and the bond's age (not logged). The true
  structure: two columns (the hinge's turn per unit compliance and times exp(-t_age / tau)), amplitudes c_inf and c_0 -
  c_inf.
* drive tendons: a wrist driven through steel tendons (cable-driven wrists: Townsend & Salisbury, the WAM's cable
  drives, 1993; tendon-driven manipulators, Tsai, *Robot Analysis*, ch. 10) runs the axis-5 tendon pair along the
  forearm at e = 30-60 mm off its neutral axis; the loaded tendon's tension tau_5 / r_p (over the pretension, which the
  geometry absorbs) compresses the tube eccentrically, a moment T e along the forearm that bends it by T e L^2 / 2EI at
  its end and turns the wrist by T e L / EI (Roark, table 8.1, end moment). Sized so that the target moves 0.15-0.4 mm.
  Unlike set Z's bowstring (a strap's constant pull) or the tendon-free gear compliances, the bend follows the wrist's
  torque. Driven by the pose and the payload (logged). The true structure: one column, amplitude e / (r_p EI).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import GRAVITY_N, mount_moment
from sim2real_indep.effects_y_thermal import lamp_side, link_bow
from sim2real_indep.effects_za_thermal import forearm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _weight_N(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * np.linalg.norm(GRAVITY_N)


# ----------------------------------------------------------------------------------------------- levelling valves
def mount_loads(p, ctx):
    """(P, 3) the three mounts' loads [N] (statically determinate: weight and moment about the base)."""
    a = p["psi"] + np.deg2rad([0.0, 120.0, 240.0])
    x, y = p["r_m"] * np.cos(a), p["r_m"] * np.sin(a)
    A = np.array([np.ones(3), y, -x])
    M = mount_moment(ctx)
    b = np.c_[_weight_N(ctx), -M[:, 0], -M[:, 1]]
    return np.linalg.solve(A, b.T).T


def plate_motion(p, ctx, z):
    """(P, 3) the target's displacement [mm] for the mounts' height changes z (P, 3) [mm]: the plate through them."""
    a = p["psi"] + np.deg2rad([0.0, 120.0, 240.0])
    X = np.c_[np.ones(3), 1000.0 * p["r_m"] * np.cos(a), 1000.0 * p["r_m"] * np.sin(a)]
    c = np.linalg.solve(X, z.T).T                                     # z = c0 + c1 x + c2 y
    rot = np.c_[c[:, 2], -c[:, 1], np.zeros(len(c))]
    return c[:, :1] * [0.0, 0.0, 1.0] + np.cross(rot, ctx.target)


def valve_play(p, ctx):
    """(P, 3) the mounts' height errors at unit band: the play operator of their loads' changes."""
    F = mount_loads(p, ctx) * p["s"]
    e = np.zeros_like(F)
    for i in range(1, len(F)):
        e[i] = np.clip(e[i - 1] - (F[i] - F[i - 1]), -1.0, 1.0)
    return e


def valves_draw(ctx, hw, rng):
    W = _weight_N(ctx).min()
    Mmax = np.linalg.norm(mount_moment(ctx)[:, :2], axis=1).max()
    p = {"psi": rng.uniform(0, 2 * np.pi), "r_m": rng.uniform(1.8, 2.5) * Mmax / W}
    dF = np.abs(np.diff(mount_loads(p, ctx), axis=0)).max()
    p["s"] = rng.uniform(2.0, 6.0) / max(dF, 1e-12)                  # 1 / (k delta): the largest change, in bands
    unit = plate_motion(p, ctx, valve_play(p, ctx))
    p["delta"] = rng.uniform(0.2, 0.5) / max(np.linalg.norm(unit, axis=1).max(), 1e-12)
    return p


def valves_features(p, ctx, hw):
    return plate_motion(p, ctx, valve_play(p, ctx))[None]


def valves_apply(p, ctx, hw):
    return _amp_apply([p["delta"]], valves_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- scissor lift
def scissor_parts(p, ctx):
    """(4, P, 3) the target's displacement per unit: heave per N of weight, heave per N m of moment along the table,
    tilt about the table's long and cross axes per N m."""
    el = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    et = np.array([-np.sin(p["psi"]), np.cos(p["psi"]), 0.0])
    M = mount_moment(ctx)
    up = np.array([0.0, 0.0, -1.0])
    return np.array([np.outer(_weight_N(ctx), up), np.outer(M @ et, up),
                     np.cross(np.outer(M @ el, el), ctx.target), np.cross(np.outer(M @ et, et), ctx.target)])


def scissor_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi)}
    parts = scissor_parts(p, ctx)
    heave = rng.uniform(0.75, 0.9)
    share = np.array([heave * rng.uniform(0.5, 0.7), 0.0, 0.0, 0.0])
    share[1] = heave - share[0]
    share[2:] = (1 - heave) * np.array([0.5, 0.5])
    size = [max(np.linalg.norm(f - f.mean(axis=0), axis=1).max(), 1e-12) for f in parts]
    tot = rng.uniform(0.4, 0.8)
    p["amp"] = tot * share / np.array(size) * np.r_[1.0, rng.choice([-1.0, 1.0]), 1.0, 1.0]
    return p


def scissor_features(p, ctx, hw):
    return scissor_parts(p, ctx)


def scissor_apply(p, ctx, hw):
    return _amp_apply(p["amp"], scissor_parts(p, ctx))


# --------------------------------------------------------------------------------------------------- curing bond
BOND_BOOM_MM = 400.0


def bond_turn(ctx, head_kg):
    """(P, 3) the boom tip's displacement per unit rotational compliance [mm per rad/(N mm)]: the root turned by the
    weight moment across the boom (the head at the tip, the boom's 0.4 kg at mid-length)."""
    p_f, Rt = kin.flange(ctx.chain, ctx.q)
    along = Rt[:, :, 0]
    M = np.cross(along * BOND_BOOM_MM, GRAVITY_N * head_kg) + np.cross(along * BOND_BOOM_MM / 2, GRAVITY_N * 0.4)
    M -= np.einsum("pi,pi->p", M, along)[:, None] * along           # bending only (the bond is stiff in torsion)
    return np.cross(M, ctx.target - p_f)


def bond_age_factor(p, session):
    return np.exp(-(session.time_s - session.time_s[0] + p["age_s"]) / p["tau_s"])


def bond_draw(ctx, hw, rng):
    p = {"head_kg": rng.uniform(1.0, 3.0), "age_s": 60.0 * rng.uniform(10.0, 30.0),
         "tau_s": 60.0 * rng.uniform(20.0, 60.0), "ratio": rng.uniform(2.0, 4.0)}
    unit = bond_turn(ctx, p["head_kg"])
    c0 = rng.uniform(0.2, 0.5) / max(np.linalg.norm(unit, axis=1).max(), 1e-12)
    f0 = bond_age_factor(p, ctx.session)[0]
    p["c_inf"] = c0 / (1 + (p["ratio"] - 1) * f0)                    # c(first pose) = c0
    p["amp"] = np.array([p["c_inf"], (p["ratio"] - 1) * p["c_inf"]])
    return p


def bond_features(p, ctx, hw):
    unit = bond_turn(ctx, p["head_kg"])
    return np.array([unit, unit * bond_age_factor(p, ctx.session)[:, None]])


def bond_apply(p, ctx, hw):
    return _amp_apply(p["amp"], bond_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- drive tendons
TENDON_JOINT = 4


def tendon_unit(p, ctx):
    """(P, 3) the target's displacement per unit e / (r_p EI): the forearm bent by the moment tau_5 e / r_p, away
    from the tendons' side."""
    li = forearm(ctx.chain)
    bow = link_bow(ctx, li, lamp_side(ctx.chain, li, p["psi"]))       # per unit curvature [1/mm]
    return bow * (ctx.loads[:, TENDON_JOINT] * 1000.0)[:, None]      # curvature = tau [N mm] e / (r_p EI)


def tendon_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi), "e_mm": rng.uniform(30.0, 60.0)}
    unit = tendon_unit(p, ctx)
    p["k"] = rng.uniform(0.15, 0.4) / max(np.linalg.norm(unit, axis=1).max(), 1e-12)
    return p


def tendon_features(p, ctx, hw):
    return tendon_unit(p, ctx)[None]


def tendon_apply(p, ctx, hw):
    return _amp_apply([p["k"]], tendon_features(p, ctx, hw))
