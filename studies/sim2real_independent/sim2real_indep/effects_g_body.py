"""Set G body effects (new physics, not in sets A-F): a mobile platform parked on four hydraulic jacks that leak
down under their loads; a table on self-levelling air isolators whose valves leave each support inside a dead band;
CFRP tube links whose unbalanced layup couples bending and twist; the target on a carbon extension rod sagging
under the reflector's weight; the wrist shafts tilting inside the radial clearance of their bearing pairs. Same
protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* leaking jacks: a jack's oil column is a spring beta A / L (hydraulic stiffness beta A^2 / V; Merritt, *Hydraulic
  Control Systems*, 1967, beta 1-1.5 GPa with hoses) and leaks past its seals and holding valve Q = C_l p (laminar
  leakage, Merritt), so it sinks at a rate proportional to its load: drift tests of load-holding cylinders
  (ISO 10100 acceptance tests, mobile elevating platforms' drift limits, as recalled). A rigid platform on four
  equal supports at (+-a, +-a) shares the weight W and the moment M as R_i = W / 4 + (M_y x_i - M_x y_i) / 4a^2
  (statics); sink rate 0.05-0.2 mm/h at the mean support load of robot and platform (platform 200-400 /
  500-900 / 1500-3000 kg, a 0.4-0.6 / 0.5-0.8 / 0.7-1.0 m on ur10 / kr16_like / tool_changer, column stiffness
  5-20 N/um; assumed). The load is held through the pauses (brakes on at the last pose); during production the
  mean of the session's loads.
* self-levelling isolators: a pneumatic isolator's height-control valve admits or vents air until the support is
  back inside its dead band +-d (Newport / TMC application notes on self-levelling isolation; three valves define
  the plane, two isolators sharing one valve, as recalled). The air springs are soft (a few N/mm), so every load
  change sweeps the support through its band: its height is a stop operator of the elastic sink -R_i / k
  (Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989): clip(z + dx, -d, d) along the load path (a
  straight path between poses, the session's poses in turn during production). d 0.02-0.06 mm, k 5-20 N/mm,
  supports at +-a (as the platform above), table 100-300 mm thick (assumed).
* bend-twist coupling: a thin-walled composite tube with a circumferentially asymmetric (unbalanced) layup couples
  bending about one section axis n with twist: [kappa_n, phi'] = [[1/EI, c], [c, 1/GJ]] [M_n, T], c = psi /
  sqrt(EI GJ), |psi| < 1 (Chandra, Stemple & Chopra, "Thin-walled composite beams under bending, torsional, and
  extensional loads", J. Aircraft 27(7), 1990; Hodges, *Nonlinear Composite Beam Theory*, 2006). CFRP tubes of
  the drawn diameters, wall 3-6 mm (E_x 70-110 GPa, G 15-25 GPa, 1600 kg/m^3, Cowper's k at nu = 0.3; |psi|
  0.15-0.4, n at random round the section; assumed; first given the drawn walls, up to 20 mm on kr16_like, which
  left the coupling absorbed) on the tube links of 400 mm or more past joint 2; they bend, shear and twist as
  cantilevers (:func:`physics.cantilever_tip`) plus the coupling's twist c int M_n dx and curvature c T.
* extension rod: the reflector (1.5" SMR and nest, 0.1-0.25 kg) on a pultruded carbon rod along the target offset
  (rods of 250-600 mm, 14-25 mm, wall 1.5-3 mm, E 100-140 GPa; assumed; extension bars of tracker target sets):
  cantilever tip deflection (P L^3 / 3 + w L^4 / 8) / EI along the gravity component normal to the rod (Timoshenko &
  Gere, *Mechanics of Materials*). The target offset drawn for the case is lengthened to the rod (see
  :func:`effects_g.probe_hook`).
* bearing-pair clearance: a shaft in two radial bearings of clearance c_r at a spacing s tilts c_r / s towards the
  moment normal to its axis once that moment beats the friction (2-8 % of its largest value; below that it stays);
  ISO 5753-1 radial internal clearance, groups C3 / C4, 15-45 um for bores of 30-150 mm (as recalled); s 30-70 /
  50-120 mm on the light / heavy arms' wrist joints (unpreloaded deep-groove pairs instead of a preloaded
  crossed-roller bearing; assumed; first drawn at 10-30 um over 40-100 / 80-200 mm, absorbed on tool_changer).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_g_joint import joint_wrench

Z = np.array([0.0, 0.0, 1.0])
#: half-spacing of the supports [m] and platform mass [kg] per arm (assumed)
SUPPORT = {"ur10": ((0.4, 0.6), (200, 400)), "kr16_like": ((0.5, 0.8), (500, 900)),
           "tool_changer": ((0.7, 1.0), (1500, 3000))}


def _weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G


def held_integral(ctx, X):
    """Time integral (P, d) [X s] of a per-pose quantity X (P, d) up to each measurement: held through dwells,
    ramped over moves, the last pose's value over pauses, the session mean over production periods."""
    s = ctx.session
    prev = np.vstack([X[:1], X[:-1]])
    gap = np.where(s.gap_s > 0, 1.0, 0.0)[:, None] * X.mean(axis=0) + np.where(s.gap_s < 0, 1.0, 0.0)[:, None] * prev
    seg = np.abs(s.gap_s)[:, None] * gap + s.move_s[:, None] * (prev + X) / 2 + s.dwell_s[:, None] * X
    return np.cumsum(seg, axis=0)


