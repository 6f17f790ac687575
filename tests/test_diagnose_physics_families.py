"""The diagnosis on the physics stage: the gear-ratio search, the family probabilities, robust fits that keep the
corners of the data, findings that are one of several readings."""

import re

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.diagnose import diagnose, generate, measurements_from_frame
from tolalloc.diagnose.calibrate import Fit, _loss_for_size, fixed_jacobian, outlier_rows, small_file_min_gain
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.guards import ParameterCheck
from tolalloc.diagnose.ratio_search import search_ratios
from tolalloc.diagnose.synth import split_frame
from tolalloc.physics.loads import point_jacobian, target_points

UR10 = tolalloc.load_robot("ur10")


def _gear_frame(seed: int, amp: float, P: int = 150, N: int = 101):
    """UR10 poses whose first three joints carry a strain-wave error at N = 101 and 2N, or a stage's at another N (and
    noise 0.02 mm)."""
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (P, 6))
    dq = np.zeros_like(q)
    for j in range(3):
        dq[:, j] = amp * np.sin(N * q[:, j] + 1.0) + 0.7 * amp * np.sin(2 * N * q[:, j] + 0.3)
    x = target_points(UR10, q + dq, np.array([0.0, 0.0, 50.0])) + rng.normal(0, 0.02, (P, 3))
    df = pd.DataFrame(np.degrees(q), columns=[f"q{i + 1}_deg" for i in range(6)])
    df[["x_mm", "y_mm", "z_mm"]] = x
    return q, x, df


@pytest.mark.parametrize("amp, N, found", [(1.5e-4, 101, True), (1.5e-4, 12, True), (0.0, 101, False)])
def test_gear_ratio_search_finds_n_only_where_the_residual_carries_it(amp, N, found):
    """A reducer's N (30-200) or, where none stands out, a stage's before the output (7-29) is found where the
    residual carries it; pure noise finds neither band's."""
    q, x, _ = _gear_frame(1, amp, N=N)
    model = build_geometry_model(UR10)
    fit = Fit(model, np.eye(3), np.zeros(3), np.array([0.0, 0.0, 50.0]), np.zeros(len(model.params)),
              np.zeros(0, int))
    resid = x - target_points(UR10, q, fit.t_mm)
    ratios, notes = search_ratios(UR10, q, fit, fixed_jacobian(fit, q, x), resid)
    if found:
        np.testing.assert_array_equal(ratios[:3], [N, N, N])
        assert re.match(rf"gear ratio of shoulder_pan_joint: N = {N} found in the training residual", notes[0].text)
        assert all(n.telling for n in notes[:3]) and not any(n.telling for n in notes[3:])
        assert np.all(np.isnan(ratios[3:]))
    else:
        assert np.all(np.isnan(ratios))
        assert all("no frequency N = 30-200 stands out" in n.text and "; no frequency N = 7-29 stands out" in n.text
                   and n.text.endswith("; no gear term") and not n.telling for n in notes)
    known = np.array([101.0, np.nan, np.nan, np.nan, np.nan, np.nan])
    ratios, notes = search_ratios(UR10, q, fit, fixed_jacobian(fit, q, x), resid, known=known)
    assert ratios[0] == 101.0 and len(notes) == 5  # a ratio the robot file gives is not searched


def test_strain_wave_gear_error_is_named_transmission_with_its_probability():
    _, _, df = _gear_frame(1, 1.5e-4)
    res = tolalloc.diagnose_measurements("ur10", df.iloc[:110], df.iloc[110:], folds=3)
    s = res.summary()
    assert s["verdict"] == "effect" and s["candidates"] == ["transmission"]
    top = max(s["ranking"], key=lambda c: c["probability"] or 0.0)  # null: a family the data cannot carry
    assert top["effect"] == "transmission" and top["variant"] == "gear" and top["probability"] > 0.9
    assert s["test_rms_mm"]["final"] < 0.5 * s["test_rms_mm"]["geometric"]
    assert any(r.startswith("gear ratio of shoulder_lift_joint: N = 101 found") for r in s["reasons"])
    # 110 training poses for more than 11 parameters: a small file, whose selection asks for a gain beyond the spread
    # of its own out-of-fold RMS (the transmission's is far above it)
    assert s["settings"]["selection_min_gain"] == pytest.approx(1.0 / np.sqrt(6 * 110))
    assert any(r.startswith("minimum gain of a selected effect raised from 2 % to 3.89 %: 110 training poses") for r
               in s["reasons"])


def test_robust_fits_choose_huber_on_small_files_and_say_so():
    assert _loss_for_size(400, 40) == ("tukey", "")
    loss, note = _loss_for_size(18, 36)
    assert loss == "huber" and note.startswith("robust loss: Huber in place of Tukey's biweight: 18 training poses "
                                               "for 36 parameters (fewer than 10 per parameter)")


