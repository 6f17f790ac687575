"""Set E body effects (new physics, not in sets A-D): a welded table frame with a soft (unbraced) direction and
the robot off its centre; a base plate on four levelling feet, one of them short (a "soft foot"), rocking between
its two tripods; a cast link of open channel section, twisted by loads that miss its shear centre; a telescopic
(ram) axis whose guide pads and overhang change with the extension. Same protocol as :mod:`effects_joint`.

Sources:

* table frame: a welded stand of square tubes braced in one direction only tilts about its feet 2-4x more
  easily in the unbraced direction (machine-stand stiffness: Koenigsberger & Tlusty, *Machine Tool Structures*,
  1970; frame formulas in Roark's *Formulas for Stress and Strain*); the robot bolted 100-350 mm off the frame's
  centre, so its weight adds a moment about the frame (statics); legs sink under the total weight (axial
  stiffness 50-200 N/um, assumed). Frame heights 400-900 mm, tilt stiffness 2-4x the plate range of
  :mod:`hardware` in the stiff direction (assumed).
* soft foot: a rigid plate on four feet, one short by a gap g, stands on three; when the gravity moment about
  the diagonal through the short foot's neighbours changes sign, it rocks onto the other tripod, a tilt of
  g / (sqrt(2) a) about that diagonal (statics of a four-legged table; "soft foot" in machinery alignment:
  Piotrowski, *Shaft Alignment Handbook*, 3rd ed., 2006, gaps of 0.05-0.1 mm treated as significant). g
  0.03-0.12 mm, feet at +-a, a by arm; elastic feet 100-300 N/um each (levelling-foot data, assumed).
* open-section link: a channel of web h, flanges b, wall t has its shear centre e = 3 b^2 / (6 b + h) behind the
  web, the centroid b^2 / (2 b + h) in front of it; a transverse load through the centroid parallel to the web
  twists the section by its distance to the shear centre; Saint-Venant torsion of an open section is soft,
  J = (h + 2 b) t^3 / 3 (Timoshenko & Gere, *Mechanics of Materials*; Vlasov, *Thin-walled Elastic Beams*, 1961;
  Roark's tables of shear centres). Ribs stiffen the casting's J by 5-15x (assumed); bending about the two
  principal axes of the channel. Flanges 0.6-0.9 h, wall 0.06-0.09 h.
* ram axis: the ram slides through a carriage on two guide pads s = 0.25-0.45 m apart; loads beyond the front pad
  (force F, moment M about it) give pad reactions R_rear = M x w / s, R_front = -F - R_rear; each pad yields by
  R / k_p (linear-guide block rigidity 100-400 N/um, THK / Hiwin catalogues, as recalled), tilting the ram; the
  ram bends as a cantilever from the front pad over its overhang L0 + q (Timoshenko & Gere; Roark).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

Z = np.array([0.0, 0.0, 1.0])


def _total_weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G            # (P,) [N]


# --------------------------------------------------------------------------------------------- table frame
def frame_draw(ctx, hw, rng):
    lo, hi = hwm.ROBOTS[ctx.chain.name]["plate"]
    k_stiff = np.exp(rng.uniform(np.log(lo), np.log(hi))) * rng.uniform(2.0, 4.0)
    a, b = rng.uniform(0, 2 * np.pi), rng.uniform(0, np.pi)
    return {"H_mm": rng.uniform(400, 900), "r0_m": rng.uniform(0.1, 0.35) * np.array([np.cos(a), np.sin(a), 0]),
            "soft_axis": np.array([np.cos(b), np.sin(b), 0.0]), "k_stiff": k_stiff,
            "k_soft": k_stiff / rng.uniform(2.0, 4.0), "k_z_N_per_mm": rng.uniform(50, 200) * 1e3}


def frame_parts(p, ctx):
    """Target displacement (3, P, 3) [mm] per unit compliance about the stiff axis, the soft axis [rad/N m] and
    per unit vertical compliance [mm/N]."""
    M = eb.mount_moment(ctx)
    W = _total_weight(ctx)
    Mc = M + np.cross(p["r0_m"], -W[:, None] * Z)           # moment about the frame's centre
    root = np.r_[-1000.0 * p["r0_m"][:2], -p["H_mm"]]
    soft = p["soft_axis"]
    stiff = np.cross(Z, soft)
    r = ctx.target - root
    return np.array([np.cross(stiff * (Mc @ stiff)[:, None], r), np.cross(soft * (Mc @ soft)[:, None], r),
                     -W[:, None] * Z])


def _frame_amp(p):
    return np.array([1 / p["k_stiff"], 1 / p["k_soft"], 1 / p["k_z_N_per_mm"]])


def frame_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", _frame_amp(p), frame_parts(p, ctx)))


def frame_features(p, ctx, hw):
    return frame_parts(p, ctx)


# ----------------------------------------------------------------------------------------------- soft foot
FOOT_A = {"ur10": (0.10, 0.18), "kr16_like": (0.20, 0.35), "tool_changer": (0.30, 0.50)}  # half spacing [m]


def softfoot_draw(ctx, hw, rng):
    """The short foot placed so that the session's gravity moment rocks the plate (between 20 and 80 % of the
    poses on each tripod; the first random angle that does, else the best of 36)."""
    M = eb.mount_moment(ctx)
    best, angles = None, rng.uniform(0, 2 * np.pi, 36)
    for ang in angles:
        u = np.cross(Z, [np.cos(ang), np.sin(ang), 0.0])
        frac = np.mean(M @ u > 0)
        if best is None or abs(frac - 0.5) < abs(best[1] - 0.5):
            best = (ang, frac)
        if 0.2 <= frac <= 0.8:
            best = (ang, frac)
            break
    a = rng.uniform(*FOOT_A[ctx.chain.name])
    k = rng.uniform(100, 300) * 1e6                          # [N/m] per foot
    return {"angle": best[0], "a_m": a, "gap_mm": rng.uniform(0.03, 0.12), "C_rot": 1 / (4 * k * a * a),
            "h_mm": rng.uniform(50, 150)}


def softfoot_parts(p, ctx):
    """Target displacement (3, P, 3) [mm]: the rocking tilt per unit rad about the diagonal (on the short foot's
    tripod where the moment about it is positive), the elastic tilt of the feet per unit [rad/N m] about x, y."""
    M = eb.mount_moment(ctx)
    n_s = np.array([np.cos(p["angle"]), np.sin(p["angle"]), 0.0])
    u_d = np.cross(Z, n_s)
    root = np.array([0.0, 0.0, -p["h_mm"]])
    r = ctx.target - root
    rock = np.cross(u_d * (M @ u_d > 0)[:, None].astype(float), r)
    ex, ey = np.eye(3)[0], np.eye(3)[1]
    return np.array([rock, np.cross(ex * M[:, :1], r), np.cross(ey * M[:, 1:2], r)])


def _softfoot_amp(p):
    return np.array([p["gap_mm"] / (np.sqrt(2) * 1000 * p["a_m"]), p["C_rot"], p["C_rot"]])


def softfoot_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", _softfoot_amp(p), softfoot_parts(p, ctx)))


def softfoot_features(p, ctx, hw):
    return softfoot_parts(p, ctx)


# -------------------------------------------------------------------------------------- open channel link
def channel_section(h, b, t, rib):
    """Area [m^2], I about the symmetry axis (bending along the web) and I about the web axis [m^4], Saint-Venant J
    (x rib) [m^4] and centroid-to-shear-centre distance [m] of a thin-walled channel."""
    A = (h + 2 * b) * t
    xc = b * b / (2 * b + h)                                  # centroid from the web
    I_sym = t * h ** 3 / 12 + 2 * b * t * (h / 2) ** 2
    I_web = h * t * xc ** 2 + 2 * (t * b ** 3 / 12 + b * t * (b / 2 - xc) ** 2)
    return A, I_sym, I_web, rib * (h + 2 * b) * t ** 3 / 3, 3 * b * b / (6 * b + h) + xc


def channel_draw(ctx, hw, rng):
    """One tube link of 500 mm or more past joint 2 (upper arm or forearm) becomes a ribbed cast channel of about
    the tube's size."""
    ch = ctx.chain
    long = [n for n in hw["tubes"] if np.linalg.norm(ch.links[ch.link_names.index(n)]) >= 500
            and ch.link_body[ch.link_names.index(n)] >= 2]
    name = str(rng.choice(long))
    tb = hw["tubes"][name]
    D = np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2)   # the tube's outer diameter [m]
    h = D * rng.uniform(0.9, 1.2)
    b, t = h * rng.uniform(0.6, 0.9), h * rng.uniform(0.06, 0.09)
    A, I_sym, I_web, J, d_sc = channel_section(h, b, t, rng.uniform(5.0, 15.0))
    return {"link": name, "angle": rng.uniform(0, 2 * np.pi), "A": A, "I_sym": I_sym, "I_web": I_web, "J": J,
            "d_sc": d_sc, "E": tb["E"], "G": tb["G"], "rho": tb["rho"]}


