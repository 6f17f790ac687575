"""Set D body effects (new physics, not in sets A-C): a base plate with one loose anchor (the joint opens past a
threshold moment on that side: bilinear, sign-dependent tilt stiffness); a robot on elastomer levelling pads that
creep under the sustained gravity moment (standard linear solid); cast links whose section tapers from shoulder
to elbow (non-uniform EI); an end-effector extension boom (offset gripper) bending under the payload. Same
protocol as :mod:`effects_joint`.

Sources:

* loose anchor: a preloaded anchor bolt keeps the base-plate joint closed until the tilting moment's uplift on its
  side exceeds the remaining preload; then the plate rocks about its far edge with the anchor's (much lower)
  elongation stiffness -- the bilinear moment-rotation law of column bases with anchor bolts (EN 1993-1-8
  6.2.8 / 6.3.4; Wald et al., "Component method for steel column bases", HERON 53, 2008). Threshold 10-60 % of
  the session's largest moment on that side, stiffness past it 2-5x lower (assumed).
* levelling pads: elastomer creep modelled as a standard linear solid (Zener; Findley, Lai & Onaran, *Creep and
  Relaxation of Nonlinear Viscoelastic Materials*, 1976; rubber mounts creep 10-30 % of the instant deflection
  within hours, e.g. Gent, *Engineering with Rubber*, ch. 6): tilt = C0 M + x, tau dx/dt = C1 M - x, C1 / C0 =
  0.3-1, tau = 5-40 min; the moment is held during pauses (brakes on at the last pose) and averaged during the
  exercise cycle. Pad rotational stiffness 0.5-1x the plate range of :mod:`hardware` (softer, assumed).
* tapered cast link: Mohr's integrals for a cantilever of variable section, tip deflection int M(x)(L - x) /
  EI(x) dx and slope int M(x) / EI(x) dx (Timoshenko & Gere, *Mechanics of Materials*, non-prismatic beams;
  Roark's tables for tapered beams); I falls linearly from the root (1x the tube's I, +-20 %) to 0.3-0.6x at the
  tip (assumed), torsion with the mean GJ.
* end-effector extension boom: a square hollow bar 200-800 mm long by arm (aluminium 30-60 mm for the lighter
  arms, steel 70-100 mm for the heavy one) from the flange mostly across the tool axis, carrying the payload and
  the target at its end (an offset gripper / reach extension): cantilever bending, shear and Bredt torsion as
  :func:`physics.cantilever_tip` (Timoshenko & Gere; Roark). Sizes assumed from typical end-of-arm tooling
  extension profiles.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution


# ---------------------------------------------------------------------------------------------- loose anchor
def anchor_draw(ctx, hw, rng):
    """The loose anchor sits at plan angle U(0, 360) deg; the moment about the axis normal to it (in the plate
    plane) lifts it when positive."""
    M = eb.mount_moment(ctx)
    a = rng.uniform(0, 2 * np.pi)
    u = np.array([-np.sin(a), np.cos(a), 0.0])
    m = M @ u
    mpos = max(m.max(), 1e-3 * np.abs(m).max())
    return {"axis": u, "M0": rng.uniform(0.1, 0.6) * mpos,
            "c_open": rng.uniform(1.0, 4.0) / min(hw["mount"]["k_plate"])}


def anchor_parts(p, ctx, hw):
    """The mount's linear parts (plate about two axes, pedestal column) and the opening beyond the threshold."""
    lin = eb.mount_parts(ctx, hw["mount"])
    M = eb.mount_moment(ctx)
    excess = np.maximum(M @ p["axis"] - p["M0"], 0.0)
    root = np.array([0.0, 0.0, -hw["mount"]["height_mm"]])
    opening = np.cross(p["axis"] * excess[:, None], ctx.target - root)
    return np.concatenate([lin, opening[None]])


def _anchor_amp(p, hw):
    mt = hw["mount"]
    amp = [1 / mt["k_plate"][0], 1 / mt["k_plate"][1]] + ([1 / mt["EI"]] if mt["height_mm"] > 0 else [])
    return np.array(amp + [p["c_open"]])


def anchor_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", _anchor_amp(p, hw), anchor_parts(p, ctx, hw)))


def anchor_features(p, ctx, hw):
    return anchor_parts(p, ctx, hw)


# --------------------------------------------------------------------------------------- creeping levelling pads
def settle_draw(ctx, hw, rng):
    lo, hi = hwm.ROBOTS[ctx.chain.name]["plate"]
    k0 = np.exp(rng.uniform(np.log(lo), np.log(hi))) * rng.uniform(0.5, 1.0)
    return {"C0": 1 / k0, "C1": rng.uniform(0.3, 1.0) / k0, "tau_s": rng.uniform(5, 40) * 60,
            "pad_mm": rng.uniform(30, 80)}


def _moment_history(ctx):
    """Tilting moment (P, 3, 2) [N m] per segment (gap, move + dwell) before each measurement: the exercise
    cycle's mean moment, or the last pose's during a pause; the pose's own during its move and dwell."""
    s = ctx.session
    M = eb.mount_moment(ctx)[:, :2]
    prev = np.vstack([M[:1], M[:-1]])
    gap = np.where((s.gap_s > 0)[:, None], M.mean(axis=0), prev)
    dur = np.stack([np.abs(s.gap_s), s.move_s + s.dwell_s], axis=1)
    return np.stack([gap, M], axis=1), dur


def creep_state(p, ctx):
    """Creep part of the moment (P, 2) [N m] (x / C1): the moment through a first-order lag of tau, from a
    robot that stood at its first pose long before the session."""
    hist, dur = _moment_history(ctx)
    t = np.r_[0.0, np.cumsum(dur.ravel())]
    u = np.r_[hist.reshape(-1, 2), hist[-1:, 1]]
    x = ph.first_order_zoh(t, u, p["tau_s"], x0=hist[0, 1])
    return x[2::2]


