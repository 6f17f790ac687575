"""The diagnosis at scale (issue 12 item 3): chunked normal-equation fit, subsampled cross-validation, progress,
memory. Known answers: SciPy's least_squares on the same residual and Jacobian (the former fit), the unchunked
fit, forward kinematics of robot.kinematics; peak memory by tracemalloc (not timed)."""

import json
import re
import tracemalloc

import numpy as np
import pytest
from scipy.optimize import least_squares

import tolalloc
from tolalloc.cli import main
from tolalloc.diagnose import calibrate, diagnose, generate, measurements_from_frame
from tolalloc.diagnose.calibrate import TUKEY_C, _Problem, fit_model
from tolalloc.diagnose.effects import effect_basis, effect_reference
from tolalloc.diagnose.scale import norm_scale, point_kinematics, robust_scale, solve
from tolalloc.robot.kinematics import fk_poe
from tolalloc.robot.lie import rotvec


@pytest.fixture(scope="module")
def case():
    robot = tolalloc.load_robot("ur10")
    m = measurements_from_frame(generate(robot, "joint_compliance", 300, np.random.default_rng(11)).frame, robot)
    cal = calibrate(robot, m)
    B = effect_basis("joint_compliance", robot, m, cal.geometric.t_mm, effect_reference(m)).B
    return robot, m, cal, B


def _scipy_fit(start, q, xyz, geo, B):
    """The former fit: scipy.optimize.least_squares (TRF, x_scale='jac'), plain pass, then soft_l1 + MAP prior."""
    prob = _Problem(start, q, xyz, geo, B)
    opts = dict(jac=prob.jac, method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10)
    sol = least_squares(prob.fun, prob.x0(), max_nfev=60, **opts)
    sig = start.model.sigma[geo]
    noise = robust_scale(sol.fun) / 3.0
    prob.prior_w = np.where(sig > 0, noise / np.where(sig > 0, sig, 1.0), 0.0)
    prob.f_scale = robust_scale(prob.raw(sol.x))
    sol = least_squares(prob.fun, sol.x, max_nfev=30, **opts)
    return prob.unpack(sol.x)


def test_fit_equals_former_least_squares_fit(case):
    robot, m, cal, B = case
    geo = cal.geometric.geo_index
    R, p, t, delta, beta = _scipy_fit(cal.nominal, m.q, m.xyz_mm, geo, B)
    # the former fit's loss, iterated to the solver's own tolerances (sd_tol=0)
    ours = fit_model(cal.nominal, m.q, m.xyz_mm, geo_index=geo, B=B, loss="soft_l1", sd_tol=0.0)
    # stated tolerance: 1e-6 mm on lengths, 1e-9 rad on angles, 1e-5 relative on effect parameters
    np.testing.assert_allclose(ours.p_mm, p, atol=1e-6)
    np.testing.assert_allclose(ours.t_mm, t, atol=1e-6)
    np.testing.assert_allclose(ours.R, R, atol=1e-9)
    to_if = np.array([prm.to_interface for prm in cal.geometric.model.params])
    np.testing.assert_allclose(ours.delta * to_if, delta * to_if, atol=1e-6)
    np.testing.assert_allclose(ours.beta, beta, rtol=1e-5, atol=1e-5 * np.abs(beta).max())


@pytest.mark.parametrize("loss", ["tukey", "soft_l1"])
def test_early_stop_is_within_a_fraction_of_a_standard_error(case, loss):
    """solve(sd_tol=0.01) stops within about 0.01 standard errors of the optimum it reaches with sd_tol=0: the
    Mahalanobis distance of the two solutions under the final normal matrix and residual variance."""
    robot, m, cal, B = case
    geo = cal.geometric.geo_index
    probs, xs = [], []
    for sd_tol in (0.0, 0.01):
        prob = _Problem(cal.nominal, m.q, m.xyz_mm, geo, B)
        x, raw = solve(prob, prob.x0(), sd_tol=0.0)
        prob.loss, prob.f_scale = loss, (TUKEY_C * norm_scale(raw) if loss == "tukey" else robust_scale(raw.ravel()))
        x, _ = solve(prob, x, max_iter=60, sd_tol=sd_tol)
        probs.append(prob)
        xs.append(x)
    (Ra, *_), (Rb, *_) = probs[0].unpack(xs[0]), probs[1].unpack(xs[1])
    d = np.concatenate([rotvec(Ra.T @ Rb), xs[1][3:] - xs[0][3:]])
    cost, H, _, _ = probs[0].normal(xs[0])
    s2 = cost / (3 * m.n_poses - len(d))
    assert np.sqrt(d @ H @ d / s2) <= 0.02
    assert np.abs(d).max() > 0  # the early stop did stop early (else the check above tests nothing)


def test_chunked_equals_unchunked(case):
    robot, m, cal, B = case
    geo = cal.geometric.geo_index
    one = fit_model(cal.nominal, m.q, m.xyz_mm, geo_index=geo, B=B)
    many = fit_model(cal.nominal, m.q, m.xyz_mm, geo_index=geo, B=lambda sl: B[sl], n_effects=B.shape[-1],
                     chunk_rows=37)  # 9 chunks, the last one short; effect basis computed chunk by chunk
    np.testing.assert_allclose(many.p_mm, one.p_mm, atol=1e-8)
    np.testing.assert_allclose(many.R, one.R, atol=1e-11)
    np.testing.assert_allclose(many.delta, one.delta, atol=1e-11)
    np.testing.assert_allclose(many.beta, one.beta, rtol=1e-8, atol=1e-8 * np.abs(one.beta).max())
    np.testing.assert_allclose(many.residual_mm, one.residual_mm, atol=1e-8)
    assert many.f_scale_mm == pytest.approx(one.f_scale_mm, rel=1e-9)


