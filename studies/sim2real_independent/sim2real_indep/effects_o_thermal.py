"""Set O thermal effects (new physics, not in sets A-N): the hollow arm of an explosion-protected (pressurised)
robot cooled from inside by its purge air, hard during each pre-purge and gently under the leakage flow that follows;
and the links warmed by an infrared curing panel beside the cell, each by the irradiance at its own distance from the
panel, which the arm's poses change. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* purge air: pressurised enclosures (IEC 60079-2, "Ex p") are purged with several enclosure volumes of air before the
  equipment may be energised, and then kept at an overpressure by a leakage-compensation flow of a few per cent of the
  purge's; painting robots and the drives of machines in gassy tunnels carry such enclosures -- the joints' motor and
  gear housings, joined through the hollow arm (as recalled from makers' notes). In hot surroundings the purge air is
  cooled by vortex-tube coolers (their cold outlets 20-40 K below the supply, as recalled from makers' data), so a
  housing or a link takes heat into the cold air by forced convection (Dittus-Boelter; Incropera & DeWitt,
  *Fundamentals of Heat and Mass Transfer*, ch. 8) and settles 12-24 K below the hall under the purge's flow, 3-10 % of
  that under the leakage flow, through a lumped lag of 4-10 min (thin walls under forced flow); the air warms along the
  duct, a part at s from the base's inlet seeing exp(-s / lambda) of the deficit, lambda 3-6 m. The booth is opened
  between blocks (2-3 blocks, pauses of 15-40 min): the purge stops and the arm drifts back towards the hall's air, and
  a pre-purge of 10-20 min precedes every block (the first before the session). The housings (150-250 / 250-350 mm
  along the main axes, 100-150 / 120-200 mm along the wrist's, kr16_like / tool_changer; none on a prismatic axis) and
  the links of 150 mm or more shorten by alpha dT, and the cold jet from the inlet on the base's rear wall bows the
  base towards it by alpha dT kappa H / D (kappa 0.2-0.4 of the deficit across a base of height 300-500 mm and depth
  300-450 mm: a beam with a linear temperature difference across its depth, Timoshenko & Goodier, *Theory of
  Elasticity*, ch. 14; assumed). kr16_like (an Ex-p painting variant) and tool_changer. The true structure: one column
  (the lag, the flows' ratio, the windows, lambda, the housings and the bow its shape). First drawn for the links alone,
  cooled 4-10 K by dryer air, the leakage flow 20-50 % of the purge's, lags of 10-25 min, pre-purges of 5-12 min
  between 4-7 blocks of a few minutes each (the deficit hardly changed within a block: absorbed on both arms), then
  6-16 K and 12-24 K with a weak leakage flow (up to 0.15 mm on tool_changer, under its noise in the set's 160-pose
  case, gain 11 %; that case moved to tool_changer and back to kr16_like).
* infrared panel: short-wave IR curing and preheating panels irradiate some 5-12 kW/m^2 at 0.5 m, falling as (r0 / r)^2
  beyond their own size (a point source; Modest, *Radiative Heat Transfer*, 3rd ed., 2013, ch. 4 on view factors);
  a painted link of diameter D absorbs a_s E D per length (a_s 0.3-0.6 for light paints in the near infrared) and
  loses h pi D (h 8-12 W/m^2 K, natural convection and radiation), settling at a_s E / (pi h) above the air through a
  lumped lag of 8-25 min (thin-walled tubes; Incropera & DeWitt, ch. 5). The panel stands 0.7-1.5 m from the base at
  a height of 0.3-1.2 m (first 1.0-2.0 m: the set's ur10 case gained 15 %, the mount model at 1.18x) and is switched
  on 10-30 % into the session (first 10-40 %) and left on (a curing cell warming up while the arm is measured, as set
  N's heater); each link's input is the irradiance at its midpoint at each pose (not closer
  than 0.3 m), held until the next pose. Links of 200 mm or more, a factor 0.7-1.3 per link for its paint and shading
  (assumed). The true structure: a column per link (its lag and its distances the shape).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_m_joint import block_index

Z = np.array([0.0, 0.0, 1.0])


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def link_mask(ctx, li):
    return np.arange(len(ctx.chain.links)) == li


# -------------------------------------------------------------------------------------------------- purge air
PURGE_ARMS = {"kr16_like", "tool_changer"}
PURGE_MIN_MM = 150.0
#: per arm: the joint housings' length along their axes [mm], main axes and wrist (assumed; none for a prismatic axis)
HOUSING_MM = {"kr16_like": ((150.0, 250.0), (100.0, 150.0)), "tool_changer": ((250.0, 350.0), (120.0, 200.0))}


def purge_draw(ctx, hw, rng):
    if ctx.chain.name not in PURGE_ARMS:
        return {}
    ch = ctx.chain
    length = np.linalg.norm(ch.links, axis=1)
    s_link = np.cumsum(length) - length / 2                             # along the duct from the base's inlet
    s_joint = np.array([length[ch.link_body <= j].sum() for j in range(ch.n)])
    (m0, m1), (w0, w1) = HOUSING_MM[ch.name]
    h = np.where(np.arange(ch.n) < 3, rng.uniform(m0, m1, ch.n), rng.uniform(w0, w1, ch.n)) * ch.revolute
    lam, az = rng.uniform(3000.0, 6000.0), rng.uniform(0, 2 * np.pi)
    return {"links": [int(i) for i in np.flatnonzero(length >= PURGE_MIN_MM)], "w": np.exp(-s_link / lam),
            "h_mm": h * np.exp(-s_joint / lam), "dT_K": rng.uniform(12.0, 24.0), "r_low": rng.uniform(0.03, 0.1),
            "tau_s": rng.uniform(4.0, 10.0) * 60, "t_pp_s": rng.uniform(10.0, 20.0) * 60,
            "e_in": np.array([np.cos(az), np.sin(az), 0.0]),
            "bow": rng.uniform(0.2, 0.4) * rng.uniform(300.0, 500.0) / rng.uniform(300.0, 450.0)}


def purge_windows(p, s):
    """Pre-purge windows and block runs [(start, end)] [s] of the session ``s``."""
    blk = block_index(s)
    pre, run = [], []
    for b in range(int(blk[-1]) + 1):
        idx = np.flatnonzero(blk == b)
        k = idx[0]
        start = s.time_s[0] - s.dwell_s[0] - s.move_s[0] if k == 0 else s.time_s[k - 1] + abs(s.gap_s[k])
        pre.append((start - p["t_pp_s"], start))
        run.append((start, s.time_s[idx[-1]]))
    return pre, run


def purge_signal(p, ctx):
    """The links' temperature deficit (P,) per K of the pre-purge's: the exact lag of the flows' schedule (1 in the
    pre-purges, r_low in the blocks, none in the pauses), from the hall's air before the first pre-purge."""
    s = ctx.session
    pre, run = purge_windows(p, s)
    edges = np.unique(np.r_[s.time_s, np.ravel(pre), np.ravel(run)])
    edges = edges[edges >= pre[0][0]]

    def u(t):
        if any(a <= t < b for a, b in pre):
            return 1.0
        return p["r_low"] if any(a <= t <= b for a, b in run) else 0.0

    x, at = 0.0, {}
    for a, b in zip(edges[:-1], edges[1:]):
        ui = u(0.5 * (a + b))
        x = ui + (x - ui) * np.exp(-(b - a) / p["tau_s"])
        at[b] = x
    return np.array([at.get(t, 0.0) for t in s.time_s])


