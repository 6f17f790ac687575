"""Set N body effects (new physics, not in sets A-M): the arm on a tracked (crawler) carrier on soft ground, whose
tracks sink plastically where the load passes its past maximum; the arm on a van's or truck's bed, the rear leaf
springs' inter-leaf friction giving the suspension its hysteresis; a ring gripper frame that bends under its weight and
is stiffened by the part it holds. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* crawler on soft ground: Bekker's pressure-sinkage law p = (k_c / b + k_phi) z^n for the first loading (Bekker, *Theory
  of Land Locomotion*, 1956; Wong, *Theory of Ground Vehicles*, 4th ed., 2008, ch. 2: n 0.5-1.1 for sands, loams and
  clays), and Wong's repetitive-loading measurements: unloading and reloading follow a line much stiffer than the virgin
  curve, p = p_u - k_u (z_u - z), until the past largest sinkage z_u is passed again (Wong, *Terramechanics and Off-Road
  Vehicle Engineering*, 2nd ed., 2010, ch. 2; soil does not rebound). Here k_u = r_u n p_u / z_u, r_u 4-10 (the
  reloading line 4-10 times the virgin curve's tangent there; assumed), the soil's k from the sinkage at the mean
  pressure, 1.5-3.5 mm (a compact carrier on firm loam or sand), n 0.6-1.1. Each track a rigid plate on 10 such soil
  columns; the carrier rigid, its heave and tilts from the equilibrium of its weight, the arm's and the payload's
  (statics; Newton's method). The carrier drove in before the session and the arm stood at its mean load (the soil's
  memory starts from the virgin equilibrium there); no production between the blocks, the payload changed between them.
  Carriers of 350-700 / 900-1800 kg (with their counterweight and batteries) with tracks of 0.8-1.2 x 0.15-0.25 /
  1.2-1.8 x 0.25-0.35 m at a gauge of 0.55-0.8 / 0.9-1.3 m, the arm's base 0.3-0.5 / 0.5-0.8 m above the ground, off the
  carrier's centre (ur10 / kr16_like; compact tracked carriers and construction robots, assumed). The displacement: the
  carrier's rigid heave, roll and pitch. First drawn with a sinkage of 3-8 mm and carriers of 250-500 / 800-1600 kg (up
  to 2.7 mm at the tool), then 1-3 mm with a reloading line 5-15 times as stiff (the ratcheting sinkage alone, a drift
  in time: the thermal or backlash model within 1.25x in trial draws), then 2-5 mm, 3-8 times, 600-1200 kg on kr16_like
  (up to 1.6 mm).
* leaf-spring suspension: the leaves of a leaf spring rub on each other, so the spring's force follows an upper
  (loading) and a lower (unloading) envelope k d +- F_f and, after each reversal, approaches the new envelope
  exponentially in the deflection: F = F_env + (F_r - F_env) exp(-|d - d_r| / beta) (Fancher, Ervin, MacAdam & Winkler,
  "Measurement and representation of the mechanical properties of truck leaf springs", SAE 800905, 1980; Cebon,
  *Handbook of Vehicle-Road Interaction*, 1999, ch. 5: friction bands of +-5-20 % of the static load). The rear corners
  (leaf spring and tyre in series, the tyre's compliance folded into the envelope's rate) follow it, the front corners
  (coil springs) are linear; the rigid body on its four corners is statically indeterminate (Newton's method on its
  heave and tilts), the deflection path between two poses monotone. A van of 1500-2200 kg sprung mass (rear corners
  40-80, front 30-50 kN/m, wheelbase 3.0-3.6 m, track 1.6-1.75 m, the bed 0.6-0.8 m up) carrying ur10; a truck of
  4000-6500 kg (250-450 / 200-350 kN/m, 3.4-4.5 m, 1.9-2.05 m, 0.9-1.2 m) carrying kr16_like; friction band +-5-12 % of
  the rear static corner load, beta 0.5-1.5 / 1-3 mm (assumed); the arm's base 0.8-1.6 / 0.8-2.0 m ahead of the rear
  axle and up to 0.4 m off the centre line; stabilisers not set (a service vehicle). The van parked with the arm at its
  first pose, the rear springs on their mid-lines (driving there shook them free of the friction band); one payload
  through the session. First the springs started on their loading envelope (the van then settled by up to F_f / k, 3-5
  mm, over the session) and the payload changed between blocks (the van's heave alone some 1 mm), the van's rates 60-120
  / 30-60 kN/m with the arm 0.3-1.0 m ahead of the rear axle (the stiff rear springs took its moments: gains of 14-16 %
  in trial draws).
* ring frame: grippers for round parts (drums, wheels, pipe flanges) carry their fingers on a ring frame -- a tube bent
  to a circle and held by three spokes from a hub on the flange; the ring between the spokes bends and twists in and out
  of its plane under its own weight and the fingers' (a statically indeterminate closed ring: Roark's *Formulas for
  Stress and Strain*, 7th ed., ch. 9, thin circular rings; solved here by the direct stiffness method with 3-D frame
  elements, Przemieniecki, *Theory of Matrix Structural Analysis*, 1968), and while a part is held it ties the three
  fingers' grip points together -- a rigid body that stiffens the ring against its ovalisation -- and loads them with
  its weight. So the frame is softer empty than holding, and its deflection is not a compliance times the held mass.
  Aluminium tubes, ring radius 120-200 / 180-300 mm, ring tube 18-24 x 1.5-2 / 28-40 x 2.5-3.5 mm, spokes 14-20 x
  1.2-1.8 / 22-30 x 2-3 mm (ur10's first 20-28 x 2-2.5 and 16-22 x 1.5-2 mm: gains of 17-21 % in two of six trial
  draws), fingers of 0.2-0.4 / 0.5-1 kg reaching 90 mm below the ring (ur10 / kr16_like; assumed); the target on the
  ring between a spoke and a finger, the part's centre on the tool axis 30-100 mm below the grip
  (:func:`effects_n.probe_hook`, :func:`effects_n.payload_hook`); pick and place, the first block empty. None on
  tool_changer.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------------------------------------ rigid carrier
def carrier_frame(p):
    """Unit axes (2, 3) along and across the carrier, and its ground centre (3,) in the arm's base frame [mm]."""
    ex = np.array([np.cos(p["yaw"]), np.sin(p["yaw"]), 0.0])
    ey = np.cross(Z, ex)
    return ex, ey, -(p["base_mm"][0] * ex + p["base_mm"][1] * ey) - p["base_mm"][2] * Z


