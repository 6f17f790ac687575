"""Capability-aware allocation: tolerances for processes that drift (mean shifts) and are required to be capable
(Cpk), or whose achieved spread and shift a fleet measured.

The centred allocation (:mod:`.problem`) takes every error ``e_k ~ N(0, (t_k / z)^2)``. Here a process asked for
``+-t_k`` delivers ``e_k ~ N(mu_k, sigma_k^2)`` with (:class:`Capability`, per parameter or for all)::

    sigma_k = a_k t_k / (z c_k)                   spread: a_k the spread factor (achieved / assumed; 1 by default),
                                                  c_k the required Cpk (1: the centred +-z sigma assumption)
    |mu_k| <= s_k t_k,  s_k = k_k / (z c_k + k_k)  bounded shift of k_k sigma within the Cpk (``shift_sigma``; the
                                                  usual assumption 1.5 sigma with Cpk >= 1.33: sigma <= t / 4,
                                                  |mu| <= 0.27 t)
    mu_k = m_k                                    or an explicit shift [mm, rad] (``mean``, e.g. a fleet's)

and optionally a given mean error ``m0_i`` (3,) [mm] at every pose (``pose_mean_mm``, e.g. bought parts). At pose ``i``
the tool error is ``x_i = m_i + b_i + y_i`` with ``m_i = J_i m + m0_i`` (explicit), ``|b_i| <= sum_k |J_ik| s_k t_k``
(bounded shifts, worst case) and ``y_i ~ N(0, Sigma_i)``. Since ``|x_i| <= |m_i| + |b_i| + |y_i|``, the requirement
``P(|x_i| < r) >= p`` holds when ``P(|y_i| < r - |m_i| - sum_k |J_ik| s_k t_k) >= p``, which the certified rules
guarantee on the reduced radius::

    trace: sqrt(chi2_1^-1(p) tr Sigma_i)       + sum_k |J_ik| s_k t_k + |m_i| <= r      (p >= 0.785)
    lmi:   sqrt(chi2_3^-1(p) lambda_max Sigma_i) + sum_k |J_ik| s_k t_k + |m_i| <= r

In the variables ``v_k = t_k / t_ref_k`` both are second-order-cone (trace) or semidefinite (lmi: the largest
singular value of ``J_i diag(sigma)``) constraints and every cost law of :mod:`.costs` is convex
(``c(u) = b u^-1/2 = b / v`` ...): one convex problem (cvxpy + Clarabel), :func:`solve_capable`. With the defaults
(``a = c = 1``, no shift, no mean) it is the centred certified problem written in ``v`` instead of ``u = v^2``: the
same optimum (tests/test_capability.py).

The probability reported (:func:`capable_probabilities`) is exact where the shifts are explicit (the non-centred ball
probability ``P(|m_i + y_i| < r)``, :func:`tolalloc.linear.probability.p_within_radius` with a mean) and the lower
bound ``P(|y_i| < r - |m_i| - |b_i|max)`` where they are bounded. :func:`rescale_exact` then widens an explicit-shift
design uniformly while the exact probability still meets the target (a design no dearer, exactly feasible).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import chi2

from tolalloc.exceptions import TolallocError, interruptible
from tolalloc.allocate.convex import cost_expression, solve_rule
from tolalloc.allocate.problem import TRACE_RULE_MIN_P, AllocationProblem, Design, Solver, _block, make_design
from tolalloc.linear.probability import p_within_radius

__all__ = ["Capability", "capability_terms", "reduced_problem", "capable_covariances", "pose_means", "shift_bounds",
           "capable_probabilities", "solve_capable", "rescale_exact", "CapableDesign"]


@dataclass(frozen=True)
class Capability:
    """How the processes deliver their tolerances (module docstring).

    Attributes
    ----------
    cpk : float or array (K,)            required Cpk ``c_k`` (> 0; 1: the centred assumption)
    shift_sigma : float or array (K,)    bounded mean shift ``k_k`` in process standard deviations (>= 0)
    spread_factor : array (K,) or None   achieved / assumed spread ``a_k`` (> 0; None: 1)
    mean : array (K,) or None            explicit mean shift per parameter [mm, rad] (None: 0)
    pose_mean_mm : array (P, 3) or None  a given mean tool error at every pose [mm] (None: 0)
    """

    cpk: object = 1.0
    shift_sigma: object = 0.0
    spread_factor: object = None
    mean: object = None
    pose_mean_mm: object = None

    @property
    def bounded(self) -> bool:
        """Whether some shift is only bounded (the reported probability is then a lower bound)."""
        return bool(np.any(np.asarray(self.shift_sigma, float) > 0))


def _per_param(value, names, name: str, *, positive: bool) -> np.ndarray:
    K = len(names)
    a = np.asarray(value, dtype=float)
    try:
        a = np.broadcast_to(a, (K,)).copy()
    except ValueError:
        raise TolallocError(f"capability: {name} expected one value or {K} (one per parameter of the problem), got "
                            f"shape {a.shape}.") from None
    bad = np.flatnonzero(~(np.isfinite(a) & ((a > 0) if positive else (a >= 0))))
    if len(bad):
        which = ", ".join(names[k] for k in bad[:3]) + (" ..." if len(bad) > 3 else "")
        raise TolallocError(f"capability: {name} expected finite values {'> 0' if positive else '>= 0'}, got "
                            f"{a[bad[0]]:g} for {which}.")
    return a


def capability_terms(problem: AllocationProblem, cap: Capability) -> dict:
    """The capability as arrays over the problem's parameters (checked): ``sigma_per_t`` (K,) (``a / (z c)``),
    ``shift_per_t`` (K,) (``s``), ``mean`` (K,) [mm, rad], ``pose_mean`` (P, 3) [mm]."""
    K, P, z = len(problem.costs.names), problem.n_poses, problem.costs.z
    if problem.angle_radius_rad is not None:
        raise TolallocError("capability: the capability-aware allocation handles the position requirement only; "
                            "leave out the orientation requirement (angle_radius_deg).")
    names = list(problem.costs.names)
    c = _per_param(cap.cpk, names, "cpk", positive=True)
    k = _per_param(cap.shift_sigma, names, "shift_sigma", positive=False)
    a = _per_param(1.0 if cap.spread_factor is None else cap.spread_factor, names, "spread_factor", positive=True)
    mean = np.zeros(K) if cap.mean is None else np.asarray(cap.mean, float)
    if mean.shape != (K,) or not np.all(np.isfinite(mean)):
        raise TolallocError(f"capability: mean expected {K} finite shifts [mm, rad] (one per parameter), got shape "
                            f"{mean.shape}.")
    m0 = np.zeros((P, 3)) if cap.pose_mean_mm is None else np.asarray(cap.pose_mean_mm, float)
    if m0.shape != (P, 3) or not np.all(np.isfinite(m0)):
        raise TolallocError(f"capability: pose_mean_mm expected ({P}, 3) finite values [mm] (one per pose), got "
                            f"shape {m0.shape}.")
    return {"sigma_per_t": a / (z * c), "shift_per_t": k / (z * c + k), "mean": mean, "pose_mean": m0}


def _t_fixed(problem: AllocationProblem) -> np.ndarray:
    t = np.zeros(len(problem.costs.names))
    t[problem.fixed] = np.asarray(problem.costs.fixed_tol, float)[problem.fixed]
    return t


def capable_covariances(problem: AllocationProblem, t, cap: Capability) -> np.ndarray:
    """Position covariance of the random part at every pose, ``sigma_k = a_k t_k / (z c_k)``, shape (P, 3, 3)."""
    s = capability_terms(problem, cap)["sigma_per_t"] * np.asarray(t, float)
    J = problem.J[:, :3, :]
    return np.einsum("pik,k,pjk->pij", J, s ** 2, J)


def pose_means(problem: AllocationProblem, cap: Capability) -> np.ndarray:
    """The explicit mean tool error at every pose, ``J_i m + m0_i`` [mm], shape (P, 3)."""
    terms = capability_terms(problem, cap)
    return problem.J[:, :3, :] @ terms["mean"] + terms["pose_mean"]


def shift_bounds(problem: AllocationProblem, t, cap: Capability) -> np.ndarray:
    """The largest displacement the bounded shifts can add at every pose, ``sum_k |J_ik| s_k t_k`` [mm], (P,)."""
    terms = capability_terms(problem, cap)
    return np.linalg.norm(problem.J[:, :3, :], axis=1) @ (terms["shift_per_t"] * np.asarray(t, float))


def capable_probabilities(problem: AllocationProblem, t, cap: Capability) -> tuple[np.ndarray, str]:
    """``(P (P,), kind)``: the probability of the position requirement at every pose -- ``exact`` (explicit shifts:
    ``P(|m_i + y_i| < r)``) or ``lower bound`` (bounded shifts: ``P(|y_i| < r - |m_i| - |b_i|max)``)."""
    C = capable_covariances(problem, t, cap)
    m = pose_means(problem, cap)
    r = problem.radius_mm
    if not cap.bounded:
        return p_within_radius(C, r, mean=m), "exact"
    left = r - np.linalg.norm(m, axis=1) - shift_bounds(problem, t, cap)
    p = np.where(left > 0, p_within_radius(C, np.maximum(left, 1e-300)), 0.0)
    return p, "lower bound"


def _constraints(problem: AllocationProblem, terms: dict, rule: str, v) -> list:
    """The certified rule's pose constraints in ``v = t / t_ref`` (module docstring)."""
    import cvxpy as cp

    a, fx = problem.alloc, problem.fixed
    tf = _t_fixed(problem)
    J = problem.J[:, :3, :]
    norms = np.linalg.norm(J, axis=1)  # (P, K)
    sig_a = terms["sigma_per_t"][a] * problem.t_ref[a]  # sigma per unit v
    sig_f = terms["sigma_per_t"][fx] * tf[fx]
    shift_a = norms[:, a] * (terms["shift_per_t"][a] * problem.t_ref[a])  # (P, Ka) per unit v
    shift_f = norms[:, fx] @ (terms["shift_per_t"][fx] * tf[fx])
    budget = problem.radius_mm - np.linalg.norm(J @ terms["mean"] + terms["pose_mean"], axis=1) - shift_f
    target = problem.blocks[0]["target"]
    q = np.sqrt(chi2.ppf(target, 1 if rule == "trace" else 3))
    r = problem.radius_mm  # constraints divided by r: order one
    cons = []
    for i in range(problem.n_poses):
        beta = (budget[i] - shift_a[i] @ v) / (q[i] * r)  # the largest spread norm the budget leaves
        if rule == "trace":
            spread = cp.norm(cp.hstack([cp.multiply(norms[i, a] * sig_a, v), norms[i, fx] * sig_f]), 2) / r
            cons.append(spread <= beta)
        else:  # ||M||_2 <= beta as the Schur complement [[beta I, M], [M^T, beta I]] >= 0 (Clarabel solves it
            # accurately; cvxpy's sigma_max form ends inaccurate)
            M = J[i][:, a] @ cp.diag(cp.multiply(sig_a / r, v))
            if len(fx):
                M = cp.hstack([M, J[i][:, fx] * (sig_f / r)])
            m = M.shape[1]
            cons.append(cp.bmat([[beta * np.eye(3), M], [M.T, beta * np.eye(m)]]) >> 0)
    return cons


