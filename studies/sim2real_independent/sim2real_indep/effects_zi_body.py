"""Set ZI body effects (new physics, not in sets A-ZH): the target on a free swivel that its unbalance turns downhill
as far as the seal friction lets it; the base on a granular bed that densifies under each move's moment; an unanchored
base rocking on its bowed sole plate against its own weight; a part floating on a Bernoulli gripper's air film; and
a part held in a granular jamming gripper that locked its shape when the block began. Same protocol as
:mod:`effects_joint`.

Sources:

* free swivel: a dispensing nozzle on a free swivel about the tool axis (a rotary union without a drive, so that its
  hose does not wind up) carries an unbalance m e; gravity's component across the axis turns it downhill with the
  torque m g e s sin(psi - phi) (s the share of gravity across the axis, psi its direction in the tool's plane), and
  the seals' friction T_f holds it anywhere within asin(f / s) of psi, f = T_f / (m g e) 0.1-0.4 (a pendulum with
  Coulomb friction: Den Hartog, *Mechanical Vibrations*, 4th ed., 1956, ch. 8, dry friction; rotary-union seal drag
  from makers' data, as recalled); where s < f it stays. The target on the swivel's end, 0.25-0.6 mm off its axis (the
  nest's adapter runout and the swivel's radial play). Unlike set ZH's loose pivot (a pin between two stops) or set
  T's plunger stiction (an axial play), the swivel turns continuously and stops at the friction band's edge. Driven by
  the tool's attitude sequence (logged pose). The true structure: two columns (the offset's two components).
* gravel ratchet: the base frame stands on a levelled bed of compacted gravel / sand (a temporary or outdoor cell). A
  granular bed densifies under repeated loading and its permanent settlement accumulates with the number of cycles,
  fast at first (Sawicki & Swidzinski, "Mechanics of a sandy subsoil subjected to cyclic loadings", Int. J. Numer. Anal.
  Meth. Geomech. 13, 1989; Wichtmann, Niemunis & Triantafyllidis, "Strain accumulation in sand due to cyclic loading",
  Soil Dyn. Earthq. Eng. 25, 2005: accumulation ~ ln(1 + N)); each move loads the bed with its pose's moment, so the
  edge under it sinks a little more: dtheta_k = a M_k / (N0 + k), theta the base's rotation about the moment's axis at
  the bed's level h 100-400 mm below the base, N0 20-200 cycles since the bed was levelled. Unlike set ZG's settlement
  tilt (a steady rate in time), set J's grout creep (the moment's history in time) or set L's anchor self-loosening (a
  compliance growing with the cycles), the tilt ratchets along each move's moment. Sized to 0.25-0.6 mm. Driven by the
  pose sequence and the payload (logged). The true structure: one column, amplitude a [rad / (N m)].
* crowned sole: an unanchored base (a mobile cell's base plate) set on the floor on a sole plate bowed along its length
  by its welding distortion rocks on it like a rocking chair about the bow's crest line (a horizontal axis e, any
  heading): a rigid body on a convex surface of radius R_c turns about its contact by theta = (M . e) / (W R_c) under a
  moment M, W the weight it stands with (rolling equilibrium of a rigid body on a curved base: Timoshenko & Young,
  *Engineering Mechanics*, 4th ed., 1956, stability of equilibrium; Housner, "The behavior of inverted pendulum
  structures during earthquakes", Bull. Seismol. Soc. Am. 53, 1963); across e the flat width stands firm. The base
  and its pedestal of 0.5-1.5 times the arm's mass, the sole h 300-800 mm below the base, the part changed between
  blocks, so W changes. (First a sole crowned both ways, rocking about the moment's own axis under a pedestal of 1-2.5
  times the arm: on tool_changer the link model at 1.07x, on kr16_like ambiguous, 5.3 % -- a tilt along the moment
  turns the arm in its plane as the joints' and links' compliance do; a 1-1.8 m riser changed nothing; now one axis,
  on ur10 and kr16_like.) Unlike the elastic mounts of sets A-ZH (a compliance of the support), the stiffness is the
  weight itself. Sized to 0.25-0.6 mm. Driven by the pose and payload (logged). The true structure: one column,
  amplitude 1 / R_c [1 / m].
* Bernoulli grip: a Bernoulli (non-contact) gripper holds a flat part (glass, a wafer, a solar cell) on an air film:
  the radial outflow's low pressure pulls it, the film's cushion pushes it off near the face, and the part floats at
  the gap where the net pull balances its weight's share along the face normal N = m g (n . g_hat), held sideways by
  friction pads (Brun & Melkote, "Modeling and prediction of the flexible part behavior in a Bernoulli gripper", J.
  Manuf. Sci. Eng. 131, 2009; Li, Kagawa et al., "Analysis of a non-contact Bernoulli gripper", Precis. Eng. 2015): a
  force-gap curve steep on the cushion side, so h(N) = h0 + a1 N + a2 N^2 about the unloaded gap. Parts of 0.2-8 kg
  changed between blocks; the target on the part 40 mm beyond the face. Unlike set S's diaphragm or set T's plunger
  (mechanical flexures) the support is an air film whose gap the normal load sets. Sized to 0.25-0.6 mm. Driven by
  the tool's attitude and the payload (logged). The true structure: two columns (N and N^2 along the face normal).
* jamming grip: a granular jamming gripper (a membrane of coffee-like grains that flows around the part and jams as
  it is evacuated: Brown et al., "Universal robotic gripper based on the jamming of granular material", PNAS 107,
  2010; Amend et al., IEEE Trans. Robot. 28, 2012) locks the part's seat in the shape it had when it jammed -- at the
  block's first pose, where the part is handed in -- and then holds it with the finite shear stiffness of the jammed
  grains, so the part tilts by c (M - M_0) with the change of its weight's moment about the seat since then (M =
  m g d (z x g_t), d 30-80 mm). Parts of 0.2-10 kg changed between blocks; the target on the part 40 mm beyond.
  Unlike set K's RCC, set X's printed fingers or set Y's foam pad (a tilt of the current moment), the reference is
  the jamming pose of each block. Sized to 0.25-0.6 mm. Driven by the tool's attitude and payload (logged). The true
  structure: one column, amplitude c [rad / (N m)].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_joint import _size_cols

PART_MM = 40.0  # the target on the held part, beyond the gripper's face along the tool axis
G = kin.G


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def tool_frame(ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt


def gravity_in_tool(Rt):
    """(P, 3) the unit gravity (0, 0, -1) in the tool frame."""
    return -Rt[:, 2, :]


def _block_starts(session):
    """(P,) the index of the first pose of each pose's block (a block begins after a gap or with a new part)."""
    start = np.zeros(len(session.gap_s), int)
    new = (session.gap_s != 0) | (np.diff(session.payload_kg, prepend=session.payload_kg[0]) != 0)
    for k in range(1, len(start)):
        start[k] = k if new[k] else start[k - 1]
    return start


