"""Coverage of a design over a joint-space region: its linear ``P`` on a fresh seeded sample (a statement that can fail).

:func:`coverage` evaluates the linear probability of every requirement of the problem -- the position requirement
``P(|dP| < r) >= p`` and, when the problem has one, the orientation requirement ``P(|dw| < a) >= p_a`` -- on a
fresh seeded uniform sample of the box, and bounds the fraction of the region below each requirement's
probability from above (one-sided 95 % Clopper-Pearson). The sample is drawn and screened in chunks, so memory
does not grow with the sample size; poses that the largest-eigenvalue bound proves above ``p`` (and above the
lowest ``P`` seen) are not integrated exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import beta, chi2

from tolalloc.allocate.problem import AllocationProblem
from tolalloc.exceptions import TolallocError, whole_number
from tolalloc.linear.probability import p_within_angle, p_within_radius

__all__ = ["Coverage", "coverage", "check_coverage_budget"]


def _position_cov(problem: AllocationProblem, t, q) -> np.ndarray:
    """Position covariance of design ``t`` at poses ``q`` (M, n), shape (M, 3, 3) [mm^2]."""
    J = problem.model.jacobian(np.atleast_2d(q))[:, :3, :]
    return np.einsum("mik,k,mjk->mij", J, problem.sigma(t) ** 2, J)


def _rotation_cov(problem: AllocationProblem, t, q) -> np.ndarray:
    """Rotation-error covariance of design ``t`` at poses ``q`` (M, n), shape (M, 3, 3) [rad^2]."""
    J = problem.model.jacobian(np.atleast_2d(q))[:, 3:6, :]
    return np.einsum("mik,k,mjk->mij", J, problem.sigma(t) ** 2, J)


@dataclass(frozen=True)
class Coverage:
    """Linear P of a design on a fresh seeded sample of the region.

    Attributes
    ----------
    n : int
    min_p : float
        Lowest position ``P(|dP| < r)`` on the sample.
    worst_q : array, shape (k', n)
        The poses for the nonlinear Monte Carlo: the ``k`` lowest position-P poses, then, with an orientation
        requirement, those of the ``k`` lowest orientation-P poses that are not among them.
    n_below : int
        Poses whose position P is below ``p``.
    frac_below : float
    frac_below_upper95 : float
        One-sided 95 % Clopper-Pearson upper bound on the fraction of the region below ``p`` (position).
    n_exact : int
        Poses whose exact position P was computed; the others are proven above ``p`` and above ``min_p`` by the
        largest-eigenvalue bound ``P >= P(chi2_3 < r^2 / lambda_max)``.
    angle_prob : float or None
        The orientation requirement's probability ``p_a``; None (and every ``*_angle`` field None) without an
        orientation requirement.
    min_p_angle : float or None
        Lowest orientation ``P(|dw| < a)`` on the same sample.
    n_below_angle : int or None
        Poses whose orientation P is below ``p_a``.
    frac_below_angle, frac_below_upper95_angle : float or None
        As ``frac_below`` and ``frac_below_upper95``, for the orientation requirement.
    n_exact_angle : int or None
        Poses whose exact orientation P was computed (the same screen with the rotation covariance).
    worst_q_angle : array, shape (k, n) or None
        The ``k`` lowest orientation-P poses.
    """

    n: int
    min_p: float
    worst_q: np.ndarray
    n_below: int
    frac_below: float
    frac_below_upper95: float
    n_exact: int = 0
    angle_prob: float | None = None
    min_p_angle: float | None = None
    n_below_angle: int | None = None
    frac_below_angle: float | None = None
    frac_below_upper95_angle: float | None = None
    n_exact_angle: int | None = None
    worst_q_angle: np.ndarray | None = None

    @property
    def ok(self) -> bool:
        """No sampled pose below ``p`` for any requirement."""
        return self.n_below == 0 and not self.n_below_angle

    def message(self, prob: float) -> str:
        head = (f"coverage: {self.n} fresh poses, min P = {self.min_p:.5f}, {self.n_below} below {prob:g} "
                f"(fraction {self.frac_below:.2e}, 95% upper bound {self.frac_below_upper95:.2e})")
        if self.angle_prob is not None:
            head += (f"; orientation: min P = {self.min_p_angle:.5f}, {self.n_below_angle} below {self.angle_prob:g} "
                     f"(fraction {self.frac_below_angle:.2e}, 95% upper bound {self.frac_below_upper95_angle:.2e})")
        return head if not self.ok else head + "; none below p"


class _Tally:
    """Screened exact P of one requirement over the chunks of the sample: count below, minimum, worst poses."""

    def __init__(self, radius: float, prob: float, tol: float, k_worst: int, dof: int, p_fn):
        self.radius, self.prob, self.tol, self.k, self.p_fn = radius, prob, tol, k_worst, p_fn
        self.below, self.done, self.p_min = 0, 0, np.inf
        self.worst_p, self.worst_q = np.empty(0), np.empty((0, dof))

    def add(self, Q: np.ndarray, C: np.ndarray) -> None:
        # screen: P(|x| < r) >= P(chi2_3 < r^2 / lambda_max) (the ball contains the lambda_max-sphere's ellipsoid);
        # the exact P is computed in order of this bound until no unevaluated pose can be lower or below p
        lower = chi2.cdf(self.radius**2 / np.maximum(np.linalg.eigvalsh(C)[:, -1], 1e-300), 3)
        order = np.argsort(lower)
        P = np.full(len(Q), np.nan)
        k = 0
        while k < len(Q) and (lower[order[k]] < self.prob - self.tol or lower[order[k]] < self.p_min):
            idx = order[k:k + 2000]
            P[idx] = self.p_fn(C[idx], self.radius)
            self.p_min = min(self.p_min, float(np.nanmin(P[idx])))
            k += len(idx)
        ev = order[:k]
        self.below += int(np.sum(P[ev] < self.prob - self.tol))
        self.done += k
        self.worst_p = np.concatenate([self.worst_p, P[ev]])
        self.worst_q = np.concatenate([self.worst_q, Q[ev]])
        keep = np.argsort(self.worst_p)[:self.k]
        self.worst_p, self.worst_q = self.worst_p[keep], self.worst_q[keep]

    def upper95(self, n: int) -> float:
        return float(beta.ppf(0.95, self.below + 1, n - self.below)) if self.below < n else 1.0


def check_coverage_budget(n: int, *, runs: int = 1, argument: str = "n", announce: bool = False):
    """Refuse ``n`` coverage poses that cannot be screened within the time budget (``runs`` coverage checks of
    ``n`` poses; :func:`tolalloc.budget.check_count`); returns the estimate."""
    from tolalloc.budget import check_count

    note = f"{runs} coverage checks" if runs > 1 else ""
    return check_count(int(n), argument, "coverage poses", "coverage", per_count=runs, example="100000",
                       announce=announce, note=note)


def coverage(problem: AllocationProblem, t, region, *, n: int = 100_000, seed: int = 12345,
             k_worst: int = 3, tol: float = 1e-4, chunk: int = 20_000, pose_cov=None) -> Coverage:
    """Coverage of a design over a region on a fresh seeded sample (uniform random, not the search's Sobol).

    A pose counts as below when ``P < p - tol``(tol: the search's convergence tolerance). The sample is drawn and
    screened ``chunk`` poses at a time (the same stream as one draw of all ``n``), so memory does not grow with
    ``n``. With an orientation requirement (``problem.angle_radius_rad``) the orientation ``P(|dw| < a)`` is
    evaluated on the same poses, screened by the same bound with the largest eigenvalue of the rotation covariance,
    and counted against ``angle_prob``. ``pose_cov`` (optional): function of poses (M, n) giving the position
    covariance (M, 3, 3) [mm^2] to check instead of the design's (e.g. the post-calibration covariance; ``t`` is then
    unused, and only the position requirement is checked).

    Parameters
    ----------
    problem : AllocationProblem
    t : array, shape (K,) [mm, rad] or None
    region : Region
        The box (``q_min``, ``q_max`` [rad, mm]).
    """
    from tolalloc.exceptions import raise_if_interrupted

    whole = whole_number(n)
    if whole is None or whole < 1:
        raise TolallocError(f"n: expected a whole number of coverage poses >= 1 (e.g. 1e5), got {n!r}.")
    n, chunk = int(n), max(1, int(chunk))
    check_coverage_budget(n)
    rng = np.random.default_rng(seed)
    dof = len(region.q_min)
    angle = pose_cov is None and problem.angle_radius_rad is not None
    pos = _Tally(problem.radius_mm, problem.prob, tol, k_worst, dof, p_within_radius)
    rot = _Tally(problem.angle_radius_rad, problem.angle_prob, tol, k_worst, dof, p_within_angle) if angle else None
    for start in range(0, n, chunk):
        raise_if_interrupted()
        Q = region.q_min + rng.random((min(chunk, n - start), dof)) * (region.q_max - region.q_min)
        if pose_cov is not None:
            pos.add(Q, pose_cov(Q))
            continue
        J = problem.model.jacobian(Q)
        s2 = problem.sigma(t) ** 2
        pos.add(Q, np.einsum("mik,k,mjk->mij", J[:, :3, :], s2, J[:, :3, :]))
        if rot is not None:
            rot.add(Q, np.einsum("mik,k,mjk->mij", J[:, 3:6, :], s2, J[:, 3:6, :]))
    if rot is None:
        return Coverage(n, pos.p_min, pos.worst_q, pos.below, pos.below / n, pos.upper95(n), int(pos.done))
    extra = [q for q in rot.worst_q if not np.any(np.all(pos.worst_q == q, axis=1))]
    worst = np.vstack([pos.worst_q, *extra]) if extra else pos.worst_q
    return Coverage(n, pos.p_min, worst, pos.below, pos.below / n, pos.upper95(n), int(pos.done),
                    float(problem.angle_prob), rot.p_min, rot.below, rot.below / n, rot.upper95(n), int(rot.done),
                    rot.worst_q)
