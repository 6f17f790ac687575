"""Re-registration with a calibration update (diagnose/recalibrate.py) on synthetic sessions with known answers.

Two sessions of one simulated UR10 (known geometric errors) in different tracker frames with different probe
offsets. The calibration is trained on the first; the second is re-registered on 40 of its poses and scored on
the rest.

* The second session differs by a small geometric change (0.3 mm of one link's length). Through
  ``diagnose(..., register_update="calibration")`` the registration poses' marginal likelihood widens the prior
  (``k`` in the thousands: the change is many training posterior sds) and the update recovers the change (within
  15 %) with the scored RMS at the noise level (0.30 -> 0.017 mm; noise 0.017 mm in 3-D); the frame-only
  re-registration's uncertainty fails its coverage check, the update's holds.
* The second session is the same robot: the marginal likelihood keeps ``k`` at its floor (the training file's
  out-of-fold factor, about 1.5 here) and the update does not move -- scored RMS and every parameter as the
  frame-only re-registration gives them, to within the noise; also with a wide prior given (``WIDE_PRIOR_K``).
* The prior is a power prior (:class:`CalibrationPrior`): the training posterior at ``k = 1``, the fit's own prior
  as ``k`` grows, never wider than it; its moments against a dense computation.
* The marginal likelihood itself (:func:`evidence_discount`) recovers a known discount on a linear-Gaussian
  problem, keeps its floor and cap exactly, and agrees with a brute-force evidence that puts a wide Gaussian prior on
  the frame instead of projecting it out (:func:`project_out`, also checked on a rank-deficient frame Jacobian);
  the scored rows never change ``k``.
* A registration pose with a gross error is set aside (named in the JSON) and changes nothing; with too few poses
  left, none is set aside.
* The predicted uncertainty of an update run is the update's posterior: narrower than the prior and than the
  frame-only run's, holding about 95 % of the same robot's scored residuals.
"""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.calibrate import Fit, calibrate
from tolalloc.diagnose.uncertainty import point_jacobian
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.pipeline import diagnose
from tolalloc.diagnose.power_prior import (INFLATION_MAX, CalibrationPrior, calibration_prior, evidence_discount,
                                          inflation_factor, project_out)
from tolalloc.diagnose.recalibrate import CalibrationUpdate, register_update, reregister
from tolalloc.diagnose.register import register_and_score, registration_split
from tolalloc.exceptions import TolallocError

NOISE_MM = 0.01
#: A wide prior given to :func:`register_update` (the library chooses ``k`` by the registration poses' marginal
#: likelihood, at least :func:`inflation_factor`, about 1.5 on these sessions).
WIDE_PRIOR_K = 20.0
#: The geometric change of the second session [mm].
CHANGE_MM = 0.3


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


@pytest.fixture(scope="module")
def changed_runs(sessions):
    """The changed second session through ``diagnose``, frame-only and with the calibration update."""
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    k = _changed_parameter(model, cal.geometric.geo_index)
    changed = delta.copy()
    changed[k] += CHANGE_MM
    test = Measurements(*_test_session(truth, q, noise, frame, changed))
    runs = {u: diagnose(robot, train, test, test_frame="refit", register_n=40, register_update=u, folds=3)
            for u in ("frame", "calibration")}
    return k, runs


def test_shipped_update_recovers_a_small_geometric_change(changed_runs):
    k, runs = changed_runs
    frame, upd = runs["frame"], runs["calibration"]
    rms = {u: r.to_dict()["test_rms_mm"]["geometric"] for u, r in runs.items()}
    noise_3d = np.sqrt(3) * NOISE_MM
    assert rms["frame"] > 10 * noise_3d
    assert rms["calibration"] < 1.5 * noise_3d
    recovered = (upd.registered.delta[k] - upd.geometric.fit.delta[k]) / CHANGE_MM
    assert recovered == pytest.approx(1.0, abs=0.15)
    assert frame.registered.delta[k] == upd.geometric.fit.delta[k]
    cu = upd.calibration_update
    floor = inflation_factor(upd.geometric.oof_mm, upd.geometric.fit.residual_mm)
    assert cu.inflation_floor_k["geometric"] == pytest.approx(floor) and 1.0 < floor < 3.0
    assert cu.inflation_k["geometric"] > 100 * floor  # the change is far outside the training posterior


