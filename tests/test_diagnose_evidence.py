"""Fitted prior scales (diagnose/evidence.py), the transmission's harmonic series chosen by them, and their refit
within every cross-validation fold (diagnose/select.py).

Known answers: the log marginal likelihood of a Gaussian linear model is the log density of ``y`` under
``N(0, sigma^2 I + Phi S Phi^T)`` (scipy.stats.multivariate_normal, an independent formula); the fitted scales of
data drawn from the model itself come back within a stated tolerance (seeded)."""

import numpy as np
import pytest
from scipy.stats import multivariate_normal

import tolalloc
from tolalloc.diagnose import synth
from tolalloc.diagnose.choice import choose_variant, prior_weights
from tolalloc.diagnose.effects import effect_bases, target_points, variants
from tolalloc.diagnose.evidence import ard_evidence
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.calibrate import calibrate, fixed_jacobian, initial_fit
from tolalloc.diagnose.measurements import measurements_from_frame
from tolalloc.diagnose.scores import clip_level, paired_pvalue
from tolalloc.diagnose.select import evaluate, make_context
from tolalloc.diagnose.geometry import build_geometry_model


def test_log_ml_is_the_gaussian_density_and_scales_come_back():
    rng = np.random.default_rng(0)
    n, groups = 300, np.repeat([0, 1, 2], [6, 6, 6])
    Phi = rng.normal(size=(n, 18))
    beta = rng.normal(size=18) * np.array([0.5, 0.05, 2.0])[groups]
    y = Phi @ beta + rng.normal(0, 0.3, n)
    ev = ard_evidence(Phi, y, groups)
    C = ev.noise_sd ** 2 * np.eye(n) + (Phi * ev.sd ** 2) @ Phi.T
    assert ev.log_ml == pytest.approx(multivariate_normal(np.zeros(n), C).logpdf(y), rel=1e-9)
    assert ev.noise_sd == pytest.approx(0.3, rel=0.15)  # 300 rows: ~4 % sd of the estimate
    # a group's fitted scale is the RMS of its coefficients as the data determine them (well determined here:
    # 300 rows, noise 0.3): within 30 % of the RMS of the coefficients actually drawn
    for g in range(3):
        drawn = np.sqrt(np.mean(beta[groups == g] ** 2))
        assert ev.sd[groups == g][0] == pytest.approx(drawn, rel=0.3), (g, drawn)


def test_noise_only_columns_are_shrunk_to_nothing():
    rng = np.random.default_rng(1)
    Phi = rng.normal(size=(300, 12))
    y = rng.normal(0, 0.1, 300)
    ev = ard_evidence(Phi, y, np.zeros(12, int))
    assert ev.dof < 1.0 and np.abs(ev.mean).max() < 0.01


def _harmonic_case(orders, amp, seed, P=120):
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (P, 6))
    t = np.array([0.0, 0.0, 100.0])
    dq = np.zeros_like(q)
    for k in orders:  # joint 2: an error with every order in ``orders`` (exact kinematics, not the basis)
        dq[:, 1] += amp * np.sin(k * q[:, 1] + 0.7 * k)
    d = target_points(robot, q + dq, t) - target_points(robot, q, t) + rng.normal(0, 0.01, (P, 3))
    model = build_geometry_model(robot)
    xyz = target_points(robot, q, t)
    from dataclasses import replace
    fit = replace(initial_fit(model, q, xyz), R=np.eye(3), p_mm=np.zeros(3), t_mm=t, residual_mm=d)
    meas = Measurements(q, xyz + d)
    return robot, meas, fit, fixed_jacobian(fit, q, xyz + d), t


def test_series_variant_chosen_by_evidence_for_a_many_order_error():
    robot, meas, fit, J, t = _harmonic_case(range(1, 11), 2e-5, seed=2)
    names = variants("transmission", meas, {}, robot)
    assert "series12" in names and "series24" not in names  # 120 poses: 2 K 6 <= 2 P for K <= 20
    best = choose_variant(effect_bases("transmission", robot, meas, t, {}, names), fit, J)
    assert best.variant == "series12" and best.prior_w is not None and len(best.prior_w) == best.B.shape[-1]
    # the ridge holds the other joints' columns far more strongly than joint 2's
    w = best.prior_w
    assert np.median(w[best.groups == 1]) < 0.1 * np.median(w[best.groups == 4])


