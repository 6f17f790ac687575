"""Tolerance allocation: cost models, the problem, the certified (cvxpy + Clarabel) and exact (CasADi + IPOPT) solvers,
and the standard design (grades chosen by a mixed-integer program, HiGHS through cvxpy)."""

from tolalloc.allocate.costs import CostSet, cost_set, load_costs
from tolalloc.allocate.discretize import DiscreteAllocation, discretize
from tolalloc.allocate.problem import AllocationProblem, Design, build_problem
from tolalloc.allocate.result import AllocationResult
from tolalloc.allocate.solve import allocate, with_standard

__all__ = ["CostSet", "cost_set", "load_costs", "AllocationProblem", "Design", "build_problem", "AllocationResult",
           "allocate", "with_standard", "DiscreteAllocation", "discretize"]