def test_update_run_says_what_was_fitted_and_whose_uncertainty_is_predicted(changed_runs):
    from tolalloc.report.diagnosis import summary_lines

    frame, upd = changed_runs[1]["frame"], changed_runs[1]["calibration"]
    text = "\n".join(summary_lines(upd))
    assert "other test poses fitted the tracker frame, the probe offset and a correction of the trained" in text
    cu = upd.calibration_update
    ks = f"geometric {cu.inflation_k['geometric']:,.0f}"
    assert f"marginal likelihood chose it: k = {ks}" in text and "huber loss" in text
    line = next(ln for ln in text.splitlines() if ln.startswith("predicted uncertainty:"))
    assert line.endswith("predicted uncertainty of the updated model: the calibration update's posterior covariance "
                         "(its prior, the power prior of the training fit at k, and the registration poses), so this "
                         "coverage checks the updated model's own uncertainty")
    js = upd.to_dict()
    reg = js["test"]["registration"]
    assert reg["update"] == "calibration" and reg["robust_loss"] == "huber"
    assert reg["inflation_k"] == cu.inflation_k and reg["inflation_k_max"] == INFLATION_MAX
    assert reg["set_aside_rows"] == {m: [] for m in cu.inflation_k}
    assert reg["inflation_floor_k"] == cu.inflation_floor_k and "marginal likelihood" in reg["prior"]
    assert "a correction of the trained geometric and effect parameters" in reg["method"]
    assert js["uncertainty"]["method"].startswith("posterior covariance sigma^2 H^-1 of the calibration update")
    assert frame.to_dict()["uncertainty"]["method"].startswith("Gauss-Newton parameter covariance")
    assert "registration and probe offset re-estimated" in frame.to_dict()["uncertainty"]["method"]
    assert js["heldout"]["sealed_test"].endswith("also fitted a correction of the trained parameters "
                                                 "(register_update='calibration')")
    assert js["settings"]["robust_loss"] == upd.calibration.loss  # auto: Tukey, or Huber on a small file
    assert js["settings"]["register_update_robust_loss"] == "huber"
    plain = "\n".join(summary_lines(frame))
    assert "other test poses fitted the tracker frame and probe offset and are not scored" in plain
    assert "calibration update" not in plain and "inflation_k" not in frame.to_dict()["test"]["registration"]


