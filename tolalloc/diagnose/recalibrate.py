"""Cross-session re-registration with a calibration update (``register_update="calibration"``).

The frame-only re-registration (:func:`tolalloc.diagnose.register.register_and_score`) re-fits the test file's
tracker frame (6) and probe offset (3) on the registration poses with the trained model frozen. The calibration
update fits, on the same registration poses, the frame, the probe offset **and** a correction of the trained
geometric and effect parameters ``theta``, with the training fit as the prior: the same robot,
re-measured, whose parameters move only as far as the training data allow.

Prior of ``theta``: a **power prior** (:mod:`tolalloc.diagnose.power_prior`) -- the training data's likelihood
raised to ``1/k`` times the training fit's own prior; ``k`` chosen by the registration poses' marginal likelihood,
at least the training file's own factor (:func:`~tolalloc.diagnose.power_prior.inflation_factor`). The update then
minimises ``|r_reg|^2 + noise^2 (theta - m_k)^T P_k (theta - m_k)`` with a robust loss: Huber's (``huber`` or
``soft_l1`` when the diagnosis uses it) -- Tukey's biweight, beside a strong prior, can reject the registration
poses that disagree with the trained parameters instead of moving the parameters.
Registration poses whose frame-only residual exceeds ``TUKEY_C`` x the median norm are set aside from the choice of
``k`` and from the update (:func:`gross_errors`; none when fewer than ``MIN_REGISTER`` poses would remain); the rest
enter the marginal likelihood without robust weights. The noise is not estimated with ``k``: across the UR10
sessions a free noise scale takes the misfit the trained model's parameters cannot explain as noise (it went to
the largest value allowed, 16 x the training variance), which held the update back (a scratch run, not kept).

On the real UR10 across sessions (train on one session, test on the other; ``studies/sim2real_ur10``) the
registration poses chose ``k`` of 328-10,000 for the final model -- the new session moved the parameters far more
than the training posterior allowed -- and with 30 registration poses spread over the session (``k`` 1,003 and
1,161) the update lowered the scored final test RMS from 0.563 to 0.266 mm (A -> C) and from 0.732 to 0.460 mm
(C -> A). A model without
parameters beyond the frame (nominal) is re-registered as before. The predicted uncertainty of the test poses
(:func:`tolalloc.diagnose.uncertainty.prediction_uncertainty`) propagates the update's posterior covariance
(:func:`posterior_covariance`: the registration rows, with their robust weights, and the prior at the chosen
``k``), so the coverage of the scored poses checks the updated model's own uncertainty (:data:`UNCERTAINTY_SCOPE`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.diagnose.calibrate import TUKEY_C, HUBER_C, Fit
from tolalloc.diagnose.uncertainty import point_jacobian
from tolalloc.diagnose.power_prior import (INFLATION_MAX, CalibrationPrior, calibration_prior,
                                          evidence_discount, inflation_factor, project_out)
from tolalloc.diagnose.measurements import file_rows
from tolalloc.diagnose.register import MIN_REGISTER, Registered, RegistrationSplit, register_and_score
from tolalloc.diagnose.scale import Problem, norm_scale, robust_scale, solve

__all__ = ["REGISTER_UPDATES", "UNCERTAINTY_SCOPE", "CalibrationUpdate", "gross_errors", "posterior_covariance",
           "registration_prior", "register_update", "reregister", "update_loss"]

#: ``register_update`` choices: re-fit the frame and probe offset only, or also update the calibration.
REGISTER_UPDATES = ("frame", "calibration")
#: What the predicted uncertainty of a calibration-update run is, said beside each of its coverage figures.
UNCERTAINTY_SCOPE = ("predicted uncertainty of the updated model: the calibration update's posterior covariance (its "
                     "prior, the power prior of the training fit at k, and the registration poses), so this coverage "
                     "checks the updated model's own uncertainty")


def update_loss(loss: str | None) -> str:
    """The robust loss of the calibration update for the diagnosis loss ``loss``: Huber's in place of Tukey's."""
    return "huber" if loss in (None, "tukey") else loss


@dataclass(frozen=True, eq=False)
class CalibrationUpdate:
    """What a ``register_update="calibration"`` re-registration fitted, for the reports.

    Attributes
    ----------
    inflation_k : dict            model label -> inflation ``k`` of its prior (models the update changed), chosen
                                  by the registration poses' marginal likelihood (:func:`registration_prior`)
    inflation_floor_k : dict      model label -> the floor of ``k``: the training file's
                                  :func:`~tolalloc.diagnose.power_prior.inflation_factor`
    set_aside_poses : dict        model label -> test poses (0-based) among the registration poses set aside as
                                  gross errors (:func:`gross_errors`), a tuple
    robust_loss : str             loss of the update (:func:`update_loss`)
    """

    inflation_k: dict
    inflation_floor_k: dict
    set_aside_poses: dict
    robust_loss: str

    def fitted(self) -> str:
        """What the registration poses fitted, in words."""
        def one(m, k):
            floor = self.inflation_floor_k.get(m)
            at = (" (its floor)" if floor is not None and k <= floor
                  else " (the largest allowed)" if k >= INFLATION_MAX else "")
            n = len(self.set_aside_poses.get(m, ()))
            aside = f", {n} registration pose{'s' if n > 1 else ''} set aside as gross error{'s' if n > 1 else ''}"
            return f"{m} {f'{k:,.0f}' if k >= 100 else f'{k:.3g}'}{at}" + (aside if n else "")

        ks = "; ".join(one(m, k) for m, k in self.inflation_k.items()) or "none"
        return ("the tracker frame, the probe offset and a correction of the trained geometric and effect parameters "
                "(power prior: the training data counting 1/k beside the fit's own prior, k as the registration poses' "
                "marginal likelihood chose it: "
                f"k = {ks}; {self.robust_loss} loss)")

    def to_dict(self, rows: np.ndarray | None = None) -> dict:
        """JSON block; ``rows``: 1-based file rows of the test poses (``Measurements.rows``; default position + 1)."""
        numbers = file_rows(rows, 1 + max((i for ix in self.set_aside_poses.values() for i in ix), default=-1))

        return {"update": "calibration", "prior": "power prior of the geometric and effect parameters: the "
                "training data's likelihood raised to 1/k times the training fit's own prior, k (inflation_k) the "
                "value that maximises the registration poses' marginal likelihood (frame and probe offset "
                "marginalised, noise at the training residual level), at least inflation_floor_k (out-of-fold / "
                "in-sample mean square residual of the training file, >= 1), at most inflation_k_max unless the floor "
                "is higher; registration rows with a gross error (set_aside_rows) are left out of the choice and the "
                "update",
                "inflation_k": dict(self.inflation_k), "inflation_floor_k": dict(self.inflation_floor_k),
                "inflation_k_max": INFLATION_MAX,
                "set_aside_rows": {m: [int(numbers[i]) for i in ix] for m, ix in self.set_aside_poses.items()},
                "robust_loss": self.robust_loss}


def gross_errors(residual_mm: np.ndarray, loss: str | None) -> np.ndarray:
    """Registration poses whose frame-only residual is a gross error (boolean, shape (r,)): 3-D norm above
    ``TUKEY_C`` x the median norm, where Tukey's biweight gives no weight; none for ``loss="none"``."""
    e = np.linalg.norm(residual_mm, axis=1)
    if loss == "none" or not len(e):
        return np.zeros(len(e), bool)
    return e > TUKEY_C * norm_scale(residual_mm)


