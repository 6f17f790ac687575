"""One call per job: the workflow functions and their results (the layer the command line is a shell over).

=========================  ==========================================  ==============================
job                        function                                    result
=========================  ==========================================  ==============================
tolerance allocation       :func:`allocate_tolerances`                 :class:`ToleranceAllocation`
                           (``calibration=PLAN``)                      :class:`CalibratedToleranceAllocation`
                           (``parts=True``: with bought parts)         :class:`PartsToleranceAllocation`
linear analysis            :func:`analyze_errors`                      :class:`ErrorAnalysis`
nonlinear Monte Carlo      :func:`simulate_errors`                     :class:`ErrorSimulation`
calibration plan           :func:`plan_calibration`                    :class:`CalibrationPlanDesign`
sim-to-real diagnosis      :func:`diagnose_measurements`               :class:`MeasurementDiagnosis`
drawing review             :func:`review_drawing`                      :class:`DrawingReview`
compensation               :func:`compensate_program`                  :class:`CompensationResult`
fleet of diagnosed robots  :func:`fleet`                               :class:`FleetAnalysis`
=========================  ==========================================  ==============================

Every result follows one protocol (:mod:`tolalloc.workflows.base`): ``save(directory, *, report=False, json=None)``
returns the paths it wrote (atomically), ``to_frame()``, ``summary()`` (the JSON the command line writes),
``text()`` (what it prints), ``plot_*(ax=None)`` returning the axes, ``ok`` and a compact repr and HTML card.

Settings are small frozen objects, checked once when built and reusable across calls: the requirements
(:class:`PositionRequirement`, :class:`OrientationRequirement`, on the base :class:`Requirement`),
:class:`ErrorModelOptions`, :class:`Costs`, :class:`Region`, :class:`Solver`, :class:`Verification`,
:class:`MonteCarlo`, :class:`Measurement`, :class:`Refit` and :class:`FitOptions`. Their defaults, and the
command line's, are in :mod:`tolalloc.workflows.defaults`.
"""

from tolalloc.workflows.requirements import OrientationRequirement, PositionRequirement, Requirement
from tolalloc.workflows.settings import Costs, ErrorModelOptions, Measurement, MonteCarlo
from tolalloc.workflows.allocation_settings import Region, Solver, Verification
from tolalloc.workflows.diagnosis_settings import FitOptions, Refit
from tolalloc.workflows.allocation import allocate_tolerances
from tolalloc.workflows.allocation_result import ToleranceAllocation
from tolalloc.workflows.parts import PartsToleranceAllocation
from tolalloc.workflows.analysis import ErrorAnalysis, analyze_errors
from tolalloc.workflows.calibrated import CalibratedToleranceAllocation
from tolalloc.workflows.calplan import CalibrationPlanDesign, plan_calibration
from tolalloc.workflows.diagnosis import MeasurementDiagnosis, diagnose_measurements
from tolalloc.workflows.review import DrawingReview, review_drawing
from tolalloc.workflows.fleet import FleetAnalysis, fleet
from tolalloc.workflows.model_use import CompensationResult, compensate_program
from tolalloc.workflows.simulation import ErrorSimulation, simulate_errors

__all__ = ["allocate_tolerances", "ToleranceAllocation", "CalibratedToleranceAllocation", "PartsToleranceAllocation",
           "analyze_errors",
           "ErrorAnalysis", "simulate_errors", "ErrorSimulation", "plan_calibration", "CalibrationPlanDesign",
           "diagnose_measurements", "MeasurementDiagnosis", "review_drawing", "DrawingReview", "fleet", "FleetAnalysis",
           "compensate_program", "CompensationResult", "Requirement", "PositionRequirement",
           "OrientationRequirement", "ErrorModelOptions", "Costs", "Region", "Solver", "Verification", "MonteCarlo",
           "Measurement", "Refit", "FitOptions"]
SETTINGS = ["Requirement", "PositionRequirement", "OrientationRequirement", "ErrorModelOptions", "Costs", "Region",
            "Solver", "Verification", "MonteCarlo", "Measurement", "Refit", "FitOptions"]
