"""Set Z joint and measurement effects (new physics, not in sets A-Y): the gears twisted by water trapped in a hollow
gripper boom, which runs to whichever end of the boom is lower; axis 2's gas balancer whose force follows its charge's
temperature, and so the outdoor air, by the gas law; the same balancer's rod-seal friction locked in against axis 2's
last motion; the laser tracker's tripod wound up by its head's slewing and held by the friction of its leg clamps; a
telescopic stage driven by a steel band winding on its drum in a spiral; and axis 1's output encoder misread as the
joint's bearing tilts under the arm's moment. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* water slug: an arm washed down daily (food handling) carries a hollow aluminium gripper boom, 350 mm along the tool's
  x with the target at its tip, that takes water in through an aged end-cap seal or cable gland (ingress against IP67 /
  IP69K seals as they age: IEC 60529 for the ratings; seal wear, e.g. Flitney, *Seals and Sealing Handbook*, 6th ed.,
  2014). The water runs to the boom's lower end: its centre of mass sits a puddle's half-length from that end once the
  boom tilts more than the puddle's depth over its length, and moves along the boom through the horizontal (modelled as
  a linear ramp over +-``RAMP`` of slope). Its weight loads the joints by tau = J^T m g (Craig, *Introduction to
  Robotics*, ch. 5) and they twist by the linear gear compliance of :mod:`hardware` (the soft wrist gears most). 0.4-1 /
  0.8-2 / 2-5 kg on ur10 / kr16_like / tool_changer (assumed), a puddle of a fifth to a third of the boom. Driven by the
  pose (logged); the water is not. Unlike set Q's fluid tank (a tank on the tool draining) or set W's swarf (a mass
  growing at the tool), the mass is constant and jumps from one end of the boom to the other as it passes the
  horizontal. The true structure: one column (the twist per kg), amplitude the water's mass [kg].
* balancer gas: axis 2's counterbalance is a sealed gas (nitrogen) spring acting between a pivot on the column r1 above
  axis 2 and an eye on the upper arm r2 along it: its moment arm r1 r2 sin psi / L, psi the upper arm's angle from the
  vertical, vanishes with the gravity torque at the upright arm (the geometry of heavy arms' balancers; Craig, ch. 5,
  for the statics), its force grows by a progression of 10-30 % over the stroke (gas-spring catalogues, e.g. Stabilus,
  as recalled). At fixed volume the charge's pressure goes as its absolute temperature (the ideal gas law), so the
  balancer's force is F_20 (T_gas + 273.15) / 293.15, F_20 its force at 20 degC, where it was set to carry 70-95 % of
  axis 2's largest gravity torque. The cylinder follows the air through a first-order lag of 20-50 min (its mass;
  Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5); the arm works in the open (tool_changer, a heavy
  machine at an outdoor site, measured with a weather-compensated tracker), and the session runs from a cold morning
  into the day or from noon into the evening, the air changing by 15-25 K. The gear twists by its compliance under the
  balancer's excess torque. Unlike set D's gas spring (its elastic law at one temperature) or set I's charge relaxation
  (the charge heated by its own compression), the outdoor air drives it. Driven by the air temperature (the
  ``temperature_c`` column) and the pose. The true structure: one column (the twist per N of F_20 times (T_gas - 20) /
  293.15), amplitude F_20 [N].
* balancer seal: the same kind of balancer's rod seal holds a friction force F_s of 8-20 % of its force (at the low
  speeds of a robot's axis 2, where a rod seal's breakaway friction is largest; seal friction of cylinders: Belforte,
  Manuello Bertetto & Mazza, *Pneumatic Actuating Systems for Automatic Equipment*, 2014; the friction of reciprocating
  rod seals, Nikas, Proc. IMechE J 224, 2010). At a stop the friction stays locked against the rod's last stroke, which
  axis 2's last motion set through the moment arm, so the gear carries an extra torque -F_s |a(psi)| d2 (d2 axis 2's
  last direction): the joint is held back against its last motion by an amount that vanishes at the balancer's dead
  centre (the upright arm) and is largest where its moment arm is. Unlike set N's balanced lash (the flank of a lost
  motion chosen under the balancer and gravity) or set E's friction windup (the joint's own seal), the seal is the
  balancer's and there is no lost motion. Driven by axis 2's direction (the ``dir2`` column) and angle. The true
  structure: one column (the twist per N of friction times -|a| d2), amplitude F_s [N].
* tripod windup: a laser tracker on a light, lockable tripod: its head's azimuth motor accelerates the head when it
  follows the target, the reaction torque twists the tripod's legs and hub about the vertical, and after each slew the
  friction in the legs' clamps and feet holds part of that twist (a torsional spring with a friction element: a play
  operator of the reaction; Al-Bender & Swevers, "Characterization of friction force dynamics", IEEE Control Syst. Mag.
  28(6), 2008, for the presliding hysteresis), so the instrument's frame stands turned by +-w about its vertical axis,
  by the sign of its last azimuth slew. w 25-60 urad (a few arcsec: a tracker's angular error budget is about 1 arcsec,
  the light tripod's hysteresis of the order of its stiffness' reaction; assumed). Unlike set G's tripod growth or set
  N's tripod tilt (thermal), this follows the instrument's last motion. Driven by the tracker's slews, i.e. by the
  measured points' order (the measured coordinates; no column logs the slews). The true structure: one column (the turn
  about the tracker's vertical by the slew's sign), amplitude w [rad].
* band spiral: tool_changer's telescopic stage pushed out by a steel band (a zip-band / spiral-band actuator) wound on a
  drum in a flat spiral: the band's radius on the drum grows by its thickness t each turn, so the travel s = r0 phi + t
  phi^2 / (4 pi) while the drive reads the drum's angle phi (the arc length of an Archimedean spiral; e.g. Bronshtein &
  Semendyayev, *Handbook of Mathematics*, curves). Calibrated at both ends of its 0-500 mm stroke S, the stage stands
  off by k (s^2 - S s), k = t / (4 pi r0^2); band 0.15-0.3 mm thick on a drum of 35-55 mm (assumed). Unlike set N's rope
  creep (slip on a sheave) or set T's rangefinder (a length meter's cyclic error), the error is the drum's spiral
  geometry, quadratic in the travel. The loop servoes the drum's reading. Driven by the stage's position (the ``q4_mm``
  column). Inert on arms without the stage. The true structure: one column (s^2 - S s on q4), amplitude k [1/mm].
* head tilt: axis 1's output encoder (a ring scale on the hollow output shaft, read by a head on the housing) sits an
  axial distance h from the centre of the joint's main bearing; the arm's gravity moment M tilts the output and the
  housing's seat against each other by c M (the bearing's and the base casting's tilting compliance: crossed-roller
  bearing catalogues' moment rigidity, e.g. THK RB series, as recalled), which moves the scale past the head at the
  head's place u_h (radius R) by h theta . u_h: the reading errs by -(h / R) c (M . u_h) (the kinematics of a tilted
  scale ring; HEIDENHAIN, *Angle encoders*, mounting tolerances and their errors, as recalled), and the loop servoes the
  reading. Sized so that the session's largest moment misreads it by 0.3-1 arcmin (h / R 1-3 on a long hollow shaft, a
  base casting compliant in tilt). Unlike set C's bearing tilt (the link itself tilting) this is a reading error of the
  vertical axis, driven by the horizontal moment along one housing-fixed direction. Driven by the pose and the payload
  (logged). The true structure: one column (axis 1 turned by M . u_h), amplitude -(h / R) c [rad/(N m)].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_w_joint import _features_of_dq
from sim2real_indep.effects_y_thermal import upper_arm

ARCMIN = np.pi / (180 * 60)


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def link_ends(ctx, li):
    """(2, P, 3) the start and end of link ``li`` in the base frame [mm]."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    b = int(ch.link_body[li])
    end = ch.links[:li + 1].sum(axis=0)
    start = end - ch.links[li]
    return np.array([np.einsum("pij,j->pi", R[:, b], x) + t[:, b] for x in (start, end)]), b


