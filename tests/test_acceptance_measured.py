"""AP_P and RP_l from measurements (tolalloc.acceptance.measured): a synthetic 30-cycle data set of one robot with
known errors in a tracker frame of its own, against the linear model of that robot; no repeated pose refused; the
real UR10 data checked for repeated poses."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from iso_setup import ur10_test
from tolalloc.exceptions import TolallocError
from tolalloc.acceptance import PoseAccuracy, PoseRepeatability, Tracker, predict_acceptance
from tolalloc.acceptance.layout import acceptance_test_at
from tolalloc.acceptance.measured import compare_with_prediction, measured_acceptance
from tolalloc.acceptance.model import evaluation_poses, statistic_models
from tolalloc.acceptance.statistics import pose_repeatability
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.scale import point_kinematics
from tolalloc.errormodel import build_error_model
from tolalloc.robot.lie import exp_so3

DATA = next((f / "shared" / "data" / "ipa-ur10" for f in Path(__file__).resolve().parents
             if (f / "shared" / "data" / "ipa-ur10").is_dir()), Path("absent"))
T_MM = np.zeros(3)  # the target at the tool point, where the error Jacobian gives the error
NOISE_MM, JOINT_RAD = 0.005, np.deg2rad(0.001)


@pytest.fixture(scope="module")
def data():
    """5 test poses x 30 cycles and 20 registration poses measured once, of one robot with errors ``s``."""
    robot, test = ur10_test()
    rng = np.random.default_rng(4)
    model = build_error_model(robot)
    s = model.sample(1, rng)[0]
    q_reg = test.placement.q_min + rng.random((20, 6)) * (test.placement.q_max - test.placement.q_min)
    q = np.vstack([np.repeat(test.q_test, 30, axis=0), q_reg])
    screws, home, dq = model.perturbed_chain(s[None])
    x, _ = point_kinematics(screws[0], home[0], q + dq[0] + rng.normal(0, JOINT_RAD, q.shape), T_MM)
    R0, p0 = exp_so3(np.array([0.3, -0.2, 1.1])), np.array([2000.0, -500.0, 300.0])
    xyz = (x + rng.normal(0, NOISE_MM, x.shape)) @ R0.T + p0
    return robot, test, model, s, Measurements(q, xyz, rows=np.arange(1, len(q) + 1), source="synthetic"), xyz


def test_measured_statistics_match_the_robots_own(data):
    robot, test, model, s, meas, xyz = data
    m = measured_acceptance(meas, robot, target_offset_mm=T_MM)
    assert list(m.cycles) == [30] * 5 and len(m.registration_rows) == 20 and "not the test poses" in m.note
    # RP_l is the repeatability of the measured points (frame-free), to round-off
    np.testing.assert_allclose(m.rp_mm, pose_repeatability(xyz[:150].reshape(5, 30, 3)), rtol=1e-9)
    # AP_P: the registered systematic error of this robot (the test's linear map), within 4 standard deviations of
    # the noise the cycles' means and the registration leave (the same map: joint noise and tracker noise)
    reg = acceptance_test_at(robot, test.q_test, meas.q[150:], tracker=Tracker(mpe_a_mm=NOISE_MM * np.sqrt(3),
                                                                                 mpe_b_mm_per_m=0.0))
    sm = statistic_models([PoseAccuracy(limit_mm=0.5)], reg, evaluation_poses(reg))[0]
    J = model.jacobian(evaluation_poses(reg).q)
    ap_linear = np.linalg.norm(np.einsum("pak,k->pa", sm.systematic_map(J), s), axis=1)
    rand = np.where(model.kinds == "joint_drive", JOINT_RAD**2, 0.0)
    noise = sm.covariance(J, np.zeros(len(s)), rand, tracker=reg.tracker)
    np.testing.assert_array_less(np.abs(m.ap_mm - ap_linear), 4 * np.sqrt(np.linalg.eigvalsh(noise)[:, -1]))
    assert np.all(m.ap_mm > 0.02)  # the robot's errors show (noise alone would give a few micrometres)


def test_measured_beside_prediction(data):
    robot, test, model, s, meas, _ = data
    m = measured_acceptance(meas, robot)  # target offset fitted with the frame
    reg = acceptance_test_at(robot, m.q, meas.q[150:], cycles=30)
    pred = predict_acceptance(reg, [PoseAccuracy(limit_mm=0.5), PoseRepeatability(limit_mm=0.05)], model)
    cmp_ = compare_with_prediction(m, pred)
    assert len(cmp_) == 10 and cmp_.fleet_share_at_or_below.between(0.001, 0.999).all()


def test_approach_groups_give_vap_and_ap_rp_from_the_first(data):
    """The 30 cycles of each test pose taken as three approaches of 10 (direction columns), the second and third
    shifted by known vectors: vAP_P is the largest distance between the shifts, within 4 standard deviations of the
    barycentres' noise; AP_P and RP_l use the first approach's 10 cycles; without the columns vAP_P is NaN."""
    robot, test, model, s, meas, xyz = data
    shifts = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.2, 0.05]])
    way = np.concatenate([np.repeat(np.arange(3), 10)] * 5 + [np.zeros(20, int)])
    d = np.ones((len(way), 6))
    d[way == 1, 0], d[way == 2, 1] = -1.0, -1.0
    R0 = exp_so3(np.array([0.3, -0.2, 1.1]))                                  # the fixture's tracker rotation
    moved = xyz + shifts[way] @ R0.T
    m = measured_acceptance(Measurements(meas.q, moved, None, d, rows=meas.rows, source="synthetic"), robot,
                            target_offset_mm=T_MM)
    expect = max(np.linalg.norm(a - b) for a in shifts for b in shifts)
    sd = xyz[:150].reshape(5, 30, 3).std(axis=1, ddof=1).max()                # the cycles' scatter per coordinate
    np.testing.assert_array_less(np.abs(m.vap_mm - expect), 4 * np.sqrt(3 * 2 / 10) * sd)
    assert list(m.approaches) == [3] * 5 and list(m.cycles) == [10] * 5 and "first approach" in m.note
    np.testing.assert_allclose(m.rp_mm, pose_repeatability(moved[:150].reshape(5, 3, 10, 3)[:, 0]), rtol=1e-9)
    frame = m.to_frame()                                                      # (it raised before: Joint.type)
    assert frame["vAP_P_mm"].notna().all() and {"q1_deg", "q6_deg"} <= set(frame.columns)
    plain = measured_acceptance(meas, robot, target_offset_mm=T_MM)
    assert np.isnan(plain.vap_mm).all() and list(plain.approaches) == [1] * 5


def test_no_repeated_pose_refused(data):
    robot, test, model, s, meas, _ = data
    once = meas.subset(np.arange(150, 170))
    with pytest.raises(TolallocError, match=r"measurements synthetic: no command pose is measured at least 2 times "
                                            r"\(20 rows, 20 distinct poses, each once\)"):
        measured_acceptance(once, robot)


@pytest.mark.skipif(not DATA.is_dir(), reason="the shared UR10 data are not here")
def test_real_ur10_data_repeat_no_pose():
    """The IPA UR10 series measure every commanded pose once (checked on the raw goals too): no AP / RP there."""
    for name in ("Series_C/measurements_random_poses.csv",):
        raw = pd.read_csv(DATA / name, sep=";", decimal=",", usecols=lambda c: c.startswith("Goal"))
        assert not raw.round(6).duplicated().any()
