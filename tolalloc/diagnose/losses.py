"""M-estimator losses of the calibration fits on the 3-D residual norm of each pose (:mod:`.scale` uses them)."""

from __future__ import annotations

import numpy as np

__all__ = ["LOSSES", "m_rho", "m_weight", "norm_scale"]


#: Robust losses of the measurement rows (``none``: plain least squares).
LOSSES = ("none", "soft_l1", "huber", "tukey")


def norm_scale(res: np.ndarray) -> float:
    """Median 3-D residual norm [mm] of residuals (P, 3), >= 1e-4 mm (Gaussian noise of sd ``s`` per coordinate:
    1.538 ``s``); the M-estimators' thresholds are multiples of it."""
    return float(max(np.median(np.linalg.norm(res, axis=1)), 1e-4)) if len(res) else 1e-4


def m_rho(s: np.ndarray, loss: str, c: float) -> np.ndarray:
    """Loss of 3-D residual norms ``s`` (>= 0), scaled so that ``rho(s) ~ s^2`` for small ``s``.

    ``huber``: ``s^2`` up to ``c``, then ``2 c s - c^2``; ``tukey``: ``c^2 / 3 (1 - (1 - (s/c)^2)^3)`` up to ``c``,
    then ``c^2 / 3`` (bounded: a gross outlier adds a constant).
    """
    if loss == "huber":
        return np.where(s <= c, s * s, 2.0 * c * s - c * c)
    if loss == "tukey":
        u = np.minimum(s / c, 1.0) ** 2
        return c * c / 3.0 * (1.0 - (1.0 - u) ** 3)
    return s * s


def m_weight(s: np.ndarray, loss: str, c: float) -> np.ndarray:
    """IRLS weight ``rho'(s) / (2 s)`` of 3-D residual norms ``s`` (1 for plain least squares)."""
    if loss == "huber":
        return np.where(s <= c, 1.0, c / np.maximum(s, 1e-300))
    if loss == "tukey":
        return np.where(s < c, (1.0 - (s / c) ** 2) ** 2, 0.0)
    return np.ones_like(s)
