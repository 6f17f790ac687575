"""Calibration-aware allocation: the cheapest tolerances that meet the requirement *after* a calibration plan.

``certified`` (the eigenvalue rule on the post-calibration covariance, convex ``step``), ``exact`` (the
post-calibration probability, IPOPT), ``region`` (cutting planes over a joint-space box), ``design`` (the whole
allocation in one call), ``standard`` (ISO 286 grades; ``margin``, ``rounding``, ``standard_result``), ``plan`` (a
calibration plan designed for the allocation) and ``summary`` (its JSON summary and printed lines).
"""

from tolalloc.allocate.calibrated.certified import CalibratedAllocation, allocate_calibrated
from tolalloc.allocate.calibrated.design import CalibratedDesign, allocate_with_calibration
from tolalloc.allocate.calibrated.exact import CalibratedExact
from tolalloc.allocate.calibrated.standard import standardize_calibrated

__all__ = ["CalibratedAllocation", "allocate_calibrated", "CalibratedDesign", "allocate_with_calibration",
           "CalibratedExact", "standardize_calibrated"]
