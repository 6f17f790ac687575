"""Effects on the robot's bodies: activity heat and ambient temperature (link expansion), sag of the link tubes,
the compliant base mount. Same protocol as :mod:`effects_joint`. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature

GRAVITY_N = kin.G * np.array([0.0, 0.0, -1.0])  # force per kg [N/kg]


# ------------------------------------------------------------------------------------------- activity heat
def _powers(ctx, hw, rng_extra):
    """Heat [W] of each drive in each segment: (P, 3, n) for gap / move / dwell before each measurement."""
    s, tau = ctx.session, ctx.loads
    P = len(s.q)
    prev = np.vstack([tau[:1], tau[:-1]])
    move_t2 = (prev ** 2 + tau ** 2) / 2
    ex_t2 = (tau ** 2).mean(axis=0) * rng_extra  # exercise: the poses' mean square load, plus acceleration
    out = np.zeros((P, 3, ctx.chain.n))
    for j, d in enumerate(hw["drives"]):
        unit = 1.0 if ctx.chain.kinds[j] == "R" else 1e-3  # prismatic speeds mm/s -> m/s
        loss = lambda v, t2: ph.motor_losses(v, np.sqrt(t2), d["T_rated"], d["P_cu_rated_W"], d["friction_frac"])
        out[:, 0, j] = np.where(s.gap_s > 0, loss(unit * s.exercise_speed[j], ex_t2[j]), 0.0)  # pause: servo off
        out[:, 1, j] = loss(unit * s.speed[:, j], move_t2[:, j])
        out[:, 2, j] = loss(0.0, tau[:, j] ** 2)
    return out


def heat_draw(ctx, hw, rng):
    """Per link body: heated by its proximal and distal drives (weights U(0.3, 1)) through a first-order lag of
    10-60 min, rising 10-30 K at its drives' rated copper loss (assumption: joint housings of robots in continuous
    service run 10-30 K above the shop); exercise loads = the session's mean square load x U(1.2, 2)
    (acceleration). Cold start at the first pose."""
    n = ctx.chain.n
    bodies = sorted(set(int(b) for b in ctx.chain.link_body if b >= 1))
    w = {b: (rng.uniform(0.3, 1.0), rng.uniform(0.3, 1.0) if b < n else 0.0) for b in bodies}
    # thermal resistance: the body warms by dT_rated at its drives' rated copper loss
    dT_rated = {b: rng.uniform(10.0, 30.0) for b in bodies}
    p_rated = {b: w[b][0] * hw["drives"][b - 1]["P_cu_rated_W"]
               + (w[b][1] * hw["drives"][b]["P_cu_rated_W"] if b < n else 0.0) for b in bodies}
    return {"bodies": bodies, "tau_s": {b: rng.uniform(10, 60) * 60 for b in bodies},
            "R_th": {b: dT_rated[b] / p_rated[b] for b in bodies}, "dT_rated_K": dT_rated, "w": w,
            "accel": rng.uniform(1.2, 2.0, n), "cte": hw["material"]["cte"]}


def heat_temperatures(params, ctx, hw):
    """Temperature rise (P, bodies) [K] of each heated body at the measurement instants (cold start)."""
    s = ctx.session
    pw = _powers(ctx, hw, params["accel"])
    dur = np.stack([np.abs(s.gap_s), s.move_s, s.dwell_s], axis=1).ravel()
    t = np.r_[0.0, np.cumsum(dur)]
    out = []
    for b in params["bodies"]:
        wa, wb = params["w"][b]
        p_body = wa * pw[:, :, b - 1] + (wb * pw[:, :, b] if b < ctx.chain.n else 0.0)
        u = params["R_th"][b] * np.r_[p_body.ravel(), 0.0]
        x = ph.first_order_zoh(t, u, params["tau_s"][b], 0.0)
        out.append(x[3::3])
    return np.array(out).T


def _body_links(ctx, b):
    return ctx.chain.link_body == b


def heat_apply(params, ctx, hw):
    dT = heat_temperatures(params, ctx, hw)
    strain = np.zeros((len(ctx.q), len(ctx.chain.links)))
    for k, b in enumerate(params["bodies"]):
        strain[:, _body_links(ctx, b)] += params["cte"] * dT[:, k:k + 1]
    return Contribution(strain=strain)


def heat_features(params, ctx, hw):
    dT = heat_temperatures(params, ctx, hw)
    return np.array([ctx.link_scale_feature(_body_links(ctx, b)) * dT[:, k:k + 1]
                     for k, b in enumerate(params["bodies"])])


# ------------------------------------------------------------------------------------------ ambient thermal
def ambient_draw(ctx, hw, rng):
    return {"tau_s": rng.uniform(20, 120) * 60, "cte": hw["material"]["cte"]}


def structure_temperature(params, ctx):
    """Structure temperature change (P,) [K] since the session start: the air lagged by tau (lumped body)."""
    s = ctx.session
    grid = np.arange(s.time_s[0], s.time_s[-1] + 60.0, 60.0)
    x = ph.first_order_foh(grid, air_temperature(s, grid), params["tau_s"])
    return np.interp(s.time_s, grid, x) - x[0]


def ambient_apply(params, ctx, hw):
    dT = structure_temperature(params, ctx)
    return Contribution(strain=np.outer(params["cte"] * dT, np.ones(len(ctx.chain.links))))


def ambient_features(params, ctx, hw):
    dT = structure_temperature(params, ctx)
    return ctx.link_scale_feature(np.ones(len(ctx.chain.links), bool))[None] * dT[None, :, None]


# --------------------------------------------------------------------------------------------------- sag
def _beam_state(ctx, li):
    """Root, unit axis, tip (P, 3) [mm] and length [m] of link ``li`` at the session's poses."""
    ch = ctx.chain
    R, t = kin.body_transforms(ch, ctx.q)
    b = ch.link_body[li]
    tip_h = np.cumsum(ch.links, axis=0)[li]
    root_h = tip_h - ch.links[li]
    L = np.linalg.norm(ch.links[li])
    e = R[:, b] @ (ch.links[li] / L)
    tip = np.einsum("pij,j->pi", R[:, b], tip_h) + t[:, b]
    return e, tip, L / 1000.0


