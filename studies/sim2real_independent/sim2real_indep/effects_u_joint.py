"""Set U joint effects (new physics, not in sets A-T): main axes whose position loop holds the load with an integrator
clamped by its anti-windup limit (the rest held by the proportional term alone); a spare tool parked in a holder on the
forearm in some blocks only (a mass the logged payload does not contain); a roller-chain stage of axis 3 whose slack
strand's sag, and so its lost motion, follows the strand's inclination; the wrist axis 5 driven through a Bowden cable
whose sheath's friction over the elbow sets its lost motion; incremental encoders of the main axes dropping counts in
the fast moves (a counter's input-frequency limit); and an optical encoder of axis 2 with a contaminated sector of its
graduation. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* integrator clamp: a PI(D) position / velocity loop cancels a static load torque with its integral term; the
  anti-windup clamp limits that term to +-T_I (conditional integration / clamping: Astrom & Hagglund, *Advanced PID
  Control*, 2006, sec. 3.5; Ellis, *Control System Design Guide*, 4th ed., 2012, ch. 6). Loads beyond the clamp are held
  by the proportional term alone, whose static stiffness at the joint K_s = K_p N^2 (the loop's torque per unit position
  error): the joint sags by dz(tau) / K_s, dz(tau) = sign(tau) max(|tau| - T_I, 0). A clamp left at 55-85 % of the
  session's largest load on axes 2 and 3 (a limit set for a lighter tool; assumed), K_s 0.3-1.5 x the gear's linear
  stiffness of :mod:`hardware` (assumed). The gears' own twist is set A's and left out. The true structure: a column per
  axis, amplitude 1 / K_s.
* parked tool: arms that change between two tools carry the idle one in a holder on the forearm (tool racks on the arm;
  the payload log holds only the flange's load, as the controller's load data do). Its weight loads the joints before
  the forearm (tau = J^T F at its centre of mass, statics: Craig, *Introduction to Robotics*, ch. 5) and twists them
  with the linear gear stiffness of :mod:`hardware`. A spare tool of 40-90 % of the arm's largest payload, its centre of
  mass 50-150 mm off the forearm's axis, 60 % of the way from axis 4's point to axis 5's (a holder by the wrist;
  assumed), parked in every other one of 4-8 blocks (the tools changed at each block; first parked at random in some
  blocks: U12 absorbed in a trial draw, its split by time leaving the training poses all with the tool). The true
  structure: one column, amplitude the mass.
* chain slack: a roller-chain stage driving axis 3 from a sprocket on axis 2 (heavy palletising arms) runs its slack
  strand with a catenary sag; the extra length of a shallow sagging span, 8 f^2 / (3 L) with f = w L^2 cos(beta) / (8 H)
  (parabolic sag of a span inclined at beta: Irvine, *Cable Structures*, 1981, ch. 1; chain drive layout: ISO 606,
  Renold / Tsubaki chain design guides, as recalled), is the play the sprocket must take up when the load reverses: b =
  w^2 L^3 cos^2(beta) / (24 H^2 r) [rad]. A tensioner holds the horizontal span's sag f to 0.5-1 % of its length (the
  makers' 2-4 % for ordinary drives), which sets H = w L / (8 f / L). The output rests on the flank its load pushes it
  to when the load beats the drag, else on its last motion's trailing flank (:func:`physics.backlash_offset`). Chain
  2.5-4 kg/m (ISO 606 16B-20B), span 0.45-0.7 m, sprocket radius 60-120 mm, drag 1-3 % of the rated torque (assumed).
  ur10 and kr16_like (their axis 3); none on tool_changer, whose axis 3 is loaded one way over its range. The true
  structure: one column, amplitude the horizontal span's play w^2 L^3 / (24 H^2 r).
* Bowden cable: a wrist axis driven through a cable in a sheath (tendon-sheath transmissions: Kaneko, Yamashita & Tanie,
  "Basic considerations on transmission characteristics for tendon drive robots", ICAR 1991; Palli & Melchiorri, "Model
  and control of tendon-sheath transmission systems", ICRA 2006): the sheath's friction over a total wrap angle theta
  raises the driving strand's tension by exp(mu theta) (Euler-Eytelwein), and the lost motion between input and output
  grows as b0 (exp(mu theta) - 1). The sheath passes the elbow, so theta = theta0 + |q3 - q3_n| (q3_n the elbow angle at
  which it runs straight). mu 0.1-0.25 (PTFE-lined sheaths), theta0 0.5-1.5 rad; the play 0.1-0.35 deg at theta0 + 1 rad
  (assumed); flank as above with a sheath drag of 10-30 % of the rated torque (a tendon-sheath drive's friction loss,
  70-90 % efficiency over such wraps; assumed). Axis 5 of ur10 and kr16_like; none on tool_changer. The true structure:
  one column, amplitude b0.
* dropped counts: an incremental encoder's counter misses edges when their rate exceeds its input filter's limit
  (HEIDENHAIN, "Encoders for servo drives", 2017: maximum input frequency and edge separation; counting errors from
  noise and cable length), so in a move faster than the limit the reading advances by (1 - eps) of the travel; the loop
  servoes the reading, so the joint overshoots by eps of each fast move's travel and the error accumulates over the
  session: e_i = eps sum_{k <= i, v_k > v_c} dq_k. eps 2e-5 - 1e-4 (one edge in 10^4 - 5 10^4), the limit at the 40-70 %
  quantile of the joint's speeds in the session's moves (assumed); main axes 1-3 (the revolute ones). The true
  structure: a column per axis, amplitude eps.
* contaminated graduation: oil mist or coolant on an optical encoder's disc attenuates and shifts its scanning signals
  over a sector (HEIDENHAIN, "Angle encoders with integral bearing", 2015: contamination, signal quality and position
  error; Renishaw encoder installation guides, as recalled): the reading errs by a bump A exp(-(theta - theta_c)^2 / (2
  w^2)) over the soiled sector. A 0.008-0.025 deg, w 8-20 deg, theta_c inside the measured range (assumed). Axis 2 of
  every arm. The true structure: one column, amplitude A.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_t_joint import twist_displacement
from sim2real_indep.hardware import PAYLOAD_MAX_KG
from sim2real_indep.session import BOXES


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def block_index(session):
    """(P,) the measurement block of each pose (a new block after each exercise or pause gap)."""
    return np.cumsum(session.gap_s != 0)


# ------------------------------------------------------------------------------------------ integrator clamp
CLAMP_JOINTS = (1, 2)


def clamp_dead_zone(tau, T_I):
    """sign(tau) max(|tau| - T_I, 0): the load the proportional term holds."""
    return np.sign(tau) * np.maximum(np.abs(tau) - T_I, 0.0)


def clamp_draw(ctx, hw, rng):
    js = [j for j in CLAMP_JOINTS if ctx.chain.revolute[j]]
    tau = np.abs(ctx.loads[:, js]).max(axis=0)
    return {"joints": js, "T_I": rng.uniform(0.55, 0.85, len(js)) * tau,
            "K_s": rng.uniform(0.3, 1.5, len(js)) / compliance(hw)[js]}


def clamp_signals(p, ctx):
    """(P, m) the proportional term's share of each clamped axis' load [N m]."""
    return clamp_dead_zone(ctx.loads[:, p["joints"]], p["T_I"])


def clamp_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = clamp_signals(p, ctx) / p["K_s"]
    return Contribution(dq=dq)


def clamp_features(p, ctx, hw):
    s = clamp_signals(p, ctx)
    return np.array([ctx.joint_feature(j, s[:, k]) for k, j in enumerate(p["joints"])])


# ---------------------------------------------------------------------------------------------- parked tool
PARKED = (0.4, 0.9)  # the spare tool's mass, a share of the arm's largest payload
PARK_BODY = 3  # the forearm (tool_changer: the boom's outer section), carried by axes 1-3


def parked_point(p, ctx):
    """(P, 3) the parked tool's centre of mass [mm], riding on the forearm body."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    return np.einsum("pij,j->pi", R[:, p["body"]], p["home"]) + t[:, p["body"]]