def registration_prior(start, q: np.ndarray, xyz: np.ndarray, B: np.ndarray | None, prior: CalibrationPrior,
                       k_min: float) -> CalibrationPrior:
    """``prior`` (at any ``k``) at the ``k`` the registration poses choose instead.

    ``start`` is the frame-only re-registration (its frame and probe offset linearise the model); ``q, xyz, B``
    are the registration poses (gross errors already set aside, :func:`gross_errors`), their measurements (test
    frame) and effect columns. The frame and probe offset are marginalised (a flat prior: with a probe-offset
    prior given, the choice of ``k`` ignores it, the conservative side) by projecting the residuals and the
    parameter columns onto the complement of their Jacobian columns
    (:func:`~tolalloc.diagnose.power_prior.evidence_discount`).
    """
    J = point_jacobian(start, q, B).reshape(3 * len(q), -1)
    r = (xyz - start.predict(q, B)).ravel()
    (y, A), n_eff = project_out(J[:, :9], r, J[:, 9:])
    k, _ = evidence_discount(y, A, prior, k_min, n_eff=n_eff)
    return prior.widened(k, float(k_min))


class _PriorProblem(Problem):
    """The measurement model with a full Gaussian prior ``(x[9:] - mean)^T precision (x[9:] - mean)``."""

    def set_full_prior(self, mean: np.ndarray, precision: np.ndarray) -> None:
        self._mean, self._prec = mean, precision

    def normal(self, x):
        cost, H, g, raw = super().normal(x)
        d = x[9:] - self._mean
        Pd = self._prec @ d
        H[9:, 9:] += self._prec
        g[9:] += Pd
        return cost + float(d @ Pd), H, g, raw


