"""Nonlinear Monte Carlo of the error model: blocks, streaming statistics, local and Dask schedulers, engines."""

from tolalloc.montecarlo.run import McResult, run_mc, pose_errors
from tolalloc.montecarlo.streaming import proportion_ci

__all__ = ["McResult", "run_mc", "pose_errors", "proportion_ci"]
