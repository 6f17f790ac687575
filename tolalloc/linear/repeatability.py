"""Distributions of the ISO 9283 repeatability statistics of ``n`` Gaussian cycles (numpy, and CasADi for IPOPT).

**Position repeatability** ``RP_l = lb + 3 S_l`` (ISO 9283 7.2.2) of ``n`` attained positions ``y_j ~ N(m, C)``
(independent cycles; ``l_j = |y_j - yb|``, ``lb`` their mean, ``S_l`` their standard deviation with ``n - 1``).
Its law has no closed form; it is approximated from the moments of ``l = |d|``, ``d ~ N(0, (n-1)/n C)`` (the
marginal law of each ``y_j - yb``), by the delta method for ``lb`` and ``S_l`` treated as the mean and standard
deviation of ``n`` independent ``l_j``::

    E RP   = mu + 3 sqrt(sigma^2 - var S)
    var RP = sigma^2 / n + 9 var S + 3 mu_3 / (sigma n),    var S = (mu_4 / n - sigma^4 (n-3)/(n(n-1))) / (4 sigma^2)

(``mu, sigma^2, mu_3, mu_4``: mean, variance, third and fourth central moments of ``l``), and a gamma law of that
mean and variance in the Wilson-Hilferty form (a smooth expression, also in CasADi)::

    P(RP <= b) = Phi(3 sqrt(k) ((b / E RP)^(1/3) - 1) + 1 / (3 sqrt(k))),   k = (E RP)^2 / var RP.

The raw moments of ``l`` are direction integrals: writing ``d = C'^(1/2) rho u`` (``rho ~ chi_3`` independent of
``u`` uniform on the sphere), ``E l^k = E rho^k * mean_u (u^T C' u)^(k/2)`` -- linear in ``C`` inside a smooth
function, exact for rank-deficient ``C`` too; the mean over directions is a Lebedev rule (order
:data:`LEBEDEV_ORDER`; its error in ``E l`` is below 0.12 % for the worst case, rank one). Against 200,000 simulated
tests per covariance (isotropic, anisotropic, rank two, rank one; 30 and 10 cycles; ``reports/iso9283/rp_law.csv``,
``studies/iso9283/run.py``) the 0.5, 0.9 and 0.95 quantiles agree within 0.45 %, the 0.99 quantile within 0.7 %
except rank one at 10 cycles (1.7 %, the law errs high). ``tests/test_repeatability_law.py`` repeats the check with
20,000.

**Angle and distance repeatability** ``3 S`` of a scalar (``RP_a``, ``RD``): ``(n-1) S^2 / var ~ chi2_{n-1}``
exactly, so ``P(3 S <= b) = F_chi2_{n-1}((n-1) b^2 / (9 var))`` (numpy: the exact law; CasADi: its
Wilson-Hilferty form, checked by the numpy law).

**Certified bounds** (sufficient conditions, linear in the covariance, for the certified allocation):

* ``RP_l``: by Cauchy-Schwarz ``lb + 3 S_l <= sqrt(9 + (n-1)/n) sqrt(tr S_y)`` with ``S_y`` the sample
  covariance, and ``(n-1) tr S_y`` is a weighted sum of ``chi2_{n-1}`` variables with weights the eigenvalues
  of ``C``; so ``lambda_max(C) <= (n-1) b^2 / ((9 + (n-1)/n) chi2_{3(n-1)}^-1(p))`` implies ``P(RP_l <= b) >= p``
  (eigenvalue rule), and, by Szekely & Bakirov (2003) for ``p >= 0.785``, ``tr C <= b^2 / ((9 + (n-1)/n)
  chi2_1^-1(p))`` too (trace rule). Both are conservative (the eigenvalue rule by about 1.5x in ``b`` for an
  isotropic ``C`` at ``n = 30``, ``p = 0.95``); the exact allocation starts from them.
* ``3 S``: ``var <= (n-1) b^2 / (9 chi2_{n-1}^-1(p))`` is necessary and sufficient.
"""

from __future__ import annotations

import numpy as np
from scipy.special import gamma as gamma_fn
from scipy.stats import chi2, norm

from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability_casadi import _lebedev_half

