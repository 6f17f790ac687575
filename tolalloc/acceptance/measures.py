"""The laws of the statistics by their *measure* (:mod:`tolalloc.acceptance.model`): one dispatch for the
prediction, the decision rule and the allocation.

=======  =====================================================  ==========================================
measure  statistic of the vector ``x`` ~ N(0, C) (3 x 3)        law
=======  =====================================================  ==========================================
ball     ``|x|`` (a scalar statistic: ``|x_0|``, C rank one)    :func:`tolalloc.linear.probability.p_within_radius`
rp       ``RP_l`` of ``n`` cycles of per-cycle covariance C     :func:`tolalloc.linear.repeatability.p_rp_within`
sd3      ``3 S`` of ``n`` cycles of variance ``tr C``           :func:`tolalloc.linear.repeatability.p_sd3_within`
=======  =====================================================  ==========================================
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf
from scipy.stats import chi2

from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability import p_within_radius, radius_for_prob
from tolalloc.linear.repeatability import (p_rp_within, p_rp_within_casadi, p_sd3_within, p_sd3_within_casadi,
                                           rp_bounds, rp_quantile, sd3_bound, sd3_quantile)

__all__ = ["measure_cdf", "measure_quantile", "measure_casadi", "measure_bounds", "expanded_uncertainty",
           "coverage_probability"]


def _check(measure: str) -> None:
    if measure not in ("ball", "rp", "sd3"):
        raise TolallocError(f"measure: expected 'ball', 'rp' or 'sd3', got {measure!r}.")


def _psd(C) -> np.ndarray:
    """``C`` with round-off symmetrised and tiny negative eigenvalues clipped (sums of PSD terms)."""
    C = np.asarray(C, float)
    return 0.5 * (C + np.swapaxes(C, -1, -2))


def measure_cdf(measure: str, C, b, n: int, mean=None) -> np.ndarray:
    """``P(statistic <= b)`` for covariances ``C`` (..., 3, 3) [mm^2 or rad^2], shape ``C.shape[:-2]``; ``mean``
    (..., 3): the vector's mean (a *ball* only)."""
    _check(measure)
    C = _psd(C)
    if measure == "ball":
        return p_within_radius(C, np.broadcast_to(np.asarray(b, float), C.shape[:-2]), mean)
    if measure == "rp":
        return p_rp_within(C, b, n)
    return p_sd3_within(np.einsum("...ii->...", C), b, n)


def measure_quantile(measure: str, C, p, n: int, mean=None) -> np.ndarray:
    """The ``p``-quantile of the statistic [mm or rad], shape ``C.shape[:-2]``; ``mean`` (..., 3): the vector's
    mean (a *ball* only; a zero covariance then gives its length)."""
    _check(measure)
    C = _psd(C)
    if measure == "ball":
        tr = np.einsum("...ii->...", C)
        safe = np.where((tr > 0)[..., None, None], C, np.eye(3))
        if mean is None:
            return np.where(tr > 0, radius_for_prob(safe, p), 0.0)
        mean = np.asarray(mean, float)
        return np.where(tr > 0, radius_for_prob(safe, p, mean), np.linalg.norm(mean, axis=-1))
    if measure == "rp":
        return rp_quantile(C, p, n)
    return sd3_quantile(np.einsum("...ii->...", C), p, n)


def measure_casadi(measure: str, V, b, n: int, ball_function=None):
    """``P(statistic <= b)`` as a CasADi expression of one symbolic 3 x 3 covariance ``V``; ``ball_function``: the
    CasADi function of the ball (:func:`tolalloc.linear.probability_casadi.casadi_function`)."""
    _check(measure)
    if measure == "ball":
        return ball_function(V, b)
    if measure == "rp":
        return p_rp_within_casadi(V, b, n)
    import casadi as ca

    return p_sd3_within_casadi(ca.trace(V), b, n)


def measure_bounds(measure: str, b, p, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Certified budgets ``(trace_bound, eig_bound)`` of ``P(statistic <= b) >= p`` (sufficient conditions
    ``tr C <= trace_bound`` and ``C <= eig_bound I``)."""
    _check(measure)
    b2 = np.asarray(b, float) ** 2
    if measure == "ball":
        return b2 / chi2.ppf(p, 1), b2 / chi2.ppf(p, 3)
    if measure == "rp":
        return rp_bounds(b, p, n)
    v = sd3_bound(b, p, n)
    return v, v


def coverage_probability(k: float) -> float:
    """The probability a coverage factor ``k`` stands for (a normal law): ``erf(k / sqrt 2)`` (0.9545 at k = 2)."""
    return float(erf(k / np.sqrt(2.0)))


def expanded_uncertainty(measure: str, C_inst, n: int, k: float) -> np.ndarray:
    """Expanded uncertainty ``U`` of the *measurement* of the statistic, from the instrument's share ``C_inst``
    (..., 3, 3) of the statistic vector's covariance (GUM, ISO/IEC Guide 98-3; coverage factor ``k``).

    * ball: the radius holding the instrument's error of ``x`` with the probability of ``k``
      (:func:`coverage_probability`; ``k`` times the standard uncertainty for a scalar statistic);
    * rp: ``k u`` with the first-order propagation of the tracker's noise through ``RP_l = lb + 3 S_l``:
      ``u^2 = lambda_max (1 - 1/n) (1/n + 9/(n-1))`` (the sum of the squared sensitivities ``1/n +
      3 (l_j - lb) / ((n-1) S_l)`` of the ``l_j``, each moved by the noise along its direction);
    * sd3: ``k u`` with ``u = 3 sqrt(tr C_inst / (n - 1))`` (the same propagation through ``3 S``).
    """
    _check(measure)
    C = _psd(C_inst)
    if measure == "ball":
        return measure_quantile("ball", C, coverage_probability(k), n)
    if measure == "rp":
        lam = np.linalg.eigvalsh(C)[..., -1]
        return k * np.sqrt(np.maximum(lam, 0.0) * (1 - 1 / n) * (1 / n + 9 / (n - 1)))
    return k * 3 * np.sqrt(np.maximum(np.einsum("...ii->...", C), 0.0) / (n - 1))
