"""The certified rules over the standard values, solved exactly by the outer approximation of
:mod:`tolalloc.allocate.discrete`.

* **trace rule**: ``tr Sigma_i(u) <= r^2 / chi2_1^-1(p)`` is linear in ``u``.
* **eigenvalue rule** ``Sigma_i(u) <= r^2 / chi2_3^-1(p) I``: cutting planes ``w^T Sigma_i(u) w <= bound``
  (implied by the rule, linear in ``u``): the coordinate axes, the eigenvectors of the continuous optimum's
  covariances and directions tilted from its top one first, then the top eigenvectors of every pose whose
  ``lambda_max`` still exceeds the bound.

Chords and cuts only relax, so every program solved is a relaxation of the discrete problem. The loop keeps
the cheapest design known to meet the rule (first: the continuous optimum rounded down; designs that miss it
are repaired by a greedy tightening, :func:`tolalloc.allocate.discrete.repair`) and asks the program for a
design cheaper by more than :data:`MIP_REL_GAP`; one that misses the rule brings its cuts and chords, one that
meets it becomes the incumbent; when the program has no such design, the incumbent is the discrete optimum
within that relative gap (a proof: the program is a relaxation).
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc.allocate.catalogue import Catalogue
from tolalloc.allocate.convex import rule_ratio
from tolalloc.allocate.discrete import COARSE_GAP, MIP_REL_GAP, OuterApproximation, RuleOutcome, repair
from tolalloc.allocate.problem import AllocationProblem

__all__ = ["rule_rows", "lmi_cuts", "rule_violation", "solve_discrete_rule"]


def rule_rows(problem: AllocationProblem, rule: str, u_ref: np.ndarray | None = None):
    """Initial rows ``A u <= s``: the trace rule itself, or eigenvalue cuts (axes and eigenvectors at ``u_ref``)."""
    A, s = [], []
    for b in problem.blocks:
        if rule == "trace":
            A.append(np.einsum("pkii->pk", b["A"]) / b["trace_bound"][:, None])
            s.append(1.0 - np.einsum("pii->p", b["C0"]) / b["trace_bound"])
            continue
        C = None if u_ref is None else b["C0"] + np.einsum("pkij,k->pij", b["A"], u_ref)
        for i in range(len(b["target"])):
            W = np.eye(3) if C is None else np.hstack([np.eye(3), _fan(np.linalg.eigh(C[i])[1])])
            a_, s_ = _cuts(b, i, W)
            A.append(a_)
            s.append(s_)
    return np.vstack(A), np.concatenate(s)


def _fan(V: np.ndarray) -> np.ndarray:
    """The eigenvectors ``V`` (3, 3, ascending) and directions tilted from the top one towards the others by
    0.1, 0.25 and 0.5 rad: where the top eigenvector of a nearby design will lie."""
    top, out = V[:, 2], [V]
    for other in (V[:, 1], V[:, 0]):
        for th in (0.1, 0.25, 0.5):
            out.append(np.stack([np.cos(th) * top + np.sin(th) * other, np.cos(th) * top - np.sin(th) * other], 1))
    return np.hstack(out)


def _cuts(b: dict, i: int, W: np.ndarray):
    """Rows ``w^T Sigma_i(u) w / bound_i <= 1`` for the columns ``w`` of ``W`` (3, m) at pose ``i`` of block ``b``."""
    eb = b["eig_bound"][i]
    a = np.einsum("am,kab,bm->mk", W, b["A"][i], W) / eb
    s = 1.0 - np.einsum("am,ab,bm->m", W, b["C0"][i], W) / eb
    return a, s


def lmi_cuts(problem: AllocationProblem, u: np.ndarray):
    """Cuts at the top eigenvectors of every pose whose ``lambda_max`` exceeds its bound; ``(None, None)`` if none."""
    A, s = [], []
    for b in problem.blocks:
        lam, vec = np.linalg.eigh(b["C0"] + np.einsum("pkij,k->pij", b["A"], u))
        if not np.any(lam[:, -1] > b["eig_bound"]):
            continue
        for i in np.flatnonzero(lam[:, -1] > b["eig_bound"] * (1 - 1e-3)):  # the violated and the nearly active
            a_, s_ = _cuts(b, i, vec[i][:, lam[i] > b["eig_bound"][i] * (1 - 1e-3)])
            A.append(a_)
            s.append(s_)
    return (None, None) if not A else (np.vstack(A), np.concatenate(s))


def rule_violation(problem: AllocationProblem, rule: str, U) -> np.ndarray:
    """Largest ``tr Sigma / trace_bound - 1`` (``lambda_max / eig_bound - 1``) over poses and blocks for each row
    of ``U`` (B, Ka), shape (B,); ``<= 0``: the rule holds."""
    U = np.atleast_2d(U)
    out = np.full(len(U), -np.inf)
    for b in problem.blocks:
        C = b["C0"][None] + np.einsum("pkij,bk->bpij", b["A"], U)
        if rule == "trace":
            r = np.einsum("bpii->bp", C) / b["trace_bound"][None]
        else:
            r = np.linalg.eigvalsh(C)[..., -1] / b["eig_bound"][None]
        out = np.maximum(out, r.max(axis=1) - 1.0)
    return out


def solve_discrete_rule(problem: AllocationProblem, cat: Catalogue, rule: str, continuous=None, *,
                        max_rounds: int = 60, time_limit: float = 120.0) -> RuleOutcome:
    """Cheapest catalogue design meeting a certified rule (``"trace"`` or ``"lmi"``), proven by the MILP.

    Parameters
    ----------
    problem : AllocationProblem
    cat : Catalogue
    rule : {"trace", "lmi"}
    continuous : Design, optional
        The continuous optimum of the rule: a feasible start (rounded down), the first chords and cuts.
    max_rounds : int
        Rounds (cuts and chords added) before stopping as ``not_converged`` with the best design found.
    time_limit : float
        HiGHS time limit per program [s].
    """
    t0 = time.perf_counter()
    cont_t = continuous.t[problem.alloc] if continuous is not None and continuous.t is not None else None
    inc = None  # best design known to meet the rule: (cost, opt, n)
    for opt, n in ([cat.round_down(cont_t)] if cont_t is not None else []) + [cat.finest()]:
        if cat.coupled(opt) and rule_ratio(problem, rule, cat.u_of(opt, n)) <= 1.0:
            inc = (cat.total_cost(opt, n), opt, n)
            break
    if inc is None and cat.coupled(cat.finest()[0]):
        return RuleOutcome(rule, "infeasible", None, None, np.nan, np.inf, 0, time.perf_counter() - t0,
                           f"no standard design meets the {rule} rule: even the finest standard values miss it")
    A, s = rule_rows(problem, rule, None if cont_t is None else problem.u_from_t(continuous.t))
    oa = OuterApproximation(cat, A, s, cont_t)
    bound, mips, msg = -np.inf, 0, ""
    for _ in range(max_rounds):
        # only designs cheaper than the incumbent by more than the gap: none left proves it optimal within the gap
        out = oa.solve(time_limit=time_limit, gap=COARSE_GAP,
                       cost_cap=None if inc is None else inc[0] * (1 - MIP_REL_GAP))
        mips += 1
        if out.status == "infeasible" and inc is not None:
            return RuleOutcome(rule, "optimal", inc[1], inc[2], inc[0], inc[0] * (1 - MIP_REL_GAP), mips,
                               time.perf_counter() - t0)
        if out.status != "optimal":
            msg = out.message
            break
        u = cat.u_of(out.opt, out.n)
        ok = rule_ratio(problem, rule, u) <= 1.0
        cand = (cat.total_cost(out.opt, out.n), out.opt, out.n) if ok else repair(
            cat, out.opt, out.n, lambda U: rule_violation(problem, rule, U))
        if cand is not None and rule_ratio(problem, rule, cat.u_of(cand[1], cand[2])) > 1.0:
            cand = None  # the vectorised check and rule_ratio disagree at rounding level: keep only what both accept
        if cand is not None and (inc is None or cand[0] < inc[0]):
            inc = cand
        added = oa.tighten(out.opt, out.n, out)
        if not ok:
            A2, s2 = lmi_cuts(problem, u) if rule == "lmi" else (None, None)
            if A2 is not None:
                oa.add_rows(A2, s2)
            elif not added:  # exact values, rows met within HiGHS' tolerance but not in numpy: tighten by the excess
                oa.s = oa.s - 2 * (rule_ratio(problem, rule, u) - 1.0)
    else:
        msg = f"{max_rounds} rounds of cuts and chords without closing the gap"
    dt = time.perf_counter() - t0
    if inc is None:
        return RuleOutcome(rule, "failed", None, None, np.nan, bound, mips, dt, msg)
    return RuleOutcome(rule, "not_converged", inc[1], inc[2], inc[0], bound, mips, dt,
                       f"{msg}; the best design found meets the rule but is not proven optimal (bound {bound:.6g})")
