"""Set H joint effects (new physics, not in sets A-G): a controller's deflection compensation working with load data
that does not match the payload actually carried; polymer strain-wave gears whose twist creeps under the sustained
load; a joint-error compensation table left active after the reducer it was measured on was exchanged; the coupling
factors of a coupled wrist configured rounded; the lost motion of a coupled wrist train, whose flank follows the
train's own last motion rather than the joint's. Same protocol as :mod:`effects_joint` (``draw``, ``apply``,
``features``).

Sources:

* load data: accuracy options model the joint deflection under the gravity load and add it to the command (ABB
  "Absolute Accuracy", KUKA "positionally accurate robot" options, as recalled; Nubiola & Bonev, "Absolute
  calibration of an ABB IRB 1600 robot using a laser tracker", RCIM 29, 2013, for the stiffness model); the model
  uses the controller's mass model (the robot file's masses) and the load data entered for the tool (mass and
  centre of mass: KUKA / ABB "load data" that must be entered or identified, as recalled). Here the load data are
  those of the heaviest load of the session, its centre of mass off the true one by N(0, 15 mm), and the model's
  stiffness off the true one by U(-15, 15) % (identification error; assumed): the joint is off by
  c tau_true - (1 + eps) c tau_model (linear gear stiffness of :mod:`hardware`).
* polymer gear creep: strain-wave gears with polymer flexsplines / circular splines (low-cost cobot joints, e.g.
  the igus ReBeL's iglidur gears, as recalled) creep under a sustained torque; polymer creep modelled as a standard
  linear solid (Findley, Lai & Onaran, *Creep and Relaxation of Nonlinear Viscoelastic Materials*, 1976; Crawford,
  *Plastics Engineering*, 3rd ed., 1998: creep modulus after hours 50-80 % of the short-term one): twist =
  c0 tau + c1 x, tau_c dx/dt = tau - x; c0 the linear compliance of :mod:`hardware` (short-term stiffness taken as
  the metal gear's, assumed), c1 = 0.3-0.8 c0, tau_c 10-40 min (assumed); the strain-wave joints (all of ur10, the
  wrists of the others). The load is held through pauses (brakes on at the last pose), the session mean during
  production; the creep state starts at the session's mean load.
* stale compensation table: controllers compensate a joint's positioning error with a table of corrections at
  fixed intervals, interpolated linearly (pitch-error / "nonlinear axis error" compensation of CNC and robot
  controllers; measured per ISO 230-2 on machine axes, as recalled). After the reducer is exchanged, a table left
  active applies the old reducer's error to the new one: the joint is off by minus the old error sampled on the
  grid and interpolated. Old error: harmonics 1-6 of the output turn (amplitudes ~1 / k, 0.5-1.2 arcmin in all;
  Ghorbel, Gandhi & Alpeter, J. Mech. Des. 123(1), 2001, for strain-wave gears; Blanche & Yang, ASME JMTAD 111(3),
  1989, for cycloid drives) and, on cycloid axes, the pin order (30-40 per turn, 0.15-0.4 arcmin) that the grid
  aliases. Grid 5-10 deg (assumed), axes 1-3. The new reducer's own error is left out (set A's gear kind).
* wrist coupling: in a wrist whose motors sit in the forearm, the train of axis 5 runs through axis 4 and that of
  axis 6 through axes 4 and 5, so motor angle = N (q_j + sum_k c_jk q_k) (the actuator-to-joint coupling matrix:
  Craig, *Introduction to Robotics*, ch. 8; the PUMA 560's wrist: Armstrong, Khatib & Burdick, ICRA 1986); c_jk
  ratios of tooth counts Z_a / Z_b (17-60 teeth), configured rounded to three decimals (assumed): the joint is off
  by (c_cfg - c) q_k. Only the arms with motor-driven coupled wrists (kr16_like: axes 4-6; tool_changer: axes 5-6;
  ur10 has a drive in every joint).
* coupled wrist lash: a final bevel stage of the wrist train with backlash 3-8 arcmin (spiral bevel sets of
  wrist units, AGMA 2005 / ISO 23509 backlash ranges, as recalled; assumed) rests on the flank its gravity load
  pushes it to when that beats the train's drag (20-50 % of the session's largest load, assumed), else on the flank
  of the train's last motion, sign of d(q_j + sum_k c_jk q_k) -- not of dq_j (Nordin & Gutman, Automatica 38,
  2002, for the dead zone; flank logic as :func:`physics.backlash_offset`); the joints whose train is coupled.
Imports nothing of tolalloc.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution, Ctx


def _stack(cols, P):
    return np.array(cols) if cols else np.zeros((0, P, 3))


# ------------------------------------------------------------------------------------------------ load data
def load_draw(ctx, hw, rng):
    return {"m_prog_kg": float(ctx.session.payload_kg.max()),
            "com_prog_mm": ctx.payload_com_mm + rng.normal(0.0, 15.0, 3),
            "eps": rng.uniform(-0.15, 0.15, ctx.chain.n)}


def model_loads(p, ctx):
    """Joint loads (P, n) [N m / N] of the controller's model: the file's masses and the programmed load data."""
    ch = ctx.chain
    sess = replace(ctx.session, payload_kg=np.full(len(ctx.q), p["m_prog_kg"]))
    return Ctx(ch, sess, ch.masses, ch.mass_com, ctx.mass_link, p["com_prog_mm"], ctx.probe_mm).loads


def load_apply(p, ctx, hw):
    tau_m = model_loads(p, ctx)
    dq = np.array([hwm.torsion(d, ctx.loads[:, j], False) - (1 + p["eps"][j]) * hwm.torsion(d, tau_m[:, j], False)
                   for j, d in enumerate(hw["drives"])]).T
    return Contribution(dq=dq)


def load_features(p, ctx, hw):
    tau_m = model_loads(p, ctx)
    cols = [ctx.joint_feature(j, s[:, j]) for j in range(ctx.chain.n) for s in (ctx.loads, tau_m)
            if np.abs(ctx.loads[:, j]).max() > 1e-9]
    return _stack(cols, len(ctx.q))


# ------------------------------------------------------------------------------------------- polymer creep
def creep_state(ctx, X, tau_s):
    """State x (P, d) of tau_s dx/dt = X - x at the measurements, X (P, d) held over each dwell, ramped (its mean)
    over each move, the last pose's over pauses and the session mean over production periods; x starts at the
    session mean."""
    s = ctx.session
    prev = np.vstack([X[:1], X[:-1]])
    gap = np.where((s.gap_s > 0)[:, None], X.mean(axis=0), prev)
    u = np.stack([gap, (prev + X) / 2, X], axis=1).reshape(-1, X.shape[1])
    dur = np.stack([np.abs(s.gap_s), s.move_s, s.dwell_s], axis=1).ravel()
    x, out = X.mean(axis=0), np.zeros_like(u)
    for k, (dt, uk) in enumerate(zip(dur, u)):
        x = uk + (x - uk) * np.exp(-dt / tau_s)
        out[k] = x
    return out[2::3]


def gcreep_draw(ctx, hw, rng):
    joints = [j for j, d in enumerate(hw["drives"]) if d["kind"] == "HD"]
    return {"joints": joints, "ratio": rng.uniform(0.3, 0.8, len(joints)), "tau_s": rng.uniform(10, 40) * 60}


def gcreep_apply(p, ctx, hw):
    dq = np.array([hwm.torsion(d, ctx.loads[:, j], False) for j, d in enumerate(hw["drives"])]).T
    x = creep_state(ctx, ctx.loads[:, p["joints"]], p["tau_s"])
    for k, j in enumerate(p["joints"]):
        dq[:, j] += p["ratio"][k] * hwm.torsion(hw["drives"][j], x[:, k], False)
    return Contribution(dq=dq)


def gcreep_features(p, ctx, hw):
    x = creep_state(ctx, ctx.loads[:, p["joints"]], p["tau_s"])
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)]
    cols += [ctx.joint_feature(j, x[:, k]) for k, j in enumerate(p["joints"])]
    return _stack(cols, len(ctx.q))


# --------------------------------------------------------------------------------------- stale table
def table_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[:3]):
        orders = np.arange(1, 7)
        amp = orders ** -1.0 * rng.uniform(0.5, 1.0, 6)
        amp *= rng.uniform(0.5, 1.2) * ph.ARCMIN / amp.sum()
        if hw["drives"][j]["kind"] == "RV":
            orders = np.r_[orders, rng.integers(30, 41)]
            amp = np.r_[amp, rng.uniform(0.15, 0.4) * ph.ARCMIN]
        out.append({"joint": int(j), "orders": orders, "amp_rad": amp, "phase": rng.uniform(0, 2 * np.pi, len(amp)),
                    "step_rad": np.deg2rad(rng.choice([5.0, 7.5, 10.0]))})
    return out


def old_error(g, theta):
    """The old reducer's transmission error [rad] at output angles ``theta`` [rad]."""
    theta = np.asarray(theta, float)
    return np.sum(g["amp_rad"] * np.sin(np.multiply.outer(theta, g["orders"]) + g["phase"]), axis=-1)


