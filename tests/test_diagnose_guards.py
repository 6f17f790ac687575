"""Guards of the diagnosis on constructed cases: extrapolation, implausible (prior) parameters, CV fallback."""

import re

import numpy as np
from scipy.spatial.transform import Rotation
from test_diagnose_geometry import _limits, _measure

import tolalloc
from tolalloc.diagnose import diagnose
from tolalloc.diagnose.calibrate import calibrate, fit_model, initial_fit
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.guards import (RANGE_MARGIN_DEG, Extrapolation, cv_fallback, extrapolation_flags,
                                      prior_flags)
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import Evaluation


def _poses(robot, n, rng, q6_deg=None):
    lo, hi = _limits(robot)
    q = rng.uniform(lo, hi, (n, robot.n_joints))
    if q6_deg is not None:
        q[:, 5] = np.deg2rad(rng.uniform(*q6_deg, n))
    return q


def _data(robot, true, q, rng):
    R = Rotation.from_rotvec([0.1, -0.2, 0.3]).as_matrix()
    return Measurements(q, _measure(true, q, R, np.array([1500.0, -200.0, 300.0]), np.array([20.0, 30.0, 90.0]), rng))


def test_extrapolation_flag_fires_outside_the_training_range():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(0)
    q_train = _poses(robot, 60, rng, (-30, 30))
    q_test = q_train[:40].copy()  # the other joints as in training: only wrist 3 leaves its range
    q_test[:, 5] = np.deg2rad(rng.uniform(90, 150, 40))
    ex = extrapolation_flags(robot, q_train, q_test)
    assert ex.outside_range.all() and ex.joints_outside == ("wrist_3_joint",)
    assert "40 of 40" in ex.message()


def test_extrapolation_flag_quiet_inside_the_training_data():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(1)
    q = _poses(robot, 400, rng, (-30, 30))
    ex = extrapolation_flags(robot, q[:300], q[300:])
    # same distribution: no range flag can fire beyond the 5 deg margin on 300 training poses of 6 joints
    # by more than chance; the distance flag (1.5x the 95th percentile of LOO distances) fires rarely
    assert ex.outside_range.sum() <= 2
    assert ex.far.mean() <= 0.05


def test_pipeline_reports_extrapolation_guard_in_result_and_json():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(2)
    train = _data(robot, robot, _poses(robot, 60, rng, (-30, 30)), rng)
    test = _data(robot, robot, _poses(robot, 30, rng, (90, 150)), rng)
    d = diagnose(robot, train, test, folds=3)
    assert d.extrapolation.flagged.all()
    assert any(g.startswith("extrapolation: 30 of 30") for g in d.guards)
    out = d.to_dict()
    assert out["guards"] == list(d.guards) and all(out["extrapolation"]["flagged"])


def test_prior_flag_fires_on_an_implausible_error_and_not_on_a_plausible_one():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(3)
    q = _poses(robot, 60, rng)
    big = calibrate(robot, _data(robot, _scaled_a2(20.0), q, rng)).geometric
    small = calibrate(robot, _data(robot, _scaled_a2(0.3), q, rng)).geometric
    assert prior_flags(big, q) and all("plausibility level" in m for m in prior_flags(big, q))
    assert prior_flags(small, q) == ()


def _scaled_a2(err_mm):
    """UR10 with its DH a2 (upper-arm length) off by ``err_mm``."""
    import copy
    import tomllib
    from importlib.resources import files

    from tolalloc.robot.io.dh import robot_from_dh_dict
    data = copy.deepcopy(tomllib.loads((files("tolalloc") / "data/robots/ur10.toml").read_text()))
    data["dh"][1]["a_m"] += err_mm * 1e-3
    return robot_from_dh_dict(data)


