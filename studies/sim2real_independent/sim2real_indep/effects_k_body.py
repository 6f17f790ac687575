"""Set K body effects (new physics, not in sets A-J): a mobile platform on outrigger pads that consolidate the soft
ground under them; the arm on a console fixed to a tunnel-boring shield's pressure bulkhead, which the excavation
chamber's support pressure bows; axis 2 driven by one hydraulic cylinder beside the arm's plane, whose offset force
twists and bends the upper arm's root out of its plane; a remote-centre compliance (RCC) device between the flange and
the gripper. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* outriggers on soil: a rigid circular pad of radius r on an elastic half-space settles w = (1 - nu^2) R / (2 E_s r)
  under a load R (Boussinesq's rigid punch: Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., 1970, sec. 138;
  Poulos & Davis, *Elastic Solutions for Soil and Rock Mechanics*, 1974), then consolidates as the pore water
  drains: a further beta w over Terzaghi's average degree of consolidation U(T_v), T_v = c_v t / H^2, U = 1 - sum
  2 / M^2 exp(-M^2 T_v), M = (2 m + 1) pi / 2 (Terzaghi, *Theoretical Soil Mechanics*, 1943; Das, *Principles of
  Geotechnical Engineering*), superposed over the load history (Boltzmann, as set J's grout). The pads share the
  arm's weight and tilting moment as four equal supports at +-a (statics of a rigid platform, set G's jacks); the
  platform's own settlement, finished when the session starts, is a constant and left out. Soft clay or silty fill
  E_s 3-10 / 6-20 / 8-25 MPa, nu 0.3-0.4, pads of r 40-70 / 80-120 / 120-200 mm at a 0.35-0.6 / 0.6-0.9 / 0.8-1.2 m on
  ur10 / kr16_like / tool_changer, beta 2-4 and H^2 / c_v 10-60 min (small pads drain fast), set up 6-24 h before
  the session under the session's mean load (assumed: mobile and construction robots standing on site). First drawn
  stiffer -- E_s 8-25 / 10-30 MPa, pads of 60-100 / 100-160 mm, beta 0.5-1.5 over 20-120 min: absorbed on ur10 in
  trial draws --, then with E_s 5-15 and 3-10 MPa on ur10 and beta 1-3 over 20-120 min: the set's ur10 case was
  named by the joint model as well (1.05x, 1.18x); its consolidation is now the larger part.
* pressure bulkhead: the chamber's support pressure p bows the bulkhead, a plate clamped at its rim a: w(r) = p (a^2 -
  r^2)^2 / (64 D), slope p r (a^2 - r^2) / (16 D) (Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, 2nd
  ed., 1959, sec. 15); stiffening ribs and the main drive's housing taken into an effective D that puts w(0) at
  0.5-1.2 mm per bar (assumed). The air bubble of a slurry shield holds the support pressure within about +-0.1 bar,
  cycling with its regulator, and the pressure drifts as the face takes up slurry (Maidl, Herrenknecht, Maidl &
  Wehrmeyer, *Mechanised Shield Tunnelling*, 2nd ed., 2012, ch. 4, as recalled): here cycles of 0.05-0.12 bar over
  5-20 min and a drift of 0.1-0.3 bar over the session (first drawn at 0.03-0.1 / 0.05-0.2 bar with 0.3-1 mm per bar:
  a gain of 9 % in one of two trial draws). The arm's console hangs on the bulkhead at r0 = 0.35-0.65 a below its
  centre (a = 2.5-4 m), 0.3-0.8 m behind the base; its base translates by w(r0) along the tunnel axis (y) and turns
  by the slope about the horizontal tangent (x). tool_changer only.
* side cylinder: axis 2 of tool_changer driven, as a boom of a hydraulic manipulator or an excavator, by one
  cylinder from a pivot r1 = 0.25-0.4 m from the axis on the proximal body to a rod eye r2 = 0.5-0.7 m along the
  arm (included angle 75-105 deg at mid-range: the cylinder at a shallow angle to the arm; the law of cosines of set
  F's levers), mounted beside the arm, e = 0.25-0.4 m off its mid-plane along the axis (assumed). The cylinder holds
  the axis's gravity load: its force F on the eye gives -tau_2 about the axis. The root segment of the upper arm
  between the axis and the eye is a cantilever from the axis's bearings loaded at its end by F and by F's moment
  e x F about the section's axis line (Timoshenko & Gere, *Mechanics of Materials*; :func:`physics.cantilever_tip`),
  which twists the segment and bends it out of the arm's plane; the arm beyond turns with the eye section. With set
  A's sag (the arm's bending under its loads from a clamped root) the in-plane part makes the pinned root's moment
  line. The tube of :mod:`hardware`. First drawn as a gas-spring counterbalance beside the arm (set D's geometry,
  kr16_like and tool_changer): its nearly constant force bent and twisted the arm by a nearly constant amount, which
  the geometry absorbs (absorbed or ambiguous in trial draws); then as the driving cylinder on a steep lever (set F's,
  r1 0.8-1.2 m, r2 0.25-0.4 m, then an included angle of 55-70 deg), nearly normal to the arm: its twist about the
  upper arm's axis was matched by the joint or the mount model (the set's case ambiguous, a rival within 1.05x both
  times); the shallow cylinder's axial force, offset, bends the arm sideways, which no model matches. None on ur10 or
  kr16_like (kr16_like's twist, e tau_2 / GJ, gave gains below 20 % in trial draws).
* RCC: a remote-centre compliance device (elastomer shear pads) lets the gripper translate under a force through its
  compliance centre, h ahead of the device, and turn about that centre under a moment (Whitney, "Quasi-static
  assembly of compliantly supported rigid parts", J. Dyn. Syst. Meas. Control 104(1), 1982; Whitney & Nevins, "What is
  the remote center compliance (RCC) and what can it do?", 9th ISIR, 1979): lateral, axial, cocking and torsional
  compliances. The gripper (1-3 / 3-8 / 20-40 kg on ur10 / kr16_like / tool_changer) and the payload hang beyond it;
  a unit sized so that the rated load's weight displaces it 0.3-0.8 mm laterally and tilts the tip 0.2-0.6 mm over
  150 mm, axially 5-10 times and in torsion 1-3 times as stiff (in the range of commercial units' catalogue
  stiffnesses, as recalled; assumed). Target and payload at the gripper (:func:`effects_k.probe_hook`). Scored as link
  deflection: the end-of-arm structure carrying the target (as set D's bracket, set G's target rod and set J's tool
  plate); in trial draws no family's model came within 1.25x of it.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_f_joint as fj
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_g_body import _plate_motion
from sim2real_indep.effects_j_body import _logu

Z = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------------------------------- outriggers on soil
#: per arm: pad spacing a [m], pad radius [m], soil modulus [Pa] (assumed)
OUTRIGGER = {"ur10": ((0.35, 0.6), (0.04, 0.07), (3e6, 10e6)),
             "kr16_like": ((0.6, 0.9), (0.08, 0.12), (6e6, 20e6)),
             "tool_changer": ((0.8, 1.2), (0.12, 0.20), (8e6, 25e6))}


def terzaghi_U(Tv):
    """Terzaghi's average degree of consolidation U (any shape) at time factors ``Tv`` (0 where Tv <= 0)."""
    T = np.maximum(np.asarray(Tv, float), 0.0)
    M = (2 * np.arange(400) + 1) * np.pi / 2
    series = 1 - np.sum(2 / M ** 2 * np.exp(-np.multiply.outer(np.maximum(T, 1e-6), M ** 2)), axis=-1)
    return np.where(T < 1e-4, np.sqrt(4 * T / np.pi), series)


