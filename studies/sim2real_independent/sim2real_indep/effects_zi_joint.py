"""Set ZI joint effects (new physics, not in sets A-ZH): the loaded axes' PI position loops still recovering from the
pose-to-pose step of their gravity load when the point is taken; the outputs of axes 2 and 3 tilted by the axial
thrust of their helical final stages; axis 1 twisted by its dress pack, whose rotary guide a dog drags with a wide
play; axis 2's tooth-mesh error switching between its two flanks' profile errors with the load's sign; and axis 1's
output encoder misread by the non-repeatable runout that turns with its bearing's cage. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* PI load step: a joint servo without model-based gravity feed-forward (a retrofit or PLC motion controller) holds a
  static load with the integral term of its PI position / velocity loop; when the next pose's load differs by dtau
  the proportional term first takes the step, a position error dtau / K, which the integral action removes with its
  time constant T_i (the load-disturbance response of a PI loop: Astrom & Hagglund, *Advanced PID Control*, 2006, sec.
  4.2; Ellis, *Control System Design Guide*, 4th ed., 2012, ch. 6): the error left at the dwell's end is c dtau
  exp(-t_dwell / T_i), T_i 1.5-5 s against dwells of 3-8 s. Unlike set Q's servo tail (the overshoot of the last
  motion, direction x speed) or set U's integrator clamp (a static sag beyond the clamp), the error follows the change
  of the load from the previous pose. Axes 2 and 3. Sized to 0.25-0.6 mm. Driven by the pose sequence and the payload
  (logged) and the dwell (not logged; the time stamps hold it with the move). The true structure: one column per
  axis, amplitude c [rad / (N m)].
* helix tilt: a helical final stage (helix angle beta 15-25 deg) carries its tangential mesh force F_t = tau / r with
  an axial component F_t tan(beta) at the mesh, r off the output's axis (ISO 21771:2007, helical gear geometry; the
  bearing loads of helical gears: Niemann & Winter, *Maschinenelemente* vol. II, 1989, ch. 21); its moment tau
  tan(beta) tilts the output about e_r x a (e_r the direction of the mesh from the axis, fixed in the housing, a the
  axis) through the output bearing's moment rigidity (crossed-roller catalogues: IKO / THK, moment rigidity of some
  1e5-1e6 N m/rad, as recalled). Unlike set C's bearing tilt (the arm's bending moment on the bearing), set G's axial
  float and set H's helical shift (a rotation about the axis), the output tilts across its axis in proportion to its
  own torque. Axes 2 and 3 of the heavy arms (open helical final stages, assumed; ur10's strain-wave gears have none).
  Sized to 0.25-0.6 mm. Driven by the pose and payload (logged). The true structure: one column per axis, amplitude
  the tilt per unit torque [rad / (N m)].
* dog play: axis 1's dress pack runs through a rotary cable guide (a turret-mounted energy-chain guide ring) that a
  dog on the turret drags only at the ends of a wide play +-D (rotary energy-chain drivers leave a free angle so that
  the chain is not pushed back and forth: igus / Kabelschlepp rotary-module guidelines, as recalled); the pack between
  the turret and the guide is a torsion spring, so axis 1's gear is twisted by c k (q1 - g), g the guide's angle, a
  play operator of q1 (Krasnosel'skii & Pokrovskii, *Systems with Hysteresis*, 1989; Visintin, *Differential Models of
  Hysteresis*, 1994). D 15-40 deg, the guide starting anywhere in its play. Unlike set N's harness lash (the harness's
  torque choosing the flank of the gear's lost motion) or set ZG's taut harness (a pull past a fixed slack), the twist
  is the pack's wind-up inside a wide play that remembers the axis's path. Sized to 0.25-0.6 mm. Driven by axis 1's
  path (logged). The true structure: one column, amplitude c k D [rad].
* flank profile: a gear's left and right flanks are ground separately and carry their own profile and pitch
  deviations (ISO 1328-1:2013, f_f alpha and f_H alpha per flank), so its tooth-mesh transmission error differs
  between the flank that carries a positive load and the one that carries a negative load (Smith, *Gear Noise and
  Vibration*, 2nd ed., 2003, ch. 3 and 9: the static TE of each flank set). Axis 2's (or 3's) final stage, z 40-80
  teeth on the output, e = [tau > 0] (a1 sin z q + b1 cos z q) + [tau < 0] (a2 sin z q + b2 cos z q), on the loaded
  axis whose load changes sign most evenly. Unlike set O's mesh TE or set ZH's running-in TE (one error pattern) and
  set ZH's pinion handover (two pinions chosen by the motion), the pattern switches with the load's sign. Sized to
  0.25-0.6 mm. Driven by the joint's angle and its load (logged pose and payload). The true structure: four columns.
* cage runout: a rolling bearing's elements differ in diameter (ISO 3290 ball grades, roller lots), so the shaft's
  centre wanders in a pattern fixed to the cage, which turns at f_c = (1 - (D_w / d_m) cos(alpha)) / 2 of the shaft's
  angle -- the bearing's non-repeatable runout (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., 2007, ch. 1
  and kinematics ch. 8). Axis 1's output encoder, a ring of radius R read by a single head, reads the shift across the
  head as an angle, rho / R sin(f_c q1 + phi) (Heidenhain, *Angle Encoders*, 2015, on eccentricity and bearing
  runout). D_w / d_m 0.05-0.15, alpha 0-45 deg. Unlike set C's runout (repeating once per turn), set Q's ball pass (the
  wave generator's balls) or set ZE's disc shift (the tilt under the moment), the error repeats with the cage, a
  non-integer share of the turn. Sized to 0.25-0.6 mm. Driven by axis 1's angle (logged). The true structure: two
  columns (sin, cos).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_ze_joint import _size


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def _size_cols(F, rng, rel=None, lo=0.25, hi=0.6):
    """Amplitudes for columns F (m, P, 3): each column scaled to a unit largest move, weighted by ``rel``
    (U(0.5, 1.5) each if None), the sum sized to U(lo, hi) mm."""
    s = np.array([np.linalg.norm(f, axis=1).max() for f in F])
    rel = rng.uniform(0.5, 1.5, len(F)) if rel is None else np.asarray(rel, float)
    return _size(F, rel / np.maximum(s, 1e-12), rng, lo, hi)


def loaded_joints(chain):
    return [j for j in (1, 2) if chain.revolute[j]]


def axis_basis(a):
    """Two unit vectors normal to the axis a (3,)."""
    u = np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return u, np.cross(a, u)


# ---------------------------------------------------------------------------------------------------- PI load step
def load_step(ctx, j):
    """(P,) the change of joint j's load from the previous pose (none at the first)."""
    tau = ctx.loads[:, j]
    return np.diff(tau, prepend=tau[0])


