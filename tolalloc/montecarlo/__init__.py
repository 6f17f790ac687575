"""Nonlinear Monte Carlo of the error model: blocks, streaming statistics, local and Dask schedulers, engines."""

from tolalloc.montecarlo.run import McResult, run_mc, pose_errors
from tolalloc.montecarlo.radii import RadiusNotSimulated, RadiusTable, probability_frame
from tolalloc.montecarlo.streaming import proportion_ci
from tolalloc.montecarlo.estimate import ProbabilityEstimate
from tolalloc.montecarlo.paired import ESTIMATORS, estimate_probabilities, estimate_radii
from tolalloc.montecarlo.importance import importance_probability
from tolalloc.montecarlo.sobol import SobolResult, sobol_indices

__all__ = ["McResult", "run_mc", "pose_errors", "RadiusNotSimulated", "RadiusTable", "probability_frame", "proportion_ci", "ProbabilityEstimate", "ESTIMATORS",
           "estimate_probabilities", "estimate_radii", "importance_probability", "SobolResult", "sobol_indices"]
