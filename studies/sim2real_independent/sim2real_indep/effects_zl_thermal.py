"""Set ZL thermal effects (new physics, not in sets A-ZK): link tubes whose thermal growth is held back by the
friction of their clamped end fits (the growth following the warming through a play operator); and a welding arm's
forearm heated on its torch side by the arc's radiation during the production. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* friction-restrained growth (``thermal_ratchet``): a link tube clamped in its joint housings' fits (a split clamp
  or a light press fit: sliding is resisted by a friction force F_s) cannot grow freely: while the thermal force E A
  alpha dT stays below F_s the tube is strained instead; once above, the fit slips and the tube grows with the
  warming less the elastic share; as the tube cools the fit holds again until the force reverses past F_s. The length
  follows the free thermal growth through a play operator of half-width r = F_s L / (E A) (friction-restrained
  thermal expansion: the frictional restraint of pipes on their supports, ASME B31.3 / Peng & Peng, *Pipe Stress
  Engineering*, 2009, ch. 4; thermal hysteresis of machine joints: Bryan, CIRP Annals 39(2), 1990; Mayr et al., CIRP
  Annals 61(2), 2012; play operators: Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989). The tubes
  warm with the joints' drives as one lumped node (tau 20-40 min, 0-30 % warm at the start, 1 while measuring, 1.0-1.4
  in production, 0.2-0.5 in the pauses; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5), by dT
  20-35 K over a share f 0.5-0.8 of each tube at full warming; r 10-30 % of the full growth. ur10's upper arm and
  forearm (a2, a3), kr16_like's a2 and d4. Unlike set ZK's drive boards (the same node, free growth), set V's
  restrained bar (an elastic restraint bowing the bar) or set K's thermal lash, the growth sticks and slips at its
  fits. Driven by the servo-on time, the production and the pauses (the time stamps and gaps hold them); the
  temperature is not logged. The true structure: one column per tube (its stretch times the play of the node),
  amplitudes CTE f dT.
* arc radiation (``arc_radiation``): a welding arc radiates some 20-30 % of its power (GMAW at 4-6 kW; Lancaster,
  *The Physics of Welding*, 2nd ed., 1986, ch. 6; Messler, *Principles of Welding*, 1999) and the forearm, 0.3-0.6 m
  from the torch, takes 300-900 W/m^2 on its torch side (absorptivity 0.3-0.6), warming that side more than the far
  one: the tube bows away from it with curvature alpha dT_x / D and grows by alpha dT_m L (Timoshenko & Goodier,
  *Theory of Elasticity*, thermal bending of beams; Roark, beams with a linear gradient); dT_x 2-5 K and dT_m 3-8 K
  at the steady state of continuous welding (assumed), one lumped node (tau 10-25 min) heated in the production
  between the blocks, cooling while the robot is measured (first with production or pauses between the blocks at
  random: ur10's trial case had one production gap, in its last, time-split block, and was absorbed; now a welding
  cell's production between all blocks). The torch side at random about the tube
  (fixed in its body). ur10's forearm a3 (D 75-95 mm) and kr16_like's d4 (D 120-160 mm). Unlike set D's thermal bend
  (the drives' heat at a tube's end), set ZJ's stray welding current (the bearings' Joule heat) or set ZB's air
  knife (a hot curtain the forearm enters by axis 1), the heat is the arc's radiation during the welding. Driven by
  the production and the pauses (gaps in the time stamps); no temperature is logged. The true structure: two columns
  (the bow per unit curvature and the stretch per unit strain, times the node), amplitudes the steady curvature
  [1/m] and strain.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zj_thermal import gap_node
from sim2real_indep.effects_zk_joint import play

TUBES = {"ur10": ("a2", "a3"), "kr16_like": ("a2", "d4")}
FOREARM = {"ur10": ("a3", (75.0, 95.0)), "kr16_like": ("d4", (120.0, 160.0))}


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _links(chain, names):
    return [chain.link_names.index(n) for n in names if n in chain.link_names]


# ---------------------------------------------------------------------------------------------------- thermal ratchet
def ratchet_node(p, session):
    """(P,) the tubes' warming per unit: 1 measuring, w_prod in production, w_pause in the pauses."""
    return gap_node(session, p["T0"], p["tau_s"], 1.0, p["w_prod"], p["w_pause"])


