"""End-to-end nonlinear Monte Carlo (manufacture, measure, calibrate, compensate) against the linear prediction."""

import numpy as np
import pytest

from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability import radius_for_prob
from tolalloc.robot.io import load_robot
from tolalloc.verify.calibrated import verify_calibration


@pytest.fixture(scope="module")
def small():
    """tool_changer with manufacturing errors at a tenth of the table2 set (small: linear regime)."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    return robot, split_errors(model.with_sigma(0.1 * model.sigma))


@pytest.mark.parametrize("registration", [False, True])
def test_monte_carlo_agrees_with_linear_prediction(small, registration):
    robot, split = small
    rng = np.random.default_rng(3)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((20, 6)),
                     registration=registration)
    q = robot.poses("working")
    C = posterior(split, plan).tool_covariance(q)
    radius = float(np.median(radius_for_prob(C, 0.7)))  # probabilities near 0.7: sensitive to a wrong variance
    chk = verify_calibration(split, plan, q, radius, n_robots=1000, seed=11)
    assert chk.rms_step < 1e-6 and chk.converged  # the fits converged
    assert chk.iterations.shape == (1000,) and chk.iterations.min() >= 2  # nonlinear: more than one step each
    assert "Gauss-Newton iterations per fit" in chk.message() and chk.fit_cpu_s > 0
    assert np.all(chk.agree), chk.message()
    if not registration:  # the calibration matters here: the uncalibrated robot is far worse at this radius
        prior = posterior(split, make_plan(robot, np.zeros((0, 6)))).tool_covariance(q)
        assert np.all(np.trace(prior, axis1=1, axis2=2) > 100 * np.trace(C, axis1=1, axis2=2))


def test_refuses_pose_plans(small):
    robot, split = small
    with pytest.raises(TolallocError, match="position"):
        verify_calibration(split, make_plan(robot, robot.poses("working"), measurement="pose"),
                           robot.poses("working"), 1.0)


@pytest.mark.parametrize("robot_name", ["tool_changer", "ur10"])
def test_plan_chains_match_the_generic_perturbed_chain(robot_name):
    """The FastChain evaluation the Monte Carlo uses equals the generic perturbed_chain + fk_poe path."""
    from tolalloc.robot.kinematics import fk_poe
    from tolalloc.verify.calibrated import _PlanChains

    robot = load_robot(robot_name)
    model = build_error_model(robot, clearance=True)
    rng = np.random.default_rng(5)
    q = robot.lower + (robot.upper - robot.lower) * rng.random((4, robot.n_joints))
    vals = 20 * model.sample(6, rng)  # 20x the manufacturing errors; joint angles beyond 1 rad (both cos branches)
    extra = model.sample(6 * 4, rng).reshape(6, 4, -1)
    p, R = _PlanChains(model, q).tool(vals, extra)
    screws, home, dq = model.perturbed_chain((vals[:, None, :] + extra).reshape(24, -1))
    T = fk_poe(screws, home, np.tile(q, (6, 1)) + dq).reshape(6, 4, 4, 4)
    np.testing.assert_allclose(p, T[..., :3, 3], atol=1e-9)
    np.testing.assert_allclose(R, T[..., :3, :3], atol=1e-12)
    p0, _ = _PlanChains(model, q).tool(vals)
    screws, home, dq = model.perturbed_chain(vals)
    np.testing.assert_allclose(p0, fk_poe(screws[:, None], home[:, None], q[None] + dq[:, None])[..., :3, 3],
                               atol=1e-9)
