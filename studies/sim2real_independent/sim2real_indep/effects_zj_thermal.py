"""Set ZJ thermal effects (new physics, not in sets A-ZI): the main axes' bearings heated by a stray welding current
that returns through the arm while the cell welds between the blocks; and a tool bracket heated by the convective
plume of the hot moulding it carries, only while the tool points down so that the bracket stands in the plume. Also
the lumped warm-up node of the joint modules' electronics that :mod:`effects_zj_joint`'s torque-sensor drift follows.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* stray welding current: an arc-welding cell whose return clamp sits on the fixture while the fixture, the robot's
  base and the torch body are tied together by a failed torch insulation or a missing ground strap lets part of the
  welding current (hundreds of A at 40-70 % duty) return through the arm: through the rolling elements and the grease
  film of the main bearings, whose contact resistance (mOhm) dissipates R I^2 -- tens of W per bearing -- while the
  arc burns (Lincoln Electric / AWS guidance on "stray welding current" and robot bearing damage, as recalled;
  electrical bearing damage: Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. on electric current;
  SKF, *Bearing damage and failure analysis*, 2017, electrical erosion). Each of axes 1-3's joint housings is a lumped
  node (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) heated in the production between the
  blocks (welding), cooling through the measuring blocks and the pauses, tau 8-20 min, starting 20-80 % warm (the cell
  welded before the session); the housing between its fixed bearing and the output grows by CTE L_h dT along the
  joint's axis and carries the distal arm with it (L_h 120-200 / 200-350 / 250-400 mm on ur10 / kr16_like /
  tool_changer, dT 15-40 K at the end of a long run, the fixed end either side: assumed). Unlike set A's drive heat,
  set I's housing growth or set ZE's holding heat (the motors' losses), the heat is the welding current's in the
  bearings and follows the welding, not the arm's motion or load. Driven by the production schedule (the time stamps
  and the gaps hold it); the current is not logged. The true structure: one column per axis (the shift along its axis
  per unit of the node), amplitudes CTE L_h dT.
* hot part's plume: a part taken hot from a moulding or casting machine (150-250 degC) hangs below a 450 mm aluminium
  bracket along the tool's z that carries the gripper and the target; the part's natural-convection plume rises
  vertically (a thermal plume over a heated body: Morton, Taylor & Turner, Proc. R. Soc. A 234, 1956; Gebhart et al.,
  *Buoyancy-Induced Flows and Transport*, 1988, ch. 3) and bathes the bracket only while the tool points down, fully
  within 25-50 deg of the vertical, not at all beyond a cone 30-40 deg wider. The bracket (a folded 1-1.5 mm sheet) is
  a lumped node (tau_b 20-60 s, rho c t / 2h with h some 30 W/m^2 K in the plume) heated by the plume in proportion to
  the part's excess temperature, which falls as the part cools (tau_p 10-30 min, a new part at each block's start),
  each pose's attitude held over its move and dwell; it grows by CTE L dT, dT 40-80 K if the plume of a fresh part
  bathed it continuously (the plume's excess 0.3-0.5 m above such a part; assumed). (First a 3-5 mm bracket, tau_b 3-8
  min, then 1.5-4 min: it averaged the attitudes away, 0.04-0.09 mm on kr16_like, absorbed or 11 % with the link model
  at 1.10x; on tool_changer, whose tool's z points up or sideways over its range, the plume misses the bracket: the
  kind is not used there.) Unlike set L's hot parts (heat conducted through the fingers' contact, whatever the
  attitude), set W's cooling part (the part's own shrinkage) or set ZI's thermosyphon (a cooling that switches with
  the forearm's attitude), the heating switches with the tool's attitude. Driven by the tool's attitude, the payload
  (a part per block) and the time (logged); the part's temperature is not. The true structure: one column, amplitude
  CTE L dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_zi_body import _block_starts

BRACKET_MM = 450.0          # the plume bracket along the tool's z, carrying the target at its end
HOUSING_MM = {"ur10": (120.0, 200.0), "kr16_like": (200.0, 350.0), "tool_changer": (250.0, 400.0)}


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _relax(x, target, rate, dt):
    return target + (x - target) * np.exp(-max(dt, 0.0) * rate)


def gap_node(session, T0, tau_s, heat_block, heat_prod, heat_pause=0.0):
    """(P,) a first-order node relaxing (time constant tau_s) towards ``heat_block`` while the poses are measured,
    ``heat_prod`` in the production between blocks (gap_s > 0) and ``heat_pause`` in the pauses (gap_s < 0)."""
    T = np.empty(len(session.time_s))
    x = T[0] = T0
    for k in range(1, len(T)):
        dt = session.time_s[k] - session.time_s[k - 1]
        g = abs(session.gap_s[k])
        if session.gap_s[k] != 0:
            x = _relax(x, heat_prod if session.gap_s[k] > 0 else heat_pause, 1 / tau_s, g)
        x = _relax(x, heat_block, 1 / tau_s, dt - g)
        T[k] = x
    return T


# ---------------------------------------------------------------------------------------------------- stray current
def weld_node(p, session):
    """(P,) the housings' rise per unit dT: heated by the welding between the blocks, cooling otherwise."""
    return gap_node(session, p["T0"], p["tau_s"], 0.0, 1.0, 0.0)


