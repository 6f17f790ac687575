"""Set ZO joint effects (new physics, not in sets A-ZN): a soft-servo gravity feed-forward read from a coarse table and
interpolated bilinearly; a hydraulic telescopic ram whose loaded chamber carries entrained air, soft under light
loads and stiffening as the air is squeezed; a roll-pitch differential wrist whose two side-gear trains each have
their own lost motion; a wrist belt stage after the reducer whose automatic tensioner is pushed to its stop when its
span is the tight one; an output encoder read on the inner ring of a bearing whose raceway is wavy; and hydraulic
axes whose controller maps the joint angle to the cylinder stroke with a fitted polynomial. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* tabulated gravity (``gravity_table``): controllers that hold the arm in a soft-servo (current-based compliant) mode
  feed the gravity torque forward and leave the rest to a low position gain K, so a torque error e deflects the joint
  by e / K (as sets ZK and ZL assume); embedded joint controllers read the gravity torque of the upper arm and forearm
  from a table over (q2, q3) computed offline at nodes h = 10-20 deg apart, and interpolate it bilinearly (the
  configuration-space table look-up of Raibert & Horn, "Manipulator control using the configuration space method", The
  Industrial Robot 5, 1978; a bilinear interpolant errs by up to h^2 / 8 |f''|: de Boor, *A Practical Guide to
  Splines*, 1978, ch. 2). The wrist's and the payload's terms are computed exactly; the residual of the table is zero
  at the nodes and bulges between them. Axes 2 and 3 of kr16_like (its set-ZO case; on ur10 the light upper arm and
  forearm leave a residual of the noise's size: see cases.SET_ZO). Unlike set ZK's magnet warming or set ZL's torque-
  constant saturation (errors of the torque's scale), set H's stale table (a joint-angle correction table) or set ZG's
  payload mismatch, the error is the table's interpolation of the links' own gravity. Driven by the pose (logged). The
  true structure: one column per axis, amplitudes 1 / K (sized to 0.25-0.6 mm).
* entrained air (``entrained_air``): hydraulic oil carries undissolved air, whose volume follows the gas law, x0 V
  (p_a / p)^(1/n) (x0 0.2-2 % of air at atmospheric pressure, n 1.0-1.4), so the mix's effective bulk modulus collapses
  at low pressure (Merritt, *Hydraulic Control Systems*, 1967, ch. 2; Yu, Chen & Lu, "The variation of oil effective
  bulk modulus with pressure in hydraulic systems", J. Dyn. Syst. Meas. Control 116, 1994). tool_changer's telescopic
  stage is a long hydraulic cylinder (its in-rod sensors in sets S and ZN) held by counterbalance valves on its loaded
  side with the other chamber vented (load holding as set ZN's valves assume), where air gathers at the high point of
  its long hoses: the loaded chamber alone carries the axial load at p = |F| / A (at least the valve's 3 bar) and
  yields by V (p / beta_l - x0 (p_a / p)^(1/n)) / A plus a constant -- soft under light loads, stiffening as the load
  grows, and moving across when the load's side changes as the ram tips past horizontal. p_s 100-200 bar (beta_l 1.5
  GPa), the cylinder's stall force 1.3-2 times the session's largest axial load; parts of up to the rated payload
  changed between blocks. Unlike set M's oil columns (a constant bulk modulus over chamber volumes that follow the
  stroke), set K's extension ropes or set ZN's holding valves, the compliance is the trapped air's gas law. Driven by
  the pose and the payload (logged). The true structure: one column, amplitude V p_s / (A^2 beta_l) [mm].
* differential-wrist lash (``differential_lash``): in a roll-pitch bevel differential (pitch = (theta_A + theta_B) / 2,
  roll = (theta_A - theta_B) / (2 i), i = Z_out / Z_side 1.0-1.5: Rosheim, *Robot Wrist Actuators*, 1989, as set J's
  differential wrist) each side gear's train has its own lost motion b_A, b_B (Nordin & Gutman, Automatica 38, 2002);
  a train carries tau_A,B = tau_p / 2 +- tau_r / (2 i) (virtual work), rests on the flank of that torque where it beats
  the train's friction (5-25 % of its largest), else trails its last motion, sign(d q5 +- i d q6), and its lost motion
  reaches both axes: dq5 = (e_A + e_B) / 2, dq6 = (e_A - e_B) / (2 i). Axes 5-6 of kr16_like and tool_changer; parts
  changed between blocks. Unlike set J's differential wrist (the side gears' runout), set H's coupled lash or set ZM's
  upstream toss, the flanks follow the trains' mixed torques and motions, and each lash moves both axes. Driven by the
  pose, the payload and the last motion (logged). The true structure: two columns, amplitudes b_A / 2, b_B / 2.
* belt tensioner (``tensioner_stop``): a wrist bend driven by a toothed belt after its reducer (motor and gear in the
  forearm) with an automatic tensioner -- a spring-loaded idler arm with a friction damper -- on one span (the slack
  span of the design's main torque: Gates, *Synchronous belt drive design manual*, tensioner on the slack side, as
  recalled; Beikmann, Perkins & Ulsoy, J. Vib. Acoust. 118, 1996, tensioner arm models). When the torque makes the
  tensioner's span the tight one beyond the spring's hold plus the damper's friction, the arm swings to its stop and
  the output turns by the span's lengthening; it swings back only when that torque falls below the hold less the
  friction (a relay: Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989). The belt carries the gravity torque
  at rest and the output's friction against the motion while it moves. ur10's axes 4 and 5, kr16_like's axis 5; parts
  changed between blocks. Unlike set P's slack belt (a symmetric span going slack), the travel opens only with the
  tensioner's span loaded, and its damper holds it in between. Driven by the pose, the payload and the motion
  (logged). The true structure: one column per axis, amplitude the travel over the pulley's radius.
* raceway waviness (``race_waviness``): axis 1's output encoder ring rides on the inner ring of a thin-section bearing
  of Z 14-24 balls; an inner-raceway waviness of order k moves the shaft's centre (the balls' least-squares centre)
  only for k = Z -+ 1, by its amplitude, turning with phase Z phi_c - k q, phi_c = f_c q the cage's angle (Yhland, "A
  linear theory of vibrations caused by ball bearings with form errors", Proc. IMechE 206, 1992; Wardle, Proc. IMechE
  202, 1988; Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. 8 and on waviness); a head read at the
  ring's radius R sees the shift across it as an angle u / R (Heidenhain, *Angle Encoders*, 2015). The reading errs at
  the non-integer orders Z f_c - Z +- 1 per turn. Waviness 3-8 um of a worn low-grade bearing on a ring of 40-70 mm:
  sized to 0.15-0.35 mm. Unlike set ZI's cage runout (the balls' sizes, order f_c), set Q's ball pass or set C's runout,
  the error is the raceway's form at orders near Z (1 - f_c). Driven by axis 1's angle (logged). The true structure:
  four columns (sin, cos of two orders), amplitudes the harmonics.
* polynomial cam (``lever_cam_fit``): a hydraulic axis turned by a cylinder between pins r1 (on the proximal body)
  and r2 (on the link) from the joint: L^2 = r1^2 + r2^2 - 2 r1 r2 cos(psi0 + q) (set F's lever drive). A hydraulic
  motion controller without trigonometric blocks maps the joint target to the stroke with a cubic fitted over the
  axis' travel (polynomial cam segments: VDI 2143 cam laws; PLCopen Motion Control part 1, MC_CamIn; hydraulic motion
  controllers' cam tables, as recalled) and closes the loop on the cylinder's stroke sensor, so the joint ends where
  L(q) = P(q_cmd): dq = (P - L) / L' to first order. r1 250-400 mm, r2 300-500 mm, psi0 such that psi spans
  40-150 deg. tool_changer's axes 2 and 3. Unlike set F's lever drive (the pins' positions off, the law exact), the
  error is the fit's residual, equioscillating over the travel. Driven by the joint angles (logged). The true
  structure: one column per axis (the residual over its largest value), amplitudes those largest values (rad).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_joint import _size_cols
from sim2real_indep.effects_zm_joint import wrist_bends


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- gravity table
TABLE_J = (1, 2)  # axes 2 and 3


def link_gravity(ctx, q):
    """(P, 2) the gravity torques [N m] of the upper arm's and forearm's masses (bodies 2 and 3) on axes 2 and 3 at
    joint values q (P, n)."""
    ch = ctx.chain
    body = np.array([ch.link_body[i] for i in ctx.mass_index[:-1]], int)
    on = (body == 2) | (body == 3)
    pos = kin.mass_positions(ch, q, com=np.asarray(ctx.com)[on], body=body[on])
    return kin.gravity_loads(ch, q, np.asarray(ctx.masses)[on], pos, body[on])[:, list(TABLE_J)]


def table_residual(p, ctx):
    """(P, 2) the exact torque less its bilinear interpolation from the table's nodes (h apart from the joints' lower
    limits)."""
    q, lo = ctx.q, ctx.chain.lower[list(TABLE_J)]
    h = np.deg2rad(p["h_deg"])
    u = (q[:, list(TABLE_J)] - lo) / h
    i0 = np.floor(u)
    f = u - i0
    out = 0.0
    for a in (0, 1):
        for b in (0, 1):
            qn = q.copy()
            qn[:, TABLE_J[0]] = lo[0] + (i0[:, 0] + a) * h
            qn[:, TABLE_J[1]] = lo[1] + (i0[:, 1] + b) * h
            w = (f[:, 0] if a else 1 - f[:, 0]) * (f[:, 1] if b else 1 - f[:, 1])
            out = out + w[:, None] * link_gravity(ctx, qn)
    return link_gravity(ctx, q) - out


def table_draw(ctx, hw, rng):
    p = {"h_deg": float(rng.uniform(10.0, 20.0))}
    p["c"] = _size_cols(table_features(p, ctx, hw), rng).tolist()
    return p


def table_features(p, ctx, hw):
    r = table_residual(p, ctx)
    return np.array([ctx.joint_feature(j, r[:, k]) for k, j in enumerate(TABLE_J)])


def table_apply(p, ctx, hw):
    return _amp_apply(p["c"], table_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- entrained air
AIR_J = (3,)  # tool_changer's telescopic ram
P_ATM_BAR = 1.013
P_MIN_BAR = 3.0   # the counterbalance valve keeps the loaded chamber above its pilot's few bar


def air_yield(p, ctx):
    """(P, 1) the loaded chamber's yield per unit V p_s / (A beta_l): r - x0 (beta_l / p_s) (p_a / p)^(1/n), p = r p_s
    the chamber's pressure, r = |tau| / tau_s; signed with the load."""
    out = []
    for k, j in enumerate(AIR_J):
        tau = ctx.loads[:, j]
        pb = np.maximum(np.abs(tau) / p["tau_s"][k] * p["ps_bar"], P_MIN_BAR)
        g = pb / p["ps_bar"] - p["x0"] * p["beta_over_ps"] * (P_ATM_BAR / pb) ** (1 / p["n"])
        out.append(np.sign(tau) * g)
    return np.array(out).T


