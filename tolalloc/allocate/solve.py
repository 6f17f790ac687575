"""The allocation driver: certified design (both rules), exact design, process-limit check, snapping.

Imports the stages below it (problem, convex, exact, result) and nothing imports it back.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.allocate.convex import solve_certified
from tolalloc.allocate.exact import solve_exact
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Solver, check_process_limits, make_design
from tolalloc.allocate.result import AllocationResult, snap_design
from tolalloc.exceptions import TolallocError

__all__ = ["allocate"]


def allocate(problem: AllocationProblem, *, solver: str = "exact", snap: bool = True,
             angle_step_deg: float | None = None) -> AllocationResult:
    """Allocate tolerances: certified (both rules) and, for ``solver="exact"``, exact; check_process_limits; snap.

    Parameters
    ----------
    problem : AllocationProblem
    solver : {"exact", "certified"}
        Which design is returned as ``design`` (the certified one is always computed).
    snap : bool
        Snap ``design`` to standard grades and re-check.
    angle_step_deg : float, optional
        Angle step for snapping (default 1 arcsec).
    """
    if solver not in ("exact", "certified"):
        raise TolallocError(f"solver: expected 'exact' or 'certified', got {solver!r}.")
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
    std, grades = (None, ("",) * len(problem.costs.names))
    if snap and design.t is not None and status == "optimal":
        std, grades = snap_design(problem, design, angle_step_deg=angle_step_deg)
    return AllocationResult(problem, status, solver, design, cert, other, exact, std, grades, diag, msg)


def _tightest(problem: AllocationProblem):
    """Every allocatable tolerance at its lower process limit, fixed ones at their value (a reference design)."""
    t = problem.t_min.copy()
    t[problem.fixed] = np.array(problem.costs.fixed_tol)[problem.fixed]
    return make_design(problem, Solver.PROCESS_LIMITS, t)