def ratchet_growth(p, session, i):
    """(P,) tube i's growth per unit of its full free growth: the play of the node with half-width r_i."""
    T = ratchet_node(p, session)
    return play(T, p["r"][i], T[0])


def ratchet_draw(ctx, hw, rng):
    links = _links(ctx.chain, TUBES.get(ctx.chain.name, ()))
    p = {"tau_s": 60 * rng.uniform(20.0, 40.0), "T0": rng.uniform(0.0, 0.3), "w_prod": rng.uniform(1.0, 1.4),
         "w_pause": rng.uniform(0.2, 0.5), "r": rng.uniform(0.1, 0.3, len(links)).tolist()}
    p["amp"] = (float(hw["material"]["cte"]) * rng.uniform(0.5, 0.8, len(links))
                * rng.uniform(20.0, 35.0, len(links))).tolist()
    return p


def ratchet_features(p, ctx, hw):
    L = len(ctx.chain.links)
    links = _links(ctx.chain, TUBES.get(ctx.chain.name, ()))
    return np.array([ctx.link_scale_feature(np.arange(L) == li) * ratchet_growth(p, ctx.session, i)[:, None]
                     for i, li in enumerate(links)]).reshape(len(links), len(ctx.q), 3)


def ratchet_apply(p, ctx, hw):
    return _amp_apply(p["amp"], ratchet_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- arc radiation
def arc_node(p, session):
    """(P,) the forearm's warming per unit: heated in the production (welding), cooling otherwise."""
    return gap_node(session, 0.0, p["tau_s"], 0.0, 1.0, 0.0)


def link_ends(chain, q, li):
    """World rotation of link li's body (P, 3, 3) and its end point (P, 3) [mm]."""
    R, t = kin.body_transforms(chain, q)
    b = chain.link_body[li]
    end = chain.links[:li + 1].sum(axis=0)
    return R[:, b], np.einsum("pij,j->pi", R[:, b], end) + t[:, b]


def bow_parts(p, ctx):
    """(2, P, 3) the target's displacement [mm] per unit curvature [1/m] (bowing away from the torch side) and per
    unit strain of the forearm."""
    ch = ctx.chain
    li = ch.link_names.index(FOREARM[ch.name][0])
    Rb, end = link_ends(ch, ctx.q, li)
    v = ch.links[li]
    L = np.linalg.norm(v)
    u = v / L
    a = np.cross(u, [1.0, 0, 0] if abs(u[0]) < 0.9 else [0, 1.0, 0])
    a /= np.linalg.norm(a)
    n = np.cos(p["psi"]) * a + np.sin(p["psi"]) * np.cross(u, a)     # the torch side, body frame
    nw, uw = Rb @ n, Rb @ u
    Lm = L / 1000.0
    shift = -nw * (Lm ** 2 / 2) * 1000.0                              # [mm per 1/m]
    rot = np.cross(uw, -nw) * Lm                                      # [rad per 1/m]
    bow = shift + np.cross(rot, ctx.target - end)
    stretch = ctx.link_scale_feature(np.arange(len(ch.links)) == li)
    return np.array([bow, stretch])


def arc_draw(ctx, hw, rng):
    D = rng.uniform(*FOREARM.get(ctx.chain.name, ("", (80.0, 120.0)))[1]) / 1000.0
    cte = float(hw["material"]["cte"])
    return {"tau_s": 60 * rng.uniform(10.0, 25.0), "psi": rng.uniform(0, 2 * np.pi),
            "amp": [cte * rng.uniform(2.0, 5.0) / D, cte * rng.uniform(3.0, 8.0)]}


def arc_features(p, ctx, hw):
    if ctx.chain.name not in FOREARM:
        return np.zeros((2, len(ctx.q), 3))
    return bow_parts(p, ctx) * arc_node(p, ctx.session)[None, :, None]


def arc_apply(p, ctx, hw):
    return _amp_apply(p["amp"], arc_features(p, ctx, hw))
