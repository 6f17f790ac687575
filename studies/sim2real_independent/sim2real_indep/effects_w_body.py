"""Set W body effects (new physics, not in sets A-V): the arm on a reinforced-concrete plinth with a flexural crack
across its root, which opens under the moments of one sign; the arm's pedestal on a grout bed poured the day before,
still stiffening as its cement hydrates; the tool on a pneumatic bellows compliance unit whose stroke follows the shop
air's pressure as the compressor cycles; and the target's bracket bent for good in a collision during the production
between two blocks. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* cracked plinth: a reinforced-concrete section cracked in flexure turns with the cracked section's moment of inertia
  I_cr while the crack is open and with the gross section's I_g once the compression closes it (ACI 318-19, 24.2.3.5,
  Branson's effective moment of inertia; I_cr of lightly reinforced sections 0.2-0.35 I_g: MacGregor & Wight,
  *Reinforced Concrete: Mechanics and Design*, ch. 9). The arm's plinth, cast in the floor, has one crack across its
  root h = 300-900 mm below the base, along a horizontal axis a of any heading; the moment about a opens it on one side
  (that sign is part of a's heading). Rotational stiffness with the crack closed 1-3e6 / 5-15e6 / 2-6e7 N m/rad on ur10
  / kr16_like / tool_changer, 3-5 times lower open; about the other axis the closed stiffness (assumed). The gravity
  moment is :func:`effects_body.mount_moment`. The true structure: three columns (about a, open and closed; about b),
  amplitudes the compliances.
* young grout: the pedestal's foot plate was regrouted 0.5-1.5 days before the session; a cementitious grout stiffens as
  it hydrates, its strength f(t) = f_28 t / (a + b t) (ACI 209R-92, eq. 2-1; a = 0.5-1.0, b = 0.90-0.95 for a rapid-
  hardening mix, t in days) and its modulus E ~ sqrt(f) (ACI 318, E_c = 4700 sqrt(f_c')), so the bed's rotational
  compliance falls as sqrt(f(t_0) / f(t)) through the session. The foot at the pedestal's base, 400-900 mm below the
  arm's base; the bed's roll and pitch stiffness at the session's start 0.5-1.5e6 / 4-12e6 / 1-3e7 N m/rad (assumed; the
  bed's share of the mount). A long day of blocks (:func:`effects_w.session_options`); the grout's age is not logged.
  The true structure: two columns (roll and pitch about the foot, times the compliance's fall), amplitudes the
  compliances at the start.
* air bellows: a pneumatic compliance unit (a bellows cylinder carrying the tool along the tool's z, balanced against a
  stiff spring pack: "constant-force" / compliance units for robotic finishing, as recalled) moves by A dp / k with
  the supply pressure and by m g_z / k with the tool's weight along its axis (Hooke; statics of a spring-balanced
  piston). The shop air swings with the compressor's load / unload cycle between a cut-in of 6-6.5 bar and a cut-out
  0.8-1.5 bar higher, loading in 20-35 % of a 2-8 min period (receiver-sizing practice, e.g. Atlas Copco, *Compressed
  Air Manual*, 8th ed., 2015, ch. 3). A / k 0.1-0.4 mm/bar, m g / k 0.02-0.15 mm (assumed). The pressure is not
  logged. The true structure: two columns (the tool's z times the pressure's swing, and times the weight's component
  along it), amplitudes A / k [mm/bar] and m g / k [mm].
* bent bracket: a collision in the production between two blocks bends the target's bracket past its yield (plastic
  hinge at the bracket's root: the deformation stays after the load goes; Timoshenko & Gere, *Mechanics of Materials*,
  plastic bending), so from the next block on the target sits off its former place in the tool frame by 0.15-0.6 mm in a
  direction mostly across the bracket (its axis the tool's z; assumed). The collision is not logged. The true
  structure: three columns (the tool's axes times the step), amplitudes the offset's components [mm].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_u_joint import block_index


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _tilt(ctx, axis, angle, h_mm):
    """(P, 3) the target's displacement for a tilt ``angle`` (P,) about the horizontal ``axis`` through a point h_mm
    below the base."""
    pivot = np.array([0.0, 0.0, -h_mm])
    return np.cross(axis[None] * angle[:, None], ctx.target - pivot)


def _axes(psi):
    return np.array([np.cos(psi), np.sin(psi), 0.0]), np.array([-np.sin(psi), np.cos(psi), 0.0])


# ----------------------------------------------------------------------------------------------- cracked plinth
PLINTH_K = {"ur10": (1e6, 3e6), "kr16_like": (5e6, 15e6), "tool_changer": (2e7, 6e7)}  # closed [N m/rad]


def plinth_open(p, ctx):
    """(P,) True where the moment about the crack's axis opens it."""
    a, _ = _axes(p["psi"])
    return eb.mount_moment(ctx) @ a > 0


