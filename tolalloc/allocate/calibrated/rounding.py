"""Rounding a calibration-aware design down to the catalogue, and the catalogue's range as a continuous relaxation.

* :func:`coupled_round_down`: every allocatable tolerance to the largest standard value at or below it
  (:meth:`tolalloc.allocate.catalogue.Catalogue.round_down`), one process per part;
* :func:`catalogue_range`: finest and coarsest standard value per parameter;
* :func:`range_relaxation`: the continuous calibration-aware design (certified, then exact) with every tolerance
  confined to that range -- the continuous problem whose only difference from the standard one is the steps
  between standard values (a local optimum of IPOPT, not a proven bound).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.allocate.catalogue import Catalogue
from tolalloc.allocate.problem import AllocationProblem

__all__ = ["coupled_round_down", "catalogue_range", "range_relaxation"]


def _round_one(cat: Catalogue, a: int, t: float, groups=None) -> tuple[tuple, int, int]:
    """``(key, option, n)`` of parameter ``a`` rounded down (options of ``groups`` only, if given)."""
    best = None
    for o in range(cat.start[a], cat.start[a + 1]):
        if groups is not None and cat.group[o] not in groups:
            continue
        if cat.stepped[o]:
            k = int(np.clip(np.floor(t / cat.step[o] * (1 + 1e-12)), cat.n_lo[o], cat.n_hi[o]))
            val, cost = k * cat.step[o], float(cat.law[o].cost(k * cat.step[o]))
        else:
            k, val, cost = 0, cat.t[o], float(cat.cost[o])
        ok = val <= t * (1 + 1e-12)
        key = (ok, val if ok else -val, -cost)
        if best is None or key > best[0]:
            best = (key, o, k)
    return best


def coupled_round_down(cat: Catalogue, t) -> tuple[np.ndarray, np.ndarray]:
    """:meth:`Catalogue.round_down`, with one process per part: where the rounding mixes processes in a part, every
    process of the part is tried for all its parameters and the one whose values all lie at or below ``t`` (else the
    one with most such values) at the lowest cost is kept."""
    t = np.asarray(t, float)
    opt, n = cat.round_down(t)
    if cat.coupled(opt):
        return opt, n
    parts: dict = {}
    for g, (part, _proc, _setup) in enumerate(cat.groups):
        parts.setdefault(part, []).append(g)
    for part, gs in parts.items():
        members = [a for a in range(cat.n_params)
                   if any(cat.group[o] in gs for o in range(cat.start[a], cat.start[a + 1]))]
        best = None
        for g in gs:
            picks = [_round_one(cat, a, t[a], {g}) for a in members]
            if any(p is None for p in picks):
                continue
            below = sum(p[0][0] for p in picks)
            cost = -sum(p[0][2] for p in picks) + cat.groups[g][2]
            if best is None or (below, -cost) > best[0]:
                best = ((below, -cost), picks)
        for a, (_key, o, k) in zip(members, best[1]):
            opt[a], n[a] = o, k
    return opt, n


def catalogue_range(cat: Catalogue) -> tuple[np.ndarray, np.ndarray]:
    """Finest and coarsest standard value (Ka,) [mm or rad] of every allocatable parameter."""
    lo, hi = np.full(cat.n_params, np.inf), np.zeros(cat.n_params)
    for o in range(len(cat.param)):
        a = cat.param[o]
        vals = (cat.n_lo[o] * cat.step[o], cat.n_hi[o] * cat.step[o]) if cat.stepped[o] else (cat.t[o],)
        lo[a], hi[a] = min(lo[a], *vals), max(hi[a], *vals)
    return lo, hi


def range_relaxation(pr: AllocationProblem, cat: Catalogue, plan, split, *,
                     exact: bool = True) -> tuple[float, str, np.ndarray | None]:
    """``(cost, label, t)`` of the continuous calibration-aware design on ``pr``'s poses with every tolerance confined
    to its catalogue's range (certified, then with ``exact`` exact: the stages of the continuous design it is compared
    with; ``(nan, "", None)`` when infeasible). ``split``: unresolved grades. ``t`` (K,) [mm or rad]: its
    half-widths."""
    from tolalloc.allocate.calibrated.certified import allocate_calibrated
    from tolalloc.allocate.calibrated.exact import solve_calibrated_exact

    lo, hi = catalogue_range(cat)
    t_min, t_max = pr.t_min.copy(), pr.t_max.copy()
    t_min[pr.alloc] = np.maximum(t_min[pr.alloc], lo)
    t_max[pr.alloc] = np.minimum(t_max[pr.alloc], hi)
    cert = allocate_calibrated(replace(pr, t_min=t_min, t_max=t_max), plan, split=split)
    if not cert.design.ok:
        return float("nan"), "", None
    ex = solve_calibrated_exact(cert, plan, split) if exact else None
    if ex is not None and ex.accepted:
        return ex.cost, "exact", ex.design.t
    return float(cert.design.cost + cert.grade_cost), "certified", cert.design.t