def purge_shape(p, ctx):
    """(P, 3): the target's displacement per unit strain at the full deficit: the joint housings shortening along their
    axes, the links shortening, the base bowing towards the inlet (kappa H / D of the strain)."""
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    shape = -np.einsum("j,pji->pi", p["h_mm"], w)
    shape = shape - sum(p["w"][li] * ctx.link_scale_feature(link_mask(ctx, li)) for li in p["links"])
    return shape + p["bow"] * np.cross(np.cross(Z, p["e_in"]), ctx.target)


def purge_part(p, ctx):
    return purge_shape(p, ctx) * purge_signal(p, ctx)[:, None]


def purge_apply(p, ctx, hw):
    return Contribution(displace=hw["material"]["cte"] * p["dT_K"] * purge_part(p, ctx) if p else None)


def purge_features(p, ctx, hw):
    return purge_part(p, ctx)[None] if p else _empty(ctx)


# ---------------------------------------------------------------------------------------------- infrared panel
IR_MIN_MM, R0_MM, R_NEAR_MM = 200.0, 500.0, 300.0


def ir_draw(ctx, hw, rng):
    length = np.linalg.norm(ctx.chain.links, axis=1)
    links = [int(i) for i in np.flatnonzero(length >= IR_MIN_MM)]
    az = rng.uniform(0, 2 * np.pi)
    t = ctx.session.time_s
    k_on = int(np.argmin(np.abs(t - (t[0] + rng.uniform(0.1, 0.3) * (t[-1] - t[0])))))
    return {"links": links, "lamp_mm": np.r_[rng.uniform(700, 1500) * np.array([np.cos(az), np.sin(az)]),
                                             rng.uniform(300, 1200)],
            "E0_W_m2": rng.uniform(5e3, 12e3), "a_s": rng.uniform(0.3, 0.6), "h": rng.uniform(8.0, 12.0),
            "f": rng.uniform(0.7, 1.3, len(links)), "tau_s": rng.uniform(8.0, 25.0, len(links)) * 60, "k_on": k_on}


def ir_inputs(p, ctx):
    """(m, P): each link's irradiance at its midpoint per E0, (r0 / r)^2, from the panel's switching on."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    ch = ctx.chain
    start = np.cumsum(ch.links, axis=0) - ch.links
    on = (np.arange(len(ctx.q)) >= p["k_on"]).astype(float)
    out = []
    for li in p["links"]:
        b = ch.link_body[li]
        mid = np.einsum("pij,j->pi", R[:, b], start[li] + ch.links[li] / 2) + t[:, b]
        r = np.maximum(np.linalg.norm(mid - p["lamp_mm"], axis=1), R_NEAR_MM)
        out.append(on * (R0_MM / r) ** 2)
    return np.array(out)


def ir_rise(p, ctx):
    """(m, P): the links' lagged rises per K of their settled rise at r0 (the input held until the next pose)."""
    u = ir_inputs(p, ctx)
    t = ctx.session.time_s
    return np.array([ph.first_order_zoh(t, ui, tau) for ui, tau in zip(u, p["tau_s"])])


def ir_amplitudes(p, hw):
    """Strain per unit of :func:`ir_rise` of each link: alpha a_s E0 f / (pi h)."""
    return hw["material"]["cte"] * p["a_s"] * p["E0_W_m2"] * p["f"] / (np.pi * p["h"])


def ir_apply(p, ctx, hw):
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    strain[:, p["links"]] = (ir_amplitudes(p, hw)[:, None] * ir_rise(p, ctx)).T
    return Contribution(strain=strain)


def ir_features(p, ctx, hw):
    x = ir_rise(p, ctx)
    return np.array([ctx.link_scale_feature(link_mask(ctx, li)) * xi[:, None] for li, xi in zip(p["links"], x)])
