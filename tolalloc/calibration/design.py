"""Calibration-plan design: choose N measurement poses among candidates (optimal experiment design).

Task-weighted A-optimal design: minimise the mean post-calibration position variance of the systematic part over
evaluation poses ``q_e``, ``trace(W Sigma_post(lambda)) / P`` with ``W = sum_e J_E(q_e)^T J_E(q_e)``, over
weights ``lambda`` (``0 <= lambda_c <= 1``, ``sum lambda = N``) on the candidates::

    Sigma_post(lambda)^-1 = Lambda_0 + sum_c lambda_c F_c,     F_c = G_c^T G_c   (whitened 3- or 6-row block)

-- the classic convex relaxation, solved by Frank-Wolfe (the SDP form ``[[M, B], [B^T, Y]] >= 0`` in cvxpy +
Clarabel ended in NumericalError on the tool_changer: information spans ~1e7 against the prior), then rounding to the N
largest weights followed by greedy exchange passes on the exact (rounded) objective. The nuisance parameters
(registration, tool offset) enter the information matrix with a zero (flat) prior and are marginalised exactly by
the Schur form (a generalised inverse); the design's reported quality is always recomputed with
:func:`tolalloc.calibration.posterior.posterior`.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.stats import qmc

from tolalloc.exceptions import TolallocError
from tolalloc.calibration.plan import CalibrationPlan, make_plan
from tolalloc.calibration.posterior import nuisance_columns, posterior
from tolalloc.calibration.split import ErrorSplit

__all__ = ["PlanDesign", "design_plan", "candidate_poses", "plan_score", "NUISANCE_PRIOR"]

#: Column scales of the nuisance parameters (rotation [rad], translation [mm], tool [mm]); conditioning only.
NUISANCE_PRIOR = np.r_[np.full(3, 1e-3), np.full(3, 1.0), np.full(3, 1.0)]


@dataclass(frozen=True, eq=False)
class PlanDesign:
    """Result of :func:`design_plan`.

    Attributes
    ----------
    plan : CalibrationPlan
        The optimised plan.
    score_mm2 : float
        Mean post-calibration position variance (trace) of the systematic part over the evaluation poses [mm^2].
    random_plan : CalibrationPlan
        N random candidates (the comparison).
    random_score_mm2 : float
    floor_mm2 : float
        Score with every candidate measured once: what no N-pose plan from these candidates beats by much
        (unidentifiable directions and random parts keep it above zero).
    relaxation_bound_mm2 : float
        Frank-Wolfe lower bound on the relaxation's optimum, hence on every N-pose plan's score [mm^2].
    time_s : float
    """

    plan: CalibrationPlan
    score_mm2: float
    random_plan: CalibrationPlan
    random_score_mm2: float
    floor_mm2: float
    relaxation_bound_mm2: float
    time_s: float


def candidate_poses(robot, n: int, region: str = "limits", *, seed: int = 0) -> np.ndarray:
    """``n`` scrambled-Sobol poses [rad, mm] in the joint limits (``limits``) or in the box of a pose set."""
    if region == "limits":
        lo, hi = robot.lower, robot.upper
    else:
        q = robot.poses(region)
        lo, hi = q.min(0), q.max(0)
    with warnings.catch_warnings():  # balance properties need a power of 2; any n is fine as candidates
        warnings.simplefilter("ignore", UserWarning)
        u = qmc.Sobol(robot.n_joints, scramble=True, seed=seed).random(n)
    return lo + (hi - lo) * u


def _blocks(split: ErrorSplit, plan_like: CalibrationPlan, q: np.ndarray) -> np.ndarray:
    """Whitened, normalised information blocks G_c (C, rows, Ke + 9) of candidate poses ``q`` (C, n)."""
    m = split.model
    rows = plan_like.rows_per_pose
    E = split.sys_index
    J = m.jacobian(q)[:, :rows, :]
    cols = [J[:, :, E] * np.sqrt(split.prior_var_of(E))]
    if plan_like.registration:
        cols.append(nuisance_columns(m, q, rows) * NUISANCE_PRIOR)
    G = np.concatenate(cols, axis=2)
    sig = np.r_[np.full(3, plan_like.noise_mm), np.full(3, plan_like.noise_rad)][:rows]
    R = np.einsum("cik,k,cjk->cij", J, split.random_variance(), J) + np.diag(sig**2)
    L = np.linalg.cholesky(R)
    return np.linalg.solve(L, G)


def _weight(split: ErrorSplit, q_eval: np.ndarray, D: int) -> np.ndarray:
    """Factor B (D, Ke) with ``B B^T`` = the task weight in normalised coordinates, per evaluation pose."""
    E = split.sys_index
    Je = split.model.jacobian(q_eval)[:, :3, E] * np.sqrt(split.prior_var_of(E))
    W = np.einsum("pik,pil->kl", Je, Je) / len(q_eval)
    lam, V = np.linalg.eigh(W)
    B = np.zeros((D, len(E)))
    B[: len(E)] = V * np.sqrt(np.maximum(lam, 0))
    return B


def plan_score(split: ErrorSplit, plan: CalibrationPlan, q_eval: np.ndarray) -> float:
    """Mean trace of the post-calibration position covariance of the systematic part over ``q_eval`` [mm^2]."""
    post = posterior(split, plan)
    J = split.model.jacobian(q_eval)[:, :3, :]
    return float(np.einsum("pik,kl,pil->", J, post.cov_sys, J) / len(q_eval))


def _score_info(info: np.ndarray, B: np.ndarray) -> float:
    return float(np.trace(B.T @ np.linalg.lstsq(info, B, rcond=None)[0]))


def _relax(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, iters: int = 300) -> tuple[np.ndarray, float]:
    """Convex relaxation ``min_lambda f(lambda) = trace(B^T M(lambda)^-1 B)``, ``M = diag(prior) + sum lam_c G_c^T G_c``
    over ``0 <= lambda <= 1, sum lambda = n``, by Frank-Wolfe (the linear oracle takes the n candidates of largest
    ``|df/dlambda_c| = |G_c M^-1 B|_F^2``). Returns the weights and the Frank-Wolfe lower bound on the optimum
    (``f + grad . (s - lambda)``, valid because f is convex)."""
    C, D = G.shape[0], G.shape[2]
    ridge = 1e-9 * max(np.einsum("cri,cri->i", G, G).max() * n / C, 1.0) * np.eye(D)  # flat nuisance block
    lam = np.full(C, n / C)
    bound = -np.inf
    best_f = np.inf
    for it in range(iters):
        M = np.diag(prior) + np.einsum("c,cri,crj->ij", lam, G, G) + ridge
        X = np.linalg.solve(M, B)  # (D, Ke)
        fval = float(np.sum(B * X))
        best_f = min(best_f, fval)
        grad = -np.einsum("crk->c", np.einsum("cri,ik->crk", G, X) ** 2)
        s = np.zeros(C)
        s[np.argsort(grad)[:n]] = 1.0
        gap = float(grad @ (lam - s))
        bound = max(bound, fval - gap)
        if gap <= 1e-4 * fval:
            break
        lam = lam + 2.0 / (it + 3.0) * (s - lam)
    return lam, bound


def _exchange(F, B, chosen, prior, passes: int = 2):
    """Greedy exchange: swap a chosen candidate for the unchosen one that lowers the exact objective most."""
    chosen = list(int(c) for c in chosen)
    info = np.diag(prior) + F[chosen].sum(0)
    best = _score_info(info, B)
    for _ in range(passes):
        improved = False
        for i in range(len(chosen)):
            base = info - F[chosen[i]]
            ridge = 1e-9 * np.abs(np.diag(info)).max() * np.eye(len(base))  # nuisance unseen with too few poses
            X = np.linalg.solve(base[None] + F + ridge, np.broadcast_to(B, (len(F),) + B.shape))
            scores = np.einsum("dk,cdk->c", B, X)
            scores[chosen] = np.inf
            j = int(np.argmin(scores))
            if scores[j] < best * (1 - 1e-9):
                chosen[i], best, info, improved = j, float(scores[j]), base + F[j], True
        if not improved:
            break
    return chosen, best


def design_plan(split: ErrorSplit, n_poses: int, candidates: np.ndarray, q_eval: np.ndarray, *,
                measurement: str = "position", noise_mm: float = 0.02, noise_deg: float = 0.001,
                registration: bool = True, seed: int = 0) -> PlanDesign:
    """Choose ``n_poses`` of ``candidates`` (C, n) [rad, mm] minimising the post-calibration error at ``q_eval``.

    Returns
    -------
    PlanDesign
    """
    t0 = time.perf_counter()
    robot = split.model.robot
    C = len(candidates)
    if not isinstance(n_poses, (int, np.integer)) or n_poses < 1 or n_poses > C:
        raise TolallocError(f"--n-poses: expected a whole number between 1 and the {C} candidates, got {n_poses!r}.")
    like = make_plan(robot, candidates[:1], measurement=measurement, noise_mm=noise_mm, noise_deg=noise_deg,
                     registration=registration)
    G = _blocks(split, like, candidates)
    F = np.einsum("cri,crj->cij", G, G)
    B = _weight(split, q_eval, F.shape[1])
    Ke = B.shape[1]
    prior = np.r_[np.ones(Ke), np.zeros(F.shape[1] - Ke)]
    lam, bound = _relax(G, B, n_poses, prior)
    chosen, _ = _exchange(F, B, np.argsort(-lam)[:n_poses], prior)
    mk = lambda idx: make_plan(robot, candidates[np.sort(idx)], measurement=measurement, noise_mm=noise_mm,  # noqa
                               noise_deg=noise_deg, registration=registration)
    plan = mk(chosen)
    rnd = mk(np.random.default_rng(seed).choice(C, n_poses, replace=False))
    floor = _score_info(np.diag(prior) + np.einsum("cri,crj->ij", G, G) + 1e-10 * np.eye(len(prior)), B)
    return PlanDesign(plan, plan_score(split, plan, q_eval), rnd, plan_score(split, rnd, q_eval), floor, bound,
                      time.perf_counter() - t0)
