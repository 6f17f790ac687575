"""Post-calibration covariance: Bayesian posterior of the systematic errors given a calibration plan.

Model of the calibration (first order, stacked over the plan's M poses, rows per pose 3 or 6)::

    d = J_E s_E + J_N n + (J_X s_X + J_R r + eps)

* ``s_E`` (Ke): the estimated systematic parts, prior ``N(0, diag(sigma_E^2))`` (manufacturing tolerances);
* ``n`` (9): tracker registration (rotation phi, translation delta: ``dp = delta + phi x p``) and the tool
  target offset in the flange frame (``dp = R(q) dt``); flat prior -- they are marginalised (projected out);
* ``s_X``: systematic parts the plan does not estimate (prior kept; they act as correlated noise);
  ``r``: random parts (new at every measurement, block-diagonal noise); ``eps``: tracker noise ``sigma_m``.

With ``W`` the whitening of the noise covariance ``R``, ``P`` the projector off ``range(W J_N)`` and
``A = P W J_E``, the posterior covariance is ``S_E = (Lambda_0 + A^T A)^-1``, evaluated in square-root form
``L (I + B^T B)^-1 L`` with ``B = A L``, ``L = diag(sigma_E)`` (stable for ``sigma_m -> 0``). Directions
with ``A v = 0`` keep their prior. After compensation with the posterior mean the remaining systematic error
has covariance ``S_E`` on E, the prior on X and cross terms ``-S_E A^T W J_X S_X``. At a pose ``q`` the
tool-position error covariance is ``J(q) (S_sys + V_random) J(q)^T``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.calibration.plan import CalibrationPlan
from tolalloc.calibration.split import ErrorSplit
from tolalloc.linear.covariance import VARIANCE_FACTOR
from tolalloc.robot.kinematics import fk_poe

__all__ = ["Posterior", "posterior", "identification_matrix", "nuisance_columns", "estimated_index", "ID_TOL"]

#: Relative singular-value threshold below which a direction counts as unidentifiable.
ID_TOL = 1e-8


@dataclass(frozen=True, eq=False)
class Posterior:
    """Post-calibration error statistics of the parameters.

    Attributes
    ----------
    split : ErrorSplit
    plan : CalibrationPlan
    cov_sys : array, shape (K, K) [mm^2, rad^2]
        Covariance of the systematic error remaining after compensation (zero rows for random-only parameters).
    prior_var : array, shape (K,)
        Prior variance of the systematic parts.
    random_var : array, shape (K,)
        Variance of the random parts.
    estimated : array of int
        Indices of the estimated parameters.
    unidentifiable : tuple of str
        Estimated parameters involved in a direction the plan cannot see: not identifiable individually (only in
        combinations, or not at all); each keeps its prior along that direction, so its post-calibration sigma lies
        between a fraction of its prior and all of it (:attr:`sigma_fraction`).
    """

    split: ErrorSplit
    plan: CalibrationPlan
    cov_sys: np.ndarray
    prior_var: np.ndarray
    random_var: np.ndarray
    estimated: np.ndarray
    unidentifiable: tuple

    @property
    def cov_total(self) -> np.ndarray:
        """Remaining parameter covariance ``S_sys + diag(V_random)``, shape (K, K)."""
        return self.cov_sys + np.diag(self.random_var)

    @property
    def sigma_post(self) -> np.ndarray:
        """Post-calibration sigma of the systematic part per parameter, shape (K,) [mm or rad]."""
        return np.sqrt(np.maximum(np.diag(self.cov_sys), 0.0))

    @property
    def sigma_fraction(self) -> np.ndarray:
        """Per parameter: post-calibration sigma of the systematic part over its prior (manufactured) sigma, shape
        (K,); 1 where the calibration leaves it as manufactured, nan without a systematic part."""
        prior = np.sqrt(self.prior_var)
        return np.divide(self.sigma_post, prior, out=np.full(len(prior), np.nan), where=prior > 0)

    def tool_covariance(self, q, rows=slice(0, 3)) -> np.ndarray:
        """Linear post-calibration covariance of the tool error at poses ``q`` (P, n) -> (P, 3, 3)."""
        J = self.split.model.jacobian(np.atleast_2d(q))[:, rows, :]
        return J @ self.cov_total @ np.swapaxes(J, -1, -2)

    def to_frame(self) -> pd.DataFrame:
        """One row per parameter: prior and posterior sigma of the systematic part, random sigma, each as a
        ``<name>_mm`` / ``<name>_deg`` pair in the row's interface unit (:func:`tolalloc.units.unit_columns`)."""
        m = self.split.model
        units = [p.interface_unit for p in m.params]
        est = np.zeros(len(units), bool)
        est[self.estimated] = True
        return pd.DataFrame({"parameter": m.names, "unit": units, "systematic": self.split.systematic,
                             "estimated": est, **m.interface_columns("sigma_prior", np.sqrt(self.prior_var)),
                             **m.interface_columns("sigma_post", self.sigma_post),
                             **m.interface_columns("sigma_random", np.sqrt(self.random_var)),
                             "identifiable": [est[k] and nm not in self.unidentifiable for k, nm in enumerate(m.names)]})


