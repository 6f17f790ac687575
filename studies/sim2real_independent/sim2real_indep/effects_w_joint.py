"""Set W joint effects (new physics, not in sets A-V): the gears twisted by the chips a deburring spindle's suction
shroud collects during the machining cycles between the blocks; the gears twisted by a spring balancer hanging from a
trolley that runs freely along an overhead rail; the tracker's stable-probe trigger firing while the servo's final
creep is still under way; a part that slides in its gripper nest to the stop the last move's deceleration (or its
weight) chose; an output hub slipping on its shaft when an emergency stop's brakes catch the arm; and welding noise
miscounting the main axes' incremental output encoders during the production cycles. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* swarf shroud: a deburring / milling spindle with a suction shroud whose chip bin sits on the tool collects part of
  the chips it cuts; the material removal rate Q gives m(t) = rho Q eta E(t), E the machining time so far (removal rates
  of light deburring and of robotic milling, e.g. Pan et al., "Chatter analysis of robotic machining process", J. Mater.
  Process. Technol. 173, 2006, and robot milling practice, as recalled: a few to over a hundred cm^3/min). Collected 20-40
  / 20-60 / 100-300 g per minute of machining on ur10 / kr16_like / tool_changer (assumed), the bin 60-150 mm along the
  tool's z. Its weight loads the joints by tau = J^T m g (Craig, *Introduction to Robotics*, ch. 5) and they twist by
  the linear gear compliance of :mod:`hardware` (the rest of the gravity twist is set A's and left out). The machining
  periods are the session's exercise gaps (:func:`effects_w.session_options`); the bin's mass is not logged (the
  payload column holds the part only). Unlike set L's emptying cartridge, the mass grows only while the spindle cuts,
  block by block. The true structure: one column (the twist per kg at the bin times E(t)), amplitude the collection
  rate [kg/s].
* rail trolley: a constant-force spring balancer (tool / hose balancer; conical drum, nearly constant pull: balancer
  catalogues, as recalled) hanging from a trolley that rolls freely on an overhead rail (a C-rail or I-beam balancer
  track); the trolley rolls until the rope has no component along the rail, so it stands at the point of the rail
  nearest the clamp and the pull T acts from the flange towards that point (statics of a frictionless trolley). Rail
  1.8-2.8 m above the base, 0.3-1.2 m from the base axis, any heading; T 20-60 / 50-150 / 150-400 N. Unlike set F's
  balancer (a fixed hook over the forearm) the anchor follows the tool along the rail. Nothing of it is logged. The
  true structure: one column (the twist per N of pull), amplitude T.
* stable probe: a laser tracker's stable-probe mode triggers a measurement once the target has moved less than eps
  within a window dt_w (Leica / FARO tracker manuals, "stable probe" / "stationary" measurement settings, as recalled);
  a position loop settles its last error e0 exp(-t / tau) along the move's final direction (a first-order closed loop),
  so the measurement is taken a distance eps / (1 - exp(-dt_w / tau)) short of the pose, behind it along the target's
  approach direction J dq. eps 0.03-0.08 mm, dt_w 0.5-1 s, tau 0.5-2 s (assumed). The direction is that of the last
  move (logged only as the joints' signs). The true structure: one column (minus the approach's unit vector), amplitude
  the lag [mm].
* part slide: a part located in its gripper nest with a clearance c slides to one stop when the last move's deceleration
  m a beats the friction mu m g (it keeps moving forwards as the gripper stops), or to the low stop when its weight's
  component along the nest beats friction (Coulomb friction on an inclined plane); otherwise it stays where it was.
  The nest opens along the tool's x, clearances 0.1-0.5 mm (loose locating for a robot gripper, assumed), mu 0.15-0.35,
  the deceleration enough when the approach has at least half its length along the nest. The target sits on the part.
  The true structure: one column (the tool's x times the stop side), amplitude c / 2.
* hub slip: the output flanges of the main axes are clamped on their shafts by keyless locking assemblies (friction
  bushes; Ringfeder / Tollok catalogue data, as recalled); an emergency stop in the production between two blocks
  catches the arm on its brakes (stop category 0, IEC 60204-1) and the inertia torque beats the clamp's slip torque, so
  the link turns on its shaft by a small angle that the motor encoder does not see (a zero shift; the collision-robust
  design that slips on purpose: overload clutches). Axes 2 and 3, slips of 0.008-0.025 deg either way, at one gap
  after the second block and before the last (assumed). Not logged. The true structure: one column per axis (the
  step), amplitudes the slips [rad].
* EMI counts: arc-welding currents (hundreds of A with high-frequency ignition) couple into unshielded or badly
  grounded encoder lines and add or drop quadrature counts (encoder makers' EMC guidance on shielding and differential
  lines, e.g. HEIDENHAIN, *Interfaces of HEIDENHAIN encoders*; Renishaw, installation guides, as recalled); an
  incremental output encoder of 2^16 counts per turn on axes 1-3 gains a net of N(0, s) counts, s 0.7-2, in each welding
  period between the blocks, and the loop servoes the miscounted reading, so the joint stands off by the running sum.
  Not logged. The true structure: one column per axis and block after the first, amplitudes the offsets [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_u_joint import block_index


def _twist(ctx, hw, point, F):
    """(P, n) the joints' twist [rad or mm] under a force F (P, 3) [N] at ``point`` (P, 3) [mm] on the last body."""
    J = kin.position_jacobian(ctx.chain, ctx.q, point)                 # [mm/rad] or [mm/mm]
    tau = np.einsum("pij,pi->pj", J, F) * np.where(ctx.chain.revolute, 1e-3, 1.0)   # [N m] or [N]
    return tau * compliance(hw)


