"""Set R joint effects (new physics, not in sets A-Q): a pneumatic counterbalance on axis 2 fed straight from the
shop's compressed-air line, whose pressure saws between the compressor's cut-in and cut-out; a pneumatic slide on the
tool whose carriage stands extended or retracted as the process left it; the stick band of axes held by a proportional
position loop against their Coulomb friction; a cable lying on the floor, dragged out or pushed back by the tool;
incremental encoders homed anew on their reference cams after each power-up; and a spliced toothed belt driving axis 5.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* line pressure: pneumatic counterbalances (a cylinder between a pivot on the rotating column r1 from axis 2 and a rod
  eye on the upper arm r2 from it) carry a share of axis 2's gravity torque with the force p A, the lever r1 r2 sin(g) /
  |r1 - r2| (g the angle between the two arms; statics of a cylinder drive: Craig, *Introduction to Robotics*, ch. 5).
  Fed straight from the line (no regulator), p follows the compressor's load / unload band: the receiver's pressure
  rises while the compressor loads, falls while the shop draws air -- a sawtooth of 0.5-1 bar around 6-7 bar (Atlas
  Copco, *Compressed Air Manual*, 8th ed., 2015, on load / unload regulation and receiver sizing; pressure bands of
  0.5-1 bar, cycles of a few minutes). The gear twists by its linear compliance (:func:`hardware.torsion`) under the
  balancer's torque change. Balancer carrying 40-70 % of the session's largest axis-2 load at the mean pressure, r1
  150-250 mm, r2 300-500 mm, angle g 60-120 deg at q2 = 0, load phases 0.3-1 min, unload 1-3 min (assumed); kr16_like
  and tool_changer (ur10 has no balancer). The pressure is not logged. The true structure: one column (the sawtooth
  times the lever times the compliance), amplitude the force swing.
* slide shift: a tool carrying a guided pneumatic slide (an ejector, pusher or second gripper stage: compact slides of
  makers' catalogues) whose carriage of mass m stands extended or retracted by a stroke s as the process left it; the
  weight's moment changes by m g x s across the stroke and the gears twist by their linear compliance (the drives'
  catalogue stiffness, :func:`hardware.torsion`; statics, Craig ch. 5). Carriage 3-6 / 4-10 / 15-40 kg (ur10 /
  kr16_like / tool_changer), stroke 80-200 mm in a direction drawn in the tool frame, extended at 40-60 % of the poses
  (assumed; the valve state is not logged). The true structure: one column (the twist per kilogram), amplitude m.
* stick band: a position loop whose integral action is frozen inside the in-position window (against hunting; drives'
  integrator-freeze options, Ellis, *Control System Design Guide*, 4th ed., 2012, ch. 14) is proportional at
  standstill: the axis stops where the servo's stiffness K_s times the error meets the Coulomb friction T_f, short of
  the target on the side of the approach, e = (tau - d T_f) / K_s (Armstrong-Helouvry, Dupont & Canudas de Wit, "A
  survey of models, analysis tools and compensation methods for the control of machines with friction", Automatica
  30, 1994: the stick band of PD control). Axes 1, 4 and 6 (little gravity load), friction 2-5 % of the rated torque,
  the band's half-width T_f / K_s 0.5-1.5 arcmin at the output (assumed). The true structure: two columns per axis
  (load, -direction), amplitudes 1 / K_s and T_f / K_s.
* floor cable: a cable (a welding or supply cable) from the flange to an anchor on the floor lies partly on the floor;
  pulled out, the lying length slides and Coulomb friction mu w L_f holds it back (Coulomb's law of dry friction);
  pushed back, the cable piles up slack and carries nothing. The pull acts at the flange along the line to the anchor,
  and the joints twist by their linear compliance under tau = J^T F (statics, Craig ch. 5). The friction's side is the
  last change of the flange's distance to the anchor (the cable's last slide). Friction 10-40 / 20-80 / 50-200 N (ur10 /
  kr16_like / tool_changer: cables of 1-5 kg/m, 1-3 m lying, mu 0.3-0.6), the anchor 1.5-3 m from the base on the floor
  0-800 mm below it (assumed). The hanging part's weight is set G's catenary and is left out. The true structure: one
  column (the pulled poses' twist per newton), amplitude the friction force.
* rehoming: drives with incremental encoders find their zero at each power-up by moving onto a reference cam and
  latching its switch's edge; the edge repeats to a few micrometres on the cam (mechanical limit switches: precision
  switch data sheets, repeatability 1-10 um; Siemens SINUMERIK function manual, "Reference point approach", as
  recalled), so every homing sets the zero anew. The session's pauses power the cell down, each block starts from a new
  homing. Axes 1-3 of kr16_like (a retrofit with incremental encoders) and 1-4 of tool_changer (assumed), spread of a
  homing 5e-5 - 1.5e-4 rad on kr16_like (10-30 arcsec: a precision switch of 5-15 um on a cam of 100 mm radius), 1.5-4e-4
  rad and 0.02-0.08 mm on the stroke on tool_changer, whose heavy axes home on inductive proximity switches
  (repeatability about 1 % of a 2-8 mm switching distance, IEC 60947-5-2 / makers' data, as recalled; first the
  precision switch's spread and 0.01-0.04 mm on the stroke: R10 gained 29 % with the thermal model at 1.22x); ur10 has
  absolute encoders. The true structure: a column per later block and axis, amplitudes the offsets (the first block's
  offsets are the calibration's zero).
* belt splice: a toothed belt welded into a loop has a splice whose pitch is off by delta (open-length belts joined by
  welding or clamping; makers' notes on welded belts: the splice's pitch and strength below the belt's); while the
  splice lies on the tight span between the pulleys, that span is longer by delta and the driven pulley lags by delta /
  r (the positive drive of a toothed belt: Perneder & Osborne, *Handbook Timing Belts*, 2012). Axis 5 of kr16_like
  driven through a compact final belt stage from a motor in the forearm (assumed), pulley radius 50-80 mm, belt 400-700
  mm (first 40-80 mm and 600-1200 mm on tool_changer's axis 5 too, whose +-90 deg then never carried the splice onto the
  tight span: R13 gained nothing; a longer belt's splice leaves the span over the axis' travel), tight span 25-45 % of
  it, delta 0.03-0.1 mm spread over 10-20 mm of belt (assumed). The true structure: one column (the splice on the tight
  span, -1 / r), amplitude delta.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _compliance(hw):
    """(n,) each joint's linear compliance [rad/(N m) or mm/N]."""
    return np.array([hwm.torsion(d, 1.0, False) for d in hw["drives"]])


