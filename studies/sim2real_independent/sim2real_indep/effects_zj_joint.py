"""Set ZJ joint effects (new physics, not in sets A-ZI): the zero of joint torque sensors drifting as the joint
modules warm, which a joint-impedance controller turns into joint offsets; wrist axes driven through traction-roller
reducers whose contacts yield by Mindlin micro-slip; link angles estimated by gyro-aided inclination sensors whose
complementary filter is still correcting the gyro's scale error of the last moves; wrist axes driven open loop by
stepper motors that lose steps in loaded, fast moves; and axis 1's final stage carrying the "ghost" order of the
hobbing machine's index gear. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* torque-sensor zero drift: joint-impedance (torque-controlled) arms close each joint's torque loop on a strain-gauge
  sensor and hold a pose with tau = K (q_d - q) + g(q) (Albu-Schaeffer, Ott & Hirzinger, IJRR 26, 2007); a sensor's
  zero drifts with its temperature (strain-gauge bridges: zero TC of 0.01-0.05 % of full scale per K, HBM / ATI data,
  as recalled; Hoffmann, *An Introduction to Stress Analysis and Transducer Design using Strain Gauges*, HBM, 2012),
  so the joint settles off by dq = -z(T) / K, z(T) the zero's shift. The joint modules' electronics warm while the
  servo is on (a lumped node, tau 15-40 min, 0-30 % warm at the start, 1-1.8 times the measuring blocks' heat in
  production, cooling in the pauses); full scales of 100-1000 N m, 10-25 K of warming and K of 2e3-2e4 N m/rad give
  1e-4-1e-3 rad. Axes 1-3 (assumed torque-controlled builds of the arms). Unlike set ZD's crosstalk (the bending
  moment read as torque) or set ZB's impedance preset (a stiffness per block), the offset follows the sensors'
  temperature, not a load. Driven by the servo-on time, the production and the pauses (time stamps and gaps, logged);
  the temperature is not logged. The true structure: one column per axis (the node), amplitudes z / K (signs drawn).
* traction micro-slip: a traction-roller (friction planetary) reducer carries its torque through rolling contacts
  whose tangential compliance grows as the tangential force approaches the slip limit (Mindlin & Deresiewicz, J. Appl.
  Mech. 20, 1953; Johnson, *Contact Mechanics*, 1985, sec. 7.2): under a torque T rising from zero the output twists
  by A g(T / T_s), g(u) = 1 - (1 - u)^(2/3), and on unloading and reloading it follows Masing's rule (the branch from
  a reversal is twice the virgin curve scaled by one half), a memory of the turning points (here by a
  Prandtl-Ishlinskii sum of play operators of the density g'', which obeys Masing's rule exactly). T_s 1.25-1.6 times
  the session's largest wrist load (the drives' service factor), one twist A at gross slip for the wrist's drives
  (+-20 %), sized so that the target moves 0.25-0.6 mm (A of some 2-6e-3 rad: a soft wrist). The wrist axes of the
  three arms (assumed; traction drives are used where backlash-free, quiet reducers are wanted). Unlike set C's
  torsion hysteresis (the strain-wave gear's friction loop, of a fixed width) or set P's magnetic coupling (a sine law
  without memory), the compliance diverges towards gross slip and its loops grow with the load's excursions. Driven by
  the pose and the payload (logged). The true structure: one column per wrist axis, amplitudes A.
* gyro-aided inclination sensors: links 2 and 3 carry inclination sensors fusing a MEMS gyro with an accelerometer by
  a complementary filter (Mahony, Hamel & Pflimlin, IEEE TAC 53, 2008; Colton, "The balance filter", MIT, 2007): the
  gyro's scale-factor error s (a calibrated gyro's residual, some 0.03-0.1 %: sized so that the target moves 0.25-0.6
  mm) adds s dtheta in each move, which the accelerometer branch removes with the filter's time constant tau (2-6 s),
  so at the measurement the estimate is off by s sum_i dtheta_i exp(-(t - t_i) / tau), the move's share decaying over
  its dwell. The controller takes q2 = theta2 and q3 = theta3 - theta2 from the estimates (axes 2 and 3 parallel) and
  servoes them. Unlike set T's MEMS inclinometers (static offsets and gains of the absolute angle) or set Q's servo
  tail (a loop's overshoot), the error is the fused estimate's memory of the last moves. Driven by the pose sequence
  and the dwells (logged as time stamps). The true structure: two columns (per sensor), amplitudes s.
* stepper stalls: wrist axes driven open loop by hybrid stepper motors (0.9 deg) through 100-160:1 gears lose
  synchronism when a move asks more than the pull-out torque, which falls with the speed (Kenjo & Sugawara, *Stepping
  Motors and their Microprocessor Controls*, 2nd ed., 1994, ch. 4); the rotor falls back by a whole electrical cycle
  (four full steps) against the motion and the step count no longer matches. A move stalls when its load (the larger
  of its end poses' gravity loads) and its speed, each over the session's largest, sum above the session's 85-95 %
  quantile (assumed); the losses add up. Unlike set U's dropped counts (an encoder missing edges in proportion to a
  fast move's travel), set ZE's reversal counts (a count per reversal) or set ZA's tooth skip (one jump between
  blocks), a fixed loss comes with each overloaded move (sized so that the target moves 0.25-0.6 mm at most: 2e-4-1e-3
  rad per stall, the order of four 0.9-deg steps over the gear). Driven by the pose sequence, the speeds and the
  payload (logged). The true structure: one column per wrist axis, amplitudes the loss per stall.
* ghost order: a gear cut on a hobbing machine whose index (master) worm gear has Z_i teeth carries a pitch error
  repeating Z_i times per turn -- the "ghost" order, unrelated to the gear's own tooth count (Smith, *Gear Noise and
  Vibration*, 2nd ed., 2003, ch. 10; Welbourn, "Gear errors and their resultant noise spectra", Proc. IMechE 184,
  1970). Axis 1's final wheel, Z_i 60-200 (a worn machine: 0.1-0.3 mm at the tool, index errors of some 10-40 um on
  the wheel's pitch circle). Unlike set O's mesh TE, set ZH's running-in TE (the gear's own tooth order) or set ZI's
  cage runout (a bearing's), the order is the cutting machine's. Driven by axis 1's angle (logged). The true
  structure: two columns (sin, cos).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_joint import _size_cols
from sim2real_indep.effects_zj_thermal import gap_node


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _signed(rng, n):
    return rng.uniform(0.5, 1.5, n) * rng.choice([-1.0, 1.0], n)


def main_joints(chain):
    return [j for j in range(min(3, chain.n)) if chain.revolute[j]]


def wrist_joints(chain):
    return [j for j in range(3, chain.n) if chain.revolute[j]]


# ---------------------------------------------------------------------------------------------------- zero drift
def zero_node(p, session):
    """(P,) the joint modules' warming per unit (1 measuring, w_prod in production, 0 in the pauses)."""
    return gap_node(session, p["T0"], p["tau_s"], 1.0, p["w_prod"], 0.0)


