"""Set Z body effects (new physics, not in sets A-Y): the arm's base on elastomer isolators of a high-damping compound
that soften as the hall warms them; the base on a fabricated table whose thin top plate snaps between its two dished
shapes as the arm's tipping moment swings; the upper arm bowed by a harness strapped taut along one side of it, whose
tension grows as the elbow bends away from the angle at which the harness runs straight through it; and a welded
gripper frame carrying the target distorting as the production's vibration relaxes its welding stresses. Same protocol
as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* warm isolators: the base plate stands on four elastomer isolators of a high-damping compound (butyl, or a filled
  natural rubber) used close to its glass transition, where the dynamic modulus falls by 1-3 % per kelvin (Gent,
  *Engineering with Rubber*, 3rd ed., 2012, ch. 4 on temperature effects; Nashif, Jones & Henderson, *Vibration
  Damping*, 1985, temperature-frequency dependence of damping polymers). Unlike set L's polymer gears (the gears' teeth
  heated by their drives, a joint's twist) the support's isolators follow the hall's air. The base tilts about the
  isolators' plane (30-80 mm below the base) by c(T) M, M the arm's horizontal gravity moment
  (:func:`effects_body.mount_moment`), c(T) = c_20 (1 + beta (T_iso - 20)), beta 3-6 %/K (a compound chosen to damp at
  room temperature works in its transition region, where the modulus falls by a decade over some 30-40 K); the isolators
  follow the hall's air through a first-order lag of 20-60 min (rubber conducts badly; Incropera & DeWitt, ch. 5), and
  the session is a working morning in a hall that warms or cools by 8-14 K. Sized so that the largest moment tilts the
  base by 0.25-0.6 mrad at 20 degC. Unlike set S's Mullins mounts (softening by the largest load so far) or set G's air
  isolators (their pressure), the stiffness follows the temperature. Driven by the pose, the payload and the air
  temperature (all logged). The true structure: two columns (the tilt per unit compliance, and that times T_iso - 20),
  amplitudes c_20 and c_20 beta.
* oil canning: the arm bolted to a fabricated steel table whose thin top plate between its stiffeners is slightly dished
  (welding distortion); a shallow dished plate is bistable and snaps through to its other shape when the load exceeds
  its snap-through load, and snaps back only at the opposite one (snap-through of shallow shells: Timoshenko & Gere,
  *Theory of Elastic Stability*, 2nd ed., 1961, ch. 11; "oil canning" of thin panels). The arm's tipping moment about a
  horizontal axis m (the plate's weak direction, drawn) loads it: the plate was bolted down and dished under the arm's
  mean moment M_c, so its state s flips to +1 when M . m - M_c exceeds +M_s and to -1 below -M_s, M_s 20-50 % of the
  half-range of M . m over the session (a play operator of the moment), and the snap's travel w 0.05-0.15 mm under one
  edge of the base, 300-500 mm from the other, turns the base by w / b about m. Unlike set F's plate uplift (a
  decompressing bolted joint, elastic) or set S's Mullins mounts, the base turns by a fixed step between two states that
  the moment's history chooses. Driven by the pose and the payload (logged) through the history. The true structure: one
  column (the turn about m by s), amplitude w / b [rad].
* bowstring: a harness (a cable bundle in a corrugated sleeve) strapped taut along one side of the upper arm, at e 30-60
  mm from its neutral axis, runs across the elbow through the joint's hollow axis: its path is shortest at the angle
  q3_0 where it runs straight through and grows as (a b / (a + b)) (q3 - q3_0)^2 / 2 for clamps a and b either side of
  the axis (the geometry of a string over a hinge), so its tension grows with the square of the elbow's bend. An
  eccentric axial tension T bends the tube to a uniform curvature T e / EI (a beam under end moments: Roark, *Formulas
  for Stress and Strain*, beams, end couples) away from the harness' side: the elbow turns by kappa L and moves by kappa
  L^2 / 2. Sized so that the largest bend of the session moves the elbow 0.1-0.25 mm. Unlike set Y's vision lamp (a
  thermal bow) or set D's dress pack (the joints loaded by the pack's stiffness), the link bends by the harness'
  eccentric pull. Driven by the elbow's angle (logged). The true structure: one column (the bow per unit curvature times
  ((q3 - q3_0) / the range's half-width)^2), amplitude the curvature [1/mm].
* stress relief: a welded steel gripper frame whose arm reaches 300 mm along the tool's x, the target at its end, holds
  welding residual stresses at the arm's root weld; the vibration of the production (the arm's own moves and the
  process' shocks) relaxes them, and the arm bends at its root towards its relaxed shape, fast at first and then slower
  -- the principle of vibratory stress relief (Claxton, "Vibratory stress relieving", Metallurgia 1974; Walker, Waddell
  & Johnston, "Vibratory stress relief -- an investigation of the underlying processes", Proc. IMechE E 209, 1995): the
  arm's end moves across the arm (in the tool's y-z plane, along a drawn heading) by d (1 - exp(-E / tau_v)), E the
  production hours so far, tau_v 0.5-1.5 h, d 0.1-0.3 mm (assumed). Unlike set V's bolt loosening (a boom's root bolts,
  move by move) or set W's bent bracket (a collision's permanent bend), the frame's own residual stresses relax with the
  production's time. Driven by the production time (not logged). The true structure: two columns (the tool's y and z
  times 1 - exp(-E / tau_v)), amplitudes the relaxed move's components [mm].
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_w_joint import machining_s
from sim2real_indep.effects_y_thermal import lamp_side, link_bow, upper_arm


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _tilt(ctx, rot, h_mm):
    """(P, 3) the target's displacement for base turns ``rot`` (P, 3) [rad] about a point h_mm below the base."""
    return np.cross(rot, ctx.target - np.array([0.0, 0.0, -h_mm]))