def _twist_features(ctx, dq):
    """(P, 3): the target's displacement for joint offsets dq (P, n)."""
    return np.einsum("pij,pj->pi", ctx.jac, dq)


# ------------------------------------------------------------------------------------------------ line pressure
BALANCER_ARMS = {"kr16_like", "tool_changer"}


def sawtooth(t, p):
    """(P,): the line's pressure per its band, -1/2 at cut-in .. +1/2 at cut-out: rising over the load phase, falling
    over the unload phase."""
    period = p["t_load_s"] + p["t_unload_s"]
    u = np.mod(np.asarray(t, float) + p["phase_s"], period)
    rise = u < p["t_load_s"]
    return np.where(rise, u / p["t_load_s"], 1 - (u - p["t_load_s"]) / p["t_unload_s"]) - 0.5


def lever_m(p, q2):
    """(P,): the balancer's lever about axis 2 [m]."""
    g = p["g0"] + q2
    r1, r2 = p["r1_mm"], p["r2_mm"]
    return r1 * r2 * np.sin(g) / np.sqrt(r1 ** 2 + r2 ** 2 - 2 * r1 * r2 * np.cos(g)) / 1000.0


def line_draw(ctx, hw, rng):
    if ctx.chain.name not in BALANCER_ARMS:
        return {}
    p = {"r1_mm": rng.uniform(150.0, 250.0), "r2_mm": rng.uniform(300.0, 500.0), "g0": np.deg2rad(rng.uniform(60, 120)),
         "t_load_s": rng.uniform(0.3, 1.0) * 60, "t_unload_s": rng.uniform(1.0, 3.0) * 60}
    p["phase_s"] = rng.uniform(0, p["t_load_s"] + p["t_unload_s"])
    tau = ctx.loads[:, 1]
    p["sign"] = -float(np.sign(tau.mean()))                         # the balancer holds the arm up
    F0 = rng.uniform(0.4, 0.7) * np.abs(tau).max() / np.abs(lever_m(p, ctx.q[:, 1])).max()
    p["dF_N"] = F0 * rng.uniform(0.5, 1.0) / 6.5                      # the band over a mean of 6.5 bar
    return p


