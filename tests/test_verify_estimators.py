"""Verification and correction with the paired / importance estimators; chunked region coverage."""

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.region import box_region, coverage
from tolalloc.errormodel import build_error_model
from tolalloc.verify.correct import correct_design
from tolalloc.verify.designs import verify_design


@pytest.fixture(scope="module")
def res():
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0, 11]])
    return allocate(pr, snap=False)


def test_paired_verification_records_the_estimator(res):
    # n_max = n_mc: no second look, every pose judged by the first (paired) one
    v = verify_design(res.problem, res.design, n_mc=50_000, n_max=50_000, seed=1, keep_samples=100)
    plain = verify_design(res.problem, res.design, n_mc=50_000, seed=1, keep_samples=100, estimator="plain")
    assert np.all(v.estimator == "paired") and np.all(plain.estimator == "plain")
    assert np.all(v.variance_reduction > 100) and v.fallback_reason == ""
    # the paired interval lies inside the plain one's span and is far narrower
    assert np.all((v.ci_high - v.ci_low) < 0.2 * (plain.ci_high - plain.ci_low))
    assert np.all((v.ci_low <= plain.ci_high) & (plain.ci_low <= v.ci_high))
    np.testing.assert_array_equal(v.samples_mm, plain.samples_mm)  # same draws
    cols = v.to_frame().columns
    assert {"estimator", "n_discordant", "variance_reduction"} <= set(cols)
    assert v.estimator_message().startswith("estimator: paired (requested auto); discordant samples")


def test_certified_redo_uses_importance_sampling(res):
    v = verify_design(res.problem, res.design, criterion="certified", n_mc=2000, n_max=200_000, seed=7,
                      keep_samples=0)
    # the exact design is tight (P_lin = p) at its binding pose: the paired interval at n = 2000 straddles p, so
    # that pose is re-run by importance sampling with n_max samples
    tight = int(np.argmin(res.design.p_linear["position"]))
    assert v.estimator[tight] == "importance" and v.n[tight] == 200_000
    assert v.ci_high[tight] - v.ci_low[tight] < 1e-4


def test_unresolvable_tail_is_refused_with_the_samples_needed(res):
    pr = build_problem(res.problem.model, res.problem.q, prob=0.9999)
    d = allocate(pr, snap=False).design
    # two poses: each interval at 97.5 % (simultaneous 95 %), z = 2.2414, n >= z^2 p / (1 - p) = 50234
    with pytest.raises(TolallocError, match=r"n_mc 1000 samples per pose cannot resolve the tail .* the simultaneous "
                                            r"95% interval \(one of 2, each at 97.5%\) .* `n_mc` >= 50234 "
                                            r"or `estimator` importance"):
        verify_design(pr, d, n_mc=1000, estimator="plain")
    with pytest.raises(TolallocError, match="the paired estimator"):
        verify_design(pr, d, n_mc=1000, estimator="paired")
    # certified: the position requirement is judged at n_max (default 4 n_mc), which the message says how to reach;
    # 2 poses + 2 possible second looks: 4 intervals at 98.75 %, z = 2.4977, n >= 62380
    with pytest.raises(TolallocError, match=r"n_max 4000 samples per pose cannot resolve the tail .* `n_max` >= 62380 "
                                            r"\(`n_max` defaults to 4 x `n_mc`, .*: `n_mc` >= 15595 gives it\)"):
        verify_design(pr, d, n_mc=1000, estimator="plain", criterion="certified")
    auto = verify_design(pr, d, n_mc=1000, keep_samples=0)  # auto: importance sampling where paired cannot resolve
    assert np.all(auto.estimator == "importance")
    v = verify_design(pr, d, n_mc=1000, estimator="importance", keep_samples=0)  # importance sampling can
    assert np.all(v.estimator == "importance") and np.all(v.ci_high - v.ci_low < 1e-4)
    with pytest.raises(TolallocError, match="estimator: expected one of"):
        verify_design(pr, d, n_mc=1000, estimator="best")


