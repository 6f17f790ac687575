"""Set ZO body effects (new physics, not in sets A-ZN): the arm on a mobile cart's fibreboard deck that cups as its
unsealed underside takes up moisture after the cell's washdown; the arm's stand on closed-cell foam pads whose trapped
cell gas stiffens them as they are squeezed; a tool hung on a cross-spring flexure pivot whose stiffness the load
along its leaves raises or lowers; and a sensor on a quasi-zero-stiffness isolator on the tool. Same protocol as
:mod:`effects_joint`.

Sources:

* deck cupping (``deck_cupping``): a cobot on a mobile cart whose deck is a fibreboard (MDF) or particle-board panel,
  laminate-sealed on top and bare underneath; the cell hosed down 3-10 min before the session (at the shift's end)
  leaves the air under the cart humid, and the underside takes up water by Fickian diffusion (a sheet of thickness h
  wetted on one face and sealed on the other: Crank, *The Mathematics of Diffusion*, 2nd ed., 1975, eq. 4.17; tau_d =
  4 h^2 / (pi^2 D) 20-100 h for 16-25 mm panels), so its hygroexpansion beta c(z) is largest underneath and the panel
  cups, edges up, with the curvature (12 / h^3) int beta c(z) z dz of a free plate with an eigenstrain (Timoshenko &
  Goodier, *Theory of Elasticity*, ch. 13, the analogue of thermal bending; *Wood Handbook*, FPL-GTR-190, 2010, ch. 13
  on cupping of panels). The cart stands on its four corner castors; the arm's base, 0.15-0.35 m from the deck's
  centre (any heading), turns with the deck's slope there and rises with it. Blocks with pauses of 20-60 min; sized to
  0.25-0.6 mm. Unlike set ZG's settlement tilt (a foundation's consolidation), set V's moisture swell (a link's
  length) or set ZN's moisture-softened gears, the support's shape changes with the water the panel takes up, whatever
  the arm does. Driven by the time since the washdown (the humidity is not logged). The true structure: one column,
  amplitude beta C_s / h.
* closed-cell foam pads (``closed_cell_pads``): the stand sits on four pads of closed-cell elastomer foam (machine
  isolation pads, e.g. cellular polyurethane); compressed by eps, a closed-cell foam carries the cell walls' stress
  E* eps plus the trapped gas's p0 eps / (1 - eps - R) (Gibson & Ashby, *Cellular Solids*, 2nd ed., 1997, ch. 5, eq.
  5.7-5.8: R = rho* / rho_s 0.1-0.3, p0 the atmospheric pressure, E* / p0 1-5 for soft foams), so the pads harden as
  the gas is squeezed. Designed for a static strain of 6-12 % under the lightest load; stand half sides 0.3-0.45 /
  0.2-0.3 m (any heading), the pads' plane 40-100 mm below the base frame; parts of up to the rated payload changed
  between blocks; sized to 0.25-0.6 mm. Unlike set ZM's cone mounts (a rubber cone's hardening), set Q's disc springs
  or set ZN's wire-rope isolators, the hardening is the cells' gas law. Driven by the pose and the payload (logged).
  The true structure: one column, amplitude the pads' thickness.
* cross-spring pivot (``cross_spring_pivot``): a compliant tool (a deburring or polishing head) hangs on a cross-spring
  flexure pivot -- two crossed leaf springs -- about the tool's x, 60 mm down the tool axis; the pivot's rotational
  stiffness changes with the load along its leaves, rising in tension and falling towards buckling in compression,
  K = K0 (1 + F_ax / F_c) to first order (Haringx, "The cross-spring pivot as a constructional element", Appl. Sci.
  Res. A1, 1949; Wittrick, Aeronaut. Q. 1, 1948; Jensen & Howell, Mech. Mach. Theory 39, 2004): the moment about the
  pivot's axis tilts the tool by M_x / K. F_c 1.7-3 times the heaviest part's weight; the part's centre 40-100 mm below
  the pivot, the target 200 mm down the tool axis; parts of 1-8 / 2-14 / 10-60 kg changed between blocks; sized to
  0.25-0.6 mm. Unlike set ZC's rubber bush, set R's swing mount or set ZN's bellows coupling, the tool turns about one
  axis with a stiffness the weight's axial component sets. Driven by the attitude and the payload (logged). The true
  structure: one column, amplitude 1 / K0.
* quasi-zero-stiffness isolator (``qzs_mount``): a camera or scanner carried on the tool by a quasi-zero-stiffness
  isolator along the tool's z -- a vertical spring in parallel with two oblique pre-compressed springs tuned to cancel
  its rate at the design load -- whose force about the design point is k1 x + k3 x^3 with a small residual k1 (Carrella,
  Brennan & Waters, "Static analysis of a passive vibration isolator with quasi-zero-stiffness characteristic", J.
  Sound Vib. 301, 2007; Ibrahim, J. Sound Vib. 314, 2008); designed for the sensor's weight with the tool pointing
  down, it moves by the cube root of the load's change as the tool turns: eta xi + xi^3 = (F_ax - F0) / F0, x = x_ref
  xi, eta 0.05-0.3. The target sits on the sensor. Sized to 0.25-0.6 mm. Unlike every tool-side spring of sets A-ZN (a
  linear, hardening or preloaded law), the mount has almost no rate at its design load. Driven by the attitude
  (logged angles). The true structure: one column, amplitude x_ref.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_body import gravity_in_tool, tool_frame
from sim2real_indep.effects_zm_body import _plate, _to_world, mount_loads, part_loads, total_weight

Z = np.array([0.0, 0.0, 1.0])
CS_MM = 60.0          # the cross-spring pivot down the tool axis
CS_TARGET_MM = 200.0


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- deck cupping
def cup_curvature(p, session):
    """(P,) the deck's curvature per unit beta C_s / h: 12 / h^2 times the first moment of the moisture profile of a
    sheet wetted underneath and sealed on top (0 dry, 0 again when saturated; the series' tail, whose terms have decayed
    after the first instants, added in closed form)."""
    t = session.time_s - session.time_s[0] + p["t_w"]
    n = np.arange(300)[:, None]
    k = 2 * n + 1
    a = 4 / (k * np.pi) * ((-1.0) ** n * 4 / (k * np.pi) ** 2 - 1 / (k * np.pi))
    tail = a.sum() * (1 - np.exp(-(2 * 300 + 1) ** 2 * t / p["tau_d"]))
    return 12 * ((a * (np.exp(-k ** 2 * t[None] / p["tau_d"]) - 1)).sum(axis=0) + tail)


def cup_features(p, ctx, hw):
    """(1, P, 3) per unit beta C_s / h [1/m]: the turn with the deck's slope at the base and its rise there."""
    kap = cup_curvature(p, ctx.session)
    c = p["r_c"] * np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])       # the deck's centre from the base [m]
    w = np.outer(kap, [-c[1], c[0], 0.0])                                    # (w_y, -w_x, 0), grad w = -kappa c
    rise = 1000.0 * kap * (c @ c - p["a"] ** 2 - p["b"] ** 2) / 2
    return (np.cross(w, ctx.target) + rise[:, None] * Z)[None]


