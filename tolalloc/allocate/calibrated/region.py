"""Calibration-aware allocation over a joint-space region: the cutting planes of :mod:`tolalloc.allocate.region` on
the post-calibration covariance.

The calibration's information does not change with the evaluation pose, only the sensitivities do: for a design
``t`` the post-calibration parameter covariance ``S(t)`` (:func:`tolalloc.calibration.posterior.posterior`) is
computed once, and the position covariance at any pose is ``J(q) S(t) J(q)^T``. So the region allocation is the same
loop as without calibration -- solve on a finite active set of poses, search the region for the pose of lowest
post-calibration ``P`` (:func:`tolalloc.allocate.region.worst_pose` with that covariance), add it, repeat until the
worst shortfall found is below ``tol`` -- with the calibrated solvers in the solve step:

1. **certified**: :func:`tolalloc.allocate.calibrated.allocate_calibrated` (eigenvalue rule on the active set,
   re-solved on every active set);
2. **exact**: :func:`tolalloc.allocate.calibrated.exact.solve_calibrated_exact` from the final active set of (1),
   started at the previous exact point, with the region's certified design as the guard's fallback (it meets the
   requirement at every pose the search can find);
3. optionally the same two stages without calibration (the baseline of the saving), with
   :func:`tolalloc.allocate.convex.solve_rule` (LMI) and :func:`tolalloc.allocate.exact.solve_exact`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from tolalloc.allocate.calibrated.certified import CalibratedAllocation, allocate_calibrated
from tolalloc.allocate.calibrated.exact import CalibratedExact, solve_calibrated_exact
from tolalloc.allocate.problem import AllocationProblem, Solver, _block, make_design
from tolalloc.allocate.region import Region, static_joints, worst_pose

__all__ = ["RegionSearch", "problem_at", "design_prob", "cutting_plane", "certified_region", "exact_region", "baseline_region",
           "region_start"]


@dataclass(frozen=True, eq=False)
class RegionSearch:
    """The cutting-plane search of one stage.

    Attributes
    ----------
    active_q : array, shape (A, n) [rad, mm]
        Poses the final solve imposed.
    rounds : int
    worst_p : float
        Lowest linear (post-calibration) ``P`` found by the last search.
    worst_q : array, shape (n,) [rad, mm]
    evaluations : int
        Probability evaluations of all searches.
    converged : bool
        Worst shortfall below ``tol`` within ``max_rounds``.
    time_s : float
    history : tuple of (round, cost, worst_p)
    stop_reason : str
        Why a search that did not converge stopped (``""`` when it converged).
    """

    active_q: np.ndarray
    rounds: int
    worst_p: float
    worst_q: np.ndarray
    evaluations: int
    converged: bool
    time_s: float
    history: tuple = field(default=())
    stop_reason: str = ""


def design_prob(problem: AllocationProblem) -> float:
    """The probability a region design is solved for: the largest per-pose target (``prob`` unless tightened)."""
    return float(np.max(problem.blocks[0]["target"]))


def problem_at(problem: AllocationProblem, q, target=None) -> AllocationProblem:
    """The same position requirement, costs and error model at other poses ``q`` (M, n) [rad, mm].

    ``target`` (M,): per-pose probability targets (default :func:`design_prob` of ``problem`` at every pose).
    """
    q = np.atleast_2d(problem.model.robot.check_q(np.asarray(q, float), "poses"))
    J = problem.model.jacobian(q)
    tgt = np.full(len(q), design_prob(problem)) if target is None else np.asarray(target, float)
    b = _block("position", slice(0, 3), problem.radius_mm, problem.prob, tgt, J, problem.alloc, problem.fixed,
               problem.t_ref, problem.model.sigma, problem.costs.z)
    return replace(problem, q=q, J=J, blocks=[b])


def cutting_plane(problem: AllocationProblem, region: Region, solve, q0, *, tol: float = 1e-4,
                  max_rounds: int = 30, seed: int = 0, n_seed: int = 512, n_starts: int = 6, static=None):
    """Generic loop: ``solve(pr) -> (state, cost, pose_cov)`` on the active set, worst-pose search, add, repeat.

    The search stops when the worst ``P`` found is within ``tol`` of :func:`design_prob` (``prob`` unless the
    problem's targets were tightened, e.g. for a margin over the requirement).

    ``pose_cov`` is the covariance function of the solved design (``None``: the solve failed; the loop stops and
    returns that state). Returns ``(state, RegionSearch, static)``; ``static`` (joints held at mid-range) is
    detected on the first solved design unless given.
    """
    t0 = time.perf_counter()
    active = np.atleast_2d(np.asarray(q0, float))
    evals, hist, state, pw, q = 0, [], None, float("nan"), active[-1]
    for rnd in range(1, max_rounds + 1):
        pr = problem_at(problem, active)
        state, cost, pose_cov = solve(pr)
        if pose_cov is None:
            return state, RegionSearch(active, rnd, float("nan"), active[-1], evals, False,
                                       time.perf_counter() - t0, tuple(hist),
                                       f"no design over the {len(active)} active pose(s) of round {rnd}"), static
        if static is None:
            static = static_joints(pr, region, seed=seed, pose_cov=pose_cov)
        q, pw, ne = worst_pose(pr, None, region, n_seed=n_seed, n_starts=n_starts, seed=seed + rnd, fixed=static,
                               pose_cov=pose_cov)
        evals += ne
        hist.append((rnd, float(cost), pw))
        if design_prob(problem) - pw < tol:
            return state, RegionSearch(active, rnd, pw, q, evals, True, time.perf_counter() - t0, tuple(hist)), static
        active = np.vstack([active, q])
    return state, RegionSearch(active[:-1], max_rounds, pw, q, evals, False, time.perf_counter() - t0,
                               tuple(hist), f"round limit ({max_rounds}) reached"), static


def region_start(problem: AllocationProblem, region: Region) -> np.ndarray:
    """Initial active set: the problem's poses inside the region, else the region's centre, shape (A, n)."""
    inside = np.all((problem.q >= region.q_min - 1e-12) & (problem.q <= region.q_max + 1e-12), axis=1)
    return problem.q[inside] if inside.any() else (0.5 * (region.q_min + region.q_max))[None]


def certified_region(problem, plan, split, region, q0, **kw):
    """Stage 1: certified calibrated designs on growing active sets. Returns ``(CalibratedAllocation, search,
    static)``."""

    def solve(pr):
        cert = allocate_calibrated(pr, plan, split=split)
        if not cert.design.ok:
            return cert, np.nan, None
        return cert, cert.design.cost + cert.grade_cost, cert.post.tool_covariance

    return cutting_plane(problem, region, solve, q0, **kw)


def _on_poses(cert: CalibratedAllocation, pr: AllocationProblem) -> CalibratedAllocation:
    """The design of ``cert`` (same posterior) as a start / fallback on the poses of ``pr``."""
    C = cert.post.tool_covariance(pr.q)
    ratio = float((np.linalg.eigvalsh(C)[:, -1] / pr.blocks[0]["eig_bound"]).max())
    d = make_design(pr, Solver.CALIBRATED_LMI, cert.design.t, time_s=cert.design.time_s, message=cert.design.message,
                    status=cert.design.status)
    base = make_design(pr, cert.baseline.solver, cert.baseline.t) if cert.baseline.ok else cert.baseline
    return replace(cert, problem=pr, design=d, baseline=base, ratio=ratio)


def exact_region(problem, plan, split, region, cert: CalibratedAllocation, q0, static,
                 **kw) -> tuple[CalibratedExact, RegionSearch, np.ndarray]:
    """Stage 2: exact calibrated designs on growing active sets, from ``q0`` (stage 1's active set); the guard's
    fallback is stage 1's design ``cert``. Returns ``(CalibratedExact, search, static)``."""
    last = {"x": None}

    def solve(pr):
        ex = solve_calibrated_exact(_on_poses(cert, pr), plan, split, x0=last["x"])
        if ex.accepted:
            last["x"] = ex.x
        elif not ex.design.ok:
            return ex, np.nan, None
        return ex, ex.cost, ex.post.tool_covariance

    return cutting_plane(problem, region, solve, q0, static=static, **kw)


def baseline_region(problem, region, q0, static, *, exact: bool = True, **kw):
    """The region design without calibration: LMI stage, then (``exact``) the exact stage from its active set.

    Returns ``(lmi Design, search, exact Design or None, search or None)`` (designs on their final active sets).
    """
    from tolalloc.allocate.convex import solve_rule
    from tolalloc.allocate.exact import solve_exact
    from tolalloc.allocate.region import _position_cov

    def cov_of(pr, d):
        return lambda Q: _position_cov(pr, d.t, Q)

    def lmi(pr):
        d = solve_rule(pr, "lmi")
        return d, d.cost, cov_of(pr, d) if d.ok else None

    d_lmi, s_lmi, static = cutting_plane(problem, region, lmi, q0, static=static, **kw)
    if not exact or not d_lmi.ok:
        return d_lmi, s_lmi, None, None

    def ex(pr):
        start = make_design(pr, Solver.CERTIFIED_LMI, d_lmi.t)
        d = solve_exact(pr, start)
        return d, d.cost, cov_of(pr, d) if d.ok else None

    d_ex, s_ex, _ = cutting_plane(problem, region, ex, s_lmi.active_q, static=static, **kw)
    return d_lmi, s_lmi, d_ex, s_ex
