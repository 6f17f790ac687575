"""Posterior probabilities of the candidate effect families from their marginal likelihood (model evidence).

Each family ``f`` (its variant as chosen on the training residual) is a linear-Gaussian model of the geometric fit's
training residual, projected off the registration, offset and geometric columns as :mod:`.choice` does:
``r = Phi_f beta + e`` with ``beta ~ N(0, s^2)`` (one prior scale per family -- per joint for the transmission's
harmonics -- fitted by type-II maximum likelihood, :func:`~.evidence.ard_evidence`) and ``e ~ N(0, sigma^2)``. The
``none`` model is the noise alone. With equal prior odds, ``P(f | data) = exp(log_ml_f) / sum exp(log_ml)`` over
``none`` and the applicable families. The evidence penalises columns a family does not need (Occam's factor), so it
complements the held-out RMS the selection scores; both are printed, and the verdict's margin rule
(:mod:`.verdict`) uses the held-out RMS.
"""

from __future__ import annotations

import numpy as np

from tolalloc.diagnose.choice import projected_residual
from tolalloc.diagnose.evidence import ard_evidence

__all__ = ["family_log_evidence", "family_probabilities"]


#: Residual degrees of freedom per column of the largest family below which no probabilities are stated: the
#: evidence of a fitted prior scale on a nearly interpolated residual says nothing.
MIN_DOF_PER_COLUMN = 3


def family_log_evidence(ctx) -> dict:
    """``{family: log marginal likelihood}`` of the training residual, with ``none`` (noise alone); empty when the
    residual has too few degrees of freedom (:data:`MIN_DOF_PER_COLUMN`)."""
    fit = ctx.cal.geometric
    Q, r, n = projected_residual(fit, ctx.J_fixed, ctx.geo_residual)
    if n < MIN_DOF_PER_COLUMN * max((b.B.shape[2] for b in ctx.bases.values()), default=1):
        return {}
    rr = max(float(r @ r), 1e-300)
    out = {"none": 0.5 * n * (np.log(max(n, 1) / rr) - 1.0 - np.log(2 * np.pi))}
    for e, b in ctx.bases.items():
        J = np.einsum("ij,pjm->pim", fit.R, b.B).reshape(len(r), -1)
        J = J - Q @ (Q.T @ J)
        keep = np.linalg.norm(J, axis=0) > 1e-9 * max(1.0, float(np.abs(J).max(initial=0.0)))
        if not keep.any():
            continue
        groups = np.zeros(J.shape[1], int) if b.groups is None else np.asarray(b.groups)
        out[e] = ard_evidence(J[:, keep], r, groups[keep], n_eff=n).log_ml
    return out


def family_probabilities(ctx) -> dict:
    """``{family: posterior probability}`` with equal prior odds over ``none`` and the applicable families (empty
    when the residual has too few degrees of freedom to weigh them)."""
    logml = family_log_evidence(ctx)
    if not logml:
        return {}
    names = list(logml)
    v = np.array([logml[k] for k in names])
    w = np.exp(v - v.max())
    return {k: float(x) for k, x in zip(names, w / w.sum())}
