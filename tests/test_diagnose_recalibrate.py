"""Re-registration with a calibration update (diagnose/recalibrate.py) on synthetic sessions with known answers.

Two sessions of one simulated UR10 (known geometric errors) in different tracker frames with different probe
offsets. The calibration is trained on the first; the second is re-registered on 40 of its poses and scored on
the rest.

* The second session differs by a small geometric change (0.3 mm of one link's length): the frame-only
  re-registration cannot absorb it, the calibration update recovers it (scored RMS within 2.5 x the noise level, the
  change found within 25 %).
* The second session is the same robot: the update must not move -- scored RMS and every parameter as the
  frame-only re-registration gives them, to within the noise.
"""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.calibrate import Fit, calibrate
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.recalibrate import calibration_prior, inflation_factor, register_update, reregister
from tolalloc.diagnose.register import register_and_score, registration_split
from tolalloc.exceptions import TolallocError

NOISE_MM = 0.01
#: Prior inflation of the tests: the training posterior widened to about the registration poses' information.
INFLATION = 20.0


def _rms(e):
    return float(np.sqrt(np.mean(np.sum(e ** 2, axis=1))))


def _sessions():
    robot = tolalloc.load_robot("ur10")
    model = build_geometry_model(robot)
    rng = np.random.default_rng(3)
    delta = rng.normal(0.0, 0.3 * model.sigma)
    q_tr = rng.uniform(-np.pi, np.pi, (60, 6))
    truth = Fit(model, np.eye(3), np.zeros(3), np.array([5.0, -3.0, 60.0]), delta, np.zeros(0, int))
    train = Measurements(q_tr, truth.predict(q_tr) + rng.normal(0.0, NOISE_MM, (60, 3)))
    cal = calibrate(robot, train, model=model)
    q_te = rng.uniform(-np.pi, np.pi, (120, 6))
    noise = rng.normal(0.0, NOISE_MM, (120, 3))
    frame = dict(R=Rotation.from_rotvec([0.1, -0.3, 0.9]).as_matrix(), p_mm=np.array([900.0, -200.0, 150.0]),
                 t_mm=np.array([5.4, -2.7, 60.2]))
    split = registration_split(q_te, robot.revolute_mask, 40, seed=0)
    return robot, model, delta, truth, train, cal, q_te, noise, frame, split


@pytest.fixture(scope="module")
def sessions():
    return _sessions()


def _test_session(truth, q, noise, frame, delta):
    from dataclasses import replace

    return q, replace(truth, delta=delta, **frame).predict(q) + noise


def _changed_parameter(model, geo):
    """A fitted length parameter (mm) of the geometry model."""
    return next(k for k in geo if model.params[k].interface_unit == "mm")


def test_update_recovers_a_small_geometric_change(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    fit = cal.geometric
    k = _changed_parameter(model, fit.geo_index)
    changed = delta.copy()
    changed[k] += 0.3
    q, xyz = _test_session(truth, q, noise, frame, changed)
    only_frame = register_and_score(fit, q, xyz, np.zeros((len(q), 3)), split)
    prior = calibration_prior(fit, train.q, None, INFLATION)
    upd = register_update(fit, q, xyz, None, split, prior)
    noise_3d = np.sqrt(3) * NOISE_MM
    assert _rms(only_frame.residual_mm) > 10 * noise_3d
    assert _rms(upd.residual_mm) < 2.5 * noise_3d
    assert upd.fit.delta[k] - fit.delta[k] == pytest.approx(0.3, rel=0.25)


def test_update_does_not_move_the_same_robot(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    fit = cal.geometric
    q, xyz = _test_session(truth, q, noise, frame, delta)
    only_frame = register_and_score(fit, q, xyz, np.zeros((len(q), 3)), split)
    prior = calibration_prior(fit, train.q, None, INFLATION)
    upd = register_update(fit, q, xyz, None, split, prior)
    noise_3d = np.sqrt(3) * NOISE_MM
    assert _rms(upd.residual_mm) < 1.5 * noise_3d
    assert _rms(upd.residual_mm) == pytest.approx(_rms(only_frame.residual_mm), abs=0.2 * noise_3d)
    sd = np.sqrt(np.diag(np.linalg.inv(prior.precision))) * prior.noise_mm
    moved = np.abs(upd.fit.delta[fit.geo_index] - fit.delta[fit.geo_index])
    assert np.all(moved < 3 * sd)
    np.testing.assert_allclose(upd.fit.t_mm, only_frame.fit.t_mm, atol=0.05)


def test_frame_update_is_the_frame_only_registration(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    q, xyz = _test_session(truth, q, noise, frame, delta)
    a = reregister(cal.geometric, q, xyz, None, split, update="frame")
    b = register_and_score(cal.geometric, q, xyz, np.zeros((len(q), 3)), split)
    np.testing.assert_array_equal(a.residual_mm, b.residual_mm)


def test_inflation_factor_is_the_out_of_fold_ratio_at_least_one():
    res = np.full((10, 3), 0.1)
    assert inflation_factor(2 * res, res) == pytest.approx(4.0)
    assert inflation_factor(0.5 * res, res) == 1.0


def test_bad_register_update_is_refused():
    robot = tolalloc.load_robot("ur10")
    m = Measurements(np.zeros((20, 6)), np.zeros((20, 3)))
    with pytest.raises(TolallocError, match="register_update: expected one of frame, calibration, got 'both'"):
        tolalloc.diagnose.diagnose(robot, m, m, test_frame="refit", register_update="both")
