"""Gaussian-process regression with per-feature (ARD) length scales, fitted by maximum marginal likelihood.

Model, for each output column ``k`` (the columns share the hyper-parameters, their values are independent)::

    y_k(x) = m_k + f_k(x) + eps,   f_k ~ GP(0, s_f^2 exp(-1/2 sum_d (x_d - x'_d)^2 / ell_d^2)),   eps ~ N(0, s_n^2)

Inputs are standardised (zero mean, unit sd per feature) and the targets centred and divided by one common
scale before fitting; the returned length scales, signal and noise sd are in the original units. The
hyper-parameters ``log(ell_1..ell_F, s_f, s_n)`` maximise the log marginal likelihood summed over the
outputs (Rasmussen & Williams 2006, eq. 2.30 and 5.9: analytic gradients, L-BFGS-B with bounds, a few
seeded multi-starts). An optimum whose signal the rows do not resolve (length scales so short that no
row correlates with another: white, the same likelihood as noise) is rejected; when every start ends
there, all the variance is noise (see :data:`RESOLVED_CORR`). Leave-one-out residuals come in closed
form (R&W eq. 5.12). numpy/scipy only (Cholesky).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.linalg.lapack import dpotri
from scipy.optimize import minimize

__all__ = ["GPFit", "fit_gp"]

#: Bounds of the standardised log hyper-parameters: length scales, signal sd, noise sd.
LOG_ELL = (np.log(0.03), np.log(100.0))
LOG_SF = (np.log(1e-3), np.log(30.0))
LOG_SN = (np.log(1e-4), np.log(10.0))
JITTER = 1e-8
#: A fitted signal counts only when the rows resolve it: the median over the rows of the largest kernel
#: correlation with another row must reach this. Below it the "signal" is white -- its variance trades
#: one-to-one against the noise variance at the same likelihood -- so it is counted as noise.
RESOLVED_CORR = 0.5


def _kernel(A, B, ell, sf):
    """Squared-exponential ARD kernel between rows of ``A`` (P, F) and ``B`` (Q, F); shape (P, Q)."""
    a, b = A / ell, B / ell
    d2 = np.sum(a ** 2, 1)[:, None] + np.sum(b ** 2, 1)[None, :] - 2 * a @ b.T
    return sf ** 2 * np.exp(-0.5 * np.maximum(d2, 0.0))


def _cho_inverse(L):
    """Inverse of ``L L^T`` from its lower Cholesky factor ``L`` (LAPACK potri)."""
    inv, info = dpotri(L, lower=1)
    if info:
        raise np.linalg.LinAlgError(f"potri failed (info {info})")
    return np.tril(inv) + np.tril(inv, -1).T


def _nlml(theta, X, Y):
    """Negative log marginal likelihood (summed over the columns of ``Y``) and its gradient in ``theta``."""
    P, m = Y.shape
    ell, sf, sn = np.exp(theta[:-2]), np.exp(theta[-2]), np.exp(theta[-1])
    Kf = _kernel(X, X, ell, sf)
    try:
        c = cho_factor(Kf + (sn ** 2 + JITTER) * np.eye(P), lower=True)
    except np.linalg.LinAlgError:
        return 1e25, np.zeros_like(theta)
    alpha = cho_solve(c, Y)
    nll = 0.5 * np.sum(Y * alpha) + m * np.sum(np.log(np.diag(c[0]))) + 0.5 * m * P * np.log(2 * np.pi)
    W = alpha @ alpha.T - m * _cho_inverse(c[0])  # dLML/dK = W / 2
    WK = W * Kf
    r = WK.sum(1)
    grad_ell = np.array([2 * (X[:, d] ** 2 @ r) - 2 * X[:, d] @ WK @ X[:, d] for d in range(X.shape[1])]) / ell ** 2
    grad = 0.5 * np.concatenate([grad_ell, [2 * np.sum(WK), 2 * sn ** 2 * np.trace(W)]])
    return float(nll), -grad


@dataclass(frozen=True, eq=False)
class GPFit:
    """A fitted GP (see the module docstring).

    Attributes
    ----------
    length_scales : array, shape (F,)   ARD length scales, in the units of the input features
    signal_sd, noise_sd : float         ``s_f`` and ``s_n`` in the units of the targets (per output column)
    log_ml : float                      log marginal likelihood at the optimum (standardised data)
    n_fit : int                         number of rows the hyper-parameters were fitted on
    neighbour_corr : float              median over those rows of the largest signal correlation with another
        row at the chosen optimum (below :data:`RESOLVED_CORR`: the fit fell back to pure noise)
    X_mean, X_sd : array, shape (F,)    input standardisation
    y_mean : array, shape (m,)          target means (the constant prior mean)
    y_scale : float                     common target scale
    X : array, shape (P, F)             standardised training inputs the posterior is conditioned on
    alpha : array, shape (P, m)         ``(K + s_n^2 I)^-1 (Y - y_mean) / y_scale``
    loo_residual : array, shape (P, m)  leave-one-out residuals of the training targets, target units
    """

    length_scales: np.ndarray
    signal_sd: float
    noise_sd: float
    log_ml: float
    n_fit: int
    neighbour_corr: float
    X_mean: np.ndarray
    X_sd: np.ndarray
    y_mean: np.ndarray
    y_scale: float
    X: np.ndarray
    alpha: np.ndarray
    loo_residual: np.ndarray

    def predict(self, Xn: np.ndarray) -> np.ndarray:
        """Posterior mean at new inputs ``Xn`` (Q, F); shape (Q, m), target units."""
        Ks = _kernel((np.asarray(Xn, float) - self.X_mean) / self.X_sd, self.X, self.length_scales / self.X_sd,
                     self.signal_sd / self.y_scale)
        return Ks @ self.alpha * self.y_scale + self.y_mean


def _starts(F, restarts, rng):
    """Initial standardised log hyper-parameters: long and short length scales, then seeded random ones."""
    out = [np.r_[np.full(F, ell), np.log(0.8), np.log(0.5)] for ell in (0.0, np.log(0.2))][:restarts]
    for _ in range(restarts - 2):
        out.append(np.r_[rng.uniform(np.log(0.3), np.log(3.0), F), rng.uniform(np.log(0.3), 0.0),
                         rng.uniform(np.log(0.1), np.log(0.9))])
    return out


def fit_gp(X: np.ndarray, Y: np.ndarray, *, restarts: int = 3, max_iter: int = 100, max_fit: int = 1000,
           seed: int = 0) -> GPFit:
    """Fit the GP's hyper-parameters by maximum marginal likelihood; condition on all rows.

    Parameters
    ----------
    X : array, shape (P, F)   inputs (features)
    Y : array, shape (P, m)   targets; the columns share the hyper-parameters
    restarts : int            L-BFGS-B starts (unit and short length scales, then seeded random ones)
    max_iter : int            L-BFGS-B iteration cap per start
    max_fit : int             the hyper-parameters are fitted on at most this many rows (a seeded random
        subset); the posterior is conditioned on all ``P`` rows
    seed : int

    Returns
    -------
    GPFit
    """
    X, Y = np.asarray(X, float), np.asarray(Y, float)
    if Y.ndim == 1:
        Y = Y[:, None]
    if X.ndim != 2 or len(X) != len(Y) or len(X) < 3:
        raise ValueError(f"fit_gp: X must be (P, F) and Y (P, m) with P >= 3; got {X.shape} and {Y.shape}")
    rng = np.random.default_rng(seed)
    x_mean, x_sd = X.mean(0), X.std(0)
    x_sd = np.where(x_sd > 0, x_sd, 1.0)
    y_mean = Y.mean(0)
    y_scale = float(np.sqrt(np.mean((Y - y_mean) ** 2))) or 1.0
    Xs, Ys = (X - x_mean) / x_sd, (Y - y_mean) / y_scale
    sub = np.sort(rng.choice(len(X), max_fit, replace=False)) if len(X) > max_fit else np.arange(len(X))
    theta, corr = _fit_hyper(Xs[sub], Ys[sub], restarts, max_iter, rng)
    ell, sf, sn = np.exp(theta[:-2]), float(np.exp(theta[-2])), float(np.exp(theta[-1]))
    c = cho_factor(_kernel(Xs, Xs, ell, sf) + (sn ** 2 + JITTER) * np.eye(len(Xs)), lower=True)
    alpha = cho_solve(c, Ys)
    loo = alpha / np.diag(_cho_inverse(c[0]))[:, None] * y_scale  # R&W eq. 5.12: y_i - mu_-i
    return GPFit(ell * x_sd, sf * y_scale, sn * y_scale, -_nlml(theta, Xs[sub], Ys[sub])[0], len(sub), corr,
                 x_mean, x_sd, y_mean, y_scale, Xs, alpha, loo)


def _neighbour_corr(Xs, ell):
    """Median over the rows of ``Xs`` of the largest signal correlation with another row."""
    K = _kernel(Xs, Xs, ell, 1.0)
    np.fill_diagonal(K, 0.0)
    return float(np.median(K.max(1)))


def _fit_hyper(Xs, Ys, restarts, max_iter, rng):
    """Standardised log hyper-parameters: the best resolved L-BFGS-B optimum over the starts, else pure noise."""
    F = Xs.shape[1]
    bounds = [LOG_ELL] * F + [LOG_SF, LOG_SN]
    best = None
    for t0 in _starts(F, restarts, rng):
        res = minimize(_nlml, t0, args=(Xs, Ys), jac=True, method="L-BFGS-B", bounds=bounds,
                       options={"maxiter": max_iter})
        corr = _neighbour_corr(Xs, np.exp(res.x[:-2]))
        key = (corr < RESOLVED_CORR, res.fun)
        if best is None or key < best[0]:
            best = (key, res.x, corr)
    theta, corr = best[1], best[2]
    if corr < RESOLVED_CORR:  # a signal uncorrelated between the rows is noise: move its variance there
        theta = np.r_[np.zeros(F), LOG_SF[0], 0.5 * np.log(np.exp(2 * theta[-2]) + np.exp(2 * theta[-1]))]
    return theta, corr
