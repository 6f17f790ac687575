"""Independent physics for the blind benchmark: its own kinematics, geometric errors and effect physics.

Nothing here imports :mod:`tolalloc.diagnose.effects`, :mod:`tolalloc.diagnose.synth`, the error model or
the POE kinematics of :mod:`tolalloc.robot`: the robot file is only read for its nominal description (the
UR10's DH table straight from the TOML file; the tool_changer's chain of link vectors and joint axes), and
every measured point comes from :func:`walk`, a frame-walking forward kinematics written for this study.

Geometry (all parameters of the description, not the calibration model's parametrisation):

* DH robots (ur10): per row ``d, a`` [mm], ``alpha, theta_offset`` [rad] and the Hayati angle ``beta``
  [rad] (rotation about the new y axis, the parallel-axis parameter DH lacks);
* chain robots (tool_changer): per link the 3 components of its vector [mm]; per joint 2 axis-direction
  tilts [rad], 2 axis-position shifts [mm] (a sideways offset before the joint, undone after it) and the
  joint offset.

Effects (each an amplitude vector that enters the walk itself, not a first-order displacement basis):

``joint_compliance``  ``dq_j = c_j tau_j``; ``tau_j`` from this module's own mass model: uniform rods along
                      every segment (6-14 kg/m), a motor mass of 1.5-5 kg at every joint and a payload of
                      0-5 kg at the probe -- not the robot file's masses.
``link_deflection``   beam sag of every segment >= 250 mm between consecutive revolute joints (spanning a
                      prismatic joint, so the tool_changer's telescopic stage lengthens with ``q4``): tip drop
                      ``c (L^4/8 + r L^3/3) cos(phi)`` [mm] along gravity and slope ``c (L^3/6 + r L^2/2)
                      cos(phi) 1e-3`` [rad], ``L`` [m], ``phi`` the segment's elevation, ``r`` a tip-load ratio.
``backlash``          ``dq_j = b_j s_j``; the side ``s_j`` is the approach direction or -- "gravity-held" --
                      the sign of the gravity torque (tanh-smoothed over 2 % of its range).
``thermal``           every length grows by ``alpha dT``; ``dT`` either the logged temperature through a
                      first-order lag (tau 15-45 min) or a motor warm-up ``(1 - exp(-t/tau))`` that the logged
                      (ambient) temperature does not show.
``transmission``      ``dq_j = a_j sin(k q_j) + b_j cos(k q_j)``, ``k`` = 1 (once per revolution) or 2.

Physics added for issue 25 (each differs from the diagnosis's bases):

* thermal from the **motion history** (:func:`motion_temperatures`): every joint's motor heats with its own
  power times the joint speed between poses, through a first-order lag (tau_m); every link's temperature
  follows the mean of its two motors through a second lag (tau_l); every link its own expansion coefficient.
  The logged ``temperature_c`` is the ambient only. (The diagnosis has one lag and equal weights per joint.)
* **telescopic-guide deflection** (``walk(guide=...)``): at the prismatic joint the stage tilts in its guide
  about the horizontal axis perpendicular to it, by ``theta = M / (k b(s)^2) + c_r tanh(M / M0) / b(s)``: two
  bearings at spacing ``b(s) = b0 + (s_max - s)`` (the overlap shrinks as the stage extends) with compliance and
  a gravity-closed radial clearance. ``M``: moment of a downstream weight at the probe's horizontal lever arm.
  (The diagnosis's guide basis is linear in ``M`` and ``M s``.)
* **friction-banded backlash**: the gear sits on the gravity flank where ``|tau|`` exceeds a friction torque
  (5-25 % of its range), on the approach flank below it. (The diagnosis has a fixed 10 % band or a tanh.)
* **periodic bumps** (:func:`periodic_bumps`): a joint error made of von Mises bumps
  ``a exp(kappa (cos(q - c) - 1))`` (kappa 20-60) on the arm joints -- periodic per revolution but not a
  finite harmonic series.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from importlib.resources import files

import numpy as np
from scipy.spatial.transform import Rotation

G = 9.81
EFFECT_NAMES = ("joint_compliance", "link_deflection", "backlash", "thermal", "transmission")


def _rot(axis: np.ndarray, ang: np.ndarray) -> np.ndarray:
    """Rotation matrices about unit ``axis`` (3,) by angles ``ang`` (P,) [rad], shape (P, 3, 3)."""
    return Rotation.from_rotvec(np.outer(np.atleast_1d(ang), axis)).as_matrix()


@dataclass
class Description:
    """A robot's nominal description as a list of local operations (see :func:`walk`).

    ops : list of tuples
        ``("joint", j, axis (3,), revolute: bool)``, ``("trans", vec_mm (3,))``, ``("rot", R (3, 3))``.
    geo_names : list of str      geometric error parameter names
    geo_scale : array            typical size of each [mm or rad] (0.3 mm / 0.05 deg)
    n : int                      joints
    revolute : array of bool
    """

    ops: list
    geo_names: list
    geo_scale: np.ndarray
    n: int
    revolute: np.ndarray
    tool_mm: np.ndarray = field(default_factory=lambda: np.zeros(3))


def describe(robot) -> Description:
    """The nominal description of a built-in robot: the DH table for ur10, the chain otherwise."""
    rev = np.array([j.is_revolute for j in robot.joints])
    ang, ln = np.deg2rad(0.05), 0.3
    if robot.name == "ur10":
        data = tomllib.loads((files("tolalloc") / "data/robots/ur10.toml").read_text())
        ops, names = [], []
        for i, r in enumerate(data["dh"]):
            ops += [("joint", i, np.array([0.0, 0.0, 1.0]), True), ("trans", np.array([0.0, 0.0, 1e3 * r.get("d_m", 0.0)])),
                    ("rot", _rot(np.array([0.0, 0.0, 1.0]), r.get("theta_offset_rad", 0.0))[0]),
                    ("trans", np.array([1e3 * r.get("a_m", 0.0), 0.0, 0.0])),
                    ("rot", _rot(np.array([1.0, 0.0, 0.0]), r.get("alpha_rad", 0.0))[0])]
            names += [f"d{i + 1}", f"a{i + 1}", f"alpha{i + 1}", f"theta{i + 1}", f"beta{i + 1}"]
        scale = np.array([ln, ln, ang, ang, ang] * len(data["dh"]))
        return Description(ops, names, scale, robot.n_joints, rev)
    ops, names, scale = [], [], []
    for el in robot.chain:
        if hasattr(el, "vector_mm"):
            ops.append(("trans", np.asarray(el.vector_mm, float)))
            names += [f"{el.name}_{c}" for c in "xyz"]
            scale += [ln] * 3
        else:
            j = [jt.name for jt in robot.joints].index(el.name)
            ops.append(("joint", j, np.asarray(el.axis, float), el.is_revolute))
            names += [f"{el.name}_tilt1", f"{el.name}_tilt2", f"{el.name}_pos1", f"{el.name}_pos2", f"{el.name}_zero"]
            # a prismatic joint's axis has no position: its two shifts get scale 0 (never perturbed)
            scale += [ang, ang, ln if el.is_revolute else 0.0, ln if el.is_revolute else 0.0,
                      ang if el.is_revolute else ln]
    return Description(ops, names, np.array(scale), robot.n_joints, rev, np.asarray(robot.tool_offset_mm, float))


def _perp(w: np.ndarray) -> tuple:
    a = np.eye(3)[int(np.argmin(np.abs(w)))]
    e1 = np.cross(w, a)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(w, e1)


def _perturbed_ops(desc: Description, geo: np.ndarray) -> list:
    """The description's operations with the geometric errors ``geo`` (K,) applied."""
    ops, k = [], 0
    if desc.geo_names[0] == "d1":  # DH rows: joint, d, theta_offset, a, alpha (+ Hayati beta)
        x, y, z = np.eye(3)
        for row in range(desc.n):
            jt, td, rth, ta, ral = desc.ops[5 * row: 5 * row + 5]
            dd, da, dal, dth, dbe = geo[5 * row: 5 * row + 5]
            ops += [jt, ("trans", td[1] + dd * z), ("rot", rth[1] @ _rot(z, dth)[0]), ("trans", ta[1] + da * x),
                    ("rot", ral[1] @ _rot(x, dal)[0]), ("rot", _rot(y, dbe)[0])]
        return ops
    for op in desc.ops:
        if op[0] == "trans":
            ops.append(("trans", op[1] + geo[k:k + 3]))
            k += 3
        else:
            _, j, w, revo = op
            t1, t2, s1, s2, z = geo[k:k + 5]
            k += 5
            e1, e2 = _perp(w)
            shift = s1 * e1 + s2 * e2
            R = _rot(e1, t1)[0] @ _rot(e2, t2)[0]
            ops += [("trans", shift), ("rot", R), ("joint", j, w, revo, z), ("trans", -shift)]
    return ops


