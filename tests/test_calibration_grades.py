"""Repeatability grades (issue 14 item 1): the random part of a systematic parameter as a decision variable with
its own cost law, in the calibration-aware allocation."""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.certified import allocate_calibrated, post_ratio
from tolalloc.allocate.problem import build_problem
from tolalloc.calibration import make_plan, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot

GRADE = dict(model="reciprocal", a=0.2, b=0.3, t_ref_deg=0.001, t_min_deg=0.0003, t_max_deg=0.01)


@pytest.fixture(scope="module")
def case():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    pr = build_problem(model, robot.poses("working")[:4])
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    return model, pr, plan


def _solve(case, grade):
    model, pr, plan = case
    split = split_errors(model, {"kinds": {"joint_drive": {"grade": grade}}})
    return split, allocate_calibrated(pr, plan, split=split)


def test_a_pinned_grade_equals_the_fixed_repeatability(case):
    """A grade whose limits pin the band at z * 0.0003 deg (the default sigma) gives the default design."""
    model, pr, plan = case
    fixed = allocate_calibrated(pr, plan, split=split_errors(model))
    band = pr.costs.z * 0.0003
    _, res = _solve(case, dict(GRADE, t_min_deg=band, t_max_deg=band))
    assert res.certified and fixed.certified
    assert res.design.cost == pytest.approx(fixed.design.cost, rel=1e-3)
    n_graded = int(np.isfinite(res.grade_t).sum())
    assert n_graded == 5  # five revolute joint drives (the prismatic drive has its own kind)
    assert res.grade_cost == pytest.approx(n_graded * (0.2 + 0.3 / (band / 0.001)), rel=1e-9)
    assert res.summary()["cost"] == pytest.approx(res.design.cost + res.grade_cost)


def test_free_grades_are_certified_and_no_dearer_than_any_uniform_fixed_grade(case):
    model, pr, plan = case
    split, res = _solve(case, GRADE)
    assert res.certified
    t = res.grade_t[np.isfinite(res.grade_t)]
    assert np.all(t >= np.radians(0.0003) * (1 - 1e-9)) and np.all(t <= np.radians(0.01) * (1 + 1e-9))
    # independent re-check of the requirement with the chosen random parts
    rnd = split.random_sigma.copy()
    ok = np.isfinite(res.grade_t)
    rnd[ok] = res.grade_t[ok] / pr.costs.z
    ratio, _ = post_ratio(pr, split.with_random_sigma(rnd), plan, res.design.t)
    assert ratio <= 1.0 + 1e-7
    totals = []
    for tg in (0.0003, 0.001, 0.0015, 0.003):
        _, r = _solve(case, dict(GRADE, t_min_deg=tg, t_max_deg=tg))
        assert r.design.ok
        totals.append(r.summary()["cost"])
    assert res.summary()["cost"] <= min(totals) * (1 + 1e-3)
    frame = res.to_frame()
    assert {"repeatability_grade_mm", "repeatability_grade_deg", "repeatability_grade_cost"} <= set(frame.columns)
    drives = frame["parameter"].isin(["dth1", "dth2", "dth3", "dth5", "dth6"])  # revolute drives: deg
    assert frame.loc[drives, "repeatability_grade_deg"].notna().all()
    assert frame.loc[drives, "repeatability_grade_mm"].isna().all()


@pytest.mark.parametrize("over, match", [
    ({"kinds": {"clearance_axial": {"grade": GRADE}}}, "no systematic part"),
    ({"kinds": {"joint_drive": {"grade": GRADE, "repeatability_deg": 0.001}}}, "not both"),
    ({"kinds": {"joint_drive": {"grade": 0.001}}}, "cost-law table"),
])
def test_bad_grade_tables_are_refused_when_read(case, over, match):
    model = case[0]
    with pytest.raises(TolallocError, match=match):
        split_errors(build_error_model(load_robot("tool_changer"), clearance=True) if "clearance" in str(over)
                     else model, over)


@pytest.mark.parametrize("grade, match", [
    (dict(GRADE, tol_deg=0.001), "no meaning for a grade"),
    ({k: v for k, v in GRADE.items() if k != "t_max_deg"}, "t_max are required"),
    ({**{k: v for k, v in GRADE.items() if not k.endswith("_deg")}, "t_ref_mm": 1, "t_min_mm": 1, "t_max_mm": 1},
     "wrong unit"),
])
def test_bad_grade_cost_laws_name_the_parameter(case, grade, match):
    with pytest.raises(TolallocError, match=match) as exc:
        _solve(case, grade)
    assert "calibration grade of dth1" in str(exc.value)
