"""Set X joint effects (new physics, not in sets A-W): the gears twisted by the pull of a destacker's permanent-magnet
sheet fanner on the steel blank in the gripper; the gears unloaded by a spring-balanced tool-support arm whose lift
changes with the height of the flange; the rack-and-pinion lash of the linear track (a seventh axis) that carries the
arm, left on the side from which the carriage last came back to the measuring station; a freshly replaced gear set
whose lost motion opens as its flanks run in during the production between the blocks; axis 1's ring scale distorted
into three lobes by its three clamping screws; and tool_changer's telescopic stage read by a length sensor mounted at
an angle to the stage's axis (a cosine error). Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* magnetic fanner: sheet fanners (permanent-magnet blocks beside a stack of steel blanks) magnetise the blanks so that
  the top ones repel each other (fanner makers' catalogues, as recalled: pulls of tens to hundreds of N on a blank near
  the face). Far from a long bar magnet's pole face its field is that of a point pole (Gilbert's model: B = mu0 q / (4
  pi r^2); Furlani, *Permanent Magnet and Electromechanical Devices*, Academic Press, 2001, ch. 3); a blank magnetised
  to saturation carries a fixed moment m along B and feels F = m dB/dr, towards the pole and falling as 1 / r^3. The
  pole face's finite size (radius a 100-200 mm: a fanner's block is about as tall as the stack) softens the law near it:
  F = F_ref (r_ref^2 + a^2)^(3/2) / (r^2 + a^2)^(3/2), r_ref = 300 mm (assumed). The pole stands in the working volume's
  footprint (at 0.8-1.1 times the targets' median distance from the base axis, any heading) below its lower tenth of
  heights (the stack's top); F_ref 15-40 / 40-120 / 150-400 N on ur10 / kr16_like / tool_changer (the blank a few kg,
  assumed). The pull acts at the target (the blank carries it) and twists the gears by tau = J^T F (Craig, *Introduction
  to Robotics*, ch. 5) through the linear gear compliance of :mod:`hardware`. Not logged. The true structure: one column
  (the twist under the unit law), amplitude F_ref [N].
* support arm: a spring-balanced articulated support arm (a parallelogram arm with a gas or coil spring, as the
  zero-gravity tool arms that carry heavy hand tools) holds the tool at the flange with a vertical lift that is set
  to the tool's weight at its mid height z0 and changes linearly with the height, F = F0 + k (z - z0) (a spring
  balance's lift drifts with the stroke: a few per cent per 100 mm, assumed from balancer data); the parallelogram
  keeps the force vertical. F0 20-60 / 40-120 / 150-400 N, k 20-60 / 40-120 / 150-400 N/m. Not logged. Unlike a
  balancer on a rope (sets F, W) the force has no horizontal part and does not point at an anchor. The true structure:
  two columns (the twist under a unit lift and under a unit lift per metre of height), amplitudes F0 and k.
* track lash: a robot on a linear track (a seventh axis) is driven by a pinion on a rack; the carriage stops on the
  flank of its last approach (the load trails the pinion), shifted by half the backlash c along the rail from the
  other flank (rack-and-pinion backlash of 0.1-0.3 mm at the pitch line, e.g. ISO 1328 quality 6-8 racks, as
  recalled; here 0.15-0.5 mm at the carriage with its gearbox's lash). Between the blocks the arm serves stations on
  both sides of the measuring station and comes back from either side; the track is not a column of the data. The
  true structure: one column (the rail's unit vector times the side of each block), amplitude c / 2.
* run-in wear: a replaced gear set on axes 1-3 starts with its lost motion taken up by the assembly's preload and
  opens as its flanks run in: the wear rate is high at first and falls as the asperities flatten (the running-in
  curve: Blau, *Friction and Wear Transitions of Materials*, Noyes, 1989; Archard's law, J. Appl. Phys. 24, 1953),
  b(E) = b_r (1 - exp(-E / tau_w)), E the production time so far (the exercise gaps), tau_w 20-60 min, b_r
  1-3 arcmin (a starved, fast run-in: assumed). The joint rests on the flank its load chooses, or trails its last
  motion when the load is below 10 % of its largest (:func:`physics.backlash_offset`). The true structure: one column
  per axis, amplitudes b_r / 2.
* ring lobing: a thin steel ring scale clamped to its hub by three screws is pulled into three lobes; a thin ring bent
  inextensionally moves its points tangentially by u = -(a / n) sin n theta for a radial lobing a cos n theta
  (Timoshenko, *Strength of Materials*, thin rings; ring-scale installation guides, e.g. Renishaw RESM / HEIDENHAIN ERA,
  advise many clamping points against it, as recalled), so the reading errs by (a / (n R)) sin n (theta - phi), n = 3.
  Axis 1, ring radius 40-80 mm, lobing 10-40 um. The loop servoes the reading, so the joint stands off by minus the
  error. Not logged (the axis' angle is). The true structure: two columns (sin 3q, cos 3q on axis 1).
* cosine error: a length sensor (draw wire or laser) along a line at beta to the travel reads x cos beta (Bryan's
  cosine error: Slocum, *Precision Machine Design*, Prentice Hall, 1992, ch. 2); the loop servoes the reading to the
  command, so the stage stands at q / cos beta, off by kappa q, kappa = 1 / cos beta - 1. beta 1.5-3.5 deg (a bracket
  set by eye). tool_changer's telescopic stage (axis 4) only; inert on arms without a prismatic joint. The true
  structure: one column (axis 4's displacement times q4), amplitude kappa.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import _features_of_dq, _twist, machining_s

ARCMIN = np.pi / (180 * 60)


# --------------------------------------------------------------------------------------------- magnetic fanner
FANNER_N = {"ur10": (15.0, 40.0), "kr16_like": (40.0, 120.0), "tool_changer": (150.0, 400.0)}
FANNER_REF_MM = 300.0


def fanner_law(p, pts):
    """(P, 3) the pull per newton of F_ref at the points ``pts`` (P, 3) [mm]: towards the pole, softened near it."""
    d = p["pole_mm"] - pts
    r = np.linalg.norm(d, axis=1, keepdims=True)
    a2 = p["face_mm"] ** 2
    return d / r * ((FANNER_REF_MM ** 2 + a2) / (r ** 2 + a2)) ** 1.5


def fanner_draw(ctx, hw, rng):
    tgt = ctx.target
    psi = rng.uniform(0, 2 * np.pi)
    rho = np.median(np.linalg.norm(tgt[:, :2], axis=1)) * rng.uniform(0.8, 1.1)
    z = np.percentile(tgt[:, 2], 10) + rng.uniform(-100.0, 0.0)
    return {"pole_mm": np.array([rho * np.cos(psi), rho * np.sin(psi), z]), "face_mm": rng.uniform(100.0, 200.0),
            "F_ref": rng.uniform(*FANNER_N[ctx.chain.name])}


def fanner_twist(p, ctx, hw):
    """(P, n) the twist per newton of F_ref."""
    return _twist(ctx, hw, ctx.target, fanner_law(p, ctx.target))


def fanner_features(p, ctx, hw):
    return _features_of_dq(ctx, fanner_twist(p, ctx, hw))[None]


def fanner_apply(p, ctx, hw):
    return Contribution(dq=p["F_ref"] * fanner_twist(p, ctx, hw))


# ------------------------------------------------------------------------------------------------ support arm
SUPPORT_N = {"ur10": (20.0, 60.0), "kr16_like": (40.0, 120.0), "tool_changer": (150.0, 400.0)}


def support_twists(p, ctx, hw):
    """(2, P, n) the twist per newton of lift F0 and per N/m of the lift's rate k."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    up = np.broadcast_to([0.0, 0.0, 1.0], B.shape)
    t = _twist(ctx, hw, B, up)
    return np.array([t, t * ((B[:, 2] - p["z0_mm"]) / 1000.0)[:, None]])