def carrier_loads(p, ctx):
    """Total weight W (P,) [N] and its lever (P, 2) [mm] along and across the carrier from its ground centre."""
    m, pos, _ = ctx.mass_state
    ex, ey, O = carrier_frame(p)
    M = p["M_kg"] + m.sum(axis=1)
    r = pos - O
    lever = np.stack([(m * (r @ ex)).sum(axis=1), (m * (r @ ey)).sum(axis=1)], axis=1) / M[:, None]
    return kin.G * M, lever


def solve_carrier(x0, W, e, xy, force):
    """Heave and tilts x = (w, a, b) [mm, rad, rad] with the support sinkages z = w + a x + b y in equilibrium with the
    weight W at the lever e (2,); ``force(z) -> (F, dF/dz)`` per support (damped Newton)."""
    A = np.c_[np.ones(len(xy)), xy]
    target = W * np.r_[1.0, e]
    scale = W * np.r_[1.0, 1e3, 1e3]                              # [N, N mm, N mm]
    res = lambda x: (A.T @ force(A @ x)[0] - target) / scale
    x = np.array(x0, float)
    for _ in range(100):
        F, k = force(A @ x)
        r = (A.T @ F - target) / scale
        if np.abs(r).max() < 1e-12:
            break
        J = A.T @ (k[:, None] * A) / scale[:, None] + 1e-12 * np.diag([1.0, 1e6, 1e6])
        dx = np.linalg.solve(J, -r)
        t = 1.0
        while t > 1e-4 and np.abs(res(x + t * dx)).max() >= np.abs(r).max():
            t *= 0.5
        x = x + t * dx
    return x


