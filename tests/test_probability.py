"""P(|x| < r) for a 3-D Gaussian: closed forms, Monte Carlo, inverse, CasADi value and gradient."""

import casadi as ca
import numpy as np
import pytest
from scipy.stats import chi2, norm

from tolalloc import TolallocError
from tolalloc.linear.probability import angle_for_prob, chi2_3_cdf, p_within_angle, p_within_radius, radius_for_prob
from tolalloc.linear.probability_casadi import (casadi_rule_error, p_within_angle_casadi, p_within_radius_casadi,
                                                p_within_radius_lebedev)


def _rotation(rng):
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return Q


def _cov(Q, lam):
    return Q @ np.diag(lam) @ Q.T


SCALES = np.geomspace(1e-3, 1e4, 29)


def test_isotropic_is_chi2_3():
    s = SCALES
    cov = s[:, None, None] ** 2 * np.eye(3)
    P = p_within_radius(cov, 1.0)
    np.testing.assert_allclose(P, chi2.cdf(1 / s**2, 3), atol=1e-12, rtol=0)
    np.testing.assert_allclose(chi2_3_cdf([0.5, 2.0, 9.0]), chi2.cdf([0.5, 2.0, 9.0], 3), atol=1e-15)


def test_rank_one_is_two_sided_normal():
    rng = np.random.default_rng(3)
    Q = _rotation(rng)
    cov = np.array([_cov(Q, [s**2, 0, 0]) for s in SCALES])
    np.testing.assert_allclose(p_within_radius(cov, 1.0), 2 * norm.cdf(1 / SCALES) - 1, atol=1e-10, rtol=0)


def test_rank_two_isotropic_is_rayleigh():
    rng = np.random.default_rng(4)
    Q = _rotation(rng)
    cov = np.array([_cov(Q, [s**2, s**2, 0]) for s in SCALES])
    np.testing.assert_allclose(p_within_radius(cov, 1.0), 1 - np.exp(-1 / (2 * SCALES**2)), atol=1e-12, rtol=0)


def test_rank_two_anisotropic_is_marcum_like_1d_integral():
    # P(a z1^2 + b z2^2 < 1) = 1 - (1/pi) int_0^pi exp(-1 / (2 (a cos^2 + b sin^2))) dphi (trapezoid, periodic)
    phi = np.linspace(0, np.pi, 20001)[:-1]
    for a, b in [(1.0, 0.01), (0.3, 0.05), (4.0, 1e-4)]:
        ref = 1 - np.mean(np.exp(-1 / (2 * (a * np.cos(phi) ** 2 + b * np.sin(phi) ** 2))))
        assert abs(p_within_radius(np.diag([a, 0.0, b]), 1.0) - ref) < 1e-9


def test_nearly_isotropic_and_repeated_eigenvalues_are_continuous():
    base = p_within_radius(0.25 * np.eye(3), 0.9)
    for d in (1e-14, 1e-10, 1e-6):
        assert abs(p_within_radius(np.diag([0.25 + d, 0.25, 0.25 - d]), 0.9) - base) < 1e-9
    # l3 -> 0 continuity
    assert abs(p_within_radius(np.diag([0.3, 0.1, 1e-30]), 1.0) - p_within_radius(np.diag([0.3, 0.1, 0.0]), 1.0)) < 1e-12


def test_monte_carlo_random_covariances_1e7():
    """10^7 draws per covariance: |P - MC| < 4 standard errors (< 6.4e-4)."""
    rng = np.random.default_rng(20240501)
    z2 = np.square(rng.standard_normal((10_000_000, 3)).astype(np.float32))
    for _ in range(4):
        Q = _rotation(rng)
        lam = np.exp(rng.uniform(np.log(1e-4), np.log(2.0), 3))
        cov = _cov(Q, lam)
        # x = Q diag(sqrt(lam)) z has |x|^2 = sum lam_i z_i^2: the draws need no rotation, the function under test does
        mc = int(np.count_nonzero(z2 @ lam.astype(np.float32) < 1.0)) / len(z2)
        P = float(p_within_radius(cov, 1.0))
        se = np.sqrt(max(P * (1 - P), 1e-12) / len(z2))
        assert abs(P - mc) < 4 * se + 1e-6, (lam, P, mc)


