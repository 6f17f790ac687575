"""Set J joint effects (new physics, not in sets A-I): a planetary output stage whose planets sample the ring gear's
form error; a bevel-gear differential wrist mixing its two side-gear trains' errors into pitch and roll; a joint's
bolted output flange that slips inside its bolt-hole clearance; pin clearances in a parallelogram's link bar; a dress
pack's retraction spring pulling the tool towards the forearm; the torsion of a coupled wrist's long drive shafts.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* planetary stage (ring fixed, carrier = output, floating sun): a planet rolling between the sun (held by the input)
  and the ring moves by half the sum of the tooth deviations at its two meshes, and the rigid carrier takes the
  planets' mean, so the ring's tangential deviation F(psi) sampled by Np equally spaced planets keeps only its
  harmonics k = 0 mod Np (eccentricity and ovality cancel); a planet's eccentricity e_i shifts its pin by -e_i
  sin(spin + beta_i), the spin -(Zr / Zp) per carrier turn (Kahraman, "Load sharing characteristics of planetary
  transmissions", Mech. Mach. Theory 29(8), 1994; Bodas & Kahraman, JSME Int. J. C 47(3), 2004; Inalpolat &
  Kahraman, J. Sound Vib. 323, 2009, on the planets' phasing): dtheta = mean_i F(theta + 2 pi i / Np) / (2 r_c) -
  mean_i e_i sin(-(Zr / Zp) theta + beta_i) / r_c. Assembly (Zr + Zs) / Np integer, Zr = Zs + 2 Zp. Ring harmonics
  1..2Np of 30-70 um / k^0.7 (x 0.5-1: a ring shaped and heat-treated, not ground), planets 3-10 um, carrier radius
  by arm; the main axes of arms built with planetary output stages (assumed).
* differential wrist: side bevel gears A, B, each driven by its own train, and an output bevel on the roll axis
  between them give pitch = (theta_A + theta_B) / 2, roll = (theta_A - theta_B) / (2 i), i = Z_out / Z_side
  (roll-pitch differential wrists: Rosheim, *Robot Wrist Actuators*, 1989; Craig, *Introduction to Robotics*, ch. 8),
  so each train's error -- its side gear's runout once per turn, its drive pinion's at Z_side / z_p per turn (ISO
  17485 bevel gears of grade 10-11, as recalled: eccentricities 15-35 / 8-20 um on pitch radii of 20-35 / 35-55 mm
  on kr16_like / tool_changer; assumed) -- reaches both joints: dq_p = (e_A + e_B) / 2, dq_r = (e_A - e_B) / (2 i).
  Axes 5-6 of the arms with motor-driven wrists (none on ur10).
* flange slip: a link bolted to its joint's output flange through clearance holes holds by friction up to the slip
  torque mu n F_V r_b (VDI 2230 Part 1; EN 1993-1-8 3.9); bolts that lost preload (embedding, self-loosening: Junker,
  SAE 690055, 1969) let a torque beyond +-T_s turn the link across its travel c / r_b, where it stays until a torque
  beyond the other threshold: a non-ideal relay in the joint torque (Krasnosel'skii & Pokrovskii, *Systems with
  Hysteresis*, 1989). Travel 0.01-0.05 mm on bolt circles by arm, T_s 30-70 % of the smaller of the session's two
  extreme loads (assumed), the path monotone between poses, production and the time before the session a pass
  through the session's loads; the joints whose loads take both signs.
* bar pins: a parallelogram's link bar (crank r on the base side, lever on the forearm) is made longer or shorter by
  half its pins' diametral clearance c as its force pulls or pushes it (Flores, Ambrosio, Claro & Lankarani,
  *Kinematics and Dynamics of Multibody Systems with Imperfect Joints*, 2008), turning the forearm by delta / (r sin
  gamma), gamma between the bar (parallel to the upper arm) and the lever (first order in the four-bar's loop
  equation; Hartenberg & Denavit, *Kinematic Synthesis of Linkages*, 1964): dq3 = +-c / (2 r sin gamma). The bar
  force follows tau_3 once |tau_3| beats the pins' drag (2-8 % of its largest value); below, the bar trails the
  crank's last motion, the sign of d(q2 + q3). Worn bushings, c 0.06-0.24 mm (ISO 286 running fits 0.01-0.05 mm per
  pin), r 0.15-0.3 m, gamma 80-100 deg at mid-range (assumed, as set G's bar). tool_changer and kr16_like.
* retraction: a dress-pack retract unit on the forearm pulls the hose back through a guide ring with a nearly
  constant spring force F0 (20-250 N by size, as recalled from dress-pack catalogues) and a rate of 5-20 % over the
  session's pull-out; the hose pulls its clamp on the tool towards the ring -- an internal force, carried only by the
  joints between forearm and tool: tau_j = w_j . ((p_clamp - c_j) x F) (statics, Craig, ch. 5). Those joints twist
  with the linear gear stiffness of :mod:`hardware` under gravity plus the pull (the main axes' twist is set A's and
  left out). Ring 80-150 mm off the forearm's far end, clamp 50-120 mm off the tool axis, 30-100 mm along it (assumed).
* wrist drive shafts: a coupled wrist with its reducers at the forearm's rear drives axes 5-6 through long hollow
  shafts and final bevel stages of ratio N2; with actuator angles a = G q, G = diag(N2) (I + C) (Craig, ch. 8; set
  H's coupling factors), virtual work gives shaft torques G^-T tau and joint deflections G^-1 diag(L / GJ) G^-T tau
  (Rivin, *Stiffness and Damping in Mechanical Design*, 1999, ch. 2). Steel tubes of 30-40 / 45-70 x 3-5 / 5-8 mm,
  0.5-0.7 / 0.7-1 m long, N2 1.5-3 / 2.5-4 on kr16_like / tool_changer (assumed; first drawn at 2-3.5 / 3-5: the twist
  near the noise); the wrist gears twist under gravity as well (the main axes' as set A's). None on ur10.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_h_joint import _ratio, train_direction, wrist_pairs
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all

TWO_PI = 2 * np.pi


# -------------------------------------------------------------------------------------------- planetary stage
#: carrier radius [m] by arm (assumed)
PLANET_RC_M = {"ur10": (0.035, 0.06), "kr16_like": (0.05, 0.08), "tool_changer": (0.08, 0.14)}


def planet_teeth(rng, Np):
    """Sun, planet and ring teeth (Zs, Zp, Zr) of an assemblable stage: Zr = Zs + 2 Zp, (Zr + Zs) / Np integer,
    ratio 1 + Zr / Zs of 3.5-6."""
    while True:
        Zs = int(rng.integers(15, 31))
        Zp = int(rng.integers(Zs * 3 // 4, 2 * Zs + 1))
        Zr = Zs + 2 * Zp
        if (Zr + Zs) % Np == 0 and 2.5 <= Zr / Zs <= 5.0:
            return Zs, Zp, Zr


def planet_draw(ctx, hw, rng):
    out = []
    for j in [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j < 3]:
        Np = int(rng.choice([3, 4, 5]))
        teeth = planet_teeth(rng, Np)
        k = np.arange(1, 2 * Np + 1)
        out.append({"joint": j, "Np": Np, "teeth": teeth, "r_c_m": rng.uniform(*PLANET_RC_M[ctx.chain.name]),
                    "ring_um": rng.uniform(30, 70) * rng.uniform(0.5, 1.0, len(k)) / k ** 0.7,
                    "ring_phase": rng.uniform(0, TWO_PI, len(k)), "ecc_um": rng.uniform(3, 10, Np),
                    "ecc_phase": rng.uniform(0, TWO_PI, Np)})
    return out


def ring_deviation(g, psi):
    """Tangential deviation [um] of the ring's teeth at ring angles ``psi`` (any shape)."""
    k = np.arange(1, len(g["ring_um"]) + 1)
    return np.sum(g["ring_um"] * np.sin(np.multiply.outer(psi, k) + g["ring_phase"]), axis=-1)


