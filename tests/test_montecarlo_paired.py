"""Paired (control-variate) and importance-sampling estimators of P(|dP| < r), and their intervals."""

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.importance import importance_probability
from tolalloc.montecarlo.intervals import paired_difference_ci, z_of_level
from tolalloc.montecarlo.paired import estimate_probabilities
from tolalloc.montecarlo.run import run_mc

Z = z_of_level(0.95)


@pytest.fixture(scope="module")
def big():
    """A tool_changer design for r = 10 mm with process limits widened: tolerances large enough (mm, 0.1 deg) that
    the nonlinearity moves tens of samples across the sphere in 1e5 (12 and 34 at seed 3)."""
    import copy

    from tolalloc.allocate.costs import DEFAULT_COSTS

    robot = load_robot("tool_changer")
    costs = copy.deepcopy(DEFAULT_COSTS)
    for kind in costs["kinds"].values():
        for key in [k for k in kind if k.startswith("t_max")]:
            kind[key] *= 40
    q = robot.poses("working")[[0, 11]]
    res = allocate(build_problem(build_error_model(robot), q, radius_mm=10.0, costs=costs), snap=False)
    return res.problem.model_for(res.design.t), q


def test_zero_discordant_interval_is_the_closed_form():
    n = 10**6
    d = paired_difference_ci(0, 0, n)
    half = Z**2 / (n + Z**2)
    np.testing.assert_allclose(d, [0.0, -half, half], rtol=1e-6, atol=0)


def _restricted_score(d0, b, c, n):
    """Score statistic with the restricted MLE of p01 found numerically (independent of the closed form)."""
    # multinomial (p10, p01, rest) with p10 = p01 + d0: maximise over p01
    def nll(p01):
        p10 = p01 + d0
        rest = 1 - p10 - p01
        if p01 <= 0 or p10 <= 0 or rest <= 0:
            return np.inf
        return -(b * np.log(p10) + c * np.log(p01) + (n - b - c) * np.log(rest))

    lo, hi = max(0.0, -d0) + 1e-15, (1 - d0) / 2 - 1e-15
    p01 = minimize_scalar(nll, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14}).x
    return (b - c - n * d0) / np.sqrt(n * (2 * p01 + d0 * (1 - d0)))


@pytest.mark.parametrize("b, c, n", [(40, 20, 160), (6, 16, 161), (12, 3, 10**6), (1, 7, 21)])
def test_interval_ends_solve_the_score_equation(b, c, n):
    est, lo, hi = paired_difference_ci(b, c, n)
    assert est == pytest.approx((b - c) / n)
    assert _restricted_score(lo, b, c, n) == pytest.approx(Z, rel=1e-4)
    assert _restricted_score(hi, b, c, n) == pytest.approx(-Z, rel=1e-4)


@pytest.mark.parametrize("p10, p01", [(3e-6, 1e-6), (2e-5, 2e-5), (0.0, 2e-6)])
def test_interval_coverage_over_seeds(p10, p01):
    # 4000 paired runs of n = 1e6 (counts drawn from the multinomial): the 95 % interval covers the true
    # difference in at least 93 % of them (binomial sd of the coverage 0.35 %)
    rng = np.random.default_rng(0)
    n = 10**6
    counts = rng.multinomial(n, [p10, p01, 1 - p10 - p01], size=4000)
    d = paired_difference_ci(counts[:, 0], counts[:, 1], n)
    cover = np.mean((d[:, 1] <= p10 - p01) & (p10 - p01 <= d[:, 2]))
    assert cover >= 0.93, cover


def test_plain_part_is_run_mc_and_paired_agrees(big):
    model, q = big
    n = 100_000
    est = estimate_probabilities(model, q, n, 3, radius_mm=10.0)["position"]
    mc = run_mc(model, q, n, 3, radii_mm=(10.0,))
    np.testing.assert_array_equal(np.rint(est.p_plain * n), np.rint(mc.p_within[10.0][:, 0] * n))
    assert np.all(est.estimator == "paired") and np.all(est.n_discordant >= 5)
    # the paired and plain intervals describe the same P: they overlap, and the paired one is narrower
    assert np.all((est.ci_low <= est.plain_high) & (est.plain_low <= est.ci_high))
    assert np.all(est.ci_high - est.ci_low < 0.5 * (est.plain_high - est.plain_low))
    assert np.all(est.variance_reduction > 3)
    assert "discordant samples" in est.message() and "variance reduction" in est.message()


def test_auto_falls_back_to_plain_for_uniform_errors_and_paired_is_refused():
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0]], costs={"distribution": "uniform"})
    model = pr.model_for(allocate(pr, snap=False).design.t)
    est = estimate_probabilities(model, pr.q, 5000, 0, radius_mm=0.25)["position"]
    assert np.all(est.estimator == "plain") and "non-Gaussian parameters (uniform)" in est.fallback[0]
    np.testing.assert_array_equal(est.p_hat, est.p_plain)
    assert "fallback to plain" in est.message()
    with pytest.raises(TolallocError, match="estimator: 'paired' needs Gaussian parameters"):
        estimate_probabilities(model, pr.q, 5000, 0, radius_mm=0.25, estimator="paired")
    with pytest.raises(TolallocError, match="estimator: expected one of"):
        estimate_probabilities(model, pr.q, 5000, 0, radius_mm=0.25, estimator="stratified")


def test_importance_sampling_agrees_with_paired_and_covers(big):
    model, q = big
    ref = estimate_probabilities(model, q[[1]], 400_000, 11, radius_mm=10.0)["position"]
    runs = [importance_probability(model, q[[1]], 8192, s, radius_mm=10.0) for s in range(20)]
    truth = ref.p_hat[0]
    ref_half = 0.5 * (ref.ci_high[0] - ref.ci_low[0])
    covered = sum(r.ci_low[0] - ref_half <= truth <= r.ci_high[0] + ref_half for r in runs)
    assert covered >= 17, covered  # 20 seeds at 95 %: P(covered < 17) < 2 %
    assert all(r.estimator[0] == "importance" and np.isnan(r.p_plain[0]) for r in runs)
    assert runs[0].details["scale"][0] >= 1.0 and runs[0].variance_reduction[0] > 1


def test_run_mc_with_an_estimator(big):
    model, q = big
    res = run_mc(model, q, 20_000, 1, radii_mm=(10.0,), angle_radii_rad=(0.01,), estimator="auto")
    e = res.p_estimates[10.0]
    np.testing.assert_allclose(e.p_plain, res.p_within[10.0][:, 0])
    assert set(res.p_estimates_angle) == {0.01} and res.p_estimates_angle[0.01].quantity == "orientation"
    assert run_mc(model, q, 1000, 1, radii_mm=(10.0,)).p_estimates is None
    with pytest.raises(TolallocError, match="estimator"):
        run_mc(model, q, 1000, 1, radii_mm=(10.0,), estimator="fast")
