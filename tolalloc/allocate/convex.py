"""Certified allocation (cvxpy + Clarabel): trace rule and eigenvalue (LMI) rule.

Both are convex problems in the scaled variances ``u`` (see :mod:`tolalloc.allocate.problem`)::

    minimise   sum_k c_k(u_k)                                 (convex laws of tolalloc.costs)
    subject to u_min <= u <= u_max
               trace: tr Sigma_i(u) / (r^2 / chi2_1^-1(p)) <= 1        for every pose i
               lmi:   Sigma_i(u) / (r^2 / chi2_3^-1(p)) <= I (PSD)      for every pose i

The trace rule implies ``P(|x| < r) >= p`` for every covariance when ``p >= 0.785``
(Szekely & Bakirov 2003: for fixed trace the probability is smallest with all variance on one
axis); the eigenvalue rule implies it for every ``p`` (``|x|^2 <= lambda_max chi2_3``). The
multipliers of the pose constraints say which poses drive the cost; ``sum_i y_i`` is
``-d cost / d ln(budget)``, i.e. ``d cost / d ln r = -2 sum_i y_i``.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from tolalloc.allocate.problem import (NOT_CONVERGED, TRACE_RULE_MIN_P, AllocationProblem, Design, Solver,
                                       block_covariances, make_design)
from tolalloc.exceptions import interruptible

__all__ = ["solve_certified", "solve_rule", "cost_expression"]


def cost_expression(problem: AllocationProblem, x, variable: str = "u"):
    """Total cost of the allocatable parameters as a DCP expression of the scaled variances ``x = u`` or of the
    scaled tolerances ``x = v = sqrt(u) = t / t_ref`` (``variable="v"``), grouped by law: ``b u^-1/2 = b v^-1``,
    ``b u^-k/2 = b v^-k``, ``b exp(-sqrt(u)) = b exp(-v)`` -- convex in either."""
    import cvxpy as cp

    u = x
    half = 1.0 if variable == "v" else 0.5  # the exponent of the variable per unit of t / t_ref
    models = [problem.costs.models[k] for k in problem.alloc]
    const = sum(m.a for m in models)
    terms = []
    groups: dict = {}
    for i, m in enumerate(models):
        key = (m.model, m.k if m.model in ("reciprocal_power", "michael_siddall") else None)
        groups.setdefault(key, []).append(i)
    for (form, k), idx in groups.items():
        b = np.array([models[i].b for i in idx])
        ui = u[idx] if len(idx) < len(models) else u
        if form == "reciprocal":
            terms.append(b @ cp.power(ui, -half))
        elif form == "reciprocal_power":
            terms.append(b @ cp.power(ui, -k * half))
        elif form == "michael_siddall":
            terms.append(b @ cp.exp(-k * half * cp.log(ui) - (ui if variable == "v" else cp.sqrt(ui))))
        else:
            terms.append(b @ cp.exp(-(ui if variable == "v" else cp.sqrt(ui))))
    return const + cp.sum(cp.hstack(terms)) if len(terms) > 1 else const + terms[0]


def solve_rule(problem: AllocationProblem, rule: str, *, verbose: bool = False) -> Design:
    """Solve the certified problem with one rule (``"trace"`` or ``"lmi"``).

    Where the design with every tolerance at its process limit ``t_max`` meets the rule, that design is the optimum
    (every cost law decreases in its tolerance) and is returned without a conic solve.

    Returns
    -------
    Design
        ``status`` ``optimal``, ``infeasible`` (the rule cannot be met within the limits),
        ``not_applicable`` (trace rule with ``p < 0.785``), ``failed``, or ``not_converged`` (Clarabel ended
        ``optimal_inaccurate`` even with its default tolerances, or the repair below did not restore the rule:
        the design is kept for reference, never called certified).
    """
    import cvxpy as cp

    t0 = time.perf_counter()
    solver = Solver(f"certified-{rule}")
    if rule == "trace" and min(b["prob"] for b in problem.blocks) < TRACE_RULE_MIN_P:
        return Design(solver, "not_applicable", message=f"the trace rule is valid only for p >= {TRACE_RULE_MIN_P}")
    if rule_ratio(problem, rule, problem.u_max) <= 1.0:
        # Every cost law decreases in its tolerance, so a design with every tolerance at its process limit that meets
        # the rule is the optimum: no solve, and none of the solver's accuracy limits on such a slack problem.
        return make_design(problem, solver, problem.t_from_u(problem.u_max), pose_dual=np.zeros(problem.n_poses),
                           time_s=time.perf_counter() - t0,
                           message=f"every tolerance at its process limit t_max meets the {rule} rule")
    Ka = len(problem.alloc)
    u_min, u_max = problem.u_min, problem.u_max
    u = cp.Variable(Ka)
    lo, hi = u >= u_min, u <= u_max
    cons = [lo, hi]
    pose_cons = _pose_constraints(problem, rule, u)
    for kind, c in pose_cons:
        cons += [c] if kind == "vector" else c
    prob = cp.Problem(cp.Minimize(cost_expression(problem, u)), cons)
    # tight tolerances; Clarabel's defaults (1e-8) if they end inaccurate, given explicitly: without them a re-solve
    # keeps the previous call's settings and ends inaccurate again
    for tol in (1e-10, 1e-8):
        settings = {"tol_gap_abs": tol, "tol_gap_rel": tol, "tol_feas": tol}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)
                interruptible(prob.solve, solver="CLARABEL", verbose=verbose, **settings)
        except cp.error.SolverError as exc:  # pragma: no cover - solver failure
            return Design(solver, "failed", time_s=time.perf_counter() - t0, message=f"Clarabel failed: {exc}")
        if prob.status != "optimal_inaccurate":
            break
    dt = time.perf_counter() - t0
    if prob.status in ("infeasible", "infeasible_inaccurate"):
        return Design(solver, "infeasible", time_s=dt,
                      message=f"the {rule} rule cannot be met within the process limits")
    if prob.status not in ("optimal", "optimal_inaccurate") or u.value is None:
        return Design(solver, "failed", time_s=dt, message=f"Clarabel status {prob.status}")
    uv, rho = _repair(problem, rule, np.clip(u.value, u_min, u_max))
    pose_dual = np.zeros(problem.n_poses)  # the working poses' (blocks of the acceptance test have their own poses)
    for b, (kind, c) in zip(problem.blocks, pose_cons):
        if b.get("q") is not None:
            continue
        if kind == "vector":
            pose_dual += np.maximum(np.asarray(c.dual_value, float).reshape(-1), 0.0)
        else:
            pose_dual += np.array([max(float(np.trace(ci.dual_value)), 0.0) for ci in c])
    K = len(problem.costs.names)
    bound_dual = np.zeros(K)
    bound_dual[problem.alloc] = np.asarray(lo.dual_value, float) - np.asarray(hi.dual_value, float)
    status, msg = "optimal", ""
    if prob.status != "optimal":
        status, msg = NOT_CONVERGED, f"Clarabel did not converge (status {prob.status})"
    if rho > 1.0:
        status = NOT_CONVERGED
        msg = (msg + "; " if msg else "") + (f"the repair stopped without a successful re-check: the {rule} rule "
                                             f"is exceeded by a factor {rho:.6g}")
    return make_design(problem, solver, problem.t_from_u(uv), pose_dual=pose_dual, bound_dual=bound_dual,
                       time_s=dt, message=msg, status=status)


def _pose_constraints(problem: AllocationProblem, rule: str, u) -> list:
    """The rule's pose constraints per block: ``("vector", c)`` (trace) or ``("psd", [c per pose])`` (lmi)."""
    import cvxpy as cp

    out = []
    for b in problem.blocks:
        A, C0 = b["A"], b["C0"]
        if rule == "trace":
            bound = b["trace_bound"]
            G = np.einsum("pkii->pk", A) / bound[:, None]
            h = 1.0 - np.einsum("pii->p", C0) / bound
            out.append(("vector", G @ u <= h))
        else:
            bound = b["eig_bound"]
            lst = []
            for p in range(A.shape[0]):
                M = A[p].reshape(A.shape[1], 9).T / bound[p]
                S = cp.reshape(M @ u, (3, 3), order="C") + C0[p] / bound[p]
                lst.append(np.eye(3) - S >> 0)
            out.append(("psd", lst))
    return out


