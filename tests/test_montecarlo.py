"""Nonlinear Monte Carlo: fast exact path vs the generic POE path, closed forms, reproducibility, statistics."""

import numpy as np
import pytest
from scipy import stats

from tolalloc import TolallocError, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.robot.lie import rot_x, rot_z
from tolalloc.montecarlo.run import (BLOCK_SIZE, generic_pose_errors, pose_errors, proportion_ci, run_mc,
                                 sample_values)
from conftest import skew_robot


@pytest.fixture(scope="module")
def robot():
    return load_robot("tool_changer")


@pytest.fixture(scope="module")
def model(robot):
    return build_error_model(robot, "table2")




@pytest.mark.parametrize("opts", [{}, {"link_mode": "axes_only"}, {"deflection_mode": "tilt"}, {"clearance": True},
                                  {"clearance": True, "link_mode": "axes_only", "deflection_mode": "tilt"}])
def test_fast_path_equals_generic_poe_path(robot, opts):
    m = build_error_model(robot, "table2", **opts)
    v = m.sample(400, np.random.default_rng(3)) * 30  # large errors: nonlinear regime
    q = robot.poses("working")[7]
    a, b = pose_errors(m, q, v), generic_pose_errors(m, q, v)
    for k in a:
        assert np.allclose(a[k], b[k], rtol=0, atol=1e-9), k


def test_fast_path_generic_axes():
    r = skew_robot()
    m = build_error_model(r, "generic", clearance=True)
    v = m.sample(300, np.random.default_rng(0)) * 200
    q = np.array([0.4, -0.7, 30.0])
    a, b = pose_errors(m, q, v), generic_pose_errors(m, q, v)
    for k in a:
        assert np.allclose(a[k], b[k], rtol=0, atol=1e-9), k


def test_zero_sigma_gives_zero_error(model, robot):
    m0 = model.with_sigma(np.zeros(len(model.params)))
    res = run_mc(m0, robot.poses("working")[:3], 1000, seed=1, radii_mm=(1e-9,))
    for arr in (res.mean_mm, res.std_mm, res.norm_mm, res.reach_mm, res.angle_std_rad, res.rotvec_std_rad):
        assert np.all(np.abs(arr) < 1e-9)
    assert np.all(res.p_within[1e-9][:, 0] == 1.0)


def test_single_link_error_closed_form(model, robot):
    q = robot.q_nominal
    k = model.index("dl3")
    v = np.zeros((1, len(model.params)))
    v[0, k] = 0.5
    dp = pose_errors(model, q, v)["dp_mm"][0]
    # consistent model: link 3 (after joints 1, 2) translates the rest of the chain along its rotated direction
    assert np.allclose(dp, 0.5 * rot_z(q[0]) @ rot_x(q[1]) @ [0, 1, 0], atol=1e-12)
    # drive error of joint 1 (axis z through the origin): the tool rotates rigidly about z
    v[:] = 0
    v[0, model.index("dth1")] = 0.01
    p = robot.fk_internal(q)[:3, 3]
    assert np.allclose(pose_errors(model, q, v)["dp_mm"][0], rot_z(0.01) @ p - p, atol=1e-10)


def test_axes_only_link_error_closed_form(robot):
    m = build_error_model(robot, "table2", link_mode="axes_only")
    q = robot.q_nominal
    v = np.zeros((1, len(m.params)))
    v[0, m.index("dl1")] = 0.7
    R = robot.fk_internal(q)[:3, :3]
    ez = np.array([0.0, 0.0, 1.0])
    # T' = Tr(d ez) E1..E6 Tr(-d ez) M  =>  dp = d (ez - R ez)
    assert np.allclose(pose_errors(m, q, v)["dp_mm"][0], 0.7 * (ez - R @ ez), atol=1e-12)


