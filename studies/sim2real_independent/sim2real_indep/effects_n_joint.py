"""Set N joint effects (new physics, not in sets A-M): the wind on a flat panel the arm carries outdoors, twisting the
gears by the panel's normal force; the reaction of a high-pressure water jet leaving the tool's nozzle; axis 1's lost
motion whose flank the torsion of the base's cable harness chooses; axis 2's lost motion under the net torque of
gravity and a counterbalance whose seal friction follows the axis's last motion; a telescopic stage driven by a wire
rope over a traction sheave, the rope creeping on the sheave by the load it carries; the pin joints of a lattice
(truss) gripper boom, whose members take up their pins' clearance as their forces change sign. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* wind on a panel: a flat plate at incidence alpha to the wind takes a normal force 1/2 rho V^2 A C_N90 sin(alpha)
  |sin(alpha)| -- the cross-flow principle, C_N90 = 1.17 for a square plate (Hoerner, *Fluid-Dynamic Drag*, 1965, ch. 3
  and 13; Simiu & Scanlan, *Wind Effects on Structures*, 3rd ed., 1996, ch. 4) --, written with the wind vector V as 1/2
  rho A C_N90 (n . V) |n . V| n. Near the ground the wind gusts: the along-wind, cross-wind and vertical fluctuations
  have standard deviations I U, 0.75 I U and 0.5 I U, turbulence intensity I 0.15-0.3 (EN 1991-1-4, 4.4; ESDU 85020; the
  ratios of the turbulence components near the ground, as recalled), and a tracker's 2-5 s measurement averages little
  of them (integral time scales of 5-20 s): each pose sees its own wind. A glazing / facade / solar panel held flat on a
  vacuum frame (the panel normal along the tool axis, its centre of pressure 40-120 mm out along it), of 5-10 kg/m^2 (a
  composite facade panel, an insulated sandwich or a light module; the panel is the session's payload), mean wind 8-12.5
  m/s from a fixed direction (a site robot; panel installation stops at about 10-14 m/s, as recalled from glazing-robot
  data sheets). First drawn as glass of 10-16 kg/m^2 in 6-11 m/s (gains of 12-18 % in trial draws). The joints carry tau
  = J^T F (Craig, *Introduction to Robotics*, ch. 5) and twist with the linear gear stiffness of :mod:`hardware`; the
  panel's weight is set A's compliance and left out. ur10 and kr16_like.
* water-jet reaction: a jet leaving a nozzle at v = C_v sqrt(2 p / rho) pushes the nozzle back by its momentum flux rho
  Q v (Bernoulli and the momentum balance; Momber & Kovacevic, *Principles of Abrasive Water Jet Machining*, 1998, ch.
  2; the WaterJet Technology Association's rule F = 0.052 Q sqrt(p), lbf with gpm and psi -- 0.23 N per l/min and
  sqrt(bar)), C_v 0.95. Deburring / cleaning nozzles of 200-800 bar and 6-15 l/min on kr16_like (first 300-1000 bar and
  8-20 l/min: up to 1.1 mm at the tool), the cutter-housing cleaning lance of the tunnel machine's tool changer at
  150-400 bar and 30-80 l/min (assumed); the nozzle 150-350 / 300-600 mm out along the tool axis, the jet within 40 deg
  of it (an angled head). The pump runs in some blocks only (the measurement taken while the cleaning program runs into
  a catcher); the hose's pressure and momentum at the swivel are carried inside the tool (a closed duct) and left out.
  The joints carry tau = J^T F and twist with the linear gear stiffness. kr16_like and tool_changer.
* harness lash: axis 1 carries no gravity torque, so its drag keeps it on the flank of its last motion (the output
  trails by b / 2; Nordin & Gutman, "Controlling mechanical systems with backlash -- a survey", Automatica 38, 2002) --
  unless another torque beats the drag: the cable harness twisted through the hollow base is a torsion spring with
  friction in its guides (dress-pack guidelines limit the twist to about +-180 deg with torques of a few N m; set D's
  dress pack on the wrist): tau_h = -k_h (q1 - q_n) - f_h d, the friction held against the last motion d. The flank
  follows :func:`physics.backlash_offset` with tau_h and the output-side drag T_d. Lost motion of the cycloid axis 1
  0.5-1.5 arcmin (1 arcmin catalogue, worn), of ur10's strain-wave axis 1 its hysteresis loss 0.8-2 arcmin (a worn
  flexspline; first 0.5-1.5 arcmin: the set's 45-pose case gained 16 %, the joint model at 1.17x); harness torque at 180
  deg 3-8 / 8-25 / 30-80 N m, friction 10-30 % of it, drag 0.5-1.5 % of the rated torque, neutral twist within the
  middle 40 % of the session's range (ur10 / kr16_like / tool_changer; assumed).
* balanced lash: a counterbalance (gas spring between a pivot r1 from axis 2 on the base column and a rod eye r2 on the
  upper arm; the law of cosines of set D's gas spring, a polytropic charge of n 1.1 compressed by 20-40 % over the
  session's stroke where the gravity torque grows) takes 80-105 % of the mean gravity torque of axis 2 (a well-balanced
  arm), so the net torque on the gear changes sign inside the workspace; the cylinder's seal and guide friction, 2-5 %
  of its force (hydraulic seal friction, as recalled from seal makers' data), opposes the rod's last motion: tau_net =
  tau_g + s F(L) a - F_s |a| d2 (a the moment arm). The gear rests on the flank of tau_net where |tau_net| beats the
  output-side drag (1-3 % of the rated torque), else on the flank of its last motion (:func:`physics.backlash_offset`).
  Lost motion 0.5-1.5 arcmin (cycloid). The flank at each pose is computed once from the true loads (a shape parameter
  of the true structure: the file's geometry moves the net torque by some 0.5 N m, which flips a pose near the drag's
  threshold). kr16_like and tool_changer.
* rope creep: a rope driven by friction over a traction sheave creeps on it: along the arc of contact the rope's strain
  changes with its tension (Euler-Eytelwein), so the rope leaves the sheave longer or shorter than it came on, by (S1 -
  S2) / EA per unit of travel (Feyrer, *Wire Ropes*, 2nd ed., 2015, ch. 5 on traction sheaves and rope creep; the creep
  of belts, Johnson, *Contact Mechanics*, 1985, ch. 8) -- the load side always slipping towards the load: a telescopic
  stage whose position is read from the sheave's encoder ends each move by F |du| / EA off, F the axial load along the
  stage (positive along it) and du the travel. Ropes of 8-14 mm, metallic fill 0.5-0.6, E 90-110 GPa (Feyrer); the stage
  re-referenced at its home switch before each block (assumed). tool_changer's telescopic stage (the rope-driven
  alternative of sets K's ropes and M's chain); scored as transmission, a ratio error of the stage's drive.
* truss slack: a lattice boom of pin-jointed members (an N-truss of 3-5 panels, chords, verticals and diagonals) whose
  pins sit in worn holes: each member lengthens by half its clearance under tension and shortens by as much under
  compression (Flores, Ambrosio, Claro & Lankarani, *Kinematics and Dynamics of Multibody Systems with Imperfect
  Joints*, 2008), once its force beats the pins' friction (2-8 % of its largest force in the session); below, it stays
  (a relay). The boom's tip moves by the sum of the members' slacks times their forces under a unit tip load (the
  Williot-Mohr displacement of a statically determinate truss; unit-load method: Timoshenko & Young, *Theory of
  Structures*, 1965, ch. 8). The member forces from the in-plane gravity components of the boom's weight (lumped at its
  nodes) and of the part at the tip (statics, method of joints); the out-of-plane loads carried by a welded side plate.
  Members' clearances 0.02-0.07 mm (two pins, worn; first 0.03-0.10 mm: up to 1.2 mm at the tool), booms of 0.3-0.5 /
  0.5-0.8 / 0.7-1.1 m with 1-2 / 2-4 / 15-30 kg, depth 0.08-0.12 / 0.12-0.2 / 0.2-0.3 m (ur10 / kr16_like /
  tool_changer; assumed), the target at the tip's lower node (:func:`effects_n.probe_hook`), production before the
  session a pass through the session's loads; the members' state at each pose is computed once from the true loads (a
  shape parameter, as the counterbalanced lash's). Scored as link deflection: the end-of-arm structure carrying
  the target.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_f_joint as fj
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all
from sim2real_indep.effects_m_joint import block_index

RHO_AIR, RHO_WATER, C_N90, C_V = 1.2, 1000.0, 1.17, 0.95
Z = np.array([0.0, 0.0, 1.0])


def tool_point(ctx, offset_mm):
    """Points (P, 3) [mm] at ``offset_mm`` (3,) in the tool frame, and the tool rotation (P, 3, 3)."""
    p, Rt = kin.flange(ctx.chain, ctx.q)
    return p + Rt @ np.asarray(offset_mm, float), Rt


# ------------------------------------------------------------------------------------------------ wind on a panel
WIND_ARMS = {"ur10", "kr16_like"}


def wind_draw(ctx, hw, rng):
    if ctx.chain.name not in WIND_ARMS:
        return {}
    P = len(ctx.q)
    m = max(float(ctx.session.payload_kg.max()), 1.0)
    U, psi, I = rng.uniform(8.0, 12.5), rng.uniform(0, 2 * np.pi), rng.uniform(0.15, 0.3)
    e = np.array([np.cos(psi), np.sin(psi), 0.0])
    eps = rng.normal(size=(P, 3))
    V = U * ((1 + I * eps[:, :1]) * e + 0.75 * I * eps[:, 1:2] * np.cross(Z, e) + 0.5 * I * eps[:, 2:] * Z)
    return {"V": V, "A_m2": m / rng.uniform(5.0, 10.0), "cp_mm": np.array([0.0, 0.0, rng.uniform(40.0, 120.0)])}


def panel_force(p, Rt):
    """The panel's normal force (P, 3) [N]: 1/2 rho A C_N90 (n . V) |n . V| n, n the tool axis."""
    n = Rt[:, :, 2]
    vn = np.einsum("pi,pi->p", n, p["V"])
    return (0.5 * RHO_AIR * p["A_m2"] * C_N90 * vn * np.abs(vn))[:, None] * n


