"""Set ZF joint effects (new physics, not in sets A-ZE): the tool held up by an elastic shock cord from an overhead
eye; gears whose bearings' preload and hence stiffness rise as the joints warm; an oil-bath gearbox whose output creeps
across its lash during the dwell against the oil's drag; a spring-centred lash; a repaired (welded and re-cut) sector of
axis 1's ring gear; and a wrist encoder disc that sags on its hub under its own weight. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* bungee cord: a rubber shock cord (Hooke's law over its working stretch, tension k (|d| - L0); Treloar, *The Physics of
  Rubber Elasticity*, 3rd ed., 1975, ch. 1: near-linear up to ~100 % strain) from an overhead eye 1.5-2.5 m above the
  base (within 0.6 reaches of the base axis) holds up the tool's hose; its tension grows with the distance to the eye
  and pulls along the line to it, twisting the main axes' gears by tau = J^T F (Craig, *Introduction to Robotics*, ch.
  5). Unlike set ZE's tether (a constant tension) or set F's balancer (a constant vertical pull), the pull's size is a
  spring's stretch. L0 0.5-0.9 of the shortest distance. Sized to 0.25-0.6 mm. On ur10 and tool_changer (first also
  on kr16_like, ZF19: the link model within 1.08x -- the near-vertical pull bends its long upper arm and forearm as
  gravity does). Driven by the pose (logged) and the cord
  (not logged). The true structure: one column per main revolute axis, amplitudes c_j k [rad].
* warm preload: a joint's angular-contact bearings and gear mesh gain preload as the shaft warms faster than the
  housing (thermally induced preload: Stein & Tu, "A state-space model for monitoring thermally induced preload in
  anti-friction spindle bearings of high-speed machine tools", ASME J. Dyn. Syst. 116, 1994), so the joint stiffens
  through the session: compliance c (1 - beta (1 - exp(-t / tau))), beta 0.3-0.6, tau 0.3-0.8 of the session. Unlike
  sets A-ZE's compliances (fixed laws of the torque) the compliance changes with the time since the session's start.
  Sized to 0.3-0.7 mm. Driven by the pose, payload and time (logged). The true structure: one column per main loaded
  axis, amplitudes c_j [rad/(N m)].
* viscous crossing: an oil-bath gearbox (the lash's gap filled with oil: squeeze-film drag, Hamrock, *Fundamentals of
  Fluid Film Lubrication*, 1994, ch. 17) on axes 2 and 3; the motion leaves the output on its trailing flank, and where
  the gravity torque points the other way it pushes the output across the lash during the dwell at a speed |tau| / b:
  the share crossed is min(1, t_d |tau| / B). Unlike the lash of sets A-ZE (a flank set at once by the load or the
  motion) the flank depends on the dwell time (logged in the time stamps). Half-play sized to 0.25-0.6 mm. The true
  structure: one column per axis, amplitudes the half-plays [rad].
* centring spring: a spring-centred coupling (an elastomer-centred jaw coupling or a centring-spring anti-backlash
  device: the output held in the middle of its clearance by a soft spring, Slocum, *Precision Machine Design*, 1992, ch.
  7) on axes 2 and 3: the gravity torque moves the output across the clearance against the spring, linearly up to
  T_c 5-12 % of the largest torque (a soft spring, its force a few per cent of the gravity load; first 20-40 %: ZF02 and
  ZF17 let the joint model's linear + hardening law within 1.07x and 1.08x -- so stiff a spring is a compliance), then it
  rests on the flank: flank = clip(tau / T_c, -1, 1); the motion's direction plays no part. Unlike sets A-ZE's lost motions (flank by motion or by load sign) the output sits anywhere inside the
  clearance. Sized to 0.25-0.6 mm. Driven by the pose and the payload (logged). The true structure: one column per
  axis, amplitudes the half-plays [rad].
* repaired sector: a large ring gear (axis 1) whose broken teeth were built up by welding and re-cut (gear repair
  practice; the sector's pitch deviations those of a local cumulative-pitch error, ISO 1328-1:2013), leaving a local
  transmission error over the sector: e exp(-((q - q_s) / w)^2), w 12-25 deg (a repair of 4-8 teeth of a ~100-tooth
  ring; first 6-15 deg, one or two teeth: ZF03 gained 9.5 %, few poses fell in so narrow a sector), the sector within
  the session's range of axis 1. Unlike sets A-ZE's periodic (per turn, per tooth, per motor turn) or stepwise transmission errors, the error
  is a single bump in angle. Sized to 0.25-0.6 mm. Driven by the angle (logged). The true structure: one column.
* sagging disc: a wrist encoder's large thin disc on a compliant hub (a hub clamped by an elastomer ring) sinks under
  its own weight by a few micrometres; its read head, fixed in the housing at angle psi, reads the tangential share of
  the sink as an angle: (delta / R) (g_h . t_psi), g_h the gravity in the housing's frame. Unlike set ZE's disc shift
  (the bearing's tilt under the arm's moment) or set ZD's fixed eccentricity, the error follows the housing's attitude
  to gravity. On the first revolute wrist axis; sized to 0.1-0.3 mm. On kr16_like (first also on tool_changer, ZF11:
  the joint model within 1.17x -- its axis-5 housing's attitude follows the wrist's gravity torque). Driven by the pose (logged). The true structure:
  two columns (the gravity's components across the axis), amplitudes (delta / R)(cos psi, sin psi) [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _main_joints, _size


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- bungee cord
def cord_force(p, ctx):
    """(P, 3) the cord's pull per unit stiffness [mm]: stretch times the unit vector to the eye."""
    d = np.asarray(p["eye_mm"], float) - ctx.target
    L = np.linalg.norm(d, axis=1, keepdims=True)
    return d / L * np.maximum(L - p["L0_mm"], 0.0)


