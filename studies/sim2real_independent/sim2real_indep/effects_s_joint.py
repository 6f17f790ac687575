"""Set S joint effects (new physics, not in sets A-R): axis 2 driven by a pinion held in mesh with its sector gear by a
radial spring, which the teeth's pressure angle wedges out of mesh under a large torque; the forearm passing a booth
wall through a rubber bellows whose spring rates pull it towards the bellows' relaxed position; the lost motion of the
lightly loaded axes crossed back, in part or in full, by the position loop's overshoot at the end of each move; the
cogging torque of the drives of those axes against a position loop whose integral action is frozen at standstill; and
the boom cylinders' in-rod potentiometric stroke transducers read through an input of finite impedance. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* floating pinion: a pinion kept in zero-backlash mesh by a spring pressing its bearing block radially into the gear
  (spring-loaded or pivoting pinion mounts of rack-and-pinion and slewing-ring drives: makers' application notes, as
  recalled). The mesh force has a separating component F_t tan(alpha_w) (involute gearing: Niemann & Winter,
  *Maschinenelemente* II, 1989, ch. 21; ISO 21771); once it beats the spring's preload F_0 the pinion backs off radially
  by (F_t tan alpha_w - F_0) / k_s, and a centre distance grown by da lets the gear turn by da tan(alpha_w) at its pitch
  radius R (the flank's involute: the backlash grows by 2 da tan alpha_w, ISO 21771), so the joint gives by sign(tau)
  (|tau| - T_0)+ tan^2(alpha_w) / (k_s R^2), T_0 = F_0 R / tan(alpha_w), beyond the gear's own twist. Axis 2 of the arms
  whose main axes are driven through a sector gear (kr16_like, tool_changer; set G's sector gear; none on ur10), alpha_w
  20-25 deg, R 250-350 / 450-650 mm, a spring set for the lighter tools of a pick-and-place session: T_0 between the
  50th and the 80th percentile of the session's axis-2 loads, the pinion's give at the largest 2-5e-4 / 2-4e-4 rad
  (kr16_like / tool_changer; assumed; first T_0 at 30-60 % of the largest load, a give of 1.5-4e-4 / 0.6-1.5e-4 rad and
  no pick and place: axis 2's load then nearly a function of q2, and tool_changer's never below a third of its largest,
  so nearly every pose was past the knee -- the transmission and link models copied it at 1.04-1.12x). The true
  structure: one column (the load beyond T_0), amplitude tan^2(alpha_w) / (k_s R^2).
* wall bellows: a pass-through installation (the arm outside a booth or isolator, its forearm reaching in through a port
  in the wall) seals the port with a rubber bellows clamped to the port ring and to a collar on the forearm; the bellows
  resists the collar's displacement from its relaxed position with its axial and lateral spring rates, F = -(k_a n n^T +
  k_l (1 - n n^T)) (p - p_0) (the spring rates of bellows: EJMA, *Standards of the Expansion Joint Manufacturers
  Association*, 10th ed., 2015, as recalled, linearised about the relaxed shape), n the port's normal (horizontal). The
  joints between the base and the collar carry tau = J_c^T F (statics: Craig, *Introduction to Robotics*, ch. 5) and
  twist with the linear gear stiffness of :mod:`hardware`. The collar on the forearm's axis at 30-70 % of its length,
  relaxed where the collar stood at one of the session's poses (+-30 mm), k_a 0.03-0.1 / 0.08-0.25 and k_l 0.05-0.15 /
  0.12-0.35 N/mm on ur10 / kr16_like (rubber bellows of 0.3-0.5 m bore and long travel; assumed; none on tool_changer,
  whose arm does not pass a wall). The true structure: two columns (axial and lateral pull per unit rate), amplitudes
  k_a and k_l.
* overshoot lash: after a move, a position loop overshoots its target and comes back -- the overshoot a share of the
  following error v / K_v (Ellis, *Control System Design Guide*, 4th ed., 2012, ch. 17; set Q's servo tail: 1-3e-3 s
  times the speed); with lost motion b between motor and output, the motor's return of o crosses the gap only as far as
  it reaches: an output that trailed by b / 2 and that the drag keeps where it is (Nordin & Gutman, "Controlling
  mechanical systems with backlash -- a survey", Automatica 38, 2002, on the dead zone) ends at d (min(o, b) - b / 2), d
  the move's direction; a gravity torque beyond the drag holds it on its flank, sign(tau) b / 2
  (:func:`physics.backlash_offset`). The axes that carry little gravity load (1, 4, 6), worn gears of 0.8-2 arcmin
  (strain-wave) or 0.6-1.5 arcmin (cycloid), drag 1-3 % of the rated torque, overshoot 0.5-3e-3 s times the move's
  cruise speed (trapezoidal moves with 0.5 s ramps, :mod:`session`) (assumed). The flank is computed once from the true
  loads (a shape parameter). The true structure: a column per axis, amplitude b.
* cogging: a permanent-magnet servo motor's cogging torque repeats Z times per motor turn, Z the least common multiple
  of its slots and poles (Zhu & Howe, "Influence of design parameters on cogging torque in permanent magnet machines",
  IEEE Trans. Energy Convers. 15(4), 2000; 0.5-3 % of the rated torque for unskewed iron-core motors); a proportional
  loop at standstill (its integral action frozen in the in-position window, set R's stick band) holds the motor against
  it with its stiffness K_s, so the output is off by A sin(Z N q + phi), A = T_c / K_s at the output (N the gear ratio).
  Axes 1, 4 and 6, Z 24-72, ratios 80-160 (strain-wave) or 81-161 (cycloid), cogging 1-3 % of the rated torque against a
  loop giving 1-2 arcmin at 3 % of it (assumed; the load's and friction's share is set R's stick band and left out). The
  true structure: two columns per axis (sin and cos), amplitudes A cos(phi) and A sin(phi).
* potentiometer loading: a potentiometric (conductive-plastic) in-rod stroke transducer gives the ratio u = x / X of its
  wiper; read by an input of resistance R_L, the divider loads to u / (1 + rho u (1 - u)), rho = R_p / R_L (the loaded
  potentiometer: Doebelin, *Measurement Systems*, 5th ed., 2004, ch. 4; Bentley, *Principles of Measurement Systems*,
  4th ed., 2005, ch. 5), an error that a two-point calibration at the stroke's ends leaves in place. The loop servoes
  the reading, so the stroke is off by -e(u) and the joint by -e / (dL / dq) through the cylinder's lever (law of
  cosines, set F's levers: pivot r1 0.25-0.4 m, rod eye r2 0.5-0.8 m, 70-110 deg at mid-range). Axes 2 and 3 of
  tool_changer (the hydraulic boom of sets L and M; none on the others), rho 3e-4 - 1.5e-3 (a 1-4 kOhm track on a 2.5-10
  MOhm input; assumed; first 4e-4 - 2e-3: 1.06 mm at the tool). The true structure: a column per axis, amplitude rho.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import BOXES

RAMP_S = 0.5  # the session's acceleration time at each end of a move


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def compliance(hw):
    """(n,) each joint's linear compliance [rad/(N m) or mm/N]."""
    return np.array([hwm.torsion(d, 1.0, False) for d in hw["drives"]])


