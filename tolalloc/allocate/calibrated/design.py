"""Calibration-aware allocation in one call: pose set, trajectory or joint-space box; certified, then exact.

:func:`allocate_with_calibration` validates its arguments (plan against robot, size and header; region against the
joint limits), then

* on a pose set or a trajectory (finite poses): the certified calibrated design
  (:func:`tolalloc.allocate.calibrated.allocate_calibrated`) and the exact stage from it
  (:func:`tolalloc.allocate.calibrated.exact.solve_calibrated_exact`); every pose is checked exactly;
* on a box: both stages by cutting planes over the box (:mod:`tolalloc.allocate.calibrated.region`) and a coverage
  statement on a fresh sample (:func:`tolalloc.allocate.region.coverage` on the post-calibration covariance);

and the same without calibration as the baseline of the saving. The result carries both costs, the region record
and what the end-to-end Monte Carlo (:mod:`tolalloc.verify.calibrated_worst`) needs: the design's split, the plan
and the worst poses.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.allocate.calibrated.certified import CalibratedAllocation, allocate_calibrated, parameter_status
from tolalloc.allocate.calibrated.exact import CalibratedExact, post_probabilities, solve_calibrated_exact
from tolalloc.allocate.calibrated.region import (RegionSearch, baseline_region, certified_region, exact_region,
                                                 problem_at, region_start)
from tolalloc.allocate.problem import AllocationProblem, Design
from tolalloc.allocate.region import Coverage, Region, box_region, coverage
from tolalloc.calibration.check import check_plan
from tolalloc.calibration.split import ErrorSplit, split_errors
from tolalloc.exceptions import TolallocError

__all__ = ["CalibratedDesign", "allocate_with_calibration", "resolve_region"]


@dataclass(frozen=True, eq=False)
class CalibratedDesign:
    """Result of :func:`allocate_with_calibration`.

    Attributes
    ----------
    problem : AllocationProblem
        On the poses of the chosen design (the pose set, the trajectory or the box's final active set).
    plan : CalibrationPlan
    split : ErrorSplit
    region_kind : {"poses", "trajectory", "box"}
    region : Region or None
    certified : CalibratedAllocation
        The certified calibrated design (on its own final active set for a box).
    exact : CalibratedExact or None
        The exact stage (``None`` when not asked for); its ``design`` is the certified one, labelled as the
        fallback, when the guard refused the exact point.
    search, search_exact : RegionSearch or None
        Cutting-plane records of the two stages (box only).
    coverage : Coverage or None
        Post-calibration ``P`` of the chosen design on a fresh sample of the box, or at every pose of a pose set or
        trajectory.
    baseline, baseline_exact : Design or None
        Without calibration: LMI design and exact design over the same poses / box.
    static : array of bool or None
        Joints held at mid-range by the box search.
    time_s : float
    """

    problem: AllocationProblem
    plan: object
    split: ErrorSplit
    region_kind: str
    region: Region | None
    certified: CalibratedAllocation
    exact: CalibratedExact | None
    search: RegionSearch | None
    search_exact: RegionSearch | None
    coverage: Coverage | None
    baseline: Design | None
    baseline_exact: Design | None
    static: np.ndarray | None
    time_s: float

    @property
    def exact_accepted(self) -> bool:
        return self.exact is not None and self.exact.accepted

    @property
    def design(self) -> Design:
        """The chosen design: the exact one if accepted, else the certified one (labelled as a fallback)."""
        return self.exact.design if self.exact is not None else self.certified.design

    @property
    def post(self):
        """Post-calibration statistics of the chosen design."""
        return self.exact.post if self.exact is not None else self.certified.post

    @property
    def ok(self) -> bool:
        """A design that meets the requirement wherever it was checked (certified or exact; coverage clean)."""
        return self.design.ok and (self.coverage is None or self.coverage.ok)

    @property
    def cost_certified(self) -> float:
        return float(self.certified.design.cost + self.certified.grade_cost)

    @property
    def cost_exact(self) -> float | None:
        return self.exact.cost if self.exact_accepted else None

    @property
    def cost(self) -> float:
        return self.cost_exact if self.exact_accepted else self.cost_certified

    @property
    def cost_no_calibration(self) -> float | None:
        """Baseline at the same stage as the chosen design (exact if the calibrated design is exact)."""
        loose = self.certified.grade_cost_loosest
        b = self.baseline_exact if self.exact_accepted and self.baseline_exact is not None else self.baseline
        if b is None or not b.ok or (self.exact_accepted and b.fallback_from is not None):
            return None
        return float(b.cost + loose)

    def check_poses(self, k: int = 3, which: str = "chosen") -> np.ndarray:
        """Poses for the end-to-end Monte Carlo, shape (m, n) [rad, mm]: the lowest-``P`` ones of a design.

        ``which``: ``"chosen"`` (:attr:`design`) or ``"certified"``. Box: the last search's worst pose, (chosen
        design) the ``k`` worst poses of the coverage sample, and the ``k`` active poses of lowest ``P``; pose set or
        trajectory: its ``k`` poses of lowest ``P``.
        """
        if which not in ("chosen", "certified"):
            raise TolallocError(f"which: expected 'chosen' or 'certified', got {which!r}.")
        cert = which == "certified" or self.exact is None
        pr, post, t = ((self.certified.problem, self.certified.post, self.certified.design.t) if cert else
                       (self.problem, self.post, self.design.t))
        p, _ = post_probabilities(pr, post.split, self.plan, t)
        low = pr.q[np.argsort(p)[:k]]
        if self.region_kind != "box":
            return low
        s = self.search if cert else self.search_exact
        cov = self.coverage.worst_q[:k] if self.coverage is not None and not cert else low[:0]
        return _unique_rows(np.concatenate([s.worst_q[None], cov, low]))

    def end_to_end_inputs(self, k: int = 3, which: str = "chosen") -> dict:
        """Keyword arguments of :func:`tolalloc.verify.calibrated.verify_calibration` for a design (``which`` as in
        :meth:`check_poses`)."""
        post = self.certified.post if which == "certified" else self.post
        return {"split": post.split, "plan": self.plan, "q_eval": self.check_poses(k, which),
                "radius_mm": self.problem.radius_mm}

    def worst_p(self) -> float:
        """Lowest post-calibration ``P`` of the chosen design wherever it was evaluated."""
        vals = [self.coverage.min_p] if self.coverage is not None else []
        s = self.search_exact if self.exact_accepted else self.search
        if s is not None:
            vals.append(s.worst_p)
        p, _ = post_probabilities(self.problem, self.post.split, self.plan, self.design.t)
        return float(min(vals + [float(p.min())]))

    def to_frame(self) -> pd.DataFrame:
        """Per parameter: the certified table of :class:`CalibratedAllocation` (``tol_*`` renamed
        ``tol_certified_*``, ``cost`` ``cost_certified``) and, when the exact stage was accepted, ``tol_exact_*``
        (after ``tol_certified_*``), ``sigma_post_calibration_exact_*``, ``cost_exact``, ``status_exact``;
        ``tol_no_calibration_exact_*`` with an exact baseline. Quantities in mm or deg in ``_mm`` / ``_deg`` pairs
        (:func:`tolalloc.units.unit_columns`)."""
        df = self.certified.to_frame().rename(columns={"tol_mm": "tol_certified_mm", "tol_deg": "tol_certified_deg",
                                                       "cost": "cost_certified"})
        model = self.problem.model
        if self.exact_accepted:
            at = df.columns.get_loc("tol_certified_deg") + 1
            for k, (name, values) in enumerate(model.interface_columns("tol_exact", self.exact.design.t).items()):
                df.insert(at + k, name, values)
            df = df.assign(**model.interface_columns("sigma_post_calibration_exact", self.exact.post.sigma_post))
            df["cost_exact"] = self.problem.param_costs(self.exact.design.t)
            df["status_exact"] = parameter_status(self.exact.design, self.exact.post)
        if self.baseline_exact is not None and self.baseline_exact.ok:
            df = df.assign(**model.interface_columns("tol_no_calibration_exact", self.baseline_exact.t))
        return df

    def summary(self) -> dict:
        """JSON-ready summary (see the integration notes of the module)."""
        from tolalloc.allocate.calibrated.summary import summary

        return summary(self)

    def message(self) -> str:
        """The lines a command line prints: region, coverage, designs and costs."""
        from tolalloc.allocate.calibrated.summary import message

        return message(self)


def _unique_rows(Q: np.ndarray) -> np.ndarray:
    keep = []
    for i, q in enumerate(Q):
        if not any(np.allclose(q, Q[j], atol=1e-9) for j in keep):
            keep.append(i)
    return Q[keep]


def resolve_region(robot, region):
    """``(kind, Region or None, poses or None)`` from ``None``, a :class:`Region`, ``"limits"``, a region name of the
    robot file, or poses (M, n) [rad, mm] (a trajectory); checked against the joint limits."""
    if region is None:
        return "poses", None, None
    if isinstance(region, str):
        if region == "limits":
            return "box", box_region(robot, robot.lower, robot.upper, "limits", "region='limits'"), None
        if region in robot.regions:
            lo, hi = robot.regions[region]
            return "box", box_region(robot, lo, hi, region, f"region={region!r}"), None
        known = ", ".join(["limits", *robot.regions])
        raise TolallocError(f"region: {region!r} is not a region of {robot.name}; known: {known}, or give a Region "
                            "(tolalloc.allocate.region.box_region) or an array of poses (a trajectory).")
    if isinstance(region, Region):
        return "box", box_region(robot, region.q_min, region.q_max, region.name, f"region {region.name!r}"), None
    try:
        q = np.asarray(region, dtype=float)
    except (TypeError, ValueError):
        raise TolallocError(f"region: expected None, a Region, 'limits', a region name or poses (M, "
                            f"{robot.n_joints}) [rad, mm]; got {type(region).__name__}.") from None
    if q.ndim != 2 or q.shape[1] != robot.n_joints or not len(q):
        raise TolallocError(f"region: a trajectory must be poses of shape (M, {robot.n_joints}) [rad, mm], got shape "
                            f"{q.shape}.")
    if not np.all(np.isfinite(q)):
        raise TolallocError("region: the trajectory has missing or non-finite joint values; every value must be a "
                            "finite number [rad, mm].")
    return "trajectory", None, np.atleast_2d(robot.check_q(q, "region (trajectory)"))


def _check_args(problem, plan, split, coverage_n, seed, k):
    if not isinstance(problem, AllocationProblem):
        raise TolallocError(f"problem: expected an AllocationProblem (tolalloc.allocate.build_problem), got "
                            f"{type(problem).__name__}.")
    if len(problem.blocks) != 1 or problem.acceptance is not None:
        raise TolallocError("problem: the calibration-aware allocation handles the position requirement only; build "
                            "the problem without angle_radius_deg and without ISO 9283 requirements (acceptance).")
    split = split_errors(problem.model) if split is None else split
    if not isinstance(split, ErrorSplit) or list(split.model.names) != list(problem.model.names):
        raise TolallocError("split: expected the ErrorSplit of the problem's error model (tolalloc.calibration."
                            "split_errors(problem.model, overrides)); it was made for another error model.")
    for name, v, lo in (("coverage_n", coverage_n, 0), ("seed", seed, 0), ("k_worst", k, 1)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
            raise TolallocError(f"{name}: expected a whole number >= {lo}, got {v!r}.")
    return split


def allocate_with_calibration(problem: AllocationProblem, plan, *, split: ErrorSplit | None = None, region=None,
                              exact: bool = True, baseline: bool = True, coverage_n: int = 100_000, seed: int = 0,
                              tol: float = 1e-4, max_rounds: int = 30, k_worst: int = 3,
                              measurement: str | None = None, noise_mm: float | None = None,
                              registration: bool | None = None, design_prob: float | None = None,
                              n_seed: int = 512, n_starts: int = 6) -> CalibratedDesign:
    """Calibration-aware allocation over poses, a trajectory or a box; certified then exact (module docstring).

    Parameters
    ----------
    problem : AllocationProblem
        Position requirement, costs and error model (:func:`tolalloc.allocate.build_problem`); its poses are the pose
        set when ``region`` is None, and the initial active set of a box (those inside it).
    plan : CalibrationPlan
        Position or pose measurements estimating every systematic parameter; written for this robot, with at least
        :func:`tolalloc.calibration.check.min_plan_poses` poses.
    split : ErrorSplit, optional
        Default :func:`tolalloc.calibration.split.split_errors` of the problem's model.
    region : None, Region, "limits", a region name of the robot file, or array (M, n) [rad, mm]
        ``None``: the problem's poses; an array: a trajectory (every pose imposed).
    exact : bool
        Run the exact stage after the certified one.
    baseline : bool
        Also allocate without calibration over the same poses / box (the saving).
    coverage_n : int
        Fresh poses of the box's coverage sample (seeded with ``seed + 12345``); 0: no coverage check.
    tol : float
        Box search: stop when ``p - worst P < tol``; coverage counts a pose below when ``P < p - tol``.
    k_worst : int
        Worst poses kept for the end-to-end check.
    measurement, noise_mm, registration : optional
        When given, they must agree with the plan's header.
    design_prob : float, optional
        Solve for this probability at every pose (in ``[problem.prob, 1)``: a margin for the end-to-end
        demonstration); the requirement checked by the coverage and the verification stays ``problem.prob``.
    n_seed, n_starts : int
        Box search: Sobol seed poses and local searches per round (:func:`tolalloc.allocate.region.worst_pose`).
    """
    t0 = time.perf_counter()
    split = _check_args(problem, plan, split, coverage_n, seed, k_worst)
    for name, v in (("n_seed", n_seed), ("n_starts", n_starts), ("max_rounds", max_rounds)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            raise TolallocError(f"{name}: expected a whole number >= 1, got {v!r}.")
    if isinstance(tol, bool) or not isinstance(tol, (int, float, np.floating)) or not 0 < tol < 1 - problem.prob:
        raise TolallocError(f"tol: expected a probability tolerance in (0, 1 - prob = {1 - problem.prob:g}), e.g. "
                            f"1e-4; got {tol!r}.")
    robot = problem.model.robot
    check_plan(plan, split, measurement=measurement, noise_mm=noise_mm, registration=registration)
    if design_prob is not None:
        dp = float(design_prob) if isinstance(design_prob, (int, float, np.floating)) else np.nan
        if isinstance(design_prob, bool) or not problem.prob <= dp < 1:
            raise TolallocError(f"design_prob: expected a probability in [prob = {problem.prob:g}, 1), got "
                                f"{design_prob!r}.")
        problem = problem_at(problem, problem.q, np.full(problem.n_poses, dp))
    kind, box, traj = resolve_region(robot, region)
    if kind == "box":
        kw = dict(tol=tol, max_rounds=max_rounds, seed=seed, n_seed=n_seed, n_starts=n_starts)
        return _box(problem, plan, split, box, exact, baseline, coverage_n, k_worst, t0, kw)
    pr = problem if traj is None else problem_at(problem, traj)
    cert = allocate_calibrated(pr, plan, split=split)
    ex = solve_calibrated_exact(cert, plan, split) if exact and cert.design.ok else None
    b_ex = None
    if baseline and exact and cert.baseline.ok:
        from tolalloc.allocate.exact import solve_exact

        b_ex = solve_exact(pr, cert.baseline)
    res = CalibratedDesign(pr, plan, split, kind, None, cert, ex, None, None, None,
                           cert.baseline if baseline else None, b_ex, None, 0.0)
    cov = _pose_coverage(res, k_worst, tol) if cert.design.ok else None
    return CalibratedDesign(pr, plan, split, kind, None, cert, ex, None, None, cov, res.baseline, b_ex, None,
                            time.perf_counter() - t0)


def _pose_coverage(res: CalibratedDesign, k: int, tol: float) -> Coverage:
    """Every pose of a pose set / trajectory checked exactly, as a :class:`Coverage` (no sampling)."""
    p, _ = post_probabilities(res.problem, res.post.split, res.plan, res.design.t)
    return _coverage_of(res.problem.q, p, res.problem.prob, k, tol)


def _coverage_of(q: np.ndarray, p: np.ndarray, prob: float, k: int, tol: float) -> Coverage:
    """A :class:`Coverage` of exact probabilities ``p`` (n,) at every pose ``q`` (n, dof): below when ``P < prob - tol``."""
    from scipy.stats import beta

    n = len(p)
    below = int(np.sum(p < prob - tol))
    upper = float(beta.ppf(0.95, below + 1, n - below)) if below < n else 1.0
    return Coverage(n, float(p.min()), q[np.argsort(p)[:k]], below, below / n, upper, n)


def _box(problem, plan, split, box, exact, baseline, coverage_n, k, t0, kw):
    """The box path: certified and exact cutting planes (search settings ``kw``), coverage, baseline."""
    seed, tol = kw["seed"], kw["tol"]
    q0 = region_start(problem, box)
    cert, search, static = certified_region(problem, plan, split, box, q0, **kw)
    ex, search_ex = None, None
    if exact and cert.design.ok:
        ex, search_ex, static = exact_region(problem, plan, split, box, cert, search.active_q, static, **kw)
    b, b_ex = None, None
    if baseline:
        b, _, b_ex, _ = baseline_region(problem, box, q0, None, exact=exact, **kw)  # its own static joints
    pr = problem_at(problem, search_ex.active_q) if ex is not None else cert.problem
    res = CalibratedDesign(pr, plan, split, "box", box, cert, ex, search, search_ex, None, b, b_ex, static, 0.0)
    cov = None
    if res.design.ok and coverage_n:
        cov = coverage(pr, None, box, n=coverage_n, seed=seed + 12345, k_worst=k, tol=tol,
                       pose_cov=res.post.tool_covariance)
    return CalibratedDesign(pr, plan, split, "box", box, cert, ex, search, search_ex, cov, b, b_ex, static,
                            time.perf_counter() - t0)
