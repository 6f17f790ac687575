"""The convex step of the calibration-aware allocation (:mod:`tolalloc.allocate.calibrated.certified`), built once
and re-solved.

One majorisation-minimisation step minimises the (tangent-majorised) cost subject to the per-pose Schur LMIs::

    [[ diag(omega) + I_w ,  D J_E,i^T                            ],
     [ J_E,i D           ,  b_i I - J_R,i V(u, v) J_R,i^T - C_fixed,i ]]  >= 0

``I_w = D A^T A D`` is the normalised information matrix with the random variances of the previous iterate in the
whitening. Two things keep the step cheap without changing its solution:

* **One compiled problem, re-solved (DPP).** Everything that changes between MM steps -- the tangent slopes and
  offset of the concave cost laws, the information matrix, the upper limits ``u_rand_max`` and ``v_max`` -- is a
  cvxpy ``Parameter`` entering affinely, so the problem is DPP (``is_dcp(dpp=True)``) and cvxpy compiles it once;
  later steps only re-stuff the parameter values.
* **Working set of poses (active-set / cutting-plane).** The interior-point cost grows with the cube of each PSD
  block (``Ke + 3`` rows, one block per pose) and usually only a few working poses are binding. The LMIs are imposed
  on a working set; after each solve the requirement is checked *exactly* at every working pose
  (``lambda_max(Sigma_i) <= b_i``, :func:`pose_ratios`) and every violated pose joins the set and the step is
  re-solved. A solution of the smaller problem that satisfies all poses is feasible for the full problem and optimal
  for a relaxation of it, hence optimal for the full step; an infeasible smaller problem means an infeasible step.
  The set only grows (at most ``P`` rounds), starts from the poses within :data:`START_SHARE` of the worst ratio at
  the starting point and is carried over to the next MM step.
"""

from __future__ import annotations

import warnings

import numpy as np

from tolalloc.calibration.posterior import identification_matrix
from tolalloc.exceptions import interruptible

__all__ = ["StepData", "solve_step", "information", "pose_ratios", "START_SHARE", "CLARABEL_SETTINGS"]

#: Initial working set: the poses whose requirement ratio at the starting point is at least this share of the largest.
START_SHARE = 0.9

#: Clarabel tolerances of the step (the final design is re-checked and repaired, so the rule holds exactly).
CLARABEL_SETTINGS = dict(tol_gap_abs=1e-6, tol_gap_rel=1e-6, tol_feas=1e-7)


class StepData:
    """What the MM steps share: the problem's fixed arrays and the compiled cvxpy problems (by live set and poses).

    Parameters
    ----------
    problem : AllocationProblem
    split : ErrorSplit
    E : array of int (Ke,)
        Estimated (systematic) parameter indices.
    gr : _Grades
        Allocatable repeatability grades (``idx``, ``models``, ``t_ref``, ``z``, ``v_min``).
    start_share : float
        Initial working set: poses with a ratio of at least this share of the largest at the starting point (``0``:
        every pose).
    """

    def __init__(self, problem, split, E, gr, start_share: float = START_SHARE):
        pr, z = problem, problem.costs.z
        self.pr, self.E, self.gr = pr, np.asarray(E, int), gr
        self.role = np.array(pr.costs.role)
        self.s = pr.t_ref / z  # reference sigma (K,)
        self.a_pos = {k: i for i, k in enumerate(pr.alloc)}
        self.R_idx = np.flatnonzero(~split.systematic)
        self.R_alloc = np.array([k for k in self.R_idx if k in self.a_pos], int)
        self.J = pr.J[:, :3, :]  # (P, 3, K)
        self.JEs = self.J[:, :, self.E] * self.s[self.E]  # (P, 3, Ke)
        self.b = np.asarray(pr.blocks[0]["eig_bound"], float)  # (P,)
        fixed_var = np.where(split.systematic, split.random_sigma, 0.0) ** 2  # repeatability variances
        fixed_var[gr.idx] = 0.0
        for k in self.R_idx:
            if k not in self.a_pos:
                fixed_var[k] = (pr.costs.fixed_tol[k] / z) ** 2
        self.C_fixed = np.einsum("pik,k,pjk->pij", self.J, fixed_var, self.J)  # (P, 3, 3)
        if getattr(pr, "extra_cov", None) is not None:  # bought parts (allocate.parts_problem): what calibration leaves
            self.C_fixed, self.b = self.C_fixed + pr.extra_cov, self.b / pr.scale
        # random-part direction of each variable u_j (random-only allocatable) and v_g (grade), (P, 3, 3) each
        self.R_dirs = [self.s[k] ** 2 * np.einsum("pi,pj->pij", self.J[:, :, k], self.J[:, :, k]) for k in self.R_alloc]
        self.G_dirs = [(gr.t_ref[g] / gr.z) ** 2 * np.einsum("pi,pj->pij", self.J[:, :, k], self.J[:, :, k])
                       for g, k in enumerate(gr.idx)]
        self.om_out = np.array([1.0 / pr.u_max[self.a_pos[k]] if self.role[k] == "allocate"
                                else (self.s[k] * z / pr.costs.fixed_tol[k]) ** 2 for k in self.E])
        self.compiled = {}  # (live, poses) -> _StepLMI
        self.start_share = float(start_share)
        self.work = None  # working set of poses, carried over between MM steps

    def random_cov(self, u, v) -> np.ndarray:
        """Random-part and fixed tool covariance at every working pose (P, 3, 3) [mm^2]."""
        C = self.C_fixed.copy()
        for j, k in enumerate(self.R_alloc):
            C += u[self.a_pos[k]] * self.R_dirs[j]
        for g in range(len(self.gr.idx)):
            C += v[g] * self.G_dirs[g]
        return C


