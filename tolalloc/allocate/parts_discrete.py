"""Machining grades and bought parts chosen together: the certified rules as one mixed-integer program.

The standard-grade machinery of :mod:`tolalloc.allocate.discrete` (binaries per standard value, integer chords of
the stepped options, rows ``A u <= s``) gains one binary ``z`` per part option, one option bought per slot, and per
row the option's coefficient: ``A u + R z <= s``. Within one signature combination (:mod:`.parts_problem`) an
option adds a covariance ``B_z`` and nothing to the mean, so

* **trace rule**: ``tr(C0_i + sum_k u_k A_ik + sum_z z B_zi) <= r^2 / chi2_1^-1(p)`` is linear in ``(u, z)``;
* **eigenvalue rule**: cutting planes ``w^T (...) w <= r^2 / chi2_3^-1(p)`` at the coordinate axes and at the top
  eigenvectors of every point that a design violates.

Every program is a relaxation of the discrete problem (chords and cuts only relax). The loop keeps the cheapest
design known to meet the rule and asks HiGHS for one cheaper by more than ``gap``; a design that misses the rule
brings its cuts and chords (and a greedy repair of its machining may turn it into an incumbent); when the program
has no cheaper design, the incumbent is the discrete optimum within ``gap`` -- a proof, the program being a
relaxation.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.catalogue import Catalogue
from tolalloc.allocate.discrete import COARSE_GAP, MIP_REL_GAP, OuterApproximation, repair
from tolalloc.allocate.parts_problem import OptionBlocks, PartsProblem
from tolalloc.allocate.discrete_rules import _cuts

__all__ = ["PartsOutcome", "solve_parts_rule", "parts_ratio", "PARTS_GAP"]

#: Relative gap the joint program closes (the standard-grade machinery's): no design meeting the rule costs less than
#: ``(1 - PARTS_GAP)`` times the one returned.
PARTS_GAP = MIP_REL_GAP


@dataclass(frozen=True, eq=False)
class PartsOutcome:
    """The certified discrete optimum of one rule over machining grades and part options.

    Attributes
    ----------
    rule : {"trace", "lmi"}
    status : {"optimal", "not_converged", "infeasible", "failed", "pruned"}
    opt, n : arrays of int (Ka,)        machining choice (:class:`~tolalloc.allocate.catalogue.Catalogue`)
    part : array of int (S,)            option index (into ``blocks.names``) per slot
    cost, machining_cost, parts_cost : float
    bound : float                       no design meeting the rule costs less (``optimal``)
    gap : float                         relative gap proven
    mips : int
    time_s : float
    message : str
    """

    rule: str
    status: str
    opt: np.ndarray | None
    n: np.ndarray | None
    part: np.ndarray | None
    cost: float
    machining_cost: float
    parts_cost: float
    bound: float
    gap: float
    mips: int
    time_s: float
    message: str = ""


def _scaled(problem: PartsProblem, blocks: OptionBlocks) -> np.ndarray:
    return blocks.cov * problem.scale[None, :, None, None]


def _cov(problem: PartsProblem, Bs, U, part) -> np.ndarray:
    """Scaled covariance (B, P, 3, 3) of machining rows ``U`` (B, Ka) with part options ``part`` (B, S)."""
    b = problem.blocks[0]
    return b["C0"][None] + np.einsum("pkij,bk->bpij", b["A"], U) + Bs[np.asarray(part)].sum(axis=1)


def parts_ratio(problem: PartsProblem, blocks: OptionBlocks, rule: str, U, part) -> np.ndarray:
    """Largest ``tr C / trace_bound`` (``lambda_max / eig_bound``) over the points for each row of ``U`` (B, Ka) with
    the part options ``part`` (B, S); ``<= 1``: the rule holds. Shape (B,)."""
    U, part = np.atleast_2d(U), np.atleast_2d(part)
    C = _cov(problem, _scaled(problem, blocks), U, np.broadcast_to(part, (len(U), part.shape[1])))
    b = problem.blocks[0]
    r = (np.einsum("bpii->bp", C) / b["trace_bound"][None] if rule == "trace"
         else np.linalg.eigvalsh(C)[..., -1] / b["eig_bound"][None])
    return r.max(axis=1)


def _trace_rows(problem: PartsProblem, Bs):
    b = problem.blocks[0]
    tb = b["trace_bound"]
    A = np.einsum("pkii->pk", b["A"]) / tb[:, None]
    R = np.einsum("zpii->pz", Bs) / tb[:, None]
    return A, R, 1.0 - np.einsum("pii->p", b["C0"]) / tb


def _lmi_rows(problem: PartsProblem, Bs, W_of):
    """Cuts at the directions ``W_of(i)`` (3, m) of every point ``i`` (None: skip)."""
    b = problem.blocks[0]
    A, R, s = [], [], []
    for i in range(problem.n_poses):
        W = W_of(i)
        if W is None:
            continue
        a_, s_ = _cuts(b, i, W)
        A.append(a_), s.append(s_)
        R.append(np.einsum("am,zab,bm->mz", W, Bs[:, i], W) / b["eig_bound"][i])
    if not A:
        return None, None, None
    return np.vstack(A), np.vstack(R), np.concatenate(s)


def _violated_cuts(problem: PartsProblem, Bs, u, part):
    C = _cov(problem, Bs, u[None], part[None])[0]
    lam, vec = np.linalg.eigh(C)
    eb = problem.blocks[0]["eig_bound"]
    near = lam > eb[:, None] * (1 - 1e-3)
    return _lmi_rows(problem, Bs, lambda i: vec[i][:, near[i]] if near[i, -1] else None)


def _finest_parts(blocks: OptionBlocks, Bs) -> np.ndarray:
    """Per slot, the option with the smallest largest trace over the points."""
    tr = np.einsum("zpii->zp", Bs).max(axis=1)
    return np.array([np.flatnonzero(blocks.slot == s)[np.argmin(tr[blocks.slot == s])]
                     for s in range(len(blocks.keys))], int)


def solve_parts_rule(problem: PartsProblem, cat: Catalogue, blocks: OptionBlocks, rule: str, *, max_rounds: int = 60,
                     time_limit: float = 60.0, gap: float = PARTS_GAP, cutoff: float | None = None) -> PartsOutcome:
    """Cheapest machining grades and part options meeting a certified rule at every point of ``problem``.

    ``cutoff``: a cost known to be reached elsewhere (another rule or signature combination); when the first
    program's bound (a relaxation) already reaches it, the solve stops with status ``pruned``."""
    t0 = time.perf_counter()
    Bs = _scaled(problem, blocks)

    def total(opt, n, part):
        return cat.total_cost(opt, n) + float(blocks.cost[part].sum())

    def ok(opt, n, part):
        return cat.coupled(opt) and parts_ratio(problem, blocks, rule, cat.u_of(opt, n), part)[0] <= 1.0

    inc = None
    fo, fn = cat.finest()
    fp = _finest_parts(blocks, Bs)
    if ok(fo, fn, fp):
        inc = (total(fo, fn, fp), fo, fn, fp)
    if rule == "trace":
        A, R, s = _trace_rows(problem, Bs)
    else:
        A, R, s = _lmi_rows(problem, Bs, lambda i: np.eye(3))
    oa = OuterApproximation(cat, A, s, part_slot=blocks.slot, part_cost=blocks.cost, R=R)
    mips, msg = 0, ""
    for _ in range(max_rounds):
        out = oa.solve(time_limit=time_limit, gap=COARSE_GAP, cost_cap=None if inc is None else inc[0] * (1 - gap))
        mips += 1
        if mips == 1 and cutoff is not None and out.status == "optimal" and out.bound >= cutoff * (1 - gap):
            return PartsOutcome(rule, "pruned", None, None, None, np.nan, np.nan, np.nan, out.bound, gap, mips,
                                time.perf_counter() - t0, f"its relaxation's bound {out.bound:.6g} reaches the "
                                f"cost {cutoff:.6g} of another design")
        if out.status == "infeasible":
            if inc is None:
                return PartsOutcome(rule, "infeasible", None, None, None, np.nan, np.nan, np.nan, np.inf, 0.0, mips,
                                    time.perf_counter() - t0, f"no combination of standard values and parts meets "
                                    f"the {rule} rule")
            return _outcome(rule, "optimal", inc, cat, blocks, inc[0] * (1 - gap), gap, mips, t0)
        if out.status != "optimal":
            msg = out.message
            break
        part = out.part
        u = cat.u_of(out.opt, out.n)
        met = ok(out.opt, out.n, part)
        if met:
            cand = (total(out.opt, out.n, part), out.opt, out.n, part)
        else:
            rep = repair(cat, out.opt, out.n, lambda U: parts_ratio(problem, blocks, rule, U, part) - 1.0)
            cand = None if rep is None else (rep[0] + float(blocks.cost[part].sum()), rep[1], rep[2], part)
            if cand is not None and not ok(cand[1], cand[2], part):
                cand = None
        if cand is not None and (inc is None or cand[0] < inc[0]):
            inc = cand
        added = oa.tighten(out.opt, out.n, out)
        if not met:
            A2, R2, s2 = _violated_cuts(problem, Bs, u, part) if rule == "lmi" else (None, None, None)
            if A2 is not None:
                oa.add_rows(A2, s2, R2)
            elif not added:  # rows met within HiGHS' tolerance but not in numpy: tighten by the excess
                oa.s = oa.s - 2 * (parts_ratio(problem, blocks, rule, u, part)[0] - 1.0)
    else:
        msg = f"{max_rounds} rounds of cuts and chords without closing the gap"
    if inc is None:
        return PartsOutcome(rule, "failed", None, None, None, np.nan, np.nan, np.nan, np.nan, np.nan, mips,
                            time.perf_counter() - t0, msg)
    return _outcome(rule, "not_converged", inc, cat, blocks, np.nan, np.nan, mips, t0,
                    f"{msg}; the best design found meets the rule but is not proven optimal")


def _outcome(rule, status, inc, cat, blocks, bound, gap, mips, t0, msg="") -> PartsOutcome:
    cost, opt, n, part = inc
    pc = float(blocks.cost[part].sum())
    return PartsOutcome(rule, status, opt, n, part, cost, cost - pc, pc, bound, gap, mips, time.perf_counter() - t0,
                        msg or f"proven optimal within a relative gap of {gap:.0e} ({mips} programs)")
