"""Solver status honesty (issue 11): non-converged solvers are labelled so; the NLP's Lebedev rule accuracy;
per-pose targets; the one variance_share; the correction loop's target rule."""

import numpy as np
import pytest
from scipy.stats import special_ortho_group

from solver_patches import clarabel_inaccurate, ipopt_not_converged
import tolalloc.allocate.convex as convex
import tolalloc.allocate.exact as exact_mod
from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.problem import NOT_CONVERGED, Solver
from tolalloc.errormodel import build_error_model
from tolalloc.linear import budget, linear_map, variance_share
from tolalloc.linear.probability_casadi import casadi_rule_error
from tolalloc.verify.correct import needed_targets
from tolalloc.verify.designs import Verification, verify_design


@pytest.fixture(scope="module")
def problem():
    robot = load_robot("tool_changer")
    return build_problem(build_error_model(robot), robot.poses("working")[[0, 5, 11]])


def test_clarabel_optimal_inaccurate_is_not_certified(problem, monkeypatch):
    clarabel_inaccurate(monkeypatch)
    d = convex.solve_rule(problem, "lmi")
    assert d.status == NOT_CONVERGED and not d.ok and d.t is not None
    assert d.label == "certified-lmi (NOT CONVERGED)" and "optimal_inaccurate" in d.message
    res = allocate(problem, solver="certified", snap=False)
    assert res.status == NOT_CONVERGED and res.design.label.endswith("(NOT CONVERGED)")
    assert res.summary()["costs"]["certified"] is None and res.summary()["status"] == NOT_CONVERGED
    with pytest.raises(TolallocError, match="did not converge"):
        verify_design(problem, res.design, n_mc=1000)


def test_repair_without_a_successful_recheck_is_not_converged(problem, monkeypatch):
    monkeypatch.setattr(convex, "rule_ratio", lambda *a, **k: 1.01)  # the rule never re-checks as met
    d = convex.solve_rule(problem, "trace")
    assert d.status == NOT_CONVERGED and "repair stopped without a successful re-check" in d.message


def test_ipopt_not_converged_is_never_called_exact(problem, monkeypatch):
    cert = convex.solve_rule(problem, "lmi")
    ipopt_not_converged(monkeypatch)
    d = exact_mod.solve_exact(problem, cert)  # with a certified start: the guard keeps it, labelled as a fallback
    assert d.solver == Solver.CERTIFIED_LMI and d.fallback_from == Solver.EXACT and d.ok
    assert d.label == "certified-lmi (fallback from exact)"
    assert "IPOPT did not converge (Maximum_Iterations_Exceeded)" in d.message
    d = exact_mod.solve_exact(problem, None)  # without one: the IPOPT point, labelled not converged
    assert d.solver == Solver.EXACT and d.status == NOT_CONVERGED and not d.ok
    assert d.label == "exact (NOT CONVERGED)" and "Maximum_Iterations_Exceeded" in d.message
    res = allocate(problem, snap=False)
    assert res.status == "optimal" and res.design.fallback_from == "exact"
    s = res.summary()
    assert s["costs"]["exact"] is None and s["fallback_from"] == "exact" and s["design_label"] == res.design.label


def test_converged_designs_say_so(problem):
    res = allocate(problem, snap=False)
    assert res.design.solver == Solver.EXACT and res.design.status == "optimal" and res.design.fallback_from is None
    assert res.design.label == "exact" and res.certified.solver.certified and not res.design.solver.certified
    assert verify_design(problem, res.certified, n_mc=1000).criterion == "certified"


@pytest.mark.parametrize("scale, bound", [(0.51, 2e-7), (0.75, 3e-6), (1.0, 3e-5)])
def test_nlp_lebedev_order_accuracy_as_stated(scale, bound):
    # exact.LEBEDEV_ORDER's comment: worst error < 2e-7 / 3e-6 / 3e-5 for the largest principal sd 0.51 / 0.75 / 1 r
    assert exact_mod.LEBEDEV_ORDER == 41
    rng = np.random.default_rng(11)
    err = []
    for i in range(200):
        R = special_ortho_group.rvs(3, random_state=rng)
        lam = np.array([1.0, 0, 0]) if i % 4 == 0 else np.array([1.0, rng.random(), rng.random() ** 2])
        err.append(abs(float(casadi_rule_error(R @ np.diag(lam * scale**2) @ R.T, 1.0, exact_mod.LEBEDEV_ORDER))))
    assert max(err) < bound
    assert max(err) > bound / 30  # the stated bound is not loose by orders of magnitude


def test_per_pose_targets(problem):
    model, q = problem.model, problem.q
    target = np.array([0.95, 0.95, 0.97])  # working pose 12 binds at p
    pr = build_problem(model, q, target=target)
    assert pr.prob == 0.95 and np.all(pr.blocks[0]["target"] == target)
    for rule in ("trace", "lmi"):
        d = convex.solve_rule(pr, rule)
        assert d.ok and np.all(d.p_linear["position"] >= target - 1e-9)
    d = allocate(pr, snap=False).design
    assert d.label == "exact" and np.all(d.p_linear["position"] >= target - exact_mod.FEAS_TOL)
    assert d.p_linear["position"][2] == pytest.approx(0.97, abs=1e-5)
    assert d.cost > allocate(problem, snap=False).design.cost
    with pytest.raises(TolallocError, match="target"):
        build_problem(model, q, target=[0.9, 0.95, 0.95])  # below the requirement


def test_one_variance_share(problem):
    # closed form, the error budget's share of the norm, and the tolerance table all agree
    J = np.array([[[1.0, 2.0, 0.0], [0.0, 0.0, 3.0], [0.0, 0.0, 0.0]]])
    np.testing.assert_allclose(variance_share(J, np.array([1.0, 1.0, 1.0])), [[1 / 14, 4 / 14, 9 / 14]])
    np.testing.assert_allclose(variance_share(J, np.eye(3)), [[1 / 14, 4 / 14, 9 / 14]])
    assert np.all(variance_share(np.zeros((3, 2)), np.ones(2)) == 0)
    res = allocate(problem, snap=False)
    d = res.design
    lin = linear_map(problem.model_for(d.t), problem.q)
    b = budget(lin)
    i = res.worst_pose
    np.testing.assert_allclose(res.variance_share(d), b.share[i, :, 3], rtol=1e-9, atol=1e-15)


def test_correction_target_rule():
    # hand-made verification at p = 0.95: pose 1 demonstrated, pose 2 short of its linear P by 0.004, pose 3
    # consistent with no shortfall; target = p + shortfall + 3 se, never below the previous target
    p_mc = np.array([0.96, 0.946, 0.95])
    n = np.array([10**5] * 3)
    se = np.sqrt(p_mc * (1 - p_mc) / n)
    ver = Verification("exact", 0.25, 0.95, n, 0, np.array([0.95, 0.95, 0.95]), p_mc, p_mc - 1.96 * se,
                       p_mc + 1.96 * se, np.ones(3, bool), ("", "", ""), 1)
    new = needed_targets(ver, np.full(3, 0.95), k_se=3.0)
    np.testing.assert_allclose(new, [0.95, 0.95 + 0.004 + 3 * se[1], 0.95 + 3 * se[2]])
    np.testing.assert_allclose(needed_targets(ver, np.array([0.95, 0.99, 0.95]))[1], 0.99)
