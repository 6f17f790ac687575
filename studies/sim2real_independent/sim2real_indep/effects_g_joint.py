"""Set G joint effects (new physics, not in sets A-F): axes 2-3 driven through a sector gear by two pinions preloaded
against each other (an electronic torque bias), a heavy process hose hanging as a catenary from a boom to the flange,
a helical output stage whose shaft floats axially in its bearings' play, a cycloid reducer's fractional ratio entered
rounded in the drive configuration, and an output-side ring encoder whose ring shifts against its read head as the
joint bearing tilts under load. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* twin pinions with torque bias: two motors drive one gear through two pinions; a bias torque T_b loads them
  against each other so both flanks stay engaged (no backlash) while |tau| < 2 T_b; then the unloaded pinion leaves
  its flank and the mesh stiffness halves (Gawronski, Beech-Brandt, Ahlstrom & Maneri, "Torque-bias profile for
  improved tracking of the Deep Space Network antennas", IEEE Antennas Propag. Mag. 42(6), 2000; the "master-slave
  torque bias / electronic bracing" of CNC drives). Per pinion mesh at the output k = 0.5-1x the cycloid gear's
  rigidity of :mod:`hardware` (softened as the assembled joint there; first drawn at 0.3-0.6x, which put 4 mm on
  tool_changer), T_b 10-30 % of the session's largest load (assumed); only on the arms whose main
  axes have cycloid drives (tool_changer, kr16_like: the kind replaces the reducers of axes 2 and 3; none on ur10).
  The other joints twist with their linear gear stiffness.
* hose catenary: an inextensible hose of weight w per length hanging between a fixed point A and the flange B
  takes the catenary y = a cosh((x - x0) / a) + c with a = H / w and sqrt(S^2 - v^2) = 2 a sinh(h / 2a) for span h,
  rise v and length S (Irvine, *Cable Structures*, 1981, ch. 1); the hose pulls B along its tangent with the
  horizontal tension H. Welding / coolant hose packages 1-2.5 / 1.5-4 / 3-8 kg/m on ur10 / kr16_like /
  tool_changer, the hook on a boom 0.8-1.5 m aside the workspace and 0.2-0.8 m above the flange's highest point,
  S 1.1-1.3x the largest distance (assumed). Joint loads tau = J^T F (Craig, *Introduction to Robotics*, ch. 5);
  every joint twists with the linear stiffness of :mod:`hardware` under gravity plus hose.
* axial float of a helical stage: a helical gear displaced axially by delta against its mate turns by
  delta tan(beta) / r (the tooth is a helix of lead 2 pi r / tan beta; ISO 21771 helical-gear geometry). The output
  shaft rests against the bearing the axial force pushes it to -- the gravity component along the joint axis --
  once it beats the friction of seals and bearings (5-15 % of its largest value, assumed); below that it stays where
  it was. Axial play of deep-groove bearing pairs 0.08-0.2 mm (about ten times the radial clearance, group C3;
  bearing catalogues as recalled; first drawn at 0.02-0.08 mm, absorbed by the geometry), beta 20-30 deg, r 25-50
  mm (assumed): the wrist axes of the arms given helical (positioner-type) output stages, tool_changer and
  kr16_like.
* fractional ratio: cycloid reducers have ratios R = 1 + (Z2 / Z1) Z_p that are fractions (Nabtesco RV-N
  catalogue: e.g. 164.07 = 2133 / 13, as recalled). A drive configured with the catalogue's rounded value runs the
  joint by (R_cfg / R - 1)(q - q_m) off, q_m the mastering position (joint zero). Here R = n + k / d (n 41-185,
  d 11-31), rounded to one decimal (assumed); the cycloid main axes only (none on ur10: its strain-wave ratios are
  integers).
* ring-encoder shift: an eccentricity e of the graduation against the read head reads as e / R_e in angle
  (HEIDENHAIN, "Angle encoders" brochure: 2e/D); the bearing tilts theta = M_perp / K_tilt under the moment normal to
  its axis (K_tilt as set C's bearing_tilt: RV 1.5-4 T_rated per arcmin, strain-wave units 2-5 K3, softened in the
  assembled joint by the factor of :mod:`hardware`), so a ring at
  a_e from the tilt centre moves by a_e theta x axis: the reading errs by a_e (M_perp . n_h) / (R_e K_tilt), n_h the
  read head's radial direction in the housing. One read head (no opposed pair averaging it out), R_e 30-60 / 60-120
  mm (light / heavy arms), a_e 15-40 / 60-150 mm (on the heavy arms the ring sits on the link casting beyond the
  stiff cycloid bearing; first drawn at 20-60 mm there, absorbed), on axes 1-3 read by output-side encoders
  (dual-encoder joints, as in cobots and accuracy options; assumed). The tilt itself is set C's physics and left
  out here: the case isolates the reading error.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_f_joint import point_loads

DOWN = np.array([0.0, 0.0, -1.0])


def joint_wrench(ctx):
    """Gravity force (P, n, 3) [N] and moment (P, n, 3) [N m] about each joint's axis point of everything beyond it."""
    m, pos, body = ctx.mass_state
    F = m[..., None] * kin.G * DOWN
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    P, n = ctx.q.shape
    Fo, Mo = np.zeros((P, n, 3)), np.zeros((P, n, 3))
    for j in range(n):
        on = body >= j + 1
        Fo[:, j] = F[:, on].sum(axis=1)
        Mo[:, j] = np.cross((pos[:, on] - c[:, j, None]) / 1000.0, F[:, on]).sum(axis=1)
    return Fo, Mo, w, c