def information(data: StepData, split, plan, u_rand_max) -> np.ndarray:
    """Normalised information matrix ``D A^T A D`` (Ke, Ke) with the random variances at ``u_rand_max``."""
    costs, s = data.pr.costs, data.s
    rand_sig = np.where(split.systematic, split.random_sigma, 0.0)
    for k in data.R_idx:
        rand_sig[k] = s[k] * np.sqrt(u_rand_max[data.a_pos[k]]) if k in data.a_pos else costs.fixed_tol[k] / costs.z
    G = identification_matrix(split.with_random_sigma(rand_sig), plan, data.E) * s[data.E]  # (m, Ke)
    return G.T @ G


def pose_ratios(data: StepData, live, info, om, u, v) -> np.ndarray:
    """Exact requirement ratio ``lambda_max(Sigma_i) / b_i`` (P,) of a step's point at every working pose.

    ``Sigma_i = B_i (diag(om) + I_w)^-1 B_i^T + random and fixed parts``, ``B_i = D J_E,i`` on the live columns: the
    Schur LMI of pose ``i`` holds iff the ratio is ``<= 1``. ``om`` (Ke,), ``u`` (Ka,), ``v`` (G,).
    """
    lam = np.diag(om[live]) + info[np.ix_(live, live)]
    B = data.JEs[:, :, live]  # (P, 3, L)
    X = np.linalg.solve(lam, B.reshape(-1, len(live)).T)  # (L, 3P)
    C = np.einsum("pil,lpj->pij", B, X.reshape(len(live), -1, 3)) + data.random_cov(u, v)
    return np.linalg.eigvalsh(0.5 * (C + np.swapaxes(C, 1, 2)))[:, -1] / data.b


