"""Set M thermal effects (new physics, not in sets A-L): a column of hot air rising from a heat source between the
laser tracker and the robot, which bends and delays the beams that pass through its flanks; and the hydraulic oil
warming through the production, so that the cylinders driving axes 2 and 3 grow between their pins at a held stroke.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* hot-air plume: the refractivity of air falls with its temperature, d(n - 1)/dT = -(n - 1)/T, about -0.93e-6 /K at 20
  degC (Edlen, "The refractive index of air", Metrologia 2, 1966; Ciddor, Appl. Opt. 35, 1996); a ray bends towards the
  denser (cooler) air, d^2 r / ds^2 = grad_perp n (the paraxial ray equation: Born & Wolf, *Principles of Optics*, ch.
  3), and its optical path is lengthened by the integral of n - 1. A laser tracker compensates the refractivity its
  weather station measures, not a local plume: a ray aimed along u0 that bends on its way reaches the target displaced
  across by int (D - s) grad_perp n ds, so the tracker reports the target shifted back by that and along the beam by int
  (n - n_station) ds (the tracker-side refraction error of Estler et al., "Large-scale metrology -- an update", CIRP
  Annals 51, 2002). The plume: a vertical Gaussian column, excess temperature 40-100 K on its axis, radius 0.1-0.25 m,
  from 0-600 mm above the base plane upward, its axis at 15-50 % of the way from the tracker to the working volume and
  up to 1.2 radii off the line (first 30-80 K, 0.1-0.3 m, 30-70 %: absorbed on ur10 in trial draws) (above a hydraulic
  power pack's oil cooler on a tunnel machine's back-up, a casting line's cooling conveyor, a curing oven's vent;
  assumed). A measurement effect: needs the tracker's frame (:data:`effects_m.AFTER_TRACKER`). All three arms.
* oil growth: a hydraulic power pack's oil warms through the production by its pump's and valves' throttling losses and
  cools with the pack idle or off -- one lumped node, 15-25 K above its start at the production's steady state, time
  constant 10-30 min (first 8-15 K and 20-60 min: absorbed in a trial draw; then 20-35 K: up to 2.6 mm), 20-40 % of the
  production heat while the arm is measured (pump on, valves closed), none in the pauses (pump off), the session
  starting 0-15 % warm (Merritt 1967, ch. 1 on heat generation; the lumped-capacitance model of Incropera & DeWitt, ch.
  5; assumed). A cylinder measuring its own stroke (an in-rod position transducer) and held at it grows between its pins
  with its steel barrel head and rod, alpha L_0 dT (L_0 the retracted pin-to-pin length, steel 11.7e-6 /K), turning the
  joint by dL / a through the lever of :func:`effects_m_joint.lever_draw`. tool_changer axes 2 and 3 (the hydraulic boom
  of :mod:`effects_m_joint`'s oil column).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import effects_f_joint as fj
from sim2real_indep.context import Contribution
from sim2real_indep.effects_m_joint import OIL, lever_draw

KAPPA = 0.93e-6          # -d(n - 1)/dT [1/K]
STEEL_CTE = 11.7e-6
EDGE_MM = 50.0           # the plume's lower edge's width


# ------------------------------------------------------------------------------------------------ hot plume
def plume_draw(ctx, hw, rng):
    t = ctx.target
    return {"dT_K": rng.uniform(40, 100), "w_mm": rng.uniform(100, 250), "along": rng.uniform(0.15, 0.5),
            "off": rng.uniform(-1.2, 1.2), "z_src_mm": rng.uniform(0, 600),
            "work_mm": np.array([np.median(t[:, 0]), np.median(t[:, 1])])}


def tracker_origin(hw):
    """The tracker's origin (3,) in the base frame (measured = R_f x + t_f)."""
    return -hw["tracker"]["R"].T @ hw["tracker"]["t"]


