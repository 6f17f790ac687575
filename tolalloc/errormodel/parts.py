"""The bought parts in the error model: each effect as terms with a mean, a systematic and a random part.

A *term* moves the tool point along a column ``c`` (P, 3) -- a column of the error Jacobian of
:func:`parts_error_model` (joint offsets, link lengths, the bearings' body displacements), or a displacement the
physics stage computes directly (beam sag, mount tilt) -- by a value with, at each point (pose, payload, ambient):

* a **mean** -- the deterministic part at that payload and temperature, which a compensation model removes (a
  stiffness model given the payload, a temperature model);
* a **systematic** standard deviation -- fixed for one built robot, different between robots (part-to-part spread,
  a gear's or a bearing's error at its random phase), which a calibration or an error table removes;
* a **random** standard deviation -- new at every move, what repeatability sees.

The split, per effect (:data:`EFFECTS`; one implementation of each physical model, in :mod:`tolalloc.physics`)::

    effect        term (per joint / link)              mean                      systematic sd        random sd
    compliance    gear wind-up (motor-side loop)       catalogue curve at load   s |wind-up|          -
    lost_motion   flank +-b/2 by approach direction    0                         -                    b / 2
    transmission  gear error at orders 1, N, 2N (*)    0                         sqrt(sum a^2 / 2)    repeat. / sqrt(3)
    encoder       graduation and eccentricity          0                         sqrt(sum a^2 / 2)    -
    homing        zero of an incremental encoder       0                         -                    h / sqrt(3)
    bearing       runout of the bearing pair (4)       0                         eps / 2, eps / span  -
    compliance    bearing tilt under its moment        M_perp / k (tilt)         TILT_SD |tilt|       -
    thermal       link growth (ambient and motors)     alpha dT L                THERMAL_SD |mean|    -
                  an encoder's scale (declared)        c q dT (ambient)          THERMAL_SD |mean|    -
    beam          link bending (sections)              sag                       BEAM_SD |sag|        -
    mount         base tilt                            tilt                      MOUNT_SD |tilt|      -

(*) a linear reducer (a ball screw): one half-wave of its travel deviation over the stroke (:func:`gear_harmonics`).
A joint whose encoder is on the **output** side closes its position loop on the output angle: its gear's wind-up,
lost motion and transmission error do not reach the joint angle, the encoder's own error does. ``s`` is the
reducer's ``stiffness_sd``. An incremental encoder's zero (``homing_repeatability`` +-h) is set anew at every
power-up: no calibration or compensation removes it, so it is random here; within one power cycle it holds still
(:mod:`tolalloc.acceptance.parts` keeps it through an acceptance test). Statistics: :class:`EffectTerms`
(``mean_mm``, ``systematic_covariance``, ``random_covariance``, ``moments``); :mod:`tolalloc.errormodel.parts_sample` draws the same effects physically
(nonlinear in the catalogue curve, at the actual joint angle) for the Monte Carlo.
"""

from __future__ import annotations

import copy
import functools
from dataclasses import dataclass, replace

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.build import build_error_model
from tolalloc.errormodel.model import ErrorModel, ErrorParameter, perpendicular_axes
from tolalloc.errormodel.parts_terms import (BEAM_SD, COMPENSATION_RESIDUAL, EFFECTS, MOUNT_SD, THERMAL_SD, TILT_SD,
                                             EffectTerms, residual_factors)
from tolalloc.physics.beams import beam_sag
from tolalloc.physics.bearings import budgets_runout, runout_sd
from tolalloc.physics.compliance import bearing_rotations, joint_loads, mount_tilt
from tolalloc.physics.loads import target_points
from tolalloc.physics.thermal_design import link_cte, link_temperature, motor_rise
from tolalloc.physics.thermal_scale import scale_error
from tolalloc.physics.transmission import catalogue_amplitudes
from tolalloc.robot.model import Robot

__all__ = ["EFFECTS", "THERMAL_SD", "BEAM_SD", "MOUNT_SD", "TILT_SD", "COMPENSATION_RESIDUAL", "residual_factors",
           "Conditions", "PartsModel", "parts_error_model", "EffectTerms", "PartEffects", "with_parts", "motor_side",
           "gear_harmonics", "stroke_of", "encoder_harmonics"]