def _plate_motion(ctx, tilt_xy, sink, ref_mm):
    """Displacement (P, 3) [mm] of the target for plate tilts (P, 2) [rad] about x, y through ``ref_mm`` (3,)
    and sinks (P,) [mm]."""
    omega = np.c_[tilt_xy, np.zeros(len(tilt_xy))]
    return np.cross(omega, ctx.target - ref_mm) - sink[:, None] * Z


# ------------------------------------------------------------------------------------------ leaking jacks
def leak_draw(ctx, hw, rng):
    (alo, ahi), (mlo, mhi) = SUPPORT[ctx.chain.name]
    W_p = rng.uniform(mlo, mhi) * kin.G
    F_mean = (_weight(ctx).mean() + W_p) / 4
    return {"a_m": rng.uniform(alo, ahi), "W_platform_N": W_p, "k_N_per_m": rng.uniform(5, 20) * 1e6,
            "lambda_m_per_Ns": rng.uniform(0.05, 0.2) * 1e-3 / 3600 / F_mean, "h_ref_mm": rng.uniform(0, 300)}


def leak_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per unit support compliance [m/N] and per unit leak rate [m/(N s)]."""
    M = eb.mount_moment(ctx)[:, :2]
    W = (_weight(ctx) + p["W_platform_N"])[:, None]
    X = np.hstack([M, W])
    ref = np.array([0.0, 0.0, -p["h_ref_mm"]])
    out = []
    for Y in (X, held_integral(ctx, X)):                  # support loads now; their time integral
        tilt = Y[:, :2] / (4 * p["a_m"] ** 2)             # [rad per m/N]: omega = (M_x, M_y) / 4a^2 per unit
        out.append(_plate_motion(ctx, tilt, 1000.0 * Y[:, 2] / 4, ref))
    return np.array(out)


def leak_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["k_N_per_m"], p["lambda_m_per_Ns"]],
                                           leak_parts(p, ctx)))


def leak_features(p, ctx, hw):
    return leak_parts(p, ctx)


# ---------------------------------------------------------------------------------------- air isolators
def air_draw(ctx, hw, rng):
    (alo, ahi), _ = SUPPORT[ctx.chain.name]
    return {"a_m": rng.uniform(alo, ahi), "k_N_per_mm": rng.uniform(5, 20), "band_mm": rng.uniform(0.02, 0.06),
            "h_ref_mm": rng.uniform(100, 300)}


def valve_sinks(p, ctx):
    """Elastic sink (P, 3) [mm] of the three valves' supports (corner (a, a), corner (-a, a), the pair at y = -a)."""
    M = eb.mount_moment(ctx)
    W = _weight(ctx)
    a = p["a_m"]
    R = lambda x, y: W / 4 + (M[:, 1] * x - M[:, 0] * y) / (4 * a * a)  # noqa: E731
    return np.c_[R(a, a), R(-a, a), (R(-a, -a) + R(a, -a)) / 2] / p["k_N_per_mm"]