def _features_of_dq(ctx, dq):
    return np.einsum("pij,pj->pi", ctx.jac, dq)


def approach(ctx):
    """(P, 3) the unit direction of the target's last move (J dq at the pose); zero at the first pose or no move."""
    dq = np.diff(ctx.q, axis=0, prepend=ctx.q[:1])
    v = np.einsum("pij,pj->pi", ctx.jac, dq)
    n = np.linalg.norm(v, axis=1, keepdims=True)
    return np.where(n > 1e-9, v / np.maximum(n, 1e-12), 0.0)


# ----------------------------------------------------------------------------------------------- swarf shroud
SWARF_G_PER_MIN = {"ur10": (20.0, 40.0), "kr16_like": (20.0, 60.0), "tool_changer": (100.0, 300.0)}


def machining_s(session):
    """(P,) the machining time [s] before each pose (the exercise gaps so far)."""
    return np.cumsum(np.maximum(session.gap_s, 0.0))


def swarf_draw(ctx, hw, rng):
    return {"bin_mm": np.array([0.0, 0.0, rng.uniform(60.0, 150.0)]),
            "rate": rng.uniform(*SWARF_G_PER_MIN[ctx.chain.name]) / 1000.0 / 60.0}       # [kg/s]


def swarf_twist(p, ctx, hw):
    """(P, n) the twist per kg of chips in the bin [rad/kg]."""
    pt = kin.target(ctx.chain, ctx.q, p["bin_mm"])
    return _twist(ctx, hw, pt, np.broadcast_to([0.0, 0.0, -kin.G], pt.shape))


def swarf_features(p, ctx, hw):
    return (_features_of_dq(ctx, swarf_twist(p, ctx, hw)) * machining_s(ctx.session)[:, None])[None]


def swarf_apply(p, ctx, hw):
    return Contribution(dq=swarf_twist(p, ctx, hw) * (p["rate"] * machining_s(ctx.session))[:, None])


# ----------------------------------------------------------------------------------------------- rail trolley
TROLLEY_N = {"ur10": (20.0, 60.0), "kr16_like": (50.0, 150.0), "tool_changer": (150.0, 400.0)}


def trolley_pull(p, ctx):
    """(P, 3) the unit pull on the flange, towards the rail's point nearest the flange."""
    B, _ = kin.flange(ctx.chain, ctx.q)
    e, o = p["e"], p["o_mm"]
    A = o + np.outer((B - o) @ e, e)
    d = A - B
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def trolley_draw(ctx, hw, rng):
    psi = rng.uniform(0, np.pi)
    e = np.array([np.cos(psi), np.sin(psi), 0.0])
    n = np.array([-e[1], e[0], 0.0])
    o = n * rng.uniform(300.0, 1200.0) * rng.choice([-1.0, 1.0]) + np.array([0.0, 0.0, rng.uniform(1800.0, 2800.0)])
    return {"e": e, "o_mm": o, "T": rng.uniform(*TROLLEY_N[ctx.chain.name])}


def trolley_twist(p, ctx, hw):
    B, _ = kin.flange(ctx.chain, ctx.q)
    return _twist(ctx, hw, B, trolley_pull(p, ctx))


