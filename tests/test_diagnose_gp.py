"""The ARD Gaussian process of tolalloc.diagnose.gp against known answers: the analytic gradient against finite
differences, hyper-parameters recovered from data drawn from a GP with known length scales and noise (fixed
seed), the posterior mean against the textbook formula, the closed-form leave-one-out residuals against
refits without each row, and pure noise is called noise."""

import numpy as np
import pytest

import tolalloc.diagnose.gp as gp_mod
from tolalloc.diagnose.gp import _kernel, _nlml, fit_gp


def _draw(rng, P, ell, sf, sn, m=3):
    """Rows X (P, 2) and targets Y (P, m) from a zero-mean GP (plus offsets) with the given hyper-parameters."""
    X = rng.uniform(-1.0, 1.0, (P, 2)) * [1.0, 3.0]
    L = np.linalg.cholesky(_kernel(X, X, np.asarray(ell), sf) + 1e-8 * np.eye(P))
    return X, L @ rng.normal(size=(P, m)) + sn * rng.normal(size=(P, m)) + np.array([1.0, -2.0, 0.5])[:m]


def test_gradient_matches_finite_differences():
    rng = np.random.default_rng(0)
    X, Y = rng.normal(size=(40, 3)), rng.normal(size=(40, 2))
    theta = rng.normal(scale=0.3, size=5)
    f, g = _nlml(theta, X, Y)
    h = 1e-6
    fd = [(_nlml(theta + h * e, X, Y)[0] - _nlml(theta - h * e, X, Y)[0]) / (2 * h) for e in np.eye(5)]
    assert g == pytest.approx(fd, rel=1e-5, abs=1e-6)


def test_known_length_scales_and_noise_are_recovered():
    ell, sf, sn = np.array([0.3, 1.5]), 1.0, 0.1
    X, Y = _draw(np.random.default_rng(0), 400, ell, sf, sn)
    g = fit_gp(X, Y, seed=0)
    assert g.length_scales == pytest.approx(ell, rel=0.15)  # seed 0: 0.320, 1.59
    assert g.noise_sd == pytest.approx(sn, rel=0.1)  # seed 0: 0.102
    assert g.signal_sd == pytest.approx(sf, rel=0.3)  # 3 outputs of 400 rows pin sf only loosely
    assert g.neighbour_corr > 0.5


def test_posterior_mean_is_the_textbook_formula():
    rng = np.random.default_rng(1)
    X, Y = _draw(rng, 150, [0.5, 1.0], 0.8, 0.05)
    g = fit_gp(X, Y, seed=1, restarts=2)
    Xn = rng.uniform(-1.0, 1.0, (20, 2)) * [1.0, 3.0]
    ell, sf, sn = g.length_scales, g.signal_sd, g.noise_sd  # original units
    K = _kernel(X, X, ell, sf) + (sn ** 2 + 1e-8 * g.y_scale ** 2) * np.eye(len(X))
    mu = Y.mean(0) + _kernel(Xn, X, ell, sf) @ np.linalg.solve(K, Y - Y.mean(0))  # R&W eq. 2.25
    assert g.predict(Xn) == pytest.approx(mu, rel=1e-7, abs=1e-9)


def test_loo_residuals_equal_refits_without_each_row():
    rng = np.random.default_rng(2)
    X, Y = _draw(rng, 60, [0.5, 1.0], 0.8, 0.05)
    g = fit_gp(X, Y, seed=2, restarts=2)
    ell, sf, sn = g.length_scales, g.signal_sd, g.noise_sd
    for i in (0, 17, 59):
        keep = np.arange(len(X)) != i
        K = _kernel(X[keep], X[keep], ell, sf) + (sn ** 2 + 1e-8 * g.y_scale ** 2) * np.eye(keep.sum())
        mu_i = Y.mean(0) + _kernel(X[i:i + 1], X[keep], ell, sf) @ np.linalg.solve(K, Y[keep] - Y.mean(0))
        assert g.loo_residual[i] == pytest.approx(Y[i] - mu_i[0], rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("seed", [0, 1])
def test_pure_noise_is_called_noise(seed):
    rng = np.random.default_rng(seed)
    X, Y = rng.uniform(-np.pi, np.pi, (300, 3)), rng.normal(0.0, 0.03, (300, 3))
    g = fit_gp(X, Y, seed=seed)
    assert g.noise_sd == pytest.approx(0.03, rel=0.1)
    assert g.signal_sd < 0.3 * g.noise_sd


def test_hyper_parameters_fitted_on_a_seeded_subset_posterior_on_all_rows():
    X, Y = _draw(np.random.default_rng(3), 200, [0.5, 1.0], 0.8, 0.05)
    g = fit_gp(X, Y, max_fit=120, restarts=2, seed=3)
    assert g.n_fit == 120 and g.alpha.shape == (200, 3)
    assert fit_gp(X, Y, max_fit=120, restarts=2, seed=3).length_scales == pytest.approx(g.length_scales, rel=1e-12)


def test_bad_shapes_are_refused():
    with pytest.raises(ValueError, match="X must be"):
        fit_gp(np.zeros((5, 2)), np.zeros((4, 3)))


def test_an_unresolved_white_signal_is_moved_into_the_noise(monkeypatch):
    """Started only at length scales far below the row spacing, the optimum's 'signal' is white; the fit then
    reports all of the variance as noise and predicts the mean."""
    rng = np.random.default_rng(0)
    X, Y = rng.uniform(-np.pi, np.pi, (300, 3)), rng.normal(0.0, 0.03, (300, 3))
    monkeypatch.setattr(gp_mod, "_starts", lambda F, restarts, rng: [np.r_[np.full(F, np.log(0.03)), np.log(0.8),
                                                                           np.log(0.5)]])
    g = fit_gp(X, Y, restarts=1)
    assert g.neighbour_corr < gp_mod.RESOLVED_CORR
    assert g.noise_sd == pytest.approx(np.sqrt(np.mean((Y - Y.mean(0)) ** 2)), rel=0.02)
    assert g.predict(X[:5]) == pytest.approx(np.tile(Y.mean(0), (5, 1)), abs=1e-5)
