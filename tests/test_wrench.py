"""A logged process wrench (``force_x_n`` ... ``torque_z_nm``): its joint loads, its moment on the mount, the
columns of a measurement file, and the diagnosis of gears twisted by a logged tool force.

Known answers: a force ``m g`` at the target loads the joints as ``m`` kilograms of payload there (exactly); the
joint loads equal the virtual work of the wrench per unit joint motion (finite differences of the target point and
of the flange rotation, revolute and prismatic joints); a pure moment about the base's vertical loads the first
joint by that moment. The end-to-end case is a self-consistency check (the data are written with the same load
model the diagnosis fits): with the columns the joints' compliance is named and predicts the held-out poses; without
them the same data name nothing.
"""

import shlex

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.diagnose import diagnose, generate, measurements_from_frame
from tolalloc.diagnose.synth import split_frame
from tolalloc.exceptions import TolallocError
from tolalloc.physics.compliance import joint_loads, mount_columns
from tolalloc.physics.loads import G, point_jacobian, target_points, tip_load, wrench_load, wrench_moment
from tolalloc.robot.lie import rotvec

FORCES = ["force_x_n", "force_y_n", "force_z_n"]
TORQUES = ["torque_x_nm", "torque_y_nm", "torque_z_nm"]


def _poses(robot, n, seed):
    rng = np.random.default_rng(seed)
    lo = np.maximum(robot.lower, np.where(robot.revolute_mask, -np.pi, robot.lower))
    hi = np.minimum(robot.upper, np.where(robot.revolute_mask, np.pi, robot.upper))
    return rng.uniform(lo, hi, (n, robot.n_joints))