def motion_temperatures(q: np.ndarray, time_s: np.ndarray, power: np.ndarray, tau_m_s: float, tau_l_s: float,
                        link_joints: list) -> np.ndarray:
    """Link temperature rises (P, L) from the motion history (module docstring); ``link_joints``: per link the
    joints at its ends."""
    dt = np.diff(time_s)
    heat = np.vstack([np.zeros(q.shape[1]), np.abs(np.diff(q, axis=0)) / dt[:, None]]) * power
    motor = np.zeros_like(heat)
    for i in range(1, len(q)):
        motor[i] = motor[i - 1] + (1 - np.exp(-dt[i - 1] / tau_m_s)) * (heat[i] - motor[i - 1])
    drive = np.column_stack([motor[:, js].mean(axis=1) for js in link_joints])
    link = np.zeros_like(drive)
    for i in range(1, len(q)):
        link[i] = link[i - 1] + (1 - np.exp(-dt[i - 1] / tau_l_s)) * (drive[i] - link[i - 1])
    return link


def periodic_bumps(q: np.ndarray, centres: np.ndarray, kappa: np.ndarray, amps: np.ndarray, joints) -> np.ndarray:
    """Joint errors (P, n) made of von Mises bumps: for each (joint, centre, kappa, amplitude)."""
    dq = np.zeros_like(q)
    for j, c, k, a in zip(joints, centres, kappa, amps):
        dq[:, j] += a * np.exp(k * (np.cos(q[:, j] - c) - 1.0))
    return dq


