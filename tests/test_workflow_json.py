"""Every job's summary() is plain JSON data (lists and Python numbers), as summary.json holds it: a notebook can
pass it to json.dumps as it is."""

import json

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose import generate
from tolalloc.diagnose.synth import split_frame
from tolalloc.outputs import json_native


def test_json_native_turns_numpy_into_python():
    out = json_native({"a": np.arange(3), "b": (np.float32(1.5), [np.int64(2), {"c": np.array([[1.0]])}]),
                       "d": np.bool_(True), "e": "x"})
    assert out == {"a": [0, 1, 2], "b": [1.5, [2, {"c": [[1.0]]}]], "d": True, "e": "x"}
    assert type(out["b"][1][0]) is int and type(out["d"]) is bool


@pytest.mark.parametrize("job", ["analysis", "allocation", "diagnosis"])
def test_summary_is_json_as_it_is(job):
    if job == "analysis":
        res = tolalloc.analyze_errors("tool_changer", radius_mm=0.25)
    elif job == "allocation":
        res = tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False)
    else:
        robot = tolalloc.load_robot("ur10")
        case = generate(robot, "none", 40, np.random.default_rng(1))
        tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
        res = tolalloc.diagnose_measurements(robot, tr, te, folds=2)
    s = res.summary()
    assert json.loads(json.dumps(s)) == s


def test_predictions_carry_the_test_row_to_join_on():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "none", 40, np.random.default_rng(1))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    te = te.copy()
    te.loc[2, "x_mm"] = np.nan  # a skipped row keeps its place, with empty predictions
    pred = tolalloc.diagnose_measurements(robot, tr, te, folds=2).predictions_frame()
    assert pred["row"].tolist() == list(range(1, len(te) + 1))
    assert pred.loc[2, ["x_mm", "y_mm", "z_mm"]].isna().all() and pred.drop(index=2)["x_mm"].notna().all()


def test_analysis_text_labels_each_pose_value():
    a = tolalloc.analyze_errors("tool_changer", radius_mm=0.25, poses="working", prob=0.95)
    line = next(ln for ln in a.text().splitlines() if ln.startswith("P(|dp| < 0.25 mm) = "))
    p = a.linear.p_within(0.25)
    assert line == "P(|dp| < 0.25 mm) = per pose " + ", ".join(f"{i + 1}: {v:.6g}" for i, v in enumerate(p))


def test_plan_headline_gives_absolute_figures_and_says_what_the_floor_is():
    plan = tolalloc.plan_calibration("tool_changer", 8, n_candidates=24)
    d = plan.design
    pct = 100 * (d.random_score_mm2 - d.score_mm2) / d.random_score_mm2
    assert plan.headline()[1] == ("mean post-calibration position variance (systematic part) [mm^2]: designed "
                                  f"{d.score_mm2:.6g}, random {d.random_score_mm2:.6g} (designed {pct:.2g} % lower); "
                                  f"no calibration {d.no_calibration_mm2:.6g}")
    assert plan.headline()[2] == (f"floor (all 24 candidates measured) {d.floor_mm2:#.6g} mm^2, of which "
                                  f"{d.floor_unidentifiable_mm2:#.6g} in parameter combinations no candidate "
                                  "identifies (the rest: noise and repeatability); above the floor: designed "
                                  f"{d.score_mm2 - d.floor_mm2:.4g}, random "
                                  f"{d.random_score_mm2 - d.floor_mm2:.4g} mm^2")
    assert plan.headline()[2] in plan.text()
    assert 0 < d.floor_unidentifiable_mm2 <= d.floor_mm2 <= d.score_mm2 < d.no_calibration_mm2
    s = plan.summary()
    assert s["floor_unidentifiable_mm2"] == d.floor_unidentifiable_mm2
    assert s["no_calibration_mm2"] == d.no_calibration_mm2
    assert list(s["unidentifiable_sigma_fraction"]) == list(plan.unidentifiable)
    assert json.loads(json.dumps(s)) == s
    few = tolalloc.plan_calibration("tool_changer", 2, n_candidates=24)  # 6 rows < 9 registration unknowns
    assert "(the same); no calibration" in few.headline()[1]