@pytest.mark.parametrize("name", ["ur10", "tool_changer"])
def test_a_weight_at_the_target_loads_the_joints_as_that_payload(name):
    robot = tolalloc.load_robot(name)
    q = _poses(robot, 7, 1)
    tip = target_points(robot, q, np.array([10.0, -20.0, 80.0]))
    kg = np.linspace(0.5, 12.0, len(q))
    F = kg[:, None] * G * np.asarray(robot.gravity, float)
    np.testing.assert_allclose(wrench_load(robot, q, tip, np.hstack([F, np.zeros_like(F)])),
                               kg[:, None] * tip_load(robot, q, tip), rtol=1e-12, atol=1e-12)
    with_wrench, _ = joint_loads(robot, q, tip, None, np.hstack([F, np.zeros_like(F)]))
    as_payload, _ = joint_loads(robot, q, tip, kg)
    np.testing.assert_allclose(with_wrench, as_payload, rtol=1e-12, atol=1e-9)
    # the mount: the same moment as the payload
    B_w, _ = mount_columns(robot, q, tip, tip, None, "axes", np.hstack([F, np.zeros_like(F)]))
    B_p, _ = mount_columns(robot, q, tip, tip, kg, "axes")
    np.testing.assert_allclose(B_w, B_p, rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("name", ["ur10", "tool_changer"])
def test_joint_loads_are_the_virtual_work_of_the_wrench(name):
    """tau_j = F . dp/dq_j [N mm -> N m for a revolute joint] + M . dtheta/dq_j (finite differences)."""
    robot = tolalloc.load_robot(name)
    q = _poses(robot, 5, 2)
    t = np.array([5.0, 15.0, 120.0])
    tip = target_points(robot, q, t)
    rng = np.random.default_rng(3)
    W = np.hstack([rng.normal(0, 200, (len(q), 3)), rng.normal(0, 30, (len(q), 3))])
    tau = wrench_load(robot, q, tip, W)
    h = 1e-6
    for j, joint in enumerate(robot.joints):
        e = np.zeros(robot.n_joints)
        e[j] = h
        dp = (target_points(robot, q + e, t) - target_points(robot, q - e, t)) / (2 * h)
        Rp, Rm = robot.fk_internal(q + e)[:, :3, :3], robot.fk_internal(q - e)[:, :3, :3]
        dth = np.array([rotvec(a @ b.T) for a, b in zip(Rp, Rm)]) / (2 * h)
        per = 1000.0 if joint.is_revolute else 1.0  # N mm per rad -> N m; N per mm of stroke stays N
        want = np.einsum("pi,pi->p", dp, W[:, :3]) / per + np.einsum("pi,pi->p", dth, W[:, 3:])
        np.testing.assert_allclose(tau[:, j], want, rtol=1e-6, atol=1e-6 * np.abs(W).max())
    # and through the point Jacobian the diagnosis uses for the target's motion
    Jp = point_jacobian(robot, q, tip)
    force_part = wrench_load(robot, q, tip, np.hstack([W[:, :3], np.zeros((len(q), 3))]))
    scale = np.where(robot.revolute_mask, 1000.0, 1.0)
    np.testing.assert_allclose(force_part, np.einsum("pin,pi->pn", Jp, W[:, :3]) / scale, rtol=1e-9, atol=1e-9)


def test_a_moment_about_the_vertical_loads_the_first_joint_by_itself():
    robot = tolalloc.load_robot("ur10")  # joint 1 turns about the base's vertical
    q = _poses(robot, 4, 4)
    tip = target_points(robot, q, np.zeros(3))
    W = np.zeros((len(q), 6))
    W[:, 5] = 40.0
    np.testing.assert_allclose(wrench_load(robot, q, tip, W)[:, 0], 40.0, rtol=1e-12)
    np.testing.assert_allclose(wrench_moment(tip, W), W[:, 3:], atol=1e-12)


def _table(robot, n=6):
    q = np.rad2deg(_poses(robot, n, 5))
    pts = target_points(robot, np.deg2rad(q), np.zeros(3))
    df = pd.DataFrame({f"q{j + 1}": q[:, j] for j in range(robot.n_joints)})
    df[["x_mm", "y_mm", "z_mm"]] = pts
    return df


def test_the_columns_are_read_as_a_base_frame_wrench_and_bad_ones_refused():
    robot = tolalloc.load_robot("ur10")
    df = _table(robot)
    assert measurements_from_frame(df, robot).wrench is None
    df[FORCES] = np.arange(18.0).reshape(6, 3)
    df["torque_j1"] = 1.0  # not a wrench column: ignored as before
    m = measurements_from_frame(df, robot)
    np.testing.assert_array_equal(m.wrench, np.hstack([np.arange(18.0).reshape(6, 3), np.zeros((6, 3))]))
    np.testing.assert_array_equal(m.subset([1, 3]).wrench, m.wrench[[1, 3]])
    only_moment = _table(robot)
    only_moment[TORQUES] = 2.0
    np.testing.assert_array_equal(measurements_from_frame(only_moment, robot).wrench[:, :3], 0.0)
    for bad, match in [(df.drop(columns="force_z_n"), r"column\(s\) \['force_x_n', 'force_y_n'\] given, expected "
                                                      r"all of \['force_x_n', 'force_y_n', 'force_z_n'\]"),
                       (df.rename(columns={"force_x_n": "force_x_kn"}), r"column 'force_x_kn': expected 'force_x_n'"),
                       (df.rename(columns={"force_y_n": "torque_y_nmm"}), r"'torque_y_nmm': expected 'torque_y_nm'"),
                       (df.assign(force_y_n=np.r_[np.nan, np.ones(5)]), r"'force_y_n' has empty / NaN cells"),
                       (df.assign(force_y_n=np.r_[np.inf, np.ones(5)]), r"hold an infinite value")]:
        with pytest.raises(TolallocError, match=match):
            measurements_from_frame(bad, robot)


@pytest.fixture(scope="module")
def cutting_session():
    """A ur10 session whose joints wind up under a logged cutting force that changes direction and size from pose to
    pose (about 100 N per axis, a light milling cut; 0.3 mm RMS at the tool), geometry errors and 0.01 mm tracker
    noise."""
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "none", 120, np.random.default_rng(11), noise_mm=0.01)
    df = case.frame.copy()
    q = np.deg2rad(df[[f"q{j + 1}" for j in range(6)]].to_numpy())
    rng = np.random.default_rng(12)
    F = rng.normal(0, 100.0, (len(df), 3))
    tip = target_points(robot, q, case.truth["t_mm"])
    tau = wrench_load(robot, q, tip, np.hstack([F, np.zeros_like(F)]))
    c = np.array([2.0, 1.5, 2.5, 6.0, 6.0, 8.0]) * 1e-6  # rad/(N m): ur10-sized gears
    move = np.einsum("pin,pn->pi", point_jacobian(robot, q, tip), c * tau)
    df[["x_mm", "y_mm", "z_mm"]] += move @ case.truth["R"].T
    df[FORCES] = F
    return robot, df, float(np.sqrt(np.mean(np.sum(move ** 2, axis=1))))


