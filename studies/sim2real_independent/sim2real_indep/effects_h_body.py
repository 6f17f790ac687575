"""Set H body effects (new physics, not in sets A-G): the arm on a mobile platform that stands on elastomer-tyred
wheels with a pendulum axle; the arm and the tracker on one long base skid bedded on the floor; a curved
(gooseneck) forearm casting whose out-of-plane loads twist it along its arc; tube links bonded into their end
fittings with an adhesive that creeps. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* mobile platform: a chassis on two fixed wheels and a pendulum (rocker) axle is statically determinate (three
  supports: the rocker's pivot shares its load between its two wheels), so the wheel loads follow from statics; an
  elastomer tyre on a rigid hub pressed on the floor deflects about as F^(2/3) (Hertz-type contact: Johnson,
  *Contact Mechanics*, 1985, ch. 4-5; the exponent taken as in Hertz's law, assumed for a thick tyre): delta = c
  R^(2/3), c from the tyre's secant stiffness at the mean wheel load (1-3 / 3-8 / 3-8 kN/mm on ur10 / kr16_like /
  tool_changer, rocker wheels 0.5-1x the fixed ones; platforms of 150-300 / 600-1200 / 1500-3000 kg with wheel
  half-spans 0.3-0.4 x 0.2-0.3 / 0.6-0.9 x 0.4-0.6 / 1.0-1.4 x 0.7-1.0 m and heights 0.3-0.5 / 0.5-0.8 / 0.6-1.0
  m; mobile manipulators, assumed). The chassis tilts and sinks as the plane through its three supports.
* base skid: the arm and the tracker's stand on one welded skid bedded on the floor along the line to the tracker,
  a beam on an elastic foundation (Hetenyi, *Beams on Elastic Foundation*, 1946; Roark's *Formulas for Stress and
  Strain*, semi-infinite beams): at distance x from the arm's end w = (2 P beta / k) D - (2 M beta^2 / k) C,
  dw/dx = -(2 P beta^2 / k) A + (4 M beta^3 / k) D, beta^4 = k / 4 EI, with A, C, D the decaying Hetenyi functions;
  its torsion as a bar on a torsional foundation, phi = (T lambda / k_t) exp(-lambda x), lambda^2 = k_t / GJ.
  P the weight of arm and payload, M and T the arm's base moment about the skid's normal and axis. The tracker's
  stand follows the skid at its foot, so the measured points move by the skid's motion under the arm minus that
  under the tracker. Skid EI 0.5-2e7 / 2-6e7 / 1-3e8 N m^2, beta 0.2-0.45 /m, GJ 5-30 % of EI (an open-section
  frame), lambda 0.2-0.6 /m (assumed).
* curved forearm: an arc-shaped (gooseneck) casting between its joints, sagitta 15-30 % of the chord, bowed in a
  random direction normal to it; a space-curved slender rod deflects by the unit-load (Mohr) integrals dtheta = (M_b
  / EI + M_t t / GJ) ds, u_tip = int dtheta x (x_tip - x) (Timoshenko & Gere, *Mechanics of Materials*; Roark,
  curved beams loaded normal to their plane): out-of-plane loads twist the arc. The link's tube section; the forearm
  tubes (400 mm or more past joint 2).
* bonded joints: tubes bonded into aluminium end fittings (CFRP or aluminium tubes of lightweight arms); the bond
  line's root rotation is elastic plus creep (structural epoxies creep under sustained shear: a standard linear
  solid, Findley et al. 1976; adhesive creep in bonded joints: Adams, Comyn & Wake, *Structural Adhesive Joints in
  Engineering*, 1997): rot = c_e M + c_c x, tau_c dx/dt = M - x with the root moment M in the tube's own frame
  (the joint turns with the link), c_e 0.3-1 L / EI (bending) and L / GJ (torsion), c_c 0.5-1.5 c_e, tau_c 10-40 min
  (assumed); the tube links of 400 mm or more past joint 1.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_h_joint import creep_state

Z = np.array([0.0, 0.0, 1.0])
#: per arm: platform mass [kg], half-spans x / y [m], height [m], fixed-wheel secant stiffness [N/mm] (assumed)
AGV = {"ur10": ((150, 300), (0.3, 0.4), (0.2, 0.3), (0.3, 0.5), (1e3, 3e3)),
       "kr16_like": ((600, 1200), (0.6, 0.9), (0.4, 0.6), (0.5, 0.8), (3e3, 8e3)),
       "tool_changer": ((1500, 3000), (1.0, 1.4), (0.7, 1.0), (0.6, 1.0), (3e3, 8e3))}
SKID_EI = {"ur10": (5e6, 2e7), "kr16_like": (2e7, 6e7), "tool_changer": (1e8, 3e8)}


def _weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G


# ------------------------------------------------------------------------------------------ mobile platform
def agv_draw(ctx, hw, rng):
    (m0, m1), ax, ay, h, s = AGV[ctx.chain.name]
    W_p = rng.uniform(m0, m1) * kin.G
    R0 = (_weight(ctx).mean() + W_p) / 4
    c = R0 ** (1 / 3) / rng.uniform(*s)              # delta = c R^(2/3) [mm]: R0 / delta(R0) = s
    return {"W_platform_N": W_p, "a_x_m": rng.uniform(*ax), "a_y_m": rng.uniform(*ay), "h_mm": rng.uniform(*h) * 1e3,
            "c_fixed": c, "c_rocker": c / rng.uniform(0.5, 1.0)}


def wheel_loads(p, ctx):
    """Loads (P, 3) [N] of the two fixed wheels (+x, +-y) and of each rocker wheel (at -x)."""
    M = eb.mount_moment(ctx)
    W = _weight(ctx) + p["W_platform_N"]
    front = (W + M[:, 1] / p["a_x_m"]) / 2
    diff = -M[:, 0] / p["a_y_m"]
    return np.maximum(np.c_[(front + diff) / 2, (front - diff) / 2, (W - M[:, 1] / p["a_x_m"]) / 4], 1.0)


def agv_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per unit c of the fixed and of the rocker wheels: the plane through the
    supports, tilting about the contact plane under the base."""
    R = wheel_loads(p, ctx) ** (2 / 3)
    ax, ay = 1000 * p["a_x_m"], 1000 * p["a_y_m"]
    out = []
    for d in (np.c_[R[:, :2], 0 * R[:, 2]], np.c_[0 * R[:, :2], R[:, 2]]):
        gy = (d[:, 1] - d[:, 0]) / (2 * ay)
        gx = (d[:, 2] - (d[:, 0] + d[:, 1]) / 2) / (2 * ax)
        z0 = -((d[:, 0] + d[:, 1]) / 2 + d[:, 2]) / 2
        omega = np.c_[gy, -gx, np.zeros(len(d))]
        out.append(np.cross(omega, ctx.target - np.array([0, 0, -p["h_mm"]])) + z0[:, None] * Z)
    return np.array(out)


