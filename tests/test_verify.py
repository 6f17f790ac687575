"""Monte Carlo verification of allocated designs (seeded; modest sample sizes)."""

import numpy as np
import pytest
from dataclasses import replace

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.problem import make_design
from tolalloc.errormodel import build_error_model
from tolalloc.verify.designs import overall_verdict, pose_verdicts, verify_design

N = 100_000  # sd of P_hat near 0.95: 0.0007


@pytest.fixture(scope="module")
def res():
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0, 9, 11]])
    return allocate(pr, snap=False)


def test_exact_design_passes(res):
    v = verify_design(res.problem, res.design, n_mc=N, seed=1, keep_samples=500)
    assert v.criterion == "exact" and v.ok, v.message()
    assert np.all(v.ci_high >= 0.95) and v.verdict in ("demonstrated", "consistent")
    # MC agrees with the linear prediction (the design is small against the arm: nonlinearity is negligible)
    assert np.all(np.abs(v.p_mc - v.p_linear) < 4 * np.sqrt(0.05 * 0.95 / N) + 1e-3)
    assert np.all((v.ci_low <= v.p_mc) & (v.p_mc <= v.ci_high))
    assert v.samples_mm.shape == (500, 3) and v.samples_pose == int(np.argmin(v.p_linear))
    assert "verified" in v.message() and list(v.to_frame().columns)[:3] == ["pose", "p_linear", "p_mc"]


def test_certified_design_passes_with_the_whole_interval(res):
    v = verify_design(res.problem, res.certified, n_mc=N, seed=2, keep_samples=0)
    assert v.criterion == "certified" and v.ok, v.message()
    assert np.all(v.ci_low >= 0.95)
    assert v.verdict == "demonstrated" and "verified: demonstrated" in v.message()


def test_under_specified_design_fails_with_reason(res):
    pr = res.problem
    loose = make_design(pr, "exact", res.design.t * 1.3)
    v = verify_design(pr, loose, n_mc=N, seed=3, keep_samples=0)
    assert not v.ok
    worst = int(np.argmin(loose.p_linear["position"]))
    assert not v.passed[worst]
    assert "under-specified" in v.reason[worst]
    assert f"pose {worst + 1}" in v.message() and "verified: failed" in v.message()
    assert v.failing[0][0] == np.flatnonzero(~v.passed)[0] + 1


def test_nonlinearity_is_named_when_the_linear_prediction_passes(res):
    # a design that the linear map passes but the MC does not: fake the linear prediction
    pr = res.problem
    loose = make_design(pr, "exact", res.design.t * 1.3)
    fake = replace(loose, p_linear={"position": np.full(pr.n_poses, 0.99)})
    v = verify_design(pr, fake, n_mc=N, seed=4, keep_samples=0)
    assert not v.ok and all(r.startswith("nonlinearity") for r, ok in zip(v.reason, v.passed) if not ok)


def test_bad_inputs(res):
    with pytest.raises(TolallocError, match="n_mc"):
        verify_design(res.problem, res.design, n_mc=10)
    with pytest.raises(TolallocError, match="no tolerances"):
        verify_design(res.problem, replace(res.design, t=None, status="infeasible"))


def test_orientation_columns_in_the_verification_table():
    # regression: with an orientation requirement the per-pose orientation P_hat was computed but not reported
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0, 11]], angle_radius_deg=0.02)
    ver = verify_design(pr, allocate(pr, snap=False).design, n_mc=20000, seed=1)
    frame = ver.to_frame()
    for col in ("p_linear_angle", "p_mc_angle", "ci_low_angle", "ci_high_angle"):
        assert col in frame.columns
    assert np.all(frame.ci_low_angle <= frame.p_mc_angle) and np.all(frame.p_mc_angle <= frame.ci_high_angle)
    np.testing.assert_allclose(frame.p_linear_angle, ver.angle["p_linear"])
    assert ver.ok, ver.message()  # the branch "or not ver.ok" made this check unfalsifiable (issue 11)
    assert "orientation: lowest P_hat" in ver.message()