def test_mean_shift_rank_one_closed_form_and_monte_carlo():
    e = np.array([0.0, 0.6, 0.8])
    s = 0.4
    for m in (np.array([0.1, 0, 0]), 0.3 * e, 0.5 * e + np.array([0.5, 0, 0]), 1.3 * e):
        mpar = m @ e
        rr = np.sqrt(max(1 - (m @ m - mpar**2), 0))
        ref = norm.cdf((rr - mpar) / s) - norm.cdf((-rr - mpar) / s)
        assert abs(p_within_radius(s**2 * np.outer(e, e), 1.0, m) - ref) < 1e-9
    rng = np.random.default_rng(7)
    z = rng.standard_normal((2_000_000, 3))
    for _ in range(3):
        Q = _rotation(rng)
        lam = np.exp(rng.uniform(np.log(1e-3), np.log(0.5), 3))
        m = rng.normal(size=3) * 0.4
        x = z @ (Q * np.sqrt(lam)).T + m
        mc = np.mean(np.einsum("ij,ij->i", x, x) < 1.0)
        P = float(p_within_radius(_cov(Q, lam), 1.0, m))
        assert abs(P - mc) < 4 * np.sqrt(P * (1 - P) / len(z)) + 1e-5
    # zero mean given explicitly takes the exact path
    C = np.diag([0.2, 0.1, 0.05])
    assert p_within_radius(C, 0.7, np.zeros(3)) == p_within_radius(C, 0.7)


def test_broadcasting_and_edge_values():
    covs = np.stack([np.diag([0.1, 0.2, 0.3]), np.zeros((3, 3))])
    P = p_within_radius(covs, np.array([[0.5], [1.0]]))
    assert P.shape == (2, 2)
    assert np.all(P[:, 1] == 1.0)  # zero covariance: always within r > 0
    assert p_within_radius(np.diag([0.1, 0.2, 0.3]), 0.0) == 0.0


def test_inverse_roundtrip():
    rng = np.random.default_rng(11)
    covs = np.array([_cov(_rotation(rng), np.exp(rng.uniform(-12, 2, 3))) for _ in range(50)])
    covs[0] = np.diag([1.0, 0, 0])
    for p in (0.5, 0.95, 0.9973):
        r = radius_for_prob(covs, p)
        np.testing.assert_allclose(p_within_radius(covs, r), p, atol=1e-10)
    assert abs(radius_for_prob(np.diag([4.0, 0, 0]), 0.95) - 2 * norm.ppf(0.975)) < 1e-9
    assert abs(radius_for_prob(np.eye(3), 0.9) - np.sqrt(chi2.ppf(0.9, 3))) < 1e-9
    m = np.array([0.2, 0.0, 0.1])
    r = radius_for_prob(np.diag([0.04, 0.02, 0.01]), 0.9, m)
    assert abs(p_within_radius(np.diag([0.04, 0.02, 0.01]), r, m) - 0.9) < 1e-8


def test_orientation_aliases():
    C = np.diag([1e-6, 4e-6, 0.0])
    assert p_within_angle(C, 0.002) == p_within_radius(C, 0.002)
    assert angle_for_prob(C, 0.9) == radius_for_prob(C, 0.9)
    assert abs(float(p_within_angle_casadi(C, 0.002)) - float(p_within_radius(C, 0.002))) < 1e-6


def test_bad_input():
    with pytest.raises(TolallocError, match="shape"):
        p_within_radius(np.eye(2), 1.0)
    with pytest.raises(TolallocError, match="positive semi-definite"):
        p_within_radius(np.diag([1.0, -1.0, 1.0]), 1.0)
    with pytest.raises(TolallocError, match="symmetric"):
        p_within_radius(np.array([[1.0, 0.5, 0], [0, 1, 0], [0, 0, 1]]), 1.0)
    with pytest.raises(TolallocError, match=">= 0"):
        p_within_radius(np.eye(3), -1.0)
    with pytest.raises(TolallocError, match="strictly between"):
        radius_for_prob(np.eye(3), 1.0)
    with pytest.raises(TolallocError, match="Lebedev order"):
        p_within_radius_casadi(np.eye(3), 1.0, order=4)