def planet_error(g, theta):
    """Carrier (output) angle error (P,) [rad] at carrier angles ``theta`` (P,): the planets' mean of half the ring's
    deviation at each planet and of each planet's pin shift by its eccentricity."""
    Np, (_, Zp, Zr), rc = g["Np"], g["teeth"], g["r_c_m"] * 1e6
    at = theta[:, None] + TWO_PI * np.arange(Np) / Np
    spin = -(Zr / Zp) * theta
    pins = g["ecc_um"] * np.sin(spin[:, None] + g["ecc_phase"])
    return ring_deviation(g, at).mean(axis=1) / (2 * rc) - pins.mean(axis=1) / rc


def planet_orders(g):
    """The orders per carrier turn that reach the output: ring harmonics k Np, the planets' spin Zr / Zp."""
    return [float(k) for k in range(g["Np"], len(g["ring_um"]) + 1, g["Np"])] + [g["teeth"][2] / g["teeth"][1]]


def planet_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] += planet_error(g, ctx.q[:, g["joint"]])
    return Contribution(dq=dq)


def planet_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], f(o * ctx.q[:, g["joint"]])) for g in p for o in planet_orders(g)
                   for f in (np.sin, np.cos)], len(ctx.q))


# ---------------------------------------------------------------------------------------- differential wrist
#: arms given a roll-pitch differential on axes 5-6: side-gear pitch radius [m]
DIFF_R_M = {"kr16_like": (0.02, 0.035), "tool_changer": (0.035, 0.055)}


