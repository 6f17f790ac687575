"""Set C body effects (new physics, not in sets A / B): a robot on a linear-track carriage (preloaded ball guide
blocks with Hertzian contact, a box track beam twisting and bending between its feet); box-section links bending
anisotropically and twisting (Bredt) under an offset payload; round tube links with a bolted root flange whose
moment-rotation stiffness drops past decompression. Same protocol as :mod:`effects_joint`.

Sources:

* Hertzian point contact, deflection ~ F^(2/3) (Harris & Kotzalas, *Rolling Bearing Analysis*; Hertz 1881); a
  preloaded pair of opposed raceways F = k[(d0 + d)^1.5 - max(d0 - d, 0)^1.5] (preload F0 = k d0^1.5, rigidity at
  no load 3 k d0^0.5); block rigidity 200-800 N/um and preload 1-3 kN are assumed from the order of linear-guide
  catalogue values (THK / Hiwin, medium preload, sizes 25-35). Load sharing of a rigid carriage on four equal
  blocks: linear in the first moments of the load (statics of a rigid plate on springs).
* track beam (steel box section, span 1.5-3 m between feet bolted to the floor, the carriage at mid-span): torsion
  T / (4 GJ / L) with Bredt's J = 4 A_m^2 t / s for a thin-walled closed section; slope under a couple at mid-span
  of a simply supported beam M L / (12 EI); mid-span deflection W L^3 / (48 EI) (Timoshenko & Gere, *Mechanics of
  Materials*; Roark's *Formulas for Stress and Strain*, beam and torsion tables).
* box-section link: bending about the two principal axes (I of a rectangular tube), shear on the walls parallel
  to the load (2 B t), Bredt torsion; cantilever laws as :func:`physics.cantilever_tip`.
* bolted flange joint: the joint's rotational stiffness is high until the bolted interface decompresses
  (VDI 2230 Part 1, opening limit under eccentric load / bending), then drops; a bilinear moment-rotation law in
  the spirit of EN 1993-1-8 6.3.1 (stiffness ratio of 2-3 beyond 2/3 of the moment resistance; here 2-3 past the
  decompression moment, reached at 40-80 % of the session's largest moment). Initial stiffness 2-5 x the tube's
  EI / L (assumed).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])


# -------------------------------------------------------------------------------------------- linear track
#: per arm: track beam (height, width, wall [m], material), span [m], block half spacings a, b [m], block
#: rigidity [N/um] and preload [kN]: a light aluminium axis for the cobot, steel box tracks for the others (assumed)
TRACKS = {"ur10": ((0.10, 0.16), (0.08, 0.14), (0.005, 0.008), hwm.ALUMINIUM, (1.0, 2.0), (0.1, 0.2), (0.08, 0.15),
                   (100, 300), (0.3, 1.0)),
          "tool_changer": ((0.25, 0.40), (0.2, 0.35), (0.010, 0.016), hwm.STEEL, (1.5, 3.0), (0.25, 0.45),
                           (0.2, 0.35), (300, 900), (2.0, 4.0)),
          "kr16_like": ((0.2, 0.35), (0.15, 0.3), (0.008, 0.014), hwm.STEEL, (1.5, 3.0), (0.2, 0.4), (0.15, 0.3),
                        (200, 800), (1.0, 3.0))}


def track_draw(ctx, hw, rng):
    H, B, T, mat, span, a, b, K0, F0 = TRACKS[ctx.chain.name]
    Hb, Bb, tb = rng.uniform(*H), rng.uniform(*B), rng.uniform(*T)
    Am, s = (Bb - tb) * (Hb - tb), 2 * ((Bb - tb) + (Hb - tb))
    I_pitch = (Bb * Hb ** 3 - (Bb - 2 * tb) * (Hb - 2 * tb) ** 3) / 12
    K0, F0 = rng.uniform(*K0) * 1e6, rng.uniform(*F0) * 1e3   # N/m, N
    d0 = 3 * F0 / K0
    psi = rng.uniform(0, np.pi)
    return {"a": rng.uniform(*a), "b": rng.uniform(*b), "psi": psi, "h_mm": rng.uniform(120, 250),
            "k": F0 / d0 ** 1.5, "d0": d0, "span": rng.uniform(*span), "beam_h_mm": Hb * 1000,
            "GJ": mat["E"] / (2 * (1 + mat["nu"])) * 4 * Am ** 2 * tb / s, "EI": mat["E"] * I_pitch}


def preloaded_deflection(F, k, d0):
    """Deflection [m] of a preloaded opposed pair under load F [N] (bisection of the monotone Hertz law)."""
    F = np.asarray(F, float)
    law = lambda d: k * (np.maximum(d0 + d, 0) ** 1.5 - np.maximum(d0 - d, 0) ** 1.5)  # noqa: E731
    lo, hi = np.full(F.shape, -d0 * 50), np.full(F.shape, d0 * 50)
    for _ in range(80):
        mid = (lo + hi) / 2
        up = law(mid) < F
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    return (lo + hi) / 2


def track_parts(p, ctx):
    """Target displacement (5, P, 3) [mm]: carriage tilt and sink on its blocks (true, nonlinear: amplitude 1),
    then per unit 1/k_torsion, per unit pitch compliance L / 12 EI, per unit L^3 / 48 EI of the track beam."""
    m, _, _ = ctx.mass_state
    W = m.sum(axis=1) * kin.G
    M = eb.mount_moment(ctx)
    ex = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    ey = np.cross(Z, ex)
    X, Y = M @ ey, -(M @ ex)                      # first moments of the weight along / across the rail [N m]
    a, b = p["a"], p["b"]
    xs, ys = np.array([a, a, -a, -a]), np.array([b, -b, b, -b])
    C = W[:, None] / 4 + X[:, None] * xs / (4 * a * a) + Y[:, None] * ys / (4 * b * b)
    d = preloaded_deflection(C, p["k"], p["d0"])  # compression [m]
    pitch, roll = -(d @ xs) / (4 * a * a), -(d @ ys) / (4 * b * b)
    omega = roll[:, None] * ex - pitch[:, None] * ey
    rail = np.array([0.0, 0.0, -p["h_mm"]])
    blocks = np.cross(omega, ctx.target - rail) - 1000.0 * d.mean(axis=1)[:, None] * Z
    shear_c = np.array([0.0, 0.0, -(p["h_mm"] + 40.0 + p["beam_h_mm"] / 2)])
    torsion = np.cross((M @ ex)[:, None] * ex, ctx.target - shear_c)
    bend = np.cross((M @ ey)[:, None] * ey, ctx.target - shear_c)
    sink = -1000.0 * W[:, None] * Z
    return np.array([blocks, torsion, bend, sink])


def _track_amp(p):
    L = p["span"]
    return np.array([1.0, L / (4 * p["GJ"]), L / (12 * p["EI"]), L ** 3 / (48 * p["EI"])])


def track_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", _track_amp(p), track_parts(p, ctx)))


def track_features(p, ctx, hw):
    return track_parts(p, ctx)


# ------------------------------------------------------------------------------------- box-section links
def _section_axis(ctx, li):
    """Unit section axis u1 at home of link ``li``: its proximal joint axis made normal to the link."""
    ch = ctx.chain
    e0 = ch.links[li] / np.linalg.norm(ch.links[li])
    b = ch.link_body[li]
    a0 = ch.axes[b - 1] if b >= 1 else np.array([0, 0, 1.0])
    u = a0 - (a0 @ e0) * e0
    if np.linalg.norm(u) < 0.3:
        u = np.cross(e0, [1.0, 0, 0] if abs(e0[0]) < 0.9 else [0, 1.0, 0])
    return u / np.linalg.norm(u)


def box_draw(ctx, hw, rng):
    """A rectangular box of the same outer size as the tube each link was given (B along the proximal joint axis
    0.55-0.85 D, H in the plane of motion 0.9-1.2 D, wall 4-10 mm)."""
    out = {}
    for name, tb in hw["tubes"].items():
        D = np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2)  # the tube's outer diameter [m]
        t = rng.uniform(0.004, 0.010)
        B, H = D * rng.uniform(0.55, 0.85), D * rng.uniform(0.9, 1.2)  # B along u1, H in the plane of motion
        out[name] = {"B": B, "H": H, "t": t, "E": tb["E"], "G": tb["G"], "rho": tb["rho"]}
    return out


def _box_props(s):
    B, H, t = s["B"], s["H"], s["t"]
    A = B * H - (B - 2 * t) * (H - 2 * t)
    I1 = (H * B ** 3 - (H - 2 * t) * (B - 2 * t) ** 3) / 12   # bending with displacement along u1
    I2 = (B * H ** 3 - (B - 2 * t) * (H - 2 * t) ** 3) / 12   # along u2
    J = 4 * ((B - t) * (H - t)) ** 2 * t / (2 * ((B - t) + (H - t)))
    return A, I1, I2, J, 2 * B * t, 2 * H * t


def _box_displacement(ctx, li, s, E, G):
    """Target displacement (P, 3) [mm] of box link ``li`` with moduli E, G (np.inf: that part rigid)."""
    A, I1, I2, J, As1, As2 = _box_props(s)
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    if ctx.chain.link_names[li] not in ctx.mass_link:
        w = s["rho"] * A * eb.GRAVITY_N
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    u1 = R[:, ctx.chain.link_body[li]] @ _section_axis(ctx, li)
    u2 = np.cross(e, u1)
    dA, rA = ph.cantilever_tip(e, L, F, M, w, E * I1, G * As1, G * J)
    dB, rB = ph.cantilever_tip(e, L, F, M, w, E * I2, G * As2, G * J)
    dot = lambda x, y: np.sum(x * y, axis=-1, keepdims=True)  # noqa: E731
    d = dot(dA, u1) * u1 + dot(dB, u2) * u2
    r = dot(rA, u2) * u2 + dot(rB, u1) * u1 + dot(rA, e) * e
    return 1000.0 * d + np.cross(r, ctx.target - tip)


def box_apply(p, ctx, hw):
    return Contribution(displace=eb.links_sum(_box_displacement, p, ctx))


def box_features(p, ctx, hw):
    return eb.links_columns(_box_displacement, p, ctx)


# ---------------------------------------------------------------------------------- bolted tube links
def bolted_draw(ctx, hw, rng):
    names = list(hw["tubes"])
    pick = list(rng.permutation(names))[:int(rng.integers(1, min(2, len(names)) + 1))]
    out = {}
    for name in sorted(pick):
        tb = hw["tubes"][name]
        li = ctx.chain.link_names.index(name)
        L = np.linalg.norm(ctx.chain.links[li]) / 1000
        m = np.linalg.norm(_root_moment(ctx, li, tb), axis=1)
        k1 = rng.uniform(2.0, 5.0) * tb["E"] * tb["I"] / L
        out[name] = {"k1": k1, "k2": k1 / rng.uniform(2.0, 3.0), "M_d": rng.uniform(0.4, 0.8) * m.max()}
    return out


def _root_moment(ctx, li, tb):
    """Moment (P, 3) [N m] about the root of link ``li`` of the loads beyond it and its own weight, normal to it."""
    e, tip, L = eb._beam_state(ctx, li)
    F, M_tip, w = eb._beam_loads(ctx, li)
    own = eb._own_weight(ctx, ctx.chain.link_names[li], tb)
    w = w if own is None else own
    M = M_tip + np.cross(e * L, F) + np.cross(e * L / 2, w * L)
    return M - np.sum(M * e, axis=-1, keepdims=True) * e


def _bolted_parts(p, ctx, hw):
    cols = []
    for name, b in p.items():
        tb = hw["tubes"][name]
        li = ctx.chain.link_names.index(name)
        e, tip, L = eb._beam_state(ctx, li)
        root = tip - 1000.0 * L * e
        M = _root_moment(ctx, li, tb)
        m = np.linalg.norm(M, axis=1, keepdims=True)
        u = M / np.maximum(m, 1e-12)
        w = eb._own_weight(ctx, name, tb)
        nu = tb["E"] / (2 * tb["G"]) - 1
        cols += [eb._beam_displacement(ctx, li, 1.0, np.inf, 1.0 / (1 + nu), w),
                 eb._beam_displacement(ctx, li, np.inf, 1.0, np.inf, w),
                 np.cross(u * np.minimum(m, b["M_d"]), ctx.target - root),
                 np.cross(u * np.maximum(m - b["M_d"], 0), ctx.target - root)]
    return np.array(cols)


def _bolted_amp(p, hw):
    return np.array([a for name, b in p.items() for a in
                     (1 / (hw["tubes"][name]["E"] * hw["tubes"][name]["I"]),
                      1 / (hw["tubes"][name]["k"] * hw["tubes"][name]["G"] * hw["tubes"][name]["A"]),
                      1 / b["k1"], 1 / b["k2"])])


def bolted_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", _bolted_amp(p, hw), _bolted_parts(p, ctx, hw)))


def bolted_features(p, ctx, hw):
    return _bolted_parts(p, ctx, hw)
