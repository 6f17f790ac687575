"""Set ZC thermal effects (new physics, not in sets A-ZB): a freshly bonded part, carrying the target, warmed by its
adhesive's curing exotherm and cooling again, a new part each block; and the hollow forearm bowed by the warm air its
wrist motors stratify inside it, its warm side the side that is up, so that the bow turns with the forearm's
orientation. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* cure exotherm: the gripper holds a bonded assembly (an aluminium bracket bonded with a two-part epoxy 1-3 min before
  it is picked (0.5-2 min), a new one each block; the part's mass logged as the payload); the adhesive's cure releases
  its heat at a rate falling with the conversion (first-order cure kinetics, the m = 0 case of Kamal & Sourour,
  "Kinetics and thermal characterization of thermoset cure", Polym. Eng. Sci. 13, 1973: dalpha/dt = k (1 - alpha)), and
  the part, a lumped body losing heat to the hall with a time constant tau_c (Incropera & DeWitt, *Fundamentals of Heat
  and Mass Transfer*, ch. 5), warms and cools: dT = dT_pk (exp(-t / tau_c) - exp(-t / tau_r)) normalised to its peak, t
  from the bonding, tau_r 1-3 min (the cure), tau_c 5-12 min (a thin-walled bracket), dT_pk 15-40 K (a thick bond line).
  The target sits on the part 450 mm along the tool's z, which the part lengthens by alpha_Al L dT (first 300 mm, a lead
  of 1-3 min, tau_r 1.5-4 and tau_c 8-20 min: ZC14 gained 8 %, the part hardly changing within a block). Unlike set L's
  hot part or set W's cooling part (a part taken hot, cooling), the part's own exotherm heats it after it is taken, and
  each block's part starts anew. Driven by the time (logged) and the bonding times (not logged). The true structure: one
  column, amplitude alpha [1/K].
* link convection: the wrist motors in a hollow forearm (80-250 W lost) warm the enclosed air, which stratifies: the
  warm air rises to the tube's upper wall (natural convection in enclosures: Ostrach, "Natural convection in
  enclosures", J. Heat Transfer 110, 1988; Incropera & DeWitt, ch. 9), so the wall's side that is up (gravity's
  direction across the forearm, set by the pose) runs dT_g warmer than the side that is down, dT_g rising with the
  motors' warm-up 1 - exp(-t / tau) from the session's start (tau 10-25 min), 3-8 K. The gradient bows the tube by alpha
  dT_g / D about the horizontal axis across it, weighted by how far the forearm is from vertical, and the mean rise
  (0.3-0.8 of dT_g) lengthens it (thermal bowing: Timoshenko & Goodier, *Theory of Elasticity*, thermal stress). Unlike
  the lamps, jets and curtains of sets Y-ZB (a side fixed on the link), the warm side follows gravity, not the link.
  Driven by the time and the pose (logged). The true structure: two columns (the growth and the bow per unit),
  amplitudes alpha m and alpha / D.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_y_thermal import lamp_side, link_bow
from sim2real_indep.effects_za_thermal import forearm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ------------------------------------------------------------------------------------------------- cure exotherm
PART_MM = 450.0          # the target on the part along the tool's z
CURE_CTE = 23e-6         # aluminium bracket


def cure_temperature(p, session):
    """(P,) the part's rise over the hall [K]: each block's part from its bonding time."""
    b = np.minimum(block_index(session), len(p["lead_s"]) - 1)
    t = session.time_s
    start = np.array([t[b == k].min() if (b == k).any() else 0.0 for k in range(len(p["lead_s"]))])
    age = t - start[b] + p["lead_s"][b]
    tr, tc = p["tau_r_s"], p["tau_c_s"]
    tp = np.log(tc / tr) * tr * tc / (tc - tr)                       # the peak's time
    peak = np.exp(-tp / tc) - np.exp(-tp / tr)
    return p["dT_K"] * (np.exp(-age / tc) - np.exp(-age / tr)) / peak


def cure_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    return {"lead_s": 60.0 * rng.uniform(0.5, 2.0, nb), "tau_r_s": 60.0 * rng.uniform(1.0, 3.0),
            "tau_c_s": 60.0 * rng.uniform(5.0, 12.0), "dT_K": rng.uniform(15.0, 40.0), "cte": CURE_CTE}


def cure_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (Rt[:, :, 2] * (PART_MM * cure_temperature(p, ctx.session))[:, None])[None]


def cure_apply(p, ctx, hw):
    return _amp_apply([p["cte"]], cure_features(p, ctx, hw))


# ----------------------------------------------------------------------------------------------- link convection
CONV_D_MM = {"ur10": (75.0, 95.0), "kr16_like": (110.0, 160.0), "tool_changer": (150.0, 250.0)}


def convection_parts(p, ctx):
    """(2, P, 3) the forearm's growth and its bow per unit, both times the warm-up: the bow away from the side that
    is up, weighted by the cross-section's share of the vertical."""
    ch = ctx.chain
    li = forearm(ch)
    b = int(ch.link_body[li])
    R, _ = kin.body_transforms(ch, ctx.q)
    up = np.einsum("pji,j->pi", R[:, b], [0.0, 0.0, 1.0])          # the vertical in the body's home frame
    e1, e2 = lamp_side(ch, li, 0.0), lamp_side(ch, li, np.pi / 2)
    w1, w2 = up @ e1, up @ e2
    warm = 1.0 - np.exp(-(ctx.session.time_s - ctx.session.time_s[0]) / p["tau_s"])
    bow = link_bow(ctx, li, e1) * w1[:, None] + link_bow(ctx, li, e2) * w2[:, None]
    grow = ctx.link_scale_feature(np.arange(len(ch.links)) == li)
    return np.array([grow * warm[:, None], bow * warm[:, None]]) * p["dT_K"]


def convection_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    D, m = rng.uniform(*CONV_D_MM[ctx.chain.name]), rng.uniform(0.3, 0.8)
    return {"dT_K": rng.uniform(3.0, 8.0), "tau_s": 60.0 * rng.uniform(10.0, 25.0), "D_mm": D, "mean": m,
            "amp": np.array([cte * m, cte / D])}


def convection_features(p, ctx, hw):
    return convection_parts(p, ctx)


def convection_apply(p, ctx, hw):
    return _amp_apply(p["amp"], convection_features(p, ctx, hw))