def test_paper_literal_options_change_what_they_should(robot):
    q = robot.q_nominal.copy()
    q[5] = 0.0  # joint 6 at zero
    q[1] = 0.0  # joint 2 at zero
    cons, axes = build_error_model(robot, "table2"), build_error_model(robot, "table2", link_mode="axes_only")
    v = np.zeros((1, len(cons.params)))
    v[0, cons.index("dl6")] = 0.3
    # axes-only: the last link only moves axis 6, on which the tool lies -> no error at q6 = 0
    assert np.linalg.norm(pose_errors(axes, q, v)["dp_mm"]) < 1e-12
    assert np.isclose(np.linalg.norm(pose_errors(cons, q, v)["dp_mm"]), 0.3)
    screw, tilt = cons, build_error_model(robot, "table2", deflection_mode="tilt")
    v[:] = 0
    v[0, screw.index("e2y")] = 0.004
    # a tilted axis turned by 0 leaves the chain unchanged; an error screw does not
    assert np.linalg.norm(pose_errors(tilt, q, v)["dp_mm"]) < 1e-12
    # the error screw (home-frame y axis through joint 2, carried by joint 1) turns the downstream chain
    c, pt, R1 = robot.joint_points_mm[1], robot.fk_internal(q)[:3, 3], rot_z(q[0])
    from tolalloc.robot.lie import rot_y
    assert np.allclose(pose_errors(screw, q, v)["dp_mm"][0], R1 @ (c + rot_y(0.004) @ (R1.T @ pt - c)) - pt, atol=1e-11)
    # both options leave drive errors untouched
    v[:] = 0
    v[0, screw.index("dth3")] = 0.003
    for m in (axes, tilt):
        assert np.allclose(pose_errors(m, q, v)["dp_mm"], pose_errors(cons, q, v)["dp_mm"], atol=1e-12)


def test_table1_table2_differ_only_in_link_and_drive_sigma(robot):
    t1, t2 = build_error_model(robot, "table1"), build_error_model(robot, "table2")
    assert t1.names == t2.names
    diff = {n for n, a, b in zip(t1.names, t1.sigma, t2.sigma) if a != b}
    assert diff == {f"dl{i}" for i in (1, 2, 4, 5, 6)} | {"dth1", "dth2", "dth3", "dd4", "dth5", "dth6"}
    assert np.isclose(t1.sigma[t1.index("dth5")], 0.0087) and np.isclose(t2.sigma[t2.index("dth5")], np.deg2rad(0.5))
    # Table 1's much larger revolute drive sigma (0.0087 rad = 0.5 deg vs 0.15-0.5 deg) raises the MC std
    q = robot.q_nominal
    s1 = run_mc(t1, q, 4000, seed=2).std_mm[0]
    s2 = run_mc(t2, q, 4000, seed=2).std_mm[0]
    assert np.all(s1 > s2)


def test_same_seed_same_numbers_and_chunk_independence(model, robot):
    q = robot.poses("working")[:2]
    n = 2 * BLOCK_SIZE + 123
    kw = dict(radii_mm=(10.0, 20.0), angle_radii_rad=(0.01,))
    a = run_mc(model, q, n, seed=5, chunk_size=BLOCK_SIZE, n_jobs=1, **kw)
    b = run_mc(model, q, n, seed=5, chunk_size=10 * BLOCK_SIZE, n_jobs=2, **kw)
    c = run_mc(model, q, n, seed=5, chunk_size=1, n_jobs=2, **kw)
    d = run_mc(model, q, n, seed=6, **kw)
    for f in ("mean_mm", "std_mm", "cov_mm2", "norm_mm", "reach_mm", "angle_std_rad", "rotvec_std_rad"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), f
        assert np.array_equal(getattr(a, f), getattr(c, f)), f
        assert not np.array_equal(getattr(a, f), getattr(d, f)), f
    assert all(np.array_equal(a.p_within[r], b.p_within[r]) for r in a.p_within)
    assert a.n == n


def test_moments_merge_matches_direct_computation(model, robot):
    q = robot.q_nominal
    n = BLOCK_SIZE + 5000
    res = run_mc(model, q, n, seed=9, keep_samples=n)
    s = res.samples
    assert s["dp_mm"].shape == (n, 3)
    assert np.allclose(res.mean_mm[0], s["dp_mm"].mean(0), atol=1e-10)
    assert np.allclose(res.cov_mm2[0], np.cov(s["dp_mm"].T), rtol=1e-10)
    assert np.allclose(res.norm_mm[0], [s["norm_mm"].mean(), s["norm_mm"].std(ddof=1), s["norm_mm"].max(), s["norm_mm"].min()])
    assert np.allclose(res.angle_std_rad[0], s["euler_rad"].std(0, ddof=1))
    k = np.count_nonzero(s["norm_mm"] < 10.0)
    res2 = run_mc(model, q, n, seed=9, radii_mm=(10.0,))
    assert res2.p_within[10.0][0, 0] == k / n


def test_mc_std_matches_linear_prediction(model, robot):
    """At the paper's sigma the chain is nearly linear: MC std within 3 % of sqrt(diag(J S J^T))."""
    q = robot.q_nominal
    n = 20000
    res = run_mc(model, q, n, seed=11)
    J = model.jacobian(q)
    cov = J @ np.diag(model.sigma**2) @ J.T
    sd_lin = np.sqrt(np.diag(cov))
    assert np.allclose(res.std_mm[0], sd_lin[:3], rtol=0.03)
    assert np.allclose(res.rotvec_std_rad[0], sd_lin[3:], rtol=0.03)
    # zero-mean inputs: mean within sampling noise plus a 1 % second-order bias allowance
    assert np.all(np.abs(res.mean_mm[0]) < 4 * sd_lin[:3] / np.sqrt(n) + 0.01 * sd_lin[:3])


