"""Set ZE thermal effects (new physics, not in sets A-ZD): the links warmed by the copper loss of the motors of axes 2
and 3 holding the gravity torque at standstill (a heat input growing as the torque squared); and a tool head on a
phase-change (paraffin) heat sink whose bracket warms, halts while the wax melts, and warms again. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* holding heat: a servo motor holding a static load carries the current I = tau / (k_t i) and dissipates I^2 R
  (copper loss; Hughes & Drury, *Electric Motors and Drives*, 4th ed., 2013, ch. 9: the stalled motor's losses are the
  copper's), so the motors of axes 2 and 3, mounted on the upper arm and the forearm, heat their housings by the square
  of the torque they hold, pose by pose, and nothing while the brakes hold in the pauses (servo off). The link follows
  through a first-order lag of 5-15 min (Incropera & DeWitt, ch. 5, lumped capacitance: the motor's flange on a thin
  casting) and grows uniformly by alpha dT, dT 15-35 K at the largest torque held for long (a motor held near its
  continuous stall torque; first 6-20 K through 8-25 min: ZE12 moved 0.06 mm, a gain of 19 %, ZE21 was absorbed; at the final
  ranges kr16_like's thick steel castings still gained 11 % with the link model at 1.10x, so the holding heat is on
  tool_changer alone, ZE12). Unlike set A's heat (drive activity: the speed) or the ambient's,
  the heat follows the gravity load held at standstill. Driven by the pose, payload and time (logged) and the servo's
  state (the pauses, in the time stamps). The true structure: two columns (the upper arm's and the forearm's growth
  times their lagged tau^2), amplitudes alpha dT_j.
* PCM tool: a tool head (a laser-line sensor's electronics, 20-40 W) on an aluminium bracket carrying the target 450 mm
  along the tool's z (first 300 mm and a rise of 25-40 K: ZE05 on ur10 gained 19 %, the joint model at 1.23x), cooled by a paraffin phase-change heat sink (Mehling & Cabeza, *Heat and Cold Storage with PCM*,
  Springer, 2008, ch. 1; the enthalpy method: Voller, "Fast implicit finite-difference method for the analysis of phase
  change problems", Numer. Heat Transfer B 17, 1990): the lumped sink warms with time constant tau 5-12 min towards a
  rise T_inf 30-45 K, but halts at the wax's melting rise T_m 6-15 K until a latent store of 8-25 K (the latent heat
  over the sink's capacity) is melted, then warms on. Switched on 0-3 min before the first pose. Unlike sets D-ZD's
  single-lag or two-node tool heating (smooth curves), the growth halts on a plateau for the melt's duration. Driven by
  the time (logged) and the switch-on (not logged). The true structure: one column, amplitude alpha [1/K].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_za_thermal import forearm, lagged_source

PCM_MM = 450.0
PCM_CTE = 23e-6


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- holding heat
HOLD_JOINTS = (1, 2)


def upper_arm(chain):
    """Index of the upper arm: the longest link of body 2."""
    body = np.asarray(chain.link_body)
    return int(np.argmax(np.linalg.norm(chain.links, axis=1) * (body == 2)))


def holding_source(p, ctx, j):
    """A function of the time from the session's start [s]: the held tau_j^2 over its largest, 0 in the pauses."""
    s = ctx.session
    t = s.time_s - s.time_s[0]
    u = (ctx.loads[:, j] / p["tau_max"][HOLD_JOINTS.index(j)]) ** 2
    start = t - s.move_s - s.dwell_s                                  # each pose's move starts here
    paused = s.gap_s < 0

    def on(tt):
        k = np.clip(np.searchsorted(t, tt, side="left"), 0, len(t) - 1)
        return np.where(paused[k] & (tt < start[k]), 0.0, u[k])
    return on


def holding_temperature(p, ctx):
    """(2, P) the two links' rise at unit dT."""
    return np.array([lagged_source(ctx.session.time_s, holding_source(p, ctx, j), tau)
                     for j, tau in zip(HOLD_JOINTS, p["tau_s"])])


def holding_draw(ctx, hw, rng):
    cte = hw["material"]["cte"]
    p = {"tau_max": [float(np.abs(ctx.loads[:, j]).max()) for j in HOLD_JOINTS],
         "tau_s": list(60.0 * rng.uniform(5.0, 15.0, 2)), "dT_K": list(rng.uniform(15.0, 35.0, 2)), "cte": cte}
    p["amp"] = [cte * d for d in p["dT_K"]]
    return p


def holding_features(p, ctx, hw):
    T = holding_temperature(p, ctx)
    n = len(ctx.chain.links)
    links = [upper_arm(ctx.chain), forearm(ctx.chain)]
    return np.array([ctx.link_scale_feature(np.arange(n) == li) * T[k][:, None] for k, li in enumerate(links)])


def holding_apply(p, ctx, hw):
    return _amp_apply(p["amp"], holding_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- PCM tool
def pcm_temperature(p, t_s, step_s=2.0):
    """(P,) the bracket's rise [K] at times ``t_s`` from the session's start, by the enthalpy method: heat stored H
    (in K of sensible rise), dH/dt = (T_inf - T(H)) / tau, T(H) = H below T_m, T_m across the latent store, H - L after."""
    t = np.asarray(t_s, float) - t_s[0] + p["lead_s"]
    grid = np.arange(0.0, t[-1] + 2 * step_s, step_s)
    Tm, L, Tinf, tau = p["T_m"], p["L_K"], p["T_inf"], p["tau_s"]

    def temp(H):
        return np.where(H < Tm, H, np.where(H < Tm + L, Tm, H - L))
    H = np.zeros_like(grid)
    for k in range(1, len(grid)):
        H[k] = H[k - 1] + step_s * (Tinf - temp(H[k - 1])) / tau
    return np.interp(t, grid, temp(H))


def pcm_draw(ctx, hw, rng):
    return {"lead_s": 60.0 * rng.uniform(0.0, 3.0), "tau_s": 60.0 * rng.uniform(5.0, 12.0),
            "T_inf": rng.uniform(30.0, 45.0), "T_m": rng.uniform(6.0, 15.0), "L_K": rng.uniform(8.0, 25.0),
            "cte": PCM_CTE}


def pcm_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return (Rt[:, :, 2] * (PCM_MM * pcm_temperature(p, ctx.session.time_s))[:, None])[None]


def pcm_apply(p, ctx, hw):
    return _amp_apply([p["cte"]], pcm_features(p, ctx, hw))
