"""Complete, minimal geometric error model for calibration (the model the diagnosis fits).

Which model is used where:

* **Tolerance model** (allocation, Monte Carlo, verification): the paper's 22-parameter error-screw model
  of :func:`tolalloc.errormodel.model.build_error_model` (link lengths along each link vector, joint drives,
  axis tilts, clearances) -- parameters a designer tolerances.
* **Calibration model** (:mod:`tolalloc.diagnose`): this module. Per-joint perturbations of the screw axes
  ``S_i`` and of the home pose ``M`` in the style of Okamura & Park (1996) and He, Zhao, Yang & Yang
  (IEEE T-RO 2010): ``S_i -> S_i + dS_i`` with ``dS_i`` in the tangent space orthogonal to the screw's own
  motion -- 4-dimensional for a revolute joint (two direction errors, two position errors perpendicular to
  the axis), 2-dimensional for a prismatic joint (two direction errors) -- plus the joint offsets, the base
  (the tracker registration ``R, p``, 6, fitted in :mod:`.calibrate`) and the tool/probe offset (``t``, 3;
  position-only measurements see no tool rotation).

Each ``dS_i`` is realised as a small rigid displacement inserted into the POE chain right before joint ``i``
(site ``i`` of :class:`~tolalloc.errormodel.model.ErrorModel`): a rotation about a base axis ``e`` perpendicular
to the joint axis through the joint point ``r_i`` (twist ``(e, r_i x e)``, "tilt") or a translation along
``e`` (twist ``(0, e)``, "shift"). This moves the line of joint ``i`` by exactly the 4 (2) independent
line errors and carries every downstream axis and ``M`` along, so the chain stays consistent. The two
missing directions per revolute site (rotation about / translation along its own axis) are the joint
offset and a translation that commutes with the joint and is carried to the next site or into ``t``, so
the set spans every first-order geometric error of the chain (complete). Which of these parameters the
measured poses can separate from the registration, the probe offset and each other is decided by the
column-pivoted QR of the scaled identification Jacobian in :func:`tolalloc.diagnose.calibrate.identifiability`;
the rest is reported as dropped with the reason.

Priors (MAP calibration): every parameter gets a Gaussian prior ``N(0, sigma)`` with ``sigma`` taken from the
robot's sigma set (tilts: the joint's largest axis-deflection sigma; shifts: the robot's largest link-length
sigma; offsets: the joint-drive sigma), scaled by ``prior_scale`` (default 10). The prior is a regulariser: a
well-identified parameter is hardly shrunk (shrink factor ``s_data^2 / sigma^2``: ~2 % for a UR10 elbow
offset known to 0.03 mm under a 0.2 mm prior), a weakly identified direction is held near 0 instead of
drifting with unmodelled error. (A prior at the as-built level, below, let the geometry fitted on one UR10
session transfer worse to the other.)

Plausibility is judged separately, against the **as-built accuracy level** of the robot class
(:func:`as_built_levels`): :data:`AS_BUILT_MM_PER_M` (1 mm) per metre of robot size for position errors,
:data:`AS_BUILT_DEG` (0.1 deg) for direction errors and revolute offsets -- the order by which factory
calibration files of industrial arms (e.g. UR's) differ from the nominal DH table. A tolerance sigma set
describes a design, not a built robot: a real UR10's 1 mm elbow offset is 50 sigma of its generic set but
ordinary as built. The guards (:func:`tolalloc.diagnose.guards.parameter_checks`) use the larger of this
level and the prior sigma.
"""

from __future__ import annotations

import numpy as np

from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.model import ErrorModel, ErrorParameter, perpendicular_axes
from tolalloc.robot.model import Robot

__all__ = ["build_geometry_model", "as_built_levels", "plausibility_levels", "robot_size_mm", "PRIOR_SCALE",
           "AS_BUILT_MM_PER_M", "AS_BUILT_DEG"]

#: Factor between the robot's sigma set and the calibration prior's standard deviations.
PRIOR_SCALE = 10.0
#: As-built position error level of a joint axis per metre of robot size [mm/m].
AS_BUILT_MM_PER_M = 1.0
#: As-built direction error / joint offset level [deg].
AS_BUILT_DEG = 0.1


