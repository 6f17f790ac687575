"""Calibration-plan design: choose N measurement poses among candidates (optimal experiment design).

Task-weighted A-optimal design: minimise the mean post-calibration position variance of the systematic part over
evaluation poses ``q_e``, ``trace(W Sigma_post(lambda)) / P`` with ``W = sum_e J_E(q_e)^T J_E(q_e)``, over
weights ``lambda`` (``0 <= lambda_c <= 1``, ``sum lambda = N``) on the candidates::

    Sigma_post(lambda)^-1 = Lambda_0 + sum_c lambda_c F_c,     F_c = G_c^T G_c   (whitened 3- or 6-row block)

-- the classic convex relaxation, solved by SciPy's interior-point method with the exact Hessian (the cvxpy
Schur-complement SDP ``cp.matrix_frac`` with Clarabel if it fails), well scaled (congruence by the uniform design)
and by column generation over the candidates, with Frank-Wolfe as the documented last fallback
(:mod:`tolalloc.calibration.relax`; :attr:`PlanDesign.relaxation_method` says which ran), then rounding to the N largest weights followed by greedy exchange passes on the exact
(rounded) objective. The nuisance parameters
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
from tolalloc.calibration.posterior import ID_TOL, nuisance_columns, posterior
from tolalloc.calibration.relax import METHODS, relax
from tolalloc.calibration.split import ErrorSplit

__all__ = ["PlanDesign", "design_plan", "candidate_poses", "plan_score", "NUISANCE_PRIOR", "check_design_budget"]

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
        Certified lower bound on the relaxation's optimum, hence on every N-pose plan's score [mm^2].
    time_s : float
    relaxation_value_mm2 : float
        The relaxation's objective at its (fractional) weights [mm^2].
    relaxation_method : str
        ``"SciPy trust-constr"``, ``"cvxpy/Clarabel"`` or ``"Frank-Wolfe"`` (the fallbacks, in that order).
    relaxation_note : str
        How the relaxation ended (rounds, iterations, gap; for a fallback, what failed before it).
    floor_unidentifiable_mm2 : float
        The part of ``floor_mm2`` along the parameter combinations no candidate identifies (the null space of the
        candidates' information, relative threshold :data:`~tolalloc.calibration.posterior.ID_TOL`): what a plan
        of any number of these poses, measured without noise, would leave [mm^2]. The rest of the floor is
        measurement noise and random parts.
    no_calibration_mm2 : float
        The same score without calibration (the prior) [mm^2].
    """

    plan: CalibrationPlan
    score_mm2: float
    random_plan: CalibrationPlan
    random_score_mm2: float
    floor_mm2: float
    relaxation_bound_mm2: float
    time_s: float
    relaxation_value_mm2: float = float("nan")
    relaxation_method: str = ""
    relaxation_note: str = ""
    floor_unidentifiable_mm2: float = float("nan")
    no_calibration_mm2: float = float("nan")


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


def check_design_budget(n_candidates: int, n_poses: int, *, argument: str = "n_candidates", announce: bool = False):
    """Refuse a design over ``n_candidates`` candidates that cannot finish within the time budget, announce a long
    one (:func:`tolalloc.budget.check_count`; the work grows with the candidates, and with the poses chosen beyond 30);
    returns the estimate."""
    from tolalloc.budget import check_count

    return check_count(int(n_candidates), argument, f"candidate poses for {n_poses} measurement poses", "candidate",
                       per_count=max(1.0, n_poses / 30), example="2000", announce=announce)


def design_plan(split: ErrorSplit, n_poses: int, candidates: np.ndarray, q_eval: np.ndarray, *,
                measurement: str = "position", noise_mm: float = 0.02, noise_deg: float = 0.001,
                registration: bool = True, seed: int = 0, relaxation: str = "auto") -> PlanDesign:
    """Choose ``n_poses`` of ``candidates`` (C, n) [rad, mm] minimising the post-calibration error at ``q_eval``.

    ``relaxation``: ``auto`` (SciPy's interior point, cvxpy/Clarabel if it fails, then Frank-Wolfe),
    ``interior-point``, ``cvxpy`` or ``frank-wolfe``.

    Returns
    -------
    PlanDesign
    """
    t0 = time.perf_counter()
    robot = split.model.robot
    C = len(candidates)
    if not isinstance(n_poses, (int, np.integer)) or n_poses < 1 or n_poses > C:
        raise TolallocError(f"--n-poses: expected a whole number between 1 and the {C} candidates, got {n_poses!r}.")
    if relaxation not in METHODS:
        raise TolallocError(f"relaxation: expected one of {', '.join(METHODS)}, got {relaxation!r}.")
    check_design_budget(C, int(n_poses), announce=True)
    like = make_plan(robot, candidates[:1], measurement=measurement, noise_mm=noise_mm, noise_deg=noise_deg,
                     registration=registration)
    G = _blocks(split, like, candidates)
    F = np.einsum("cri,crj->cij", G, G)
    B = _weight(split, q_eval, F.shape[1])
    Ke = B.shape[1]
    prior = np.r_[np.ones(Ke), np.zeros(F.shape[1] - Ke)]
    rel = relax(G, B, n_poses, prior, relaxation)
    chosen, _ = _exchange(F, B, np.argsort(-rel.lam)[:n_poses], prior)
    mk = lambda idx: make_plan(robot, candidates[np.sort(idx)], measurement=measurement, noise_mm=noise_mm,  # noqa
                               noise_deg=noise_deg, registration=registration)
    plan = mk(chosen)
    rnd = mk(np.random.default_rng(seed).choice(C, n_poses, replace=False))
    GtG = np.einsum("cri,crj->ij", G, G)
    floor = _score_info(np.diag(prior) + GtG + 1e-10 * np.eye(len(prior)), B)
    return PlanDesign(plan, plan_score(split, plan, q_eval), rnd, plan_score(split, rnd, q_eval), floor, rel.bound,
                      time.perf_counter() - t0, rel.value, rel.method, rel.note, _null_floor(GtG, prior, B),
                      float(np.sum(B**2)))


def _null_floor(info: np.ndarray, prior: np.ndarray, B: np.ndarray) -> float:
    """The score left along the null space N of the candidates' information ``info`` (D, D), the limit of the floor
    as the information on its range grows without bound: ``tr(B^T N (N^T P N)^+ N^T B)``, P = diag(``prior``)."""
    lam, V = np.linalg.eigh(info)
    N = V[:, lam <= ID_TOL * max(lam.max(initial=0.0), 1e-300)]
    if not N.shape[1]:
        return 0.0
    NB = N.T @ B
    return float(np.trace(NB.T @ np.linalg.lstsq(N.T @ (prior[:, None] * N), NB, rcond=None)[0]))