def register_update(fit: Fit, q: np.ndarray, xyz: np.ndarray, B: np.ndarray | None, split: RegistrationSplit,
                    prior: CalibrationPrior, *, t_prior=None, loss: str | None = None,
                    k_min: float | None = None) -> Registered:
    """Re-register the test file's frame and probe offset and update ``theta`` on ``split.register_index``.

    Parameters
    ----------
    fit : Fit                        trained model
    q : array, shape (T, n) [rad, mm]; xyz : array, shape (T, 3) [mm]   test poses, test tracker frame
    B : array, shape (T, 3, m), optional   the effect columns of ``fit.beta`` on the test poses
    split : RegistrationSplit
    prior : CalibrationPrior         :func:`calibration_prior` of ``fit``
    t_prior, loss                    as :func:`tolalloc.diagnose.register.register_and_score`
    k_min : float, optional          given: ``prior`` is the one at ``k = 1`` and the registration poses choose
                                     ``k >= k_min`` (:func:`registration_prior`); None: ``prior`` as given

    Starts from the frame-only re-registration; returns the updated fit (test frame), its predictions of every
    test pose, the residuals of the scored poses, the posterior covariance and the prior used.
    """
    no_b = B is None or not B.shape[-1]
    extra = np.zeros((len(q), 3)) if no_b else B @ fit.beta
    start = register_and_score(fit, q, xyz, extra, split, t_prior=t_prior, loss=loss)
    if not len(prior.trained):
        return start
    r, s0 = split.register_index, start.fit
    gross = gross_errors(xyz[r] - start.pred_mm[r], update_loss(loss))
    kept = tuple(int(i) for i in r[gross]) if gross.sum() > len(r) - MIN_REGISTER else ()
    r = r if kept else r[~gross]
    Br = None if no_b else B[r]
    aside = tuple(int(i) for i in np.setdiff1d(split.register_index, r))
    prior = replace(prior if k_min is None else registration_prior(s0, q[r], xyz[r], Br, prior, k_min),
                    set_aside=aside, gross_kept=kept)
    prob = _PriorProblem(fit.model, s0.R, s0.p_mm, s0.t_mm, fit.delta, q[r], xyz[r], fit.geo_index, Br)
    prob.set_full_prior(prior.mean, prior.precision)
    if t_prior is not None:
        prob.set_priors((t_prior[0], prior.noise_mm / np.broadcast_to(np.asarray(t_prior[1], float), (3,))))
    x0 = np.concatenate([np.zeros(3), s0.p_mm, s0.t_mm, prior.mean])
    x, raw = solve(prob, x0, max_iter=60, label="calibration update")
    # Tukey's biweight is not used here: beside a strong prior it can reject the registration poses that disagree
    # with the trained parameters (bounded loss) instead of moving them; Huber's convex loss cannot.
    loss = update_loss(loss)
    if loss == "soft_l1":
        prob.f_scale = robust_scale(raw.ravel())
    else:
        prob.loss = loss
        prob.f_scale = (HUBER_C if loss == "huber" else TUKEY_C) * norm_scale(raw)
    x, raw = solve(prob, x, max_iter=30, label="calibration update (robust)")
    R, p, t, delta, beta = prob.unpack(x)
    f = replace(fit, R=R, p_mm=p, t_mm=t, delta=delta, beta=beta if not no_b else fit.beta)
    pred = (f.base_points(q) + (np.zeros((len(q), 3)) if no_b else B @ f.beta)) @ R.T + p
    s = split.score_index
    return Registered(f, pred, xyz[s] - pred[s], posterior_covariance(prob, x, prior.noise_mm), prior)


