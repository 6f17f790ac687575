"""A fleet of diagnosed robots: :func:`fleet` (job) and :class:`FleetAnalysis` (result).

N diagnosed robots -> per identifiable parameter the achieved mean and spread with intervals
(:mod:`tolalloc.diagnose.fleet_pool`), and with the allocation the robots were built to: every combination's
allocated spread, its Cpk, the tolerances over- or under-achieved, the fleet's shared error
(:mod:`tolalloc.diagnose.fleet_map`), and a re-allocation under the capability the fleet showed
(:meth:`FleetAnalysis.reallocate`, :mod:`tolalloc.allocate.capability`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.outputs import json_native
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult
from tolalloc.workflows.model_use import save_result

__all__ = ["fleet", "FleetAnalysis"]


def _model_of(item, robot, index: int, options: dict):
    """``(name, IdentifiedModel)`` of one fleet member: a diagnosis result, a Diagnosis, an IdentifiedModel, or a
    measurement file / DataFrame diagnosed here."""
    from tolalloc.diagnose.diagnosis import Diagnosis
    from tolalloc.diagnose.model_use import IdentifiedModel, identified_model
    from tolalloc.workflows.diagnosis import MeasurementDiagnosis, diagnose_measurements

    if isinstance(item, MeasurementDiagnosis):
        return item.diagnosis.train.source, item.identified_model()
    if isinstance(item, Diagnosis):
        return item.train.source, identified_model(item)
    if isinstance(item, IdentifiedModel):
        if item.train is None:
            raise ArgumentError("robots", f"item {index + 1}: an identified model without its training poses (rebuilt "
                                "from a file) cannot be pooled; give the diagnosis.")
        return f"robot {index + 1}", item
    if isinstance(item, (str, os.PathLike, pd.DataFrame)):
        if robot is None:
            raise ArgumentError("robot", f"item {index + 1} is a measurement set: give the robot they were measured on "
                                "(robot=...), or pass diagnoses.")
        md = diagnose_measurements(robot, item, progress=False, **options)
        return (str(item) if not isinstance(item, pd.DataFrame) else f"robot {index + 1}"), md.identified_model()
    raise ArgumentError("robots", f"item {index + 1}: expected a MeasurementDiagnosis, a Diagnosis, an IdentifiedModel "
                        f"or a measurement file / DataFrame, got {inputs.shown(item)}.")


@inputs.job_entry
def fleet(robots, *, robot=None, names=None, allocation=None, tolerances=None, level: float = 0.95, folds: int = 5,
          seed: int = 0, trust_units: bool = False) -> "FleetAnalysis":
    """Pool a fleet of diagnosed robots: what the factory achieves, parameter by parameter.

    Parameters
    ----------
    robots : sequence
        At least two robots of one model: :class:`~tolalloc.workflows.MeasurementDiagnosis` results, or measurement
        sets (CSV paths / DataFrames; then ``robot`` is required and each is diagnosed with ``folds`` and ``seed``).
        Robots whose verdict is ``inconclusive``, or whose poses identify other combinations, are left out with the
        reason; robots of another model are refused.
    robot : str, path or Robot, optional
        The robot model of measurement sets.
    names : sequence of str, optional
        One name per robot (default: the training files' names, or ``robot 1`` ...).
    allocation : ToleranceAllocation, optional
        The allocation the robots were built to: adds the allocated spread of every combination, Cpk, the tolerances
        over- or under-achieved and enables :meth:`FleetAnalysis.reallocate`.
    tolerances : str, path or DataFrame, optional
        Instead of ``allocation``: the tolerance table an allocation wrote (``tolerances.csv``: ``parameter`` and
        ``sigma_mm`` / ``sigma_deg``), for the default error model of the fleet's robot (no re-allocation).
    level : float
        Two-sided confidence level of the intervals.

    Returns
    -------
    FleetAnalysis
    """
    from tolalloc.diagnose.fleet_pool import pool_fleet, robot_estimate

    level = inputs.check_probability(level, "level", example="0.95")
    if isinstance(robots, (str, bytes, os.PathLike, pd.DataFrame)) or not hasattr(robots, "__len__"):
        raise ArgumentError("robots", f"expected a sequence of diagnosed robots or measurement sets, got "
                            f"{inputs.shown(robots)}.")
    if len(robots) < 2:
        raise ArgumentError("robots", f"a fleet needs at least two robots to estimate a spread; got {len(robots)}.")
    if names is not None and len(names) != len(robots):
        raise ArgumentError("names", f"expected {len(robots)} names (one per robot), got {len(names)}.")
    rob = None if robot is None else inputs.as_robot(robot)
    models = [_model_of(item, rob, i, {"folds": folds, "seed": seed}) for i, item in enumerate(robots)]
    labels = [str(n) for n in names] if names is not None else [nm for nm, _ in models]
    if len(set(labels)) < len(labels):
        labels = [f"{nm} ({i + 1})" for i, nm in enumerate(labels)]
    try:
        pool = pool_fleet([robot_estimate(m, nm) for nm, (_, m) in zip(labels, models)], level)
    except TolallocError as exc:
        raise ArgumentError("robots", str(exc)) from None
    if allocation is not None and tolerances is not None:
        raise ArgumentError("tolerances", "and `allocation` both given; give one.")
    mapping = None
    if allocation is not None:
        problem, design = getattr(allocation, "problem", None), getattr(allocation, "design", None)
        if problem is None or design is None or design.t is None:
            raise ArgumentError("allocation", "expected a ToleranceAllocation with a design "
                                f"(tolalloc.allocate_tolerances), got {inputs.shown(allocation)}.")
        mapping = _allocation_map(pool, problem.model, problem.sigma(design.t), problem.costs.z)
    elif tolerances is not None:
        mapping = _allocation_map(pool, *_table_sigmas(pool.robots[0].model.robot, tolerances), 3.0)
    record = {"robots": len(robots), "robot": pool.robots[0].model.robot.name, "level": level,
              "allocation": None if allocation is None else allocation.label,
              "tolerances": None if tolerances is None or isinstance(tolerances, pd.DataFrame) else str(tolerances),
              "folds": folds, "seed": seed}
    return FleetAnalysis(pool, mapping, allocation, record)


def _table_sigmas(robot, table) -> tuple:
    """``(ErrorModel, sigma (K,) [mm, rad])`` of a tolerance table (``parameter``, ``sigma_mm`` / ``sigma_deg``) on the
    robot's default error model."""
    from tolalloc.errormodel import build_error_model

    frame = inputs.read_table(table, "tolerances", "the tolerances.csv an allocation wrote")
    if frame is None:
        raise ArgumentError("tolerances", f"expected the tolerances.csv an allocation wrote (or a DataFrame), got "
                            f"{inputs.shown(table)}.")
    need = {"parameter", "sigma_mm", "sigma_deg"}
    if not need <= set(frame.columns):
        raise ArgumentError("tolerances", f"expected the columns {', '.join(sorted(need))} (the tolerances.csv of "
                            f"`tolalloc allocate --out`), got {', '.join(map(str, frame.columns))}.")
    model = build_error_model(robot)
    sigma = np.zeros(len(model.params))
    for _, row in frame.iterrows():
        if row["parameter"] not in model.names:
            raise ArgumentError("tolerances", f"parameter {row['parameter']!r} is not one of robot {robot.name!r}'s "
                                "default error model; give the allocation itself (allocation=...) for other options.")
        k = model.index(row["parameter"])
        unit = model.params[k].unit
        v = row["sigma_mm"] if unit == "mm" else np.deg2rad(row["sigma_deg"])
        if not np.isfinite(v) or v < 0:
            raise ArgumentError("tolerances", f"parameter {row['parameter']!r}: expected a sigma >= 0, got {v!r}.")
        sigma[k] = v
    return model, sigma


def _allocation_map(pool, model, sigma, z) -> dict:
    """The map to the allocation's tolerance model and what follows from it (:mod:`tolalloc.diagnose.fleet_map`)."""
    from tolalloc.diagnose.fleet_map import capability_frame, combination_map, parameter_capability

    G, resid = combination_map(pool, model)
    kinds = [p.kind for p in model.params]
    G[:, [k.startswith("clearance") for k in kinds]] = 0.0  # clearances change from move to move, not robot to robot
    sigma = np.asarray(sigma, float)
    return {"G": G, "residual": resid, "sigma": sigma, "frame": capability_frame(pool, G, sigma, z),
            "parameters": parameter_capability(pool, G, sigma), "names": tuple(model.names),
            "units": tuple(p.unit for p in model.params)}


@dataclass(frozen=True, eq=False, repr=False)
class FleetAnalysis(JobResult):
    """A pooled fleet (:func:`fleet`).

    Attributes
    ----------
    pool : FleetPool           (:class:`tolalloc.diagnose.fleet_pool.FleetPool`) per-robot and pooled estimates
    mapping : dict or None     with an allocation: ``G`` (combinations x tolerance parameters), ``residual``, ``sigma``
                               (the allocated sigmas), ``frame``
                               (:func:`~tolalloc.diagnose.fleet_map.capability_frame`),
                               ``parameters`` (:func:`~tolalloc.diagnose.fleet_map.parameter_capability`)
    allocation : ToleranceAllocation or None
    inputs : dict
    """

    pool: object
    mapping: dict | None = None
    allocation: object = None
    inputs: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return True

    @property
    def shared(self) -> dict:
        """The fleet's shared and robot-to-robot geometric error at its poses (:func:`~.fleet_map.shared_error`)."""
        from tolalloc.diagnose.fleet_map import shared_error

        return shared_error(self.pool)

    def headline(self) -> list[str]:
        p = self.pool
        sh = self.shared
        lines = [f"robot: {p.robots[0].model.robot.name}   {len(p.robots)} robots pooled"
                 + (f", {len(p.excluded)} left out" if p.excluded else "") + f"   {len(p.names)} parameters",
                 f"shared (systematic) error {sh['shared_rms_mm']:.4g} mm RMS, robot-to-robot "
                 f"{sh['spread_rms_mm']:.4g} "
                 f"mm RMS at the fleet's poses ({100 * sh['shared_share']:.0f} % of the mean square is shared)"]
        if self.mapping is not None:
            st = self.mapping["frame"]["status"]
            lines.append(f"against the allocation: {int(st.str.startswith('tighter').sum())} tighter than asked, "
                         f"{int(st.str.startswith('looser').sum())} looser, {int(st.str.contains('shifted').sum())} "
                         f"shifted; lowest Cpk {self.mapping['frame']['cpk'].min():.3g}")
            if self.unbudgeted():
                lines.append(f"not budgeted by the tolerance model: {', '.join(self.unbudgeted())}")
        return lines

    def to_frame(self) -> pd.DataFrame:
        """Per pooled parameter: unit, kind, robots, mean with interval, spread (between-robot sd) with interval,
        sampling sd, and with an allocation the allocated sd and tolerance of the combination, Cpk, ``cpk_lo`` and the
        status. Values in mm / rad / the effect column's unit (see ``unit``)."""
        tab = self.pool.table.copy()
        if self.mapping is not None:
            extra = self.mapping["frame"][["parameter", "allocated_sd", "allocated_tol", "cpk", "cpk_lo", "status"]]
            tab = tab.merge(extra, on="parameter", how="left")
        return tab

    def robots_frame(self) -> pd.DataFrame:
        """Per robot and parameter: the de-shrunk estimate and its sd (long format)."""
        rows = []
        for r, vals in zip(self.pool.robots, self.pool.values):
            sd = np.sqrt(np.diag(r.cov))
            for k, nm in enumerate(self.pool.names):
                j = list(r.names).index(nm)
                rows.append({"robot": r.name, "parameter": nm, "unit": self.pool.units[k], "value": vals[k],
                             "sd": sd[j]})
        return pd.DataFrame(rows)

    def parameters_frame(self) -> pd.DataFrame | None:
        """With an allocation: per tolerance parameter the spread factor (achieved / allocated sd), the shift [mm /
        rad] the fleet implies, and whether the fleet observes it at all (None without)."""
        if self.mapping is None:
            return None
        m = self.mapping
        pc = m["parameters"]
        return pd.DataFrame({"parameter": list(m["names"]), "unit": list(m["units"]),
                             "allocated_sd": m["sigma"], "spread_factor": pc["spread_factor"], "shift": pc["mean"],
                             "observed": pc["observed"], "map_residual": m["residual"]})

    def unbudgeted(self) -> list[str]:
        """The combinations whose achieved spread the allocation does not budget for (more than
        :data:`~tolalloc.diagnose.fleet_map.MAX_RATIO` x its allocated sd): error sources outside the tolerance
        model, or held far too small in it."""
        if self.mapping is None:
            return []
        b = self.mapping["parameters"]["budgeted"]
        return [nm for nm, ok in zip(self.pool.names[:len(b)], b) if not ok]

    def summary(self) -> dict:
        p = self.pool
        outliers = [] if p.outliers is None else p.outliers.to_dict(orient="records")
        return json_native({"inputs": self.inputs, "robots": [r.name for r in p.robots], "excluded": p.excluded,
                            "outliers": outliers,
                            "unidentifiable": p.unidentifiable, "unpooled": p.unpooled, "shared": self.shared,
                            "parameters": self.to_frame().to_dict(orient="records")})

    def text(self) -> str:
        lines = self.headline()
        for name, why in self.pool.excluded.items():
            lines.append(f"left out {name}: {why}")
        out = self.pool.outliers
        for r in ([] if out is None else out.itertuples()):
            lines.append(f"OUTLIER {r.robot}: {r.parameter} = {r.value:.4g}, where the other robots give "
                         f"{r.others_mean:.4g} +- {r.others_spread:.4g} (z = {r.z:+.1f}); it stays in the pool, whose "
                         "mean and spread it moves -- check its build, its measurement or its diagnosis")
        tab = self.to_frame()
        cols = [c for c in ("parameter", "unit", "mean", "mean_lo", "mean_hi", "spread", "spread_lo", "spread_hi",
                            "cpk", "status") if c in tab.columns]
        lines += ["", tab[cols].to_string(index=False, float_format=lambda x: f"{x:.4g}")]
        if self.pool.unidentifiable:
            lines += ["", f"not estimated ({len(self.pool.unidentifiable)} geometric parameters the poses cannot "
                          "separate; see summary()['unidentifiable'])"]
        return "\n".join(lines)

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """``fleet.csv`` (:meth:`to_frame`), ``robots.csv`` (:meth:`robots_frame`), with an allocation
        ``tolerance_parameters.csv``, and ``spread.png``; the names written."""
        import matplotlib.pyplot as plt

        folder = Path(folder)
        self.to_frame().to_csv(folder / "fleet.csv", index=False, float_format="%.6g")
        self.robots_frame().to_csv(folder / "robots.csv", index=False, float_format="%.6g")
        names = ["fleet.csv", "robots.csv"]
        if self.mapping is not None:
            self.parameters_frame().to_csv(folder / "tolerance_parameters.csv", index=False, float_format="%.6g")
            names.append("tolerance_parameters.csv")
        ax = self.plot_spread()
        ax.figure.savefig(folder / "spread.png", dpi=90)
        plt.close(ax.figure)
        return names + ["spread.png"]

    def save(self, directory=None, *, json=None) -> list[Path]:
        """Write :meth:`write_files` into ``directory`` and / or the JSON summary to ``json``; the paths written."""
        return save_result(self, directory, json)

    def plot_spread(self, ax=None):
        """Between-robot spread of every geometric parameter with its interval -- against the allocated sd where there
        is an allocation (ratio), else in mm / deg; draws into ``ax`` or a new figure and returns the Axes."""
        from tolalloc.report.plots.fleet import plot_spread

        return plot_spread(self.to_frame(), ax=ax)

    def plot_cpk(self, ax=None):
        """Cpk of every geometric combination against the allocation (needs one); draws into ``ax`` or a new figure
        and returns the Axes."""
        from tolalloc.report.plots.fleet import plot_cpk

        if self.mapping is None:
            raise ArgumentError("allocation", "plot_cpk needs the allocation the robots were built to "
                                "(fleet(..., allocation=...)).")
        return plot_cpk(self.to_frame(), ax=ax)

    def reallocate(self, *, keep_shift: bool = True, rule: str = "lmi"):
        """The allocation re-solved with the capability the fleet showed: each tolerance parameter's spread factor and
        (``keep_shift``) its shift (:func:`~tolalloc.diagnose.fleet_map.parameter_capability`); ``keep_shift=False``:
        the shared part removed by a design change. Returns a
        :class:`~tolalloc.allocate.capability.CapableDesign` (its ``design.cost`` against ``allocation.cost``)."""
        from tolalloc.allocate.capability import Capability, solve_capable

        if self.allocation is None:
            raise ArgumentError("allocation", "reallocate needs the allocation the robots were built to "
                                "(fleet(..., allocation=...)).")
        pc = self.mapping["parameters"]
        cap = Capability(spread_factor=np.maximum(pc["spread_factor"], 1e-6), mean=pc["mean"] if keep_shift else None)
        return solve_capable(self.allocation.problem, cap, rule)
