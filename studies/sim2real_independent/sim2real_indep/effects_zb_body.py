"""Set ZB body effects (new physics, not in sets A-ZA): a mobile manipulator standing on four mecanum wheels whose
rollers touch the floor at other points after each re-docking; a base plate with a void in its grout bed under one
edge; a welding torch on an insulating flange that bends and twists under the torch's weight; and a tool boom held
by a stay cable whose sag straightens as its tension rises. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* mecanum base: a mobile manipulator (the arm on an AMR) docks at the station against locating cones that fix its
  horizontal position and heading, and stands on its four mecanum wheels. A mecanum wheel carries its load on the one or
  two free rollers touching the floor; the contact's radial stiffness changes with where along the barrel-shaped roller
  (and between rollers) the wheel stopped (Gfrerrer, "Geometry and kinematics of the Mecanum wheel", Comput. Aided Geom.
  Des. 25, 2008; the rollers' polyurethane tread thin at their ends), so each wheel's stiffness is k0 (1 + a cos(2 pi
  phi_i)) with the roller phase phi_i new at each docking (per block; unlogged), a 0.4-0.7. The four springs at (+-a_x,
  +-a_y) carry the weight W and the arm's gravity moment M: K u = (-W, M_x, M_y), K = B^T diag(k) B, B's rows (1, y_i,
  -x_i) (statics of a rigid plate on springs; Roark, plates on elastic supports), the base turning about the wheels'
  contact plane h below it. Sized so that the target's largest move about its mean is 0.2-0.6 mm (first a tilt of
  0.1-0.3 mrad by a rough moment rule: 1.0 mm at the tool on ZB12). Unlike set H's AGV wheels or set M's cart docking
  (one stiffness, or a new rigid pose per docking), the support's compliance matrix changes at each docking. Driven by
  the pose and the payload (logged) and the rollers' phases (not logged). The true structure: one column (the base's
  turn and sink per unit 1 / k0), amplitude 1 / k0 [mm/N].
* grout void: a base plate on a grout bed with a void under one edge (incomplete grouting: ACI 351.1R, *Grouting between
  foundations and bases for support of equipment and machinery*; voids under edges are the typical defect): a moment
  pressing that edge down turns the plate about its opposite edge, held only by the plate's bending and the anchors, c_v
  max(M . a, 0) about the axis a along the void's edge, the plate w (400-800 mm) wide; a moment lifting the edge meets
  the full bed (a small, linear c_0 M about the base). c_0 giving 0.02-0.05 mrad, the void 0.15-0.4 mrad at the
  session's largest. Unlike set E's soft foot (a rocking step between two tripods) or set F's plate yield, the
  compliance is one-sided and turns about the plate's edge. Driven by the pose and the payload (logged). The true
  structure: two columns (the bed's linear tilt, the void's one-sided tilt about the far edge), amplitudes c_0 and c_v.
* insulating flange: a welding torch is mounted through an insulating flange (a glass-fibre laminate disc, G10 / FR4, E
  about 20 GPa, with insulated bolt sleeves) that isolates the arm from the welding current; the disc and its sleeved
  bolts are far softer than the steel flange, so the torch tilts by c_b M_perp and twists by c_t M_axial under its
  weight's moment about the flange (the torch is the logged payload, its centre of mass in the torch body) (bolted
  joints with compliant interlayers: VDI 2230, as recalled; G10's modulus: NEMA LI 1). c_b sized so that the torch tip
  (40 mm across, 320 mm out) moves 0.15-0.4 mm at the largest moment, c_t / c_b 0.5-1.5. Unlike set J's tool plate (a
  plate bending) or set L's preloaded float holder (a breakaway), the torch turns on an insulating layer in bending and
  torsion. Driven by the pose and the payload (logged). The true structure: two columns (tilt and twist per unit
  compliance), amplitudes c_b and c_t [1/(N mm)].
* stay cable: a long lightweight tool boom (500 mm along the tool's x, the target at its tip) is hinged at its root and
  held by a stay cable from a short mast; the cable's sag makes it softer at low tension, its equivalent modulus 1 /
  E_eq = 1 / E + (gamma l)^2 / (12 sigma^3) (Ernst, "Der E-Modul von Seilen unter Beruecksichtigung des Durchhanges",
  Der Bauingenieur 40, 1965; Gimsing & Georgakis, *Cable Supported Bridges*, 3rd ed., 2012), so the stay lengthens by l
  / (E A) (T - T0) + l (gamma l)^2 A^2 / 24 (1 / T0^2 - 1 / T^2) as the tension goes from its pretension T0 to T = T0 +
  F / sin(alpha), F the tip load across the boom (the part, logged as the payload, and half the boom's weight); the tip
  drops by the stretch over sin(alpha). T0 0.3-0.6 of the largest load's share (assumed), each term sized to its share
  (the sag's 40-70 %) of a largest drop of 0.2-0.5 mm (first 0.15-0.4: ZB14 gained 10 % on a trial seed). Unlike the
  end-of-arm beams of sets I-ZA (a linear or preloaded stiffness), the stay stiffens as its sag is pulled out. Driven by
  the pose and the payload (logged). The true structure: two columns (the elastic and the sag stretch per unit),
  amplitudes their compliances.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import GRAVITY_N, mount_moment
from sim2real_indep.effects_u_joint import block_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _weight_N(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * np.linalg.norm(GRAVITY_N)


# ------------------------------------------------------------------------------------------------- mecanum base
WHEELS_MM = {"ur10": (300.0, 250.0), "kr16_like": (500.0, 400.0), "tool_changer": (800.0, 600.0)}


def mecanum_unit(p, ctx):
    """(P, 3) the target's displacement per unit 1 / k0 [N]: the base's sink and turn on the four wheels."""
    ax, ay = p["half_mm"]
    xy = np.array([[ax, ay], [ax, -ay], [-ax, ay], [-ax, -ay]])
    B = np.c_[np.ones(4), xy[:, 1], -xy[:, 0]]
    b = np.minimum(block_index(ctx.session), len(p["phase"]) - 1)
    f = 1.0 + p["a"] * np.cos(2 * np.pi * np.asarray(p["phase"]))          # (blocks, 4) relative stiffness
    M = mount_moment(ctx) * 1000.0                                          # [N mm]
    load = np.c_[-_weight_N(ctx), M[:, 0], M[:, 1]]
    out = np.zeros((len(ctx.q), 3))
    root = np.array([0.0, 0.0, -p["h_mm"]])
    for k in range(len(f)):
        on = b == k
        if not on.any():
            continue
        u = np.linalg.solve(B.T @ (f[k][:, None] * B), load[on].T).T       # (z0 [mm], theta_x, theta_y) per 1/k0
        rot = np.c_[u[:, 1], u[:, 2], np.zeros(on.sum())]
        out[on] = u[:, :1] * np.array([0.0, 0.0, 1.0]) + np.cross(rot, ctx.target[on] - root)
    return out


def mecanum_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"half_mm": WHEELS_MM[ctx.chain.name], "a": rng.uniform(0.4, 0.7), "phase": rng.uniform(0, 1, (nb, 4)),
         "h_mm": rng.uniform(200.0, 400.0)}
    unit = mecanum_unit(p, ctx)
    p["inv_k0"] = rng.uniform(0.2, 0.6) / max(np.linalg.norm(unit - unit.mean(axis=0), axis=1).max(), 1e-12)
    return p


def mecanum_features(p, ctx, hw):
    return mecanum_unit(p, ctx)[None]


def mecanum_apply(p, ctx, hw):
    return _amp_apply([p["inv_k0"]], mecanum_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- grout void
def void_parts(p, ctx):
    """(2, P, 3) the target's displacement per unit bed compliance (linear, about the base) and per unit void
    compliance (one-sided, about the plate's far edge) [per N m]."""
    M = mount_moment(ctx)
    n = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])             # towards the void's edge
    a = np.cross(n, [0.0, 0.0, 1.0])                                    # a positive turn about a lowers that edge
    lin = M.copy()
    lin[:, 2] = 0.0
    lin = np.cross(lin, ctx.target)
    press = np.clip(M @ a, 0.0, None)
    edge = -0.5 * p["w_mm"] * n                                         # the far edge the plate turns about
    one = np.cross(press[:, None] * a, ctx.target - edge)
    return np.array([lin, one])