def test_gears_twisted_by_a_logged_tool_force_are_named_and_predict_held_out_poses(cutting_session):
    robot, df, size_mm = cutting_session
    assert 0.05 < size_mm < 0.5
    train, test = split_frame(df, 0.25, np.random.default_rng(0))
    d = diagnose(robot, measurements_from_frame(train, robot), measurements_from_frame(test, robot), folds=3,
                 max_effects=1)
    assert d.verdict.verdict == "effect" and tuple(d.effects) == ("joint_compliance",), d.verdict.headline()
    rms = lambda a: float(np.sqrt(np.mean(np.sum(a ** 2, axis=1))))  # noqa: E731
    assert rms(d.final.test_mm) < 0.35 * rms(d.geometric.test_mm)
    assert rms(d.final.test_mm) < 0.03  # noise 0.01 mm per axis
    assert not any("force / torque columns" in g for g in d.guards)  # both files carry them
    # the same positions without the force columns: the compliance has no load to follow
    blind = diagnose(robot, measurements_from_frame(train.drop(columns=FORCES), robot),
                     measurements_from_frame(test.drop(columns=FORCES), robot), folds=3, max_effects=1)
    assert not blind.effects and rms(blind.final.test_mm) > 5 * rms(d.final.test_mm)
    assert not any("instrument's stated noise" in g for g in blind.guards)  # no noise stated: no such guard


def test_the_noise_guard_fires_above_three_times_the_stated_noise():
    """Known answers of the rule: out-of-fold residuals of RMS r against sqrt(3) sigma; silent without sigma."""
    from types import SimpleNamespace

    from tolalloc.diagnose.guards import noise_guard

    oof = np.tile([0.06, 0.0, 0.0], (10, 1))  # 0.06 mm RMS in 3-D
    final = SimpleNamespace(oof_mm=oof)
    assert noise_guard(final, None) is None
    assert noise_guard(final, 0.06 / (3 * np.sqrt(3)) * 1.001) is None  # just inside 3x
    text = noise_guard(final, 0.01)
    assert text.startswith("the final model's out-of-fold error, 0.06 mm RMS, is 3.5 times the instrument's stated "
                           "noise (0.01 mm per axis, 0.0173 mm in 3-D): about 0.0574 mm RMS is neither noise")


def test_an_error_far_above_the_instruments_noise_is_said_once_the_noise_is_stated(cutting_session, tmp_path):
    """The tool-force session without its force columns: the final model's held-out error is far above the 0.01 mm
    noise the data were written with (self-consistent: the noise is the generator's). Stated, the noise gives one
    guard; the result records it and its command line gives it back; a bad value is refused naming the field."""
    from tolalloc.cli import build_parser, main
    from tolalloc.workflows import diagnose_measurements
    from tolalloc.workflows.reproduce import diagnosis_command

    robot, df, _ = cutting_session
    df.drop(columns=FORCES).to_csv(tmp_path / "train.csv", index=False)
    job = diagnose_measurements(robot, tmp_path / "train.csv", folds=3, progress=False,
                                fit=tolalloc.FitOptions(instrument_noise_mm=0.01))
    noisy = [g for g in job.diagnosis.guards if "times the instrument's stated noise" in g]
    assert len(noisy) == 1 and "(0.01 mm per axis, 0.0173 mm in 3-D)" in noisy[0]
    assert job.inputs["instrument_noise_mm"] == job.diagnosis.settings["instrument_noise_mm"] == 0.01
    cli, python, _ = diagnosis_command(job)
    assert build_parser().parse_args(shlex.split(cli)[1:]).instrument_noise_mm == 0.01
    assert "instrument_noise_mm=0.01" in python
    for bad in (0, -0.01, "0.01", True, float("nan")):
        with pytest.raises(tolalloc.ArgumentError, match=r"^FitOptions.instrument_noise_mm: expected the measuring"):
            tolalloc.FitOptions(instrument_noise_mm=bad)
    assert main(["diagnose", "ur10", "--train", str(tmp_path / "train.csv"), "--instrument-noise-mm", "-1"]) == 2


@pytest.mark.parametrize("variant", ["beam", "beam+tip"])
def test_the_beams_and_the_flange_carry_a_force_at_the_target_as_the_payload(variant):
    from tolalloc.physics.beams import beam_columns, flange_columns

    robot = tolalloc.load_robot("ur10")
    q = _poses(robot, 6, 7)
    tip = target_points(robot, q, np.array([0.0, 30.0, 150.0]))
    kg = np.linspace(1.0, 9.0, len(q))
    W = np.hstack([kg[:, None] * G * np.asarray(robot.gravity, float), np.zeros((len(q), 3))])
    for columns in (lambda **kw: beam_columns(robot, q, tip, variant, **kw),
                    lambda **kw: flange_columns(robot, q, tip, **kw)):
        B_w, names_w = columns(wrench=W)
        B_p, names_p = columns(payload_kg=kg)
        assert names_w == names_p
        np.testing.assert_allclose(B_w, B_p, rtol=1e-10, atol=1e-12)