def outrig_draw(ctx, hw, rng):
    (a0, a1), (r0, r1), (E0, E1) = OUTRIGGER[ctx.chain.name]
    r, nu = rng.uniform(r0, r1), rng.uniform(0.3, 0.4)
    return {"a_m": rng.uniform(a0, a1),
            "k_N_per_m": 2 * _logu(rng, E0, E1) * r / (1 - nu ** 2), "beta": rng.uniform(2.0, 4.0),
            "t_ref_s": rng.uniform(10, 60) * 60, "pre_s": rng.uniform(6, 24) * 3600, "h_ref_mm": rng.uniform(200, 500)}


def _support_loads(p, ctx):
    """(P, 3): the tilting moment about x, y [N m] and the weight [N] of arm and payload (the platform's own weight
    settled the pads before the session: a constant offset, left out)."""
    m, _, _ = ctx.mass_state
    return np.c_[eb.mount_moment(ctx)[:, :2], m.sum(axis=1) * kin.G]


def load_history(ctx, X):
    """Per-pose quantities X (P, d) as held over the segments before each measurement, (P, 2, d), and the segments'
    durations (P, 2) [s]: the production cycle's mean or the last pose's value over a pause; the pose's own over its
    move and dwell."""
    s = ctx.session
    prev = np.vstack([X[:1], X[:-1]])
    gap = np.where((s.gap_s > 0)[:, None], X.mean(axis=0), prev)
    return np.stack([gap, X], axis=1), np.stack([np.abs(s.gap_s), s.move_s + s.dwell_s], axis=1)


