"""The verdict counts the orientation requirement as it counts the position one; the correction loop tightens both."""

from dataclasses import replace

import numpy as np
import pytest

import tolalloc
from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.errormodel import build_error_model
from tolalloc.verify.correct import correct_design, needed_targets
from tolalloc.verify.designs import Verification, verify_design
from tolalloc.verify.verdicts import weakest

P = 0.95


def _verification(pos, ang, criterion="exact"):
    """A hand-made verification at p = 0.95 from (P_hat, lower, upper) rows per pose, position and orientation."""
    pos, ang = np.asarray(pos, float), np.asarray(ang, float)
    n = len(pos)
    a_ok = ang[:, 1] >= P if criterion == "certified" else ang[:, 2] >= P
    ok = pos[:, 1] >= P if criterion == "certified" else pos[:, 2] >= P
    angle = {"prob": P, "p_linear": np.full(n, P), "p_mc": ang[:, 0], "ci_low": ang[:, 1], "ci_high": ang[:, 2],
             "passed": a_ok, "estimator": np.full(n, "paired")}
    return Verification(criterion, 0.5, P, np.full(n, 2000), 0, np.full(n, P), pos[:, 0], pos[:, 1], pos[:, 2],
                        ok & a_ok, ("",) * n, int(np.argmin(pos[:, 0])), angle=angle)


ABOVE, STRADDLE, BELOW = (0.96, 0.955, 0.965), (0.95, 0.948, 0.952), (0.94, 0.935, 0.945)


def test_weakest_of_the_requirements_pose_by_pose():
    a = np.array(["demonstrated", "demonstrated", "consistent", "failed"])
    b = np.array(["demonstrated", "consistent", "demonstrated", "consistent"])
    assert weakest(a, b).tolist() == ["demonstrated", "consistent", "consistent", "failed"]


def test_orientation_below_p_is_not_demonstrated():
    # position demonstrated at both poses, orientation's lower bound below p at pose 2
    v = _verification([ABOVE, ABOVE], [ABOVE, STRADDLE])
    assert v.verdicts.tolist() == ["demonstrated", "consistent"] and v.verdict == "consistent"
    assert v.limited_by == "orientation" and v.ok  # an exact design passes a consistent pose
    msg = v.message()
    assert msg.startswith("verified: consistent") and "lower 95% bound >= p at every pose" not in msg
    assert "orientation: lower 95% bound below p = 0.95 at 1 pose(s), by up to 0.0020 at pose 2 (0.9480)" in msg
    req = v.requirements_summary()
    assert req["limited_by"] == "orientation"
    pos, ang = req["requirements"]
    assert (pos["requirement"], pos["verdict"], pos["margin"]) == ("position", "demonstrated", pytest.approx(0.005))
    assert (ang["verdict"], ang["poses_not_demonstrated"], ang["worst_pose"]) == ("consistent", [2], 2)
    assert ang["bound"] == "lower" and ang["margin"] == pytest.approx(-0.002)


def test_position_below_p_with_orientation_demonstrated():
    v = _verification([STRADDLE, ABOVE], [ABOVE, ABOVE])
    assert v.verdicts.tolist() == ["consistent", "demonstrated"] and v.limited_by == "position"
    msg = v.message()
    assert "position: lower 95% bound below p = 0.95 at 1 pose(s), by up to 0.0020 at pose 1 (0.9480)" in msg
    assert "orientation: lower" not in msg and "orientation: upper" not in msg


def test_orientation_wholly_below_p_fails_and_certified_needs_both_demonstrated():
    v = _verification([ABOVE, ABOVE], [ABOVE, BELOW])
    assert v.verdicts.tolist() == ["demonstrated", "failed"] and v.verdict == "failed" and not v.ok
    assert "orientation: upper 95% bound below p = 0.95 at 1 pose(s), by up to 0.0050 at pose 2 (0.9450)" in v.message()
    c = _verification([ABOVE, ABOVE], [ABOVE, STRADDLE], criterion="certified")
    assert c.verdict == "consistent" and not c.ok and c.message().startswith("verified: consistent, criterion not met")
    both = _verification([ABOVE, ABOVE], [ABOVE, ABOVE], criterion="certified")
    assert both.verdict == "demonstrated" and both.ok
    assert "at every pose for position and orientation" in both.message() and "least margin: position" in both.message()


