"""Compliance under gravity and payload: the joints' torsional stiffness (linear or hardening) and the base mount.

**Joint compliance.** A joint under the gravity load ``tau_j`` (:func:`~.loads.gravity_torques`, robot masses plus
the payload at the target) winds up by ``dq_j = phi_j(tau_j)`` [rad, or mm for a prismatic joint]. Laws:

* ``linear``: ``phi = c tau`` (``c = 1/K`` [rad/(N m)]);
* ``catalogue``: the strain-wave / cycloid catalogue's piecewise-linear curve ``T/K1`` up to ``T1``, slope ``1/K2``
  up to ``T2``, ``1/K3`` beyond (:meth:`~tolalloc.robot.components.Reducer.deflection`), linear in
  ``(1/K1, 1/K2, 1/K3)`` once the bands ``T1, T2`` are known (from the robot file's reducer);
* ``hardening``: a smooth law for a gear whose bands are not known, ``phi = c tau + s T0 tanh(tau / T0)``: slope
  ``c + s`` near zero torque (the soft zone), ``c`` beyond ``T0`` -- a stiffness that rises with torque for
  ``s > 0``. ``T0`` is a shape parameter chosen from the data (:data:`HARDENING_FRACTIONS` of the joint's largest
  gravity load).

Unknown loads at the target add columns to any law: an unknown tool mass (``d_j`` per kg, the vertical) and an unknown
constant force in the horizontal plane (``h1_j``, ``h2_j`` per N, :func:`side_loads`; not on an axis that stays
vertical, where it reads as a transmission error) -- a hose, cable or balancer that pulls in a fixed direction
whatever the pose.

**Mount compliance.** A robot on a compliant base (a floor plate, a pedestal, a mobile platform) tilts as a whole under
the gravity moment of its moving masses and payload about the base (:func:`~.loads.base_moment`): the rotation
``omega = (c_x M_x, c_y M_y, 0)`` [rad] about the base origin moves the target by ``omega x p``. ``isotropic`` (one
``c``) or ``axes`` (``c_x``, ``c_y``). ``pivot``: one ``c`` about a pivot at a depth ``h`` below the base origin
(a pedestal or column bending under the moment turns about a point inside it, an anchor plate about the floor:
``omega x (p + h g_hat)``); linear in ``c`` and ``c h`` [rad mm/(N m)], so ``h`` is their ratio. ``play``: ``c`` plus
a rocking ``r`` [mrad] in the direction of the horizontal moment whatever its size, ``omega = c M_h + r M_h / |M_h|``
(a base that rocks within a clearance -- a short foot, a loose anchor, a carriage on its rollers -- and then stands
on the side the moment presses; the first joint's bearing tilt clearance has the same signature, so the clearance
model of :mod:`~.clearance` leaves it to this one). ``tensor``: a symmetric 2 x 2 compliance in the horizontal plane,
``omega = C M_h`` (``c_xx``, ``c_yy``, ``c_xy``; ``x``, ``y`` the base axes projected across gravity), about a pivot at
a fitted depth: a support whose stiffest and softest axes lie at any heading -- a rectangular plate or anchor
pattern, a base rocking on a sole bowed along one direction (``C = e e^T / (W R)``, rank one) -- with its columns
times the depth beside them (six, linear in ``C`` and ``C h``). A support that keeps giving under the moment it holds
(pads, grout, asphalt) tilts with the history of the poses: :mod:`~.mount_creep`.

**Bearing tilt.** A revolute joint's bearing pair (a cross-roller bearing, an angular-contact pair) carries the
moment across its axis of everything beyond it (:func:`~.loads.joint_wrenches`), taken about the pair's centre, and
tilts by ``M_perp / k`` [rad] with its catalogue moment stiffness ``k`` (``tilt_stiffness_Nm_per_rad``): the distal
chain turns about that centre (``centre_mm`` along the axis from the joint point; :func:`bearing_rotations`,
:func:`bearing_tilt`). It is a
joint-axis deflection, the rotary counterpart of the mount's tilt.

**A logged process wrench.** Where the data carry the force and moment a process applies at the tool (a cut, a
press, a screwing reaction; :func:`~.loads.wrench_load`), both loads include it: the joints carry its virtual work
and the mount its moment about the base (the beams and the flange element of :mod:`~.beams` carry it too).

All three are linear in their compliances, so the diagnosis fits them by least squares (the joints' and the
mount's) and the design samples them from the catalogue's stiffness figures.
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Robot
from tolalloc.physics.loads import (base_moment, gravity_torques, joint_wrenches, tip_load, unit_along, wrench_load,
                                   wrench_moment)

__all__ = ["COMPLIANCE_LAWS", "HARDENING_FRACTIONS", "MOUNT_VARIANTS", "joint_loads", "compliance_columns",
           "catalogue_bands", "side_loads", "mount_moment", "mount_columns", "joint_windup", "mount_tilt",
           "bearing_rotations", "bearing_tilt"]

#: Joint-compliance laws (``hardening_<f>``: T0 = f x the joint's largest gravity load on the poses).
COMPLIANCE_LAWS = ("linear", "catalogue", "hardening")
#: Shape parameters of the ``hardening`` law: T0 as a fraction of the joint's largest load.
HARDENING_FRACTIONS = (0.2, 0.4)
MOUNT_VARIANTS = ("isotropic", "axes", "pivot", "play", "tensor")


def joint_loads(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None, payload_kg=None,
                wrench=None) -> tuple:
    """Gravity loads (P, n) of the robot's masses plus the payload at the target points ``tip_mm`` (P, 3) and a
    logged process wrench there (``wrench`` (P, 6), :func:`~tolalloc.physics.loads.wrench_load`), and the load of
    1 kg at the target (P, n) [N m or N per kg] (zeros without ``tip_mm``)."""
    tau = gravity_torques(robot, q)
    tip = np.zeros_like(tau) if tip_mm is None else tip_load(robot, q, tip_mm)
    if payload_kg is not None:
        tau = tau + np.asarray(payload_kg, float)[:, None] * tip
    if wrench is not None and tip_mm is not None:
        tau = tau + wrench_load(robot, q, tip_mm, wrench)
    return tau, tip


def _unit(robot: Robot, j: int) -> tuple:
    rev = robot.joints[j].is_revolute
    return ("rad", "N m") if rev else ("mm", "N")


def catalogue_bands(robot: Robot) -> dict:
    """``{joint index: (T1, T2)}`` of the joints whose reducer gives the catalogue's three-band stiffness curve."""
    out = {}
    for j, jt in enumerate(robot.joints):
        red = robot.components.joint(jt.name).reducer
        if red is not None and len(red.stiffness) == 3:
            out[j] = red.torque_bands
    return out