def parked_loads(p, ctx):
    """(P, n) joint loads per kg of parked tool, times its presence [N m / kg]."""
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    x = parked_point(p, ctx)
    F = np.array([0.0, 0.0, -kin.G])
    out = np.zeros(ctx.q.shape)
    for j in range(p["body"]):
        arm = np.cross((x - c[:, j]) / 1000.0, F) if ctx.chain.revolute[j] else np.broadcast_to(F, x.shape)
        out[:, j] = np.einsum("pi,pi->p", arm, w[:, j])
    return out * p["present"][:, None]


def parked_draw(ctx, hw, rng):
    b = block_index(ctx.session)
    nb = int(b.max()) + 1
    pattern = (np.arange(nb) + rng.integers(2)) % 2 == 1               # a tool change at each block
    body = PARK_BODY
    pts = ctx.chain.points()
    home = pts[3] + 0.6 * (pts[4] - pts[3]) + rng.normal(0.0, 1.0, 3) / np.sqrt(3) * rng.uniform(50.0, 150.0)
    return {"m_kg": rng.uniform(*PARKED) * PAYLOAD_MAX_KG[ctx.chain.name], "body": body, "home": home,
            "present": pattern[b].astype(float), "pattern": pattern}


def parked_apply(p, ctx, hw):
    return Contribution(dq=p["m_kg"] * parked_loads(p, ctx) * compliance(hw))


def parked_features(p, ctx, hw):
    return twist_displacement(ctx, hw, parked_loads(p, ctx))[None]


# ---------------------------------------------------------------------------------------------- chain slack
CHAIN = {"ur10": 2, "kr16_like": 2}  # the joint the chain stage drives (axis 3)


def chain_cos2(p, ctx):
    """(P,) cos^2 of the slack span's inclination: the span along the upper arm, from axis 2's point to axis 3's."""
    _, c = kin.joint_frames(ctx.chain, ctx.q)
    j = p["joint"]
    d = c[:, j] - c[:, j - 1]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return 1.0 - d[:, 2] ** 2