def test_wide_prior_recovers_nearly_all_of_a_small_geometric_change(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    fit = cal.geometric
    k = _changed_parameter(model, fit.geo_index)
    changed = delta.copy()
    changed[k] += CHANGE_MM
    q, xyz = _test_session(truth, q, noise, frame, changed)
    only_frame = register_and_score(fit, q, xyz, np.zeros((len(q), 3)), split)
    prior = calibration_prior(fit, train.q, None, WIDE_PRIOR_K)
    upd = register_update(fit, q, xyz, None, split, prior)
    noise_3d = np.sqrt(3) * NOISE_MM
    assert _rms(only_frame.residual_mm) > 10 * noise_3d
    assert _rms(upd.residual_mm) < 2.5 * noise_3d
    assert upd.fit.delta[k] - fit.delta[k] == pytest.approx(CHANGE_MM, rel=0.25)


def test_update_does_not_move_the_same_robot(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    fit = cal.geometric
    q, xyz = _test_session(truth, q, noise, frame, delta)
    only_frame = register_and_score(fit, q, xyz, np.zeros((len(q), 3)), split)
    prior = calibration_prior(fit, train.q, None, WIDE_PRIOR_K)
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


def test_reregister_refuses_an_unknown_update_and_a_calibration_update_without_training_poses(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    q, xyz = _test_session(truth, q, noise, frame, delta)
    with pytest.raises(TolallocError, match="update: expected one of frame, calibration, got 'both'"):
        reregister(cal.geometric, q, xyz, None, split, update="both", q_train=train.q)
    with pytest.raises(TolallocError, match="update='calibration' needs the training poses `q_train`"):
        reregister(cal.geometric, q, xyz, None, split, update="calibration")


def test_calibration_update_without_a_test_file_is_refused():
    robot = tolalloc.load_robot("ur10")
    m = Measurements(np.zeros((20, 6)), np.zeros((20, 3)))
    with pytest.raises(TolallocError, match="register_update='calibration' needs a test file with "
                                            "test_frame='refit' \\(got no test file\\)"):
        diagnose(robot, m, None, test_frame="refit", register_update="calibration")


@pytest.fixture(scope="module")
def same_robot_runs(sessions):
    """The second session of the same robot through ``diagnose``, frame-only and with the calibration update."""
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    test = Measurements(*_test_session(truth, q, noise, frame, delta))
    return {u: diagnose(robot, train, test, test_frame="refit", register_n=40, register_update=u, folds=3)
            for u in ("frame", "calibration")}


def test_update_posterior_narrows_the_prior_and_is_a_covariance(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    fit = cal.geometric
    q, xyz = _test_session(truth, q, noise, frame, delta)
    prior = calibration_prior(fit, train.q, None, 1.5)
    upd = register_update(fit, q, xyz, None, split, prior)
    cov = upd.posterior_cov
    m = 9 + len(fit.geo_index)
    assert cov.shape == (m, m)
    np.testing.assert_allclose(cov, cov.T, atol=1e-15)
    assert np.linalg.eigvalsh(cov).min() > 0
    # the registration poses add information: every parameter's posterior sd is at most its prior sd
    prior_sd = np.sqrt(np.diag(np.linalg.inv(prior.precision))) * prior.noise_mm
    assert np.all(np.sqrt(np.diag(cov))[9:] <= prior_sd * (1 + 1e-9))
    assert np.sqrt(np.diag(cov))[9:].mean() < 0.9 * prior_sd.mean()
    # against the linear-Gaussian posterior built here from the point Jacobian at the registration poses (columns:
    # frame, probe offset, geometric parameters) and the prior precision: Huber's weights (<= 1, a few poses) may
    # only widen it, and only a little at noise-level residuals
    r = split.register_index
    A = point_jacobian(upd.fit, q[r]).reshape(3 * len(r), -1)
    H = A.T @ A
    H[9:, 9:] += prior.precision
    independent = prior.noise_mm ** 2 * np.linalg.inv(H)
    ratio = np.sqrt(np.diag(cov) / np.diag(independent))
    assert ratio.min() >= 1 - 1e-6 and ratio.max() < 1.02


def test_update_run_predicts_its_posterior_uncertainty_and_covers_the_same_robot(same_robot_runs):
    frame, upd = same_robot_runs["frame"], same_robot_runs["calibration"]
    assert frame.final.test_cov is None and frame.uncertainty_scope() == ""
    assert upd.final.test_cov is not None
    # the same robot: the updated model's 95 % radius holds about 95 % of the scored residuals
    assert upd.uncertainty.inside.mean() >= 0.88
    # and it is the narrower posterior, not the training covariance
    assert np.median(upd.uncertainty.sigma_mm[upd.scored_index]) < np.median(frame.uncertainty.sigma_mm[frame.scored_index])


def test_update_run_covers_a_change_the_frame_only_run_fails_to_cover(changed_runs):
    frame, upd = changed_runs[1]["frame"], changed_runs[1]["calibration"]
    assert frame.uncertainty.inside.mean() < 0.1  # the change is systematic error the training covariance ignores
    assert any(g.startswith("uncertainty: only ") for g in frame.guards)
    assert upd.uncertainty.inside.mean() >= 0.88
    assert not any(g.startswith("uncertainty: ") for g in upd.guards)


def test_same_robot_keeps_the_prior_at_its_floor(same_robot_runs):
    cu = same_robot_runs["calibration"].calibration_update
    assert set(cu.inflation_k) >= {"geometric"}
    for m, k in cu.inflation_k.items():  # every updated model
        assert k == pytest.approx(cu.inflation_floor_k[m])
        assert cu.set_aside_poses[m] == ()


def _linear_prior(rng, m=40, noise_mm=0.01):
    """A power prior with informative training data (``S``) and a weak own prior (``Lambda``), trained values off 0."""
    L = rng.normal(size=(m, m))
    S = 1e6 * (L @ L.T / m + 0.1 * np.eye(m))  # training information [1 / units^2]
    lam = np.full(m, 1e2)  # the fit's own prior: sd 0.1 units
    return CalibrationPrior(rng.normal(0.0, 0.05, m), S, lam, noise_mm)


@pytest.mark.parametrize("k_true", [1.0, 30.0, 1000.0])
def test_marginal_likelihood_recovers_a_known_discount(k_true):
    rng = np.random.default_rng(11)
    n, m = 3000, 40
    prior = _linear_prior(rng, m)
    A = rng.normal(size=(n, m))
    mean, C = prior.moments(k_true)
    ks = []
    for t in rng.multivariate_normal(mean, C, size=60):  # k is estimated from the m = 40 parameters of one draw
        y = A @ (t - prior.trained) + rng.normal(0.0, prior.noise_mm, n)  # residuals at the trained values
        ks.append(evidence_discount(y, A, prior)[0])
    assert np.median(ks) == pytest.approx(k_true, rel=0.25)
    assert evidence_discount(y, A, prior, k_min=2 * k_true)[0] >= 2 * k_true  # the floor holds exactly


def test_power_prior_moves_from_the_training_posterior_to_the_fits_own_prior():
    rng = np.random.default_rng(12)
    prior = _linear_prior(rng, 6)
    S, lam, theta = prior.information, np.diag(prior.prior_precision), prior.trained
    # k = 1: the training posterior (mean the trained values, precision S + Lambda)
    mean1, C1 = prior.moments(1.0)
    np.testing.assert_allclose(mean1, theta, rtol=1e-12)
    np.testing.assert_allclose(C1, np.linalg.inv(S + lam), rtol=1e-8)
    np.testing.assert_allclose(prior.precision, prior.noise_mm ** 2 * (S + lam), rtol=1e-12)
    # any k: the Gaussian likelihood raised to 1/k times the own prior, by completing the square densely
    for k in (3.0, 300.0):
        P = S / k + lam
        theta_ml = np.linalg.solve(S, (S + lam) @ theta)  # the training data's own estimate
        mean, C = prior.moments(k)
        np.testing.assert_allclose(C, np.linalg.inv(P), rtol=1e-8)
        np.testing.assert_allclose(mean, np.linalg.solve(P, S @ theta_ml / k), rtol=1e-6, atol=1e-12)
        assert np.all(np.diag(C) <= 1.0 / prior.prior_precision)  # never wider than the fit's own prior
    mean_far, C_far = prior.moments(1e9)
    np.testing.assert_allclose(np.diag(C_far), 1.0 / prior.prior_precision, rtol=1e-4)
    np.testing.assert_allclose(mean_far, 0.0, atol=1e-4 * np.abs(theta).max())
    # a parameter the training data never pinned keeps its own prior at every k
    S0 = S.copy()
    S0[0, :] = S0[:, 0] = 0.0
    unpinned = CalibrationPrior(theta, S0, prior.prior_precision, prior.noise_mm)
    for k in (1.0, 50.0, 5e3):
        assert unpinned.moments(k)[1][0, 0] == pytest.approx(1.0 / prior.prior_precision[0], rel=1e-9)
    w = prior.widened(50.0, 2.0)
    assert (w.inflation, w.inflation_floor) == (50.0, 2.0)
    np.testing.assert_allclose(w.mean, prior.moments(50.0)[0])


def _changed_session(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    k = _changed_parameter(model, cal.geometric.geo_index)
    changed = delta.copy()
    changed[k] += CHANGE_MM
    return _test_session(truth, q, noise, frame, changed)


def test_chosen_k_matches_a_brute_force_evidence_with_a_wide_prior_on_the_frame(sessions):
    """The frame and probe offset are marginalised by projection (flat prior); a very wide Gaussian prior on them,
    evaluated by brute force over a k grid, must pick the same k."""
    robot, model, delta, truth, train, cal, q0, noise, frame, split = sessions
    fit = cal.geometric
    q, xyz = _changed_session(sessions)
    reg = reregister(fit, q, xyz, None, split, update="calibration", q_train=train.q,
                     oof_mm=cal.geometric.residual_mm)
    r = split.register_index
    start = register_and_score(fit, q, xyz, np.zeros((len(q), 3)), split).fit
    J = point_jacobian(start, q[r]).reshape(3 * len(r), -1)
    y = (xyz[r] - start.predict(q[r])).ravel()
    prior1 = calibration_prior(fit, train.q, None)
    s = np.linalg.norm(J[:, :9], axis=0)
    W = np.diag((1e4 / s) ** 2)  # the frame's prior sd: 1e4 mm of effect per column
    ks = np.geomspace(100, 1e4, 400)

    def logev(k):
        mean, C = prior1.moments(k)
        e = y - J[:, 9:] @ (mean - prior1.trained)
        S = prior1.noise_mm ** 2 * np.eye(len(y)) + J[:, :9] @ W @ J[:, :9].T + J[:, 9:] @ C @ J[:, 9:].T
        return -0.5 * (np.linalg.slogdet(S)[1] + e @ np.linalg.solve(S, e))

    brute = ks[np.argmax([logev(k) for k in ks])]
    assert reg.prior.inflation == pytest.approx(brute, rel=0.03)


def test_scored_rows_do_not_change_k(sessions):
    robot, model, delta, truth, train, cal, q0, noise, frame, split = sessions
    q, xyz = _changed_session(sessions)
    other = xyz.copy()
    other[split.score_index] += np.random.default_rng(5).normal(0.0, 5.0, (len(split.score_index), 3))
    a, b = (reregister(cal.geometric, q, x, None, split, update="calibration", q_train=train.q) for x in (xyz, other))
    assert a.prior.inflation == pytest.approx(b.prior.inflation, rel=1e-12)


def test_a_gross_registration_error_is_set_aside_and_does_not_widen_the_prior(sessions):
    robot, model, delta, truth, train, cal, q0, noise, frame, split = sessions
    q, xyz = _test_session(truth, q0, noise, frame, delta)  # the same robot
    bad = xyz.copy()
    bad[split.register_index[3]] += [10.0, 0.0, 0.0]
    fixed = register_update(cal.geometric, q, bad, None, split, calibration_prior(cal.geometric, train.q, None),
                            loss="tukey")
    assert fixed.prior.set_aside == (split.register_index[3],)  # also with a given prior
    clean, dirty = (reregister(cal.geometric, q, x, None, split, update="calibration", q_train=train.q,
                               loss="tukey") for x in (xyz, bad))
    assert dirty.prior.set_aside == (split.register_index[3],) and clean.prior.set_aside == ()
    assert dirty.prior.inflation < 1.5  # at its floor, 1 here (no out-of-fold residuals given)
    assert _rms(dirty.residual_mm) < 1.5 * np.sqrt(3) * NOISE_MM
    np.testing.assert_allclose(dirty.residual_mm, clean.residual_mm, atol=0.2 * NOISE_MM)


def test_evidence_without_information_keeps_the_floor_and_the_floor_may_exceed_the_cap():
    rng = np.random.default_rng(2)
    y = rng.normal(0.0, 0.01, 30)
    prior = CalibrationPrior(np.full(4, 0.01), 1e8 * np.eye(4), np.full(4, 1e6), 0.01)  # sd 1e-4 at k = 1
    assert evidence_discount(y, np.zeros((30, 4)), prior, k_min=3.0)[0] == 3.0  # flat evidence
    silent = CalibrationPrior(prior.trained, prior.information, prior.prior_precision, 0.0)
    assert evidence_discount(y, rng.normal(size=(30, 4)), silent, k_min=3.0)[0] == 3.0  # no noise variance
    k, ev = evidence_discount(y * np.nan, rng.normal(size=(30, 4)), prior, k_min=3.0)
    assert k == 3.0 and np.isnan(ev)
    big = evidence_discount(100 * y, rng.normal(size=(30, 4)), prior, k_min=2 * INFLATION_MAX)[0]
    assert big == 2 * INFLATION_MAX
    A = rng.normal(size=(30, 4))
    far = A @ np.full(4, -0.01)  # parameters at the own prior's mean, 100 training sd from the trained values
    assert evidence_discount(far, A, prior)[0] == INFLATION_MAX  # at the cap exactly


@pytest.fixture(scope="module")
def unmodelled_run(sessions):
    """A second session with an error no trained parameter can represent: 0.15 mm along x, periodic in q1."""
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    q, xyz = _test_session(truth, q, noise, frame, delta)
    xyz = xyz + 0.15 * np.sin(3 * q[:, :1]) * np.array([1.0, 0.0, 0.0])
    return diagnose(robot, train, Measurements(q, xyz), test_frame="refit", register_n=40,
                    register_update="calibration", folds=3)


def test_update_run_with_an_unmodelled_error_fails_its_coverage_check_and_says_whose_uncertainty(unmodelled_run):
    from tolalloc.diagnose.recalibrate import UNCERTAINTY_SCOPE

    upd = unmodelled_run
    assert upd.uncertainty.inside.mean() < 0.5
    assert any(g.startswith("uncertainty: only ") and g.endswith(f"({UNCERTAINTY_SCOPE})") for g in upd.guards)


def test_too_few_registration_poses_left_keeps_them_all(sessions):
    robot, model, delta, truth, train, cal, q0, noise, frame, split = sessions
    q, xyz = _test_session(truth, q0, noise, frame, delta)
    few = registration_split(q, robot.revolute_mask, 5, seed=0)
    bad = xyz.copy()
    bad[few.register_index[2]] += [10.0, 0.0, 0.0]  # setting it aside would leave 4 < MIN_REGISTER = 5 poses
    upd = reregister(cal.geometric, q, bad, None, few, update="calibration", q_train=train.q, loss="tukey")
    assert upd.prior.set_aside == () and upd.prior.gross_kept == (few.register_index[2],)
    d = diagnose(robot, train, Measurements(q, bad), test_frame="refit", register_n=5, register_update="calibration",
                 folds=3, robust_loss="tukey")
    np.testing.assert_array_equal(d.registration.register_index, few.register_index)
    row = few.register_index[2] + 1
    assert any(g.startswith(f"registration: 1 registration pose(s) with a gross error (test rows {row}) kept in the "
                            "calibration update: setting them aside would leave fewer than 5") for g in d.guards)


def test_update_text_and_json_name_the_floor_the_cap_and_the_rows_set_aside():
    cu = CalibrationUpdate({"geometric": 3.0, "final": INFLATION_MAX}, {"geometric": 3.0, "final": 1.5},
                           {"geometric": (4,), "final": (1, 2)}, "huber")
    text = cu.fitted()
    assert "k = geometric 3 (its floor), 1 registration pose set aside as gross error; " in text
    assert "final 10,000 (the largest allowed), 2 registration poses set aside as gross errors; huber loss" in text
    js = cu.to_dict(np.array([10, 11, 12, 13, 14, 15]))
    assert js["set_aside_rows"] == {"geometric": [14], "final": [11, 12]}
    assert cu.to_dict()["set_aside_rows"] == {"geometric": [5], "final": [2, 3]}  # 1-based positions without rows


def test_widening_is_relative_to_the_priors_own_k(sessions):
    robot, model, delta, truth, train, cal, q, noise, frame, split = sessions
    p20, p5 = (calibration_prior(cal.geometric, train.q, None, k) for k in (20.0, 5.0))
    np.testing.assert_allclose(p20.widened(5.0).precision, p5.precision, rtol=1e-12)
    assert p20.widened(5.0).inflation == 5.0


def test_projection_removes_a_rank_deficient_nuisance_space():
    rng = np.random.default_rng(4)
    N = rng.normal(size=(60, 9))
    N[:, 4] = N[:, 0] + 2 * N[:, 3]  # a column that depends on earlier ones, independent ones after it
    M = rng.normal(size=(60, 5))
    (P,), n_eff = project_out(N, M)
    assert n_eff == 60 - 8
    np.testing.assert_allclose(N.T @ P, 0.0, atol=1e-10)  # nothing of the nuisance space left
    resid = M - N @ np.linalg.lstsq(N, M, rcond=None)[0]
    np.testing.assert_allclose(P, resid, atol=1e-10)
