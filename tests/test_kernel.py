"""The optional numba Monte Carlo kernel against the numpy path (same draws), and the engine switch."""

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc import engine
from tolalloc.montecarlo.engines import numba_engine as kernel
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import BLOCK_SIZE, run_mc
from conftest import skew_robot


MOMENTS = ("mean_mm", "std_mm", "cov_mm2", "angle_mean_rad", "angle_std_rad", "rotvec_std_rad")
KW = dict(radii_mm=(0.05, 0.15, 0.3), angle_radii_rad=(0.002, 0.01), hist_bins=12, keep_samples=300)


@pytest.fixture(scope="module")
def robot():
    return load_robot("tool_changer")




def assert_same(a, b):
    """Moments to 1e-12 relative (absolute floor 1e-12 x the feature's spread); extrema to a few ulps of the
    tool position (dp = p' - p with |p| ~ 1e3 mm); counts and histogram counts exactly."""
    for f in MOMENTS:
        x, y = getattr(a, f), getattr(b, f)
        spread = np.max(np.abs(getattr(b, "std_mm" if f.endswith("mm") or f.startswith("cov") else "angle_std_rad")))
        scale = spread**2 if f.startswith("cov") else spread
        assert np.allclose(x, y, rtol=1e-12, atol=1e-12 * scale + 1e-300), f
    for f in ("norm_mm", "reach_mm"):
        x, y = getattr(a, f), getattr(b, f)
        assert np.allclose(x[:, :2], y[:, :2], rtol=1e-12, atol=1e-12 * np.max(y[:, 1]) + 1e-300), f
        assert np.allclose(x[:, 2:], y[:, 2:], rtol=0, atol=1e-11), f
    for f in ("dp_max_mm", "dp_min_mm"):
        assert np.allclose(getattr(a, f), getattr(b, f), rtol=0, atol=1e-11), f
    for f in ("angle_max_rad", "angle_min_rad"):
        assert np.allclose(getattr(a, f), getattr(b, f), rtol=0, atol=1e-14), f
    for d in ("p_within", "p_within_angle"):
        for r in getattr(b, d):
            assert np.array_equal(getattr(a, d)[r], getattr(b, d)[r]), (d, r)
    if b.hist is not None:
        assert np.array_equal(a.hist.counts, b.hist.counts) and np.array_equal(a.hist.outside, b.hist.outside)
    if b.samples is not None:
        for k in b.samples:
            assert np.allclose(a.samples[k], b.samples[k], rtol=0, atol=1e-11), k


CASES = [
    ("table2", {}),
    ("table2", {"link_mode": "axes_only"}),
    ("table2", {"deflection_mode": "tilt"}),
    ("table1", {"clearance": True}),
    ("table2", {"clearance": True, "link_mode": "axes_only", "deflection_mode": "tilt", "distribution": "uniform"}),
    ("table2", {"distribution": {"dl2": "truncnormal", "e2y": "uniform"}}),
    ("table2", {"sigma": {"dl3": 0.0, "dth2": 0.0, "e3z": 0.0}}),  # zero sigma: identity factors, non-contiguous normals
]


@pytest.mark.parametrize("sigma_set,opts", CASES)
def test_kernel_equals_numpy_path(robot, sigma_set, opts):
    m = build_error_model(robot, sigma_set, **opts)
    q = robot.poses("working")[[0, 4, 9]]
    n = BLOCK_SIZE + 3001  # a full and a partial block, sub-blocks of both sizes
    a = run_mc(m, q, n, seed=11, engine="numba", **KW)
    b = run_mc(m, q, n, seed=11, engine="numpy", **KW)
    assert_same(a, b)


def test_kernel_generic_axes_and_large_errors():
    """Non-axis-aligned joints (general rotation branch), errors of 0.1 rad, joint angles beyond pi/2."""
    r = skew_robot()
    m = build_error_model(r, "generic", clearance=True)
    m = m.with_sigma(m.sigma * 30)
    q = np.array([[0.4, -0.7, 30.0], [2.5, 1.9, -50.0]])
    kw = dict(radii_mm=(1.0, 5.0), angle_radii_rad=(0.05,), hist_bins=8, keep_samples=100)
    assert_same(run_mc(m, q, 20000, seed=3, engine="numba", **kw), run_mc(m, q, 20000, seed=3, engine="numpy", **kw))