@dataclass(frozen=True)
class Conditions:
    """Where the design must hold besides the poses: a payload range [kg], an ambient range [degC] about the
    ``reference_c`` the robot was built and measured at, a duty cycle (the fraction of time the motors carry the
    pose's load), and a process force ``process_force_n`` [N] and moment ``process_torque_nm`` [N m] at the tool
    point in the tool frame (a drill's thrust, a spindle's cutting force), acting at every pose -- the same loads
    the diagnosis reads from a logged wrench (:func:`tolalloc.physics.loads.wrench_load`)."""

    payload_kg: tuple = (0.0, 0.0)
    ambient_c: tuple = (20.0, 20.0)
    reference_c: float = 20.0
    duty: float = 0.5
    process_force_n: tuple = (0.0, 0.0, 0.0)
    process_torque_nm: tuple = (0.0, 0.0, 0.0)

    def check(self, robot: Robot) -> "Conditions":
        """Validated against ``robot`` (a payload above its rating is refused)."""
        lo, hi = (float(x) for x in self.payload_kg)
        rated = robot.components.payload.rated_kg
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 <= lo <= hi):
            raise TolallocError(f"payload_kg: expected a range 0 <= low <= high [kg], got {self.payload_kg!r}")
        if rated is not None and hi > rated * (1 + 1e-9):
            raise TolallocError(f"payload_kg: {hi:g} kg is above the rated payload of robot {robot.name!r} "
                                f"({rated:g} kg, [components.payload] rated_kg); give a range up to {rated:g} kg")
        t = tuple(float(x) for x in self.ambient_c)
        if len(t) != 2 or not all(np.isfinite(t)) or t[0] > t[1]:
            raise TolallocError(f"ambient_c: expected a range low <= high [degC], got {self.ambient_c!r}")
        if not 0 <= self.duty <= 1:
            raise TolallocError(f"duty: expected a fraction of time in [0, 1], got {self.duty!r}")
        wrench = {}
        for key in ("process_force_n", "process_torque_nm"):
            v = np.asarray(getattr(self, key), dtype=object).ravel()
            ok = v.size == 3 and all(isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool)
                                     and np.isfinite(float(x)) for x in v)
            if not ok:
                raise TolallocError(f"{key}: expected three finite numbers (x, y, z in the tool frame), got "
                                    f"{getattr(self, key)!r}")
            wrench[key] = tuple(float(x) for x in v)
        return replace(self, payload_kg=(lo, hi), ambient_c=t, reference_c=float(self.reference_c), **wrench)

    @property
    def has_process_wrench(self) -> bool:
        """Whether a process force or moment acts."""
        return any(float(x) != 0.0 for x in (*self.process_force_n, *self.process_torque_nm))

    def corners(self) -> np.ndarray:
        """The corners of the payload x ambient box, shape (C, 2) [kg, degC] (duplicates dropped)."""
        pts = {(m, t) for m in self.payload_kg for t in self.ambient_c}
        return np.array(sorted(pts), float)


def with_parts(robot: Robot, choice: dict) -> Robot:
    """A copy of ``robot`` whose joints carry the catalogue parts ``choice`` ``{(joint, kind): part name}``."""
    try:
        comps = robot.components.with_choice(choice)
    except ValueError as exc:
        raise TolallocError(str(exc)) from None
    out = copy.copy(robot)
    object.__setattr__(out, "components", comps)
    return out


def _process_wrench(R: np.ndarray, tool: np.ndarray, payload_point: np.ndarray, conditions: Conditions) -> tuple:
    """The conditions' process wrench in the base frame, shape (P, 6) [N, N m], at the tool point and moved to the
    payload's point (the moment about it: ``M + (tool - payload point) x F``, the lever in m); ``(None, None)``
    without one. ``R`` (P, 3, 3): the tool frame's orientation at each pose; ``tool``, ``payload_point`` (P, 3) [mm]."""
    if not conditions.has_process_wrench:
        return None, None
    F = R @ np.asarray(conditions.process_force_n, float)
    M = R @ np.asarray(conditions.process_torque_nm, float)
    moved = M + 1e-3 * np.cross(tool - payload_point, F)
    return np.concatenate([F, M], axis=1), np.concatenate([F, moved], axis=1)


