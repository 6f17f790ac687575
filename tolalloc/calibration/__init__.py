"""Design for calibration: systematic/random split, calibration plans and post-calibration covariance."""

from tolalloc.calibration.split import ErrorSplit, split_errors
from tolalloc.calibration.plan import CalibrationPlan, make_plan, read_plan, write_plan
from tolalloc.calibration.posterior import Posterior, posterior
from tolalloc.calibration.check import check_plan, min_plan_poses

__all__ = ["ErrorSplit", "split_errors", "CalibrationPlan", "make_plan", "read_plan", "write_plan", "Posterior",
           "posterior", "check_plan", "min_plan_poses"]
