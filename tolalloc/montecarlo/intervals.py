"""Confidence intervals of the paired Monte Carlo estimators.

The paired estimator of ``P = P(|dP_nonlinear| < r)`` is ``P_linear + D`` with ``P_linear`` exact and
``D = P(nonlinear inside) - P(linear inside) = p_10 - p_01`` estimated from the *discordant* samples of the
shared draws: ``b`` samples inside by the nonlinear chain only, ``c`` inside by the linear map only, out of
``n``. ``D`` is a difference of paired proportions, and its interval is Tango's asymptotic score interval
(Tango 1998, Stat. Med. 17: 891-908): the values ``D0`` with::

    |b - c - n D0| <= z sqrt(n (2 p01~ + D0 (1 - D0)))

where ``p01~`` is the maximum-likelihood ``p_01`` restricted to ``p_10 - p_01 = D0`` (closed form, the
positive root of ``2n p^2 + B p + C = 0``, ``B = -b - c + (2n - b + c) D0``, ``C = -c D0 (1 - D0)``). With no
discordant sample it is ``+-z^2 / (n + z^2)``, so a run always states how far the nonlinear P may lie from the
linear one. Counts may be non-integer (effective counts of an importance-sampling run).

Intervals judged together -- every pose (and every requirement) of a verification -- are made simultaneous by
Bonferroni's rule (:func:`simultaneous_level`): ``m`` intervals each at level ``1 - (1 - level) / m`` all cover
their true values with probability at least ``level``. A quantity that may be estimated twice (a second look with
more samples, where the first interval could not decide) is judged by either interval, so the family counts both
(:func:`family_size`).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq
from scipy.stats import norm

from tolalloc.exceptions import TolallocError, whole_number

__all__ = ["paired_difference_ci", "z_of_level", "simultaneous_level", "family_size"]


def z_of_level(level: float) -> float:
    """Two-sided standard-normal quantile of a confidence level (1.959964 for 0.95)."""
    return float(norm.ppf(0.5 + level / 2))


def simultaneous_level(level: float, m: int) -> float:
    """Level of each of ``m`` intervals that hold together with probability at least ``level`` (Bonferroni).

    ``1 - (1 - level) / m``: 0.95 over 18 intervals gives 0.997222 each (``z`` 2.99 instead of 1.96).

    Parameters
    ----------
    level : float
        Family (simultaneous) confidence level, in (0, 1).
    m : int
        Intervals judged together (>= 1), e.g. poses x requirements.

    Raises
    ------
    TolallocError
        ``m`` not a whole number >= 1, or ``level`` not in (0, 1).
    """
    whole = whole_number(m)
    if whole is None or whole < 1:
        raise TolallocError(f"simultaneous_level: expected a whole number of intervals m >= 1 (poses x requirements), "
                            f"got m = {m!r}; count the intervals judged together.")
    ok = not isinstance(level, bool) and isinstance(level, (int, float, np.floating)) and 0.0 < float(level) < 1.0
    if not ok:
        raise TolallocError(f"simultaneous_level: expected a family confidence level in (0, 1) (e.g. 0.95), got "
                            f"level = {level!r}.")
    return 1.0 - (1.0 - float(level)) / whole


def family_size(n_intervals: int, second_looks: int = 0) -> int:
    """Intervals in a Bonferroni family: ``n_intervals`` judged once plus ``second_looks`` possible second looks.

    A quantity whose first interval may be followed by a second one (more samples, the same level) is passed by
    either, so by the union bound its chance of a wrong verdict is up to twice the level's ``alpha``: each
    possible second look is one more interval of the family, counted whether or not it runs (which quantities get
    one depends on the data). ``simultaneous_level(level, family_size(m, k))`` is then the level of every interval,
    first and second looks alike: 18 poses with a possible second look at each, 36 intervals at 99.86 %.

    Parameters
    ----------
    n_intervals : int
        Intervals judged at the first look (>= 1), e.g. poses x requirements.
    second_looks : int
        Intervals that may be re-estimated (>= 0), e.g. one per pose for the certified criterion's re-run of a
        straddling position interval; 0 where nothing is re-run.

    Raises
    ------
    TolallocError
        A count that is not a whole number (``n_intervals`` >= 1, ``second_looks`` >= 0).
    """
    m, k = whole_number(n_intervals), whole_number(second_looks)
    if m is None or m < 1:
        raise TolallocError(f"family_size: expected a whole number of intervals n_intervals >= 1 (poses x "
                            f"requirements), got n_intervals = {n_intervals!r}; count the intervals judged together.")
    if k is None or k < 0:
        raise TolallocError(f"family_size: expected a whole number of possible second looks >= 0 (one per interval "
                            f"that may be re-run, 0 for none), got second_looks = {second_looks!r}.")
    return m + k


def _score(d0: float, b: float, c: float, n: float) -> float:
    """Tango's score statistic at ``D = d0``."""
    A = 2.0 * n
    B = -b - c + (2.0 * n - b + c) * d0
    C = -c * d0 * (1.0 - d0)
    p01 = (np.sqrt(max(B * B - 4.0 * A * C, 0.0)) - B) / (2.0 * A)
    var = n * (2.0 * p01 + d0 * (1.0 - d0))
    return (b - c - n * d0) / np.sqrt(max(var, 1e-300))


def _one(b: float, c: float, n: float, z: float) -> tuple[float, float]:
    d = (b - c) / n
    # the score is decreasing in d0 and crosses +-z within a few standard deviations of d; bracket generously
    width = z * np.sqrt(b + c + z * z) / n * 4.0 + 4.0 * z * z / n
    lo_a, hi_b = max(-1.0 + 1e-15, d - width), min(1.0 - 1e-15, d + width)
    while _score(lo_a, b, c, n) < z and lo_a > -1.0 + 1e-15:
        lo_a = max(-1.0 + 1e-15, d - 4 * (d - lo_a))
    while _score(hi_b, b, c, n) > -z and hi_b < 1.0 - 1e-15:
        hi_b = min(1.0 - 1e-15, d + 4 * (hi_b - d))
    tol = 1e-6 / n
    lo = brentq(lambda x: _score(x, b, c, n) - z, lo_a, d, xtol=tol, rtol=1e-12) if d > lo_a else lo_a
    hi = brentq(lambda x: _score(x, b, c, n) + z, d, hi_b, xtol=tol, rtol=1e-12) if hi_b > d else hi_b
    return lo, hi


def paired_difference_ci(b, c, n, level: float = 0.95) -> np.ndarray:
    """Tango's score interval for the difference of paired proportions ``(b - c) / n``.

    Parameters
    ----------
    b : array
        Samples inside by the first indicator only (nonlinear chain inside, linear map outside).
    c : array
        Samples inside by the second indicator only.
    n : array
        Samples (pairs); broadcasts with ``b`` and ``c``.
    level : float
        Two-sided confidence level.

    Returns
    -------
    array, shape (..., 3)
        ``D_hat, low, high`` with ``D_hat = (b - c) / n``.
    """
    b, c, n = np.broadcast_arrays(np.asarray(b, float), np.asarray(c, float), np.asarray(n, float))
    z = z_of_level(level)
    out = np.empty(b.shape + (3,))
    for idx in np.ndindex(b.shape):
        lo, hi = _one(float(b[idx]), float(c[idx]), float(n[idx]), z)
        out[idx] = ((b[idx] - c[idx]) / n[idx], lo, hi)
    return out