def as_built_levels(robot: Robot) -> tuple[float, float]:
    """As-built position level [mm] (:data:`AS_BUILT_MM_PER_M` x robot size) and angle level [rad] of ``robot``."""
    return AS_BUILT_MM_PER_M * robot_size_mm(robot) / 1000.0, float(np.deg2rad(AS_BUILT_DEG))


def plausibility_levels(model: ErrorModel) -> np.ndarray:
    """Per parameter of ``model`` the larger of its prior sigma and the robot's as-built level [mm, rad], shape (K,)."""
    pos, ang = as_built_levels(model.robot)
    return np.maximum(model.sigma, np.array([pos if p.unit == "mm" else ang for p in model.params]))


def robot_size_mm(robot: Robot) -> float:
    """Largest distance of a joint point or the flange (home pose) from the first joint point [mm]."""
    pts = np.vstack([robot.joint_points_mm, robot.home[:3, 3]])
    return float(np.linalg.norm(pts - robot.joint_points_mm[0], axis=1).max())


def _base_sigmas(robot: Robot, sigma_set: str | None) -> tuple[dict, dict, float]:
    """Per joint the largest tilt and the drive sigma, and the largest link-length sigma, from ``sigma_set``."""
    base = build_error_model(robot, sigma_set, exclude=tuple(k for k in ("clearance_axial", "clearance_radial",
                                                                         "clearance_tilt")))
    tilt, drive, link = {}, {}, 0.0
    for p in base.params:
        if p.kind == "axis_deflection":
            tilt[p.element] = max(tilt.get(p.element, 0.0), p.sigma)
        elif p.kind == "joint_drive":
            drive[p.element] = p.sigma
        elif p.kind == "link_length":
            link = max(link, p.sigma)
    return tilt, drive, link


def build_geometry_model(robot: Robot, sigma_set: str | None = None, prior_scale: float = PRIOR_SCALE) -> ErrorModel:
    """The complete geometric calibration model of ``robot`` (see the module docstring).

    Parameters
    ----------
    robot : Robot
    sigma_set : str or None
        Sigma set of the robot file (or ``generic``) the prior standard deviations derive from; None: the
        robot's default set, as :func:`~tolalloc.errormodel.model.build_error_model`.
    prior_scale : float
        Prior sigma = ``prior_scale`` x the set's sigma.

    Returns
    -------
    ErrorModel
        Parameters per joint ``<joint>_tilt_<a>``, ``<joint>_tilt_<b>`` [rad] (direction errors, all joints),
        ``<joint>_shift_<a>``, ``<joint>_shift_<b>`` [mm] (position errors, revolute joints) and
        ``<joint>_offset`` [rad or mm]; ``sigma`` holds the prior standard deviations.
        ``4 R + 2 P + n`` parameters; base and probe offset are fitted by :mod:`.calibrate`.
    """
    tilt_s, drive_s, link_s = _base_sigmas(robot, sigma_set)
    fallback_tilt = max(tilt_s.values(), default=np.deg2rad(0.005))
    link_s = link_s or 0.02
    params = []
    for j, joint in enumerate(robot.joints):
        w = robot.screws[j, :3] if joint.is_revolute else robot.screws[j, 3:]
        r = robot.joint_points_mm[j]
        for letter, e in perpendicular_axes(w):
            twist = np.concatenate([e, np.cross(r, e)])
            params.append(ErrorParameter(f"{joint.name}_tilt_{letter}", "axis_deflection", joint.name, "rad", j, twist,
                                         sigma=prior_scale * tilt_s.get(joint.name, fallback_tilt)))
        if joint.is_revolute:
            for letter, e in perpendicular_axes(w):
                params.append(ErrorParameter(f"{joint.name}_shift_{letter}", "link_length", joint.name, "mm", j,
                                             np.concatenate([np.zeros(3), e]), sigma=prior_scale * link_s))
        params.append(ErrorParameter(f"{joint.name}_offset", "joint_drive", joint.name,
                                     "rad" if joint.is_revolute else "mm", j, robot.screws[j].copy(),
                                     sigma=prior_scale * drive_s[joint.name], joint_index=j))
    return ErrorModel(robot, tuple(params), sigma_set=f"{sigma_set or 'default'} x{prior_scale:g} (calibration prior)")