def consolidated(p, ctx, X):
    """Boltzmann's sum (P, d) of the steps of X through Terzaghi's U(t / t_ref) at the measurements; the session's
    mean applied ``pre_s`` before it."""
    hist, dur = load_history(ctx, X)
    vals = np.vstack([hist[:, 1].mean(axis=0), hist.reshape(-1, X.shape[1])])
    ends = np.cumsum(dur.ravel())
    starts = np.r_[-p["pre_s"], ends - dur.ravel()]
    steps = np.diff(np.vstack([np.zeros((1, X.shape[1])), vals]), axis=0)
    return terzaghi_U((ends[1::2, None] - starts[None, :]) / p["t_ref_s"]) @ steps


def outrig_parts(p, ctx):
    """Target displacement (2, P, 3) [mm] per unit pad compliance [m/N]: immediate and consolidation settlements."""
    X = _support_loads(p, ctx)
    ref = np.array([0.0, 0.0, -p["h_ref_mm"]])
    out = []
    for Y in (X, consolidated(p, ctx, X)):
        out.append(_plate_motion(ctx, Y[:, :2] / (4 * p["a_m"] ** 2), 1000.0 * Y[:, 2] / 4, ref))
    return np.array(out)


def outrig_apply(p, ctx, hw):
    c = 1 / p["k_N_per_m"]
    return Contribution(displace=np.einsum("k,kpi->pi", [c, p["beta"] * c], outrig_parts(p, ctx)))


def outrig_features(p, ctx, hw):
    return outrig_parts(p, ctx)


# ----------------------------------------------------------------------------------------- pressure bulkhead
BULKHEAD_ARMS = {"tool_changer"}


def bulk_draw(ctx, hw, rng):
    if ctx.chain.name not in BULKHEAD_ARMS:
        return {}
    a = rng.uniform(2.5, 4.0)
    return {"a_m": a, "r0_m": rng.uniform(0.35, 0.65) * a, "w0_mm_per_bar": rng.uniform(0.5, 1.2),
            "behind_mm": rng.uniform(300, 800), "drift_bar": rng.choice([-1, 1]) * rng.uniform(0.1, 0.3),
            "cycle_bar": rng.uniform(0.05, 0.12), "period_s": rng.uniform(5, 20) * 60,
            "phase": rng.uniform(0, 2 * np.pi)}


