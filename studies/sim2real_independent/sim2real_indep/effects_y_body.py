"""Set Y body effects (new physics, not in sets A-X): the arm's base plate walking on its friction-grip bolted joint
under the shocks of a neighbouring press through the production; the arm on a three-wheeled cart one of whose pneumatic
tyres leaks; a part held on a foam-sealed vacuum pad that compresses and shears under the part's weight; and a long,
thin panel held at one edge that bends under its own weight across its thickness. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* press walk: a base plate held to its pedestal by preloaded bolts carries shear by friction (VDI 2230 Part 1, 2015;
  slip-critical joints); the ground shock of a stamping press beside the cell adds at each stroke a transverse impulse
  that lets the joint micro-slip, and under a steady bias (the arm's own cycle reaction, the floor's slope) the plate
  ratchets a little further each stroke -- the walking of friction joints under transverse vibration (Junker, SAE Trans.
  78, 1969, on transverse slip; Pai & Hess, "Three-dimensional finite element analysis of threaded fastener loosening
  due to dynamic shear load", Eng. Fail. Anal. 9, 2002: accumulated slip per cycle). Unlike a collision's single slip
  (set X) the plate creeps at a steady rate while the presses run (the production between the blocks): slides of
  0.08-0.25 mm/h along a heading, turns of 0.004-0.015 deg/h about the base axis (assumed). Driven by the production
  time (no column logs it). The true structure: three columns (the two slides and the turn, times the production hours
  so far), amplitudes the rates.
* tyre leak: the arm on a mobile cart standing on three pneumatic tyres (statically determinate); a tyre's vertical
  deflection under a fixed load goes as 1 / p (its stiffness grows with the inflation pressure: Rhyne, "Development of a
  vertical stiffness relationship for belted radial tires", Tire Sci. Technol. 33(3), 2005), and a slow leak through a
  small hole lets the pressure fall as exp(-t / tau) (isothermal outflow through an orifice, choked: dp/dt proportional
  to p), so the leaking tyre's corner sinks by delta0 (exp(t / tau) - 1) and the cart turns about the line through the
  other two (the geometry of set X's levelling foot, which sinks with the production's vibration, linearly; here the
  time and the pressure's exponential law drive it). Tyres 300-500 mm from the base axis, 300-600 mm below it, delta0
  2-5 mm at the session's start, tau 30-80 h (a seeping valve core or a nail hole: a tyre that goes flat over days,
  assumed). Driven by the time (the ``time_s`` column); the pressure is not logged. The true structure: one column (the
  turn per mm of sink times exp(t / tau) - 1), amplitude delta0 [mm].
* foam gripper: a part held on a foam-sealed vacuum pad (area grippers, e.g. Schmalz FMP / Piab foam grippers, as
  recalled) rests on the foam, which the vacuum's pull compresses once (absorbed by the geometry) and the part's weight
  then compresses along the pad's axis by its normal component and shears across it by the rest; a thin elastomeric
  layer's shear compliance is E / G = 2 (1 + nu), i.e. 2.0-2.7 times its normal one for foams of nu 0-0.35 (Gibson &
  Ashby, *Cellular Solids*, 2nd ed., 1997, ch. 5: Poisson's ratios of foams). Sized so that the session's heaviest part
  compresses the pad by 0.1-0.25 mm along its axis (a soft, open-cell foam 15-30 mm thick that seals on uneven parts).
  The part's mass is the payload column (logged); the target sits on the part, 50 mm along the tool's z. Unlike set X's
  suction cup (a tilt under the part's moment) the pad moves the part along and across its axis with the weight itself.
  The true structure: one column ((W.z) z + (E / G) W_perp), amplitude the normal compliance [mm/N].
* sheet part: a long, thin panel (a stiffened sheet-metal part) held along one edge by the gripper and reaching 400 mm
  along the tool's x bends under its own weight across its thickness (the tool's y) as a cantilever under a uniform
  load, delta = q L^4 / (8 E I) with q = W_y / L (Roark, *Formulas for Stress and Strain*, cantilever, uniformly
  distributed load); in its own plane it is stiff. Sized so that the session's heaviest part hanging flat sags its edge
  by 0.2-0.6 mm (a ribbed panel). The part's mass is the payload column (logged); the target sits at the free edge.
  Unlike set X's printed fingers (the fingers bending under the part) the part itself bends, across one axis only. The
  true structure: one column ((W.y) y), amplitude the panel's compliance [mm/N].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_w_joint import machining_s
from sim2real_indep.effects_x_body import foot_geometry


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _weight(ctx):
    """(P, 3) the part's weight [N], base frame."""
    W = np.zeros((len(ctx.q), 3))
    W[:, 2] = -kin.G * ctx.session.payload_kg
    return W


