"""Set ZE joint effects (new physics, not in sets A-ZD): the tool pulled towards a fixed anchor by a self-retracting
tether; ball reducers whose Hertzian contacts twist by a 2/3-power law; a rotary clamp that, in the blocks in which it
is used, pulls axis 1 across its lash to the clamp's side; a no-back brake on axis 2 whose release travel makes the
output lag only when the motor drives with the load; axis 1's encoder disc shifted under its read head by the main
bearing's tilt under the overturning moment; and a motor encoder's decoder gaining a count at each reversal. Same
protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* tether reel: a self-retracting tether (a constant-force spring reel: a prestressed flat spiral spring, Wahl,
  *Mechanical Springs*, 2nd ed., 1963, ch. on constant-force springs) anchored at a fixed point beside the cell holds the
  tool's hose or a safety lanyard; it pulls the target towards the anchor with a constant tension T whatever the
  payout. The pull twists the main axes' gears by tau = J^T F (Craig, *Introduction to Robotics*, ch. 5) through their
  compliances c_j. The anchor stands 1.0-1.4 times the targets' median reach from the base axis, any heading, 0.5-2 m
  above the base, over the cell's fence (first 1.2-1.8 times, 0-1.2 m: ZE14 on tool_changer gained 19 %, the link
  model at 1.22x -- a far, low anchor pulls nearly one way; at the final anchor 11 %, the link model at 1.11x: the
  pull bends tool_changer's long boom as much as it twists its stiff gears, so the reel is on ur10 alone, ZE01); the twist sized so that the target moves 0.25-0.6 mm. Unlike set X's magnetic fanner (a pull towards
  a pole falling as 1 / r^3) or set F's cable balancer (a vertical pull), the pull's size is constant and its direction
  is the line to a point beside the cell. Driven by the pose (logged) and the tether (not logged). The true structure:
  one column per main revolute axis (the unit pull's torque), amplitudes c_j T [rad].
* ball reducer: a cycloidal ball reducer (balls running in epi- and hypo-cycloidal grooves; Terada, "The development
  of gearless reducers with rolling balls", J. Mech. Sci. Tech. 24, 2010, as recalled) on the wrist axes 4 and 5 (5
  and 6 on tool_changer), whose torques such compact reducers carry (first on axes 2 and 3: ZE02 on ur10 let the mount
  model come within 1.06x, then on 3 and 5: the link model within 1.12x and 1.19x on ZE02 and ZE18 -- axis 3 twists as
  the forearm bends; axes 2 and 3 carry more torque than a ball reducer is rated for):
  its stiffness is that of the balls' Hertzian point contacts, whose approach grows as the load to the 2/3 power
  (Johnson, *Contact Mechanics*, 1985, ch. 4; Harris & Kotzalas, *Rolling Bearing Analysis*, 2007: delta ~ Q^(2/3)), so
  the twist is c sign(tau) |tau|^(2/3) tau_ref^(1/3) -- soft at small loads, stiffening, unlike the linear and
  hardening (tau |tau|) laws of sets A-ZD or set ZA's asymmetric flanks. Sized to 0.25-0.6 mm. Driven by the pose and
  the payload (logged). The true structure: one column per axis, amplitudes c_j [rad/(N m)].
* rotary clamp: a heavy axis 1 with a hydraulic clamping ring (rotary tables' and positioners' clamps; closing a clamp
  turns the output by a few arc-seconds to its lash's end: machine-tool rotary-table practice, ISO 230-1 on clamping
  effects, as recalled): in the blocks run with the clamp (unlogged, both kinds present) the output rests on the side s
  the clamp's shoes drag it to, elsewhere on the flank the last motion left (the gear's lash; Nordin & Gutman,
  Automatica 38, 2002). Half-play sized to move the target 0.25-0.6 mm. Unlike the lost motions of sets A-ZD (the load's
  or a motion's flank), a clamp's closing chooses the flank, block by block. Driven by the direction (logged) and the
  clamp's use (not logged). The true structure: one column, amplitude the half-play [rad].
* no-back brake: a load-holding no-back device (a wrap-spring or ratchet-disc no-back in the drive, as in screw jacks
  and actuators holding gravity loads without power; Duff-Norton no-back catalogue, as recalled) on axis 2: while the
  motor drives against the load the no-back free-wheels; driven with the load (lowering) the brake engages and the
  motor winds its release travel, so the output lags by delta only when the last motion went the load's way. Unlike the
  symmetric lost motions of sets A-ZD, the lost motion exists in one of the four (load, motion) quadrants pairs only:
  offset -delta d (1 + d s) / 2 with s the load's sign. Sized to 0.25-0.6 mm. Driven by the pose, payload and direction
  (logged). The true structure: one column, amplitude delta [rad].
* disc shift: axis 1's output encoder (a ring disc of radius R 60-120 mm read by one head at angle psi fixed in the
  base) sits h 80-200 mm above the main bearing; the bearing tilts under the arm's overturning moment M (crossed-roller
  bearing tilting stiffness: IKO / THK catalogues, as recalled), the shaft carries the disc sideways by h theta, and the
  head reads the tangential share as an angle, (h c / R) (M x z).t_psi, which the closed loop turns into the opposite
  rotation. Unlike sets C's bearing tilt (the tilt moving the arm) or ZD's read-head eccentricity (a fixed geometric
  error), the reading follows the moment across the bearing. Sized to 0.25-0.6 mm. Driven by the pose and the payload
  (logged). The true structure: two columns (M_x, M_y on joint 1), amplitudes k (cos psi, sin psi) [rad/(N m)].
* reversal counts: a motor encoder's quadrature decoder with a marginal phase between its channels counts a spurious
  edge at every reversal of its axis (the edge jitter of a slowly reversing signal; Hagiwara, encoder signal
  processing, as recalled), always in the same sense, so the reading drifts by one count (2 pi / (N_c i)) per reversal
  since homing: 100-300 reversals in a session. Unlike sets W's dropped counts (lost at speed) or R's EMI counts, the
  error counts the axis' reversals. On axis 1; sized to 0.25-0.6 mm at the session's end. Driven by the directions
  (logged: the reversals are in the dir columns). The true structure: one column, amplitude the count's angle [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_u_joint import block_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _size(F, rel, rng, lo=0.25, hi=0.6):
    """Amplitudes ``rel`` scaled so that the largest displacement is U(lo, hi) mm."""
    size = np.linalg.norm(np.einsum("k,kpi->pi", np.asarray(rel, float), F), axis=1).max()
    return np.asarray(rel, float) * rng.uniform(lo, hi) / max(size, 1e-12)


def _main_joints(chain):
    return [j for j in range(3) if chain.revolute[j]]


# ---------------------------------------------------------------------------------------------------- tether reel
def tether_pull(p, ctx):
    """(P, 3) the unit pull at the target, towards the anchor."""
    d = np.asarray(p["anchor_mm"], float) - ctx.target
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def tether_torques(p, ctx):
    """(P, n) the joints' torques [N m per N] of the unit pull."""
    return np.einsum("pij,pi->pj", ctx.jac, tether_pull(p, ctx)) / 1000.0


