"""Set ZK joint effects (new physics, not in sets A-ZJ): the gravity feed-forward of current-based (soft-servo) joint
control falling short as the motors' magnets warm and their torque constant drops; a cable-capstan stage whose free
spans lengthen and shorten as the joint turns; the hysteresis of joint torque sensors read by a joint-impedance
controller; axis 1's lost motion widened as its housing spreads under the arm's tilting moment; axis 1's ring gear
distorted out of round by its hardening; and axis 1's magnetic ring encoder read across an air gap that the axial
bearing load sets. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* magnet warming (``kt_magnet_drift``): in current-based compliant control -- soft-servo / "soft float" modes of
  industrial controllers and the proprioceptive torque control of sensorless cobots (Wensing et al., IEEE T-RO 33,
  2017; Albu-Schaeffer, Ott & Hirzinger, IJRR 26, 2007, for the joint-impedance law) -- the controller holds the
  gravity torque by a feed-forward current i = g(q) / K_t and lets the low position gain K take any rest; a permanent
  magnet motor's torque constant follows its magnets' remanence, which falls by 0.09-0.12 %/K for NdFeB (Hendershot &
  Miller, *Design of Brushless Permanent-Magnet Machines*, 2010, ch. 3; magnet makers' data sheets, as recalled), so a
  magnet dT warmer leaves beta dT g(q) to the position gain: dq = beta dT g(q) / K. The rotors warm as a lumped node
  (tau 25-50 min, 0-30 % warm at the start, 1.5-2.5 times the measuring blocks' heat in production, cooling in the
  pauses); K of 2e3-2e4 N m/rad and dT of 20-40 K give 0.3-3 mm at the tool, sized to 0.25-0.6 mm. The loaded axes 2
  and 3. Unlike set ZJ's torque-sensor zero drift (an offset without load) or set ZG's declared payload (a wrong load,
  not a drifting torque per amp), the error is the whole gravity torque times the magnets' warming. Driven by the pose
  and the payload (logged) and the magnets' temperature (not logged; the production and pauses that set it are, as
  gaps in the time stamps). The true structure: one column per axis (load times node), amplitudes beta dT / K.
* capstan spans (``capstan_spans``): a cable-capstan stage (a steel cable wrapped on a capstan of radius r, its ends
  fixed to a sector of radius R on the joint; lightweight arms such as the WAM: Townsend, *The effect of transmission
  design on force-controlled manipulator performance*, MIT PhD thesis, 1988; Baser & Konukseven, Mech. Mach. Theory
  45, 2010) has two free spans L1,2 = L0 -+ R (q - q_c) between the tangent points, one lengthening as the other
  shortens; their stiffnesses EA / L_i act in parallel at the sector, so the joint's compliance is
  L1 L2 / (R^2 EA (L1 + L2)) = (L0^2 - R^2 u^2) / (2 L0 R^2 EA), u = q - q_c: stiffest at the ends of the sector's
  travel. The sector's centre q_c within 30 % of the half range from the measured range's centre (the cable's
  terminations set at assembly) and R u_far / L0 = 0.85-0.95 at the farther end, the span there nearly wound off
  (assumed); sized to 0.25-0.6 mm. ur10's wrist axes 4 and 5 (an assumed cable-driven wrist, as the WAM's). (First
  axes 2 and 3 with a centred sector and 0.6-0.9 at the ends: ZK02 ambiguous with the link model at 1.04x; then with
  the centre shifted and the spans nearly wound off, 1.06x -- on ur10 the upper arm's and forearm's joint compliance
  bends the arm as its tubes' bending does; the wrist's short links are not the link model's.) Unlike set E's mesh
  stiffness varying along the turn (tooth contact), set F's lever stiffness (a cylinder's lever arm) or set P's belt
  slack (a span dropping out), the spans' lengths change with the angle. Driven by the pose and the payload (logged).
  The true structure: one column per axis (load times (1 - (rho u / u_far)^2)), amplitudes 1 / (2 L0 R^2 EA).
* torque-sensor hysteresis (``sensor_hysteresis``): a strain-gauge joint torque sensor's flexure and bond give a
  hysteresis of 0.02-0.2 % of full scale between rising and falling loads (HBM / ATI specifications, as recalled;
  Hoffmann, *An Introduction to Stress Analysis and Transducer Design using Strain Gauges*, HBM, 2012); in a
  joint-impedance controller (Albu-Schaeffer et al., above) the reading's error e moves the joint by e / K. The error
  is a play operator of the load (the simplest Preisach element: Visintin, *Differential Models of Hysteresis*, 1994):
  the reading lags a rising load by up to r and a falling one by up to r, r 3-8 % of the session's load range. Axes 2
  and 3 (assumed torque-sensing builds); sized to 0.25-0.6 mm. Unlike set ZJ's zero drift (temperature), set ZD's
  crosstalk (bending moment) or set Q's overload stops, the error follows the load's last change, not its value.
  Driven by the pose sequence and the payload (logged). The true structure: one column per axis, amplitudes r / K.
* housing spread (``housing_spread``): the backlash of a spur or helical final stage changes with its centre distance,
  j_n = j_n0 + 2 da sin(alpha_n) (ISO 21771:2007, sec. 8; Niemann & Winter, *Maschinenelemente* II, 1989, ch. 21),
  and axis 1's gear housing spreads under the bearing couple of the arm's tilting moment (the moment carried by the
  two bearings as forces M / s: da = M / (s k_h)); so axis 1's lost motion b = b0 + b1 |M_h| / M_ref with b1 / b0 of
  1-3 at the session's largest moment (a light cast housing, assumed), 1-3 arcmin. Axis 1 carries no gravity torque on
  a level base: its output trails its last motion by b / 2. Unlike set D's varying lash (an eccentric gear, a function
  of the angle) or set K's thermal lash, the width follows the load on the housing. Driven by the pose, the payload
  and the last motion (logged). The true structure: two columns (trailing flank, and flank times |M_h| / M_ref),
  amplitudes b0 / 2, b1 / 2.
* hardening distortion (``quench_ovality``): a large ring gear induction- or case-hardened and not ground after
  hardening keeps its quench distortion, an ovality and a four-lobed out-of-roundness of 0.05-0.5 mm on its pitch
  circle (Totten & Howes, *Steel Heat Treatment Handbook*, 1997, ch. on distortion; slewing-ring gears are commonly
  left unground), which a pinion reads as transmission error e_k tan(alpha) / R at orders 2 and 4 per turn (radial
  runout into TE: Smith, *Gear Noise and Vibration*, 2nd ed., 2003, ch. 3). Axis 1's ring gear (tool_changer,
  kr16_like), sized to 0.25-0.6 mm. Unlike set A's gear (orders 1, N, 2N), set E's ring gear (cumulative pitch), set
  X's ring lobing (the encoder's ring clamped into three lobes) or set ZJ's ghost order (the hobbing machine), the
  error is the gear's heat-treatment distortion. Driven by axis 1's angle (logged). The true structure: four columns
  (sin, cos at orders 2 and 4).
* ride height (``ride_height``): a magnetic ring encoder's errors (the ring's magnetisation and the head's
  alignment, mostly once and twice per turn) grow as the read head's air gap opens, the field's harmonics decaying as
  exp(-2 pi g / lambda) (Renishaw / RLS ring-encoder data on ride height, as recalled; Furlani, *Permanent Magnet and
  Electromechanical Devices*, 2001, ch. 4); axis 1's ring on the rotating part and its head on the base see the gap
  set by the slewing bearing's axial deflection under the weight above it, delta ~ W^(2/3) (Hertz: Harris &
  Kotzalas, *Rolling Bearing Analysis*, 2007), so the error scales as 1 + gamma (W^(2/3) - W_0^(2/3)) / W_0^(2/3).
  gamma 0.3-0.8 (a gap opening of some 0.1 mm on 0.2-0.5 mm), parts of 0-1 times the arm's payload changed between
  blocks, sized to 0.25-0.6 mm. Unlike set N's magnetic drift (the errors growing with the encoders' warming) or set
  Z's head tilt (the bearing's tilt under the moment), the gap follows the axial load. Driven by axis 1's angle and
  the payload (logged). The true structure: eight columns (sin, cos at orders 1, 2, each plain and load-scaled).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_joint import _size_cols, loaded_joints
from sim2real_indep.effects_zj_thermal import gap_node
from sim2real_indep.session import BOXES


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


# ---------------------------------------------------------------------------------------------------- magnet warming
def magnet_node(p, session):
    """(P,) the magnets' warming per unit (1 measuring, w_prod in production, 0 in the pauses)."""
    return gap_node(session, p["T0"], p["tau_s"], 1.0, p["w_prod"], 0.0)