# ---------------------------------------------------------------------------------------------------- water slug
SLUG_KG = {"ur10": (0.4, 1.0), "kr16_like": (0.8, 2.0), "tool_changer": (2.0, 5.0)}
BOOM_MM = 350.0   # the hollow gripper boom along the tool's x; the target at its tip
RAMP = 0.05       # slope (sin) over which the water moves from one end to the other


def slug_position(p, ctx):
    """(P, 3) the water's centre of mass [mm] in the boom (base frame)."""
    pf, Rt = kin.flange(ctx.chain, ctx.q)
    x = Rt[:, :, 0]
    f = np.clip(x[:, 2] / RAMP, -1.0, 1.0)                         # +1: the tip is higher, the water at the root
    s = BOOM_MM * (0.5 - 0.5 * (1 - p["puddle"]) * f)              # its distance from the root along the boom
    return pf + s[:, None] * x


def slug_twist(p, ctx, hw):
    """(P, n) the twist per kg of water."""
    pos = slug_position(p, ctx)
    tau = kin.gravity_loads(ctx.chain, ctx.q, np.ones((len(ctx.q), 1)), pos[:, None], np.array([ctx.chain.n]))
    return tau * compliance(hw)


def slug_draw(ctx, hw, rng):
    return {"kg": rng.uniform(*SLUG_KG[ctx.chain.name]), "puddle": rng.uniform(0.2, 0.33)}