def line_signal(p, ctx, hw):
    """(P,): axis 2's twist per newton of the force's swing [rad/N]."""
    c = _compliance(hw)[1]
    return c * p["sign"] * lever_m(p, ctx.q[:, 1]) * sawtooth(ctx.session.time_s, p)


def line_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 1] = p["dF_N"] * line_signal(p, ctx, hw)
    return Contribution(dq=dq)


def line_features(p, ctx, hw):
    return ctx.joint_feature(1, line_signal(p, ctx, hw))[None] if p else _empty(ctx)


# -------------------------------------------------------------------------------------------------- slide shift
SLIDE_KG = {"ur10": (3.0, 6.0), "kr16_like": (4.0, 10.0), "tool_changer": (15.0, 40.0)}


def slide_draw(ctx, hw, rng):
    d = rng.normal(size=3)
    share = rng.uniform(0.4, 0.6)
    return {"m_kg": rng.uniform(*SLIDE_KG[ctx.chain.name]), "p_ret": np.array([0.0, 0.0, rng.uniform(60.0, 150.0)]),
            "s_mm": d / np.linalg.norm(d) * rng.uniform(80.0, 200.0),
            "state": (rng.uniform(0, 1, len(ctx.q)) < share).astype(float)}


def slide_signal(p, ctx, hw):
    """(P, n): each joint's twist per kilogram of carriage [rad/kg or mm/kg] from retracted to the pose's state."""
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    body = np.array([ctx.chain.n])
    loads = [kin.gravity_loads(ctx.chain, ctx.q, np.ones(1), (fl + Rt @ x)[:, None], body)
             for x in (p["p_ret"], p["p_ret"] + p["s_mm"])]
    return p["state"][:, None] * (loads[1] - loads[0]) * _compliance(hw)


def slide_apply(p, ctx, hw):
    return Contribution(dq=p["m_kg"] * slide_signal(p, ctx, hw))


def slide_features(p, ctx, hw):
    return _twist_features(ctx, slide_signal(p, ctx, hw))[None]


# --------------------------------------------------------------------------------------------------- stick band
BAND_JOINTS = (0, 3, 5)


def band_draw(ctx, hw, rng):
    js = [j for j in BAND_JOINTS if ctx.chain.revolute[j]]
    T_f = rng.uniform(0.02, 0.05, len(js)) * np.array([hw["drives"][j]["T_rated"] for j in js])
    half = rng.uniform(0.5, 1.5, len(js)) * ph.ARCMIN
    return {"joints": js, "T_f": T_f, "K_s": T_f / half}


def band_signals(p, ctx):
    """(2m, P): per axis its load [N m] and minus its last motion's direction."""
    js = p["joints"]
    return np.concatenate([ctx.loads[:, js].T, -ctx.session.direction[:, js].T])


def band_amplitudes(p):
    return np.r_[1 / p["K_s"], p["T_f"] / p["K_s"]]


def band_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    m = len(p["joints"])
    s = band_amplitudes(p)[:, None] * band_signals(p, ctx)
    dq[:, p["joints"]] = (s[:m] + s[m:]).T
    return Contribution(dq=dq)


def band_features(p, ctx, hw):
    js = list(p["joints"]) * 2
    return np.array([ctx.joint_feature(j, s) for j, s in zip(js, band_signals(p, ctx))])


# -------------------------------------------------------------------------------------------------- floor cable
CABLE_N = {"ur10": (10.0, 40.0), "kr16_like": (20.0, 80.0), "tool_changer": (50.0, 200.0)}


def cable_draw(ctx, hw, rng):
    az, R = rng.uniform(0, 2 * np.pi), rng.uniform(1500.0, 3000.0)
    return {"anchor": np.array([R * np.cos(az), R * np.sin(az), -rng.uniform(0.0, 800.0)]),
            "F_N": rng.uniform(*CABLE_N[ctx.chain.name]), "s0": float(rng.choice([-1.0, 1.0]))}


