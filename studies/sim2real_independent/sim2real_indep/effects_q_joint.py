"""Set Q joint effects (new physics, not in sets A-P): joint-torque-sensor flexures in series with the main axes' gears,
whose overload stops lock them past a torque; a liquid carried in a closed tank on the tool, whose centre of mass moves
as its free surface stays level, twisting the gears; the controller's backlash compensation, set at commissioning and
now off the worn gears' lost motion; the slow tail of a PI-controlled axis' overshoot after each move; the error at the
wave-generator bearing's ball-pass rate of strain-wave gears; and the telescopic stage's draw-wire position sensor.
Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* torque-sensor stops: torque-controlled arms carry a strain-gauge torque sensor -- a flexure -- between each gear's
  output and the link (Hirzinger et al., "DLR's torque-controlled light weight robot III", ICRA 2002; Albu-Schaeffer et
  al., Industrial Robot 34, 2007); the flexure's stiffness is of the order of the gear's, and sensors carry mechanical
  overload stops that close past 1.5-3 times their nominal torque (Kashiri, Malzahn & Tsagarakis, "On the sensor design
  of torque controlled actuators", IEEE RA-L 2, 2017). The position loop reads the motor side, so the link trails by the
  flexure's twist, tau / k up to the stop's torque and no further (the stop rigid). Axes 2 and 3, stops at 40-70 % of
  the session's largest load (the sensor sized for the arm's dynamic torques, here the static ones exceed its nominal),
  twist at the stop 1.5-4e-4 rad (assumed). The true structure: a column per axis, clip(tau, +-T_stop), amplitude 1 / k.
* fluid tank: a closed tank on the tool (a dispensing or spraying tool's supply of paint, sealant, coolant) is part
  full; the liquid's free surface stays level, so the liquid fills the tank's lowest fraction in every pose and its
  centre of mass moves within the tank (the free-surface effect of naval architecture: Rawson & Tupper, *Basic Ship
  Theory*, 5th ed., 2001, ch. 4). Its weight at that centre twists the gears by their linear compliance (the drives'
  catalogue stiffness, :func:`hardware.torsion`). A box tank of half-sizes 50-90 mm (ur10, kr16_like) or 100-160 mm
  (tool_changer), its centre 80-160 mm out along the tool axis and 30-80 mm across, 30-70 % full of a liquid of 1000-
  1300 kg/m^3 (assumed); the liquid is not logged (the payload column logs the tool's rated load). The true structure:
  one column (the twist per kilogram), amplitude the liquid's mass.
* backlash compensation: controllers add a backlash value to the command at each reversal of an axis, in the new
  direction (Siemens SINUMERIK 840D function manual, "Backlash compensation", MD32450; FANUC parameter 1851), set at
  commissioning. The output rests on the flank its load pushes it to (+b/2 sign(tau)) or, unloaded, trails the last
  motion by b/2 (:func:`physics.backlash_offset`); the compensation shifts it by +b_c/2 in the motion direction,
  whichever flank holds it. Main axes 1-3; lost motion now 2-4 arcmin on cycloid gears (RV catalogues: 1 arcmin new),
  1-2 on strain-wave gears, the compensation 0.5-1.2 times the new gear's value (assumed); a load holds the flank above
  5-15 % of the axis' largest, and never below 3 % of the gear's rated torque (the output's friction). The true
  structure: two columns per axis (flank, direction), amplitudes b / 2 and b_c / 2.
* servo tail: a PI velocity loop inside a P position loop makes the position loop type 2; after a move at speed v it
  overshoots in the motion direction by a share of the following error v / K_v and the integrator's slow mode removes
  it with the time constant T_i of the integral action (Ellis, *Control System Design Guide*, 4th ed., 2012, ch. 6 and
  17 on PI velocity loops and position loops; Gross, Hamann & Wiegaertner, *Electrical Feed Drives in Automation*,
  2001: following error v / K_v). A soft tuning on heavy arms: the overshoot 1-3e-3 s times the move's speed, T_i
  1.5-4 s (assumed), left at the measurement after the dwell. Every revolute axis; the mean speed of the move into the
  pose (from the logged angles and times). The true structure: a column per axis, direction x speed x exp(-dwell /
  T_i), amplitude the overshoot per speed.
* ball pass: the wave generator of a strain-wave gear runs on a thin-section ball bearing; a ball of another size (or a
  cage pocket's error) loads the flexspline each time it passes the ellipse's major axes, twice per turn of the cage
  relative to the wave generator; the cage turns at f_c = (1 - (d / D_p) cos alpha) / 2 of the wave generator's speed
  (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. 8), so the error has 2 (1 - f_c) N periods per
  output turn (N the ratio; harmonic drive kinematic error beyond the 2-per-wave-generator-turn tooth component: Tuttle
  & Seering, IEEE T-RA 12, 1996; Ghorbel, Gandhi & Alpeter, J. Mech. Des. 123, 2001). Ratios 80-160, d / D_p 0.15-0.25,
  amplitudes 10-30 arcsec (assumed; first 8-25); the strain-wave axes of each arm, the cage not slipping over the
  session (assumed). The true structure: two columns per axis (cos, sin), amplitudes the error's components.
* draw wire: the telescopic stage of tool_changer reads its absolute position from a draw-wire sensor (a steel wire
  wound on a spring-returned drum turning an encoder; wireSENSOR / ASM data sheets: linearity 0.02-0.1 % of a 0.5-2 m
  range); the drum of radius r turns about an axis off its centre by e, so the wire paid out differs from r theta by
  e (cos(theta + phi) - cos phi); and the retraction spring's force F0 + k_s x stretches the free wire (length x + L0)
  by (F0 + k_s x)(x + L0) / EA (Gere & Timoshenko, *Mechanics of Materials*: axial bar). Drums of 30-50 mm radius,
  eccentricity 20-60 um, spring 5-12 N at 0.5-1.5 N per 100 mm, stranded wire 0.45-0.6 mm (EA 1.5-3e4 N) over 200-400
  mm of free length at x = 0 (assumed). The controller closes the loop on the reading: the stage stands off by the
  error. The true structure: three columns (the stretch's x and x^2 terms, the drum's eccentricity), amplitudes -1.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

ARCSEC = np.pi / (180 * 3600)


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


# ----------------------------------------------------------------------------------------- torque-sensor stops
SENSOR_JOINTS = (1, 2)


def sensor_draw(ctx, hw, rng):
    js = [j for j in SENSOR_JOINTS if ctx.chain.revolute[j]]
    T_stop = rng.uniform(0.4, 0.7, len(js)) * np.abs(ctx.loads[:, js]).max(axis=0)
    return {"joints": js, "T_stop": T_stop, "k": T_stop / rng.uniform(1.5e-4, 4e-4, len(js))}


def sensor_signals(p, ctx):
    """(m, P): the torque through each flexure [N m], clipped at its stops."""
    tau = ctx.loads[:, p["joints"]].T
    return np.clip(tau, -p["T_stop"][:, None], p["T_stop"][:, None])


def sensor_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = (sensor_signals(p, ctx) / p["k"][:, None]).T
    return Contribution(dq=dq)


def sensor_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], sensor_signals(p, ctx))])


# ------------------------------------------------------------------------------------------------ fluid tank
TANK_HALF_MM = {"ur10": (50.0, 90.0), "kr16_like": (50.0, 90.0), "tool_changer": (100.0, 160.0)}
TANK_GRID = 12


def tank_draw(ctx, hw, rng):
    half = rng.uniform(*TANK_HALF_MM[ctx.chain.name], 3)
    az = rng.uniform(0, 2 * np.pi)
    centre = np.array([np.cos(az), np.sin(az), 0.0]) * rng.uniform(30.0, 80.0) + [0, 0, rng.uniform(80.0, 160.0)]
    fill = rng.uniform(0.3, 0.7)
    rho = rng.uniform(1000.0, 1300.0)
    return {"half_mm": half, "centre_mm": centre, "fill": fill, "mass_kg": rho * fill * np.prod(2 * half) * 1e-9}


def tank_points(p):
    """(K, 3): the tank's volume sampled on a regular grid (cell centres), tool frame [mm]."""
    u = (np.arange(TANK_GRID) + 0.5) / TANK_GRID * 2 - 1
    g = np.stack(np.meshgrid(u, u, u, indexing="ij"), -1).reshape(-1, 3)
    return p["centre_mm"] + g * p["half_mm"]


