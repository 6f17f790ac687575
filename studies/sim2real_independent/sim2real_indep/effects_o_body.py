"""Set O body effects (new physics, not in sets A-N): the arm on a floating pontoon, heaving and heeling by
hydrostatics; the arm on a pinned mast held by pretensioned guy ropes, whose sag softens the slackening guys; the
C-frame of a clinching or riveting tool opened by its squeeze force; a milling spindle's bracket bent and twisted by
the cutting force. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* pontoon: a floating body heaves by dW / (rho g A_w) and heels by M / (rho g I_w) -- the waterplane's area and second
  moment (the metacentric restoring moment rho g V BM, BM = I_w / V; Rawson & Tupper, *Basic Ship Theory*, 5th ed.,
  2001, ch. 4; Biran, *Ship Hydrostatics and Stability*, 2003, ch. 2-3); the gravity term W (KB - KG) is below 1 % of
  rho g I_w for these wide, shallow hulls and left out. The arm works from a moored work pontoon (hull cleaning, quay
  wall or sluice repair) and the tracker stands on the quay; rectangular pontoons of 6-10 x 3-5 m (ur10: modular
  work floats; first 8-14 x 4-7 m, a trial draw at another seed gained 11 %, the backlash model at 1.12x) and 12-20 x
  6-10 m (kr16_like), freeboard 0.3-0.8 m, the arm within 30 % of the hull's half length and width from its centre,
  still water (assumed). The arm's and the payload's weights move the pontoon about its waterplane's centroid; pick
  and place changes the payload between blocks (the heave). The true structure: three columns (heave per newton,
  heel and trim per newton metre).
* guyed mast: a mast pinned at its foot (a ball seat) and held by three guy ropes from its head to ground anchors
  (temporary and site installations, antenna masts: TIA-222-H / EN 1993-3-1 on guyed masts). An inclined rope of
  weight w per length between two points takes up chord length by its elastic stretch and by its sag: d(chord) = (T -
  T0) l / EA + (w l cos(beta))^2 l / 24 (1 / T0^2 - 1 / T^2) (Irvine, *Cable Structures*, 1981, ch. 2; Ernst's
  equivalent modulus is its derivative), so a guy slackening towards a small tension softens. Hand-tensioned guys
  (turnbuckles) of 300-800 / 1000-2500 N, ropes of 5-8 / 10-14 mm (metallic fill 0.55, E 90-110 GPa on the metal,
  Feyrer, *Wire Ropes*, 2015), masts of 1.0-1.6 m with 30-60 / 80-150 kg of mast and platform, guys at 45-60 deg
  elevation (ur10 / kr16_like; assumed; first 150-400 / 400-1000 N, 4-6 / 6-8 mm, masts of 1.2-2.0 / 1.5-2.5 m: 2.6 mm
  at kr16_like's tool). Each pose's equilibrium (Newton's method): the weights' moment about the foot
  (with their second-order shift as the mast tilts) against the guys' tensions at the head. Pick and place changes the
  payload between blocks. The true structure: the mast's two tilts about its foot (shape parameters, amplitudes one).
* C-frame: clinching, self-piercing riveting and servo spot-welding tools close their punch and die across a C-frame
  whose throat opens under the squeeze force -- the gun-arm deflection that controllers compensate (Zhang & Senkara,
  *Resistance Welding*, 2nd ed., 2011, ch. 10 on gun arm deflection; riveting C-frames deflect 0.5-2 mm at full force,
  as recalled from makers' notes). Castigliano on the frame: the die arm (throat a) a cantilever from the back, the
  back (gap b) bent by F a between its mount and the arm: the die tip moves along the punch axis by F (a^3 / (3 E I_a)
  + a^2 b / (2 E I_b) + b / (2 E A_b)) (Roark's *Formulas for Stress and Strain*, 7th ed., ch. 8). The target on the
  die, the tool floating (equalised), so the robot carries no squeeze force; the force per joint set by the weld
  schedule (2-4 levels over the sheet stacks). Solid steel arms: clinching tongs on kr16_like (throat 80-160 mm, gap
  150-250 mm, arms 20-30 x 40-60 mm, 8-20 kN), a deep-throat riveting C-frame on tool_changer (200-400, 300-500, 40-60 x
  90-140 mm, 25-60 kN; assumed; first arms of 25-40 x 50-80 / 50-80 x 110-180 mm: the die moved 0.1-0.35 mm, its change
  between the schedule's forces under the noise, gain 9 %); the tool is the session's payload.
* spindle bracket: the spindle of :mod:`effects_o_joint`'s cut sits on a flat bar across the flange (width w along the
  tool axis, thickness t), its cutter b below the bar; the cut's force and torque at the cutter bend the bar in its
  soft plane, twist it (St Venant torsion of a thin rectangle, J = w t^3 / 3 (1 - 0.63 t / w); Roark, ch. 10) and bend
  it in its stiff plane (Timoshenko & Gere, *Mechanics of Materials*, cantilever formulas). Aluminium bars of 30-50 x
  6-10 mm on ur10 (first 40-60 x 8-12 mm: a trial draw at another seed gained 24 %, the mount model at 1.30x), steel
  of 60-90 x 12-20 mm on kr16_like, clamped 30 / 50 mm from the flange's axis (assumed); the
  target on the spindle's nose (:func:`effects_o.probe_hook`). The true structure: one column, the displacement at
  E = 1 (amplitude 1 / E). The joints' twist under the same cut is milling_force's.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])
RHO_G = 1000.0 * kin.G * 1e-9          # [N/mm^3], fresh water
STEEL_E, STEEL_RHO = 210e3, 7850e-9    # [N/mm^2], [kg/mm^3]


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def _unit_xy(v):
    d = np.array([v[0], v[1], 0.0])
    n = np.linalg.norm(d)
    return d / n if n > 1e-9 else np.array([1.0, 0.0, 0.0])


def weights(ctx, origin):
    """Total weight W (P,) [N] and the weights' moment (P, 3) [N mm] about ``origin`` (3,) [mm]."""
    m, pos, _ = ctx.mass_state
    F = -kin.G * m[..., None] * Z
    return kin.G * m.sum(axis=1), np.cross(pos - origin, F).sum(axis=1)


