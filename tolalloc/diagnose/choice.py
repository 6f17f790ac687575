"""Which variant of an effect: chosen on the training residual of the geometric fit, before any held-out scoring.

Linearised at the geometric fit: residual and effect columns are projected off the registration, offset and
geometric columns; residual components beyond 3 robust sigma are clipped first, so a few outliers do not pick the
variant. Variants without a prior compete by BIC on the residual degrees of freedom; variants whose columns carry
a fitted prior (``EffectBasis.groups``, e.g. the transmission's harmonic series) by their marginal likelihood
with the prior scales fitted (:mod:`.evidence`), and the chosen one keeps its ridge weights (``prior_w``). A variant
with a prior among variants without one (backlash's ``reseat`` beside the flank variants) competes by BIC and, when
chosen, keeps the ridge weights its evidence fits.

The prior scales are hyper-parameters fitted to data: a cross-validation fold must fit them on its own training
poses (:func:`prior_weights`), or the held-out block has helped to set the ridge that predicts it -- and ``M``
free scales tuned on the held-out noise make a many-column series look better out of fold than it is.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.diagnose.evidence import ard_evidence
from tolalloc.physics.thermal import is_air_variant

__all__ = ["choose_variant", "combined_thermal", "projected_residual", "prior_weights"]


def projected_residual(fit, J_fixed: np.ndarray, residual_mm: np.ndarray | None = None):
    """(Q, r, n): orthonormal basis of ``J_fixed``, the clipped residual projected off it, its degrees of freedom."""
    Q, _ = np.linalg.qr(J_fixed)
    r = (fit.residual_mm if residual_mm is None else residual_mm).ravel()
    r = r - Q @ (Q.T @ r)
    s = 1.4826 * np.median(np.abs(r - np.median(r)))
    r = np.clip(r, -3 * s, 3 * s)
    return Q, r, len(r) - Q.shape[1]


def choose_variant(cands: list, fit, J_fixed: np.ndarray, residual_mm: np.ndarray | None = None):
    """The variant whose columns best explain the geometric fit's training residual (BIC, winsorised residual).

    Linearised at the geometric fit: residual and effect columns are projected off the registration, offset
    and geometric columns ``J_fixed``; residual components beyond 3 robust sigma are clipped first, so a few
    outliers do not pick the variant. ``BIC = n log(RSS / (n - M)) + M log n`` with ``n`` the residual degrees
    of freedom (3P rows minus the fixed columns) and ``M`` the variant's columns: the noise variance is estimated
    from the degrees of freedom the variant leaves, so on few poses a many-column variant (e.g. two harmonics on
    every joint) cannot win by fitting the noise of a nearly interpolated residual.
    ``residual_mm`` (P, 3): the fit's residual on the poses of ``J_fixed`` (default ``fit.residual_mm``, when the
    fit was made on those very poses; a subsampled diagnosis passes the subsample's).
    """
    # a variant with no column on this robot explains nothing: it is the choice only when every variant is so
    cands = [c for c in cands if c.B.shape[2]] or cands[:1]
    if len(cands) == 1 and getattr(cands[0], "groups", None) is None:
        return cands[0]
    Q, r, n = projected_residual(fit, J_fixed, residual_mm)  # n: residual degrees of freedom left
    if all(getattr(c, "groups", None) is not None for c in cands):
        return _by_evidence(cands, fit, Q, r, n)
    best, best_bic = cands[0], np.inf
    for c in cands:
        Jc = np.einsum("ij,pjm->pim", fit.R, c.B).reshape(len(r), -1)
        Jc = Jc - Q @ (Q.T @ Jc)
        if Jc.shape[1] == 0:  # a variant with no column on this robot explains nothing
            rss, M = float(np.sum(r**2)), 0
        else:
            beta, *_ = np.linalg.lstsq(Jc, r, rcond=1e-8)
            rss = float(np.sum((r - Jc @ beta) ** 2))
            M = np.linalg.matrix_rank(Jc, 1e-8 * max(1.0, np.abs(Jc).max()))
        bic = n * np.log(max(rss, 1e-300) / (n - M)) + M * np.log(n) if n - M > 0 else np.inf
        if bic < best_bic:
            best, best_bic = c, bic
    # a winner whose columns carry a prior among variants without one keeps its ridge, fitted as below
    return best if getattr(best, "groups", None) is None else _by_evidence([best], fit, Q, r, n)


def combined_thermal(cands: list, fit, J_fixed: np.ndarray, residual_mm: np.ndarray | None = None) -> list:
    """The thermal variant that takes both drivers at once: the best air-driven variant (logged temperature, lagged
    or not) and the best activity-driven one (warm-up, motion, motor losses), each chosen by :func:`choose_variant`
    among its kind, their columns side by side -- a one-element list, empty when the data carry only one kind.
    It then competes with the single variants by the same BIC, which charges it for its extra columns."""
    air = [c for c in cands if is_air_variant(c.variant)]
    work = [c for c in cands if not is_air_variant(c.variant)]
    if not air or not work:
        return []
    a, w = (choose_variant(k, fit, J_fixed, residual_mm) for k in (air, work))
    return [replace(a, names=a.names + w.names, B=np.concatenate([a.B, w.B], axis=2),
                    variant=f"{a.variant}+{w.variant}")]


def _by_evidence(cands: list, fit, Q, r, n: int):
    """The variant of largest marginal likelihood, with its fitted ridge weights."""
    best, best_ml = cands[0], -np.inf
    for c in cands:
        Jc = np.einsum("ij,pjm->pim", fit.R, c.B).reshape(len(r), -1)
        Jc = Jc - Q @ (Q.T @ Jc)
        if Jc.shape[1] == 0:  # no column on this robot: the evidence of the noise alone (its ML precision n / |r|^2)
            rr = max(float(r @ r), 1e-300)
            log_ml = 0.5 * n * (np.log(max(n, 1) / rr) - 1.0 - np.log(2 * np.pi))
            if log_ml > best_ml:
                best, best_ml = c, log_ml
            continue
        ev = ard_evidence(Jc, r, c.groups, n_eff=n)
        if ev.log_ml > best_ml:
            best, best_ml = replace(c, prior_w=ev.prior_w, prior_dof=ev.dof), ev.log_ml
    return best


def prior_weights(basis, fit, J_fixed: np.ndarray, residual_mm: np.ndarray) -> np.ndarray:
    """Ridge weights (M,) of ``basis``'s columns with its prior scales fitted on the poses of ``J_fixed`` only.

    ``basis``: an effect basis with ``groups`` on those poses (P, 3, M); ``residual_mm`` (P, 3): the geometric
    fit's residual on them. Linearised like :func:`choose_variant`: residual and columns projected off ``J_fixed``.
    """
    Q, r, n = projected_residual(fit, J_fixed, residual_mm)
    Jc = np.einsum("ij,pjm->pim", fit.R, basis.B).reshape(len(r), -1)
    Jc = Jc - Q @ (Q.T @ Jc)
    return ard_evidence(Jc, r, basis.groups, n_eff=n).prior_w