@dataclass(frozen=True, eq=False)
class CapableDesign:
    """A capability-aware design.

    Attributes
    ----------
    design : Design               tolerances ``t`` (K,), cost, solver status (``p_linear``: the centred
                                  probabilities the design would have under the centred assumption)
    capability : Capability
    probability : array, shape (P,)   the position requirement's probability under the capability
    kind : str                    ``exact`` or ``lower bound`` (:func:`capable_probabilities`)
    rule : str                    ``trace`` or ``lmi``
    """

    design: Design
    capability: Capability
    probability: np.ndarray | None
    kind: str
    rule: str

    @property
    def ok(self) -> bool:
        return self.design.ok


def reduced_problem(problem: AllocationProblem, cap: Capability) -> AllocationProblem:
    """The problem of a capability without bounded shifts as a centred one: error columns scaled by ``a / c`` and at
    every pose the radius reduced by the explicit mean, ``r - |m_i|`` (the certified rules' budgets); refused when a
    mean alone reaches the radius."""
    if cap.bounded:
        raise TolallocError("reduced_problem: bounded shifts change the budget with the tolerances; use solve_capable.")
    terms = capability_terms(problem, cap)
    J = problem.J * (terms["sigma_per_t"] * problem.costs.z)[None, None, :]
    left = problem.radius_mm - np.linalg.norm(pose_means(problem, cap), axis=1)
    if np.any(left <= 0):
        i = int(np.argmin(left))
        raise TolallocError(f"capability: the mean error alone is {problem.radius_mm - left[i]:.4g} mm at pose "
                            f"{i + 1}, "
                            f"at or beyond the required radius {problem.radius_mm:g} mm: no tolerances can meet the "
                            "requirement; remove the mean (a design change) or relax the radius.")
    b = problem.blocks[0]
    blk = _block(b["name"], b["rows"], b["radius"], b["prob"], b["target"], J, problem.alloc, problem.fixed,
                 problem.t_ref, problem.model.sigma, problem.costs.z)
    blk["trace_bound"] = left ** 2 / chi2.ppf(b["target"], 1)
    blk["eig_bound"] = left ** 2 / chi2.ppf(b["target"], 3)
    return replace(problem, J=J, blocks=[blk])


