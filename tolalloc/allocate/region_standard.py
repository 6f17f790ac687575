"""The standard design over a joint-space region: the cutting planes continued with the discrete step inside.

:func:`tolalloc.allocate.region.allocate_region` finds the active poses for the continuous design. A standard
design chosen on those poses has other slack and may fall short elsewhere in the region, so the loop goes
on with the design that will be built: choose the standard design on the active set
(:func:`tolalloc.allocate.solve.with_standard`), search the region for its worst pose
(:func:`tolalloc.allocate.region.search_region`), add that pose if it falls more than ``tol`` below ``p``, repeat.
With an orientation requirement both requirements are searched and the worst pose of each one that falls short is
added, as in the continuous loop.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.problem import build_problem
from tolalloc.allocate.region import Region, RegionAllocation, allocate_region, search_region
from tolalloc.exceptions import TolallocError

__all__ = ["StandardRegionAllocation", "allocate_region_standard"]


@dataclass(frozen=True, eq=False)
class StandardRegionAllocation(RegionAllocation):
    """Result of :func:`allocate_region_standard`: the fields of :class:`RegionAllocation` for the standard design
    (``result.standard`` is the design searched; ``rounds`` counts the standard loop's rounds, ``evaluations`` and
    ``time_s`` include the continuous loop), and:

    Attributes
    ----------
    continuous : RegionAllocation
        The continuous cutting planes it continued.
    message : str
    """

    continuous: RegionAllocation | None = None
    message: str = ""


def allocate_region_standard(model, region: Region, q0=None, *, solver: str = "exact", tol: float = 1e-4,
                             max_rounds: int = 30, seed: int = 0, n_seed: int = 512, n_starts: int = 6,
                             angle_step_deg: float | None = None, discrete_certified: bool = False,
                             time_limit_s: float = 120.0, continuous: RegionAllocation | None = None,
                             **problem_kw) -> StandardRegionAllocation:
    """Standard design that holds over a box: the continuous cutting planes, then the same with the discrete step.

    Parameters
    ----------
    model : ErrorModel
    region : Region
    q0 : array, shape (A0, n), optional
        Initial active poses of the continuous loop (default: the box centre).
    solver : {"exact", "certified"}
    tol : float
        Stop when ``p - worst P`` of the standard design is below ``tol`` (for every requirement).
    max_rounds : int
        Rounds of each loop (continuous, then standard).
    angle_step_deg, discrete_certified, time_limit_s
        As :func:`tolalloc.allocate.solve.allocate`.
    continuous : RegionAllocation, optional
        A finished continuous loop to continue (saves running it again); ``q0`` is then ignored.
    problem_kw
        Passed to :func:`tolalloc.allocate.problem.build_problem` (radius_mm, prob, costs, ...).
    """
    from tolalloc.allocate.solve import allocate, with_standard

    if not isinstance(max_rounds, (int, np.integer)) or max_rounds < 1:
        raise TolallocError(f"max_rounds: expected a whole number >= 1, got {max_rounds!r}.")
    t0 = time.perf_counter() - (continuous.time_s if continuous is not None else 0.0)  # time of the loop continued
    ra = continuous if continuous is not None else allocate_region(
        model, region, q0, solver=solver, tol=tol, max_rounds=max_rounds, seed=seed, n_seed=n_seed, n_starts=n_starts,
        **problem_kw)
    kw = dict(angle_step_deg=angle_step_deg, discrete_certified=discrete_certified, time_limit_s=time_limit_s)
    res = ra.result
    d = res.design if solver == "exact" else res.certified
    if not d.ok:  # infeasible (or not converged) on the active set: nothing to make standard
        return _out(ra, res, ra.active_q, 0, ra.worst_p, ra.worst_q, ra.evaluations, False, t0, (),
                    "the continuous region allocation has no design; no standard design",
                    ra.worst_p_angle, ra.worst_q_angle)
    active, evals, hist = ra.active_q, ra.evaluations, []
    res = with_standard(res, **kw)
    for rnd in range(1, max_rounds + 1):
        std = res.standard
        if std is None or not std.ok:
            return _out(ra, res, active, rnd, np.nan, active[-1], evals, False, t0, tuple(hist),
                        f"no standard design on the active set: {'' if std is None else std.message}")
        w = search_region(res.problem, std.t, region, n_seed=n_seed, n_starts=n_starts, seed=seed + 1000 + rnd,
                          fixed=ra.static)
        evals += w.evaluations
        hist.append(w.history_row(rnd, float(std.cost)))
        cuts = w.cuts(res.problem, tol)
        if not len(cuts):
            return _out(ra, res, active, rnd, w.p, w.q, evals, True, t0, tuple(hist),
                        f"standard design holds over the region: worst linear P found {_found(w)}", w.p_angle,
                        w.q_angle)
        active = np.vstack([active, cuts])
        res = allocate(build_problem(model, active, **problem_kw), solver=solver, snap=True, discrete=True, **kw)
        if res.status != "optimal":
            return _out(ra, res, active, rnd, w.p, w.q, evals, False, t0, tuple(hist),
                        f"the allocation on the grown active set is {res.status}: {res.message}", w.p_angle, w.q_angle)
    return _out(ra, res, active, max_rounds, w.p, w.q, evals, False, t0, tuple(hist),
                f"round limit reached: the standard design falls to {_found(w, 'P = ')} in the region", w.p_angle,
                w.q_angle)


def _found(w, prefix: str = "") -> str:
    """The worst linear P found, per requirement when there is an orientation requirement."""
    if w.p_angle is None:
        return f"{prefix}{w.p:.5f}"
    return f"{prefix}{w.p:.5f} (position), {prefix}{w.p_angle:.5f} (orientation)"


def _out(ra, res, active, rounds, pw, q, evals, converged, t0, hist, msg, pa=None, qa=None) -> StandardRegionAllocation:
    return StandardRegionAllocation(res, ra.region, active, rounds, float(pw), np.asarray(q), int(evals), ra.static,
                                    bool(converged), time.perf_counter() - t0, hist,
                                    None if pa is None else float(pa), None if qa is None else np.asarray(qa),
                                    continuous=ra, message=msg)
