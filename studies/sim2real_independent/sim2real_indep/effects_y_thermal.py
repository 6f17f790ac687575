"""Set Y thermal effects (new physics, not in sets A-X): the upper arm bowed by the lamps of a vision system clamped to
one side of it, which are lit through the inspection cycles and the blocks after them; and the steel pedestal under the
arm bowed and lengthened by the exhaust air of the drive cabinet beside it, which blows while the drives work in the
production between the blocks. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* vision lamp: machine-vision lights (LED bars or halogen spots of tens of W, most of it heat) on a bracket clamped to
  one side of the upper arm are lit while an inspection program runs: the production between the blocks alternates
  between inspection cycles and other work, and the lights stay lit through the block that follows an inspection cycle
  -- every second gap and block of the session (which ones is the program's choice; not logged). The clamp conducts the
  heat into that side of the tube: a lumped, first-order warming while lit and cooling while dark (Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 5), tau 5-12 min (the wall near the clamp), to a mean rise of 2-5 K and
  a difference of 3-8 K across the tube's diameter D (80-110 / 150-220 / 200-300 mm on ur10 / kr16_like / tool_changer).
  A temperature difference dT across a beam of depth D bends it to the uniform curvature alpha dT / D (thermal bowing;
  Timoshenko & Goodier, *Theory of Elasticity*, thermal stress in beams; Boley & Weiner, *Theory of Thermal Stresses*,
  1960), away from the warm side: the elbow turns by kappa L and moves by kappa L^2 / 2; the mean rise lengthens the
  link by alpha dT_m. The bracket's side is drawn about the link. Unlike set X's induction heater (the forearm
  lengthening in every production gap) the lamps bow the upper arm in every second gap and block. The lamps' state is
  not logged. The true structure: two columns (the link's growth and its bow per unit curvature, times the lamp's
  temperature history per unit rise), amplitudes alpha dT_m and alpha dT / D.
* cabinet exhaust: the drive cabinet beside the arm blows its exhaust (its drives' and braking resistors' losses, a few
  hundred W while the arm works) at the arm's steel pedestal; the side facing the cabinet warms by a first-order lag
  while the drives work (the production between the blocks) and cools while the arm is measured (idle drives), tau 15-40
  min (Incropera & DeWitt, ch. 5), to a mean rise of 4-10 K and a difference of 4-10 K across its width D (250-400 mm).
  The pedestal (400-800 mm tall, steel: :mod:`hardware`'s CTE) lengthens by alpha dT_m H and bows away from the cabinet,
  turning its top (the arm's base) by kappa H and moving it by kappa H^2 / 2 (thermal bowing as above). Unlike set N's
  heated pads (elastomer pads under the base expanding) the steel pedestal bows, in the production gaps. The cabinet's
  heading is drawn; nothing of it is logged. The true structure: two columns (the base's rise and its bow, times the
  pedestal's temperature history per unit rise), amplitudes alpha dT_m H [mm] and kappa H [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_x_thermal import stray_temperature

STEEL_CTE = 11.7e-6


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- vision lamp
LAMP_D_MM = {"ur10": (80.0, 110.0), "kr16_like": (150.0, 220.0), "tool_changer": (200.0, 300.0)}


def upper_arm(chain):
    """Index of the upper arm: the longest link moved by joint 2 (body 2)."""
    body = np.asarray(chain.link_body)
    lengths = np.linalg.norm(chain.links, axis=1) * (body == 2)
    return int(np.argmax(lengths))


def lamp_on(p, session):
    """(P,) 1 in the inspection blocks (every second block, from the drawn parity)."""
    return (block_index(session) % 2 == p["parity"]).astype(float)


def lamp_temperature(p, session):
    """(P,) the upper arm's temperature per unit rise: warming towards 1 while the lamps are lit (the inspection cycles
    in the gap before an inspection block and that block), cooling otherwise (exact first-order steps; the first
    block, lit or not, from the session's start)."""
    tau, on = p["tau_s"], lamp_on(p, session)
    T, out = 0.0, np.zeros(len(session.time_s))
    prev = session.time_s[0] - session.move_s[0] - session.dwell_s[0]
    for k in range(len(out)):
        T = on[k] + (T - on[k]) * np.exp(-(session.time_s[k] - prev) / tau)
        out[k], prev = T, session.time_s[k]
    return out


def link_bow(ctx, li, side):
    """(P, 3) the target's displacement per unit curvature [1/mm] of link ``li`` bowed away from ``side`` (unit vector
    across the link, home frame of its body)."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    b = int(ch.link_body[li])
    v = ch.links[li]
    L = np.linalg.norm(v)
    end = ch.links[:li + 1].sum(axis=0)
    a = np.cross(side, v / L)
    a_w, u_w = R[:, b] @ a, R[:, b] @ (v / L)
    end_w = np.einsum("pij,j->pi", R[:, b], end) + t[:, b]
    return L * np.cross(a_w, ctx.target - end_w) + L ** 2 / 2 * np.cross(a_w, u_w)


def lamp_side(chain, li, psi):
    """A unit vector across link ``li`` at angle ``psi`` about it (home frame)."""
    v = chain.links[li] / np.linalg.norm(chain.links[li])
    u = np.cross(v, [1.0, 0, 0] if abs(v[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return np.cos(psi) * u + np.sin(psi) * np.cross(v, u)


def lamp_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    dTm, dTg, D = rng.uniform(2.0, 5.0), rng.uniform(3.0, 8.0), rng.uniform(*LAMP_D_MM[ctx.chain.name])
    return {"parity": int(rng.integers(2)), "tau_s": 60.0 * rng.uniform(5.0, 12.0), "psi": rng.uniform(0, 2 * np.pi),
            "dT_m": dTm, "dT_g": dTg, "D_mm": D, "amp": np.array([cte * dTm, cte * dTg / D])}


def lamp_features(p, ctx, hw):
    li = upper_arm(ctx.chain)
    T = lamp_temperature(p, ctx.session)[:, None]
    grow = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li)
    bow = link_bow(ctx, li, lamp_side(ctx.chain, li, p["psi"]))
    return np.array([grow * T, bow * T])


def lamp_apply(p, ctx, hw):
    return _amp_apply(p["amp"], lamp_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------ cabinet exhaust
def exhaust_draw(ctx, hw, rng):
    H, D = rng.uniform(400.0, 800.0), rng.uniform(250.0, 400.0)
    dTm, dTg, psi = rng.uniform(4.0, 10.0), rng.uniform(4.0, 10.0), rng.uniform(0, 2 * np.pi)
    return {"H_mm": H, "D_mm": D, "dT_m": dTm, "dT_g": dTg, "psi": psi, "tau_s": 60.0 * rng.uniform(15.0, 40.0),
            "amp": np.array([STEEL_CTE * dTm * H, STEEL_CTE * dTg / D * H])}


def exhaust_features(p, ctx, hw):
    """(2, P, 3): the base's rise and its bow (per unit turn kappa H), times the pedestal's temperature history."""
    T = stray_temperature(p, ctx.session)[:, None]
    h = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])      # towards the cabinet
    a = np.cross(h, [0.0, 0.0, 1.0])
    rise = np.broadcast_to([0.0, 0.0, 1.0], ctx.target.shape)
    bow = np.cross(a, ctx.target) - p["H_mm"] / 2 * h
    return np.array([rise * T, bow * T])


def exhaust_apply(p, ctx, hw):
    return _amp_apply(p["amp"], exhaust_features(p, ctx, hw))
