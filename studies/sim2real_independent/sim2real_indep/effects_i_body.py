"""Set I body effects (new physics, not in sets A-H): the arm's base bolted across two steel floor beams of a
mezzanine, off their mid-span; the arm on a portal bridge (two fixed columns and a beam) over a line; a tube link
spliced by a bolted lap joint that micro-slips; a fork-type upper arm of two side plates that twists by
non-uniform (warping-restrained) torsion. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* floor beams: a rigid base plate across two parallel simply supported beams (spacing s) at a = 0.2-0.4 of their
  span L from a support; a force P and a couple C at a give the deflection and slope there (Roark's *Formulas for
  Stress and Strain*, Table 8.1, simply supported beam, concentrated load and concentrated moment at an
  intermediate point): [w, slope] = 1 / (3 EI L) [[a^2 b^2, a b (b - a)], [a b (b - a), a^2 - a b + b^2]] [P, C],
  b = L - a. Statics of the plate: P1 + P2 = W, (P1 - P2) s / 2 = -M . e (the moment about the beam axis), C1 + C2
  = M . n, equal slopes (a rigid plate): the weight tilts the plate (off mid-span) and the moment sinks it. Steel
  mezzanine beams EI 0.6-2.5e6 / 0.4-1.5e7 / 3-10e7 N m^2 (IPE 120-360-like), spans 2.5-4 / 3-5 / 3.5-6 m, spacing
  0.35-0.6 / 0.5-0.8 / 0.7-1.1 m on ur10 / kr16_like / tool_changer (assumed).
* portal bridge: the arm at the mid-span of the beam of a portal frame with fixed feet (a bridge over a conveyor):
  in its plane a 2-D frame solved by the direct stiffness method (Euler-Bernoulli frame elements; e.g.
  Przemieniecki, *Theory of Matrix Structural Analysis*, 1968) under the weight and the in-plane couple -- the
  couple sways the frame; out of its plane the couple about the beam axis twists each half of the beam (T / 2,
  Saint-Venant torsion of a closed box, Bredt) into the column tops, which bend out of plane as cantilevers under
  T / 2 (Timoshenko & Gere, *Mechanics of Materials*). Columns 1-1.8 / 1.5-2.5 / 1.8-3 m high, spans 1.2-2.5 /
  1.5-3 / 2-3.5 m, box sections of EI and GJ by arm (:data:`PORTAL`; assumed).
* lap splice: a bolted splice transmits the bending moment by friction; patches of the interface slip as the
  moment grows (micro-slip) and stick again on reversal, a Masing hysteresis (Goodman & Klumpp, "Analysis of slip
  damping with reference to turbine-blade vibration", J. Appl. Mech. 23, 1956; Iwan, J. Appl. Mech. 33, 1966;
  Segalman, "A four-parameter Iwan model for lap-type joints", J. Appl. Mech. 72, 2005). Here a series Iwan model
  of the section moment m (a vector normal to the tube): rotation = m / k0 + sum_i P_ri(m) / k_i, P_r the vector
  play operator of radius r (Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989) along the moment path
  (straight between poses; production periods a pass through the session's moments, one of them before the
  session). Splice at 0.2-0.5 of the upper arm's tube (the link carrying the largest moments); k0 2-5 EI / L, slip
  radii 0.3 / 0.5 / 0.7 of the session's largest moment there (x 0.8-1.2), the slip at the largest moment 2-4 x the
  elastic rotation (a splice whose bolts lost much of their preload; assumed). The tube's own bending is set A's sag
  and left out: the case isolates the splice. Oracle check: on the planar arms the moment lies in the arm's plane,
  where the joint model mimics the splice's rotation (ambiguous or absorbed in most draws); on ur10 the wrist
  offsets give its upper arm out-of-plane moments the parallel joints 2-4 cannot reproduce, and the set uses it
  there.
* fork upper arm: two side plates (depth D, thickness t, spacing h across the arm's plane) joined by the end
  housings and diaphragms. Torsion by a torque T at the tip of a cantilever with warping restrained at the root and
  free at the tip (Vlasov, *Thin-walled Elastic Beams*, 1961; Timoshenko & Gere, *Theory of Elastic Stability*,
  ch. 5): phi = T / (G J) (L - tanh(lambda L) / lambda), lambda^2 = G J / (E Gamma), Gamma = I_p h^2 / 2 with the
  plates' own in-plane I_p = t D^3 / 12 and J = 2 D t^3 / 3 x 1-1.5 (diaphragms). D 0.9-1.2, h 0.6-0.9, t
  0.04-0.07 of the tube diameter of :mod:`hardware` (assumed). The fork's bending is set A's sag and left out: the
  case isolates the twist, which the loads of a rolled forearm (axis 4) put on the upper arm of kr16_like (none on
  the others: tool_changer's upper arm sees only the payload's offset, which left the twist absorbed).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])


def _weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G


def _logu(rng, lo, hi):
    return float(np.exp(rng.uniform(np.log(lo), np.log(hi))))


def _rigid(ctx, omega, shift_mm):
    """Displacement (P, 3) [mm] of the target under a base rotation ``omega`` (P, 3) [rad] about the base origin
    and a translation ``shift_mm`` (P, 3)."""
    return np.cross(omega, ctx.target) + shift_mm


# ------------------------------------------------------------------------------------------ floor beams
#: per arm: span [m], beam EI [N m^2], beam spacing [m] (assumed)
FLOOR = {"ur10": ((2.5, 4.0), (0.6e6, 2.5e6), (0.35, 0.6)), "kr16_like": ((3.0, 5.0), (4e6, 1.5e7), (0.5, 0.8)),
         "tool_changer": ((3.5, 6.0), (3e7, 1e8), (0.7, 1.1))}


def floor_draw(ctx, hw, rng):
    (L0, L1), (e0, e1), (s0, s1) = FLOOR[ctx.chain.name]
    L = rng.uniform(L0, L1)
    return {"L_m": L, "a_m": rng.uniform(0.2, 0.4) * L, "EI": _logu(rng, e0, e1), "s_m": rng.uniform(s0, s1),
            "yaw": rng.uniform(0, np.pi)}


def beam_flexibility(L, a):
    """EI times the flexibility (2, 2) of a simply supported beam at a from a support: deflection (down) and slope
    under a force (down) and a couple there [m, rad per N, N m] (Roark, Table 8.1)."""
    b = L - a
    return np.array([[a * a * b * b, a * b * (b - a)], [a * b * (b - a), a * a - a * b + b * b]]) / (3 * L)


def floor_state(p, ctx):
    """Per unit 1/EI: beam loads (P1, P2, C1, C2) and the plate's sink [m], rotations about n and e [rad]."""
    e = np.array([np.cos(p["yaw"]), np.sin(p["yaw"]), 0.0])
    n = np.cross(Z, e)
    W, M = _weight(ctx), eb.mount_moment(ctx)
    F = beam_flexibility(p["L_m"], p["a_m"])
    dP = -2 * (M @ e) / p["s_m"]
    P1, P2 = (W + dP) / 2, (W - dP) / 2
    dC = -F[1, 0] * dP / F[1, 1]
    C1, C2 = ((M @ n) + dC) / 2, ((M @ n) - dC) / 2
    w1, w2 = F[0, 0] * P1 + F[0, 1] * C1, F[0, 0] * P2 + F[0, 1] * C2
    return (P1, P2, C1, C2), (w1 + w2) / 2, F[1, 0] * P1 + F[1, 1] * C1, -(w1 - w2) / p["s_m"], e, n


