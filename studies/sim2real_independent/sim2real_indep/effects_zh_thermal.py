"""Set ZH thermal effects (new physics, not in sets A-ZG): a heated tool whose heat diffuses into the forearm from its
wrist end, the warmed length growing with the square root of the time; and a braking resistor on the pedestal that
the arm's lowering moves heat with the potential energy they give back. Same protocol as :mod:`effects_joint`.

Sources:

* wrist conduction: a heated tool (a hot-knife, hot-melt or soldering head whose flange runs dT0 15-40 K above the air)
  switched on 0-20 min before the session; its heat diffuses into the forearm's wall from the wrist end as into a
  semi-infinite rod whose end is held at dT0: T(x, t) = dT0 erfc(x / (2 sqrt(a t))), so the warmed wall's expansion is
  CTE dT0 integral erfc = CTE dT0 2 sqrt(a t / pi) (Carslaw & Jaeger, *Conduction of Heat in Solids*, 2nd ed., 1959,
  sec. 2.4), a an effective diffusivity 0.5-2e-5 m^2/s (a thin wall losing heat to the air and a steel / cast wrist
  housing between), the warmed length capped at the forearm's. Unlike the lumped lags of sets A-ZG (drive heat, tool
  heat, a bracket's first-order rise) the expansion follows the diffusion's sqrt(t) along the forearm alone. Driven by
  time (logged); the tool's heater is not. The true structure: one column, amplitude CTE dT0.
* regen resistor: a drive's DC bus takes back the energy of a load lowered under gravity and dumps it in a braking
  resistor (regenerative braking: Mohan, Undeland & Robbins, *Power Electronics*, 3rd ed., 2003, ch. 14, dynamic
  braking), here bolted to the arm's steel pedestal (height H 0.5-0.9 m); each move into a pose returns the fall of
  the arm's and the part's potential energy, max(-dE, 0), and the pedestal's heated web loses it to the air with a time
  constant tau 4-12 min (lumped capacitance): T_k = (T_{k-1} + max(-dE_k, 0)) exp(-(t_k - t_{k-1}) / tau), normalised to
  a peak rise of dT 15-40 K, lifting the base by CTE H dT. Unlike set Y's cabinet exhaust (the drives' losses blown at
  the pedestal while the arm works between the blocks) or the drive losses of sets A-ZG, the heat is the gravity
  energy of the measured moves themselves. Driven by the pose sequence and time (logged); the resistor is not. The true
  structure: one column, amplitude CTE dT.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep.context import Contribution

CTE_AL, CTE_STEEL = 23e-6, 12e-6


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def forearm_index(chain):
    """The longest link after joint 3 (the forearm) of the chain."""
    body = np.asarray(chain.link_body)
    norms = np.linalg.norm(chain.links, axis=1) * (body >= 3)
    return int(np.argmax(norms))


# ---------------------------------------------------------------------------------------------------- wrist conduction
def conduction_length(p, t_s, L_mm):
    """(P,) the warmed length [mm]: 2 sqrt(a t / pi), t since the heater came on, capped at the forearm's length."""
    t = np.asarray(t_s, float) - t_s[0] + p["t_on_s"]
    return np.minimum(2.0 * np.sqrt(p["a_m2s"] * t / np.pi) * 1000.0, L_mm)


def conduction_draw(ctx, hw, rng):
    dT = rng.uniform(30.0, 60.0)
    cte = float(hw["material"]["cte"])  # the arm's own material
    return {"t_on_s": 60.0 * rng.uniform(0.0, 20.0), "a_m2s": rng.uniform(0.5e-5, 2e-5), "dT_K": dT, "amp": cte * dT}


def conduction_features(p, ctx, hw):
    li = forearm_index(ctx.chain)
    L = float(np.linalg.norm(ctx.chain.links[li]))
    u = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li) / L
    return (u * conduction_length(p, ctx.session.time_s, L)[:, None])[None]


def conduction_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], conduction_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- regen resistor
def potential_energy(ctx):
    """(P,) the arm's and part's potential energy [J] above the base."""
    m, pos, _ = ctx.mass_state
    return (m * pos[:, :, 2] / 1000.0).sum(axis=1) * 9.81


def resistor_temperature(p, E, time_s):
    """(P,) the pedestal's rise per unit peak: each lowering move's energy decayed to each pose, over its max."""
    t = np.asarray(time_s, float)
    heat = np.maximum(-np.diff(np.asarray(E, float), prepend=E[0]), 0.0)
    T = np.zeros(len(t))
    for k in range(1, len(t)):
        T[k] = (T[k - 1] + heat[k]) * np.exp(-(t[k] - t[k - 1]) / p["tau_s"])
    return T / max(T.max(), 1e-12)


def resistor_draw(ctx, hw, rng):
    dT = rng.uniform(15.0, 40.0)
    return {"tau_s": 60.0 * rng.uniform(4.0, 12.0), "H_mm": rng.uniform(500.0, 900.0), "dT_K": dT,
            "amp": CTE_STEEL * dT}


def resistor_features(p, ctx, hw):
    T = resistor_temperature(p, potential_energy(ctx), ctx.session.time_s)
    out = np.zeros((len(T), 3))
    out[:, 2] = p["H_mm"] * T
    return out[None]


def resistor_apply(p, ctx, hw):
    return _amp_apply([p["amp"]], resistor_features(p, ctx, hw))
