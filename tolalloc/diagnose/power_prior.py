"""The prior of a calibration update (:mod:`tolalloc.diagnose.recalibrate`): a power prior of the trained parameters.

The prior of ``theta = [delta[geo_index], beta]`` is a **power prior** -- the training data's likelihood raised to
``1/k`` times the training fit's own prior (the MAP prior of the geometric parameters, the ridge weights of the
effect columns), ``k >= 1``. With the training data's information marginalised over the training registration and
probe offset (Schur complement: that frame is not the test file's),

    S = (J_tt - J_tf J_ff^-1 J_ft) / noise^2,    Lambda = diag(prior precisions of the training fit),

(``J`` the training Jacobian, :func:`tolalloc.diagnose.uncertainty.point_jacobian`; ``noise^2`` the training
residual variance per coordinate; :func:`tolalloc.diagnose.uncertainty.information_parts`) the prior is Gaussian
with precision ``P_k = S / k + Lambda`` and mean ``m_k = P_k^-1 (S + Lambda) theta_trained / k``: at ``k = 1`` the
training posterior; as ``k`` grows the training data count less and the prior tends to the fit's own prior -- never
wider than it, so parameters the training poses never pinned (harmonics of a joint at angles the training session
did not visit) stay where the physical prior keeps them while the pinned ones are free to move. How far the
parameters may have moved since the training session is not known from the training file: ``k`` is chosen by the
**registration poses' marginal likelihood** (type-II maximum likelihood, :func:`evidence_discount`): the linearised
model ``r = J_f d_f + J_t d_t + e`` at the frame-only re-registration, the frame and probe offset ``d_f``
marginalised (a flat prior, restricted likelihood), ``theta ~ N(m_k, P_k^-1)`` and ``e ~ N(0, noise^2 I)``, the
noise at the training residual level. ``k`` is at least the training file's own factor (:func:`inflation_factor`:
the ratio of the model's out-of-fold, time blocks, to its in-sample mean square residual, at least 1), so the
training data never count more than their error on poses they did not see allows.

An earlier form widened the whole training posterior by ``k`` (``P_1 / k``, mean the trained values): it lets
parameters the training poses never pinned grow ``sqrt(k)`` times beyond their physical prior; on the real UR10 its
scored final RMS was higher in all 12 calibration-update rows of the study's registration table (its report at
commit ``bde2bd7``: 0.409 and 0.501 mm where the power prior gives 0.266 and 0.460 mm).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from tolalloc.diagnose.calibrate import Fit
from tolalloc.diagnose.uncertainty import _diag_scale, information_parts

__all__ = ["INFLATION_MAX", "CalibrationPrior", "calibration_prior", "evidence_discount", "inflation_factor",
           "project_out"]

#: Largest ``k`` the registration poses may choose.
INFLATION_MAX = 1e4


@dataclass(frozen=True, eq=False)
class CalibrationPrior:
    """Power prior of the trained parameters ``theta = [delta[geo_index], beta]`` for the update (module docstring).

    Attributes
    ----------
    trained : array, shape (m,)       trained values [mm, rad; effect units]
    information : array, shape (m, m) training data's information ``S``, marginal over the training registration
                                      [1 / units squared]
    prior_precision : array, shape (m,)  the training fit's own prior precisions ``Lambda`` (0: none)
    noise_mm : float                  training residual sd per coordinate [mm]
    inflation : float                 ``k`` (>= 1): the training data count ``1/k``
    inflation_floor : float or None   the smallest ``k`` allowed when ``k`` was chosen by the registration poses
                                      (:func:`inflation_factor`); None when ``k`` was given
    set_aside : tuple of int          test poses (0-based) among the registration poses left out of that choice and
                                      of the update as gross errors
                                      (:func:`tolalloc.diagnose.recalibrate.gross_errors`)
    gross_kept : tuple of int         gross errors kept because setting them aside would leave fewer than
                                      ``MIN_REGISTER`` registration poses
    """

    trained: np.ndarray
    information: np.ndarray
    prior_precision: np.ndarray
    noise_mm: float
    inflation: float = 1.0
    inflation_floor: float | None = None
    set_aside: tuple = ()
    gross_kept: tuple = ()

    def precision_at(self, k: float) -> np.ndarray:
        """``P_k = S / k + Lambda`` (symmetric), shape (m, m) [1 / units squared]."""
        P = self.information / k + np.diag(self.prior_precision)
        return 0.5 * (P + P.T)

    def factor(self, k: float) -> tuple:
        """Mean, shape (m,), and a factor ``L``, shape (m, r), of the covariance ``C = L L^T`` of the prior at ``k``.

        ``C`` is the pseudo-inverse of ``P_k`` scaled to unit diagonal (the parameters mix mm, rad and effect units),
        as :func:`tolalloc.diagnose.uncertainty.scaled_pinv`: a direction with no precision gets no variance.
        """
        P = self.precision_at(k)
        d = _diag_scale(P)
        w, V = np.linalg.eigh(P / np.outer(d, d))
        keep = w > len(w) * np.finfo(float).eps * max(float(w.max(initial=0.0)), 0.0)
        L = V[:, keep] / np.sqrt(w[keep]) / d[:, None]
        return self.trained - (1.0 - 1.0 / k) * L @ (L.T @ (self.prior_precision * self.trained)), L

    def moments(self, k: float) -> tuple:
        """Mean, shape (m,), and covariance, shape (m, m), of the prior at ``k`` [units, units squared]."""
        mean, L = self.factor(k)
        return mean, L @ L.T

    @cached_property
    def mean(self) -> np.ndarray:
        """Prior mean at :attr:`inflation`, shape (m,)."""
        return self.factor(self.inflation)[0]

    @property
    def precision(self) -> np.ndarray:
        """Prior precision at :attr:`inflation` in data units (``noise^2 P_k``), shape (m, m)."""
        return self.noise_mm ** 2 * self.precision_at(self.inflation)

    def widened(self, k: float, floor: float | None = None) -> "CalibrationPrior":
        """This prior with the training data counting ``1/k`` instead."""
        return CalibrationPrior(self.trained, self.information, self.prior_precision, self.noise_mm, float(k), floor,
                                self.set_aside, self.gross_kept)


def inflation_factor(oof_mm: np.ndarray, residual_mm: np.ndarray) -> float:
    """Out-of-fold over in-sample mean square 3-D residual of a training fit, at least 1."""
    ms = lambda e: float(np.mean(np.sum(np.asarray(e) ** 2, axis=1)))  # noqa: E731
    insample = ms(residual_mm)
    return max(1.0, ms(oof_mm) / insample) if insample > 0 else 1.0


def calibration_prior(fit: Fit, q: np.ndarray, B: np.ndarray | None, inflation: float = 1.0) -> CalibrationPrior:
    """The power prior of ``fit``'s geometric and effect parameters (marginal over its registration) at ``inflation``.

    Parameters
    ----------
    fit : Fit                          the training fit
    q : array, shape (P, n) [rad, mm]  training poses (a subsample of them gives a wider, conservative prior)
    B : array, shape (P, 3, m), optional  the effect columns of ``fit.beta`` on ``q``
    inflation : float                  ``k`` (:func:`inflation_factor`)
    """
    data, prec, noise2 = information_parts(fit, q, B)
    Aff, Aft = data[:9, :9] + np.diag(prec[:9]), data[:9, 9:]
    S = data[9:, 9:] - Aft.T @ np.linalg.lstsq(Aff, Aft, rcond=None)[0]
    trained = np.concatenate([fit.delta[fit.geo_index], fit.beta])
    return CalibrationPrior(trained, 0.5 * (S + S.T), prec[9:], float(np.sqrt(noise2)), max(float(inflation), 1.0))


def evidence_discount(y: np.ndarray, A: np.ndarray, prior: CalibrationPrior, k_min: float = 1.0,
                      n_eff: int | None = None) -> tuple:
    """Type-II maximum likelihood ``(k, log_evidence)`` of ``y ~ N(A (m_k - m_1), noise^2 I + A C_k A^T)``.

    Parameters
    ----------
    y : array, shape (n,)          residuals at the trained values ``m_1``, the nuisance directions projected out
    A : array, shape (n, m)        their Jacobian in the parameters (projected the same way)
    prior : CalibrationPrior       gives ``m_k`` and ``C_k`` (:meth:`CalibrationPrior.moments`) and the noise
    k_min : float                  smallest ``k`` (largest: :data:`INFLATION_MAX`, or ``k_min`` if that is larger)
    n_eff : int, optional          dimension of the space ``y`` and ``A``'s columns lie in (``n`` minus the nuisance
                                   rank when they were projected in the original coordinates); default ``n``

    The log evidence is maximised over ``log k`` (a grid, then a bounded scalar refinement), each value in the
    parameter space (``A^T A`` and ``A^T y`` once; Woodbury and Sylvester's determinant identity), so the cost does
    not grow with the rows. Without information about ``k`` (no noise variance, no rows, non-finite input, a flat
    evidence) ``k = k_min``.
    """
    from scipy.optimize import minimize_scalar

    n_eff = len(y) if n_eff is None else int(n_eff)
    noise2 = prior.noise_mm ** 2
    k_lo = max(float(k_min), 1.0)
    k_hi = max(INFLATION_MAX, k_lo)
    if not (noise2 > 0 and n_eff > 0 and np.all(np.isfinite(y)) and np.all(np.isfinite(A))):
        return k_lo, float("nan")
    G, b, yy = A.T @ A, A.T @ y, float(y @ y)

    def nll(x):
        mean, L = prior.factor(np.exp(x))  # C = L L^T
        s = mean - prior.trained
        h = L.T @ (b - G @ s)
        M = noise2 * np.eye(L.shape[1]) + L.T @ G @ L
        c = np.linalg.cholesky(0.5 * (M + M.T))
        z = np.linalg.solve(c, h)
        r2 = yy - 2.0 * s @ b + s @ G @ s
        logdet = (n_eff - L.shape[1]) * np.log(noise2) + 2.0 * np.sum(np.log(np.diag(c)))
        return 0.5 * (logdet + (r2 - z @ z) / noise2)

    grid = np.linspace(np.log(k_lo), np.log(k_hi), 41)
    i = int(np.argmin([nll(x) for x in grid]))
    a, c = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    x = minimize_scalar(nll, bounds=(a, c), method="bounded").x if c > a else grid[i]
    x = x if nll(x) < nll(grid[i]) else grid[i]  # a tie (flat evidence) keeps the grid point: k_min when flat
    k = k_lo if x == grid[0] else k_hi if x == grid[-1] else float(np.clip(np.exp(x), k_lo, k_hi))
    return k, -nll(x) - 0.5 * n_eff * np.log(2 * np.pi)


def project_out(N: np.ndarray, *arrays: np.ndarray) -> tuple:
    """``arrays`` with the column space of ``N`` (n, p) removed, and the dimension left, ``n - rank(N)``.

    The basis is the thin SVD of ``N`` (rank-revealing also where a column depends on earlier ones); memory is
    ``n p``. Returns ``([array - Q Q^T array, ...], n_eff)``.
    """
    U, sv, _ = np.linalg.svd(N, full_matrices=False)
    Q = U[:, sv > 1e-9 * sv[0]] if len(sv) and sv[0] > 0 else U[:, :0]
    return [a - Q @ (Q.T @ a) for a in arrays], N.shape[0] - Q.shape[1]
