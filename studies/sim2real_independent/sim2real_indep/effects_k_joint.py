"""Set K joint effects (new physics, not in sets A-J): a vacuum gripper's hose pulling the tool towards its fixed
anchor while the vacuum holds a part; a telescopic arm held by extension and retraction wire ropes; the telescopic ram
rolling about its own axis inside the clearance of its anti-rotation key; wrist drives carried along the telescopic
arm by Cardan shafts; the ball splines of those shafts twisting the wrist as the arm extends. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* vacuum hose: a flexible hose under vacuum pulls each of its end fittings into the hose, along the end's tangent,
  with the pressure thrust dp A_eff (the pressure thrust of bellows and hoses: EJMA, *Standards of the Expansion Joint
  Manufacturers Association*, 10th ed., 2015, as recalled; A_eff from the corrugations' mean diameter). A gripper fed
  by its hose from a vacuum generator on a fixed stand is pulled towards the stand (the end's tangent taken along
  the chord, assumed) only while the vacuum is on -- while it holds a part, a payload logged. The arm's joints carry
  the pull (tau = J^T F, statics: Craig, *Introduction to Robotics*, ch. 5) and twist with the linear gear stiffness of
  :mod:`hardware`; the gravity twist is set A's and left out. dp 0.6-0.85 bar (vacuum pumps and ejectors), hoses of
  14-25 / 25-40 mm on ur10 / kr16_like (first drawn at 20-32 mm on kr16_like: its link model within 1.25x in the set's
  case), the stand 0.8-1.5 m aside the workspace and 0.2-0.8 m above the flange's highest point, the fitting 20-60 mm
  off the tool axis and 30-80 mm along it (assumed). None on tool_changer. (It replaced a magnetic coupling with a
  sine torque law in canned drives: mostly linear in the gravity load, its twist was matched by the link model on all
  three arms in trial draws -- within 1.25x in most, ambiguous in some.)
* extension ropes: a two-stage telescope is extended and held by wire ropes over sheaves (the rope-synchronised
  booms of cranes and handling arms); the axial force along the arm stretches the rope that holds it: the extension
  rope, whose free length between the front sheave and the inner section shrinks as the arm extends, when the force
  pulls the arm in, the retraction rope, which lengthens, when it pushes out. A stranded rope stiffens with its load
  (Feyrer, *Wire Ropes*, 2nd ed., 2015, ch. 3, the rope modulus rising with the tensile force, as recalled): strain
  c |F|^(1 - g), g 0.15-0.3. Two ropes of 5-8 mm, metallic fill 0.5-0.6, E 90-110 GPa (Feyrer's range for stranded
  ropes); the extension rope runs back over the rear sheave to the drive, 1.0-1.8 m free beyond the stroke, the
  retraction rope 0.2-0.5 m at the shortest stroke (assumed). First drawn with ropes of 8-12, then 6-10 and 5-8 mm,
  both free lengths alike (0.3-0.8, 0.5-1.2, 0.8-1.5 m) and g 0.1-0.2: gains near or below 20 % in trial draws and the
  set's case with the link model at 1.25x, then 1.17x; unequal ropes make the compliance differ with the load's sign,
  which a model linear in the load cannot follow. The prismatic stage of tool_changer (none on the others).
* ram roll: the inner section of the telescopic arm is kept from rolling about its axis by a key in a guide slot;
  a worn slot's clearance c at the key's radius r_k lets it roll by c / 2 r_k to the flank the roll torque pushes it
  to once that torque beats the guide's friction (2-8 % of its largest value), else it stays (a non-ideal relay:
  Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989; clearances of imperfect joints: Flores, Ambrosio,
  Claro & Lankarani, *Kinematics and Dynamics of Multibody Systems with Imperfect Joints*, 2008); production periods
  and the time before the session a pass through the session's torques (set J's flange relay). c 0.15-0.35 mm,
  r_k 60-100 mm (a worn slot; assumed; first drawn at 0.06-0.2, then 0.1-0.25 mm over 80-120 mm: the set's case
  gained 24 % with the mount model at 1.30x); the roll torque is the gravity moment about the ram's axis of the
  masses beyond it, which the disc cutter gripped at its rim, off the wrist axis (:func:`effects_k.payload_hook`),
  makes change sign as axis 6 turns. tool_changer only.
* Cardan shafts: the wrist motors of tool_changer sit on the outer arm and drive the wrist's bevel stages (ratio
  N_b = Z2 / Z1, 1.3-2.9) through telescopic shafts with a Cardan (Hooke's) joint at the front; a joint bent by beta
  turns its output by atan(tan(phi) / cos(beta)) (Seherr-Thoss, Schmelz & Aucktor, *Universal Joints and
  Driveshafts*, 2nd ed., 2006, ch. 1; Mabie & Reinholtz, *Mechanisms and Dynamics of Machinery*, 4th ed., 1987),
  an error of about beta^2 / 4 sin(2 phi) twice per shaft turn. The shaft's front end sits e_o = 60-100 mm off the
  line of its rear bearing (assumed; first drawn at 40-70, then 50-90 mm: the set's case gained 22 % with the
  backlash model at 1.28x), so beta = atan(e_o / (L_0 + q4)) falls as the arm extends (L_0 0.6-0.9 m); axis 6's
  train runs through axis 5 (set H's coupling factors). tool_changer only.
* spline twist: the telescopic wrist shafts pass the torque through a ball spline whose nut slides along the shaft as
  the arm extends; the spline grooves are not exactly straight, their torsion tolerated per 100 mm of length (THK /
  NB ball-spline catalogues, accuracy tables: some 6-33 um per 100 mm by grade, as recalled), so the nut turns by
  delta q4 / (100 mm r_g) as it slides and the wrist joint by that over the bevel's ratio: a wrist joint off in
  proportion to the extension. delta 8-20 um per 100 mm, groove radius r_g 10-20 mm (assumed; first drawn at 4-15 um
  over 12-25 mm: ambiguous in a trial draw), the bevel ratios drawn as the Cardan shafts'. tool_changer only.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_f_joint import point_loads
from sim2real_indep.effects_h_joint import _ratio
from sim2real_indep.effects_i_joint import _load_cols, _stack, _torsion_all
from sim2real_indep.effects_j_joint import relay

TWO_PI = 2 * np.pi


def _prismatic(chain):
    """Index of the prismatic joint (the telescopic stage), or None."""
    idx = np.flatnonzero(~chain.revolute)
    return int(idx[0]) if len(idx) else None


# ------------------------------------------------------------------------------------------------ vacuum hose
#: per arm: the hose's mean corrugation diameter [mm] (assumed)
VACUUM_D_MM = {"ur10": (14.0, 25.0), "kr16_like": (25.0, 40.0)}


def vac_draw(ctx, hw, rng):
    if ctx.chain.name not in VACUUM_D_MM:
        return {}
    fl, _ = kin.flange(ctx.chain, ctx.q)
    a = rng.uniform(0, TWO_PI)
    side = rng.uniform(800, 1500) * np.array([np.cos(a), np.sin(a)])
    D = rng.uniform(*VACUUM_D_MM[ctx.chain.name]) / 1000
    b = rng.uniform(0, TWO_PI)
    return {"anchor_mm": np.r_[fl[:, :2].mean(axis=0) + side, fl[:, 2].max() + rng.uniform(200, 800)],
            "fitting_mm": np.array([rng.uniform(20, 60) * np.cos(b), rng.uniform(20, 60) * np.sin(b),
                                    rng.uniform(30, 80)]),
            "thrust_N": rng.uniform(0.6, 0.85) * 1e5 * np.pi / 4 * D * D}


def vac_loads(p, ctx):
    """Joint loads (P, n) [N m / N] per N of the hose's thrust: the fitting pulled towards the anchor while the
    vacuum holds a part (a payload logged), none otherwise."""
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    fit = fl + Rt @ p["fitting_mm"]
    u = p["anchor_mm"] - fit
    u *= (ctx.session.payload_kg > 0)[:, None] / np.linalg.norm(u, axis=1, keepdims=True)
    return point_loads(ctx, ctx.chain.n, fit, u)


def vac_apply(p, ctx, hw):
    if not p:
        return Contribution()
    return Contribution(dq=_torsion_all(ctx, hw, p["thrust_N"] * vac_loads(p, ctx)))


def vac_features(p, ctx, hw):
    return _stack(_load_cols(ctx, vac_loads(p, ctx)) if p else [], len(ctx.q))


# ----------------------------------------------------------------------------------------- extension ropes
def rope_draw(ctx, hw, rng):
    j = _prismatic(ctx.chain)
    if j is None:
        return {}
    d, fill, E = rng.uniform(5, 8) / 1000, rng.uniform(0.5, 0.6), rng.uniform(90e9, 110e9)
    EA = 2 * E * fill * np.pi / 4 * d ** 2
    F = np.abs(ctx.loads[:, j]).max()
    stroke = float(ctx.q[:, j].max())
    return {"joint": j, "g": rng.uniform(0.15, 0.3), "F_ref": F, "c_per_m": 1.0 / EA,
            "L_ext_m": rng.uniform(1.0, 1.8) + stroke / 1000, "L_ret_m": rng.uniform(0.2, 0.5)}


def rope_signals(p, ctx):
    """(4, P): the rope strain's load shapes |F|^(1-g) F_ref^g, signed, of the retraction rope (the load pushes out,
    F > 0) and of the extension rope (F < 0), each alone and times the stroke q [m]."""
    F = ctx.loads[:, p["joint"]]
    f = np.sign(F) * np.abs(F) ** (1 - p["g"]) * p["F_ref"] ** p["g"]
    q = ctx.q[:, p["joint"]] / 1000
    out_, in_ = np.where(F > 0, f, 0.0), np.where(F < 0, f, 0.0)
    return np.array([out_, out_ * q, in_, in_ * q])


def rope_amplitudes(p):
    """Per unit of :func:`rope_signals`: the free lengths [m] times the rope's compliance [1/N], [mm]: the retraction
    rope L_ret + q, the extension rope L_ext - q."""
    c = 1000 * p["c_per_m"]
    return np.array([c * p["L_ret_m"], c, c * p["L_ext_m"], -c])


def rope_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = rope_amplitudes(p) @ rope_signals(p, ctx)
    return Contribution(dq=dq)


def rope_features(p, ctx, hw):
    return _stack([ctx.joint_feature(p["joint"], s) for s in rope_signals(p, ctx)] if p else [], len(ctx.q))


# ------------------------------------------------------------------------------------------------ ram roll
def roll_torque(ctx, j):
    """Gravity moment (P,) [N m] about the ram's axis (joint ``j``'s line) of the masses beyond it."""
    m, pos, body = ctx.mass_state
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    on = body >= j + 1
    F = m[:, on, None] * eb.GRAVITY_N
    r = (pos[:, on] - c[:, j, None]) / 1000.0
    return np.einsum("pi,pi->p", np.cross(r, F).sum(axis=1), w[:, j])


def roll_draw(ctx, hw, rng):
    j = _prismatic(ctx.chain)
    if j is None:
        return {}
    T = roll_torque(ctx, j)
    return {"joint": j, "half_rad": rng.uniform(0.15, 0.35) / 1000 / (2 * rng.uniform(0.06, 0.10)),
            "T_f": rng.uniform(0.02, 0.08) * np.abs(T).max()}


def roll_part(p, ctx):
    """Target displacement (P, 3) [mm] per unit roll [rad]: the ram turned about its axis to its flank."""
    j = p["joint"]
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    side = relay(roll_torque(ctx, j), p["T_f"], ctx.session.gap_s)
    return np.cross(w[:, j], ctx.target - c[:, j]) * side[:, None]


def roll_apply(p, ctx, hw):
    return Contribution(displace=p["half_rad"] * roll_part(p, ctx) if p else None)


def roll_features(p, ctx, hw):
    return _stack([roll_part(p, ctx)] if p else [], len(ctx.q))


# ---------------------------------------------------------------------------------------------- Cardan shafts
def cardan_draw(ctx, hw, rng):
    jp = _prismatic(ctx.chain)
    if jp is None:
        return {}
    wrist = [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j > jp]
    shafts = []
    for i, j in enumerate(wrist):
        Z1 = int(rng.integers(17, 26))
        shafts.append({"joint": j, "N_b": int(rng.integers(int(1.3 * Z1), int(2.9 * Z1))) / Z1,
                       "e_o_mm": rng.uniform(60, 100), "L0_mm": rng.uniform(600, 900), "phase": rng.uniform(0, TWO_PI),
                       "c": {k: _ratio(rng) * rng.choice([-1, 1]) for k in wrist[:i]}})
    return {"prismatic": jp, "shafts": shafts}


def hooke_error(phi, beta):
    """Output minus input angle [rad] of a Cardan joint bent by ``beta`` at input angles ``phi``."""
    out = np.arctan2(np.sin(phi), np.cos(phi) * np.cos(beta))
    return np.angle(np.exp(1j * (out - phi)))


def cardan_signal(p, s, q):
    """Joint error (P,) [rad] of shaft ``s``: the Cardan joint's error at the shaft angle N_b (q_j + sum c q_k) over
    the bevel's ratio, bent by atan(e_o / (L_0 + q4))."""
    phi = s["N_b"] * (q[:, s["joint"]] + sum(c * q[:, k] for k, c in s["c"].items())) + s["phase"]
    beta = np.arctan(s["e_o_mm"] / (s["L0_mm"] + q[:, p["prismatic"]]))
    return hooke_error(phi, beta) / s["N_b"]