def tank_com(p, ctx):
    """(P, 3): the liquid's centre of mass in the base frame -- the mean of the tank's lowest ``fill`` share."""
    pts = tank_points(p)
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    z = np.einsum("pj,kj->pk", Rt[:, 2, :], pts)                      # heights over the flange (P, K)
    n = int(round(p["fill"] * len(pts)))
    low = np.argsort(z, axis=1, kind="stable")[:, :n]
    local = pts[low].mean(axis=1)                                      # (P, 3) tool frame
    return fl + np.einsum("pij,pj->pi", Rt, local)


def tank_signal(p, ctx, hw):
    """(P, n): each joint's twist per kilogram of liquid [rad/kg or mm/kg] (its load times the drive's compliance)."""
    com = tank_com(p, ctx)[:, None]
    tau = kin.gravity_loads(ctx.chain, ctx.q, np.ones(1), com, np.array([ctx.chain.n]))
    comp = np.array([hwm.torsion(d, 1.0, False) for d in hw["drives"]])
    return tau * comp


def tank_apply(p, ctx, hw):
    return Contribution(dq=p["mass_kg"] * tank_signal(p, ctx, hw))


def tank_features(p, ctx, hw):
    s = tank_signal(p, ctx, hw)
    return np.sum([ctx.joint_feature(j, s[:, j]) for j in range(ctx.chain.n)], axis=0)[None]


