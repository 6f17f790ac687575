"""Allocation over a joint-space region (issue 13): worst-pose search, cutting planes, coverage."""

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.region import allocate_region, box_region, coverage, static_joints, worst_pose
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io.robotfile import robot_from_chain_dict

PLANAR = {"name": "planar2", "chain": [
    {"joint": "j1", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l1", "vector_mm": [300, 0, 0]},
    {"joint": "j2", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l2", "vector_mm": [200, 0, 0]}]}


@pytest.fixture(scope="module")
def planar():
    # in-plane errors only (link lengths, joint offsets): the error grows with the reach |p| = |l1 + l2 e^{i q2}|,
    # so over any box containing q2 = 0 the worst pose is the fully stretched arm (any q1: rotation symmetry)
    robot = robot_from_chain_dict(PLANAR)
    model = build_error_model(robot, exclude=("axis_deflection",))
    box = box_region(robot, np.deg2rad([0, -40]), np.deg2rad([20, 60]), "box")
    return robot, model, box


def test_search_finds_the_stretched_pose_and_the_region_design_equals_it(planar):
    robot, model, box = planar
    ra = allocate_region(model, box, solver="exact")
    assert ra.converged and ra.worst_p > 0.95 - 1e-4
    stretched = np.abs(ra.active_q[:, 1]) < np.deg2rad(0.01)
    assert stretched.any(), np.rad2deg(ra.active_q)
    at = allocate(build_problem(model, np.deg2rad([[10.0, 0.0]])), snap=False).design
    np.testing.assert_allclose(ra.result.design.t, at.t, rtol=1e-4)
    # and the search on a centre-only design finds the stretched pose too
    centre = allocate(build_problem(model, np.deg2rad([[10.0, 10.0]])), snap=False).design
    q, p, n_eval = worst_pose(build_problem(model, np.deg2rad([[10.0, 10.0]])), centre.t, box, seed=1)
    assert abs(np.rad2deg(q[1])) < 0.01 and p < 0.95 and n_eval > 512


def test_certified_region_design_is_certified_at_every_active_pose(planar):
    robot, model, box = planar
    ra = allocate_region(model, box, solver="certified")
    assert ra.converged
    d = ra.result.certified
    assert d.ok and np.all(d.p_linear["position"] >= 0.95 - 1e-9)


def test_coverage_fails_for_a_pose_set_design_on_a_region_it_does_not_cover(planar):
    robot, model, box = planar
    folded = build_problem(model, np.deg2rad([[10.0, 60.0]]))
    cov = coverage(folded, allocate(folded, snap=False).design.t, box, n=20000, seed=7)
    assert cov.n_below > 0 and not cov.ok and cov.min_p < 0.95
    assert cov.frac_below < cov.frac_below_upper95 < 1 and "below 0.95" in cov.message(0.95)
    ra = allocate_region(model, box)
    cov2 = coverage(ra.result.problem, ra.result.design.t, box, n=20000, seed=7)
    assert cov2.ok and cov2.min_p >= 0.95 - 1e-4
    # zero failures: the one-sided 95 % Clopper-Pearson bound is 1 - 0.05^(1/n)
    assert cov2.frac_below_upper95 == pytest.approx(1 - 0.05 ** (1 / 20000), rel=1e-6)


def test_the_tool_axis_joint_is_static():
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[:2])
    lo, hi = robot.regions["working"]
    s = static_joints(pr, box_region(robot, lo, hi))
    assert s.tolist() == [False] * 5 + [True]


def test_working_box_contains_the_working_poses():
    robot = load_robot("tool_changer")
    lo, hi = robot.regions["working"]
    W = robot.poses("working")
    assert np.all((W >= lo - 1e-12) & (W <= hi + 1e-12))


@pytest.mark.parametrize("lo,hi,match", [
    ([10, 0], [0, 10], "inverted"),
    ([0, 0], [10, 100], "outside its limits"),
    ([0, 0, 0], [1, 1, 1], "2 joint values"),
    ([0, np.nan], [1, 1], "finite"),
])
def test_bad_boxes(planar, lo, hi, match):
    robot = planar[0]
    with pytest.raises(TolallocError, match=match):
        box_region(robot, np.deg2rad(lo), np.deg2rad(hi))


def test_robot_file_region_inverted_is_refused():
    bad = {**PLANAR, "regions": {"w": {"q_min_deg_mm": [10, 0], "q_max_deg_mm": [0, 10]}}}
    with pytest.raises(TolallocError, match=r"regions\.w.*inverted"):
        robot_from_chain_dict(bad)
    ok = robot_from_chain_dict({**PLANAR, "regions": {"w": {"q_min_deg_mm": [0, 0], "q_max_deg_mm": [10, 20]}}})
    np.testing.assert_allclose(ok.regions["w"][1], np.deg2rad([10, 20]))


def test_screened_coverage_equals_brute_force():
    # the eigenvalue screen skips poses proven above p; count and minimum must equal evaluating every pose
    from tolalloc.allocate.region import pose_probability

    robot = load_robot("tool_changer")
    W = robot.poses("working")
    pr = build_problem(build_error_model(robot), W)
    t = allocate(pr, snap=False).design.t
    box = box_region(robot, W.min(0), W.max(0))
    cov = coverage(pr, t, box, n=20000, seed=3)
    Q = box.q_min + np.random.default_rng(3).random((20000, 6)) * (box.q_max - box.q_min)
    P = pose_probability(pr, t, Q)
    assert cov.n_below == int(np.sum(P < 0.95 - 1e-4)) > 0 and cov.min_p == pytest.approx(P.min(), abs=1e-12)
    assert cov.n_exact < 20000
