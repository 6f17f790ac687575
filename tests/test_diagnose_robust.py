"""Robust M-estimates of the fits (diagnose/scale.py losses, calibrate.fit_model) and the listed outliers.

Known answers: the IRLS solution is a minimum of the estimator's own cost (an independent minimiser, SciPy's
BFGS on ``sum rho(|r_i|)``, finds nothing lower from nearby starts); gross outliers injected at known rows are
the rows listed, and Tukey's biweight leaves the geometric fit as good as on clean data."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import minimize

import tolalloc
from tolalloc.diagnose import calibrate, generate, measurements_from_frame
from tolalloc.diagnose.calibrate import TUKEY_C, _Problem, fit_model, initial_fit, outlier_rows
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.scale import m_rho, m_weight
from tolalloc.diagnose.scores import rms
from tolalloc.diagnose.synth import split_frame


def test_loss_weights_are_the_derivative_of_the_loss():
    s = np.linspace(0.01, 3.0, 50)
    for loss in ("huber", "tukey"):
        h = 1e-6
        d = (m_rho(s + h, loss, 1.0) - m_rho(s - h, loss, 1.0)) / (2 * h)
        np.testing.assert_allclose(m_weight(s, loss, 1.0), d / (2 * s), atol=1e-6)
    assert np.all(m_weight(np.array([1.0, 2.0]), "tukey", 1.0) == 0.0)  # no influence beyond the threshold


@pytest.mark.parametrize("loss", ["huber", "tukey"])
def test_irls_reaches_a_minimum_of_its_own_cost(loss):
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "none", 30, np.random.default_rng(3))
    m = measurements_from_frame(case.frame, robot)
    xyz = m.xyz_mm.copy()
    xyz[[4, 17]] += [[2.0, -1.0, 0.5], [0.0, 1.5, -2.0]]
    model = build_geometry_model(robot)
    fit = fit_model(initial_fit(model, m.q, xyz), m.q, xyz, loss=loss, prior=False)
    prob = _Problem(replace(fit, R=fit.R), m.q, xyz, fit.geo_index)
    prob.loss, prob.f_scale = loss, fit.f_scale_mm

    def cost(x):
        return float(np.sum(m_rho(np.linalg.norm(prob.raw(x).reshape(-1, 3), axis=1), loss, fit.f_scale_mm)))

    x0 = prob.x0()
    ours = cost(x0)
    rng = np.random.default_rng(0)
    for _ in range(3):
        start = x0 + rng.normal(0, 1e-3, len(x0)) * np.r_[1e-3, 1e-3, 1e-3, 1, 1, 1, 1, 1, 1]
        res = minimize(cost, start, method="BFGS", options={"gtol": 1e-10, "maxiter": 2000})
        assert res.fun >= ours * (1 - 1e-6), (res.fun, ours)


def test_gross_outliers_are_listed_and_do_not_move_the_geometry():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "none", 120, np.random.default_rng(6), noise_mm=0.02)
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(2))
    clean = measurements_from_frame(tr, robot)
    dirty_frame = tr.copy()
    bad = [3, 40, 77]
    dirty_frame.loc[bad, "z_mm"] += [2.0, -2.5, 1.5]
    dirty = measurements_from_frame(dirty_frame, robot)
    test = measurements_from_frame(te, robot)
    cal_clean = calibrate(robot, clean)
    tukey = calibrate(robot, dirty).geometric
    assert [o["row"] for o in outlier_rows(tukey, dirty.rows)] == sorted((dirty.rows[b] for b in bad),
                                                                          key=lambda r: -abs(dirty_frame.loc[r - 1, "z_mm"] - tr.loc[r - 1, "z_mm"]))
    assert all(o["weight"] == 0.0 and o["error_mm"] > TUKEY_C * 0.02 for o in outlier_rows(tukey, dirty.rows))
    plain = calibrate(robot, dirty, loss="soft_l1").geometric
    err = {k: rms(test.xyz_mm - f.predict(test.q)) for k, f in
           (("clean", cal_clean.geometric), ("tukey", tukey), ("soft_l1", plain))}
    assert err["tukey"] <= 1.05 * err["clean"], err  # the outliers leave no trace
    assert err["tukey"] <= err["soft_l1"], err