def test_orientation_target_rule_and_problem_target():
    v = _verification([ABOVE, ABOVE], [ABOVE, STRADDLE])
    pos, ang = v.requirements()
    z = 1.959963984540054  # a single 95 % interval: the default margin is z + 3 standard errors
    # ABOVE clears p (lower bound 0.955) by 1.96 standard errors of its interval, less than the 3 that fresh draws
    # need: it is tightened too, to p + (z + 3) se (no shortfall: its P_hat lies above its linear P)
    se_above = 0.01 / (2 * z)
    np.testing.assert_allclose(needed_targets(pos, np.full(2, P)), [P + (z + 3) * se_above] * 2)
    wide = replace(v, ci_low=np.array([0.99, 0.99]), ci_high=np.array([0.991, 0.991]))  # 0.99: far above p
    np.testing.assert_array_equal(needed_targets(wide.requirements()[0], np.full(2, P)), [P, P])
    se = 0.004 / (2 * z)
    np.testing.assert_allclose(needed_targets(ang, np.full(2, P)), [P + (z + 3) * se_above, P + (z + 3) * se])
    # k_se = 3 leaves a margin of 3 - z = 1.04 se beyond z: ABOVE clears p by 1.96 se, so it stays
    np.testing.assert_allclose(needed_targets(ang, np.full(2, P), k_se=3.0), [P, P + 3 * se])
    # simultaneous over 2 poses x 2 requirements: each interval at 1 - 0.05 / 4, z = 2.4977; se from that z
    sim = replace(v, n_intervals=4).requirements()[1]
    z4 = 2.4977054744123865
    np.testing.assert_allclose(needed_targets(sim, np.full(2, P)),
                               [P + (z4 + 3) * 0.01 / (2 * z4), P + (z4 + 3) * 0.004 / (2 * z4)])
    model = build_error_model(load_robot("ur10"))
    q = model.robot.poses("working")[[0, 2]]
    pr = build_problem(model, q, radius_mm=0.5, angle_radius_deg=0.05, angle_target=[0.95, 0.96])
    np.testing.assert_array_equal(pr.blocks[1]["target"], [0.95, 0.96])
    with pytest.raises(TolallocError, match=r"angle_target: expected 2 per-pose probabilities in \[angle_prob = 0.95"):
        build_problem(model, q, radius_mm=0.5, angle_radius_deg=0.05, angle_target=[0.9, 0.96])
    with pytest.raises(TolallocError, match="angle_target: per-pose orientation targets need an orientation"):
        build_problem(model, q, radius_mm=0.5, angle_target=[0.95, 0.96])


@pytest.fixture(scope="module")
def ur10_orientation():
    # ur10, r = 0.5 mm and 0.05 deg at p = 0.95: the exact design sits on the orientation requirement at every pose
    return tolalloc.allocate_tolerances("ur10", [tolalloc.PositionRequirement(radius_mm=0.5),
                                                 tolalloc.OrientationRequirement(radius_deg=0.05)],
                                        solver=tolalloc.Solver(snap=False),
                                        verification=tolalloc.Verification(n_mc=2000, correction=False))


def test_allocation_with_orientation_below_p_is_not_demonstrated(ur10_orientation):
    res = ur10_orientation
    v = res.verification_frame()
    assert (v.ci_low_angle < 0.95).any()
    assert res.verdict != "demonstrated" and (v.verdict[v.ci_low_angle < 0.95] != "demonstrated").all()
    s = res.summary()["verification"]
    assert s["requirements"][1]["requirement"] == "orientation" and s["requirements"][1]["verdict"] == "consistent"
    assert "orientation: lower simultaneous 95% bound below p = 0.95" in s["message"]


def test_correction_raises_the_orientation_target(ur10_orientation):
    res = ur10_orientation
    c = correct_design(build_error_model(load_robot("ur10")), res.problem.q, n_mc=2000, result=res.result,
                       verification=res.verification, radius_mm=0.5, angle_radius_deg=0.05)
    assert c.before.verdict == "consistent" and c.verification.verdict == "demonstrated" and not c.stopped
    assert c.tightened_angle.size and np.all(c.angle_targets[c.tightened_angle] > 0.95)
    np.testing.assert_array_equal(c.result.problem.blocks[1]["target"], c.angle_targets)
    assert np.all(c.verification.angle["ci_low"] >= 0.95) and c.cost_of_correction > 0
    assert "orientation poses tightened (target): " in c.message()
    d = c.to_dict()
    assert d["poses_tightened_angle"] == [int(i) + 1 for i in c.tightened_angle]
    assert d["angle_target_per_pose"] == pytest.approx(c.angle_targets.tolist())