def estimated_index(split: ErrorSplit, plan: CalibrationPlan) -> np.ndarray:
    """Indices of the parameters a plan estimates (checked: known names with a systematic part)."""
    m = split.model
    if plan.estimate is None:
        return split.sys_index
    idx = []
    for nm in plan.estimate:
        if nm not in m.names:
            raise TolallocError(f"calibration plan: unknown parameter {nm!r} in estimate; known: {', '.join(m.names)}.")
        k = m.names.index(nm)
        if not split.systematic[k]:
            raise TolallocError(f"calibration plan: {nm} has no systematic part (random only), so a calibration "
                                "cannot estimate it; drop it from estimate or mark it systematic.")
        idx.append(k)
    return np.array(sorted(set(idx)), dtype=int)


def nuisance_columns(model, q: np.ndarray, rows: int) -> np.ndarray:
    """Registration (6: phi, delta) and tool-offset (3) columns at poses ``q`` (M, n), shape (M, rows, 9)."""
    T = fk_poe(model.robot.screws, model.robot.home, q)  # (M, 4, 4)
    p = T[:, :3, 3]
    M = len(q)
    out = np.zeros((M, rows, 9))
    px = np.zeros((M, 3, 3))
    px[:, 0, 1], px[:, 0, 2], px[:, 1, 2] = -p[:, 2], p[:, 1], -p[:, 0]
    px = px - np.swapaxes(px, 1, 2)  # [p]x
    out[:, :3, 0:3] = -px  # phi x p = -[p]x phi
    out[:, :3, 3:6] = np.eye(3)
    out[:, :3, 6:9] = T[:, :3, :3]
    if rows == 6:
        out[:, 3:, 0:3] = np.eye(3)
    return out


def _noise_blocks(plan: CalibrationPlan, J: np.ndarray, rand_var: np.ndarray, random_noise: bool) -> np.ndarray:
    """Per-pose measurement-noise covariance blocks (M, rows, rows): tracker noise plus the random parts."""
    M, rows, _ = J.shape
    sig = np.r_[np.full(3, plan.noise_mm), np.full(3, plan.noise_rad)][:rows]
    blk = np.broadcast_to(np.diag(sig**2), (M, rows, rows)).copy()
    if random_noise and np.any(rand_var > 0):
        blk += J @ (rand_var[:, None] * np.swapaxes(J, 1, 2))
    return blk


def _whitener(plan: CalibrationPlan, J: np.ndarray, rand_var: np.ndarray, X: np.ndarray, prior_var: np.ndarray,
              random_noise: bool):
    """Function ``Y (M*rows, c) -> L^-1 Y`` with ``L L^T`` the stacked measurement-noise covariance.

    The covariance is block-diagonal per pose unless systematic parts the plan does not estimate (``X``, non-zero
    prior) correlate the poses; the block-diagonal case is whitened pose by pose (batched ``rows x rows``
    factors: no dense ``M*rows`` factorisation, which multithreaded LAPACK runs slowly on a loaded machine).
    """
    M, rows, _ = J.shape
    blk = _noise_blocks(plan, J, rand_var, random_noise)
    if not len(X) or not np.any(prior_var[X] > 0):
        Lb = np.linalg.cholesky(blk)
        return lambda Y: np.linalg.solve(Lb, Y.reshape(M, rows, -1)).reshape(M * rows, -1)
    R = np.zeros((M * rows, M * rows))
    for i in range(M):
        R[i * rows:(i + 1) * rows, i * rows:(i + 1) * rows] = blk[i]
    JX = J[:, :, X].reshape(M * rows, len(X))
    R += JX @ (prior_var[X][:, None] * JX.T)
    Lc = np.linalg.cholesky(R)
    return lambda Y: np.linalg.solve(Lc, Y)


