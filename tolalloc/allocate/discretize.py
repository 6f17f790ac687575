"""The standard design: grades, classes, steps and processes chosen by the optimiser instead of by rounding.

:func:`discretize` takes the continuous designs of an allocation and returns the cheapest standard design
it can establish (:class:`DiscreteAllocation`):

* for a **certified** design, the discrete optimum of the certified rules (trace and eigenvalue), proven by
  the mixed-integer program of :mod:`tolalloc.allocate.discrete` (a rule whose continuous optimum already
  costs more than the other rule's discrete optimum is skipped: the continuous optimum bounds its discrete
  one from below);
* for an **exact** design, the outer approximation and local search of :mod:`tolalloc.allocate.discrete_exact`
  under the Gaussian probability, started from the cheapest known standard design that meets it (the
  continuous design rounded down, and the certified discrete optimum when computed).

The premium over the continuous design (``gap_pct``) is reported beside that of the rounding it replaces
(``rounded_premium_pct``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from tolalloc.allocate.catalogue import Catalogue, build_catalogue
from tolalloc.allocate.discrete import MIP_REL_GAP, RuleOutcome
from tolalloc.allocate.discrete_rules import solve_discrete_rule
from tolalloc.allocate.discrete_exact import exact_margin, solve_discrete_exact
from tolalloc.allocate.problem import NOT_CONVERGED, AllocationProblem, Design, Solver, make_design

__all__ = ["DiscreteAllocation", "discretize"]

_SOLVER = {"trace": Solver.DISCRETE_TRACE, "lmi": Solver.DISCRETE_LMI, "exact": Solver.DISCRETE_EXACT}


@dataclass(frozen=True, eq=False)
class DiscreteAllocation:
    """Result of :func:`discretize`.

    Attributes
    ----------
    design : Design
        The standard design (``discrete-exact``, ``discrete-lmi`` or ``discrete-trace``); if no discrete solve
        gave one, the rounded design with ``fallback_from`` set (or a design with status ``failed``).
    grade : tuple of str, (K,)
        ``"IT7"``, a class name, or ``""`` (a multiple of the resolution step, or a fixed parameter).
    process : tuple of str, (K,)
        Process per parameter (``""`` without processes).
    param_cost : array, shape (K,)
        Cost of each parameter in the standard design (its process's cost where it has one; setups not included).
    continuous : Design
        The continuous design it replaces.
    rounded : Design or None
        The continuous design rounded down to standard values (:func:`tolalloc.allocate.result.snap_design`).
    outcomes : tuple of RuleOutcome
        Every discrete solve (``trace``, ``lmi``, ``exact``), in the order run.
    bound : float
        Proven lower bound on the cost of any standard design meeting the design's rule (certified rules:
        the larger of the MILP's dual bound and the continuous optimum; NaN for the exact requirement).
    proven : bool
        ``design`` is the proven discrete optimum of its (certified) rule within :data:`MIP_REL_GAP`.
    time_s : float
    message : str
    """

    design: Design
    grade: tuple
    process: tuple
    param_cost: np.ndarray
    continuous: Design
    rounded: Design | None
    outcomes: tuple
    bound: float
    proven: bool
    time_s: float
    message: str = ""

    @property
    def gap_pct(self) -> float:
        """Premium of the standard design over the continuous design [%]."""
        return 100.0 * (self.design.cost - self.continuous.cost) / self.continuous.cost

    @property
    def rounded_premium_pct(self) -> float:
        """Premium of the rounded design over the continuous design [%] (NaN without one)."""
        if self.rounded is None:
            return float("nan")
        return 100.0 * (self.rounded.cost - self.continuous.cost) / self.continuous.cost

    def message_line(self) -> str:
        """One line for the terminal: the standard design's cost against the continuous and the rounded one."""
        rnd = "" if self.rounded is None else (f"; rounding down would cost {self.rounded.cost:.4f} "
                                               f"({self.rounded_premium_pct:+.2f} %)")
        return (f"standard grades ({self.design.label}): cost {self.design.cost:.4f}, {self.gap_pct:+.2f} % over the "
                f"continuous {self.continuous.label} design ({self.continuous.cost:.4f}){rnd}; {self.message}")

    def to_dict(self) -> dict:
        """JSON-ready ``discrete`` block of summary.json."""
        def num(x):
            return None if x is None or not np.isfinite(x) else float(x)

        return {
            "solver": str(self.design.solver), "status": self.design.status, "label": self.design.label,
            "cost": num(self.design.cost), "continuous_cost": num(self.continuous.cost),
            "continuous_solver": str(self.continuous.solver),
            "rounded_cost": None if self.rounded is None else num(self.rounded.cost),
            "rounded_meets": None if self.rounded is None else self.rounded.status == "optimal",
            "gap_pct": num(self.gap_pct), "rounded_premium_pct": num(self.rounded_premium_pct),
            "bound": num(self.bound), "proven_optimal": self.proven, "mip_rel_gap": MIP_REL_GAP,
            "time_s": self.time_s, "message": self.message,
            "solves": [{"rule": o.rule, "status": o.status, "cost": num(o.cost), "bound": num(o.bound),
                        "programs": o.mips, "time_s": o.time_s, "message": o.message} for o in self.outcomes],
        }


def _labels(problem: AllocationProblem, cat: Catalogue, opt) -> tuple[tuple, tuple]:
    K = len(problem.costs.names)
    grade, proc = [""] * K, [""] * K
    for a, k in enumerate(problem.alloc):
        grade[k], proc[k] = cat.label[opt[a]], cat.process[opt[a]]
    return tuple(grade), tuple(proc)


def _rules(problem, cat, certified, time_limit) -> list:
    """Discrete optima of the certified rules, cheaper continuous rule first; the other skipped when its
    continuous optimum (a lower bound without processes) already costs more than the first's discrete one."""
    conts = sorted([d for d in certified if d is not None and d.ok and d.solver.certified], key=lambda d: d.cost)
    out = []
    for d in conts:
        best = min((o.cost for o in out if o.opt is not None), default=np.inf)
        if not cat.groups and d.cost >= best:
            continue
        out.append(solve_discrete_rule(problem, cat, str(d.solver).split("-")[1], d, time_limit=time_limit))
    return out


def discretize(problem: AllocationProblem, continuous: Design, *, certified=(), rounded: Design | None = None,
               angle_step_deg: float | None = None, certified_first: bool = True,
               time_limit: float = 120.0) -> DiscreteAllocation:
    """The cheapest standard design for ``continuous`` (see the module docstring).

    Parameters
    ----------
    problem : AllocationProblem
    continuous : Design
        The continuous design (exact or certified) that the standard design replaces; must be ``ok``.
    certified : sequence of Design
        The continuous optima of the certified rules (``trace``, ``lmi``); their discrete optima are solved
        when ``continuous`` is certified, or when ``certified_first`` is True.
    rounded : Design, optional
        ``continuous`` rounded down to standard values (reported beside; a start for the exact search).
    angle_step_deg : float, optional
        Resolution of angle tolerances [deg] (default the costs file's, else 1 arcsec).
    certified_first : bool
        For an exact ``continuous``: also compute the certified rules' discrete optima (the exact search
        starts from the cheapest). False saves their time (the cutting-plane region loop).
    time_limit : float
        HiGHS time limit per program [s].
    """
    t0 = time.perf_counter()
    cat = build_catalogue(problem, angle_step_deg=angle_step_deg)
    exact = not continuous.solver.certified
    outcomes = _rules(problem, cat, certified, time_limit) if (certified_first or not exact) else []
    if exact:
        starts = [(o.cost, o.opt, o.n) for o in outcomes if o.opt is not None]
        for opt, n in (cat.round_down(continuous.t[problem.alloc]), cat.finest()):
            if cat.coupled(opt) and exact_margin(problem, cat.u_of(opt, n))[0] >= 0:
                starts.append((cat.total_cost(opt, n), opt, n))
                break
        if not starts and cat.groups and not outcomes:  # roundings that mix processes in a part: a certified start
            outcomes = _rules(problem, cat, certified, time_limit)
            starts = [(o.cost, o.opt, o.n) for o in outcomes if o.opt is not None]
        if starts:
            _, opt, n = min(starts, key=lambda x: x[0])
            outcomes.append(solve_discrete_exact(problem, cat, (opt, n), continuous, time_limit=time_limit))
        else:
            fin = cat.finest()
            worst = exact_margin(problem, cat.u_of(*fin))[0]
            outcomes.append(RuleOutcome("exact", "infeasible", None, None, np.nan, np.nan, 0, time.perf_counter() - t0,
                                        f"no standard design meets the requirement: even every parameter at its finest "
                                        f"standard value falls {-worst:.3g} short in probability; allow finer grades, "
                                        "classes or steps (costs file: grades, classes_<unit>, step_<unit>; "
                                        "angle_step_deg)"))
    kind = "exact" if exact else None
    pick = [o for o in outcomes if o.opt is not None and (kind is None or o.rule == kind)]
    dt = time.perf_counter() - t0
    if not pick:
        why = "; ".join(f"{o.rule}: {o.status} ({o.message})" for o in outcomes) or "no standard design meets the requirement"
        return _fallback(problem, continuous, rounded, outcomes, dt, why)
    best = min(pick, key=lambda o: o.cost)
    t = np.array(problem.costs.fixed_tol, dtype=float)
    t[problem.alloc] = cat.t_of(best.opt, best.n)
    proven = best.rule != "exact" and best.status == "optimal"
    status = "optimal" if best.status == "optimal" else NOT_CONVERGED
    msg = _message(best, proven)
    d = make_design(problem, _SOLVER[best.rule], t, time_s=dt, message=msg, status=status)
    fixed = float(problem.param_costs(t)[problem.fixed].sum())  # parts the costs file fixes cost as they are
    d = replace(d, cost=cat.total_cost(best.opt, best.n) + fixed)  # setups of the processes included
    grade, proc = _labels(problem, cat, best.opt)
    pc = problem.param_costs(t)
    pc[problem.alloc] = cat.costs_of(best.opt, best.n)
    bound = max(best.bound + fixed, continuous.cost if continuous.solver.certified and not cat.groups else -np.inf) \
        if best.rule != "exact" else float("nan")
    return DiscreteAllocation(d, grade, proc, pc, continuous, rounded, tuple(outcomes), float(bound), proven, dt, msg)


def _message(best: RuleOutcome, proven: bool) -> str:
    if best.rule == "exact":
        return (f"standard values under the exact probability ({best.message}); meets the requirement at every pose "
                "(re-checked with the exact Gaussian probability); not a proven optimum")
    if proven:
        return (f"discrete optimum of the {best.rule} rule over the standard values, proven by the MILP "
                f"(HiGHS, relative gap <= {MIP_REL_GAP:g}); the rule holds at every pose (re-checked)")
    return f"{best.rule} rule met at every pose, optimum not proven: {best.message}"


def _fallback(problem, continuous, rounded, outcomes, dt, why) -> DiscreteAllocation:
    """No discrete design: the rounded one (if it meets the requirement), labelled as a fallback."""
    kind = Solver.DISCRETE_LMI if continuous.solver.certified else Solver.DISCRETE_EXACT
    msg = f"no discrete design: {why}"
    if rounded is not None and rounded.ok:
        d = replace(rounded, fallback_from=kind, message=f"{msg}; kept the rounded design ({rounded.message})")
    else:
        infeasible = bool(outcomes) and all(o.status == "infeasible" for o in outcomes)
        d = Design(kind, "infeasible" if infeasible else "failed", time_s=dt, message=msg)
    K = len(problem.costs.names)
    pc = problem.param_costs(d.t) if d.t is not None else np.full(K, np.nan)
    return DiscreteAllocation(d, ("",) * K, ("",) * K, pc, continuous, rounded, tuple(outcomes), float("nan"), False,
                              dt, d.message)
