"""Calibration plans for an allocation: maximise the worst post-calibration probability at the binding poses.

The plan criterion of :mod:`tolalloc.calibration.design` (mean post-calibration variance over evaluation poses,
under the robot file's manufacturing sigmas) is not what a calibration-aware allocation needs: the allocation
loosens what the calibration removes (to its process limit) and holds what it cannot, so the plan should identify
well the parameters *at the design's sigmas*, in the directions that matter at the poses where the requirement
binds. Here, for a given design (its :class:`~tolalloc.calibration.split.ErrorSplit`: prior = the design's sigmas,
random parts = its repeatability), the plan of ``N`` candidate poses maximises::

    min_e  P(|x_e| < r),    x_e ~ N(0, J_E,e S_E(plan) J_E,e^T + J_e V_random J_e^T)

over evaluation poses ``q_e`` (the allocation's binding / active poses), ``S_E`` the posterior covariance of the
estimated parameters with registration and tool offset marginalised (flat prior). Started from the task-weighted
A-optimal plan of :func:`tolalloc.calibration.design.design_plan` for the same prior and poses (and from any given
plan; the better is kept), then greedy exchange: each chosen pose is replaced by the candidate that raises the
objective most (rank-3 / rank-6 updates of the posterior for all candidates at once; eigenvalue screening, then the
exact probability on the most promising candidates), until a pass changes nothing. The plan's quality is always
re-evaluated with :func:`tolalloc.calibration.posterior.posterior` (:func:`plan_worst_p`).

:func:`random_plan_worst_p` gives the distribution over random plans of the same size (the comparison).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tolalloc.calibration.design import _blocks, design_plan
from tolalloc.calibration.plan import CalibrationPlan, make_plan
from tolalloc.calibration.posterior import posterior
from tolalloc.calibration.split import ErrorSplit
from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability import p_within_radius

__all__ = ["WorstPlanDesign", "design_plan_worst", "plan_worst_p", "random_plan_worst_p",
           "check_random_plans_budget"]

#: Candidates per slot whose exact probability is evaluated after the eigenvalue screening.
SCREEN = 48


@dataclass(frozen=True, eq=False)
class WorstPlanDesign:
    """Result of :func:`design_plan_worst`.

    Attributes
    ----------
    plan : CalibrationPlan
    index : array of int, shape (N,)
        Chosen candidates.
    worst_p : float
        Worst post-calibration ``P`` over the evaluation poses (recomputed with :func:`posterior`).
    p_eval : array, shape (Pe,)
    start_worst_p : float
        The same for the start plan (A-optimal, or the given one if better).
    swaps : int
        Exchanges made.
    time_s : float
    """

    plan: CalibrationPlan
    index: np.ndarray
    worst_p: float
    p_eval: np.ndarray
    start_worst_p: float
    swaps: int
    time_s: float


def plan_worst_p(split: ErrorSplit, plan: CalibrationPlan, q_eval, radius_mm: float) -> np.ndarray:
    """Post-calibration ``P(|dP| < r)`` of ``plan`` at ``q_eval`` (Pe, n) under ``split``, shape (Pe,)."""
    return np.asarray(p_within_radius(posterior(split, plan).tool_covariance(q_eval), radius_mm))


def check_random_plans_budget(count: int, n_eval_poses: int, *, argument: str = "random_plans",
                              announce: bool = False):
    """Refuse ``count`` random plans (each evaluated at ``n_eval_poses`` poses) that cannot be compared within the
    time budget, announce a long comparison (:func:`tolalloc.budget.check_count`); returns the estimate."""
    from tolalloc.budget import check_count

    return check_count(int(count), argument, "random plans", "random_plan", per_count=max(1, n_eval_poses),
                       bytes_each=8.0, example="100", announce=announce)


def random_plan_worst_p(split: ErrorSplit, candidates, n_poses: int, q_eval, radius_mm: float, *, count: int = 200,
                        seed: int = 0, like: CalibrationPlan | None = None) -> np.ndarray:
    """Worst-pose post-calibration ``P`` of ``count`` random ``n_poses``-subsets of ``candidates``, shape (count,).

    ``like`` gives the measurement settings (default: position, 0.02 mm, registration).
    """
    robot = split.model.robot
    check_random_plans_budget(int(count), len(np.atleast_2d(q_eval)), argument="count")
    rng = np.random.default_rng(seed)
    out = np.empty(count)
    for i in range(count):
        idx = np.sort(rng.choice(len(candidates), n_poses, replace=False))
        plan = _like_plan(robot, candidates[idx], like)
        out[i] = plan_worst_p(split, plan, q_eval, radius_mm).min()
    return out


def _like_plan(robot, q, like):
    if like is None:
        return make_plan(robot, q)
    return make_plan(robot, q, measurement=like.measurement, noise_mm=like.noise_mm,
                     noise_deg=np.rad2deg(like.noise_rad), registration=like.registration)


class _Objective:
    """Worst-pose probability of candidate sets, with the posterior updated by one candidate's block at a time."""

    def __init__(self, split: ErrorSplit, like: CalibrationPlan, candidates, q_eval, radius_mm):
        E = split.sys_index
        self.G = _blocks(split, like, candidates)  # (C, rows, D), normalised by the prior sigma
        self.C, self.rows, self.D = self.G.shape
        Ke = len(E)
        self.prior = np.r_[np.ones(Ke), np.zeros(self.D - Ke)]
        J = split.model.jacobian(q_eval)[:, :3, :]
        B = np.zeros((len(q_eval), 3, self.D))
        B[:, :, :Ke] = J[:, :, E] * np.sqrt(split.prior_var_of(E))
        self.B = B.reshape(-1, self.D)  # (3 Pe, D)
        self.R = np.einsum("pik,k,pjk->pij", J, split.random_variance(), J)  # plan-independent part (Pe, 3, 3)
        self.Pe, self.r = len(q_eval), float(radius_mm)
        # the flat nuisance block gets a tiny ridge (a plan too small to fix the registration stays solvable); the
        # estimated block has its unit prior and no ridge
        nui = np.einsum("cri,cri->i", self.G, self.G)[Ke:]
        self.ridge = np.diag(np.r_[np.zeros(Ke), np.full(self.D - Ke, 1e-12 * max(nui.max(initial=0.0), 1.0))])

    def info(self, idx) -> np.ndarray:
        Gi = self.G[np.asarray(idx, int)].reshape(-1, self.D)
        return np.diag(self.prior) + Gi.T @ Gi + self.ridge

    def cov(self, M) -> np.ndarray:
        X = np.linalg.solve(M, self.B.T)  # (D, 3 Pe)
        S = (self.B @ X).reshape(self.Pe, 3, self.Pe, 3)
        return S[np.arange(self.Pe), :, np.arange(self.Pe), :] + self.R

    def score(self, cov) -> float:
        p = np.asarray(p_within_radius(cov, self.r))
        return float(p.min() + 1e-3 * p.mean())  # worst pose first; the mean breaks ties between equal minima

    def best_swap(self, Mi: np.ndarray, exclude) -> tuple[int, float]:
        """Best candidate to add to the information ``Mi`` (one slot removed) and its score."""
        Minv = np.linalg.inv(Mi)
        H = self.G @ Minv  # (C, rows, D)
        S = np.eye(self.rows) + H @ np.swapaxes(self.G, 1, 2)  # (C, rows, rows)
        K = np.einsum("ed,crd->cer", self.B @ Minv, self.G)  # (C, 3 Pe, rows)
        Y = np.linalg.solve(S, np.swapaxes(K, 1, 2))  # (C, rows, 3 Pe)
        Pe = self.Pe
        red = np.einsum("cpir,crpj->cpij", K.reshape(self.C, Pe, 3, -1), Y.reshape(self.C, -1, Pe, 3))
        base = (self.B @ Minv @ self.B.T).reshape(Pe, 3, Pe, 3)[np.arange(Pe), :, np.arange(Pe), :]
        cov = base[None] - red + self.R[None]  # (C, Pe, 3, 3): Woodbury update of the posterior per candidate
        lam = np.linalg.eigvalsh(cov)[..., -1].max(axis=1)  # screening: worst largest eigenvalue
        lam[list(exclude)] = np.inf
        top = np.argsort(lam)[:SCREEN]
        top = top[np.isfinite(lam[top])]
        scores = [self.score(cov[c]) for c in top]
        j = int(np.argmax(scores))
        return int(top[j]), float(scores[j])