def floor_parts(p, ctx):
    """Target displacement (1, P, 3) [mm] per unit 1/EI [1/(N m^2)]."""
    _, sink, phi, psi, e, n = floor_state(p, ctx)
    omega = phi[:, None] * n + psi[:, None] * e
    return _rigid(ctx, omega, -1000.0 * sink[:, None] * Z)[None]


def floor_apply(p, ctx, hw):
    return Contribution(displace=floor_parts(p, ctx)[0] / p["EI"])


def floor_features(p, ctx, hw):
    return floor_parts(p, ctx)


# ------------------------------------------------------------------------------------------ portal bridge
#: per arm: column height, span [m], column EI, beam EI, beam GJ [N m^2] (assumed)
PORTAL = {"ur10": ((1.0, 1.8), (1.2, 2.5), (2.5e5, 1e6), (5e5, 2e6), (3e5, 1.2e6)),
          "kr16_like": ((1.5, 2.5), (1.5, 3.0), (3e6, 1.2e7), (5e6, 2e7), (2e6, 8e6)),
          "tool_changer": ((1.8, 3.0), (2.0, 3.5), (2e7, 8e7), (3e7, 1e8), (1.5e7, 6e7))}


def portal_draw(ctx, hw, rng):
    H, B, Ec, Eb, Gb = PORTAL[ctx.chain.name]
    EIc = _logu(rng, *Ec)
    return {"H_m": rng.uniform(*H), "B_m": rng.uniform(*B), "EI_col": EIc, "EI_col_out": EIc * rng.uniform(0.5, 1.5),
            "EI_beam": _logu(rng, *Eb), "GJ_beam": _logu(rng, *Gb), "yaw": rng.uniform(0, np.pi)}


