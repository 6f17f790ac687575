"""Guards of the diagnosis: implausible parameters, extrapolating test poses, fits worse than nominal.

* :func:`prior_flags` -- a fitted geometric parameter beyond ``n_sigma`` (3) prior standard deviations of the
  MAP calibration (:mod:`.geometry`): the data pulled it far past what the robot's sigma set makes plausible
  (an unidentifiable combination drifting, a wrong robot or probe, gross outliers).
* :func:`extrapolation_flags` -- per test pose: a joint value outside the training range by more than a
  margin (5 deg / 5 mm), or a joint-space distance to the nearest training pose (each joint divided by its
  training standard deviation) beyond ``far_factor`` x the 95th percentile of the training poses'
  leave-one-out nearest-neighbour distances. Such predictions are extrapolations.
* :func:`cv_fallback` -- a fitted model that does worse than a simpler one on cross-validation (out-of-fold RMS
  larger by more than ``FALLBACK_MARGIN``, 1 %) is not used: final worse than nominal -> nominal; final (with
  effects) worse than geometric -> geometric. Geometry alone worse than nominal while the final model wins
  is reported as a note, without fallback.
* :func:`prediction_uncertainty` -- per test pose the predicted 1-sigma of the final model's prediction from the
  parameter covariance of its fit (Gauss-Newton ``sigma^2 (J^T J)^-1`` over the fitted parameters, with the MAP
  prior's precision added), and the 95 % radius of measured - predicted (prediction + measurement noise). The
  fraction of scored test residuals inside that radius is the calibration check; below 85 % (and beyond 3
  binomial standard deviations below 95 %) it fires: the model misses systematic error its covariance does not
  know of.

Every guard returns plain messages; the pipeline lists them in ``Diagnosis.guards`` (JSON ``guards``) and the
CLI prints them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from tolalloc.linear.probability import radius_for_prob
from tolalloc.robot.lie import hat
from tolalloc.robot.model import Robot
from tolalloc.diagnose.calibrate import fixed_jacobian

__all__ = ["Extrapolation", "extrapolation_flags", "prior_flags", "cv_fallback", "RANGE_MARGIN_DEG",
           "RANGE_MARGIN_MM", "FAR_FACTOR", "PRIOR_N_SIGMA", "FALLBACK_MARGIN",
           "PoseUncertainty", "point_jacobian", "parameter_covariance", "prediction_uncertainty", "COVERAGE_P", "COVERAGE_LOW"]

RANGE_MARGIN_DEG = 5.0
RANGE_MARGIN_MM = 5.0
FAR_FACTOR = 1.5
PRIOR_N_SIGMA = 3.0
FALLBACK_MARGIN = 0.01
COVERAGE_P = 0.95
#: The coverage guard fires below this (and 3 binomial sd below 95 %): the noise level is itself estimated
#: (a few % off on ~100 training poses), which alone moves a correct model's coverage by a few points.
COVERAGE_LOW = 0.85


@dataclass(frozen=True, eq=False)
class Extrapolation:
    """Extrapolation flags of test poses.

    Attributes
    ----------
    outside_range : array of bool, shape (T,)   some joint outside the training range by more than the margin
    far : array of bool, shape (T,)             nearest training pose farther than ``threshold``
    distance : array, shape (T,)                normalised joint-space distance to the nearest training pose
    threshold : float                           ``FAR_FACTOR`` x 95th percentile of training LOO distances
    joints_outside : tuple of str               joints some test pose leaves the training range of
    """

    outside_range: np.ndarray
    far: np.ndarray
    distance: np.ndarray
    threshold: float
    joints_outside: tuple

    @property
    def flagged(self) -> np.ndarray:
        return self.outside_range | self.far

    def message(self) -> str | None:
        """One guard line, or None when no pose extrapolates."""
        n = int(self.flagged.sum())
        if n == 0:
            return None
        return (f"extrapolation: {n} of {len(self.flagged)} test poses lie outside the training data "
                f"({int(self.outside_range.sum())} outside the training range of {', '.join(self.joints_outside) or '-'} "
                f"by more than {RANGE_MARGIN_DEG:g} deg / {RANGE_MARGIN_MM:g} mm; {int(self.far.sum())} farther from every "
                f"training pose than {self.threshold:.3g} (normalised joint space)); their predictions are extrapolations")

    def to_dict(self) -> dict:
        return {"flagged": self.flagged.tolist(), "outside_range": self.outside_range.tolist(), "far": self.far.tolist(),
                "distance": self.distance.tolist(), "threshold": self.threshold, "joints_outside": list(self.joints_outside)}


def extrapolation_flags(robot: Robot, q_train: np.ndarray, q_test: np.ndarray, *, far_factor: float = FAR_FACTOR) -> Extrapolation:
    """Flag test poses that extrapolate from the training poses (see the module docstring).

    Parameters
    ----------
    robot : Robot
    q_train : array, shape (P, n) [rad, mm]
    q_test : array, shape (T, n) [rad, mm]
    """
    rev = robot.revolute_mask
    margin = np.where(rev, np.deg2rad(RANGE_MARGIN_DEG), RANGE_MARGIN_MM)
    lo, hi = q_train.min(0), q_train.max(0)
    out_j = (q_test < lo - margin) | (q_test > hi + margin)
    floor = np.where(rev, np.deg2rad(1.0), 1.0)  # a joint held still in training: 1 deg / 1 mm scale
    scale = np.maximum(q_train.std(0), floor)
    tree = cKDTree(q_train / scale)
    loo = tree.query(q_train / scale, k=2)[0][:, 1] if len(q_train) > 1 else np.zeros(1)
    threshold = float(far_factor * np.percentile(loo, 95))
    dist = tree.query(q_test / scale, k=1)[0]
    joints = tuple(j.name for k, j in enumerate(robot.joints) if out_j[:, k].any())
    return Extrapolation(out_j.any(1), dist > threshold, dist, threshold, joints)


def prior_flags(fit, n_sigma: float = PRIOR_N_SIGMA) -> tuple:
    """Messages for fitted geometric parameters beyond ``n_sigma`` prior standard deviations.

    Parameters
    ----------
    fit : :class:`tolalloc.diagnose.calibrate.Fit` (its model's ``sigma`` is the prior)
    """
    out = []
    for k in fit.geo_index:
        prm = fit.model.params[k]
        if prm.sigma > 0 and abs(fit.delta[k]) > n_sigma * prm.sigma:
            f, u = prm.to_interface, prm.interface_unit
            out.append(f"implausible parameter: {prm.name} = {fit.delta[k] * f:.3g} {u} is {abs(fit.delta[k]) / prm.sigma:.1f} "
                       f"prior sigma ({prm.sigma * f:.3g} {u}); check the probe offset, the robot model and outliers")
    return tuple(out)


def cv_fallback(nominal, geometric, final, margin: float = FALLBACK_MARGIN) -> tuple:
    """Which evaluation to report as final, and the guard messages.

    Parameters
    ----------
    nominal, geometric, final : :class:`tolalloc.diagnose.select.Evaluation`
    margin : float   relative CV RMS excess that counts as worse

    Returns
    -------
    chosen : Evaluation
    messages : tuple of str   empty when nothing fired
    """
    cv = {name: float(np.sqrt(np.mean(np.sum(ev.oof_mm ** 2, axis=1))))
          for name, ev in (("nominal", nominal), ("geometric", geometric), ("final", final))}

    def pct(a, b):
        return f"{cv[a]:.4g} vs {cv[b]:.4g} mm RMS, {100 * (cv[a] / cv[b] - 1):+.1f} %"

    if cv["final"] > (1 + margin) * cv["nominal"]:
        return nominal, (f"fallback: the fitted model ({final.label}) does worse than the nominal model on "
                         f"cross-validation ({pct('final', 'nominal')}); reporting the nominal model "
                         "(registration + probe offset only) as final, no effect",)
    if final is not geometric and cv["final"] > (1 + margin) * cv["geometric"]:
        return geometric, (f"fallback: the model with effects ({final.label}) does worse than the geometric model on "
                           f"cross-validation ({pct('final', 'geometric')}); reporting the geometric model as final, "
                           "no effect",)
    if cv["geometric"] > (1 + margin) * cv["nominal"]:
        return final, (f"note: the geometric calibration alone does worse than the nominal model on cross-validation "
                       f"({pct('geometric', 'nominal')}); the final model ({final.label}) does better",)
    return final, ()


@dataclass(frozen=True, eq=False)
class PoseUncertainty:
    """Predicted uncertainty of the final model's test predictions and its calibration check.

    Attributes
    ----------
    cov_mm2 : array, shape (T, 3, 3)   covariance of each predicted test position from the parameter covariance [mm^2]
    sigma_mm : array, shape (T,)       ``sqrt(trace(cov))``: predicted 1-sigma of the 3-D prediction error [mm]
    radius95_mm : array, shape (T,)    radius holding measured - predicted with 95 % probability, measurement noise
                                       included (``cov + noise^2 I``) [mm]
    noise_mm : float                   measurement noise per coordinate, from the training residual [mm]
    scored : array of int, shape (S,)  test poses the check uses (all, or the non-registration poses)
    inside : array of bool, shape (S,) scored residual norm within ``radius95_mm``
    n_params : int                     parameters in the covariance
    """

    cov_mm2: np.ndarray
    sigma_mm: np.ndarray
    radius95_mm: np.ndarray
    noise_mm: float
    scored: np.ndarray
    inside: np.ndarray
    n_params: int

    @property
    def coverage(self) -> float:
        """Fraction of scored test residuals within the predicted 95 % radius (0.95 when calibrated)."""
        return float(self.inside.mean()) if len(self.inside) else float("nan")

    def message(self) -> str | None:
        """A guard line when the coverage is below :data:`COVERAGE_LOW` (85 %) and 3 binomial sd below 95 %."""
        n = len(self.inside)
        low = min(COVERAGE_LOW, COVERAGE_P - 3.0 * np.sqrt(COVERAGE_P * (1 - COVERAGE_P) / max(n, 1)))
        if n == 0 or self.coverage >= low:
            return None
        return (f"uncertainty: only {100 * self.coverage:.0f} % of the {n} scored test residuals lie within the "
                f"predicted 95 % radius (expected 95 %; this guard fires below {100 * low:.0f} %); the predicted "
                "uncertainties are too small -- systematic error the fitted model does not contain")

    def to_dict(self) -> dict:
        return {"sigma_mm": self.sigma_mm.tolist(), "radius95_mm": self.radius95_mm.tolist(), "noise_mm": self.noise_mm,
                "coverage95": self.coverage, "scored_poses": len(self.inside), "n_params": self.n_params,
                "method": "Gauss-Newton parameter covariance sigma^2 (J^T J + prior)^-1 of the final fit, "
                          "propagated J_pose Sigma J_pose^T; radius95 includes the measurement noise"}


def point_jacobian(fit, q: np.ndarray, B: np.ndarray | None = None) -> np.ndarray:
    """Jacobian of the predicted points at ``fit``, shape (P, 3, 9 + k + m) [mm per unit].

    Columns: registration rotation (3, rad, local), translation (3), target offset (3), the fitted geometric
    parameters ``fit.geo_index`` (k) and the effect columns ``B`` (P, 3, m) of ``fit.beta``.
    """
    J = fixed_jacobian(fit, q, np.zeros((len(q), 3))).reshape(len(q), 3, -1)
    if B is not None and B.shape[-1]:
        J[:, :, :3] = -np.einsum("ij,pjk->pik", fit.R, hat(fit.base_points(q, B)))
        J = np.concatenate([J, np.einsum("ij,pjk->pik", fit.R, B)], axis=2)
    return J


def parameter_covariance(fit, q: np.ndarray, B: np.ndarray | None = None) -> tuple:
    """Covariance of the fitted parameters (columns of :func:`point_jacobian`) and the noise per coordinate.

    ``noise^2 = RSS / (3 P - n)`` from ``fit.residual_mm``; covariance ``(J^T J / noise^2 + diag(1 / s^2))^-1``
    with ``s`` the MAP prior standard deviations of the geometric parameters (``fit.model.sigma``; none for
    registration, offset and effects).

    Returns
    -------
    cov : array, shape (n, n) [units of the parameters squared]
    noise_mm : float
    """
    J = point_jacobian(fit, q, B).reshape(3 * len(q), -1)
    n = J.shape[1]
    noise2 = float(np.sum(fit.residual_mm ** 2)) / max(J.shape[0] - n, 1)
    prec = np.zeros(n)
    sig = fit.model.sigma[fit.geo_index]
    prec[9:9 + len(sig)] = np.where(sig > 0, 1.0 / np.where(sig > 0, sig, 1.0) ** 2, 0.0)
    info = J.T @ J / noise2 + np.diag(prec)
    d = 1.0 / np.sqrt(np.maximum(np.diag(info), 1e-300))
    cov = d[:, None] * np.linalg.pinv(d[:, None] * info * d[None, :], rcond=1e-12, hermitian=True) * d[None, :]
    return cov, float(np.sqrt(noise2))


def prediction_uncertainty(fit, q_train, q_test, residual_test, *, B_train=None, B_test=None, registered=None,
                           split=None) -> PoseUncertainty:
    """Predicted uncertainty of the test predictions of ``fit`` (see the module docstring).

    Parameters
    ----------
    fit : Fit                         final fit on the training poses
    q_train : array, shape (P, n); q_test : array, shape (T, n) [rad, mm]
    residual_test : array, shape (S, 3) [mm]   measured - predicted on the scored test poses
    B_train, B_test : arrays, shape (P, 3, m), (T, 3, m), optional   effect columns of ``fit.beta``
    registered : Fit, optional        ``fit`` re-registered to the test frame (``--test-frame refit``)
    split : RegistrationSplit, optional  with ``registered``: registration and scored poses

    With ``registered`` the registration (rotation, translation, probe offset) is re-estimated on the
    registration poses, so the prediction error is ``(J_theta - J_phi G A_theta) d_theta + J_phi G n_reg``
    (``theta`` geometry and effects with the training covariance, ``phi`` the 9 registration parameters,
    ``A`` the Jacobian at the registration poses, ``G`` its least-squares inverse in ``phi``, ``n_reg`` their noise).
    """
    cov, noise = parameter_covariance(fit, q_train, B_train)
    if registered is None:
        Jt = point_jacobian(fit, q_test, B_test)
        C = np.einsum("tik,kl,tjl->tij", Jt, cov, Jt)
        scored = np.arange(len(q_test))
    else:
        Jt = point_jacobian(registered, q_test, B_test)
        A = Jt[split.register_index].reshape(-1, Jt.shape[2])
        G = np.linalg.pinv(A[:, :9])
        M = Jt[:, :, 9:] - Jt[:, :, :9] @ (G @ A[:, 9:])
        Jphi = Jt[:, :, :9]
        C = np.einsum("tik,kl,tjl->tij", M, cov[9:, 9:], M) + noise ** 2 * np.einsum("tik,kl,tjl->tij", Jphi, G @ G.T, Jphi)
        scored = split.score_index
    C = 0.5 * (C + np.swapaxes(C, 1, 2))
    r95 = radius_for_prob(C + noise ** 2 * np.eye(3), COVERAGE_P)
    inside = np.linalg.norm(residual_test, axis=1) <= r95[scored]
    return PoseUncertainty(C, np.sqrt(np.trace(C, axis1=1, axis2=2)), r95, noise, scored, inside, cov.shape[0])
