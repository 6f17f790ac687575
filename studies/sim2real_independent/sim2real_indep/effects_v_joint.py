"""Set V joint effects (new physics, not in sets A-U): the tool pulled by a coiled (self-retracting) cord from a
junction box on a column, a tension spring whose pull grows with the distance; the tool pulled by a festooned hose
hanging as a catenary of fixed length from a swivel on an overhead boom; a wrist axis whose drive shaft runs through the
previous wrist axis, so that its lost motion's flank follows its motor's net motion (its own move plus the coupling's
compensation); the pinned boom joints of tool_changer whose pins climb the walls of their worn bushes against the
rotation; output encoders of axes 2 and 3 read with a sub-divisional (interpolation) error; and tool_changer's
telescopic stage driven by a pinion on a rack of butted segments. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* coiled cord: a coiled (recoil) cord or hose is a close-wound helical tension spring: no extension below its initial
  tension F_i, then F = F_i + k (d - L0) along its chord (Wahl, *Mechanical Springs*, 2nd ed., 1963, ch. on extension
  springs; recoil-hose makers' pull-force data, as recalled). The tool's supply runs as a coiled cord from a junction
  box on a column 1.5-2.5 m from the base axis, 0.5-1.5 m above the base, closed length 0.3-0.6 m; k 5-15 / 30-80 /
  100-300 N/m and F_i 3-10 / 20-50 / 50-150 N on ur10 / kr16_like / tool_changer (a light cord, heavy recoil hose
  bundles; assumed). The joints take tau = J^T F at the flange (statics: Craig, *Introduction to Robotics*, ch. 5) and
  twist with the linear gear compliance of :mod:`hardware`; the gravity twist is set A's and left out. Unlike set K's
  vacuum hose (a constant pressure thrust while a part is held), the pull is elastic and always on. Nothing of it is
  logged. The true structure: one column (the twist per unit spring rate, F_i / k known), amplitude k.
* overhead festoon: the tool's supply hose hangs from a swivel on an overhead boom (balancer-free festoon) as a
  catenary of fixed length L between the swivel A and the flange B (Irvine, *Cable Structures*, 1981, ch. 1: span s,
  height difference h, sqrt(L^2 - h^2) = 2 a sinh(s / 2a), H = w a, the vertex at s/2 - a atanh(h / L)); the hose pulls
  the flange along its end tangent with H (horizontal) and H y'(B) (vertical), the joints take tau = J^T F and twist by
  the linear gear compliance of :mod:`hardware`. Swivel 2.2-3.2 m from the base axis, 1.8-2.8 m above the base, the
  hose 5-20 % longer than the session's longest chord; a hose bundle of 1-2.5 / 2-4 / 3-6 kg/m on ur10 / kr16_like /
  tool_changer (assumed). The true structure: one column (the twist per unit hose weight), amplitude w [N/m].
* coupled flank: in a wrist whose axis-j drive shaft runs inside axis j-1's (bevel-gear wrists: Rosheim, *Robot Wrist
  Actuators*, 1989, ch. 2-3), turning axis j-1 turns the axis-j gear's input, and the controller moves axis j's motor by
  c dq_{j-1} to hold axis j still (coupling compensation). The input crosses the lost motion in the direction of its
  net motion dq_j + c dq_{j-1}, so the output trails on that flank unless its load beats the drag (then the load's
  flank, :func:`physics.backlash_offset`). c of 0.5-1.5 in magnitude (sign as built), play 2-6 arcmin (a worn wrist;
  new RV / bevel stages 1-3 arcmin, maker data as recalled), drag 50-90 % of the axis' largest load (wrist axes carry
  little gravity torque). Axis 5 (inside axis 4) on kr16_like; none on ur10, whose joints each carry their own motor,
  and none on tool_changer (its axis 6 turns the target about itself: first tried there, 0.008 mm). The true structure: one column (the flank), amplitude b/2.
* journal climb: a pin turning in a plain bush with radial clearance c_r under a load W rolls up the bush's wall
  against its rotation until the friction angle phi = atan(mu) (the friction circle of a journal bearing: Shigley's
  *Mechanical Engineering Design*, ch. 12; Hamrock, *Fundamentals of Fluid Film Lubrication*, on dry / boundary
  journals), so the pin's centre -- and the whole distal arm -- sits c_r sin(phi) to the side of the load, on the side
  the last rotation chose. tool_changer's boom joints 2 and 3 (pinned in bronze bushes, horizontal axes under the
  distal weight): worn radial clearance 0.25-0.6 mm (wear limits of heavy-equipment pins, as recalled), mu 0.15-0.3
  (boundary-lubricated bronze on steel). None on ur10 and kr16_like (rolling bearings). The true structure: a column per
  joint (the sideways shift), amplitude c_r sin(phi) [mm].
* interpolation error: an incremental / absolute ring encoder interpolates within its signal period from two
  quadrature signals; their offsets, amplitude mismatch and phase error give errors once and twice per signal period
  (Heydemann, "Determination and correction of quadrature fringe measurement errors in interferometers", Applied
  Optics 20(19), 1981; HEIDENHAIN, "Interpolation error" in *Linear and angle encoders*, 2017: sub-divisional error).
  To first order: e = (o_s cos phi - o_c sin phi + eps/2 sin 2phi + delta/2 cos 2phi) / N, phi = N q. Magnetic ring
  encoders on the outputs of axes 2 and 3 (hollow-shaft magnetic rings with N = 128-256 periods per turn, assumed;
  offsets 0.5-2 %, amplitude mismatch 1-4 %, phase error 0.5-2 deg, uncompensated). The loop servoes the reading, so
  the joint stands off by -e. The true structure: four columns per axis (the harmonics), amplitudes the coefficients.
* rack segments: long-stroke linear axes are driven by a pinion on a rack of butted segments; each butt joint set
  without a joining gauge shifts all the following teeth by its gap error, and the pinion's runout adds a
  once-per-revolution error (DIN 3962 / ISO 1328 pitch deviations; rack makers' mounting instructions on joining
  segments with a gauge, as recalled). Segments 150-250 mm long, butt errors +-(0.06-0.15) mm, the pinion's runout
  0.02-0.05 mm times tan(20 deg) along the rack, pitch diameter 40-80 mm. The motor's encoder reads the axis, so the
  stage stands off by the rack's error. tool_changer's telescopic axis 4 (the only prismatic one); none on the others.
  The true structure: a column per butt joint within the stroke and two for the pinion, amplitudes the errors [mm].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.session import BOXES


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


# ------------------------------------------------------------------------------------------------ coiled cord
CORD = {"ur10": ((5.0, 15.0), (3.0, 10.0)), "kr16_like": ((30.0, 80.0), (20.0, 50.0)),
        "tool_changer": ((100.0, 300.0), (50.0, 150.0))}  # spring rate [N/m], initial tension [N]


def cord_pull(p, ctx):
    """(P, 3) the cord's pull on the flange per unit spring rate [N per N/m]: (F_i / k + d - L0) towards the anchor
    while stretched beyond its closed length, nothing when slack."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    d = p["A_m"] - B / 1000.0
    dist = np.linalg.norm(d, axis=1)
    mag = np.where(dist > p["L0_m"], p["Fi"] / p["k"] + dist - p["L0_m"], 0.0)
    return d / dist[:, None] * mag[:, None]