def wind_loads(p, ctx):
    """Joint loads (P, n) [N m / N] of the wind on the panel."""
    cp, Rt = tool_point(ctx, p["cp_mm"])
    return fj.point_loads(ctx, ctx.chain.n, cp, panel_force(p, Rt))


def wind_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, wind_loads(p, ctx)) if p else None)


def wind_features(p, ctx, hw):
    return _stack(_load_cols(ctx, wind_loads(p, ctx)) if p else [], len(ctx.q))


# ---------------------------------------------------------------------------------------------- water-jet reaction
#: per arm: pressure [bar], flow [l/min], nozzle distance along the tool axis [mm] (assumed)
JET = {"kr16_like": ((200.0, 800.0), (6.0, 15.0), (150.0, 350.0)),
       "tool_changer": ((150.0, 400.0), (30.0, 80.0), (300.0, 600.0))}


def jet_force(p_bar, q_lpm):
    """Reaction [N] of a jet of ``q_lpm`` [l/min] at ``p_bar`` [bar]: rho Q v, v = C_v sqrt(2 p / rho)."""
    return RHO_WATER * q_lpm / 60000.0 * C_V * np.sqrt(2 * p_bar * 1e5 / RHO_WATER)


def jet_draw(ctx, hw, rng):
    if ctx.chain.name not in JET:
        return {}
    (p0, p1), (q0, q1), (l0, l1) = JET[ctx.chain.name]
    B = int(block_index(ctx.session)[-1]) + 1
    on = rng.random(B) < 0.5
    if on.all() or not on.any():
        on[0] = not on[0]
    tilt, az = np.deg2rad(rng.uniform(0.0, 40.0)), rng.uniform(0, 2 * np.pi)
    return {"p_bar": rng.uniform(p0, p1), "q_lpm": rng.uniform(q0, q1), "on": on,
            "nozzle_mm": np.array([0.0, 0.0, rng.uniform(l0, l1)]),
            "e_jet": np.array([np.sin(tilt) * np.cos(az), np.sin(tilt) * np.sin(az), np.cos(tilt)])}