def _beam_loads(ctx, li):
    """Resultant force (P, 3) [N] at the tip of link ``li`` and moment (P, 3) [N m] about it of the loads beyond it,
    and its own weight per length (3,) [N/m]."""
    m, pos, _ = ctx.mass_state
    e, tip, L = _beam_state(ctx, li)
    beyond = ctx.mass_index > li
    F = m[:, beyond, None] * GRAVITY_N
    M = np.cross((pos[:, beyond] - tip[:, None]) / 1000.0, F).sum(axis=1)
    own = ctx.mass_index == li
    w = (m[0, own].sum() if own.any() else 0.0) * GRAVITY_N / L
    return F.sum(axis=1), M, w


def _beam_displacement(ctx, li, EI, kGA, GJ, w_override=None):
    e, tip, L = _beam_state(ctx, li)
    F, M, w = _beam_loads(ctx, li)
    if w_override is not None:
        w = w_override
    d, r = ph.cantilever_tip(e, L, F, M, w, EI, kGA, GJ)
    return 1000.0 * d + np.cross(r, ctx.target - tip)


def sag_draw(ctx, hw, rng):
    return {}


def _own_weight(ctx, name, tube):
    if name in ctx.mass_link:
        return None
    return tube["rho"] * tube["A"] * GRAVITY_N  # a link without a listed mass: its tube's own weight


def links_sum(displacement, p, ctx) -> np.ndarray:
    """Sum over the links of ``p`` ({link name: section}) of ``displacement(ctx, li, section, E, G)`` at the
    sections' own moduli, (P, 3) [mm]: the apply of a per-link beam kind."""
    out = np.zeros((len(ctx.q), 3))
    for name, s in p.items():
        out += displacement(ctx, ctx.chain.link_names.index(name), s, s["E"], s["G"])
    return out


def links_columns(displacement, p, ctx) -> np.ndarray:
    """Per link of ``p``, the displacement per unit 1/E (shear rigid) and per unit 1/G (bending rigid),
    (2 links, P, 3) [mm]: the true-structure features of a per-link beam kind."""
    cols = []
    for name, s in p.items():
        li = ctx.chain.link_names.index(name)
        cols += [displacement(ctx, li, s, 1.0, np.inf), displacement(ctx, li, s, np.inf, 1.0)]
    return np.array(cols)


def sag_apply(params, ctx, hw):
    out = np.zeros((len(ctx.q), 3))
    for name, tb in hw["tubes"].items():
        li = ctx.chain.link_names.index(name)
        out += _beam_displacement(ctx, li, tb["E"] * tb["I"], tb["k"] * tb["G"] * tb["A"], tb["G"] * tb["J"],
                                  _own_weight(ctx, name, tb))
    return Contribution(displace=out)


def sag_features(params, ctx, hw):
    cols = []
    for name, tb in hw["tubes"].items():
        li = ctx.chain.link_names.index(name)
        nu = tb["E"] / (2 * tb["G"]) - 1
        w = _own_weight(ctx, name, tb)
        cols.append(_beam_displacement(ctx, li, 1.0, np.inf, 1.0 / (1 + nu), w))   # per 1/EI
        cols.append(_beam_displacement(ctx, li, np.inf, 1.0, np.inf, w))           # per 1/kGA
    return np.array(cols)


# -------------------------------------------------------------------------------------------------- mount
def mount_moment(ctx):
    """Gravity moment (P, 3) [N m] of the whole arm and payload about the base origin."""
    m, pos, _ = ctx.mass_state
    return np.cross(pos / 1000.0, m[..., None] * GRAVITY_N).sum(axis=1)


def mount_parts(ctx, mount):
    """Target displacements (3, P, 3) per unit plate compliance about its two axes and per unit 1/EI of the
    pedestal column."""
    M = mount_moment(ctx)
    h = mount["height_mm"]
    root = np.array([0.0, 0.0, -h])
    a = mount["plate_axis_rad"]
    axes = [np.array([np.cos(a), np.sin(a), 0.0]), np.array([-np.sin(a), np.cos(a), 0.0])]
    out = [np.cross(ax * (M @ ax)[:, None], ctx.target - root) for ax in axes]
    if h > 0:
        d, r = ph.cantilever_tip(np.array([0, 0, 1.0]), h / 1000.0, np.zeros(3), M, np.zeros(3), 1.0, np.inf, np.inf)
        out.append(1000.0 * d + np.cross(r, ctx.target))
    return np.array(out)


def mount_draw(ctx, hw, rng):
    return {}


def mount_apply(params, ctx, hw):
    mt = hw["mount"]
    amp = np.array([1 / mt["k_plate"][0], 1 / mt["k_plate"][1], 1 / mt["EI"]])

    parts = mount_parts(ctx, mt)
    return Contribution(displace=np.einsum("k,kpi->pi", amp[:len(parts)], parts))


def mount_features(params, ctx, hw):
    return mount_parts(ctx, hw["mount"])
