"""The simulated calibrations of :func:`tolalloc.verify.calibrated.verify_calibration`: chains, readings, fits.

:class:`_PlanChains` evaluates the model's chain program (:class:`~tolalloc.errormodel.chain.FastChain`) at fixed
poses for many parameter sets; :func:`_measure` turns the unknowns (systematic parts, tracker registration and
target offset) into tracker readings; :func:`_fit` is the batched MAP fit of the unknowns to the readings
(Gauss-Newton on the exact residuals with the nominal Jacobian, restarted with the Jacobian at the estimate,
:func:`_exact_step`, where a fit's step stops contracting), iterated up to ``_MAX_ITER`` times or until the
normalised step is below ``_STEP_TOL``.
"""

from __future__ import annotations

import numpy as np

from tolalloc.calibration.plan import CalibrationPlan
from tolalloc.calibration.posterior import nuisance_columns
from tolalloc.errormodel.chain import FastChain
from tolalloc.robot.lie import exp_so3

__all__ = []

#: Gauss-Newton iteration cap and step tolerance (normalised units) of the simulated calibrations.
_MAX_ITER, _STEP_TOL = 30, 1e-8


class _PlanChains:
    """The chain program at fixed poses ``q`` (M, n), evaluated by :class:`FastChain` for many parameter sets.

    The pose programs are built once; each evaluation runs them on a structure-of-arrays block of samples.
    """

    def __init__(self, model, q: np.ndarray):
        self.chain = FastChain(model)
        self.progs = [self.chain.program(qm) for qm in np.asarray(q, float)]
        self.K = self.chain.K

    def tool(self, values: np.ndarray, extra: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Exact tool positions (B, M, 3) and rotations (B, M, 3, 3).

        ``values`` (B, K) [mm, rad] are the same at every pose; ``extra`` (B, M, K), if given, is added per pose.
        """
        B, M = len(values), len(self.progs)
        p, R = np.empty((B, M, 3)), np.empty((B, M, 3, 3))
        X = np.empty((3, 4, B))
        work = FastChain.workspace(B)
        V = np.ascontiguousarray(values.T)
        for m, prog in enumerate(self.progs):
            Vm = V if extra is None else np.ascontiguousarray((values + extra[:, m]).T)
            self.chain.run(prog, Vm, X, work)
            p[:, m] = X[:, 3].T
            R[:, m] = np.moveaxis(X[:, :3], 2, 0)
        return p, R


def _measure(chains: _PlanChains, x: np.ndarray, E: np.ndarray, extra: np.ndarray | None = None) -> np.ndarray:
    """Tracker readings (B, M, 3) predicted from unknowns x (B, Ke + 9) (random parts ``extra`` (B, M, K) optional)."""
    vals = np.zeros((len(x), chains.K))
    vals[:, E] = x[:, : len(E)]
    p, R = chains.tool(vals, extra)
    reg = x[:, len(E):]
    if reg.shape[1] == 0:  # registration known (not estimated)
        return p
    p = p + np.einsum("bmij,bj->bmi", R, reg[:, 6:9])
    Rr = exp_so3(reg[:, 0:3])
    return np.einsum("bij,bmj->bmi", Rr, p) + reg[:, None, 3:6]


def _exact_step(chains, E, xa, r, y, scale, prior_prec, noise_mm, h: float = 1e-6) -> np.ndarray:
    """Gauss-Newton step (normalised, (b, D)) with the Jacobian at ``xa`` (forward differences of the exact
    residuals ``r`` (b, 3M), step ``h`` prior sigmas): ``(J^T J + Lambda0) dx = -(J^T r + Lambda0 x)``."""
    b, D = xa.shape
    xp = (xa[:, None, :] + np.diag(h * scale)[None]).reshape(b * D, D)  # all D perturbations in one batch
    rp = (_measure(chains, xp, E).reshape(b, D, -1) - y.reshape(b, 1, -1)) / noise_mm
    J = np.swapaxes(rp - r[:, None, :], 1, 2) / h  # (b, 3M, D)
    H = np.einsum("bmi,bmj->bij", J, J) + np.diag(prior_prec)
    H += 1e-12 * np.trace(H, axis1=1, axis2=2)[:, None, None] / D * np.eye(D)
    g = np.einsum("bmi,bm->bi", J, r) + prior_prec * (xa / scale)
    return -np.linalg.solve(H, g[..., None])[..., 0]


def _fit(chains: _PlanChains, model, E, prior_sd, plan: CalibrationPlan, y: np.ndarray, *, max_iter: int = _MAX_ITER,
         tol: float = _STEP_TOL):
    """Batched MAP fit of the unknowns (B, Ke + 9) to the readings ``y`` (B, M, 3).

    Gauss-Newton on the exact residuals (evaluated by :class:`FastChain`), every robot started at the nominal model
    and iterated until its normalised step is below ``tol`` (converged robots leave the batch). First with the
    Jacobian fixed at the nominal model (error Jacobian and registration/target columns, the same for every robot,
    factorised once): its fixed point solves ``J0^T r(x) + Lambda0 x = 0``, the exact MAP ``J(x)^T r(x) + Lambda0 x
    = 0``; they differ by ``O(|x| sigma_m)`` -- second order. A robot whose step stops contracting (large errors:
    the fixed-Jacobian iteration converges slowly or diverges) restarts from the nominal model with the Jacobian
    at the current estimate (forward differences, :func:`_exact_step`), which solves the exact MAP equations.

    Returns
    -------
    x : array, shape (B, Ke + 9)
    steps : array, shape (B,)
        Last normalised step of each robot (converged: below ``tol``).
    iters : array of int, shape (B,)
        Gauss-Newton iterations per robot, both phases (``max_iter`` where it did not converge).
    exact : array of bool, shape (B,)
        Robots fitted with the Jacobian at the estimate.
    """
    nN = 9 if plan.registration else 0
    B, D = len(y), len(E) + nN
    scale = np.r_[prior_sd, np.full(3, 1e-3), np.full(6, 1.0)][:D]
    J0 = model.jacobian(plan.q)[:, :3, E]
    if nN:
        J0 = np.concatenate([J0, nuisance_columns(model, plan.q, 3)], axis=2)
    J0 = J0.reshape(-1, D) * scale / plan.noise_mm  # (3M, D) per normalised unit
    prior_prec = np.r_[np.ones(len(E)), np.zeros(nN)]  # normalised by the prior sigma
    A = J0.T @ J0 + np.diag(prior_prec)
    A += 1e-12 * np.trace(A) / D * np.eye(D)
    Ainv = np.linalg.inv(A)  # D x D, symmetric positive definite; one small product per step
    x = np.zeros((B, D))
    iters = np.full(B, max_iter)
    steps = np.full(B, np.inf)
    exact = np.zeros(B, bool)
    live = np.arange(B)
    for it in range(1, max_iter + 1):
        xa = x[live]
        r = (_measure(chains, xa, E) - y[live]).reshape(len(live), -1) / plan.noise_mm  # (b, 3M)
        dxn = -(r @ J0 + prior_prec * (xa / scale)) @ Ainv
        ex = exact[live]
        if ex.any():
            dxn[ex] = _exact_step(chains, E, xa[ex], r[ex], y[live[ex]], scale, prior_prec, plan.noise_mm)
        x[live] = xa + dxn * scale
        prev, steps[live] = steps[live], np.abs(dxn).max(axis=1)
        done = steps[live] < tol
        iters[live[done]] = it
        stall = ~done & ~ex & (steps[live] > prev) & (steps[live] > 100 * tol)
        x[live[stall]] = 0.0  # restart from the nominal model with the exact Jacobian
        exact[live[stall]] = True
        live = live[~done]
        if not len(live):
            break
    return x, steps, iters, exact