def cruise_speed(session):
    """(P, n): each joint's cruise speed in the move into each pose [rad/s or mm/s] (trapezoid with 0.5 s ramps)."""
    dq = np.abs(np.diff(np.vstack([session.q[:1], session.q]), axis=0))
    T = session.move_s[:, None] - RAMP_S
    return np.where(T > 0, dq / np.maximum(T, 1e-9), 0.0)


def _lightly_loaded(ctx):
    return [j for j in (0, 3, 5) if ctx.chain.revolute[j]]


# ---------------------------------------------------------------------------------------------- floating pinion
PINION = {"kr16_like": ((250.0, 350.0), (2e-4, 5e-4)), "tool_changer": ((450.0, 650.0), (2e-4, 4e-4))}


def pinion_draw(ctx, hw, rng):
    if ctx.chain.name not in PINION:
        return {}
    (r_lo, r_hi), (g_lo, g_hi) = PINION[ctx.chain.name]
    tau = np.abs(ctx.loads[:, 1])
    tmax = tau.max()
    p = {"alpha": np.deg2rad(rng.uniform(20.0, 25.0)), "R_m": rng.uniform(r_lo, r_hi) / 1000,
         "T0": np.quantile(tau, rng.uniform(0.5, 0.8))}
    p["c_x"] = rng.uniform(g_lo, g_hi) / (tmax - p["T0"])             # [rad/(N m)]
    p["k_s"] = np.tan(p["alpha"]) ** 2 / (p["c_x"] * p["R_m"] ** 2)   # the spring's rate [N/m]
    p["F0"] = p["T0"] * np.tan(p["alpha"]) / p["R_m"]                 # its preload [N]
    return p


def pinion_signal(p, tau):
    """(P,): the axis-2 load beyond the lift-off torque [N m] (signed)."""
    tau = np.asarray(tau, float)
    return np.sign(tau) * np.maximum(np.abs(tau) - p["T0"], 0.0)