def jet_loads(p, ctx):
    """Joint loads (P, n) of the jet's reaction -F e_jet at the nozzle while the pump runs."""
    x, Rt = tool_point(ctx, p["nozzle_mm"])
    on = p["on"][block_index(ctx.session)].astype(float)
    F = -(jet_force(p["p_bar"], p["q_lpm"]) * on)[:, None] * (Rt @ p["e_jet"])
    return fj.point_loads(ctx, ctx.chain.n, x, F)


def jet_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, jet_loads(p, ctx)) if p else None)


def jet_features(p, ctx, hw):
    return _stack(_load_cols(ctx, jet_loads(p, ctx)) if p else [], len(ctx.q))


# -------------------------------------------------------------------------------------------------- harness lash
#: per arm: harness torque at 180 deg of twist [N m] (assumed)
HARNESS_NM = {"ur10": (3.0, 8.0), "kr16_like": (8.0, 25.0), "tool_changer": (30.0, 80.0)}


def harness_draw(ctx, hw, rng):
    d = hw["drives"][0]
    q = ctx.q[:, 0]
    T180 = rng.uniform(*HARNESS_NM[ctx.chain.name])
    b = rng.uniform(0.8, 2.0) if d["kind"] == "HD" else rng.uniform(0.5, 1.5)
    return {"b_rad": b * ph.ARCMIN, "k_Nm_rad": T180 / np.pi, "f_Nm": rng.uniform(0.1, 0.3) * T180,
            "q_n": q.min() + rng.uniform(0.3, 0.7) * np.ptp(q), "drag_Nm": rng.uniform(0.005, 0.015) * d["T_rated"]}