def plinth_draw(ctx, hw, rng):
    k_c = rng.uniform(*PLINTH_K[ctx.chain.name])
    return {"psi": rng.uniform(0, 2 * np.pi), "h_mm": rng.uniform(300.0, 900.0),
            "c": np.array([rng.uniform(3.0, 5.0) / k_c, 1 / k_c, 1 / rng.uniform(*PLINTH_K[ctx.chain.name])])}


def plinth_features(p, ctx, hw):
    M = eb.mount_moment(ctx)
    a, b = _axes(p["psi"])
    op = plinth_open(p, ctx)
    Ma, Mb = M @ a, M @ b
    return np.array([_tilt(ctx, a, Ma * op, p["h_mm"]), _tilt(ctx, a, Ma * ~op, p["h_mm"]),
                     _tilt(ctx, b, Mb, p["h_mm"])])


def plinth_apply(p, ctx, hw):
    return _amp_apply(p["c"], plinth_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- young grout
GROUT_K = {"ur10": (0.5e6, 1.5e6), "kr16_like": (4e6, 12e6), "tool_changer": (1e7, 3e7)}  # at the start [N m/rad]


def grout_strength(t_days, a, b):
    """f(t) / f_28 of ACI 209: t / (a + b t)."""
    return t_days / (a + b * t_days)


def grout_fall(p, session):
    """(P,) the bed's compliance relative to the session's start: sqrt(f(t0) / f(t))."""
    t = p["age_d"] + (session.time_s - session.time_s[0]) / 86400.0
    return np.sqrt(grout_strength(p["age_d"], p["a"], p["b"]) / grout_strength(t, p["a"], p["b"]))


def grout_draw(ctx, hw, rng):
    return {"age_d": rng.uniform(0.5, 1.5), "a": rng.uniform(0.5, 1.0), "b": rng.uniform(0.90, 0.95),
            "psi": rng.uniform(0, np.pi), "h_mm": rng.uniform(400.0, 900.0),
            "c": 1 / rng.uniform(*GROUT_K[ctx.chain.name], 2)}


def grout_features(p, ctx, hw):
    M = eb.mount_moment(ctx)
    s = grout_fall(p, ctx.session)
    return np.array([_tilt(ctx, ax, (M @ ax) * s, p["h_mm"]) for ax in _axes(p["psi"])])


def grout_apply(p, ctx, hw):
    return _amp_apply(p["c"], grout_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------- air bellows
def bellows_pressure(p, t_s):
    """(P,) the supply pressure's swing about its mean [bar]: a rise while the compressor loads (fraction ``load`` of
    the period), a fall while it unloads."""
    ph = np.mod(np.asarray(t_s, float) / p["period_s"] + p["phase"], 1.0)
    L = p["load"]
    up = ph / L
    down = 1 - (ph - L) / (1 - L)
    return p["band_bar"] * (np.where(ph < L, up, down) - 0.5)


def bellows_draw(ctx, hw, rng):
    return {"period_s": 60 * rng.uniform(2.0, 8.0), "phase": rng.uniform(0, 1), "load": rng.uniform(0.2, 0.35),
            "band_bar": rng.uniform(0.8, 1.5), "cut_in_bar": rng.uniform(6.0, 6.5),
            "a": np.array([rng.uniform(0.1, 0.4), rng.uniform(0.02, 0.15)])}


def bellows_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    z = Rt[:, :, 2]
    dp = bellows_pressure(p, ctx.session.time_s)
    return np.array([z * dp[:, None], z * (-z[:, 2])[:, None]])   # weight along the tool's z: g (0, 0, -1) . z


def bellows_apply(p, ctx, hw):
    return _amp_apply(p["a"], bellows_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------ bent bracket
def bracket_step(p, session):
    return (block_index(session) >= p["block"]).astype(float)


def bracket_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    block = 1 + int(rng.integers(max(nb // 2, 1)))
    phi = rng.uniform(0, 2 * np.pi)
    d = rng.uniform(0.15, 0.6) * np.array([np.cos(phi), np.sin(phi), rng.uniform(-0.3, 0.3)])
    return {"block": block, "d_mm": d}


def bracket_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    s = bracket_step(p, ctx.session)
    return np.array([Rt[:, :, i] * s[:, None] for i in range(3)])


def bracket_apply(p, ctx, hw):
    return _amp_apply(p["d_mm"], bracket_features(p, ctx, hw))