def pinion_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 1] = p["c_x"] * pinion_signal(p, ctx.loads[:, 1])
    return Contribution(dq=dq)


def pinion_features(p, ctx, hw):
    return ctx.joint_feature(1, pinion_signal(p, ctx.loads[:, 1]))[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------ wall bellows
BOOT = {"ur10": ("a3", (0.03, 0.1), (0.05, 0.15)), "kr16_like": ("d4", (0.08, 0.25), (0.12, 0.35))}


def collar(p, ctx):
    """(P, 3) the collar's position [mm] and its body (int)."""
    ch = ctx.chain
    li = ch.link_names.index(p["link"])
    R, t = kin.body_transforms(ch, ctx.q)
    b = ch.link_body[li]
    local = np.cumsum(ch.links, axis=0)[li] - (1 - p["s"]) * ch.links[li]
    return np.einsum("pij,j->pi", R[:, b], local) + t[:, b], b


def boot_draw(ctx, hw, rng):
    if ctx.chain.name not in BOOT:
        return {}
    link, ka, kl = BOOT[ctx.chain.name]
    az = rng.uniform(0, 2 * np.pi)
    p = {"link": link, "s": rng.uniform(0.3, 0.7), "n": np.array([np.cos(az), np.sin(az), 0.0]),
         "k_a": rng.uniform(*ka), "k_l": rng.uniform(*kl)}
    pc, _ = collar(p, ctx)
    p["p0"] = pc[int(rng.integers(len(pc)))] + rng.normal(0.0, 30.0, 3)
    return p


def boot_signals(p, ctx, hw):
    """(2, P, n): each joint's twist per unit axial and lateral spring rate [rad per N/mm]."""
    pc, b = collar(p, ctx)
    d = pc - p["p0"]
    n = p["n"]
    f_a = -np.outer(d @ n, n)                                          # per N/mm of axial rate [N]
    f_l = -(d - np.outer(d @ n, n))
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    J = np.where(ctx.chain.revolute[None, :, None], np.cross(w, pc[:, None, :] - c), w)   # (P, n, 3)
    J[:, b:] = 0.0                                                     # joints beyond the collar's body
    scale = np.where(ctx.chain.revolute, 1e-3, 1.0) * compliance(hw)
    return np.array([np.einsum("pni,pi->pn", J, f) * scale for f in (f_a, f_l)])


def boot_apply(p, ctx, hw):
    if not p:
        return Contribution(dq=np.zeros_like(ctx.q))
    s = boot_signals(p, ctx, hw)
    return Contribution(dq=p["k_a"] * s[0] + p["k_l"] * s[1])


def boot_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    return np.einsum("pij,mpj->mpi", ctx.jac, boot_signals(p, ctx, hw))


# ---------------------------------------------------------------------------------------------- overshoot lash
def lash_draw(ctx, hw, rng):
    js = _lightly_loaded(ctx)
    hd = np.array([hw["drives"][j]["kind"] == "HD" for j in js])
    b = np.where(hd, rng.uniform(0.8, 2.0, len(js)), rng.uniform(0.6, 1.5, len(js))) * ph.ARCMIN
    drag = rng.uniform(0.01, 0.03, len(js)) * np.array([hw["drives"][j]["T_rated"] for j in js])
    p = {"joints": js, "b": b, "drag": drag, "kappa": rng.uniform(0.5e-3, 3e-3, len(js))}
    p["flank"] = lash_flank(p, ctx.loads[:, js], ctx.session)            # a shape parameter (true loads)
    return p


def lash_flank(p, tau, session):
    """(P, m): where the output rests, in units of the lost motion: on its gravity flank +-1/2 where the load beats the
    drag; else the trailing flank moved back by the overshoot's return, d (min(o / b, 1) - 1/2)."""
    js = p["joints"]
    d = session.direction[:, js]
    o = p["kappa"] * cruise_speed(session)[:, js]
    free = d * (np.minimum(o / p["b"], 1.0) - 0.5)
    return np.where(np.abs(tau) > p["drag"], 0.5 * np.sign(tau), free)


def lash_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = p["b"] * p["flank"]
    return Contribution(dq=dq)


def lash_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, p["flank"][:, k]) for k, j in enumerate(p["joints"])])


# ----------------------------------------------------------------------------------------------------- cogging
HD_RATIOS, RV_RATIOS, Z_COG = (80, 100, 120, 160), (81, 101, 121, 141, 161), (24, 36, 48, 60, 72)


