"""Set ZC joint effects (new physics, not in sets A-ZB): a wire laid from a dancer-tensioned spool pulling the tool
towards the spool's guide eye with a tension set per material roll; a coupled wrist whose drive trains' compliances act
in motor coordinates; a tool on a bayonet coupling turned across its lugs' play by its hose's drag against axis 6's last
rotation; axis 1's gear play taken up by a pneumatic preload cylinder in the blocks in which the cell's air is on; the
output encoders' words read through an interface with two data lines crossed; and a multi-start worm stage whose starts
are unevenly indexed. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* spool tension: a wire, fibre tow or tape laid by the tool (cable-harness routing, filament winding, tape laying) runs
  from a spool through a fixed guide eye; a dancer arm or a hysteresis brake holds its tension T constant whatever the
  length paid out (web-tension control: Ebler, Arnason, Michaelis & D'Sa, "Tension control: dancer rolls or load cells",
  IEEE Trans. Ind. Appl. 29, 1993), so the flange is pulled by T along the unit vector towards the eye. The joints yield
  by their compliance: dq = C J_f^T T u (Craig, *Introduction to Robotics*, ch. 5, static forces). Each block lays from
  a new roll whose brake is set anew (T_b per block; unlogged), sized so that the largest pull moves the target 0.2-0.5
  mm. Unlike set V's coiled cord (a spring pull growing with the stretch) or set G's hose catenary (a weight), the pull
  is a constant-magnitude force towards a point, its magnitude a setting per block. Driven by the pose (logged) and the
  tension (not logged). The true structure: one column per block, amplitudes T_b [N].
* coupled wrist: in a wrist whose motors sit in the forearm, the drive of axis 5 passes through axis 4's hollow shaft
  and that of axis 6 through 4 and 5, so each train's angle is theta = T q with T lower-triangular (coupling ratios of
  the bevel stages; Tsai, *Robot Analysis*, 1999, ch. 10, coupled / geared robotic mechanisms); the trains' compliances
  act on their own torques tau_m = T^-T tau, so the joints stand off by dq = T^-1 diag(c) T^-T tau (a compliance matrix
  with off-diagonal terms: a torque on axis 4 also turns axes 5 and 6). Coupling ratios 0.3-1, trains' compliances
  within a factor 2 of each other, sized so that the largest offset moves the target 0.15-0.45 mm; the part (logged as
  the payload) held off the flange's axis. An arm whose wrist motors sit in the forearm (kr16_like; ur10's joints each
  carry their own motor, and on tool_changer it competed with the link model at 1.05-1.32x in trial draws). Unlike the
  diagonal gear compliances of sets A-ZB, the error of one axis follows another axis' torque. Driven by the pose and the
  payload (logged). The true structure: one column per train, amplitudes its compliance [rad/(N m)].
* bayonet play: a tool on a bayonet coupling (lugs in helical slots, a quarter-turn quick change) has a rotational play
  of 0.2-0.6 deg about the tool axis between the lugs and the slots' flanks (quick-change tool couplings, as recalled);
  the tool's supply hose drags it, so after axis 6 turns, the tool lags on the trailing flank by half the play (a lost
  motion about the tool axis chosen by axis 6's last direction: Nordin & Gutman, "Controlling mechanical systems with
  backlash -- a survey", Automatica 38, 2002). The target sits 60-100 mm off the tool axis. Unlike set P's quick change
  (re-seated at each change) or the gear play of sets A-ZB, the play is in the tool's coupling and its flank is set by
  the hose's drag. Driven by axis 6's direction (logged: ``dir6``). The true structure: one column, amplitude the
  half-play [rad].
* air preload: a pneumatic anti-backlash cylinder presses axis 1's drive pinion against one flank while the cell's
  compressed air is on (pneumatically preloaded gear trains, as in positioners and rotary tables: makers' notes, as
  recalled); with the air off (a block run with the air supply shut for maintenance, unlogged) the gear's play is free,
  and the unloaded axis 1 stands on the flank of its last motion's approach (lagging, half the play b / 2). b / 2
  0.1-0.25 mrad (assumed). Unlike set E's scissor gear (a spring always on) or the flank models of sets A-ZB, a block's
  air chooses whether the lash is preloaded. Driven by axis 1's direction (logged) and the air (not logged). The true
  structure: two columns (the last direction in the air-off blocks; a constant in the air-on blocks), amplitudes -b/2
  and b/2.
* swapped bits: the output encoders' absolute words (2^19-2^21 counts a turn) reach the cell's log through a parallel
  interface card with two neighbouring data lines crossed (a wiring fault; parallel binary absolute-encoder outputs:
  makers' data sheets, as recalled); the robot closes its loop on its motor encoders, so the arm stands where it was
  sent and the log holds the word with bits k and k + 1 exchanged: reading = count + (b_(k+1) - b_k) 2^k, the exchange
  its own inverse. The bit k whose weight moves the target 0.15-0.4 mm (first 2^k of 0.006-0.02 deg whatever the arm:
  too much at tool_changer's long reach), on one of axes 1-3. Unlike set ZB's fieldbus rounding (quantisation) or set
  O's counts (a count's width), the error is a digital permutation of the word. Driven by the joint angle (logged). The
  true structure: one column (the signed bit difference), amplitude the weight 2^k of one count's bit [rad].
* multistart worm: a worm of s starts (2-4) drives a wheel of Z teeth (31-61); the starts' index (spacing) errors make
  the wheel's transmission error repeat with each worm turn, i.e. Z / s times per output turn (worm gear accuracy:
  start-to-start index error, DIN 3974 / ISO 1328 single-pitch deviation; Dudley, *Handbook of Practical Gear Design*,
  1984, worm gearing, as recalled); its first two harmonics. Sized so that the target moves 0.15-0.4 mm. Unlike set O's
  tooth-mesh error (Z per turn) or set E's ring gear (once per turn), the error repeats with the worm's turn. Driven by
  the joint's angle (logged). The true structure: four columns (cos, sin of the two harmonics), amplitudes [rad].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_w_joint import _features_of_dq


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _blocks(session, n):
    return np.minimum(block_index(session), n - 1)


# ------------------------------------------------------------------------------------------------- spool tension
def spool_unit(p, ctx, hw):
    """(P, 3) the target's displacement per unit tension [mm/N]: the joints' yield to a unit pull towards the eye."""
    pf, _ = kin.flange(ctx.chain, ctx.q)
    u = p["eye_mm"] - pf
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    Jf = kin.position_jacobian(ctx.chain, ctx.q, pf)
    tau = np.einsum("pij,pi->pj", Jf, u)                      # [N mm per N; N per N]
    tau[:, ctx.chain.revolute] /= 1000.0                     # revolute joints: [N m per N]
    return _features_of_dq(ctx, compliance(hw)[None] * tau)


def spool_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    reach = np.linalg.norm(ctx.target[:, :2], axis=1).max()
    phi = rng.uniform(0, 2 * np.pi)
    p = {"eye_mm": np.array([1.5 * reach * np.cos(phi), 1.5 * reach * np.sin(phi), rng.uniform(1500.0, 2500.0)]),
         "rel": rng.uniform(0.4, 1.0, nb)}
    size = np.linalg.norm(spool_unit(p, ctx, hw), axis=1).max()
    p["T_N"] = p["rel"] * rng.uniform(0.2, 0.5) / max(size, 1e-12)
    return p


def spool_features(p, ctx, hw):
    unit = spool_unit(p, ctx, hw)
    b = _blocks(ctx.session, len(p["T_N"]))
    return np.array([unit * (b == k)[:, None] for k in range(len(p["T_N"]))])


def spool_apply(p, ctx, hw):
    return _amp_apply(p["T_N"], spool_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------- coupled wrist
def wrist_joints(chain):
    return [j for j in (3, 4, 5) if chain.revolute[j]]


def coupling(p, chain):
    """(w, w) the trains' angles per joint angle, lower-triangular with a unit diagonal."""
    w = len(wrist_joints(chain))
    T = np.eye(w)
    T[np.tril_indices(w, -1)] = p["k"][:w * (w - 1) // 2]
    return T


def coupled_features(p, ctx, hw):
    W = wrist_joints(ctx.chain)
    T = coupling(p, ctx.chain)
    Ti = np.linalg.inv(T)
    tau_m = ctx.loads[:, W] @ Ti                              # T^-T tau, per pose (row vectors)
    out = []
    for i in range(len(W)):
        dq = np.zeros_like(ctx.q)
        dq[:, W] = tau_m[:, i:i + 1] * Ti[:, i][None]
        out.append(_features_of_dq(ctx, dq))
    return np.array(out)


def coupled_draw(ctx, hw, rng):
    p = {"k": rng.choice([-1.0, 1.0], 3) * rng.uniform(0.3, 1.0, 3), "rel": np.exp(rng.uniform(-0.35, 0.35, 3))}
    F = coupled_features(p, ctx, hw)
    rel = p["rel"][:len(F)]
    size = np.linalg.norm(np.einsum("k,kpi->pi", rel, F), axis=1).max()
    p["c"] = rel * rng.uniform(0.15, 0.45) / max(size, 1e-12)
    return p


def coupled_apply(p, ctx, hw):
    return _amp_apply(p["c"], coupled_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- bayonet play
BAYONET_JOINT = 5


def bayonet_draw(ctx, hw, rng):
    return {"half": 0.5 * np.deg2rad(rng.uniform(0.2, 0.6))}


def bayonet_features(p, ctx, hw):
    return ctx.joint_feature(BAYONET_JOINT, -ctx.session.direction[:, BAYONET_JOINT])[None]


def bayonet_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, BAYONET_JOINT] = -p["half"] * ctx.session.direction[:, BAYONET_JOINT]
    return Contribution(dq=dq)


# --------------------------------------------------------------------------------------------------- air preload
PRELOAD_JOINT = 0


def air_on(p, session):
    """(P,) 1 in the blocks run with the air on (the pinion preloaded), 0 in those with the air off."""
    return np.asarray(p["air"], float)[_blocks(session, len(p["air"]))]


def preload_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    air = rng.random(nb) < 0.5
    if nb > 1 and (air.all() or not air.any()):
        air[int(rng.integers(nb))] = not air[0]
    return {"air": air.astype(int), "half": rng.uniform(0.1e-3, 0.25e-3)}


def preload_signals(p, session):
    """(2, P) the last direction where the air is off, the constant flank where it is on."""
    on = air_on(p, session)
    return np.array([session.direction[:, PRELOAD_JOINT] * (1 - on), on])


def preload_features(p, ctx, hw):
    return np.array([ctx.joint_feature(PRELOAD_JOINT, s) for s in preload_signals(p, ctx.session)])


def preload_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, PRELOAD_JOINT] = np.array([-p["half"], p["half"]]) @ preload_signals(p, ctx.session)
    return Contribution(dq=dq)


