"""How far the held-out error could still shrink: split it into geometry, effect, unnamed-systematic and noise.

On the held-out (test) poses, in mean squares (3-D error, mm^2), so that the parts add up::

    MS(nominal) = removed_by_geometry + removed_by_effect + systematic_unnamed + noise_floor + rest

* ``removed_by_geometry = MS(nominal) - MS(geometric)``, ``removed_by_effect = MS(geometric) - MS(final)``
  (negative when a model made the held-out error worse -- reported as is);
* ``systematic_unnamed``: the part of the final residual a non-parametric regressor on the joint values
  predicts on the held-out poses, ``MS(final) - MS(final - prediction)`` (clipped at 0). The regressor is a
  kernel ridge regression (Gaussian kernel on ``cos q, sin q`` of revolute joints and the scaled stroke of
  prismatic joints; the posterior mean of a Gaussian process with that kernel), trained on the training
  poses' out-of-fold final residuals; its length scale and ridge are chosen by **blocked** cross-validation
  (contiguous blocks of rows, i.e. of time);
* ``noise_floor``: from repeated poses when the data has them (pairs closer than ``repeat_tol`` in the
  features: half the mean squared difference of their residuals), else the regressor's cross-validated
  error on the training poses (its noise term, an upper bound of the noise);
* ``rest``: what is left (``MS(final)`` minus the two above; negative when the noise estimate is too high).

No scikit-learn: a few eigendecompositions of the kernel matrix.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["GapSplit", "gap_split", "joint_features", "KernelRidge"]

LENGTH_FACTORS = (0.25, 0.5, 1.0, 2.0)
RIDGES = (1e-3, 1e-2, 1e-1, 1.0, 10.0)
MAX_TRAIN = 800


def joint_features(q: np.ndarray, revolute: np.ndarray, stroke_mm: np.ndarray | None = None) -> np.ndarray:
    """Features of joint values ``q`` (P, n) [rad, mm]: ``cos, sin`` per revolute joint, ``q / stroke`` per prismatic."""
    cols = []
    for j in range(q.shape[1]):
        if revolute[j]:
            cols += [np.cos(q[:, j]), np.sin(q[:, j])]
        else:
            s = 1.0 if stroke_mm is None else max(float(stroke_mm[j]), 1e-9)
            cols.append(q[:, j] / s)
    return np.column_stack(cols)


class KernelRidge:
    """Gaussian-kernel ridge regression with multi-output targets, hyper-parameters by blocked CV.

    Parameters
    ----------
    X : array, shape (P, F)      features
    Y : array, shape (P, 3) [mm] targets
    folds : int                  contiguous blocks of rows
    """

    def __init__(self, X: np.ndarray, Y: np.ndarray, folds: int = 5):
        self.X, self.Y = X, Y
        d2 = _sqdist(X, X)
        self.med = float(np.sqrt(np.median(d2[d2 > 0]))) if np.any(d2 > 0) else 1.0
        blocks = np.array_split(np.arange(len(X)), min(folds, len(X)))
        best = (np.inf, None, None)
        self.cv_pred = None
        for lf in LENGTH_FACTORS:
            ell = lf * self.med
            preds = {lam: np.zeros_like(Y) for lam in RIDGES}
            for b in blocks:
                tr = np.setdiff1d(np.arange(len(X)), b)
                K = np.exp(-d2[np.ix_(tr, tr)] / (2 * ell ** 2))
                s, U = np.linalg.eigh(K)
                Kb = np.exp(-d2[np.ix_(b, tr)] / (2 * ell ** 2))
                UtY = U.T @ (Y[tr] - Y[tr].mean(0))
                for lam in RIDGES:
                    preds[lam][b] = Kb @ (U @ (UtY / (s + lam)[:, None])) + Y[tr].mean(0)
            for lam in RIDGES:
                mse = float(np.mean(np.sum((Y - preds[lam]) ** 2, axis=1)))
                if mse < best[0]:
                    best = (mse, (ell, lam), preds[lam])
        self.cv_mse, (self.ell, self.lam), self.cv_pred = best
        K = np.exp(-d2 / (2 * self.ell ** 2))
        self.mean = Y.mean(0)
        self.alpha = np.linalg.solve(K + self.lam * np.eye(len(X)), Y - self.mean)

    def predict(self, Xn: np.ndarray) -> np.ndarray:
        """Predicted targets [mm], shape (Q, 3)."""
        return np.exp(-_sqdist(Xn, self.X) / (2 * self.ell ** 2)) @ self.alpha + self.mean


def _sqdist(A, B):
    return np.maximum(np.sum(A ** 2, 1)[:, None] + np.sum(B ** 2, 1)[None, :] - 2 * A @ B.T, 0.0)


def _ms(e):
    return float(np.mean(np.sum(e ** 2, axis=1)))


@dataclass(frozen=True)
class GapSplit:
    """Held-out mean-square error split (see the module docstring); all values [mm^2] unless noted.

    Attributes
    ----------
    ms_nominal, removed_by_geometry, removed_by_effect, systematic_unnamed, noise_floor, rest : float
    noise_source : str           ``repeated poses`` or ``regressor CV error``
    regressor_cv_explained : float  share of the training out-of-fold residual's MS the regressor explains
        by blocked CV (0-1)
    length_scale, ridge : float  the regressor's chosen hyper-parameters (feature units, relative)
    """

    ms_nominal: float
    removed_by_geometry: float
    removed_by_effect: float
    systematic_unnamed: float
    noise_floor: float
    rest: float
    noise_source: str
    regressor_cv_explained: float
    length_scale: float
    ridge: float

    def to_frame(self):
        import pandas as pd

        parts = ["removed_by_geometry", "removed_by_effect", "systematic_unnamed", "noise_floor", "rest"]
        vals = [getattr(self, p) for p in parts]
        return pd.DataFrame({"part": parts, "ms_mm2": vals, "rms_equiv_mm": np.sign(vals) * np.sqrt(np.abs(vals)),
                             "share_of_nominal_pct": [100 * v / self.ms_nominal for v in vals]})

    def to_dict(self) -> dict:
        return {k: (float(v) if not isinstance(v, str) else v) for k, v in self.__dict__.items()}


def gap_split(q_train, e_train_final, q_test, e_test: dict, revolute, *, stroke_mm=None, folds: int = 5,
              repeat_tol: float = 1e-3, seed: int = 0) -> GapSplit:
    """Split the held-out error (see the module docstring).

    Parameters
    ----------
    q_train : array, shape (P, n) [rad, mm], in time order
    e_train_final : array, shape (P, 3) [mm]   out-of-fold residuals of the final model on the training poses
    q_test : array, shape (T, n)
    e_test : dict with ``nominal``, ``geometric``, ``final`` residual arrays, shape (T, 3) [mm], in the same
        frame as ``e_train_final``
    revolute : array of bool, shape (n,)
    stroke_mm : array, shape (n,), optional   range of each prismatic joint (feature scaling)
    """
    Xtr = joint_features(q_train, revolute, stroke_mm)
    Xte = joint_features(q_test, revolute, stroke_mm)
    keep = np.arange(len(Xtr))
    if len(keep) > MAX_TRAIN:  # evenly spaced in time, so the blocks stay contiguous
        keep = np.linspace(0, len(Xtr) - 1, MAX_TRAIN).round().astype(int)
    kr = KernelRidge(Xtr[keep], e_train_final[keep], folds)
    ms_f = _ms(e_test["final"])
    pred = kr.predict(Xte)
    systematic = max(ms_f - _ms(e_test["final"] - pred), 0.0)
    explained = max(1.0 - kr.cv_mse / max(_ms(e_train_final[keep]), 1e-300), 0.0)
    d2 = _sqdist(Xtr, Xtr)
    i, j = np.nonzero(np.triu(d2 < repeat_tol ** 2, k=1))
    if len(i) >= 3:
        noise = 0.5 * _ms(e_train_final[i] - e_train_final[j])
        source = f"repeated poses ({len(i)} pairs)"
    else:
        noise = kr.cv_mse
        source = "regressor CV error (no repeated poses)"
    ms_n, ms_g = _ms(e_test["nominal"]), _ms(e_test["geometric"])
    return GapSplit(ms_n, ms_n - ms_g, ms_g - ms_f, systematic, noise, ms_f - systematic - noise, source, explained,
                    kr.ell, kr.lam)