def _torsion_all(ctx, hw, loads, skip=()):
    return np.array([hwm.torsion(d, loads[:, j], False) if j not in skip else np.zeros(len(ctx.q))
                     for j, d in enumerate(hw["drives"])]).T


# --------------------------------------------------------------------------------------------- twin pinions
def dual_draw(ctx, hw, rng):
    out = []
    for j in (1, 2):
        d = hw["drives"][j]
        if d["kind"] != "RV":
            continue
        T_max = float(np.abs(ctx.loads[:, j]).max())
        out.append({"joint": j, "k_Nm_per_rad": rng.uniform(0.5, 1.0) * d["K"] / d["soften"],
                    "T_bias_Nm": rng.uniform(0.1, 0.3) * T_max})
    return out


def dual_signals(g, ctx):
    """Load (P,) [N m] and its part beyond twice the bias, signed (P,): the twist is (tau + that) / 2k."""
    tau = ctx.loads[:, g["joint"]]
    return tau, np.sign(tau) * np.maximum(np.abs(tau) - 2 * g["T_bias_Nm"], 0.0)


def dual_apply(p, ctx, hw):
    if not p:                                           # no cycloid main axes: no twin-pinion drive
        return Contribution()
    dq = _torsion_all(ctx, hw, ctx.loads, skip={g["joint"] for g in p})
    for g in p:
        tau, extra = dual_signals(g, ctx)
        dq[:, g["joint"]] = (tau + extra) / (2 * g["k_Nm_per_rad"])
    return Contribution(dq=dq)


def dual_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    own = {g["joint"]: g for g in p}
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)]
    cols += [ctx.joint_feature(j, dual_signals(g, ctx)[1]) for j, g in own.items()]
    return np.array(cols)


# ------------------------------------------------------------------------------------------- hose catenary
HOSE_N_PER_M = {"ur10": (10.0, 25.0), "kr16_like": (15.0, 40.0), "tool_changer": (30.0, 80.0)}


def hose_draw(ctx, hw, rng):
    B = kin.flange(ctx.chain, ctx.q)[0] / 1000.0
    az = rng.uniform(0, 2 * np.pi)
    A = np.r_[B[:, :2].mean(axis=0) + rng.uniform(0.8, 1.5) * np.array([np.cos(az), np.sin(az)]),
              B[:, 2].max() + rng.uniform(0.2, 0.8)]
    S = rng.uniform(1.1, 1.3) * np.linalg.norm(B - A, axis=1).max()
    return {"A_m": A, "S_m": S, "w_N_per_m": rng.uniform(*HOSE_N_PER_M[ctx.chain.name])}


def catenary_end_force(A, B, S):
    """Force (P, 3) [N per N/m of hose weight] of a hose of length S [m] hanging from A (3,) on points B (P, 3) [m]."""
    d = B - A
    h = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-3)
    e_h = np.c_[d[:, :2] / h[:, None], np.zeros(len(B))]
    v = d[:, 2]
    target = np.sqrt(S * S - v * v)
    lo, hi = np.log(h / 1400.0), np.log(h * 1e4)
    for _ in range(80):                                  # 2 a sinh(h / 2a) falls with a: bisect in log a
        mid = 0.5 * (lo + hi)
        a = np.exp(mid)
        big = 2 * a * np.sinh(h / (2 * a)) > target
        lo, hi = np.where(big, mid, lo), np.where(big, hi, mid)
    a = np.exp(0.5 * (lo + hi))
    x0 = h / 2 - a * np.arcsinh(v / (2 * a * np.sinh(h / (2 * a))))
    slope = np.sinh((h - x0) / a)
    return a[:, None] * (-e_h - slope[:, None] * np.array([0.0, 0.0, 1.0]))