def harness_torque(p, ctx):
    """The harness's torque (P,) [N m] on axis 1: its spring about the neutral twist, its friction against the last
    motion."""
    return -p["k_Nm_rad"] * (ctx.q[:, 0] - p["q_n"]) - p["f_Nm"] * ctx.session.direction[:, 0]


def harness_side(p, ctx):
    """Flank (P,) +-1 (units of b / 2) of axis 1."""
    return ph.backlash_offset(ctx.session.direction[:, 0], harness_torque(p, ctx), p["drag_Nm"], 2.0, 0.0)


def harness_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, 0] = p["b_rad"] / 2 * harness_side(p, ctx)
    return Contribution(dq=dq)


def harness_features(p, ctx, hw):
    return ctx.joint_feature(0, harness_side(p, ctx))[None]


# ------------------------------------------------------------------------------------------------- balanced lash
#: per arm: pivot radius r1 and rod-eye radius r2 [m] of the counterbalance (assumed, as set I's balancer)
BALANCE_M = {"kr16_like": ((0.30, 0.45), (0.15, 0.25)), "tool_changer": ((0.50, 0.80), (0.25, 0.40))}


def balance_geometry(p, q2):
    """Cylinder length L (P,) [m] and moment arm a = dL/dpsi (P,) [m]."""
    psi = p["psi_mid"] + p["s"] * (q2 - p["q_mid"])
    L = np.sqrt(p["r1"] ** 2 + p["r2"] ** 2 - 2 * p["r1"] * p["r2"] * np.cos(psi))
    return L, p["r1"] * p["r2"] * np.sin(psi) / L


def balance_torque(p, q2):
    """The counterbalance's torque (P,) on axis 2 per unit F0 and its moment arm |a| (P,)."""
    L, a = balance_geometry(p, q2)
    u = (L - p["L_lo"]) / max(p["L_hi"] - p["L_lo"], 1e-12)
    V = 1.0 - p["dv"] * (u if p["grow"] > 0 else 1.0 - u)          # gas volume, compressed where gravity grows
    return p["sign"] * V ** -1.1 * a, np.abs(a)


def net_torque(p, ctx):
    """Gravity, counterbalance and seal friction on axis 2's gear (P,) [N m]."""
    shape, a = balance_torque(p, ctx.q[:, 1])
    return ctx.loads[:, 1] + p["F0_N"] * shape - p["Fs_N"] * a * ctx.session.direction[:, 1]


