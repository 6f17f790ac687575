"""Exact stage of the calibration-aware allocation: the post-calibration probability itself as the constraint.

::

    minimise   sum_k c_k(u_k) + sum_g c_g(v_g)
    subject to u_min <= u <= u_max,  v_min <= v <= v_start,  u_j <= u_start,j (random-only parts),
               P(|x_i| < r) >= target_i  at every pose i,   x_i ~ N(0, Sigma_i(u, v))

with the post-calibration covariance of :mod:`tolalloc.allocate.calibrated.certified` (normalised coordinates,
``omega_k = 1 / u_k`` for the allocatable systematic parts)::

    Sigma_i = B_i (diag(omega) + I_w)^-1 B_i^T + J_R,i V(u, v) J_R,i^T + C_fixed,i,     B_i = D J_E,i

and ``P`` the differentiable direction rule of :mod:`tolalloc.linear.probability_casadi` (CasADi + IPOPT, as the
uncalibrated exact stage :mod:`tolalloc.allocate.exact`). The cost laws enter exactly (no tangent majoriser).

The information ``I_w`` is whitened with the random variances of the start design, and the random variances are
constrained not to exceed them, so the posterior the NLP sees is never optimistic (the same rule as the certified
majorisation-minimisation). IPOPT starts from the certified calibrated design (feasible: the eigenvalue rule implies
the probability) and sees first the poses that bind there; poses its solution violates are added (constraint
generation). The result is accepted only if IPOPT reports ``Solve_Succeeded``, the design meets every pose's target
by the exact numpy probability of the re-computed posterior (:func:`tolalloc.calibration.posterior.posterior`, to
:data:`~tolalloc.allocate.exact.FEAS_TOL`) and it is not dearer than the certified design; otherwise the certified
design is kept with the reason (the *guard*). A non-converged solve is never labelled optimal.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from tolalloc.allocate.calibrated.certified import CalibratedAllocation, _grades
from tolalloc.allocate.calibrated.step import StepData, information
from tolalloc.allocate.exact import FEAS_TOL, LEBEDEV_ORDER
from tolalloc.allocate.problem import NOT_CONVERGED, Design, Solver, make_design
from tolalloc.calibration.posterior import Posterior, posterior
from tolalloc.exceptions import signals_deferred
from tolalloc.linear.probability import p_within_radius

__all__ = ["CalibratedExact", "solve_calibrated_exact", "post_probabilities"]

_KEEP_ALIVE: list = []


@dataclass(frozen=True, eq=False)
class CalibratedExact:
    """Result of :func:`solve_calibrated_exact`.

    Attributes
    ----------
    design : Design
        ``solver`` ``exact`` when accepted (status ``optimal``); else the certified calibrated design with
        ``fallback_from = exact`` and the guard's reason in ``message``; ``not_converged`` only without a usable
        start.
    grade_t : array, shape (K,) or None
        Repeatability grade bands (NaN where no grade) [mm or rad].
    grade_cost : float
    post : Posterior or None
        Post-calibration statistics at the design's sigmas (and grades).
    p_post : array, shape (P,)
        Post-calibration ``P(|dP| < r)`` at the problem's poses (exact numpy probability).
    nlp_poses : tuple of int
        Poses whose constraints the last IPOPT round imposed (the others were checked and hold).
    ipopt_status : str
    x : array, shape (Ka + G,) or None
        The accepted point ``(u, v)`` (a warm start for a larger pose set).
    """

    design: Design
    grade_t: np.ndarray | None
    grade_cost: float
    post: Posterior | None
    p_post: np.ndarray
    nlp_poses: tuple = ()
    ipopt_status: str = ""
    x: np.ndarray | None = None

    @property
    def accepted(self) -> bool:
        """Whether the exact design was accepted (not the certified fallback, not a non-converged point)."""
        return self.design.ok and self.design.fallback_from is None

    @property
    def cost(self) -> float:
        """Parts plus repeatability grades."""
        return float(self.design.cost + self.grade_cost)


def post_probabilities(problem, split, plan, t, q=None) -> tuple[np.ndarray, Posterior]:
    """Post-calibration ``P(|dP| < r)`` of half-widths ``t`` at poses ``q`` (default the problem's) and the posterior.

    ``split`` carries the random parts (grades set); the systematic priors follow ``t``.
    """
    post = posterior(split.with_model(problem.model_for(t)), plan)
    q = problem.q if q is None else q
    return np.asarray(p_within_radius(post.tool_covariance(q), problem.radius_mm)), post


class _NLP:
    """The IPOPT problem over a set of poses (built per pose set; the data arrays are shared)."""

    def __init__(self, data: StepData, info: np.ndarray, live: np.ndarray, poses, u_rand_max, v_max):
        import casadi as ca

        from tolalloc.linear.probability_casadi import casadi_function

        pr, gr, E = data.pr, data.gr, data.E
        Ka, G, L = len(pr.alloc), len(gr.idx), len(live)
        x = ca.MX.sym("x", Ka + G)
        u, v = x[:Ka], x[Ka:]
        f = 0
        for i, k in enumerate(pr.alloc):
            f = f + pr.costs.models[k].cost_u(u[i], "casadi")
        for g, cm in enumerate(gr.models):
            f = f + cm.cost_u(v[g], "casadi")
        om = [1.0 / u[data.a_pos[E[i]]] if data.role[E[i]] == "allocate" else float(data.om_out[i]) for i in live]
        lam = ca.diag(ca.vertcat(*om)) + ca.DM(info[np.ix_(live, live)])
        s = float(np.max(data.b))  # covariances scaled so the probability function sees O(1) numbers
        B = data.JEs[np.asarray(poses, int)][:, :, live] / np.sqrt(s)  # (m, 3, L)
        X = ca.solve(lam, ca.DM(B.reshape(-1, L).T))  # (L, 3m)
        F = casadi_function(LEBEDEV_ORDER)
        g = []
        for j, p in enumerate(poses):
            S = ca.mtimes(ca.DM(B[j]), X[:, 3 * j:3 * j + 3]) + ca.DM(data.C_fixed[p] / s)
            for jj, k in enumerate(data.R_alloc):
                S = S + u[data.a_pos[k]] * ca.DM(data.R_dirs[jj][p] / s)
            for gg in range(G):
                S = S + v[gg] * ca.DM(data.G_dirs[gg][p] / s)
            g.append(F(S, pr.radius_mm / np.sqrt(s)))
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-9,
                "ipopt.constr_viol_tol": 1e-9, "ipopt.max_iter": 300}
        self.solver = ca.nlpsol("tolalloc_calibrated_exact", "ipopt", {"x": x, "f": f, "g": ca.vertcat(*g)}, opts)
        _KEEP_ALIVE[:] = [self.solver]
        ub_u = pr.u_max.copy()
        for k in data.R_alloc:
            ub_u[data.a_pos[k]] = min(ub_u[data.a_pos[k]], u_rand_max[data.a_pos[k]])
        self.lbx = np.r_[pr.u_min, gr.v_min]
        self.ubx = np.r_[ub_u, v_max]
        self.lbg = np.asarray(pr.blocks[0]["target"], float)[np.asarray(poses, int)]

    def solve(self, x0):
        """``(x, ok, return_status)`` from the start ``x0`` (clipped into the bounds)."""
        x0 = np.clip(x0, self.lbx, self.ubx)
        with signals_deferred():  # CasADi would trap an interrupt as a solver stop and carry on
            sol = self.solver(x0=x0, lbx=self.lbx, ubx=self.ubx, lbg=self.lbg,
                              ubg=np.full(self.lbg.shape, 1.0 + 1e-9))
        st = self.solver.stats()
        why = str(st.get("return_status", ""))
        x = np.clip(np.asarray(sol["x"]).ravel(), self.lbx, self.ubx)
        # IPOPT ends a hair inside an active bound; put such values on it (a tolerance at t_max is t_max)
        x = np.where(x >= self.ubx * (1 - 1e-7), self.ubx, np.where(x <= self.lbx * (1 + 1e-7), self.lbx, x))
        return x, bool(st.get("success", False)) and why == "Solve_Succeeded", why


def _start_point(problem, cert: CalibratedAllocation, gr):
    """``(u (Ka,), v (G,))`` of the certified design."""
    u = problem.u_from_t(cert.design.t)
    v = (cert.grade_t[gr.idx] / gr.t_ref) ** 2 if len(gr.idx) else np.zeros(0)
    return u, v


def solve_calibrated_exact(cert: CalibratedAllocation, plan, split, *, max_rounds: int = 8, n0: int = 6,
                           x0=None) -> CalibratedExact:
    """Exact post-calibration allocation warm-started from the certified calibrated design, with the guard.

    Parameters
    ----------
    cert : CalibratedAllocation
        The certified calibrated design (:func:`tolalloc.allocate.calibrated.allocate_calibrated`) on the problem
        whose poses the exact design must meet; the start and the fallback.
    plan : CalibrationPlan
    split : ErrorSplit
        The split the certified design was allocated with (grades unresolved: their values come from ``cert``).
    max_rounds : int
        IPOPT rounds of the constraint generation.
    n0 : int
        Lowest-probability poses of the start in the first round (with every pose within 10 % of the worst ratio).
    x0 : array, shape (Ka + G,), optional
        IPOPT's start ``(u, v)`` (e.g. the exact design of a smaller pose set); default the certified design. The
        guard still compares with ``cert``.
    """
    t0 = time.perf_counter()
    pr = cert.problem
    gr = _grades(pr, split)
    if not cert.design.ok:
        return CalibratedExact(replace(cert.design, message="no certified calibrated design to start from: "
                                       + cert.design.message), None, 0.0, None, np.zeros(pr.n_poses))
    u0, v0 = _start_point(pr, cert, gr)
    sp0 = gr.split_at(split, v0)
    data = StepData(pr, sp0, split.sys_index, gr, start_share=0.0)
    info = information(data, sp0, plan, u0)
    mag = np.abs(data.JEs).max(axis=(0, 1)) + np.abs(info).max(axis=0)
    live = np.flatnonzero(mag > 1e-12 * mag.max())
    p_start, _ = post_probabilities(pr, sp0, plan, cert.design.t)
    target = np.asarray(pr.blocks[0]["target"], float)
    active = set(np.argsort(p_start - target)[:n0].tolist())
    ratio = np.linalg.eigvalsh(cert.post.tool_covariance(pr.q))[:, -1] / data.b
    active |= set(np.flatnonzero(ratio >= 0.9 * ratio.max()).tolist())
    x0 = np.r_[u0, v0] if x0 is None else np.asarray(x0, float)
    x, ok, why, p_new = None, False, "no IPOPT round run (max_rounds = 0)", None
    Ka = len(pr.alloc)
    for _ in range(max_rounds):
        nlp = _NLP(data, info, live, sorted(active), u0, v0)
        try:
            x, ok, why = nlp.solve(x0)
        except RuntimeError as exc:  # pragma: no cover - casadi raises on internal errors
            x, ok, why = None, False, str(exc)
            break
        t = pr.t_from_u(x[:Ka])
        p_new, _ = post_probabilities(pr, gr.split_at(split, x[Ka:]), plan, t)
        viol = np.setdiff1d(np.flatnonzero(p_new < target - FEAS_TOL), sorted(active))
        if not viol.size:
            break
        active |= set(viol[np.argsort(p_new[viol])[:max(4, len(active))]].tolist())
        x0 = x
    return _accept(cert, plan, split, gr, x, ok, why, p_new, tuple(sorted(active)), time.perf_counter() - t0)


def _accept(cert, plan, split, gr, x, ok, why, p_new, active, dt) -> CalibratedExact:
    """The guard: the exact design if converged, feasible and not dearer; else the certified one with the reason."""
    pr = cert.problem
    Ka = len(pr.alloc)
    target = np.asarray(pr.blocks[0]["target"], float)
    cost_cert = cert.design.cost + cert.grade_cost
    if x is not None:
        t, v = pr.t_from_u(x[:Ka]), x[Ka:]
        p_post, post = post_probabilities(pr, gr.split_at(split, v), plan, t)
        short = float((p_post - target).min())
        cost = float(pr.param_costs(t).sum()) + gr.total(v)
        reason = ""
        if not ok:
            reason = f"IPOPT did not converge ({why})"
        elif short < -FEAS_TOL:
            reason = f"IPOPT ({why}) ended infeasible by {-short:.2g} in post-calibration probability"
        elif cost > cost_cert * (1 + 1e-9):
            reason = f"IPOPT ({why}) ended dearer than the certified calibrated design ({cost:.6g} > {cost_cert:.6g})"
        if not reason:
            grade_t = None
            if len(gr.idx):
                grade_t = np.full(len(pr.model.params), np.nan)
                grade_t[gr.idx] = gr.t_ref * np.sqrt(v)
            d = make_design(pr, Solver.EXACT, t, time_s=dt, message=(
                f"post-calibration probability (IPOPT {why}), poses in the NLP: {len(active)} of {pr.n_poses} "
                f"(all checked); worst P {p_post.min():.5f}"))
            return CalibratedExact(d, grade_t, gr.total(v), post, p_post, active, why, np.asarray(x, float))
    else:
        reason = f"IPOPT failed: {why}"
    p_cert, _ = post_probabilities(pr, gr.split_at(split, _start_point(pr, cert, gr)[1]), plan, cert.design.t)
    d = replace(cert.design, time_s=cert.design.time_s + dt, fallback_from=Solver.EXACT,
                message=f"guard: {reason}; kept the certified calibrated design")
    if not cert.design.ok:  # pragma: no cover - the caller passes a certified start
        d = replace(d, status=NOT_CONVERGED)
    return CalibratedExact(d, cert.grade_t, cert.grade_cost, cert.post, p_cert, active, why)