def agv_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [p["c_fixed"], p["c_rocker"]], agv_parts(p, ctx)))


def agv_features(p, ctx, hw):
    return agv_parts(p, ctx)


# ---------------------------------------------------------------------------------------------- base skid
def skid_draw(ctx, hw, rng):
    EI = np.exp(rng.uniform(*np.log(SKID_EI[ctx.chain.name])))
    beta, lam = rng.uniform(0.2, 0.45), rng.uniform(0.2, 0.6)
    return {"EI": EI, "beta": beta, "k": 4 * EI * beta ** 4, "lam": lam,
            "k_t": rng.uniform(0.05, 0.3) * EI * lam ** 2, "h_mm": hw["mount"]["height_mm"]}


def hetenyi(beta, x):
    """Hetenyi's A, C, D functions of beta x (x >= 0)."""
    e, c, s = np.exp(-beta * x), np.cos(beta * x), np.sin(beta * x)
    return e * (c + s), e * (c - s), e * c


def skid_response(p, x):
    """Per unit of P / k, M / k, T / k_t: sink w [m], slope [rad], twist [rad] at x [m] (rows: P, M, T)."""
    b = p["beta"]
    A, C, D = hetenyi(b, x)
    return np.array([[2 * b * D, -2 * b * b * A, 0.0], [-2 * b * b * C, 4 * b ** 3 * D, 0.0],
                     [0.0, 0.0, p["lam"] * np.exp(-p["lam"] * x)]])


