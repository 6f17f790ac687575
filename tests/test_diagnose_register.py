"""Cross-session registration (diagnose/register.py): registration poses are never scored.

Known answers: the split is a partition of the test poses; a constructed session in which the tracker moved
rigidly (1.2 mm, 0.5 mrad) after the registration poses were taken -- registering on the scored poses
themselves absorbs that move completely (residual at the noise level, the error hidden), registering on the
held-out poses reports it (residual ~ the move).
"""

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose import diagnose
from tolalloc.diagnose.calibrate import calibrate
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.register import (REGISTER_N, RegistrationSplit, register_and_score, register_count,
                                        registration_split)
from tolalloc.exceptions import TolallocError

NOISE_MM = 0.02
T_MM = np.array([10.0, 20.0, 80.0])


def _limits(robot):
    rev = robot.revolute_mask
    return np.where(rev, np.maximum(robot.lower, -np.pi), robot.lower), np.where(rev, np.minimum(robot.upper, np.pi), robot.upper)


def _points(robot, q, R, p, t=T_MM):
    T = robot.fk_internal(q)
    return (T[:, :3, 3] + T[:, :3, :3] @ t) @ R.T + p


def _rms(e):
    return float(np.sqrt(np.mean(np.sum(e ** 2, axis=1))))


def test_register_count_and_its_errors():
    assert register_count(100, REGISTER_N) == 30
    assert register_count(100, 0.2) == 20
    with pytest.raises(TolallocError, match="at least 5 registration and 5 scored"):
        register_count(32, 30)
    with pytest.raises(TolallocError, match="at least 5 registration"):
        register_count(100, 0.02)
    with pytest.raises(TolallocError, match="whole number"):
        register_count(100, 12.5)
    with pytest.raises(TolallocError, match="expected a pose count"):
        register_count(100, -3)


def test_split_is_a_partition_spread_over_the_test_series():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(0)
    q = rng.uniform(*_limits(robot), (200, 6))
    sp = registration_split(q, robot.revolute_mask, 30, seed=3)
    assert len(sp.register_index) == 30 and len(sp.score_index) == 170
    assert np.intersect1d(sp.register_index, sp.score_index).size == 0
    assert np.array_equal(np.union1d(sp.register_index, sp.score_index), np.arange(200))
    # spread: on every joint the registration poses cover most of the test range
    span = np.ptp(q[sp.register_index], axis=0) / np.ptp(q, axis=0)
    assert span.min() > 0.8
    assert np.array_equal(registration_split(q, robot.revolute_mask, 30, seed=3).register_index, sp.register_index)
    # duplicate poses (fewer distinct poses than clusters) still give 30 distinct registration poses
    dup = np.repeat(q[:20], 3, axis=0)
    sp = registration_split(dup, robot.revolute_mask, 30, seed=0)
    assert len(np.unique(sp.register_index)) == 30 and len(sp.score_index) == 30


def _moved_session(robot, rng, n=90):
    """Test session in another frame; the tracker moved rigidly after the registration poses were taken."""
    q = rng.uniform(*_limits(robot), (n, 6))
    R, p = Rotation.from_rotvec([0.3, 0.1, 0.2]).as_matrix(), np.array([900.0, -100.0, 40.0])
    sp = registration_split(q, robot.revolute_mask, REGISTER_N, seed=0)
    x = _points(robot, q, R, p, T_MM + np.array([0.4, -0.2, 0.3]))
    move = Rotation.from_rotvec([0.0, 5e-4, 0.0]).as_matrix()
    s = sp.score_index
    x[s] = (x[s] - x[s].mean(0)) @ move.T + x[s].mean(0) + np.array([1.2, 0.0, 0.0])
    return Measurements(q, x + rng.normal(0.0, NOISE_MM, x.shape), rows=np.arange(2, n + 2)), sp


def test_registering_on_the_scored_poses_would_hide_the_error():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(1)
    q = rng.uniform(*_limits(robot), (80, 6))
    train = Measurements(q, _points(robot, q, np.eye(3), np.zeros(3)) + rng.normal(0.0, NOISE_MM, (80, 3)))
    test, sp = _moved_session(robot, rng)
    fit = calibrate(robot, train).nominal
    zero = np.zeros((test.n_poses, 3))
    held = register_and_score(fit, test.q, test.xyz_mm, zero, sp)
    insample = register_and_score(fit, test.q, test.xyz_mm, zero,
                                  RegistrationSplit(sp.score_index, sp.score_index, REGISTER_N))
    assert held.residual_mm.shape == (test.n_poses - 30, 3)
    assert _rms(insample.residual_mm) < 2.5 * np.sqrt(3) * NOISE_MM      # hidden: noise level
    assert _rms(held.residual_mm) > 0.8                                   # reported: ~ the 1.2 mm move
    # the pipeline scores exactly the held-out poses and says which poses registered the frame
    d = diagnose(robot, train, test, folds=3, test_frame="refit", max_effects=1)
    assert np.array_equal(d.registration.register_index, sp.register_index)
    assert np.array_equal(d.scored_index, sp.score_index)
    assert len(d.final.test_mm) == len(d.nominal.test_mm) == test.n_poses - 30
    assert d.before_after("test")["rms_mm"].iloc[0] > 0.8
    js = d.to_dict()["test"]
    assert js["scored_poses"] == 60 and js["registration"]["registration_poses"] == 30
    assert js["registration"]["registration_rows"] == (sp.register_index + 2).tolist()
    assert d.uncertainty.message() is not None  # the 1.2 mm move is far outside the predicted 95 % radius


def test_pipeline_rejects_a_register_n_that_leaves_too_few_scored_poses_before_fitting():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(2)
    q = rng.uniform(*_limits(robot), (40, 6))
    m = Measurements(q, _points(robot, q, np.eye(3), np.zeros(3)))
    with pytest.raises(TolallocError, match="^register_n 38 gives 38 registration and 2 scored"):
        diagnose(robot, m, m, test_frame="refit", register_n=38)


def test_a_refit_registration_count_is_refused_as_its_field():
    """Through the job, a Refit's count that the test file cannot hold names ``Refit.register_n``."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(2)
    q = rng.uniform(*_limits(robot), (80, 6))
    frame = pd.DataFrame(np.column_stack([np.rad2deg(q), _points(robot, q, np.eye(3), np.zeros(3))]),
                         columns=[*(f"q{i + 1}" for i in range(6)), "x_mm", "y_mm", "z_mm"])
    with pytest.raises(tolalloc.ArgumentError, match="^Refit.register_n 38 gives 38 registration"):
        tolalloc.diagnose_measurements(robot, frame.iloc[:40], frame.iloc[40:],
                                       test_frame=tolalloc.Refit(register_n=38))
