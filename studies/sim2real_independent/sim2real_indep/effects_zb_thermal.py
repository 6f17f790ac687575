"""Set ZB thermal effects (new physics, not in sets A-ZA): the forearm heated by a drying air knife's hot curtain over
a conveyor whenever axis 1 turns it into the curtain; and an ultrasonic welding horn carrying the target that warms
through the welds of the production between the blocks and cools in them. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* air knife: a drying air knife blows a hot curtain (60-90 degC, exit speeds of tens of m/s) across a conveyor in a
  sector of the arm's reach; the forearm is in the curtain whenever axis 1 stands within the sector (half-width 25-50
  deg about its centre, drawn within the session's range: a conveyor across the cell), and its wall under the jet heats
  towards dT_max 20-40 K above the hall (the wall's jet side nearly at the jet's temperature) (impinging slot jets:
  Martin, "Heat and mass transfer between impinging gas jets and solid surfaces", Adv. Heat Transfer 13, 1977, h of
  100-300 W/m^2 K) through a first-order lag of 1-3 min (a 3-5 mm wall under the jet: rho c t / h about a minute or two;
  first 2-6 min, 15-30 deg and 10-20 K, absorbed on a trial seed -- the wall hardly warmed; then 0.75-2 min, 25-50 deg
  and 10-20 K: ZB03 at a gain of 20 %, the link model at 1.23x), cooling with the same lag outside it. The jet heats one
  side: the gradient share 0.5-0.9 of the rise across the tube bows it by alpha share dT / D, the mean grows it by alpha
  dT / 2 (thermal bowing: Timoshenko & Goodier, thermal stress). Unlike set ZA's oven door or AC jet (sources switched
  by the clock) or set Y's lamp, the arm's own pose puts the forearm into the source. Driven by axis 1's angle and the
  time (logged). The true structure: two columns (the forearm's growth and bow per unit), amplitudes alpha and alpha
  share / D.
* sonotrode: an ultrasonic welding stack (converter, booster, horn: 300 mm along the tool's z, the target at the horn's
  face) warms in production, the horn's internal (hysteresis) losses and the weld's heat raising it by 40-80 K (horn and
  booster temperatures of ultrasonic welders: Branson / Herrmann application notes; Graff, in *Power Ultrasonics*,
  Woodhead, 2015, ch. 2, as recalled), towards that rise with a time constant of 3-8 min (a compact aluminium or
  titanium stack; first-order heating and Newton cooling: Incropera & DeWitt, ch. 5), and cools with the same constant
  while the blocks are measured (no welding). The stack grows by alpha L dT along the tool's z, alpha of aluminium
  (23e-6) or titanium (8.6e-6) horns. Unlike set D's tool heating or set L's hot part (a part, a gripper), the process
  tool's own stack grows along its axis with the production. Driven by the production between the blocks (not logged)
  and the time (logged). The true structure: one column (the stack's growth per unit alpha), amplitude alpha [1/K].
  First 250 mm and 30-60 K (ZB11: a gain of 20 %, the transmission model at 1.24x): the whole stack, converter and
  booster included, now counts, and a horn welding continuously runs hotter.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_za_thermal import _bow_features, forearm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ------------------------------------------------------------------------------------------------------ air knife
KNIFE_D_MM = {"ur10": (75.0, 95.0), "kr16_like": (110.0, 160.0), "tool_changer": (150.0, 250.0)}


def in_curtain(p, q1):
    """(P,) 1 where axis 1 holds the forearm in the curtain's sector."""
    return (np.abs(np.angle(np.exp(1j * (q1 - p["centre"])))) < p["half"]).astype(float)


def knife_temperature(p, session):
    """(P,) the forearm's jet side less the hall's [K]: the lagged exposure (each pose's move and dwell)."""
    on = in_curtain(p, session.q[:, 0])
    a = np.exp(-(session.move_s + session.dwell_s) / p["tau_s"])
    gap = np.exp(-np.abs(session.gap_s) / p["tau_s"])
    x, out = 0.0, np.zeros(len(on))
    for k in range(len(on)):
        x = x * gap[k]
        x = x * a[k] + (1 - a[k]) * on[k]
        out[k] = x
    return p["dT_K"] * out


def knife_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    q1 = ctx.q[:, 0]
    D, share = rng.uniform(*KNIFE_D_MM[ctx.chain.name]), rng.uniform(0.5, 0.9)
    return {"centre": q1.min() + (q1.max() - q1.min()) * rng.uniform(0.3, 0.7), "half": np.deg2rad(rng.uniform(25, 50)),
            "dT_K": rng.uniform(20.0, 40.0), "tau_s": 60.0 * rng.uniform(1.0, 3.0), "D_mm": D, "share": share,
            "psi": rng.uniform(0, 2 * np.pi), "amp": np.array([cte, cte * share / D])}


def knife_features(p, ctx, hw):
    return _bow_features(ctx, forearm(ctx.chain), p["psi"], knife_temperature(p, ctx.session))


def knife_apply(p, ctx, hw):
    return _amp_apply(p["amp"], knife_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------------ sonotrode
HORN_MM = 300.0
HORN_CTE = {"aluminium": 23e-6, "titanium": 8.6e-6}


def horn_temperature(p, session):
    """(P,) the stack's rise over the hall [K]: heating towards dT_K through each production gap, cooling in the
    blocks (cold at the session's start)."""
    x, out, t_last = 0.0, np.zeros(len(session.time_s)), session.time_s[0] - session.move_s[0] - session.dwell_s[0]
    for k, t in enumerate(session.time_s):
        g = session.gap_s[k]
        dt = t - t_last
        if g > 0:                                       # production: welding for g, then the move and dwell
            x = p["dT_K"] + (x - p["dT_K"]) * np.exp(-g / p["tau_s"])
            dt -= g
        x *= np.exp(-max(dt, 0.0) / p["tau_s"])
        out[k], t_last = x, t
    return out


def horn_draw(ctx, hw, rng):
    mat = str(rng.choice(["aluminium", "titanium"]))
    return {"material": mat, "cte": HORN_CTE[mat], "dT_K": rng.uniform(40.0, 80.0),
            "tau_s": 60.0 * rng.uniform(3.0, 8.0)}


def horn_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (Rt[:, :, 2] * (HORN_MM * horn_temperature(p, ctx.session))[:, None])[None]


def horn_apply(p, ctx, hw):
    return _amp_apply([p["cte"]], horn_features(p, ctx, hw))
