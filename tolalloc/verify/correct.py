"""Correction loop: tighten the target where the nonlinear Monte Carlo falls short of the linear P (issue 13).

After a design is verified, every pose whose 95 % interval does not lie wholly at or above ``p`` gets the
measured shortfall of ``P_hat`` below the linear prediction (zero if none) plus ``k_se`` standard errors
added to its target. The allocation is solved again and re-verified (same seed, same poses), at most
``max_rounds`` times; then the loop stops and says so.

Simplification (stated): the allocation takes one probability per requirement, so the tightened target is
the largest per-pose target, applied at every pose (conservative: it can cost more than per-pose targets).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.problem import build_problem
from tolalloc.verify.designs import Verification, verify_design

__all__ = ["Correction", "correct_design"]


@dataclass(frozen=True, eq=False)
class Correction:
    """Result of :func:`correct_design`.

    Attributes
    ----------
    result : AllocationResult
        The final allocation (the input one if no round was needed).
    verification : Verification
        Its verification (verdict per pose and overall).
    rounds : int
        Correction rounds run (0: the first design was already demonstrated).
    targets : tuple of float
        The probability target of each solve (first: the requirement ``p``).
    costs : tuple of float
        The design cost of each solve.
    stopped : bool
        True when ``max_rounds`` were used and the design is still not demonstrated.
    """

    result: object
    verification: Verification
    rounds: int
    targets: tuple
    costs: tuple
    stopped: bool

    @property
    def cost_of_correction(self) -> float:
        """Final cost minus the uncorrected cost."""
        return float(self.costs[-1] - self.costs[0])

    def message(self) -> str:
        v = self.verification
        head = (f"verified: {v.verdict} after {self.rounds} correction round(s); target "
                f"{' -> '.join(f'{t:.5f}' for t in self.targets)}; cost {self.costs[0]:.4f} -> {self.costs[-1]:.4f} "
                f"(+{self.cost_of_correction:.4f})")
        return head + ("; stopped at the round limit, not demonstrated" if self.stopped else "")


def _needed_target(ver: Verification, k_se: float) -> float:
    """Largest per-pose target ``p + max(0, p_lin - P_hat) + k_se se`` over poses not demonstrated, or ``p``."""
    se = np.sqrt(np.maximum(ver.p_mc * (1 - ver.p_mc), 1e-12) / ver.n)
    short = ver.ci_low < ver.prob
    if not short.any():
        return ver.prob
    need = ver.prob + np.maximum(0.0, ver.p_linear - ver.p_mc)[short] + k_se * se[short]
    return float(need.max())


def correct_design(model, q, *, solver: str = "exact", radius_mm: float = 0.25, prob: float = 0.95,
                   costs=None, n_mc: int = 10**5, seed: int = 0, k_se: float = 3.0, max_rounds: int = 2,
                   result=None) -> Correction:
    """Allocate, verify and, where the Monte Carlo falls short of the linear P, tighten and re-solve.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (P, n) [rad, mm]
    solver : {"exact", "certified"}
    radius_mm, prob, costs
        The requirement and costs (as :func:`tolalloc.allocate.problem.build_problem`).
    n_mc : int
        Monte Carlo samples per pose.
    k_se : float
        Margin in standard errors added to the measured shortfall.
    max_rounds : int
        Correction rounds before the loop stops.
    result : AllocationResult, optional
        An allocation already solved for ``p`` on ``q`` (saves the first solve).
    """
    from tolalloc.allocate.solve import allocate

    def solve(target):
        pr = build_problem(model, q, radius_mm=radius_mm, prob=target, costs=costs)
        return allocate(pr, solver=solver, snap=False)

    def check(res):
        pr = build_problem(model, q, radius_mm=radius_mm, prob=prob, costs=costs)  # verified against p itself
        d = res.design if solver == "exact" else res.certified
        from tolalloc.allocate.problem import make_design

        return verify_design(pr, make_design(pr, d.solver, d.t), n_mc=n_mc, seed=seed, keep_samples=0,
                             criterion="certified")

    res = result if result is not None else solve(prob)
    targets, cost_list = [prob], [float(res.design.cost)]
    ver = check(res)
    rounds = 0
    while ver.verdict != "demonstrated" and rounds < max_rounds:
        target = _needed_target(ver, k_se)
        if target <= targets[-1] or target >= 1:
            break
        rounds += 1
        res = solve(target)
        if res.design.t is None:
            break
        targets.append(target)
        cost_list.append(float(res.design.cost))
        ver = check(res)
    return Correction(res, ver, rounds, tuple(targets), tuple(cost_list), ver.verdict != "demonstrated")