def trans_links(ops: list) -> list:
    """Per "trans" operation of ``ops`` (in order) the number of joint operations before it (its link)."""
    out, joints = [], 0
    for op in ops:
        if op[0] == "trans":
            out.append(joints)
        elif op[0] == "joint":
            joints += 1
    return out


def walk(ops: list, q: np.ndarray, tool_mm: np.ndarray, *, growth=None, sag=None, gravity=np.array([0, 0, -1.0]),
         guide=None):
    """Forward kinematics by walking the local operations; probe point and joint data in the base frame.

    Parameters
    ----------
    ops : list of operations (see :class:`Description`); a joint op may carry a 5th entry, its offset
    q : array, shape (P, n) [rad, mm]
    tool_mm : array, shape (3,), probe offset in the last frame [mm]
    growth : array, shape (P,) or (P, T), optional   relative length change of every translation (thermal), or of
        each of the ``T`` translation operations in order
    sag : tuple (c (S,), r), optional      beam sag compliance per segment and tip-load ratio
    guide : tuple (j, rotvec (P, 3)), optional   tilt of the stage of prismatic joint ``j`` in its guide (base frame
        rotation vector about the guide point, before the stage extends)

    Returns
    -------
    x : array, shape (P, 3) [mm]; joints : list of (point (P, 3), axis (P, 3), revolute) per joint op;
    segments : list of (start (P, 3), end (P, 3)) between consecutive revolute joints and to the probe
    """
    P = q.shape[0]
    R = np.broadcast_to(np.eye(3), (P, 3, 3)).copy()
    p = np.zeros((P, 3))
    joints, segs, seg_start, s_i = [], [], None, 0
    grow = np.ones((P, 1)) if growth is None else 1.0 + np.asarray(growth, float).reshape(P, -1)
    t_i = 0

    def close_segment(end, end_joint):
        nonlocal R, p, s_i
        segs.append((seg_start, end.copy(), end_joint))
        if sag is not None and s_i < len(sag[0]):
            d = end - seg_start
            L = np.linalg.norm(d, axis=1) / 1000.0
            horiz = d - np.outer(d @ gravity, gravity)
            cphi = np.linalg.norm(horiz, axis=1) / np.maximum(1e3 * L, 1e-9)
            c, r = sag[0][s_i], sag[1]
            drop = c * (L ** 4 / 8 + r * L ** 3 / 3) * cphi
            slope = 1e-3 * c * (L ** 3 / 6 + r * L ** 2 / 2) * cphi
            ax = np.cross(horiz, gravity)
            ax /= np.maximum(np.linalg.norm(ax, axis=1), 1e-12)[:, None]
            Rs = Rotation.from_rotvec(ax * slope[:, None]).as_matrix()
            p = p + drop[:, None] * gravity
            R = Rs @ R
        s_i += 1

    for op in ops:
        if op[0] == "trans":
            g_op = grow[:, min(t_i, grow.shape[1] - 1)]
            p = p + g_op[:, None] * (R @ op[1])
            t_i += 1
        elif op[0] == "rot":
            R = R @ op[1]
        else:
            j, w, revo = op[1], op[2], op[3]
            z = op[4] if len(op) > 4 else 0.0
            if revo:
                if seg_start is not None:
                    close_segment(p, j)
                joints.append((p.copy(), R @ w, True))
                seg_start = p.copy()
                R = R @ _rot(w, q[:, j] + z)
            else:
                joints.append((p.copy(), R @ w, False))
                if guide is not None and guide[0] == j:  # the stage tilts about the guide point, then extends
                    R = Rotation.from_rotvec(guide[1]).as_matrix() @ R
                p = p + (R @ w) * (q[:, j] + z)[:, None]
    x = p + R @ tool_mm
    if seg_start is not None:
        close_segment(x, len(joints))
        x = p + R @ tool_mm
    return x, joints, segs