def _channel_axes(p, ctx, li):
    """Unit symmetry axis (P, 3) of the section (towards the flanges), normal to the link."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    e0 = ctx.chain.links[li] / np.linalg.norm(ctx.chain.links[li])
    u = np.cross(e0, [1.0, 0, 0] if abs(e0[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    u0 = np.cos(p["angle"]) * u + np.sin(p["angle"]) * np.cross(e0, u)
    return R[:, ctx.chain.link_body[li]] @ u0


def channel_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per unit 1/E (bending about both principal axes) and per unit 1/G
    (torsion about the shear-centre axis by the loads' own torque and their offset from the shear centre)."""
    li = ctx.chain.link_names.index(p["link"])
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    if p["link"] not in ctx.mass_link:
        w = np.broadcast_to(p["rho"] * p["A"] * eb.GRAVITY_N, F.shape)
    w = np.broadcast_to(w, F.shape)
    us = _channel_axes(p, ctx, li)
    uw = np.cross(e, us)
    Mb = M - np.sum(M * e, axis=1, keepdims=True) * e
    dot = lambda x, y: np.sum(x * y, axis=-1, keepdims=True)  # noqa: E731
    dS, rS = ph.cantilever_tip(e, L, F, Mb, w, p["I_web"], np.inf, np.inf)   # displacement along us
    dW, rW = ph.cantilever_tip(e, L, F, Mb, w, p["I_sym"], np.inf, np.inf)   # along uw
    d = dot(dS, us) * us + dot(dW, uw) * uw
    r = dot(rS, uw) * uw + dot(rW, us) * us
    bend = 1000.0 * d + np.cross(r, ctx.target - tip)
    arm = p["d_sc"] * us                                        # shear centre -> centroid
    T = dot(M, e)[:, 0] + dot(np.cross(arm, F), e)[:, 0]
    t_w = dot(np.cross(arm, w), e)[:, 0]
    phi = (T * L + t_w * L * L / 2) / p["J"]
    sc = tip - 1000.0 * arm
    return np.array([bend, np.cross(phi[:, None] * e, ctx.target - sc)])


