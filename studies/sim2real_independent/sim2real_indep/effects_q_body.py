"""Set Q body effects (new physics, not in sets A-P): the arm's base on three feet preloaded through stacks of disc
(Belleville) springs, ever softer towards their flat position; the arm's base plate on a three-ball kinematic
coupling clamped by a central preload, its six Hertzian contacts; the tracker's reflector on an articulated
(two-ball-joint) holder on the tool, the clamped ball joints giving under its weight; and a curved (gooseneck) supply
tube carrying the nozzle, uncurling under its pressure like a Bourdon tube. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* disc springs: the arm's base stands on three feet, each a bolt through a stack of disc (Belleville) springs that
  preloads it onto the floor (spring-isolated levelling mounts); a disc spring's force follows Almen & Laszlo, F = 4 E
  t^4 / ((1 - nu^2) K1 D^2) (s / t) [(h / t - s / t)(h / t - s / 2t) + 1] (Almen & Laszlo, Trans. ASME 58, 1936; DIN EN
  16983 / DIN 2093), regressive -- ever softer towards the flat position -- for cone heights h / t of 1.3-1.41 (first
  1-1.35: nearly linear over the session). The feet carry the weights statically determinately (their force and two
  moments fix the three reactions), each stack compresses by n h x(F) with x the curve's inverse, and the three
  compressions sink and tilt the base. Feet at 250-400 mm from the base's axis, 50-120 mm below it; the bolts' preload
  and the discs chosen so that over the session the stacks work between s / h = 0.15 and 0.95 (first 0.2-0.85; a stack
  pressed flat is solid), a stack's stroke n h of 0.1-0.3 mm (assumed); every arm. The true structure: one column (the
  curve's inverse its shape), amplitude the stroke.
* kinematic coupling: three balls in three radial vee grooves locate a plate exactly (Maxwell coupling; Slocum, "Design
  of three-groove kinematic couplings", Precision Engineering 14, 1992; Slocum, *Precision Machine Design*, 1992, ch.
  7), the contacts at 45 deg; a central clamp presses the plate down with F_p; each contact's approach follows Hertz,
  delta = (9 F^2 / (16 E*^2 R))^(1/3) for a ball of radius R on a flat flank (Johnson, *Contact Mechanics*, 1985, ch.
  4), and the plate moves so that its contacts' normal motions are -delta (statics: Merlet, *Parallel Robots*, 2nd ed.,
  2006, ch. 6: A f = -W, A's columns the contacts' normals and their moments). Balls of 6-12 mm radius (first 8-16) at
  120-200 mm (first 150-250) from the base's axis, 40-80 mm below it (a re-locatable robot base: move it between
  stations and back), the clamp sized so that the least-loaded contact keeps 5-15 % (first 10-30 %) of its share of the
  clamp (assumed); every arm. The true structure: one column (the contact forces' 2/3 power its shape), amplitude (9 /
  (16 E*^2 R))^(1/3).
* articulated holder: a reflector held on the tool by a two-segment holder whose ball joints are locked by a clamp
  (magnetic-base / "Noga"-type articulated holders carrying 1.5" SMR nests); a locked ball joint is a rotational spring
  (the ball's contact with its clamping cups and the thin rods), so each joint turns by M / k under the moment of the
  weights beyond it (Timoshenko & Gere, *Mechanics of Materials*: a chain of rigid bars on rotational springs). Joints
  of 100-400 N m/rad, an SMR and nest of 0.15-0.25 kg, segments of 0.05-0.15 kg, the holder's base on the tool 20-50 mm
  out, a kink of 30-60 mm across the line to the target (assumed); the target 150-250 mm from the flange
  (:func:`effects_q.probe_hook`). The true structure: two columns (one per joint), amplitudes 1 / k.
* gooseneck: a curved tube of an oval section straightens under internal pressure (the Bourdon effect: Wolf, "Die
  Berechnung der Bourdonfeder", 1946; Clark & Reissner, "Deformations and stresses in Bourdon tubes", J. Appl. Phys. 21,
  1950), its curvature falling by a share eps that grows with the pressure and the section's ovality; at fixed length s
  a circular arc's tip moves by -eps kappa d(tip)/d(kappa). A dispensing or spraying tool's supply tube leaves the tool
  along its axis 40 mm out, then bends through 90 deg on a radius of 60-120 mm to the nozzle, which carries the target
  (:func:`effects_q.probe_hook`); pressurised while the valve is open, at 50-80 % of the measurements (the process's
  signal, not logged), eps 1-4e-3 (a slightly oval steel tube at 3-8 bar, assumed). The true structure: one column (the
  valve's states its shape), amplitude eps.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])
E_STEEL, NU_STEEL = 210e3, 0.3          # [N/mm^2]


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _unit(v):
    return v / np.linalg.norm(v)


def wrench(ctx, O):
    """(P, 6): the weights' force [N] and moment about O [N mm] on the arm's base."""
    m, pos, _ = ctx.mass_state
    F = -kin.G * m[..., None] * Z                                   # (P, B, 3)
    return np.c_[F.sum(axis=1), np.cross(pos - O, F).sum(axis=1)]


def support_matrix(points, normals, O):
    """(6, 6): columns the supports' unit directions and their moments about O."""
    return np.vstack([normals.T, np.cross(points - O, normals).T])


