"""Result of :func:`tolalloc.allocate.calibrated.standard.standardize_calibrated`: the standard-grade design of a
calibration-aware allocation, its costs against the continuous and the rounded design, where it was checked."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.calibrated.region import RegionSearch
from tolalloc.allocate.problem import AllocationProblem, Design
from tolalloc.allocate.region import Coverage, Region

__all__ = ["CalibratedStandard", "RECHECK_TOL"]

#: Slack on the re-check with the reference posterior: the search's fast evaluation and
#: :func:`tolalloc.calibration.posterior.posterior` agree to rounding (about 1e-15 in probability).
RECHECK_TOL = 1e-12


@dataclass(frozen=True, eq=False)
class CalibratedStandard:
    """Result of :func:`standardize_calibrated`.

    Attributes
    ----------
    problem : AllocationProblem
        On the final poses (the pose set, the trajectory, or the box's active set grown by the standard loop).
    split : ErrorSplit
        The split of the continuous design (repeatability grades set).
    plan : CalibrationPlan
    design : Design
        The standard design (``solver`` ``discrete-exact``); status ``failed`` / ``infeasible`` when none was found.
    grade, process : tuple of str, (K,)
        ``"IT7"``, a class name or ``""`` per parameter; process name or ``""``.
    param_cost : array, shape (K,)
        Cost of each parameter in the standard design (its process's cost where it has one).
    grade_cost : float
        Repeatability grades (kept at the continuous design's values).
    post : Posterior or None
        Post-calibration statistics of the standard design (reference :func:`~tolalloc.calibration.posterior.posterior`).
    p_post : array, shape (P,)
        Post-calibration ``P`` at ``problem``'s poses (reference posterior).
    continuous_cost : float
    continuous_label : str
    rounded : Design or None
        The continuous design rounded down (on the continuous design's poses).
    rounded_cost : float
        Its cost (repeatability grades and process setups included).
    rounded_p_min : float
        Its lowest post-calibration ``P`` on the continuous design's poses.
    relaxed_cost : float
        The continuous calibration-aware design (certified, then exact) on the continuous design's poses with every
        tolerance confined to its catalogue's range (coarsest to finest standard value): what is left of the premium
        above it is due to the steps between standard values, the rest to the range (NaN when not computed).
    relaxed_label : str
        ``exact``, ``certified`` (the exact stage was refused) or ``""``.
    range_limited : tuple of str
        Parameters whose continuous tolerance lies above their coarsest standard value.
    outer_approximation : str
        ``converged`` (its program had no cheaper design left), the reason it stopped, or ``""`` (not run).
    region_kind : {"poses", "trajectory", "box"}
    region : Region or None
    search : RegionSearch or None
        The standard loop's worst-pose search (box only).
    coverage : Coverage or None
        Fresh box sample, or every pose of a pose set / trajectory (exact).
    moves : int
        Local-search moves of all rounds.
    evaluations : int
        Candidate designs whose post-calibration probability was evaluated.
    time_s : float
    message : str
    """

    problem: AllocationProblem
    split: object
    plan: object
    design: Design
    grade: tuple
    process: tuple
    param_cost: np.ndarray
    grade_cost: float
    post: object
    p_post: np.ndarray
    continuous_cost: float
    continuous_label: str
    rounded: Design | None
    rounded_cost: float
    rounded_p_min: float
    region_kind: str
    region: Region | None
    search: RegionSearch | None
    coverage: Coverage | None
    moves: int
    evaluations: int
    time_s: float
    message: str = ""
    relaxed_cost: float = float("nan")
    relaxed_label: str = ""
    range_limited: tuple = ()
    outer_approximation: str = ""

    @property
    def cost(self) -> float:
        """Parts (setups of processes included) plus repeatability grades."""
        return float(self.design.cost + self.grade_cost)

    @property
    def rounded_meets(self) -> bool:
        """Whether the rounded design meets ``p`` at every pose of the continuous design."""
        return bool(np.isfinite(self.rounded_p_min) and self.rounded_p_min >= self.problem.prob - RECHECK_TOL)

    @property
    def premium_pct(self) -> float:
        """Premium of the standard design over the continuous calibration-aware design [%]."""
        return 100.0 * (self.cost / self.continuous_cost - 1.0) if self.design.ok else float("nan")

    @property
    def rounded_premium_pct(self) -> float:
        """Premium of plain rounding down over the continuous design [%]."""
        return 100.0 * (self.rounded_cost / self.continuous_cost - 1.0)

    @property
    def range_premium_pct(self) -> float:
        """Premium of the range-confined continuous design over the continuous design [%] (NaN without one)."""
        return 100.0 * (self.relaxed_cost / self.continuous_cost - 1.0)

    @property
    def step_premium_pct(self) -> float:
        """Premium of the standard design over the range-confined continuous design [%] (NaN without one)."""
        return 100.0 * (self.cost / self.relaxed_cost - 1.0) if self.design.ok else float("nan")

    @property
    def ok(self) -> bool:
        """A standard design meeting ``p`` at every pose of its set, converged over the box, coverage clean."""
        return (self.design.ok and (self.search is None or self.search.converged)
                and (self.coverage is None or self.coverage.ok))

    def check_poses(self, k: int = 3) -> np.ndarray:
        """Poses for the end-to-end Monte Carlo (m, n) [rad, mm]: for a box the search's worst pose, the coverage's
        ``k`` worst and the ``k`` active poses of lowest ``P``; else the ``k`` poses of lowest ``P``."""
        from tolalloc.allocate.calibrated.design import _unique_rows

        low = self.problem.q[np.argsort(self.p_post)[:k]]
        if self.region_kind != "box":
            return low
        cov = self.coverage.worst_q[:k] if self.coverage is not None else low[:0]
        return _unique_rows(np.concatenate([self.search.worst_q[None], cov, low]))

    def end_to_end_inputs(self, k: int = 3) -> dict:
        """Keyword arguments of :func:`tolalloc.verify.calibrated.verify_calibration` for the standard design."""
        return {"split": self.post.split, "plan": self.plan, "q_eval": self.check_poses(k),
                "radius_mm": self.problem.radius_mm}

    def worst_p(self) -> float:
        """Lowest post-calibration ``P`` of the standard design wherever it was evaluated."""
        vals = [float(self.p_post.min())] if len(self.p_post) else []
        if self.coverage is not None:
            vals.append(self.coverage.min_p)
        if self.search is not None:
            vals.append(self.search.worst_p)
        return float(min(vals)) if vals else float("nan")

    def message_line(self) -> str:
        """One line for the terminal: the standard design's cost against the continuous and the rounded one."""
        rnd = (f"; rounding down would cost {self.rounded_cost:.4f} ({self.rounded_premium_pct:+.2f} %"
               + ("" if self.rounded_meets else ", and misses p") + ")")
        if not self.design.ok:
            return f"standard grades: none ({self.design.message}){rnd}"
        why = ""
        if np.isfinite(self.relaxed_cost):
            why = (f"; within the catalogue's range the continuous {self.relaxed_label} design costs "
                   f"{self.relaxed_cost:.4f}: {self.range_premium_pct:+.2f} % for the range"
                   + (f" ({', '.join(self.range_limited)} above the coarsest standard value)" if self.range_limited
                      else "") + f", {self.step_premium_pct:+.2f} % for the steps")
        return (f"standard grades ({self.design.label}): cost {self.cost:.4f}, {self.premium_pct:+.2f} % over the "
                f"continuous {self.continuous_label} calibrated design ({self.continuous_cost:.4f}){rnd}{why}; "
                f"{self.design.message}")

    def to_dict(self) -> dict:
        """JSON-ready ``standard`` block of summary.json."""
        def num(x):
            return None if x is None or not np.isfinite(x) else float(x)

        names = self.problem.model.names
        s = self.search
        return {"solver": str(self.design.solver), "status": self.design.status, "label": self.design.label,
                "ok": self.ok, "cost": num(self.cost) if self.design.ok else None,
                "continuous_cost": num(self.continuous_cost), "continuous_design": self.continuous_label,
                "rounded_cost": num(self.rounded_cost), "rounded_meets": self.rounded_meets,
                "rounded_p_min": num(self.rounded_p_min), "premium_pct": num(self.premium_pct),
                "rounded_premium_pct": num(self.rounded_premium_pct), "proven_optimal": False,
                "relaxed_cost": num(self.relaxed_cost), "relaxed_design": self.relaxed_label or None,
                "range_premium_pct": num(self.range_premium_pct), "step_premium_pct": num(self.step_premium_pct),
                "range_limited": list(self.range_limited), "outer_approximation": self.outer_approximation or None,
                "worst_p_post": num(self.worst_p()) if self.design.ok else None,
                "grades": dict(zip(names, self.grade)), "processes": dict(zip(names, self.process)),
                "moves": self.moves, "evaluations": self.evaluations, "poses": self.problem.n_poses,
                "search": None if s is None else {"rounds": s.rounds, "active_poses": len(s.active_q),
                                                  "evaluations": s.evaluations, "worst_p": num(s.worst_p),
                                                  "converged": s.converged, "time_s": s.time_s},
                "coverage": None if self.coverage is None else {
                    "n": self.coverage.n, "min_p": self.coverage.min_p, "n_below": self.coverage.n_below,
                    "frac_below_upper95": self.coverage.frac_below_upper95, "ok": self.coverage.ok},
                "time_s": self.time_s, "message": self.design.message}
