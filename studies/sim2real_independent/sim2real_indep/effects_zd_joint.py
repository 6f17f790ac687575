"""Set ZD joint effects (new physics, not in sets A-ZC): a controller's Cartesian soft-float compliance yielding to the
tool's and part's weight in the tool frame; joint torque sensors whose bending-moment crosstalk a torque-controlled arm
turns into joint offsets; a planetary stage whose floating sun adds lost motion that the load takes up; tool_changer's
wrist lost motion whose flank the telescopic stroke's spline drag chooses; a diametric pair of encoder read-heads whose
averaging lapses in the blocks in which one head drops out; and a range-change gearbox whose low range's ratio the
controller holds rounded. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* soft float: Cartesian stiffness control renders a chosen stiffness at the flange, K = R diag(k_x, k_y, k_z) R^T in
  the tool frame (Salisbury, "Active stiffness control of a manipulator in Cartesian coordinates", IEEE CDC 1980;
  Hogan, "Impedance control", ASME J. Dyn. Syst. 107, 1985; the "soft float" / Cartesian compliance options of
  industrial controllers, used for fitting and press-in work, as recalled). The weight of the tool (m_t, unlogged,
  constant) and of the part (logged as the payload, a new part each block) displaces the flange by K^-1 W: softest along
  the tool's axis (the float direction), 2-5 times stiffer across it. Sized so that the largest shift is 0.2-0.5 mm.
  Unlike the joint-space compliances of sets A-ZC (gears, joint impedance), the compliance is diagonal in the tool's
  frame, whatever the pose. Driven by the pose and the payload (logged). The true structure: three columns (the weight's
  share along each tool axis), amplitudes 1 / k_i [mm/N].
* torque crosstalk: a torque-controlled arm closes each joint's torque loop on a strain-gauge torque sensor; the sensor
  also reads a fraction kappa (1-3 %) of the bending moment across it along one direction e fixed in its hub (gauge
  misalignment; Kashiri, Malzahn & Tsagarakis, "On the sensor design of torque controlled actuators", IEEE RA-L 2,
  2017; Tsetserukou et al., torque sensor crosstalk, as recalled). With joint impedance K (Albu-Schaeffer, Ott &
  Hirzinger, IJRR 26, 2007) the joint settles at dq = -(kappa / K) M.e. Axes 1-3, whose sensors carry the largest
  moments; sized so that the target moves 0.3-0.6 mm (a compliant impedance of some 10^3 N m/rad; first 0.15-0.45 mm:
  ZD02 gained 18 % with the transmission model at 1.10x). Unlike the gear and impedance compliances of sets A-ZC (the
  torque about the axis), the offset follows the moment across the axis. Driven by the pose and the payload (logged).
  The true structure: one column per joint (M.e), amplitudes -kappa / K [rad/(N m)].
* floating sun: a planetary stage with a floating sun (load sharing; Mueller, *Epicyclic Drive Trains*, 1982; Kahraman,
  "Load sharing characteristics of planetary transmissions", Mech. Mach. Theory 29, 1994) has, besides the meshes'
  lash b_g, the sun's radial float, which adds lost motion b_f at light load and is taken up as the mesh forces centre
  the sun: b(tau) = b_g + b_f exp(-|tau| / tau_c), tau_c 10-30 % of the largest load. The output rests on the load's
  flank where the load beats the friction (3 % of the largest load), else it trails the last motion (Nordin & Gutman,
  Automatica 38, 2002). On the loaded axis 2 or 3; the float moves the target 0.3-0.6 mm (a sun floating in a worn
  stage; first 0.15-0.4 mm: ZD03 gained 13 %, the link model at 1.13x). Unlike the lost motions of sets A-ZC (fixed, worn, heated, varying
  along the turn), the play closes as the load grows. Driven by the pose, payload and direction (logged). The true
  structure: two columns (flank, flank exp(-|tau| / tau_c)), amplitudes b_g / 2, b_f / 2 [rad].
* spline drag: tool_changer's wrist trains run through ball splines along the telescopic stage; the splines' friction
  and their slight helix drag the wrist shafts round as the stage strokes, so a wrist axis that gravity does not hold
  rests on the flank that the telescope's last stroke chose (helix sense per shaft; spline friction: THK ball spline
  catalogue, as recalled). Each wrist axis' half-play moves the target 0.15-0.4 mm (a worn heavy wrist, some 1-3
  mrad; first 0.1-0.3 mrad: ZD09 moved 0.05 mm, a gain of 17 % with the joint model at 1.14x). Unlike set V's coupled flank (a wrist motor's net motion) or
  set ZA's guide drag (the stage itself), the flank of a rotary axis follows a prismatic one's stroke. tool_changer only
  (none elsewhere). Driven by the direction of q4 and the pose (logged). The true structure: one column per wrist axis,
  amplitudes the half-plays [rad].
* read-head dropout: an output ring encoder read by two diametric heads averages out the ring's eccentricity e
  (HEIDENHAIN, modular angle encoders, as recalled: e / R per head, cancelled by the opposite head); in blocks in which
  one head's signal is lost (coolant mist on its window; the controller falls back to the other head, unlogged) the
  error (e / R) sin(q + phi) returns, and the closed loop turns the joint by its negative. Axis 1 or 2; sized so that
  the target moves 0.3-0.6 mm (a ring mounted 20-50 um off centre; first 0.15-0.4 mm: trial draws on other seeds gave
  ZD04 and ZD20 gains of 9-15 %, the error present in a few blocks only). Unlike set C's dual encoders or the runouts of sets A-ZC, the eccentricity is present
  in some blocks only. Driven by the joint angle (logged) and the heads' state (not logged). The true structure: two
  columns (the dropout blocks' sin q, cos q), amplitudes -(e / R) (cos phi, sin phi).
* range shift: axis 1 behind a two-speed (range-change) gearbox, the high range for traverse, the low for fine work
  (shiftable gearboxes of positioners, as recalled); the low range's stage ratio is a non-terminating fraction that the
  controller holds rounded (epsilon of some 1e-4, sized so that the target moves 0.15-0.45 mm), so in the low-range blocks (unlogged) the output is off by epsilon
  times the angle from the range's reference (q = 0). Unlike set G's rounded ratio (always on), the error exists in
  the low-range blocks only. Driven by the angle (logged) and the range (not logged). The true structure: one column,
  amplitude epsilon.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index

G = kin.G


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _dq_apply(ctx, cols):
    """A Contribution of joint offsets from (joint, signal) pairs."""
    dq = np.zeros_like(ctx.q)
    for j, s in cols:
        dq[:, j] += s
    return Contribution(dq=dq)


def _blocks(session, n):
    return np.minimum(block_index(session), n - 1)


def _two_states(rng, nb):
    on = rng.random(nb) < 0.5
    if nb > 1 and (on.all() or not on.any()):
        on[int(rng.integers(nb))] = not on[0]
    return on.astype(int)


# ---------------------------------------------------------------------------------------------------- soft float
TOOL_KG = {"ur10": (1.0, 3.0), "kr16_like": (2.0, 6.0), "tool_changer": (10.0, 30.0)}


def float_parts(p, ctx):
    """(3, P, 3) the flange's shift per unit compliance along each tool axis [mm per mm/N]: the weight's share."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    W = (ctx.session.payload_kg + p["tool_kg"])[:, None] * np.array([0.0, 0.0, -G])       # [N]
    return np.array([Rt[:, :, i] * np.einsum("pi,pi->p", Rt[:, :, i], W)[:, None] for i in range(3)])