def _rotation_of(displacement, p: np.ndarray) -> np.ndarray:
    """Rotation [rad] (P, 3) of the rigid body beyond a deflection whose displacement of a target point ``p`` (P, 3)
    is ``displacement(p)``: ``d(p + e) - d(p) = theta x e`` for the unit axes ``e`` (the loads stay where they are;
    a process wrench moves with the point by 1 mm, a 1e-3 relative change of its moment at a metre's reach)."""
    d0 = displacement(p)
    dx, dy, dz = (displacement(p + e) - d0 for e in np.eye(3))
    # theta x e_x = (0, t_z, -t_y), theta x e_y = (-t_z, 0, t_x), theta x e_z = (t_y, -t_x, 0)
    return np.stack([(dy[:, 2] - dz[:, 1]) / 2, (dz[:, 0] - dx[:, 2]) / 2, (dx[:, 1] - dy[:, 0]) / 2], axis=1)


def gear_harmonics(red, revolute: bool, stroke_mm: float | None = None) -> tuple:
    """``(orders (K,), amplitudes (K,))`` [rad or mm] of reducer ``red``'s transmission error in its joint's angle
    (:func:`~tolalloc.physics.transmission.catalogue_amplitudes`; zero amplitudes without a transmission accuracy):
    sinusoids at random phases, each of variance ``a^2 / 2``. A linear reducer's figure (a ball screw's travel
    deviation, ISO 3408-3) is the peak-to-peak over the stroke: one half-wave over the joint's ``stroke_mm``, order
    ``pi / stroke`` [rad/mm] (a bow and, at its phase, a trend over the stroke; a screw's wobble within one turn of
    its lead is not in the catalogue's figure and is not modelled)."""
    ptp = red.transmission_accuracy or 0.0
    if revolute:
        return catalogue_amplitudes(ptp, red.ratio)
    if not stroke_mm or not np.isfinite(stroke_mm) or stroke_mm <= 0:
        raise TolallocError(f"a linear reducer's transmission error needs the joint's stroke [mm], got {stroke_mm!r}")
    return np.array([np.pi / float(stroke_mm)]), np.array([ptp / 2.0])


def stroke_of(robot: Robot, j: int) -> float | None:
    """Joint ``j``'s range [mm] if it is prismatic (its limits), else None."""
    return None if robot.joints[j].is_revolute else float(robot.upper[j] - robot.lower[j])


def encoder_harmonics(enc, ratio: float | None, revolute: bool) -> tuple:
    """``(orders (K,), amplitudes (K,))`` [rad or mm] of encoder ``enc``'s error in its joint's angle: the graduation
    error ``accuracy / 2`` once per turn, and an output-side rotary scale's eccentricity ``e / r`` once per turn
    beside it; a motor-side encoder's error at the gear ``ratio``, divided by it."""
    a = (enc.accuracy or 0.0) / 2.0
    if enc.side == "motor" and ratio and revolute:
        return np.array([float(ratio)]), np.array([a / ratio])
    if enc.eccentricity and enc.scale_radius_mm and revolute:
        return np.ones(2), np.array([a, enc.eccentricity / enc.scale_radius_mm])
    return np.ones(1), np.array([a])


def motor_side(robot: Robot, j: int) -> bool:
    """Whether joint ``j``'s position loop closes on the motor (its encoder is motor-side, or it has none)."""
    enc = robot.components.joint(robot.joints[j].name).encoder
    return enc is None or enc.side == "motor"


@dataclass(frozen=True, eq=False)
class PartsModel:
    """An error model with the parameters the effects move: every joint drive, every link length and, for joints whose
    bearing's runout is budgeted (:func:`~tolalloc.physics.bearings.budgets_runout`), four body displacements after
    the joint (``br<j><a|b>`` translations [mm], ``bw<j><a|b>`` tilts [rad]). ``drive`` (n,), ``link`` (L,) and
    ``bearing`` {joint: (4,)} index the parameters."""

    model: ErrorModel
    drive: np.ndarray
    link: np.ndarray
    bearing: dict


