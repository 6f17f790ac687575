"""Standard grades under the Gaussian probability itself: outer approximation, then a local search.

The certified rules are sufficient, not necessary; the exact requirement ``P(|x_i| < r) >= p_i`` admits
cheaper designs. Starting from a catalogue design that meets it (the certified discrete optimum):

1. **Outer approximation** (Duran & Grossmann 1986): the probability is linearised at the continuous exact
   optimum and at every design tried, ``P_i(u_m) + grad P_i(u_m) . (u - u_m) >= p_i``; the MILP of
   :class:`tolalloc.allocate.discrete.OuterApproximation` (cost capped :data:`MIP_REL_GAP` below the incumbent)
   proposes a design, which is checked with the exact probability
   (:func:`tolalloc.linear.probability.p_within_radius`): it becomes the incumbent if it meets the requirement
   (else its greedy repair may), and is linearised in turn if it fails; the loop ends when the program has no
   design left. Where ``P`` is concave in the variances (near ``p = 0.95`` along
   every scaling, ``P(chi2_3 < r^2 / s)`` is concave in ``s`` for ``r^2 / s > 5``) the linearisations are
   outer approximations and the loop ends at the discrete optimum; elsewhere it is a heuristic, so the
   result is called *converged*, never proven.
2. **Local search**: moves to neighbouring designs (one parameter a step or grade looser; or one looser and
   another a step or grade tighter) that are cheaper and meet the exact probability at every pose, best
   saving first, until no move is left.

Gradients by central differences in ``u`` (relative step 1e-4; ``P`` is accurate to 1e-10).
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc.allocate.catalogue import Catalogue
from tolalloc.allocate.discrete import COARSE_GAP, MIP_REL_GAP, OuterApproximation, RuleOutcome, repair
from tolalloc.allocate.problem import AllocationProblem, block_probability

__all__ = ["exact_margin", "screened_violation", "solve_discrete_exact", "local_search"]


def exact_margin(problem: AllocationProblem, U: np.ndarray, poses: list | None = None) -> np.ndarray:
    """Smallest ``P_i - target_i`` over poses and blocks for each row of ``U`` (B, Ka), shape (B,).

    ``poses``: per block, the pose indices to evaluate (default every pose); the result is then the smallest margin
    over those poses only, an upper bound of the margin over all.
    """
    U = np.atleast_2d(U)
    out = np.full(len(U), np.inf)
    for i, b in enumerate(problem.blocks):
        sel = slice(None) if poses is None else poses[i]
        if poses is not None and len(sel) == 0:
            continue
        C = b["C0"][sel][None] + np.einsum("pkij,bk->bpij", b["A"][sel], U)
        p = np.asarray(block_probability(b, C.reshape(-1, 3, 3))).reshape(len(U), -1)
        out = np.minimum(out, (p - b["target"][sel][None]).min(axis=1))
    return out


def screened_violation(problem: AllocationProblem, U: np.ndarray, n_screen: int = 3) -> np.ndarray:
    """Minus :func:`exact_margin` where it is ``<= 0`` (the requirement holds), some positive value elsewhere.

    For the local search, which only asks which rows of ``U`` (B, Ka) meet the requirement: every row is first
    evaluated at the ``n_screen`` poses of each block where the first row has the least margin (the rows are
    neighbours of one design, so they bind at much the same poses); only the rows that pass there are evaluated
    at every pose. A row failing the screen fails the requirement, so the rows found to meet it are exactly those
    of :func:`exact_margin`. Returns shape (B,).
    """
    U = np.atleast_2d(U)
    first = [np.asarray(block_probability(b, b["C0"] + np.einsum("pkij,k->pij", b["A"], U[0])))
             - b["target"] for b in problem.blocks]
    screen = [np.argsort(m)[:n_screen] for m in first]
    out = -exact_margin(problem, U, screen)
    passed = np.flatnonzero(out <= 0)
    if passed.size:
        out[passed] = -exact_margin(problem, U[passed])
    return out


def _linearise(problem: AllocationProblem, u: np.ndarray, near: float = 0.02):
    """Rows ``-grad P_i . u <= P_i(u) - p_i - grad P_i . u`` at the poses within ``near`` of their target."""
    A, s = [], []
    Ka = len(u)
    h = 1e-4 * np.maximum(u, 1e-300)
    for b in problem.blocks:
        C = b["C0"] + np.einsum("pkij,k->pij", b["A"], u)
        p = np.asarray(block_probability(b, C))
        idx = np.flatnonzero(p - b["target"] < near)
        if not idx.size:
            continue
        dC = b["A"][idx] * h[None, :, None, None]  # (m, Ka, 3, 3)
        Cp = (C[idx][:, None] + dC).reshape(-1, 3, 3)
        Cm = (C[idx][:, None] - dC).reshape(-1, 3, 3)
        pp = np.asarray(block_probability(b, np.concatenate([Cp, Cm]))).reshape(2, len(idx), Ka)
        g = (pp[0] - pp[1]) / (2 * h[None, :])
        A.append(-g)
        s.append(p[idx] - b["target"][idx] - g @ u)
    if not A:
        return np.zeros((0, Ka)), np.zeros(0)
    return np.vstack(A), np.concatenate(s)


def solve_discrete_exact(problem: AllocationProblem, cat: Catalogue, start, continuous=None, *, max_rounds: int = 25,
                         time_limit: float = 120.0, search: bool = True, margin=None, linearise=None,
                         batch: int = 128) -> RuleOutcome:
    """Cheapest catalogue design found under the exact probability, starting from ``start``.

    Parameters
    ----------
    problem : AllocationProblem
    cat : Catalogue
    start : (opt, n)
        A catalogue design that meets the exact requirement (e.g. the certified discrete optimum).
    continuous : Design, optional
        The continuous exact design (the first linearisation point and the chords' hint).
    max_rounds : int
        Outer-approximation rounds.
    search : bool
        Run the local search after the outer approximation.
    margin, linearise : callable, optional
        Another probability requirement: ``margin(U)`` (B,) the smallest ``P_i - target_i`` of each row of ``U``
        (B, Ka), and ``linearise(u) -> (A, s)`` its rows ``A u' <= s`` at ``u`` (default :func:`exact_margin` and
        the Gaussian probability's linearisation on ``problem``; e.g. the post-calibration probability of
        :mod:`tolalloc.allocate.calibrated.standard`).
    batch : int
        Candidate moves evaluated together by the local search.

    Returns
    -------
    RuleOutcome
        ``rule = "exact"``; ``status`` ``optimal`` when the outer approximation converged (the program, capped
        :data:`MIP_REL_GAP` below the incumbent, has no design left), ``not_converged`` when the rounds ran out
        (the best design found is kept; it meets the requirement either way). ``bound`` is NaN (no proven bound).
    """
    t0 = time.perf_counter()
    custom = margin is not None
    margin = margin or (lambda U: exact_margin(problem, U))
    linearise = linearise or (lambda u: _linearise(problem, u))
    opt, n = (np.asarray(x, int) for x in start)
    if margin(cat.u_of(opt, n)[None])[0] < 0:
        raise ValueError("solve_discrete_exact: the start design does not meet the exact requirement")
    inc = (cat.total_cost(opt, n), opt, n)
    hint = None if continuous is None or continuous.t is None else continuous.t[problem.alloc]
    A, s = linearise(cat.u_of(opt, n))
    if hint is not None:
        A2, s2 = linearise(problem.u_from_t(continuous.t))
        A, s = np.vstack([A, A2]), np.concatenate([s, s2])
    oa = OuterApproximation(cat, A, s, hint if hint is not None else cat.t_of(opt, n))
    status, mips, msg = "not_converged", 0, f"outer approximation stopped after {max_rounds} rounds"
    for _ in range(max_rounds):
        out = oa.solve(cost_cap=inc[0] * (1 - MIP_REL_GAP), time_limit=time_limit, gap=COARSE_GAP)
        mips += 1
        if out.status == "infeasible":
            status, msg = "optimal", f"outer approximation converged: no design cheaper by {MIP_REL_GAP:g}"
            break
        if out.status != "optimal":
            msg = out.message
            break
        u = cat.u_of(out.opt, out.n)
        ok = margin(u[None])[0] >= 0
        cand = (cat.total_cost(out.opt, out.n), out.opt, out.n) if ok else repair(
            cat, out.opt, out.n, lambda U: -margin(U))
        if cand is not None and cand[0] < inc[0]:
            inc = cand
        oa.tighten(out.opt, out.n, out)
        if not ok:
            oa.add_rows(*linearise(u))
    moves = 0
    if search:
        violation = (lambda U: -margin(U)) if custom else (lambda U: screened_violation(problem, U))
        opt, n, moves = local_search(cat, inc[1], inc[2], violation, batch=batch)
        inc = (cat.total_cost(opt, n), opt, n)
    return RuleOutcome("exact", status, inc[1], inc[2], inc[0], np.nan, mips, time.perf_counter() - t0,
                       f"{msg}; local search: {moves} move(s)")


def _neighbours(cat: Catalogue, opt, n, a: int):
    """Choices of parameter ``a`` one or two steps (or one grade / class) from the current one, same process."""
    o = int(opt[a])
    if cat.stepped[o]:
        return [(o, int(n[a]) + d) for d in (-2, -1, 1, 2) if cat.n_lo[o] <= n[a] + d <= cat.n_hi[o]]
    same = [q for q in range(cat.start[a], cat.start[a + 1])
            if not cat.stepped[q] and cat.group[q] == cat.group[o]]
    same.sort(key=lambda q: cat.t[q])
    i = same.index(o)
    return [(q, 0) for q in same[max(0, i - 1):i] + same[i + 1:i + 2]]


def local_search(cat: Catalogue, opt, n, violation, *, max_moves: int = 500, batch: int = 128):
    """Best-saving-first descent over single and paired moves that keep ``violation(U) <= 0``.

    Parameters
    ----------
    cat : Catalogue
    opt, n : arrays of int (Ka,)
        A choice that meets the requirement.
    violation : callable
        ``violation(U)`` for scaled variances ``U`` (B, Ka) -> (B,); ``<= 0``: the requirement holds (e.g. minus
        :func:`exact_margin`).

    Moves keep each part's process, so setups do not change and a move's saving is the sum of its parameters'.

    Returns
    -------
    (opt, n, moves)
    """
    opt, n = np.array(opt, int), np.array(n, int)
    moves = 0
    while moves < max_moves:
        cur = cat.costs_of(opt, n)
        nb = []  # (a, o, k, cost change)
        for a in range(cat.n_params):
            for o, k in _neighbours(cat, opt, n, a):
                c = float(cat.law[o].cost(k * cat.step[o])) if cat.stepped[o] else float(cat.cost[o])
                nb.append((a, o, k, c - cur[a]))
        par = np.array([x[0] for x in nb])
        dc = np.array([x[3] for x in nb])
        i, j = np.meshgrid(np.arange(len(nb)), np.arange(len(nb)), indexing="ij")
        pair = (par[i] < par[j]) & (dc[i] + dc[j] < -1e-12 * cur.sum())
        moves_i = [(x,) for x in np.flatnonzero(dc < -1e-12 * cur.sum())] + list(zip(i[pair], j[pair]))
        saving = np.array([-sum(dc[x] for x in mv) for mv in moves_i])
        found = None
        for start in range(0, len(moves_i), batch):
            sel = np.argsort(saving)[::-1][start:start + batch]
            U = np.repeat(cat.u_of(opt, n)[None], len(sel), axis=0)
            for r, m in enumerate(sel):
                for x in moves_i[m]:
                    a, o, k, _ = nb[x]
                    U[r, a] = ((k * cat.step[o]) if cat.stepped[o] else cat.t[o]) ** 2 / cat.t_ref[a] ** 2
            ok = violation(U) <= 0
            if ok.any():
                found = moves_i[sel[int(np.argmax(ok))]]
                break
        if found is None:
            break
        for x in found:
            a, o, k, _ = nb[x]
            opt[a], n[a] = o, k
        moves += 1
    return opt, n, moves
