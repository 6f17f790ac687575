"""Tolerance allocation: cost models, the problem, the certified (cvxpy + Clarabel) and exact (CasADi + IPOPT) solvers."""

from tolalloc.allocate.costs import CostSet, cost_set, load_costs
from tolalloc.allocate.problem import AllocationProblem, Design, build_problem
from tolalloc.allocate.result import AllocationResult
from tolalloc.allocate.solve import allocate

__all__ = ["CostSet", "cost_set", "load_costs", "AllocationProblem", "Design", "build_problem", "AllocationResult", "allocate"]