def air_draw(ctx, hw, rng):
    T = np.abs(ctx.loads[:, list(AIR_J)]).max(axis=0)
    p = {"ps_bar": float(rng.uniform(100.0, 200.0)), "x0": float(rng.uniform(0.002, 0.02)),
         "n": float(rng.uniform(1.0, 1.4)), "tau_s": (T * rng.uniform(1.3, 2.0, len(AIR_J))).tolist()}
    p["beta_over_ps"] = 1.5e4 / p["ps_bar"]            # beta_l 1.5 GPa over p_s [bar]
    p["c"] = _size_cols(air_features(p, ctx, hw), rng).tolist()
    return p


def air_features(p, ctx, hw):
    e = air_yield(p, ctx)
    return np.array([ctx.joint_feature(j, e[:, k]) for k, j in enumerate(AIR_J)])


def air_apply(p, ctx, hw):
    return _amp_apply(p["c"], air_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- differential lash
PITCH_J, ROLL_J = 4, 5


def _relay_flank(tau, f, d):
    """(P,) sign(tau) where |tau| > f, else -d (trailing the last motion)."""
    return np.where(np.abs(tau) > f, np.sign(tau), -d)


def train_motion(ctx, i_r):
    """(P, 2) the last motion's direction of trains A and B (sign of dq5 +- i dq6; kept while they stand)."""
    s = ctx.session
    dq = np.diff(np.vstack([s.q[:1], s.q]), axis=0)
    out = np.empty((len(dq), 2))
    prev = np.sign(s.direction[0, PITCH_J] + i_r * s.direction[0, ROLL_J] * np.array([1.0, -1.0]))
    prev = np.where(prev == 0, 1.0, prev)
    for k in range(len(dq)):
        v = dq[k, PITCH_J] + i_r * dq[k, ROLL_J] * np.array([1.0, -1.0])
        prev = np.where(np.abs(v) > 1e-12, np.sign(v), prev)
        out[k] = prev
    return out


def diff_flanks(p, ctx):
    tp, tr = ctx.loads[:, PITCH_J], ctx.loads[:, ROLL_J]
    tau = np.stack([tp / 2 + tr / (2 * p["i"]), tp / 2 - tr / (2 * p["i"])], axis=1)
    d = train_motion(ctx, p["i"])
    return np.stack([_relay_flank(tau[:, k], p["f"][k], d[:, k]) for k in range(2)], axis=1)


def diff_draw(ctx, hw, rng):
    i_r = float(rng.uniform(1.0, 1.5))
    tp, tr = ctx.loads[:, PITCH_J], ctx.loads[:, ROLL_J]
    T = np.abs(np.stack([tp / 2 + tr / (2 * i_r), tp / 2 - tr / (2 * i_r)])).max(axis=1)
    p = {"i": i_r, "f": (T * rng.uniform(0.05, 0.25, 2)).tolist()}
    p["b2"] = _size_cols(diff_features(p, ctx, hw), rng).tolist()
    return p


def diff_features(p, ctx, hw):
    s = diff_flanks(p, ctx)
    sg = (1.0, -1.0)
    return np.array([ctx.joint_feature(PITCH_J, s[:, k] / 2) + ctx.joint_feature(ROLL_J, sg[k] * s[:, k] / (2 * p["i"]))
                     for k in range(2)])


def diff_apply(p, ctx, hw):
    return _amp_apply(p["b2"], diff_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- belt tensioner
def tensioner_state(p, ctx, j, k):
    """(P,) 1 where joint j's tensioner arm sits on its stop, 0 at rest: a relay in sigma x the belt's torque (the
    output's friction against the move while it moves, the gravity torque at rest)."""
    s, tau = ctx.session, ctx.loads[:, j]
    sig, hi, lo, fr = p["sigma"][k], p["hi"][k], p["lo"][k], p["fric"][k]
    out, x = np.empty(len(tau)), p["s0"][k]
    for i in range(len(tau)):
        loads = ([tau[i] - fr * s.direction[i, j]] if s.speed[i, j] > 0 else []) + [tau[i]]
        for t in loads:
            if sig * t > hi:
                x = 1.0
            elif sig * t < lo:
                x = 0.0
        out[i] = x
    return out


def tensioner_draw(ctx, hw, rng):
    J = wrist_bends(ctx.chain)
    T = np.abs(ctx.loads[:, J]).max(axis=0)
    hold = T * rng.uniform(0.15, 0.45, len(J))
    fric = T * rng.uniform(0.05, 0.15, len(J))
    p = {"sigma": rng.choice([-1.0, 1.0], len(J)).tolist(), "hi": (hold + fric).tolist(),
         "lo": (hold - fric).tolist(), "fric": (T * rng.uniform(0.03, 0.1, len(J))).tolist(),
         "s0": rng.choice([0.0, 1.0], len(J)).tolist()}
    p["c"] = _size_cols(tensioner_features(p, ctx, hw), rng).tolist()
    return p


def tensioner_features(p, ctx, hw):
    J = wrist_bends(ctx.chain)
    return np.array([ctx.joint_feature(j, p["sigma"][k] * tensioner_state(p, ctx, j, k)) for k, j in enumerate(J)])


def tensioner_apply(p, ctx, hw):
    return _amp_apply(p["c"], tensioner_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- raceway waviness
def wave_orders(p):
    """The two reading orders per turn of axis 1: Z f_c - (Z -+ 1)."""
    Z, fc = p["Z"], p["f_c"]
    return [Z * fc - (Z - 1), Z * fc - (Z + 1)]


def wave_draw(ctx, hw, rng):
    gamma, alpha = rng.uniform(0.05, 0.15), np.deg2rad(rng.uniform(0.0, 30.0))
    p = {"Z": int(rng.integers(14, 25)), "f_c": float(0.5 * (1 - gamma * np.cos(alpha)))}
    ph = rng.uniform(0, 2 * np.pi, 2)
    rel = np.repeat(rng.uniform(0.5, 1.0, 2), 2) * np.ravel([[np.cos(a), np.sin(a)] for a in ph])
    p["amp"] = _size(wave_features(p, ctx, hw), rel, rng, 0.15, 0.35).tolist()
    return p


def wave_features(p, ctx, hw):
    q = ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, f(nu * q)) for nu in wave_orders(p) for f in (np.sin, np.cos)])