def settle_parts(p, ctx):
    M = eb.mount_moment(ctx)[:, :2]
    Mc = creep_state(p, ctx)
    root = np.array([0.0, 0.0, -p["pad_mm"]])
    ex, ey = np.eye(3)[0], np.eye(3)[1]
    r = ctx.target - root
    return np.array([np.cross(ex * M[:, :1], r), np.cross(ey * M[:, 1:], r),
                     np.cross(ex * Mc[:, :1], r), np.cross(ey * Mc[:, 1:], r)])


def settle_apply(p, ctx, hw):
    amp = np.array([p["C0"], p["C0"], p["C1"], p["C1"]])
    return Contribution(displace=np.einsum("k,kpi->pi", amp, settle_parts(p, ctx)))


def settle_features(p, ctx, hw):
    return settle_parts(p, ctx)


# -------------------------------------------------------------------------------------------- tapered castings
def _taper_integrals(L, I_root, beta, n=400):
    """a_k = int_0^L (L - x)^k / I(x) dx, k = 0..3, I(x) = I_root (1 - (1 - beta) x / L) (midpoint rule)."""
    x = (np.arange(n) + 0.5) * L / n
    inv = 1.0 / (I_root * (1 - (1 - beta) * x / L))
    return np.array([np.sum((L - x) ** k * inv) * L / n for k in range(4)])


def taper_draw(ctx, hw, rng):
    out = {}
    for name, tb in hw["tubes"].items():
        out[name] = {"I_root": tb["I"] * rng.uniform(0.8, 1.2), "beta": rng.uniform(0.3, 0.6),
                     "E": tb["E"], "G": tb["G"], "J": tb["J"], "rho_A": tb["rho"] * tb["A"]}
    return out


def _taper_displacement(ctx, li, s, E, G):
    e, tip, L = eb._beam_state(ctx, li)
    F, M, w = eb._beam_loads(ctx, li)
    if ctx.chain.link_names[li] not in ctx.mass_link:
        w = s["rho_A"] * eb.GRAVITY_N
    a = _taper_integrals(L, s["I_root"], s["beta"]) / E
    perp = lambda v: v - np.sum(v * e, axis=-1, keepdims=True) * e  # noqa: E731
    Fp, wp, Mb = perp(F), perp(w), perp(M)
    Mt = np.sum(M * e, axis=-1, keepdims=True) * e
    delta = Fp * a[2] + wp * a[3] / 2 + np.cross(Mb, e) * a[1]
    rot = np.cross(e, Fp) * a[1] + np.cross(e, wp) * a[2] / 2 + Mb * a[0] + Mt * L / (G * s["J"])
    return 1000.0 * delta + np.cross(rot, ctx.target - tip)


def taper_apply(p, ctx, hw):
    return Contribution(displace=eb.links_sum(_taper_displacement, p, ctx))


def taper_features(p, ctx, hw):
    return eb.links_columns(_taper_displacement, p, ctx)


# ----------------------------------------------------------------------------------------- end-effector bracket
#: per arm: length [m], outer side [m], wall [m], material
BRACKETS = {"ur10": ((0.20, 0.40), (0.03, 0.05), (0.002, 0.004), hwm.ALUMINIUM),
            "kr16_like": ((0.25, 0.50), (0.04, 0.06), (0.003, 0.005), hwm.ALUMINIUM),
            "tool_changer": ((0.40, 0.80), (0.07, 0.10), (0.004, 0.008), hwm.STEEL)}


def bracket_draw(ctx, hw, rng):
    Lr, Br, tr, mat = BRACKETS[ctx.chain.name]
    L, B, t = rng.uniform(*Lr), rng.uniform(*Br), rng.uniform(*tr)
    a = rng.uniform(0, 2 * np.pi)
    u = np.array([np.cos(a), np.sin(a), rng.uniform(-0.3, 0.3)])   # mostly across the tool axis
    A = B * B - (B - 2 * t) ** 2
    I = (B ** 4 - (B - 2 * t) ** 4) / 12
    J = (B - t) ** 4 * t / (B - t)   # Bredt, square section: 4 A_m^2 t / s
    return {"L_m": L, "u_tool": u / np.linalg.norm(u), "A": A, "I": I, "J": J, "k": 0.5, "E": mat["E"],
            "G": mat["E"] / (2 * (1 + mat["nu"])), "w_N_per_m": mat["rho"] * A * kin.G}


def _bracket_displacement(p, ctx, EI, kGA, GJ):
    tip, Rt = kin.flange(ctx.chain, ctx.q)
    e = -(Rt @ p["u_tool"])               # from the root on the flange side to the tip at the tool point
    F = ctx.session.payload_kg[:, None] * eb.GRAVITY_N
    pay = tip + Rt @ ctx.payload_com_mm
    M = np.cross((pay - tip) / 1000.0, F)
    w = np.broadcast_to(-p["w_N_per_m"] * np.array([0, 0, 1.0]), F.shape)
    d, r = ph.cantilever_tip(e, p["L_m"], F, M, w, EI, kGA, GJ)
    return 1000.0 * d + np.cross(r, ctx.target - tip)


def bracket_parts(p, ctx):
    """Per unit 1/E (bending) and per unit 1/G (shear + torsion)."""
    return np.array([_bracket_displacement(p, ctx, p["I"], np.inf, np.inf),
                     _bracket_displacement(p, ctx, np.inf, p["k"] * p["A"], p["J"])])


def bracket_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["E"], 1 / p["G"]], bracket_parts(p, ctx)))


def bracket_features(p, ctx, hw):
    return bracket_parts(p, ctx)
