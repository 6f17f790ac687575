"""Set ZE body effects (new physics, not in sets A-ZD): the arm on a slender pedestal column whose tilt the weight
amplifies (P-delta); the arm on a slewing ring whose tilting clearance lets the base rock towards the overturning
moment; a tool boom along which a shuttle carriage is parked at a new station each block; and a lightly damped tool
boom still ringing from the last stop when the tracker measures. Same protocol as :mod:`effects_joint`.

Sources:

* slender pedestal: a riser column of height H 1.5-2.5 m (a tall pedestal bringing the arm over a machine) bends under
  the arm's overturning moment M: its head turns by M H / EI and shifts by M H^2 / (2 EI), a rotation about a point
  H / 2 below the base; the column also carries the arm's and the part's weight W, and a compressed slender column's
  bending is amplified by 1 / (1 - W / W_cr) (the P-delta or beam-column effect: Timoshenko & Gere, *Theory of Elastic
  Stability*, 2nd ed., 1961, ch. 1), W_max / W_cr 0.4-0.7 (a slender riser). The part is new each block (logged). Sized
  so that the target moves 0.6-1.0 mm (first W / W_cr 0.3-0.6 and 0.25-0.6 mm: ZE09 and ZE22 gained 8 and 13 %, the
  link and joint models within 1.05x -- a riser that slender sways that far; at the final ranges still the link model
  at 1.11x on tool_changer and 0.99x on kr16_like: under a heavy arm the part is a small share of the column's load, the
  amplification nearly constant and the tilt a linear one; the pedestal is under ur10 alone, ZE04, whose part is up to
  a quarter of the load). Unlike the linear mount compliances of sets A-ZD, the tilt's compliance grows
  with the weight on the column. Driven by the pose and the payload (logged). The true structure: one column,
  amplitude H / EI [rad/(N m)].
* slewing rock: the arm on a slewing-ring bearing (a turntable seventh axis) whose tilting clearance (axial and radial
  play of a four-point ball ring; Rothe Erde slewing-bearing catalogue, as recalled: 0.1-0.3 mrad of tilt) lets the
  base rock towards the overturning moment's axis; the balls take up the play progressively as the moment grows,
  theta = theta_c M / sqrt(|M|^2 + M_c^2), M_c 10-25 % of the largest moment, about the ring's plane 150-400 mm below
  the base. Unlike set M's carriage play (a track carriage across its rollers, one axis) or the linear mounts, the
  rock follows the moment's direction in the plane with a saturating size. Sized to 0.25-0.6 mm. Driven by the pose and
  the payload (logged). The true structure: one column, amplitude theta_c [rad]. First also under tool_changer
  (ZE16, with the PCM tool): its moment hardly turns within axis 1's +-60 deg, the ring stays rocked one way and the
  rock was absorbed (its removal cost nothing); it is on kr16_like alone (ZE17).
* shuttle boom: an aluminium tool boom L (400 mm on ur10, 700 on the others) along the tool's x carrying the target at
  its tip and a shuttle carriage (a feeder or a camera slide, m 1-3 / 3-8 / 15-40 kg on ur10 / kr16_like /
  tool_changer) parked at a station a 0.2-1.0 L, a new one each block (unlogged). A cantilever's tip deflects under a
  point load at a by W_perp a^2 (3 L - a) / (6 EI) (Roark's *Formulas for Stress and Strain*, 7th ed., table 8.1, case
  1a), W_perp the weight's share across the boom. Unlike sets A-ZD's booms (a load at the tip, or the part's weight),
  the load's station moves along the boom from block to block. Sized to 0.25-0.6 mm. Driven by the pose (logged) and
  the station (not logged). The true structure: one column, amplitude m g L^3 / (6 EI) [mm per unit].
* ringing boom: a slender tool boom (450 mm along the tool's z, carrying the target) of first bending frequency f 3-6 Hz and damping
  ratio zeta 0.005-0.02 (welded steel, little structural damping) is excited by the stop's deceleration (the move's
  mean tool speed v = J qdot taken out over its 0.5 s ramp); its residual vibration (Singer & Seering, "Preshaping
  command inputs to reduce system vibration", ASME J. Dyn. Syst. 112, 1990) is, at the measurement after the dwell t_d,
  a_perp / omega^2 |sinc(omega T_r / 2)| exp(-zeta omega t_d) cos(omega_d t_d): the tracker catches the boom still
  swinging. Unlike every earlier kind (static or thermal states), the error is the unsettled dynamics of the last
  move. Sized to 0.25-0.6 mm. Driven by the move and the dwell (logged: joint angles and time stamps), with the
  boom's modal data unknown. The true structure: one column, amplitude the modal gain (dimensionless).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_u_joint import block_index
from sim2real_indep.effects_ze_joint import _size

G = kin.G


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def total_weight_N(ctx):
    """(P,) the weight [N] of the arm and the part on the mount."""
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * G


def _horizontal_moment(ctx):
    M = mount_moment(ctx).copy()
    M[:, 2] = 0.0
    return M


# ---------------------------------------------------------------------------------------------------- slender pedestal
def pedestal_amplification(p, ctx):
    """(P,) the P-delta amplification 1 / (1 - W / W_cr)."""
    return 1.0 / (1.0 - total_weight_N(ctx) / p["W_cr_N"])


def pedestal_draw(ctx, hw, rng):
    p = {"H_mm": rng.uniform(1500.0, 2500.0)}
    p["W_cr_N"] = total_weight_N(ctx).max() / rng.uniform(0.4, 0.7)
    p["c"] = _size(pedestal_features(p, ctx, hw), [1.0], rng, 0.6, 1.0)
    return p


def pedestal_features(p, ctx, hw):
    M = _horizontal_moment(ctx) * pedestal_amplification(p, ctx)[:, None]
    root = np.array([0.0, 0.0, -0.5 * p["H_mm"]])
    return np.cross(M, ctx.target - root)[None]


def pedestal_apply(p, ctx, hw):
    return _amp_apply(p["c"], pedestal_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- slewing rock
def rock_axis(p, ctx):
    """(P, 3) the rock's axis times its share of the clearance: M / sqrt(|M|^2 + M_c^2)."""
    M = _horizontal_moment(ctx)
    return M / np.sqrt((M ** 2).sum(axis=1) + p["M_c"] ** 2)[:, None]


