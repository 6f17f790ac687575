"""Tolerance allocation: the cheapest tolerances meeting ``P(|dP| < r) >= p`` at every working pose.

Decision variables: a symmetric tolerance ``±t_k`` per allocatable parameter with ``sigma_k = t_k / z``.
Internally the solvers use the scaled variance ``u_k = (t_k / t_ref_k)**2`` (order one for every
kind, mm or rad), in which the position covariance at pose ``i`` is linear::

    Sigma_i(u) = C0_i + sum_k u_k A_ik,   A_ik = J_ik J_ik^T t_ref_k^2 / z^2

(``J_ik`` the first-order error Jacobian column, ``C0_i`` the fixed parameters' share) and every
cost law of :mod:`tolalloc.allocate.costs` is convex. Two solvers (see :mod:`tolalloc.allocate.convex`,
:mod:`.allocate_exact`):

* **certified** (cvxpy + Clarabel): the trace rule ``tr Sigma <= r^2 / chi2_1^-1(p)`` (valid for
  ``p >= 0.785``, Szekely & Bakirov 2003) and the eigenvalue rule ``Sigma <= r^2 / chi2_3^-1(p) I``
  (an LMI); each implies the requirement for any covariance, both are solved, the cheaper kept;
* **exact** (CasADi + IPOPT): the Gaussian probability itself per pose, warm-started from the
  certified design, never dearer than it (falls back to it otherwise).

ISO 9283 requirements (``acceptance=``, :mod:`tolalloc.acceptance.terms`) add one block per statistic (``AP_P``,
``RP_l``, ...) at the poses of the acceptance test, of the same affine form; a block's ``measure`` names the law
its probability follows (``ball``: ``P(|x| < r)``; ``rp`` and ``sd3``: the repeatabilities,
:mod:`tolalloc.acceptance.measures`), and its certified budgets are that law's.

:func:`allocate` runs both, diagnoses infeasibility (best probability at ``r`` and radius at ``p``
with every tolerance at its process limit, and the limits that bind: :mod:`tolalloc.allocate.limits`) and snaps to
standard grades.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import StrEnum

import numpy as np
from scipy.stats import chi2

from tolalloc.exceptions import TolallocError, check_positive
from tolalloc.allocate.blocks import acceptance_blocks, block_covariances, block_probability, block_radius
from tolalloc.allocate.costs import CostSet, cost_set
from tolalloc.errormodel.model import ErrorModel

__all__ = ["AllocationProblem", "Design", "Solver", "NOT_CONVERGED", "build_problem", "make_design", "TRACE_RULE_MIN_P",
           "block_covariances", "block_probability", "block_radius"]

#: The trace rule is a valid sufficient condition only for p at or above this (Szekely & Bakirov 2003).
TRACE_RULE_MIN_P = 0.785


@dataclass(frozen=True, eq=False)
class AllocationProblem:
    """A tolerance-allocation problem (build with :func:`build_problem`).

    Attributes
    ----------
    model : ErrorModel
        Error model without the excluded parameters; fixed parameters carry ``sigma = fixed_tol / z``.
    costs : CostSet
        Aligned with ``model.params``.
    q : array, shape (P, n) [rad, mm]
    radius_mm, prob : float
        Requirement ``P(|dP| < radius_mm) >= prob`` at every pose (``radius_mm`` None: no position requirement, only
        ISO 9283 ones).
    angle_radius_rad : float or None
        Optional orientation requirement ``P(|dw| < angle_radius_rad) >= angle_prob``.
    angle_prob : float
    J : array, shape (P, 6, K)
        Error Jacobian at the poses.
    alloc, fixed : arrays of int
        Indices of the allocatable and fixed parameters.
    t_ref, t_min, t_max : arrays, shape (K,) [mm or rad]
    blocks : list of dict
        One per requirement: ``name``, ``rows``, ``radius``, ``prob`` (the requirement), ``target`` (P,) (the
        probability each pose is solved for: ``prob`` unless tightened by the correction loop), ``A`` (P, Ka, 3, 3),
        ``C0`` (P, 3, 3), ``trace_bound`` and ``eig_bound`` (P,) (the certified rules' budgets at ``target``). A
        block of an ISO 9283 requirement has its own poses: ``measure``, ``cycles``, ``q`` (its poses), ``labels``
        and ``rows`` None; its arrays run over its own poses.
    acceptance : AcceptanceSpec or None
        The ISO 9283 requirements and their test.
    """

    model: ErrorModel
    costs: CostSet
    q: np.ndarray
    radius_mm: float
    prob: float
    angle_radius_rad: float | None = None
    angle_prob: float = 0.95
    J: np.ndarray = field(default=None, repr=False)
    alloc: np.ndarray = field(default=None, repr=False)
    fixed: np.ndarray = field(default=None, repr=False)
    t_ref: np.ndarray = field(default=None, repr=False)
    t_min: np.ndarray = field(default=None, repr=False)
    t_max: np.ndarray = field(default=None, repr=False)
    blocks: list = field(default=None, repr=False)
    acceptance: object = field(default=None, repr=False)

    @property
    def n_poses(self) -> int:
        return self.q.shape[0]

    @property
    def u_min(self) -> np.ndarray:
        a = self.alloc
        return (self.t_min[a] / self.t_ref[a]) ** 2

    @property
    def u_max(self) -> np.ndarray:
        a = self.alloc
        return (self.t_max[a] / self.t_ref[a]) ** 2

    def t_from_u(self, u) -> np.ndarray:
        """Full half-width vector (K,) [mm or rad] from the allocatable ``u`` (Ka,); fixed ones at their value."""
        t = np.array(self.costs.fixed_tol, dtype=float)
        t[self.alloc] = self.t_ref[self.alloc] * np.sqrt(np.maximum(np.asarray(u, float), 0.0))
        return t

    def u_from_t(self, t) -> np.ndarray:
        a = self.alloc
        return (np.asarray(t, float)[a] / self.t_ref[a]) ** 2

    def sigma(self, t) -> np.ndarray:
        """Standard deviations (K,) [mm or rad] of half-widths ``t``."""
        return np.asarray(t, float) / self.costs.z

    def param_costs(self, t) -> np.ndarray:
        """Cost of every parameter (K,) at half-widths ``t``."""
        return np.array([cm.cost(tk) for cm, tk in zip(self.costs.models, t)], dtype=float)

    def covariances(self, t, rows=slice(0, 3)) -> np.ndarray:
        """Linear covariance of the error rows at every pose, shape (P, 3, 3)."""
        J = self.J[:, rows, :]
        return np.einsum("pik,k,pjk->pij", J, self.sigma(t) ** 2, J)

    def probabilities(self, t) -> dict:
        """Gaussian ``P(|x| < radius)`` (an ISO block: its statistic's law) per requirement block at each of its
        poses: name -> (P,)."""
        return {b["name"]: block_probability(b, block_covariances(self, b, t)) for b in self.blocks}

    def model_for(self, t) -> ErrorModel:
        """The error model of a design (``sigma = t / z``) for the nonlinear Monte Carlo."""
        return self.model.with_sigma(self.sigma(t))


def build_problem(model: ErrorModel, q=None, *, radius_mm: float | None = 0.25, prob: float = 0.95,
                  costs: CostSet | dict | None = None, pose_set: str | None = None,
                  angle_radius_deg: float | None = None, angle_prob: float | None = None,
                  target=None, angle_target=None, acceptance=None) -> AllocationProblem:
    """Set up an allocation problem.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (P, n) [rad, mm], optional
        Working poses; default: the robot's ``pose_set`` (``working`` if it has one, else nominal); with ISO 9283
        requirements only, the test's poses P1-P5.
    radius_mm : float or None
        None: no position requirement (then ``acceptance`` states what the design must meet).
    prob : float in (0, 1)
    costs : CostSet or dict, optional
        Resolved costs (:func:`tolalloc.allocate.costs.load_costs`) or a parsed costs dict; default the built-in defaults.
    angle_radius_deg, angle_prob : float, optional
        Orientation requirement ``P(|dw| < angle) >= angle_prob`` (``angle_prob`` defaults to ``prob``).
    target : array, shape (P,), optional
        Per-pose probability the position requirement is solved for, each in ``[prob, 1)`` (default ``prob``):
        the correction loop (:mod:`tolalloc.verify.correct`) tightens the poses where the nonlinear Monte Carlo
        falls short of the linear prediction. ``prob`` stays the requirement that is verified.
    angle_target : array, shape (P,), optional
        The same for the orientation requirement: each in ``[angle_prob, 1)`` (default ``angle_prob``); needs
        ``angle_radius_deg``.
    acceptance : AcceptanceSpec, optional
        ISO 9283 requirements and their acceptance test (:class:`tolalloc.acceptance.terms.AcceptanceSpec`): one
        block per statistic at the test's poses.
    """
    if radius_mm is None and acceptance is None:
        raise TolallocError("radius_mm: without a position requirement the problem needs ISO 9283 requirements "
                            "(acceptance=AcceptanceSpec(...)); give radius_mm or acceptance.")
    radius_mm = None if radius_mm is None else check_positive(radius_mm, "radius_mm")
    prob = float(prob)
    if not np.isfinite(prob) or not 0 < prob < 1:
        raise TolallocError(f"prob: expected a probability strictly between 0 and 1, got {prob!r}.")
    robot = model.robot
    if q is None and radius_mm is None and hasattr(acceptance, "test"):
        q = acceptance.test.q_test  # only ISO 9283 requirements: the test's poses P1-P5
    if q is None:
        q = robot.poses(pose_set if pose_set is not None else ("working" if "working" in robot.pose_sets else None))
    q = np.atleast_2d(robot.check_q(q, "poses"))
    cs = costs if isinstance(costs, CostSet) else cost_set(model, costs)
    if set(cs.names) | set(cs.excluded) != set(model.names):
        raise TolallocError("costs: the cost set was resolved for another error model; resolve it again for this one.")
    keep = [model.index(nm) for nm in cs.names]
    params = [model.params[i] for i in keep]
    if cs.distribution == "uniform":  # errors uniform over +-t: the Monte Carlo verification samples them so
        params = [p if p.distribution == "ring" else replace(p, distribution="uniform") for p in params]
    sub = replace(model, params=tuple(params))
    role = np.array(cs.role)
    alloc = np.flatnonzero(role == "allocate")
    fixed = np.flatnonzero(role == "fixed")
    sig = sub.sigma.copy()
    sig[fixed] = np.array(cs.fixed_tol)[fixed] / cs.z
    sub = sub.with_sigma(sig)
    t_ref = np.array([m.t_ref for m in cs.models])
    J = sub.jacobian(q)
    tgt = _targets(target, "target", "prob", prob, len(q))
    blocks = [] if radius_mm is None else [_block("position", slice(0, 3), radius_mm, prob, tgt, J, alloc, fixed,
                                                  t_ref, sig, cs.z)]
    if angle_radius_deg is not None:
        ar = np.deg2rad(check_positive(angle_radius_deg, "angle_radius_deg"))
        ap = prob if angle_prob is None else float(angle_prob)
        if not np.isfinite(ap) or not 0 < ap < 1:
            raise TolallocError(f"angle_prob: expected a probability strictly between 0 and 1, got {angle_prob!r}.")
        atgt = _targets(angle_target, "angle_target", "angle_prob", ap, len(q))
        blocks.append(_block("orientation", slice(3, 6), ar, ap, atgt, J, alloc, fixed, t_ref, sig, cs.z))
    elif angle_target is not None:
        raise TolallocError("angle_target: per-pose orientation targets need an orientation requirement; give "
                            "angle_radius_deg too, or drop angle_target.")
    else:
        ar, ap = None, prob
    if acceptance is not None:
        blocks += acceptance_blocks(acceptance, sub, alloc, fixed, t_ref, sig, cs.z)
    return AllocationProblem(sub, cs, q, radius_mm, prob, ar, ap, J, alloc, fixed, t_ref,
                             np.array([m.t_min for m in cs.models]), np.array([m.t_max for m in cs.models]), blocks,
                             acceptance)


def _targets(target, name: str, prob_name: str, prob: float, n_poses: int) -> np.ndarray:
    """Per-pose probability targets (default ``prob`` at every pose), each in ``[prob, 1)``."""
    tgt = np.full(n_poses, prob) if target is None else np.asarray(target, float).reshape(-1)
    if tgt.shape != (n_poses,) or not np.all((tgt >= prob) & (tgt < 1)):
        raise TolallocError(f"{name}: expected {n_poses} per-pose probabilities in [{prob_name} = {prob:g}, 1), "
                            f"got {target!r}.")
    return tgt


def _block(name, rows, radius, prob, target, J, alloc, fixed, t_ref, sig, z) -> dict:
    Jr = J[:, rows, :]
    Ja = Jr[:, :, alloc] * (t_ref[alloc] / z)  # (P, 3, Ka)
    A = np.einsum("pik,pjk->pkij", Ja, Ja)
    Jf = Jr[:, :, fixed]
    C0 = np.einsum("pik,k,pjk->pij", Jf, sig[fixed] ** 2, Jf)
    return {"name": name, "rows": rows, "radius": float(radius), "prob": float(prob), "target": target, "A": A,
            "C0": C0, "trace_bound": radius**2 / chi2.ppf(target, 1), "eig_bound": radius**2 / chi2.ppf(target, 3)}


# ------------------------------------------------------------------------ results
#: ``Design.status`` of a design whose solver stopped without converging: never certified or exact.
NOT_CONVERGED = "not_converged"


class Solver(StrEnum):
    """The method that produced a design (``Design.solver``); compares equal to its string value."""

    CERTIFIED_TRACE = "certified-trace"
    CERTIFIED_LMI = "certified-lmi"
    EXACT = "exact"
    STANDARD = "standard"  # snapped to standard grades, re-checked by the linear P
    DISCRETE_TRACE = "discrete-trace"  # standard values chosen by a mixed-integer program, trace rule
    DISCRETE_LMI = "discrete-lmi"  # ... eigenvalue rule (cutting planes)
    DISCRETE_EXACT = "discrete-exact"  # ... improved under the Gaussian probability itself
    CALIBRATED_LMI = "calibrated-lmi"
    PROCESS_LIMITS = "process-limits"  # every tolerance at its tightest limit (reference when infeasible)

    @property
    def certified(self) -> bool:
        """Whether a converged design of this solver carries the certified (sufficient) rule."""
        return self in (Solver.CERTIFIED_TRACE, Solver.CERTIFIED_LMI, Solver.DISCRETE_TRACE, Solver.DISCRETE_LMI)


@dataclass(frozen=True, eq=False)
class Design:
    """One allocated design.

    Attributes
    ----------
    solver : Solver
        The method that produced ``t`` (``certified-trace``, ``certified-lmi``, ``exact``, ``standard`` ...).
    status : str
        ``optimal``, ``infeasible``, ``not_applicable``, ``failed``, ``violated`` (snapped design) or
        ``not_converged`` (the solver stopped without converging: ``t`` is shown for reference, never called
        certified, exact or optimal; ``ok`` is False).
    t : array, shape (K,) [mm or rad] or None
        Half-widths of all parameters (fixed ones included).
    cost : float
        Total cost (NaN if no design).
    p_linear : dict name -> array (P,)
        Gaussian probability per requirement block at every pose.
    pose_dual : array, shape (P,) or None
        Multipliers of the pose constraints (certified: per unit of the relative budget
        ``tr Sigma / bound`` or ``lambda_max``; exact: per unit of probability): which poses drive the cost.
    bound_dual : array, shape (K,) or None
        Multipliers of the process limits (> 0 at ``t_min``, < 0 at ``t_max``, per unit of ``u``).
    at_limit : tuple of str
        ``t_min``, ``t_max`` or ``""`` per parameter.
    time_s : float
    message : str
    fallback_from : Solver or None
        The solver that was asked for when this design is a fallback (e.g. ``exact`` when IPOPT failed or
        was not accepted and the certified design was kept).
    """

    solver: Solver
    status: str
    t: np.ndarray | None = None
    cost: float = float("nan")
    p_linear: dict = field(default_factory=dict)
    pose_dual: np.ndarray | None = None
    bound_dual: np.ndarray | None = None
    at_limit: tuple = ()
    time_s: float = 0.0
    message: str = ""
    fallback_from: Solver | None = None

    def __post_init__(self):
        object.__setattr__(self, "solver", Solver(self.solver))
        if self.fallback_from is not None:
            object.__setattr__(self, "fallback_from", Solver(self.fallback_from))

    @property
    def ok(self) -> bool:
        return self.status == "optimal" and self.t is not None

    @property
    def label(self) -> str:
        """Human label: the solver, the fallback and any status other than optimal, e.g.
        ``certified-lmi (fallback from exact)`` or ``exact (NOT CONVERGED)``."""
        out = str(self.solver)
        if self.fallback_from is not None:
            out += f" (fallback from {self.fallback_from})"
        if self.status == NOT_CONVERGED:
            out += " (NOT CONVERGED)"
        elif self.status != "optimal":
            out += f" ({self.status})"
        return out


def make_design(problem: AllocationProblem, solver: Solver | str, t, *, pose_dual=None, bound_dual=None, time_s=0.0,
                message="", status="optimal", fallback_from: Solver | str | None = None) -> Design:
    """Evaluate cost, probabilities and limit flags of half-widths ``t`` (K,) into a :class:`Design`."""
    t = np.asarray(t, dtype=float)
    at = []
    for k in range(len(t)):
        if problem.costs.role[k] == "fixed":
            at.append("fixed")
        elif t[k] <= problem.t_min[k] * (1 + 1e-4):
            at.append("t_min")
        elif t[k] >= problem.t_max[k] * (1 - 1e-4):
            at.append("t_max")
        else:
            at.append("")
    return Design(solver, status, t, float(problem.param_costs(t).sum()), problem.probabilities(t),
                  None if pose_dual is None else np.asarray(pose_dual, float),
                  None if bound_dual is None else np.asarray(bound_dual, float), tuple(at), float(time_s), message,
                  fallback_from)
