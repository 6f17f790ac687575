"""Set W thermal effects (new physics, not in sets A-V): a hot part, fresh from a washer or a die-casting cell at the
start of each block, carrying the target and shrinking as it cools in the gripper; and the links of an arm that works
beside a furnace, each at the temperature of the stratified air at its own height. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* cooling part: a thin part cooling in still air is a lumped body (Biot number h t / (2 k) << 0.1), its excess
  temperature falling as exp(-t / tau) with tau = rho c t / (2 h) (Incropera & DeWitt, *Fundamentals of Heat and Mass
  Transfer*, ch. 5, lumped capacitance); for aluminium castings of 2-4 mm walls and h 10-20 W/m^2K (free convection
  and radiation), tau = 3-8 min. Each block starts with a new part picked 30-90 s earlier at 40-100 K above the air
  (a washer's hot rinse at 60-80 degC, a trimmed casting hotter; assumed). The part reaches 300 mm along the tool's x
  from the grip, the target at its end (:func:`effects_w.probe_hook`); the grip holds the part's root, so the target
  moves towards it by alpha dT L (alpha 23e-6 /K, aluminium). Production between the blocks
  (:func:`effects_w.session_options`). The part's temperature is not logged (the air's is). The true structure: one
  column (minus the tool's x times alpha L exp(-(t - t_pick) / tau)), amplitude the pick-up excess dT0 [K].
* air stratification: the air of a hall with a hot process stratifies, warmer upwards (vertical gradients of 1-3 K/m in
  ventilated halls and several K/m near furnaces and ovens: ASHRAE Handbook -- Fundamentals, ch. 20, displacement
  ventilation and industrial spaces; Awbi, *Ventilation of Buildings*, 2nd ed., 2003, ch. 8); a thin-walled link
  follows the air around it, so each link expands by alpha G (z_mid - z_s), z_mid its middle's height and z_s the
  logged sensor's (1.0-1.8 m above the base). G 3-8 K/m once settled beside a heat-treatment furnace (assumed),
  building up as 1 - exp(-t / tau) from the furnace's lighting 0-60 min before the first pose, tau 1-3 h (the hall's
  upper air filling with the plume: a first-order fill, assumed); a long day of blocks
  (:func:`effects_w.session_options`); alpha of the arm's material (:mod:`hardware`). The logged temperature is the
  air at the sensor, held by the lower zone's ventilation, so the gradient is not logged. The true structure: one
  column (the links' stretch with their heights, times the build-up), amplitude the settled G [K/m].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index

PART_MM = 300.0          # the part's reach along the tool's x (the target at its end)
PART_CTE = 23e-6         # aluminium [1/K]


# ------------------------------------------------------------------------------------------------- cooling part
def part_decay(p, session):
    """(P,) exp(-(t - t_pick) / tau): the part's excess temperature relative to its pick-up value."""
    b = block_index(session)
    first = np.r_[0, np.flatnonzero(np.diff(b)) + 1]
    t_pick = session.time_s[first][b] - (session.move_s + session.dwell_s)[first][b] - p["transfer_s"][b]
    return np.exp(-(session.time_s - t_pick) / p["tau_s"])


def part_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    return {"tau_s": 60 * rng.uniform(3.0, 8.0), "transfer_s": rng.uniform(30.0, 90.0, nb),
            "dT0": rng.uniform(40.0, 100.0)}


def part_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (-Rt[:, :, 0] * (PART_CTE * PART_MM * part_decay(p, ctx.session))[:, None])[None]


def part_apply(p, ctx, hw):
    return Contribution(displace=p["dT0"] * part_features(p, ctx, hw)[0])


# ---------------------------------------------------------------------------------------------- stratification
def link_heights(ctx):
    """(P, L) the height [m] of each link's middle above the base."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    start = np.cumsum(ch.links, axis=0) - ch.links
    mid = start + ch.links / 2
    return np.array([np.einsum("pij,j->pi", R[:, b], m)[:, 2] + t[:, b, 2]
                     for b, m in zip(ch.link_body, mid)]).T / 1000.0


def strat_growth(p, session):
    """(P,) the gradient's build-up since the furnace was lit, 1 - exp(-(t - t_on) / tau)."""
    return 1.0 - np.exp(-(session.time_s - session.time_s[0] + p["t_on_s"]) / p["tau_s"])


def strat_strain(p, ctx, hw):
    """(P, L) each link's strain per K/m of the settled gradient."""
    return hw["material"]["cte"] * (link_heights(ctx) - p["z_s_m"]) * strat_growth(p, ctx.session)[:, None]


def strat_draw(ctx, hw, rng):
    return {"z_s_m": rng.uniform(1.0, 1.8), "G": rng.uniform(3.0, 8.0), "tau_s": 3600 * rng.uniform(1.0, 3.0),
            "t_on_s": 60 * rng.uniform(0.0, 60.0)}


def strat_features(p, ctx, hw):
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    e = strat_strain(p, ctx, hw)
    out = np.zeros((len(ctx.q), 3))
    for li, (b, v) in enumerate(zip(ctx.chain.link_body, ctx.chain.links)):
        out += (R[:, b] @ v) * e[:, li:li + 1]
    return out[None]


def strat_apply(p, ctx, hw):
    return Contribution(strain=p["G"] * strat_strain(p, ctx, hw))
