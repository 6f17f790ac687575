"""Set X body effects (new physics, not in sets A-W): the arm's base plate slipped on its friction-grip bolted joint by
a collision in the production between two blocks; the arm's stand on three levelling feet, one of whose screws turns
loose in the vibration of the production, lowering its corner; a part held by 3D-printed polymer fingers that creep
under its weight from the moment it is gripped; and a part held on a suction cup that tilts under the part's weight
moment. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* collision shift: a base plate held to its pedestal by preloaded bolts carries shear by friction up to mu F_p
  (slip-critical joints: VDI 2230 Part 1, 2015; EN 1993-1-8 slip resistance); a collision's impulse beats it and the
  plate slides to a new place and turns about its bolt pattern within the holes' clearance (1-2 mm holes for M16-M20
  bolts, as recalled), by 0.05-0.25 mm and 0.004-0.015 deg, at a gap with blocks before and after (assumed). The
  collision is not logged. The true structure: three columns (the two slides and the turn about the base axis, from
  the collision's block on), amplitudes the slides [mm] and the turn [rad].
* levelling foot: a stand on three levelling feet (a screw in a threaded bush, held by a lock nut) is statically
  determinate; a foot whose lock nut was left loose turns in the transverse slips that each move's reaction causes at
  its pad and unscrews under its load (self-loosening of threaded fasteners under transverse vibration: Junker, "New
  criteria for self-loosening of fasteners under vibration", SAE Trans. 78, 1969; VDI 2230 Part 1), so its corner sinks
  at a rate d = s E (E the production time so far, the exercise gaps) and the stand turns by d / l about the line
  through the other two feet (l the foot's distance from it). Feet 300-500 mm from the base's axis, 200-600 mm below it;
  0.04-0.12 mm per hour of production (6-17 degrees of an M20 screw's 2.5-mm pitch an hour, assumed). Not logged. The
  true structure: one column (the turn per mm of drop times E), amplitude s [mm/h].
* printed fingers: gripper fingers printed in PLA or PETG (E 2-3 GPa) are cantilevers of length L = 80 mm that bend by
  W_perp L^3 / (3 E I) shared between the two (Roark, *Formulas for Stress and Strain*, cantilever with an end load),
  their section sized so that the heaviest part of the session sags them by 0.15-0.4 mm (a stiffness-driven design), and
  creep under the constant load by Findley's power law, eps(t) = eps0 (1 + r (t / 1 h)^n) (Findley, Lai & Onaran,
  *Creep and Relaxation of Nonlinear Viscoelastic Materials*, 1976; n 0.2-0.35, r 0.2-0.5 for printed thermoplastics
  at room temperature, as recalled) from the moment the part is gripped; a new part is gripped for each block (the
  payload column logs it) about a minute before its first pose. W_perp is the part's weight across the fingers (the
  tool's z). The target sits on the part at the fingertips. The true structure: two columns (W_perp and W_perp times
  (t / 1 h)^n), amplitudes the elastic and the creep compliance [mm/N].
* suction cup: a part held on a suction cup (a flat or bellows cup, or a few of them on one plate) tilts on the cup's
  elastomer lip under its weight's moment about the cup, theta = M_perp / k_t (cup makers' data on the lateral and
  angular compliance of cups, e.g. Schmalz / Piab catalogues, as recalled); the part's centre of mass lies 40-150 mm
  off the cup's axis and 10-40 mm below its face, which is 60 mm along the tool's z. k_t 100-300 / 300-800 /
  800-2500 N m/rad on ur10 / kr16_like / tool_changer. The part's mass is the payload column (logged). The target
  sits on the part. The true structure: one column (the target's displacement per unit angular compliance), amplitude
  1 / k_t [rad/(N m)].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import machining_s


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ------------------------------------------------------------------------------------------------ collision shift
def collision_step(p, session):
    """(P,) 1 from the block after the collision on."""
    return (block_index(session) >= p["block"]).astype(float)


def collision_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    block = 2 + int(rng.integers(max(nb - 3, 1)))
    ang = rng.uniform(0, 2 * np.pi)
    s = rng.uniform(0.05, 0.25)
    yaw = np.deg2rad(rng.uniform(0.004, 0.015)) * rng.choice([-1.0, 1.0])
    return {"block": block, "amp": np.array([s * np.cos(ang), s * np.sin(ang), yaw])}


def collision_features(p, ctx, hw):
    st = collision_step(p, ctx.session)[:, None]
    ez = np.array([0.0, 0.0, 1.0])
    return np.array([st * np.array([1.0, 0, 0]), st * np.array([0, 1.0, 0]), st * np.cross(ez, ctx.target)])


def collision_apply(p, ctx, hw):
    return _amp_apply(p["amp"], collision_features(p, ctx, hw))


# ----------------------------------------------------------------------------------------------- levelling foot
def foot_geometry(p):
    """The stand's feet (3, 3) [mm] and the tilt's axis: unit vector e along the line through feet 1 and 2 (oriented
    so that a positive turn lowers foot 0), a point on it, and foot 0's distance from it [mm]."""
    ang = p["psi"] + 2 * np.pi * np.arange(3) / 3
    f = np.stack([p["r_mm"] * np.cos(ang), p["r_mm"] * np.sin(ang), np.full(3, -p["h_mm"])], axis=1)
    e = (f[2] - f[1]) / np.linalg.norm(f[2] - f[1])
    if np.cross(e, f[0] - f[1])[2] > 0:
        e = -e
    d = np.linalg.norm(np.cross(e, f[0] - f[1]))
    return f, e, f[1], d