def posterior_covariance(prob: Problem, x: np.ndarray, noise_mm: float) -> np.ndarray:
    """Covariance of the update's parameters at its solution ``x``: ``noise^2 H^-1`` with ``H`` the Gauss-Newton
    matrix of the registration rows (robust weights at ``x``) plus the prior, shape (9 + k + m, 9 + k + m).

    The rotation is re-based at ``x`` so that its three columns are local rotations about the updated frame,
    as in :func:`tolalloc.diagnose.uncertainty.point_jacobian`.
    """
    _, H, _, _ = prob.normal(prob.rebase(x))
    H = 0.5 * (H + H.T)
    try:
        cov = np.linalg.inv(H)
    except np.linalg.LinAlgError:
        cov = np.linalg.pinv(H, hermitian=True)
    return noise_mm ** 2 * 0.5 * (cov + cov.T)


def reregister(fit: Fit, q: np.ndarray, xyz: np.ndarray, B: np.ndarray | None, split: RegistrationSplit, *,
               update: str = "frame", q_train: np.ndarray | None = None, B_train: np.ndarray | None = None,
               oof_mm: np.ndarray | None = None, t_prior=None, loss: str | None = None) -> Registered:
    """The test file re-registered for scoring: frame-only, or with the calibration update (``update``).

    ``q_train``, ``B_train`` (training poses and the effect columns of ``fit.beta`` on them) and ``oof_mm`` (the
    model's out-of-fold training residuals: :func:`~tolalloc.diagnose.power_prior.inflation_factor`, the floor of
    ``k``) are needed for ``"calibration"``; its ``k`` is chosen by the registration poses (:func:`registration_prior`).
    """
    if update not in REGISTER_UPDATES:
        raise TolallocError(f"update: expected one of {', '.join(REGISTER_UPDATES)}, got {update!r}.")
    no_b = B is None or not B.shape[-1]
    if update == "calibration" and (q_train is None or (not no_b and B_train is None)):
        raise TolallocError("update='calibration' needs the training poses `q_train` (and `B_train`, the effect "
                            "columns on them, when `B` is given): the prior is the training fit's posterior; pass "
                            "them, or use update='frame'.")
    if update == "frame" or (not len(fit.geo_index) and no_b):
        extra = np.zeros((len(q), 3)) if no_b else B @ fit.beta
        return register_and_score(fit, q, xyz, extra, split, t_prior=t_prior, loss=loss)
    k_min = 1.0 if oof_mm is None else inflation_factor(oof_mm, fit.residual_mm)
    prior = calibration_prior(fit, q_train, None if no_b else B_train)
    return register_update(fit, q, xyz, None if no_b else B, split, prior, t_prior=t_prior, loss=loss, k_min=k_min)
