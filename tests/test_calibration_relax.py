"""The plan design's convex relaxation: cvxpy/Clarabel SDP against Frank-Wolfe and the planar 2R closed form."""

import numpy as np
import pytest

from tolalloc.calibration import posterior, split_errors
from tolalloc.calibration import relax as relax_mod
from tolalloc.calibration.design import candidate_poses, design_plan
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot

from test_calibration import PLANAR


@pytest.fixture(scope="module")
def planar(tmp_path_factory):
    path = tmp_path_factory.mktemp("robot") / "planar2r.toml"
    path.write_text(PLANAR, encoding="utf-8")
    return load_robot(str(path))


@pytest.mark.parametrize("method, rel", [("cvxpy", 1e-6), ("frank-wolfe", 2e-4)])
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
    assert d.relaxation_method == ("cvxpy/Clarabel" if method == "cvxpy" else "Frank-Wolfe")
    assert d.relaxation_value_mm2 == pytest.approx(exact, rel=rel)
    assert exact * (1 - rel) <= d.relaxation_bound_mm2 <= exact * (1 + 1e-9)
    assert abs(np.cos(d.plan.q[:, 1]).sum()) < 1e-12
    assert np.trace(posterior(split, d.plan).cov_sys) == pytest.approx(exact, rel=1e-10)


@pytest.fixture(scope="module")
def tool_changer_designs():
    """tool_changer, tracker frame known (the design matters: random plans are ~3x worse), 400 candidates
    (more than the working set, so the column generation runs), 8 poses, both methods."""
    robot = load_robot("tool_changer")
    split = split_errors(build_error_model(robot))
    cand = candidate_poses(robot, 400)
    return {m: design_plan(split, 8, cand, robot.poses("working"), registration=False, relaxation=m)
            for m in ("cvxpy", "frank-wolfe")}


def test_tool_changer_cvxpy_and_frank_wolfe_agree(tool_changer_designs):
    cv, fw = tool_changer_designs["cvxpy"], tool_changer_designs["frank-wolfe"]
    assert cv.relaxation_method == "cvxpy/Clarabel" and fw.relaxation_method == "Frank-Wolfe"
    assert cv.relaxation_bound_mm2 > cv.relaxation_value_mm2 * (1 - relax_mod.GAP_TOL)  # solved to its gap
    # each method's value lies above the other's certified bound; cvxpy's optimum inside Frank-Wolfe's bracket
    assert cv.relaxation_value_mm2 >= fw.relaxation_bound_mm2 * (1 - 1e-9)
    assert fw.relaxation_value_mm2 >= cv.relaxation_bound_mm2 * (1 - 1e-9)
    assert cv.relaxation_value_mm2 <= fw.relaxation_value_mm2 * (1 + 1e-6)
    assert cv.relaxation_value_mm2 == pytest.approx(fw.relaxation_value_mm2, rel=5e-3)
    for d in (cv, fw):  # every rounded plan scores above the relaxation bound, and beats the random plan
        assert d.relaxation_bound_mm2 <= d.score_mm2 * (1 + 1e-9)
        assert d.score_mm2 < 0.5 * d.random_score_mm2


def test_auto_falls_back_to_frank_wolfe_and_says_why(planar, monkeypatch):
    import cvxpy as cp

    def fail(*args, **kwargs):
        raise cp.error.SolverError("Solver 'CLARABEL' failed (simulated)")

    monkeypatch.setattr(relax_mod, "_sdp", fail)
    model = build_error_model(planar, sigma={"dl1": 0.04, "dl2": 0.04}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0}}})
    cand = np.column_stack([np.zeros(7), np.deg2rad(np.arange(0.0, 181.0, 30.0))])
    d = design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False)
    assert d.relaxation_method == "Frank-Wolfe"
    assert "cvxpy not used" in d.relaxation_note and "simulated" in d.relaxation_note
    with pytest.raises(cp.error.SolverError):
        design_plan(split, 2, cand, cand[:2], noise_mm=0.01, registration=False, relaxation="cvxpy")
    with pytest.raises(TolallocError, match="relaxation: expected one of auto, cvxpy, frank-wolfe"):
        design_plan(split, 2, cand, cand[:2], relaxation="sdp")