def table_signal(g, q):
    """The stale table's correction (P,) [rad]: the old error on the grid, interpolated linearly."""
    grid = np.arange(-2 * np.pi, 2 * np.pi + g["step_rad"], g["step_rad"])
    return np.interp(q[:, g["joint"]], grid, old_error(g, grid))


def table_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = -table_signal(g, ctx.q)
    return Contribution(dq=dq)


def table_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], table_signal(g, ctx.q)) for g in p], len(ctx.q))


# --------------------------------------------------------------------------------------- coupled wrist
def wrist_pairs(chain):
    """(driven joint, joint its train runs through) of a coupled wrist: the revolute joints from axis 4 on (none
    on ur10, whose every joint has its own drive)."""
    if chain.name == "ur10":
        return []
    W = [int(j) for j in np.flatnonzero(chain.revolute) if j >= 3]
    return [(j, k) for i, j in enumerate(W) for k in W[:i]]


def _ratio(rng):
    """A ratio of tooth counts Z_a / Z_b (17-60 teeth) that three decimals do not give exactly."""
    for _ in range(50):
        c = int(rng.integers(17, 61)) / int(rng.integers(17, 61))
        if abs(round(c, 3) - c) > 5e-5:
            break
    return c


def couple_draw(ctx, hw, rng):
    out = []
    for j, k in wrist_pairs(ctx.chain):
        c = _ratio(rng)
        out.append({"joint": j, "through": k, "c": c, "c_cfg": round(c, 3)})
    return out