def test_zero_sigma_and_same_seed(robot):
    m0 = build_error_model(robot, "table2").with_sigma(np.zeros(22))
    res = run_mc(m0, robot.poses("working")[:2], 5000, seed=1, radii_mm=(1e-9,), engine="numba")
    for arr in (res.mean_mm, res.std_mm, res.norm_mm, res.reach_mm, res.angle_std_rad, res.rotvec_std_rad):
        assert np.all(np.abs(arr) < 1e-9)
    assert np.all(res.p_within[1e-9][:, 0] == 1.0)
    m = build_error_model(robot, "table2")
    a = run_mc(m, robot.q_nominal, 3 * BLOCK_SIZE, seed=4, engine="numba", n_jobs=1)
    b = run_mc(m, robot.q_nominal, 3 * BLOCK_SIZE, seed=4, engine="numba", n_jobs=2, scheduler="sync")
    assert np.array_equal(a.cov_mm2, b.cov_mm2) and np.array_equal(a.dp_max_mm, b.dp_max_mm)


def test_rotation_near_pi_falls_back_to_numpy(robot):
    """Huge deflections give rotation errors near pi in every block: the kernel hands those blocks to numpy."""
    m = build_error_model(robot, "table2")
    sig = m.sigma.copy()
    sig[12:] = 3.0  # rad
    m = m.with_sigma(sig)
    a = run_mc(m, robot.q_nominal, 20000, seed=2, engine="numba", **KW)
    b = run_mc(m, robot.q_nominal, 20000, seed=2, engine="numpy", **KW)
    assert np.max(b.angle_max_rad) > 3.0
    for f in MOMENTS + ("norm_mm", "dp_max_mm", "angle_min_rad"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), f


@pytest.mark.parametrize("seed", [0, 7, 123456789])
def test_compiled_normals_equal_numpy(seed):
    out = np.empty((5, 3001))
    kernel.fill_standard_normal(np.random.default_rng(seed), out)
    assert np.array_equal(out, np.random.default_rng(seed).standard_normal((5, 3001)))
    g1, g2 = np.random.default_rng(seed), np.random.default_rng(seed)
    kernel.fill_standard_normal(g1, out)
    g2.standard_normal((5, 3001))
    assert g1.uniform() == g2.uniform()  # the generator state advanced identically


def test_sincos_atan2_accuracy():
    from tolalloc.montecarlo.engines._kernel_nb import _atan2, _sincos

    rng = np.random.default_rng(0)
    x = np.concatenate([rng.normal(0, 1e-3, 300), rng.uniform(-7, 7, 700), [0.0, -0.0, np.pi / 2, -np.pi, 1e-300]])
    sc = np.array([_sincos(v) for v in x])
    assert np.allclose(sc[:, 0], np.sin(x), rtol=2.3e-16, atol=2.3e-16)
    assert np.allclose(sc[:, 1], np.cos(x), rtol=2.3e-16, atol=2.3e-16)
    y, z = rng.normal(0, 1, 1000) * 10.0 ** rng.integers(-6, 3, 1000), rng.normal(0, 1, 1000)
    y = np.concatenate([y, [0.0, -0.0, 0.0, -0.0, 1.0, -1.0, 2.0]])
    z = np.concatenate([z, [1.0, 1.0, -1.0, -1.0, 0.0, 0.0, 2.0]])
    a = np.array([_atan2(u, v) for u, v in zip(y, z)])
    assert np.allclose(a, np.arctan2(y, z), rtol=4.5e-16, atol=1e-300)
    assert np.array_equal(np.signbit(a[-7:-3]), np.signbit(np.arctan2(y[-7:-3], z[-7:-3])))


def test_engine_switch(robot, monkeypatch):
    m = build_error_model(robot, "table2")
    assert engine.resolve_engine("numpy") == "numpy" and engine.resolve_engine(None) == "numba"
    monkeypatch.setenv("TOLALLOC_NUMBA", "0")
    assert engine.resolve_engine(None) == "numpy" and engine.resolve_engine("numba") == "numba"
    monkeypatch.delenv("TOLALLOC_NUMBA")
    with pytest.raises(TolallocError, match="engine"):
        engine.resolve_engine("fortran")
    b = run_mc(m, robot.q_nominal, 3000, seed=5, engine="numpy", **KW)
    monkeypatch.setattr(engine, "NUMBA_AVAILABLE", False)  # as if numba were not installed
    assert engine.resolve_engine(None) == "numpy"
    with pytest.raises(TolallocError, match="numba"):
        engine.resolve_engine("numba")
    a = run_mc(m, robot.q_nominal, 3000, seed=5, **KW)
    for f in MOMENTS + ("norm_mm", "dp_max_mm"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), f
