"""The Monte Carlo estimates of a verification at its poses: the first look and the second.

:func:`_estimate` runs the requested estimator (plain, paired or importance sampling,
:mod:`tolalloc.montecarlo.paired`) at all poses with the intervals at the level of each simultaneous interval;
:func:`_redo` gives the poses whose position interval straddles ``p`` their second look with more samples
(pooled with the first, or importance sampling). :func:`tolalloc.verify.designs.verify_design` calls both and
judges the result.
"""

from __future__ import annotations

import numpy as np

from tolalloc.montecarlo.paired import control_fallback_reason

__all__ = []


def _estimate(model, q, n, seed, radius, angle, keep, scheduler, estimator, level):
    """Position (and orientation) estimates at poses ``q`` by the requested estimator, intervals at ``level``."""
    from tolalloc.montecarlo.importance import importance_probability
    from tolalloc.montecarlo.paired import estimate_probabilities

    other = "auto" if estimator == "importance" else estimator
    est = estimate_probabilities(model, q, int(n), seed, radius_mm=radius, angle_radius_rad=angle, estimator=other,
                                 level=level, keep_samples=keep, scheduler=scheduler)
    if estimator == "importance":
        from dataclasses import replace

        kept = est["position"].details.get("kept_mm")
        isr = importance_probability(model, q, int(n), seed, radius_mm=radius, level=level, scheduler=scheduler)
        est["position"] = replace(isr, details={**isr.details, "kept_mm": kept})
    return est


def _redo(model, problem, est, redo, n_mc, n_max, seed, scheduler, estimator):
    """Re-estimate the poses ``redo`` whose interval straddles ``p`` with more samples (intervals at the
    level of ``est``).

    Plain and paired runs are pooled with ``n_max - n_mc`` fresh samples (seed + 1); ``auto`` on a Gaussian model
    switches those poses to importance sampling with ``n_max`` samples (its interval is far narrower in the tail).
    """
    from tolalloc.montecarlo.importance import importance_probability
    from tolalloc.montecarlo.paired import PairedCounts, estimate_from_counts, paired_counts

    q, r = problem.q[redo], problem.radius_mm
    if estimator == "importance" or (estimator == "auto" and not control_fallback_reason(model)):
        return est.with_rows(redo, importance_probability(model, q, n_max, seed + 1, radius_mm=r, level=est.level,
                                                          scheduler=scheduler))
    extra = n_max - int(n_mc)
    pc = paired_counts(model, q, extra, seed + 1, radii_mm=(r,), scheduler=scheduler)
    first = est.take(redo)
    nl = np.rint(first.p_plain * first.n)
    lin_in = nl - first.n_nonlinear_only + first.n_linear_only
    both = nl - first.n_nonlinear_only
    counts = pc.counts + np.stack([nl, lin_in, both], axis=1)[:, None, :].astype(np.int64)
    pooled = PairedCounts(first.n + extra, pc.seed, counts, pc.max_deviation_mm)
    new = estimate_from_counts(pooled, 0, r, first.p_linear, estimator=est.requested if est.requested != "importance"
                               else "auto", model_reason=control_fallback_reason(model), level=est.level)
    return est.with_rows(redo, new)