def test_verdicts_from_intervals():
    # hand-made intervals against p = 0.95: above, straddling, wholly below
    v = pose_verdicts([0.951, 0.949, 0.940], [0.960, 0.955, 0.9499], 0.95)
    assert v.tolist() == ["demonstrated", "consistent", "failed"]
    assert overall_verdict(v[:2]) == "consistent" and overall_verdict(v) == "failed"
    assert overall_verdict(v[:1]) == "demonstrated"


def test_no_allowance_an_interval_below_p_fails(res):
    # issue 13: an exact design whose whole MC interval lies below p (here ~0.005 below, inside the old
    # 0.002-allowance's neighbourhood only at the tightest pose) must fail, however the linear map looks
    pr = res.problem
    loose = make_design(pr, "exact", res.design.t * 1.05)
    fake = replace(loose, p_linear={"position": np.full(pr.n_poses, 0.99)})
    v = verify_design(pr, fake, n_mc=N, seed=5, keep_samples=0)
    below = v.ci_high < 0.95
    assert below.any(), v.to_frame()
    assert not v.ok and np.all(~v.passed[below]) and v.verdict == "failed"
    assert np.all(v.verdicts[below] == "failed")


def test_scheduler_does_not_change_the_verification(res):
    """The verification's Monte Carlo gives the same numbers on a Dask scheduler as locally."""
    pytest.importorskip("dask")
    local = verify_design(res.problem, res.design, n_mc=20_000, seed=5, keep_samples=0)
    dask = verify_design(res.problem, res.design, n_mc=20_000, seed=5, keep_samples=0, scheduler="threads")
    np.testing.assert_array_equal(local.p_mc, dask.p_mc)
    np.testing.assert_array_equal(local.ci_low, dask.ci_low)


def test_non_gaussian_reason_is_named():
    # every parameter uniform over +-t (costs distribution "uniform"): a design that the (faked) linear map passes
    # but the Monte Carlo does not is attributed to the non-Gaussian parameters, which carry all of the variance
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0, 11]], costs={"distribution": "uniform"})
    d = allocate(pr, snap=False).design
    loose = make_design(pr, "exact", d.t * 1.3)
    fake = replace(loose, p_linear={"position": np.full(pr.n_poses, 0.99)})
    v = verify_design(pr, fake, n_mc=20_000, seed=6, keep_samples=0)
    assert not v.ok and v.verdict == "failed"
    failing = [r for r, ok in zip(v.reason, v.passed) if not ok]
    assert failing and all(r.startswith("non-Gaussian parameters (uniform) carry 100% of the variance") for r in failing)


def test_interval_containing_p_with_few_samples_is_inconclusive(res):
    # certified criterion without pooling at n = 2000 (interval +-0.01): the exact design's poses on P = p have
    # intervals that contain p -> "inconclusive" (never "nonlinearity"), verdict consistent, not "failed"
    v = verify_design(res.problem, res.design, criterion="certified", n_mc=2000, n_max=2000, seed=7, keep_samples=0)
    contains = (v.ci_low < 0.95) & (v.ci_high >= 0.95)
    assert contains.any() and not v.ok
    for i in np.flatnonzero(contains):
        assert v.reason[i].startswith("inconclusive: interval") and "contains 0.95 at n = 2000" in v.reason[i]
        assert v.verdicts[i] == "consistent"
    assert "nonlinearity" not in v.message() and not v.message().startswith("verified: failed")
    assert v.message().startswith("verified: consistent, criterion not met")