def carrier_parts(p, ctx, states):
    """(3, P, 3): the target's displacement per unit heave change, roll and pitch change (amplitudes 1)."""
    ex, ey, O = carrier_frame(p)
    dw, da, db = (states - p["ref"]).T
    r = ctx.target - O
    return np.array([-dw[:, None] * Z, -db[:, None] * np.cross(ex, r), da[:, None] * np.cross(ey, r)])


# ------------------------------------------------------------------------------------------------ crawler sinkage
#: per arm: carrier mass [kg], track length, width, gauge [m], base height [m] (assumed)
CRAWLER = {"ur10": ((350, 700), (0.8, 1.2), (0.15, 0.25), (0.55, 0.8), (0.3, 0.5)),
           "kr16_like": ((900, 1800), (1.2, 1.8), (0.25, 0.35), (0.9, 1.3), (0.5, 0.8))}
SEGMENTS = 10


def crawler_draw(ctx, hw, rng):
    if ctx.chain.name not in CRAWLER:
        return {}
    M, (l0, l1), (b0, b1), (s0, s1), (h0, h1) = CRAWLER[ctx.chain.name]
    l, b, s = 1000 * rng.uniform(l0, l1), 1000 * rng.uniform(b0, b1), 1000 * rng.uniform(s0, s1)
    p = {"M_kg": rng.uniform(*M), "yaw": rng.uniform(0, 2 * np.pi), "n": rng.uniform(0.6, 1.1),
         "r_u": rng.uniform(4.0, 10.0), "A_mm2": l * b / SEGMENTS,
         "base_mm": np.array([rng.uniform(-0.25, 0.25) * l, rng.uniform(-0.2, 0.2) * s, 1000 * rng.uniform(h0, h1)])}
    x = (np.arange(SEGMENTS) + 0.5) / SEGMENTS * l - l / 2
    p["xy"] = np.r_[np.c_[x, np.full(SEGMENTS, s / 2)], np.c_[x, np.full(SEGMENTS, -s / 2)]]
    W, e = carrier_loads(p, ctx)
    p_mean = W.mean() / (2 * l * b)                                   # [N/mm^2]
    p["k"] = p_mean / rng.uniform(1.5, 3.5) ** p["n"]                # Bekker's k: the sinkage at the mean pressure
    zmax = np.zeros(2 * SEGMENTS)
    p["ref"] = solve_carrier([2.0, 0, 0], W.mean(), e.mean(axis=0), p["xy"], _soil(p, zmax))
    p["zmax0"] = p["xy"] @ p["ref"][1:] + p["ref"][0]
    return p


def _soil(p, zmax):
    """Support forces and their slopes (F, dF/dz) [N, N/mm] of the soil columns with the memory ``zmax``."""
    k, n, A = p["k"], p["n"], p["A_mm2"]
    pu = k * np.maximum(zmax, 0.0) ** n
    ku = p["r_u"] * n * pu / np.maximum(zmax, 1e-9)

    def force(z):
        virgin = z >= zmax
        zp = np.maximum(z, 1e-12)
        pv, dv = k * zp ** n, n * k * zp ** (n - 1)
        pr = pu - ku * (zmax - z)
        p_ = np.where(virgin, pv, np.maximum(pr, 0.0))
        d_ = np.where(virgin, dv, np.where(pr > 0, ku, 0.0))
        return A * p_, A * d_
    return force


def crawler_states(p, ctx):
    """Heave and tilts (P, 3) of the carrier along the session, the soil remembering its largest sinkage."""
    W, e = carrier_loads(p, ctx)
    zmax, x, out = p["zmax0"].copy(), p["ref"].copy(), np.zeros((len(W), 3))
    for i in range(len(W)):
        x = solve_carrier(x, W[i], e[i], p["xy"], _soil(p, zmax))
        zmax = np.maximum(zmax, p["xy"] @ x[1:] + x[0])
        out[i] = x
    return out


def crawler_apply(p, ctx, hw):
    return Contribution(displace=carrier_parts(p, ctx, crawler_states(p, ctx)).sum(axis=0) if p else None)


def crawler_features(p, ctx, hw):
    return carrier_parts(p, ctx, crawler_states(p, ctx)) if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------------ leaf springs
