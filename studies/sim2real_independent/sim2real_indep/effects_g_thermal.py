"""Set G thermal effects (new physics, not in sets A-F): the laser tracker's tripod growing with the hall's air, so
that the instrument rises and every measured point sinks; and the parallelogram drive of axis 3, whose link bar and
upper arm follow the air through different lags (and are of different metals), so that the four-bar turns the
forearm. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* tripod: a tripod's legs and centre column (aluminium 23e-6 /K or steel 11.7e-6 /K, handbook values) carry the
  tracker's head 1.2-1.9 m above the floor; thin-walled tubes follow the air through a lumped lag tau = rho c t / h
  (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5: 2-3 mm aluminium, h 5-10 W/m^2 K:
  10-20 min; 5-20 min taken). The head rises alpha h_t dT along the vertical; a point fixed in the robot's frame
  is then measured lower by as much (the thermal drift of the metrology frame: Bryan, "International status of
  thermal error research", CIRP Annals 39(2), 1990; tracker set-ups on carbon-fibre stands avoid it). Sessions in a
  hall whose air drifts by 2-5 K.
* parallelogram: axis 3's drive on the base side turns the forearm through a crank of radius r, a bar of the upper
  arm's length and a lever on the forearm (the parallelogram of palletising and heavy-duty arms, as set E's
  parallelogram). A bar longer than the upper arm by delta turns the lever by delta / (r sin gamma), gamma the
  angle between the upper arm and the lever (first order in the four-bar's loop equation; Hartenberg & Denavit,
  *Kinematic Synthesis of Linkages*, 1964). The bar (a thin tube: 10-30 min) and the upper-arm casting (40-120 min)
  follow the air through their own lags (Incropera & DeWitt), in different metals (a steel bar on the aluminium
  kr16_like, an aluminium bar on the steel tool_changer; assumed): delta = alpha_b L dT_b - alpha_a L dT_a;
  r 0.15-0.3 m, gamma 80-100 deg at mid-range (assumed). The whole arm expands with the casting's temperature as
  well. Only on the arms with a cycloid-driven axis 3 (tool_changer, kr16_like; none on ur10).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_f_thermal import lagged_air

Z = np.array([0.0, 0.0, 1.0])
ALUMINIUM_CTE, STEEL_CTE = 23e-6, 11.7e-6


# ------------------------------------------------------------------------------------------------- tripod
def tripod_draw(ctx, hw, rng):
    return {"h_mm": rng.uniform(1200, 1900), "cte": float(rng.choice([ALUMINIUM_CTE, STEEL_CTE])),
            "tau_s": rng.uniform(5, 20) * 60}


def tripod_part(p, ctx):
    """Target displacement (P, 3) [mm] per unit alpha h [mm/K]: the points sink as the head rises."""
    return -lagged_air(ctx, p["tau_s"])[:, None] * Z


def tripod_apply(p, ctx, hw):
    return Contribution(displace=p["cte"] * p["h_mm"] * tripod_part(p, ctx))


def tripod_features(p, ctx, hw):
    return tripod_part(p, ctx)[None]


# --------------------------------------------------------------------------------------------- parallelogram
def bar_draw(ctx, hw, rng):
    if ctx.chain.name == "ur10":
        return {}
    ch = ctx.chain
    up = [i for i in range(len(ch.links)) if ch.link_body[i] == 2]
    L = float(np.linalg.norm(ch.links[up].sum(axis=0))) / 1000.0      # joint 2 -> joint 3 [m]
    q = ctx.q[:, 2]
    s = float(rng.choice([-1.0, 1.0]))
    return {"L_m": L, "r_m": rng.uniform(0.15, 0.3), "s": s,
            "gamma0": np.deg2rad(rng.uniform(80, 100)) - s * 0.5 * (q.min() + q.max()),
            "cte_bar": STEEL_CTE if hw["material"]["cte"] > 15e-6 else ALUMINIUM_CTE, "cte_arm": hw["material"]["cte"],
            "tau_bar_s": rng.uniform(10, 30) * 60, "tau_arm_s": rng.uniform(40, 120) * 60}


def bar_signals(p, ctx):
    """Axis-3 offset per unit alpha L dT of the bar and of the arm (2, P) [rad / m], and the arm's temperature (P,)."""
    gamma = p["gamma0"] + p["s"] * ctx.q[:, 2]
    k = p["s"] / (p["r_m"] * np.sin(gamma))
    Tb, Ta = lagged_air(ctx, p["tau_bar_s"]), lagged_air(ctx, p["tau_arm_s"])
    return np.array([k * Tb, -k * Ta]), Ta


def bar_apply(p, ctx, hw):
    if not p:
        return Contribution()
    sig, Ta = bar_signals(p, ctx)
    dq = np.zeros_like(ctx.q)
    dq[:, 2] = p["L_m"] * (p["cte_bar"] * sig[0] + p["cte_arm"] * sig[1])
    return Contribution(dq=dq, strain=np.outer(p["cte_arm"] * Ta, np.ones(len(ctx.chain.links))))


def bar_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    sig, Ta = bar_signals(p, ctx)
    uni = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool)) * Ta[:, None]
    return np.array([ctx.joint_feature(2, sig[0]), ctx.joint_feature(2, sig[1]), uni])