def diff_draw(ctx, hw, rng):
    if ctx.chain.name not in DIFF_R_M:
        return {}
    trains = []
    for sign in (1.0, -1.0):
        z_s, z_p = int(rng.integers(30, 51)), int(rng.integers(12, 21))
        ecc = np.array([rng.uniform(15, 35), rng.uniform(8, 20)]) * 1e-6
        trains.append({"sign": sign, "orders": np.array([1.0, z_s / z_p]),
                       "amp_rad": ecc / rng.uniform(*DIFF_R_M[ctx.chain.name]), "phase": rng.uniform(0, TWO_PI, 2)})
    return {"pitch": 4, "roll": 5, "i": int(rng.integers(25, 46)) / int(rng.integers(25, 46)), "trains": trains}


def side_angle(p, t, q):
    """Side gear angle (P,) [rad]: pitch + i roll (gear A), pitch - i roll (gear B)."""
    return q[:, p["pitch"]] + t["sign"] * p["i"] * q[:, p["roll"]]


def diff_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for t in p.get("trains", []):
        phi = side_angle(p, t, ctx.q)
        e = np.sum(t["amp_rad"] * np.sin(np.multiply.outer(phi, t["orders"]) + t["phase"]), axis=1)
        dq[:, p["pitch"]] += e / 2
        dq[:, p["roll"]] += t["sign"] * e / (2 * p["i"])
    return Contribution(dq=dq)


def diff_features(p, ctx, hw):
    sig = [(t, f(o * side_angle(p, t, ctx.q))) for t in p.get("trains", []) for o in t["orders"]
           for f in (np.sin, np.cos)]
    return _stack([ctx.joint_feature(p["pitch"], s / 2) + ctx.joint_feature(p["roll"], t["sign"] * s / (2 * p["i"]))
                   for t, s in sig], len(ctx.q))


# -------------------------------------------------------------------------------------------- flange slip
#: bolt-circle radius [m] of the output flanges: main axes 1-3, wrist axes (assumed)
SLIP_R_M = {"ur10": ((0.04, 0.06), (0.025, 0.04)), "kr16_like": ((0.06, 0.10), (0.03, 0.05)),
            "tool_changer": ((0.10, 0.16), (0.05, 0.08))}


def slip_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        tau = ctx.loads[:, j]
        reach = min(tau.max(), -tau.min())
        if reach <= 0.1 * np.abs(tau).max() or reach < 1.0:
            continue
        r = rng.uniform(*SLIP_R_M[ctx.chain.name][0 if j < 3 else 1])
        out.append({"joint": int(j), "T_s": rng.uniform(0.3, 0.7) * reach,
                    "half_rad": rng.uniform(0.01, 0.05) / 2e3 / r})
    return out


