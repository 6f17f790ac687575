"""Set R thermal effects (new physics, not in sets A-Q): a heated hot-melt hose strapped along one side of the forearm,
switched on around the session's start, warming that side of the link more than the other; and a welding power cable
strapped along the upper arm, its Joule heat flowing into the link while the robot welds between the measurement
blocks. Both bow their link away from the warm side and lengthen it. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* heated hose: hot-melt adhesive is fed to a robot-held gun through an electrically heated hose held at 150-200 degC by
  its own thermostat (makers' data of hot-melt systems, as recalled); strapped to a link, it warms it through the
  straps' contact and its radiation, the hose's side more than the other. A temperature difference dT_g across a beam of
  depth D bends it with curvature alpha dT_g / D, its tip shifting kappa L^2 / 2 away from the warm side and turning by
  kappa L, and the mean rise dT lengthens it by alpha dT L (Timoshenko & Goodier, *Theory of Elasticity*, ch. 13,
  thermal bending of a bar; Boley & Weiner, *Theory of Thermal Stresses*, 1960). The link's lumped lag (Incropera &
  DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) 10-25 min (ur10's thin tubes) or 20-45 min (the heavier
  arms); the hose switched on 30 min before to 10 min after the session's start, a steady mean rise of 3-8 K with 50-100
  % of it across the depth, on tool_changer's steel 4-10 K with 70-120 % (steel conducts a quarter of aluminium's heat
  round the section, so the strapped side runs hotter; first 2-5 K and 50-100 %: 0.06 mm at the tool, R14 absorbed)
  (assumed); the forearm (ur10 a3, kr16_like d4, tool_changer l4) of depth 80-110 / 140-220 / 180-260 mm. Nothing of the
  hose is logged. The true structure: one column (the switch-on's lagged step through the bow and the growth), amplitude
  the steady mean rise.
* welding cable: a MIG torch's power cable (35-70 mm^2 copper, 250-400 A at 40-70 % duty) dissipates I^2 R, some 10-30
  W/m (copper 0.017 Ohm mm^2/m; IEC 60228 conductor resistances); strapped along the upper arm it warms that side while
  the robot welds -- the production periods between the measurement blocks -- and the link cools back while it is
  measured (Joule heating into a lumped node: Incropera & DeWitt, ch. 5; the bow and growth as above). Upper arm (ur10
  a2, kr16_like a2, tool_changer l3), its side 2-6 K (1.5-4 K on steel) above the hall in steady welding, 50-100 % of it
  across the depth, lag 8-20 / 15-40 min, the shift starting with the session, the cell idle before it, left it at 0-30
  % of the steady rise (first 0-100 %: R22 on kr16_like rose only from 58 to 95 % of it, 0.2 mm of which most was
  constant, and was absorbed; it now holds the heated hose) (assumed; the production periods are the session's exercise
  gaps, not logged as such). The true structure: one column (the welding periods through the lag, the bow and growth),
  amplitude the steady mean rise.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

DEPTH_MM = {"ur10": (80.0, 110.0), "kr16_like": (140.0, 220.0), "tool_changer": (180.0, 260.0)}
TAU_MIN = {"ur10": (10.0, 25.0), "kr16_like": (20.0, 45.0), "tool_changer": (20.0, 45.0)}
FOREARM = {"ur10": "a3", "kr16_like": "d4", "tool_changer": "l4"}
UPPER_ARM = {"ur10": "a2", "kr16_like": "a2", "tool_changer": "l3"}
WELD_TAU_MIN = {"ur10": (8.0, 20.0), "kr16_like": (15.0, 40.0), "tool_changer": (15.0, 40.0)}
GRID_S = 10.0


def _side(chain, li, rng):
    """A unit direction across link ``li`` (home, base frame)."""
    v = chain.links[li] / np.linalg.norm(chain.links[li])
    d = rng.normal(size=3)
    d -= (d @ v) * v
    return d / np.linalg.norm(d)


def bow_per_kelvin(ctx, li, side, r_g, D, cte):
    """(P, 3): the target's displacement per kelvin of mean rise of link ``li`` with r_g of it across its depth D
    towards ``side`` (home frame): the link's far end shifts alpha (L e_v - r_g L^2 / 2D side) and turns by -alpha r_g L
    / D about e_v x side, carrying the chain beyond it."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    b = ch.link_body[li]
    end = np.cumsum(ch.links, axis=0)[li]
    L = np.linalg.norm(ch.links[li])
    v = ch.links[li] / L
    Rb = R[:, b]
    p_end = np.einsum("pij,j->pi", Rb, end) + t[:, b]
    shift = cte * (L * v - r_g * L ** 2 / (2 * D) * side)
    omega = -cte * r_g * L / D * np.cross(v, side)
    return np.einsum("pij,j->pi", Rb, shift) + np.cross(np.einsum("pij,j->pi", Rb, omega), ctx.target - p_end)