# ------------------------------------------------------------------------------------------------- warm isolators
def iso_temperature(p, session):
    return ph.first_order_foh(session.time_s, session.air_c, p["tau_s"])


def iso_draw(ctx, hw, rng):
    M = mount_moment(ctx)
    Mh = np.linalg.norm(M[:, :2], axis=1).max()
    tilt = rng.uniform(0.25e-3, 0.6e-3)
    return {"h_mm": rng.uniform(30.0, 80.0), "tau_s": 60.0 * rng.uniform(20.0, 60.0), "beta": rng.uniform(0.03, 0.06),
            "c20": tilt / max(Mh, 1e-9)}


def iso_features(p, ctx, hw):
    M = mount_moment(ctx)
    rot = np.zeros_like(M)
    rot[:, :2] = M[:, :2]
    base = _tilt(ctx, rot, p["h_mm"])
    dT = (iso_temperature(p, ctx.session) - 20.0)[:, None]
    return np.array([base, base * dT])


def iso_apply(p, ctx, hw):
    return _amp_apply([p["c20"], p["c20"] * p["beta"]], iso_features(p, ctx, hw))


# --------------------------------------------------------------------------------------------------- oil canning
def can_axis(p):
    return np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])


def can_state(p, ctx):
    """(P,) the plate's state +-1: a play operator of the moment about its weak axis."""
    m = mount_moment(ctx) @ can_axis(p) - p["Mc"]
    s, out = p["s0"], np.zeros(len(m))
    for k, v in enumerate(m):
        if v > p["Ms"]:
            s = 1.0
        elif v < -p["Ms"]:
            s = -1.0
        out[k] = s
    return out


def can_draw(ctx, hw, rng):
    psi = rng.uniform(0, 2 * np.pi)
    m = mount_moment(ctx) @ np.array([np.cos(psi), np.sin(psi), 0.0])
    w, b = rng.uniform(0.05, 0.15), rng.uniform(300.0, 500.0)
    Mc, half = 0.5 * (m.max() + m.min()), 0.5 * (m.max() - m.min())
    return {"psi": psi, "Mc": Mc, "Ms": rng.uniform(0.2, 0.5) * half, "s0": float(rng.choice([-1.0, 1.0])),
            "w_mm": w, "b_mm": b, "turn": w / b, "h_mm": rng.uniform(100.0, 250.0)}


def can_features(p, ctx, hw):
    rot = can_axis(p)[None] * can_state(p, ctx)[:, None]
    return _tilt(ctx, rot, p["h_mm"])[None]


def can_apply(p, ctx, hw):
    return _amp_apply([p["turn"]], can_features(p, ctx, hw))


# ----------------------------------------------------------------------------------------------------- bowstring
BOW_JOINT = 2


def bow_tension(p, ctx):
    """(P,) the harness' tension per its value at the range's edge: ((q3 - q3_0) / half-width)^2."""
    return ((ctx.q[:, BOW_JOINT] - p["q0"]) / p["half"]) ** 2


def bow_draw(ctx, hw, rng):
    q = ctx.q[:, BOW_JOINT]
    lo, hi = q.min(), q.max()
    q0 = lo + (hi - lo) * rng.uniform(0.3, 0.7)
    half = max(hi - q0, q0 - lo)
    li = upper_arm(ctx.chain)
    L = np.linalg.norm(ctx.chain.links[li])
    move = rng.uniform(0.1, 0.25)
    return {"q0": q0, "half": half, "psi": rng.uniform(0, 2 * np.pi), "e_mm": rng.uniform(30.0, 60.0),
            "elbow_mm": move, "kappa": 2 * move / L ** 2}


def bow_features(p, ctx, hw):
    li = upper_arm(ctx.chain)
    bow = link_bow(ctx, li, lamp_side(ctx.chain, li, p["psi"]))
    return (bow * bow_tension(p, ctx)[:, None])[None]


def bow_apply(p, ctx, hw):
    return _amp_apply([p["kappa"]], bow_features(p, ctx, hw))


# -------------------------------------------------------------------------------------------------- stress relief
FRAME_MM = 300.0   # the frame's arm along the tool's x; the target at its end


def relief_share(p, session):
    """(P,) 1 - exp(-E / tau_v), E the production time so far."""
    return -np.expm1(-machining_s(session) / p["tau_s"])


def relief_draw(ctx, hw, rng):
    ang, d = rng.uniform(0, 2 * np.pi), rng.uniform(0.1, 0.3)
    return {"tau_s": 3600.0 * rng.uniform(0.5, 1.5), "psi": ang, "d_mm": d,
            "amp": d * np.array([np.cos(ang), np.sin(ang)])}


def relief_features(p, ctx, hw):
    """(2, P, 3): the arm's end moved across the arm (the tool's y and z) as its root weld relaxes."""
    Rt = kin.flange(ctx.chain, ctx.q)[1]
    g = relief_share(p, ctx.session)[:, None]
    return np.array([Rt[:, :, 1] * g, Rt[:, :, 2] * g])


def relief_apply(p, ctx, hw):
    return _amp_apply(p["amp"], relief_features(p, ctx, hw))