def posterior(split: ErrorSplit, plan: CalibrationPlan, *, random_noise: bool = True) -> Posterior:
    """Post-calibration covariance of the parameters for ``plan``.

    Parameters
    ----------
    split : ErrorSplit
    plan : CalibrationPlan
    random_noise : bool
        Count the random parts at the measurement poses as measurement noise (physical; ``False`` isolates the
        tracker noise, e.g. for the noise -> 0 limit).

    Returns
    -------
    Posterior
    """
    model = split.model
    if (plan.robot is not None and plan.robot != model.robot.name) or plan.q.shape[-1] != model.robot.n_joints:
        raise TolallocError(f"plan: made for the robot {plan.robot!r} ({plan.q.shape[-1]} joints), but the error split "
                            f"is of {model.robot.name!r} ({model.robot.n_joints} joints); make the plan for this robot "
                            "(make_plan(robot, q) or plan_calibration).")
    fac = np.array([VARIANCE_FACTOR[p.distribution] for p in model.params])
    prior_var = np.where(split.systematic, fac * model.sigma**2, 0.0)
    rand_var = split.random_variance()
    E = estimated_index(split, plan)
    X = np.setdiff1d(split.sys_index, E)
    cov = np.diag(prior_var)
    if plan.n_poses == 0 or len(E) == 0:
        return Posterior(split, plan, cov, prior_var, rand_var, E, tuple(model.names[k] for k in E))
    A, JE, white = _reduced(split, plan, E, X, prior_var, rand_var, random_noise)
    L = np.sqrt(prior_var[E])
    sb, Vt = _right_svd(A * L)
    d = np.ones(len(E))
    d[: len(sb)] = 1.0 / (1.0 + sb**2)
    SE = (L[:, None] * (Vt.T * d) @ Vt) * L[None, :]
    cov[np.ix_(E, E)] = 0.5 * (SE + SE.T)
    if len(X):
        WJX = white(X)
        C = -SE @ A.T @ WJX * prior_var[X][None, :]
        cov[np.ix_(E, X)], cov[np.ix_(X, E)] = C, C.T
    return Posterior(split, plan, cov, prior_var, rand_var, E,
                     _unidentifiable(A, np.linalg.norm(JE, axis=0), [model.names[k] for k in E]))


def _reduced(split, plan, E, X, prior_var, rand_var, random_noise):
    """``A = P W J_E`` (m, Ke), ``W J_E`` and a function giving ``W J_cols`` for parameter indices."""
    model = split.model
    rows = plan.rows_per_pose
    J = model.jacobian(plan.q)[:, :rows, :]  # (M, rows, K)
    M = len(plan.q)
    whiten = _whitener(plan, J, rand_var, X, prior_var, random_noise)

    def white(cols):
        return whiten(J[:, :, cols].reshape(M * rows, len(cols)))

    JE = white(E)
    if not plan.registration:
        return JE, JE, white
    JN = whiten(nuisance_columns(model, plan.q, rows).reshape(M * rows, 9))
    U, s, _ = np.linalg.svd(JN, full_matrices=False)
    Q = U[:, s > ID_TOL * max(s.max(), 1e-300)]
    return JE - Q @ (Q.T @ JE), JE, white


def identification_matrix(split: ErrorSplit, plan: CalibrationPlan, E=None, *, random_noise: bool = True):
    """Whitened identification matrix of the estimated parameters, nuisance projected out.

    Returns ``A`` (m, Ke) with posterior precision ``diag(1 / prior_var_E) + A^T A`` (m = 0 for an empty plan).
    """
    E = estimated_index(split, plan) if E is None else np.asarray(E, int)
    if plan.n_poses == 0:
        return np.zeros((0, len(E)))
    fac = np.array([VARIANCE_FACTOR[p.distribution] for p in split.model.params])
    prior_var = np.where(split.systematic, fac * split.model.sigma**2, 0.0)
    X = np.setdiff1d(split.sys_index, E)
    return _reduced(split, plan, E, X, prior_var, split.random_variance(), random_noise)[0]


def _right_svd(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Singular values and the full square ``Vt`` (n, n) of ``A`` (m, n), without the (m, m) left factor."""
    _, s, Vt = np.linalg.svd(A, full_matrices=A.shape[0] < A.shape[1])
    return s, Vt


def _unidentifiable(A: np.ndarray, scale: np.ndarray, names: list) -> tuple:
    """Names of the columns of ``A`` involved in its numerical null space.

    Columns are scaled by ``scale`` (their norm before the nuisance projection), so a parameter whose effect
    the registration absorbs shows up as (numerically) zero.
    """
    seen = scale > ID_TOL * max(scale.max(initial=0.0), 1e-300)  # columns the measurement rows see at all
    An = A / np.where(seen, scale, 1.0) * seen
    s, Vt = _right_svd(An)
    rank = int(np.sum(s > ID_TOL ** 0.5)) if len(s) else 0
    null = Vt[rank:]
    weight = np.sum(null**2, axis=0) if len(null) else np.zeros(len(names))
    return tuple(nm for nm, w, c in zip(names, weight, seen) if w > 1e-6 or not c)