def test_map_prior_shrinks_towards_zero():
    """A prior far tighter than the error pins the parameters at 0; without a prior they move."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(4)
    q = _poses(robot, 60, rng)
    meas = _data(robot, _scaled_a2(0.3), q, rng)
    model = build_geometry_model(robot)
    cal = calibrate(robot, meas, model=model)
    geo = cal.geometric.geo_index
    tight = model.with_sigma(np.full(len(model.params), 1e-7))
    start = initial_fit(tight, meas.q, meas.xyz_mm)
    pinned = fit_model(start, meas.q, meas.xyz_mm, geo_index=geo)
    free = fit_model(start, meas.q, meas.xyz_mm, geo_index=geo, prior=False)
    assert np.abs(pinned.delta).max() < 1e-5
    assert np.abs(free.delta).max() > 1e-4
    assert free.rms_mm < pinned.rms_mm


def _ev(label, oof):
    return Evaluation(label, (), None, (), np.zeros(0, int), oof, None, None)


def test_cv_fallback_on_constructed_evaluations():
    rng = np.random.default_rng(5)
    base = rng.normal(size=(50, 3))
    nominal, geometric = _ev("nominal", 0.10 * base), _ev("geometric", 0.05 * base)
    worse = _ev("geometric+thermal", 0.20 * base)
    chosen, msgs = cv_fallback(nominal, geometric, worse)
    assert chosen is nominal and msgs[0].startswith("fallback:") and "+100.0 %" in msgs[0]
    chosen, msgs = cv_fallback(nominal, geometric, _ev("geometric+thermal", 0.07 * base))
    assert chosen is geometric and msgs[0].startswith("fallback:")
    chosen, msgs = cv_fallback(nominal, geometric, geometric)
    assert chosen is geometric and msgs == ()


def test_pipeline_falls_back_when_geometry_overfits():
    """Perfect nominal geometry, 24 noisy poses, 3 folds: ~27 parameters on 16 poses per fold overfit."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(6)
    d = diagnose(robot, _data(robot, robot, _poses(robot, 24, rng), rng), folds=3)
    cv = {k: np.sqrt(np.mean(np.sum(ev.oof_mm ** 2, 1))) for k, ev in (("n", d.nominal), ("g", d.geometric))}
    assert cv["g"] > 1.01 * cv["n"]
    assert d.fallback == "nominal" and d.final is d.nominal and d.effect == "none"
    assert any(g.startswith("fallback:") for g in d.guards) and d.to_dict()["fallback"] == "nominal"


def test_cli_prints_guards_and_writes_them_to_json(tmp_path, capsys):
    import json

    import pandas as pd

    from tolalloc.cli import main

    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(7)
    for name, q6 in (("train", (-30, 30)), ("test", (90, 150))):
        m = _data(robot, robot, _poses(robot, 60 if name == "train" else 30, rng, q6), rng)
        df = pd.DataFrame(robot.q_to_interface(m.q), columns=[f"q{j + 1}" for j in range(6)])
        df[["x_mm", "y_mm", "z_mm"]] = m.xyz_mm
        df.to_csv(tmp_path / f"{name}.csv", index=False)
    rc = main(["diagnose", "ur10", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
               "--folds", "3", "--json", str(tmp_path / "d.json")])
    assert rc == 0
    out = capsys.readouterr().out
    assert "GUARD: extrapolation: 30 of 30 test poses" in out
    assert any(g.startswith("extrapolation") for g in json.loads((tmp_path / "d.json").read_text())["guards"])