def solve_capable(problem: AllocationProblem, cap: Capability, rule: str = "lmi") -> CapableDesign:
    """The cheapest tolerances meeting the requirement under the capability, by the certified ``rule`` (module
    docstring); ``infeasible`` when no design within the process limits meets it. Without bounded shifts the problem
    is the centred one of :func:`reduced_problem`, solved by :func:`tolalloc.allocate.convex.solve_rule`; with them the
    cone program in ``v`` below."""
    import cvxpy as cp

    if rule not in ("trace", "lmi"):
        raise TolallocError(f"rule: expected 'trace' or 'lmi', got {rule!r}.")
    terms = capability_terms(problem, cap)
    if not cap.bounded:
        d = solve_rule(reduced_problem(problem, cap), rule)
        if d.t is not None:
            d = make_design(problem, d.solver, d.t, pose_dual=d.pose_dual, bound_dual=d.bound_dual, time_s=d.time_s,
                            status=d.status, message="; ".join(x for x in ("capability-aware", d.message) if x))
        p, kind = capable_probabilities(problem, d.t, cap) if d.t is not None else (None, "")
        return CapableDesign(d, cap, p, kind, rule)
    solver = Solver.CERTIFIED_TRACE if rule == "trace" else Solver.CERTIFIED_LMI
    t0 = time.perf_counter()
    if rule == "trace" and min(problem.blocks[0]["target"]) < TRACE_RULE_MIN_P:
        return CapableDesign(Design(solver, "not_applicable", message=f"the trace rule is valid only for p >= "
                                    f"{TRACE_RULE_MIN_P}"), cap, None, "", rule)
    v = cp.Variable(len(problem.alloc))
    lo, hi = np.sqrt(problem.u_min), np.sqrt(problem.u_max)
    cons = [v >= lo, v <= hi, *_constraints(problem, terms, rule, v)]
    ref = float(problem.param_costs(problem.t_from_u(np.ones(len(problem.alloc)))).sum())
    scale = 1.0 / ref if np.isfinite(ref) and ref > 0 else 1.0  # an objective of order one: Clarabel ends accurate
    prob = cp.Problem(cp.Minimize(scale * cost_expression(problem, v, variable="v")), cons)
    # tight tolerances, then Clarabel's defaults, then more equilibration: a flat objective (a tolerance at its
    # process limit that hardly moves the tool) can leave the first ones "inaccurate"
    for tol, extra in ((1e-10, {}), (1e-8, {}), (1e-8, {"equilibrate_max_iter": 50})):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            try:
                interruptible(prob.solve, solver="CLARABEL", tol_gap_abs=tol, tol_gap_rel=tol, tol_feas=tol, **extra)
            except cp.error.SolverError as exc:  # pragma: no cover - solver failure
                return CapableDesign(Design(solver, "failed", message=f"Clarabel failed: {exc}"), cap, None, "", rule)
        if prob.status != "optimal_inaccurate":
            break
    dt = time.perf_counter() - t0
    if prob.status in ("infeasible", "infeasible_inaccurate"):
        return CapableDesign(Design(solver, "infeasible", time_s=dt, message=f"the {rule} rule with the capability "
                                    "cannot be met within the process limits"), cap, None, "", rule)
    if prob.status not in ("optimal", "optimal_inaccurate") or v.value is None:
        return CapableDesign(Design(solver, "failed", time_s=dt, message=f"Clarabel status {prob.status}"), cap,
                             None, "", rule)
    vv = _repair(problem, terms, rule, np.clip(v.value, lo, hi))
    status = "optimal" if prob.status == "optimal" and vv is not None else "not_converged"
    vv = np.clip(v.value, lo, hi) if vv is None else vv
    design = make_design(problem, solver, problem.t_from_u(vv ** 2), time_s=dt, status=status,
                         message="capability-aware" + ("" if status == "optimal" else "; the certified rule is not met "
                                                       "exactly after the solver's tolerance (not converged)"))
    p, kind = capable_probabilities(problem, design.t, cap)
    return CapableDesign(design, cap, p, kind, rule)


