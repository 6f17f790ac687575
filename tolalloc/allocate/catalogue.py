"""Standard candidates of every allocatable parameter: the values a drawing may carry, with their cost.

Link lengths (nominal size 0-3150 mm) take ISO 286 grades ``±IT/2`` of their grade range, other
parameters their standard classes or any multiple ``n * step`` of their resolution step, all within the
process limits ``[t_min, t_max]``. Each parameter has *options*: a *listed* option is one value (a grade or
a class) with its cost; a *stepped* option is the range ``n_lo <= n <= n_hi`` of multiples with a cost law.
With processes (:mod:`tolalloc.allocate.processes`) each value exists once per process that attains it, at
that process's cost. The discrete allocation (:mod:`tolalloc.allocate.discrete`) picks one option per
parameter (and ``n`` for a stepped one); a *choice* is the pair of arrays ``(opt, n)``, shape (Ka,) each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.problem import AllocationProblem
from tolalloc.allocate.standards import ANGLE_STEP_DEG, IT_SIZES_MM, IT_TABLE_UM, it_row
from tolalloc.exceptions import TolallocError

__all__ = ["Catalogue", "build_catalogue", "LENGTH_STEP_MM"]

#: Default resolution of length tolerances that are not ISO 286 sizes [mm].
LENGTH_STEP_MM = 0.001


@dataclass(frozen=True, eq=False)
class Catalogue:
    """Options of the allocatable parameters (``problem.alloc`` order), flattened (M options).

    Attributes
    ----------
    param : array of int, shape (M,)
        Allocatable parameter (0..Ka-1) of each option; a parameter's options are contiguous.
    stepped : array of bool, shape (M,)
    t, cost : arrays, shape (M,)
        Half-width [mm or rad] and cost of a listed option (NaN for stepped ones).
    step : array, shape (M,)
        Step [mm or rad] of a stepped option (NaN for listed ones).
    n_lo, n_hi : arrays of int, shape (M,)
        Range of the multiple ``n`` of a stepped option.
    law : tuple of CostModel or None, (M,)
        Cost law of a stepped option.
    label, process : tuples of str, (M,)
        ``"IT7"``, a class name or ``""``; process name or ``""``.
    group : array of int, shape (M,)
        Index into ``groups`` (part-process pair), -1 without processes.
    groups : tuple of (part, process, setup)
    t_ref : array, shape (Ka,) [mm or rad]
        ``u = (t / t_ref)**2``.
    start : array of int, shape (Ka + 1,)
        Options of parameter ``a``: ``start[a]:start[a + 1]``.
    """

    param: np.ndarray
    stepped: np.ndarray
    t: np.ndarray
    cost: np.ndarray
    step: np.ndarray
    n_lo: np.ndarray
    n_hi: np.ndarray
    law: tuple
    label: tuple
    process: tuple
    group: np.ndarray
    groups: tuple
    t_ref: np.ndarray
    start: np.ndarray

    @property
    def n_params(self) -> int:
        return len(self.start) - 1

    def t_of(self, opt, n) -> np.ndarray:
        """Half-widths (Ka,) [mm or rad] of a choice."""
        opt, n = np.asarray(opt, int), np.asarray(n, float)
        return np.where(self.stepped[opt], n * np.nan_to_num(self.step[opt]), self.t[opt])

    def u_of(self, opt, n) -> np.ndarray:
        return (self.t_of(opt, n) / self.t_ref) ** 2

    def costs_of(self, opt, n) -> np.ndarray:
        """Cost of every parameter (Ka,) of a choice (setups not included)."""
        t = self.t_of(opt, n)
        return np.array([self.law[o].cost(t[a]) if self.stepped[o] else self.cost[o] for a, o in enumerate(opt)])

    def total_cost(self, opt, n) -> float:
        """Cost of a choice, setups of the part-process pairs used included."""
        used = {int(g) for g in self.group[np.asarray(opt, int)] if g >= 0}
        return float(self.costs_of(opt, n).sum() + sum(self.groups[g][2] for g in used))

    def coupled(self, opt) -> bool:
        """Whether every part uses one process only."""
        seen: dict = {}
        for g in self.group[np.asarray(opt, int)]:
            if g >= 0 and seen.setdefault(self.groups[g][0], g) != g:
                return False
        return True

    def round_down(self, t) -> tuple[np.ndarray, np.ndarray]:
        """The choice with the largest value at or below ``t`` (Ka,) per parameter (cheapest on ties); the
        smallest value where none lies below. Processes are ignored (check :meth:`coupled`)."""
        t = np.asarray(t, float)
        opt, n = np.empty(self.n_params, int), np.zeros(self.n_params, int)
        for a in range(self.n_params):
            best = None
            for o in range(self.start[a], self.start[a + 1]):
                if self.stepped[o]:
                    k = int(np.clip(np.floor(t[a] / self.step[o] * (1 + 1e-12)), self.n_lo[o], self.n_hi[o]))
                    val = k * self.step[o]
                else:
                    k, val = 0, self.t[o]
                ok = val <= t[a] * (1 + 1e-12)
                cost = self.law[o].cost(val) if self.stepped[o] else self.cost[o]
                key = (ok, val if ok else -val, -cost)
                if best is None or key > best[0]:
                    best = (key, o, k)
            opt[a], n[a] = best[1], best[2]
        return opt, n

    def finest(self) -> tuple[np.ndarray, np.ndarray]:
        """Every parameter at its smallest value."""
        return self.round_down(np.zeros(self.n_params))


def build_catalogue(problem: AllocationProblem, *, angle_step_deg: float | None = None,
                    length_step_mm: float = LENGTH_STEP_MM) -> Catalogue:
    """The standard options of ``problem``'s allocatable parameters.

    Parameters
    ----------
    problem : AllocationProblem
    angle_step_deg : float, optional
        Resolution of every angle tolerance without classes [deg] (replaces the costs file's ``step_deg``);
        default the costs file's, else 1 arcsec.
    length_step_mm : float
        Default resolution of length tolerances that are neither graded nor classed [mm].
    """
    if angle_step_deg is not None and not (np.isfinite(angle_step_deg) and angle_step_deg > 0):
        raise TolallocError(f"angle_step_deg: expected a number > 0 [deg] (e.g. 0.0002778 for 1 arcsec), got "
                            f"{angle_step_deg!r}.")
    lengths = {lk.name: lk.length_mm for lk in problem.model.robot.links}
    params = problem.model.params
    cols = {k: [] for k in ("param", "stepped", "t", "cost", "step", "n_lo", "n_hi", "law", "label", "process",
                            "group")}
    groups: dict = {}
    start = [0]
    for a, k in enumerate(problem.alloc):
        p, spec = params[k], problem.costs.spec(k)
        lo, hi = problem.t_min[k], problem.t_max[k]
        listed, step, what = _values(p, spec, lengths.get(p.element, 0.0), angle_step_deg, length_step_mm)
        m0 = len(cols["param"])
        for opt in spec.processes or (None,):
            g = -1
            if opt is not None:
                g = groups.setdefault((p.element, opt.name), (len(groups), opt.setup))[0]
            row = {"param": a, "process": "" if opt is None else opt.name, "group": g}
            if listed is None:
                plo, phi = (lo, hi) if opt is None else (max(lo, opt.t_lo), min(hi, opt.t_hi))
                n_lo = max(1, int(np.ceil(plo / step * (1 - 1e-12))))
                n_hi = int(np.floor(phi / step * (1 + 1e-12)))
                if n_lo <= n_hi:
                    law = problem.costs.models[k] if opt is None else opt.law
                    _add(cols, row, stepped=True, t=np.nan, cost=np.nan, step=step, n_lo=n_lo, n_hi=n_hi, law=law,
                         label="")
                continue
            for t, lab in listed:
                if not lo * (1 - 1e-12) <= t <= hi * (1 + 1e-12) or (opt is not None and not opt.attains(t, lab)):
                    continue
                c = float(problem.costs.models[k].cost(t)) if opt is None else opt.cost(t, lab)
                _add(cols, row, stepped=False, t=t, cost=c, step=np.nan, n_lo=0, n_hi=0, law=None, label=lab)
        if len(cols["param"]) == m0:
            f, unit = p.to_interface, p.interface_unit
            via = f" attainable by its processes ({', '.join(o.name for o in spec.processes)})" if spec.processes else ""
            raise TolallocError(f"standard values of {p.name}: none of its {what}{via} lies within its process limits "
                                f"[{lo * f:.4g}, {hi * f:.4g}] {unit}; widen the grades (grades = \"IT5-IT12\"), the "
                                "classes, the step or the limits in the costs file.")
        start.append(len(cols["param"]))
    glist = sorted((i, part, proc, setup) for (part, proc), (i, setup) in groups.items())
    arr = {k: np.array(cols[k], dtype=float if k in ("t", "cost", "step") else int)
           for k in ("param", "t", "cost", "step", "n_lo", "n_hi", "group")}
    return Catalogue(arr["param"], np.array(cols["stepped"], bool), arr["t"], arr["cost"], arr["step"], arr["n_lo"],
                     arr["n_hi"], tuple(cols["law"]), tuple(cols["label"]), tuple(cols["process"]), arr["group"],
                     tuple((part, proc, setup) for _, part, proc, setup in glist), problem.t_ref[problem.alloc].copy(),
                     np.array(start, int))


def _add(cols: dict, row: dict, **kw) -> None:
    for key, val in {**row, **kw}.items():
        cols[key].append(val)


def _values(p, spec, size_mm: float, angle_step_deg, length_step_mm):
    """``(listed [(t, label)] or None, step or None, description)`` of one parameter."""
    if spec.grades is not None and p.kind == "link_length" and 0 < size_mm <= IT_SIZES_MM[-1]:
        g0, g1 = spec.grades
        widths = IT_TABLE_UM[it_row(size_mm), g0 - 1:g1] / 1000.0
        return ([(w / 2.0, f"IT{g}") for g, w in zip(range(g0, g1 + 1), widths)], None,
                f"grades IT{g0}-IT{g1} (nominal {size_mm:g} mm: ±{widths[0] / 2:.4g} .. ±{widths[-1] / 2:.4g} mm)")
    if spec.classes is not None:
        return [(t, lab) for lab, t in spec.classes], None, "standard classes"
    if p.unit == "mm":
        step = spec.step if spec.step is not None else length_step_mm
    else:
        step = np.deg2rad(angle_step_deg) if angle_step_deg is not None else (
            spec.step if spec.step is not None else np.deg2rad(ANGLE_STEP_DEG))
    return None, float(step), f"multiples of the step {step * p.to_interface:.4g} {p.interface_unit}"
