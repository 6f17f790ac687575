"""Set ZA body effects (new physics, not in sets A-Z): the arm on a cantilevered slide table pulled out to another
length for each block; the arm's outrigger pads on frozen ground thawing through the morning; a gripper bar twisted by
parts picked off its centre line; and a soft (inflatable) gripper whose fingers' stiffness follows the inflation
pressure set for each part. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* slide overhang: a cell that serves two machines puts the arm on a telescopic slide table (a heavy-duty drawer slide
  pulled out between the blocks and locked; an unlogged setting): the slide is a cantilever of free length L_b = L_0 +
  e_b, e_b 0-300 mm for the block, L_0 200-400 mm, so its tip (the base) turns by (M_a + W L_b / 2) L_b / EI about the
  horizontal axis across the slide and sinks by (M_a / 2 + W L_b / 3) L_b^2 / EI (a cantilever under an end moment and
  an end load: Roark, *Formulas for Stress and Strain*, cantilever cases), M_a the arm's gravity moment about that axis
  (:func:`effects_body.mount_moment`), W the arm's and the part's weight. Sized so that the largest tilt of the session
  is 0.15-0.4 mrad. Unlike set M's cart docking (a new location, rigid) or set C's track (a beam under a moving
  carriage), the support's compliance changes with the slide's extension. Driven by the pose and the payload (logged)
  and by the slide's extension (not logged). The true structure: one column (the base's turn and sink per unit 1 / EI),
  amplitude 1 / EI.
* ground thaw: an arm on a mobile carrier set on outrigger pads on frozen ground in the morning: from sunrise the thaw
  front descends as X = (2 k_u dT_s t / L_v)^(1/2) (the Stefan solution: Lunardini, *Heat Transfer with Freezing and
  Thawing*, 1991, ch. 3; Andersland & Ladanyi, *Frozen Ground Engineering*, 2004, on thaw weakening), and the thawed
  layer, far softer than the frozen soil below (5-20 against 100-500 MPa), adds a compliance growing with its depth
  while it is thin next to the pad (a layer on a rigid base: Poulos & Davis, *Elastic Solutions for Soil and Rock
  Mechanics*, 1974): the base tilts by (c_0 + c_1 (t / t_1)^(1/2)) M about the pads' plane, t from sunrise (0.5-1.5 h
  before the first pose), M the arm's horizontal gravity moment. Frozen tilt 0.03-0.08 mrad at the largest moment, the
  thawed layer adding 0.15-0.35 mrad by the session's end (the thawed soil 10-50 times softer; first frozen 0.05-0.15
  and thawed 1.5-3 times that: ZA05 on ur10 had the link model at 1.05x). Unlike set Z's warm isolators (a modulus
  following the air) or set N's crawler sinking (Bekker's first loading), a softer layer grows under the pads with the
  square root of the time. Driven by the pose, the payload and the time (logged). The true structure: two columns (the
  tilt per unit compliance, and that times (t / t_1)^(1/2)), amplitudes c_0 and c_1.
* off-centre pick: a gripper bar (an open aluminium channel, 250 mm along the tool's x, the target on a 40 mm post at
  its end) picks a part per block whose centre of mass sits e_b off the bar's centre line (-25-25 mm, across it;
  unlogged), and the part's weight twists the bar by T L / G J_t, T = m (g x r) . x its moment about the bar (the
  Saint-Venant torsion of an open thin-walled section, J_t = sum b t^3 / 3: Young & Budynas, *Roark's Formulas*, ch.
  10). Sized so that the session's largest twist moves the target 0.2-0.5 mm (a 2-3 mm wall; first 0.1-0.3 mm, a 4 mm
  wall: gains of 20 % and 16 % on ZA06 and ZA20, the joint model at 1.25x). Unlike set E's channel (a link's shear
  centre) or set M's gripper bar (bending at two rates), the bar twists by the part's offset across it. Driven by the
  pose and the payload (logged) and the part's offset (not logged). The true structure: one column (the target turned
  about the bar per unit compliance), amplitude L / G J_t [1/(N mm)].
* soft fingers: a soft gripper's inflatable elastomer fingers (fluidic elastomer actuators) carry the part, the target
  on it 80 mm out along the tool's z; an inflated beam's bending stiffness rises with its pressure (Comer & Levy,
  "Deflections of an inflated circular-cylindrical cantilever beam", AIAA J. 1, 1963; for soft fingers Polygerinos et
  al., Adv. Eng. Mater. 19, 2017), k = k_p (kappa + p_b), kappa 5-20 kPa the elastomer's own share, p_b 20-120 kPa set
  for each block's part (unlogged; first kappa 10-40, p_b 30-100: ZA13 on tool_changer had the joint model at 1.08x).
  The part's weight across the fingers deflects them by m g_perp / k. Sized so that the session's largest deflection is
  0.15-0.4 mm. Unlike set X's printed fingers (a fixed modulus) or set Y's foam pad, the stiffness is the inflation's.
  Driven by the pose and the payload (logged) and the pressure (not logged). The true structure: one column (m g_perp /
  (kappa + p_b)), amplitude 1 / k_p.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import GRAVITY_N, mount_moment
from sim2real_indep.effects_u_joint import block_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _weight_N(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * np.linalg.norm(GRAVITY_N)


# ------------------------------------------------------------------------------------------------ slide overhang
def slide_length(p, session):
    """(P,) the slide's free length [m] in each pose's block."""
    return p["L0_m"] + np.asarray(p["ext_m"])[np.minimum(block_index(session), len(p["ext_m"]) - 1)]


def slide_unit(p, ctx):
    """(P, 3) the target's displacement per unit 1 / EI [1/(N m^2)]: the base's turn and sink."""
    u = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    a = np.cross([0.0, 0.0, 1.0], u)
    L = slide_length(p, ctx.session)
    Ma, W = mount_moment(ctx) @ a, _weight_N(ctx)
    turn = (Ma + W * L / 2) * L
    sink = (Ma / 2 + W * L / 3) * L ** 2 * 1000.0                   # [mm]
    return turn[:, None] * np.cross(a, ctx.target) - sink[:, None] * np.array([0.0, 0.0, 1.0])


def slide_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"psi": rng.uniform(0, 2 * np.pi), "L0_m": rng.uniform(0.2, 0.4), "ext_m": rng.uniform(0.0, 0.3, nb)}
    u = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    a = np.cross([0.0, 0.0, 1.0], u)
    L = slide_length(p, ctx.session)
    turn = np.abs((mount_moment(ctx) @ a + _weight_N(ctx) * L / 2) * L).max()
    p["inv_EI"] = rng.uniform(0.15e-3, 0.4e-3) / max(turn, 1e-9)
    return p


def slide_features(p, ctx, hw):
    return slide_unit(p, ctx)[None]


def slide_apply(p, ctx, hw):
    return _amp_apply([p["inv_EI"]], slide_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- ground thaw
def thaw_root(p, session):
    """(P,) (t / t_1)^(1/2), t from sunrise, t_1 the session's end."""
    t = session.time_s - session.time_s[0] + p["t0_s"]
    return np.sqrt(t / t[-1])