# ------------------------------------------------------------------ CasADi path
def _random_feasible_covs(rng, n, smax):
    out = []
    for i in range(n):
        lam = smax**2 * np.array([1.0, rng.uniform() ** 2, 0.0 if i % 3 == 0 else rng.uniform() ** 4])
        out.append(_cov(_rotation(rng), lam))
    return out


def test_casadi_value_equals_numpy():
    rng = np.random.default_rng(5)
    S = ca.SX.sym("S", 3, 3)
    f = ca.Function("f", [S], [p_within_radius_casadi(S, 0.25)])
    for C in _random_feasible_covs(rng, 20, 0.25):  # largest std <= r: documented error < 1e-6
        v = float(f(C))
        assert abs(v - float(p_within_radius(C, 0.25))) < 1e-6
        assert abs(v - float(p_within_radius_lebedev(C, 0.25))) < 1e-13  # same rule in numpy
    # documented error bound at 1.5 r is 5e-6
    for C in _random_feasible_covs(rng, 10, 1.5):
        assert abs(casadi_rule_error(C, 1.0)) < 5e-6
    # MX input and rank-deficient / zero covariance give finite values
    M = ca.MX.sym("M", 3, 3)
    g = ca.Function("g", [M], [p_within_radius_casadi(M, 1.0)])
    assert float(g(np.zeros((3, 3)))) == pytest.approx(1.0, abs=1e-14)
    assert float(g(np.diag([0.09, 0, 0]))) == pytest.approx(2 * norm.cdf(1 / 0.3) - 1, abs=1e-9)


def test_casadi_gradient_equals_finite_differences():
    rng = np.random.default_rng(6)
    x = ca.SX.sym("x", 6)  # unique entries of a symmetric matrix
    S = ca.vertcat(ca.horzcat(x[0], x[3], x[4]), ca.horzcat(x[3], x[1], x[5]), ca.horzcat(x[4], x[5], x[2]))
    r = ca.SX.sym("r")
    P = p_within_radius_casadi(S, r)
    fun = ca.Function("P", [x, r], [P, ca.gradient(P, ca.vertcat(x, r))])

    def vec(C):
        return np.array([C[0, 0], C[1, 1], C[2, 2], C[0, 1], C[0, 2], C[1, 2]])

    for C in _random_feasible_covs(rng, 6, 0.3):
        x0 = vec(C)
        for rr in (0.3, 0.5):
            _, g = fun(x0, rr)
            g = np.array(g).ravel()
            fd = []
            for i in range(7):
                h = 1e-6 * max(abs(np.r_[x0, rr][i]), 1e-3)
                e = np.zeros(7)
                e[i] = h
                z = np.r_[x0, rr]
                fd.append((float(fun(*(np.split(z + e, [6])))[0]) - float(fun(*(np.split(z - e, [6])))[0])) / (2 * h))
            np.testing.assert_allclose(g, fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())
        # dP/dr from CasADi equals the exact density of |x| from the numpy path
        P0, dP = fun(x0, 0.4)
        hr = 1e-6
        exact = (p_within_radius(C, 0.4 + hr) - p_within_radius(C, 0.4 - hr)) / (2 * hr)
        assert abs(float(np.array(dP).ravel()[-1]) - exact) < 1e-4 * max(exact, 1.0)


def test_casadi_works_inside_ipopt():
    """Smallest isotropic variance scaling s.t. P >= 0.95 equals the closed-form chi2_3 answer."""
    s2 = ca.MX.sym("s2")
    C = s2 * ca.DM(np.diag([1.0, 0.5, 0.1]))
    nlp = {"x": s2, "f": -s2, "g": p_within_radius_casadi(C, 0.25)}
    solver = ca.nlpsol("s", "ipopt", nlp, {"ipopt.print_level": 0, "print_time": False})
    sol = solver(x0=0.001, lbx=1e-8, ubx=1.0, lbg=0.95, ubg=1.0)
    s2_opt = float(sol["x"])
    assert abs(p_within_radius(s2_opt * np.diag([1.0, 0.5, 0.1]), 0.25) - 0.95) < 1e-6