def test_a_couple_beyond_a_cantilever_bends_it_by_the_closed_form():
    """End moment M on a cantilever of length L: tip deflection M L^2 / (2 EI), slope M L / EI (per unit 1/EI)."""
    from tolalloc.physics.beams import _load_integrals

    L = np.array([1000.0])
    start, e = np.zeros((1, 3)), np.array([[1.0, 0.0, 0.0]])
    M = np.array([[0.0, 2.0, 0.0]])  # [N m] about +y: the +x tip goes down
    tip = _load_integrals(start, e, L, [], np.array([[1000.0, 0.0, 0.0]]), (M,))
    np.testing.assert_allclose(tip["bend"], [[0.0, 0.0, -2000.0 * 1000.0 ** 2 / 2]])
    beyond = _load_integrals(start, e, L, [], np.array([[1500.0, 0.0, 0.0]]), (M,))  # the slope carries it on
    np.testing.assert_allclose(beyond["bend"], [[0.0, 0.0, -2000.0 * (1000.0 ** 2 / 2 + 1000.0 * 500.0)]])
    np.testing.assert_allclose(tip["twist"], 0.0, atol=1e-9)
    twist = _load_integrals(start, e, L, [], np.array([[1000.0, 0.0, 50.0]]), (np.array([[3.0, 0.0, 0.0]]),))
    np.testing.assert_allclose(twist["twist"], [[0.0, -3000.0 * 1000.0 * 50.0, 0.0]])  # turn T L / GJ about x


def test_the_identified_model_predicts_and_compensates_under_a_logged_wrench(cutting_session, tmp_path):
    """The model fitted with the force columns predicts the held-out measured points (tracker frame) within the noise
    when it is given their forces -- as an array or as a program's columns -- and not without them; compensation
    takes the columns too."""
    robot, df, _ = cutting_session
    train, test = split_frame(df, 0.25, np.random.default_rng(0))
    train.to_csv(tmp_path / "train.csv", index=False)
    job = tolalloc.diagnose_measurements(robot, tmp_path / "train.csv", folds=3, progress=False)
    assert "joint_compliance" in job.diagnosis.effects
    qcols = [f"q{j + 1}" for j in range(6)]
    measured = test[["x_mm", "y_mm", "z_mm"]].to_numpy()
    xyz = ["x_mm", "y_mm", "z_mm"]
    err = lambda p: float(np.sqrt(np.mean(np.sum((p[xyz].to_numpy() - measured) ** 2, axis=1))))  # noqa: E731
    W = np.hstack([test[FORCES].to_numpy(), np.zeros((len(test), 3))])
    with_array = job.predict(test[qcols].to_numpy(), wrench=W, frame="tracker")
    with_columns = job.predict(test[qcols + FORCES], frame="tracker")
    without = job.predict(test[qcols].to_numpy(), frame="tracker")
    np.testing.assert_allclose(with_array[["x_mm", "y_mm", "z_mm"]], with_columns[["x_mm", "y_mm", "z_mm"]])
    assert err(with_columns) < 0.04 < 0.2 < err(without)
    comp = job.compensate(test[qcols + FORCES]).to_frame()
    assert (comp["status"] == "ok").all() and comp["error_mm"].max() < 1e-3  # under the wrench, on the targets
    dq = [f"dq{j + 1}_deg" for j in range(6)]
    unloaded = job.compensate(test[qcols]).to_frame()
    assert np.abs(comp[dq].to_numpy() - unloaded[dq].to_numpy()).max() > 1e-3  # the force moves the correction


def test_a_test_file_without_the_training_files_force_columns_gets_a_guard(cutting_session):
    robot, df, _ = cutting_session
    train, test = split_frame(df, 0.25, np.random.default_rng(0))
    d = diagnose(robot, measurements_from_frame(train, robot), measurements_from_frame(test.drop(columns=FORCES), robot),
                 folds=3, max_effects=1)
    said = [g for g in d.guards if "force / torque columns" in g]
    assert said == ["test file: no force / torque columns while the training file has them; the test poses are taken "
                    "as without a process force"]