def frame_element(x0, x1, EA, EI):
    """Global stiffness (6, 6) of a 2-D Euler-Bernoulli frame element from x0 to x1 (2,) [m] (dofs u, v, theta)."""
    d = np.asarray(x1, float) - np.asarray(x0, float)
    L = np.hypot(*d)
    c, s = d / L
    a, b2, b4 = 6 * L, 2 * L * L, 4 * L * L
    k = EI / L ** 3 * np.array([[0, 0, 0, 0, 0, 0], [0, 12, a, 0, -12, a], [0, a, b4, 0, -a, b2],
                                [0, 0, 0, 0, 0, 0], [0, -12, -a, 0, 12, -a], [0, a, b2, 0, -a, b4]])
    k[np.ix_([0, 3], [0, 3])] += EA / L * np.array([[1, -1], [-1, 1]])
    r = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
    T = np.kron(np.eye(2), r)
    return T.T @ k @ T


def portal_flexibility(H, B, EI_col, EI_beam):
    """Flexibility (3, 3) of a portal with fixed feet at its beam's mid-span: (u along the beam, v up, theta) per
    unit (force along the beam, force up, couple) [m, rad per N, N m]."""
    xy = np.array([[-B / 2, -H], [-B / 2, 0], [0, 0], [B / 2, 0], [B / 2, -H]])
    K = np.zeros((15, 15))
    for (i, j), EI in zip([(0, 1), (1, 2), (2, 3), (3, 4)], [EI_col, EI_beam, EI_beam, EI_col]):
        idx = np.r_[3 * i:3 * i + 3, 3 * j:3 * j + 3]
        K[np.ix_(idx, idx)] += frame_element(xy[i], xy[j], EI / 0.08 ** 2, EI)  # EA: radius of gyration 80 mm
    free = np.arange(3, 12)
    return np.linalg.inv(K[np.ix_(free, free)])[3:6, 3:6]


def portal_parts(p, ctx):
    """Target displacement (3, P, 3) [mm]: in-plane frame response (amplitude 1), beam torsion per unit 1/GJ and
    column out-of-plane bending per unit 1/EI."""
    e = np.array([np.cos(p["yaw"]), np.sin(p["yaw"]), 0.0])
    a = np.cross(e, Z)                                          # frame normal: in-plane rotations turn e to z
    W, M = _weight(ctx), eb.mount_moment(ctx)
    u, v, th = portal_flexibility(p["H_m"], p["B_m"], p["EI_col"], p["EI_beam"]) @ np.array(
        [np.zeros_like(W), -W, M @ a])
    T = M @ e
    inplane = _rigid(ctx, th[:, None] * a, 1000.0 * (u[:, None] * e + v[:, None] * Z))
    torsion = _rigid(ctx, (T * p["B_m"] / 4)[:, None] * e, np.zeros_like(ctx.target))
    column = _rigid(ctx, (T / 2 * p["H_m"])[:, None] * e, 1000.0 * (T / 2 * p["H_m"] ** 2 / 2)[:, None] * a)
    return np.array([inplane, torsion, column])


def portal_apply(p, ctx, hw):
    amp = [1.0, 1.0 / p["GJ_beam"], 1.0 / p["EI_col_out"]]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, portal_parts(p, ctx)))


def portal_features(p, ctx, hw):
    return portal_parts(p, ctx)


# ----------------------------------------------------------------------------------------------- lap splice
def _long_tubes(ctx, hw, min_body, min_mm=400.0):
    ch = ctx.chain
    return [n for n in hw["tubes"] if ch.link_body[ch.link_names.index(n)] >= min_body
            and np.linalg.norm(ch.links[ch.link_names.index(n)]) >= min_mm]


def section_moment(ctx, li, s_frac, w_own=None):
    """Bending moment (P, 3) [N m], base frame, at the section s_frac along link ``li`` from its root, of all loads
    beyond it (own weight ``w_own`` [N/m] or the file's), and the section's position (P, 3) [mm]."""
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    w = w if w_own is None else w_own
    d = (1 - s_frac) * L
    M_s = M + np.cross(d * e, F) + np.cross(d / 2 * e, np.broadcast_to(w * d, F.shape))
    return M_s - np.einsum("pi,pi->p", M_s, e)[:, None] * e, tip - 1000.0 * d * e


def play_vec(y, m, r):
    """Vector play operator: ``y`` moved the least so that |m - y| <= r."""
    d = m - y
    n = np.linalg.norm(d)
    return y if n <= r else m - r * d / n


def play_path(moments, gap_s, radii, substeps=8):
    """Play outputs (P, len(radii), 3) along the moment path: straight between poses, production periods (gap > 0)
    and the time before the session a pass through all the session's moments."""
    ys = [np.zeros(3) for _ in radii]

    def walk(a, b):
        for t in np.linspace(0, 1, substeps + 1)[1:]:
            m = (1 - t) * a + t * b
            for i, r in enumerate(radii):
                ys[i] = play_vec(ys[i], m, r)

    def production(last):
        for m in moments:
            walk(last, m)
            last = m
        return last

    last = production(moments[0])
    out = np.zeros((len(moments), len(radii), 3))
    for k, m in enumerate(moments):
        if k > 0 and gap_s[k] > 0:
            last = production(last)
        walk(last, m)
        last = m
        out[k] = np.array(ys)
    return out


