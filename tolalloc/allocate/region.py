"""Allocation over a joint-space region: worst-pose search and cutting planes (issue 13).

The requirement ``P(|dP| < r) >= p`` is imposed on a finite *active set* of poses; the region (a box
in joint space) is then searched for the pose where the linear probability falls furthest below ``p``
(multistart bounded L-BFGS-B seeded from a scrambled Sobol sample); that pose joins the active set
and the allocation is solved again, until the worst shortfall found is below ``tol`` (default 1e-4).

Joints that cannot change the position error (e.g. the last joint about the tool axis) are detected
from the error Jacobian (the position block of the covariance does not move when the joint moves) and
held at their mid-range: they cost nothing to search.

A coverage statement that can fail (:func:`coverage`) evaluates the linear ``P`` on a fresh seeded
sample of the region and bounds the fraction below ``p`` from above (one-sided 95 % Clopper-Pearson).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize
from scipy.stats import beta, chi2, qmc

from tolalloc.exceptions import TolallocError
from tolalloc.allocate.problem import AllocationProblem, build_problem
from tolalloc.linear.probability import p_within_radius

__all__ = ["Region", "box_region", "pose_probability", "static_joints", "worst_pose", "allocate_region",
           "RegionAllocation", "Coverage", "coverage"]


@dataclass(frozen=True)
class Region:
    """A box in joint space.

    Attributes
    ----------
    name : str
    q_min, q_max : array, shape (n,) [rad, mm]
    """

    name: str
    q_min: np.ndarray
    q_max: np.ndarray

    def sample(self, n: int, seed: int) -> np.ndarray:
        """``n`` scrambled-Sobol points of the box, shape (n, dof) [rad, mm]."""
        s = qmc.Sobol(len(self.q_min), scramble=True, seed=seed).random(int(n))
        return self.q_min + s * (self.q_max - self.q_min)


def box_region(robot, q_min, q_max, name: str = "box", where: str = "--region") -> Region:
    """Validate a box against the robot: shape, finiteness, non-empty, inside the joint limits.

    Parameters
    ----------
    robot : Robot
    q_min, q_max : array, shape (n,) [rad, mm]
    name : str
    where : str
        Named in error messages (the flag or the robot-file key).
    """
    lo, hi = np.asarray(q_min, float).ravel(), np.asarray(q_max, float).ravel()
    n = robot.n_joints
    if lo.shape != (n,) or hi.shape != (n,):
        raise TolallocError(f"{where}: expected q_min and q_max with {n} joint values each, got {lo.size} and "
                            f"{hi.size}; give one value per joint.")
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        raise TolallocError(f"{where}: the box bounds must be finite numbers; got q_min={robot.q_to_interface(lo)}, "
                            f"q_max={robot.q_to_interface(hi)} (deg / mm); give the joints finite limits in the robot "
                            "file, or a region of finite bounds (a box of the robot file, a pose set or a trajectory).")
    bad = np.flatnonzero(hi < lo)
    if bad.size:
        raise TolallocError(f"{where}: the box is inverted or empty at joint(s) {[int(j) + 1 for j in bad]} "
                            "(q_max < q_min); give q_min <= q_max for every joint.")
    robot.check_q(np.stack([lo, hi]), where)  # names the joint outside its limits
    return Region(name, lo, hi)


def pose_probability(problem: AllocationProblem, t, q) -> np.ndarray:
    """Linear ``P(|dP| < r)`` of the design ``t`` at arbitrary poses (batched).

    Parameters
    ----------
    problem : AllocationProblem
    t : array, shape (K,) [mm, rad]
        Half-widths of the design.
    q : array, shape (M, n) [rad, mm]

    Returns
    -------
    array, shape (M,)
    """
    return np.asarray(p_within_radius(_position_cov(problem, t, q), problem.radius_mm))


def _position_cov(problem: AllocationProblem, t, q) -> np.ndarray:
    """Position covariance of design ``t`` at poses ``q`` (M, n), shape (M, 3, 3) [mm^2]."""
    J = problem.model.jacobian(np.atleast_2d(q))[:, :3, :]
    return np.einsum("mik,k,mjk->mij", J, problem.sigma(t) ** 2, J)


def static_joints(problem: AllocationProblem, region: Region, *, n_probe: int = 8, seed: int = 0,
                  rtol: float = 1e-9, pose_cov=None) -> np.ndarray:
    """Joints whose motion never changes the position-error covariance, shape (n,) bool.

    Probed at ``n_probe`` Sobol poses: each joint is moved across its range and the position rows of the
    error Jacobian compared (rotation of the Jacobian about the measuring point changes ``J`` but not
    ``J Σ J^T``, so the covariance with unit sigmas is compared). ``pose_cov`` (a function of poses (M, n) giving
    covariances (M, 3, 3) [mm^2], e.g. a post-calibration covariance) replaces the unit-sigma covariance.
    """
    Q = region.sample(n_probe, seed)
    s2 = np.ones(problem.model.sigma.shape)

    def cov(Qx):
        if pose_cov is not None:
            return pose_cov(Qx)
        J = problem.model.jacobian(Qx)[:, :3, :]
        return np.einsum("mik,k,mjk->mij", J, s2, J)

    base = cov(Q)
    scale = np.abs(base).max()
    out = np.zeros(len(region.q_min), bool)
    for j in range(len(out)):
        if region.q_max[j] == region.q_min[j]:
            out[j] = True
            continue
        Q2 = Q.copy()
        Q2[:, j] = region.q_min[j] + region.q_max[j] - Q[:, j]  # mirror inside the range
        out[j] = np.abs(cov(Q2) - base).max() <= rtol * scale
    return out


def worst_pose(problem: AllocationProblem, t, region: Region, *, n_seed: int = 512, n_starts: int = 6,
               seed: int = 0, fixed: np.ndarray | None = None, pose_cov=None):
    """Pose of the region with the lowest linear ``P`` for the design ``t``.

    ``pose_cov`` (optional): function of poses (M, n) [rad, mm] giving the position covariance (M, 3, 3) [mm^2]
    whose ``P`` is searched instead of the design's (e.g. the post-calibration covariance; ``t`` is then unused).

    Returns
    -------
    q : array, shape (n,) [rad, mm]
    p : float
    evaluations : int
        Poses whose probability was evaluated (seed sample plus local searches; each local step evaluates
        ``2 m + 1`` poses at once: the point and a central difference along each of the ``m`` free joints).
    """
    fixed = np.zeros(len(region.q_min), bool) if fixed is None else fixed
    prob_at = pose_probability if pose_cov is None else (
        lambda pr, _t, Qx: np.asarray(p_within_radius(pose_cov(Qx), pr.radius_mm)))
    free = np.flatnonzero(~fixed)
    mid = 0.5 * (region.q_min + region.q_max)
    Q = region.sample(n_seed, seed)
    Q[:, fixed] = mid[fixed]
    P = prob_at(problem, t, Q)
    n_eval = len(Q)
    best_q, best_p = Q[int(np.argmin(P))].copy(), float(P.min())
    bounds = list(zip(region.q_min[free], region.q_max[free]))
    m = len(free)
    X = np.repeat(mid[None], 2 * m + 1, axis=0)
    step = np.zeros((2 * m + 1, m))
    step[1:m + 1], step[m + 1:] = 1e-6 * np.eye(m), -1e-6 * np.eye(m)

    def f_and_grad(x):  # P and its central-difference gradient in one batched evaluation of 2m + 1 poses
        X[:, free] = x + step
        p = prob_at(problem, t, X)
        return float(p[0]), (p[1:m + 1] - p[m + 1:]) / 2e-6

    for i in np.argsort(P)[:n_starts]:
        r = minimize(f_and_grad, Q[i, free], jac=True, method="L-BFGS-B", bounds=bounds, options={"maxiter": 60})
        n_eval += int(r.nfev) * (2 * m + 1)
        if r.fun < best_p:
            best_p = float(r.fun)
            best_q = mid.copy()
            best_q[free] = r.x
    return best_q, best_p, n_eval


@dataclass(frozen=True, eq=False)
class RegionAllocation:
    """Result of :func:`allocate_region`.

    Attributes
    ----------
    result : AllocationResult
        The allocation on the final active set.
    region : Region
    active_q : array, shape (A, n) [rad, mm]
    rounds : int
    worst_p : float
        Lowest linear P found by the last search.
    worst_q : array, shape (n,)
    evaluations : int
        Probability evaluations of all searches.
    static : array of bool, shape (n,)
        Joints held fixed (cannot change the position error).
    converged : bool
        Worst shortfall below ``tol`` within ``max_rounds``.
    time_s : float
    history : tuple of (round, cost, worst_p)
    """

    result: object
    region: Region
    active_q: np.ndarray
    rounds: int
    worst_p: float
    worst_q: np.ndarray
    evaluations: int
    static: np.ndarray
    converged: bool
    time_s: float
    history: tuple = field(default=())


def allocate_region(model, region: Region, q0=None, *, solver: str = "exact", tol: float = 1e-4,
                    max_rounds: int = 30, seed: int = 0, n_seed: int = 512, n_starts: int = 6,
                    **problem_kw) -> RegionAllocation:
    """Cutting-plane allocation over a box: solve on the active set, add the worst pose, repeat.

    Parameters
    ----------
    model : ErrorModel
    region : Region
    q0 : array, shape (A0, n), optional
        Initial active poses (default: the box centre).
    solver : {"exact", "certified"}
        The design whose worst pose is searched (the certified design is re-solved on every active set,
        so it is certified at every pose the search has added).
    tol : float
        Stop when ``p - worst P < tol``.
    problem_kw
        Passed to :func:`build_problem` (radius_mm, prob, costs, ...).
    """
    from tolalloc.allocate.solve import allocate

    t0 = time.perf_counter()
    active = np.atleast_2d(0.5 * (region.q_min + region.q_max) if q0 is None else np.asarray(q0, float))
    static = None
    evals, hist = 0, []
    for rnd in range(1, max_rounds + 1):
        pr = build_problem(model, active, **problem_kw)
        res = allocate(pr, solver=solver, snap=False)
        d = res.design if solver == "exact" else res.certified
        if not d.ok:  # infeasible (or not converged) on the active set: the caller reports the allocation's diagnosis
            return RegionAllocation(res, region, active, rnd, float("nan"), active[-1], evals,
                                    np.zeros(len(region.q_min), bool), False, time.perf_counter() - t0, tuple(hist))
        if static is None:
            static = static_joints(pr, region, seed=seed)
        q, pw, ne = worst_pose(pr, d.t, region, n_seed=n_seed, n_starts=n_starts, seed=seed + rnd,
                               fixed=static)
        evals += ne
        hist.append((rnd, float(d.cost), pw))
        if pr.prob - pw < tol:
            return RegionAllocation(res, region, active, rnd, pw, q, evals, static, True,
                                    time.perf_counter() - t0, tuple(hist))
        active = np.vstack([active, q])
    return RegionAllocation(res, region, active[:-1], max_rounds, pw, q, evals, static, False,
                            time.perf_counter() - t0, tuple(hist))


@dataclass(frozen=True)
class Coverage:
    """Linear P of a design on a fresh seeded sample of the region.

    Attributes
    ----------
    n : int
    min_p : float
    worst_q : array, shape (k, n)
        The ``k`` lowest-P poses (for nonlinear Monte Carlo).
    n_below : int
    frac_below : float
    frac_below_upper95 : float
        One-sided 95 % Clopper-Pearson upper bound on the fraction of the region below ``p``.
    n_exact : int
        Poses whose exact P was computed; the others are proven above ``p`` and above ``min_p`` by the
        largest-eigenvalue bound ``P >= P(chi2_3 < r^2 / lambda_max)``.
    """

    n: int
    min_p: float
    worst_q: np.ndarray
    n_below: int
    frac_below: float
    frac_below_upper95: float
    n_exact: int = 0

    @property
    def ok(self) -> bool:
        return self.n_below == 0

    def message(self, prob: float) -> str:
        head = (f"coverage: {self.n} fresh poses, min P = {self.min_p:.5f}, {self.n_below} below {prob:g} "
                f"(fraction {self.frac_below:.2e}, 95% upper bound {self.frac_below_upper95:.2e})")
        return head if not self.ok else head + "; none below p"


def coverage(problem: AllocationProblem, t, region: Region, *, n: int = 100_000, seed: int = 12345,
             k_worst: int = 3, tol: float = 1e-4, chunk: int = 20_000, pose_cov=None) -> Coverage:
    """Coverage of a design over a region on a fresh seeded sample (uniform random, not the search's Sobol).

    A pose counts as below when ``P < p - tol``(tol: the search's convergence tolerance). The sample is drawn and
    screened ``chunk`` poses at a time (the same stream as one draw of all ``n``), so memory does not grow with
    ``n``. ``pose_cov`` (optional): function of poses (M, n) giving the position covariance (M, 3, 3) [mm^2] to
    check instead of the design's (e.g. the post-calibration covariance; ``t`` is then unused).
    """
    from tolalloc.exceptions import raise_if_interrupted

    try:
        n_ok = int(n) == n and n >= 1
    except (TypeError, ValueError, OverflowError):
        n_ok = False
    if not n_ok:
        raise TolallocError(f"n: expected a whole number of coverage poses >= 1 (e.g. 1e5), got {n!r}.")
    n, chunk = int(n), max(1, int(chunk))
    rng = np.random.default_rng(seed)
    cov_of = pose_cov if pose_cov is not None else (lambda Qx: _position_cov(problem, t, Qx))
    below, done, p_min = 0, 0, np.inf
    worst_p, worst_q = np.empty(0), np.empty((0, len(region.q_min)))
    for start in range(0, n, chunk):
        raise_if_interrupted()
        Q = region.q_min + rng.random((min(chunk, n - start), len(region.q_min))) * (region.q_max - region.q_min)
        C = cov_of(Q)
        # screen: P(|x| < r) >= P(chi2_3 < r^2 / lambda_max) (the ball contains the lambda_max-sphere's ellipsoid);
        # the exact P is computed in order of this bound until no unevaluated pose can be lower or below p
        lower = chi2.cdf(problem.radius_mm**2 / np.maximum(np.linalg.eigvalsh(C)[:, -1], 1e-300), 3)
        order = np.argsort(lower)
        P = np.full(len(Q), np.nan)
        k = 0
        while k < len(Q) and (lower[order[k]] < problem.prob - tol or lower[order[k]] < p_min):
            idx = order[k:k + 2000]
            P[idx] = p_within_radius(C[idx], problem.radius_mm)
            p_min = min(p_min, float(np.nanmin(P[idx])))
            k += len(idx)
        ev = order[:k]
        below += int(np.sum(P[ev] < problem.prob - tol))
        done += k
        worst_p = np.concatenate([worst_p, P[ev]])
        worst_q = np.concatenate([worst_q, Q[ev]])
        keep = np.argsort(worst_p)[:k_worst]
        worst_p, worst_q = worst_p[keep], worst_q[keep]
    upper = float(beta.ppf(0.95, below + 1, n - below)) if below < n else 1.0
    return Coverage(n, p_min, worst_q, below, below / n, upper, int(done))