def hose_unit_loads(p, ctx):
    """Joint loads (P, n) of the hose per N/m of its weight."""
    B = kin.flange(ctx.chain, ctx.q)[0]
    return point_loads(ctx, ctx.chain.n, B, catenary_end_force(p["A_m"], B / 1000.0, p["S_m"]))


def hose_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, ctx.loads + p["w_N_per_m"] * hose_unit_loads(p, ctx)))


def hose_features(p, ctx, hw):
    unit = hose_unit_loads(p, ctx)
    return np.array([ctx.joint_feature(j, s[:, j]) for s in (ctx.loads, unit) for j in range(ctx.chain.n)])


# ------------------------------------------------------------------------------------------- axial float
def float_draw(ctx, hw, rng):
    if ctx.chain.name == "ur10":
        return []
    F, _, w, _ = joint_wrench(ctx)
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[3:]) + 3:
        Fa = np.einsum("pi,pi->p", F[:, j], w[:, j])
        out.append({"joint": int(j), "amp_rad": rng.uniform(0.08, 0.2) * np.tan(np.deg2rad(rng.uniform(20, 30)))
                    / (2 * rng.uniform(25, 50)) * rng.choice([-1, 1]),
                    "F_friction_N": rng.uniform(0.05, 0.15) * np.abs(Fa).max(), "start": float(rng.choice([-1, 1]))})
    return out


def float_state(g, ctx):
    """Side of the axial play the shaft rests on (P,) +-1: the axial gravity force's sign once it beats friction."""
    F, _, w, _ = joint_wrench(ctx)
    Fa = np.einsum("pi,pi->p", F[:, g["joint"]], w[:, g["joint"]])
    out, s = np.zeros(len(Fa)), g["start"]
    for i, f in enumerate(Fa):
        s = np.sign(f) if abs(f) > g["F_friction_N"] else s
        out[i] = s
    return out


def float_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["amp_rad"] * float_state(g, ctx)
    return Contribution(dq=dq)


def float_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(g["joint"], float_state(g, ctx)) for g in p])


# ---------------------------------------------------------------------------------------- fractional ratio
def ratio_draw(ctx, hw, rng):
    out = []
    for j in range(3):
        if hw["drives"][j]["kind"] != "RV":
            continue
        d = int(rng.integers(11, 32))
        R = int(rng.integers(41, 186)) + int(rng.integers(1, d)) / d
        out.append({"joint": j, "R": R, "R_cfg": round(R, 1)})
    return out


def ratio_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = (g["R_cfg"] / g["R"] - 1.0) * ctx.q[:, g["joint"]]
    return Contribution(dq=dq)


def ratio_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(g["joint"], ctx.q[:, g["joint"]]) for g in p])


# ------------------------------------------------------------------------------------------ ring-encoder shift
def ring_draw(ctx, hw, rng):
    heavy = ctx.chain.name != "ur10"
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[:3]):
        d = hw["drives"][j]
        K = (rng.uniform(1.5, 4.0) * d["T_rated"] / ph.ARCMIN if d["kind"] == "RV"
             else rng.uniform(2.0, 5.0) * d["K3"]) / d["soften"]
        R_e = rng.uniform(60, 120) if heavy else rng.uniform(30, 60)
        a_e = (rng.uniform(60, 150) if heavy else rng.uniform(15, 40)) * rng.choice([-1, 1])
        w0 = ctx.chain.axes[j]
        u = np.cross(w0, [1.0, 0, 0] if abs(w0[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        phi = rng.uniform(0, 2 * np.pi)
        out.append({"joint": int(j), "K_tilt": K, "R_e_mm": R_e, "a_e_mm": a_e,
                    "n_home": np.cos(phi) * u + np.sin(phi) * np.cross(w0, u)})
    return out


def ring_signal(g, ctx, R=None, M=None):
    """Moment normal to the axis along the read head's radial direction (P,) [N m]."""
    if M is None:
        _, M, _, _ = joint_wrench(ctx)
    if R is None:
        R, _ = kin.body_transforms(ctx.chain, ctx.q)
    n_h = R[:, g["joint"]] @ g["n_home"]               # the housing is the body before the joint
    return np.einsum("pi,pi->p", M[:, g["joint"]], n_h)


def ring_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        dq[:, g["joint"]] = g["a_e_mm"] / (g["R_e_mm"] * g["K_tilt"]) * ring_signal(g, ctx)
    return Contribution(dq=dq)


def ring_features(p, ctx, hw):
    return np.array([ctx.joint_feature(g["joint"], ring_signal(g, ctx)) for g in p])