def cup_draw(ctx, hw, rng):
    p = {"t_w": 60 * float(rng.uniform(3.0, 10.0)), "tau_d": 3600 * float(rng.uniform(20.0, 100.0)),
         "r_c": float(rng.uniform(0.15, 0.35)), "psi": float(rng.uniform(0, 2 * np.pi)),
         "a": float(rng.uniform(0.4, 0.6)), "b": float(rng.uniform(0.3, 0.4))}
    p["c"] = float(_size(cup_features(p, ctx, hw), [1.0], rng)[0])
    return p


def cup_apply(p, ctx, hw):
    return _amp_apply([p["c"]], cup_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- foam pads
def foam_stress(eps, g, R):
    """sigma / E* of a closed-cell foam at strain eps: the walls' eps plus the gas's g eps / (1 - eps - R)."""
    return eps + g * eps / (1 - eps - R)


def foam_strain(p, load):
    """(...) the pads' strain under loads [N] (0 where unloaded), the design strain eps0 at the lightest quarter
    weight."""
    eps = np.linspace(0.0, 0.9 * (1 - p["R"]), 4000)
    sig = foam_stress(eps, p["g"], p["R"])
    s = np.maximum(load, 0.0) / p["W4"] * foam_stress(p["eps0"], p["g"], p["R"])
    return np.interp(s, sig, eps)


def pads_features(p, ctx, hw):
    """(1, P, 3) per unit pad thickness [mm]: the plate through the pads' compressions."""
    R, xy = mount_loads(p, ctx)
    return _plate(p, ctx, foam_strain(p, R), xy)


def pads_draw(ctx, hw, rng):
    p = {"psi": float(rng.uniform(0, np.pi)), "a": float(rng.uniform(0.3, 0.45)), "b": float(rng.uniform(0.2, 0.3)),
         "pivot_mm": float(rng.uniform(40.0, 100.0)), "g": float(1 / rng.uniform(1.0, 5.0)),
         "R": float(rng.uniform(0.1, 0.3)), "eps0": float(rng.uniform(0.06, 0.12))}
    p["W4"] = float(total_weight(ctx).min() / 4)
    p["t_mm"] = float(_size(pads_features(p, ctx, hw), [1.0], rng)[0])
    return p


def pads_apply(p, ctx, hw):
    return _amp_apply([p["t_mm"]], pads_features(p, ctx, hw))


# ----------------------------------------------------------------------------------------------- cross-spring pivot
def cross_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / K0 [rad / N m]: the tilt M_x / (1 + F_z / F_c) about the pivot's axis (the tool's x)."""
    F, M = part_loads(ctx, CS_MM)
    theta = np.zeros_like(M)
    theta[:, 0] = M[:, 0] / (1 + F[:, 2] / p["F_c"])
    arm = ctx.probe_mm - np.array([0.0, 0.0, CS_MM])
    return _to_world(ctx, np.cross(theta, arm))[None]


def cross_draw(ctx, hw, rng):
    W = 9.80665 * max(float(ctx.session.payload_kg.max()), 0.1)
    p = {"F_c": float(W / rng.uniform(0.35, 0.6))}
    p["inv_K0"] = float(_size(cross_features(p, ctx, hw), [1.0], rng)[0])
    return p


def cross_apply(p, ctx, hw):
    return _amp_apply([p["inv_K0"]], cross_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- QZS isolator
def qzs_stroke(eta, y):
    """The real root xi of eta xi + xi^3 = y (Cardano; eta > 0)."""
    s = np.sqrt(y ** 2 / 4 + eta ** 3 / 27)
    return np.cbrt(y / 2 + s) + np.cbrt(y / 2 - s)


def qzs_features(p, ctx, hw):
    """(1, P, 3) per unit x_ref [mm]: the sensor's move along the tool's z as the weight's axial share leaves its
    design value (the tool pointing down)."""
    Rt = tool_frame(ctx)
    y = gravity_in_tool(Rt)[:, 2] - 1.0
    return (Rt[:, :, 2] * qzs_stroke(p["eta"], y)[:, None])[None]


def qzs_draw(ctx, hw, rng):
    p = {"eta": float(rng.uniform(0.05, 0.3))}
    p["x_ref"] = float(_size(qzs_features(p, ctx, hw), [1.0], rng)[0])
    return p


def qzs_apply(p, ctx, hw):
    return _amp_apply([p["x_ref"]], qzs_features(p, ctx, hw))