def cog_draw(ctx, hw, rng):
    js = _lightly_loaded(ctx)
    N = np.array([rng.choice(HD_RATIOS if hw["drives"][j]["kind"] == "HD" else RV_RATIOS) for j in js], float)
    amp = rng.uniform(0.01, 0.03, len(js)) / 0.03 * rng.uniform(1.0, 2.0, len(js)) * ph.ARCMIN
    return {"joints": js, "N": N, "Z": rng.choice(Z_COG, len(js)).astype(float), "A": amp,
            "phi": rng.uniform(0, 2 * np.pi, len(js))}


def cog_signals(p, q):
    """(2m, P): sin and cos of the cogging phase Z N q per axis."""
    arg = p["Z"] * p["N"] * np.asarray(q)[:, p["joints"]]
    return np.concatenate([np.sin(arg).T, np.cos(arg).T])


def cog_amplitudes(p):
    return np.r_[p["A"] * np.cos(p["phi"]), p["A"] * np.sin(p["phi"])]


def cog_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    m = len(p["joints"])
    s = cog_amplitudes(p)[:, None] * cog_signals(p, ctx.q)
    dq[:, p["joints"]] = (s[:m] + s[m:]).T
    return Contribution(dq=dq)


def cog_features(p, ctx, hw):
    js = list(p["joints"]) * 2
    return np.array([ctx.joint_feature(j, s) for j, s in zip(js, cog_signals(p, ctx.q))])


# -------------------------------------------------------------------------------------- potentiometer loading
LEVER_JOINTS = {"tool_changer": (1, 2)}


def lever_draw(robot_key, joints, rng):
    """Cylinder levers of ``joints``: pivot r1, rod eye r2 [mm], included angle at the box's mid-range, the sense, and
    the electrical stroke X and its start (the transducer spans the stroke over the box +-5 deg and 10-30 mm more at
    each end)."""
    lo, hi = (np.deg2rad(BOXES[robot_key][k]) for k in (0, 1))
    out = []
    for j in joints:
        lv = {"joint": j, "r1": rng.uniform(250.0, 400.0), "r2": rng.uniform(500.0, 800.0),
              "psi_mid": np.deg2rad(rng.uniform(70.0, 110.0)), "q_mid": 0.5 * (lo[j] + hi[j]),
              "sense": float(rng.choice([-1.0, 1.0]))}
        L = lever_length(lv, np.linspace(lo[j] - np.deg2rad(5), hi[j] + np.deg2rad(5), 201))
        m0, m1 = rng.uniform(10.0, 30.0, 2)
        lv.update(L_start=L.min() - m0, X=L.max() - L.min() + m0 + m1)
        out.append(lv)
    return out


def lever_length(lv, q):
    """The cylinder's pin-to-pin length [mm] at joint angles ``q`` (law of cosines)."""
    psi = lv["psi_mid"] + lv["sense"] * (np.asarray(q, float) - lv["q_mid"])
    return np.sqrt(lv["r1"] ** 2 + lv["r2"] ** 2 - 2 * lv["r1"] * lv["r2"] * np.cos(psi))


def lever_arm(lv, q):
    """dL/dq [mm/rad] (signed by the sense)."""
    psi = lv["psi_mid"] + lv["sense"] * (np.asarray(q, float) - lv["q_mid"])
    return lv["sense"] * lv["r1"] * lv["r2"] * np.sin(psi) / lever_length(lv, q)


def pot_draw(ctx, hw, rng):
    if ctx.chain.name not in LEVER_JOINTS:
        return {}
    levers = lever_draw(ctx.chain.name, LEVER_JOINTS[ctx.chain.name], rng)
    return {"levers": levers, "rho": rng.uniform(3e-4, 1.5e-3, len(levers))}


def pot_error(u, rho):
    """The loaded divider's reading minus the true ratio (in units of the stroke X)."""
    return u / (1 + rho * u * (1 - u)) - u


def pot_signals(p, q):
    """(m, P): each axis' angle error per unit rho [rad]."""
    out = []
    for lv, rho in zip(p["levers"], p["rho"]):
        qj = np.asarray(q)[:, lv["joint"]]
        u = (lever_length(lv, qj) - lv["L_start"]) / lv["X"]
        out.append(-lv["X"] * pot_error(u, rho) / rho / lever_arm(lv, qj))
    return np.array(out)


def pot_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        for lv, rho, s in zip(p["levers"], p["rho"], pot_signals(p, ctx.q)):
            dq[:, lv["joint"]] = rho * s
    return Contribution(dq=dq)


def pot_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    return np.array([ctx.joint_feature(lv["joint"], s) for lv, s in zip(p["levers"], pot_signals(p, ctx.q))])