__all__ = ["rp_moments", "p_rp_within", "rp_quantile", "p_rp_within_casadi", "p_sd3_within", "sd3_quantile",
           "p_sd3_within_casadi", "rp_bounds", "sd3_bound", "LEBEDEV_ORDER", "RP_LAW_MIN_CYCLES"]

#: Lebedev order of the direction rule of the moments (numpy and CasADi alike, so the allocation's re-check
#: evaluates the same expression IPOPT saw)
LEBEDEV_ORDER = 41
#: E chi_3^k for k = 1, 3
_RHO1 = np.sqrt(2.0) * gamma_fn(2.0) / gamma_fn(1.5)
_RHO3 = 2.0**1.5 * gamma_fn(3.0) / gamma_fn(1.5)
#: Fewest cycles the ``RP_l`` law is used for: against simulated tests its 0.95 quantile errs high by 1.0 % at 5
#: cycles, 1.9 % at 4, 6.4 % at 3 and 117 % at 2 (there ``l_1 = l_2`` and ``S_l = 0``, which the moments treat as
#: independent); the certified bounds hold from 2 cycles.
RP_LAW_MIN_CYCLES = 5
#: floor of the variance of l relative to its mean square (a covariance of zero has no spread at all)
_TINY = 1e-30


def _check_n(n, minimum: int = 2) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or int(n) < minimum:
        why = "" if minimum == 2 else " (the RP_l law's range, RP_LAW_MIN_CYCLES; ISO 9283 uses 30)"
        raise TolallocError(f"n: expected a whole number of cycles of at least {minimum}{why}, got {n!r}.")
    return int(n)


def _central(m1, m2, m3, m4, n, sqrt):
    """Mean and variance of RP from the raw moments of l (numpy or CasADi through ``sqrt``)."""
    var = m2 - m1**2
    mu3 = m3 - 3 * m1 * m2 + 2 * m1**3
    mu4 = m4 - 4 * m1 * m3 + 6 * m1**2 * m2 - 3 * m1**4
    var_s = (mu4 / n - var**2 * (n - 3) / (n * (n - 1))) / (4 * var)
    mean = m1 + 3 * sqrt(var - var_s)
    v = var / n + 9 * var_s + 3 * mu3 / (sqrt(var) * n)
    return mean, v