def cord_draw(ctx, hw, rng):
    az = rng.uniform(0, 2 * np.pi)
    r = rng.uniform(1.5, 2.5)
    (k, Fi) = CORD[ctx.chain.name]
    return {"A_m": np.array([r * np.cos(az), r * np.sin(az), rng.uniform(0.5, 1.5)]), "L0_m": rng.uniform(0.3, 0.6),
            "k": rng.uniform(*k), "Fi": rng.uniform(*Fi)}


def cord_twist(p, ctx, hw):
    """(P, n) the joints' twist per unit spring rate [rad per N/m]."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    J = kin.position_jacobian(ctx.chain, ctx.q, B)            # [mm/rad]
    return np.einsum("pij,pi->pj", J, cord_pull(p, ctx)) / 1000.0 * compliance(hw)


def cord_features(p, ctx, hw):
    return np.einsum("pij,pj->pi", ctx.jac, cord_twist(p, ctx, hw))[None]


def cord_apply(p, ctx, hw):
    return Contribution(dq=p["k"] * cord_twist(p, ctx, hw))


# ------------------------------------------------------------------------------------------- overhead festoon
FESTOON_W = {"ur10": (1.0, 2.5), "kr16_like": (2.0, 4.0), "tool_changer": (3.0, 6.0)}  # [kg/m]


def catenary_end_force(A, B, L, w=1.0):
    """(P, 3) force [N] a hanging cable of length L [m] and weight w [N/m] puts on its end B (P, 3) [m], its other end
    at A (3,) [m]; the parameter a solved by bisection of sqrt(L^2 - h^2) = 2 a sinh(s / 2a)."""
    d = B - A
    s = np.hypot(d[:, 0], d[:, 1])
    h = d[:, 2]
    target = np.sqrt(np.maximum(L ** 2 - h ** 2, 1e-12))
    lo, hi = np.full(len(s), -8.0), np.full(len(s), 8.0)  # log10 a [m]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        a = 10.0 ** mid
        f = 2 * a * np.sinh(np.minimum(s / (2 * a), 700.0)) - target   # decreasing in a
        lo, hi = np.where(f > 0, mid, lo), np.where(f > 0, hi, mid)
    a = 10.0 ** (0.5 * (lo + hi))
    x0 = s / 2 - a * np.arctanh(np.clip(h / L, -1 + 1e-12, 1 - 1e-12))
    slope = np.sinh((s - x0) / a)                                      # dy/dx at B, x from A towards B
    eh = np.where(s[:, None] > 0, np.c_[d[:, 0], d[:, 1], np.zeros(len(s))] / np.maximum(s, 1e-12)[:, None], 0.0)
    H = w * a
    return -H[:, None] * eh + (-H * slope)[:, None] * np.array([0.0, 0.0, 1.0])


def festoon_force(p, ctx):
    """(P, 3) the hose's pull on the flange per unit weight [N per N/m]."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    return catenary_end_force(p["A_m"], B / 1000.0, p["L_m"])


