"""Parameter covariance of a diagnosis fit and the predicted uncertainty of its test predictions.

* :func:`information` -- the Gauss-Newton information matrix of a fit's parameters (columns of
  :func:`point_jacobian`: registration, probe offset, geometric parameters, effect columns) with the fit's prior
  precisions, and the noise variance per coordinate (the data and prior parts apart: :func:`information_parts`);
  :func:`parameter_covariance` inverts it (scaled pseudo-inverse, :func:`scaled_pinv`);
  :func:`tolalloc.diagnose.power_prior.calibration_prior` marginalises it over the registration.
* :func:`prediction_uncertainty` -- per test pose the predicted 1-sigma of the final model's prediction from the
  parameter covariance of its fit (Gauss-Newton ``sigma^2 (J^T J)^-1`` over the fitted parameters, with the MAP
  prior's precision added; after a calibration update on a new session's registration poses, the update's
  posterior), and the 95 % radius of measured - predicted (prediction + measurement noise). The
  fraction of scored test residuals inside that radius is the calibration check; below 85 % (and beyond 3
  binomial standard deviations below 95 %) it fires (:meth:`PoseUncertainty.message`): the model misses
  systematic error its covariance does not know of.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.linear.probability import radius_for_prob
from tolalloc.robot.lie import hat
from tolalloc.diagnose.calibrate import fixed_jacobian

__all__ = ["COVERAGE_P", "COVERAGE_LOW", "UNCERTAINTY_METHODS", "PoseUncertainty", "point_jacobian", "information",
           "information_parts", "scaled_pinv", "parameter_covariance", "prediction_uncertainty"]

#: Noise variance per coordinate [mm^2] assumed for a fit without residuals.
NOISE2_NO_RESIDUAL = 0.05 ** 2
COVERAGE_P = 0.95
#: The coverage guard fires below this (and 3 binomial sd below 95 %): the noise level is itself estimated
#: (a few % off on ~100 training poses), which alone moves a correct model's coverage by a few points.
COVERAGE_LOW = 0.85


#: How the prediction covariance of :func:`prediction_uncertainty` is obtained, per case.
UNCERTAINTY_METHODS = {
    "same": "Gauss-Newton parameter covariance sigma^2 (J^T J + prior)^-1 of the final fit, propagated "
            "J_pose Sigma J_pose^T",
    "refit": "Gauss-Newton parameter covariance sigma^2 (J^T J + prior)^-1 of the final fit for the geometric and "
             "effect parameters, with the registration and probe offset re-estimated on the registration poses "
             "(their noise propagated), propagated to each test pose",
    "update": "posterior covariance sigma^2 H^-1 of the calibration update (registration rows with their robust "
              "weights plus the update's prior), frame, probe offset and updated parameters together, propagated "
              "J_pose Sigma J_pose^T",
}


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
    method : str                       how ``cov_mm2`` was obtained (:data:`UNCERTAINTY_METHODS`)
    """

    cov_mm2: np.ndarray
    sigma_mm: np.ndarray
    radius95_mm: np.ndarray
    noise_mm: float
    scored: np.ndarray
    inside: np.ndarray
    n_params: int
    method: str = ""

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
                "method": self.method + "; radius95 includes the measurement noise"}


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


def information_parts(fit, q: np.ndarray, B: np.ndarray | None = None) -> tuple:
    """The two parts of :func:`information`: the data's ``J^T J / noise^2`` and the prior precisions (diagonal).

    Returns
    -------
    data : array, shape (n, n) [1 / units of the parameters squared]
    prior : array, shape (n,) [1 / units squared]   0 where a parameter has no prior
    noise2 : float [mm^2]
    """
    J = point_jacobian(fit, q, B).reshape(3 * len(q), -1)
    n = J.shape[1]
    res = np.asarray(fit.residual_mm)
    noise2 = float(np.sum(res ** 2)) / max(res.size - n, 1) if res.size else NOISE2_NO_RESIDUAL
    prec = np.zeros(n)
    sig = fit.model.sigma[fit.geo_index]
    prec[9:9 + len(sig)] = np.where(sig > 0, 1.0 / np.where(sig > 0, sig, 1.0) ** 2, 0.0)
    if getattr(fit, "t_prior_mm", None) is not None:  # the target-offset prior the fit used
        prec[6:9] = 1.0 / np.asarray(fit.t_prior_mm[1], float) ** 2
    w = getattr(fit, "beta_prior_w", None)
    if w is not None and n - 9 - len(sig) == len(w):  # ridge rows w beta: precision w^2 / noise^2
        prec[9 + len(sig):] = np.asarray(w, float) ** 2 / noise2
    return J.T @ J / noise2, prec, noise2