def rp_moments(cov, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Mean and standard deviation of ``RP_l`` of ``n`` cycles with per-cycle covariance ``cov``.

    Parameters
    ----------
    cov : array, shape (..., 3, 3) [mm^2]
    n : int

    Returns
    -------
    mean, sd : arrays, shape (...) [mm]
    """
    n = _check_n(n, RP_LAW_MIN_CYCLES)
    C = np.asarray(cov, float) * ((n - 1) / n)
    u, w = _lebedev_half(LEBEDEV_ORDER)
    q = np.maximum(np.einsum("mi,...ij,mj->...m", u, C, u), 0.0)
    tr = np.einsum("...ii->...", C)
    m1 = _RHO1 * (np.sqrt(q) @ w)
    m3 = _RHO3 * ((q * np.sqrt(q)) @ w)
    m4 = tr**2 + 2 * np.einsum("...ij,...ji->...", C, C)
    zero = tr <= 0
    with np.errstate(invalid="ignore", divide="ignore"):
        mean, v = _central(m1, tr, m3, m4, n, np.sqrt)
    mean = np.where(zero, 0.0, mean)
    sd = np.where(zero, 0.0, np.sqrt(np.maximum(v, 0.0)))
    return mean, sd


def p_rp_within(cov, b, n: int) -> np.ndarray:
    """``P(RP_l <= b)`` of ``n`` cycles with per-cycle covariance ``cov`` (gamma law, Wilson-Hilferty form).

    Parameters
    ----------
    cov : array, shape (..., 3, 3) [mm^2]
    b : float or array broadcasting with ``cov.shape[:-2]`` [mm]
    n : int

    Returns
    -------
    array, shape (...)
    """
    mean, sd = rp_moments(cov, n)
    b = np.asarray(b, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        rk = np.where(sd > 0, mean / np.where(sd > 0, sd, 1.0), np.inf)  # sqrt(k)
        x = 3 * rk * (np.cbrt(np.maximum(b, 0.0) / np.where(mean > 0, mean, 1.0)) - 1) + 1 / (3 * rk)
        p = norm.cdf(x)
    return np.where(mean > 0, np.where(sd > 0, p, (b >= mean) * 1.0), (b >= 0) * 1.0)


def rp_quantile(cov, p, n: int) -> np.ndarray:
    """The ``p``-quantile of ``RP_l`` [mm] (the inverse of :func:`p_rp_within`), shape ``cov.shape[:-2]``."""
    mean, sd = rp_moments(cov, n)
    z = norm.ppf(np.asarray(p, float))
    with np.errstate(invalid="ignore", divide="ignore"):
        rk = np.where(sd > 0, mean / np.where(sd > 0, sd, 1.0), np.inf)
        return np.where(sd > 0, mean * np.maximum(1 - 1 / (9 * rk**2) + z / (3 * rk), 0.0) ** 3, mean)


def p_rp_within_casadi(V, b, n: int):
    """``P(RP_l <= b)`` as a CasADi expression of one symbolic 3 x 3 covariance ``V`` (as :func:`p_rp_within`)."""
    import casadi as ca

    n = _check_n(n, RP_LAW_MIN_CYCLES)
    u, w = _lebedev_half(LEBEDEV_ORDER)
    C = V * ((n - 1) / n)
    U = ca.DM(u)
    q = ca.sum2(ca.mtimes(U, C) * U)  # (m, 1): u_m^T C u_m
    q = ca.fmax(q, _TINY)
    W = ca.DM(w).T
    m1 = _RHO1 * ca.mtimes(W, ca.sqrt(q))
    m3 = _RHO3 * ca.mtimes(W, q * ca.sqrt(q))
    tr = ca.trace(C)
    m4 = tr**2 + 2 * ca.trace(ca.mtimes(C, C))
    mean, v = _central(m1, tr, m3, m4, n, ca.sqrt)
    rk = mean / ca.sqrt(ca.fmax(v, _TINY))
    x = 3 * rk * ((b / mean) ** (1.0 / 3.0) - 1) + 1 / (3 * rk)
    return 0.5 * (1 + ca.erf(x / np.sqrt(2.0)))


def p_sd3_within(var, b, n: int) -> np.ndarray:
    """``P(3 S <= b)`` of ``n`` Gaussian values of variance ``var`` (exact: ``(n-1) S^2 / var ~ chi2_{n-1}``).

    Parameters
    ----------
    var : array [mm^2 or rad^2]
    b : float or array [mm or rad]
    n : int
    """
    n = _check_n(n)
    var = np.asarray(var, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(var > 0, chi2.cdf((n - 1) * np.asarray(b, float) ** 2 / (9 * np.where(var > 0, var, 1.0)),
                                          n - 1), 1.0)


def sd3_quantile(var, p, n: int) -> np.ndarray:
    """The ``p``-quantile of ``3 S`` of ``n`` Gaussian values of variance ``var``."""
    n = _check_n(n)
    return 3 * np.sqrt(np.maximum(np.asarray(var, float), 0.0) * chi2.ppf(p, n - 1) / (n - 1))


def p_sd3_within_casadi(var, b, n: int):
    """``P(3 S <= b)`` as a CasADi expression of a symbolic variance (Wilson-Hilferty form of the chi-square)."""
    import casadi as ca

    n = _check_n(n)
    nu = n - 1
    x = (nu * b**2 / (9 * ca.fmax(var, _TINY)) / nu) ** (1.0 / 3.0)
    z = (x - (1 - 2 / (9 * nu))) / np.sqrt(2 / (9 * nu))
    return 0.5 * (1 + ca.erf(z / np.sqrt(2.0)))


def rp_bounds(b, p, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Certified budgets of ``RP_l <= b`` at probability ``p``: ``(trace_bound, eig_bound)`` [mm^2] (module
    docstring)."""
    n = _check_n(n)
    c = 9.0 + (n - 1) / n
    b2 = np.asarray(b, float) ** 2
    return b2 / (c * chi2.ppf(p, 1)), (n - 1) * b2 / (c * chi2.ppf(p, 3 * (n - 1)))


def sd3_bound(b, p, n: int) -> np.ndarray:
    """The largest variance with ``P(3 S <= b) >= p`` [mm^2 or rad^2] (necessary and sufficient)."""
    n = _check_n(n)
    return (n - 1) * np.asarray(b, float) ** 2 / (9 * chi2.ppf(p, n - 1))