def slug_features(p, ctx, hw):
    return _features_of_dq(ctx, slug_twist(p, ctx, hw))[None]


def slug_apply(p, ctx, hw):
    return Contribution(dq=slug_twist(p, ctx, hw) * p["kg"])


# ------------------------------------------------------------------------------------------ the balancer's geometry
BAL_JOINT = 1
BAL_GEOM_MM = {"ur10": ((120, 180), (150, 250)), "kr16_like": ((200, 300), (250, 400)),
               "tool_changer": ((250, 400), (300, 500))}


def upright_angle(ctx):
    """(P,) the upper arm's angle psi from the vertical about axis 2 [rad]."""
    li = upper_arm(ctx.chain)
    (a, b), _ = link_ends(ctx, li)
    u = b - a
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    w = R[:, BAL_JOINT] @ ctx.chain.axes[BAL_JOINT]
    return np.arctan2(np.einsum("pi,pi->p", np.cross([0.0, 0.0, 1.0], u), w), u[:, 2])


def balancer_arm(p, ctx):
    """(P,) the balancer's signed moment arm [m] and (P,) its force per unit F_20 (the stroke's progression)."""
    psi = upright_angle(ctx)
    r1, r2 = p["r1_mm"], p["r2_mm"]
    L = np.sqrt(r1 ** 2 + r2 ** 2 - 2 * r1 * r2 * np.cos(psi))
    L0, L1 = abs(r2 - r1), r1 + r2
    prog = 1 + p["prog"] * (L - L0) / (L1 - L0)                     # a tension spring: more force as it is pulled
    return r1 * r2 * np.sin(psi) / L / 1000.0, prog


def balancer_draw_geometry(ctx, rng):
    (a1, b1), (a2, b2) = BAL_GEOM_MM[ctx.chain.name]
    p = {"r1_mm": rng.uniform(a1, b1), "r2_mm": rng.uniform(a2, b2), "prog": rng.uniform(0.1, 0.3), "sign": 1.0}
    arm, prog = balancer_arm(p, ctx)
    tb = arm * prog
    load = ctx.loads[:, BAL_JOINT]
    p["sign"] = -1.0 if np.dot(tb, load) > 0 else 1.0                # the balancer opposes gravity
    p["F_full"] = np.abs(load).max() / max(np.abs(tb).max(), 1e-9)  # the force that carries the largest torque
    return p


def balancer_torque(p, ctx):
    """(P,) the balancer's torque on axis 2 per N of F_20 [N m / N] (the gravity loads' sign convention)."""
    arm, prog = balancer_arm(p, ctx)
    return p["sign"] * arm * prog


# --------------------------------------------------------------------------------------------------- balancer gas
def gas_temperature(p, session):
    """(P,) the charge's temperature [degC]: the logged air through a first-order lag."""
    return ph.first_order_foh(session.time_s, session.air_c, p["tau_s"])


def gas_signal(p, ctx, hw):
    """(P,) axis 2's twist per N of F_20."""
    th = (gas_temperature(p, ctx.session) - 20.0) / 293.15
    return compliance(hw)[BAL_JOINT] * balancer_torque(p, ctx) * th


def gas_draw(ctx, hw, rng):
    p = balancer_draw_geometry(ctx, rng)
    p.update(share=rng.uniform(0.7, 0.95), tau_s=60.0 * rng.uniform(20.0, 50.0))
    p["F20_N"] = p["share"] * p["F_full"]
    return p