def test_small_files_raise_the_minimum_gain_to_the_spread_of_their_rms():
    assert small_file_min_gain(400, 40, 0.02) == (0.02, "")  # 10 poses per parameter: not small
    gain, note = small_file_min_gain(30, 25, 0.02)
    assert gain == pytest.approx(1.0 / np.sqrt(180))  # relative sd of an RMS over 90 coordinates
    assert note.startswith("minimum gain of a selected effect raised from 2 % to 7.45 %: 30 training poses for 25 "
                           "parameters") and "1/sqrt(2 x 90)" in note
    assert small_file_min_gain(30, 25, 0.10) == (0.10, "")  # asked for more than the spread: kept


def test_down_weighted_rows_are_listed_with_their_stage():
    res = np.zeros((6, 3))
    res[:, 0] = [0.01, -0.01, 0.012, 0.2, -0.011, 2.0]
    fit = Fit(None, np.eye(3), np.zeros(3), np.zeros(3), np.zeros(0), np.zeros(0, int), residual_mm=res,
              weights=np.array([1.0, 1.0, 1.0, 0.3, 1.0, 0.0]))
    out = outlier_rows(fit, np.arange(11, 17), stage="geometric")
    assert [(o["stage"], o["row"], o["weight"]) for o in out] == [("geometric", 16, 0.0), ("geometric", 14, 0.3)]


def test_gross_training_errors_that_move_the_least_squares_baseline_are_said_in_the_verdict():
    case = generate(UR10, "none", 120, np.random.default_rng(6), noise_mm=0.02)
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(2))
    tr = tr.copy()
    tr.loc[[3, 40, 77], "z_mm"] += [30.0, -40.0, 25.0]
    d = diagnose(UR10, measurements_from_frame(tr, UR10), measurements_from_frame(te, UR10), folds=3,
                 max_effects=0)
    line = next(r for r in d.verdict.reasons if r.startswith("robust weighting moved the nominal baseline"))
    assert re.search(r"its test RMS is [\d.]+ mm with the robust fit and [\d.]+ mm by least squares \(-\d+ %", line)
    stages = {o["stage"] for o in d.outliers}
    assert {"nominal", "geometric"} <= stages and {o["row"] for o in d.outliers} >= {4, 41, 78}


def test_a_finding_that_stands_for_another_parameter_is_reported_as_the_combination():
    check = ParameterCheck(("j3_offset", "probe_offset_x", "probe_offset_y", "probe_offset_z"),
                           ("deg", "mm", "mm", "mm"), np.array([0.2, 0.0, 0.0, 0.0]), np.array([0.001, 0.1, 0.1, 0.1]),
                           np.array([0.1, 1.0, 1.0, 1.0]), ("finding", "ok", "ok", "ok"), 3.0)
    plain = check.findings()
    assert plain[0].startswith("finding: j3_offset = 0.2 +- 0.001 deg (well identified")
    (line,) = check.findings({"j3_offset": (("j4_tilt_y", 9.8),)})
    assert "is one combination, j3_offset + 9.8 x j4_tilt_y, well identified as such" in line
    assert "joint j3's zero is off (re-master the joint), or joint j4's axis is tilted" in line


def test_separating_poses_outside_the_training_data_are_flagged_with_the_joints_to_move():
    """Training poses with joint 2 held within -60..-40 deg: poses that would separate two fitted families mostly need
    joint 2 elsewhere; each is flagged as outside the training data (both fits extrapolate there), with the joints
    that must move beyond their training range."""
    from tolalloc.diagnose.calibrate import calibrate
    from tolalloc.diagnose.select import evaluate, make_context
    from tolalloc.diagnose.verdict import separating_poses

    rng = np.random.default_rng(4)
    q = rng.uniform(-np.pi, np.pi, (60, 6))
    q[:, 1] = np.radians(rng.uniform(-60, -40, 60))
    x = target_points(UR10, q, np.array([0.0, 0.0, 50.0])) + rng.normal(0, 0.02, (60, 3))
    df = pd.DataFrame(np.degrees(q), columns=[f"q{i + 1}_deg" for i in range(6)])
    df[["x_mm", "y_mm", "z_mm"]] = x
    train = measurements_from_frame(df, UR10)
    ctx = make_context(calibrate(UR10, train), train, folds=2)
    a, b = evaluate(ctx, ("joint_compliance",)), evaluate(ctx, ("mount_compliance",))
    sug = separating_poses(ctx, [(a, b, "joint_compliance", "mount_compliance")], {}, n=4, n_sampled=300)
    assert len(sug) == 4 and sug["outside_training"].dtype == bool
    out_q2 = (sug["q2_deg"] < -65) | (sug["q2_deg"] > -35)
    assert sug["outside_training"][out_q2].all()
    assert all("shoulder_lift_joint" in j for j in sug["joints_outside_training_range"][out_q2])
