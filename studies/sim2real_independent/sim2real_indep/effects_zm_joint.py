"""Set ZM joint effects (new physics, not in sets A-ZL): wrist gears whose torsional stiffness falls with the tilting
moment on their output bearing; wrist strain-wave gears whose mesh stiffness ripples with the wave generator's angle;
a wrist bend's lost motion tossed onto a flank by the main axes' deceleration; the seat play of a ball-detent torque
limiter on the tool flange; and open-loop stepper wrists' microstep error and step-angle (tooth-pitch) error. Same
protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* moment softening (``moment_softening``): a strain-wave or cycloid joint carries its link's tilting moment on its
  output bearing (a crossed-roller or angular-contact pair: Harmonic Drive AG, *Engineering Data CSF/CSG units*,
  tilting-moment stiffness of the output bearing; Nabtesco RV catalogue, allowable moment); the moment tilts the
  circular spline against the flexspline (the pins against the disc) and opens the tooth engagement on one side, so
  fewer teeth share the torque and the torsional stiffness falls (the load-sharing argument of Dhaouadi & Ghorbel,
  Int. J. Modelling & Simulation 28, 2008, for strain-wave teeth; Li, Chen et al. on cycloid pin load sharing under
  moment, as recalled). Written as twist = tau / K0 (1 + g |M_t| / M_r), M_t the moment normal to the axis, M_r the
  bearing's rated tilting moment (the session's largest at 30-70 % of it), g 1-2 (assumed). Wrist bends (ur10's
  axes 4 and 5, the others' axis 5); parts changed between blocks; sized to 0.25-0.6 mm. Unlike set C's bearing tilt
  (the axis itself tilting under the moment), set ZK's housing spread (the lost motion widened by the moment) or set A's
  hardening (the torque alone), the torsional compliance is raised by the moment across the axis. Driven by the pose
  and the payload (logged). The true structure: one column per joint (tau (1 + g |M_t| / M_r)), amplitudes 1 / K0.
* mesh-stiffness ripple (``mesh_ripple``): the number of teeth in contact, and with it a gear's mesh stiffness,
  changes periodically with the mesh position (time-varying mesh stiffness: Kahraman & Singh, J. Sound Vib. 142,
  1990; for strain-wave gears the engagement pattern turns with the wave generator, twice per its turn: Tuttle &
  Seering, ASME J. Dyn. Sys. 118, 1996, measured stiffness varying with the wave generator's position). The static
  twist is tau / K0 (1 + e sin(2 N q + phi)), N 80-160, e 10-30 % (assumed). Wrist bends (as above) on strain-wave
  gears; sized to 0.25-0.6 mm. ur10 and kr16_like (first on tool_changer too: ZM11 ambiguous with the link model at
  1.11x -- its axis 5 under a 120 kg end-effector twists almost in proportion to the load, as the boom bends). Unlike set ZH's cracked tooth or worn zone (softening once per output turn at a
  damaged zone), set L's pin ring or set A's gear error (a transmission error, present without load), the stiffness of
  a sound gear ripples with its mesh phase. Driven by the pose and the payload (logged). The true structure: one column
  per joint, amplitudes 1 / K0.
* upstream toss (``upstream_toss``): a wrist bend's lost motion (its gear's backlash, Nordin & Gutman, Automatica 38,
  2002) is crossed when the torque on it beats its friction f; at the end of each move the main axes (1-3) decelerate
  the wrist and the part, whose inertia puts a torque on axis 5 (the wrist's d'Alembert load, J_k(p) a_k per mass);
  the output is left on the flank sign(tau_g + tau_in) where that beats f, by axis 5's own last motion where it moved,
  and then on the gravity flank where gravity alone beats f. a_k = the move's mean speed over the 0.5 s ramps; f
  20-40 % of the session's largest gravity torque on axis 5. kr16_like (fast main axes) and tool_changer (whose slow
  boom seldom tosses: there mostly the gravity and motion flanks); sized to 0.25-0.6 mm.
  Unlike set ZG's coast flank (the loaded axes' own link's inertia), set O's cut flank or set Z's wind flank (external
  torques), the toss comes from the axes upstream of the lash. Driven by the pose sequence, the speeds and the payload
  (logged). The true structure: one column (the flank), amplitude the half lash.
* detent limiter (``limiter_play``): a ball-detent torque limiter (overload clutch) between the flange and the tool
  (R+W / Mayr EAS catalogues, as recalled: the balls seat in conical detents with a small angular play until the
  disengaging torque) lets the tool turn about the roll axis across its seat play; the tool's centre of mass off the
  roll axis (30-100 mm, a side-mounted gripper; 1-4 / 2-8 / 10-30 kg) and the part put a torque on it: the tool sits
  on the flank sign(tau_6) where |tau_6| beats the seats' friction (10-30 % of its largest), on the last rotation's
  flank otherwise. Sized to 0.25-0.6 mm. Unlike set ZC's bayonet play (a hose's drag choosing it), set P's quick change
  (re-seating at each change) or set ZL's hose flank, the flank is chosen by the off-axis tool's own weight. Driven by
  the pose, the payload and the last motion (logged). The true structure: one column, amplitude the half play.
* microstep error (``microstep_error``): a hybrid stepper driven with sine/cosine microstep currents stops short of
  the commanded microstep because its detent torque and the non-sinusoidal static torque curve bend the current-angle
  relation: an error periodic in each full step, e sin(4 N_r theta_m + phi) (Kenjo & Sugawara, *Stepping Motors and
  Their Microprocessor Controls*, 1994, ch. 6; Acarnley, *Stepping Motors*, 2002, microstepping accuracy), e 5-10 % of
  a full step (1.8 deg), N_r = 50. Behind a belt-and-planetary head of ratio N_g 2-5 the output errs by
  e / N_g sin(200 N_g q + phi). Wrist axes 4 and 5 of ur10 and kr16_like (assumed stepper builds, as sets ZJ and ZL).
  Unlike set ZL's step truncation (a running sum of cut fractions) or set V's interpolation error (an encoder's), the
  error is the open-loop motor's position within each full step. Driven by the commanded angle (logged). The true
  structure: two columns per axis (sin, cos of 200 N_g q), amplitudes e cos phi / N_g, e sin phi / N_g.
* step accuracy (``step_accuracy``): the full-step positions of a hybrid stepper are off by its rotor's and stator's
  tooth-pitch errors and the rotor's eccentricity in the air gap: a non-cumulative error of up to 3-5 % of a step,
  repeating once per motor turn (NEMA ICS 16 "step angle accuracy"; makers' data, as recalled; Kenjo & Sugawara, ch.
  3), written as a once- and twice-per-turn part (rotor eccentricity and ovality, 2-4 % of a step) plus a tooth-by-tooth
  part (1.5-3 %, one value for each of the 50 rotor teeth, linear between them). Behind a belt stage of ratio 1.5-3 on
  wrist axes 4 and 5 of ur10 and kr16_like (first 1-3 % and 1-2 % behind N_g 2-4, the better motors' figures: kr16_like's
  ZM19 gained 8.7 %, 0.07 mm against 0.04 mm of noise; now the catalogue's +-5 % class behind a belt only). Unlike this set's microstep error (within each step) or set S's cogging (a torque against a
  servo), the error follows the motor's turn. Driven by the commanded angle (logged). The true structure: one column
  per axis, amplitude 1.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zi_joint import _size_cols

N_R = 50                  # rotor teeth of a 1.8 deg hybrid stepper
STEP = 2 * np.pi / 200    # a full step [rad]
RAMP_S = 0.5              # the session's acceleration ramps
TOOL_KG = {"ur10": (1.0, 4.0), "kr16_like": (2.0, 8.0), "tool_changer": (10.0, 30.0)}


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def wrist_bends(chain):
    """ur10's axes 4 and 5, the others' axis 5 (0-based 3, 4 / 4)."""
    return [3, 4] if chain.name == "ur10" else [4]


def joint_moment(ctx, j):
    """(P, 3) the gravity moment [N m] of the masses beyond joint j about its axis point."""
    m, pos, body = ctx.mass_state
    _, c = kin.joint_frames(ctx.chain, ctx.q)
    on = body >= j + 1
    F = m[:, on, None] * kin.G * np.array([0.0, 0.0, -1.0])
    return np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F).sum(axis=1)


def tilt_moment(ctx, j):
    """(P,) the moment's magnitude normal to joint j's axis [N m]."""
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    M = joint_moment(ctx, j)
    return np.linalg.norm(M - np.einsum("pi,pi->p", M, w[:, j])[:, None] * w[:, j], axis=1)


# ---------------------------------------------------------------------------------------------------- moment softening
def softening_twist(p, ctx, j):
    """(P,) tau (1 + g |M_t| / M_r) of joint j."""
    return ctx.loads[:, j] * (1 + p["g"] * tilt_moment(ctx, j) / p["M_r"][j])


def softening_draw(ctx, hw, rng):
    js = wrist_bends(ctx.chain)
    p = {"g": float(rng.uniform(1.0, 2.0)),
         "M_r": {j: float(tilt_moment(ctx, j).max() / rng.uniform(0.3, 0.7)) + 1e-9 for j in js}}
    p["c"] = _size_cols(softening_features(p, ctx, hw), rng)
    return p


def softening_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, softening_twist(p, ctx, j)) for j in wrist_bends(ctx.chain)])


def softening_apply(p, ctx, hw):
    return _amp_apply(p["c"], softening_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- mesh ripple
def ripple_twist(p, ctx, j):
    """(P,) tau (1 + e sin(2 N q + phi)) of joint j."""
    return ctx.loads[:, j] * (1 + p["e"][j] * np.sin(2 * p["N"][j] * ctx.q[:, j] + p["phi"][j]))


def ripple_draw(ctx, hw, rng):
    js = wrist_bends(ctx.chain)
    p = {"N": {j: int(rng.integers(80, 161)) for j in js}, "e": {j: float(rng.uniform(0.1, 0.3)) for j in js},
         "phi": {j: float(rng.uniform(0, 2 * np.pi)) for j in js}}
    p["c"] = _size_cols(ripple_features(p, ctx, hw), rng)
    return p


def ripple_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, ripple_twist(p, ctx, j)) for j in wrist_bends(ctx.chain)])


def ripple_apply(p, ctx, hw):
    return _amp_apply(p["c"], ripple_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- upstream toss
TOSS_J = 4  # axis 5


def inertial_torque(ctx, j=TOSS_J):
    """(P,) the torque [N m] on joint j of the masses beyond it decelerated by the joints before it at each move's
    end (mean move speed over the ramps)."""
    m, pos, body = ctx.mass_state
    ch, s = ctx.chain, ctx.session
    w, c = kin.joint_frames(ch, ctx.q)
    acc = -s.direction[:, :j] * s.speed[:, :j] / RAMP_S          # [rad/s^2, mm/s^2]
    on = body >= j + 1
    a = np.zeros(pos[:, on].shape)                                 # [mm/s^2]
    for k in range(j):
        col = np.cross(w[:, k, None], pos[:, on] - c[:, k, None]) if ch.revolute[k] else w[:, k, None]
        a += col * acc[:, k, None, None]
    F = -m[:, on, None] * a / 1000.0                               # [N]
    return np.einsum("pi,pi->p", np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F).sum(axis=1), w[:, j])


def toss_flank(p, ctx, j=TOSS_J):
    """(P,) the flank of joint j's lost motion after the toss and the settling."""
    tau, s = ctx.loads[:, j], ctx.session
    dyn = tau + inertial_torque(ctx, j)
    out, prev = np.empty(len(tau)), -s.direction[0, j]
    for i in range(len(tau)):
        f = prev
        if abs(dyn[i]) > p["f"]:
            f = np.sign(dyn[i])
        elif i == 0 or s.speed[i, j] > 0:
            f = -s.direction[i, j]
        if abs(tau[i]) > p["f"]:
            f = np.sign(tau[i])
        out[i] = prev = f
    return out