# ------------------------------------------------------------------------------------------------- swapped bits
def swap_signal(p, q):
    """(P,) the logged word less the true count in units of 2^k: b_(k+1) - b_k of the count (its own inverse)."""
    c = np.floor(np.mod(q, 2 * np.pi) / (2 * np.pi) * p["counts"]).astype(np.int64)
    k = p["bit"]
    return ((c >> (k + 1)) & 1).astype(float) - ((c >> k) & 1).astype(float)


def swap_draw(ctx, hw, rng):
    j = int(rng.choice([i for i in (0, 1, 2) if ctx.chain.revolute[i]]))
    counts = 2 ** int(rng.integers(19, 22))
    lever = np.linalg.norm(ctx.jac[:, :, j], axis=1).max()             # [mm/rad]
    want = rng.uniform(0.15, 0.4) / lever / (2 * np.pi) * counts       # the bit whose weight moves the target so far
    k = int(np.clip(np.round(np.log2(want)), 1, 30))
    return {"joint": j, "counts": counts, "bit": k, "weight": 2 * np.pi * 2 ** k / counts}


def swap_features(p, ctx, hw):
    # the true angle is the logged one less the swap: dq = -(reading - count)
    return ctx.joint_feature(p["joint"], -swap_signal(p, ctx.q[:, p["joint"]]))[None]