def skid_parts(p, ctx, hw):
    """Measured-point displacement (3, P, 3) [mm] per unit 1 / k (weight and moment about the skid's normal) and
    1 / k_t (moment about its axis): the skid's motion under the arm minus that under the tracker's stand."""
    tr = hw["tracker"]
    o_T = -tr["R"].T @ tr["t"]
    e = np.r_[o_T[:2], 0.0] / np.linalg.norm(o_T[:2])
    n = np.cross(Z, e)
    d = np.linalg.norm(o_T[:2]) / 1000.0
    feet = np.array([[0, 0, -p["h_mm"]], [o_T[0], o_T[1], -p["h_mm"]]])
    M = eb.mount_moment(ctx)
    loads = np.c_[_weight(ctx), M @ n, M @ e]                  # P [N], M_n, M_e [N m]
    out = np.zeros((3, len(ctx.q), 3))
    for sign, x, foot in ((1.0, 0.0, feet[0]), (-1.0, d, feet[1])):
        resp = skid_response(p, x)
        for r in range(3):
            w, slope, twist = resp[r]
            rot = np.outer(loads[:, r], slope * n + twist * e)
            out[r] += sign * (np.cross(rot, ctx.target - foot) - 1000.0 * w * loads[:, r:r + 1] * Z)
    return out


def skid_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["k"], 1 / p["k"], 1 / p["k_t"]],
                                           skid_parts(p, ctx, hw)))


def skid_features(p, ctx, hw):
    return skid_parts(p, ctx, hw)


# ------------------------------------------------------------------------------------------- curved forearm
def _forearms(ctx, hw, min_body):
    ch = ctx.chain
    return [n for n in hw["tubes"] if ch.link_body[ch.link_names.index(n)] >= min_body
            and np.linalg.norm(ch.links[ch.link_names.index(n)]) >= 400]


