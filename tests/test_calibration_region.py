"""Calibration-aware allocation over a box and the exact stage (tolalloc.allocate.calibrated.region / _exact / _design).

Known answers: the problem rebuilt at other poses equals build_problem there; every probability is re-derived from an
independently computed posterior (tolalloc.calibration.posterior) on fresh poses; the exact stage's binding poses sit
at p and it is cheaper than the certified design; a refused IPOPT point falls back to the certified design, labelled.
"""

import json

import numpy as np
import pytest

from tolalloc.allocate.calibrated.design import allocate_with_calibration
from tolalloc.allocate.calibrated.exact import FEAS_TOL
from tolalloc.allocate.calibrated.region import (
    baseline_region,
    certified_region,
    cutting_plane,
    problem_at,
)
from tolalloc.allocate.calibrated.summary import summary_search_lines
from tolalloc.allocate.problem import build_problem
from tolalloc.allocate.region import _position_cov, box_region, worst_pose
from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.linear.probability import p_within_radius
from tolalloc.robot.io import load_robot


@pytest.fixture(scope="module")
def case():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    pr = build_problem(model, robot.poses("working")[:4])
    lo, hi = robot.regions["working"]
    mid, half = 0.5 * (lo + hi), 0.25 * (hi - lo)
    return robot, plan, pr, box_region(robot, mid - half, mid + half, "small")


@pytest.fixture(scope="module")
def box_result(case):
    robot, plan, pr, box = case
    return allocate_with_calibration(pr, plan, region=box, baseline=False, coverage_n=2000, seed=1, n_seed=128,
                                     n_starts=3)


def _fresh_p(res, design_t, grades_split, q):
    """Post-calibration P at poses q from a posterior computed here (not the allocation's)."""
    post = posterior(grades_split.with_model(res.problem.model_for(design_t)), res.plan)
    return p_within_radius(post.tool_covariance(q), res.problem.radius_mm)


def test_problem_at_equals_build_problem(case):
    robot, plan, pr, box = case
    q = robot.poses("working")[4:9]
    a, b = problem_at(pr, q), build_problem(pr.model, q)
    np.testing.assert_allclose(a.J, b.J, rtol=0, atol=0)
    for key in ("A", "C0", "eig_bound", "trace_bound", "target"):
        np.testing.assert_allclose(a.blocks[0][key], b.blocks[0][key], rtol=1e-15, atol=0)


def test_pose_cov_callback_defaults_to_the_design(case):
    robot, plan, pr, box = case
    t = pr.t_max.copy()
    ref = worst_pose(pr, t, box, n_seed=64, n_starts=2, seed=3)
    cb = worst_pose(pr, None, box, n_seed=64, n_starts=2, seed=3, pose_cov=lambda Q: _position_cov(pr, t, Q))
    assert cb[1] == pytest.approx(ref[1], abs=1e-14) and np.allclose(cb[0], ref[0])


def test_search_that_stops_says_why(case):
    """A search that does not converge names its reason: the round limit, or a round with no design."""
    robot, plan, pr, box = case
    loose = lambda Q: _position_cov(pr, pr.t_max, Q)  # noqa: E731 (the loosest design misses p everywhere)
    _, s, _ = cutting_plane(pr, box, lambda p: ("design", 1.0, loose), pr.q[:1], max_rounds=2, n_seed=32,
                            n_starts=1)
    assert not s.converged and s.rounds == 2 and s.stop_reason == "round limit (2) reached"
    _, s, _ = cutting_plane(pr, box, lambda p: (None, float("nan"), None), pr.q[:3], max_rounds=5)
    assert not s.converged and s.rounds == 1 and s.stop_reason == "no design over the 3 active pose(s) of round 1"
    line = summary_search_lines("small", {"certified": s})[0]
    assert line.endswith("(NOT converged: no design over the 3 active pose(s) of round 1)"), line