def swap_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = -p["weight"] * swap_signal(p, ctx.q[:, p["joint"]])
    return Contribution(dq=dq)


# ----------------------------------------------------------------------------------------------- multistart worm
def worm_signals(p, q):
    """(4, P) cos and sin of the first two harmonics of the worm's turn (Z / s per output turn)."""
    x = p["Z"] / p["starts"] * q
    return np.array([np.cos(x), np.sin(x), np.cos(2 * x), np.sin(2 * x)])


def worm_features(p, ctx, hw):
    return np.array([ctx.joint_feature(p["joint"], s) for s in worm_signals(p, ctx.q[:, p["joint"]])])


def worm_draw(ctx, hw, rng):
    p = {"joint": int(rng.choice([i for i in (0, 1) if ctx.chain.revolute[i]])), "starts": int(rng.integers(2, 5)),
         "Z": int(rng.integers(31, 62))}
    a = rng.normal(0, 1, 4) * np.array([1.0, 1.0, 0.5, 0.5])
    F = worm_features(p, ctx, hw)
    size = np.linalg.norm(np.einsum("k,kpi->pi", a, F), axis=1).max()
    p["a"] = a * rng.uniform(0.15, 0.4) / max(size, 1e-12)
    return p


def worm_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joint"]] = p["a"] @ worm_signals(p, ctx.q[:, p["joint"]])
    return Contribution(dq=dq)