def kt_draw(ctx, hw, rng):
    p = {"tau_s": 60 * rng.uniform(25.0, 50.0), "T0": rng.uniform(0.0, 0.3), "w_prod": rng.uniform(1.5, 2.5)}
    p["c"] = _size_cols(kt_features(p, ctx, hw), rng)  # positive: the joints sag with their loads
    return p


def kt_features(p, ctx, hw):
    T = magnet_node(p, ctx.session)
    return np.array([ctx.joint_feature(j, ctx.loads[:, j] * T) for j in loaded_joints(ctx.chain)])


def kt_apply(p, ctx, hw):
    return _amp_apply(p["c"], kt_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- capstan spans
def span_factor(p, j, q):
    """(P,) the compliance's dependence on the angle: 1 - (rho u / u_far)^2, u from the sector's centre q_c, u_far
    the measured range's end farthest from it."""
    lo, hi = (np.deg2rad(v[j]) for v in BOXES[p["robot"]])
    qc = (lo + hi) / 2 + p["shift"][j] * (hi - lo) / 2
    u = (q - qc) / max(hi - qc, qc - lo)
    return 1.0 - (p["rho"][j] * u) ** 2


def capstan_joints(chain):
    """The cable-driven wrist axes 4 and 5."""
    return [j for j in (3, 4) if j < chain.n and chain.revolute[j]]


def capstan_draw(ctx, hw, rng):
    js = capstan_joints(ctx.chain)
    p = {"robot": ctx.chain.name if ctx.chain.name in BOXES else "ur10",
         "rho": {j: float(rng.uniform(0.85, 0.95)) for j in js},
         "shift": {j: float(rng.uniform(-0.3, 0.3)) for j in js}}
    p["c"] = _size_cols(capstan_features(p, ctx, hw), rng)
    return p


def capstan_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, ctx.loads[:, j] * span_factor(p, j, ctx.q[:, j]))
                     for j in capstan_joints(ctx.chain)])