def soft_float_draw(ctx, hw, rng):
    p = {"tool_kg": rng.uniform(*TOOL_KG[ctx.chain.name]), "rel": np.r_[rng.uniform(0.2, 0.5, 2), 1.0]}
    F = float_parts(p, ctx)
    size = np.linalg.norm(np.einsum("k,kpi->pi", p["rel"], F), axis=1).max()
    p["c"] = p["rel"] * rng.uniform(0.2, 0.5) / max(size, 1e-12)
    return p


def soft_float_features(p, ctx, hw):
    return float_parts(p, ctx)


def soft_float_apply(p, ctx, hw):
    return _amp_apply(p["c"], float_parts(p, ctx))


# ---------------------------------------------------------------------------------------------- torque crosstalk
def crosstalk_joints(chain):
    return [j for j in (0, 1, 2) if chain.revolute[j]]


def bending_moments(ctx):
    """(P, n, 3) the gravity moment [N m] of everything beyond each joint about its axis point (base frame)."""
    m, pos, body = ctx.mass_state
    _, c = kin.joint_frames(ctx.chain, ctx.q)
    F = m[..., None] * np.array([0.0, 0.0, -G])
    out = np.zeros((len(ctx.q), ctx.chain.n, 3))
    for j in range(ctx.chain.n):
        on = body >= j + 1
        out[:, j] = np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F[:, on]).sum(axis=1)
    return out


def sensor_direction(p, ctx, j):
    """(P, 3) the direction of joint j's crosstalk, fixed in its output hub (body j + 1), across its axis."""
    w = ctx.chain.axes[j]
    u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    e = np.cos(p["psi"][j]) * u + np.sin(p["psi"][j]) * np.cross(w, u)
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    return R[:, j + 1] @ e


def crosstalk_signals(p, ctx):
    M = bending_moments(ctx)
    return {j: np.einsum("pi,pi->p", M[:, j], sensor_direction(p, ctx, j)) for j in crosstalk_joints(ctx.chain)}


def crosstalk_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, s) for j, s in crosstalk_signals(p, ctx).items()])


def crosstalk_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi, ctx.chain.n), "kappa": rng.uniform(0.01, 0.03, 3)}
    F = crosstalk_features(p, ctx, hw)
    rel = rng.choice([-1.0, 1.0], len(F)) * np.exp(rng.uniform(-0.3, 0.3, len(F)))
    rel /= np.array([max(np.linalg.norm(f, axis=1).max(), 1e-12) for f in F])
    size = np.linalg.norm(np.einsum("k,kpi->pi", rel, F), axis=1).max()
    p["a"] = rel * rng.uniform(0.3, 0.6) / max(size, 1e-12)
    p["K"] = p["kappa"][:len(F)] / np.abs(p["a"])            # the joint impedances it implies [N m/rad]
    return p