def test_clearance_radial_is_not_gaussian(robot):
    m = build_error_model(robot, "table2", clearance=True, exclude=("link_length", "joint_drive", "axis_deflection"))
    V = sample_values(m, 200000, np.random.default_rng(0))
    x, y = V[m.index("cr2y")], V[m.index("cr2z")]
    # each component has sigma 0.5/sqrt(2) mm but kurtosis 3 * 3/8 / (1/2)^2 = 4.5, not the Gaussian 3
    assert np.isclose(x.std(), 0.5 / np.sqrt(2), rtol=0.01)
    assert np.isclose(stats.kurtosis(x, fisher=False), 4.5, atol=0.15)
    # the radius |s| is half-normal (sigma 0.5 mm), not the Rayleigh law of two independent Gaussians
    r = np.hypot(x, y)
    assert stats.kstest(r, stats.halfnorm(scale=0.5).cdf).pvalue > 1e-3
    assert stats.kstest(r, stats.rayleigh(scale=0.5 / np.sqrt(2)).cdf).pvalue < 1e-6
    # through the chain: only the joint-6 radial clearance -> tool error component is non-Gaussian too
    m6 = build_error_model(robot, "table2", clearance=True, sigma={"clearance_axial": 0, "clearance_tilt": 0},
                           exclude=("link_length", "joint_drive", "axis_deflection", "cr1x", "cr1y", "cr2y", "cr2z",
                                    "cr3y", "cr3z", "cr5y", "cr5z"))
    res = run_mc(m6, robot.q_nominal, 50000, seed=1, keep_samples=50000)
    assert stats.kurtosis(res.samples["dp_mm"][:, 0], fisher=False) > 4.0


def test_sample_values_stream_rederived_by_hand(robot):
    """The documented stream, rebuilt with numpy's generator directly: all non-zero-sigma normal rows in one
    ``standard_normal`` call, then the others in parameter order (ring pairs: ``s ~ N(0, 2 sigma^2)`` then
    ``t ~ U(0, 2 pi)``). Identical numbers, exactly."""
    m = build_error_model(robot, "table2", clearance=True, distribution={"link_length": "uniform", "dd4": "truncnormal"},
                          sigma={"dth3": 0.0})
    n = 1000
    got = sample_values(m, n, np.random.default_rng(1))
    rng = np.random.default_rng(1)
    dist = [p.distribution for p in m.params]
    sig = np.array([p.sigma for p in m.params])
    want = np.zeros((len(dist), n))
    normal = [k for k, d in enumerate(dist) if d == "normal" and sig[k] > 0]
    want[normal] = sig[normal, None] * rng.standard_normal((len(normal), n))
    done = set(normal)
    for k, d in enumerate(dist):
        if k in done or sig[k] == 0:
            continue
        if d == "uniform":
            want[k] = rng.uniform(-np.sqrt(3) * sig[k], np.sqrt(3) * sig[k], n)
        elif d == "truncnormal":
            want[k] = stats.truncnorm.rvs(-3, 3, scale=sig[k], size=n, random_state=rng)
        elif d == "ring":
            k2 = next(i for i, p in enumerate(m.params) if p.group == m.params[k].group and i != k)
            r, t = rng.standard_normal(n) * (np.sqrt(2) * sig[k]), rng.uniform(0, 2 * np.pi, n)
            want[k], want[k2] = r * np.cos(t), r * np.sin(t)
            done.add(k2)
    assert m.params[m.index("dth3")].distribution == "normal" and not np.any(got[m.index("dth3")])
    assert np.array_equal(got, want)
    assert np.array_equal(m.sample(n, np.random.default_rng(1)), want.T)