def _target_motion(x, ctx, O):
    """(P, 3): the target's displacement for the base's small motions x (P, 6) = (u, omega) about O."""
    return x[:, :3] + np.cross(x[:, 3:], ctx.target - O)


# ------------------------------------------------------------------------------------------------ disc springs
DISC_ARMS = {"ur10", "kr16_like", "tool_changer"}
DISC_X = (0.15, 0.95)                    # the stacks' working range of s / h


def disc_curve(x, r):
    """Almen-Laszlo: a disc spring's force per its unit force at deflection x = s / h, cone height over thickness r."""
    return r * x * (r ** 2 * (1 - x) * (1 - x / 2) + 1)


def disc_draw(ctx, hw, rng):
    R, az = rng.uniform(250.0, 400.0), rng.uniform(0, 2 * np.pi)
    ang = az + 2 * np.pi * np.arange(3) / 3
    p = {"feet": np.c_[R * np.cos(ang), R * np.sin(ang)], "h_mm": rng.uniform(50.0, 120.0),
         "r": rng.uniform(1.3, 1.41), "stroke_mm": rng.uniform(0.1, 0.3), "F_pre": 0.0, "F_unit": 1.0}
    F = disc_reactions(p, ctx)                                          # without preload (P, 3)
    # the preload bolts sized so that the least-loaded stack sits at s / h = 0.2 and the most loaded at 0.85
    lo, hi = disc_curve(np.array(DISC_X), p["r"])
    p["F_unit"] = (F.max() - F.min()) / (hi - lo)
    p["F_pre"] = lo * p["F_unit"] - F.min()
    return p


def disc_reactions(p, ctx):
    """(P, 3): the feet's reactions [N] to the weights' force and moments (statically determinate), plus the preload."""
    O = -p["h_mm"] * Z
    m, pos, _ = ctx.mass_state
    W = kin.G * m.sum(axis=1)
    M = np.cross(pos - O, -kin.G * m[..., None] * Z).sum(axis=1)
    c = p["feet"]
    A = np.array([np.ones(3), c[:, 1], -c[:, 0]])
    return p["F_pre"] + np.linalg.solve(A, np.c_[W, -M[:, 0], -M[:, 1]].T).T


def disc_x(p, F):
    """s / h of a stack at forces F [N] (the curve's inverse, monotone for r < sqrt 2; a stack pressed flat is solid:
    s / h stops at 1)."""
    grid = np.linspace(0.0, 1.0, 4001)
    return np.interp(F / p["F_unit"], disc_curve(grid, p["r"]), grid)


def disc_shape(p, ctx):
    """(P, 3): the target's displacement per unit stroke (the stacks' n h): the base sinking and tilting as the three
    stacks compress."""
    d = disc_x(p, disc_reactions(p, ctx))
    c = p["feet"]
    A = np.c_[np.ones(3), c[:, 1], -c[:, 0]]
    sol = np.linalg.solve(A, -d.T).T
    r = ctx.target + p["h_mm"] * Z
    w = np.c_[sol[:, 1], sol[:, 2], np.zeros(len(sol))]
    return sol[:, :1] * Z + np.cross(w, r)


def disc_apply(p, ctx, hw):
    return Contribution(displace=p["stroke_mm"] * disc_shape(p, ctx))


def disc_features(p, ctx, hw):
    return disc_shape(p, ctx)[None]


# ------------------------------------------------------------------------------------------ kinematic coupling
def kc_draw(ctx, hw, rng):
    az, R, h = rng.uniform(0, 2 * np.pi), rng.uniform(120, 200), rng.uniform(40, 80)
    rb = rng.uniform(6.0, 12.0)
    a = az + 2 * np.pi * np.arange(3) / 3
    pts, nrm = [], []
    g = np.pi / 4
    for ak in a:
        r, t = np.array([np.cos(ak), np.sin(ak), 0.0]), np.array([-np.sin(ak), np.cos(ak), 0.0])
        for s in (1, -1):
            nk = np.cos(g) * Z + s * np.sin(g) * t                     # the flank's push on the ball (the plate)
            nrm.append(nk)
            pts.append(R * r - h * Z - rb * nk)
    p = {"points": np.array(pts), "normals": np.array(nrm), "O": -h * Z, "R_ball": rb, "F_p": 0.0,
         "share": rng.uniform(0.05, 0.15)}
    A = support_matrix(p["points"], p["normals"], p["O"])
    fW = -np.linalg.solve(A, wrench(ctx, p["O"]).T).T                  # (P, 6) the weights' contact forces
    f1 = np.linalg.solve(A, np.r_[Z, 0, 0, 0])                         # per newton of clamp (equal by symmetry)
    c1 = f1.mean()
    p["F_p"] = max(-fW.min(), 0.1 * np.abs(fW).max()) / (c1 * (1 - p["share"]))
    Es = E_STEEL / (2 * (1 - NU_STEEL ** 2))
    p["c_H"] = (9 / (16 * Es ** 2 * rb)) ** (1 / 3)
    return p