# ------------------------------------------------------------------------------------ backlash compensation
COMP_JOINTS = (0, 1, 2)


def comp_draw(ctx, hw, rng):
    js = [j for j in COMP_JOINTS if ctx.chain.revolute[j]]
    rv = np.array([hw["drives"][j]["kind"] == "RV" for j in js])
    b = np.where(rv, rng.uniform(2.0, 4.0, len(js)), rng.uniform(1.0, 2.0, len(js))) * ph.ARCMIN
    b_c = np.where(rv, 1.0, 0.5) * rng.uniform(0.5, 1.2, len(js)) * ph.ARCMIN
    T_r = np.array([hw["drives"][j]["T_rated"] for j in js])
    hold = np.maximum(rng.uniform(0.05, 0.15, len(js)) * np.abs(ctx.loads[:, js]).max(axis=0), 0.03 * T_r)
    return {"joints": js, "b": b, "b_c": b_c, "hold": hold}


def comp_signals(p, ctx):
    """(2m, P): per axis the flank (+-1: the load's or against the last motion) and the direction."""
    tau, d = ctx.loads[:, p["joints"]].T, ctx.session.direction[:, p["joints"]].T
    flank = np.where(np.abs(tau) > p["hold"][:, None], np.sign(tau), -d)
    return np.concatenate([flank, d])


def comp_amplitudes(p):
    return np.r_[p["b"] / 2, p["b_c"] / 2]


def comp_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    m = len(p["joints"])
    s = comp_amplitudes(p)[:, None] * comp_signals(p, ctx)
    dq[:, p["joints"]] = (s[:m] + s[m:]).T
    return Contribution(dq=dq)


def comp_features(p, ctx, hw):
    js = list(p["joints"]) * 2
    return np.array([ctx.joint_feature(j, s) for j, s in zip(js, comp_signals(p, ctx))])


# ----------------------------------------------------------------------------------------------- servo tail
def tail_draw(ctx, hw, rng):
    js = [int(j) for j in np.flatnonzero(ctx.chain.revolute)]
    return {"joints": js, "A_s": rng.uniform(1e-3, 3e-3, len(js)), "T_i": rng.uniform(1.5, 4.0, len(js))}


