"""Prior scales of many-column effects by marginal likelihood (type-II maximum likelihood, ARD).

A linear model ``y = Phi beta + e`` with ``beta_i ~ N(0, s_g(i)^2)`` -- one prior scale per group of columns (a
transmission's harmonics of one joint) -- and ``e ~ N(0, sigma^2 I)``. The scales and the noise maximise the
marginal likelihood ``p(y | s, sigma)`` (MacKay's fixed-point updates, Bishop, *Pattern Recognition and
Machine Learning*, eqs. 3.92 and 3.95, per group): with ``A = diag(1 / s^2) + Phi^T Phi / sigma^2``,
``m = A^-1 Phi^T y / sigma^2`` and ``gamma_i = 1 - (A^-1)_ii / s_i^2``::

    s_g^2 = sum_(i in g) m_i^2 / sum_(i in g) gamma_i,      sigma^2 = |y - Phi m|^2 / (n - sum gamma).

The fitted model is a ridge regression whose penalty ``sigma^2 / s_i^2`` is the data's own: a long harmonic series
on a joint that carries no such error gets a tiny scale (its columns are held near 0) instead of fitting noise.
``log_ml`` compares variants with different columns (each with its own fitted scales); ``dof = sum(gamma)``
counts the parameters the data determine.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

__all__ = ["Evidence", "ard_evidence"]


@dataclass(frozen=True)
class Evidence:
    """Fitted prior scales of one linear model.

    Attributes
    ----------
    sd : array, shape (M,)       prior sd of every column's coefficient [its unit]
    noise_sd : float             noise sd per row [unit of y]
    log_ml : float               log marginal likelihood at the optimum
    dof : float                  effective number of parameters, ``sum gamma``
    mean : array, shape (M,)     posterior mean of the coefficients
    """

    sd: np.ndarray
    noise_sd: float
    log_ml: float
    dof: float
    mean: np.ndarray

    @property
    def prior_w(self) -> np.ndarray:
        """Ridge weights ``noise_sd / sd`` (rows ``w_i beta_i`` beside the data rows)."""
        return self.noise_sd / self.sd


def _posterior(G, h, alpha, beta):
    """Posterior mean, diagonal of the posterior covariance and ``log |A|`` for ``A = beta G + diag(alpha)``.

    LAPACK directly (Cholesky, then the triangular inverse ``L^-1``: ``A^-1 = L^-T L^-1``): the evidence iterates
    this hundreds of times per fit on small matrices, where scipy's wrappers cost as much as the factorisation."""
    M = len(h)
    A = beta * G
    A[np.diag_indices(M)] += alpha
    A[np.diag_indices(M)] += 1e-12 * np.trace(A) / M
    L, info = scipy.linalg.lapack.dpotrf(A, lower=1, clean=1, overwrite_a=1)
    if info == 0:
        Linv, info = scipy.linalg.lapack.dtrtri(L, lower=1)
    if info != 0:
        raise np.linalg.LinAlgError(f"the posterior precision is not positive definite (LAPACK info {info})")
    m = beta * (Linv.T @ (Linv @ h))
    return m, np.einsum("ij,ij->j", Linv, Linv), 2.0 * float(np.sum(np.log(np.diag(L))))


def _log_ml(alpha, beta, E, m, logdet, n) -> float:
    """Log marginal likelihood (Bishop eq. 3.86 with one precision per column)."""
    return 0.5 * float(np.sum(np.log(alpha)) + n * np.log(beta) - beta * E - np.sum(alpha * m * m) - logdet
                       - n * np.log(2 * np.pi))


def ard_evidence(Phi: np.ndarray, y: np.ndarray, groups: np.ndarray, *, n_eff: int | None = None,
                 iters: int = 200, tol: float = 1e-3) -> Evidence:
    """Maximise the marginal likelihood over one prior scale per group and the noise (module docstring).

    Parameters
    ----------
    Phi : array, shape (n, M)   columns (already projected off any always-fitted columns)
    y : array, shape (n,)
    groups : array of int, shape (M,)   group of every column
    n_eff : int, optional   data rows minus the rank of the projected-off columns (default ``n``)
    iters, tol : the fixed-point updates stop after ``iters`` or when the log evidence rises by less than ``tol``
    """
    n = len(y) if n_eff is None else int(n_eff)
    G, h, yy = Phi.T @ Phi, Phi.T @ y, float(y @ y)
    groups = np.asarray(groups, int)
    ug, gi = np.unique(groups, return_inverse=True)
    colsq = np.maximum(np.diag(G), 1e-300)
    beta = max(n, 1) / max(yy, 1e-300)  # noise precision
    alpha = np.full(len(ug), float(np.median(colsq)) * beta)  # prior precision per group: modest start
    cap = 1e12 * alpha[0] + 1e-300
    last = -np.inf
    for _ in range(iters):
        m, Sdiag, logdet = _posterior(G, h, alpha[gi], beta)
        E = max(yy - 2 * m @ h + m @ G @ m, 1e-300)
        ml = _log_ml(alpha[gi], beta, E, m, logdet, n)
        if ml - last < tol:  # the evidence no longer rises (pruned groups creep towards infinite precision)
            break
        last = ml
        gamma = 1.0 - alpha[gi] * Sdiag
        g_sum = np.bincount(gi, gamma, len(ug))
        m2 = np.bincount(gi, m * m, len(ug))
        alpha = np.minimum(np.maximum(g_sum, 1e-12) / np.maximum(m2, 1e-300), cap)
        beta = max(n - gamma.sum(), 1.0) / E
    m, Sdiag, logdet = _posterior(G, h, alpha[gi], beta)
    E = max(yy - 2 * m @ h + m @ G @ m, 0.0)
    log_ml = _log_ml(alpha[gi], beta, E, m, logdet, n)
    dof = float(np.sum(1.0 - alpha[gi] * Sdiag))
    return Evidence(1.0 / np.sqrt(alpha[gi]), float(1.0 / np.sqrt(beta)), float(log_ml), dof, m)