def _law_columns(t: np.ndarray, law: str, bands=None, scale: float | None = None) -> list:
    """Columns ``(label, values (P,))`` of one joint's law, linear in its compliances."""
    if law == "catalogue" and bands:
        a, s = np.abs(t), np.sign(t)
        t1, t2 = bands
        return [("c1", s * np.minimum(a, t1)), ("c2", s * np.clip(a - t1, 0.0, t2 - t1)),
                ("c3", s * np.maximum(a - t2, 0.0))]
    cols = [("c", t)]
    if law.startswith("hardening") and scale:
        frac = float(law.split("_")[1]) if "_" in law else HARDENING_FRACTIONS[1]
        t0 = frac * scale
        cols.append(("s", t0 * np.tanh(t / t0)))
    return cols


def compliance_columns(robot: Robot, tau: np.ndarray, tip: np.ndarray, law: str = "linear",
                       tip_mass: bool = False, scale: np.ndarray | None = None,
                       side: np.ndarray | None = None) -> tuple:
    """Joint-offset basis of joint compliance: ``dq = A @ beta``, ``A`` shape (P, n, M), and the column names.

    Parameters
    ----------
    tau, tip : arrays, shape (P, n)     gravity loads and the load of 1 kg at the target (:func:`joint_loads`)
    law : str                           ``linear``, ``catalogue`` (bands from the robot's reducers; joints without
                                        them stay linear) or ``hardening_<f>``
    tip_mass : bool                     also a column per joint for an unknown mass at the target (``d_j``)
    scale : array, shape (n,), optional the torque scale of ``hardening`` (default: the largest ``|tau_j|``)
    side : array, shape (P, n, 2), optional
                                        the loads of 1 N at the target along the two horizontal directions
                                        (:func:`side_loads`): a column per joint and direction for an unknown
                                        constant force there (``h1_j``, ``h2_j``)
    """
    P, n = tau.shape
    bands = catalogue_bands(robot) if law == "catalogue" else {}
    scale = np.abs(tau).max(0) if scale is None else scale
    cols, names = [], []
    for j in range(n):
        dq, load = _unit(robot, j)
        nm = robot.joints[j].name
        if np.abs(tau[:, j]).max() > 1e-9:
            for lab, v in _law_columns(tau[:, j], law, bands.get(j), float(scale[j])):
                a = np.zeros((P, n))
                a[:, j] = v
                cols.append(a)
                names.append(f"{lab}_{nm} [{dq}/({load})]")
        if tip_mass and np.abs(tip[:, j]).max() > 1e-9:
            a = np.zeros((P, n))
            a[:, j] = tip[:, j]
            cols.append(a)
            names.append(f"d_{nm} [{dq}/kg]")
        for k in range(0 if side is None else side.shape[2]):
            if np.abs(side[:, j, k]).max() > 1e-9:
                a = np.zeros((P, n))
                a[:, j] = side[:, j, k]
                cols.append(a)
                names.append(f"h{k + 1}_{nm} [{dq}/N]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))), names


def side_loads(robot: Robot, q: np.ndarray, tip_mm: np.ndarray) -> np.ndarray:
    """Loads on every joint of a force of 1 N at the target points ``tip_mm`` (P, 3) along each of the two horizontal
    directions (:func:`_horizontal_axes`: base x and y projected across gravity), shape (P, n, 2) [N m or N per N].
    With :func:`tip_load` (the vertical) they span any constant force at the target: a hose or cable pulled towards
    a fixed anchor, a spring balancer hung off the vertical, a fixture the tool presses against.

    A revolute joint whose axis stays along gravity on every pose (the first axis of an upright arm) gets zeros: there
    the side force's moment is ``|r| F sin(q_j - phi)``, once per turn of that joint -- the signature of its
    transmission error, which that family owns."""
    g = np.asarray(robot.gravity, dtype=float)
    g = g / max(np.linalg.norm(g), 1e-12)
    q = np.atleast_2d(q)
    out = []
    for e in _horizontal_axes(g):
        w = np.zeros((len(q), 6))
        w[:, :3] = e
        out.append(wrench_load(robot, q, tip_mm, w))
    loads = np.stack(out, axis=-1)
    prefix = poe_prefix(robot.screws, q)
    for j, joint in enumerate(robot.joints):
        if joint.is_revolute and np.all(np.abs(prefix[:, j, :3, :3] @ joint.axis @ g) > 1.0 - 1e-6):
            loads[:, j] = 0.0
    return loads


def mount_moment(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None, payload_kg=None,
                 wrench=None) -> np.ndarray:
    """The horizontal part of the moment the mount carries [N m], shape (P, 3): the robot's moving masses, the payload
    ``payload_kg`` (P,) and a logged process wrench ``wrench`` (P, 6) at ``tip_mm`` (P, 3) (the moment about the
    vertical does not tilt the base)."""
    if tip_mm is None and (wrench is not None or payload_kg is not None):
        raise ValueError("mount_moment: a payload or a process wrench needs tip_mm, the point it acts at")
    M = base_moment(robot, q, tip_mm, 0.0 if payload_kg is None else payload_kg)
    if wrench is not None:
        M = M + wrench_moment(tip_mm, wrench)
    g = np.asarray(robot.gravity, dtype=float)
    return M - (M @ g)[:, None] * g


def mount_columns(robot: Robot, q: np.ndarray, p: np.ndarray, tip_mm: np.ndarray | None = None, payload_kg=None,
                  variant: str = "isotropic", wrench=None) -> tuple:
    """Target-displacement basis of a compliant mount, ``B`` shape (P, 3, M) [mm per rad/(N m)], and names.

    ``p`` (P, 3): the target points [mm]; the payload ``payload_kg`` (P,) and a logged process wrench ``wrench``
    (P, 6) (:func:`~tolalloc.physics.loads.wrench_moment`) act at ``tip_mm`` (P, 3).
    """
    Mh = mount_moment(robot, q, tip_mm, payload_kg, wrench)
    g = np.asarray(robot.gravity, dtype=float)
    if variant == "isotropic":
        return np.cross(Mh, p)[:, :, None], ["c_mount [rad/(N m)]"]
    if variant == "pivot":
        return (np.stack([np.cross(Mh, p), np.cross(Mh, np.broadcast_to(-g, p.shape))], axis=-1),
                ["c_mount [rad/(N m)]", "c_mount_depth [rad mm/(N m)]"])
    if variant == "play":
        side = unit_along(Mh, np.linalg.norm(Mh, axis=1).max(initial=0.0), 1e-9)
        return (np.stack([np.cross(Mh, p), 1e-3 * np.cross(side, p)], axis=-1),
                ["c_mount [rad/(N m)]", "r_mount [mrad]"])
    if variant == "tensor":
        return _tensor_columns(Mh, p, g)
    cols, names = [], []
    for i, ax in enumerate("xyz"):
        if abs(g[i]) > 0.99:
            continue
        om = np.zeros_like(Mh)
        om[:, i] = Mh[:, i]
        cols.append(np.cross(om, p))
        names.append(f"c_mount_{ax} [rad/(N m)]")
    return np.stack(cols, axis=-1), names


def _horizontal_axes(g: np.ndarray) -> tuple:
    """Unit axes ``(u, v)`` across the unit gravity direction ``g`` (3,): ``u`` the base x axis projected (y where x
    lies along gravity), ``v = u x g`` -- ``(u, v, up)`` right-handed, base x and y where gravity is -z."""
    ref = np.eye(3)[0] if abs(g[0]) < 0.9 else np.eye(3)[1]
    u = ref - (ref @ g) * g
    u = u / np.linalg.norm(u)
    return u, np.cross(u, g)


def _tensor_columns(Mh: np.ndarray, p: np.ndarray, g: np.ndarray) -> tuple:
    """The ``tensor`` variant's six columns (P, 3, 6): the rotations ``m_u u``, ``m_v v``, ``m_v u + m_u v`` of a
    symmetric horizontal compliance (``u``, ``v``: :func:`_horizontal_axes`), about the base origin and times a
    pivot's depth along gravity."""
    u, v = _horizontal_axes(g)
    mu, mv = Mh @ u, Mh @ v
    omegas = [mu[:, None] * u, mv[:, None] * v, mv[:, None] * u + mu[:, None] * v]
    up = np.broadcast_to(-g, p.shape)
    cols = [np.cross(om, p) for om in omegas] + [np.cross(om, up) for om in omegas]
    names = [f"c_mount_{ab} [rad/(N m)]" for ab in ("xx", "yy", "xy")]
    names += [f"c_mount_{ab}_depth [rad mm/(N m)]" for ab in ("xx", "yy", "xy")]
    return np.stack(cols, axis=-1), names


def joint_windup(robot: Robot, tau: np.ndarray, stiffness_scale: np.ndarray | float = 1.0) -> np.ndarray:
    """Wind-up of every joint under ``tau`` (P, n) from the robot's reducer figures [rad or mm], shape (P, n);
    ``stiffness_scale``: a factor (n,) on each joint's stiffness (the spread of built parts). Joints whose reducer
    gives no stiffness do not wind up."""
    out = np.zeros_like(tau, dtype=float)
    k = np.broadcast_to(np.asarray(stiffness_scale, float), (tau.shape[1],))
    for j, jt in enumerate(robot.joints):
        red = robot.components.joint(jt.name).reducer
        if red is not None and red.stiffness:
            out[:, j] = red.deflection(tau[:, j]) / k[j]
    return out


def mount_tilt(robot: Robot, q: np.ndarray, p: np.ndarray, tip_mm=None, payload_kg=None, wrench=None) -> np.ndarray:
    """Target displacement [mm] (P, 3) of the mount tilting under its load (a process ``wrench`` (P, 6) at ``tip_mm``
    included) with the robot file's mount stiffness (zeros when the file gives none)."""
    k = robot.components.mount.tilt_stiffness
    if k is None:
        return np.zeros_like(p)
    k = np.asarray(k, float)
    if k[0] == k[1]:  # one stiffness about every horizontal axis, whichever way gravity points
        return mount_columns(robot, q, p, tip_mm, payload_kg, "isotropic", wrench)[0][..., 0] / k[0]
    g = np.asarray(robot.gravity, dtype=float)
    if abs(g[2]) < 0.99:
        raise TolallocError(f"robot {robot.name!r}: [components.mount] tilt_stiffness_Nm_per_rad gives two values, "
                            f"about the base x and y axes, which are the horizontal ones only with gravity along base "
                            f"z; this robot's gravity is {np.round(g, 3).tolist()}. Give one value (the same about "
                            "every horizontal axis).")
    B, _ = mount_columns(robot, q, p, tip_mm, payload_kg, "axes", wrench)  # columns about x, then y
    return B @ (1.0 / k)


def bearing_rotations(robot: Robot, q: np.ndarray, tip_mm=None, payload_kg=None, wrench=None) -> tuple:
    """Each revolute joint's bearing tilt under the moment across its axis (module docstring): the rotation [rad]
    ``theta`` (P, n, 3) and the pair's centre it turns about [mm] ``c`` (P, n, 3) (``centre_mm`` along the axis from
    the joint point); zero rotation for joints whose bearing gives no ``tilt_stiffness``. The payload ``payload_kg``
    (P,) and a process ``wrench`` (P, 6) act at ``tip_mm`` (P, 3)."""
    q = np.atleast_2d(q)
    theta, centre = np.zeros((len(q), robot.n_joints, 3)), np.zeros((len(q), robot.n_joints, 3))
    bearings = {j: robot.components.joint(jt.name).bearing for j, jt in enumerate(robot.joints) if jt.is_revolute}
    bearings = {j: b for j, b in bearings.items() if b is not None and b.tilt_stiffness}
    if not bearings:
        return theta, centre
    F, M, o, w = joint_wrenches(robot, q, tip_mm, 0.0 if payload_kg is None else payload_kg, wrench)
    for j, b in bearings.items():
        shift = b.centre_mm * w[:, j]                               # the pair's centre from the joint point [mm]
        Mc = M[:, j] - np.cross(shift / 1000.0, F[:, j])            # the moment about the centre [N m]
        across = Mc - np.einsum("pi,pi->p", Mc, w[:, j])[:, None] * w[:, j]
        theta[:, j], centre[:, j] = across / b.tilt_stiffness, o[:, j] + shift
    return theta, centre


def bearing_tilt(robot: Robot, q: np.ndarray, p: np.ndarray, tip_mm=None, payload_kg=None, wrench=None) -> np.ndarray:
    """Displacement [mm] of the points ``p`` (P, 3) from each revolute joint's bearing tilt
    (:func:`bearing_rotations`, same arguments), shape (P, 3, n); zeros for joints whose bearing gives no
    ``tilt_stiffness``."""
    theta, centre = bearing_rotations(robot, q, tip_mm, payload_kg, wrench)
    return np.cross(theta, np.asarray(p, float)[:, None, :] - centre).transpose(0, 2, 1)
