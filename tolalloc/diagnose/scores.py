"""Scores of the effect selection: error statistics, robust (clipped) RMS, paired tests, and the result records.

Held-out residuals are the out-of-fold residuals of the training file's cross-validation only
(:attr:`Evaluation.selection_mm`); the test file is scored once, after the selection (:mod:`.pipeline`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import norm, wilcoxon

__all__ = ["rms", "error_stats", "robust_rms", "clip_level", "paired_pvalue", "Evaluation", "Candidate", "Stage",
           "scheme_text"]


def scheme_text(cv: str, selection: bool = True) -> str:
    """The cross-validation scheme behind an out-of-fold figure: ``selection`` -- the selection's score
    (:attr:`Evaluation.selection_mm`: with ``blocked``, the time blocks and the joint-space blocks), else the
    first scheme alone (:attr:`Evaluation.oof_mm`)."""
    if cv == "blocked":
        return "time and joint-space blocks" if selection else "time blocks"
    return {"time": "time blocks", "joint": "joint-space blocks", "random": "random folds"}.get(cv, cv)


def rms(res: np.ndarray) -> float:
    """RMS of the 3-D error [mm] of residuals shape (P, 3)."""
    return float(np.sqrt(np.mean(np.sum(res ** 2, axis=1)))) if len(res) else float("nan")


def error_stats(res: np.ndarray) -> dict:
    """RMS, 95th percentile and max of the 3-D error norm [mm]."""
    d = np.linalg.norm(res, axis=1)
    return {"rms_mm": rms(res), "p95_mm": float(np.percentile(d, 95)), "max_mm": float(d.max()),
            "mean_mm": float(d.mean())}


@dataclass(frozen=True, eq=False)
class Evaluation:
    """One model (registration + offset [+ geometry] [+ effects]) fitted and scored on held-out poses.

    Attributes
    ----------
    label : str                  ``nominal``, ``geometric`` or ``geometric+effect+...``
    effects : tuple of str
    fit : Fit                    fitted on all training poses (``Fit`` of :mod:`.calibrate`)
    param_names : tuple of str   fitted (identifiable) effect parameters
    keep : array of int          their columns in the concatenated basis
    oof_mm : array, shape (P, 3)         out-of-fold residuals of the training poses (measured - predicted)
    test_mm : array, shape (T, 3) or None  residuals on the test file (``refit``: scored poses only, (T - r, 3));
                                 set only for the nominal, geometric and final models, after the selection
    test_pred_mm : array, shape (T, 3) or None  predictions on the test file (``refit``: in the re-registered frame)
    oof_joint_mm : array, shape (P, 3) or None  out-of-fold residuals of the joint-space blocks (``cv="blocked"``)
    registered : Registered or None  ``refit``: the test-file registration the model was scored with
                                 (:class:`~tolalloc.diagnose.register.Registered`: the fit in the test file's
                                 frame; with the calibration update also its posterior covariance and prior)
    """

    label: str
    effects: tuple
    fit: object
    param_names: tuple
    keep: np.ndarray
    oof_mm: np.ndarray
    test_mm: np.ndarray | None
    test_pred_mm: np.ndarray | None
    oof_joint_mm: np.ndarray | None = None
    registered: object | None = None

    @property
    def test_fit(self):
        """``refit``: the fit in the test file's frame it was scored with (None otherwise)."""
        return None if self.registered is None else self.registered.fit

    @property
    def test_cov(self) -> np.ndarray | None:
        """The calibration update's posterior covariance of :attr:`test_fit`'s frame and parameters (None without)."""
        return None if self.registered is None else self.registered.posterior_cov

    @property
    def test_prior(self):
        """The calibration update's prior (:class:`~tolalloc.diagnose.power_prior.CalibrationPrior`; None without)."""
        return None if self.registered is None else self.registered.prior

    @property
    def selection_mm(self) -> np.ndarray:
        """Residuals the selection scores: out-of-fold residuals of the training file (time blocks, then
        joint-space blocks). The test file never enters: it is sealed until the model is chosen."""
        parts = [self.oof_mm] + ([self.oof_joint_mm] if self.oof_joint_mm is not None else [])
        return np.concatenate(parts)

    @property
    def selection_stack(self) -> np.ndarray:
        """:attr:`selection_mm` per CV scheme, shape (S, P, 3): the schemes score the same poses, so a paired test
        takes one difference per pose (their mean), not one per scheme and pose."""
        return np.stack([self.oof_mm] + ([self.oof_joint_mm] if self.oof_joint_mm is not None else []))

    @property
    def cv_rms_mm(self) -> float:
        """RMS of :attr:`selection_mm` (the training file's out-of-fold residuals) [mm]."""
        return rms(self.selection_mm)

    @property
    def heldout_mm(self) -> np.ndarray:
        """All held-out residuals: out-of-fold, then test, shape (P + T, 3)."""
        return self.oof_mm if self.test_mm is None else np.concatenate([self.oof_mm, self.test_mm])

    @property
    def heldout_rms_mm(self) -> float:
        return rms(self.heldout_mm)


