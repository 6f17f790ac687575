"""Set S thermal effects (new physics, not in sets A-R): the oil trapped in the boom cylinders' loaded chambers by the
load-holding valves, warm from the power pack, contracting as it cools towards the barrel during the dwell, so that the
boom sinks while it is measured; and axis 1 read by a measuring wheel with a polyurethane tyre rolling on the steel
slewing ring, whose radius ratio follows the hall's air through the wheel's and the ring's different expansions and
lags. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* trapped oil: a cylinder held by load-holding (counterbalance) valves keeps the oil of its loaded chamber; hydraulic
  oil expands by beta = 6.5-7.5e-4 /K (mineral oils: Merritt, *Hydraulic Control Systems*, 1967, ch. 2; Totten,
  *Handbook of Hydraulic Fluid Technology*, 2000, as recalled), so a chamber of oil length l that cools by dT shortens
  by l beta dT at the held load (drift of load-holding cylinders by the oil's thermal contraction, as recalled from
  makers' notes on cylinder drift). The oil that entered the chamber in the move -- a fresh share phi = phi_0 + |dL| /
  l, phi_0 0.1-0.3 (the pipe's and the valve block's volume) -- arrives at the supply's excess temperature and cools
  towards the barrel (at the hall's air) with the chamber's lumped time constant tau_c = rho c V / (h A) of 6-15 min
  (natural convection inside an oil-filled barrel, h 50-150 W/m^2 K: Incropera & DeWitt, *Fundamentals of Heat and Mass
  Transfer*, ch. 5 and 9); the measurement at the dwell's end sees phi x(t) dT_s (1 - exp(-t_dwell / tau_c)) of cooling
  (the valves closed, the loop off at standstill). The supply: one lumped node (set M's power pack) heated by production
  (the session's exercise gaps), at 20-40 % of that while the arm is measured, cooling in the pauses, time constant
  10-30 min, 0-15 % warm at the start, its steady excess dT_s 15-30 K over the hall (hydraulic oil at 35-50 degC;
  assumed; first 25-40 K with tau_c 4-12 min: 1.4 mm at the tool). The chamber that carries the load (the cap side for a
  push, the rod side for a pull, decided once from the true loads) with 20-60 mm of dead length; the levers of
  :func:`effects_s_joint.lever_draw`. Axes 2 and 3 of tool_changer (none on the others). Nothing of the oil is logged.
  The true structure: one column (both axes' sink per kelvin of dT_s), amplitude dT_s.
* wheel growth: a measuring wheel of radius r rolling on the ring of radius R reads R q / r turns (set M's friction
  wheel, whose static radius error and eccentricity are left out); a wheel of an aluminium hub (23e-6 /K) and a
  polyurethane tread of 4-8 mm (150-200e-6 /K; polyurethane data sheets, as recalled; first 3-6 mm: a trial draw on
  tool_changer gained 10 %) grows by alpha_eff = (alpha_Al (r - t) + alpha_PU t) / r per kelvin, the steel ring (11.7e-6
  /K) by its own; both follow the hall's air (logged) with their lumped lags (Incropera & DeWitt, ch. 5: 5-15 min for
  the wheel, 30-90 min for the massive ring). Homed at the joint's zero at the session's start, the axis servoed on the
  wheel stands off by q1 (alpha_eff dT_w - alpha_St dT_R) (the ratio's change times the turn since the reference). Axis
  1 of kr16_like and tool_changer (the arms given a slewing ring; none on ur10), r 20-40 mm; the session a working day
  of blocks and pauses while the air drifts by 2-6 K (assumed). The true structure: one column, amplitude alpha_eff.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import LEVER_JOINTS, lever_arm, lever_draw, lever_length
from sim2real_indep.session import air_temperature

GRID_S = 10.0
ALU_CTE, STEEL_CTE = 23e-6, 11.7e-6


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# --------------------------------------------------------------------------------------------------- trapped oil
def supply_node(p, session):
    """(P,): the supply oil's excess per its steady value at the measurements: heated in the production periods (the
    exercise gaps), at ``idle`` of that while measuring, unheated in the pauses; a 10 s grid from the session's
    start."""
    s = session
    t = s.time_s
    grid = np.arange(t[0] - s.dwell_s[0] - s.move_s[0] - GRID_S, t[-1] + GRID_S, GRID_S)
    mid = grid + GRID_S / 2
    gap_end = t - s.dwell_s - s.move_s
    per = np.c_[gap_end - np.abs(s.gap_s), gap_end][s.gap_s != 0]
    kind = np.sign(s.gap_s[s.gap_s != 0])                             # +1 production, -1 pause
    u = np.full(len(grid), p["idle"])
    for (a, b), k in zip(per, kind):
        u[(mid >= a) & (mid < b)] = 1.0 if k > 0 else 0.0
    x = ph.first_order_zoh(grid, u, p["tau_s"], x0=p["x0"])
    return np.interp(t, grid, x)


def oil_draw(ctx, hw, rng):
    if ctx.chain.name not in LEVER_JOINTS:
        return {}
    levers = lever_draw(ctx.chain.name, LEVER_JOINTS[ctx.chain.name], rng)
    p = {"levers": levers, "beta": rng.uniform(6.5e-4, 7.5e-4), "tau_c": rng.uniform(6.0, 15.0) * 60,
         "phi0": rng.uniform(0.1, 0.3), "idle": rng.uniform(0.2, 0.4), "tau_s": rng.uniform(10.0, 30.0) * 60,
         "x0": rng.uniform(0.0, 0.15), "dT_s": rng.uniform(15.0, 30.0), "dead": rng.uniform(20.0, 60.0, (2, 2))}
    # the loaded chamber: the cylinder pushes (cap side) where it must lengthen against the load, tau_cyl = -tau
    p["push"] = np.array([-ctx.loads[:, lv["joint"]] / lever_arm(lv, ctx.q[:, lv["joint"]]) > 0 for lv in levers])
    return p


def oil_signals(p, ctx):
    """(m, P): each axis' angle change per kelvin of the supply's steady excess [rad/K]."""
    s = ctx.session
    node = supply_node(p, s)
    cool = 1 - np.exp(-s.dwell_s / p["tau_c"])
    out = []
    for k, lv in enumerate(p["levers"]):
        q = ctx.q[:, lv["joint"]]
        L = lever_length(lv, q)
        x = L - lv["L_start"]
        cap, rod = x + p["dead"][k, 0], lv["X"] - x + p["dead"][k, 1]
        ell = np.where(p["push"][k], cap, rod)
        fresh = np.minimum(1.0, p["phi0"] + np.abs(np.diff(np.r_[L[0], L])) / ell)
        shrink = ell * p["beta"] * fresh * node * cool                 # [mm per K of dT_s]
        dL = np.where(p["push"][k], -shrink, shrink)                  # the loaded chamber shortens
        out.append(dL / lever_arm(lv, q))
    return np.array(out)


def oil_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        for lv, s in zip(p["levers"], oil_signals(p, ctx)):
            dq[:, lv["joint"]] = p["dT_s"] * s
    return Contribution(dq=dq)


def oil_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    cols = [ctx.joint_feature(lv["joint"], s) for lv, s in zip(p["levers"], oil_signals(p, ctx))]
    return np.sum(cols, axis=0)[None]


# ------------------------------------------------------------------------------------------------- wheel growth
WHEEL_ARMS = {"kr16_like", "tool_changer"}


def lagged_air(session, tau_s):
    """(P,): the air through a first-order lag, less its value at the session's start (the body then in equilibrium)."""
    t = session.time_s
    grid = np.arange(t[0], t[-1] + 60.0, 60.0)
    x = ph.first_order_foh(grid, air_temperature(session, grid), tau_s)
    return np.interp(t, grid, x) - x[0]


def wheel_draw(ctx, hw, rng):
    if ctx.chain.name not in WHEEL_ARMS:
        return {}
    r, t = rng.uniform(20.0, 40.0), rng.uniform(4.0, 8.0)
    p = {"r_mm": r, "t_mm": t, "alpha_pu": rng.uniform(150e-6, 200e-6), "tau_w": rng.uniform(5.0, 15.0) * 60,
         "tau_r": rng.uniform(30.0, 90.0) * 60}
    p["alpha_eff"] = (ALU_CTE * (r - t) + p["alpha_pu"] * t) / r
    return p


def wheel_signal(p, ctx):
    """(P,): axis 1's error per unit alpha_eff [rad K / (1/K)]: q1 (dT_w - alpha_St / alpha_eff dT_R)."""
    s = ctx.session
    dT = lagged_air(s, p["tau_w"]) - STEEL_CTE / p["alpha_eff"] * lagged_air(s, p["tau_r"])
    return ctx.q[:, 0] * dT


def wheel_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 0] = p["alpha_eff"] * wheel_signal(p, ctx)
    return Contribution(dq=dq)


def wheel_features(p, ctx, hw):
    return ctx.joint_feature(0, wheel_signal(p, ctx))[None] if p else _empty(ctx)