def kc_forces(p, ctx):
    """(P, 6): the contacts' forces [N] under the clamp and the weights."""
    A = support_matrix(p["points"], p["normals"], p["O"])
    W = wrench(ctx, p["O"])
    W[:, 2] -= p["F_p"]
    return -np.linalg.solve(A, W.T).T


def kc_shape(p, ctx):
    """(P, 3): the target's displacement per unit Hertz constant: the plate moving so that each contact approaches by
    its force^(2/3)."""
    A = support_matrix(p["points"], p["normals"], p["O"])
    d = np.maximum(kc_forces(p, ctx), 0.0) ** (2 / 3)
    x = -np.linalg.solve(A.T, d.T).T
    return _target_motion(x, ctx, p["O"])


def kc_apply(p, ctx, hw):
    return Contribution(displace=p["c_H"] * kc_shape(p, ctx))


def kc_features(p, ctx, hw):
    return kc_shape(p, ctx)[None]


# ---------------------------------------------------------------------------------------- articulated holder
HOLDER_MM = (150.0, 250.0)


def holder_draw(ctx, hw, rng):
    S = np.asarray(ctx.probe_mm, float)
    B1 = rng.uniform(20.0, 50.0) * Z
    line = S - B1
    across = _unit(np.cross(line, rng.normal(size=3)))
    B2 = B1 + rng.uniform(0.4, 0.6) * line + rng.uniform(30.0, 60.0) * across
    return {"S": S, "B1": B1, "B2": B2, "m_S": rng.uniform(0.15, 0.25), "m_seg": rng.uniform(0.05, 0.15, 2),
            "k_Nmm": rng.uniform(1e5, 4e5, 2)}


def holder_moments(p, g_t):
    """(2, P, 3): the weights' moments [N mm] about the two joints, tool frame, for gravity g_t (P, 3) [m/s^2]."""
    S, B1, B2 = p["S"], p["B1"], p["B2"]
    mid1, mid2 = (B1 + B2) / 2, (B2 + S) / 2
    W_S, W1, W2 = p["m_S"] * g_t, p["m_seg"][0] * g_t, p["m_seg"][1] * g_t
    M2 = np.cross(S - B2, W_S) + np.cross(mid2 - B2, W2)
    M1 = np.cross(S - B1, W_S) + np.cross(mid2 - B1, W2) + np.cross(mid1 - B1, W1)
    return np.array([M1, M2])


def holder_cols(p, ctx):
    """(2, P, 3): the target's displacement per unit compliance of each joint [mm per rad/(N mm)], base frame."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g_t = np.einsum("pji,j->pi", Rt, -kin.G * Z)                       # gravity in the tool frame
    M = holder_moments(p, g_t)
    cols = [np.cross(M[0], p["S"] - p["B1"]), np.cross(M[1], p["S"] - p["B2"])]
    return np.array([np.einsum("pij,pj->pi", Rt, c) for c in cols])


def holder_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("m,mpi->pi", 1 / p["k_Nmm"], holder_cols(p, ctx)))


def holder_features(p, ctx, hw):
    return holder_cols(p, ctx)


# -------------------------------------------------------------------------------------------------- gooseneck
NECK_L0_MM, NECK_R_MM = 40.0, (60.0, 120.0)


def neck_geometry(tip):
    """Radius [mm], bend direction (3,) of a 90 deg gooseneck leaving the tool axis at NECK_L0_MM with its nozzle at
    ``tip`` (tool frame)."""
    rho = float(np.hypot(tip[0], tip[1]))
    return rho, np.array([tip[0] / rho, tip[1] / rho, 0.0])


def neck_draw(ctx, hw, rng):
    duty = rng.uniform(0.5, 0.8)
    return {"eps": rng.uniform(1e-3, 4e-3), "duty": duty, "tip": np.asarray(ctx.probe_mm, float),
            "state": (rng.uniform(0, 1, len(ctx.q)) < duty).astype(float)}


def neck_local(p):
    """(3,): the nozzle's displacement per unit eps in the tool frame: -kappa d(tip)/d(kappa) at fixed length."""
    R, e = neck_geometry(p["tip"])
    k, s = 1 / R, R * np.pi / 2
    dz = s * np.cos(k * s) / k - np.sin(k * s) / k ** 2
    de = s * np.sin(k * s) / k - (1 - np.cos(k * s)) / k ** 2
    return -k * (de * e + dz * Z)


def neck_shape(p, ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return p["state"][:, None] * (Rt @ neck_local(p))


def neck_apply(p, ctx, hw):
    return Contribution(displace=p["eps"] * neck_shape(p, ctx))


def neck_features(p, ctx, hw):
    return neck_shape(p, ctx)[None]