def _rule_slack(problem, terms, rule, v) -> np.ndarray:
    """``r`` minus the rule's left side at every pose for ``v`` (numpy; >= 0: the certified rule holds)."""
    t = problem.t_from_u(v ** 2)
    J = problem.J[:, :3, :]
    s = terms["sigma_per_t"] * t
    C = np.einsum("pik,k,pjk->pij", J, s ** 2, J)
    target = problem.blocks[0]["target"]
    spread = np.sqrt(chi2.ppf(target, 1) * np.einsum("pii->p", C)) if rule == "trace" else \
        np.sqrt(chi2.ppf(target, 3) * np.linalg.eigvalsh(C)[:, -1])
    shift = np.linalg.norm(J, axis=1) @ (terms["shift_per_t"] * t)
    return problem.radius_mm - np.linalg.norm(J @ terms["mean"] + terms["pose_mean"], axis=1) - shift - spread


def _repair(problem, terms, rule, v):
    """``v`` scaled down by the smallest common factor (bisection) under which the rule holds, undoing the small
    excess the solver's tolerance leaves; None when even the process limits' floor does not hold it."""
    lo_v = np.sqrt(problem.u_min)
    if _rule_slack(problem, terms, rule, v).min() >= 0:
        return v
    if _rule_slack(problem, terms, rule, np.maximum(v * 0.999, lo_v)).min() < 0:
        return None  # more than the solver's tolerance: not a rounding excess
    lo, hi = 0.999, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _rule_slack(problem, terms, rule, np.maximum(v * mid, lo_v)).min() >= 0 else (lo, mid)
    return np.maximum(v * lo, lo_v)


