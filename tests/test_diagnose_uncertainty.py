"""Per-test-pose predicted uncertainty (uncertainty.prediction_uncertainty) against known answers.

* the point Jacobian agrees with central finite differences of ``Fit.predict`` (registration columns to
  1e-5; probe-offset and geometric columns, first-order at the nominal model as in calibrate.py, to 2 %);
* synthetic UR10 data with known noise (0.03 mm per coordinate) and geometric errors the calibration model
  contains (every DH a, d off by N(0, 0.3 mm)): the fraction of held-out residuals inside the predicted 95 %
  radius is 95 % within 3 percentage points (3 fixed seeds pooled, 1,200 test poses; binomial sd 0.6 points,
  the rest is the noise estimate's spread) in the training frame, within 4 points after re-registering
  another frame on 30 poses (810 scored poses);
* the same data scored against a robot with an error the model does not know of (a3 + 1.5 mm): coverage
  collapses and the guard fires.
"""

import copy
import tomllib
from dataclasses import replace
from importlib.resources import files

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.calibrate import calibrate
from tolalloc.diagnose.uncertainty import point_jacobian, prediction_uncertainty
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.register import register_and_score, registration_split
from tolalloc.robot.io.dh import robot_from_dh_dict

NOISE_MM = 0.03
T_MM = np.array([20.0, 30.0, 90.0])
R_A, P_A = Rotation.from_rotvec([0.1, -0.2, 0.3]).as_matrix(), np.array([1500.0, -200.0, 300.0])
R_B, P_B = Rotation.from_rotvec([0.4, 0.1, -0.3]).as_matrix(), np.array([-800.0, 900.0, 100.0])


def _dh(rng=None, a3_mm=0.0):
    data = copy.deepcopy(tomllib.loads((files("tolalloc") / "data/robots/ur10.toml").read_text()))
    for row in data["dh"]:
        for k in ("a_m", "d_m"):
            row[k] = row.get(k, 0.0) + (rng.normal(0.0, 0.3e-3) if rng is not None else 0.0)
    data["dh"][2]["a_m"] += a3_mm * 1e-3
    return robot_from_dh_dict(data)


def _measure(true, n, R, p, t, rng):
    robot = tolalloc.load_robot("ur10")
    rev = robot.revolute_mask
    lo = np.where(rev, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(rev, np.minimum(robot.upper, np.pi), robot.upper)
    q = rng.uniform(lo, hi, (n, 6))
    T = true.fk_internal(q)
    x = (T[:, :3, 3] + T[:, :3, :3] @ t) @ R.T + p
    return Measurements(q, x + rng.normal(0.0, NOISE_MM, x.shape))


def test_point_jacobian_matches_finite_differences():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(0)
    tr = _measure(_dh(rng), 80, R_A, P_A, T_MM, rng)
    fit = calibrate(robot, tr).geometric
    q = tr.q[:5]
    J = point_jacobian(fit, q)
    k = len(fit.geo_index)
    assert J.shape == (5, 3, 9 + k)

    def moved(j, h):
        if j < 3:
            w = np.zeros(3)
            w[j] = h
            return replace(fit, R=fit.R @ Rotation.from_rotvec(w).as_matrix())
        if j < 6:
            return replace(fit, p_mm=fit.p_mm + h * np.eye(3)[j - 3])
        if j < 9:
            return replace(fit, t_mm=fit.t_mm + h * np.eye(3)[j - 6])
        d = fit.delta.copy()
        d[fit.geo_index[j - 9]] += h
        return replace(fit, delta=d)

    for j in range(9 + k):
        h = 1e-6 if (j < 3 or (j >= 9 and fit.model.params[fit.geo_index[j - 9]].unit == "rad")) else 1e-3
        fd = (moved(j, h).predict(q) - moved(j, -h).predict(q)) / (2 * h)
        # registration columns exact; offset and geometric columns use the nominal flange rotation and the
        # nominal model's first-order error Jacobian (calibrate.py): ~1 % from the finite difference at the fit
        rel = 1e-5 if j < 6 else 2e-2
        assert J[:, :, j] == pytest.approx(fd, rel=rel, abs=rel * np.abs(fd).max() + 1e-9), j


def _coverage(seed, refit):
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(seed)
    true = _dh(rng)
    tr = _measure(true, 120, R_A, P_A, T_MM, rng)
    fit = calibrate(robot, tr).geometric
    if not refit:
        te = _measure(true, 400, R_A, P_A, T_MM, rng)
        return prediction_uncertainty(fit, tr.q, te.q, te.xyz_mm - fit.predict(te.q))
    te = _measure(true, 300, R_B, P_B, T_MM + np.array([0.5, -0.3, 1.0]), rng)
    sp = registration_split(te.q, robot.revolute_mask, 30, 0)
    reg = register_and_score(fit, te.q, te.xyz_mm, np.zeros((te.n_poses, 3)), sp)
    return prediction_uncertainty(fit, tr.q, te.q, reg.residual_mm, registered=reg.fit, split=sp)


@pytest.mark.parametrize("refit, tol", [(False, 0.03), (True, 0.04)])
def test_coverage_near_95_percent_with_known_noise(refit, tol):
    us = [_coverage(seed, refit) for seed in range(3)]
    inside = np.concatenate([u.inside for u in us])
    assert abs(inside.mean() - 0.95) <= tol
    for u in us:
        assert u.noise_mm == pytest.approx(NOISE_MM, rel=0.15)
        assert 0.2 * NOISE_MM < np.median(u.sigma_mm) < NOISE_MM  # 120 poses: prediction below the noise
        assert u.message() is None


def test_coverage_collapses_on_an_error_the_model_does_not_know():
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(5)
    true = _dh(rng)
    tr = _measure(true, 120, R_A, P_A, T_MM, rng)
    fit = calibrate(robot, tr).geometric
    te = _measure(_dh(np.random.default_rng(5), a3_mm=1.5), 200, R_A, P_A, T_MM, rng)
    u = prediction_uncertainty(fit, tr.q, te.q, te.xyz_mm - fit.predict(te.q))
    assert u.coverage < 0.5
    assert u.message().startswith("uncertainty: only")
