"""Set V body effects (new physics, not in sets A-U): the arm on a mobile carrier that lowers stabiliser jacks in some
blocks and stands on its wheels' suspension in the others; the arm on a carrier levelled on its locked jacks at the
start of each block; a gripper boom whose root flange's bolts, left short of their preload after a tool change, loosen
with each move; and a 3D-printed polyamide gripper boom swelling as it takes up the hall's humidity after leaving its
dry store. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* stabiliser jacks: mobile manipulators stand either on their wheels' suspension or, for accurate work, on jacks
  lowered to the floor (mobile-manipulator practice, e.g. KUKA KMR / omniMove with lifting supports, as recalled). The
  carrier tilts under the arm's gravity moment about a point at floor level, h = 400-900 mm below the arm's base (the
  deck's height), with roll and pitch compliances in the carrier's axes (a platform's support stiffness: statics of a
  rigid deck on springs, as :mod:`effects_body`'s mount). On its suspension k = 0.5-1.5e6 / 4-12e6 / 1-3e7 N m/rad
  (ur10 / kr16_like / tool_changer), on its jacks 5-15 times stiffer (assumed). The jacks are down in every other
  block of 4-8 (the carrier docked at the cell in some blocks, standing by on its wheels in the others;
  :func:`effects_v.session_options`); which blocks is not logged. The true structure: four columns (roll and pitch,
  on wheels and on jacks), amplitudes the compliances.
* self-levelling: mobile platforms on hydraulic outriggers / jacks level themselves from an inclinometer when they are
  set up and then hold the jacks' oil locked (automatic levelling of truck-mounted cranes and mobile work platforms,
  e.g. EN 280 / EN 13000 levelling requirements, as recalled); the arm was set down and levelled at the start of each
  block, so within a block the carrier tilts by the change of the arm's gravity moment since that block's first pose,
  about a point at floor level h = 400-900 mm below the base, with the locked jacks' roll and pitch compliances (oil
  columns and the carrier's frame: 0.5-1.5e6 / 4-12e6 / 1-3e7 N m/rad on ur10 / kr16_like / tool_changer, assumed).
  4-8 blocks with pauses of 5-20 min (:func:`effects_v.session_options`); the levelling is not logged. The true
  structure: two columns (roll and pitch), amplitudes the compliances.
* bolt loosening: a bolted joint whose preload is too low to stop micro-slip under transverse cyclic loads loses
  preload with the cycles, fast at first and then about logarithmically (Junker, "New criteria for self-loosening of
  fasteners under vibration", SAE 690055, 1969; VDI 2230 part 1, 2015, on self-loosening), so the joint's bending
  compliance grows: c(n) = c0 (1 + gamma ln(1 + n / n0)) (a law of Junker's form, assumed; gamma 0.2-0.5, n0 5-30
  moves: each move's accelerations are two slip cycles). The boom (400 mm along the tool's x, its target at the tip,
  :func:`effects_v.probe_hook`) turns at its root by c M with M = (m_tip + m_boom / 2) L g_perp, g_perp the gravity's
  part across the boom. Root stiffness 1-3e4 / 3-8e4 / 1-3e5 N m/rad (ur10's small ISO 9409-1-50-4-M6 flange: four M6
  bolts on a 50 mm circle), tip masses 0.5-2 / 1-4 / 3-10 kg, booms 1-2 /
  1.5-3 / 3-6 kg (assumed). The bolts were tightened by hand after a tool change at the session's start; the move count
  is the pose's index (not logged as such). The true structure: two columns (the sag and its growth), amplitudes c0 and
  c0 gamma.
* moisture swelling: polyamide 12 takes up water from the air by Fickian diffusion; at early times the uptake of a wall
  of thickness h exposed on both faces is M(t) / M_inf = (4 / h) sqrt(D t / pi) (Crank, *The Mathematics of
  Diffusion*, 2nd ed., 1975, ch. 4; accurate to M / M_inf ~ 0.5), and the part swells by beta M (coefficient of
  hygroscopic swelling). SLS PA12 (EOS PA 2200 data sheet, as recalled: 0.7-1.2 % water in a humid hall), beta 0.2-0.35,
  D 2-5e-12 m^2/s, walls 2-3 mm; a gripper boom of 400 mm along the tool's x carrying the target at its tip, taken out
  of its dry cabinet 0-20 min before the first pose. The humidity and the boom's history are not logged. The true
  structure: one column (the tool's x times L sqrt(t - t0)), amplitude beta M_inf (4 / h) sqrt(D / pi).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index

Z = np.array([0.0, 0.0, 1.0])


def _tool(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# --------------------------------------------------------------------------------------------- stabiliser jacks
JACKS_K = {"ur10": (0.5e6, 1.5e6), "kr16_like": (4e6, 12e6), "tool_changer": (1e7, 3e7)}  # on wheels [N m/rad]


def jacks_draw(ctx, hw, rng):
    b = block_index(ctx.session)
    nb = int(b.max()) + 1
    pattern = (np.arange(nb) + rng.integers(2)) % 2 == 1
    k_w = rng.uniform(*JACKS_K[ctx.chain.name], 2)
    k_j = k_w * rng.uniform(5.0, 15.0, 2)
    return {"psi": rng.uniform(0, np.pi), "h_mm": rng.uniform(400.0, 900.0), "pattern": pattern,
            "jacks": pattern[b].astype(float), "c": np.r_[1 / k_w, 1 / k_j]}


def jacks_features(p, ctx, hw):
    M = eb.mount_moment(ctx)
    a = p["psi"]
    axes = [np.array([np.cos(a), np.sin(a), 0.0]), np.array([-np.sin(a), np.cos(a), 0.0])]
    pivot = np.array([0.0, 0.0, -p["h_mm"]])
    out = []
    for on in (1.0 - p["jacks"], p["jacks"]):
        out += [np.cross(ax[None] * ((M @ ax) * on)[:, None], ctx.target - pivot) for ax in axes]
    return np.array(out)


def jacks_apply(p, ctx, hw):
    return _amp_apply(p["c"], jacks_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------- self-levelling
LEVEL_K = {"ur10": (0.5e6, 1.5e6), "kr16_like": (4e6, 12e6), "tool_changer": (1e7, 3e7)}  # [N m/rad]


def level_moment(p, ctx):
    """(P, 3) the gravity moment about the base [N m] minus its value at the block's first pose (the carrier
    levelled then)."""
    M = eb.mount_moment(ctx)
    b = block_index(ctx.session)
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    return M - M[first][b]


def level_draw(ctx, hw, rng):
    return {"psi": rng.uniform(0, np.pi), "h_mm": rng.uniform(400.0, 900.0),
            "c": 1 / rng.uniform(*LEVEL_K[ctx.chain.name], 2)}


def level_features(p, ctx, hw):
    M = level_moment(p, ctx)
    a = p["psi"]
    axes = [np.array([np.cos(a), np.sin(a), 0.0]), np.array([-np.sin(a), np.cos(a), 0.0])]
    pivot = np.array([0.0, 0.0, -p["h_mm"]])
    return np.array([np.cross(ax[None] * (M @ ax)[:, None], ctx.target - pivot) for ax in axes])


def level_apply(p, ctx, hw):
    return _amp_apply(p["c"], level_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------- bolt loosening
BOLT_BOOM_MM = 400.0  # the boom's length along the tool's x (the target's offset, effects_v.probe_hook)
BOLT = {"ur10": ((1e4, 3e4), (0.5, 2.0), (1.0, 2.0)), "kr16_like": ((3e4, 8e4), (1.0, 4.0), (1.5, 3.0)),
        "tool_changer": ((1e5, 3e5), (3.0, 10.0), (3.0, 6.0))}  # root stiffness [N m/rad], tip and boom mass [kg]


def bolt_count(p, session):
    """(P,) ln(1 + n / n0), n the moves since the bolts were tightened (the pose's index)."""
    return np.log1p(np.arange(len(session.q)) / p["n0"])


def bolt_sag(p, ctx):
    """(P, 3) the boom tip's displacement [mm] per unit root compliance [rad/(N m)]: M L along g_perp."""
    Rt = _tool(ctx)
    g_t = np.einsum("pji,j->pi", Rt, -kin.G * Z)
    g_t[:, 0] = 0.0                                                    # the part across the boom
    L = BOLT_BOOM_MM / 1000.0
    return 1000.0 * (p["m_tip"] + p["m_boom"] / 2) * L ** 2 * np.einsum("pij,pj->pi", Rt, g_t)


def bolt_draw(ctx, hw, rng):
    k, mt, mb = BOLT[ctx.chain.name]
    c0, g = 1 / rng.uniform(*k), rng.uniform(0.2, 0.5)
    return {"c0": c0, "gamma": g, "n0": rng.uniform(5.0, 30.0), "m_tip": rng.uniform(*mt), "m_boom": rng.uniform(*mb)}


def bolt_features(p, ctx, hw):
    S = bolt_sag(p, ctx)
    return np.array([S, S * bolt_count(p, ctx.session)[:, None]])


def bolt_apply(p, ctx, hw):
    return _amp_apply([p["c0"], p["c0"] * p["gamma"]], bolt_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------- moisture swelling
MOIST_BOOM_MM = 400.0  # the boom's length along the tool's x (the target's offset, effects_v.probe_hook)


def moist_root(p, session):
    """(P,) sqrt(t - t0) [sqrt(s)], t0 the boom's leaving its dry cabinet."""
    return np.sqrt(session.time_s - session.time_s[0] + p["t_out_s"])


def moist_draw(ctx, hw, rng):
    beta, M_inf = rng.uniform(0.2, 0.35), rng.uniform(0.007, 0.012)
    D, h = rng.uniform(2e-12, 5e-12), rng.uniform(2e-3, 3e-3)
    return {"beta": beta, "M_inf": M_inf, "D": D, "h_m": h, "t_out_s": rng.uniform(0.0, 1200.0),
            "a": beta * M_inf * 4 / h * np.sqrt(D / np.pi)}


def moist_features(p, ctx, hw):
    return (_tool(ctx)[:, :, 0] * (MOIST_BOOM_MM * moist_root(p, ctx.session))[:, None])[None]


def moist_apply(p, ctx, hw):
    return _amp_apply([p["a"]], moist_features(p, ctx, hw))
