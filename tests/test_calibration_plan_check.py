"""Bad input to the calibration-aware allocation: one TolallocError each, naming the argument and what would work.

A plan written for another robot, a plan with fewer poses than the combinations it must identify, a plan whose header
contradicts the arguments (or its own rows), a region the robot cannot reach. The size rule's rank is checked against
an independent route (nuisance projected out, as the posterior does it).
"""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.design import allocate_with_calibration
from tolalloc.allocate.problem import build_problem
from tolalloc.allocate.region import Region
from tolalloc.calibration import make_plan, read_plan, split_errors, write_plan
from tolalloc.calibration.check import identifiable_count, min_plan_poses
from tolalloc.calibration.design import candidate_poses
from tolalloc.calibration.posterior import identification_matrix
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot


@pytest.fixture(scope="module")
def tc():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    return robot, build_problem(model, robot.poses("working")[:3]), split_errors(model)


def _plan(robot, n, **kw):
    return make_plan(robot, candidate_poses(robot, n, seed=4), **kw)


def test_identifiable_count_matches_the_projected_rank(tc):
    robot, pr, split = tc
    total, n_model, n_nui = identifiable_count(split, _plan(robot, 1))
    A = identification_matrix(split, _plan(robot, 200), random_noise=False)  # nuisance projected out
    raw = identification_matrix(split, _plan(robot, 200, registration=False), random_noise=False)
    s = np.linalg.svd(A / np.linalg.norm(raw, axis=0), compute_uv=False)  # scaled before the projection
    assert n_nui == 9 and n_model == int(np.sum(s > 1e-9 * s[0]))
    assert total == n_model + n_nui <= len(split.sys_index) + 9


def test_plan_size_rule(tc):
    robot, pr, split = tc
    need = min_plan_poses(split, _plan(robot, 1))
    assert need == -(-identifiable_count(split, _plan(robot, 1))[0] // 3)
    allocate_with_calibration(pr, _plan(robot, need), exact=False, baseline=False)  # enough: accepted
    with pytest.raises(TolallocError, match=rf"plan: {need - 1} position measurement pose\(s\).*at least {need} "
                                            rf"poses.*--n-poses {need}"):
        allocate_with_calibration(pr, _plan(robot, need - 1), exact=False, baseline=False)
    with pytest.raises(TolallocError, match="plan: 0 position measurement pose"):
        allocate_with_calibration(pr, make_plan(robot, np.zeros((0, 6))))


def test_plan_for_another_robot(tc, tmp_path):
    robot, pr, split = tc
    ur10 = load_robot("ur10")
    other = make_plan(ur10, candidate_poses(ur10, 12))
    with pytest.raises(TolallocError, match="written for the robot 'ur10'.*allocation is for 'tool_changer'.*calplan "
                                            "tool_changer"):
        allocate_with_calibration(pr, other)
    path = tmp_path / "ur10_plan.csv"
    write_plan(_plan(robot, 12), robot, path)
    path.write_text(path.read_text().replace("# robot = tool_changer", "# robot = ur10"))
    with pytest.raises(TolallocError, match="written for the robot 'ur10'"):
        read_plan(path, robot)


def test_header_contradicting_the_arguments_or_the_rows(tc, tmp_path):
    robot, pr, split = tc
    plan = _plan(robot, 12, noise_mm=0.05)
    with pytest.raises(TolallocError, match="header says noise_mm = 0.05, but noise_mm=0.02 was asked for"):
        allocate_with_calibration(pr, plan, noise_mm=0.02)
    with pytest.raises(TolallocError, match="header says measurement = position, but measurement=pose"):
        allocate_with_calibration(pr, plan, measurement="pose")
    with pytest.raises(TolallocError, match="header says registration = true, but registration=false"):
        allocate_with_calibration(pr, plan, registration=False)
    path = tmp_path / "plan.csv"
    write_plan(plan, robot, path)
    assert read_plan(path, robot).robot == "tool_changer"
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:-2]) + "\n")  # two pose rows lost
    with pytest.raises(TolallocError, match="header says n_poses = 12, but the file has 10 pose row"):
        read_plan(path, robot)


@pytest.mark.parametrize("region, msg", [
    (Region("far", np.deg2rad([100, 10, -20, 0, -30, -10]), np.deg2rad([120, 50, 0, 400, 0, 10])), "region 'far'"),
    ("nowhere", "'nowhere' is not a region of tool_changer; known: limits, working"),
    (np.zeros((4, 5)), r"shape \(M, 6\)"),
    (np.full((2, 6), 3.0), "region \\(trajectory\\)"),
])
def test_region_the_robot_cannot_reach(tc, region, msg):
    robot, pr, split = tc
    with pytest.raises(TolallocError, match=msg):
        allocate_with_calibration(pr, _plan(robot, 12), region=region)


def test_other_arguments(tc):
    robot, pr, split = tc
    plan = _plan(robot, 12)
    with pytest.raises(TolallocError, match="coverage_n: expected a whole number >= 0"):
        allocate_with_calibration(pr, plan, coverage_n=-1)
    with pytest.raises(TolallocError, match=r"tol: expected a probability tolerance in \(0, 1 - prob"):
        allocate_with_calibration(pr, plan, tol=0.2)
    with pytest.raises(TolallocError, match="max_rounds: expected a whole number >= 1"):
        allocate_with_calibration(pr, plan, max_rounds=0)
    with pytest.raises(TolallocError, match=r"design_prob: expected a probability in \[prob = 0.95, 1\)"):
        allocate_with_calibration(pr, plan, design_prob=0.9)
    with pytest.raises(TolallocError, match="split: expected the ErrorSplit of the problem's error model"):
        allocate_with_calibration(pr, plan, split=split_errors(build_error_model(load_robot("ur10"))))
    with pytest.raises(TolallocError, match="estimate = all"):
        allocate_with_calibration(pr, _plan(robot, 12, estimate=["dl3"]))


def test_infeasible_requirement_is_a_result_not_an_exception(tc):
    """A requirement no design meets (radius far below what the process limits allow): status infeasible, one
    INFEASIBLE line, a summary that is valid JSON (no inf / NaN), no design called certified or exact."""
    import json

    robot, pr, split = tc
    tight = build_problem(pr.model, pr.q, radius_mm=0.001)
    res = allocate_with_calibration(tight, _plan(robot, 12))
    assert not res.design.ok and not res.ok and res.exact is None and not res.certified.certified
    assert res.message().count("\n") == 0 and res.message().startswith("status: INFEASIBLE.")
    s = json.loads(json.dumps(res.summary(), allow_nan=False))
    assert s["status"] == "infeasible" and s["cost"] is None and s["saving"] is None