@dataclass(frozen=True, eq=False)
class Candidate:
    """Score of one candidate effect on top of a base model.

    ``heldout_rms_mm``: RMS of the training file's out-of-fold residuals, both CV schemes
    (:attr:`Evaluation.selection_mm`); ``cv_rms_mm``: of the first scheme only. Candidates are never scored on the
    sealed test file. ``probability``: the family's posterior probability from its marginal likelihood on the
    training residual (:mod:`.families`; first step only, NaN elsewhere).
    """

    effect: str
    applicable: bool
    reason: str
    n_params: int
    heldout_rms_mm: float
    cv_rms_mm: float
    p_value: float
    gain_pct: float
    significant: bool
    robust_rms_mm: float = float("nan")
    variant: str = ""
    probability: float = float("nan")
    #: significant at the uncorrected level as the family the evidence singles out (:func:`.families.evidence_leader`)
    evidence_led: bool = False

    def to_dict(self) -> dict:
        return {"effect": self.effect, "heldout_rms_mm": self.heldout_rms_mm, "p_value": self.p_value,
                "cv_rms_mm": self.cv_rms_mm, "gain_pct": self.gain_pct,
                "n_params": self.n_params, "significant": self.significant, "applicable": self.applicable,
                "reason": self.reason, "robust_rms_mm": self.robust_rms_mm, "variant": self.variant,
                "probability": self.probability if np.isfinite(self.probability) else None,
                "evidence_led": self.evidence_led}


@dataclass(frozen=True, eq=False)
class Stage:
    """One step of the sequential selection: candidates tested on top of ``base``."""

    base: tuple
    base_rms_mm: float
    candidates: tuple
    selected: str | None
    removed: str | None = None  # backward step (:func:`.stepwise._backward`): the effect dropped from ``base``, if any
    n_tests: int = 1  # candidates tested at this step: the Bonferroni divisor of its significance level
    leader: str | None = None  # the family the model evidence singles out (:func:`.families.evidence_leader`)
    n_poses: int = 0  # poses of the out-of-fold residuals the step's p-values are computed on


def robust_rms(res: np.ndarray, clip_mm: float) -> float:
    """RMS of the 3-D error norms clipped at ``clip_mm`` [mm] (a Huber-type statistic outliers cannot dominate)."""
    d = np.minimum(np.linalg.norm(res, axis=1), clip_mm)
    return float(np.sqrt(np.mean(d ** 2))) if len(d) else float("nan")


def clip_level(res: np.ndarray) -> float:
    """Clip level of :func:`robust_rms`: 2.5 x the median 3-D error norm (~3.8 sigma for Gaussian noise) [mm]."""
    return float(max(2.5 * np.median(np.linalg.norm(res, axis=1)), 1e-6))


def paired_pvalue(base: np.ndarray, cand: np.ndarray, clip_mm: float) -> float:
    """One-sided Wilcoxon signed-rank p-value that ``cand`` has smaller clipped 3-D errors than ``base``.

    ``base``, ``cand``: residuals (P, 3), or (S, P, 3) for S cross-validation schemes on the same P poses
    (:attr:`Evaluation.selection_stack`): the per-pose differences of clipped squared error are averaged over
    the schemes, so each pose counts once.
    """
    b, c = np.asarray(base), np.asarray(cand)
    d = np.minimum(np.sum(b ** 2, axis=-1), clip_mm ** 2) - np.minimum(np.sum(c ** 2, axis=-1), clip_mm ** 2)
    if d.ndim == 2:
        d = d.mean(axis=0)
    if np.allclose(d, 0):
        return 1.0
    return float(wilcoxon(d, alternative="greater").pvalue)


def poses_to_pass(p_value: float, level: float, n_poses: int, power: float = 0.8) -> int | None:
    """Training poses at which a one-sided test that gave ``p_value`` on ``n_poses`` poses would pass ``level`` with
    probability ``power``, the per-pose gain unchanged: the test statistic's z grows with the square root of the
    poses (the signed-rank statistic's normal approximation), ``n (z_level + z_power)^2 / z_observed^2``. None where
    the observed gain is not positive (``p_value`` >= 0.5) or the inputs are unusable: a rough extrapolation, not a
    design."""
    if not (0.0 < p_value < 0.5 and 0.0 < level < 0.5 and n_poses > 0):
        return None
    z = float(norm.isf(p_value))
    return int(np.ceil(n_poses * ((norm.isf(level) + norm.ppf(power)) / z) ** 2 - 1e-9))