def relay(tau, T_s, gap_s):
    """Side (P,) +-1 of the slipped flange: +1 once the torque passed +T_s, -1 once it passed -T_s, else kept;
    production periods (gap > 0) and the time before the session a pass through the session's torques."""
    def step(s, t):
        return 1.0 if t > T_s else (-1.0 if t < -T_s else s)

    def production(s):
        for t in tau:
            s = step(s, t)
        return s

    s, out = production(1.0), np.zeros(len(tau))
    for k, t in enumerate(tau):
        if k > 0 and gap_s[k] > 0:
            s = production(s)
        s = step(s, t)
        out[k] = s
    return out


def slip_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["half_rad"] * relay(ctx.loads[:, g["joint"]], g["T_s"], ctx.session.gap_s)
    return Contribution(dq=dq)


def slip_features(p, ctx, hw):
    return _stack([ctx.joint_feature(g["joint"], relay(ctx.loads[:, g["joint"]], g["T_s"], ctx.session.gap_s))
                   for g in p], len(ctx.q))


# ----------------------------------------------------------------------------------------------- bar pins
#: arms given a parallelogram-driven axis 3 (axes 2 and 3 parallel)
PIN_ARMS = {"kr16_like", "tool_changer"}


def pin_draw(ctx, hw, rng):
    if ctx.chain.name not in PIN_ARMS:
        return {}
    q3, tau = ctx.q[:, 2], ctx.loads[:, 2]
    return {"r_m": rng.uniform(0.15, 0.3), "gamma_mid": np.deg2rad(rng.uniform(80, 100)),
            "q_mid": 0.5 * (q3.min() + q3.max()), "c_mm": rng.uniform(0.03, 0.12, 2).sum(),
            "T_f": rng.uniform(0.02, 0.08) * np.abs(tau).max()}


def pin_signal(p, ctx):
    """dq3 per unit c / 2r (P,): the flank (+-1) over sin(gamma); the flank the load's once |tau_3| > T_f, else
    trailing the crank's last motion (the sign of d(q2 + q3))."""
    tau = ctx.loads[:, 2]
    crank = train_direction({"joint": 2, "c": {1: 1.0}}, ctx.session)
    flank = np.where(np.abs(tau) > p["T_f"], np.sign(tau), -crank)
    return flank / np.sin(p["gamma_mid"] + ctx.q[:, 2] - p["q_mid"])


def pin_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, 2] = p["c_mm"] / 2e3 / p["r_m"] * pin_signal(p, ctx) if p else 0.0
    return Contribution(dq=dq)


def pin_features(p, ctx, hw):
    return _stack([ctx.joint_feature(2, pin_signal(p, ctx))] if p else [], len(ctx.q))


# --------------------------------------------------------------------------------------------- retraction
#: per arm: retract force F0 [N], ring offset [mm], clamp offset off / along the tool axis [mm] (assumed)
RETRACT = {"ur10": ((20, 60), (80, 150), (50, 120), (30, 100)),
           "kr16_like": ((50, 150), (80, 150), (50, 120), (30, 100)),
           "tool_changer": ((100, 250), (100, 150), (80, 150), (50, 120))}
RETRACT_BODY = 3  # the body carrying the forearm: the retract unit and its guide ring


def retract_draw(ctx, hw, rng):
    ch = ctx.chain
    F0, ring, off, along = RETRACT[ch.name]
    on = np.flatnonzero(ch.link_body == RETRACT_BODY)
    li = on[np.argmax(np.linalg.norm(ch.links[on], axis=1))]
    e = ch.links[li] / np.linalg.norm(ch.links[li])
    u = np.cross(e, rng.normal(size=3))
    a = rng.uniform(0, TWO_PI)
    p = {"ring_home": np.cumsum(ch.links, axis=0)[li] + rng.uniform(*ring) * u / np.linalg.norm(u),
         "clamp_tool": np.array([np.cos(a) * rng.uniform(*off), np.sin(a) * rng.uniform(*off), rng.uniform(*along)]),
         "F0_N": rng.uniform(*F0), "rate": rng.uniform(0.05, 0.2)}
    ell = np.linalg.norm(np.subtract(*retract_points(p, ctx)), axis=1)
    p.update(ell_mid=0.5 * (ell.min() + ell.max()), ell_span=max(ell.max() - ell.min(), 1.0))
    return p