def bungee_draw(ctx, hw, rng):
    reach = np.median(np.linalg.norm(ctx.target[:, :2], axis=1))
    a, r = rng.uniform(0, 2 * np.pi), reach * rng.uniform(0.0, 0.6)
    p = {"eye_mm": np.array([r * np.cos(a), r * np.sin(a), rng.uniform(1500.0, 2500.0)])}
    p["L0_mm"] = float(np.linalg.norm(p["eye_mm"] - ctx.target, axis=1).min() * rng.uniform(0.5, 0.9))
    p["c"] = _size(bungee_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(_main_joints(ctx.chain))), rng)
    return p


def bungee_features(p, ctx, hw):
    tau = np.einsum("pij,pi->pj", ctx.jac, cord_force(p, ctx)) / 1000.0
    return np.array([ctx.joint_feature(j, tau[:, j]) for j in _main_joints(ctx.chain)])


def bungee_apply(p, ctx, hw):
    return _amp_apply(p["c"], bungee_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- warm preload
def loaded_joints(chain):
    return [j for j in (1, 2) if chain.revolute[j]]


def preload_factor(p, session):
    """(P,) the compliance's share left: 1 - beta (1 - exp(-t / tau))."""
    t = session.time_s - session.time_s[0]
    return 1.0 - p["beta"] * (1.0 - np.exp(-t / p["tau_s"]))


def preload_draw(ctx, hw, rng):
    t = ctx.session.time_s
    p = {"beta": rng.uniform(0.3, 0.6), "tau_s": (t[-1] - t[0]) * rng.uniform(0.3, 0.8)}
    p["c"] = _size(preload_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(loaded_joints(ctx.chain))), rng, 0.3, 0.7)
    return p


def preload_features(p, ctx, hw):
    f = preload_factor(p, ctx.session)
    return np.array([ctx.joint_feature(j, ctx.loads[:, j] * f) for j in loaded_joints(ctx.chain)])


def preload_apply(p, ctx, hw):
    return _amp_apply(p["c"], preload_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- viscous crossing
def crossing_flank(p, ctx, j, B):
    """(P,) the flank: trailing the motion, moved towards the load's side by the share crossed in the dwell."""
    d = ctx.session.direction[:, j].astype(float)
    tau = ctx.loads[:, j]
    share = np.minimum(1.0, ctx.session.dwell_s * np.abs(tau) / B)
    return -d + (np.sign(tau) + d) * share


def crossing_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    dw = float(np.median(ctx.session.dwell_s))
    p = {"B": [float(np.abs(ctx.loads[:, j]).max() * dw * rng.uniform(1.0, 4.0)) for j in js]}
    p["half"] = _size(crossing_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(js)), rng)
    return p


def crossing_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, crossing_flank(p, ctx, j, B)) for j, B in zip(loaded_joints(ctx.chain), p["B"])])


def crossing_apply(p, ctx, hw):
    return _amp_apply(p["half"], crossing_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- centring spring
def centring_flank(tau, T_c):
    return np.clip(tau / T_c, -1.0, 1.0)


def centring_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    p = {"T_c": [float(np.abs(ctx.loads[:, j]).max() * rng.uniform(0.05, 0.12)) for j in js]}
    p["half"] = _size(centring_features(p, ctx, hw), rng.uniform(0.5, 1.5, len(js)), rng)
    return p


def centring_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, centring_flank(ctx.loads[:, j], T)) for j, T in
                     zip(loaded_joints(ctx.chain), p["T_c"])])


def centring_apply(p, ctx, hw):
    return _amp_apply(p["half"], centring_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- repaired sector
def sector_bump(p, q):
    return np.exp(-((q - p["q_s"]) / p["w"]) ** 2)


def sector_draw(ctx, hw, rng):
    q = ctx.q[:, 0]
    p = {"q_s": float(np.quantile(q, rng.uniform(0.3, 0.7))), "w": float(np.deg2rad(rng.uniform(12.0, 25.0)))}
    p["e"] = _size(sector_features(p, ctx, hw), [1.0], rng)
    return p


def sector_features(p, ctx, hw):
    return ctx.joint_feature(0, sector_bump(p, ctx.q[:, 0]))[None]


def sector_apply(p, ctx, hw):
    return _amp_apply(p["e"], sector_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- sagging disc
def disc_joint(chain):
    return [j for j in (3, 4, 5) if chain.revolute[j]][0]


def housing_gravity(ctx, j):
    """(P, 2) gravity's components across axis j in its housing's frame (the disc's plane)."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    g_h = np.einsum("pba,b->pa", R[:, j], np.array([0.0, 0.0, -1.0]))
    w = ctx.chain.axes[j]
    u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return np.stack([g_h @ u, g_h @ np.cross(w, u)], axis=1)


def sagdisc_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    p = {"joint": disc_joint(ctx.chain), "psi": psi}
    p["k"] = _size(sagdisc_features(p, ctx, hw), [np.cos(psi), np.sin(psi)], rng, 0.1, 0.3)
    return p


def sagdisc_features(p, ctx, hw):
    g = housing_gravity(ctx, p["joint"])
    return np.array([ctx.joint_feature(p["joint"], g[:, 0]), ctx.joint_feature(p["joint"], g[:, 1])])


def sagdisc_apply(p, ctx, hw):
    return _amp_apply(p["k"], sagdisc_features(p, ctx, hw))
