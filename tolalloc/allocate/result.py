"""Result of a tolerance allocation (:class:`AllocationResult`) and snapping to standard grades.

Split from :mod:`tolalloc.allocate.problem`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from tolalloc.allocate.problem import AllocationProblem, Design, LimitReport, make_design
from tolalloc.linear.covariance import variance_share

__all__ = ["AllocationResult", "snap_design"]


@dataclass(frozen=True, eq=False)
class AllocationResult:
    """Result of :func:`allocate`.

    Attributes
    ----------
    problem : AllocationProblem
    status : {"optimal", "infeasible", "not_converged"}
        ``not_converged``: the chosen solver stopped without converging; ``design`` is its point, labelled so.
    solver : {"exact", "certified"}
        The solver asked for.
    design : Design
        The chosen design (if infeasible: the tightest design the limits allow, status ``infeasible``).
    certified, certified_other : Design
        The cheaper and the other certified rule.
    exact : Design or None
    standard : Design or None
        The standard design, the one to build: grades (ISO 286 for link lengths), classes and resolution steps
        chosen by the optimiser (:mod:`tolalloc.allocate.discretize`; ``rounded`` if ``allocate(discrete=False)``
        or if no discrete design was found, then labelled as a fallback).
    it_grade : tuple of str
        IT grade per parameter of ``standard`` (``""`` for parameters without one).
    diagnosis : LimitReport
    message : str
    rounded : Design or None
        ``design`` rounded down to standard values and re-checked (what the standard design replaces).
    rounded_grade : tuple of str
        IT grade per parameter of ``rounded``.
    discrete : DiscreteAllocation or None
        The discrete step: grades and processes, the continuous and rounded costs, the gap, every solve.
    """

    problem: AllocationProblem
    status: str
    solver: str
    design: Design
    certified: Design
    certified_other: Design
    exact: Design | None
    standard: Design | None
    it_grade: tuple
    diagnosis: LimitReport
    message: str = ""
    rounded: Design | None = None
    discrete: object = None
    rounded_grade: tuple = ()

    @property
    def grade(self) -> tuple:
        """Standard label per parameter of ``standard``: ``"IT7"``, a class name or ``""`` (a step multiple)."""
        if self.discrete is not None and self.standard is self.discrete.design and self.standard.fallback_from is None:
            return self.discrete.grade
        return self.it_grade

    @property
    def process(self) -> tuple:
        """Process per parameter of ``standard`` (``""`` without processes)."""
        if self.discrete is not None and self.standard is self.discrete.design:
            return self.discrete.process
        return ("",) * len(self.problem.costs.names)

    @property
    def worst_pose(self) -> int:
        """Pose index with the lowest position probability of ``design``."""
        return int(np.argmin(self.design.p_linear["position"]))

    def variance_share(self, design: Design | None = None, pose: int | None = None) -> np.ndarray:
        """Share of each parameter in ``tr Sigma`` of the position error at ``pose`` (default: the worst), (K,)."""
        d = design or self.design
        i = self.worst_pose if pose is None else pose
        return variance_share(self.problem.J[i, :3, :], self.problem.sigma(d.t) ** 2)

    def to_frame(self, design: Design | None = None) -> pd.DataFrame:
        """Tolerance table: one row per parameter, tolerance and sigma in the interface unit (mm or deg)."""
        d = design or self.design
        pr = self.problem
        params = pr.model.params
        f = np.array([p.to_interface for p in params])
        nan = np.full(len(f), np.nan)
        std = self.standard.t if self.standard is not None and self.standard.t is not None else nan
        rnd = self.rounded.t if self.rounded is not None and self.rounded.t is not None else nan
        std_cost = pr.param_costs(std) if self.standard is not None and self.standard.t is not None else nan
        if self.discrete is not None and self.standard is self.discrete.design:
            std_cost = self.discrete.param_cost
        return pd.DataFrame({
            "parameter": [p.name for p in params],
            "kind": [p.kind for p in params],
            "element": [p.element for p in params],
            "unit": [p.interface_unit for p in params],
            "role": list(pr.costs.role),
            "tolerance": d.t * f,
            "sigma": pr.sigma(d.t) * f,
            "tolerance_std": std * f,
            "it_grade": list(self.it_grade),
            "grade": list(self.grade),
            "process": list(self.process),
            "cost_std": std_cost,
            "tolerance_rounded": rnd * f,
            "cost": pr.param_costs(d.t),
            "variance_share": self.variance_share(d),
            "at_limit": list(d.at_limit),
            "t_min": pr.t_min * f,
            "t_max": pr.t_max * f,
        })

    def summary(self) -> dict:
        """JSON-ready summary (the ``summary.json`` content without the Monte Carlo verification)."""
        pr = self.problem
        robot = pr.model.robot

        def cost(d):
            return None if d is None or not d.ok else d.cost

        exact_ok = self.exact is not None and self.exact.fallback_from is None  # a fallback is no exact design
        cert, ex = cost(self.certified), (cost(self.exact) if exact_ok else None)
        out = {
            "robot": robot.name,
            "sigma_set": pr.model.sigma_set,
            "requirement": {"radius_mm": pr.radius_mm, "prob": pr.prob,
                            "angle_radius_deg": None if pr.angle_radius_rad is None else float(np.rad2deg(pr.angle_radius_rad)),
                            "angle_prob": pr.angle_prob if pr.angle_radius_rad is not None else None},
            "status": self.status,
            "solver": str(self.design.solver),
            "solver_requested": self.solver,
            "fallback_from": None if self.design.fallback_from is None else str(self.design.fallback_from),
            "design_status": self.design.status,
            "design_label": self.design.label,
            "cost": self.design.cost,
            "z": pr.costs.z,
            "distribution": pr.costs.distribution,
            "costs_source": pr.costs.source,
            "message": self.message,
            "costs": {
                "certified": cert, "certified_rule": str(self.certified.solver), "certified_status": self.certified.status,
                "certified_other": cost(self.certified_other), "certified_other_rule": str(self.certified_other.solver),
                "certified_other_status": self.certified_other.status,
                "exact": ex, "exact_solver": None if self.exact is None else self.exact.label,
                "exact_status": None if self.exact is None else self.exact.status,
                "exact_message": None if self.exact is None else self.exact.message,
                "saving": None if cert is None or ex is None else cert - ex,
                "saving_pct": None if cert is None or ex is None else 100 * (cert - ex) / cert,
                "standard": cost(self.standard),
                "standard_solver": None if self.standard is None else self.standard.label,
                "continuous": cost(self.design),
                "rounded": cost(self.rounded),
                "standard_premium_pct": _pct(cost(self.standard), cost(self.design)),
                "rounded_premium_pct": _pct(cost(self.rounded), cost(self.design)),
            },
            "times_s": {"certified": self.certified.time_s, "certified_other": self.certified_other.time_s,
                        "exact": None if self.exact is None else self.exact.time_s},
            "diagnosis": {"feasible": self.diagnosis.feasible, "message": self.diagnosis.message,
                          "p_best_min": {k: float(v.min()) for k, v in self.diagnosis.p_best.items()},
                          "radius_best_max": {f"{k}_{'mm' if k == 'position' else 'deg'}":
                                              float(v.max() if k == "position" else np.rad2deg(v.max()))
                                              for k, v in self.diagnosis.radius_best.items()},
                          "binding": [{"parameter": n, "variance_share": s} for n, s in self.diagnosis.binding]},
            "standard": None if self.standard is None else {
                "meets": self.standard.status == "optimal", "message": self.standard.message,
                "solver": str(self.standard.solver), "label": self.standard.label,
                "p_linear_min": {k: float(v.min()) for k, v in self.standard.p_linear.items()},
                "grades": dict(zip(pr.costs.names, self.grade)), "processes": dict(zip(pr.costs.names, self.process))},
            "rounded": None if self.rounded is None else {
                "meets": self.rounded.status == "optimal", "message": self.rounded.message, "cost": self.rounded.cost,
                "grades": dict(zip(pr.costs.names, self.rounded_grade or ("",) * len(pr.costs.names)))},
            "discrete": None if self.discrete is None else self.discrete.to_dict(),
            "worst_pose": self.worst_pose + 1,
        }
        poses = []
        qi = np.round(robot.q_to_interface(pr.q), 9)
        for i in range(pr.n_poses):
            # "q" is the contract name; "q_deg_mm" says the units (deg revolute, mm prismatic)
            row = {"pose": i + 1, "q": qi[i], "q_deg_mm": qi[i], "p_linear": float(self.design.p_linear["position"][i])}
            if "orientation" in self.design.p_linear:
                row["p_linear_angle"] = float(self.design.p_linear["orientation"][i])
            if self.certified.ok:
                row["p_linear_certified"] = float(self.certified.p_linear["position"][i])
                row["pose_dual_certified"] = float(self.certified.pose_dual[i]) if self.certified.pose_dual is not None else None
            if exact_ok and self.exact.ok and self.exact.pose_dual is not None:
                row["pose_dual_exact"] = float(self.exact.pose_dual[i])
            poses.append(row)
        out["poses"] = poses
        return out


def _pct(x, ref):
    return None if x is None or ref is None or not ref else 100.0 * (x - ref) / ref


def snap_design(problem: AllocationProblem, design: Design, *, angle_step_deg: float | None = None,
                length_step_mm: float = 0.001) -> tuple[Design, tuple]:
    """Round a design down to the standard values and re-check the requirement.

    Every allocatable parameter takes the largest standard value at or below its tolerance, from the same
    catalogue the discrete allocation chooses from (:mod:`tolalloc.allocate.catalogue`: ISO 286 grades of the
    link lengths' grade range, standard classes, multiples of the resolution step -- ``angle_step_deg``, default
    1 arcsec, and ``length_step_mm`` -- within the process limits); where none lies at or below it, the smallest
    (a loosening, which the re-check judges). Fixed parameters are kept. With processes the cheapest process of
    each value is taken (its cost includes the set-ups).

    Returns
    -------
    (Design, it_grade)
        ``Design.solver`` is ``standard``; its status is ``optimal`` if every requirement still holds,
        else ``violated`` with the failing poses in ``message``.
    """
    from tolalloc.allocate.catalogue import build_catalogue

    cat = build_catalogue(problem, angle_step_deg=angle_step_deg, length_step_mm=length_step_mm)
    opt, n = cat.round_down(design.t[problem.alloc])
    t = np.asarray(design.t, float).copy()
    t[problem.alloc] = cat.t_of(opt, n)
    grades = [""] * len(t)
    for a, k in enumerate(problem.alloc):
        grades[k] = cat.label[opt[a]] if cat.label[opt[a]].startswith("IT") else ""
    d = make_design(problem, "standard", t)
    if cat.groups:
        d = replace(d, cost=cat.total_cost(opt, n) + float(problem.param_costs(t)[problem.fixed].sum()))
    bad = []
    for b in problem.blocks:
        p = d.p_linear[b["name"]]
        bad += [f"{b['name']} pose {i + 1} (P = {p[i]:.4f})" for i in np.flatnonzero(p < b["target"] - 1e-9)]
    if bad:
        d = replace(d, status="violated", message="after rounding to standard values the requirement fails at "
                    + ", ".join(bad) + "; use the standard design chosen by the optimiser, or finer standard values")
    else:
        d = replace(d, message="requirement re-checked after snapping: met at every pose")
    return d, tuple(grades)
