"""The plan design's convex relaxation: SciPy's interior point, the cvxpy/Clarabel SDP and Frank-Wolfe against each
other and the planar 2R closed form."""

import numpy as np
import pytest

from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.calibration import relax as relax_mod
from tolalloc.calibration.design import _blocks, _weight, candidate_poses, design_plan
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot

from test_calibration import PLANAR


@pytest.fixture(scope="module")
def planar(tmp_path_factory):
    path = tmp_path_factory.mktemp("robot") / "planar2r.toml"
    path.write_text(PLANAR, encoding="utf-8")
    return load_robot(str(path))


NAMES = {"interior-point": "SciPy trust-constr", "cvxpy": "cvxpy/Clarabel", "frank-wolfe": "Frank-Wolfe"}


@pytest.mark.parametrize("method, rel", [("interior-point", 1e-6), ("cvxpy", 1e-6), ("frank-wolfe", 2e-4)])
def test_planar_2r_relaxation_is_the_closed_form(planar, method, rel):
    """Equal priors s0, W = I: the relaxed optimum is trace S = 2 / (1/s0^2 + 2/s^2), reached at
    sum lambda_c cos t2_c = 0, the same as the best 2-pose plan; both methods must find it."""
    s0, s = 0.04, 0.01
    model = build_error_model(planar, sigma={"dl1": s0, "dl2": s0}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0}}})
    t2 = np.deg2rad(np.arange(0.0, 181.0, 15.0))
    cand = np.column_stack([np.deg2rad(np.linspace(-60, 60, len(t2))), t2])
    q_eval = np.deg2rad([[0.0, 90.0], [30.0, -90.0]])
    d = design_plan(split, 2, cand, q_eval, noise_mm=s, registration=False, relaxation=method)
    exact = 2 / (1 / s0**2 + 2 / s**2)
    assert d.relaxation_method == NAMES[method]
    assert d.relaxation_value_mm2 == pytest.approx(exact, rel=rel)
    assert exact * (1 - rel) <= d.relaxation_bound_mm2 <= exact * (1 + 1e-9)
    assert abs(np.cos(d.plan.q[:, 1]).sum()) < 1e-12
    assert np.trace(posterior(split, d.plan).cov_sys) == pytest.approx(exact, rel=1e-10)


@pytest.fixture(scope="module")
def tool_changer_designs():
    """tool_changer, tracker frame known (the design matters: random plans are ~3x worse), 400 candidates
    (more than the working set, so the column generation runs), 8 poses, every method."""
    robot = load_robot("tool_changer")
    split = split_errors(build_error_model(robot))
    cand = candidate_poses(robot, 400)
    return {m: design_plan(split, 8, cand, robot.poses("working"), registration=False, relaxation=m)
            for m in ("auto", "cvxpy", "frank-wolfe")}


def test_tool_changer_methods_agree(tool_changer_designs):
    ip, cv, fw = (tool_changer_designs[m] for m in ("auto", "cvxpy", "frank-wolfe"))
    assert (ip.relaxation_method, cv.relaxation_method, fw.relaxation_method) == tuple(NAMES.values())
    for d in (ip, cv):  # solved to the gap, over all 400 candidates
        assert d.relaxation_bound_mm2 > d.relaxation_value_mm2 * (1 - relax_mod.GAP_TOL)
        assert "of 400 candidates" in d.relaxation_note
    # each method's value lies above every other's certified bound; the two solvers' optima inside Frank-Wolfe's
    # bracket and equal to their gaps
    for a in (ip, cv, fw):
        for b in (ip, cv, fw):
            assert a.relaxation_value_mm2 >= b.relaxation_bound_mm2 * (1 - 1e-9)
    assert ip.relaxation_value_mm2 <= fw.relaxation_value_mm2 * (1 + 1e-6)
    assert ip.relaxation_value_mm2 == pytest.approx(cv.relaxation_value_mm2, rel=relax_mod.GAP_TOL)
    assert cv.relaxation_value_mm2 == pytest.approx(fw.relaxation_value_mm2, rel=5e-3)
    for d in (ip, cv, fw):  # every rounded plan scores above the relaxation bound, and beats the random plan
        assert d.relaxation_bound_mm2 <= d.score_mm2 * (1 + 1e-9)
        assert d.score_mm2 < 0.5 * d.random_score_mm2


def test_interior_point_hessian_is_the_finite_difference_of_its_gradient(monkeypatch):
    """The exact gradient and Hessian the interior-point method is given, against central differences of f."""
    robot = load_robot("tool_changer")
    split = split_errors(build_error_model(robot))
    cand = candidate_poses(robot, 12)
    G = _blocks(split, make_plan(robot, cand[:1], registration=False), cand)
    B = _weight(split, robot.poses("working"), G.shape[2])
    prior = np.r_[np.ones(B.shape[1]), np.zeros(G.shape[2] - B.shape[1])]
    seen = {}

    def spy(fun, x0, *, jac, hess, **kwargs):
        seen.update(fun=fun, jac=jac, hess=hess, x0=x0)
        raise ValueError("stop after the set-up")

    import scipy.optimize

    monkeypatch.setattr(scipy.optimize, "minimize", spy)
    with pytest.raises(ValueError, match="stop after the set-up"):
        relax_mod._interior_point(G, B, 3, prior, relax_mod._ridge(G, 3), np.arange(12))
    lam = np.random.default_rng(0).uniform(0.1, 0.4, 12)
    f, g, h = seen["fun"], seen["jac"], seen["hess"]
    e = 1e-5
    fd_g = np.array([(f(lam + e * u) - f(lam - e * u)) / (2 * e) for u in np.eye(12)])
    fd_h = np.array([(g(lam + e * u) - g(lam - e * u)) / (2 * e) for u in np.eye(12)])
    assert np.allclose(g(lam), fd_g, rtol=1e-6, atol=1e-9 * np.abs(fd_g).max())
    assert np.allclose(h(lam), fd_h, rtol=1e-5, atol=1e-7 * np.abs(fd_h).max())
    assert np.allclose(h(lam), h(lam).T)


def test_auto_falls_back_to_cvxpy_then_frank_wolfe_and_says_why(planar, monkeypatch):
    import cvxpy as cp

    def not_converged(G, B, n, prior, ridge, S):
        return np.full(len(S), n / len(S)), "not converged (simulated)", 1000

    def fail(*args, **kwargs):
        raise cp.error.SolverError("Solver 'CLARABEL' failed (simulated)")

    model = build_error_model(planar, sigma={"dl1": 0.04, "dl2": 0.04}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0}}})
    cand = np.column_stack([np.zeros(7), np.deg2rad(np.arange(0.0, 181.0, 30.0))])
    monkeypatch.setattr(relax_mod, "_interior_point", not_converged)
    d = design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False)
    assert d.relaxation_method == "cvxpy/Clarabel"
    assert "interior-point not used: SciPy trust-constr status 'not converged (simulated)'" in d.relaxation_note
    with pytest.raises(RuntimeError, match="not converged"):
        design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False, relaxation="interior-point")
    monkeypatch.setattr(relax_mod, "_sdp", fail)
    d = design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False)
    assert d.relaxation_method == "Frank-Wolfe"
    assert "interior-point not used" in d.relaxation_note and "cvxpy not used" in d.relaxation_note
    assert "simulated" in d.relaxation_note
    with pytest.raises(cp.error.SolverError):
        design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False, relaxation="cvxpy")
    with pytest.raises(TolallocError, match="relaxation: expected one of auto, interior-point, cvxpy, frank-wolfe"):
        design_plan(split, 2, cand, cand[:2], relaxation="sdp")