# ----------------------------------------------------------------------------------------------------- press walk
def walk_hours(session):
    """(P,) the production hours so far (the exercise gaps: the presses running)."""
    return machining_s(session) / 3600.0


def walk_draw(ctx, hw, rng):
    ang, v = rng.uniform(0, 2 * np.pi), rng.uniform(0.08, 0.25)
    w = np.deg2rad(rng.uniform(0.004, 0.015)) * rng.choice([-1.0, 1.0])
    return {"amp": np.array([v * np.cos(ang), v * np.sin(ang), w])}


def walk_features(p, ctx, hw):
    E = walk_hours(ctx.session)[:, None]
    ez = np.array([0.0, 0.0, 1.0])
    return np.array([E * np.array([1.0, 0, 0]), E * np.array([0, 1.0, 0]), E * np.cross(ez, ctx.target)])


def walk_apply(p, ctx, hw):
    return _amp_apply(p["amp"], walk_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------------ tyre leak
def leak_growth(p, session):
    """(P,) exp(t / tau) - 1, t from the session's first pose."""
    return np.expm1((session.time_s - session.time_s[0]) / p["tau_s"])


def leak_draw(ctx, hw, rng):
    return {"r_mm": rng.uniform(300.0, 500.0), "h_mm": rng.uniform(300.0, 600.0), "psi": rng.uniform(0, 2 * np.pi),
            "delta0": rng.uniform(2.0, 5.0), "tau_s": 3600.0 * rng.uniform(30.0, 80.0)}


def leak_features(p, ctx, hw):
    _, e, pt, d = foot_geometry(p)
    return (np.cross(e, ctx.target - pt) / d * leak_growth(p, ctx.session)[:, None])[None]


def leak_apply(p, ctx, hw):
    return _amp_apply([p["delta0"]], leak_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- foam gripper
FOAM_MM = 50.0


def foam_load(p, ctx):
    """(P, 3) (W.z) z + (E / G) W_perp [N]: the weight's normal part and its shear part weighted by the foam's E / G."""
    z = kin.flange(ctx.chain, ctx.q)[1][:, :, 2]
    W = _weight(ctx)
    Wn = np.einsum("pi,pi->p", W, z)[:, None] * z
    return Wn + p["E_over_G"] * (W - Wn)


def foam_draw(ctx, hw, rng):
    nu = rng.uniform(0.0, 0.35)
    sag = rng.uniform(0.1, 0.25)
    return {"nu": nu, "E_over_G": 2 * (1 + nu), "sag_mm": sag,
            "c": sag / (kin.G * max(ctx.session.payload_kg.max(), 0.1))}


def foam_features(p, ctx, hw):
    return foam_load(p, ctx)[None]


def foam_apply(p, ctx, hw):
    return _amp_apply([p["c"]], foam_features(p, ctx, hw))


# ------------------------------------------------------------------------------------------------------ sheet part
SHEET_MM = 400.0


def sheet_load(ctx):
    """(P, 3) (W.y) y [N]: the weight's component across the panel (the tool's y)."""
    y = kin.flange(ctx.chain, ctx.q)[1][:, :, 1]
    return np.einsum("pi,pi->p", _weight(ctx), y)[:, None] * y


def sheet_draw(ctx, hw, rng):
    sag = rng.uniform(0.2, 0.6)
    return {"sag_mm": sag, "c": sag / (kin.G * max(ctx.session.payload_kg.max(), 0.1))}


def sheet_features(p, ctx, hw):
    return sheet_load(ctx)[None]


def sheet_apply(p, ctx, hw):
    return _amp_apply([p["c"]], sheet_features(p, ctx, hw))