def toss_draw(ctx, hw, rng):
    p = {"f": float(rng.uniform(0.2, 0.4) * np.abs(ctx.loads[:, TOSS_J]).max())}
    p["b"] = float(_size_cols(toss_features(p, ctx, hw), rng)[0])
    return p


def toss_features(p, ctx, hw):
    return ctx.joint_feature(TOSS_J, toss_flank(p, ctx))[None]


def toss_apply(p, ctx, hw):
    return _amp_apply([p["b"]], toss_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- detent limiter
ROLL_J = 5  # axis 6


def roll_torque(p, ctx):
    """(P,) the tool's and the part's weight torque about the roll axis [N m]."""
    ch = ctx.chain
    w, c = kin.joint_frames(ch, ctx.q)
    pf, Rt = kin.flange(ch, ctx.q)
    g = np.array([0.0, 0.0, -kin.G])
    tool = pf + Rt @ np.asarray(p["tool_com_mm"], float)
    part = pf + Rt @ np.asarray(ctx.payload_com_mm, float)
    M = (np.cross((tool - c[:, ROLL_J]) / 1000.0, p["tool_kg"] * g)
         + np.cross((part - c[:, ROLL_J]) / 1000.0, ctx.session.payload_kg[:, None] * g))
    return np.einsum("pi,pi->p", M, w[:, ROLL_J])


def limiter_flank(p, ctx):
    t = roll_torque(p, ctx)
    return np.where(np.abs(t) > p["f"], np.sign(t), -ctx.session.direction[:, ROLL_J])


def limiter_draw(ctx, hw, rng):
    robot = ctx.chain.name if ctx.chain.name in TOOL_KG else "ur10"
    r, psi = rng.uniform(30.0, 100.0), rng.uniform(0, 2 * np.pi)
    p = {"tool_kg": float(rng.uniform(*TOOL_KG[robot])),
         "tool_com_mm": [r * np.cos(psi), r * np.sin(psi), float(rng.uniform(50.0, 150.0))]}
    p["f"] = float(rng.uniform(0.1, 0.3) * np.abs(roll_torque(p, ctx)).max())
    p["b"] = float(_size_cols(limiter_features(p, ctx, hw), rng)[0])
    return p


def limiter_features(p, ctx, hw):
    return ctx.joint_feature(ROLL_J, limiter_flank(p, ctx))[None]


def limiter_apply(p, ctx, hw):
    return _amp_apply([p["b"]], limiter_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- stepper errors
def stepper_joints(chain):
    return [3, 4]


def microstep_draw(ctx, hw, rng):
    js = stepper_joints(ctx.chain)
    p = {"N_g": {j: int(rng.integers(2, 6)) for j in js}}
    e, phi = rng.uniform(0.05, 0.10, len(js)) * STEP, rng.uniform(0, 2 * np.pi, len(js))
    p["amp"] = np.ravel([[e[i] * np.cos(phi[i]) / p["N_g"][j], e[i] * np.sin(phi[i]) / p["N_g"][j]]
                         for i, j in enumerate(js)]).tolist()
    return p


def microstep_features(p, ctx, hw):
    cols = []
    for j in stepper_joints(ctx.chain):
        K = 4 * N_R * p["N_g"][j]
        cols += [ctx.joint_feature(j, np.sin(K * ctx.q[:, j])), ctx.joint_feature(j, np.cos(K * ctx.q[:, j]))]
    return np.array(cols)


def microstep_apply(p, ctx, hw):
    return _amp_apply(p["amp"], microstep_features(p, ctx, hw))


def step_error(p, j, theta_m):
    """(P,) the motor's full-step position error [rad] at motor angle theta_m: once and twice per turn plus the
    tooth-by-tooth part (linear between the 50 teeth)."""
    a1, f1, a2, f2 = p["harm"][j]
    th = np.mod(theta_m, 2 * np.pi)
    teeth = np.asarray(p["teeth"][j], float)
    x = np.arange(N_R + 1) * 2 * np.pi / N_R
    return a1 * np.sin(th + f1) + a2 * np.sin(2 * th + f2) + np.interp(th, x, np.r_[teeth, teeth[0]])


def accuracy_draw(ctx, hw, rng):
    js = stepper_joints(ctx.chain)
    p = {"N_g": {j: float(rng.choice([1.5, 2.0, 2.5, 3.0])) for j in js}, "harm": {}, "teeth": {}}
    for j in js:
        p["harm"][j] = [float(rng.uniform(0.02, 0.04) * STEP), float(rng.uniform(0, 2 * np.pi)),
                        float(rng.uniform(0.02, 0.04) * STEP), float(rng.uniform(0, 2 * np.pi))]
        p["teeth"][j] = (rng.uniform(-1, 1, N_R) * rng.uniform(0.015, 0.03) * STEP).tolist()
    p["amp"] = [1.0] * len(js)
    return p


def accuracy_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, step_error(p, j, p["N_g"][j] * ctx.q[:, j]) / p["N_g"][j])
                     for j in stepper_joints(ctx.chain)])


def accuracy_apply(p, ctx, hw):
    return _amp_apply(p["amp"], accuracy_features(p, ctx, hw))