# ------------------------------------------------------------------------------------------------------ pontoon
#: per arm: hull length, beam [m] (assumed)
PONTOON = {"ur10": ((6.0, 10.0), (3.0, 5.0)), "kr16_like": ((12.0, 20.0), (6.0, 10.0))}


def pontoon_draw(ctx, hw, rng):
    if ctx.chain.name not in PONTOON:
        return {}
    L, B = (1000 * rng.uniform(*r) for r in PONTOON[ctx.chain.name])
    yaw = rng.uniform(0, 2 * np.pi)
    ex = np.array([np.cos(yaw), np.sin(yaw), 0.0])
    ey = np.cross(Z, ex)
    base = rng.uniform(-0.3, 0.3, 2) * np.array([L / 2, B / 2])
    return {"L_mm": L, "B_mm": B, "ex": ex, "ey": ey, "O": -(base[0] * ex + base[1] * ey) - rng.uniform(300, 800) * Z}


def pontoon_parts(p, ctx):
    """(3, P, 3): the target's displacement per unit heave, heel and trim compliance: the weight's change sinking the
    hull, the moments' changes turning it about the waterplane's centroid."""
    W, M = weights(ctx, p["O"])
    r = ctx.target - p["O"]
    dW, dMx, dMy = W - W.mean(), M @ p["ex"] - (M @ p["ex"]).mean(), M @ p["ey"] - (M @ p["ey"]).mean()
    return np.array([-dW[:, None] * Z, dMx[:, None] * np.cross(p["ex"], r), dMy[:, None] * np.cross(p["ey"], r)])


def pontoon_compliance(p):
    """Heave [mm/N], heel and trim [rad/(N mm)] compliances: 1 / (rho g A_w), 1 / (rho g I_w) about both axes."""
    L, B = p["L_mm"], p["B_mm"]
    return np.array([1 / (RHO_G * L * B), 1 / (RHO_G * L * B ** 3 / 12), 1 / (RHO_G * B * L ** 3 / 12)])


def pontoon_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("m,mpi->pi", pontoon_compliance(p), pontoon_parts(p, ctx)) if p else None)


def pontoon_features(p, ctx, hw):
    return pontoon_parts(p, ctx) if p else _empty(ctx)


# --------------------------------------------------------------------------------------------------- guyed mast
#: per arm: mast height [mm], rope diameter [mm], pretension [N], mast and platform mass [kg] (assumed)
MAST = {"ur10": ((1000.0, 1600.0), (5.0, 8.0), (300.0, 800.0), (30.0, 60.0)),
        "kr16_like": ((1000.0, 1600.0), (10.0, 14.0), (1000.0, 2500.0), (80.0, 150.0))}
HEAD_MM = 50.0      # the guys' shackles below the base frame's origin


def guy_tension(p, dl):
    """Tension (k,) [N] of the guys at chord length changes ``dl`` (k,) [mm]: the elastic catenary's chord law
    inverted (Newton's method; monotonic in T > 0)."""
    T = np.full(len(dl), p["T0"])
    for _ in range(60):
        g = (T - p["T0"]) * p["l0"] / p["EA"] + p["c"] * (1 / p["T0"] ** 2 - 1 / T ** 2) - dl
        T = np.maximum(T - g / (p["l0"] / p["EA"] + 2 * p["c"] / T ** 3), T / 4)
    return T


