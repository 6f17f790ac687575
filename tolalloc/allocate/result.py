"""Result of a tolerance allocation (:class:`AllocationResult`) and snapping to standard grades.

Split from :mod:`tolalloc.allocate.problem`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from tolalloc.allocate.limits import LimitReport
from tolalloc.allocate.problem import AllocationProblem, Design, make_design
from tolalloc.linear.covariance import variance_share

__all__ = ["AllocationResult", "snap_design", "parameter_columns"]


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
        The chosen continuous design (if infeasible: the tightest design the limits allow, status ``infeasible``).
        The design to build is :attr:`built`: ``standard`` when it meets the requirement, else this one.
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
    def built(self) -> Design:
        """The design to build: ``standard`` when it meets the requirement, else ``design`` (the continuous one)."""
        std = self.standard
        return std if std is not None and std.ok else self.design

    @property
    def worst_pose(self) -> int:
        """Pose index with the lowest position probability of the design to build (``built``); without a position
        requirement, the pose where an ISO 9283 statistic of the test's poses has the least margin."""
        return int(np.argmin(_pose_score(self.problem, self.built)))

    def variance_share(self, design: Design | None = None, pose: int | None = None) -> np.ndarray:
        """Share of each parameter in ``tr Sigma`` of the position error of ``design`` (default: ``built``) at
        ``pose`` (default: that design's worst pose), (K,), a fraction."""
        d = design or self.built
        i = int(np.argmin(_pose_score(self.problem, d))) if pose is None else pose
        return variance_share(self.problem.J[i, :3, :], self.problem.sigma(d.t) ** 2)

    def to_frame(self, design: Design | None = None) -> pd.DataFrame:
        """Tolerance table of ``design`` (default: the design to build, ``built``): one row per parameter.

        Every quantity in mm or deg has two columns, ``<name>_mm`` (length rows) and ``<name>_deg`` (angle rows),
        the other one empty; ``unit`` names the row's unit. Columns: ``parameter, kind, element, role, unit,
        nominal_mm`` (a link length's nominal size, the size its ISO 286 grade applies to), ``tol_mm, tol_deg``
        (± half-width), ``grade`` (ISO 286 IT grade of a link length, a class name, or empty: a multiple of the
        resolution step, or no standard value), ``process``, ``sigma_mm, sigma_deg`` (t / z), ``cost``,
        ``variance_share_pct`` (share of ``tr Sigma`` of the position error at the design's worst pose, in %),
        ``at_limit`` (``t_min``, ``t_max`` or ``fixed``), ``t_min_mm .. t_max_deg`` (process limits), then for
        comparison ``tol_continuous_mm, tol_continuous_deg, cost_continuous`` (the continuous optimum,
        ``design``) and ``tol_rounded_mm, tol_rounded_deg`` (it rounded down to standard values).
        ``grade`` and ``process`` are empty unless ``design`` is the standard design.
        """
        d = design or self.built
        pr = self.problem
        params = pr.model.params
        nan = np.full(len(params), np.nan)
        rnd = self.rounded.t if self.rounded is not None and self.rounded.t is not None else nan
        is_std = d is self.standard and d is not None
        cost = pr.param_costs(d.t)
        if is_std and self.discrete is not None and d is self.discrete.design:
            cost = self.discrete.param_cost  # per part, its process's set-up included
        blank = ("",) * len(params)
        cols = parameter_columns(pr)
        cols.update(pr.model.interface_columns("tol", d.t))
        cols.update({"grade": list(self.grade) if is_std else list(blank),
                     "process": list(self.process) if is_std else list(blank)})
        cols.update(pr.model.interface_columns("sigma", pr.sigma(d.t)))
        cols.update({"cost": np.asarray(cost, float), "variance_share_pct": 100.0 * self.variance_share(d),
                     "at_limit": list(d.at_limit)})
        cols.update({**pr.model.interface_columns("t_min", pr.t_min), **pr.model.interface_columns("t_max", pr.t_max)})
        cont = self.design.t if self.design.t is not None else nan
        cols.update(pr.model.interface_columns("tol_continuous", cont))
        cols["cost_continuous"] = pr.param_costs(cont) if self.design.t is not None else nan
        cols.update(pr.model.interface_columns("tol_rounded", rnd))
        return pd.DataFrame(cols)

    def summary(self) -> dict:
        """JSON-ready summary (the ``summary.json`` content without the Monte Carlo verification).

        ``solver``, ``design_label``, ``design_status``, ``fallback_from``, ``cost``, ``worst_pose`` and the
        per-pose ``p_linear`` describe the design to build (``built``; ``standard_built``: whether it is the
        standard design); the continuous optimum is in ``cost_continuous``, ``solver_continuous``,
        ``design_label_continuous``, the per-pose ``p_linear_continuous`` (when it differs) and ``costs``.
        """
        pr = self.problem
        robot = pr.model.robot
        built = self.built

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
            "solver": str(built.solver),
            "solver_requested": self.solver,
            "fallback_from": None if built.fallback_from is None else str(built.fallback_from),
            "design_status": built.status,
            "design_label": built.label,
            "cost": built.cost,
            "standard_built": built is self.standard,
            "cost_continuous": self.design.cost,
            "solver_continuous": str(self.design.solver),
            "design_label_continuous": self.design.label,
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
                          "radius_best_max": {f"{k}_{_unit(pr, k)}":
                                              float(v.max() if _unit(pr, k) == "mm" else np.rad2deg(v.max()))
                                              for k, v in self.diagnosis.radius_best.items()},
                          "binding": [{"parameter": n, "variance_share_pct": 100.0 * s}
                                      for n, s in self.diagnosis.binding]},
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
        out["poses"] = self._pose_rows(built, exact_ok)
        return out

    def _pose_rows(self, built: Design, exact_ok: bool) -> list:
        """summary.json's ``poses``: joint values ``q_deg_mm`` (deg revolute, mm prismatic), linear P of the design
        to build (and of the continuous one), pose duals."""
        pr = self.problem
        poses = []
        qi = np.round(pr.model.robot.q_to_interface(pr.q), 9)
        for i in range(pr.n_poses):
            pos = "position" in built.p_linear
            row = {"pose": i + 1, "q_deg_mm": qi[i], "p_linear": float(built.p_linear["position"][i]) if pos else None}
            if "orientation" in built.p_linear:
                row["p_linear_angle"] = float(built.p_linear["orientation"][i])
            if built is not self.design and pos:
                row["p_linear_continuous"] = float(self.design.p_linear["position"][i])
            if self.certified.ok and pos:
                row["p_linear_certified"] = float(self.certified.p_linear["position"][i])
                row["pose_dual_certified"] = float(self.certified.pose_dual[i]) if self.certified.pose_dual is not None else None
            if exact_ok and self.exact.ok and self.exact.pose_dual is not None:
                row["pose_dual_exact"] = float(self.exact.pose_dual[i])
            poses.append(row)
        return poses