def information(fit, q: np.ndarray, B: np.ndarray | None = None) -> tuple:
    """Gauss-Newton information matrix of ``fit``'s parameters on the poses ``q`` with the fit's prior precisions,
    and the noise variance per coordinate.

    ``noise^2 = RSS / (3 P - n)`` from ``fit.residual_mm`` (all rows of the fit; ``q`` may be a subsample of
    them); information ``J^T J / noise^2 + diag(1 / s^2)`` with ``J`` the columns of :func:`point_jacobian` and
    ``s`` the MAP prior standard deviations of the geometric parameters (``fit.model.sigma``), of the target offset
    when the fit had a prior on it (``fit.t_prior_mm``) and of ridge-regularised effect parameters
    (``fit.beta_prior_w``: precision ``w^2 / noise^2``); none for the registration (:func:`information_parts`).

    Returns
    -------
    info : array, shape (n, n) [1 / units of the parameters squared]
    noise2 : float [mm^2]
    """
    data, prec, noise2 = information_parts(fit, q, B)
    return data + np.diag(prec), noise2


def _diag_scale(M: np.ndarray) -> np.ndarray:
    """Square roots of the diagonal of ``M`` (1 where it is not positive): the parameters mix mm, rad and effect units."""
    d = np.sqrt(np.clip(np.diag(M), 0.0, None))
    return np.where(d > 0, d, 1.0)


def scaled_pinv(M: np.ndarray, rcond: float | None = None) -> np.ndarray:
    """Pseudo-inverse of the symmetric matrix ``M`` (n, n) after scaling it to unit diagonal; ``rcond`` as
    :func:`numpy.linalg.pinv` (on the scaled matrix)."""
    d = _diag_scale(M)
    S = np.outer(d, d)
    return np.linalg.pinv(M / S, rcond=rcond, hermitian=True) / S


def parameter_covariance(fit, q: np.ndarray, B: np.ndarray | None = None, *, unresolved: str = "drop") -> tuple:
    """Covariance of the fitted parameters (columns of :func:`point_jacobian`) and the noise per coordinate.

    The inverse of :func:`information`. ``unresolved``: directions the information matrix does not resolve
    (scaled eigenvalue below 1e-12 of the largest) get variance 0 (``"drop"``, a pseudo-inverse: prediction
    uncertainty) or a variance 1e12 x their scale (``"inflate"``: the parameter is not pinned down).

    Returns
    -------
    cov : array, shape (n, n) [units of the parameters squared]
    noise_mm : float
    """
    info, noise2 = information(fit, q, B)
    if unresolved == "drop":
        return scaled_pinv(info, rcond=1e-12), float(np.sqrt(noise2))
    d = _diag_scale(info)
    w, V = np.linalg.eigh(info / np.outer(d, d))
    cov = ((V / np.maximum(w, 1e-12 * w.max())) @ V.T) / np.outer(d, d)
    return cov, float(np.sqrt(noise2))


def prediction_uncertainty(fit, q_train, q_test, residual_test, *, B_train=None, B_test=None, registered=None,
                           split=None, posterior_cov=None) -> PoseUncertainty:
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
    With ``posterior_cov`` (the calibration update's covariance of the frame, probe offset and updated parameters,
    :class:`~tolalloc.diagnose.register.Registered`) the prediction covariance is ``J cov J^T`` at ``registered``:
    the updated model's own uncertainty.
    """
    cov, noise = parameter_covariance(fit, q_train, B_train)
    if registered is not None and posterior_cov is not None:
        Jt = point_jacobian(registered, q_test, B_test)
        C = np.einsum("tik,kl,tjl->tij", Jt, posterior_cov, Jt)
        scored, method = split.score_index, "update"
    elif registered is None:
        Jt = point_jacobian(fit, q_test, B_test)
        C = np.einsum("tik,kl,tjl->tij", Jt, cov, Jt)
        scored, method = np.arange(len(q_test)), "same"
    else:
        method = "refit"
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
    n_par = posterior_cov.shape[0] if method == "update" else cov.shape[0]
    return PoseUncertainty(C, np.sqrt(np.trace(C, axis1=1, axis2=2)), r95, noise, scored, inside, n_par,
                           UNCERTAINTY_METHODS[method])
