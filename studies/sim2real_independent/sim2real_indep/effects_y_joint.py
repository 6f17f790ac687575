"""Set Y joint effects (new physics, not in sets A-X): the gears twisted by the frost that a cold-store arm gathers on
its links through the session; the outputs of axes 2 and 3 held in some blocks by safety brakes whose armatures give
under the load; the output encoders of axes 1-3 driven through couplings with play, dragged across it by their own seal
friction; the lost motion of axes 2 and 3 crossed slowly under their load through stiff grease, still under way when the
point is taken; axis 1's secondary encoder driven by a pinion running eccentrically on its shaft; and the output
encoders of axes 3-5 turned by their own weight on their torque arms. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* frost load: an arm working in a cold store (-20 to -28 degC) gathers frost from the moist air carried in through the
  doors: water vapour desublimates on the cold surfaces at a rate set by the mass transfer coefficient and the
  vapour-density difference, h_m (rho_v,air - rho_v,sat(T_s)), steady while the door traffic is (Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 6, heat and mass transfer analogy; frost growth on cold surfaces:
  Hayashi, Aoki & Yuhara, "Study of frost formation based on a theoretical model of the frost layer", Heat Transfer Jpn.
  Res. 6, 1977). The mass grows linearly with the time since the session began, on each link in proportion to its length
  (its surface); 0.3-0.8 / 0.6-1.5 / 1.5-4 kg/h on ur10 / kr16_like / tool_changer (a few hundred g/m^2 h, assumed). Its
  weight loads the joints by tau = J^T m g (Craig, *Introduction to Robotics*, ch. 5) and they twist by the linear gear
  compliance of :mod:`hardware`. Driven by the time (the ``time_s`` column); the frost's mass is not logged. The
  session: blocks between pauses of 40-90 min (the arm idles while the store's trucks shuffle pallets). Unlike set W's
  swarf bin (chips collected at the tool while the spindle cuts) the mass grows on every link, with the time, not the
  machining. The true structure: one column (the twist per kg/h of frost times the hours so far), amplitude the rate
  [kg/h].
* output brake: axes 2 and 3 of a heavy arm carry spring-applied safety brakes on their outputs (gravity-loaded axes
  need a brake that holds the load without the gear: EN ISO 10218-1, 5.13; the "second brake" of heavy handling arms, as
  recalled); in an energy-saving brake mode the controller closes them at each pose and switches the servo off before
  the point is taken. The brake closes on the output where the gear's twist left it; as the servo lets go, the load
  passes from the gear to the brake, whose armature (a disc on leaf springs, a splined hub) gives by its own compliance
  c_b: the output moves a further c_b tau (the load path through two springs: Shigley's *Mechanical Engineering Design*,
  ch. 16 on brakes, and spring-applied brake makers' data, e.g. Mayr ROBA-stop, as recalled). c_b 0.2-0.5 times the
  gear's compliance (assumed). The brake mode is a setting of the measuring program: some blocks (at random, both kinds
  present) are measured braked, the others with the servo holding. Driven by the gravity torque (the pose and the logged
  payload) and the brake mode (not logged). The session: 3-5 blocks between pauses of 5-15 min. The true structure: one
  column per axis (the load in the braked blocks), amplitudes c_b [rad/(N m)].
* encoder coupling play: an output-side encoder is coupled to its shaft by a coupling whose hub has play (a loose clamp
  or a worn jaw-coupling spider: a few tenths of a degree at the hub radius are common after years; coupling makers'
  guidance, e.g. R+W / KTR catalogues, as recalled); the encoder's own shaft seal and bearings drag it, so the reading
  trails the joint across the play by d / 2 against the motion, and the loop, closed on that reading, drives the joint d
  / 2 past its target along the last motion (the gear's own lash, set A's, trails it). Play 0.5-2 arcmin at the joint on
  axes 1-3 (assumed). Driven by the last motion's direction (the ``dir`` columns). The true structure: one column per
  axis (the direction), amplitudes d / 2.
* squeeze film: the gears of axes 2 and 3 of an arm in a cold hall, their lost motion b (a worn cycloid or strain-wave
  stage, 0.7-2 arcmin) filled with stiff grease. A joint that stops while moving with its load stops on the trailing
  flank; its load then pushes the output across the lash to the other flank, but the grease between the teeth must be
  squeezed out first, which slows the crossing (squeeze-film damping: Hamrock, Schmid & Jacobson, *Fundamentals of Fluid
  Film Lubrication*, 2nd ed., 2004, ch. on squeeze films; the viscosity of a lithium grease grows tenfold or more from
  20 to 0 degC, as recalled); modelled as a first-order approach with tau 1.5-5 s (assumed), so the point taken after
  the dwell t_d catches the output at b / 2 (s_g + (s_0 - s_g) exp(-t_d / tau)), s_0 the trailing flank (-direction) and
  s_g the load's flank (the trailing one where the load is below 5 % of its largest, held by friction;
  :func:`physics.backlash_offset`). Unlike set H's cold grease (friction holding a lost motion that fades as the joints
  warm) the output is on its way across the lash when measured, and how far it got depends on the dwell (3-8 s; not a
  column of the data, though the time stamps bound it). Driven by the direction, the gravity torque and the dwell. The
  true structure: one column per axis, amplitudes b / 2.
* pinion runout: axis 1's absolute position read by a secondary encoder on a pinion that meshes with the ring (the
  "gauge pinion" of slewing drives); a pinion turning eccentrically on its shaft by e advances and retards by e / r_p
  once per its turn, and the output's reading (the pinion's angle over i = Z_r / Z_p) errs by (e / R) sin(i q1 + phi)
  (the kinematics of an eccentric gear: Smith, *Gear Noise and Vibration*, 2nd ed., 2003, ch. 2; Litvin & Fuentes, *Gear
  Geometry and Applied Theory*, 2004). Z_r 96-160, Z_p 14-20, e 20-50 um, R 100-200 mm. The loop servoes the reading, so
  the joint stands off by minus the error. Unlike set L's gauge pinion (the lost motion of its mesh) this is the
  pinion's runout, periodic in i q1. Driven by axis 1's angle (logged; the error is not). The true structure: two
  columns (sin and cos of i q1 on axis 1).
* torque arm: an output-side hollow-shaft encoder rides on the joint's shaft and is kept from turning by a torque arm (a
  leaf-spring stator coupling) anchored to the housing (encoder makers' mounting instructions, e.g. HEIDENHAIN, *Rotary
  encoders*, stator couplings, as recalled); the encoder body's centre of mass lies r off the axis (its connector and
  electronics), so its weight puts a torque m g r (u x g) . w on the torque arm, which turns the stator, and with it the
  reading, by that torque over the arm's torsional stiffness k (Craig, *Introduction to Robotics*, ch. 5, for the
  statics). The housing of axis j is on the body before it, so the torque changes with the joints before axis j: axis
  3's reading errs as a function of q2, axis 4's and 5's of q2 + q3 and q4 -- not of the axis' own angle. m 0.5-1.5 kg
  (large hollow-shaft encoders), r 20-50 mm, the arm's stiffness such that the full weight turns it by 0.8-2.5 arcmin (a
  thin leaf-spring arm, k of a few hundred N m/rad; assumed); axes 3-5 (revolute ones). The loop servoes the reading, so
  the joint stands off by minus the error. Driven by the other joints' angles (logged; the error is not). The true
  structure: one column per axis (the unit torque's turn of the joint), amplitudes -m g r / k.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import _features_of_dq

ARCMIN = np.pi / (180 * 60)


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# --------------------------------------------------------------------------------------------------- frost load
FROST_KG_H = {"ur10": (0.3, 0.8), "kr16_like": (0.6, 1.5), "tool_changer": (1.5, 4.0)}


def frost_shares(ctx):
    """(B,) the share of the frost on each of the arm's masses' links (by the link's length)."""
    L = np.array([np.linalg.norm(ctx.chain.links[i]) for i in ctx.mass_index[:-1]])
    return L / L.sum()


def frost_hours(session):
    """(P,) the hours since the session's first pose."""
    return (session.time_s - session.time_s[0]) / 3600.0


def frost_twist(ctx, hw):
    """(P, n) the twist per kg of frost spread over the links."""
    _, pos, body = ctx.mass_state
    share = np.broadcast_to(frost_shares(ctx), (len(ctx.q), len(body) - 1))
    tau = kin.gravity_loads(ctx.chain, ctx.q, share, pos[:, :-1], body[:-1])
    return tau * compliance(hw)


def frost_draw(ctx, hw, rng):
    return {"rate_kg_h": rng.uniform(*FROST_KG_H[ctx.chain.name])}


def frost_features(p, ctx, hw):
    return (_features_of_dq(ctx, frost_twist(ctx, hw)) * frost_hours(ctx.session)[:, None])[None]


def frost_apply(p, ctx, hw):
    return Contribution(dq=frost_twist(ctx, hw) * (p["rate_kg_h"] * frost_hours(ctx.session))[:, None])


# -------------------------------------------------------------------------------------------------- output brake
BRAKE_JOINTS = (1, 2)


def brake_states(nb, rng):
    """(nb,) 1 for a block measured with the brakes closed, 0 with the servo holding; both present."""
    st = (rng.random(nb) < 0.5).astype(float)
    if nb > 1 and st.min() == st.max():
        st[int(rng.integers(nb))] = 1.0 - st[0]
    return st


def brake_draw(ctx, hw, rng):
    C = compliance(hw)
    joints = tuple(j for j in BRAKE_JOINTS if ctx.chain.revolute[j])
    nb = int(block_index(ctx.session).max()) + 1
    return {"joints": joints, "braked": brake_states(nb, rng),
            "c_b": np.array([rng.uniform(0.2, 0.5) * C[j] for j in joints])}


def brake_signal(p, ctx):
    """(P, k) the joints' loads in the braked blocks, zero elsewhere."""
    on = p["braked"][block_index(ctx.session)]
    return np.array([ctx.loads[:, j] * on for j in p["joints"]]).T


def brake_features(p, ctx, hw):
    sig = brake_signal(p, ctx)
    return np.array([ctx.joint_feature(j, sig[:, i]) for i, j in enumerate(p["joints"])])


def brake_apply(p, ctx, hw):
    sig, dq = brake_signal(p, ctx), np.zeros_like(ctx.q)
    for i, j in enumerate(p["joints"]):
        dq[:, j] = p["c_b"][i] * sig[:, i]
    return Contribution(dq=dq)


# ------------------------------------------------------------------------------------------ encoder coupling play
PLAY_JOINTS = (0, 1, 2)


def play_draw(ctx, hw, rng):
    joints = tuple(j for j in PLAY_JOINTS if ctx.chain.revolute[j])
    return {"joints": joints, "play": rng.uniform(0.5, 2.0, len(joints)) * ARCMIN}


def play_features(p, ctx, hw):
    d = ctx.session.direction
    return np.array([ctx.joint_feature(j, d[:, j]) for j in p["joints"]])


def play_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for i, j in enumerate(p["joints"]):
        dq[:, j] = p["play"][i] / 2 * ctx.session.direction[:, j]
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------------- squeeze film
FILM_JOINTS = (1, 2)
FILM_FRICTION = 0.05


def film_sides(p, ctx):
    """(2, P, k) the flank each axis stopped on (trailing its motion) and the flank its load pushes it to (the same
    where the load is below the friction)."""
    tau, d = ctx.loads, ctx.session.direction
    s0 = np.array([-d[:, j] for j in p["joints"]]).T
    sg = np.array([np.where(np.abs(tau[:, j]) > FILM_FRICTION * np.abs(tau[:, j]).max(), np.sign(tau[:, j]), -d[:, j])
                   for j in p["joints"]]).T
    return s0, sg


def film_signal(p, ctx):
    """(P, k) the output's place in the lash per unit b / 2 when the point is taken, dwell_s after the stop."""
    s0, sg = film_sides(p, ctx)
    decay = np.exp(-ctx.session.dwell_s[:, None] / p["tau_s"][None, :])
    return sg + (s0 - sg) * decay


def film_draw(ctx, hw, rng):
    joints = tuple(j for j in FILM_JOINTS if ctx.chain.revolute[j])
    return {"joints": joints, "b": rng.uniform(0.7, 2.0, len(joints)) * ARCMIN,
            "tau_s": rng.uniform(1.5, 5.0, len(joints))}


def film_features(p, ctx, hw):
    sig = film_signal(p, ctx)
    return np.array([ctx.joint_feature(j, sig[:, i]) for i, j in enumerate(p["joints"])])


def film_apply(p, ctx, hw):
    sig, dq = film_signal(p, ctx), np.zeros_like(ctx.q)
    for i, j in enumerate(p["joints"]):
        dq[:, j] = p["b"][i] / 2 * sig[:, i]
    return Contribution(dq=dq)


# --------------------------------------------------------------------------------------------------- pinion runout
def pinion_draw(ctx, hw, rng):
    Zr, Zp = int(rng.integers(96, 161)), int(rng.integers(14, 21))
    e, R, phi = rng.uniform(0.020, 0.050), rng.uniform(100.0, 200.0), rng.uniform(0, 2 * np.pi)
    A = e / R
    # dq = -A sin(i q + phi) = -A cos(phi) sin(i q) - A sin(phi) cos(i q)
    return {"i": Zr / Zp, "Zr": Zr, "Zp": Zp, "e_mm": e, "R_mm": R, "A": A, "phi": phi,
            "amp": np.array([-A * np.cos(phi), -A * np.sin(phi)])}


def pinion_features(p, ctx, hw):
    x = p["i"] * ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, np.sin(x)), ctx.joint_feature(0, np.cos(x))])