def tether_draw(ctx, hw, rng):
    reach = np.median(np.linalg.norm(ctx.target[:, :2], axis=1))
    a = rng.uniform(0, 2 * np.pi)
    r = reach * rng.uniform(1.0, 1.4)
    p = {"anchor_mm": np.array([r * np.cos(a), r * np.sin(a), rng.uniform(500.0, 2000.0)])}
    p["c"] = _size(tether_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(_main_joints(ctx.chain))), rng)
    return p


def tether_features(p, ctx, hw):
    tau = tether_torques(p, ctx)
    return np.array([ctx.joint_feature(j, tau[:, j]) for j in _main_joints(ctx.chain)])


def tether_apply(p, ctx, hw):
    return _amp_apply(p["c"], tether_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ball reducer


def hertz_twist(tau, tau_ref):
    """sign(tau) |tau|^(2/3) tau_ref^(1/3) [N m]: the Hertzian contacts' load law, equal to tau at tau_ref."""
    return np.sign(tau) * np.abs(tau) ** (2.0 / 3.0) * tau_ref ** (1.0 / 3.0)


def ball_joints(chain):
    """The first two revolute wrist axes (4 and 5; 5 and 6 on tool_changer, whose axis 4 is the telescope)."""
    return [j for j in (3, 4, 5) if chain.revolute[j]][:2]


def ball_draw(ctx, hw, rng):
    p = {"joints": ball_joints(ctx.chain)}
    p["tau_ref"] = [float(np.abs(ctx.loads[:, j]).max()) for j in p["joints"]]
    p["c"] = _size(ball_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(p["joints"])), rng)
    return p