def test_once_per_revolution_error_keeps_a_low_order_variant():
    robot, meas, fit, J, t = _harmonic_case([1], 5e-5, seed=3)
    names = variants("transmission", meas, {}, robot)
    best = choose_variant(effect_bases("transmission", robot, meas, t, {}, names), fit, J)
    assert best.variant in ("1x", "1x2x")


def test_prior_weights_on_all_poses_are_the_variant_choice_s():
    robot, meas, fit, J, t = _harmonic_case([1], 5e-5, seed=3)
    best = choose_variant(effect_bases("transmission", robot, meas, t, {}, ("1x",)), fit, J)
    assert prior_weights(best, fit, J, fit.residual_mm) == pytest.approx(best.prior_w, rel=1e-9)


@pytest.mark.parametrize("seed", [1, 4])
def test_fold_fits_refit_the_prior_scales_so_noise_is_not_an_effect(seed):
    # noise-only data (geometric errors and tracker noise, no effect): the series must not beat the geometric
    # model out of fold. Fold fits that borrowed the ridge fitted on every training pose (held-out blocks
    # included) had seen the held-out noise and did, with Wilcoxon p ~ 0.005 on these seeds; a null p-value is
    # uniform (median 0.5).
    robot = tolalloc.load_robot("ur10")
    case = synth.generate(robot, "none", 90, np.random.default_rng(seed))
    m = measurements_from_frame(case.frame, robot, "train")
    ctx = make_context(calibrate(robot, m), m, folds=3)
    geo, trans = evaluate(ctx), evaluate(ctx, ("transmission",))
    clip = clip_level(geo.selection_mm)
    assert paired_pvalue(geo.selection_stack, trans.selection_stack, clip) > 0.05


def test_fold_weights_are_kept_per_basis_and_fold():
    """The ridge weights of a fold (select._fold_prior_w) are those of prior_weights on the fold's poses, computed once
    per (effect basis, fold) and reused by later models; a context copied with another basis for the effect (as the
    step check makes one) gets that basis's weights, not the kept ones."""
    import copy
    from dataclasses import replace

    from tolalloc.diagnose.select import _fold_prior_w

    robot = tolalloc.load_robot("ur10")
    case = synth.generate(robot, "none", 90, np.random.default_rng(1))
    m = measurements_from_frame(case.frame, robot, "train")
    ctx = make_context(calibrate(robot, m), m, folds=3)
    ridged = [e for e, b in ctx.bases.items() if getattr(b, "prior_w", None) is not None]
    assert ridged
    e = ridged[0]
    P = m.n_poses

    def direct(basis, rows):
        J = ctx.J_fixed.reshape(P, 3, -1)[rows].reshape(3 * len(rows), -1)
        return prior_weights(replace(basis, B=basis.B[rows]), ctx.cal.geometric, J, ctx.geo_residual[rows])

    b = ctx.bases[e]
    keep = np.arange(b.B.shape[-1])
    for f in ctx.folds:
        rows = np.setdiff1d(np.arange(P), f)
        want = direct(b, rows)
        got = _fold_prior_w(ctx, (e,), keep, rows)
        np.testing.assert_allclose(got if got is not None else np.zeros_like(want), want, rtol=0, atol=0)
        n_kept = len(ctx.fold_weights)
        again = _fold_prior_w(ctx, (e,), keep, rows)
        assert len(ctx.fold_weights) == n_kept and (again is None) == (got is None)
        if got is not None:
            np.testing.assert_array_equal(again, got)
    alt = copy.copy(ctx)
    alt.bases = {**ctx.bases, e: replace(b, B=2.0 * b.B)}
    rows = np.setdiff1d(np.arange(P), ctx.folds[0])
    want = direct(alt.bases[e], rows)
    got = _fold_prior_w(alt, (e,), keep, rows)
    np.testing.assert_allclose(got if got is not None else np.zeros_like(want), want, rtol=0, atol=0)
    assert not np.allclose(want, direct(b, rows))