@pytest.mark.parametrize("numba", ["1", "0"])
def test_point_kinematics_matches_fk_poe(case, monkeypatch, numba):
    monkeypatch.setenv("TOLALLOC_NUMBA", numba)
    robot, m, cal, _ = case
    screws, home, dq = cal.geometric.model.perturbed_chain(np.random.default_rng(1).normal(0, 1e-3, (1, 30)))
    t = np.array([10.0, -50.0, 120.0])
    T = fk_poe(screws[0], home[0], m.q + dq[0])
    pts, rots = point_kinematics(screws[0], home[0], m.q + dq[0], t, chunk_rows=70)
    np.testing.assert_allclose(rots, T[:, :3, :3], atol=1e-12)
    np.testing.assert_allclose(pts, T[:, :3, 3] + T[:, :3, :3] @ t, atol=1e-9)


@pytest.fixture(scope="module")
def tc_frame():
    robot = tolalloc.load_robot("tool_changer")
    return robot, generate(robot, "backlash", 500, np.random.default_rng(3)).frame


def test_subsample_reported_and_final_fit_on_all_rows(tc_frame):
    robot, frame = tc_frame
    m = measurements_from_frame(frame, robot)
    d = diagnose(robot, m, folds=3, subsample_rows=250, seed=4)
    assert d.subsample["rows"] == 500 and d.subsample["cv_rows"] == 250 and d.subsample["seed"] == 4
    js = d.to_dict()
    assert js["subsample"] == d.subsample and js["heldout"]["cv_poses"] == 250
    assert len(d.final.oof_mm) == 250  # cross-validated on the subsample
    assert len(d.final.fit.residual_mm) == 500  # final model fitted on every row
    assert d.effect == "backlash"
    # the final fit is the fit of the selected model on all rows
    B = effect_basis("backlash", robot, m, d.calibration.geometric.t_mm, effect_reference(m)).B  # no reference used
    ref = fit_model(d.calibration.geometric, m.q, m.xyz_mm, geo_index=d.calibration.geometric.geo_index,
                    B=B[:, :, d.final.keep])
    np.testing.assert_allclose(d.final.fit.beta, ref.beta, rtol=1e-9, atol=1e-12)
    small = diagnose(robot, m, folds=3)
    assert small.subsample is None and small.to_dict()["subsample"] is None and len(small.final.oof_mm) == 500


def test_cli_says_what_was_subsampled_and_progress_stays_on_stderr(tc_frame, tmp_path, capsys):
    robot, frame = tc_frame
    frame.to_csv(tmp_path / "train.csv", index=False)
    rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--folds", "3", "--cv-rows", "250",
               "--json", "-", "--progress"])
    assert rc == 0
    cap = capsys.readouterr()
    out = cap.out
    js, _ = json.JSONDecoder().raw_decode(out)  # the JSON document, then the printed summary
    assert js["subsample"]["cv_rows"] == 250 and js["subsample"]["rows"] == 500
    assert "subsample: cross-validation and effect selection on 250 of 500 training rows (seed 0)" in out
    assert "cross-validation (250 rows)" in cap.err and "fit/s" not in out and "\r" not in out
    stage = re.compile(r".+: ([\d,]+ \w+, )?\d+\.\d+ s")  # stderr is no terminal: a line per stage, no bar
    assert all(stage.fullmatch(line) for line in cap.err.splitlines()), cap.err
    # --no-progress: nothing on stderr
    rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--folds", "3", "--cv-rows", "250",
               "--no-progress"])
    assert rc == 0 and capsys.readouterr().err == ""


def test_cv_rows_too_small_is_one_error_line(tc_frame, tmp_path, capsys):
    robot, frame = tc_frame
    frame.to_csv(tmp_path / "train.csv", index=False)
    rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--cv-rows", "50"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("error:") and "--cv-rows" in err[0]


def test_fit_memory_grows_linearly_with_a_small_constant(case):
    robot, _, cal, _ = case
    rng = np.random.default_rng(0)
    lo, hi = np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi)
    peaks = {}
    for n in (5000, 20000):
        q = rng.uniform(lo, hi, (n, robot.n_joints))
        xyz = cal.geometric.predict(q) + rng.normal(0, 0.02, (n, 3))
        tracemalloc.start()
        fit_model(cal.geometric, q, xyz, chunk_rows=2000)
        peaks[n] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    per_row = (peaks[20000] - peaks[5000]) / 15000
    # data are allocated before; the fit holds residuals (P, 3) a few times over and one chunk's Jacobian:
    # stated bound 200 bytes per row (vs ~1,100 bytes per row for a full 3P x 40 Jacobian) ...
    assert per_row < 200, per_row
    # ... and the 5k-row peak is mostly the chunk (constant), so 4x the rows costs well under 4x the memory
    assert peaks[20000] < 2.5 * peaks[5000], peaks