def step_share(p, session):
    return np.exp(-session.dwell_s / p["Ti_s"])


def step_draw(ctx, hw, rng):
    p = {"Ti_s": rng.uniform(1.5, 5.0)}
    p["c"] = _size_cols(step_features(p, ctx, hw), rng)
    return p


def step_features(p, ctx, hw):
    share = step_share(p, ctx.session)
    return np.array([ctx.joint_feature(j, load_step(ctx, j) * share) for j in loaded_joints(ctx.chain)])


def step_apply(p, ctx, hw):
    return _amp_apply(p["c"], step_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- helix tilt
def tilt_axes(p, ctx):
    """(m, P, 3) the tilt axis e_r x a of each loaded joint's output and (m, P, 3) the joint's point."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    ax, pt = [], []
    for j, psi in zip(loaded_joints(ctx.chain), p["psi"]):
        u, v = axis_basis(ctx.chain.axes[j])
        e_r = np.einsum("pab,b->pa", R[:, j], np.cos(psi) * u + np.sin(psi) * v)  # the mesh, fixed in the housing
        ax.append(np.cross(e_r, w[:, j]))
        pt.append(c[:, j])
    return np.array(ax), np.array(pt)


def helix_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, 2 * np.pi, len(loaded_joints(ctx.chain))).tolist(),
         "beta_deg": rng.uniform(15.0, 25.0)}
    p["c"] = _size_cols(helix_features(p, ctx, hw), rng)
    return p


def helix_features(p, ctx, hw):
    ax, pt = tilt_axes(p, ctx)
    js = loaded_joints(ctx.chain)
    return np.array([np.cross(ax[k], ctx.target - pt[k]) * ctx.loads[:, j:j + 1] for k, j in enumerate(js)])


def helix_apply(p, ctx, hw):
    return _amp_apply(p["c"], helix_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dog play
def guide_angle(p, q1):
    """(P,) the guide's angle: a play operator of half-width D started at q1[0] + u D."""
    D = p["D"]
    g = q1[0] + p["u0"] * D
    out = np.empty(len(q1))
    for k, x in enumerate(q1):
        g = min(max(g, x - D), x + D)
        out[k] = g
    return out


def dog_draw(ctx, hw, rng):
    p = {"D": float(np.deg2rad(rng.uniform(15.0, 40.0))), "u0": rng.uniform(-1.0, 1.0)}
    p["twist"] = _size(dog_features(p, ctx, hw), [1.0], rng)
    return p


def dog_features(p, ctx, hw):
    q1 = ctx.q[:, 0]
    return ctx.joint_feature(0, -(q1 - guide_angle(p, q1)) / p["D"])[None]


def dog_apply(p, ctx, hw):
    return _amp_apply(p["twist"], dog_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- flank profile
def flank_joint(ctx):
    """The loaded joint whose load changes sign most evenly."""
    js = loaded_joints(ctx.chain)
    share = [min((ctx.loads[:, j] > 0).mean(), (ctx.loads[:, j] < 0).mean()) for j in js]
    return js[int(np.argmax(share))]


def flank_signals(p, q, tau):
    a, b = (tau > 0).astype(float), (tau < 0).astype(float)
    x = p["z"] * q
    return np.array([a * np.sin(x), a * np.cos(x), b * np.sin(x), b * np.cos(x)])


def flank_draw(ctx, hw, rng):
    p = {"z": int(rng.integers(40, 81)), "j": flank_joint(ctx)}
    ph, amp = rng.uniform(0, 2 * np.pi, 2), rng.uniform(0.5, 1.5, 2)
    rel = [amp[0] * np.cos(ph[0]), amp[0] * np.sin(ph[0]), amp[1] * np.cos(ph[1]), amp[1] * np.sin(ph[1])]
    p["e"] = _size(flank_features(p, ctx, hw), rel, rng)
    return p


def flank_features(p, ctx, hw):
    j = p["j"]
    return np.array([ctx.joint_feature(j, s) for s in flank_signals(p, ctx.q[:, j], ctx.loads[:, j])])


def flank_apply(p, ctx, hw):
    return _amp_apply(p["e"], flank_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- cage runout
def cage_ratio(gamma, alpha):
    """The cage's turn per turn of the shaft (outer ring fixed): (1 - gamma cos(alpha)) / 2."""
    return 0.5 * (1.0 - gamma * np.cos(alpha))


def cage_draw(ctx, hw, rng):
    p = {"f_c": float(cage_ratio(rng.uniform(0.05, 0.15), np.deg2rad(rng.uniform(0.0, 45.0))))}
    ph = rng.uniform(0, 2 * np.pi)
    p["e"] = _size(cage_features(p, ctx, hw), [np.cos(ph), np.sin(ph)], rng)
    return p


def cage_features(p, ctx, hw):
    x = p["f_c"] * ctx.q[:, 0]
    return np.array([ctx.joint_feature(0, np.sin(x)), ctx.joint_feature(0, np.cos(x))])


def cage_apply(p, ctx, hw):
    return _amp_apply(p["e"], cage_features(p, ctx, hw))