def channel_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["E"], 1 / p["G"]], channel_parts(p, ctx)))


def channel_features(p, ctx, hw):
    return channel_parts(p, ctx)


# ------------------------------------------------------------------------------------------------ ram axis
def ram_draw(ctx, hw, rng):
    """The first prismatic joint (none on an all-revolute arm: the kind does nothing there); the ram is the
    tube after it."""
    pj = np.flatnonzero(~ctx.chain.revolute)
    if not len(pj):
        return {}
    j = int(pj[0])
    after = [n for n, b in zip(ctx.chain.link_names, ctx.chain.link_body) if b == j + 1 and n in hw["tubes"]]
    tb = hw["tubes"][after[0]]
    return {"joint": j, "link": after[0], "s_m": rng.uniform(0.25, 0.45), "c_pad": 1 / (rng.uniform(100, 400) * 1e6),
            "I": tb["I"], "J": tb["J"], "E": tb["E"], "G": tb["G"]}


def ram_parts(p, ctx):
    """Target displacement (3, P, 3) [mm] per unit pad compliance [m/N], per unit 1/E and per unit 1/G of the
    ram (cantilever from the front pad, loads beyond the joint lumped at the ram's end)."""
    j, li = p["joint"], ctx.chain.link_names.index(p["link"])
    m, pos, body = ctx.mass_state
    on = body >= j + 1
    Fi = m[:, on, None] * eb.GRAVITY_N
    w_ax, c = kin.joint_frames(ctx.chain, ctx.q)
    w, front = w_ax[:, j], c[:, j]
    F = Fi.sum(axis=1)
    perp = lambda v: v - np.sum(v * w, axis=1, keepdims=True) * w  # noqa: E731
    Mf = np.cross((pos[:, on] - front[:, None]) / 1000.0, Fi).sum(axis=1)
    R_rear = np.cross(perp(Mf), w) / p["s_m"]
    R_front = -perp(F) - R_rear
    u_f, u_r = -R_front, -R_rear                                    # per unit pad compliance [m per m/N]
    phi = np.cross(w, u_f - u_r) / p["s_m"]
    pads = 1000.0 * u_f + np.cross(phi, ctx.target - front)
    _, tip, _ = eb._beam_state(ctx, li)
    L = np.linalg.norm(tip - front, axis=1) / 1000.0
    Mt = np.cross((pos[:, on] - tip[:, None]) / 1000.0, Fi).sum(axis=1)
    out = [pads]
    for EI, GJ in ((p["I"], np.inf), (np.inf, p["J"])):
        d, r = ph.cantilever_tip(w, L[:, None], F, Mt, np.zeros(3), EI, np.inf, GJ)
        out.append(1000.0 * d + np.cross(r, ctx.target - tip))
    return np.array(out)


def _ram_amp(p):
    return np.array([p["c_pad"], 1 / p["E"], 1 / p["G"]])


def ram_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(displace=np.einsum("k,kpi->pi", _ram_amp(p), ram_parts(p, ctx)))


def ram_features(p, ctx, hw):
    return ram_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))
