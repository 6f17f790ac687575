"""Exact allocation (CasADi + IPOPT): the Gaussian probability itself as the constraint.

::

    minimise   sum_k c_k(u_k)
    subject to u_min <= u <= u_max,
               P(|x_i| < r) >= p  at every pose i,   x_i ~ N(0, Sigma_i(u))

with ``P`` the differentiable probability of :func:`tolalloc.probability.p_within_radius_casadi`.
The problem is not convex in general, so IPOPT starts from the certified design (feasible, since
the certified rules imply the constraint) and the result is accepted only if it is feasible by the
exact numpy probability (to 1e-6) and not dearer than the certified design; otherwise the
certified design is returned with the reason (the *guard*).
"""

from __future__ import annotations

import time

import numpy as np

from .allocate import AllocationProblem, Design, make_design

__all__ = ["solve_exact", "FEAS_TOL"]

#: Accepted shortfall of the exact probability below p (the CasADi rule is accurate to ~1e-6).
FEAS_TOL = 1e-6


def _build(problem: AllocationProblem):
    import casadi as ca

    from .probability import p_within_radius_casadi

    Ka = len(problem.alloc)
    u = ca.SX.sym("u", Ka)
    f = 0
    for i, k in enumerate(problem.alloc):
        f = f + problem.costs.models[k].cost_u(u[i], "casadi")
    g, lbg = [], []
    for b in problem.blocks:
        A, C0 = b["A"], b["C0"]
        # scale covariances by the eigenvalue bound so the probability function sees O(1) numbers
        s = b["eig_bound"]
        r = b["radius"] / np.sqrt(s)
        for p in range(A.shape[0]):
            M = ca.DM(A[p].reshape(Ka, 9).T / s)
            S = ca.reshape(ca.mtimes(M, u), 3, 3) + ca.DM(C0[p] / s)
            g.append(p_within_radius_casadi(S, r))
            lbg.append(b["prob"])
    nlp = {"x": u, "f": f, "g": ca.vertcat(*g)}
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-10,
            "ipopt.constr_viol_tol": 1e-9, "ipopt.max_iter": 500, "ipopt.mu_strategy": "adaptive",
            "ipopt.warm_start_init_point": "yes", "ipopt.nlp_scaling_method": "gradient-based"}
    return ca.nlpsol("tolalloc_exact", "ipopt", nlp, opts), np.array(lbg)


def solve_exact(problem: AllocationProblem, start: Design | None = None) -> Design:
    """Exact allocation warm-started from ``start`` (the certified design), with the guard.

    Parameters
    ----------
    problem : AllocationProblem
    start : Design, optional
        Certified design; if missing or not optimal, IPOPT starts from the tightest limits.

    Returns
    -------
    Design
        ``solver`` is ``exact``; if IPOPT fails, or its result is infeasible or dearer than ``start``,
        ``start`` is returned relabelled ``exact (fallback: certified-...)`` with the reason in ``message``.
    """
    t0 = time.perf_counter()
    solver, lbg = _build(problem)
    u_lo, u_hi = problem.u_min, problem.u_max
    x0 = problem.u_from_t(start.t) if start is not None and start.ok else u_lo.copy()
    try:
        sol = solver(x0=x0, lbx=u_lo, ubx=u_hi, lbg=lbg, ubg=np.full(lbg.shape, 1.0 + 1e-9))
        stats = solver.stats()
        ok, why = bool(stats.get("success", False)), str(stats.get("return_status", ""))
        u = np.clip(np.asarray(sol["x"]).ravel(), u_lo, u_hi)
        lam = np.asarray(sol["lam_g"]).ravel()
    except RuntimeError as exc:  # pragma: no cover - casadi raises on internal errors
        ok, why, u, lam = False, str(exc), None, None
    dt = time.perf_counter() - t0
    reason = ""
    if u is not None:
        d = make_design(problem, "exact", problem.t_from_u(u), pose_dual=np.maximum(-lam, 0.0), time_s=dt,
                        message="" if ok else f"IPOPT: {why}")
        short = min(float((d.p_linear[b["name"]] - b["prob"]).min()) for b in problem.blocks)
        if short < -FEAS_TOL:
            reason = f"IPOPT ({why}) ended infeasible by {-short:.2g} in probability"
        elif start is not None and start.ok and d.cost > start.cost * (1 + 1e-9):
            reason = f"IPOPT ({why}) ended dearer than the certified design"
        elif not ok and not (start is None or not start.ok):
            # not converged but feasible and cheaper: keep it, say so
            pass
        if not reason:
            return d
    else:
        reason = f"IPOPT failed: {why}"
    if start is not None and start.ok:
        return Design(f"exact (fallback: {start.solver})", "optimal", start.t, start.cost, start.p_linear,
                      start.pose_dual, start.bound_dual, start.at_limit, dt + start.time_s,
                      f"guard: {reason}; kept the certified design")
    return Design("exact", "failed", time_s=dt, message=reason)