def support_draw(ctx, hw, rng):
    B, _ = kin.flange(ctx.chain, ctx.q)
    lo, hi = SUPPORT_N[ctx.chain.name]
    return {"z0_mm": float(np.median(B[:, 2])), "F0": rng.uniform(lo, hi), "k": rng.uniform(lo, hi)}


def support_features(p, ctx, hw):
    return np.array([_features_of_dq(ctx, t) for t in support_twists(p, ctx, hw)])


def support_apply(p, ctx, hw):
    t = support_twists(p, ctx, hw)
    return Contribution(dq=p["F0"] * t[0] + p["k"] * t[1])


# ------------------------------------------------------------------------------------------------- track lash
def track_sides(nb, rng):
    """(nb,) the side (+1 / -1) each block's approach came from, both present."""
    s = rng.choice([-1.0, 1.0], nb)
    if nb > 1 and abs(s.sum()) == nb:
        s[int(rng.integers(nb))] *= -1
    return s


def track_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    psi = rng.uniform(0, np.pi)
    return {"e": np.array([np.cos(psi), np.sin(psi), 0.0]), "c_mm": rng.uniform(0.15, 0.5),
            "sides": track_sides(nb, rng)}


def track_features(p, ctx, hw):
    s = p["sides"][block_index(ctx.session)]
    return (s[:, None] * p["e"])[None]


