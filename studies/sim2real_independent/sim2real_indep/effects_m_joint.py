"""Set M joint effects (new physics, not in sets A-L): a slurry shield's excavation chamber half-drained for a tool
change, whose slurry buoys the cutter and the wrist below its level; the oil columns of the hydraulic cylinders driving
axes 2 and 3, compressed by the load, with entrained air; the lost motion of the main axes whose flank a running
spindle's vibration chooses in the blocks it runs; a telescopic stage pulled out by a roller chain from a sprocket
(chordal action and wear elongation); axis 1 read by a secondary encoder on a friction wheel rolling on the slewing
ring. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* slurry buoyancy: a slurry shield's tool changes are made with the excavation chamber's bentonite slurry lowered to
  about half its height, the upper half held by compressed air (Maidl, Herrenknecht, Maidl & Wehrmeyer, *Mechanised
  Shield Tunnelling*, 2nd ed., 2012, ch. on interventions and slurry shields); a slurry of density 1.05-1.3 t/m^3
  (bentonite suspension with spoil) buoys what dips into it by rho g V (Archimedes), here the cutter the arm holds (a
  solid steel disc cutter, V = m / 7850 kg/m^3) and the two wrist bodies (hollow castings displacing 1.5-3x their
  material volume; assumed), each by the share of its height (cutter 0.3-0.45 m, wrist bodies 0.2-0.35 m; assumed)
  below the level. The upward forces twist the gears (tau = J^T F, Craig, *Introduction to Robotics*, ch. 5) at their
  linear stiffness of :mod:`hardware`. The level 10-40 % up the target's height range in the session (assumed). The
  arm's own weight's twist is set A's compliance and left out. tool_changer only (the shield's tool changer).
* oil column: a cylinder held by a closed valve is a spring of its trapped oil, each chamber's volume change being
  V dp / beta (Merritt, *Hydraulic Control Systems*, 1967, ch. 2 and 5: the hydraulic spring beta A^2 / V); entrained
  air, a volume share eps at atmospheric pressure p0, compresses isothermally, so a chamber's volume at pressure p
  loses V (dp / beta + eps p0 (1 / p_b - 1 / p)) from its back pressure p_b (Yu, Chen & Lu, "A study of the effective
  bulk modulus of hydraulic fluid with entrained air", ASME J. Dyn. Syst. Meas. Control 116, 1994; Jelali & Kroll,
  *Hydraulic Servo-systems*, 2003, ch. 3). The chamber that carries the load (the cap side for a push, the rod side for
  a pull, F = tau / a through the lever) rises from p_b by F / A; its oil volume grows with the stroke (chamber length
  plus a dead length of 20-60 mm and the pipe to the valve block, 0.1-0.5 l; assumed). Bores 200-280 / 140-200 mm,
  rod 0.5-0.7 of the bore, beta of oil with its steel pipes 1.4-1.8 GPa, eps 0.3-1.2 %, p_b 8-20 bar (the
  counterbalance valves' holding pressure; assumed; first drawn at 180-250 / 125-180 mm, 1.2-1.6 GPa, 0.2-1 % and
  10-30 bar: the link model within 1.18x in a trial draw); the levers of set L's valve (pivot r1 0.25-0.4 m, rod eye
  0.5-0.8 m, 70-110 deg at mid-range). tool_changer axes 2 and 3 (the tunnel machine's hydraulic boom).
* spindle dither: a vibration superposed on a contact lets it slide at a much lower mean force -- the static friction
  that holds a gear inside its lost motion vanishes (Littmann, Storck & Wallaschek, "Sliding friction in the presence
  of ultrasonic oscillations: superposition of longitudinal oscillations", Arch. Appl. Mech. 71, 2001; Storck et al.,
  Int. J. Mech. Sci. 44, 2002). A grinding or deburring spindle run idle at the tool in some blocks (its unbalance
  shaking the arm) lets every main axis with lost motion settle on the flank its gravity load pushes it to, and an axis
  loaded below the vibration's own torque (0.5-2 % of the rated torque; axis 1, which gravity does not load) centre
  in its play; in the blocks it stands still the friction holds a lightly loaded
  axis on the flank of its last motion (:func:`physics.backlash_offset`). Lost motion of the cycloid main axes 0.5-1.5x
  the catalogue's 1 arcmin (worn), friction 2-6 % of the rated torque (assumed). kr16_like and tool_changer (cycloid
  main axes; none on ur10's strain-wave gears).
* chain stage: a roller chain running onto a sprocket of z teeth moves at the speed of its engaging link's pitch radius
  R cos(phi), phi within +-pi / z of the tooth's middle -- the polygonal (chordal) action (Binder, *Roller Chain
  Drives*, 1956; ISO 606; Litvin & Fuentes, *Gear Geometry*, on chain drives): the chain's travel is R sin(phi) per
  tooth against the mean z p phi / 2 pi, an error periodic once per tooth of some 0.05-0.15 mm for z 8-12. Wear
  elongates the chain (pins and bushings wear, 0.03-0.15 % here, a run-in chain; replacement at 2-3 %), a scale error
  of the travel. tool_changer's telescopic stage pulled out by a chain from a motor sprocket that carries its encoder
  (pitch 19.05 / 25.4 / 31.75 mm, z 8-12; assumed).
* friction wheel: a measuring wheel pressed against a slewing ring and carrying a secondary encoder reads the ring's
  angle through the radius ratio R / r; its effective rolling radius differs from the nominal one (tyre compression,
  wear), a scale error of the reading, and its eccentricity e_w gives an error of e_w / R once per wheel turn, R / r
  times per ring turn -- a non-integer order (measuring-wheel encoders, as recalled from Kuebler / Baumer data; the
  eccentricity rule of the HEIDENHAIN angle-encoder brochure). Radius error 0.005-0.03 %, eccentricity 5-20 um, wheel
  radius 20-40 mm on the axis-1 ring of kr16_like / tool_changer (the radii of sets K and L; assumed). Axis 1 is servoed
  on the wheel's encoder.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_f_joint as fj
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all

TWO_PI = 2 * np.pi
UP = np.array([0.0, 0.0, 1.0])
STEEL_RHO = 7850.0


def block_index(session):
    """Block number (P,) of each pose: a new block after every production period or pause."""
    return np.cumsum(session.gap_s != 0)


# ------------------------------------------------------------------------------------------- slurry buoyancy
SLURRY_ARMS = {"tool_changer"}


def slurry_draw(ctx, hw, rng):
    if ctx.chain.name not in SLURRY_ARMS:
        return {}
    z = ctx.target[:, 2]
    _, _, body = ctx.mass_state
    wrist = [int(i) for i in np.flatnonzero((body >= 4) & (body < ctx.chain.n))]
    return {"rho": rng.uniform(1050, 1300), "level_mm": z.min() + rng.uniform(0.1, 0.4) * np.ptp(z),
            "wrist": wrist, "fill": rng.uniform(1.5, 3.0, len(wrist)), "h_part_mm": rng.uniform(300, 450),
            "h_wrist_mm": rng.uniform(200, 350, len(wrist))}


def submerged(level_mm, z_mm, h_mm):
    """Share (P,) of a body of height h centred at z below the level (linear across its height)."""
    return np.clip((level_mm - np.asarray(z_mm)) / h_mm + 0.5, 0.0, 1.0)


def slurry_loads(p, ctx):
    """Joint loads (P, n) [N m / N] of the slurry's lift on the cutter and the wrist bodies."""
    m, pos, body = ctx.mass_state
    loads = np.zeros_like(ctx.q)
    vols = [(len(body) - 1, m[:, -1] / STEEL_RHO, p["h_part_mm"])]
    vols += [(i, m[:, i] * f / STEEL_RHO, h) for i, f, h in zip(p["wrist"], p["fill"], p["h_wrist_mm"])]
    for i, V, h in vols:
        F = (p["rho"] * kin.G * V * submerged(p["level_mm"], pos[:, i, 2], h))[:, None] * UP
        loads += fj.point_loads(ctx, int(body[i]), pos[:, i], F)
    return loads