def mast_residual(p, th, m, pos):
    """Horizontal moment [N mm] about the foot of the weights (shifted by the tilt ``th`` (2,)) and the guys."""
    foot = -p["H_mm"] * Z
    w = np.array([th[0], th[1], 0.0])
    r = pos - foot
    M = np.cross(r + np.cross(w, r), -kin.G * m[:, None] * Z).sum(axis=0)
    h = -HEAD_MM * Z - foot
    head = foot + h + np.cross(w, h)
    v = p["anchors"] - head
    ln = np.linalg.norm(v, axis=1)
    T = guy_tension(p, ln - p["l0"])
    M = M + np.cross(head - foot, (T / ln)[:, None] * v).sum(axis=0)
    return M[:2]


def mast_states(p, ctx):
    """The mast's tilts (P, 2) [rad] about the base frame's x and y axes through its foot (Newton's method)."""
    m, pos, _ = ctx.mass_state
    m = np.c_[m, np.full(len(m), p["m_mast_kg"])]
    pos = np.concatenate([pos, np.broadcast_to(-0.5 * p["H_mm"] * Z, (len(m), 1, 3))], axis=1)
    out, th = np.zeros((len(m), 2)), np.zeros(2)
    for i in range(len(m)):
        for _ in range(20):
            r = mast_residual(p, th, m[i], pos[i])
            J = np.array([(mast_residual(p, th + 1e-7 * e, m[i], pos[i]) - r) / 1e-7 for e in np.eye(2)]).T
            step = np.linalg.solve(J, -r)
            th = th + step
            if np.abs(step).max() < 1e-12:
                break
        out[i] = th
    return out


def mast_draw(ctx, hw, rng):
    if ctx.chain.name not in MAST:
        return {}
    H, d, T0, mm = MAST[ctx.chain.name]
    H, d, beta, phi0 = rng.uniform(*H), rng.uniform(*d), np.deg2rad(rng.uniform(45, 60)), rng.uniform(0, 2 * np.pi)
    R = (H - HEAD_MM) / np.tan(beta)
    az = phi0 + 2 * np.pi * np.arange(3) / 3
    A_m = 0.55 * np.pi / 4 * d * d                                       # metallic area [mm^2]
    l0 = (H - HEAD_MM) / np.sin(beta)
    w = STEEL_RHO * A_m * kin.G                                          # [N/mm]
    return {"H_mm": H, "anchors": np.c_[R * np.cos(az), R * np.sin(az), np.full(3, -H)], "l0": l0,
            "EA": A_m * rng.uniform(90e3, 110e3), "c": (w * l0 * np.cos(beta)) ** 2 * l0 / 24,
            "T0": rng.uniform(*T0), "m_mast_kg": rng.uniform(*mm)}


def mast_parts(p, ctx):
    """(2, P, 3): the target's displacement under the mast's tilts about its foot (amplitudes one)."""
    th = mast_states(p, ctx)
    r = ctx.target + p["H_mm"] * Z
    return np.array([th[:, :1] * np.cross(np.eye(3)[0], r), th[:, 1:] * np.cross(np.eye(3)[1], r)])


def mast_apply(p, ctx, hw):
    return Contribution(displace=mast_parts(p, ctx).sum(axis=0) if p else None)


def mast_features(p, ctx, hw):
    return mast_parts(p, ctx) if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------------ C-frame
#: per arm: throat a [mm] (the target's mapping), die height [mm], gap b [mm], arm width, depth [mm], force [N]
CFRAME = {"kr16_like": ((80.0, 160.0), 220.0, (150.0, 250.0), (20.0, 30.0), (40.0, 60.0), (8e3, 20e3)),
          "tool_changer": ((200.0, 400.0), 450.0, (300.0, 500.0), (40.0, 60.0), (90.0, 140.0), (25e3, 60e3))}


def cframe_draw(ctx, hw, rng):
    if ctx.chain.name not in CFRAME:
        return {}
    _, _, b, w, h, F = CFRAME[ctx.chain.name]
    a = float(np.linalg.norm(np.asarray(ctx.probe_mm, float)[:2]))
    b, w, h = rng.uniform(*b), rng.uniform(*w), rng.uniform(*h)
    I, A = w * h ** 3 / 12, w * h
    levels = np.sort(rng.uniform(*F, int(rng.integers(2, 5))))
    return {"a_mm": a, "b_mm": b, "c_mm_N": a ** 3 / (3 * STEEL_E * I) + a * a * b / (2 * STEEL_E * I)
            + b / (2 * STEEL_E * A), "F_N": rng.choice(levels, len(ctx.q)), "levels": levels}


