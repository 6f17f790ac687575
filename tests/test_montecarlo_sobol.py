"""Sobol' indices (Saltelli sampling, Jansen estimators): Ishigami closed form, SALib as the reference, one pose."""

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import pose_errors
from tolalloc.montecarlo.sobol import factor_groups, jansen_indices, sobol_indices

salib = pytest.importorskip("SALib")

# Ishigami (a = 7, b = 0.1), x uniform on [-pi, pi]^3: closed-form indices
ISHIGAMI_S1 = np.array([0.3139, 0.4424, 0.0])
ISHIGAMI_ST = np.array([0.5576, 0.4424, 0.2437])


def ishigami(X):
    return np.sin(X[:, 0]) + 7 * np.sin(X[:, 1]) ** 2 + 0.1 * X[:, 2] ** 4 * np.sin(X[:, 0])


def test_jansen_estimators_on_ishigami_match_the_closed_form_and_salib():
    from SALib.analyze import sobol as sa
    from SALib.sample import sobol as ss

    rng = np.random.default_rng(0)
    N = 2**15
    A, B = rng.uniform(-np.pi, np.pi, (N, 3)), rng.uniform(-np.pi, np.pi, (N, 3))
    fAB = []
    for i in range(3):
        AB = A.copy()
        AB[:, i] = B[:, i]
        fAB.append(ishigami(AB))
    s1, st = jansen_indices(ishigami(A), ishigami(B), np.array(fAB))
    np.testing.assert_allclose(s1, ISHIGAMI_S1, atol=0.02)
    np.testing.assert_allclose(st, ISHIGAMI_ST, atol=0.02)
    problem = {"num_vars": 3, "names": ["x1", "x2", "x3"], "bounds": [[-np.pi, np.pi]] * 3}
    X = ss.sample(problem, 2**13, calc_second_order=False, seed=1)
    ref = sa.analyze(problem, ishigami(X), calc_second_order=False, seed=1)
    np.testing.assert_allclose(s1, ref["S1"], atol=0.03)
    np.testing.assert_allclose(st, ref["ST"], atol=0.03)


@pytest.fixture(scope="module")
def design_model():
    robot = load_robot("tool_changer")
    q = robot.poses("working")[[11]]
    res = allocate(build_problem(build_error_model(robot), q), snap=False)
    return res.problem.model_for(res.design.t), q[0]


def test_indices_at_one_pose_agree_with_salib(design_model):
    from SALib.analyze import sobol as sa
    from SALib.sample import sobol as ss

    model, q = design_model
    res = sobol_indices(model, q, 2**12, seed=2, radius_mm=0.25)
    groups = factor_groups(model)
    assert all(len(g) == 1 for g in groups)  # Gaussian model: one factor per varying parameter
    ks = [g[0] for g in groups]
    problem = {"num_vars": len(ks), "names": [model.names[k] for k in ks],
               "bounds": [[0.0, model.sigma[k]] for k in ks], "dists": ["norm"] * len(ks)}
    X = ss.sample(problem, 2**12, calc_second_order=False, seed=3)
    vals = np.zeros((len(X), len(model.params)))
    vals[:, ks] = X
    ref = sa.analyze(problem, pose_errors(model, q, vals)["norm_mm"], calc_second_order=False, seed=3)
    np.testing.assert_allclose(res.total_norm, ref["ST"], atol=0.04)
    np.testing.assert_allclose(res.first_norm, ref["S1"], atol=0.06)
    # small tolerances: the nonlinear indices are the linear model's, nothing is flagged
    assert not res.flagged.any() and "within 0.05" in res.message()
    np.testing.assert_allclose(res.total_norm, res.total_norm_linear, atol=0.01)
    frame = res.to_frame()
    assert {"linear_variance_share", "ST_norm", "ST_norm_linear", "ST_pass", "flagged"} <= set(frame.columns)
    assert frame["linear_variance_share"].sum() == pytest.approx(1.0)


def test_a_large_joint_error_is_flagged_against_the_linear_share():
    # dth2 with sigma 60 deg beside dl3 with the same linear variance (all else 1e-3 of the default): the chord of
    # a large rotation saturates, so dth2's nonlinear share of |dP| falls well below the linear model's (0.42 vs
    # 0.53 at seed 0) and dl3's rises; both flagged at 0.05
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    q = robot.poses("working")[11]
    J = model.jacobian(q)[:3]
    sig = np.array(model.sigma) * 1e-3
    k, L = model.index("dth2"), model.index("dl3")
    sig[k] = np.deg2rad(60.0)
    sig[L] = np.linalg.norm(J[:, k]) * sig[k] / np.linalg.norm(J[:, L])
    res = sobol_indices(model.with_sigma(sig), q, 2**11, seed=0, flag_diff=0.05)
    names = [res.names[i] for i in np.flatnonzero(res.flagged)]
    assert names == ["dl3", "dth2"] and "dl3, dth2" in res.message()
    assert res.linear_share[res.names.index("dth2")] == pytest.approx(0.5, abs=1e-3)
    assert res.total_norm[res.names.index("dth2")] < res.total_norm_linear[res.names.index("dth2")] - 0.05
    with pytest.raises(TolallocError, match="n: expected a whole number of base samples"):
        sobol_indices(model, q, 3)