def test_mean_isotropic_is_noncentral_chi2_and_rank_one_off_axis():
    """Means inside, on and outside the ball against noncentral chi-square closed forms (3 and 2 dof)."""
    from scipy.stats import ncx2

    for s in [0.05, 0.1, 0.3, 1.0, 4.0]:
        for mn in [0.4, 0.9, 1.0, 1.1, 2.5]:
            # ray rule (|mean| <= 0.75 r): < 1e-6; nested quadrature (beyond): ~1e-11
            P = p_within_radius(s * s * np.eye(3), 1.0, [0.0, mn, 0.0])
            assert abs(P - ncx2.cdf(1 / s**2, 3, mn**2 / s**2)) < (1e-6 if mn <= 0.75 else 1e-9)
            P2 = p_within_radius(s * s * np.diag([1.0, 1.0, 0.0]), 1.0, [mn / 2, mn / 2, 0.0])
            tol2 = 1e-6 if mn / np.sqrt(2) <= 0.75 else 1e-9
            assert abs(P2 - ncx2.cdf(1 / s**2, 2, mn**2 / (2 * s**2))) < tol2
    # rank one along x, mean (m, m_perp): r' = sqrt(r^2 - m_perp^2)
    s, m, mp = 0.4, 0.3, 0.6
    rp = np.sqrt(1 - mp**2)
    P = p_within_radius(np.diag([s * s, 0, 0]), 1.0, [m, mp, 0.0])
    assert abs(P - (norm.cdf((rp - m) / s) - norm.cdf((-rp - m) / s))) < 1e-9


def test_ray_rule_agrees_with_nested_quadrature_inside_its_range():
    """The fast ray rule is used only for |mean| <= 0.75 r: there it matches the exact nested rule to 1e-6."""
    from tolalloc.linear.probability_mean import RAY_RULE_MAX_MEAN, _p_mean_nested, _p_with_mean

    rng = np.random.default_rng(11)
    for _ in range(3):  # each exact reference takes seconds (nested adaptive quadrature)
        lam = np.sort(10 ** rng.uniform(-5, 0, 3))[::-1] * 0.4
        d = rng.normal(size=3)
        m = rng.uniform(0, RAY_RULE_MAX_MEAN) * d / np.linalg.norm(d)
        ray = float(_p_with_mean(lam[None], m[None], np.array([1.0]))[0])
        assert abs(ray - _p_mean_nested(lam, m, 1.0)) < 1e-6


def test_mean_on_and_outside_the_ball_anisotropic_monte_carlo():
    rng = np.random.default_rng(5)
    z = rng.standard_normal((1_000_000, 3))
    for lam, m in [((0.5, 0.05, 1e-4), (0.6, -0.5, 0.3)), ((0.3, 0.01, 1e-6), (1.0, 0.0, 0.0)),
                   ((0.2, 0.2, 0.001), (0.0, 0.9, 0.8))]:
        Q = _rotation(rng)
        lam, m = np.array(lam), np.array(m)
        x = z @ (Q * np.sqrt(lam)).T + m
        mc = np.mean(np.einsum("ij,ij->i", x, x) < 1.0)
        P = float(p_within_radius(_cov(Q, lam), 1.0, m))
        assert abs(P - mc) < 4 * np.sqrt(P * (1 - P) / len(z)) + 1e-6


def test_mean_inverse_roundtrip():
    cov = _cov(_rotation(np.random.default_rng(9)), [0.5, 0.05, 1e-4])
    mean = np.array([0.3, -0.2, 0.4])
    r = radius_for_prob(cov, 0.9, mean)
    assert abs(p_within_radius(cov, r, mean) - 0.9) < 1e-9
    # isotropic with a mean: the noncentral chi-square quantile
    from scipy.stats import ncx2

    r = radius_for_prob(0.09 * np.eye(3), 0.5, [0.0, 0.0, 0.5])
    np.testing.assert_allclose(r, 0.3 * np.sqrt(ncx2.ppf(0.5, 3, 0.25 / 0.09)), rtol=1e-8)