def chamber_pressure(p, t_s):
    """Support pressure change [bar] since the first measurement: a drift over the session and the regulator's
    cycle."""
    t = np.asarray(t_s, float) - t_s[0]
    span = max(t[-1], 1.0)
    cyc = np.sin(2 * np.pi * t / p["period_s"] + p["phase"]) - np.sin(p["phase"])
    return p["drift_bar"] * t / span + p["cycle_bar"] * cyc


def plate_shape(a, r):
    """Deflection and slope (per unit w(0)) of a clamped circular plate under uniform pressure at radius r."""
    return (1 - (r / a) ** 2) ** 2, 4 * r * (a ** 2 - r ** 2) / a ** 4


def bulk_pattern(p, ctx):
    """Target displacement (P, 3) [mm] per bar: the base carried along the tunnel axis (y) by w(r0) and turned about
    x by the slope (the bulkhead bows most at its centre, r0 above the console)."""
    w, slope = plate_shape(p["a_m"], p["r0_m"])
    c = np.array([0.0, -p["behind_mm"], 0.0])
    omega = np.array([-slope * p["w0_mm_per_bar"] / 1000, 0.0, 0.0])
    return w * p["w0_mm_per_bar"] * np.array([0.0, 1.0, 0.0]) + np.cross(omega, ctx.target - c)


def bulk_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(displace=bulk_pattern(p, ctx) * chamber_pressure(p, ctx.session.time_s)[:, None])


def bulk_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return (bulk_pattern(p, ctx) * chamber_pressure(p, ctx.session.time_s)[:, None])[None]


# ------------------------------------------------------------------------------------------- side cylinder
#: per arm: the cylinder's offset e from the arm's mid-plane along axis 2 [m] (assumed)
CYL_OFFSET = {"tool_changer": (0.25, 0.4)}
CYL_JOINT = 1  # axis 2


#: per arm: pivot radius r1, rod-eye radius r2 [m], included angle at mid-range [deg] (assumed)
CYL_LEVER = {"tool_changer": ((0.25, 0.4), (0.5, 0.7), (75.0, 105.0))}


def cyl_draw(ctx, hw, rng):
    if ctx.chain.name not in CYL_OFFSET:
        return {}
    (a0, a1), (b0, b1), (m0, m1) = CYL_LEVER[ctx.chain.name]
    q = ctx.q[:, CYL_JOINT]
    s = float(rng.choice([-1.0, 1.0]))
    p = {"joint": CYL_JOINT, "r1": rng.uniform(a0, a1), "r2": rng.uniform(b0, b1), "s": s,
         "psi0": np.deg2rad(rng.uniform(m0, m1)) - s * 0.5 * (q.min() + q.max())}
    ch = ctx.chain
    on = [i for i in np.flatnonzero(ch.link_body == CYL_JOINT + 1) if ch.link_names[i] in hw["tubes"]]
    li = int(on[np.argmax(np.linalg.norm(ch.links[on], axis=1))])
    tb = hw["tubes"][ch.link_names[li]]
    p.update(e_m=rng.choice([-1, 1]) * rng.uniform(*CYL_OFFSET[ch.name]), link=li, I=tb["I"], A=tb["A"], J=tb["J"],
             k=tb["k"], E=tb["E"], G=tb["G"])
    return p


def cyl_force(p, ctx):
    """Force (P, 3) [N] of the cylinder on the upper arm at its rod eye, holding axis 2's gravity load, its line
    from the pivot (r1 from axis 2 on the proximal body, included angle psi = psi0 + s q2) to the eye (r2 along the
    arm); the arm's unit axis (P, 3), root and eye (P, 3) [mm]."""
    e, tip, L = eb._beam_state(ctx, p["link"])
    root = tip - 1000.0 * L * e
    w, _ = kin.joint_frames(ctx.chain, ctx.q)
    w2 = w[:, CYL_JOINT]
    psi, _, _ = fj.lever_state(p, ctx.q[:, CYL_JOINT])
    th = -p["s"] * psi[:, None]
    pivot = p["r1"] * (e * np.cos(th) + np.cross(w2, e) * np.sin(th))
    u = p["r2"] * e - pivot
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    arm = np.einsum("pi,pi->p", np.cross(p["r2"] * e, u), w2)
    return (-ctx.loads[:, CYL_JOINT] / arm)[:, None] * u, e, w2, root + 1000.0 * p["r2"] * e


