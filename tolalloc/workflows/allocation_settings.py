"""The settings of :func:`~tolalloc.workflows.allocate_tolerances`: where the requirement holds (:class:`Region`), how
the design is found (:class:`Solver`) and checked (:class:`Verification`), and :func:`allocation_settings`, which
turns a call's arguments (objects or their short keyword forms) into one checked :class:`AllocationSettings`.

Combinations no job could honour are refused here, before the robot is loaded, each naming the field: a
verification that is off with a correction loop on, the calibration-aware allocation with a scheduler, an
importance sampler or an orientation requirement, an error model with sigma overrides (the allocation chooses the
sigmas).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.workflows import defaults as D
from tolalloc.workflows.checks import (check_choice, check_count, check_flag, check_name, check_not_both,
                                       check_optional_flag, check_path, check_positive, check_scheduler, check_seed,
                                       shown)
from tolalloc.workflows.requirements import PositionRequirement, check_requirements
from tolalloc.workflows.settings import Costs, ErrorModelOptions, Settings, as_settings, named_fields

__all__ = ["Region", "Solver", "Verification", "AllocationSettings", "allocation_settings", "MAX_CORRECTION_ROUNDS"]

#: correction rounds at most (each re-solves the allocation and re-runs the verification)
MAX_CORRECTION_ROUNDS = 50


@dataclass(frozen=True, eq=False)
class Region(Settings):
    """Where the requirement must hold, and how a box region's coverage is checked.

    Parameters
    ----------
    where : str, path, array or DataFrame, optional
        A pose set of the robot, ``"limits"`` (the box of the joint limits), a box of the robot file
        (``[regions.NAME]``), a trajectory CSV (a pose per row, deg / mm) or an array / DataFrame of poses (deg / mm).
        Boxes are searched for their worst pose (cutting planes) and checked on ``coverage_n`` fresh poses. Default:
        the robot's ``working`` box, else the pose set ``poses``.
    poses : str, optional
        A pose set, used without ``where`` (``working`` names the pose set where ``where="working"`` names the box).
    coverage_n : int
        Fresh poses of the coverage check of a box region (default 100 000).
    """

    where: object = None
    poses: str | None = None
    coverage_n: int = D.COVERAGE_N

    def check(self) -> None:
        check_not_both(self.where, "where", self.poses, "poses", "say where the requirement holds",
                       " (`where` also takes a pose set name)")
        if isinstance(self.where, (str, os.PathLike)):
            check_path(self.where, "where", "a region, a pose set or a trajectory CSV")
        check_name(self.poses, "poses", "the name of a pose set of the robot")
        self._set(coverage_n=check_count(self.coverage_n, "coverage_n", example="100000"))

    def to_dict(self) -> dict:
        where = self.where
        if where is not None and not isinstance(where, (str, os.PathLike)):
            where = "given poses"
        return {"where": None if where is None else str(where), "poses": self.poses, "coverage_n": self.coverage_n}


@dataclass(frozen=True)
class Solver(Settings):
    """How the design is found.

    Parameters
    ----------
    method : {"exact", "certified"}
        The design reported: exact probability (CasADi + IPOPT, default) or certified (cvxpy + Clarabel; with a
        calibration plan: no exact stage).
    snap : bool
        Choose standard values (ISO 286 grades for link lengths, ``angle_step_deg`` steps for angles).
    angle_step_deg : float, optional
        Standard step of an angle tolerance [deg] (default one arc-second).
    """

    method: str = D.SOLVER
    snap: bool = True
    angle_step_deg: float | None = None

    def check(self) -> None:
        check_choice(self.method, "method", ("exact", "certified"))
        check_flag(self.snap, "snap")
        if self.angle_step_deg is not None:
            check_positive(self.angle_step_deg, "angle_step_deg", "deg", "0.001")


@dataclass(frozen=True)
class Verification(Settings):
    """How the design is checked by nonlinear Monte Carlo, and corrected where it falls short.

    Parameters
    ----------
    n_mc : int or None
        Monte Carlo samples per verified pose (>= 100; default 1 000 000, the command line's too); None: no
        Monte Carlo verification (the linear prediction and a box region's coverage only; ``verification=False``
        says the same). With a calibration plan: the simulated calibrations of the end-to-end check, clipped to
        200 .. 4000.
    seed : int
        The job's seed: the verification's draws, the coverage sample and the region search.
    estimator : {"auto", "plain", "paired", "importance"}
        How ``P(|dP| < r)`` is estimated: ``paired`` = exact linear P + mean difference of nonlinear and linear
        indicators on shared draws; ``importance`` = that difference by importance sampling (rare events);
        ``auto`` = paired for Gaussian parameters, else plain, importance where the tail is too thin for ``n_mc``.
    correction : bool, optional
        Re-solve with raised targets where a pose is not demonstrated (default on; there is no loop after a
        calibration plan).
    correction_rounds : int, optional
        Rounds of the correction loop at most (default 2; 0 .. 50).
    scheduler : str or dask.distributed.Client, optional
        Where the Monte Carlo runs (threads by default); never changes a number.
    """

    n_mc: int | None = D.N_MC
    seed: int = D.SEED
    estimator: str = D.ESTIMATOR
    correction: bool | None = None
    correction_rounds: int | None = None
    scheduler: object = None

    _unrecorded = ("scheduler",)

    def check(self) -> None:
        from tolalloc.workflows.requirements import ESTIMATORS

        n = self.n_mc
        if n is not None:
            try:
                n = check_count(n, "n_mc", minimum=100)
            except ArgumentError:
                raise ArgumentError("n_mc", f"expected at least 100 samples per pose (a whole number, e.g. 1000000), "
                                    f"got {shown(n)}; or switch the verification off (verification=False)."
                                    ) from None
        check_choice(self.estimator, "estimator", ESTIMATORS)
        check_optional_flag(self.correction, "correction")
        rounds = self.correction_rounds
        if rounds is not None and (isinstance(rounds, (bool, np.bool_)) or not isinstance(rounds, (int, np.integer))
                                   or not 0 <= rounds <= MAX_CORRECTION_ROUNDS):
            raise ArgumentError("correction_rounds", f"expected a whole number from 0 to {MAX_CORRECTION_ROUNDS} "
                                f"(rounds of the correction loop, e.g. 2), got {shown(rounds)}; or switch the "
                                "correction off.")
        if self.correction is False and rounds is not None:
            raise ArgumentError("correction_rounds", f"{rounds} rounds of a correction loop that is off (`correction` "
                                "False); leave out one of them.")
        if n is None and self.correction:
            raise ArgumentError("correction", "True needs the Monte Carlo verification the loop re-runs, but `n_mc` "
                                "is None (no verification); give n_mc or leave out correction.")
        self._set(n_mc=n, seed=check_seed(self.seed), scheduler=check_scheduler(self.scheduler))

    @property
    def monte_carlo(self) -> bool:
        """Whether a nonlinear Monte Carlo verification runs."""
        return self.n_mc is not None


@dataclass(frozen=True, eq=False)
class AllocationSettings:
    """Everything an allocation reads besides the robot, checked together (:func:`allocation_settings`)."""

    requirements: tuple
    region: Region
    costs: Costs
    error_model: ErrorModelOptions
    solver: Solver
    verification: Verification
    calibration: object = None

    @property
    def position(self) -> PositionRequirement:
        return next(r for r in self.requirements if r.kind == "position")

    def problem_arguments(self) -> dict:
        """Keywords of :func:`tolalloc.allocate.build_problem` stating every requirement."""
        out = {"angle_radius_deg": None, "angle_prob": None}
        for r in self.requirements:
            out.update(r.problem_arguments())
        return out

    @property
    def correction(self) -> bool | None:
        """The correction loop: on unless switched off; None after a calibration plan (no loop)."""
        v = self.verification
        if self.calibration is not None:
            return v.correction
        return True if v.correction is None else v.correction

    @property
    def correction_rounds(self) -> int | None:
        if self.calibration is not None:
            return None
        return D.CORRECTION_ROUNDS if self.verification.correction_rounds is None else self.verification.correction_rounds


def allocation_settings(requirement=None, *, radius_mm=None, prob=None, region=None, costs=None, error_model=None,
                        solver=None, verification=None, n_mc=None, calibration=None) -> AllocationSettings:
    """The arguments of :func:`~tolalloc.workflows.allocate_tolerances` as one checked :class:`AllocationSettings`:
    short forms turned into objects (``radius_mm`` / ``prob`` -> :class:`PositionRequirement`, a region name ->
    :class:`Region`, a costs path -> :class:`Costs`, ``"certified"`` -> :class:`Solver`, ``n_mc`` / a bool ->
    :class:`Verification`), and the combinations no allocation can honour refused."""
    reqs = _requirements(requirement, radius_mm, prob)
    reg = as_settings(region, Region, "region", lambda v: Region(where=v))
    cost = as_settings(costs, Costs, "costs", lambda v: Costs(file=v))
    model = as_settings(error_model, ErrorModelOptions, "error_model")
    sol = as_settings(solver, Solver, "solver", lambda v: Solver(method=v))
    ver = _verification(verification, n_mc)
    for name in ("sigma", "clearance_tilt_literal"):
        if getattr(model, name):
            raise ArgumentError(f"ErrorModelOptions.{name}", "is not read by an allocation (it chooses the sigmas of "
                                "the allocated parameters; fixed ones take theirs from the sigma set or the costs "
                                f"file); leave out {name}.")
    cal = _calibration(calibration)
    if cal is not None:
        _check_calibrated(reqs, ver)
    return AllocationSettings(reqs, reg, cost, model, sol, ver, cal)


def _requirements(requirement, radius_mm, prob) -> tuple:
    if requirement is not None:
        for name, value in (("radius_mm", radius_mm), ("prob", prob)):
            if value is not None:
                raise ArgumentError(name, f"{shown(value)} and `requirement` both state the position requirement; "
                                    f"give one of them (PositionRequirement({name}=...) in the requirement).")
        return check_requirements(requirement, need=("position",))
    with named_fields("", {"radius_mm": "radius_mm", "prob": "prob"}):
        return (PositionRequirement(D.RADIUS_MM if radius_mm is None else radius_mm, D.PROB if prob is None else prob),)


def _verification(verification, n_mc) -> Verification:
    if verification is not None and n_mc is not None:
        raise ArgumentError("n_mc", f"{shown(n_mc)} and `verification` both set the Monte Carlo samples; give one of "
                            "them (Verification(n_mc=...)).")
    if isinstance(verification, (bool, np.bool_)):
        return Verification() if verification else Verification(n_mc=None)
    if n_mc is not None:
        with named_fields("", {"n_mc": "n_mc"}):
            return Verification(n_mc=n_mc)
    return as_settings(verification, Verification, "verification")


def _calibration(calibration):
    """None, a CalibrationPlanDesign (anything with its ``plan_for``), or the path of a plan CSV (checked as a
    path)."""
    if calibration is None or callable(getattr(calibration, "plan_for", None)):
        return calibration
    if not isinstance(calibration, (str, os.PathLike)):
        raise ArgumentError("calibration", "expected the CalibrationPlanDesign plan_calibration returns, or the path "
                            f"of a calibration plan CSV (a str or pathlib.Path), got {shown(calibration)}.")
    return check_path(calibration, "calibration", "a calibration plan CSV (from plan_calibration)")


def _check_calibrated(reqs: tuple, ver: Verification) -> None:
    """Refuse, by their fields, what the calibration-aware allocation cannot honour."""
    no_loop = ("the calibration-aware allocation (`calibration`) has no correction loop: its end-to-end Monte Carlo "
               "states per pose whether the design to build passed, and nothing is re-solved")
    if ver.correction:
        raise ArgumentError("Verification.correction", f"expected False or nothing with `calibration` ({no_loop}), got "
                            "True; leave out `correction`.")
    if ver.correction_rounds is not None:
        raise ArgumentError("Verification.correction_rounds", f"expected nothing with `calibration` ({no_loop}), got "
                            f"{shown(ver.correction_rounds)}; leave out `correction_rounds`.")
    if ver.scheduler is not None:
        raise ArgumentError("Verification.scheduler", "expected nothing with `calibration` (the end-to-end Monte Carlo "
                            "of the calibration-aware allocation runs in this process, vectorised over the simulated "
                            f"robots, and takes no scheduler), got {shown(ver.scheduler)}; leave out `scheduler`.")
    for r in reqs:
        if not r.calibration_aware:
            raise ArgumentError("requirement", f"{r.text()} is not handled by the calibration-aware allocation "
                                f"(`calibration`: the {' and '.join(q.kind for q in reqs if q.calibration_aware)} "
                                "requirement only); leave it out, or allocate without `calibration`.")
        allowed = r.estimators(calibrated=True)
        if ver.estimator not in allowed:
            raise ArgumentError("Verification.estimator", f"expected one of {', '.join(map(repr, allowed))} with "
                                "`calibration` (the end-to-end Monte Carlo of the calibration-aware allocation has no "
                                f"importance sampler), got {ver.estimator!r}; use 'paired' for a rare-event "
                                "requirement.")