def slurry_apply(p, ctx, hw):
    return Contribution(dq=_torsion_all(ctx, hw, slurry_loads(p, ctx)) if p else None)


def slurry_features(p, ctx, hw):
    return _stack(_load_cols(ctx, slurry_loads(p, ctx)) if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------------ oil column
#: per arm and joint: bore [m], pivot radius r1, rod-eye radius r2 [m], included angle at mid-range [deg] (assumed)
OIL = {"tool_changer": {1: ((0.20, 0.28), (0.25, 0.40), (0.5, 0.8), (70.0, 110.0)),
                        2: ((0.14, 0.20), (0.25, 0.40), (0.5, 0.8), (70.0, 110.0))}}
P0 = 1.0e5  # atmospheric pressure [Pa]


def lever_draw(ctx, rng, j, r1, r2, mid_deg):
    """A cylinder's lever on joint j (:func:`effects_f_joint.lever_state`): the included angle at the session's
    mid-range drawn in ``mid_deg``."""
    q = ctx.q[:, j]
    s = float(rng.choice([-1.0, 1.0]))
    return {"r1": rng.uniform(*r1), "r2": rng.uniform(*r2), "s": s,
            "psi0": np.deg2rad(rng.uniform(*mid_deg)) - s * 0.5 * (q.min() + q.max())}


def oil_draw(ctx, hw, rng):
    if ctx.chain.name not in OIL:
        return {}
    cyl = {}
    for j, (bore, r1, r2, mid) in OIL[ctx.chain.name].items():
        lv = lever_draw(ctx, rng, j, r1, r2, mid)
        D = rng.uniform(*bore)
        d = rng.uniform(0.5, 0.7) * D
        _, L, _ = fj.lever_state(lv, ctx.q[:, j])
        cyl[j] = {**lv, "A_cap": np.pi / 4 * D * D, "A_rod": np.pi / 4 * (D * D - d * d),
                  "L_lo": float(L.min()) - rng.uniform(0.02, 0.06), "L_hi": float(L.max()) + rng.uniform(0.02, 0.06),
                  "V_pipe": rng.uniform(0.1, 0.5) * 1e-3}
    return {"cyl": cyl, "beta_Pa": rng.uniform(1.4e9, 1.8e9), "eps": rng.uniform(0.003, 0.012),
            "p_b_Pa": rng.uniform(8e5, 20e5)}


def oil_signals(p, ctx, j):
    """(2, P) [rad per 1/Pa, rad per unit eps]: joint j's offset per unit 1/beta (the oil) and per unit air share."""
    c = p["cyl"][j]
    _, L, a = fj.lever_state(c, ctx.q[:, j])
    F = c["s"] * ctx.loads[:, j] / a                      # the cylinder's push [N] holding the load
    push = F >= 0
    A = np.where(push, c["A_cap"], c["A_rod"])
    V = np.where(push, c["A_cap"] * (L - c["L_lo"]), c["A_rod"] * (c["L_hi"] - L)) + c["V_pipe"]
    dp = np.abs(F) / A
    shorten = np.where(push, -1.0, 1.0) * V / A          # a push compresses the cap side: the cylinder shortens
    geo = c["s"] * shorten / a                            # dq = s dL / a
    return np.array([geo * dp, geo * P0 * (1 / p["p_b_Pa"] - 1 / (p["p_b_Pa"] + dp))])


def oil_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for j in (p["cyl"] if p else {}):
        oil, air = oil_signals(p, ctx, j)
        dq[:, j] = oil / p["beta_Pa"] + p["eps"] * air
    return Contribution(dq=dq)


def oil_features(p, ctx, hw):
    return _stack([ctx.joint_feature(j, s) for j in (p["cyl"] if p else {}) for s in oil_signals(p, ctx, j)],
                  len(ctx.q))


# ------------------------------------------------------------------------------------------- spindle dither
DITHER_ARMS = {"kr16_like", "tool_changer"}


def dither_draw(ctx, hw, rng):
    if ctx.chain.name not in DITHER_ARMS:
        return {}
    joints = [j for j, d in enumerate(hw["drives"]) if d["kind"] == "RV"]
    B = int(block_index(ctx.session)[-1]) + 1
    on = rng.random(B) < 0.5
    if on.all() or not on.any():
        on[0] = not on[0]
    return {"joints": joints, "on": on,
            "b_rad": np.array([hw["drives"][j]["lost_motion"] for j in joints]) * rng.uniform(0.5, 1.5, len(joints)),
            "f_Nm": np.array([hw["drives"][j]["T_rated"] for j in joints]) * rng.uniform(0.02, 0.06, len(joints)),
            "v_Nm": np.array([hw["drives"][j]["T_rated"] for j in joints]) * rng.uniform(0.005, 0.02, len(joints))}


def dither_sides(p, ctx):
    """Flank (joints, P) in units of half the lost motion: while the spindle runs, the load's flank where the load
    passes the vibration's own torque ``v_Nm`` and the play's middle below it; :func:`physics.backlash_offset`'s
    friction-held flank otherwise."""
    on = p["on"][block_index(ctx.session)]
    out = []
    for j, f, v in zip(p["joints"], p["f_Nm"], p["v_Nm"]):
        tau, d = ctx.loads[:, j], ctx.session.direction[:, j]
        held = ph.backlash_offset(d, tau, f, 2.0, 0.0)
        out.append(np.where(on, np.where(np.abs(tau) > v, np.sign(tau), 0.0), held))
    return np.array(out)


def dither_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joints"]] = (p["b_rad"][:, None] / 2 * dither_sides(p, ctx)).T
    return Contribution(dq=dq)


def dither_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return _stack([ctx.joint_feature(j, s) for j, s in zip(p["joints"], dither_sides(p, ctx))], len(ctx.q))


# ------------------------------------------------------------------------------------------------ chain stage
CHAIN_ARMS = {"tool_changer"}


def chain_draw(ctx, hw, rng):
    idx = np.flatnonzero(~ctx.chain.revolute)
    if ctx.chain.name not in CHAIN_ARMS or not len(idx):
        return {}
    return {"joint": int(idx[0]), "pitch_mm": float(rng.choice([19.05, 25.4, 31.75])), "z": int(rng.integers(8, 13)),
            "phase": rng.uniform(0, TWO_PI), "elong": rng.uniform(3e-4, 1.5e-3)}


def chordal_error(p, u_mm):
    """Chain travel minus its mean (P,) [mm] at sprocket travel ``u_mm``: R sin(phi) - z p phi / 2 pi per tooth."""
    z, pt = p["z"], p["pitch_mm"]
    R = pt / (2 * np.sin(np.pi / z))
    theta = TWO_PI * np.asarray(u_mm) / (z * pt) + p["phase"]
    phi = np.mod(theta, TWO_PI / z) - np.pi / z
    return R * np.sin(phi) - z * pt * phi / TWO_PI


def chain_signals(p, ctx):
    u = ctx.q[:, p["joint"]]
    return np.array([chordal_error(p, u), u])


def chain_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = np.array([1.0, p["elong"]]) @ chain_signals(p, ctx)
    return Contribution(dq=dq)


def chain_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], s) for s in chain_signals(p, ctx)] if p else [], len(ctx.q))