def test_sample_values_distributions_ks(robot):
    """Each distribution against its law (Kolmogorov-Smirnov, 20 000 draws, seed 3; each p-value > 1e-3):
    normal N(0, sigma^2), uniform on +-sqrt(3) sigma, normal truncated at +-3 sigma, ring pair with half-normal
    radius (scale sqrt(2) sigma) and uniform angle."""
    m = build_error_model(robot, "table2", clearance=True, distribution={"link_length": "uniform", "dd4": "truncnormal"})
    V = sample_values(m, 20000, np.random.default_rng(3))
    laws = {"normal": lambda s: stats.norm(scale=s), "uniform": lambda s: stats.uniform(-np.sqrt(3) * s, 2 * np.sqrt(3) * s),
            "truncnormal": lambda s: stats.truncnorm(-3, 3, scale=s)}
    seen = set()
    for k, p in enumerate(m.params):
        seen.add(p.distribution)
        if p.distribution in laws:
            assert stats.kstest(V[k], laws[p.distribution](p.sigma).cdf).pvalue > 1e-3, p.name
        elif p.name.endswith(("x", "y")) and p.distribution == "ring" and m.params[k + 1].group == p.group:
            x, y = V[k], V[k + 1]
            assert stats.kstest(np.hypot(x, y), stats.halfnorm(scale=np.sqrt(2) * p.sigma).cdf).pvalue > 1e-3, p.name
            assert stats.kstest(np.arctan2(y, x), stats.uniform(-np.pi, 2 * np.pi).cdf).pvalue > 1e-3, p.name
    assert seen == {"normal", "uniform", "truncnormal", "ring"}


def test_proportion_ci_matches_scipy():
    for k, n in [(0, 50), (13, 50), (500, 1000), (1000, 1000)]:
        p, lo, hi = proportion_ci(k, n, "wilson")
        ref = stats.binomtest(k, n).proportion_ci(0.95, method="wilson")
        assert np.isclose(lo, ref.low) and np.isclose(hi, ref.high) and p == k / n
        p, lo, hi = proportion_ci(k, n, "exact")
        ref = stats.binomtest(k, n).proportion_ci(0.95, method="exact")
        assert np.isclose(lo, ref.low) and np.isclose(hi, ref.high)


def test_to_frame_table3_layout(model, robot):
    res = run_mc(model, robot.poses("working")[:2], 500, seed=0)
    df = res.to_frame()
    assert list(df.columns) == ["pose", "quantity", "unit", "mean_mm", "std_mm", "max_mm", "min_mm", "mean_deg",
                                "std_deg", "max_deg", "min_deg"]
    assert len(df) == 2 * 8
    row = df[(df.pose == 2) & (df.quantity == "dy")].iloc[0]  # tables number poses from 1
    assert row["unit"] == "mm" and np.isnan(row["std_deg"])
    assert row["std_mm"] == res.std_mm[1, 1] and row["max_mm"] == res.dp_max_mm[1, 1]
    ang = df[(df.pose == 1) & (df.quantity == "dbeta")].iloc[0]  # angles in deg, never in a mm column
    assert ang["unit"] == "deg" and np.isnan(ang["std_mm"])
    assert ang["std_deg"] == pytest.approx(np.rad2deg(res.angle_std_rad[0, 1]), rel=1e-12)
    assert res.labels["clearance"] is False and res.labels["sigma_set"] == "table2"


@pytest.mark.parametrize("call", [
    lambda m, r: run_mc(m, r.q_nominal, 0),
    lambda m, r: run_mc(m, r.q_nominal, 2.5),
    lambda m, r: run_mc(m, np.array([0, 0, 0, 0, 0, 4.0]), 10),  # joint 6 outside +-180 deg
    lambda m, r: run_mc(m, r.q_nominal, 10, radii_mm=(-1.0,)),
    lambda m, r: run_mc(m, r.q_nominal, 10, ci="bayes"),
    lambda m, r: pose_errors(m, r.q_nominal, np.zeros((3, 5))),
    lambda m, r: pose_errors(m, r.q_nominal, np.full((1, len(m.params)), np.nan)),
    lambda m, r: m.with_sigma(-np.ones(len(m.params))),
    lambda m, r: build_error_model(r, "table9"),
    lambda m, r: build_error_model(r, "table2", sigma={"dl1": np.inf}),
    lambda m, r: build_error_model(r, "table2", sigma={"dl99": 1.0}),
])
def test_bad_input_raises(model, robot, call):
    with pytest.raises(TolallocError):
        call(model, robot)


@pytest.mark.parametrize("k, n, level", [(12, 10, 0.95), (-1, 10, 0.95), (3, 0, 0.95), (np.nan, 10, 0.95),
                                         (5, 10, 1.5), (5, 10, 0.0)])
def test_proportion_ci_refuses_counts_and_levels_that_are_not_a_proportion(k, n, level):
    # regression: k > n gave NaN bounds and a RuntimeWarning
    with pytest.raises(TolallocError, match=r"^(k, n: expected 0 <= k <= n|level: expected a confidence level)"):
        proportion_ci(k, n, "wilson", level)
    assert proportion_ci(np.array([0, 10]), 10).shape == (2, 3)