def test_intervals_are_simultaneous_over_the_poses(res):
    # 3 poses, position only: each interval at 1 - 0.05 / 3, and every output says so
    v = verify_design(res.problem, res.design, n_mc=20_000, n_max=20_000, seed=8, keep_samples=0)
    per = 1 - 0.05 / 3
    assert (v.family_level, v.n_intervals) == (0.95, 3) and v.level_per_interval == pytest.approx(per)
    assert v.estimate.level == pytest.approx(per)
    frame = v.to_frame()
    assert np.allclose(frame.level_per_interval, per) and np.all(frame.family_level == 0.95)
    assert v.message().endswith("; intervals: 95% simultaneous over the 3 poses (Bonferroni: 3 intervals at 98.33% "
                                "each)")
    assert "simultaneous 95% bound" in v.message() and v.interval_label() == "simultaneous 95% interval"
    # a wider family level gives narrower intervals on the same draws
    w = verify_design(res.problem, res.design, n_mc=20_000, n_max=20_000, seed=8, keep_samples=0, level=0.8)
    assert np.all(w.ci_high - w.ci_low < v.ci_high - v.ci_low) and np.array_equal(w.p_mc, v.p_mc)
    with pytest.raises(TolallocError, match=r"level: expected a confidence level in \[0.5, 1\) .* got 1.5"):
        verify_design(res.problem, res.design, n_mc=20_000, level=1.5)


def test_a_possible_second_look_is_counted_in_the_family(res):
    # certified with n_max > n_mc: each of the 3 position intervals may be re-run, so 6 intervals at 1 - 0.05 / 6;
    # so with the exact criterion and auto on a Gaussian model (the second look is importance sampling); with
    # n_max = n_mc (no second look) or the exact criterion with another estimator, 3 at 1 - 0.05 / 3
    v = verify_design(res.problem, res.design, criterion="certified", n_mc=2000, n_max=8000, seed=7, keep_samples=0)
    per = 1 - 0.05 / 6
    assert (v.n_intervals, v.second_looks) == (6, 3) and v.level_per_interval == pytest.approx(per)
    assert v.estimate.level == pytest.approx(per) and np.allclose(v.to_frame().level_per_interval, per)
    assert v.n.max() == 8000  # the design sits on p at a pose: its interval straddled p and was looked at again
    assert v.message().endswith("; intervals: 95% simultaneous over the 3 poses (Bonferroni: 6 intervals at 99.17% "
                                "each, a possible second look at each position interval counted)")
    # the correction loop's margin, z + 3 standard errors, takes z of the same per-interval level
    from tolalloc.montecarlo.intervals import z_of_level
    from tolalloc.verify.correct import needed_targets

    chk = v.requirements()[0]
    se = (chk.ci_high - chk.ci_low) / (2 * z_of_level(per))
    short = chk.ci_low < 0.95 + 3 * se
    assert short.any()
    want = 0.95 + np.maximum(0, chk.p_linear - chk.p_mc) + (z_of_level(per) + 3) * se
    np.testing.assert_allclose(needed_targets(chk, np.full(3, 0.95))[short], want[short])
    once = verify_design(res.problem, res.design, criterion="certified", n_mc=2000, n_max=2000, seed=7,
                         keep_samples=0)
    exact = verify_design(res.problem, res.design, criterion="exact", n_mc=2000, n_max=8000, seed=7, keep_samples=0,
                          estimator="paired")
    for w in (once, exact):
        assert (w.n_intervals, w.second_looks) == (3, 0) and w.level_per_interval == pytest.approx(1 - 0.05 / 3)
        assert "second look" not in w.message() and w.n.max() == 2000
    auto = verify_design(res.problem, res.design, criterion="exact", n_mc=2000, n_max=8000, seed=7, keep_samples=0)
    assert (auto.n_intervals, auto.second_looks) == (6, 3)
    tight = int(np.argmin(res.design.p_linear["position"]))  # on p: its paired interval straddled p
    assert auto.estimator[tight] == "importance" and auto.n[tight] == 8000
    assert auto.estimate.requested == "auto" and "(requested auto)" in auto.estimator_message()