# ---------------------------------------------------------------------------------------------------- free swivel
def swivel_angle(p, g_t):
    """(P,) the unbalance's angle in the tool's plane: it stays within asin(f / s) of the downhill direction."""
    psi = np.arctan2(g_t[:, 1], g_t[:, 0])
    s = np.hypot(g_t[:, 0], g_t[:, 1])
    phi = np.empty(len(psi))
    last = psi[0] + p["u0"]
    for k in range(len(psi)):
        if s[k] > p["f"]:
            band = np.arcsin(p["f"] / s[k])
            d = np.angle(np.exp(1j * (last - psi[k])))
            last = psi[k] + np.clip(d, -band, band)
        phi[k] = last
    return phi


def swivel_draw(ctx, hw, rng):
    p = {"f": rng.uniform(0.1, 0.4), "u0": rng.uniform(-0.3, 0.3)}
    beta = rng.uniform(0, 2 * np.pi)  # the target's offset from the axis, at any angle to the unbalance
    p["e"] = _size(swivel_features(p, ctx, hw), [np.cos(beta), np.sin(beta)], rng)
    return p


def swivel_features(p, ctx, hw):
    Rt = tool_frame(ctx)
    phi = swivel_angle(p, gravity_in_tool(Rt))
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    return np.array([Rt[:, :, 0] * c + Rt[:, :, 1] * s, -Rt[:, :, 0] * s + Rt[:, :, 1] * c])