def test_box_design_meets_p_on_fresh_poses(box_result):
    res = box_result
    assert res.region_kind == "box" and res.search.converged and res.search_exact.converged
    assert res.exact_accepted and res.coverage is not None and res.coverage.ok
    rng = np.random.default_rng(99)
    box = res.region
    q = box.q_min + rng.random((3000, 6)) * (box.q_max - box.q_min)
    p = _fresh_p(res, res.design.t, res.post.split, q)
    assert p.min() >= res.problem.prob - 1e-4  # the search's tolerance
    # the certified design on its own active set holds the eigenvalue rule (certified) and P >= p on the box
    assert res.certified.certified
    pc = _fresh_p(res, res.certified.design.t, res.certified.post.split, q)
    assert pc.min() >= res.problem.prob - 1e-4


def test_exact_stage_sits_at_p_and_is_cheaper(box_result):
    res = box_result
    p = _fresh_p(res, res.design.t, res.post.split, res.problem.q)
    assert p.min() == pytest.approx(res.problem.prob, abs=FEAS_TOL)  # a binding pose at p, none below
    assert res.cost_exact < res.cost_certified
    s = json.loads(json.dumps(res.summary(), allow_nan=False))  # valid JSON as it is
    assert s["cost"] == s["cost_exact"] and s["region"]["search_exact"]["converged"]
    assert s["coverage"]["ok"] and s["worst_p_post"] >= res.problem.prob - 1e-4
    assert "exact" in res.message() and "coverage" in res.message()
    frame = res.to_frame()
    assert (frame["tol_exact_mm"].notna() | frame["tol_exact_deg"].notna()).all()
    assert list(frame.columns[2:6]) == ["tol_certified_mm", "tol_certified_deg", "tol_exact_mm", "tol_exact_deg"]


def test_guard_keeps_the_certified_design_when_ipopt_fails(case, monkeypatch):
    from tolalloc.allocate.calibrated import exact as calibrated_exact

    robot, plan, pr, box = case

    def fail(self, x0):
        return np.clip(x0, self.lbx, self.ubx) * 1.1, False, "Maximum_Iterations_Exceeded"

    monkeypatch.setattr(calibrated_exact._NLP, "solve", fail)
    res = allocate_with_calibration(pr, plan, baseline=False)
    assert not res.exact_accepted and res.design.fallback_from == "exact"
    assert res.design.solver == "calibrated-lmi" and res.design.ok  # the certified design, not called exact
    assert "did not converge" in res.design.message and res.cost == res.cost_certified
    assert res.summary()["cost_exact"] is None and "fallback from exact" in res.summary()["design"]


def test_empty_plan_region_equals_the_uncalibrated_lmi_region(case):
    """Without calibration and without repeatability, the calibrated cutting plane is the LMI region design."""
    robot, plan, pr, box = case
    split = split_errors(pr.model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0},
                                              "joint_drive_prismatic": {"repeatability_mm": 0.0}}})
    empty = make_plan(robot, np.zeros((0, 6)))
    q0 = pr.q
    kw = dict(seed=2, n_seed=128, n_starts=3)
    cert, s1, static = certified_region(pr, empty, split, box, q0, **kw)
    lmi, s2, _, _ = baseline_region(pr, box, q0, static, exact=False, **kw)
    assert s1.converged and s2.converged
    assert cert.design.cost == pytest.approx(lmi.cost, rel=1e-4)


def test_exact_stage_with_grades_and_clearances():
    """Random-only parts and repeatability grades: the exact stage never loosens them beyond the certified design
    (its whitening is the certified design's), and its design holds by the recomputed posterior."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot, clearance=True)
    pr = build_problem(model, robot.poses("working")[:3])
    grade = dict(model="reciprocal", a=0.2, b=0.3, t_ref_deg=0.001, t_min_deg=0.0003, t_max_deg=0.01)
    split = split_errors(model, {"kinds": {"joint_drive": {"grade": grade}}})
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    res = allocate_with_calibration(pr, plan, split=split, baseline=False)
    assert res.exact_accepted and res.cost_exact <= res.cost_certified
    rand = ~split.systematic
    assert np.all(res.exact.design.t[rand] <= res.certified.design.t[rand] * (1 + 1e-9))
    g = split.graded
    assert np.all(res.exact.grade_t[g] <= res.certified.grade_t[g] * (1 + 1e-9))
    p = _fresh_p(res, res.design.t, res.post.split, pr.q)
    assert p.min() >= pr.prob - FEAS_TOL