def festoon_draw(ctx, hw, rng):
    az = rng.uniform(0, 2 * np.pi)
    r = rng.uniform(2.2, 3.2)
    A = np.array([r * np.cos(az), r * np.sin(az), rng.uniform(1.8, 2.8)])
    B, _ = kin.flange(ctx.chain, ctx.q)
    chord = np.linalg.norm(B / 1000.0 - A, axis=1).max()
    return {"A_m": A, "L_m": chord * rng.uniform(1.05, 1.2), "w": rng.uniform(*FESTOON_W[ctx.chain.name]) * kin.G}


def festoon_twist(p, ctx, hw):
    """(P, n) the joints' twist per unit hose weight [rad per N/m]."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    J = kin.position_jacobian(ctx.chain, ctx.q, B)            # [mm/rad]
    tau = np.einsum("pij,pi->pj", J, festoon_force(p, ctx)) / 1000.0
    return tau * compliance(hw)


def festoon_features(p, ctx, hw):
    return np.einsum("pij,pj->pi", ctx.jac, festoon_twist(p, ctx, hw))[None]


def festoon_apply(p, ctx, hw):
    return Contribution(dq=p["w"] * festoon_twist(p, ctx, hw))


# ---------------------------------------------------------------------------------------------- coupled flank
COUPLED = {"kr16_like": (4, 3)}  # (the coupled axis, the axis it passes through), 0-based


def coupled_net_motion(p, session):
    """(P,) the sign of the coupled axis' motor motion into each pose (its own move plus c times the other's); the
    first pose and still motors keep the last sign."""
    j, i = p["joints"]
    dq = np.diff(session.q, axis=0, prepend=session.q[:1])
    net = np.sign(dq[:, j] + p["c"] * dq[:, i])
    net[0] = session.direction[0, j]
    for k in range(1, len(net)):
        if net[k] == 0:
            net[k] = net[k - 1]
    return net


def coupled_draw(ctx, hw, rng):
    if ctx.chain.name not in COUPLED:
        return {"joints": None}
    j, i = COUPLED[ctx.chain.name]
    c = rng.uniform(0.5, 1.5) * rng.choice([-1.0, 1.0])
    p = {"joints": (j, i), "c": c, "b": np.deg2rad(rng.uniform(2.0, 6.0) / 60.0)}
    tau = ctx.loads[:, j]
    drag = rng.uniform(0.5, 0.9) * np.abs(tau).max()
    net = coupled_net_motion(p, ctx.session)
    p.update(drag=drag, flank=np.where(np.abs(tau) > drag, np.sign(tau), -net))
    return p


def coupled_features(p, ctx, hw):
    if p["joints"] is None:
        return _empty(ctx)
    return ctx.joint_feature(p["joints"][0], p["flank"])[None]


def coupled_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p["joints"] is not None:
        dq[:, p["joints"][0]] = p["flank"] * p["b"] / 2
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------- journal climb
CLIMB_JOINTS = {"tool_changer": (1, 2)}


def climb_shift(p, ctx):
    """(m, P, 3) unit sideways shift of the distal arm per joint: horizontal, normal to the joint's axis, against its
    last rotation (-direction times axis x z)."""
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    out = []
    for j in p["joints"]:
        side = _unit(np.cross(w[:, j], [0.0, 0.0, 1.0]))
        out.append(-ctx.session.direction[:, j, None] * side)
    return np.array(out) if out else _empty(ctx)


def climb_draw(ctx, hw, rng):
    js = CLIMB_JOINTS.get(ctx.chain.name, ())
    c_r, mu = rng.uniform(0.25, 0.6, len(js)), rng.uniform(0.15, 0.3)
    return {"joints": js, "c_r_mm": c_r, "mu": mu, "e_mm": c_r * np.sin(np.arctan(mu))}


def climb_features(p, ctx, hw):
    return climb_shift(p, ctx)


def climb_apply(p, ctx, hw):
    if not p["joints"]:
        return Contribution()
    return Contribution(displace=np.einsum("k,kpi->pi", p["e_mm"], climb_shift(p, ctx)))


# --------------------------------------------------------------------------------------- interpolation error
INTERP_JOINTS = (1, 2)


def interp_signals(p, q):
    """(m, 4, P) the harmonics of each encoder's signal phase N q: cos, sin, sin 2, cos 2 (divided by N)."""
    out = []
    for k, j in enumerate(p["joints"]):
        ph_ = p["N"][k] * q[:, j]
        out.append(np.array([np.cos(ph_), np.sin(ph_), np.sin(2 * ph_), np.cos(2 * ph_)]) / p["N"][k])
    return np.array(out)