def parts_error_model(model: ErrorModel, robot: Robot | None = None) -> PartsModel:
    """``model`` with the parameters of :class:`PartsModel` it lacks appended (sigma 0); ``robot``: the same robot
    with its parts chosen (:func:`with_parts`; default the model's), whose bearings get parameters."""
    robot = model.robot if robot is None else robot
    params = list(model.params)
    full = build_error_model(robot, "generic", link_mode=model.link_mode, deflection_mode=model.deflection_mode)
    names = {p.name for p in params}
    for p in full.params:
        if p.kind in ("joint_drive", "link_length") and p.name not in names:
            params.append(replace(p, sigma=0.0))
    bearing = {}
    for j, jt in enumerate(robot.joints):
        b = robot.components.joint(jt.name).bearing
        if not jt.is_revolute or b is None or not budgets_runout(b):
            continue
        pt, idx = robot.joint_points_mm[j] + b.centre_mm * jt.axis, []
        for kind, tag, rot in (("clearance_radial", "br", False), ("clearance_tilt", "bw", True)):
            for letter, e in perpendicular_axes(jt.axis):
                twist = np.concatenate([e, -np.cross(e, pt)]) if rot else np.concatenate([np.zeros(3), e])
                idx.append(len(params))
                params.append(ErrorParameter(f"{tag}{j + 1}{letter}", kind, jt.name, "rad" if rot else "mm", j + 1,
                                             twist, sigma=0.0))
        bearing[j] = np.array(idx)
    out = replace(model, robot=robot, params=tuple(params))
    pos = {p.name: k for k, p in enumerate(out.params)}
    drive = np.array([pos[f"dth{j + 1}" if jt.is_revolute else f"dd{j + 1}"] for j, jt in enumerate(robot.joints)])
    link = np.array([pos[f"d{lk.name}"] for lk in robot.links if lk.length_mm > 0], int)
    return PartsModel(out, drive, link, bearing)


