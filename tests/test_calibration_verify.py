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
    from tolalloc.verify.calibrated_fit import _PlanChains

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


def test_exact_gauss_newton_reaches_a_stationary_point_of_the_map_objective():
    """Jacobian-at-the-estimate steps (the large-error fallback of the fit) end where the gradient of the MAP
    objective |r(x)|^2 + |x|^2_prior, by independent central differences, vanishes (tool_changer, 3x errors)."""
    from tolalloc.verify.calibrated_fit import _PlanChains, _exact_step, _measure

    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    split = split_errors(model.with_sigma(3 * model.sigma))
    rng = np.random.default_rng(4)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((15, 6)), registration=False)
    E = split.sys_index
    scale = np.sqrt(split.prior_var_of(E))
    chains = _PlanChains(model, plan.q)
    truth = split.model.with_sigma(np.where(split.systematic, split.model.sigma, 0)).sample(1, rng)[:, E]
    y = _measure(chains, truth, E) + rng.normal(0, plan.noise_mm, (1, 15, 3))
    prior = np.ones(len(E))

    def phi(xn):  # normalised unknowns (D,)
        r = (_measure(chains, (xn * scale)[None], E) - y).ravel() / plan.noise_mm
        return float(r @ r + xn @ xn)

    x = np.zeros((1, len(E)))
    for _ in range(15):
        r = (_measure(chains, x, E) - y).reshape(1, -1) / plan.noise_mm
        x = x + _exact_step(chains, E, x, r, y, scale, prior, plan.noise_mm) * scale
    xn, h = x[0] / scale, 1e-5
    grad = np.array([(phi(xn + h * e) - phi(xn - h * e)) / (2 * h) for e in np.eye(len(E))])
    grad0 = np.array([(phi(h * e) - phi(-h * e)) / (2 * h) for e in np.eye(len(E))])
    assert np.abs(grad).max() < 1e-4 * np.abs(grad0).max()
    assert phi(xn) < 1e-3 * phi(np.zeros(len(E)))


def test_paired_estimator_uses_the_linearised_pipeline(small):
    from tolalloc.verify.calibrated import _linear_pipeline

    robot, split = small
    rng = np.random.default_rng(3)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((20, 6)), registration=True)
    q = robot.poses("working")[:4]
    # without random parts the simulated MAP fit and the posterior's weighting coincide: the linearised pipeline's
    # covariance is the posterior tool covariance (an independent computation: GLS with the nuisance projected out)
    quiet = split.with_random_sigma(np.zeros_like(split.random_sigma))
    m = quiet.model
    E = np.array([k for k in quiet.sys_index if m.sigma[k] > 0], dtype=int)
    var_sys = np.where(quiet.systematic, m.sigma, 0.0) ** 2
    cov = _linear_pipeline(m, E, np.sqrt(quiet.prior_var_of(E)), plan, q, var_sys, np.zeros(len(m.params)))[-1]
    np.testing.assert_allclose(cov, posterior(quiet, plan).tool_covariance(q), rtol=1e-6,
                               atol=1e-9 * np.abs(cov).max())
    C = posterior(split, plan).tool_covariance(q)
    radius = float(np.median(radius_for_prob(C, 0.7)))
    plain = verify_calibration(split, plan, q, radius, n_robots=500, seed=5)
    paired = verify_calibration(split, plan, q, radius, n_robots=500, seed=5, estimator="auto")
    assert np.all(paired.estimator == "paired") and np.all(plain.estimator == "plain")
    assert np.all(paired.ci_high - paired.ci_low < 0.5 * (plain.ci_high - plain.ci_low))
    assert np.all((paired.ci_low <= plain.ci_high) & (plain.ci_low <= paired.ci_high))
    assert {"p_linear_pipeline", "n_discordant", "variance_reduction"} <= set(paired.to_frame().columns)
    with pytest.raises(TolallocError, match="estimator: expected one of"):
        verify_calibration(split, plan, q, radius, n_robots=10, estimator="importance")