def zero_draw(ctx, hw, rng):
    p = {"tau_s": 60 * rng.uniform(15.0, 40.0), "T0": rng.uniform(0.0, 0.3), "w_prod": rng.uniform(1.0, 1.8)}
    F = zero_features(p, ctx, hw)
    p["c"] = _size_cols(F, rng, _signed(rng, len(F)))
    return p


def zero_features(p, ctx, hw):
    T = zero_node(p, ctx.session)
    return np.array([ctx.joint_feature(j, T) for j in main_joints(ctx.chain)])


def zero_apply(p, ctx, hw):
    return _amp_apply(p["c"], zero_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- traction
N_PLAYS, U_TOP = 40, 0.85


def mindlin_virgin(u):
    """The virgin twist per unit A at u = T / T_s (odd): 1 - (1 - |u|)^(2/3)."""
    u = np.asarray(u, float)
    return np.sign(u) * (1.0 - (1.0 - np.abs(u)) ** (2 / 3))


def mindlin_masing(u):
    """(P,) the twist per unit A along the load path u (P,) [T / T_s, |u| < U_TOP], from the unloaded state: a
    Prandtl-Ishlinskii sum of play operators whose virgin curve is :func:`mindlin_virgin`."""
    r = (np.arange(N_PLAYS) + 0.5) * U_TOP / N_PLAYS
    w = (2 / 9) * (1.0 - r) ** (-4 / 3) * (U_TOP / N_PLAYS)
    y = np.clip(0.0, u[0] - r, u[0] + r)
    out = np.empty(len(u))
    for k, x in enumerate(u):
        y = np.clip(y, x - r, x + r)
        out[k] = (2 / 3) * x + w @ y
    return out


def traction_draw(ctx, hw, rng):
    js = wrist_joints(ctx.chain)
    p = {"Ts": [float(np.abs(ctx.loads[:, j]).max() * rng.uniform(1.25, 1.6)) + 1e-9 for j in js]}
    F = traction_features(p, ctx, hw)  # one twist at gross slip for the wrist's drives (a jitter of +-20 %)
    p["A"] = _size(F, rng.uniform(0.8, 1.2, len(F)), rng)
    return p


def traction_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, mindlin_masing(ctx.loads[:, j] / Ts))
                     for j, Ts in zip(wrist_joints(ctx.chain), p["Ts"])])