def interp_draw(ctx, hw, rng):
    js = [j for j in INTERP_JOINTS if ctx.chain.revolute[j]]
    m = len(js)
    o_s, o_c = (rng.uniform(0.005, 0.02, m) * rng.choice([-1.0, 1.0], m) for _ in range(2))
    eps = rng.uniform(0.01, 0.04, m) * rng.choice([-1.0, 1.0], m)
    delta = np.deg2rad(rng.uniform(0.5, 2.0, m)) * rng.choice([-1.0, 1.0], m)
    coef = -np.stack([o_s, -o_c, eps / 2, delta / 2], axis=1)        # the joint stands off by -e
    return {"joints": js, "N": rng.integers(128, 257, m).astype(float), "coef": coef}


def interp_features(p, ctx, hw):
    s = interp_signals(p, ctx.q)
    return np.array([ctx.joint_feature(j, s[k, h]) for k, j in enumerate(p["joints"]) for h in range(4)])


def interp_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    s = interp_signals(p, ctx.q)
    for k, j in enumerate(p["joints"]):
        dq[:, j] = p["coef"][k] @ s[k]
    return Contribution(dq=dq)


# ---------------------------------------------------------------------------------------------- rack segments
RACK_JOINT = 3  # tool_changer's telescopic axis


def rack_signals(p, q):
    """(K + 2, P) a step per butt joint in the stroke, then the pinion's once-per-revolution sin and cos [mm/mm]."""
    x = q[:, RACK_JOINT]
    steps = [(x >= s).astype(float) for s in p["joints_mm"]]
    ph_ = x / (np.pi * p["d_mm"]) * 2 * np.pi
    return np.array(steps + [np.sin(ph_ + p["phase"]), np.cos(ph_ + p["phase"])])


def rack_draw(ctx, hw, rng):
    if ctx.chain.name != "tool_changer":
        return {"joints_mm": None}
    lo, hi = BOXES["tool_changer"][0][RACK_JOINT], BOXES["tool_changer"][1][RACK_JOINT]
    seg = rng.uniform(150.0, 250.0)
    first = lo - rng.uniform(0.0, seg)
    joints = np.arange(first + seg, hi, seg)
    joints = joints[joints > lo]
    gaps = rng.uniform(0.06, 0.15, len(joints)) * rng.choice([-1.0, 1.0], len(joints))
    run = rng.uniform(0.02, 0.05) * np.tan(np.deg2rad(20.0))
    return {"joints_mm": joints, "gaps_mm": gaps, "d_mm": rng.uniform(40.0, 80.0), "phase": rng.uniform(0, 2 * np.pi),
            "amp": np.r_[gaps, run, 0.0]}


def rack_features(p, ctx, hw):
    if p["joints_mm"] is None:
        return _empty(ctx)
    s = rack_signals(p, ctx.q)
    return np.array([ctx.joint_feature(RACK_JOINT, row) for row in s])


def rack_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p["joints_mm"] is not None:
        dq[:, RACK_JOINT] = p["amp"] @ rack_signals(p, ctx.q)
    return Contribution(dq=dq)