def curve_draw(ctx, hw, rng):
    out = {}
    for name in _forearms(ctx, hw, 3 if ctx.chain.name != "ur10" else 2):
        v = ctx.chain.links[ctx.chain.link_names.index(name)]
        e0 = v / np.linalg.norm(v)
        u = np.cross(e0, [1.0, 0, 0] if abs(e0[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        phi = rng.uniform(0, 2 * np.pi)
        out[name] = {"b_home": np.cos(phi) * u + np.sin(phi) * np.cross(e0, u),
                     "half_angle": 2 * np.arctan(2 * rng.uniform(0.15, 0.3))}
    return out


def arc_displacement(e, b, tip, L, alpha, F, M_tip, w, EI, GJ, target, n=60):
    """Tip-borne target displacement (P, 3) [mm] of a circular arc of chord L [m] (unit chord e, bow b (P, 3), tip
    (P, 3) [mm]) bowed by half-angle alpha, clamped at its root, under a tip force F [N], tip moment M_tip [N m]
    and weight w (3,) [N/m] along the arc: Mohr's integrals of bending (1 / EI) and twist (1 / GJ)."""
    R = L / (2 * np.sin(alpha)) if alpha > 1e-9 else np.inf
    phi = -alpha + (np.arange(n) + 0.5) * 2 * alpha / n
    xi = (np.arange(n) + 0.5) / n
    if np.isfinite(R):
        a, c, ds = R * np.sin(phi), R * (np.cos(phi) - np.cos(alpha)), np.full(n, 2 * alpha * R / n)
        ta, tb = np.cos(phi), -np.sin(phi)
    else:
        a, c, ds, ta, tb = xi * L - L / 2, 0 * xi, np.full(n, L / n), np.ones(n), 0 * xi
    # positions relative to the tip [m] (P, n, 3) and tangents (a, c: along the chord from its middle, bow)
    rel = (a - L / 2)[None, :, None] * e[:, None] + c[None, :, None] * b[:, None]
    t = ta[None, :, None] * e[:, None] + tb[None, :, None] * b[:, None]
    beyond_s = np.cumsum((ds)[::-1])[::-1] - ds / 2
    beyond_x = (np.cumsum((rel * ds[None, :, None])[:, ::-1], axis=1)[:, ::-1] - rel * ds[None, :, None] / 2)
    Mk = (M_tip[:, None] + np.cross(-rel, F[:, None])
          + np.cross(beyond_x - rel * beyond_s[None, :, None], np.broadcast_to(w, F.shape)[:, None]))
    Mt = np.einsum("pki,pki->pk", Mk, t)[..., None] * t
    dth = ((Mk - Mt) / EI + Mt / GJ) * ds[None, :, None]
    rot = dth.sum(axis=1)
    disp = np.cross(dth, -rel).sum(axis=1)
    return 1000.0 * disp + np.cross(rot, target - tip)


def curve_columns(p, ctx, hw):
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    cols = []
    for name, s in p.items():
        li = ctx.chain.link_names.index(name)
        e, tip, L = eb._beam_state(ctx, li)
        F, M, w = eb._beam_loads(ctx, li)
        if name not in ctx.mass_link:
            w = hw["tubes"][name]["rho"] * hw["tubes"][name]["A"] * eb.GRAVITY_N
        b = R[:, ctx.chain.link_body[li]] @ s["b_home"]
        args = (e, b, tip, L, s["half_angle"], F, M, w)
        cols += [arc_displacement(*args, 1.0, np.inf, ctx.target), arc_displacement(*args, np.inf, 1.0, ctx.target)]
    return np.array(cols) if cols else np.zeros((0, len(ctx.q), 3))


def curve_apply(p, ctx, hw):
    cols = curve_columns(p, ctx, hw)
    amp = [a for n in p for a in (1 / (hw["tubes"][n]["E"] * hw["tubes"][n]["I"]),
                                  1 / (hw["tubes"][n]["G"] * hw["tubes"][n]["J"]))]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, cols))


def curve_features(p, ctx, hw):
    return curve_columns(p, ctx, hw)


# -------------------------------------------------------------------------------------------- bonded joints
def bond_draw(ctx, hw, rng):
    out = {}
    for name in _forearms(ctx, hw, 2):
        tb, L = hw["tubes"][name], np.linalg.norm(ctx.chain.links[ctx.chain.link_names.index(name)]) / 1000
        ce = rng.uniform(0.3, 1.0) * L * np.array([1 / (tb["E"] * tb["I"]), 1 / (tb["G"] * tb["J"])])
        out[name] = {"c_e": ce, "c_c": ce * rng.uniform(0.5, 1.5, 2), "tau_s": rng.uniform(10, 40) * 60}
    return out


def root_state(ctx, li):
    """Root (P, 3) [mm], the tube's body rotation (P, 3, 3), its home axis and the root moment in the tube's frame
    (P, 3) [N m] of all loads beyond the root (own weight included)."""
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    root = tip - 1000.0 * L * e
    M_root = M + np.cross(L * e, F) + np.cross(L / 2 * e, np.broadcast_to(w * L, F.shape))
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    Rb = R[:, ctx.chain.link_body[li]]
    v = ctx.chain.links[li]
    return root, Rb, v / np.linalg.norm(v), np.einsum("pji,pj->pi", Rb, M_root)


def bond_parts(p, ctx):
    """Target displacement (4, P, 3) [mm] per tube: per unit compliance of bending and twist, elastic and creep."""
    out = []
    for name, s in p.items():
        li = ctx.chain.link_names.index(name)
        root, Rb, e0, m = root_state(ctx, li)
        for X in (m, creep_state(ctx, m, s["tau_s"])):
            tw = (X @ e0)[:, None] * e0
            for local in (X - tw, tw):                           # bending, twist (tube frame)
                out.append(np.cross(np.einsum("pij,pj->pi", Rb, local), ctx.target - root))
    return np.array(out) if out else np.zeros((0, len(ctx.q), 3))


def bond_apply(p, ctx, hw):
    amp = [a for s in p.values() for a in (*s["c_e"], *s["c_c"])]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, bond_parts(p, ctx)))


def bond_features(p, ctx, hw):
    return bond_parts(p, ctx)