class PartEffects:
    """The effects at P points of a robot whose parts are resolved (:func:`with_parts`).

    Parameters
    ----------
    robot : Robot
    q : array, shape (P, n) [rad, mm]
    payload_kg, ambient_c : arrays, shape (P,)   the condition at each point
    conditions : Conditions                       reference temperature and duty
    model : ErrorModel, optional                  the geometric model to extend (default: the robot's generic one)
    pm : PartsModel, optional                     the extended model, when built already (for ``robot``)
    rotations : bool                              also the rotation beyond the beams', the bearings' tilt and the
                                                  mount's deflection
                                                  (three more evaluations each; the chain terms carry theirs)
    """

    def __init__(self, robot: Robot, q, payload_kg, ambient_c, conditions: Conditions = Conditions(),
                 model: ErrorModel | None = None, pm: PartsModel | None = None, rotations: bool = False):
        self.robot, self.conditions, self.rotations = robot, conditions, rotations
        self.q = np.atleast_2d(np.asarray(q, float))
        P = len(self.q)
        self.payload = np.broadcast_to(np.asarray(payload_kg, float), (P,)).copy()
        self.ambient = np.broadcast_to(np.asarray(ambient_c, float), (P,)).copy()
        self.pm = pm if pm is not None else parts_error_model(
            model if model is not None else build_error_model(robot, "generic"), robot)
        self.J6 = self.pm.model.jacobian(self.q)
        self.J = self.J6[:, :3, :]
        self.tool = target_points(robot, self.q, np.zeros(3))
        T = robot.fk_internal(self.q)
        self.payload_point = self.tool + T[:, :3, :3] @ robot.components.payload.com_mm
        self.wrench_tool, self.wrench = _process_wrench(T[:, :3, :3], self.tool, self.payload_point, conditions)
        self.tau = joint_loads(robot, self.q, self.payload_point, self.payload, self.wrench)[0]

    @property
    def n_points(self) -> int:
        return len(self.q)

    def _term(self, names, effect, j, col, mean=None, sys=None, rnd=None, rot=None) -> EffectTerms:
        """One term along ``col`` (P, 3), or along the error model's parameter ``col`` (an index: its position and
        rotation columns); ``rot`` (P, 3) the rotation of a direct displacement."""
        P = self.n_points
        z = np.zeros((P, 1))
        f = (lambda a: z if a is None else np.broadcast_to(np.asarray(a, float), (P,))[:, None].copy())
        if np.ndim(col) == 0:
            col, rot = self.J6[:, :3, col], self.J6[:, 3:, col]
        rot = np.zeros((P, 3)) if rot is None else rot
        return EffectTerms((names,), (effect,), np.array([j]), col[:, :, None], f(mean), f(sys), f(rnd),
                           rot[:, :, None])

    def reducer_terms(self, j: int, red, loop_on_motor: bool = True,
                      effects: tuple = ("compliance", "lost_motion", "transmission")) -> EffectTerms:
        """Terms of joint ``j``'s reducer ``red`` among ``effects`` (compliance, lost motion, transmission); none when
        the loop closes on an output-side encoder."""
        out, nm = EffectTerms.empty(self.n_points), self.robot.joints[j].name
        if red is None or not loop_on_motor:
            return out
        col = self.pm.drive[j]
        if red.stiffness and "compliance" in effects:
            w = red.deflection(self.tau[:, j])
            out += self._term(f"windup_{nm}", "compliance", j, col, w, (red.stiffness_sd or 0.0) * np.abs(w))
        if red.lost_motion and "lost_motion" in effects:
            out += self._term(f"lost_motion_{nm}", "lost_motion", j, col, rnd=red.lost_motion / 2.0)
        if (red.transmission_accuracy or red.repeatability) and "transmission" in effects:
            _, amp = gear_harmonics(red, self.robot.joints[j].is_revolute, stroke_of(self.robot, j))
            out += self._term(f"transmission_{nm}", "transmission", j, col, sys=np.sqrt(np.sum(amp ** 2) / 2),
                              rnd=(red.repeatability or 0.0) / np.sqrt(3.0))
        return out

    def encoder_terms(self, j: int, enc, ratio: float | None) -> EffectTerms:
        """Terms of joint ``j``'s encoder ``enc``: graduation error (and eccentricity ``e / r`` of an output-side
        rotary scale) once per turn; a motor-side encoder's error divided by the gear ratio ``ratio``."""
        out, nm = EffectTerms.empty(self.n_points), self.robot.joints[j].name
        if enc is not None and (enc.accuracy or enc.eccentricity):
            _, amp = encoder_harmonics(enc, ratio, self.robot.joints[j].is_revolute)
            out += self._term(f"encoder_{nm}", "encoder", j, self.pm.drive[j], sys=np.sqrt(np.sum(amp ** 2) / 2))
        if enc is not None and enc.homing_repeatability:
            out += self._term(f"homing_{nm}", "homing", j, self.pm.drive[j],
                              rnd=enc.homing_repeatability / np.sqrt(3.0))
        if enc is not None and enc.scale_expansion is not None:
            grow = scale_error(enc.scale_expansion, self.q[:, j], self.ambient - self.conditions.reference_c)
            out += self._term(f"scale_{nm}", "thermal", j, self.pm.drive[j], grow, THERMAL_SD * np.abs(grow))
        return out

    def bearing_terms(self, j: int, bearing, effects: tuple = ("bearing", "compliance")) -> EffectTerms:
        """Terms of joint ``j``'s bearing pair among ``effects``: its runout (``bearing``, the four body
        displacements of :mod:`tolalloc.physics.bearings`, where :func:`~tolalloc.physics.bearings.budgets_runout`)
        and its tilt under the moment across the axis (``compliance``, where it gives a tilt stiffness)."""
        out = EffectTerms.empty(self.n_points)
        if bearing is None or not self.robot.joints[j].is_revolute:
            return out
        if "bearing" in effects and j in self.pm.bearing:
            if bearing.radial_runout is None or bearing.span_mm is None:
                name = self.robot.joints[j].name
                raise TolallocError(f"robot {self.robot.name!r}: joint {name!r}'s bearing gives no "
                                    f"{'radial_runout_um' if bearing.radial_runout is None else 'span_mm'}; add "
                                    f"components.joints.{name}.bearing.radial_runout_um (Kia of its ISO 492 class at "
                                    "its bore) and span_mm, or choose the bearing from a catalogue slot")
            for k, sd in zip(self.pm.bearing[j], runout_sd(bearing)):
                out += self._term(f"bearing_{self.pm.model.params[k].name}", "bearing", j, k, sys=sd)
        if bearing.tilt_stiffness and "compliance" in effects:
            theta, centre = (x[:, j] for x in self.bearing_rotations)
            out += self._term(f"tilt_{self.robot.joints[j].name}", "compliance", j,
                              np.cross(theta, self.tool - centre), 1.0, TILT_SD, rot=theta if self.rotations else None)
        return out

    @functools.cached_property
    def bearing_rotations(self) -> tuple:
        """Every bearing's tilt [rad] and the centre it turns about [mm] at these points, each (P, n, 3)
        (:func:`~tolalloc.physics.compliance.bearing_rotations`): computed once for all the joints' terms."""
        return bearing_rotations(self.robot, self.q, self.payload_point, self.payload, self.wrench)

    def joint_terms(self, j: int) -> EffectTerms:
        """Every term of joint ``j``'s resolved parts."""
        parts = self.robot.components.joint(self.robot.joints[j].name)
        ratio = getattr(parts.reducer, "ratio", None)
        return (self.reducer_terms(j, parts.reducer, motor_side(self.robot, j))
                + self.encoder_terms(j, parts.encoder, ratio) + self.bearing_terms(j, parts.bearing))

    def link_temperatures(self) -> np.ndarray:
        """Temperature of every link above the reference [K], shape (P, L) (:func:`tolalloc.physics.thermal.
        link_temperature` at the duty's motor heating)."""
        rise = motor_rise(self.robot, self.tau, self.conditions.duty)
        return link_temperature(self.robot, self.ambient - self.conditions.reference_c, rise)

    def _rotation(self, displacement) -> np.ndarray | None:
        return _rotation_of(displacement, self.tool) if self.rotations else None

    def body_terms(self) -> EffectTerms:
        """The terms that belong to no joint: thermal growth of every link, beam sag, mount tilt."""
        out, r = EffectTerms.empty(self.n_points), self.robot
        cte, dT = link_cte(r), self.link_temperatures()
        links = [lk for lk in r.links if lk.length_mm > 0]
        for k, lk in enumerate(links):
            if cte[k] > 0:
                grow = cte[k] * dT[:, k] * lk.length_mm
                out += self._term(f"thermal_{lk.name}", "thermal", -1, self.pm.link[k], grow,
                                  THERMAL_SD * np.abs(grow))
        if r.components.links:
            sag = (lambda p: beam_sag(r, self.q, p, self.payload, self.payload_point, self.wrench_tool))
            out += self._term("beam", "beam", -1, sag(self.tool), 1.0, BEAM_SD, rot=self._rotation(sag))
        if r.components.mount.tilt_stiffness is not None:
            tilt = (lambda p: mount_tilt(r, self.q, p, self.payload_point, self.payload, self.wrench))
            out += self._term("mount", "mount", -1, tilt(self.tool), 1.0, MOUNT_SD, rot=self._rotation(tilt))
        return out

    def terms(self) -> EffectTerms:
        """Every term of the robot's resolved parts, joints first."""
        out = EffectTerms.empty(self.n_points)
        for j in range(self.robot.n_joints):
            out += self.joint_terms(j)
        return out + self.body_terms()

    def check_rated(self, where: str = "the region") -> None:
        """Refuse reducers whose rated torque (force) the load at these points exceeds, naming the joint, the
        part, the load and by how much."""
        for j, jt in enumerate(self.robot.joints):
            red = self.robot.components.joint(jt.name).reducer
            if red is None or red.rated_torque is None:
                continue
            i = int(np.argmax(np.abs(self.tau[:, j])))
            load = abs(float(self.tau[i, j]))
            if load > red.rated_torque:
                unit = "N m" if jt.is_revolute else "N"
                raise TolallocError(
                    f"joint {jt.name}: the load reaches {load:.4g} {unit} in {where} (payload "
                    f"{self.payload[i]:g} kg), {load - red.rated_torque:.4g} {unit} ({100 * (load / red.rated_torque - 1):.0f} %) "
                    f"above the rated torque {red.rated_torque:.4g} {unit} of its reducer ({red.source[:60] or red.type}); "
                    f"choose a reducer rated for at least {load:.4g} {unit}, or lower the payload range")