def valve_heights(p, ctx):
    """Support heights (P, 3) [mm] after levelling: stop operators of the elastic sinks (levelled at pose 1)."""
    x = -valve_sinks(p, ctx)
    gap, d = ctx.session.gap_s, p["band_mm"]
    z, prev, out = np.zeros(3), x[0], np.zeros_like(x)
    for i, xi in enumerate(x):
        path = list(x) if gap[i] > 0 else []           # production: a pass through the session's loads
        for y in path + [xi]:
            z = np.clip(z + (y - prev), -d, d)
            prev = y
        out[i] = z
    return out


def air_parts(p, ctx):
    """Target displacement (3, P, 3) [mm] per mm of each valve's support height."""
    a = 1000.0 * p["a_m"]
    ref = np.array([0.0, 0.0, -p["h_ref_mm"]])
    P = len(ctx.q)
    # plane through (a, a), (-a, a), (0, -a): gx = (zA - zB) / 2a, gy = (zA + zB - 2 zC) / 4a, z0 = (zA + zB + 2 zC) / 4
    gx, gy, z0 = np.array([1, -1, 0]) / (2 * a), np.array([1, 1, -2]) / (4 * a), np.array([1, 1, 2]) / 4
    return np.array([_plate_motion(ctx, np.tile([gy[k], -gx[k]], (P, 1)), np.full(P, -z0[k]), ref)
                     for k in range(3)])


def air_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("pk,kpi->pi", valve_heights(p, ctx), air_parts(p, ctx)))


def air_features(p, ctx, hw):
    z = valve_heights(p, ctx)
    return air_parts(p, ctx) * z.T[:, :, None]