def retract_points(p, ctx):
    """Guide ring (on the forearm body) and hose clamp (on the tool) (P, 3) [mm]."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    return np.einsum("pij,j->pi", R[:, RETRACT_BODY], p["ring_home"]) + t[:, RETRACT_BODY], fl + Rt @ p["clamp_tool"]


def retract_loads(p, ctx):
    """Joint loads (P, n) [N m / N] of the pull on the clamp towards the ring; zero on the joints before the ring."""
    ring, clamp = retract_points(p, ctx)
    d, ell = ring - clamp, np.linalg.norm(ring - clamp, axis=1)
    F = (p["F0_N"] * (1 + p["rate"] * (ell - p["ell_mid"]) / p["ell_span"]) / ell)[:, None] * d
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    out = np.zeros(ctx.q.shape)
    for j in range(RETRACT_BODY, ctx.chain.n):
        arm = np.cross((clamp - c[:, j]) / 1000.0, F) if ctx.chain.revolute[j] else F
        out[:, j] = np.einsum("pi,pi->p", arm, w[:, j])
    return out


def _beyond(loads, first):
    """``loads`` (P, n) on the joints from ``first`` on, zero before (the main axes' twist is set A's)."""
    return loads * (np.arange(loads.shape[1]) >= first)


def retract_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, _beyond(ctx.loads + retract_loads(p, ctx), RETRACT_BODY)))


def retract_features(p, ctx, hw):
    return _stack(_load_cols(ctx, _beyond(ctx.loads + retract_loads(p, ctx), RETRACT_BODY)), len(ctx.q))


# ------------------------------------------------------------------------------------------ wrist drive shafts
#: per arm: shaft outer diameter, wall, length [m], final bevel ratio N2 (assumed)
SHAFT = {"kr16_like": ((0.030, 0.040), (0.003, 0.005), (0.5, 0.7), (1.5, 3.0)),
         "tool_changer": ((0.045, 0.070), (0.005, 0.008), (0.7, 1.0), (2.5, 4.0))}
STEEL_G = 81e9


def shaft_draw(ctx, hw, rng):
    if ctx.chain.name not in SHAFT:
        return {}
    D, t, L, N2 = SHAFT[ctx.chain.name]
    W = [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j >= 3]
    c = {(j, k): _ratio(rng) * rng.choice([-1, 1]) for j, k in wrist_pairs(ctx.chain)}
    shafts = []
    for j in [j for j in W if j >= 4]:
        Do, tw = rng.uniform(*D), rng.uniform(*t)
        shafts.append({"joint": j, "L_m": rng.uniform(*L), "GJ": STEEL_G * np.pi / 32 * (Do ** 4 - (Do - 2 * tw) ** 4)})
    return {"W": W, "c": c, "N2": {j: rng.uniform(*N2) for j in W}, "shafts": shafts}


def shaft_matrix(p):
    """G (m, m) over the wrist joints W: actuator angles a = G q_W, G = diag(N2) (I + C)."""
    W, G = p["W"], np.eye(len(p["W"]))
    for (j, k), c in p["c"].items():
        G[W.index(j), W.index(k)] = c
    return np.diag([p["N2"][j] for j in W]) @ G


def shaft_columns(p, ctx):
    """Joint deflections (shafts, P, n) per unit shaft compliance: G^-1 e_s e_s^T G^-T tau_W."""
    W, Gi = p["W"], np.linalg.inv(shaft_matrix(p))
    T = ctx.loads[:, W] @ Gi                                          # shaft torques G^-T tau (rows: poses)
    out = np.zeros((len(p["shafts"]), len(ctx.q), ctx.chain.n))
    for i, s in enumerate(p["shafts"]):
        a = W.index(s["joint"])
        out[i][:, W] = np.outer(T[:, a], Gi[:, a])
    return out


def shaft_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(dq=_torsion_all(ctx, hw, _beyond(ctx.loads, 3)) + np.einsum(
        "s,spn->pn", [s["L_m"] / s["GJ"] for s in p["shafts"]], shaft_columns(p, ctx)))


def shaft_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return _stack(_load_cols(ctx, _beyond(ctx.loads, 3)) + [np.einsum("pij,pj->pi", ctx.jac, d)
                                                           for d in shaft_columns(p, ctx)], len(ctx.q))