def rock_draw(ctx, hw, rng):
    Mmax = np.linalg.norm(_horizontal_moment(ctx), axis=1).max()
    p = {"M_c": Mmax * rng.uniform(0.10, 0.25), "depth_mm": rng.uniform(150.0, 400.0)}
    p["theta"] = _size(rock_features(p, ctx, hw), [1.0], rng)
    return p


def rock_features(p, ctx, hw):
    root = np.array([0.0, 0.0, -p["depth_mm"]])
    return np.cross(rock_axis(p, ctx), ctx.target - root)[None]


def rock_apply(p, ctx, hw):
    return _amp_apply(p["theta"], rock_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- shuttle boom
SHUTTLE_L_MM = {"ur10": 400.0, "kr16_like": 700.0, "tool_changer": 700.0}


def station_factor(p, session):
    """(P,) a^2 (3 L - a) / (2 L^3) of the block's station (1 at the tip)."""
    b = np.minimum(block_index(session), len(p["station"]) - 1)
    a = np.asarray(p["station"], float)[b]
    return a ** 2 * (3.0 - a) / 2.0


def shuttle_draw(ctx, hw, rng):
    nb = int(block_index(ctx.session).max()) + 1
    p = {"station": np.round(rng.uniform(0.2, 1.0, nb), 3), "L_mm": SHUTTLE_L_MM[ctx.chain.name]}
    p["amp"] = _size(shuttle_features(p, ctx, hw), [1.0], rng)
    return p


def shuttle_features(p, ctx, hw):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    e = Rt[:, :, 0]                                            # the boom's axis
    g = np.array([0.0, 0.0, -1.0])
    perp = g - e * (e @ g)[:, None]
    return (perp * station_factor(p, ctx.session)[:, None])[None]


def shuttle_apply(p, ctx, hw):
    return _amp_apply(p["amp"], shuttle_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ringing boom
RING_RAMP_S = 0.5
RING_MM = 450.0


def ring_response(p, session):
    """(P,) the boom's residual vibration per unit quasi-static deflection at the measurement."""
    w = 2 * np.pi * p["f_hz"]
    z = p["zeta"]
    wd = w * np.sqrt(1 - z ** 2)
    x = w * RING_RAMP_S / 2
    t = session.dwell_s
    return np.abs(np.sin(x) / x) * np.exp(-z * w * t) * np.cos(wd * t)


def ring_unit(p, ctx):
    """(P, 3) the stop's deceleration across the boom over omega^2 [mm]."""
    s = ctx.session
    v = np.einsum("pij,pj->pi", ctx.jac, s.speed * s.direction)        # mm/s into the pose
    a = v / RING_RAMP_S
    _, Rt = kin.flange(ctx.chain, ctx.q)
    e = Rt[:, :, 2]
    a_perp = a - e * np.einsum("pi,pi->p", a, e)[:, None]
    return a_perp / (2 * np.pi * p["f_hz"]) ** 2


def ring_draw(ctx, hw, rng):
    p = {"f_hz": rng.uniform(3.0, 6.0), "zeta": rng.uniform(0.005, 0.02)}
    p["gain"] = _size(ring_features(p, ctx, hw), [1.0], rng)
    return p


def ring_features(p, ctx, hw):
    return (ring_unit(p, ctx) * ring_response(p, ctx.session)[:, None])[None]


def ring_apply(p, ctx, hw):
    return _amp_apply(p["gain"], ring_features(p, ctx, hw))
