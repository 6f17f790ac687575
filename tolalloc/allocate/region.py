"""Allocation over a joint-space region: worst-pose search and cutting planes (issue 13).

The requirement ``P(|dP| < r) >= p`` (and, when the problem has one, the orientation requirement
``P(|dw| < a) >= p_a``) is imposed on a finite *active set* of poses; the region (a box in joint space) is then
searched, per requirement, for the pose where the linear probability falls furthest below its ``p`` (multistart
bounded L-BFGS-B seeded from a scrambled Sobol sample); the worst pose of every requirement that falls more than
``tol`` (default 1e-4) below its ``p`` joins the active set and the allocation is solved again, until every
requirement's worst shortfall found is below ``tol``.

Each requirement is searched on its own: each objective is smooth, whereas the smaller of the two shortfalls
is not, and a round that cuts at the worst pose of each requirement saves the rounds in which one requirement
would wait for the other.

Joints that cannot change the error covariance (e.g. the last joint about the tool axis) are detected from the
error Jacobian (the position block -- and, with an orientation requirement, the rotation block -- of the
covariance does not move when the joint moves) and held at their mid-range: they cost nothing to search.

A coverage statement that can fail (:func:`coverage`, :mod:`tolalloc.allocate.region_coverage`) evaluates the
linear ``P`` of every requirement on a fresh seeded sample of the region and bounds the fraction below ``p`` from
above (one-sided 95 % Clopper-Pearson).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize
from scipy.stats import qmc

from tolalloc.exceptions import TolallocError
from tolalloc.allocate.problem import AllocationProblem, build_problem
from tolalloc.allocate.region_coverage import Coverage, _position_cov, _rotation_cov, coverage
from tolalloc.linear.probability import p_within_angle, p_within_radius

__all__ = ["REGION_TOL", "Region", "box_region", "pose_probability", "pose_angle_probability", "static_joints",
           "worst_pose", "WorstPoses", "search_region", "region_static", "allocate_region", "RegionAllocation", "Coverage", "coverage"]


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
        open_ = ", ".join(j.name for j, a, b in zip(robot.joints, lo, hi) if not np.isfinite(a + b))
        raise TolallocError(f"{where}: the box bounds must be finite numbers; joint(s) {open_} have none (NaN or "
                            "inf); give the joints finite limits in the robot file, or a region of finite bounds (a "
                            "box of the robot file, a pose set or a trajectory).")
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


def pose_angle_probability(problem: AllocationProblem, t, q) -> np.ndarray:
    """Linear ``P(|dw| < a)`` of the design ``t`` at arbitrary poses (batched), for a problem with an orientation
    requirement (``a = problem.angle_radius_rad``).

    Parameters
    ----------
    problem : AllocationProblem
    t : array, shape (K,) [mm, rad]
    q : array, shape (M, n) [rad, mm]

    Returns
    -------
    array, shape (M,)
    """
    if problem.angle_radius_rad is None:
        raise TolallocError("pose_angle_probability: the problem has no orientation requirement; build it with "
                            "angle_radius_deg, or use pose_probability for the position requirement.")
    return np.asarray(p_within_angle(_rotation_cov(problem, t, q), problem.angle_radius_rad))


def static_joints(problem: AllocationProblem, region: Region, *, n_probe: int = 8, seed: int = 0,
                  rtol: float = 1e-9, pose_cov=None, requirement: str = "position") -> np.ndarray:
    """Joints whose motion never changes the position-error (or rotation-error) covariance, shape (n,) bool.

    Probed at ``n_probe`` Sobol poses: each joint is moved across its range and the position rows of the
    error Jacobian compared (rotation of the Jacobian about the measuring point changes ``J`` but not
    ``J Σ J^T``, so the covariance with unit sigmas is compared). ``pose_cov`` (a function of poses (M, n) giving
    covariances (M, 3, 3) [mm^2], e.g. a post-calibration covariance) replaces the unit-sigma covariance.

    ``requirement="orientation"`` compares the rotation rows instead, weighted by seeded random variances in
    [0.5, 2]: with unit sigmas a joint's drive error and its two axis deflections add up to an isotropic rotation
    covariance, which any joint motion turns without changing, so every joint would look static.
    """
    if requirement not in ("position", "orientation"):
        raise TolallocError(f"requirement: expected 'position' or 'orientation', got {requirement!r}.")
    Q = region.sample(n_probe, seed)
    angle = requirement == "orientation"
    rows = slice(3, 6) if angle else slice(0, 3)
    s2 = (np.random.default_rng(seed).uniform(0.5, 2.0, problem.model.sigma.shape) if angle
          else np.ones(problem.model.sigma.shape))

    def cov(Qx):
        if pose_cov is not None and not angle:
            return pose_cov(Qx)
        J = problem.model.jacobian(Qx)[:, rows, :]
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
               seed: int = 0, fixed: np.ndarray | None = None, pose_cov=None, requirement: str = "position"):
    """Pose of the region with the lowest linear ``P`` for the design ``t``.

    ``pose_cov`` (optional): function of poses (M, n) [rad, mm] giving the position covariance (M, 3, 3) [mm^2]
    whose ``P`` is searched instead of the design's (e.g. the post-calibration covariance; ``t`` is then unused).
    ``requirement="orientation"`` searches the orientation ``P(|dw| < a)`` of a problem with an orientation
    requirement instead of the position ``P`` (not with ``pose_cov``).

    Returns
    -------
    q : array, shape (n,) [rad, mm]
    p : float
    evaluations : int
        Poses whose probability was evaluated (seed sample plus local searches; each local step evaluates
        ``2 m + 1`` poses at once: the point and a central difference along each of the ``m`` free joints).
    """
    if requirement == "orientation":
        if pose_cov is not None:
            raise TolallocError("worst_pose: pose_cov is a position covariance; search the orientation requirement "
                                "without it, or search requirement='position'.")
        prob_at = pose_angle_probability
    elif requirement == "position":
        prob_at = pose_probability if pose_cov is None else (
            lambda pr, _t, Qx: np.asarray(p_within_radius(pose_cov(Qx), pr.radius_mm)))
    else:
        raise TolallocError(f"requirement: expected 'position' or 'orientation', got {requirement!r}.")
    fixed = np.zeros(len(region.q_min), bool) if fixed is None else fixed
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
class WorstPoses:
    """The worst pose of each requirement found by one search of the region (:func:`search_region`).

    Attributes
    ----------
    q : array, shape (n,) [rad, mm]
        Lowest position ``P(|dP| < r)`` found, and ``p`` its value.
    p : float
    evaluations : int
        Probability evaluations of the searches (both requirements).
    q_angle : array, shape (n,) or None
        Lowest orientation ``P(|dw| < a)`` found, and ``p_angle`` its value (None without an orientation
        requirement).
    p_angle : float or None
    """

    q: np.ndarray
    p: float
    evaluations: int
    q_angle: np.ndarray | None = None
    p_angle: float | None = None

    def cuts(self, problem: AllocationProblem, tol: float) -> np.ndarray:
        """The poses to add, shape (c, n): the worst pose of each requirement not within ``tol`` of its ``p``
        (position first; none when every requirement holds at its worst pose found)."""
        out = [] if problem.prob - self.p < tol else [self.q]
        if self.p_angle is not None and not problem.angle_prob - self.p_angle < tol:
            if not (out and np.array_equal(out[0], self.q_angle)):
                out.append(self.q_angle)
        return np.reshape(out, (len(out), len(self.q)))

    def history_row(self, rnd: int, cost: float) -> tuple:
        """``(round, cost, worst_p)``, with ``worst_p_angle`` appended when there is an orientation requirement."""
        return (rnd, cost, self.p) if self.p_angle is None else (rnd, cost, self.p, self.p_angle)


def search_region(problem: AllocationProblem, t, region: Region, *, n_seed: int = 512, n_starts: int = 6,
                  seed: int = 0, fixed: np.ndarray | None = None) -> WorstPoses:
    """Search the region for the worst pose of each requirement of ``problem`` for the design ``t``.

    The position requirement is searched by :func:`worst_pose`; with an orientation requirement the orientation
    probability is searched the same way, on its own (same seed poses and starts).
    """
    q, p, ne = worst_pose(problem, t, region, n_seed=n_seed, n_starts=n_starts, seed=seed, fixed=fixed)
    if problem.angle_radius_rad is None:
        return WorstPoses(q, p, ne)
    qa, pa, na = worst_pose(problem, t, region, n_seed=n_seed, n_starts=n_starts, seed=seed, fixed=fixed,
                            requirement="orientation")
    return WorstPoses(q, p, ne + na, qa, pa)


def region_static(problem: AllocationProblem, region: Region, seed: int = 0) -> np.ndarray:
    """Joints held fixed in every search of the region, shape (n,) bool: they change neither the position-error
    covariance nor, with an orientation requirement, the rotation-error covariance (:func:`static_joints`)."""
    static = static_joints(problem, region, seed=seed)
    if problem.angle_radius_rad is not None:
        static &= static_joints(problem, region, seed=seed, requirement="orientation")
    return static


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
        Lowest linear position P found by the last search.
    worst_q : array, shape (n,)
    evaluations : int
        Probability evaluations of all searches.
    static : array of bool, shape (n,)
        Joints held fixed (change neither the position error nor, with an orientation requirement, the rotation
        error covariance).
    converged : bool
        Every requirement's worst shortfall below ``tol`` within ``max_rounds``.
    time_s : float
    history : tuple of (round, cost, worst_p), or (round, cost, worst_p, worst_p_angle) with an orientation
        requirement
    worst_p_angle : float or None
        Lowest linear orientation P found by the last search (None without an orientation requirement).
    worst_q_angle : array, shape (n,) or None
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
    worst_p_angle: float | None = None
    worst_q_angle: np.ndarray | None = None


#: A design holds over the region when no requirement's worst shortfall found is ``tol`` or more below its ``p``
#: (the default of :func:`allocate_region`; a drawing's review accepts the same, :mod:`.tolerance_analysis`).
REGION_TOL = 1e-4


def allocate_region(model, region: Region, q0=None, *, solver: str = "exact", tol: float = REGION_TOL,
                    max_rounds: int = 30, seed: int = 0, n_seed: int = 512, n_starts: int = 6,
                    **problem_kw) -> RegionAllocation:
    """Cutting-plane allocation over a box: solve on the active set, add the worst pose, repeat.

    With an orientation requirement (``angle_radius_deg`` in ``problem_kw``) each round searches both
    requirements (:func:`search_region`) and adds the worst pose of each one that falls short (so up to two poses
    a round); the loop stops when both hold within ``tol`` at the worst poses found.

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
        Stop when ``p - worst P < tol`` (and ``p_a - worst orientation P < tol``).
    problem_kw
        Passed to :func:`build_problem` (radius_mm, prob, angle_radius_deg, angle_prob, costs, ...).
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
            static = region_static(pr, region, seed=seed)
        w = search_region(pr, d.t, region, n_seed=n_seed, n_starts=n_starts, seed=seed + rnd, fixed=static)
        evals += w.evaluations
        hist.append(w.history_row(rnd, float(d.cost)))
        cuts = w.cuts(pr, tol)
        if not len(cuts):
            return RegionAllocation(res, region, active, rnd, w.p, w.q, evals, static, True,
                                    time.perf_counter() - t0, tuple(hist), w.p_angle, w.q_angle)
        solved, active = active, np.vstack([active, cuts])
    return RegionAllocation(res, region, solved, max_rounds, w.p, w.q, evals, static, False,
                            time.perf_counter() - t0, tuple(hist), w.p_angle, w.q_angle)