def foot_drop_h(session):
    """(P,) the production time so far [h] (the exercise gaps: the vibration that turns the foot's screw)."""
    return machining_s(session) / 3600.0


def foot_draw(ctx, hw, rng):
    return {"r_mm": rng.uniform(300.0, 500.0), "h_mm": rng.uniform(200.0, 600.0), "psi": rng.uniform(0, 2 * np.pi),
            "rate": rng.uniform(0.04, 0.12)}


def foot_features(p, ctx, hw):
    _, e, pt, d = foot_geometry(p)
    return (np.cross(e, ctx.target - pt) / d * foot_drop_h(ctx.session)[:, None])[None]


def foot_apply(p, ctx, hw):
    return _amp_apply([p["rate"]], foot_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------- printed fingers
FINGER_MM = 80.0


def grip_age_h(session):
    """(P,) the time [h] since the block's part was gripped (a minute before the block's first move)."""
    b = block_index(session)
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    t0 = session.time_s[first] - session.dwell_s[first] - session.move_s[first] - 60.0
    return (session.time_s - t0[b]) / 3600.0


def finger_weight(ctx):
    """(P, 3) the part's weight across the fingers [N]."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    z = Rt[:, :, 2]
    W = np.zeros((len(ctx.q), 3))
    W[:, 2] = -kin.G * ctx.session.payload_kg
    return W - np.einsum("pi,pi->p", W, z)[:, None] * z


def finger_draw(ctx, hw, rng):
    E = rng.uniform(2.0e9, 3.0e9)
    sag = rng.uniform(0.15, 0.4)                                     # design sag under the heaviest part [mm]
    c_el = sag / (kin.G * max(ctx.session.payload_kg.max(), 0.1))    # two fingers [mm/N]
    I = (FINGER_MM / 1000.0) ** 3 / (3 * E * 2 * c_el / 1000.0)       # each finger's section [m^4]
    n, r = rng.uniform(0.2, 0.35), rng.uniform(0.2, 0.5)
    return {"E": E, "I": I, "sag_mm": sag, "n": n, "r": r, "amp": np.array([c_el, c_el * r])}


def finger_features(p, ctx, hw):
    W = finger_weight(ctx)
    return np.array([W, W * (grip_age_h(ctx.session) ** p["n"])[:, None]])


def finger_apply(p, ctx, hw):
    return _amp_apply(p["amp"], finger_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------- suction cup
CUP_MM = 60.0
CUP_K = {"ur10": (100.0, 300.0), "kr16_like": (300.0, 800.0), "tool_changer": (800.0, 2500.0)}  # [N m/rad]


def cup_moment(p, ctx):
    """(P, 3) the part's weight moment about the cup's centre across the cup's axis [N m]; the cup's centre (P, 3)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    centre = kin.target(ctx.chain, ctx.q, np.array([0.0, 0.0, CUP_MM]))
    r = np.einsum("pij,j->pi", Rt, p["com_mm"]) / 1000.0
    W = np.zeros_like(r)
    W[:, 2] = -kin.G * ctx.session.payload_kg
    M = np.cross(r, W)
    z = Rt[:, :, 2]
    return M - np.einsum("pi,pi->p", M, z)[:, None] * z, centre


def cup_draw(ctx, hw, rng):
    a, rho = rng.uniform(0, 2 * np.pi), rng.uniform(40.0, 150.0)
    return {"com_mm": np.array([rho * np.cos(a), rho * np.sin(a), rng.uniform(10.0, 40.0)]),
            "c": 1.0 / rng.uniform(*CUP_K[ctx.chain.name])}


def cup_features(p, ctx, hw):
    M, centre = cup_moment(p, ctx)
    return np.cross(M, ctx.target - centre)[None]


def cup_apply(p, ctx, hw):
    return _amp_apply([p["c"]], cup_features(p, ctx, hw))
