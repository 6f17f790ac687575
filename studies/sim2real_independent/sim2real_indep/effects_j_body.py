"""Set J body effects (new physics, not in sets A-I): a base plate on a young grout bed that creeps by the double
power law; an arm on a console cantilevered from a wall; cast links whose principal axes lie skewed to the arm's
plane; a flat tool-mounting plate, offset from the flange, twisting and bending under the gripper it carries. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* grout creep: basic creep of concrete and cementitious grout by the double power law, J(t, t') = (1 / E0) [1 +
  phi1 (t'^-m + a) (t - t')^n], t, t' in days, m = 1/3, a = 0.05, n 0.10-0.16, phi1 3-5 (Bazant & Osman, "Double
  power law for basic creep of concrete", Materiaux et Constructions 9(49), 1976; ACI 209.2R-08, creep models), with
  Boltzmann's superposition over the moment history (the moment held through pauses, the session's mean during
  production and for 2-12 h before the session; as set D's pads). A base grouted and anchored 3-60 days before
  (machinery grouting: ACI 351.1R-12), its elastic tilt stiffness in the plate range of :mod:`hardware`, of which the
  share carried by the anchors' bond and the bed in the young concrete and grout, 40-80 %, creeps (the plate's own
  bending does not; assumed); the tilt about a pivot 30-80 mm below the base (plate and bed; assumed).
* wall console: the arm on the tip of a welded steel console (a rectangular hollow section) cantilevered from a wall
  or a machine's column and bolted to it by an end plate (machine-tending cells): the tip bends, shears and twists
  under the arm's weight and moment (cantilever laws of :func:`physics.cantilever_tip`; Bredt's J = 4 A_m^2 t / s for
  the closed section: Timoshenko & Gere, *Mechanics of Materials*; Roark's *Formulas for Stress and Strain*), and the
  end plate turns the whole console by its root moment over a semi-rigid rotational stiffness S_j of 0.5-2 EI / L
  (EN 1993-1-8 5.2.2, the classification of beam-to-column joints; assumed). Weight and moment both tilt the arm, so
  a payload change turns it even where its moment does not change. Console length and section by arm
  (:data:`CONSOLE`; assumed), the arm's base on its top, at its tip, 20 mm above the section's top face.
* skewed castings: a cast link whose ribs make its section's principal axes unequal (I_max / I_min 1.5-3, their mean
  the tube's I of :mod:`hardware`) and turned 15-40 deg from the arm's plane bends out of the plane of the loads
  (unsymmetric bending: Timoshenko & Gere, *Mechanics of Materials*, bending of unsymmetric beams; Roark's *Formulas
  for Stress and Strain*, ch. 8); cantilever laws as :func:`physics.cantilever_tip` about each principal axis,
  shear and Saint-Venant torsion as the tube's. The tube links of 400 mm or more past joint 1.
* tool plate: a flat bar (width b, thickness t) bolted to the flange, reaching 100-200 mm out across the tool axis,
  with a gripper hanging 150-300 mm down the tool axis from its end (the target at the gripper's tip, see
  :func:`effects_j.probe_hook`; the payload between its jaws, :func:`effects_j.payload_hook`). The gripper's weight
  and the payload's twist the plate about its length -- Saint-Venant torsion of a rectangle, GJ = G beta b t^3, beta
  = (1 / 3)(1 - 0.63 t / b + 0.052 (t / b)^5) (Roark, Table 10.1; Timoshenko & Goodier, *Theory of Elasticity*, ch.
  10) -- and bend it about its weak (E b t^3 / 12) and strong (E t b^3 / 12) axes, a cantilever from the flange's
  bolt circle (:func:`physics.cantilever_tip`). Aluminium plates of 60-90 x 10-15 / 80-120 x 12-20 mm with
  1.5-3.5 / 4-10 kg grippers on ur10 / kr16_like, steel 150-250 x 30-50 mm with 20-40 kg on tool_changer (assumed).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_body as cb
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_d_body import _moment_history

Z = np.array([0.0, 0.0, 1.0])
EX, EY = np.eye(3)[0], np.eye(3)[1]
DAY_S = 86400.0


def _logu(rng, lo, hi):
    return float(np.exp(rng.uniform(np.log(lo), np.log(hi))))


def _dot(x, y):
    return np.sum(x * y, axis=-1, keepdims=True)


# ------------------------------------------------------------------------------------------------ grout creep
def grout_draw(ctx, hw, rng):
    age = rng.uniform(3, 60)
    return {"C0": 1 / _logu(rng, *hwm.ROBOTS[ctx.chain.name]["plate"]),
            "phi": rng.uniform(0.4, 0.8) * rng.uniform(3, 5) * (age ** (-1 / 3) + 0.05), "n": rng.uniform(0.10, 0.16),
            "pre_s": rng.uniform(2, 12) * 3600, "pivot_mm": rng.uniform(30, 80)}


def dpl_creep(starts_s, steps, t_s, n):
    """Boltzmann's sum (len(t_s), ...) of ``steps`` applied at ``starts_s`` [s] through the kernel ((t - t_i) /
    1 day)^n (zero before the step)."""
    dt = (np.asarray(t_s, float)[:, None] - np.asarray(starts_s, float)[None, :]) / DAY_S
    return np.where(dt > 0, np.maximum(dt, 0) ** n, 0.0) @ steps


def grout_creep(p, ctx):
    """Creep moment (P, 2) [N m] at the measurements (the end of each pose's dwell): the moment steps of the
    history (gaps, moves and dwells), the session's mean moment applied ``pre_s`` before the session."""
    hist, dur = _moment_history(ctx)
    vals = np.vstack([hist[:, 1].mean(axis=0), hist.reshape(-1, 2)])
    ends = np.cumsum(dur.ravel())
    steps = np.diff(np.vstack([np.zeros((1, 2)), vals]), axis=0)
    return dpl_creep(np.r_[-p["pre_s"], ends - dur.ravel()], steps, ends[1::2], p["n"])


def grout_parts(p, ctx):
    """Target displacement (4, P, 3) [mm] per unit compliance: instant tilt about x and y, creep tilt about x, y."""
    M, Mc = eb.mount_moment(ctx)[:, :2], grout_creep(p, ctx)
    r = ctx.target - np.array([0.0, 0.0, -p["pivot_mm"]])
    return np.array([np.cross(EX * M[:, :1], r), np.cross(EY * M[:, 1:], r),
                     np.cross(EX * Mc[:, :1], r), np.cross(EY * Mc[:, 1:], r)])


def grout_apply(p, ctx, hw):
    amp = p["C0"] * np.array([1.0, 1.0, p["phi"], p["phi"]])
    return Contribution(displace=np.einsum("k,kpi->pi", amp, grout_parts(p, ctx)))


def grout_features(p, ctx, hw):
    return grout_parts(p, ctx)


# ------------------------------------------------------------------------------------------------ wall console
#: per arm: console length [m], RHS depth H, width B, wall t [m] (assumed)
CONSOLE = {"ur10": ((0.3, 0.6), (0.08, 0.12), (0.05, 0.08), (0.003, 0.005)),
           "kr16_like": ((0.4, 0.8), (0.15, 0.25), (0.10, 0.15), (0.006, 0.010)),
           "tool_changer": ((0.5, 1.0), (0.30, 0.45), (0.20, 0.30), (0.010, 0.016))}


def console_draw(ctx, hw, rng):
    (L0, L1), (H0, H1), (B0, B1), (t0, t1) = CONSOLE[ctx.chain.name]
    H, B, t = rng.uniform(H0, H1), rng.uniform(B0, B1), rng.uniform(t0, t1)
    L, yaw = rng.uniform(L0, L1), rng.uniform(0, 2 * np.pi)
    I = (B * H ** 3 - (B - 2 * t) * (H - 2 * t) ** 3) / 12
    return {"L_m": L, "c": np.array([np.cos(yaw), np.sin(yaw), 0.0]), "depth_mm": 1000 * (H / 2 + 0.02), "I": I,
            "As": 2 * H * t, "J": 4 * ((B - t) * (H - t)) ** 2 * t / (2 * ((B - t) + (H - t))),
            "S_j": rng.uniform(0.5, 2.0) * hwm.STEEL["E"] * I / L, "E": hwm.STEEL["E"],
            "G": hwm.STEEL["E"] / (2 * (1 + hwm.STEEL["nu"]))}


def console_response(p, ctx, EI, kGA, GJ, S_j):
    """Target displacement (P, 3) [mm] of an arm on the tip of a cantilevered console (bending EI, shear kGA,
    torsion GJ) bolted to the wall by an end plate of rotational stiffness S_j (np.inf: that part rigid)."""
    W, M = ctx.mass_state[0].sum(axis=1) * kin.G, eb.mount_moment(ctx)
    F = -W[:, None] * Z
    d, r = ph.cantilever_tip(p["c"], p["L_m"], F, M, np.zeros(3), EI, kGA, GJ)
    n = np.cross(Z, p["c"])
    M_root = M + np.cross(p["L_m"] * p["c"], F)
    tip = np.array([0.0, 0.0, -p["depth_mm"]])
    root = tip - 1000.0 * p["L_m"] * p["c"]
    plate = (M_root @ n / S_j)[:, None] * n
    return 1000.0 * d + np.cross(r, ctx.target - tip) + np.cross(plate, ctx.target - root)


def console_parts(p, ctx):
    """Per unit 1/E (bending), 1/G (shear and Bredt torsion) and 1/S_j (end plate), (3, P, 3)."""
    inf = np.inf
    return np.array([console_response(p, ctx, p["I"], inf, inf, inf),
                     console_response(p, ctx, inf, p["As"], p["J"], inf),
                     console_response(p, ctx, inf, inf, inf, 1.0)])


def console_apply(p, ctx, hw):
    amp = [1 / p["E"], 1 / p["G"], 1 / p["S_j"]]
    return Contribution(displace=np.einsum("k,kpi->pi", amp, console_parts(p, ctx)))


def console_features(p, ctx, hw):
    return console_parts(p, ctx)


# -------------------------------------------------------------------------------------------- skewed castings
def skew_draw(ctx, hw, rng):
    ch, out = ctx.chain, {}
    for name, tb in hw["tubes"].items():
        li = ch.link_names.index(name)
        if ch.link_body[li] < 1 or np.linalg.norm(ch.links[li]) < 400.0:
            continue
        ratio = rng.uniform(1.5, 3.0)
        out[name] = {"I1": 2 * tb["I"] / (1 + ratio), "I2": 2 * ratio * tb["I"] / (1 + ratio),
                     "psi": rng.choice([-1, 1]) * np.deg2rad(rng.uniform(15, 40)), "A": tb["A"], "J": tb["J"],
                     "k": tb["k"], "E": tb["E"], "G": tb["G"], "rho": tb["rho"]}
    return out


def skew_displacement(ctx, li, s, E, G):
    """Target displacement (P, 3) [mm] of link ``li`` bending about principal axes turned by ``psi`` from the
    arm's plane (E, G: np.inf makes that part rigid)."""
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    if ctx.chain.link_names[li] not in ctx.mass_link:
        w = s["rho"] * s["A"] * eb.GRAVITY_N
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    u0 = R[:, ctx.chain.link_body[li]] @ cb._section_axis(ctx, li)
    u1 = np.cos(s["psi"]) * u0 + np.sin(s["psi"]) * np.cross(e, u0)
    d, r = principal_tip(e, u1, L, F, M, w, E * s["I1"], E * s["I2"], G * s["k"] * s["A"], G * s["J"])
    return 1000.0 * d + np.cross(r, ctx.target - tip)


def principal_tip(e, u1, L, F, M, w, EI1, EI2, kGA, GJ):
    """Tip displacement [m] and rotation [rad] of a cantilever along ``e`` bending with EI1 along the principal
    direction ``u1`` and EI2 along u2 = e x u1 (:func:`physics.cantilever_tip` in each principal plane)."""
    u2 = np.cross(e, u1)
    dA, rA = ph.cantilever_tip(e, L, F, M, w, EI1, kGA, GJ)
    dB, rB = ph.cantilever_tip(e, L, F, M, w, EI2, kGA, GJ)
    return _dot(dA, u1) * u1 + _dot(dB, u2) * u2, _dot(rA, u2) * u2 + _dot(rB, u1) * u1 + _dot(rA, e) * e


def skew_apply(p, ctx, hw):
    return Contribution(displace=eb.links_sum(skew_displacement, p, ctx))


def skew_features(p, ctx, hw):
    return eb.links_columns(skew_displacement, p, ctx)


# ------------------------------------------------------------------------------------------------- tool plate
#: per arm: material, plate width b, thickness t [m], gripper mass [kg], bolt-circle radius [m] (assumed)
PLATE = {"ur10": (hwm.ALUMINIUM, (0.06, 0.09), (0.010, 0.015), (1.5, 3.5), (0.025, 0.035)),
         "kr16_like": (hwm.ALUMINIUM, (0.08, 0.12), (0.012, 0.020), (4.0, 10.0), (0.03, 0.045)),
         "tool_changer": (hwm.STEEL, (0.15, 0.25), (0.03, 0.05), (20.0, 40.0), (0.06, 0.09))}


def torsion_beta(b, t):
    """Saint-Venant torsion factor of a b x t rectangle (b >= t): J = beta b t^3 (Roark, Table 10.1)."""
    r = t / b
    return (1 - 0.63 * r + 0.052 * r ** 5) / 3


def plate_geometry(probe_mm):
    """Plate direction d (3,) in the flange plane, reach [mm] and the gripper's drop [mm] along the tool axis of a
    target offset put at reach d + drop z by :func:`effects_j.probe_hook`."""
    reach = np.hypot(probe_mm[0], probe_mm[1])
    return np.array([probe_mm[0], probe_mm[1], 0.0]) / reach, reach, probe_mm[2]


def plate_draw(ctx, hw, rng):
    mat, b, t, m, r = PLATE[ctx.chain.name]
    d, reach, drop = plate_geometry(ctx.probe_mm)
    b, t = rng.uniform(*b), rng.uniform(*t)
    return {"d": d, "reach_mm": reach, "drop_mm": drop, "root_mm": 1000 * rng.uniform(*r), "b": b, "t": t,
            "m_grip": rng.uniform(*m), "rho": mat["rho"], "E": mat["E"], "G": mat["E"] / (2 * (1 + mat["nu"]))}


def plate_displacement(p, ctx, E, G):
    """Target displacement (P, 3) [mm], base frame, of the plate with moduli E, G (np.inf: that part rigid)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, -kin.G * Z)                         # gravity in the tool frame [m/s^2]
    tip = p["reach_mm"] * p["d"] / 1000.0
    grip = tip + 0.4 * p["drop_mm"] / 1000.0 * Z
    pay, m_pay = ctx.payload_com_mm / 1000.0, ctx.session.payload_kg[:, None]
    F = (p["m_grip"] + m_pay) * g
    M = np.cross(grip - tip, p["m_grip"] * g) + np.cross(pay - tip, m_pay * g)
    w = p["rho"] * p["b"] * p["t"] * g
    b, t = p["b"], p["t"]
    d, r = principal_tip(p["d"], Z, (p["reach_mm"] - p["root_mm"]) / 1000.0, F, M, w, E * b * t ** 3 / 12,
                         E * t * b ** 3 / 12, np.inf, G * torsion_beta(b, t) * b * t ** 3)
    local = 1000.0 * d + np.cross(r, ctx.probe_mm - 1000.0 * tip)
    return np.einsum("pij,pj->pi", Rt, local)


def plate_parts(p, ctx):
    """Per unit 1/E (bending) and per unit 1/G (torsion), (2, P, 3)."""
    return np.array([plate_displacement(p, ctx, 1.0, np.inf), plate_displacement(p, ctx, np.inf, 1.0)])


def plate_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["E"], 1 / p["G"]], plate_parts(p, ctx)))


def plate_features(p, ctx, hw):
    return plate_parts(p, ctx)