def pinion_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, 0] = -p["A"] * np.sin(p["i"] * ctx.q[:, 0] + p["phi"])
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------------- torque arm
ARM_JOINTS = (2, 3, 4)


def arm_joints(chain):
    return tuple(j for j in ARM_JOINTS if chain.revolute[j])


def arm_offset(chain, j, psi):
    """The encoder body's offset direction (unit, across axis j, home frame of the housing's body j)."""
    w = chain.axes[j]
    u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return np.cos(psi) * u + np.sin(psi) * np.cross(w, u)


def arm_signal(p, ctx):
    """(P, k) the weight's torque about each axis of its encoder body per unit m r g: (R_j u x (-z)) . (R_j w_j)."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    down = np.array([0.0, 0.0, -1.0])
    cols = []
    for i, j in enumerate(p["joints"]):
        r = R[:, j] @ arm_offset(ctx.chain, j, p["psi"][i])
        w = R[:, j] @ ctx.chain.axes[j]
        cols.append(np.einsum("pi,pi->p", np.cross(r, down), w))
    return np.array(cols).T


def arm_draw(ctx, hw, rng):
    joints = arm_joints(ctx.chain)
    k = len(joints)
    m, r, A = rng.uniform(0.5, 1.5, k), rng.uniform(0.020, 0.050, k), rng.uniform(0.8, 2.5, k) * ARCMIN
    kc = m * kin.G * r / A                                   # the torque arm's stiffness [N m/rad]
    return {"joints": joints, "m_kg": m, "r_m": r, "k_Nm_rad": kc, "A": A, "psi": rng.uniform(0, 2 * np.pi, k),
            "amp": -A}


def arm_features(p, ctx, hw):
    sig = arm_signal(p, ctx)
    return np.array([ctx.joint_feature(j, sig[:, i]) for i, j in enumerate(p["joints"])])


def arm_apply(p, ctx, hw):
    sig, dq = arm_signal(p, ctx), np.zeros_like(ctx.q)
    for i, j in enumerate(p["joints"]):
        dq[:, j] = -p["A"][i] * sig[:, i]
    return Contribution(dq=dq)