def cyl_displacement(p, ctx, E, G):
    """Target displacement (P, 3) [mm] of the upper arm's root segment (axis 2 to the rod eye), loaded at the eye by
    the cylinder's force and by its moment about the section's axis line (the offset e along axis 2); E, G: np.inf
    makes that part rigid."""
    F, e, w2, eye = cyl_force(p, ctx)
    M = np.cross(p["e_m"] * w2, F)
    d, r = ph.cantilever_tip(e, p["r2"], F, M, np.zeros(3), E * p["I"], G * p["k"] * p["A"], G * p["J"])
    return 1000.0 * d + np.cross(r, ctx.target - eye)


def cyl_parts(p, ctx):
    """Per unit 1/E (bending) and per unit 1/G (torsion and shear), (2, P, 3)."""
    return np.array([cyl_displacement(p, ctx, 1.0, np.inf), cyl_displacement(p, ctx, np.inf, 1.0)])


def cyl_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(displace=np.einsum("k,kpi->pi", [1 / p["E"], 1 / p["G"]], cyl_parts(p, ctx)))


def cyl_features(p, ctx, hw):
    return cyl_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))


# ----------------------------------------------------------------------------------------------------- RCC
#: per arm: gripper mass [kg], compliance centre ahead of the flange [mm] (assumed)
RCC = {"ur10": ((1.0, 3.0), (80, 160)), "kr16_like": ((3.0, 8.0), (100, 220)),
       "tool_changer": ((20.0, 40.0), (160, 320))}


def rcc_draw(ctx, hw, rng):
    (m0, m1), (h0, h1) = RCC[ctx.chain.name]
    m = rng.uniform(m0, m1)
    rated = (m + hwm.PAYLOAD_MAX_KG[ctx.chain.name]) * kin.G
    k_L = rated / rng.uniform(0.3, 0.8)                            # [N/mm]
    k_th = rated * 0.1 / (rng.uniform(0.2, 0.6) / 150.0)           # [N m/rad]: rated load 100 mm off the centre
    centre = np.array([0.0, 0.0, rng.uniform(h0, h1)])
    k = np.array([k_L, k_L * rng.uniform(5, 10), k_th, k_th * rng.uniform(1, 3)])
    return {"m_grip": m, "grip_mm": np.array([0.0, 0.0, 0.6 * ctx.probe_mm[2]]), "centre_mm": centre, "k": k}


def rcc_parts(p, ctx):
    """Target displacement (4, P, 3) [mm], base frame, per unit lateral [mm/N], axial [mm/N], cocking [rad/(N m)] and
    torsional [rad/(N m)] compliance of the device, under the gripper's and the payload's weight."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    g = np.einsum("pji,j->pi", Rt, -kin.G * Z)                     # gravity in the tool frame [m/s^2]
    m_pay = ctx.session.payload_kg[:, None]
    C = p["centre_mm"]
    F = (p["m_grip"] + m_pay) * g
    M = (np.cross((p["grip_mm"] - C) / 1000, p["m_grip"] * g) + np.cross((ctx.payload_com_mm - C) / 1000, m_pay * g))
    lat, ax = F * [1, 1, 0], F * [0, 0, 1]
    arm = ctx.probe_mm - C
    local = [lat, ax, np.cross(M * [1, 1, 0], arm), np.cross(M * [0, 0, 1], arm)]
    return np.array([np.einsum("pij,pj->pi", Rt, d) for d in local])


def rcc_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", 1 / p["k"], rcc_parts(p, ctx)))


def rcc_features(p, ctx, hw):
    return rcc_parts(p, ctx)
