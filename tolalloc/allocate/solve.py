"""The allocation driver: certified design (both rules), exact design, process-limit check, standard design.

Imports the stages below it (problem, convex, exact, result) and nothing imports it back.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.allocate.convex import solve_certified
from tolalloc.allocate.discretize import discretize
from tolalloc.allocate.exact import solve_exact
from tolalloc.allocate.limits import check_process_limits
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Solver, make_design
from tolalloc.allocate.result import AllocationResult, snap_design
from tolalloc.exceptions import TolallocError, describe

__all__ = ["allocate", "with_standard"]


def allocate(problem: AllocationProblem, *, solver: str = "exact", snap: bool = True,
             angle_step_deg: float | None = None, discrete: bool = True, discrete_certified: bool = False,
             time_limit_s: float = 120.0) -> AllocationResult:
    """Allocate tolerances: certified (both rules) and, for ``solver="exact"``, exact; check_process_limits; the
    standard design.

    Parameters
    ----------
    problem : AllocationProblem
    solver : {"exact", "certified"}
        Which design is returned as ``design`` (the certified one is always computed).
    snap : bool
        Compute the standard design (``standard``) and the rounded one (``rounded``); False: neither.
    angle_step_deg : float, optional
        Resolution of angle tolerances [deg] (default 1 arcsec, or the costs file's ``step_deg``).
    discrete : bool
        The standard design is chosen by the optimiser (:func:`tolalloc.allocate.discretize.discretize`);
        False: ``design`` rounded down to standard values, as ``rounded``.
    discrete_certified : bool
        With ``solver="exact"``: also solve the certified rules' discrete optima (reported in
        ``discrete.outcomes``; the exact search then starts from the cheapest).
    time_limit_s : float
        Time limit of each mixed-integer program [s].
    """
    if solver not in ("exact", "certified"):
        raise TolallocError(f"solver: expected 'exact' or 'certified', got {solver!r}.")
    _check_flags(snap=snap, discrete=discrete, discrete_certified=discrete_certified, time_limit_s=time_limit_s)
    diag = check_process_limits(problem)
    cert, other = solve_certified(problem)
    exact = None
    if solver == "exact" and diag.feasible:
        exact = solve_exact(problem, cert if cert.ok else None)
    chosen = exact if solver == "exact" else cert
    if not diag.feasible:
        design = replace(_tightest(problem), status="infeasible", message=diag.message)
        status, msg = "infeasible", diag.message
    elif chosen is not None and chosen.status == NOT_CONVERGED:
        design, status = chosen, NOT_CONVERGED
        msg = (f"the {chosen.solver} solver did not converge ({chosen.message}); its design is shown for reference "
               "only: not certified, not exact, not verified")
    elif chosen is None or not chosen.ok:
        status = "infeasible"
        msg = ("the certified rules (trace and eigenvalue) cannot be met within the process limits, although the "
               "exact requirement can (the tightest design meets it); use --solver exact"
               if solver == "certified" else f"the exact solver found no design: {chosen.message if chosen else ''}")
        design = replace(_tightest(problem), status="infeasible", message=msg)
    else:
        design, status, msg = chosen, "optimal", chosen.message
    res = AllocationResult(problem, status, solver, design, cert, other, exact, None, ("",) * len(problem.costs.names),
                           diag, msg)
    if not snap:
        return res
    return with_standard(res, angle_step_deg=angle_step_deg, discrete=discrete, discrete_certified=discrete_certified,
                         time_limit_s=time_limit_s)


def with_standard(result: AllocationResult, *, angle_step_deg: float | None = None, discrete: bool = True,
                  discrete_certified: bool = False, time_limit_s: float = 120.0) -> AllocationResult:
    """``result`` with its standard design (``standard``, ``rounded``, ``discrete``, ``it_grade``) (re)computed.

    For a result solved with ``snap=False`` (e.g. by the region's cutting planes); a result without an optimal
    ``design`` is returned unchanged. Keywords as :func:`allocate`.
    """
    _check_flags(discrete=discrete, discrete_certified=discrete_certified, time_limit_s=time_limit_s)
    problem, design = result.problem, result.design
    if result.status != "optimal" or design.t is None:
        return result
    rounded, rgrades = snap_design(problem, design, angle_step_deg=angle_step_deg)
    std, grades, disc = rounded, rgrades, None
    if discrete:
        disc = discretize(problem, design, certified=(result.certified, result.certified_other), rounded=rounded,
                          angle_step_deg=angle_step_deg, certified_first=discrete_certified, time_limit=time_limit_s)
        std = disc.design
        if disc.design.fallback_from is None:
            grades = tuple(g if g.startswith("IT") else "" for g in disc.grade)
    return replace(result, standard=std, it_grade=grades, rounded=rounded, discrete=disc, rounded_grade=rgrades)


def _check_flags(time_limit_s, **flags) -> None:
    for name, v in flags.items():
        if not isinstance(v, (bool, np.bool_)):
            raise TolallocError(f"{name}: expected True or False, got {describe(v)}.")
    if isinstance(time_limit_s, bool) or not (isinstance(time_limit_s, (int, float)) and np.isfinite(time_limit_s)
                                              and time_limit_s > 0):
        raise TolallocError(f"time_limit_s: expected a number of seconds > 0 (e.g. 120), got {time_limit_s!r}.")


def _tightest(problem: AllocationProblem):
    """Every allocatable tolerance at its lower process limit, fixed ones at their value (a reference design)."""
    t = problem.t_min.copy()
    t[problem.fixed] = np.array(problem.costs.fixed_tol)[problem.fixed]
    return make_design(problem, Solver.PROCESS_LIMITS, t)
