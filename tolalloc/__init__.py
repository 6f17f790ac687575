"""tolalloc: tolerance allocation, verification and sim-to-real diagnosis for serial robots.

One call per job (each returns a frozen result with ``to_frame()``, ``summary()``, ``text()``, ``save()``)::

    import tolalloc
    res = tolalloc.allocate_tolerances("tool_changer")      # the main job: allocate, verify, correct, grade
    res.to_frame()                                          # the tolerance table
    tolalloc.analyze_errors("ur10", poses="working")        # linear variance map and error budget
    tolalloc.simulate_errors("tool_changer", n_mc=100_000)  # nonlinear Monte Carlo
    tolalloc.plan_calibration("ur10", 30)                   # calibration plan
    tolalloc.diagnose_measurements("ur10", "train.csv", "test.csv")   # sim-to-real diagnosis
    tolalloc.allocate_acceptance("ur10", "examples/requirements_iso9283.toml")  # ISO 9283 AP / RP, test simulated

Settings go in small objects built once and reused (``tolalloc.PositionRequirement(radius_mm=0.25, prob=0.95)``,
``tolalloc.Verification(n_mc=200_000, seed=1)``, ``tolalloc.ErrorModelOptions(clearance=True)`` ...); the simple
case keeps short keywords (``radius_mm=``, ``prob=``, ``n_mc=``). Every stage is also reachable by its sub-package (:mod:`tolalloc.robot`, :mod:`tolalloc.errormodel`,
:mod:`tolalloc.linear`, :mod:`tolalloc.allocate`, :mod:`tolalloc.montecarlo`, :mod:`tolalloc.verify`,
:mod:`tolalloc.calibration`, :mod:`tolalloc.diagnose`, :mod:`tolalloc.report`).

Units inside the library: lengths in mm, angles in rad. Joint values at the
interface (workflow arguments, robot files, CLI, CSV) are in degrees (revolute) and mm (prismatic).

The names below are loaded on first use (PEP 562), so ``import tolalloc`` stays cheap and the command line can
take over SIGINT / SIGTERM before numpy and the solvers are imported (see :mod:`tolalloc.__main__`); type checkers and
IDEs read them from the ``TYPE_CHECKING`` imports. ``__version__`` is the installed package's version
(:mod:`tolalloc.version`).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # what the names below resolve to, for type checkers and IDEs; never run
    from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError, UnknownArgumentError
    from tolalloc.robot import Joint, Link, Robot, builtin_robots, load_robot
    from tolalloc.workflows import (CalibratedToleranceAllocation, CalibrationPlanDesign, CompensationResult, Costs,
                                    DrawingReview, ErrorAnalysis, ErrorModelOptions, ErrorSimulation, FitOptions,
                                    FleetAnalysis, Measurement, MeasurementDiagnosis, MonteCarlo,
                                    OrientationRequirement, PartsToleranceAllocation, PositionRequirement, Refit, Region,
                                    Requirement, Solver,
                                    ToleranceAllocation, Verification, allocate_tolerances, analyze_errors,
                                    compensate_program, diagnose_measurements, fleet, plan_calibration, review_drawing,
                                    simulate_errors)
    from tolalloc.workflows.acceptance import AcceptanceAllocation, allocate_acceptance

    __version__: str

_HOME = {
    **{name: "tolalloc.workflows" for name in ("allocate_tolerances", "analyze_errors", "simulate_errors",
                                               "plan_calibration", "diagnose_measurements", "ToleranceAllocation",
                                               "CalibratedToleranceAllocation", "PartsToleranceAllocation", "ErrorAnalysis",
                                               "ErrorSimulation",
                                               "CalibrationPlanDesign", "MeasurementDiagnosis", "review_drawing",
                                               "DrawingReview", "fleet", "FleetAnalysis", "compensate_program",
                                               "CompensationResult", "Requirement",
                                               "PositionRequirement", "OrientationRequirement", "ErrorModelOptions",
                                               "Costs", "Region", "Solver", "Verification", "MonteCarlo",
                                               "Measurement", "Refit", "FitOptions")},
    **{name: "tolalloc.workflows.acceptance" for name in ("allocate_acceptance", "AcceptanceAllocation")},
    **{name: "tolalloc.robot" for name in ("Robot", "Joint", "Link", "load_robot", "builtin_robots")},
    **{name: "tolalloc.exceptions" for name in ("TolallocError", "ArgumentError", "UnknownArgumentError",
                                                "InputFileError")},
}

__all__ = list(_HOME)


def __getattr__(name: str):
    if name == "__version__":
        from tolalloc.version import package_version

        return package_version()
    if name in _HOME:
        value = getattr(importlib.import_module(_HOME[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tolalloc' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__ + ["__version__"])
