"""Set ZK thermal effects (new physics, not in sets A-ZJ): a cobot's link tubes warmed at their ends by the servo
drives built into its joint modules, whose inverters heat while the servo is on and whose logic boards keep some heat
in the pauses; and tool_changer's telescopic ram warmed by the friction of its wiper seals and guide pads as it
strokes. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* joint drive boards (``drive_board_heat``): cobots carry their servo amplifiers inside the joint modules (the UR
  arms: Universal Robots, *UR10 user manual*, joint modules with built-in electronics, as recalled); an inverter's
  conduction and switching losses (Mohan, Undeland & Robbins, *Power Electronics*, 3rd ed., 2003, ch. 7) and the
  boards' idle losses, some 5-15 W a joint, heat the joint housings while the servo is on, less (0.3-0.6 of it, the
  logic alone) with the servo off in the pauses, and a little more in production (1.0-1.3: the motors' currents);
  the housing and the tube ends it conducts into are a lumped node (tau 20-40 min, 0-30 % warm at the start;
  Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) that lengthens the upper arm and the forearm by
  CTE f L dT, f 0.4-0.7 of each tube warmed, dT 15-30 K at full warming (joint housings at 40-50 degC, assumed).
  Unlike set A's drive heat (the motors' copper and the gears' friction, following load and motion), set ZE's
  holding heat (the holding current's copper loss) or set H's tracker warm-up (the instrument), the heat is the
  electronics', set by the servo's state. Driven by the servo-on time, the production and the pauses (the time stamps
  and gaps hold them); the temperature is not logged. The true structure: two columns (upper arm, forearm: each
  tube's stretch times the node), amplitudes CTE f dT. ur10 only (its drives sit in the joints).
* ram wipers (``ram_wiper_heat``): tool_changer's telescopic ram (a steel tube) slides through wiper seals and polymer
  guide pads whose friction heats its surface as it strokes (sliding-contact heating: Blok / Archard flash and bulk
  temperatures, Bhushan, *Introduction to Tribology*, 2nd ed., 2013, ch. 6; seal friction: Mueller & Nau, *Fluid
  Sealing Technology*, 1998); the heated length L_r 700-900 mm behind the pads (a lumped node, tau 10-25 min, cooling
  in the dwells and pauses) grows by CTE L_r dT and carries the wrist and the target along the ram. Each measuring
  move adds kappa |dq4| / stroke (kappa 0.03-0.10 of the production's warming per full stroke); production relaxes the
  node towards 1 (continuous stroking), pauses towards 0; dT 15-35 K at full warming (assumed). Unlike set F's
  ball-screw growth (the screw, read through the nut) or set ZI's motion cooling (the air the links move through), the
  heat is the sliding friction of the ram's own seals and follows its stroke travel. Driven by the stroke history,
  the production and the pauses (logged as q4, time stamps and gaps). The true structure: one column (the ram's
  growth along its axis per unit node), amplitude CTE L_r dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution
from sim2real_indep.effects_zj_thermal import _relax, gap_node

HOT_LINKS = {"ur10": ("a2", "a3")}
STROKE_MM = 500.0   # tool_changer's telescopic stroke (its robot file's limits)


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- drive boards
def board_node(p, session):
    """(P,) the joint modules' warming per unit: 1 servo on, w_prod in production, w_pause in the pauses."""
    return gap_node(session, p["T0"], p["tau_s"], 1.0, p["w_prod"], p["w_pause"])


def hot_links(chain):
    names = HOT_LINKS.get(chain.name, ())
    return [chain.link_names.index(n) for n in names if n in chain.link_names]


def board_draw(ctx, hw, rng):
    links = hot_links(ctx.chain)
    p = {"tau_s": 60 * rng.uniform(20.0, 40.0), "T0": rng.uniform(0.0, 0.3), "w_prod": rng.uniform(1.0, 1.3),
         "w_pause": rng.uniform(0.3, 0.6)}
    frac, dT = rng.uniform(0.4, 0.7, len(links)), rng.uniform(15.0, 30.0, len(links))
    p["amp"] = (float(hw["material"]["cte"]) * frac * dT).tolist()
    return p


def board_features(p, ctx, hw):
    T = board_node(p, ctx.session)
    L = len(ctx.chain.links)
    return np.array([ctx.link_scale_feature(np.arange(L) == li) * T[:, None] for li in hot_links(ctx.chain)])


def board_apply(p, ctx, hw):
    return _amp_apply(p["amp"], board_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ram wipers
def ram_node(p, session, q4):
    """(P,) the ram's warming per unit: each move adds kappa |dq4| / stroke, production relaxes it towards 1, pauses
    and dwells towards 0, with tau."""
    T = np.empty(len(q4))
    x = T[0] = p["T0"]
    for k in range(1, len(q4)):
        dt = session.time_s[k] - session.time_s[k - 1]
        g = abs(session.gap_s[k])
        if session.gap_s[k] != 0:
            x = _relax(x, 1.0 if session.gap_s[k] > 0 else 0.0, 1 / p["tau_s"], g)
        x = _relax(x, 0.0, 1 / p["tau_s"], dt - g) + p["kappa"] * abs(q4[k] - q4[k - 1]) / STROKE_MM
        T[k] = x
    return T


def ram_draw(ctx, hw, rng):
    p = {"tau_s": 60 * rng.uniform(10.0, 25.0), "T0": rng.uniform(0.0, 0.3), "kappa": rng.uniform(0.03, 0.10)}
    p["amp"] = float(hw["material"]["cte"]) * rng.uniform(700.0, 900.0) * rng.uniform(15.0, 35.0)  # [mm]
    return p


def ram_features(p, ctx, hw):
    j = 3  # the telescopic stage
    if ctx.chain.revolute[j]:
        return np.zeros((1, len(ctx.q), 3))
    return ctx.joint_feature(j, ram_node(p, ctx.session, ctx.q[:, j]))[None]


def ram_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], ram_features(p, ctx, hw))