def ball_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, hertz_twist(ctx.loads[:, j], r)) for j, r in zip(p["joints"], p["tau_ref"])])


def ball_apply(p, ctx, hw):
    return _amp_apply(p["c"], ball_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- rotary clamp
def clamp_signal(p, ctx):
    """(P,) axis 1's flank: the clamp's side in the clamped blocks, else trailing the last motion."""
    b = np.minimum(block_index(ctx.session), len(p["clamped"]) - 1)
    on = np.asarray(p["clamped"])[b].astype(bool)
    return np.where(on, float(p["side"]), -ctx.session.direction[:, 0])


def clamp_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    on = rng.random(nb) < 0.5
    if nb > 1 and (on.all() or not on.any()):
        on[int(rng.integers(nb))] = not on[0]
    p = {"clamped": on.astype(int), "side": float(rng.choice([-1.0, 1.0]))}
    p["half"] = _size(clamp_features(p, ctx, hw), [1.0], rng)
    return p


def clamp_features(p, ctx, hw):
    return ctx.joint_feature(0, clamp_signal(p, ctx))[None]


def clamp_apply(p, ctx, hw):
    return _amp_apply(p["half"], clamp_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- no-back brake
NOBACK_JOINT = 1


def noback_signal(ctx):
    """(P,) -1 or +1 times the last motion where it went the load's way (the brake's release travel), else 0."""
    d = ctx.session.direction[:, NOBACK_JOINT]
    s = np.sign(ctx.loads[:, NOBACK_JOINT])
    return -d * (1.0 + d * s) / 2.0


def noback_draw(ctx, hw, rng):
    p = {"joint": NOBACK_JOINT}
    p["delta"] = _size(noback_features(p, ctx, hw), [1.0], rng)
    return p


def noback_features(p, ctx, hw):
    return ctx.joint_feature(NOBACK_JOINT, noback_signal(ctx))[None]


def noback_apply(p, ctx, hw):
    return _amp_apply(p["delta"], noback_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- disc shift
def disc_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    p = {"psi": psi, "h_mm": rng.uniform(80.0, 200.0), "R_mm": rng.uniform(60.0, 120.0)}
    k = _size(disc_features(p, ctx, hw), [np.cos(psi), np.sin(psi)], rng)
    p["k"] = k
    return p


def disc_features(p, ctx, hw):
    M = mount_moment(ctx)
    return np.array([ctx.joint_feature(0, M[:, 0]), ctx.joint_feature(0, M[:, 1])])


def disc_apply(p, ctx, hw):
    return _amp_apply(p["k"], disc_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- reversal counts
def reversals(session, j=0):
    """(P,) the number of reversals of joint j since the session's start (from the logged directions)."""
    d = session.direction[:, j]
    return np.r_[0.0, np.cumsum(d[1:] != d[:-1])]


def counts_draw(ctx, hw, rng):
    p = {"joint": 0}
    p["step"] = _size(counts_features(p, ctx, hw), [1.0], rng)
    return p


def counts_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], reversals(ctx.session, p["joint"]))[None]


def counts_apply(p, ctx, hw):
    return _amp_apply(p["step"], counts_features(p, ctx, hw))
