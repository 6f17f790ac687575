"""An orientation requirement over a box: searched and cut by the region loop, stated by the coverage check."""

import re

import numpy as np
import pytest
from scipy.stats import beta

import tolalloc
from tolalloc import TolallocError
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.region import allocate_region, box_region, coverage, static_joints, worst_pose
from tolalloc.errormodel import build_error_model
from tolalloc.linear.probability import p_within_angle, radius_for_prob
from tolalloc.robot.io.robotfile import robot_from_chain_dict

# a yaw joint then a pitch joint: the space-frame rotation error is joint 1's tilts plus joint 2's drive and tilts
# turned by q1, so the orientation probability depends on q1 only (and the position one on both joints)
YAW_PITCH = {"name": "yaw_pitch", "chain": [
    {"joint": "j1", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l1", "vector_mm": [0, 0, 300]},
    {"joint": "j2", "type": "revolute", "axis": [0, 1, 0], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l2", "vector_mm": [200, 0, 0]}],
    "pose_sets": {"working": {"q_deg_mm": [[0, 0]]}},
    "regions": {"working": {"q_min_deg_mm": [-10, -30], "q_max_deg_mm": [80, 30]}}}
# joint 1's tilt about x held tight: its rotation covariance is not round, so how joint 2's adds to it depends on q1.
# The position requirement is loose (never binds), the orientation one binds.
COSTS = {"parameters": {"e1x": {"fixed": True, "tol_deg": 0.002}}}
REQ = dict(radius_mm=5.0, angle_radius_deg=0.05, costs=COSTS)


@pytest.fixture(scope="module")
def yaw_pitch():
    robot = robot_from_chain_dict(YAW_PITCH)
    model = build_error_model(robot)
    lo, hi = robot.regions["working"]
    return robot, model, box_region(robot, lo, hi, "working")


def test_the_search_adds_the_orientation_worst_pose_the_position_search_never_picks(yaw_pitch):
    robot, model, box = yaw_pitch
    q0 = np.zeros((1, 2))
    pr0 = build_problem(model, q0, **REQ)
    d0 = allocate(pr0, snap=False).design
    # the design of the initial pose: position nowhere short (a position-only search stops here) ...
    assert worst_pose(pr0, d0.t, box, n_seed=64, n_starts=2)[1] > 0.999
    # ... but on a fresh sample of the box the orientation requirement fails at most poses
    before = coverage(pr0, d0.t, box, n=3000, seed=7)
    assert before.n_below == 0 and before.n_below_angle > 1000 and before.min_p_angle < 0.949 and not before.ok
    assert "orientation: min P = " in before.message(0.95) and "none below p" not in before.message(0.95)
    ra = allocate_region(model, box, q0, **REQ)
    assert ra.converged and len(ra.active_q) == 2
    # the pose added is the orientation-worst one: joint 1 at the end of its range (joint 2 cannot change dw)
    assert np.rad2deg(ra.active_q[1, 0]) == pytest.approx(80.0, abs=0.01)
    assert ra.worst_p_angle >= 0.95 - 1e-4 and ra.worst_p > 0.999
    assert [len(h) for h in ra.history] == [4, 4] and ra.history[0][3] < 0.95 - 1e-4 <= ra.history[1][3]
    after = coverage(ra.result.problem, ra.result.design.t, box, n=3000, seed=7)
    assert after.ok and after.n_below == after.n_below_angle == 0 and after.min_p_angle >= 0.95 - 1e-4
    assert after.message(0.95).endswith("; none below p")


def test_orientation_coverage_equals_brute_force(yaw_pitch):
    # the statistics of the chunked, screened coverage equal p_within_angle at every pose of the same sample
    robot, model, box = yaw_pitch
    pr = build_problem(model, np.zeros((1, 2)), radius_mm=5.0, angle_radius_deg=0.07, angle_prob=0.99)
    t = np.full(len(model.names), np.deg2rad(0.0005))
    t[[model.index("dl1"), model.index("dl2")]] = 0.01
    t[[model.index("e1x"), model.index("e2x")]] = np.deg2rad(0.06)  # two tilts: aligned at q1 = 0, apart at 90 deg
    n = 3000
    cov = coverage(pr, t, box, n=n, seed=5, chunk=700)
    Q = box.q_min + np.random.default_rng(5).random((n, 2)) * (box.q_max - box.q_min)
    J = model.jacobian(Q)[:, 3:6, :]
    P = p_within_angle(np.einsum("mik,k,mjk->mij", J, (t / pr.costs.z) ** 2, J), pr.angle_radius_rad)
    below = int(np.sum(P < 0.99 - 1e-4))
    assert 0 < below < n and cov.n_below_angle == below and cov.angle_prob == 0.99
    assert cov.min_p_angle == pytest.approx(P.min(), abs=1e-12) and cov.frac_below_angle == below / n
    assert cov.frac_below_upper95_angle == pytest.approx(beta.ppf(0.95, below + 1, n - below), rel=1e-12)
    np.testing.assert_array_equal(cov.worst_q_angle, Q[np.argsort(P)[:3]])
    # the verification poses: the position-worst three, then the orientation-worst ones
    assert len(cov.worst_q) == 6 and np.array_equal(cov.worst_q[3:], cov.worst_q_angle)
    assert cov.n_below == 0 and not cov.ok
    assert f"orientation: min P = {P.min():.5f}, {below} below 0.99" in cov.message(0.95)


def test_position_only_coverage_has_no_orientation_statement(yaw_pitch):
    robot, model, box = yaw_pitch
    pr = build_problem(model, np.zeros((1, 2)), radius_mm=5.0)
    cov = coverage(pr, allocate(pr, snap=False).design.t, box, n=500, seed=1)
    assert cov.angle_prob is None and cov.min_p_angle is None and cov.n_below_angle is None and len(cov.worst_q) == 3
    assert "orientation" not in cov.message(0.95)


def test_rotation_static_joints_are_probed_with_uneven_variances():
    # with unit sigmas every joint's rotation errors are round and no joint would seem to move them
    robot = tolalloc.load_robot("tool_changer")
    lo, hi = robot.regions["working"]
    pr = build_problem(build_error_model(robot), robot.poses("working")[:2], angle_radius_deg=0.05)
    box = box_region(robot, lo, hi)
    # joint 4 is prismatic, joint 6 has no rotation error after it
    assert static_joints(pr, box, requirement="orientation").tolist() == [False, False, False, True, False, True]
    with pytest.raises(TolallocError, match="requirement: expected 'position' or 'orientation', got 'angle'"):
        static_joints(pr, box, requirement="angle")
    with pytest.raises(TolallocError, match="pose_cov is a position covariance"):
        worst_pose(pr, None, box, pose_cov=lambda Q: None, requirement="orientation")


def test_allocation_summary_and_text_state_both_requirements(tmp_path):
    (tmp_path / "costs.toml").write_text("[parameters.e1x]\nfixed = true\ntol_deg = 0.002\n")
    res = tolalloc.allocate_tolerances(robot_from_chain_dict(YAW_PITCH),
                                       [tolalloc.PositionRequirement(radius_mm=5.0),
                                        tolalloc.OrientationRequirement(radius_deg=0.05)],
                                       costs=tmp_path / "costs.toml", region=tolalloc.Region(coverage_n=1000),
                                       verification=False, solver=tolalloc.Solver(snap=False), progress=False)
    s = res.summary()
    assert res.ok and s["region"]["converged"] and s["region"]["worst_p_angle_linear"] >= 0.95 - 1e-4
    c = s["coverage"]
    assert c["n_below_angle"] == 0 and c["min_p_angle"] >= 0.95 - 1e-4 and c["frac_below_angle"] == 0.0
    assert c["frac_below_upper95_angle"] == pytest.approx(1 - 0.05 ** (1 / 1000), rel=1e-6)
    text = res.text()
    assert " (position), " in text.splitlines()[0] and "(orientation)" in text.splitlines()[0]
    assert "; orientation: min P = " in text and "(orientation) on 1000 fresh poses)" in res.design_note()


def test_report_card_gives_the_orientation_coverage(tmp_path):
    import tolalloc
    from test_report_html import Page

    # the two-joint robot of this file over the box of its limits (the card does not depend on the robot's size)
    res = tolalloc.allocate_tolerances(robot_from_chain_dict(YAW_PITCH),
                                       [tolalloc.PositionRequirement(radius_mm=0.3),
                                        tolalloc.OrientationRequirement(radius_deg=0.05)],
                                       region=tolalloc.Region("limits", coverage_n=500),
                                       solver=tolalloc.Solver(snap=False),
                                       verification=tolalloc.Verification(n_mc=500, correction=False))
    assert res.summary()["coverage"]["min_p_angle"] is not None
    res.save(tmp_path / "rep", report=True)
    page = Page((tmp_path / "rep" / "report.html").read_text(encoding="utf-8"))
    assert "coverage, orientation" in page.text("summary")


def test_region_infeasible_by_its_orientation_requirement_names_it_in_deg(tmp_path):
    # joint 1's tilt fixed at 0.2 deg: the loose position requirement holds everywhere, the orientation one nowhere
    # near the end of joint 1's range; the message names the orientation requirement with its own numbers
    (tmp_path / "costs.toml").write_text("[parameters.e1x]\nfixed = true\ntol_deg = 0.2\n")
    robot = robot_from_chain_dict(YAW_PITCH)
    res = tolalloc.allocate_tolerances(robot, [tolalloc.PositionRequirement(radius_mm=5.0),
                                               tolalloc.OrientationRequirement(radius_deg=0.05)],
                                       region="working", costs=tmp_path / "costs.toml", verification=False,
                                       solver=tolalloc.Solver(snap=False), progress=False)
    msg = res.infeasible
    m = re.fullmatch(r"`region` working: even with every tolerance at its tightest process limit, the orientation "
                     r"requirement P\(\|dw\| < 0\.05 deg\) >= 0\.95 cannot be met \(at the worst pose found for it, "
                     r"j1 = (\S+) deg, j2 = (\S+) deg, the best achievable P is (\S+) and P = 0\.95 holds only within "
                     r"(\S+) deg; limits that bind: e1x \(100%\)\)\. Lower these t_min in a costs file \(`costs`\), "
                     r"relax `angle_radius_deg` / `angle_prob`, or use a smaller region; nothing written\.", msg)
    assert m, msg
    q_deg, p, reach_deg = [float(m.group(1)), float(m.group(2))], float(m.group(3)), float(m.group(4))
    # the numbers, recomputed at the printed pose from the fixed tilt alone (sigma = t / z)
    model = build_error_model(robot)
    J = model.jacobian(robot.q_from_interface(q_deg))[3:6, model.index("e1x")]
    C = np.outer(J, J) * (np.deg2rad(0.2) / 3.0) ** 2
    assert p == pytest.approx(float(p_within_angle(C, np.deg2rad(0.05))), abs=2e-3) and p < 0.95
    assert reach_deg == pytest.approx(np.rad2deg(float(radius_for_prob(C, 0.95))), rel=1e-3) and reach_deg > 0.05
    assert q_deg[0] == pytest.approx(80.0, abs=1.0)  # joint 1 at the end of its range, as the search above finds