def gravity_torque(joints, segs, x, masses: dict, gravity=np.array([0, 0, -1.0])) -> np.ndarray:
    """Gravity load per joint [N m] / [N] of the study's own mass model, shape (P, n).

    ``masses``: ``rod_kg_per_m`` (S,), ``motor_kg`` (n,), ``payload_kg`` float. Rods and motors downstream
    of a joint load it: a rod (segment ``s``) is downstream of the joint ops before the segment's end.
    """
    P = len(x)
    pts = []  # (point (P, 3), mass (P,), downstream of joint j when j < this index)
    for s, (a, b, end_joint) in enumerate(segs):
        L = np.linalg.norm(b - a, axis=1) / 1000.0
        pts.append(((a + b) / 2, masses["rod_kg_per_m"][s] * L, end_joint))
    for j, (pj, _, _) in enumerate(joints):
        pts.append((pj, np.full(P, masses["motor_kg"][j]), j))  # a joint's own motor sits on its link
    pts.append((x, np.full(P, masses["payload_kg"]), len(joints)))
    tau = np.zeros((P, len(joints)))
    for j, (pj, w, revo) in enumerate(joints):
        for c, m, after in pts:
            if j >= after:
                continue
            F = (m * G)[:, None] * gravity
            if revo:
                tau[:, j] += np.einsum("pi,pi->p", w, np.cross((c - pj) / 1000.0, F))
            else:
                tau[:, j] += w @ F if w.ndim == 1 else np.einsum("pi,pi->p", w, F)
    return tau
