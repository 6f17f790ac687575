"""Standard grades for the calibration-aware design: ISO 286 grades, classes and steps that hold after calibration.

:func:`standardize_calibrated` turns the continuous calibration-aware design of
:func:`tolalloc.allocate.calibrated.design.allocate_with_calibration` (exact when accepted, else certified) into
the standard values of the same catalogue as the allocation without calibration
(:func:`tolalloc.allocate.catalogue.build_catalogue`), over the same poses, trajectory or box:

1. **Round down.** Every allocatable tolerance goes to the largest standard value at or below it. This keeps the
   requirement at every pose of the region: tighter systematic priors raise the posterior precision
   ``Lambda_0 + A^T A`` (so ``S_E`` falls in the Loewner order), tighter random parts lower the measurement noise
   (``A^T A`` rises: the information with the nuisance projected out is a Schur complement, monotone in the
   noise precision) and their own covariance, so ``J (S_sys + V) J^T`` falls at every pose, and for a centred
   Gaussian ``P(|x| < r)`` cannot fall when the covariance falls in the Loewner order (Anderson's theorem).
   Where a tolerance lies below every standard value the rounding goes up and the start is repaired (greedy
   tightening, :func:`tolalloc.allocate.discrete.repair`).
2. **Local search** (:func:`tolalloc.allocate.discrete_exact.local_search`): moves to neighbouring grade vectors
   (one parameter a grade or one or two steps looser; or one looser and another tighter) that are cheaper and keep
   the exact post-calibration probability (:class:`tolalloc.allocate.calibrated.margin.PostMargin`) at or above
   its target at every pose of the set, best saving first, until no move is left.
3. **Outer approximation** (:func:`tolalloc.allocate.discrete_exact.solve_discrete_exact` with the post-calibration
   margin): the probability linearised at the designs tried (central differences), a mixed-integer program
   (HiGHS) proposes cheaper designs, each checked exactly and linearised in turn if it fails, until the program has
   none cheaper by :data:`~tolalloc.allocate.discrete.MIP_REL_GAP`; then the local search again. The
   post-calibration probability is not shown concave in the variances, so its linearisations need not bound it:
   the result meets ``p`` at every pose and is a local optimum of the neighbourhood, not a proven optimum.
   Steps 2-3 also run from the rounding of the continuous design confined to the catalogue's range
   (:func:`tolalloc.allocate.calibrated.rounding.range_relaxation`); the cheaper result is kept.
4. **Region** (box only): worst-pose search over the box on the standard design's post-calibration covariance
   (:func:`tolalloc.allocate.region.worst_pose`); a pose more than ``tol`` below ``p`` joins the set, the design
   is repaired there and the local search runs again, until the worst pose found is within ``tol``; then the
   coverage statement on a fresh sample (:func:`tolalloc.allocate.region.coverage`).

The repeatability grades of the calibration (a ``[calibration]`` grade table, continuous bands) stay at the
continuous design's values. The premium over the continuous design and the cost of the plain rounding it replaces
are reported (:attr:`CalibratedStandard.premium_pct`, :attr:`CalibratedStandard.rounded_premium_pct`).
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from tolalloc.allocate.calibrated.margin import PostMargin
from tolalloc.allocate.calibrated.rounding import catalogue_range, coupled_round_down, range_relaxation
from tolalloc.allocate.calibrated.standard_result import RECHECK_TOL, CalibratedStandard
from tolalloc.allocate.calibrated.region import RegionSearch, design_prob, problem_at
from tolalloc.allocate.catalogue import Catalogue, build_catalogue
from tolalloc.allocate.discrete import MIP_REL_GAP, repair
from tolalloc.allocate.discrete_exact import local_search, solve_discrete_exact
from tolalloc.allocate.problem import Design, Solver, make_design
from tolalloc.allocate.region import coverage, worst_pose
from tolalloc.exceptions import TolallocError

__all__ = ["CalibratedStandard", "standardize_calibrated"]


# ---------------------------------------------------------------------------------------------- the search
def _descend(cat: Catalogue, margin: PostMargin, opt, n, how: dict):
    """Repair ``(opt, n)`` if it misses a pose, the local search, then (``how["oa"]``) the outer approximation from
    its result (:func:`tolalloc.allocate.discrete_exact.solve_discrete_exact` with the post-calibration margin,
    local search included). Returns ``(opt, n, moves, outer approximation status)`` or None."""
    if margin(cat.u_of(opt, n)[None])[0] < 0:
        fixed = repair(cat, opt, n, margin.violation)
        if fixed is None:
            return None
        opt, n = fixed[1], fixed[2]
    opt, n, moves = local_search(cat, opt, n, margin.violation, max_moves=how["max_moves"], batch=16)
    if not how["oa"] or not how["max_moves"]:
        return opt, n, moves, ""
    out = solve_discrete_exact(margin.problem, cat, (opt, n), how["continuous"], margin=margin,
                               linearise=margin.linearise, batch=16, time_limit=how["time_limit"])
    if out.cost < cat.total_cost(opt, n):
        opt, n = out.opt, out.n
    return opt, n, moves, "converged" if out.status == "optimal" else out.message


def _check(res, tol, max_rounds, n_seed, n_starts, coverage_n, k_worst, max_moves, time_limit_s):
    from tolalloc.allocate.calibrated.design import CalibratedDesign

    if not isinstance(res, CalibratedDesign):
        raise TolallocError(f"res: expected the CalibratedDesign of tolalloc.allocate.calibrated.design."
                            f"allocate_with_calibration, got {type(res).__name__}.")
    for name, v, lo in (("max_rounds", max_rounds, 1), ("n_seed", n_seed, 1), ("n_starts", n_starts, 1),
                        ("coverage_n", coverage_n, 0), ("k_worst", k_worst, 1), ("max_moves", max_moves, 0)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
            raise TolallocError(f"{name}: expected a whole number >= {lo}, got {v!r}.")
    if isinstance(time_limit_s, bool) or not isinstance(time_limit_s, (int, float)) or not time_limit_s > 0:
        raise TolallocError(f"time_limit_s: expected a time > 0 [s] per mixed-integer program, got {time_limit_s!r}.")
    p = res.problem.prob
    if isinstance(tol, bool) or not isinstance(tol, (int, float, np.floating)) or not 0 < tol < 1 - p:
        raise TolallocError(f"tol: expected a probability tolerance in (0, 1 - prob = {1 - p:g}), e.g. 1e-4; got "
                            f"{tol!r}.")


def standardize_calibrated(res, *, angle_step_deg: float | None = None, tol: float = 1e-4, max_rounds: int = 30,
                           seed: int = 0, n_seed: int = 512, n_starts: int = 6, coverage_n: int = 100_000,
                           k_worst: int = 3, max_moves: int = 500, relax: bool = True, outer_approximation: bool = True,
                           time_limit_s: float = 60.0) -> CalibratedStandard:
    """Standard values for a calibration-aware design over its poses, trajectory or box (module docstring).

    Parameters
    ----------
    res : CalibratedDesign
        From :func:`tolalloc.allocate.calibrated.design.allocate_with_calibration`; its chosen design (exact when
        accepted, else certified) is made standard.
    angle_step_deg : float, optional
        Resolution of angle tolerances without classes [deg] (default the costs file's, else 1 arcsec).
    tol : float
        Box: stop when the worst post-calibration ``P`` found is within ``tol`` of ``p``; the coverage counts a pose
        below when ``P < p - tol``.
    max_rounds, seed, n_seed, n_starts
        Box: worst-pose searches (seeded ``seed + 2000 + round``) as in the continuous region loop.
    coverage_n : int
        Box: fresh poses of the coverage sample (seed ``seed + 12345``); 0: none.
    k_worst : int
        Worst poses kept for the end-to-end check.
    max_moves : int
        Local-search moves per round (0: the rounded and repaired design, no search).
    outer_approximation : bool
        Run the outer approximation after the local search (step 3).
    time_limit_s : float
        HiGHS time limit per mixed-integer program [s].
    relax : bool
        Also solve the continuous design confined to the catalogue's range on the continuous design's poses
        (:func:`tolalloc.allocate.calibrated.rounding.range_relaxation`, with the stages ``res`` ran: certified, then
        exact unless its exact stage was skipped): it splits the premium into range and steps, and its rounding is a
        second start of the search (the cheaper result is kept).
    """
    t0 = time.perf_counter()
    _check(res, tol, max_rounds, n_seed, n_starts, coverage_n, k_worst, max_moves, time_limit_s)
    pr, split, plan, d = res.problem, res.post.split if res.post is not None else None, res.plan, res.design
    if not d.ok or split is None:
        raise TolallocError(f"res: the calibration-aware allocation has no design to make standard ({d.message}).")
    cat = build_catalogue(pr, angle_step_deg=angle_step_deg)
    alloc = pr.alloc
    extra = float(res.cost - pr.param_costs(d.t)[alloc].sum())  # fixed parts and repeatability grades
    margin = PostMargin(pr, split, plan)
    ropt, rn = coupled_round_down(cat, d.t[alloc])
    r_t = d.t.copy()
    r_t[alloc] = cat.t_of(ropt, rn)
    r_p = margin.probabilities(cat.u_of(ropt, rn)[None])[0]
    rounded = replace(make_design(pr, Solver.STANDARD, r_t, message="the continuous design rounded down"),
                      cost=cat.total_cost(ropt, rn) + extra - (res.cost - d.cost))
    limited = tuple(pr.model.names[k] for k, hi in zip(alloc, catalogue_range(cat)[1]) if d.t[k] > hi * (1 + 1e-9))
    # the range-confined design runs the stages the continuous one ran (no exact stage after solver='certified')
    relaxed = (range_relaxation(pr, cat, plan, res.split, exact=res.exact is not None) if relax else
               (float("nan"), "", None))
    common = dict(cat=cat, extra=extra, grade_cost=float(res.cost - d.cost), rounded=rounded,
                  rounded_cost=cat.total_cost(ropt, rn) + extra, rounded_p_min=float(r_p.min()), t0=t0,
                  relaxed=relaxed[:2], limited=limited)
    starts = [(ropt, rn, f"the continuous {d.label} design")]
    if relaxed[2] is not None:
        starts.append((*coupled_round_down(cat, relaxed[2][alloc]), "the range-confined continuous design"))
    how = dict(max_moves=max_moves, oa=outer_approximation, continuous=d, time_limit=time_limit_s)
    found = [(*x, why) for o, k, why in starts if (x := _descend(cat, margin, o, k, how)) is not None]
    if not found:  # even the tightest repair misses: try every parameter at its finest value
        fo, fn = cat.finest()
        x = _descend(cat, margin, fo, fn, how) if cat.coupled(fo) else None
        found = [] if x is None else [(*x, "every parameter at its finest value")]
    out = min(found, key=lambda x: cat.total_cost(x[0], x[1])) if found else None
    if out is None:
        return _result(res, pr, margin, None, None, None, 0, None, None, "no standard design meets the requirement "
                       "after calibration, even with every tolerance at its finest standard value; allow finer grades, "
                       "classes or steps (costs file: grades, classes_<unit>, step_<unit>; angle_step_deg)", **common)
    opt, n, moves, oa, start = out
    common["start"], common["oa"] = start, oa
    search = None
    if res.region_kind == "box":
        pr, margin, opt, n, more, oa, search = _region_loop(res, pr, cat, margin, opt, n, oa, tol, max_rounds, seed,
                                                             n_seed, n_starts, how)
        moves += more
        if opt is None:
            return _result(res, pr, margin, None, None, search, moves, None, None,
                           f"the standard design could not be repaired at a pose of the region (round "
                           f"{search.rounds}): no standard design meets it", **common)
    return _result(res, pr, margin, opt, n, search, moves, coverage_n, (k_worst, tol, seed), "", **common)


def _region_loop(res, pr, cat, margin, opt, n, oa, tol, max_rounds, seed, n_seed, n_starts, how):
    """Worst-pose search on the standard design's post-calibration covariance; add, repair, search again.

    Returns ``(problem, margin, opt, n, moves, outer approximation status, RegionSearch)``; ``opt`` None when no
    standard design meets the grown pose set."""
    from tolalloc.allocate.calibrated.exact import post_probabilities

    t0 = time.perf_counter()
    split, plan, box = res.post.split, res.plan, res.region
    evals, hist, moves = 0, [], 0

    def record(rnd, pw, q, converged, why=""):
        return RegionSearch(pr.q, rnd, pw, q, evals, converged, time.perf_counter() - t0, tuple(hist), why)

    for rnd in range(1, max_rounds + 1):
        t = margin.t_of(cat.u_of(opt, n)[None])[0]
        _, post = post_probabilities(pr, split, plan, t)
        q, pw, ne = worst_pose(pr, None, box, n_seed=n_seed, n_starts=n_starts, seed=seed + 2000 + rnd,
                               fixed=res.static, pose_cov=post.tool_covariance)
        evals += ne
        hist.append((rnd, float(cat.total_cost(opt, n)), pw))
        if design_prob(pr) - pw < tol:
            return pr, margin, opt, n, moves, oa, record(rnd, pw, q, True)
        pr = problem_at(pr, np.vstack([pr.q, q]))
        done = margin.evaluations
        margin = PostMargin(pr, split, plan)
        margin.evaluations = done
        out = _descend(cat, margin, opt, n, how)
        if out is None:
            return pr, margin, None, None, moves, "", record(rnd, pw, q, False, f"no standard design meets the "
                                                                         f"{len(pr.q)} pose(s) of round {rnd}")
        opt, n, mv, oa = out
        moves += mv
    return pr, margin, opt, n, moves, oa, record(max_rounds, pw, q, False, f"round limit ({max_rounds}) reached")


def _result(res, pr, margin, opt, n, search, moves, coverage_n, cov_args, why, *, cat, extra, grade_cost, rounded,
            rounded_cost, rounded_p_min, t0, relaxed, limited, start="", oa="") -> CalibratedStandard:
    from tolalloc.allocate.calibrated.design import _coverage_of
    from tolalloc.allocate.calibrated.exact import post_probabilities

    K = len(pr.model.names)
    label = res.design.label
    common = (res.cost, label, rounded, rounded_cost, rounded_p_min, res.region_kind, res.region, search)
    if opt is None:
        d = Design(Solver.DISCRETE_EXACT, "infeasible" if search is None else "failed",
                   time_s=time.perf_counter() - t0, message=why)
        return CalibratedStandard(pr, res.post.split, res.plan, d, ("",) * K, ("",) * K, np.full(K, np.nan),
                                  grade_cost, None, np.zeros(0), *common, None, moves, margin.evaluations,
                                  time.perf_counter() - t0, why, *relaxed, limited)
    t = margin.t_of(cat.u_of(opt, n)[None])[0]
    p_post, post = post_probabilities(pr, res.post.split, res.plan, t)
    short = float((p_post - np.asarray(pr.blocks[0]["target"], float)).min())
    cov = None
    if res.region_kind == "box" and coverage_n:
        k, tol, seed = cov_args
        cov = coverage(pr, None, res.region, n=coverage_n, seed=seed + 12345, k_worst=k, tol=tol,
                       pose_cov=post.tool_covariance)
    elif res.region_kind != "box":
        k, tol, _ = cov_args
        cov = _coverage_of(pr.q, p_post, pr.prob, k, tol)
    status = "optimal" if short >= -RECHECK_TOL else "failed"
    what = ("" if not oa else "; outer approximation on the linearised probability (HiGHS): " + (
        f"converged, no design cheaper by {MIP_REL_GAP:g} meets its linearisations, then the local search again"
        if oa == "converged" else f"stopped ({oa})"))
    msg = (f"rounded down from {start}, then a local search over neighbouring grade vectors under the exact "
           f"post-calibration probability ({moves} move(s)){what}; {margin.evaluations} candidate designs evaluated: "
           "no design one or two grades / steps away is cheaper and meets p at every pose; a local optimum, not a "
           "proven one" if status == "optimal" else
           f"the re-check with the reference posterior falls {-short:.3g} short in probability")
    d = make_design(pr, Solver.DISCRETE_EXACT, t, time_s=time.perf_counter() - t0, message=msg, status=status)
    d = replace(d, cost=cat.total_cost(opt, n) + extra - grade_cost)
    grade, proc = [""] * K, [""] * K
    pc = pr.param_costs(t)
    pc[pr.alloc] = cat.costs_of(opt, n)
    for a, kk in enumerate(pr.alloc):
        grade[kk], proc[kk] = cat.label[opt[a]], cat.process[opt[a]]
    return CalibratedStandard(pr, res.post.split, res.plan, d, tuple(grade), tuple(proc), pc, grade_cost, post,
                              p_post, *common, cov, moves, margin.evaluations, time.perf_counter() - t0, msg, *relaxed,
                              limited, oa)
