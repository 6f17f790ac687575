"""Monkeypatches that make the solvers end without converging (for the status-honesty tests, issue 11)."""

import cvxpy as cp

import tolalloc.allocate.exact as exact_mod


def clarabel_inaccurate(monkeypatch):
    """Every cvxpy solve ends ``optimal_inaccurate`` (what Clarabel reports when it stops short of its tolerances)."""
    orig = cp.Problem.solve

    def solve(self, *args, **kw):
        out = orig(self, *args, **kw)
        self._status = "optimal_inaccurate"
        return out

    monkeypatch.setattr(cp.Problem, "solve", solve)


class _MaxIter:
    """An IPOPT solver whose run ends with ``Maximum_Iterations_Exceeded``."""

    def __init__(self, solver):
        self.solver = solver

    def __call__(self, **kw):
        return self.solver(**kw)

    def stats(self):
        return {**self.solver.stats(), "success": False, "return_status": "Maximum_Iterations_Exceeded"}


def ipopt_not_converged(monkeypatch):
    """Every IPOPT run of the exact solver reports ``Maximum_Iterations_Exceeded``."""
    orig = exact_mod._build
    monkeypatch.setattr(exact_mod, "_build", lambda problem, active: (lambda s, lbg: (_MaxIter(s), lbg))(
        *orig(problem, active)))