# ------------------------------------------------------------------------------------------------- heated hose
def hose_draw(ctx, hw, rng):
    name = ctx.chain.name
    li = ctx.chain.link_names.index(FOREARM[name])
    steel = hw["material"]["cte"] < 15e-6
    return {"link": li, "side": _side(ctx.chain, li, rng), "D_mm": rng.uniform(*DEPTH_MM[name]),
            "r_g": rng.uniform(0.7, 1.2) if steel else rng.uniform(0.5, 1.0),
            "dT_K": rng.uniform(4.0, 10.0) if steel else rng.uniform(3.0, 8.0),
            "t_on_s": ctx.session.time_s[0] + rng.uniform(-30.0, 10.0) * 60, "tau_s": rng.uniform(*TAU_MIN[name]) * 60,
            "cte": hw["material"]["cte"]}


def hose_signal(p, t):
    """(P,): the link's rise per its steady value: the switch-on's step through the lag."""
    return 1 - np.exp(-np.maximum(np.asarray(t, float) - p["t_on_s"], 0.0) / p["tau_s"])


def hose_shape(p, ctx):
    bow = bow_per_kelvin(ctx, p["link"], p["side"], p["r_g"], p["D_mm"], p["cte"])
    return hose_signal(p, ctx.session.time_s)[:, None] * bow


def hose_apply(p, ctx, hw):
    return Contribution(displace=p["dT_K"] * hose_shape(p, ctx))


def hose_features(p, ctx, hw):
    return hose_shape(p, ctx)[None]


# ---------------------------------------------------------------------------------------------- welding cable
def weld_draw(ctx, hw, rng):
    name = ctx.chain.name
    li = ctx.chain.link_names.index(UPPER_ARM[name])
    steel = hw["material"]["cte"] < 15e-6
    return {"link": li, "side": _side(ctx.chain, li, rng), "D_mm": rng.uniform(*DEPTH_MM[name]),
            "r_g": rng.uniform(0.5, 1.0), "dT_K": rng.uniform(1.5, 4.0) if steel else rng.uniform(2.0, 6.0),
            "tau_s": rng.uniform(*WELD_TAU_MIN[name]) * 60,
            "x0": rng.uniform(0.0, 0.3), "cte": hw["material"]["cte"]}


def welding_periods(session):
    """(K, 2): the production (welding) periods: the session's exercise gaps [s]."""
    s = session
    k = np.flatnonzero(s.gap_s > 0)
    end = s.time_s[k] - s.dwell_s[k] - s.move_s[k]
    return np.c_[end - s.gap_s[k], end]


def weld_signal(p, session):
    """(P,): the side's rise per its steady value: welding on in the production periods, through the lag, on a 10 s
    grid from the session's start (the welding before it left x0)."""
    t = session.time_s
    grid = np.arange(t[0] - session.dwell_s[0] - GRID_S, t[-1] + GRID_S, GRID_S)
    mid = grid + GRID_S / 2
    per = welding_periods(session)
    u = np.any((mid[:, None] >= per[:, 0]) & (mid[:, None] < per[:, 1]), axis=1).astype(float)
    x = ph.first_order_zoh(grid, u, p["tau_s"], x0=p["x0"])
    return np.interp(t, grid, x)


def weld_shape(p, ctx):
    bow = bow_per_kelvin(ctx, p["link"], p["side"], p["r_g"], p["D_mm"], p["cte"])
    return weld_signal(p, ctx.session)[:, None] * bow


def weld_apply(p, ctx, hw):
    return Contribution(displace=p["dT_K"] * weld_shape(p, ctx))


def weld_features(p, ctx, hw):
    return weld_shape(p, ctx)[None]