def traction_apply(p, ctx, hw):
    return _amp_apply(p["A"], traction_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- gyro filter
def link_pitches(ctx):
    """(P, 2) the absolute pitch of links 2 and 3 up to constants (axes 2 and 3 parallel): q2 and q2 + q3."""
    return np.stack([ctx.q[:, 1], ctx.q[:, 1] + ctx.q[:, 2]], axis=1)


def filter_memory(p, session, theta):
    """(P, m) the complementary filter's memory per unit gyro scale error: sum_i dtheta_i exp(-(t - t_i) / tau), each
    move's share taken at the dwell's start."""
    d = np.diff(theta, axis=0, prepend=theta[:1])
    E = np.zeros_like(theta)
    for k in range(1, len(theta)):
        dt = session.time_s[k] - session.time_s[k - 1]
        E[k] = E[k - 1] * np.exp(-dt / p["tau_s"]) + d[k] * np.exp(-session.dwell_s[k] / p["tau_s"])
    return E


def gyro_draw(ctx, hw, rng):
    p = {"tau_s": rng.uniform(2.0, 6.0)}
    p["s"] = _size(gyro_features(p, ctx, hw), _signed(rng, 2), rng)
    return p


def gyro_features(p, ctx, hw):
    E = filter_memory(p, ctx.session, link_pitches(ctx))
    f2 = ctx.joint_feature(1, -E[:, 0]) + ctx.joint_feature(2, E[:, 0])
    return np.array([f2, ctx.joint_feature(2, -E[:, 1])])


def gyro_apply(p, ctx, hw):
    return _amp_apply(p["s"], gyro_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- stepper stalls
def stall_demand(ctx, j):
    """(P,) a move's demand on axis j: its load (the larger of its end poses') and its speed, each over the session's
    largest (the first pose has no move)."""
    tau = np.abs(ctx.loads[:, j])
    load = np.maximum(tau, np.r_[tau[0], tau[:-1]])
    v = ctx.session.speed[:, j]
    out = load / max(load.max(), 1e-12) + v / max(v.max(), 1e-12)
    out[0] = 0.0
    return out


def stall_count(events, q):
    """(P,) the steps' loss so far in units of one stall, against the motion of each stalled move (events (P,))."""
    dq = np.diff(q, prepend=q[0])
    return -np.cumsum(np.asarray(events, float) * np.sign(dq))


def stall_draw(ctx, hw, rng):
    """The stalled moves are found once from the true loads and speeds (a shape parameter, as set N's balanced lash)."""
    p = {"events": []}
    for j in wrist_joints(ctx.chain):
        d = stall_demand(ctx, j)
        p["events"].append(d > float(np.quantile(d[1:], rng.uniform(0.85, 0.95))))
    p["loss"] = _size_cols(stall_features(p, ctx, hw), rng)
    return p


def stall_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, stall_count(ev, ctx.q[:, j]))
                     for j, ev in zip(wrist_joints(ctx.chain), p["events"])])


def stall_apply(p, ctx, hw):
    return _amp_apply(p["loss"], stall_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ghost order
def ghost_draw(ctx, hw, rng):
    p = {"z": int(rng.integers(60, 201))}
    ph = rng.uniform(0, 2 * np.pi)
    p["e"] = _size(ghost_features(p, ctx, hw), [np.cos(ph), np.sin(ph)], rng, 0.1, 0.3)
    return p


def ghost_features(p, ctx, hw):
    x = p["z"] * ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, np.sin(x)), ctx.joint_feature(0, np.cos(x))])


def ghost_apply(p, ctx, hw):
    return _amp_apply(p["e"], ghost_features(p, ctx, hw))