def couple_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] += (g["c_cfg"] - g["c"]) * ctx.q[:, g["through"]]
    return Contribution(dq=dq)


def couple_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], ctx.q[:, g["through"]]) for g in p], len(ctx.q))


# ------------------------------------------------------------------------------------------ coupled lash
def wlash_draw(ctx, hw, rng):
    out = {}
    for j, k in wrist_pairs(ctx.chain):
        g = out.setdefault(j, {"joint": j, "c": {}, "b_rad": rng.uniform(3, 8) * ph.ARCMIN,
                               "drag_Nm": rng.uniform(0.2, 0.5) * np.abs(ctx.loads[:, j]).max()})
        g["c"][k] = _ratio(rng) * rng.choice([-1, 1])
    return list(out.values())


def train_direction(g, session):
    """Sign (P,) of the train's last motion d(q_j + sum_k c_jk q_k); a train that did not move keeps its sign."""
    phi = session.q[:, g["joint"]] + sum(c * session.q[:, k] for k, c in g["c"].items())
    d = np.sign(np.diff(phi, prepend=phi[0]))
    d[0] = session.direction[0, g["joint"]]
    for i in range(1, len(d)):
        d[i] = d[i] if d[i] != 0 else d[i - 1]
    return d


def wlash_flank(g, ctx):
    """Flank (P,) +-1 the train rests on: the gravity load's above the drag, else trailing the train's motion."""
    return ph.backlash_offset(train_direction(g, ctx.session), ctx.loads[:, g["joint"]], g["drag_Nm"], 2.0, 0.0)


def wlash_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["b_rad"] / 2 * wlash_flank(g, ctx)
    return Contribution(dq=dq)


def wlash_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], wlash_flank(g, ctx)) for g in p], len(ctx.q))