def splice_draw(ctx, hw, rng):
    ch = ctx.chain
    name = [n for n in _long_tubes(ctx, hw, 2) if ch.link_body[ch.link_names.index(n)] == 2][0]
    li, tb = ch.link_names.index(name), hw["tubes"][name]
    s = rng.uniform(0.2, 0.5)
    m, _ = section_moment(ctx, li, s, eb._own_weight(ctx, name, tb))
    m_max = np.linalg.norm(m, axis=1).max()
    L = np.linalg.norm(ctx.chain.links[li]) / 1000
    k0 = rng.uniform(2, 5) * tb["E"] * tb["I"] / L
    r = np.array([0.3, 0.5, 0.7]) * rng.uniform(0.8, 1.2) * m_max
    c = rng.uniform(0.5, 1.0, 3)
    c *= rng.uniform(2.0, 4.0) * m_max / k0 / np.sum(c * (m_max - r))
    return {"link": name, "s": s, "k0": k0, "radii": r, "c_slip": c}


def splice_parts(p, ctx, hw):
    """Target displacement (1 + radii, P, 3) [mm]: the splice's elastic rotation per unit 1/k0 and each play
    operator's per unit compliance."""
    name = p["link"]
    li, tb = ctx.chain.link_names.index(name), hw["tubes"][name]
    m, pos = section_moment(ctx, li, p["s"], eb._own_weight(ctx, name, tb))
    cols = []
    Rb = kin.body_transforms(ctx.chain, ctx.q)[0][:, ctx.chain.link_body[li]]
    m_body = np.einsum("pji,pj->pi", Rb, m)                       # in the tube's own frame: the splice turns with it
    ys = play_path(m_body, ctx.session.gap_s, p["radii"])
    lever = ctx.target - pos
    for rot in [m_body] + [ys[:, i] for i in range(len(p["radii"]))]:
        cols.append(np.cross(np.einsum("pij,pj->pi", Rb, rot), lever))
    return np.array(cols)


def splice_apply(p, ctx, hw):
    amp = np.r_[1 / p["k0"], p["c_slip"]]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, splice_parts(p, ctx, hw)))


def splice_features(p, ctx, hw):
    return splice_parts(p, ctx, hw)


# ----------------------------------------------------------------------------------------- fork upper arm
#: arms given a fork-type upper arm (forearm roll ahead of it loads it in torsion)
FORK_ARMS = {"kr16_like"}


def fork_draw(ctx, hw, rng):
    ch = ctx.chain
    names = [n for n in _long_tubes(ctx, hw, 2) if ch.link_body[ch.link_names.index(n)] == 2]
    if ch.name not in FORK_ARMS or not names:
        return {}
    tb = hw["tubes"][names[0]]
    Dt = np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2)    # the tube's outer diameter [m]
    D, h, t = Dt * rng.uniform(0.9, 1.2), Dt * rng.uniform(0.6, 0.9), Dt * rng.uniform(0.04, 0.07)
    Ip = t * D ** 3 / 12
    return {"link": names[0], "J": 2 * D * t ** 3 / 3 * rng.uniform(1.0, 1.5), "Gamma": Ip * h * h / 2, "E": tb["E"],
            "G": tb["G"]}


def warping_twist(T, L, GJ, EGamma):
    """Tip twist [rad] of a cantilever under a tip torque T [N m]: warping restrained at the root, free at the tip."""
    lam = np.sqrt(GJ / EGamma)
    return T / GJ * (L - np.tanh(lam * L) / lam)


def fork_parts(p, ctx):
    """Target displacement (1, P, 3) [mm] of the twist per unit 1/GJ (the warping factor of the true lambda): the
    torque about the arm's axis is that of the loads beyond its tip (constant along it: they act at the tip)."""
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    li = ctx.chain.link_names.index(p["link"])
    e, tip, L = eb._beam_state(ctx, li)
    _, M, _ = eb._beam_loads(ctx, li)
    T = np.einsum("pi,pi->p", M, e)
    phi = warping_twist(T, L, 1.0, p["E"] * p["Gamma"] / (p["G"] * p["J"]))
    return np.cross(phi[:, None] * e, ctx.target - tip)[None]


def fork_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(displace=fork_parts(p, ctx)[0] / (p["G"] * p["J"]))


def fork_features(p, ctx, hw):
    return fork_parts(p, ctx)
