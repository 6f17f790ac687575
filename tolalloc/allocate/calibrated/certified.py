"""Calibration-aware allocation: the cheapest manufacturing tolerances such that, *after* a given calibration,
``P(|dP| < r) >= p`` at every working pose (certified by the eigenvalue rule).

Variables, with ``s_k = t_ref,k / z`` the reference sigma of parameter ``k``:

* systematic parameters (estimated by the plan): normalised prior precision ``omega_k = s_k^2 / sigma_k^2
  = 1 / u_k`` -- the posterior precision ``diag(omega) + D A^T A D`` (``D = diag(s)``) is *affine* in omega;
* random-only parameters (clearances): the scaled variance ``u_k`` of :mod:`tolalloc.allocate.problem`.

Constraint per working pose ``i`` (Schur complement of ``Sigma_post,i <= b I``, ``b = r^2 / chi2_3^-1(p)``)::

    [[ diag(omega) + D A^T A D ,  D J_E,i^T                 ],
     [ J_E,i D                 ,  b I - J_R,i V(u) J_R,i^T - C_fixed,i ]]  >= 0

which is an LMI in (omega, u). Cost laws in omega: ``reciprocal`` ``a + b sqrt(omega)`` and
``reciprocal_power`` with ``k < 2`` are *concave* (minimising them is not a convex problem); they are replaced by
their tangent at the current point -- an upper bound -- and the convex problem is re-solved from the new point
(majorisation-minimisation: every iterate is feasible and certified, the cost never increases; the result is a
local optimum, not a certified global one). ``reciprocal_power`` with ``k >= 2`` is convex and kept exact;
``exponential`` is not supported for systematic parameters.

The calibration's measurements see the random parts as noise; the whitening uses the random variances of the
previous iterate (the first: the process upper limits) and the random variances are constrained not to exceed
them, so the posterior used is never optimistic. The final design is re-checked with
:func:`tolalloc.calibration.posterior.posterior` at the design's own sigmas.

The convex step is :mod:`tolalloc.allocate.calibrated.step`: one cvxpy problem compiled once and re-solved with new
parameters (DPP), its pose LMIs on a working set of poses grown until the requirement holds exactly at every
working pose (the same step solution as with all pose LMIs, at a fraction of the interior-point cost).

Bought parts: a :class:`~tolalloc.allocate.parts_problem.PartsProblem` (the parts chosen, e.g. a
:class:`~tolalloc.allocate.parts_result.PartsAllocation`'s ``problem`` allocated with ``after="compensation"``) adds
its covariance -- the parts' random parts and what the compensation leaves of their systematic ones
(:mod:`tolalloc.errormodel.parts`) -- to the fixed part, and its mean shrinks the radius, in every step and check.

Repeatability grades (``grade`` tables of the costs file's ``[calibration]`` section, see
:mod:`tolalloc.calibration.split`): the random part of a systematic parameter (e.g. a joint's encoder /
transmission repeatability) becomes a decision variable with its own cost law and process limits, in the scaled
variance ``v = (t / t_ref)**2`` of its band ``+-t`` (``sigma = t / z``). It enters the LMI affinely (``- v s_g^2
J_k J_k^T`` in the lower-right block) and the whitening like the random-only parts (at the previous iterate, never
loosened). The no-calibration baseline buys the loosest grade (the requirement without calibration is stated on the
error model's sigmas, which do not include the repeatability).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.allocate.convex import solve_rule
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Design, make_design
from tolalloc.calibration.plan import CalibrationPlan
from tolalloc.allocate.calibrated.step import START_SHARE, StepData, solve_step
from tolalloc.calibration.posterior import Posterior, estimated_index, posterior
from tolalloc.calibration.split import ErrorSplit, split_errors

__all__ = ["CalibratedAllocation", "allocate_calibrated", "CALIBRATED_AWAY_RATIO", "parameter_status"]

#: A systematic part counts as "calibrated away" when its post-calibration sigma is below this share of its prior.
CALIBRATED_AWAY_RATIO = 0.1


@dataclass(frozen=True, eq=False)
class CalibratedAllocation:
    """Result of :func:`allocate_calibrated`.

    Attributes
    ----------
    problem : AllocationProblem
    design : Design
        Calibration-aware design (``solver`` ``calibrated-lmi``).
    baseline : Design
        Certified LMI design without calibration (same problem).
    post : Posterior or None
        Post-calibration statistics at the design's sigmas.
    ratio : float
        Largest ``lambda_max(Sigma_post) / b`` over the poses (``<= 1``: certified).
    iterations : int
    lmi_poses : tuple of int
        Working poses whose Schur LMIs the last step imposed (the others were checked exactly and hold there; see
        :mod:`tolalloc.allocate.calibrated.step`).
    """

    problem: AllocationProblem
    design: Design
    baseline: Design
    post: Posterior | None
    ratio: float
    iterations: int
    grade_t: np.ndarray | None = None
    grade_cost: float = 0.0
    grade_cost_loosest: float = 0.0
    lmi_poses: tuple = ()

    @property
    def certified(self) -> bool:
        return self.design.ok and self.ratio <= 1.0

    def to_frame(self) -> pd.DataFrame:
        """Per parameter: manufactured tolerance, post-calibration sigma, status; baseline tolerance.

        Every quantity in mm or deg has two columns, ``<name>_mm`` (length rows) and ``<name>_deg`` (angle rows),
        the other one empty (:func:`tolalloc.units.unit_columns`, as the workflow's tolerance table); ``unit``
        names the row's unit. Columns: ``parameter, unit, tol_*`` (the manufactured ± half-width),
        ``tol_no_calibration_*`` (the baseline without calibration), ``sigma_manufactured_*``,
        ``sigma_post_calibration_*``, ``sigma_random_*``, ``status``, ``cost`` and, with repeatability grades,
        ``repeatability_grade_*`` and ``repeatability_grade_cost``.

        Status: ``calibrated away`` (post-calibration sigma below :data:`CALIBRATED_AWAY_RATIO` of the manufactured
        one), ``loose (at t_max)`` (not calibrated, but the process's loosest tolerance suffices), else ``must be held`` (``(random)`` for
        random-only parameters).
        """
        pr, m = self.problem, self.problem.model
        base = self.baseline.t if self.baseline.ok else np.full(len(m.params), np.nan)
        cols = {"parameter": m.names, "unit": [p.interface_unit for p in m.params],
                **m.interface_columns("tol", self.design.t),
                **m.interface_columns("tol_no_calibration", base),
                **m.interface_columns("sigma_manufactured", np.sqrt(self.post.prior_var)),
                **m.interface_columns("sigma_post_calibration", self.post.sigma_post),
                **m.interface_columns("sigma_random", np.sqrt(self.post.random_var)),
                "status": parameter_status(self.design, self.post), "cost": pr.param_costs(self.design.t)}
        if self.grade_t is not None:
            cols.update(m.interface_columns("repeatability_grade", self.grade_t))
            cols["repeatability_grade_cost"] = _grades(pr, self.post.split).costs_full(self.grade_t)
        return pd.DataFrame(cols)

    def summary(self) -> dict:
        base = self.baseline.cost + self.grade_cost_loosest if self.baseline.ok else None
        cost = self.design.cost + self.grade_cost
        return {"cost": cost, "cost_parts": self.design.cost, "cost_repeatability_grades": self.grade_cost,
                "cost_no_calibration": base,
                "saving": None if base is None else base - cost,
                "saving_pct": None if base is None else 100 * (base - cost) / base,
                "certified": self.certified, "ratio": self.ratio, "iterations": self.iterations,
                "lmi_poses": [int(p) + 1 for p in self.lmi_poses],
                "unidentifiable": list(self.post.unidentifiable) if self.post is not None else []}


def parameter_status(design: Design, post: Posterior) -> list:
    """Per parameter: ``calibrated away`` (post-calibration sigma below :data:`CALIBRATED_AWAY_RATIO` of the
    manufactured one), ``loose (at t_max)``, else ``must be held`` (``(random)`` for random-only parameters)."""
    sp, prior, postsig = post.split, np.sqrt(post.prior_var), post.sigma_post
    out = []
    for k in range(len(prior)):
        if sp.systematic[k] and postsig[k] <= CALIBRATED_AWAY_RATIO * prior[k]:
            out.append("calibrated away")
        elif design.at_limit[k] == "t_max":
            out.append("loose (at t_max)")
        else:
            out.append("must be held" + ("" if sp.systematic[k] else " (random)"))
    return out


def _check(problem: AllocationProblem, split: ErrorSplit, plan: CalibrationPlan) -> np.ndarray:
    estimated_index(split, plan)  # unknown names first
    if problem.acceptance is not None:
        raise ArgumentError("calibration", "the calibration-aware allocation handles the position requirement only, "
                            "not ISO 9283 requirements; predict their acceptance test after a calibration with "
                            "tolalloc.acceptance.predict_acceptance(..., posterior=...).")
    if len(problem.blocks) != 1:
        raise ArgumentError("calibration", "the calibration-aware allocation handles the position requirement only; "
                            "drop the orientation requirement (`angle_radius_deg`).")
    if plan.estimate is not None:
        raise ArgumentError("calibration", "the allocation needs a plan that estimates every systematic parameter "
                            "(estimate = all); got an explicit list.")
    E = split.sys_index
    for k in E:
        cm = problem.costs.models[k]
        if problem.costs.role[k] == "allocate" and cm.model in ("exponential", "michael_siddall"):
            raise ArgumentError("calibration", f"{problem.model.names[k]} has the {cm.model} cost law, which the "
                                "calibration-aware allocation does not support for systematic parameters; use "
                                "reciprocal or reciprocal_power in the costs file.")
    return E


@dataclass(frozen=True, eq=False)
class _Grades:
    """Allocatable repeatability grades of a split.

    ``idx`` (G,) parameter indices; ``models`` their cost laws; ``t_ref`` (G,) [mm or rad]; ``z`` the costs file's
    sigma factor; ``v_min``, ``v_max`` (G,) process limits of the scaled variance ``v = (t / t_ref)**2``.
    """

    idx: np.ndarray
    models: tuple
    t_ref: np.ndarray
    z: float
    v_min: np.ndarray
    v_max: np.ndarray

    def sigma(self, v) -> np.ndarray:
        """Random-part sigma (G,) [mm or rad] at scaled variances ``v``."""
        return self.t_ref * np.sqrt(np.asarray(v, float)) / self.z

    def split_at(self, split: ErrorSplit, v) -> ErrorSplit:
        """``split`` with the graded random parts at ``v``."""
        rnd = split.random_sigma.copy()
        rnd[self.idx] = self.sigma(v)
        return split.with_random_sigma(rnd)

    def costs_full(self, t_full) -> np.ndarray:
        """Cost per parameter (K,) of bands ``t_full`` (NaN where a parameter has no grade)."""
        out = np.full(len(t_full), np.nan)
        for g, k in enumerate(self.idx):
            out[k] = float(self.models[g].cost(t_full[k]))
        return out

    def total(self, v) -> float:
        """Total cost of the grades at ``v``."""
        t = self.t_ref * np.sqrt(np.asarray(v, float))
        return float(sum(float(cm.cost(tg)) for cm, tg in zip(self.models, t)))


def _grades(problem: AllocationProblem, split: ErrorSplit) -> _Grades:
    """Resolve the split's grade tables into cost models (costs-file syntax and checks)."""
    from tolalloc.allocate.costs import _cost_model
    from tolalloc.allocate.costs_entries import _check_entry

    idx = split.graded
    models = []
    for k in idx:
        p = problem.model.params[k]
        where = f"calibration grade of {p.name}"
        entry = split.grade[k]
        _check_entry(entry, where)
        bad = [key for key in entry if key in ("fixed", "exclude") or key.startswith("tol_")]
        if bad:
            raise TolallocError(f"{where}: {', '.join(bad)} has no meaning for a grade; give model, a, b, k, "
                                f"t_ref_{p.interface_unit}, t_min_{p.interface_unit}, t_max_{p.interface_unit}.")
        models.append(_cost_model(entry, p, where))
    t_ref = np.array([cm.t_ref for cm in models])
    return _Grades(idx, tuple(models), t_ref, float(problem.costs.z),
                   np.array([(cm.t_min / cm.t_ref) ** 2 for cm in models]),
                   np.array([(cm.t_max / cm.t_ref) ** 2 for cm in models]))


def allocate_calibrated(problem: AllocationProblem, plan: CalibrationPlan, *, split: ErrorSplit | None = None,
                        max_iter: int = 8, rtol: float = 1e-3, pose_screening: bool = True) -> CalibratedAllocation:
    """Calibration-aware certified allocation (see the module docstring).

    Parameters
    ----------
    problem : AllocationProblem
        From :func:`tolalloc.allocate.problem.build_problem` (position requirement only).
    plan : CalibrationPlan
        Must estimate every systematic parameter (``estimate = all``).
    split : ErrorSplit, optional
        Default :func:`tolalloc.calibration.split.split_errors` of the problem's model.
    max_iter : int
        Majorisation-minimisation iterations.
    rtol : float
        Stop when the cost changes by less than this fraction.
    pose_screening : bool
        Impose the pose LMIs on a working set grown until every pose holds (default; same design, faster); ``False``
        imposes all of them in every step (the reference formulation, for tests and the benchmark).
    """
    t0 = time.perf_counter()
    split = split or split_errors(problem.model)
    E = _check(problem, split, plan)
    gr = _grades(problem, split)
    baseline = solve_rule(problem, "lmi")
    pr = problem
    a_pos = {k: i for i, k in enumerate(pr.alloc)}
    u_start = pr.u_from_t(baseline.t) if baseline.ok else pr.u_max.copy()
    om0 = np.array([1.0 / u_start[a_pos[k]] if k in a_pos else 1.0 for k in E])
    u_rand_max, v_max = pr.u_max.copy(), gr.v_max.copy()
    best, v_best, last_cost, it = None, v_max, np.inf, 0
    data = StepData(pr, split, E, gr, start_share=START_SHARE if pose_screening else 0.0)
    for it in range(1, max_iter + 1):
        step = solve_step(data, gr.split_at(split, v_max), plan, om0, u_rand_max, v_max)
        if step is None:
            break
        om, u, v = step
        for i, k in enumerate(E):
            if k in a_pos:
                u[a_pos[k]] = 1.0 / om[i]
        u = np.clip(u, pr.u_min, pr.u_max)
        t = pr.t_from_u(u)
        cost = float(pr.param_costs(t).sum()) + gr.total(v)
        best, v_best = t, v
        om0 = np.maximum(om, 1e-12)
        u_rand_max = np.where(np.isin(pr.alloc, split.sys_index), pr.u_max, u)
        v_max = v
        if abs(last_cost - cost) <= rtol * max(cost, 1e-12):
            break
        last_cost = cost
    dt = time.perf_counter() - t0
    if best is None:
        return CalibratedAllocation(pr, Design("calibrated-lmi", "infeasible", time_s=dt,
                                               message="no design meets the requirement after this calibration "
                                                       "within the process limits"), baseline, None, np.inf, it)
    best, ratio, post = _repair(pr, gr.split_at(split, v_best), plan, best)
    ok = ratio <= 1.0  # the repair re-checked the rule; otherwise the design is not called certified
    lmi_poses = tuple(sorted(data.work))
    msg = (f"majorisation-minimisation, {it} iteration(s), pose LMIs on {len(lmi_poses)} of {pr.n_poses} poses (all "
           "checked): a certified local optimum" if ok else "the repair stopped without a successful re-check: the "
           f"rule is exceeded by a factor {ratio:.6g}")
    design = make_design(pr, "calibrated-lmi", best, time_s=time.perf_counter() - t0,
                         status="optimal" if ok else NOT_CONVERGED, message=msg)
    grade_t = None
    if len(gr.idx):
        grade_t = np.full(len(pr.model.params), np.nan)
        grade_t[gr.idx] = gr.t_ref * np.sqrt(v_best)
    return CalibratedAllocation(pr, design, baseline, post, ratio, it, grade_t, gr.total(v_best), gr.total(gr.v_max),
                                lmi_poses)


def post_ratio(problem: AllocationProblem, split: ErrorSplit, plan: CalibrationPlan, t):
    """``max_i lambda_max(Sigma_post(q_i)) / b`` of half-widths ``t`` and the :class:`Posterior`."""
    model = problem.model_for(t)
    post = posterior(split.with_model(model), plan)
    C, b = post.tool_covariance(problem.q), problem.blocks[0]["eig_bound"]
    if getattr(problem, "extra_cov", None) is not None:  # bought parts: their covariance, the radius their mean leaves
        C, b = C + problem.extra_cov, b / problem.scale
    return float((np.linalg.eigvalsh(C)[:, -1] / b).max()), post


def _repair(problem, split, plan, t):
    """Tighten the allocatable tolerances by the (tiny) excess the solver tolerance leaves, so the rule holds."""
    ratio, post = post_ratio(problem, split, plan, t)
    for _ in range(5):
        if ratio <= 1.0:
            break
        u = problem.u_from_t(t) / (ratio * (1 + 1e-9))
        t = problem.t_from_u(np.clip(u, problem.u_min, problem.u_max))
        ratio, post = post_ratio(problem, split, plan, t)
    return t, ratio, post