def crosstalk_apply(p, ctx, hw):
    return _amp_apply(p["a"], crosstalk_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- floating sun
def sun_signals(p, ctx):
    """(2, P) the flank (the load's where it beats the friction, else against the last motion) and the flank times the
    float's share exp(-|tau| / tau_c)."""
    j = p["joint"]
    tau = ctx.loads[:, j]
    flank = np.where(np.abs(tau) > p["f_Nm"], np.sign(tau), -ctx.session.direction[:, j])
    return np.array([flank, flank * np.exp(-np.abs(tau) / p["tau_c"])])


def sun_draw(ctx, hw, rng):
    cand = [j for j in (1, 2) if ctx.chain.revolute[j]]
    j = max(cand, key=lambda i: np.abs(ctx.loads[:, i]).max())
    tmax = np.abs(ctx.loads[:, j]).max()
    p = {"joint": j, "tau_c": tmax * rng.uniform(0.1, 0.3), "f_Nm": 0.03 * tmax}
    lever = np.linalg.norm(ctx.jac[:, :, j], axis=1).max()                   # [mm/rad]
    bf = rng.uniform(0.3, 0.6) / lever
    p["half"] = np.array([bf * rng.uniform(0.2, 0.5), bf])
    return p


def sun_features(p, ctx, hw):
    return np.array([ctx.joint_feature(p["joint"], s) for s in sun_signals(p, ctx)])


def sun_apply(p, ctx, hw):
    return _dq_apply(ctx, [(p["joint"], p["half"] @ sun_signals(p, ctx))])


# --------------------------------------------------------------------------------------------------- spline drag
def spline_joints(chain):
    """(prismatic joint, wrist joints beyond it) or (None, [])."""
    pr = [j for j in range(chain.n) if not chain.revolute[j]]
    if not pr:
        return None, []
    return pr[0], [j for j in range(pr[0] + 1, chain.n) if chain.revolute[j]]


def spline_flank(p, ctx, j, k):
    tau = ctx.loads[:, j]
    lim = 0.03 * max(np.abs(tau).max(), 1e-12)
    return np.where(np.abs(tau) > lim, np.sign(tau), p["sense"][k] * ctx.session.direction[:, p["prismatic"]])


def spline_draw(ctx, hw, rng):
    jp, W = spline_joints(ctx.chain)
    return {"prismatic": jp, "wrist": W, "sense": rng.choice([-1.0, 1.0], 3),
            "half": rng.uniform(0.15, 0.4, 3)[:len(W)] / np.array(
                [max(np.linalg.norm(ctx.jac[:, :, j], axis=1).max(), 1e-9) for j in W])}


def spline_features(p, ctx, hw):
    if p["prismatic"] is None:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(j, spline_flank(p, ctx, j, k)) for k, j in enumerate(p["wrist"])])


def spline_apply(p, ctx, hw):
    return _dq_apply(ctx, [(j, p["half"][k] * spline_flank(p, ctx, j, k)) for k, j in enumerate(p["wrist"])])


# ---------------------------------------------------------------------------------------------- read-head dropout
def dropout_mask(p, session):
    return np.asarray(p["single"], float)[_blocks(session, len(p["single"]))]


def dropout_signals(p, ctx):
    q = ctx.q[:, p["joint"]]
    m = dropout_mask(p, ctx.session)
    return np.array([m * np.sin(q), m * np.cos(q)])


def dropout_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"joint": int(rng.choice([j for j in (0, 1) if ctx.chain.revolute[j]])), "single": _two_states(rng, nb),
         "phi": rng.uniform(0, 2 * np.pi)}
    lever = np.linalg.norm(ctx.jac[:, :, p["joint"]], axis=1).max()
    p["e_R"] = rng.uniform(0.3, 0.6) / lever
    p["a"] = -p["e_R"] * np.array([np.cos(p["phi"]), np.sin(p["phi"])])
    return p


def dropout_features(p, ctx, hw):
    return np.array([ctx.joint_feature(p["joint"], s) for s in dropout_signals(p, ctx)])


def dropout_apply(p, ctx, hw):
    return _dq_apply(ctx, [(p["joint"], p["a"] @ dropout_signals(p, ctx))])


# --------------------------------------------------------------------------------------------------- range shift
RANGE_JOINT = 0


def range_signal(p, ctx):
    low = np.asarray(p["low"], float)[_blocks(ctx.session, len(p["low"]))]
    return low * ctx.q[:, RANGE_JOINT]


def range_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"low": _two_states(rng, nb)}
    size = np.linalg.norm(range_features(p, ctx, hw)[0], axis=1).max()
    p["eps"] = rng.choice([-1.0, 1.0]) * rng.uniform(0.15, 0.45) / max(size, 1e-12)
    return p


def range_features(p, ctx, hw):
    return ctx.joint_feature(RANGE_JOINT, range_signal(p, ctx))[None]


def range_apply(p, ctx, hw):
    return _dq_apply(ctx, [(RANGE_JOINT, p["eps"] * range_signal(p, ctx))])
