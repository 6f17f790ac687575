"""The result of every probability estimator: :class:`ProbabilityEstimate` (plain, paired, importance sampling)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from tolalloc.montecarlo.intervals import z_of_level

__all__ = ["ProbabilityEstimate", "variance_reduction", "fallback_text"]


@dataclass(frozen=True, eq=False)
class ProbabilityEstimate:
    """Estimate of ``P(|error| < radius)`` at ``P`` poses, by the estimator that ran at each pose.

    Attributes
    ----------
    quantity : {"position", "orientation"}
    radius : float
        [mm] for position, [rad] for orientation.
    requested : str
        The ``estimator`` keyword (``auto``, ``plain``, ``paired``, ``importance``).
    estimator : array of str, shape (P,)
        What ran at each pose.
    fallback : tuple of str, shape (P,)
        Why ``auto`` (or ``paired``) used plain Monte Carlo at a pose ("" otherwise).
    n : array of int, shape (P,)
    p_linear : array, shape (P,)
        Exact linear-Gaussian ``P`` (the control).
    p_hat, ci_low, ci_high : arrays, shape (P,)
        The estimate and its interval (``level``).
    p_plain, plain_low, plain_high : arrays, shape (P,)
        Plain Monte Carlo (Wilson) of the nonlinear indicator on the same draws (NaN for importance sampling).
    n_nonlinear_only, n_linear_only : arrays of float, shape (P,)
        Discordant samples: inside by the nonlinear chain only / by the linear map only (effective counts for
        importance sampling).
    variance_reduction : array, shape (P,)
        Plain-MC variance ``P (1 - P) / n`` over the estimator's variance at the same ``n`` (with no discordant
        sample, the variance of one discordant sample is used: a lower bound).
    level : float
    """

    quantity: str
    radius: float
    requested: str
    estimator: np.ndarray
    fallback: tuple
    n: np.ndarray
    p_linear: np.ndarray
    p_hat: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    p_plain: np.ndarray
    plain_low: np.ndarray
    plain_high: np.ndarray
    n_nonlinear_only: np.ndarray
    n_linear_only: np.ndarray
    variance_reduction: np.ndarray
    level: float = 0.95
    details: dict = field(default_factory=dict, repr=False)

    _ROWS = ("estimator", "n", "p_linear", "p_hat", "ci_low", "ci_high", "p_plain", "plain_low", "plain_high",
             "n_nonlinear_only", "n_linear_only", "variance_reduction")

    def take(self, idx) -> "ProbabilityEstimate":
        """The estimate at poses ``idx`` (in that order)."""
        idx = np.asarray(idx, int)
        return replace(self, fallback=tuple(self.fallback[i] for i in idx),
                       **{f: np.asarray(getattr(self, f))[idx] for f in self._ROWS})

    def with_rows(self, idx, other: "ProbabilityEstimate") -> "ProbabilityEstimate":
        """This estimate with poses ``idx`` replaced by the rows of ``other`` (same order as ``idx``)."""
        idx = np.asarray(idx, int)
        arr = {}
        for f in self._ROWS:
            a = np.asarray(getattr(self, f)).astype(object)
            a[idx] = np.asarray(getattr(other, f))
            arr[f] = a.astype(str if f == "estimator" else int if f == "n" else float)
        fb = list(self.fallback)
        for j, i in enumerate(idx):
            fb[i] = other.fallback[j]
        return replace(self, fallback=tuple(fb), **arr)

    @property
    def n_discordant(self) -> np.ndarray:
        return self.n_nonlinear_only + self.n_linear_only

    @property
    def se(self) -> np.ndarray:
        """Standard error implied by the interval: half its width over the normal quantile."""
        return (self.ci_high - self.ci_low) / (2 * z_of_level(self.level))

    def to_frame(self) -> pd.DataFrame:
        """One row per pose (1-based)."""
        u = "mm" if self.quantity == "position" else "rad"
        return pd.DataFrame({"pose": np.arange(1, len(self.p_hat) + 1), f"radius_{u}": self.radius,
                             "estimator": self.estimator, "n": self.n, "p_linear": self.p_linear,
                             "p_hat": self.p_hat, "ci_low": self.ci_low, "ci_high": self.ci_high,
                             "p_plain": self.p_plain, "plain_ci_low": self.plain_low, "plain_ci_high": self.plain_high,
                             "n_nonlinear_only": self.n_nonlinear_only, "n_linear_only": self.n_linear_only,
                             "variance_reduction": self.variance_reduction, "fallback": list(self.fallback)})

    def summary(self) -> dict:
        """JSON-ready block (poses 1-based in lists)."""
        return {"quantity": self.quantity, "radius": float(self.radius), "estimator_requested": self.requested,
                "estimator": [str(e) for e in self.estimator], "fallback_reason": fallback_text(self.fallback),
                "n": [int(x) for x in self.n], "level": self.level,
                "p_linear": self.p_linear.tolist(), "p_hat": self.p_hat.tolist(),
                "ci": [[float(a), float(b)] for a, b in zip(self.ci_low, self.ci_high)],
                "n_discordant": [float(x) for x in self.n_discordant],
                "n_nonlinear_only": [float(x) for x in self.n_nonlinear_only],
                "n_linear_only": [float(x) for x in self.n_linear_only],
                "variance_reduction": [float(x) for x in self.variance_reduction]}

    def message(self) -> str:
        """One line: estimator(s), discordant samples, variance reduction, fallback reason."""
        kinds = sorted(set(self.estimator.tolist()))
        head = f"estimator: {'/'.join(kinds)} (requested {self.requested})"
        sel = self.estimator != "plain"
        if np.any(sel):
            vr = self.variance_reduction[sel]
            head += (f"; discordant samples {int(np.rint(self.n_discordant[sel].sum()))} of "
                     f"{int(self.n[sel].sum())}; variance reduction vs plain MC x{np.min(vr):.3g} - x{np.max(vr):.3g}")
        fb = fallback_text(self.fallback)
        return head + (f"; fallback to plain: {fb}" if fb else "")


def fallback_text(fallback) -> str:
    """The reasons of a per-pose ``fallback`` tuple, each once, with the poses (from 1) it holds at when not at all
    of them: ``"poor control: variance reduction x0.48 < 1, so plain Monte Carlo (pose 10)"``; "" when none."""
    poses: dict = {}
    for i, reason in enumerate(fallback):
        if reason:
            poses.setdefault(reason, []).append(i + 1)
    every = len(fallback)
    return "; ".join(reason if len(at) == every else f"{reason} (pose{'s' if len(at) > 1 else ''} "
                     f"{', '.join(map(str, at))})" for reason, at in poses.items())


def variance_reduction(p, n, var_est):
    """Variance reduction ``P (1 - P) / n / var_est`` (inf where both vanish)."""
    plain = np.clip(p, 0, 1) * (1 - np.clip(p, 0, 1)) / n
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(var_est > 0, plain / np.maximum(var_est, 1e-300), np.inf)