def track_apply(p, ctx, hw):
    return Contribution(displace=p["c_mm"] / 2 * track_features(p, ctx, hw)[0])


# ---------------------------------------------------------------------------------------------- run-in wear
WEAR_JOINTS = (0, 1, 2)
WEAR_FRICTION = 0.10


def wear_growth(p, session):
    """(P,) the share of the run-in lost motion opened before each pose."""
    return 1.0 - np.exp(-machining_s(session) / p["tau_s"])


def wear_sides(p, ctx):
    """(P, k) the flank each axis rests on (+1 / -1): its load's, or trailing its last motion when lightly loaded."""
    tau = ctx.loads
    cols = []
    for j in p["joints"]:
        lim = WEAR_FRICTION * np.abs(tau[:, j]).max()
        cols.append(ph.backlash_offset(ctx.session.direction[:, j], tau[:, j], lim, 2.0, 0.0))
    return np.array(cols).T


def wear_draw(ctx, hw, rng):
    joints = tuple(j for j in WEAR_JOINTS if ctx.chain.revolute[j])
    return {"joints": joints, "tau_s": 60.0 * rng.uniform(20.0, 60.0),
            "b_r": rng.uniform(1.0, 3.0, len(joints)) * ARCMIN}


def wear_features(p, ctx, hw):
    g = wear_growth(p, ctx.session)
    s = wear_sides(p, ctx)
    return np.array([ctx.joint_feature(j, s[:, i] * g) for i, j in enumerate(p["joints"])])


def wear_apply(p, ctx, hw):
    g = wear_growth(p, ctx.session)
    s = wear_sides(p, ctx)
    dq = np.zeros_like(ctx.q)
    for i, j in enumerate(p["joints"]):
        dq[:, j] = p["b_r"][i] / 2 * s[:, i] * g
    return Contribution(dq=dq)


# ------------------------------------------------------------------------------------------------ ring lobing
LOBES = 3


def lobing_draw(ctx, hw, rng):
    R, a = rng.uniform(40.0, 80.0), rng.uniform(0.010, 0.040)
    A, phi = a / (LOBES * R), rng.uniform(0, 2 * np.pi)
    # dq = -A sin(n (q - phi)) = -A cos(n phi) sin(n q) + A sin(n phi) cos(n q)
    return {"R_mm": R, "a_mm": a, "A": A, "phi": phi,
            "amp": np.array([-A * np.cos(LOBES * phi), A * np.sin(LOBES * phi)])}


def lobing_features(p, ctx, hw):
    q = ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, np.sin(LOBES * q)), ctx.joint_feature(0, np.cos(LOBES * q))])


def lobing_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, 0] = -p["A"] * np.sin(LOBES * (ctx.q[:, 0] - p["phi"]))
    return Contribution(dq=dq)


# ------------------------------------------------------------------------------------------------ cosine error
def cosine_joints(chain):
    return tuple(int(j) for j in np.flatnonzero(~np.asarray(chain.revolute)))


def cosine_draw(ctx, hw, rng):
    beta = np.deg2rad(rng.uniform(1.5, 3.5))
    return {"beta": beta, "kappa": 1.0 / np.cos(beta) - 1.0, "joints": cosine_joints(ctx.chain)}


def cosine_features(p, ctx, hw):
    if not p["joints"]:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([sum(ctx.joint_feature(j, ctx.q[:, j]) for j in p["joints"])])


def cosine_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for j in p["joints"]:
        dq[:, j] = p["kappa"] * ctx.q[:, j]
    return Contribution(dq=dq)