class _StepLMI:
    """The step's cvxpy problem on the live columns ``live`` and the poses ``poses``, compiled once (DPP)."""

    def __init__(self, data: StepData, live, poses):
        import cvxpy as cp

        pr, gr, E = data.pr, data.gr, data.E
        self.live, L = live, len(live)
        self.om, self.u, self.v = cp.Variable(L), cp.Variable(len(pr.alloc)), cp.Variable(len(gr.idx))
        self.info = cp.Parameter((L, L), name="information")
        self.u_rand_max = cp.Parameter(len(pr.alloc), name="u_rand_max") if len(data.R_alloc) else None
        self.v_max = cp.Parameter(len(gr.idx), name="v_max") if len(gr.idx) else None
        cost = self._cost(data, cp)
        om, u, v = self.om, self.u, self.v
        cons = [u >= pr.u_min, u <= pr.u_max]
        for i, k in enumerate(E[live]):
            if data.role[k] == "allocate":
                j = data.a_pos[k]
                cons += [om[i] >= 1.0 / pr.u_max[j], om[i] <= 1.0 / pr.u_min[j]]
            else:
                cons.append(om[i] == data.om_out[live[i]])
        for k in data.R_alloc:
            cons.append(u[data.a_pos[k]] <= self.u_rand_max[data.a_pos[k]])
        if len(gr.idx):
            cons += [v >= gr.v_min, v <= self.v_max]
        lam = cp.diag(om) + self.info
        for p in poses:
            S = data.b[p] * np.eye(3) - data.C_fixed[p]
            for j, k in enumerate(data.R_alloc):
                S = S - u[data.a_pos[k]] * data.R_dirs[j][p]
            for g in range(len(gr.idx)):
                S = S - v[g] * data.G_dirs[g][p]
            M = cp.bmat([[lam, data.JEs[p][:, live].T], [data.JEs[p][:, live], S]])
            cons.append(0.5 * (M + M.T) >> 0)
        self.problem = cp.Problem(cp.Minimize(cost), cons)

    def _cost(self, data, cp):
        """Cost expression: exact convex laws; concave ones as tangent ``offset + slope . omega`` (parameters)."""
        pr, gr, E, live = data.pr, data.gr, data.E, self.live
        alloc = [i for i, k in enumerate(E[live]) if data.role[k] == "allocate"]
        self.tangent = [i for i in alloc if _power(pr.costs.models[E[live[i]]]) < 2]
        self.slope = cp.Parameter(len(self.tangent), name="tangent_slope") if self.tangent else None
        self.offset = cp.Parameter(name="tangent_offset")
        cost = self.offset + (self.slope @ self.om[self.tangent] if self.tangent else 0)
        for i in alloc:
            cm = pr.costs.models[E[live[i]]]
            if i not in self.tangent:
                cost += cm.a + cm.b * cp.power(self.om[i], _power(cm) / 2.0)
        for k in data.R_alloc:
            cost += pr.costs.models[k].cost_u(self.u[data.a_pos[k]], "cvxpy")
        if len(gr.idx):
            cost += sum(cm.cost_u(self.v[g], "cvxpy") for g, cm in enumerate(gr.models))
        return cost

    def solve(self, data: StepData, info, om0, u_rand_max, v_max):
        """Set the parameters and solve; ``(omega (L,), u (Ka,), v (G,))`` or ``None`` if not solved."""
        live = self.live
        self.info.value = info[np.ix_(live, live)]
        if self.u_rand_max is not None:
            self.u_rand_max.value = u_rand_max
        if self.v_max is not None:
            self.v_max.value = v_max
        slope, offset = [], 0.0
        for i in self.tangent:
            cm, w0 = data.pr.costs.models[data.E[live[i]]], om0[live[i]]
            k = _power(cm)
            slope.append(cm.b * (k / 2.0) * w0 ** (k / 2.0 - 1.0))
            offset += cm.a + cm.b * w0 ** (k / 2.0) - slope[-1] * w0
        self.offset.value = offset
        if self.tangent:
            self.slope.value = np.array(slope)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            interruptible(self.problem.solve, solver="CLARABEL", **CLARABEL_SETTINGS)
        if self.problem.status not in ("optimal", "optimal_inaccurate") or self.om.value is None:
            return None
        return (np.asarray(self.om.value, float), np.asarray(self.u.value, float) if len(data.pr.alloc) else
                np.zeros(0), np.asarray(self.v.value, float) if len(data.gr.idx) else np.zeros(0))


def _power(cm) -> float:
    """Exponent ``k`` of a cost law in sigma (``reciprocal``: 1): cost ``a + b omega^(k/2)``."""
    return 1.0 if cm.model == "reciprocal" else cm.k


def solve_step(data: StepData, split, plan, om0, u_rand_max, v_max):
    """One convex MM step: returns (omega (Ke,), u (Ka,), v (G,)) or None if infeasible.

    ``split`` carries the graded random parts at ``v_max`` (the whitening); ``v <= v_max``. Parameters that touch
    neither the working poses' position rows nor the information (e.g. rotations about an axis through the tool
    point) drop out of the LMIs exactly; they get their loosest tolerance. The LMIs are imposed on a working set of
    poses grown until every pose holds (module docstring).
    """
    gr = data.gr
    info = information(data, split, plan, u_rand_max)
    mag = np.abs(data.JEs).max(axis=(0, 1)) + np.abs(info).max(axis=0)
    live = np.flatnonzero(mag > 1e-12 * mag.max())
    if data.work is None:  # the starting point's ratios (fixed systematic parameters at their fixed precision)
        om_start = np.where(data.role[data.E] == "allocate", om0, data.om_out)
        ratio = pose_ratios(data, live, info, om_start, u_rand_max, v_max)
        data.work = frozenset(np.flatnonzero(ratio >= data.start_share * ratio.max()).tolist())
    while True:
        key = (tuple(live), tuple(sorted(data.work)))
        if key not in data.compiled:
            data.compiled[key] = _StepLMI(data, live, key[1])
        step = data.compiled[key].solve(data, info, om0, u_rand_max, v_max)
        if step is None:
            return None
        om = data.om_out.copy()
        om[live] = step[0]
        ratio = pose_ratios(data, live, info, om, step[1], step[2])
        add = set(np.flatnonzero(ratio > 1.0).tolist()) - data.work
        if not add:
            break
        data.work = data.work | add
    v_out = np.clip(step[2], gr.v_min, v_max) if len(gr.idx) else np.zeros(0)
    return om, step[1], v_out