def cardan_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for s in p.get("shafts", []):
        dq[:, s["joint"]] += cardan_signal(p, s, ctx.q)
    return Contribution(dq=dq)


def cardan_features(p, ctx, hw):
    return _stack([ctx.joint_feature(s["joint"], cardan_signal(p, s, ctx.q)) for s in p.get("shafts", [])],
                  len(ctx.q))


# --------------------------------------------------------------------------------------------- spline twist
def spline_draw(ctx, hw, rng):
    jp = _prismatic(ctx.chain)
    if jp is None:
        return {}
    out = []
    for j in [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j > jp]:
        Z1 = int(rng.integers(17, 26))
        N_b = int(rng.integers(int(1.3 * Z1), int(2.9 * Z1))) / Z1
        twist = rng.uniform(8, 20) * 1e-3 / 100 / rng.uniform(10, 20)          # [rad per mm of travel]
        out.append({"joint": j, "prismatic": jp, "N_b": N_b, "rad_per_mm": rng.choice([-1, 1]) * twist / N_b})
    return out


def spline_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for s in p:
        dq[:, s["joint"]] += s["rad_per_mm"] * ctx.q[:, s["prismatic"]]
    return Contribution(dq=dq)


def spline_features(p, ctx, hw):
    return _stack([ctx.joint_feature(s["joint"], ctx.q[:, s["prismatic"]]) for s in p], len(ctx.q))