def cframe_part(p, ctx):
    """(P, 3): the die's displacement per unit compliance: the squeeze force along the punch axis (the tool axis)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return p["F_N"][:, None] * Rt[:, :, 2]


def cframe_apply(p, ctx, hw):
    return Contribution(displace=p["c_mm_N"] * cframe_part(p, ctx) if p else None)


def cframe_features(p, ctx, hw):
    return cframe_part(p, ctx)[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------ spindle bracket
#: per arm: bar length (the target's mapping), target height below the flange [mm], bar width, thickness [mm], E
#: [N/mm^2], Poisson's ratio, clamp radius [mm] (assumed)
SPINDLE = {"ur10": ((70.0, 130.0), 130.0, (30.0, 50.0), (6.0, 10.0), 70e3, 0.33, 30.0),
           "kr16_like": ((110.0, 200.0), 210.0, (60.0, 90.0), (12.0, 20.0), 210e3, 0.30, 50.0)}
SPINDLE_HOUSING_MM, SPINDLE_NOSE_MM = 35.0, 40.0   # the target on the housing's radius, above the cutter's tip


def spindle_axis(probe_mm):
    """Bar direction (3,), bar length a [mm] and the target's height [mm] from a target on the spindle's nose."""
    probe_mm = np.asarray(probe_mm, float)
    return _unit_xy(probe_mm), float(np.linalg.norm(probe_mm[:2])) - SPINDLE_HOUSING_MM, float(probe_mm[2])


def bracket_draw(ctx, hw, rng):
    if ctx.chain.name not in SPINDLE:
        return {}
    from sim2real_indep.effects_o_joint import cut_draw
    c = cut_draw(ctx, hw, rng)
    _, _, w, t, E, nu, clamp = SPINDLE[ctx.chain.name]
    return {"cut": c, "w_mm": rng.uniform(*w), "t_mm": rng.uniform(*t), "E": E, "nu": nu, "clamp_mm": clamp}


def bar_end_motion(L, w, t, nu, d, F, M):
    """Translation (P, 3) [mm] and rotation (P, 3) [rad] at E = 1 of the end of a flat bar (length L along ``d``, width
    w along the tool axis, thickness t) clamped at its root, under forces F (P, 3) [N] and moments M (P, 3) [N mm] at
    its end: bending in its soft (across d and z) and stiff (along z) planes, St Venant torsion, stretch."""
    n = np.cross(Z, d)
    Is, It = w * t ** 3 / 12, t * w ** 3 / 12
    J, A, G = w * t ** 3 / 3 * (1 - 0.63 * t / w), w * t, 1 / (2 * (1 + nu))
    Fd, Fn, Fz, Md, Mn, Mz = F @ d, F @ n, F @ Z, M @ d, M @ n, M @ Z
    delta = (np.outer(Fn * L ** 3 / (3 * Is) + Mz * L ** 2 / (2 * Is), n)
             + np.outer(Fz * L ** 3 / (3 * It) - Mn * L ** 2 / (2 * It), Z) + np.outer(Fd * L / A, d))
    rot = (np.outer(Fn * L ** 2 / (2 * Is) + Mz * L / Is, Z) + np.outer(-Fz * L ** 2 / (2 * It) + Mn * L / It, n)
           + np.outer(Md * L / (G * J), d))
    return delta, rot


def bracket_part(p, ctx):
    """(P, 3): the target's displacement [mm] at E = 1: the bar's end under the cut's force and torque moved to it,
    then its rotation carried to the target."""
    from sim2real_indep.effects_o_joint import cut_loads_tool, spindle_tip
    d, a, _ = spindle_axis(ctx.probe_mm)
    end = a * d + p["w_mm"] / 2 * Z
    Ft, Mt = cut_loads_tool(p["cut"])
    M = np.cross(spindle_tip(ctx.probe_mm) - end, Ft) + 1e3 * Mt         # [N mm] about the bar's end
    delta, rot = bar_end_motion(a - p["clamp_mm"], p["w_mm"], p["t_mm"], p["nu"], d, Ft, M)
    local = delta + np.cross(rot, np.asarray(ctx.probe_mm, float) - end)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return np.einsum("pij,pj->pi", Rt, local)


def bracket_apply(p, ctx, hw):
    return Contribution(displace=bracket_part(p, ctx) / p["E"] if p else None)


def bracket_features(p, ctx, hw):
    return bracket_part(p, ctx)[None] if p else _empty(ctx)