def test_full_rank_path_gives_the_numbers_of_the_guarded_path():
    """A stack of full-rank covariances takes the unguarded path; with one rank-deficient covariance appended the
    whole stack takes the guarded one: the full-rank rows (P and dP/dr) must be identical, bit for bit."""
    from tolalloc.linear.probability import _p_zero_mean

    rng = np.random.default_rng(3)
    lam = np.sort(rng.random((400, 3)) ** 3, axis=1)[:, ::-1] * 10.0 ** rng.uniform(-6, 1, (400, 1))
    r = rng.uniform(0.0, 3.0, 400) * np.sqrt(lam[:, 0])
    r[::9] = 1e-9 * np.sqrt(lam[::9, 2])  # erf(y)/y at tiny y
    fast = _p_zero_mean(lam, r, with_derivative=True)
    lam_g = np.vstack([lam, [[1.0, 0.5, 0.0]]])
    guarded = _p_zero_mean(lam_g, np.append(r, 0.5), with_derivative=True)
    assert np.all(lam[:, 2] > 0) and lam_g[-1, 2] == 0
    for a, b in zip(fast, guarded):
        assert np.array_equal(a, b[:-1])


def test_grazing_means_by_imhof_agree_with_monte_carlo_and_the_nested_rule():
    """Means many standard deviations from the centre, the ball's surface near them (a multi-directional accuracy's
    lost-motion offset): Imhof's integral against 10^6 draws, and against the nested quadrature at a moderate
    offset; p_within_radius takes it there. The ray rule's extended range (mean inside by >= 0.5 sd) agrees to 1e-7."""
    from tolalloc.linear.probability_mean import RAY_RULE_MIN_MARGIN, _p_mean_imhof, _p_mean_nested, _p_with_mean

    rng = np.random.default_rng(7)
    z = rng.standard_normal((1_000_000, 3))
    for lam, m, r in [((6.2e-5, 1e-6, 4e-8), (1e-4, 0.02, 0.1726), 0.1728),
                      ((2.5e-6, 2e-6, 1e-6), (0.18, 0.01, 0.0), 0.181),
                      ((1e-4, 3e-5, 1e-5), (0.05, -0.2, 0.1), 0.228)]:
        lam, m = np.array(lam), np.array(m)
        x = z * np.sqrt(lam) + m
        mc = np.mean(np.einsum("ij,ij->i", x, x) < r * r)
        P = _p_mean_imhof(lam, m, r)
        assert abs(P - mc) < 4 * np.sqrt(mc * (1 - mc) / len(z)) + 1e-6, (P, mc)
        assert abs(float(p_within_radius(np.diag(lam), r, m)) - P) < 1e-12
    lam, m = np.array([0.04, 0.01, 0.002]), np.array([0.6, 0.8, 0.0])       # 5 sd out
    assert abs(_p_mean_imhof(lam, m, 1.05) - _p_mean_nested(lam, m, 1.05)) < 1e-9
    for r in (1.0 + RAY_RULE_MIN_MARGIN * 0.2, 1.0 + 2 * 0.2):              # inside by >= the margin
        ray = float(_p_with_mean(lam[None], m[None], np.array([r]))[0])
        assert abs(ray - _p_mean_imhof(lam, m, r)) < 1e-7
    assert p_within_radius(np.diag(lam) / 16, 1.0 - 8 * 0.05, m) == 0.0     # the half-space bound is below 1e-13
    one = _p_mean_imhof(np.array([0.01, 0.0, 0.0]), np.array([0.3, 0.2, 0.0]), 0.5)   # one direction of spread:
    assert abs(one - (norm.cdf((np.sqrt(0.21) - 0.3) / 0.1) - norm.cdf((-np.sqrt(0.21) - 0.3) / 0.1))) < 1e-12
    m = m / 2                                                               # 2.5 sd out: Imhof's integral does
    assert np.isnan(_p_mean_imhof(lam, m, 0.55))                            # not converge, the nested rule serves
    assert float(p_within_radius(np.diag(lam), 0.55, m)) == _p_mean_nested(lam, m, 0.55)


def test_radius_with_a_grazing_mean_is_the_inverse():
    """radius_for_prob with a mean (bracketed by the half-space and the shifted-ball bounds) inverts P to 1e-9."""
    lam, m = np.array([6.2e-5, 1e-6, 4e-8]), np.array([1e-4, 0.02, 0.1726])
    for p in (0.5, 0.95, 0.9833):
        r = float(radius_for_prob(np.diag(lam), p, m))
        assert abs(float(p_within_radius(np.diag(lam), r, m)) - p) < 1e-9
        assert np.linalg.norm(m) < r < np.linalg.norm(m) + 4 * np.sqrt(lam.max())