def weld_joints(chain):
    return [j for j in range(min(3, chain.n)) if chain.revolute[j]]


def weld_draw(ctx, hw, rng):
    js = weld_joints(ctx.chain)
    lo, hi = HOUSING_MM.get(ctx.chain.name, HOUSING_MM["kr16_like"])
    L = rng.uniform(lo, hi, len(js))
    dT = rng.uniform(15.0, 40.0, len(js))
    sign = rng.choice([-1.0, 1.0], len(js))
    p = {"T0": rng.uniform(0.2, 0.8), "tau_s": 60 * rng.uniform(8.0, 20.0), "L_mm": L.tolist(), "dT_K": dT.tolist()}
    p["amp"] = (sign * float(hw["material"]["cte"]) * L * dT).tolist()
    return p


def weld_features(p, ctx, hw):
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    T = weld_node(p, ctx.session)
    return np.array([w[:, j] * T[:, None] for j in weld_joints(ctx.chain)])


def weld_apply(p, ctx, hw):
    return _amp_apply(p["amp"], weld_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- plume bracket
def tool_frame(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt


def plume_share(p, Rt):
    """(P,) the share of the plume on the bracket: 1 with the tool's z within ``full_deg`` of straight down, 0 beyond
    ``none_deg``, linear in the cosine between."""
    down = -Rt[:, 2, 2]  # cosine of the tool z's angle from straight down
    c1, c0 = np.cos(np.deg2rad(p["full_deg"])), np.cos(np.deg2rad(p["none_deg"]))
    return np.clip((down - c0) / (c1 - c0), 0.0, 1.0)


def plume_temperature(p, ctx):
    """(P,) the bracket's rise per unit dT: each block's fresh part (excess 1 at the block's first pose, cooling with
    tau_p) heats it in proportion to the plume's share; between the blocks (no part) it cools."""
    s = ctx.session
    w = plume_share(p, tool_frame(ctx))
    start = _block_starts(s)
    T = np.empty(len(w))
    x = p["T0"]
    for k in range(len(w)):
        if k > 0:
            dt = s.time_s[k] - s.time_s[k - 1]
            g = abs(s.gap_s[k])
            x = _relax(x, 0.0, 1 / p["tau_b_s"], g)
            if start[k] != k:  # the part of this block still hanging below the bracket during the move and dwell
                age = s.time_s[k] - s.time_s[start[k]]
                heat = w[k] * np.exp(-age / p["tau_p_s"])
                x = _relax(x, heat, 1 / p["tau_b_s"], dt - g)
            else:
                x = _relax(x, 0.0, 1 / p["tau_b_s"], dt - g)
        T[k] = x
    return T


def plume_draw(ctx, hw, rng):
    dT = rng.uniform(40.0, 80.0)
    p = {"full_deg": rng.uniform(25.0, 50.0), "tau_b_s": 60 * rng.uniform(0.3, 1.0),
         "tau_p_s": 60 * rng.uniform(10.0, 30.0), "T0": 0.0, "dT_K": dT}
    p["none_deg"] = p["full_deg"] + rng.uniform(30.0, 40.0)
    p["amp"] = float(hw["material"]["cte"]) * dT
    return p


def plume_features(p, ctx, hw):
    Rt = tool_frame(ctx)
    return (Rt[:, :, 2] * (BRACKET_MM * plume_temperature(p, ctx))[:, None])[None]


def plume_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], plume_features(p, ctx, hw))
