"""Post-calibration probability margin of many candidate designs at once (the standard-grade search's constraint).

For a design ``t`` the post-calibration covariance of the estimated systematic parts is (square-root form of
:func:`tolalloc.calibration.posterior.posterior`, ``L = diag(sigma_prior,E)``)::

    S_E = L (I + L G L)^-1 L,      G = A^T A  (whitened identification matrix, nuisance projected out)

and ``G`` depends on the design only through the random parts (they are measurement noise of the calibration); the
systematic priors enter through ``L`` alone. A candidate that changes only systematic tolerances therefore reuses
the ``G`` of the design it came from, and the covariance at the poses is ``J (S_sys + V_random) J^T`` with a batched
``Ke x Ke`` solve -- no identification matrix, no SVD. ``G`` is computed (and kept) once per random-part state.

When the plan leaves systematic parts unestimated (they act as correlated measurement noise whose covariance
follows their prior), every candidate goes through :func:`tolalloc.calibration.posterior.posterior` instead.
"""

from __future__ import annotations

import numpy as np

from tolalloc.allocate.problem import AllocationProblem
from tolalloc.calibration.posterior import estimated_index, identification_matrix, posterior
from tolalloc.linear.covariance import VARIANCE_FACTOR
from tolalloc.linear.probability import p_within_radius

__all__ = ["PostMargin"]

_CACHE_MAX = 256  # random-part states whose information matrix is kept


class PostMargin:
    """``margin(U)``: smallest ``P_post,i - target_i`` over the poses of ``problem`` for each row of ``U``.

    Parameters
    ----------
    problem : AllocationProblem
        Poses, radius, per-pose targets and the allocatable parameters (``U`` holds their scaled variances
        ``u = (t / t_ref)**2``; the other parameters stay at their fixed tolerance).
    split : ErrorSplit
        Systematic / random split, with the random parts of systematic parameters (repeatability grades) set.
    plan : CalibrationPlan

    Attributes
    ----------
    evaluations : int
        Candidate designs evaluated so far.
    """

    def __init__(self, problem: AllocationProblem, split, plan):
        self.problem, self.split, self.plan = problem, split, plan
        m = problem.model
        self.fac = np.array([VARIANCE_FACTOR[p.distribution] for p in m.params])
        self.E = estimated_index(split, plan)
        self.fast = len(np.setdiff1d(split.sys_index, self.E)) == 0 and plan.n_poses > 0 and len(self.E) > 0
        self.J = problem.J[:, :3, :]
        self.target = np.asarray(problem.blocks[0]["target"], float)
        self.evaluations = 0
        self._info: dict = {}

    def t_of(self, U) -> np.ndarray:
        """Full half-widths (B, K) [mm or rad] of scaled variances ``U`` (B, Ka)."""
        pr = self.problem
        U = np.atleast_2d(np.asarray(U, float))
        T = np.repeat(np.asarray(pr.costs.fixed_tol, float)[None], len(U), axis=0)
        T[:, pr.alloc] = pr.t_ref[pr.alloc][None] * np.sqrt(np.maximum(U, 0.0))
        return T

    def probabilities(self, U) -> np.ndarray:
        """Post-calibration ``P(|dP| < r)`` (B, P) at the problem's poses."""
        T = self.t_of(U)
        self.evaluations += len(T)
        if not self.fast:
            return np.stack([self._slow(t) for t in T])
        C = np.stack([self._cov(t) for t in T])  # (B, K, K)
        S = np.einsum("pik,bkl,pjl->bpij", self.J, C, self.J)
        return np.asarray(p_within_radius(S.reshape(-1, 3, 3), self.problem.radius_mm)).reshape(len(T), -1)

    def __call__(self, U) -> np.ndarray:
        """Smallest ``P - target`` over the poses, shape (B,)."""
        return (self.probabilities(U) - self.target[None]).min(axis=1)

    def violation(self, U) -> np.ndarray:
        """``-margin``: ``<= 0`` where the requirement holds at every pose (the local search's convention)."""
        return -self(U)

    def linearise(self, u, near: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
        """Rows ``A u' <= s``: ``P_i(u) + grad P_i(u) . (u' - u) >= target_i`` at the poses within ``near`` of their
        target (central differences in ``u``, relative step 1e-4), shapes (m, Ka) and (m,)."""
        u = np.asarray(u, float)
        Ka = len(u)
        h = 1e-4 * np.maximum(u, 1e-300)
        P = self.probabilities(np.vstack([u, u + np.diag(h), u - np.diag(h)]))
        idx = np.flatnonzero(P[0] - self.target < near)
        if not idx.size:
            return np.zeros((0, Ka)), np.zeros(0)
        g = ((P[1:Ka + 1] - P[Ka + 1:]) / (2 * h[:, None]))[:, idx].T  # (m, Ka)
        return -g, P[0, idx] - self.target[idx] - g @ u

    def _cov(self, t) -> np.ndarray:
        """Remaining parameter covariance (K, K) after calibration for half-widths ``t``."""
        sp = self.split
        sigma = self.problem.sigma(t)
        prior = np.where(sp.systematic, self.fac * sigma**2, 0.0)
        rand = self.fac * np.where(sp.systematic, sp.random_sigma, sigma) ** 2
        G = self._information(rand, sigma)
        L = np.sqrt(prior[self.E])
        Ke = len(self.E)
        SE = L[:, None] * np.linalg.solve(np.eye(Ke) + L[:, None] * G * L[None, :], np.diag(L))
        cov = np.diag(rand)
        cov[np.ix_(self.E, self.E)] += 0.5 * (SE + SE.T)
        return cov

    def _information(self, rand, sigma) -> np.ndarray:
        key = rand.tobytes()
        G = self._info.get(key)
        if G is None:
            if len(self._info) >= _CACHE_MAX:
                self._info.clear()
            sp = self.split.with_model(self.problem.model.with_sigma(sigma))
            A = identification_matrix(sp, self.plan, self.E)
            G = self._info[key] = A.T @ A
        return G

    def _slow(self, t) -> np.ndarray:
        post = posterior(self.split.with_model(self.problem.model_for(t)), self.plan)
        return np.asarray(p_within_radius(post.tool_covariance(self.problem.q), self.problem.radius_mm))