#: per arm: sprung mass [kg], rear / front corner rates [N/mm], wheelbase, track, bed height [m], beta [mm], arm's base
#: ahead of the rear axle [m] (assumed)
VEHICLE = {"ur10": ((1500, 2200), (40, 80), (30, 50), (3.0, 3.6), (1.6, 1.75), (0.6, 0.8), (0.5, 1.5), (0.8, 1.6)),
           "kr16_like": ((4000, 6500), (250, 450), (200, 350), (3.4, 4.5), (1.9, 2.05), (0.9, 1.2), (1.0, 3.0),
                         (0.8, 2.0))}


def fancher(d, d_r, F_r, s, k, F_f, beta):
    """Fancher's leaf-spring force and slope on the branch of direction ``s`` from the reversal point (d_r, F_r)."""
    env = k * d + s * F_f
    e = np.exp(-np.abs(d - d_r) / beta)
    return env + (F_r - env) * e, k * (1 - e) - s / beta * (F_r - env) * e


def _suspension(p, st):
    """Corner forces and slopes for trial deflections z (4,): rear corners (0, 1) on their Fancher branch, continued or
    reversed at the last deflection, front corners (2, 3) linear."""
    k, F_f, beta = p["k_rear"], p["F_f"], p["beta"]

    def force(z):
        F, dF = p["k_front"] * z, np.full(4, p["k_front"])
        for i in (0, 1):
            if (z[i] - st["d"][i]) * st["s"][i] >= 0:
                F[i], dF[i] = fancher(z[i], st["d_r"][i], st["F_r"][i], st["s"][i], k, F_f, beta)
            else:
                F[i], dF[i] = fancher(z[i], st["d"][i], st["F"][i], -st["s"][i], k, F_f, beta)
        return F, dF
    return force


def leaf_draw(ctx, hw, rng):
    if ctx.chain.name not in VEHICLE:
        return {}
    M, kr, kf, wb, tr, h, beta, ahead = VEHICLE[ctx.chain.name]
    wb, tr, c = 1000 * rng.uniform(*wb), 1000 * rng.uniform(*tr), rng.uniform(0.4, 0.55)
    x_rear = -c * wb                                                   # the sprung centre of mass at the origin
    p = {"M_kg": rng.uniform(*M), "yaw": rng.uniform(0, 2 * np.pi), "k_rear": rng.uniform(*kr),
         "k_front": rng.uniform(*kf), "beta": rng.uniform(*beta),
         "xy": np.array([[x_rear, tr / 2], [x_rear, -tr / 2], [x_rear + wb, tr / 2], [x_rear + wb, -tr / 2]]),
         "base_mm": np.array([x_rear + 1000 * rng.uniform(*ahead), rng.uniform(-400, 400), 1000 * rng.uniform(*h)])}
    W, e = carrier_loads(p, ctx)
    share = 0.5 * (1 - c)                                              # static load share of a rear corner
    p["F_f"] = rng.uniform(0.05, 0.12) * share * W.mean()
    mid = dict(p, F_f=0.0)                                             # the springs' mid-lines
    st = {"d": np.zeros(2), "F": np.zeros(2), "s": np.ones(2), "d_r": np.full(2, -1e9), "F_r": np.zeros(2)}
    x = solve_carrier([W[0] / (2 * (p["k_rear"] + p["k_front"])), 0, 0], W[0], e[0], p["xy"], _suspension(mid, st))
    p["ref"] = x
    z = p["xy"][:2] @ x[1:] + x[0]
    p["init"] = {"d": z, "F": p["k_rear"] * z, "s": np.ones(2), "d_r": z, "F_r": p["k_rear"] * z}
    return p


def leaf_states(p, ctx):
    """Heave and tilts (P, 3) of the vehicle along the session, the rear springs following Fancher's hysteresis."""
    W, e = carrier_loads(p, ctx)
    st = {k: np.array(v, float) for k, v in p["init"].items()}
    x, out = p["ref"].copy(), np.zeros((len(W), 3))
    for i in range(len(W)):
        force = _suspension(p, st)
        x = solve_carrier(x, W[i], e[i], p["xy"], force)
        z = p["xy"][:2] @ x[1:] + x[0]
        F, _ = force(np.r_[z, 0.0, 0.0])
        rev = (z - st["d"]) * st["s"] < 0
        st["d_r"], st["F_r"] = np.where(rev, st["d"], st["d_r"]), np.where(rev, st["F"], st["F_r"])
        st["s"] = np.where(rev, -st["s"], st["s"])
        st["d"], st["F"] = z, F[:2]
        out[i] = x
    return out


