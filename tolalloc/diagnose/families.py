"""Posterior probabilities of the candidate effect families from their marginal likelihood (model evidence).

Each family ``f`` (its variant as chosen on the training residual) is a linear-Gaussian model of the geometric fit's
training residual, projected off the registration, offset and geometric columns as :mod:`.choice` does:
``r = Phi_f beta + e`` with ``beta ~ N(0, s^2)`` (one prior scale per family -- per joint for the transmission's
harmonics -- fitted by type-II maximum likelihood, :func:`~.evidence.ard_evidence`) and ``e ~ N(0, sigma^2)``. The
``none`` model is the noise alone. With equal prior odds, ``P(f | data) = exp(log_ml_f) / sum exp(log_ml)`` over
``none`` and the applicable families the residual can weigh (:data:`MIN_DOF_PER_COLUMN`). The evidence penalises
columns a family does not need (Occam's factor), so it complements the held-out RMS the selection scores; both are
printed.

Where the held-out RMS cannot separate two families (within the verdict's practical margin, :mod:`.verdict`), the
evidence decides when it is strong: a Bayes factor of at least :data:`DECISIVE_BAYES_FACTOR` (Kass and Raftery,
"Bayes factors", JASA 1995: ``2 ln B > 6``, *strong* evidence). The first forward step then selects the family the
evidence favours among those tied with the best (:func:`evidence_pick`), and the verdict names it alone
(:func:`bayes_factor`); a weaker factor leaves the tie ``ambiguous``.

Where no candidate passes the selection's Bonferroni-corrected test, a family the evidence singles out -- a Bayes
factor of at least :data:`LEADING_BAYES_FACTOR` against no effect and against every other family weighed (Kass and
Raftery: ``2 ln B > 10``, *very strong*) -- is the one hypothesis left to test (:func:`evidence_leader`): the first
forward step then tests it at the uncorrected level, with the practical margin as its minimum gain
(:func:`.stepwise.select_effects`).
"""

from __future__ import annotations

import numpy as np

from tolalloc.diagnose.choice import projected_residual
from tolalloc.diagnose.evidence import ard_evidence

__all__ = ["family_log_evidence", "posterior_probabilities", "bayes_factor", "evidence_pick", "evidence_leader",
           "DECISIVE_BAYES_FACTOR", "LEADING_BAYES_FACTOR"]


#: Residual degrees of freedom per column below which a family's evidence is not stated: the evidence of a fitted
#: prior scale on a nearly interpolated residual says nothing. A family with more columns (a long harmonic series)
#: is left out of the probabilities; the others are weighed among themselves and ``none``.
MIN_DOF_PER_COLUMN = 3

#: Bayes factor from which the evidence separates two families that predict the held-out poses alike
DECISIVE_BAYES_FACTOR = 20.0
#: Bayes factor against no effect and every other family from which the evidence singles one family out
LEADING_BAYES_FACTOR = 150.0


def family_log_evidence(ctx) -> dict:
    """``{family: log marginal likelihood}`` of the training residual, with ``none`` (noise alone); a family with
    more columns than the residual's degrees of freedom allow (:data:`MIN_DOF_PER_COLUMN`) is left out, and the
    result is empty when no family is left."""
    fit = ctx.cal.geometric
    Q, r, n = projected_residual(fit, ctx.J_fixed, ctx.geo_residual)
    weighed = {e: b for e, b in ctx.bases.items() if n >= MIN_DOF_PER_COLUMN * b.B.shape[2]}
    if not weighed:
        return {}
    rr = max(float(r @ r), 1e-300)
    out = {"none": 0.5 * n * (np.log(max(n, 1) / rr) - 1.0 - np.log(2 * np.pi))}
    for e, b in weighed.items():
        J = np.einsum("ij,pjm->pim", fit.R, b.B).reshape(len(r), -1)
        J = J - Q @ (Q.T @ J)
        keep = np.linalg.norm(J, axis=0) > 1e-9 * max(1.0, float(np.abs(J).max(initial=0.0)))
        if not keep.any():
            continue
        groups = np.zeros(J.shape[1], int) if b.groups is None else np.asarray(b.groups)
        out[e] = ard_evidence(J[:, keep], r, groups[keep], n_eff=n).log_ml
    return out


def posterior_probabilities(logml: dict) -> dict:
    """``{family: posterior probability}`` from ``{family: log marginal likelihood}`` (equal prior odds)."""
    if not logml:
        return {}
    names = list(logml)
    v = np.array([logml[k] for k in names])
    w = np.exp(v - v.max())
    return {k: float(x) for k, x in zip(names, w / w.sum())}


def bayes_factor(logml: dict, a: str, b: str) -> float:
    """``p(data | a) / p(data | b)`` from the log marginal likelihoods (NaN when either is not stated)."""
    if a not in logml or b not in logml:
        return float("nan")
    return float(np.exp(min(logml[a] - logml[b], 700.0)))


def evidence_leader(logml: dict) -> tuple:
    """``(family, smallest Bayes factor against the rest)`` of the family whose evidence beats no effect and every
    other family weighed by at least :data:`LEADING_BAYES_FACTOR`, or ``(None, nan)``."""
    fams = [k for k in logml if k != "none"]
    if not fams or "none" not in logml:
        return None, float("nan")
    top = max(fams, key=lambda k: logml[k])
    bf = min(bayes_factor(logml, top, o) for o in logml if o != top)
    return (top, bf) if bf >= LEADING_BAYES_FACTOR else (None, float("nan"))


def evidence_pick(candidates, logml: dict, margin: float):
    """The significant candidate the evidence favours decisively over every other significant candidate whose
    clipped out-of-fold RMS is within ``margin`` (a fraction) of the best one's; None when there is no such tie or
    the evidence does not decide it (a Bayes factor below :data:`DECISIVE_BAYES_FACTOR` against one of them).

    Parameters
    ----------
    candidates : sequence of :class:`~.scores.Candidate`   one forward step's candidates
    logml : dict    ``{family: log marginal likelihood}`` (:func:`family_log_evidence`)
    margin : float  the practical margin (:data:`~.verdict.PRACTICAL_MARGIN`)
    """
    sig = [c for c in candidates if c.significant and np.isfinite(c.robust_rms_mm)]
    if len(sig) < 2 or not logml:
        return None
    best = min(c.robust_rms_mm for c in sig)
    close = [c for c in sig if c.robust_rms_mm <= (1.0 + margin) * best]
    for c in close:
        others = [o for o in close if o is not c]
        if others and all(bayes_factor(logml, c.effect, o.effect) >= DECISIVE_BAYES_FACTOR for o in others):
            return c
    return None