def test_round_limit_names_the_orientation_shortfall(ur10_orientation):
    res = ur10_orientation
    c = correct_design(build_error_model(load_robot("ur10")), res.problem.q, n_mc=2000, result=res.result,
                       verification=res.verification, max_rounds=0, radius_mm=0.5, angle_radius_deg=0.05)
    assert c.stopped and c.reason.startswith("round limit (0) reached; still short: ")
    assert "orientation: lower simultaneous 95% bound below p = 0.95" in c.reason and "not demonstrated" in c.message()


def test_certified_criterion_names_the_orientation_reason():
    # the exact design judged by the certified criterion at n = 2000: the orientation interval contains p at the
    # poses where the design sits on it -> consistent, criterion not met, reason "orientation inconclusive"
    model = build_error_model(load_robot("ur10"))
    pr = build_problem(model, model.robot.poses("working")[[0, 2]], radius_mm=2.0, angle_radius_deg=0.05)
    v = verify_design(pr, allocate(pr, snap=False).design, criterion="certified", n_mc=2000, n_max=2000,
                      keep_samples=0)
    assert v.verdict == "consistent" and not v.ok and v.limited_by == "orientation"
    assert np.all(v.ci_low >= 0.95)  # the position requirement is demonstrated: r = 2 mm is loose
    for i in np.flatnonzero(~v.passed):
        assert v.reason[i].startswith("orientation inconclusive: P_hat = ")
        assert "contains 0.95 at n = 2000, lower bound 0.0031 below" in v.reason[i]
    assert v.message().startswith("verified: consistent, criterion not met (pass: whole simultaneous 95% interval "
                                  ">= p; orientation: lower simultaneous 95% bound below p = 0.95")
    assert v.message().endswith("; intervals: 95% simultaneous over the 2 poses and 2 requirements (Bonferroni: 4 "
                                "intervals at 98.75% each)")
    assert (v.n_intervals, v.level_per_interval) == (4, pytest.approx(0.9875))


def test_orientation_tail_too_thin_for_the_samples_is_refused_with_the_samples_needed():
    # 2 poses x 2 requirements: each interval at 1 - 0.05 / 4 = 98.75 %, z = 2.4977; the orientation tail
    # 1 - 0.999 needs n >= z^2 p / (1 - p) = 6233 -- importance sampling (position only) cannot stand in for it
    model = build_error_model(load_robot("ur10"))
    pr = build_problem(model, model.robot.poses("working")[:2], radius_mm=0.5, angle_radius_deg=0.05,
                       angle_prob=0.999)
    d = allocate(pr, snap=False).design
    # auto on this Gaussian model may give each position interval a second look (importance sampling): 6 intervals
    # at 99.17 %, z = 2.6383, n >= 6954
    for estimator, need in (("auto", 6954), ("paired", 6233), ("importance", 6233)):
        with pytest.raises(TolallocError, match=r"n_mc 2000 samples per pose cannot resolve the orientation tail "
                                                rf"1 - p = 0.001 .* give `n_mc` >= {need} \(importance sampling "
                                                r"estimates the position requirement only"):
            verify_design(pr, d, n_mc=2000, estimator=estimator, keep_samples=0)


def test_one_pose_wording_and_a_cheaper_correction_signed():
    from tolalloc.verify.correct import Correction

    v = replace(_verification([[0.97, 0.96, 0.98]], [[0.97, 0.96, 0.98]]), n_intervals=2)
    msg = v.message()
    assert "demonstrated by nonlinear Monte Carlo at the 1 pose (" in msg
    assert "95% simultaneous over 1 pose and 2 requirements (Bonferroni: 2 intervals at 97.5% each)" in msg
    c = Correction(None, v, v, 1, np.array([0.951]), (48.0, 47.9992), False, angle_targets=np.array([0.95]))
    assert c.message().endswith("cost 48.0000 -> 47.9992 (-0.0008, -0.00167 %)")