def balanced_draw(ctx, hw, rng):
    if ctx.chain.name not in BALANCE_M:
        return {}
    (a0, a1), (b0, b1) = BALANCE_M[ctx.chain.name]
    q2, tau = ctx.q[:, 1], ctx.loads[:, 1]
    p = {"r1": rng.uniform(a0, a1), "r2": rng.uniform(b0, b1), "psi_mid": np.deg2rad(rng.uniform(80, 110)),
         "q_mid": 0.5 * (q2.min() + q2.max()), "sign": -float(np.sign(tau.mean()) or 1.0), "s": 1.0,
         "dv": rng.uniform(0.2, 0.4)}
    L, _ = balance_geometry(p, q2)
    p.update(L_lo=float(L.min()), L_hi=float(L.max()), grow=float(np.sign(np.corrcoef(L, np.abs(tau))[0, 1]) or 1.0))
    shape, _ = balance_torque(p, q2)
    p["F0_N"] = rng.uniform(0.8, 1.05) * np.abs(tau).mean() / np.abs(shape).mean()
    p["Fs_N"] = rng.uniform(0.02, 0.05) * p["F0_N"]
    d = hw["drives"][1]
    p.update(b_rad=rng.uniform(0.5, 1.5) * d.get("lost_motion", ph.ARCMIN),
             drag_Nm=rng.uniform(0.01, 0.03) * d["T_rated"])
    p["side"] = ph.backlash_offset(ctx.session.direction[:, 1], net_torque(p, ctx), p["drag_Nm"], 2.0, 0.0)
    return p


def balanced_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 1] = p["b_rad"] / 2 * p["side"]
    return Contribution(dq=dq)


def balanced_features(p, ctx, hw):
    return ctx.joint_feature(1, p["side"])[None] if p else np.zeros((0, len(ctx.q), 3))


# ---------------------------------------------------------------------------------------------------- rope creep
ROPE_ARMS = {"tool_changer"}


def rope_draw(ctx, hw, rng):
    idx = np.flatnonzero(~ctx.chain.revolute)
    if ctx.chain.name not in ROPE_ARMS or not len(idx):
        return {}
    d = rng.uniform(8.0, 14.0)
    EA = rng.uniform(0.5, 0.6) * np.pi / 4 * d * d * rng.uniform(90e3, 110e3)   # [N]: mm^2 x N/mm^2
    return {"joint": int(idx[0]), "EA_N": EA}


def creep_signal(p, ctx):
    """The stage's position error (P,) [mm per 1/N of 1/EA]: sum over the moves since the block's start of the mean
    axial load times the travel's size, F |du| (the load side slipping towards the load)."""
    j, s = p["joint"], ctx.session
    F, u = ctx.loads[:, j], ctx.q[:, j]
    out, e = np.zeros(len(u)), 0.0
    for k in range(1, len(u)):
        e = 0.0 if s.gap_s[k] != 0 else e + 0.5 * (F[k] + F[k - 1]) * abs(u[k] - u[k - 1])
        out[k] = e
    return out


def rope_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = creep_signal(p, ctx) / p["EA_N"]
    return Contribution(dq=dq)


def rope_features(p, ctx, hw):
    return ctx.joint_feature(p["joint"], creep_signal(p, ctx))[None] if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------------- truss slack
#: per arm: boom length range [mm] (the target's mapping), depth [mm], boom mass [kg] (assumed)
TRUSS = {"ur10": ((300.0, 500.0), (80.0, 120.0), (1.0, 2.0)), "kr16_like": ((500.0, 800.0), (120.0, 200.0), (2.0, 4.0)),
         "tool_changer": ((700.0, 1100.0), (200.0, 300.0), (15.0, 30.0))}
CHORD_Z_MM = 40.0   # the lower chord's height along the tool axis: the boom's root plate on the flange