def chain_flank(p, ctx):
    """(P,) the output's place in the play, +-1/2: the load's flank where it beats the drag, else the trailing one."""
    j = p["joint"]
    return ph.backlash_offset(ctx.session.direction[:, j], ctx.loads[:, j], p["drag"], 1.0, 0.0)


def chain_draw(ctx, hw, rng):
    if ctx.chain.name not in CHAIN:
        return {}
    j = CHAIN[ctx.chain.name]
    w = rng.uniform(2.5, 4.0) * kin.G
    L, r = rng.uniform(0.45, 0.7), rng.uniform(0.06, 0.12)
    H = w * L / (8 * rng.uniform(0.005, 0.01))                       # a tensioner: sag 0.5-1 % of the span
    p = {"joint": j, "w_N_m": w, "L_m": L, "H_N": H, "r_m": r, "b_h": w ** 2 * L ** 3 / (24 * H ** 2 * r),
         "drag": rng.uniform(0.01, 0.03) * hw["drives"][j]["T_rated"]}
    p["flank"] = chain_flank(p, ctx)
    return p


def chain_signal(p, ctx):
    return chain_cos2(p, ctx) * p["flank"]


def chain_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["b_h"] * chain_signal(p, ctx)
    return Contribution(dq=dq)


def chain_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], chain_signal(p, ctx))[None] if p else _empty(ctx)


# --------------------------------------------------------------------------------------------- Bowden cable
BOWDEN = {"ur10": 4, "kr16_like": 4}  # axis 5


def bowden_wrap(p, q):
    """(P,) the sheath's total wrap angle [rad]: theta0 plus the elbow's bend from where it runs straight."""
    return p["theta0"] + np.abs(np.asarray(q)[:, 2] - p["q3_n"])


def bowden_draw(ctx, hw, rng):
    if ctx.chain.name not in BOWDEN:
        return {}
    j = BOWDEN[ctx.chain.name]
    lo, hi = np.deg2rad(BOXES[ctx.chain.name][0][2]), np.deg2rad(BOXES[ctx.chain.name][1][2])
    p = {"joint": j, "mu": rng.uniform(0.1, 0.25), "theta0": rng.uniform(0.5, 1.5), "q3_n": rng.uniform(lo, hi),
         "drag": rng.uniform(0.1, 0.3) * hw["drives"][j]["T_rated"]}
    p["b0"] = np.deg2rad(rng.uniform(0.1, 0.35)) / (np.exp(p["mu"] * (p["theta0"] + 1.0)) - 1.0)
    p["flank"] = ph.backlash_offset(ctx.session.direction[:, j], ctx.loads[:, j], p["drag"], 1.0, 0.0)
    return p


def bowden_signal(p, ctx):
    return (np.exp(p["mu"] * bowden_wrap(p, ctx.q)) - 1.0) * p["flank"]


def bowden_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["b0"] * bowden_signal(p, ctx)
    return Contribution(dq=dq)


def bowden_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], bowden_signal(p, ctx))[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------- dropped counts
COUNT_JOINTS = (0, 1, 2)


def count_signals(p, session):
    """(P, m) each axis' accumulated travel in the moves faster than its counter's limit [rad]."""
    js = p["joints"]
    dq = np.diff(np.vstack([session.q[:1], session.q]), axis=0)[:, js]
    fast = session.speed[:, js] > p["v_c"]
    return np.cumsum(np.where(fast, dq, 0.0), axis=0)


def count_draw(ctx, hw, rng):
    s = ctx.session
    js = [j for j in COUNT_JOINTS if ctx.chain.revolute[j]]
    v_c = np.array([np.quantile(s.speed[1:, j], rng.uniform(0.4, 0.7)) for j in js])
    return {"joints": js, "v_c": v_c, "eps": rng.uniform(2e-5, 1e-4, len(js))}  # missed edges: the joint overshoots


def count_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = count_signals(p, ctx.session) * p["eps"]
    return Contribution(dq=dq)


def count_features(p, ctx, hw):
    s = count_signals(p, ctx.session)
    return np.array([ctx.joint_feature(j, s[:, k]) for k, j in enumerate(p["joints"])])


# --------------------------------------------------------------------------------------- soiled graduation
SOIL_JOINT = 1


def soil_draw(ctx, hw, rng):
    lo, hi = (np.deg2rad(v[SOIL_JOINT]) for v in BOXES[ctx.chain.name])
    w = np.deg2rad(rng.uniform(8.0, 20.0))
    return {"joint": SOIL_JOINT, "A": np.deg2rad(rng.uniform(0.008, 0.025)) * rng.choice([-1.0, 1.0]), "w": w,
            "theta_c": rng.uniform(lo + w, hi - w)}


def soil_signal(p, q):
    """(P,) the bump's shape at the joint's reading."""
    return np.exp(-0.5 * ((np.asarray(q)[:, p["joint"]] - p["theta_c"]) / p["w"]) ** 2)


def soil_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = -p["A"] * soil_signal(p, ctx.q)               # the loop servoes the reading
    return Contribution(dq=dq)


def soil_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], -soil_signal(p, ctx.q))[None]
