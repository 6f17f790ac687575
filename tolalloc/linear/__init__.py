"""The linear variance map: error Jacobian, covariance, error budget, and ``P(|x| < r)`` for a Gaussian."""

from tolalloc.linear.covariance import LinearResult, ErrorBudget, linear_map, budget, variance_share
from tolalloc.linear.probability import p_within_radius, radius_for_prob

__all__ = ["LinearResult", "ErrorBudget", "linear_map", "budget", "variance_share", "p_within_radius", "radius_for_prob"]