def gas_features(p, ctx, hw):
    return ctx.joint_feature(BAL_JOINT, gas_signal(p, ctx, hw))[None]


def gas_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, BAL_JOINT] = p["F20_N"] * gas_signal(p, ctx, hw)
    return Contribution(dq=dq)


# -------------------------------------------------------------------------------------------------- balancer seal
def seal_signal(p, ctx, hw):
    """(P,) axis 2's twist per N of seal friction: -|a| d2 through the gear's compliance."""
    arm, _ = balancer_arm(p, ctx)
    return -compliance(hw)[BAL_JOINT] * np.abs(arm) * ctx.session.direction[:, BAL_JOINT]


def seal_draw(ctx, hw, rng):
    p = balancer_draw_geometry(ctx, rng)
    p.update(share=rng.uniform(0.5, 0.9), mu=rng.uniform(0.08, 0.2))
    p["Fs_N"] = p["mu"] * p["share"] * p["F_full"]
    return p


def seal_features(p, ctx, hw):
    return ctx.joint_feature(BAL_JOINT, seal_signal(p, ctx, hw))[None]


def seal_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, BAL_JOINT] = p["Fs_N"] * seal_signal(p, ctx, hw)
    return Contribution(dq=dq)


# -------------------------------------------------------------------------------------------------- tripod windup
def slew_sign(p, ctx, hw):
    """(P,) the sign of the tracker's last azimuth slew (the first pose: the drawn one)."""
    tr = hw["tracker"]
    pt = ctx.target @ tr["R"].T + tr["t"]
    az = np.unwrap(np.arctan2(pt[:, 1], pt[:, 0]))
    s = np.sign(np.diff(np.r_[az[0], az]))
    s[0] = p["s0"]
    for k in range(1, len(s)):
        if s[k] == 0:
            s[k] = s[k - 1]
    return s


def windup_features(p, ctx, hw):
    """(1, P, 3) the target's displacement (base frame) for a unit turn of the tracker's frame about its vertical, by
    the sign of the last slew (the tracker at the origin of its frame)."""
    tr = hw["tracker"]
    z = tr["R"].T @ np.array([0.0, 0.0, 1.0])
    centre = -tr["R"].T @ tr["t"]
    s = slew_sign(p, ctx, hw)
    return (np.cross(z, ctx.target - centre) * s[:, None])[None]


def windup_draw(ctx, hw, rng):
    return {"w_rad": rng.uniform(25e-6, 60e-6), "s0": float(rng.choice([-1.0, 1.0]))}


def windup_apply(p, ctx, hw):
    return Contribution(displace=p["w_rad"] * windup_features(p, ctx, hw)[0])


# ---------------------------------------------------------------------------------------------------- band spiral
BAND_JOINT = 3
BAND_STROKE_MM = 500.0


def band_signal(ctx):
    s = ctx.q[:, BAND_JOINT]
    return s * s - BAND_STROKE_MM * s


def band_draw(ctx, hw, rng):
    t, r0 = rng.uniform(0.15, 0.3), rng.uniform(35.0, 55.0)
    return {"t_mm": t, "r0_mm": r0, "k": t / (4 * np.pi * r0 ** 2),
            "active": bool(ctx.chain.n > BAND_JOINT and not ctx.chain.revolute[BAND_JOINT])}


def band_features(p, ctx, hw):
    if not p["active"]:
        return _empty(ctx)
    return ctx.joint_feature(BAND_JOINT, band_signal(ctx))[None]


def band_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p["active"]:
        dq[:, BAND_JOINT] = p["k"] * band_signal(ctx)
    return Contribution(dq=dq)


# ------------------------------------------------------------------------------------------------------ head tilt
def head_signal(p, ctx):
    """(P,) the arm's gravity moment along the head's direction u_h (base frame, horizontal) [N m]."""
    u = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    return mount_moment(ctx) @ u


def head_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    err = rng.uniform(0.3, 1.0) * ARCMIN
    m = np.abs(head_signal({"psi": psi}, ctx)).max()
    return {"psi": psi, "err_rad": err, "amp": -err / max(m, 1e-9)}


def head_features(p, ctx, hw):
    return ctx.joint_feature(0, head_signal(p, ctx))[None]


def head_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, 0] = p["amp"] * head_signal(p, ctx)
    return Contribution(dq=dq)