def rescale_exact(problem: AllocationProblem, result: CapableDesign, *, tol: float = 1e-4) -> CapableDesign:
    """An explicit-shift design widened by the largest common factor (the allocatable tolerances, each within its
    process limit) under which the exact probability still meets the target at every pose: never dearer, exactly
    feasible. Refused for bounded shifts (no exact probability)."""
    cap = result.capability
    if cap.bounded:
        raise TolallocError("rescale_exact: the design has bounded shifts, whose exact worst-case probability is not "
                            "computed; only explicit shifts (mean, pose_mean_mm) can be rescaled exactly.")
    if not result.ok:
        return result
    t0, target = result.design.t, problem.blocks[0]["target"]
    a = problem.alloc

    def at(f):
        t = t0.copy()
        t[a] = np.clip(t0[a] * f, problem.t_min[a], problem.t_max[a])
        return t

    def ok(f):
        return bool(np.all(capable_probabilities(problem, at(f), cap)[0] >= target))

    lo, hi = 1.0, 1.0
    while hi < 1e3 and ok(hi * 2) and not np.allclose(at(hi * 2), at(hi)):
        hi *= 2
    hi = hi * 2 if hi < 1e3 else hi
    while hi / lo > 1 + tol:
        mid = np.sqrt(lo * hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    d = replace(make_design(problem, result.design.solver, at(lo), time_s=result.design.time_s,
                            message=f"capability-aware, widened x{lo:.4g} under the exact probability"))
    p, kind = capable_probabilities(problem, d.t, cap)
    return CapableDesign(d, cap, p, kind, result.rule)