def leaf_apply(p, ctx, hw):
    return Contribution(displace=carrier_parts(p, ctx, leaf_states(p, ctx)).sum(axis=0) if p else None)


def leaf_features(p, ctx, hw):
    return carrier_parts(p, ctx, leaf_states(p, ctx)) if p else np.zeros((0, len(ctx.q), 3))


# -------------------------------------------------------------------------------------------------- ring frame
#: per arm: ring radius, ring tube D x t, spoke tube D x t [mm], finger mass [kg] (assumed)
RING = {"ur10": ((120.0, 200.0), (18.0, 24.0, 1.5, 2.0), (14.0, 20.0, 1.2, 1.8), (0.2, 0.4)),
        "kr16_like": ((180.0, 300.0), (28.0, 40.0, 2.5, 3.5), (22.0, 30.0, 2.0, 3.0), (0.5, 1.0))}
RING_NODES, HUB_Z_MM, FINGER_MM = 36, 60.0, 90.0


def _tube(D, t):
    A = np.pi / 4 * (D ** 2 - (D - 2 * t) ** 2)
    I = np.pi / 64 * (D ** 4 - (D - 2 * t) ** 4)
    return A, I, 2 * I


def _beam(x1, x2, A, I, J, E=1.0, G=1.0 / 2.66):
    """Stiffness (12, 12) of a 3-D Euler-Bernoulli frame element between points x1, x2 [mm] (global axes)."""
    L = np.linalg.norm(x2 - x1)
    ex = (x2 - x1) / L
    ey = np.cross(Z if abs(ex[2]) < 0.9 else np.array([1.0, 0, 0]), ex)
    ey /= np.linalg.norm(ey)
    T3 = np.array([ex, ey, np.cross(ex, ey)])
    k = np.zeros((12, 12))
    a, t, b = E * A / L, G * J / L, E * I / L ** 3
    k[np.ix_([0, 6], [0, 6])] = a * np.array([[1, -1], [-1, 1]])          # axial
    k[np.ix_([3, 9], [3, 9])] = t * np.array([[1, -1], [-1, 1]])          # torsion
    for u, r, s in ((1, 5, 1.0), (2, 4, -1.0)):          # bending in the local x-y and x-z planes
        idx = [u, r, u + 6, r + 6]
        c, L2 = 6 * L * s, L * L
        k[np.ix_(idx, idx)] = b * np.array([[12, c, -12, c], [c, 4 * L2, -c, 2 * L2], [-12, -c, 12, -c],
                                            [c, 2 * L2, -c, 4 * L2]])
    T = np.kron(np.eye(4), T3)
    return T.T @ k @ T


def ring_model(p):
    """Nodes (N, 3) [mm, tool frame], elements (pairs, section (A, I, J)) and the ring's node masses (N,) [kg]: the
    hub (node 0, clamped), three spokes, the ring, three stiff fingers down to their grip points and, when held, the
    part's stiff links from its centre (the last node) to the grip points."""
    R, (D, t), (Ds, ts) = p["R_mm"], p["ring_tube"], p["spoke_tube"]
    phi = p["phi0"] + 2 * np.pi * np.arange(RING_NODES) / RING_NODES
    ring = np.c_[R * np.cos(phi), R * np.sin(phi), np.full(RING_NODES, HUB_Z_MM)]
    nodes = [np.array([0.0, 0.0, HUB_Z_MM])] + list(ring)
    elems, sec, ssec = [], _tube(D, t), _tube(Ds, ts)
    elems += [(1 + i, 1 + (i + 1) % RING_NODES, sec) for i in range(RING_NODES)]
    stiff = tuple(1e3 * np.array(_tube(D, t)))
    for k in range(3):
        s, f = 1 + 12 * k, 1 + 12 * k + 6                   # spoke at 0, 120, 240 deg; finger midway
        mid = len(nodes)
        nodes.append(0.5 * (nodes[0] + nodes[s]))
        elems += [(0, mid, ssec), (mid, s, ssec)]
        nodes.append(nodes[f] + FINGER_MM * Z)
        elems.append((f, len(nodes) - 1, stiff))
    nodes.append(np.array([0.0, 0.0, HUB_Z_MM + FINGER_MM + p["part_z_mm"]]))
    grips = [1 + RING_NODES + 2 * k + 1 for k in range(3)]
    links = [(len(nodes) - 1, g, stiff) for g in grips]
    mass = np.zeros(len(nodes))
    mass[1:1 + RING_NODES] = p["ring_kg"] / RING_NODES
    mass[[1 + 12 * k + 6 for k in range(3)]] += p["finger_kg"]
    return np.array(nodes), elems, links, mass