def capstan_apply(p, ctx, hw):
    return _amp_apply(p["c"], capstan_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- sensor hysteresis
def play(x, r, y0=None):
    """(P,) the play operator of the path x with half-width r, from y0 (default x[0])."""
    y = x[0] if y0 is None else y0
    out = np.empty(len(x))
    for k, v in enumerate(x):
        y = min(max(y, v - r), v + r)
        out[k] = y
    return out


def hysteresis_error(p, ctx, j):
    """(P,) the sensor's error per unit r on axis j: (play(tau) - tau) / r, in [-1, 1]."""
    tau = ctx.loads[:, j]
    r = p["r"][j]
    return (play(tau, r) - tau) / r


def hyst_draw(ctx, hw, rng):
    js = loaded_joints(ctx.chain)
    p = {"r": {j: float(np.ptp(ctx.loads[:, j]) * rng.uniform(0.03, 0.08)) + 1e-9 for j in js}}
    p["a"] = _size_cols(hyst_features(p, ctx, hw), rng, rng.uniform(0.5, 1.5, len(js)) * rng.choice([-1, 1]))
    return p


def hyst_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, hysteresis_error(p, ctx, j)) for j in loaded_joints(ctx.chain)])


def hyst_apply(p, ctx, hw):
    return _amp_apply(p["a"], hyst_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- housing spread
def housing_moment(ctx):
    """(P,) the tilting moment on axis 1's bearings [N m]: the horizontal part of the gravity moment."""
    return np.linalg.norm(mount_moment(ctx)[:, :2], axis=1)


def spread_draw(ctx, hw, rng):
    p = {"M_ref": float(housing_moment(ctx).max()) + 1e-9, "ratio": rng.uniform(1.0, 3.0)}
    p["b"] = _size(spread_features(p, ctx, hw), [1.0, p["ratio"]], rng)  # half widths b0 / 2, b1 / 2 [rad]
    return p


def spread_features(p, ctx, hw):
    trail = -ctx.session.direction[:, 0]
    return np.array([ctx.joint_feature(0, trail), ctx.joint_feature(0, trail * housing_moment(ctx) / p["M_ref"])])


def spread_apply(p, ctx, hw):
    return _amp_apply(p["b"], spread_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- quench ovality
ORDERS = (2, 4)


def ovality_draw(ctx, hw, rng):
    p = {}
    ph = rng.uniform(0, 2 * np.pi, len(ORDERS))
    w = np.array([rng.uniform(0.6, 1.0), rng.uniform(0.2, 0.5)])  # the oval larger than the four lobes
    rel = np.ravel([[wk * np.cos(a), wk * np.sin(a)] for wk, a in zip(w, ph)])
    p["e"] = _size_cols(ovality_features(p, ctx, hw), rng, rel)
    return p


def ovality_features(p, ctx, hw):
    th = ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, f(k * th)) for k in ORDERS for f in (np.sin, np.cos)])


def ovality_apply(p, ctx, hw):
    return _amp_apply(p["e"], ovality_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- ride height
def axial_load(ctx):
    """(P,) the weight on axis 1's bearing [N]: the arm's and the payload's."""
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * kin.G


def gap_scale(ctx):
    """(P,) (W^(2/3) - W0^(2/3)) / W0^(2/3), W0 the arm without payload."""
    W = axial_load(ctx)
    W0 = float(np.sum(ctx.masses)) * kin.G
    return (W ** (2 / 3) - W0 ** (2 / 3)) / W0 ** (2 / 3)


def ride_draw(ctx, hw, rng):
    p = {"gamma": rng.uniform(0.3, 0.8)}
    ph = rng.uniform(0, 2 * np.pi, 2)
    w = np.array([rng.uniform(0.5, 1.0), rng.uniform(0.3, 0.8)])
    base = np.ravel([[wk * np.cos(a), wk * np.sin(a)] for wk, a in zip(w, ph)])
    p["e"] = _size(ride_features(p, ctx, hw), np.r_[base, p["gamma"] * base], rng)
    return p


def ride_features(p, ctx, hw):
    th, d = ctx.q[:, 0], gap_scale(ctx)
    plain = [ctx.joint_feature(0, f(k * th)) for k in (1, 2) for f in (np.sin, np.cos)]
    return np.array(plain + [f * d[:, None] for f in plain])


def ride_apply(p, ctx, hw):
    return _amp_apply(p["e"], ride_features(p, ctx, hw))