def test_n_max_below_n_mc_is_refused_and_n_max_equal_to_n_mc_means_no_second_look(res):
    pr = build_problem(res.problem.model, res.problem.q, prob=0.9999)
    d = allocate(pr, snap=False).design
    for bad in (500, 1500.5):
        with pytest.raises(TolallocError, match=r"n_max: expected a whole number n_max >= n_mc \(the second look of a "
                                                rf"certified pose uses more samples\), got n_max={bad}, n_mc=1000; "
                                                r"give n_max >= n_mc .* or leave it out \(default 4 x n_mc\)"):
            verify_design(pr, d, n_mc=1000, n_max=bad, criterion="certified")
    # n_max = n_mc: the family counts no second look, and the position requirement is judged at n_mc (2 intervals
    # at 97.5 %, n >= 50234), not at n_max with a second look counted (4 at 98.75 %, n >= 62380)
    with pytest.raises(TolallocError, match=r"^n_mc 1000 samples per pose cannot resolve the tail .* \(one of 2, each "
                                            r"at 97.5%\) reaches below p = 0.9999; give `n_mc` >= 50234 or"):
        verify_design(pr, d, n_mc=1000, n_max=1000, estimator="plain", criterion="certified")


def test_correction_with_the_paired_interval_costs_less_than_with_plain():
    import copy

    from tolalloc.allocate.costs import DEFAULT_COSTS

    robot = load_robot("tool_changer")
    costs = copy.deepcopy(DEFAULT_COSTS)
    for kind in costs["kinds"].values():
        for key in [k for k in kind if k.startswith("t_max")]:
            kind[key] *= 40
    model, q = build_error_model(robot), robot.poses("working")[[11]]
    kw = dict(radius_mm=10.0, costs=costs, n_mc=50_000, seed=1, max_rounds=2)
    paired = correct_design(model, q, estimator="paired", **kw)
    plain = correct_design(model, q, estimator="plain", **kw)
    assert paired.verification.verdict == "demonstrated" and plain.verification.verdict == "demonstrated"
    assert np.all(paired.verification.estimator == "paired")
    assert 0 < paired.cost_of_correction < plain.cost_of_correction
    assert paired.targets[0] - 0.95 < 0.5 * (plain.targets[0] - 0.95)


def test_coverage_in_chunks_is_the_same_as_in_one_piece(res):
    robot = res.problem.model.robot
    region = box_region(robot, robot.lower * 0.5, robot.upper * 0.5)
    a = coverage(res.problem, res.design.t, region, n=3000, seed=5, chunk=3000)
    b = coverage(res.problem, res.design.t, region, n=3000, seed=5, chunk=700)
    assert (a.n_below, a.min_p, a.frac_below_upper95) == (b.n_below, b.min_p, b.frac_below_upper95)
    np.testing.assert_array_equal(a.worst_q, b.worst_q)
    with pytest.raises(TolallocError, match="n: expected a whole number of coverage poses"):
        coverage(res.problem, res.design.t, region, n=0.5)


def test_rare_requirement_is_demonstrated_by_importance_sampling():
    # p = 0.99999 on two ur10 poses: the exact design sits on P_lin = p, so no estimator can demonstrate it; one
    # correction round with importance-sampling verification raises the targets by what the estimator resolves
    # (about 4e-7 at 2^14 samples) and the corrected design is demonstrated (lower simultaneous 95 % bound >= p) at
    # both poses
    robot = load_robot("ur10")
    model, q = build_error_model(robot), robot.poses("working")[[0, 2]]
    c = correct_design(model, q, estimator="importance", n_mc=2**14, radius_mm=0.25, prob=0.99999, seed=1,
                       snap=False)
    assert c.before.verdict != "demonstrated" and c.verification.verdict == "demonstrated"
    assert np.all(c.verification.ci_low >= 0.99999) and np.all(c.verification.estimator == "importance")
    assert np.all(c.targets - 0.99999 < 1e-6) and c.premium_pct > 0


def test_estimator_summary_block(res):
    import json

    v = verify_design(res.problem, res.design, n_mc=20_000, n_max=20_000, seed=2, keep_samples=0)
    block = v.estimator_summary()
    assert block["estimator"] == ["paired", "paired"] and block["estimator_requested"] == "auto"
    assert len(block["n_discordant"]) == 2 and block["fallback_reason"] == ""
    assert block["estimator_message"] == v.estimator_message()
    json.dumps(block)