def cable_pulled(p, ctx):
    """(P,): 1 where the cable was last pulled out (the flange's distance to the anchor grew), 0 where pushed back."""
    fl, _ = kin.flange(ctx.chain, ctx.q)
    dist = np.linalg.norm(fl - p["anchor"], axis=1)
    s = np.r_[p["s0"], np.sign(np.diff(dist))]
    return (s > 0).astype(float)


def cable_signal(p, ctx, hw):
    """(P, n): each joint's twist per newton of friction pull [rad/N or mm/N]."""
    fl, _ = kin.flange(ctx.chain, ctx.q)
    u = p["anchor"] - fl
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    J = kin.position_jacobian(ctx.chain, ctx.q, fl)                    # (P, 3, n) [mm/rad, mm/mm]
    tau = np.einsum("pin,pi->pn", J, u) * np.where(ctx.chain.revolute, 1e-3, 1.0)
    return cable_pulled(p, ctx)[:, None] * tau * _compliance(hw)


def cable_apply(p, ctx, hw):
    return Contribution(dq=p["F_N"] * cable_signal(p, ctx, hw))


def cable_features(p, ctx, hw):
    return _twist_features(ctx, cable_signal(p, ctx, hw))[None]


# ----------------------------------------------------------------------------------------------------- rehoming
HOMED = {"kr16_like": (0, 1, 2), "tool_changer": (0, 1, 2, 3)}
#: the spread of a homing [rad]: a precision switch on kr16_like's cams, inductive proximity switches on tool_changer's
HOME_SPREAD_RAD = {"kr16_like": (5e-5, 1.5e-4), "tool_changer": (1.5e-4, 4e-4)}


def block_of(session):
    """(P,): each pose's block, counted by the pauses (power-downs) before it."""
    return np.cumsum(session.gap_s < 0)


def home_draw(ctx, hw, rng):
    if ctx.chain.name not in HOMED:
        return {}
    js = list(HOMED[ctx.chain.name])
    B = int(block_of(ctx.session).max()) + 1
    lo, hi = HOME_SPREAD_RAD[ctx.chain.name]
    sig = np.where(ctx.chain.revolute[js], rng.uniform(lo, hi, len(js)), rng.uniform(0.02, 0.08, len(js)))
    off = rng.normal(0.0, 1.0, (B, len(js))) * sig
    off[0] = 0.0                                                       # the first homing: the calibration's zero
    return {"joints": js, "sigma": sig, "offset": off}


def home_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = p["offset"][block_of(ctx.session)]
    return Contribution(dq=dq)


def home_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    b = block_of(ctx.session)
    return np.array([ctx.joint_feature(j, (b == k).astype(float)) for k in range(1, len(p["offset"]))
                     for j in p["joints"]]).reshape(-1, len(ctx.q), 3)


def home_amplitudes(p):
    return p["offset"][1:].ravel()


# -------------------------------------------------------------------------------------------------- belt splice
SPLICE_ARMS = {"kr16_like": 4}


def splice_draw(ctx, hw, rng):
    if ctx.chain.name not in SPLICE_ARMS:
        return {}
    L = rng.uniform(400.0, 700.0)
    return {"joint": SPLICE_ARMS[ctx.chain.name], "r_mm": rng.uniform(50.0, 80.0), "L_mm": L,
            "span_mm": rng.uniform(0.25, 0.45) * L, "w_mm": rng.uniform(10.0, 20.0), "s0_mm": rng.uniform(0, L),
            "delta_mm": rng.uniform(0.03, 0.1)}


def splice_on_span(p, q):
    """(P,): the share of the splice's pitch error on the tight span (0..1, ramps over the splice's length) at output
    angle q."""
    s = np.mod(p["r_mm"] * np.asarray(q, float) + p["s0_mm"], p["L_mm"])
    return np.clip(np.minimum(s, p["span_mm"] - s) / p["w_mm"], 0.0, 1.0)


def splice_signal(p, ctx):
    return -splice_on_span(p, ctx.q[:, p["joint"]]) / p["r_mm"]


def splice_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["delta_mm"] * splice_signal(p, ctx)
    return Contribution(dq=dq)


def splice_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], splice_signal(p, ctx))[None] if p else _empty(ctx)