def parameter_columns(problem: AllocationProblem) -> dict:
    """The first columns of a tolerance table: ``parameter, kind, element, role, unit, nominal_mm`` (a link
    length's nominal size, the size its ISO 286 grade applies to; NaN on the other rows)."""
    params = problem.model.params
    lengths = {lk.name: lk.length_mm for lk in problem.model.robot.links}
    return {"parameter": [p.name for p in params], "kind": [p.kind for p in params],
            "element": [p.element for p in params], "role": list(problem.costs.role),
            "unit": [p.interface_unit for p in params],
            "nominal_mm": [float(lengths.get(p.element, np.nan)) if p.kind == "link_length" else np.nan
                           for p in params]}


def _unit(problem: AllocationProblem, name: str) -> str:
    """The unit a block's radius is reported in: mm (position, ISO length statistics) or deg."""
    b = next(b for b in problem.blocks if b["name"] == name)
    if b.get("requirement") is not None:
        return b["requirement"].unit
    return "mm" if name == "position" else "deg"


def _pose_score(problem: AllocationProblem, d: Design) -> np.ndarray:
    """Per working pose: the position probability, or without a position requirement the least margin
    ``P - target`` of the ISO 9283 statistics held at those poses (zeros if none is)."""
    if "position" in d.p_linear:
        return d.p_linear["position"]
    rows = [d.p_linear[b["name"]] - b["target"] for b in problem.blocks if len(b["target"]) == problem.n_poses]
    return np.min(rows, axis=0) if rows else np.zeros(problem.n_poses)


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