def design_plan_worst(split: ErrorSplit, n_poses: int, candidates, q_eval, radius_mm: float, *,
                      start: CalibrationPlan | None = None, measurement: str = "position", noise_mm: float = 0.02,
                      noise_deg: float = 0.001, registration: bool = True, passes: int = 4,
                      a_optimal: bool = True, relaxation: str = "auto") -> WorstPlanDesign:
    """Plan of ``n_poses`` candidates maximising the worst post-calibration ``P`` at ``q_eval`` (module docstring).

    Parameters
    ----------
    split : ErrorSplit
        At the design's sigmas (e.g. ``CalibratedAllocation.post.split``): the prior of the plan.
    n_poses : int
    candidates : array, shape (C, n) [rad, mm]
    q_eval : array, shape (Pe, n) [rad, mm]
        Poses where the requirement binds (e.g. a region allocation's active poses).
    radius_mm : float
    start : CalibrationPlan, optional
        An incumbent plan (of ``n_poses`` poses among ``candidates``): the exchange starts from the better of it and
        the A-optimal plan.
    passes : int
        Exchange passes over the chosen poses.
    a_optimal : bool
        Also start from the A-optimal plan for this prior and these poses (needs ``start`` when False).
    relaxation : str
        Relaxation of the A-optimal start (:func:`tolalloc.calibration.design.design_plan`).
    """
    t0 = time.perf_counter()
    candidates = np.asarray(candidates, float)
    q_eval = np.atleast_2d(np.asarray(q_eval, float))
    robot = split.model.robot
    if not isinstance(n_poses, (int, np.integer)) or not 1 <= n_poses <= len(candidates):
        raise TolallocError(f"n_poses: expected a whole number between 1 and the {len(candidates)} candidates, got "
                            f"{n_poses!r}.")
    kw = dict(measurement=measurement, noise_mm=noise_mm, noise_deg=noise_deg, registration=registration)
    like = make_plan(robot, candidates[:1], **kw)
    obj = _Objective(split, like, candidates, q_eval, radius_mm)
    if not a_optimal and start is None:
        raise TolallocError("start: give a start plan when a_optimal=False.")
    starts = [_indices(candidates, design_plan(split, n_poses, candidates, q_eval, relaxation=relaxation,
                                                      **kw).plan.q)] if a_optimal else []
    if start is not None:
        starts.append(_indices(candidates, start.q))
    scores = [obj.score(obj.cov(obj.info(s))) for s in starts]
    chosen = list(starts[int(np.argmax(scores))])
    best = max(scores)
    start_p = float(plan_worst_p(split, make_plan(robot, candidates[np.sort(chosen)], **kw), q_eval, radius_mm).min())
    swaps = 0
    for _ in range(passes):
        improved = False
        for i in range(n_poses):
            rest = chosen[:i] + chosen[i + 1:]
            j, s = obj.best_swap(obj.info(rest), set(chosen))
            if s > best + 1e-12:
                chosen[i], best, improved = j, s, True
                swaps += 1
        if not improved:
            break
    idx = np.sort(np.asarray(chosen, int))
    plan = make_plan(robot, candidates[idx], **kw)
    p = plan_worst_p(split, plan, q_eval, radius_mm)
    return WorstPlanDesign(plan, idx, float(p.min()), p, start_p, swaps, time.perf_counter() - t0)


def _indices(candidates: np.ndarray, q: np.ndarray) -> list:
    """Candidate index of each pose of ``q`` (poses must be candidates)."""
    out = []
    for row in q:
        d = np.abs(candidates - row).max(axis=1)
        j = int(np.argmin(d))
        if d[j] > 1e-9 * max(1.0, np.abs(row).max()):
            raise TolallocError("start: the plan's poses must be among the candidates (use the same candidate set).")
        out.append(j)
    return out
