"""Set X thermal effects (new physics, not in sets A-W): the arm rinsed with hot water in the sanitation between the
blocks (a wash-down arm in food handling) and cooling back to the air through the block; and the forearm heated by the
stray field of an induction heater it loads in the production between the blocks. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* wash-down: hygienic cells are cleaned with hot water at 50-70 degC (EHEDG guidelines on cleaning, as recalled;
  wash-down robots rated IP67 / IP69K for it); the links' thin walls (4-6 mm aluminium or steel; time constant
  rho c t / h of seconds under a jet of h ~ 10^3 W/m^2 K) reach nearly the water's temperature, are blown dry and then
  cool in still air as lumped bodies (Biot number h t / k << 0.1; Incropera & DeWitt, *Fundamentals of Heat and Mass
  Transfer*, ch. 5), dT = dT0 exp(-t / tau), tau = rho c V / (h A) of 10-25 min for h 8-15 W/m^2 K. dT0 10-25 K at the
  end of the blow-off, 30-120 s before the block's first move, each sanitation its own (the rinse's water temperature
  and length vary); every link alike, strain alpha dT (handbook CTEs of :mod:`hardware`). The sanitation is a pause
  (servo off) between the blocks; its water temperature is not logged (the air's is, and stays still). The true
  structure: one column per block (every link's expansion times the decay since the block's blow-off ended),
  amplitudes alpha dT0 of each block.
* induction stray field: an induction heater's coil (tens of kW at 10-30 kHz) has a stray field around it that heats
  conductive parts nearby by eddy currents (Rudnev, Loveless & Cook, *Handbook of Induction Heating*, 2nd ed., CRC,
  2017, on stray-field heating of fixtures and tooling); the forearm, which reaches into the coil's zone to load and
  unload parts in the production between the blocks, absorbs a steady power while it works and cools in the blocks.
  A lumped body driven by the production: tau dT/dt = dT_ss u(t) - T, u = 1 in the exercise gaps (Incropera & DeWitt,
  ch. 5), tau 15-40 min, dT_ss 5-15 K; the forearm is the longest link beyond the elbow. Not logged. The true
  structure: one column (the forearm's expansion times its temperature history per unit dT_ss), amplitude
  alpha dT_ss.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index


# -------------------------------------------------------------------------------------------------- wash-down
def wash_decay(p, session):
    """(P,) exp(-(t - t_b) / tau), t_b the end of the blow-off before the pose's block: lag_s before the block's first
    move (the session's start for the first block, which follows a sanitation too)."""
    b = block_index(session)
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    t_b = session.time_s[first] - session.dwell_s[first] - session.move_s[first] - p["lag_s"][:len(first)]
    return np.exp(-(session.time_s - t_b[b]) / p["tau_s"])


def wash_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    return {"dT0": rng.uniform(10.0, 25.0, nb), "tau_s": 60.0 * rng.uniform(10.0, 25.0),
            "lag_s": rng.uniform(30.0, 120.0, nb)}


def wash_features(p, ctx, hw):
    """(nb, P, 3): every link's expansion times the decay, one column per block (its rinse's own dT0)."""
    every = ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))
    d, b = wash_decay(p, ctx.session), block_index(ctx.session)
    return np.array([every * (d * (b == k))[:, None] for k in range(len(p["dT0"]))])


def wash_apply(p, ctx, hw):
    dT = p["dT0"][block_index(ctx.session)] * wash_decay(p, ctx.session)
    return Contribution(strain=hw["material"]["cte"] * np.outer(dT, np.ones(len(ctx.chain.links))))


# ---------------------------------------------------------------------------------------- induction stray field
def forearm_mask(chain):
    """(L,) the longest link beyond the elbow (moved by joint 3 or later)."""
    body = np.asarray(chain.link_body)
    lengths = np.linalg.norm(chain.links, axis=1) * (body >= 3)
    return np.arange(len(chain.links)) == int(np.argmax(lengths))


def stray_temperature(p, session):
    """(P,) the forearm's excess temperature per unit dT_ss: heated towards 1 in each exercise gap, cooling otherwise
    (exact first-order steps)."""
    tau = p["tau_s"]
    T, out = 0.0, np.zeros(len(session.time_s))
    prev = session.time_s[0] - session.move_s[0] - session.dwell_s[0]
    for k in range(len(out)):
        gap = session.gap_s[k]
        rest = session.time_s[k] - prev
        if gap > 0:
            T = 1.0 + (T - 1.0) * np.exp(-gap / tau)
            rest -= gap
        T *= np.exp(-max(rest, 0.0) / tau)
        out[k], prev = T, session.time_s[k]
    return out


#: the forearm's steady excess temperature [K]: ferromagnetic steel takes up the stray field by eddy currents in a thin
#: skin and by hysteresis, several times the power a non-magnetic aluminium wall does
STRAY_K = {"steel": (15.0, 35.0), "aluminium": (5.0, 15.0)}


def stray_draw(ctx, hw, rng):
    metal = "steel" if hw["material"]["cte"] < 15e-6 else "aluminium"
    return {"tau_s": 60.0 * rng.uniform(15.0, 40.0), "dT_ss": rng.uniform(*STRAY_K[metal])}


def stray_features(p, ctx, hw):
    return (ctx.link_scale_feature(forearm_mask(ctx.chain)) * stray_temperature(p, ctx.session)[:, None])[None]


def stray_apply(p, ctx, hw):
    a = hw["material"]["cte"] * p["dT_ss"]
    return Contribution(strain=a * np.outer(stray_temperature(p, ctx.session), forearm_mask(ctx.chain)))
