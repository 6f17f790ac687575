"""Exact allocation (CasADi + IPOPT): the Gaussian probability itself as the constraint.

::

    minimise   sum_k c_k(u_k)
    subject to u_min <= u <= u_max,
               P(|x_i| < r) >= p  at every pose i,   x_i ~ N(0, Sigma_i(u))

with ``P`` the differentiable probability of :func:`tolalloc.linear.probability_casadi.p_within_radius_casadi`.
The problem is not convex in general, so IPOPT starts from the certified design (feasible, since
the certified rules imply the constraint) and the result is accepted only if it is feasible by the
exact numpy probability (to 1e-5) and not dearer than the certified design; otherwise the
certified design is returned with the reason (the *guard*).
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from tolalloc.exceptions import signals_deferred
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Design, Solver, make_design

__all__ = ["solve_exact", "FEAS_TOL", "LEBEDEV_ORDER"]

#: Accepted shortfall of the exact probability below p (the CasADi direction rule is accurate to ~1e-6).
FEAS_TOL = 1e-5
_KEEP_ALIVE: list = []
#: Lebedev order of the direction rule inside the NLP (see :mod:`tolalloc.linear.probability_casadi`). Order 41
#: (not the order 65 whose accuracy that module quotes) is ~1.7x faster. Its worst error over random orientations and
#: anisotropies (3000 draws) grows with the largest principal standard deviation s: < 2e-7 at s <= 0.51 r (rank one
#: at p = 0.95), < 3e-6 at 0.75 r, < 3e-5 at r (tests/test_allocate_convergence.py). At low p it matters: rank one
#: at p = 0.7 (s = 0.96 r) errs by up to 1.1e-5, about FEAS_TOL. Every IPOPT result is re-checked with the accurate
#: numpy probability and accepted only within FEAS_TOL of the target (else the guard keeps the certified design),
#: so the rule's error cannot make an "exact" design miss the requirement by more than FEAS_TOL.
LEBEDEV_ORDER = 41


def _build(problem: AllocationProblem, active: dict):
    """IPOPT solver over the poses in ``active`` (block name -> pose indices); returns (solver, lbg)."""
    import casadi as ca

    from tolalloc.linear.probability_casadi import casadi_function

    Ka = len(problem.alloc)
    u = ca.MX.sym("u", Ka)
    f = 0
    for i, k in enumerate(problem.alloc):
        f = f + problem.costs.models[k].cost_u(u[i], "casadi")
    # LEBEDEV_ORDER (41) inside the NLP: cheaper derivatives; every design is re-checked with the accurate
    # p_within_radius below (FEAS_TOL), issue 11
    from tolalloc.acceptance.measures import measure_casadi

    F = casadi_function(LEBEDEV_ORDER)
    g, lbg = [], []
    for b in problem.blocks:
        idx = active[b["name"]]
        if len(idx) == 0:
            continue
        # scale covariances by the eigenvalue bound so the probability function sees O(1) numbers
        s = float(np.max(b["eig_bound"]))
        M = np.concatenate([b["A"][p].reshape(Ka, 9).T for p in idx], 0) / s  # (9m, Ka)
        c0 = np.concatenate([b["C0"][p].reshape(9) for p in idx]) / s
        V = ca.mtimes(ca.DM(M), u) + ca.DM(c0)  # stacked symmetric 3x3 blocks
        rr = b["radius"] / np.sqrt(s)  # every law is of degree one in the standard deviations
        if b.get("measure") is None:
            g += [F(ca.reshape(V[9 * j:9 * j + 9], 3, 3), rr) for j in range(len(idx))]
        else:
            g += [measure_casadi(b["measure"], ca.reshape(V[9 * j:9 * j + 9], 3, 3), rr, b["cycles"], F)
                  for j in range(len(idx))]
        lbg += list(b["target"][idx])
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-9,
            "ipopt.constr_viol_tol": 1e-9, "ipopt.max_iter": 300}
    solver = ca.nlpsol("tolalloc_exact", "ipopt", {"x": u, "f": f, "g": ca.vertcat(*g)}, opts)
    # CasADi caches the derivative functions of the probability function only while something
    # uses them; keeping the last solver alive saves ~0.4 s of regeneration per later build.
    _KEEP_ALIVE[:] = [solver]
    return solver, np.array(lbg)


def _initial_active(problem: AllocationProblem, start: Design | None, n0: int = 6) -> dict:
    """Poses to start with: the ``n0`` lowest-probability poses of the start design and those with a dual."""
    out = {}
    for b in problem.blocks:
        if start is not None and start.ok:
            p = start.p_linear[b["name"]]
            idx = set(np.argsort(p)[:n0].tolist())
            if start.pose_dual is not None and len(problem.blocks) == 1:
                idx |= set(np.flatnonzero(start.pose_dual > 1e-6 * max(start.pose_dual.max(), 1e-300)).tolist())
        else:
            idx = set(range(len(b["target"])))
        out[b["name"]] = np.array(sorted(idx), dtype=int)
    return out


def solve_exact(problem: AllocationProblem, start: Design | None = None, *, max_rounds: int = 8) -> Design:
    """Exact allocation warm-started from ``start`` (the certified design), with the guard.

    Parameters
    ----------
    problem : AllocationProblem
    start : Design, optional
        Certified design; if missing or not optimal, IPOPT starts from the tightest limits.
    max_rounds : int
        Constraint generation: IPOPT first sees the few poses that are nearly active in ``start``;
        poses its solution violates are added and it is solved again (at most ``max_rounds`` times).

    Returns
    -------
    Design
        ``solver`` is ``exact`` when IPOPT converged (``Solve_Succeeded``) to a design feasible by the exact
        probability and not dearer than ``start``. Otherwise (IPOPT did not converge, failed, or its result is
        infeasible or dearer) ``start`` is returned with ``fallback_from = exact`` and the reason in ``message``;
        without a usable ``start`` a non-converged IPOPT point is returned with status ``not_converged``.
    """
    t0 = time.perf_counter()
    u_lo, u_hi = problem.u_min, problem.u_max
    x0 = problem.u_from_t(start.t) if start is not None and start.ok else u_lo.copy()
    active = _initial_active(problem, start)
    u, lam_full, ok, why = None, None, False, "no IPOPT round run (max_rounds = 0)"
    for _ in range(max_rounds):
        solver, lbg = _build(problem, active)
        try:
            with signals_deferred():  # CasADi would trap an interrupt as a solver stop and carry on
                sol = solver(x0=x0, lbx=u_lo, ubx=u_hi, lbg=lbg, ubg=np.full(lbg.shape, 1.0 + 1e-9))
        except RuntimeError as exc:  # pragma: no cover - casadi raises on internal errors
            ok, why, u = False, str(exc), None
            break
        stats = solver.stats()
        why = str(stats.get("return_status", ""))
        ok = bool(stats.get("success", False)) and why == "Solve_Succeeded"
        u = np.clip(np.asarray(sol["x"]).ravel(), u_lo, u_hi)
        # IPOPT ends a hair inside an active bound (~1e-8 relative); put such values on the bound, so that a
        # tolerance at t_max is t_max (and snaps to it, not to one standard step below)
        u = np.where(u >= u_hi * (1 - 1e-7), u_hi, np.where(u <= u_lo * (1 + 1e-7), u_lo, u))
        lam = np.asarray(sol["lam_g"]).ravel()
        # constraint generation: add the poses the reduced problem violates
        probs = problem.probabilities(problem.t_from_u(u))
        added, pos, lam_full = False, 0, np.zeros(problem.n_poses)
        for b in problem.blocks:
            idx = active[b["name"]]
            if b.get("q") is None:  # the working poses' multipliers (acceptance-test blocks have their own poses)
                lam_full[idx] += np.maximum(-lam[pos:pos + len(idx)], 0.0)
            pos += len(idx)
            viol = np.setdiff1d(np.flatnonzero(probs[b["name"]] < b["target"] - FEAS_TOL), idx)
            if viol.size:
                worst = viol[np.argsort(probs[b["name"]][viol])[:max(4, len(idx))]]
                active[b["name"]] = np.union1d(idx, worst)
                added = True
        if not added:
            break
        x0 = u
    dt = time.perf_counter() - t0
    reason = ""
    if u is not None:
        d = make_design(problem, Solver.EXACT, problem.t_from_u(u), pose_dual=lam_full, time_s=dt)
        short = min(float((d.p_linear[b["name"]] - b["target"]).min()) for b in problem.blocks)
        if not ok:
            reason = f"IPOPT did not converge ({why})"
        elif short < -FEAS_TOL:
            reason = f"IPOPT ({why}) ended infeasible by {-short:.2g} in probability"
        elif start is not None and start.ok and d.cost > start.cost * (1 + 1e-9):
            reason = f"IPOPT ({why}) ended dearer than the certified design"
        if not reason:
            return d
    else:
        reason = f"IPOPT failed: {why}"
    if start is not None and start.ok:
        return replace(start, time_s=dt + start.time_s, fallback_from=Solver.EXACT,
                       message=f"guard: {reason}; kept the certified design")
    if u is not None and not ok:
        return replace(d, status=NOT_CONVERGED, message=reason + (
            "" if short >= -FEAS_TOL else f"; infeasible by {-short:.2g} in probability"))
    return Design(Solver.EXACT, "failed", time_s=dt, message=reason)