def truss_geometry(L, h, N):
    """Nodes (2N + 2, 2) [mm] in the boom's plane (along the boom, along the tool axis), members (4N, 2) node pairs;
    nodes 0 and 1 the supports at the root (lower, upper), the lower tip node last but one."""
    nodes = [(0.0, CHORD_Z_MM), (0.0, CHORD_Z_MM + h)]
    mem = []
    for i in range(1, N + 1):
        x = L * i / N
        nodes += [(x, CHORD_Z_MM), (x, CHORD_Z_MM + h)]
        lo0, up0, lo1, up1 = 2 * i - 2, 2 * i - 1, 2 * i, 2 * i + 1
        mem += [(lo0, lo1), (up0, up1), (lo1, up1), (lo0, up1) if i % 2 else (up0, lo1)]
    return np.array(nodes), np.array(mem)


def truss_matrix(nodes, mem):
    """Equilibrium of the free nodes: member forces (tension +) -> nodal forces; (2 free, m)."""
    free = np.arange(2, len(nodes))
    A = np.zeros((2 * len(free), len(mem)))
    for k, (a, b) in enumerate(mem):
        u = (nodes[b] - nodes[a]) / np.linalg.norm(nodes[b] - nodes[a])
        for node, sgn in ((a, 1.0), (b, -1.0)):
            if node >= 2:
                i = 2 * (node - 2)
                A[i:i + 2, k] += sgn * u        # a tension pulls node a towards b
    return A


def truss_unit(p):
    """Member forces (2, m) per unit gravity along the boom and along the tool axis (the boom's and the part's
    weight), per kg of part (2, m), and under unit tip loads along both (2, m)."""
    nodes, mem = truss_geometry(p["L_mm"], p["h_mm"], p["N"])
    A = truss_matrix(nodes, mem)
    free = len(nodes) - 2
    tip = 2 * (free - 2)                                          # the lower tip node's rows
    own = np.zeros((2, 2 * free))
    own[0, 0::2] = own[1, 1::2] = p["m_boom_kg"] / free
    part = np.zeros((2, 2 * free))
    part[0, tip], part[1, tip + 1] = 1.0, 1.0
    solve = lambda f: np.linalg.solve(A, -f.T).T                 # A N + f = 0
    return solve(own), solve(part), solve(part)


def truss_forces(p, ctx):
    """Member forces (m, P) [N] at the session's poses."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, -kin.G * Z)                  # gravity in the tool frame
    gin = np.stack([g @ p["d"], g[:, 2]], axis=1)                 # along the boom and along the tool axis
    own, part, _ = truss_unit(p)
    return (gin @ own + (ctx.session.payload_kg[:, None] * gin) @ part).T


def truss_draw(ctx, hw, rng):
    if ctx.chain.name not in TRUSS:
        return {}
    (_, _), (h0, h1), (m0, m1) = TRUSS[ctx.chain.name]
    d = np.array([ctx.probe_mm[0], ctx.probe_mm[1], 0.0])
    N = int(rng.integers(3, 6))
    p = {"d": d / np.linalg.norm(d), "L_mm": float(np.linalg.norm(d)), "h_mm": rng.uniform(h0, h1), "N": N,
         "m_boom_kg": rng.uniform(m0, m1), "c_mm": rng.uniform(0.02, 0.07, 4 * N)}
    F = truss_forces(p, ctx)
    f = rng.uniform(0.02, 0.08, len(F)) * np.abs(F).max(axis=1)
    side = rng.choice([-1.0, 1.0], len(F))
    for k in range(F.shape[1]):                                   # production: a pass through the session's loads
        side = np.where(np.abs(F[:, k]) > f, np.sign(F[:, k]), side)
    out = np.zeros_like(F)
    for k in range(F.shape[1]):
        side = np.where(np.abs(F[:, k]) > f, np.sign(F[:, k]), side)
        out[:, k] = side
    p["side"] = out
    return p


def truss_parts(p, ctx):
    """(m, P, 3): the tip's displacement per unit half-clearance of each member (its side times its force under the
    unit tip loads), base frame."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    _, _, unit = truss_unit(p)
    local = p["side"][:, :, None] * (unit[0][:, None, None] * p["d"] + unit[1][:, None, None] * Z)
    return np.einsum("pij,mpj->mpi", Rt, local)


def truss_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("m,mpi->pi", p["c_mm"] / 2, truss_parts(p, ctx)) if p else None)


def truss_features(p, ctx, hw):
    return truss_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))