def rule_ratio(problem: AllocationProblem, rule: str, u) -> float:
    """Largest ``tr Sigma / trace_bound`` (or ``lambda_max / eig_bound``) over poses and blocks; <= 1 is certified."""
    t = problem.t_from_u(u)
    out = 0.0
    for b in problem.blocks:
        C = block_covariances(problem, b, t)
        if rule == "trace":
            out = max(out, float((np.einsum("pii->p", C) / b["trace_bound"]).max()))
        else:
            out = max(out, float((np.linalg.eigvalsh(C)[:, -1] / b["eig_bound"]).max()))
    return out


def _repair(problem: AllocationProblem, rule: str, u, rounds: int = 3):
    """Scale ``u`` down by the (tiny) excess the solver's tolerance leaves, so the rule holds exactly.

    Returns ``(u, rho)`` with ``rho`` the rule ratio re-checked after the last step (``<= 1``: certified).
    """
    rho = rule_ratio(problem, rule, u)
    for _ in range(rounds):
        if rho <= 1.0:
            break
        u = np.clip(u / (rho * (1 + 1e-12)), problem.u_min, problem.u_max)
        rho = rule_ratio(problem, rule, u)
    return u, rho


def solve_certified(problem: AllocationProblem) -> tuple[Design, Design]:
    """Solve both rules; return ``(kept, other)`` where ``kept`` is the cheaper feasible design."""
    tr = solve_rule(problem, "trace")
    lmi = solve_rule(problem, "lmi")
    cands = [d for d in (tr, lmi) if d.ok]
    if not cands:  # a non-converged design is kept (labelled so) before an infeasible or inapplicable one
        rank = {NOT_CONVERGED: 0, "infeasible": 1, "failed": 2, "not_applicable": 3}
        kept = min((tr, lmi), key=lambda d: rank.get(d.status, 2))
        return kept, (lmi if kept is tr else tr)
    best = min(cands, key=lambda d: d.cost)
    return (best, lmi if best is tr else tr)
