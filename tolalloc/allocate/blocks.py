"""The requirement blocks of an allocation problem: their covariances and laws, and the blocks of ISO 9283
requirements (:mod:`tolalloc.acceptance.terms`).

A block (see :class:`tolalloc.allocate.problem.AllocationProblem`) holds a requirement's affine covariance model
``C0 + sum_k u_k A_k`` at its poses. A block without a ``measure`` is an error ball of the working poses
(``P(|x| < r)``, its covariance from the problem's Jacobian rows); an ISO 9283 block has its own poses and the law of
its statistic (:mod:`tolalloc.acceptance.measures`).
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability import p_within_radius, radius_for_prob

__all__ = ["acceptance_blocks", "block_covariances", "block_probability", "block_radius"]


def acceptance_blocks(spec, sub, alloc, fixed, t_ref, sig, z) -> list:
    """One block per ISO 9283 statistic (:func:`tolalloc.acceptance.terms.statistic_terms`), at its own poses."""
    from tolalloc.acceptance.measures import measure_bounds
    from tolalloc.acceptance.terms import AcceptanceSpec, statistic_terms

    if not isinstance(spec, AcceptanceSpec):
        raise TolallocError(f"acceptance: expected tolalloc.acceptance.terms.AcceptanceSpec(requirements, test), got "
                            f"{spec!r}.")
    if spec.test.robot is not sub.robot and spec.test.robot.name != sub.robot.name:
        raise TolallocError(f"acceptance: the test was laid out for robot {spec.test.robot.name!r}, the model is of "
                            f"{sub.robot.name!r}; lay the test out for this robot.")
    out = []
    for tm in statistic_terms(spec, sub):
        A = tm.per_tolerance[:, alloc] * ((t_ref[alloc] / z) ** 2)[None, :, None, None]
        C0 = tm.const + tm.repeatability + np.einsum("pkij,k->pij", tm.per_tolerance[:, fixed], sig[fixed] ** 2)
        tb, eb = measure_bounds(tm.measure, tm.radius, tm.target, tm.cycles)
        out.append({"name": tm.name, "rows": None, "radius": tm.radius, "prob": tm.requirement.share,
                    "target": np.asarray(tm.target, float), "A": A, "C0": C0, "trace_bound": np.asarray(tb, float),
                    "eig_bound": np.asarray(eb, float), "measure": tm.measure, "cycles": tm.cycles, "q": tm.q,
                    "labels": tm.labels, "requirement": tm.requirement, "bias": tm.bias})
    return out


def block_covariances(problem, b: dict, t) -> np.ndarray:
    """Covariance of a block's error vector at each of its poses for half-widths ``t`` (K,), shape (P_b, 3, 3)."""
    if b.get("measure") is None:
        return problem.covariances(t, b["rows"])
    return b["C0"] + np.einsum("pkij,k->pij", b["A"], problem.u_from_t(t))


def block_probability(b: dict, C) -> np.ndarray:
    """The probability a block's requirement holds, per pose, for covariances ``C`` (P_b, 3, 3) (a lower bound where
    the block carries a mean: :mod:`tolalloc.acceptance.terms`)."""
    if b.get("measure") is None:
        return p_within_radius(C, b["radius"])
    from tolalloc.acceptance.measures import measure_cdf

    return measure_cdf(b["measure"], C, b["radius"], b["cycles"])


def block_radius(b: dict, C, p) -> np.ndarray:
    """The radius (an ISO block: the statistic) reached with probability ``p`` per pose, shape (P_b,)."""
    if b.get("measure") is None:
        return radius_for_prob(C, p)
    from tolalloc.acceptance.measures import measure_quantile

    r = measure_quantile(b["measure"], C, p, b["cycles"])
    bias = b.get("bias")
    if bias is None or not np.any(bias):
        return r
    return r * (b["radius"] - bias) / b["radius"] + bias     # back from the scaled covariances: an upper bound
