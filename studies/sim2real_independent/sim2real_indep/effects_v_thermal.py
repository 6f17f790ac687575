"""Set V thermal effects (new physics, not in sets A-U): an aluminium crossbar held between the steel side plates of a
gripper frame, carrying the target at its midspan, whose restrained thermal expansion compresses it and amplifies its
initial crookedness (or, cooling, straightens it); and the floor slab between the arm and the tracker curling as its top
follows the hall's air while its bottom stays at the ground's temperature. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* restrained bar: a bar restrained against expansion takes the axial force P = k_r dalpha dT L (dalpha the difference
  between the aluminium bar's and the steel frame's expansion, 23 vs 12e-6 /K; k_r the frame's and the bar's series
  stiffness), and a member of initial crookedness delta0 under compression P bows by delta0 P / (P_cr - P) more (the
  amplification of an initial imperfection, Timoshenko & Gere, *Theory of Elastic Stability*, 2nd ed., 1961, sec. 1.12;
  tension straightens it, P < 0). With r = dT / dT_cr the bow grows by delta0 r / (1 - r). Crookedness L/1000-L/500 of
  a 300-600 mm bar (EN 1090-2 straightness tolerance L/750, as recalled), the frame's restraint such that dT_cr is 1.5-3
  times the session's largest excursion (assumed, so the bar stays stable); the bar's temperature is the air's (logged)
  lagged by 5-20 min (a thin bar: Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5), straight-ish
  at an assembly temperature within 1 K of its start. The bar spans the tool's y at 150 mm along its z
  (:func:`effects_v.probe_hook`), bowing along the tool's x. The session is set A's working day (the hall drifting by
  2-6 K). The true structure: one column (the tool's x times r / (1 - r)), amplitude delta0.
* slab curl: a slab on grade whose top warms relative to its bottom curls with curvature kappa = alpha dT_g / h, of
  which the slab's weight and the subgrade restrain most in its interior (Westergaard, "Analysis of stresses in concrete
  pavements due to variations of temperature", 1926; Bradbury's restraint coefficients, as recalled: a free share rho of
  0.3-0.6 assumed here, the arm and the tracker on one panel of a jointed slab). The arm and the tracker stand
  D = 1.5-5 m apart on the slab, so the arm's base turns by kappa D about the horizontal axis across that line and
  sinks by kappa D^2 / 2 relative to the tracker. The top layer
  follows the hall's air (logged) with a lag of 30-90 min, the bottom stays at the ground's; concrete alpha 10e-6 /K,
  slabs 120-200 mm thick. The session is set A's working day. The true structure: one column (the base's turn and sink
  per unit curvature times D), amplitude rho alpha / h.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature


def air_lag(session, tau_s):
    """(P,) the air's (true, fine-grained) temperature lagged by tau_s, minus its value at the first pose [K]."""
    t = session.time_s
    grid = np.unique(np.r_[np.linspace(t[0], t[-1], 2000), t])
    T = np.interp(t, grid, ph.first_order_foh(grid, air_temperature(session, grid), tau_s))
    return T - T[0]


# -------------------------------------------------------------------------------------------- restrained bar
BAR_MM = 150.0  # the bar's distance along the tool's z (the target's offset, effects_v.probe_hook)


def bar_ratio(p, session):
    """(P,) r = dT / dT_cr, dT the bar's temperature over its assembly temperature."""
    return (air_lag(session, p["tau_s"]) - p["T_off"]) / p["dT_cr"]


def bar_draw(ctx, hw, rng):
    p = {"tau_s": rng.uniform(5.0, 20.0) * 60, "T_off": rng.uniform(-1.0, 1.0)}
    span = np.abs(air_lag(ctx.session, p["tau_s"]) - p["T_off"]).max()
    L = rng.uniform(300.0, 600.0)
    p.update(dT_cr=rng.uniform(1.5, 3.0) * max(span, 1.0), L_mm=L,
             delta0_mm=L / rng.uniform(500.0, 1000.0) * rng.choice([-1.0, 1.0]))
    return p


def bar_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    r = bar_ratio(p, ctx.session)
    return (Rt[:, :, 0] * (r / (1 - r))[:, None])[None]


def bar_apply(p, ctx, hw):
    return Contribution(displace=p["delta0_mm"] * bar_features(p, ctx, hw)[0])


# ------------------------------------------------------------------------------------------------- slab curl
def curl_draw(ctx, hw, rng):
    h, rho, az = rng.uniform(0.12, 0.2), rng.uniform(0.3, 0.6), rng.uniform(0, 2 * np.pi)
    return {"tau_s": rng.uniform(30.0, 90.0) * 60, "h_m": h, "rho": rho, "alpha": 10e-6, "D_m": rng.uniform(1.5, 5.0),
            "e": np.array([np.cos(az), np.sin(az), 0.0]), "a": rho * 10e-6 / h}


def curl_features(p, ctx, hw):
    """(1, P, 3) [mm per unit rho alpha / h, 1/(m K)]: the base's turn -kappa D about z x e and its sink kappa D^2/2."""
    dT = air_lag(ctx.session, p["tau_s"])
    n = np.cross([0.0, 0.0, 1.0], p["e"])
    D = p["D_m"]
    shape = -D * np.cross(n, ctx.target) - np.array([0.0, 0.0, 1000.0 * D ** 2 / 2])
    return (dT[:, None] * shape)[None]


def curl_apply(p, ctx, hw):
    return Contribution(displace=p["a"] * curl_features(p, ctx, hw)[0])