def wave_apply(p, ctx, hw):
    return _amp_apply(p["amp"], wave_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- polynomial cam
CAM_J = (1, 2)  # tool_changer's axes 2 and 3


def cam_residual(g, q, lo, hi):
    """(P,) the joint's error [rad] where a cubic fitted to the cylinder's length over [lo, hi] sets the stroke."""
    L = lambda x: np.sqrt(g["r1"] ** 2 + g["r2"] ** 2 - 2 * g["r1"] * g["r2"] * np.cos(g["psi0"] + x))
    xs = np.linspace(lo, hi, 400)
    c = np.polyfit(xs - (lo + hi) / 2, L(xs), 3)
    q = np.asarray(q, float)
    return (np.polyval(c, q - (lo + hi) / 2) - L(q)) * L(q) / (g["r1"] * g["r2"] * np.sin(g["psi0"] + q))


def cam_draw(ctx, hw, rng):
    p = {"geo": [], "amp": []}
    for j in CAM_J:
        lo, hi = ctx.chain.lower[j], ctx.chain.upper[j]
        start = np.deg2rad(rng.uniform(40.0, 150.0 - np.rad2deg(hi - lo)))
        g = {"r1": float(rng.uniform(250.0, 400.0)), "r2": float(rng.uniform(300.0, 500.0)), "psi0": float(start - lo)}
        p["geo"].append(g)
        p["amp"].append(float(np.abs(cam_residual(g, np.linspace(lo, hi, 400), lo, hi)).max()))
    return p


def cam_features(p, ctx, hw):
    cols = []
    for g, j, a in zip(p["geo"], CAM_J, p["amp"]):
        r = cam_residual(g, ctx.q[:, j], ctx.chain.lower[j], ctx.chain.upper[j])
        cols.append(ctx.joint_feature(j, r / a))
    return np.array(cols)


def cam_apply(p, ctx, hw):
    return _amp_apply(p["amp"], cam_features(p, ctx, hw))