def ring_compliance(p):
    """(3, 3, 3): the target's displacement [mm per (m/s^2)] at E = 1 N/mm^2 per unit tool-frame gravity -- of the frame
    empty, of the frame holding a part, and per kg of the part held."""
    nodes, elems, links, mass = ring_model(p)
    n = len(nodes)

    def stiffness(with_part):
        K = np.zeros((6 * n, 6 * n))
        for a, b, (A, I, J) in elems + (links if with_part else []):
            idx = np.r_[6 * a:6 * a + 6, 6 * b:6 * b + 6]
            K[np.ix_(idx, idx)] += _beam(nodes[a], nodes[b], A, I, J)
        K[n * 6 - 6:, n * 6 - 6:] += 0.0 if with_part else np.eye(6)   # the part's node idle when empty
        return K[6:, 6:]                                                   # the hub clamped

    tgt = 1 + p["target_node"]
    out = np.zeros((3, 3, 3))
    for s, (with_part, m) in enumerate(((False, mass), (True, mass), (True, np.eye(n)[-1]))):
        K = stiffness(with_part)
        for i in range(3):
            f = np.zeros(6 * n)
            f[i::6] = m * 1.0                                               # N per (m/s^2) per kg
            out[s, :, i] = np.linalg.solve(K, f[6:])[6 * tgt - 6:6 * tgt - 3]
    return out


def ring_draw(ctx, hw, rng):
    if ctx.chain.name not in RING:
        return {}
    (R0, R1), (D0, D1, t0, t1), (d0, d1, s0, s1), (f0, f1) = RING[ctx.chain.name]
    pr = np.asarray(ctx.probe_mm, float)
    D, t = rng.uniform(D0, D1), rng.uniform(t0, t1)
    p = {"R_mm": float(np.linalg.norm(pr[:2])), "ring_tube": (D, t),
         "spoke_tube": (rng.uniform(d0, d1), rng.uniform(s0, s1)),
         "finger_kg": rng.uniform(f0, f1), "part_z_mm": float(ctx.payload_com_mm[2]) - HUB_Z_MM - FINGER_MM, "E": 70e3,
         "phi0": float(np.arctan2(pr[1], pr[0])) - rng.uniform(0.2, 0.8) * np.pi / 3}
    p["ring_kg"] = 2700e-9 * _tube(D, t)[0] * 2 * np.pi * p["R_mm"]
    p["target_node"] = int(round((np.arctan2(pr[1], pr[0]) - p["phi0"]) / (2 * np.pi) * RING_NODES)) % RING_NODES
    p["C"] = ring_compliance(p)
    return p


def ring_part(p, ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, -kin.G * Z)
    m = ctx.session.payload_kg
    held = (m > 0)[:, None]
    local = np.where(held, g @ p["C"][1].T, g @ p["C"][0].T) + m[:, None] * (g @ p["C"][2].T)
    return np.einsum("pij,pj->pi", Rt, local)


def ring_apply(p, ctx, hw):
    return Contribution(displace=ring_part(p, ctx) / p["E"] if p else None)


def ring_features(p, ctx, hw):
    return ring_part(p, ctx)[None] if p else np.zeros((0, len(ctx.q), 3))