def thaw_tilt(p, ctx):
    M = mount_moment(ctx)
    rot = np.zeros_like(M)
    rot[:, :2] = M[:, :2]
    return np.cross(rot, ctx.target - np.array([0.0, 0.0, -p["h_mm"]]))


def thaw_draw(ctx, hw, rng):
    Mh = np.linalg.norm(mount_moment(ctx)[:, :2], axis=1).max()
    c0 = rng.uniform(0.03e-3, 0.08e-3) / max(Mh, 1e-9)
    return {"t0_s": 3600.0 * rng.uniform(0.5, 1.5), "h_mm": rng.uniform(100.0, 300.0), "c0": c0,
            "c1": rng.uniform(0.15e-3, 0.35e-3) / max(Mh, 1e-9)}


def thaw_features(p, ctx, hw):
    base = thaw_tilt(p, ctx)
    return np.array([base, base * thaw_root(p, ctx.session)[:, None]])


def thaw_apply(p, ctx, hw):
    return _amp_apply([p["c0"], p["c1"]], thaw_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------- off-centre pick
BAR_MM = 250.0
POST_MM = 40.0


def pick_unit(p, ctx):
    """(P, 3) the target's displacement per unit torsional compliance [1/(N mm)] (base frame)."""
    pf, Rt = kin.flange(ctx.chain, ctx.q)
    e = np.asarray(p["e_mm"])[np.minimum(block_index(ctx.session), len(p["e_mm"]) - 1)]
    r = np.c_[np.full(len(e), p["x_mm"]), e, np.zeros(len(e))]                      # the part's centre (tool frame)
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N) * ctx.session.payload_kg[:, None]     # its weight (tool frame) [N]
    T = np.cross(r, g)[:, 0]                                                         # its moment about the bar [N mm]
    turn = np.cross([1.0, 0.0, 0.0], np.array([BAR_MM, 0.0, POST_MM]))               # the post's tip per unit twist
    return T[:, None] * np.einsum("pij,j->pi", Rt, turn)


def pick_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"e_mm": rng.uniform(-25.0, 25.0, nb), "x_mm": rng.uniform(0.5, 0.9) * BAR_MM}
    p["c"] = rng.uniform(0.2, 0.5) / max(np.linalg.norm(pick_unit(p, ctx), axis=1).max(), 1e-9)
    return p


def pick_features(p, ctx, hw):
    return pick_unit(p, ctx)[None]


def pick_apply(p, ctx, hw):
    return _amp_apply([p["c"]], pick_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- soft fingers
FINGER_MM = 80.0


def finger_unit(p, ctx):
    """(P, 3) m g_perp / (kappa + p_b) (base frame) [N / kPa]."""
    _, Rt = kin.flange(ctx.chain, ctx.q)
    pb = np.asarray(p["p_kPa"])[np.minimum(block_index(ctx.session), len(p["p_kPa"]) - 1)]
    g = np.einsum("pji,j->pi", Rt, GRAVITY_N) * ctx.session.payload_kg[:, None]
    g[:, 2] = 0.0                                                                     # across the fingers only
    return np.einsum("pij,pj->pi", Rt, g) / (p["kappa"] + pb)[:, None]


def finger_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"kappa": rng.uniform(5.0, 20.0), "p_kPa": rng.uniform(20.0, 120.0, nb)}
    p["inv_kp"] = rng.uniform(0.15, 0.4) / max(np.linalg.norm(finger_unit(p, ctx), axis=1).max(), 1e-9)
    return p


def finger_features(p, ctx, hw):
    return finger_unit(p, ctx)[None]


def finger_apply(p, ctx, hw):
    return _amp_apply([p["inv_kp"]], finger_features(p, ctx, hw))