def plume_axis(p, hw):
    T = tracker_origin(hw)[:2]
    v = p["work_mm"] - T
    side = np.array([-v[1], v[0]]) / np.linalg.norm(v)
    return T + p["along"] * v + p["off"] * p["w_mm"] * side


def plume_part(p, ctx, hw, n=240):
    """Target displacement (P, 3) [mm] per K of the plume's excess temperature, as the tracker reports it: the beam's
    bend taken back and its optical path added along it (straight-ray integrals, midpoint rule over ``n`` steps)."""
    T = tracker_origin(hw)
    c = plume_axis(p, hw)
    X = ctx.target
    D = np.linalg.norm(X - T, axis=1)
    u = (X - T) / D[:, None]
    s = (np.arange(n) + 0.5) / n * D[:, None]                       # (P, n)
    r = T + s[..., None] * u[:, None, :]                             # (P, n, 3)
    dxy = r[..., :2] - c
    H = 1 / (1 + np.exp(-(r[..., 2] - p["z_src_mm"]) / EDGE_MM))
    nn = -KAPPA * np.exp(-np.sum(dxy ** 2, axis=-1) / p["w_mm"] ** 2) * H   # n - n_station per K
    grad = nn[..., None] * np.concatenate([-2 * dxy / p["w_mm"] ** 2, ((1 - H) / EDGE_MM)[..., None]], axis=-1)
    grad = grad - np.einsum("pni,pi->pn", grad, u)[..., None] * u[:, None, :]
    ds = (D / n)[:, None]
    bend = np.sum((D[:, None] - s)[..., None] * grad * ds[..., None], axis=1)
    path = np.sum(nn * ds, axis=1)
    return -bend + path[:, None] * u


def plume_apply(p, ctx, hw):
    return Contribution(displace=p["dT_K"] * plume_part(p, ctx, hw))


def plume_features(p, ctx, hw):
    return plume_part(p, ctx, hw)[None]


# ---------------------------------------------------------------------------------------------------- oil growth
def growth_draw(ctx, hw, rng):
    if ctx.chain.name not in OIL:
        return {}
    cyl = {}
    for j, (_, r1, r2, mid) in OIL[ctx.chain.name].items():
        lv = lever_draw(ctx, rng, j, r1, r2, mid)
        _, L, _ = fj.lever_state(lv, ctx.q[:, j])
        cyl[j] = {**lv, "L0_m": float(L.min()) - rng.uniform(0.02, 0.06)}
    return {"cyl": cyl, "rise_K": rng.uniform(15, 25), "tau_s": rng.uniform(10, 30) * 60,
            "idle": rng.uniform(0.2, 0.4), "x0": rng.uniform(0.0, 0.15)}


def oil_temperature(p, session):
    """The oil's rise (P,) [K] at the measurements: heated fully in production, by ``idle`` in the measurement's moves
    and dwells, not at all in the pauses; exact for the heat held over each segment."""
    dur = ct._segment_times(session)
    gap = np.repeat(session.gap_s, 3)
    u = np.where(np.arange(len(dur)) % 3 == 0, np.where(gap > 0, 1.0, 0.0), p["idle"])
    x, out = p["x0"], np.zeros(len(dur))
    for k, (dt, uk) in enumerate(zip(dur, u)):
        x = uk + (x - uk) * np.exp(-dt / p["tau_s"])
        out[k] = x
    return p["rise_K"] * out[2::3]


def growth_signals(p, ctx):
    """(joints, P) [rad per unit CTE]: s L_0 dT / a per cylinder."""
    dT = oil_temperature(p, ctx.session)
    out = []
    for j, c in p["cyl"].items():
        _, _, a = fj.lever_state(c, ctx.q[:, j])
        out.append(c["s"] * c["L0_m"] * dT / a)
    return np.array(out)


def growth_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, list(p["cyl"])] = STEEL_CTE * growth_signals(p, ctx).T
    return Contribution(dq=dq)


def growth_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["cyl"], growth_signals(p, ctx))])