# ---------------------------------------------------------------------------------------------- friction wheel
#: per arm: the axis-1 ring's radius [m] (assumed; sets K and L)
WHEEL_RING_M = {"kr16_like": (0.25, 0.38), "tool_changer": (0.42, 0.55)}


def wheel_draw(ctx, hw, rng):
    if ctx.chain.name not in WHEEL_RING_M:
        return {}
    R, r = rng.uniform(*WHEEL_RING_M[ctx.chain.name]), rng.uniform(0.020, 0.040)
    return {"joint": 0, "R_m": R, "order": R / r, "scale": rng.uniform(5e-5, 3e-4) * rng.choice([-1.0, 1.0]),
            "ecc_rad": rng.uniform(5e-6, 20e-6) / R, "phase": rng.uniform(0, TWO_PI)}


def wheel_signals(p, ctx):
    """(3, P): axis 1's angle (the scale error's shape) and the wheel's once-per-turn sine and cosine."""
    q = ctx.q[:, p["joint"]]
    return np.array([q, np.sin(p["order"] * q), np.cos(p["order"] * q)])


def wheel_amplitudes(p):
    return np.array([p["scale"], p["ecc_rad"] * np.cos(p["phase"]), p["ecc_rad"] * np.sin(p["phase"])])


def wheel_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = wheel_amplitudes(p) @ wheel_signals(p, ctx)
    return Contribution(dq=dq)


def wheel_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], s) for s in wheel_signals(p, ctx)] if p else [], len(ctx.q))
