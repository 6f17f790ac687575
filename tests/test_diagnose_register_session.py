"""Cross-session re-registration on synthetic sessions with known answers (diagnose/register.py).

* Two sessions of an exactly known robot in different tracker frames with different probe offsets (the probe
  re-mounted): re-registering the frame (6) **and** the probe offset (3) on 30 poses scores the other poses at
  the noise level (RMS of the 3-D noise ``sqrt(3) sigma``); re-registering the frame alone cannot (the
  0.5-0.8 mm probe change stays in the score).
* A test session with a systematic error the trained model lacks, largest at the extremes of the session's
  joint space: the registration poses must be representative of the session. Registered on the chosen 30
  poses, the score is within 10 % of a registration on every test pose (the best the 9 parameters can do); a
  registration on the 30 most extreme poses (farthest-point sampling, the former selection, written out here
  as a reference) is measurably worse.
"""

import numpy as np
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.calibrate import calibrate, kabsch
from tolalloc.diagnose.gap import joint_features
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.register import RegistrationSplit, register_and_score, registration_split

NOISE_MM = 0.02


def _rms(e):
    return float(np.sqrt(np.mean(np.sum(e ** 2, axis=1))))


def _points(robot, q, R, p, t):
    T = robot.fk_internal(q)
    return (T[:, :3, 3] + T[:, :3, :3] @ t) @ R.T + p


def _session(robot, rng, n, R, p, t, extra=None):
    q = rng.uniform(-np.pi, np.pi, (n, 6))
    x = _points(robot, q, R, p, t)
    if extra is not None:
        x = x + extra(q) @ R.T
    return Measurements(q, x + rng.normal(0.0, NOISE_MM, x.shape))


def _frozen_tool_score(fit, test, split):
    """Re-register the tracker frame only (Kabsch on the registration poses), probe offset kept from training."""
    r, s = split.register_index, split.score_index
    R, p = kabsch(fit.base_points(test.q[r]), test.xyz_mm[r])
    return _rms(test.xyz_mm[s] - (fit.base_points(test.q[s]) @ R.T + p))


def test_probe_remounted_between_sessions_is_re_registered():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(11)
    train = _session(robot, rng, 120, np.eye(3), np.zeros(3), np.array([10.0, 20.0, 80.0]))
    R = Rotation.from_rotvec([0.2, -0.4, 1.1]).as_matrix()
    test = _session(robot, rng, 150, R, np.array([1500.0, -300.0, 200.0]), np.array([10.5, 19.4, 80.3]))
    fit = calibrate(robot, train).nominal
    split = registration_split(test.q, robot.revolute_mask, 30, seed=0)
    reg = register_and_score(fit, test.q, test.xyz_mm, np.zeros((test.n_poses, 3)), split)
    noise_3d = np.sqrt(3) * NOISE_MM
    assert _rms(reg.residual_mm) < 1.3 * noise_3d
    np.testing.assert_allclose(reg.fit.t_mm, [10.5, 19.4, 80.3], atol=0.05)
    np.testing.assert_allclose(reg.fit.R, R, atol=1e-4)
    assert _frozen_tool_score(fit, test, split) > 10 * noise_3d  # frame alone: the probe change stays


def _farthest_points(q, revolute, n, seed=0):
    """Reference: farthest-point sampling in the same joint features (takes the extremes of the series)."""
    X = joint_features(q, revolute)
    X = X / X.std(0)
    chosen = [int(np.random.default_rng(seed).integers(len(q)))]
    d = np.linalg.norm(X - X[chosen[0]], axis=1)
    for _ in range(n - 1):
        chosen.append(int(np.argmax(d)))
        d = np.minimum(d, np.linalg.norm(X - X[chosen[-1]], axis=1))
    r = np.sort(chosen)
    return RegistrationSplit(r, np.setdiff1d(np.arange(len(q)), r), float(n))


def test_registration_poses_are_representative_not_extreme():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(5)
    t = np.array([0.0, 0.0, 90.0])
    train = _session(robot, rng, 120, np.eye(3), np.zeros(3), t)
    fit = calibrate(robot, train).nominal
    # test session: poses concentrated around a centre (as a real session is), with an unmodelled error of
    # 0.1 mm per unit squared standardised distance from the centre in joint features -- largest at the extremes
    q = rng.normal(0.0, 0.8, (400, 6))
    X = joint_features(q, robot.revolute_mask)
    r2 = np.sum(((X - X.mean(0)) / X.std(0)) ** 2, axis=1)
    R = Rotation.from_rotvec([0.0, 0.3, -0.7]).as_matrix()
    x = _points(robot, q, R, np.array([800.0, 200.0, -50.0]), t)
    x += (0.1 * np.column_stack([r2 - r2.mean(), 0.5 * (r2 - r2.mean()), np.zeros(len(q))])) @ R.T
    test = Measurements(q, x + rng.normal(0.0, NOISE_MM, x.shape))
    zero = np.zeros((test.n_poses, 3))
    split = registration_split(test.q, robot.revolute_mask, 30, seed=0)
    chosen = _rms(register_and_score(fit, test.q, test.xyz_mm, zero, split).residual_mm)
    everything = RegistrationSplit(np.arange(test.n_poses), split.score_index, float(test.n_poses))
    best = _rms(register_and_score(fit, test.q, test.xyz_mm, zero, everything).residual_mm)
    extreme = _rms(register_and_score(fit, test.q, test.xyz_mm, zero,
                                      _farthest_points(test.q, robot.revolute_mask, 30)).residual_mm)
    assert best > 20 * NOISE_MM  # the systematic error dominates the noise
    assert chosen < 1.1 * best
    assert extreme > 1.5 * chosen