def void_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi), "w_mm": rng.uniform(400.0, 800.0)}
    M = mount_moment(ctx)
    a = np.cross([np.cos(p["psi"]), np.sin(p["psi"]), 0.0], [0.0, 0.0, 1.0])
    p["c0"] = rng.uniform(0.02e-3, 0.05e-3) / max(np.linalg.norm(M[:, :2], axis=1).max(), 1e-9)
    p["cv"] = rng.uniform(0.15e-3, 0.4e-3) / max(np.clip(M @ a, 0.0, None).max(), 1e-9)
    return p


def void_features(p, ctx, hw):
    return void_parts(p, ctx)


def void_apply(p, ctx, hw):
    return _amp_apply([p["c0"], p["cv"]], void_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------- insulating flange
TORCH_MM = np.array([0.0, 40.0, 320.0])        # the torch tip (the target) in the tool frame
TORCH_COM_MM = np.array([0.0, 15.0, 140.0])    # the torch's centre of mass (the payload) in the tool frame


def flange_parts(p, ctx):
    """(2, P, 3) the target's displacement per unit bending and torsional compliance [per 1/(N mm)] (base frame)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N) * ctx.session.payload_kg[:, None]      # the torch's weight, tool frame
    M = np.cross(ctx.payload_com_mm, g)                                                # [N mm], tool frame
    bend, twist = M.copy(), np.zeros_like(M)
    bend[:, 2] = 0.0
    twist[:, 2] = M[:, 2]
    arm = ctx.probe_mm
    return np.array([np.einsum("pij,pj->pi", Rt, np.cross(bend, arm)),
                     np.einsum("pij,pj->pi", Rt, np.cross(twist, arm))])


def flange_draw(ctx, hw, rng):
    parts = flange_parts({}, ctx)
    p = {"ratio": rng.uniform(0.5, 1.5)}
    p["cb"] = rng.uniform(0.15, 0.4) / max(np.linalg.norm(parts[0], axis=1).max(), 1e-12)
    p["ct"] = p["ratio"] * p["cb"]
    return p


def flange_features(p, ctx, hw):
    return flange_parts(p, ctx)


def flange_apply(p, ctx, hw):
    return _amp_apply([p["cb"], p["ct"]], flange_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- stay cable
BOOM_MM = 500.0
BOOM_KG = 1.5


def stay_load(ctx):
    """(P,) the tip load across the boom [N], positive along the tool's -z (what the stay carries)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N) * (ctx.session.payload_kg + 0.5 * BOOM_KG)[:, None]
    return -g[:, 2]


def stay_parts(p, ctx):
    """(2, P, 3) the tip's displacement per unit elastic and sag compliance (base frame)."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    T = np.clip(p["T0"] + stay_load(ctx) / p["sin_a"], 0.1 * p["T0"], None)
    drop = -Rt[:, :, 2] / p["sin_a"]                                   # the tip drops along the tool's -z
    return np.array([drop * (T - p["T0"])[:, None], drop * (1 / p["T0"] ** 2 - 1 / T ** 2)[:, None]])


def stay_draw(ctx, hw, rng):
    p = {"sin_a": np.sin(np.deg2rad(rng.uniform(20.0, 35.0)))}
    F = np.abs(stay_load(ctx)).max() / p["sin_a"]
    p["T0"] = rng.uniform(0.3, 0.6) * F
    parts = stay_parts(p, ctx)
    total, share = rng.uniform(0.2, 0.5), rng.uniform(0.4, 0.7)
    p["c_el"] = total * (1 - share) / max(np.linalg.norm(parts[0], axis=1).max(), 1e-12)
    p["c_sag"] = total * share / max(np.linalg.norm(parts[1], axis=1).max(), 1e-12)
    return p


def stay_features(p, ctx, hw):
    return stay_parts(p, ctx)


def stay_apply(p, ctx, hw):
    return _amp_apply([p["c_el"], p["c_sag"]], stay_features(p, ctx, hw))
