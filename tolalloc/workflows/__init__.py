"""One call per job: the workflow functions and their results (the layer the command line is a shell over).

=========================  ==========================================  ==============================
job                        function                                    result
=========================  ==========================================  ==============================
tolerance allocation       :func:`allocate_tolerances`                 :class:`ToleranceAllocation`
                           (``calibration=PLAN``)                      :class:`CalibratedToleranceAllocation`
linear analysis            :func:`analyze_errors`                      :class:`ErrorAnalysis`
nonlinear Monte Carlo      :func:`simulate_errors`                     :class:`ErrorSimulation`
calibration plan           :func:`plan_calibration`                    :class:`CalibrationPlanDesign`
sim-to-real diagnosis      :func:`diagnose_measurements`               :class:`MeasurementDiagnosis`
compensation               :func:`compensate_program`                  :class:`CompensationResult`
fleet of diagnosed robots  :func:`fleet`                               :class:`FleetAnalysis`
=========================  ==========================================  ==============================

Every result is frozen and has ``to_frame()``, ``summary()`` (the JSON the command line writes), ``text()`` (what
it prints), ``save(...)`` (the files it writes, atomically), ``ok`` and a compact repr.
"""

from tolalloc.workflows.allocation import allocate_tolerances
from tolalloc.workflows.allocation_result import ToleranceAllocation
from tolalloc.workflows.analysis import ErrorAnalysis, analyze_errors
from tolalloc.workflows.calibrated import CalibratedToleranceAllocation
from tolalloc.workflows.calplan import CalibrationPlanDesign, plan_calibration
from tolalloc.workflows.diagnosis import MeasurementDiagnosis, diagnose_measurements
from tolalloc.workflows.fleet import FleetAnalysis, fleet
from tolalloc.workflows.model_use import CompensationResult, compensate_program
from tolalloc.workflows.simulation import ErrorSimulation, simulate_errors

__all__ = ["allocate_tolerances", "ToleranceAllocation", "CalibratedToleranceAllocation", "analyze_errors",
           "ErrorAnalysis", "simulate_errors", "ErrorSimulation", "plan_calibration", "CalibrationPlanDesign",
           "diagnose_measurements", "MeasurementDiagnosis", "fleet", "FleetAnalysis", "compensate_program",
           "CompensationResult"]