def test_tool_points_on_one_line_are_a_guard_not_a_warning():
    """A single prismatic slide puts every tool point on one line: the tracker rotation about it is undetermined.
    The diagnosis says so in a guard (no SciPy warning from the registration's point-set alignment); a robot whose
    poses span a volume gets no such guard."""
    import warnings

    import pandas as pd

    from tolalloc.robot.model import Joint, Link, Robot

    robot = Robot("slide", (Link("l1", np.array([0.0, 0.0, 300.0])),
                            Joint("j1", "prismatic", np.array([1.0, 0.0, 0.0]), -200.0, 200.0),
                            Link("l2", np.array([0.0, 0.0, 100.0]))))
    rng = np.random.default_rng(0)
    q = rng.uniform(-200.0, 200.0, 60)
    pts = np.array([robot.fk([v])[:3, 3] for v in q]) + rng.normal(0.0, 0.02, (60, 3))
    frame = pd.DataFrame({"q1": q, "x_mm": pts[:, 0], "y_mm": pts[:, 1], "z_mm": pts[:, 2]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = tolalloc.diagnose_measurements(robot, frame, folds=3)
    assert any(g.startswith("registration: the 60 training poses put the tool point on one straight line")
               for g in d.diagnosis.guards)
    tc = tolalloc.load_robot("tool_changer")
    case = tolalloc.diagnose.generate(tc, "none", 40, np.random.default_rng(2))
    d = diagnose(tc, tolalloc.diagnose.measurements_from_frame(case.frame, tc), folds=3)
    assert not any("straight line" in g for g in d.guards)


def test_extrapolation_counts_revolute_angles_modulo_a_turn():
    """A test angle one turn away from the training angles is the same joint position for every fitted model:
    no range flag and no distance flag; a training range across +-180 deg is one short arc, not 360 deg."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(3)
    q_train = _poses(robot, 200, rng, (-30, 30))
    q_test = q_train[:50] + rng.normal(0.0, 0.01, (50, robot.n_joints))
    q_test[:, 5] += 2 * np.pi * rng.choice([-1, 1], 50)  # wrist 3 one turn away (its limits are +-360 deg)
    ex = extrapolation_flags(robot, q_train, q_test)
    assert not ex.outside_range.any() and not ex.far.any()
    q_train[:, 0] = np.deg2rad(rng.uniform(160.0, 200.0, 200))  # base angles across 180 deg: a 40 deg arc
    q_test = q_train[:20].copy()
    q_test[:, 0] = np.deg2rad(rng.uniform(-60.0, 60.0, 20))  # inside the linear range -160..200, outside the arc
    ex = extrapolation_flags(robot, np.where(q_train > np.pi, q_train - 2 * np.pi, q_train), q_test)
    assert ex.outside_range.all() and ex.joints_outside == ("shoulder_pan_joint",)
    q_edge = np.zeros((3, robot.n_joints))
    q_edge[1], q_edge[2] = -1e-17, 2 * np.pi  # -1e-17 wraps to the period itself in floating point
    d = extrapolation_flags(robot, np.vstack([q_train, q_edge[1]]), q_edge).distance  # one position three times
    np.testing.assert_allclose(d[1:], d[0], rtol=1e-12)


def test_training_angles_round_the_whole_turn_leave_no_outside():
    """Wrist angles spread over the full turn: the largest gap between them is a gap inside the range like the
    others, so a test angle in it is not outside the range; a clearly larger gap still is."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(8)
    q_train = _poses(robot, 90, rng, (-30, 30))
    q_train[:, 5] = rng.uniform(-np.pi, np.pi, 90)
    a = np.sort(np.mod(q_train[:, 5], 2 * np.pi))
    gaps = np.diff(np.append(a, a[0] + 2 * np.pi))
    k = int(np.argmax(gaps))
    assert np.rad2deg(gaps[k]) > 2 * RANGE_MARGIN_DEG  # a test angle in its middle is beyond the margin
    q_test = q_train[:5].copy()
    q_test[:, 5] = a[k] + gaps[k] / 2  # the middle of the largest gap
    ex = extrapolation_flags(robot, q_train, q_test)
    assert not ex.outside_range.any()
    q_train[:, 5] = rng.uniform(-np.pi, np.pi / 2, 90)  # a 90 deg quarter never visited: that gap is the outside
    q_test[:, 5] = 3 * np.pi / 4
    ex = extrapolation_flags(robot, q_train, q_test)
    assert ex.outside_range.all() and ex.joints_outside == ("wrist_3_joint",)
    assert re.search(r"5 outside the training range of wrist_3_joint", ex.message())


def test_extrapolation_message_names_only_the_criteria_that_fired():
    far_only = Extrapolation(np.zeros(4, bool), np.array([True, False, True, False]), np.ones(4), 0.5, ())
    msg = far_only.message()
    assert msg.startswith("extrapolation: 2 of 4 test poses") and "outside the training range" not in msg
    assert "2 farther from every training pose than 0.5" in msg
    range_only = Extrapolation(np.array([True, False]), np.zeros(2, bool), np.zeros(2), 0.5, ("elbow_joint",))
    assert "1 outside the training range of elbow_joint" in range_only.message()
    assert "farther" not in range_only.message()