def trolley_features(p, ctx, hw):
    return _features_of_dq(ctx, trolley_twist(p, ctx, hw))[None]


def trolley_apply(p, ctx, hw):
    return Contribution(dq=p["T"] * trolley_twist(p, ctx, hw))


# ------------------------------------------------------------------------------------------------ stable probe
def stable_lag(eps, dt_w, tau):
    """The distance [mm] still to creep when the stability test passes: eps / (1 - exp(-dt_w / tau))."""
    return eps / (1.0 - np.exp(-dt_w / tau))


def stable_draw(ctx, hw, rng):
    eps, dt_w, tau = rng.uniform(0.03, 0.08), rng.uniform(0.5, 1.0), rng.uniform(0.5, 2.0)
    return {"eps": eps, "dt_w": dt_w, "tau": tau, "lag": float(stable_lag(eps, dt_w, tau))}


def stable_features(p, ctx, hw):
    return -approach(ctx)[None]


def stable_apply(p, ctx, hw):
    return Contribution(displace=p["lag"] * stable_features(p, ctx, hw)[0])


# -------------------------------------------------------------------------------------------------- part slide
def slide_side(p, ctx):
    """(P,) the stop (+1 / -1 along the tool's x) the part rests on: downhill when its weight beats friction, else
    forwards when the approach ran along the nest, else where it was."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    x = Rt[:, :, 0]
    g_along = -x[:, 2]                                    # unit gravity (0, 0, -1) along the nest
    u_along = np.einsum("pi,pi->p", approach(ctx), x)
    side = np.zeros(len(x))
    last = p["s0"]
    for k in range(len(x)):
        if abs(g_along[k]) > p["mu"]:
            last = np.sign(g_along[k])
        elif abs(u_along[k]) > 0.5:
            last = np.sign(u_along[k])
        side[k] = last
    return side


def slide_draw(ctx, hw, rng):
    return {"c_mm": rng.uniform(0.1, 0.5), "mu": rng.uniform(0.15, 0.35), "s0": float(rng.choice([-1.0, 1.0]))}


def slide_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (Rt[:, :, 0] * slide_side(p, ctx)[:, None])[None]


def slide_apply(p, ctx, hw):
    return Contribution(displace=p["c_mm"] / 2 * slide_features(p, ctx, hw)[0])


# ---------------------------------------------------------------------------------------------------- hub slip
HUB_JOINTS = (1, 2)


def hub_step(p, session):
    """(P,) 1 from the block after the emergency stop on."""
    return (block_index(session) >= p["block"]).astype(float)


def hub_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    block = 2 + int(rng.integers(max(nb - 3, 1)))                 # a gap inside the session, blocks before and after
    slip = np.deg2rad(rng.uniform(0.008, 0.025, len(HUB_JOINTS))) * rng.choice([-1.0, 1.0], len(HUB_JOINTS))
    return {"joints": HUB_JOINTS, "block": block, "slip": slip}


def hub_features(p, ctx, hw):
    s = hub_step(p, ctx.session)
    return np.array([ctx.joint_feature(j, s) for j in p["joints"]])


def hub_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for j, a in zip(p["joints"], p["slip"]):
        dq[:, j] = a * hub_step(p, ctx.session)
    return Contribution(dq=dq)


# -------------------------------------------------------------------------------------------------- EMI counts
EMI_JOINTS, EMI_COUNTS = (0, 1, 2), 2 ** 16


def emi_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    s = rng.uniform(0.7, 2.0)
    counts = np.rint(rng.normal(0, s, (nb - 1, len(EMI_JOINTS))))
    off = -np.cumsum(counts, axis=0) * 2 * np.pi / EMI_COUNTS     # the joint stands off by minus the miscount
    return {"joints": EMI_JOINTS, "sigma": s, "counts": counts, "offset": off}


def emi_features(p, ctx, hw):
    b = block_index(ctx.session)
    nb = len(p["offset"]) + 1
    return np.array([ctx.joint_feature(j, (b == k).astype(float)) for k in range(1, nb) for j in p["joints"]]
                    ).reshape(-1, len(ctx.q), 3) if nb > 1 else np.zeros((0, len(ctx.q), 3))


def emi_apply(p, ctx, hw):
    b = block_index(ctx.session)
    dq = np.zeros_like(ctx.q)
    for k in range(1, len(p["offset"]) + 1):
        for i, j in enumerate(p["joints"]):
            dq[b == k, j] += p["offset"][k - 1, i]
    return Contribution(dq=dq)
