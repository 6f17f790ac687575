"""Calibration-aware allocation: empty plan (no repeatability term) = today's certified LMI design; a plan's design is certified and cheaper."""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.certified import allocate_calibrated, post_ratio
from tolalloc.allocate.problem import build_problem
from tolalloc.calibration import make_plan, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot
from tolalloc.units import in_row_unit


@pytest.fixture(scope="module")
def tc_problem():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    return robot, build_problem(model, robot.poses("working")[:4])


def test_empty_plan_reproduces_the_lmi_design(tc_problem):
    robot, pr = tc_problem
    no_rep = split_errors(pr.model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0},
                                               "joint_drive_prismatic": {"repeatability_mm": 0.0}}})
    res = allocate_calibrated(pr, make_plan(robot, np.zeros((0, 6))), split=no_rep)
    assert res.baseline.ok and res.certified
    assert res.design.cost == pytest.approx(res.baseline.cost, rel=1e-4)


def test_plan_design_is_certified_and_cheaper(tc_problem):
    robot, pr = tc_problem
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    res = allocate_calibrated(pr, plan)
    ratio, post = post_ratio(pr, split_errors(pr.model), plan, res.design.t)  # independent re-check
    assert res.certified and ratio <= 1.0
    assert res.design.cost < res.baseline.cost
    table = res.to_frame()
    # every column carries one unit: each quantity in a _mm / _deg pair, the row's unit filled, the other empty
    assert not {"tolerance", "tolerance_no_calibration", "sigma_manufactured"} & set(table.columns)
    mm = (table["unit"] == "mm").to_numpy()
    f = np.array([p.to_interface for p in pr.model.params])
    for name, values in (("tol", res.design.t), ("tol_no_calibration", res.baseline.t),
                         ("sigma_manufactured", np.sqrt(res.post.prior_var)), ("sigma_post_calibration", res.post.sigma_post),
                         ("sigma_random", np.sqrt(res.post.random_var))):
        assert table[f"{name}_mm"][~mm].isna().all() and table[f"{name}_deg"][mm].isna().all(), name
        np.testing.assert_allclose(in_row_unit(table, name), values * f, rtol=1e-12, err_msg=name)
    away = table.loc[table.status == "calibrated away", "parameter"]
    assert len(away) > 0 and not set(away) & set(post.unidentifiable)
    # a calibrated-away parameter is not held tighter than without calibration
    for nm in away:
        k = pr.model.index(nm)
        assert res.design.t[k] >= res.baseline.t[k] * (1 - 1e-6)


def test_refuses_orientation_and_explicit_estimate(tc_problem):
    robot, pr = tc_problem
    q = robot.poses("working")[:3]
    with pytest.raises(TolallocError, match="estimate = all"):
        allocate_calibrated(pr, make_plan(robot, q, estimate=["dl1"]))
    pr2 = build_problem(pr.model, q, angle_radius_deg=0.05)
    with pytest.raises(TolallocError, match="position requirement only"):
        allocate_calibrated(pr2, make_plan(robot, q))