# ----------------------------------------------------------------------------------------- bend-twist tubes
def cfrp_draw(ctx, hw, rng):
    ch, out = ctx.chain, {}
    for name, tb in hw["tubes"].items():
        li = ch.link_names.index(name)
        if ch.link_body[li] < 2 or np.linalg.norm(ch.links[li]) < 400:
            continue
        e0 = ch.links[li] / np.linalg.norm(ch.links[li])
        u = np.cross(e0, [1.0, 0, 0] if abs(e0[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        phi = rng.uniform(0, 2 * np.pi)
        E, G = rng.uniform(70, 110) * 1e9, rng.uniform(15, 25) * 1e9
        psi = rng.uniform(0.15, 0.4) * rng.choice([-1, 1])
        D = np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2)     # the drawn tube's outer diameter [m]
        A, I, J = ph.tube_section(D, rng.uniform(3.0, 6.0) / 1000)
        out[name] = {"n_home": np.cos(phi) * u + np.sin(phi) * np.cross(e0, u), "E": E, "G": G, "A": A, "I": I,
                     "J": J, "k": ph.cowper_k_thin_tube(0.3), "c": psi / np.sqrt(E * I * G * J), "rho": 1600.0}
    return out


def span_moment_integral(M_tip, F, w, e, L):
    """int_0^L M(x) dx [N m^2] of the section moment M(x) = M_tip + (L - x) e x F + (L - x)^2 / 2 e x w of a
    cantilever (tip moment and force (P, 3), uniform load w (P, 3) or (3,) [N/m], axis e (P, 3), length L [m])."""
    return L * M_tip + L ** 2 / 2 * np.cross(e, F) + L ** 3 / 6 * np.cross(e, np.broadcast_to(w, np.shape(e)))


def coupling_displacement(ctx, li, s):
    """Target displacement (P, 3) [mm] per unit coupling compliance c [1 / (N m^2)] of link ``li``."""
    e, tip, L = eb._beam_state(ctx, li)
    F, M_tip, w = eb._beam_loads(ctx, li)
    if ctx.chain.link_names[li] not in ctx.mass_link:
        w = s["rho"] * s["A"] * eb.GRAVITY_N
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    n = R[:, ctx.chain.link_body[li]] @ s["n_home"]
    dot = lambda a, b: np.einsum("pi,pi->p", a, b)[:, None]  # noqa: E731
    I_n = dot(span_moment_integral(M_tip, F, w, e, L), n)
    T = dot(M_tip, e)
    rot = I_n * e + T * L * n                                    # twist from bending, bending from torque
    return 1000.0 * T * np.cross(n, e) * L ** 2 / 2 + np.cross(rot, ctx.target - tip)


def _cfrp_columns(p, ctx):
    cols, amp = [], []
    for name, s in p.items():
        li = ctx.chain.link_names.index(name)
        w = None if name in ctx.mass_link else s["rho"] * s["A"] * eb.GRAVITY_N
        cols += [eb._beam_displacement(ctx, li, 1.0, np.inf, np.inf, w),
                 eb._beam_displacement(ctx, li, np.inf, 1.0, np.inf, w),
                 eb._beam_displacement(ctx, li, np.inf, np.inf, 1.0, w), coupling_displacement(ctx, li, s)]
        amp += [1 / (s["E"] * s["I"]), 1 / (s["k"] * s["G"] * s["A"]), 1 / (s["G"] * s["J"]), s["c"]]
    return np.array(cols), np.array(amp)


def cfrp_apply(p, ctx, hw):
    cols, amp = _cfrp_columns(p, ctx)
    return Contribution(displace=np.einsum("k,kpi->pi", amp, cols))


def cfrp_features(p, ctx, hw):
    return _cfrp_columns(p, ctx)[0]


# -------------------------------------------------------------------------------------------- extension rod
def rod_draw(ctx, hw, rng):
    L = np.linalg.norm(ctx.probe_mm) / 1000.0
    D, t = rng.uniform(14, 25) / 1000, rng.uniform(1.5, 3.0) / 1000
    I = np.pi / 64 * (D ** 4 - (D - 2 * t) ** 4)
    w = 1550.0 * np.pi / 4 * (D ** 2 - (D - 2 * t) ** 2) * kin.G
    EI = rng.uniform(100, 140) * 1e9 * I
    m_tip = rng.uniform(0.1, 0.25)
    return {"L_m": L, "EI": EI, "m_tip_kg": m_tip,
            "sag_mm": 1000.0 * (m_tip * kin.G * L ** 3 / 3 + w * L ** 4 / 8) / EI}


def rod_direction(ctx):
    """Unit gravity component normal to the rod (P, 3) (the rod along the target offset)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    u = Rt @ (ctx.probe_mm / np.linalg.norm(ctx.probe_mm))
    g = -Z
    return g - np.einsum("pi,i->p", u, g)[:, None] * u


def rod_apply(p, ctx, hw):
    return Contribution(displace=p["sag_mm"] * rod_direction(ctx))


def rod_features(p, ctx, hw):
    return rod_direction(ctx)[None]


# ------------------------------------------------------------------------------------- bearing clearance
def clear_draw(ctx, hw, rng):
    heavy = ctx.chain.name != "ur10"
    _, M, w, _ = joint_wrench(ctx)
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[3:]) + 3:
        Mp = M[:, j] - np.einsum("pi,pi->p", M[:, j], w[:, j])[:, None] * w[:, j]
        out.append({"joint": int(j), "theta_rad": rng.uniform(0.015, 0.045) / rng.uniform(*((50, 120) if heavy
                                                                                            else (30, 70))),
                    "M_friction_Nm": rng.uniform(0.02, 0.08) * np.linalg.norm(Mp, axis=1).max(),
                    "start_angle": rng.uniform(0, 2 * np.pi)})
    return out


def clear_tilt(g, ctx, wrench=None, R=None):
    """Unit tilt (P, 3) of the shaft in the base frame: towards the normal moment once it beats friction, else
    where it was (kept in the housing's frame)."""
    _, M, w, _ = joint_wrench(ctx) if wrench is None else wrench
    R = kin.body_transforms(ctx.chain, ctx.q)[0] if R is None else R
    j = g["joint"]
    Mp = M[:, j] - np.einsum("pi,pi->p", M[:, j], w[:, j])[:, None] * w[:, j]
    a0 = ctx.chain.axes[j]
    u = np.cross(a0, [1.0, 0, 0] if abs(a0[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    state = np.cos(g["start_angle"]) * u + np.sin(g["start_angle"]) * np.cross(a0, u)   # housing frame
    out = np.zeros_like(Mp)
    for i in range(len(Mp)):
        n = np.linalg.norm(Mp[i])
        if n > g["M_friction_Nm"]:
            state = R[i, j].T @ (Mp[i] / n)
        out[i] = R[i, j] @ state
    return out


def clear_parts(p, ctx):
    wrench = joint_wrench(ctx)
    R = kin.body_transforms(ctx.chain, ctx.q)[0]
    c = wrench[3]
    return np.array([np.cross(clear_tilt(g, ctx, wrench, R), ctx.target - c[:, g["joint"]]) for g in p])


def clear_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [g["theta_rad"] for g in p], clear_parts(p, ctx)))


def clear_features(p, ctx, hw):
    return clear_parts(p, ctx)