def tail_signals(p, ctx):
    """(m, P): direction x mean speed of the move [rad/s] x the integrator's decay over the dwell."""
    s = ctx.session
    js = p["joints"]
    return (s.direction[:, js] * s.speed[:, js] * np.exp(-s.dwell_s[:, None] / p["T_i"][None])).T


def tail_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = (p["A_s"][:, None] * tail_signals(p, ctx)).T
    return Contribution(dq=dq)


def tail_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, s) for j, s in zip(p["joints"], tail_signals(p, ctx))])


# ------------------------------------------------------------------------------------------------- ball pass
def pass_draw(ctx, hw, rng):
    js = [j for j, d in enumerate(hw["drives"]) if d["kind"] == "HD"]
    N = rng.integers(80, 161, len(js)).astype(float)
    fc = 0.5 * (1 - rng.uniform(0.15, 0.25, len(js)) * np.cos(np.deg2rad(rng.uniform(0.0, 15.0, len(js)))))
    amp = rng.uniform(10.0, 30.0, len(js)) * ARCSEC
    ph0 = rng.uniform(0, 2 * np.pi, len(js))
    return {"joints": js, "N": N, "f_c": fc, "order": 2 * (1 - fc) * N,
            "ab": np.c_[amp * np.cos(ph0), amp * np.sin(ph0)]}


def pass_signals(p, ctx):
    """(2m, P): cos and sin of the ball-pass phase of each axis."""
    th = ctx.q[:, p["joints"]] * p["order"][None]
    return np.concatenate([np.cos(th).T, np.sin(th).T])


def pass_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    m = len(p["joints"])
    s = pass_signals(p, ctx)
    dq[:, p["joints"]] = (p["ab"][:, 0:1] * s[:m] + p["ab"][:, 1:2] * s[m:]).T
    return Contribution(dq=dq)


def pass_features(p, ctx, hw):
    js = list(p["joints"]) * 2
    return np.array([ctx.joint_feature(j, s) for j, s in zip(js, pass_signals(p, ctx))])


def pass_amplitudes(p):
    return np.r_[p["ab"][:, 0], p["ab"][:, 1]]


# ------------------------------------------------------------------------------------------------- draw wire
WIRE_ARMS = {"tool_changer": 3}


def wire_draw(ctx, hw, rng):
    if ctx.chain.name not in WIRE_ARMS:
        return {}
    return {"joint": WIRE_ARMS[ctx.chain.name], "r_mm": rng.uniform(30.0, 50.0), "e_mm": rng.uniform(0.02, 0.06),
            "phi": rng.uniform(0, 2 * np.pi), "F0_N": rng.uniform(5.0, 12.0), "ks_N_mm": rng.uniform(0.005, 0.015),
            "EA_N": rng.uniform(1.5e4, 3e4), "L0_mm": rng.uniform(200.0, 400.0)}


def wire_terms(p, x):
    """(3, P): the reading's error terms [mm] at stroke x: the wire's stretch (linear and quadratic in x) and the
    drum's eccentricity (all per their own amplitude of 1: see :func:`wire_error`)."""
    th = x / p["r_mm"]
    stretch_lin = (p["F0_N"] + p["ks_N_mm"] * p["L0_mm"]) * x / p["EA_N"]
    stretch_sq = p["ks_N_mm"] * x ** 2 / p["EA_N"]
    ecc = p["e_mm"] * (np.cos(th + p["phi"]) - np.cos(p["phi"]))
    return np.array([stretch_lin, stretch_sq, ecc])


def wire_error(p, x):
    """The wire paid out minus what the reading assumes [mm]: stretch plus eccentricity; the stage stands short of its
    command by it (the loop drives the reading to the command)."""
    return -wire_terms(p, x).sum(axis=0)


def wire_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = wire_error(p, ctx.q[:, p["joint"]])
    return Contribution(dq=dq)


def wire_features(p, ctx, hw):
    """Three columns: the stretch's linear and quadratic terms and the drum's eccentricity at its drawn phase (the
    shape parameters known), amplitudes -1 each."""
    if not p:
        return _empty(ctx)
    t = wire_terms(p, ctx.q[:, p["joint"]])
    return np.array([ctx.joint_feature(p["joint"], s) for s in t])