def swivel_apply(p, ctx, hw):
    return _amp_apply(p["e"], swivel_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- gravel ratchet
def ratchet_tilt(p, M):
    """(P, 3) the accumulated rotation per unit a: sum over the moves so far of M_xy / (N0 + k)."""
    k = np.arange(1, len(M) + 1)
    return np.cumsum(M * np.array([1.0, 1.0, 0.0]) / (p["N0"] + k)[:, None], axis=0)


def ratchet_draw(ctx, hw, rng):
    p = {"N0": rng.uniform(20.0, 200.0), "h_mm": rng.uniform(100.0, 400.0)}
    p["a"] = _size(ratchet_features(p, ctx, hw), [1.0], rng)
    return p


def ratchet_features(p, ctx, hw):
    th = ratchet_tilt(p, mount_moment(ctx))
    return np.cross(th, ctx.target - np.array([0.0, 0.0, -p["h_mm"]]))[None]


def ratchet_apply(p, ctx, hw):
    return _amp_apply(p["a"], ratchet_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- crowned sole
def standing_weight(p, ctx):
    """(P,) the weight [N] the base stands with: the arm, its part and the base's own mass."""
    m, _, _ = ctx.mass_state
    return (m.sum(axis=1) + p["base_kg"]) * G


def sole_draw(ctx, hw, rng):
    arm_kg = float(np.sum(ctx.masses))
    p = {"base_kg": arm_kg * rng.uniform(0.5, 1.5), "h_mm": rng.uniform(300.0, 800.0), "psi": rng.uniform(0, np.pi)}
    p["inv_Rc"] = _size(sole_features(p, ctx, hw), [1.0], rng)
    return p


def rocking_axis(p):
    """The horizontal axis the sole rocks about (the bow's crest line lies across its long side)."""
    return np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])


def sole_features(p, ctx, hw):
    e = rocking_axis(p)
    th = np.outer(mount_moment(ctx) @ e / standing_weight(p, ctx), e)  # [m] per unit 1 / R_c [1 / m]
    return np.cross(th, ctx.target - np.array([0.0, 0.0, -p["h_mm"]]))[None]


def sole_apply(p, ctx, hw):
    return _amp_apply(p["inv_Rc"], sole_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- Bernoulli grip
def normal_load(ctx):
    """(P,) the part's weight along the face normal (tool z) [N]: positive pulls it off the face."""
    return ctx.session.payload_kg * G * gravity_in_tool(tool_frame(ctx))[:, 2]


def bernoulli_draw(ctx, hw, rng):
    p = {}
    p["a"] = _size_cols(bernoulli_features(p, ctx, hw), rng, [1.0, rng.uniform(0.3, 1.0)])
    return p


def bernoulli_features(p, ctx, hw):
    Rt = tool_frame(ctx)
    N = normal_load(ctx)
    n = Rt[:, :, 2]
    return np.array([n * N[:, None], n * (N * np.abs(N))[:, None] / max(np.abs(N).max(), 1e-9)])


def bernoulli_apply(p, ctx, hw):
    return _amp_apply(p["a"], bernoulli_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- jamming grip
def seat_moment(p, ctx):
    """(P, 3) the part's weight moment about its seat in the tool frame [N m], less its value at the block's first
    pose (when the grains jammed)."""
    g_t = gravity_in_tool(tool_frame(ctx))
    M = np.cross([0.0, 0.0, p["d_mm"] / 1000.0], g_t) * (ctx.session.payload_kg * G)[:, None]
    return M - M[_block_starts(ctx.session)]


def jamming_draw(ctx, hw, rng):
    p = {"d_mm": rng.uniform(30.0, 80.0)}
    p["c"] = _size(jamming_features(p, ctx, hw), [1.0], rng)
    return p


def jamming_features(p, ctx, hw):
    Rt = tool_frame(ctx)
    rot = seat_moment(p, ctx)  # the tilt per unit c, tool frame
    arm = np.array([0.0, 0.0, p["d_mm"] + PART_MM])  # the target beyond the seat
    return np.einsum("pij,pj->pi", Rt, np.cross(rot, arm))[None]


def jamming_apply(p, ctx, hw):
    return _amp_apply(p["c"], jamming_features(p, ctx, hw))
