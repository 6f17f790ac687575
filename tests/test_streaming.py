"""Streaming statistics: merged moments, exact extras, fixed-range histograms, bounded memory, progress bar."""

import tracemalloc

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import BLOCK_SIZE, run_mc
from tolalloc.montecarlo.streaming import PLANES, Extras, HistSpec, Moments


@pytest.fixture(scope="module")
def model():
    return build_error_model(load_robot("tool_changer"), "table2")


def test_moments_merge_equals_direct():
    rng = np.random.default_rng(0)
    F = rng.normal(size=(4, 4)) @ rng.normal(3.0, 2.0, (4, 1000))
    acc = Moments()
    for a, b in [(0, 1), (1, 250), (250, 251), (251, 700), (700, 1000)]:
        acc.merge(Moments.of(F[:, a:b].copy()))
    assert acc.n == 1000
    assert np.allclose(acc.mean, F.mean(axis=1), rtol=0, atol=1e-12)
    assert np.allclose(acc.cov(), np.cov(F), rtol=1e-12)
    assert np.allclose(Moments().merge(acc).M2, acc.M2)  # merging into empty copies


def test_extras_merge_is_exact():
    a = Extras(np.array([1.0, 5.0]), np.array([0.0, -1.0]), np.array([3, 4]), np.ones((3, 2, 2), dtype=np.int64))
    b = Extras(np.array([2.0, 4.0]), np.array([-2.0, 0.0]), np.array([1, 1]), np.ones((3, 2, 2), dtype=np.int64))
    a.merge(b)
    assert a.mx.tolist() == [2.0, 5.0] and a.mn.tolist() == [-2.0, -1.0] and a.counts.tolist() == [4, 5]
    assert np.all(a.hist == 2)


def test_histspec_matches_histogram2d_with_overflow():
    rng = np.random.default_rng(1)
    dp = rng.normal(0, 1.0, (3, 5000))
    spec = HistSpec.symmetric(np.array([[2.0, 2.5, 3.0]]), 10)
    cells = np.empty((3, dp.shape[1]), dtype=np.intp)
    spec.cell_index(dp, 0, cells, np.empty(dp.shape[1]))
    H = spec.count(cells)
    assert H.sum() == 3 * 5000
    for k, (i, j, _) in enumerate(PLANES):
        ei = np.linspace(-[2.0, 2.5, 3.0][i], [2.0, 2.5, 3.0][i], 11)
        ej = np.linspace(-[2.0, 2.5, 3.0][j], [2.0, 2.5, 3.0][j], 11)
        ref, _, _ = np.histogram2d(dp[i], dp[j], bins=[ei, ej])
        assert np.array_equal(H[k, 1:-1, 1:-1], ref.astype(np.int64))
    with pytest.raises(TolallocError):
        HistSpec.symmetric(np.array([[1.0, 0.0, 1.0]]), 10)
    with pytest.raises(TolallocError):
        HistSpec.symmetric(np.array([[1.0, 1.0, 1.0]]), 1)


def test_run_mc_histogram_equals_histogram_of_all_samples(model):
    q = model.robot.q_nominal
    n = BLOCK_SIZE + 3000
    res = run_mc(model, q, n, seed=2, keep_samples=n, hist_bins=24, hist_range_mm=(0.3, 0.4, 0.5))
    h = res.hist
    dp = res.samples["dp_mm"]
    assert h.counts.shape == (1, 3, 24, 24) and h.n == n
    for k, (i, j, name) in enumerate(PLANES):
        ref, _, _ = np.histogram2d(dp[:, i], dp[:, j], bins=[h.edges_mm[0, i], h.edges_mm[0, j]])
        assert np.array_equal(h.counts[0, k], ref.astype(np.int64)), name
        inside = np.count_nonzero((np.abs(dp[:, i]) < [0.3, 0.4, 0.5][i]) & (np.abs(dp[:, j]) < [0.3, 0.4, 0.5][j]))
        assert h.outside[0, k] == n - inside
        area = np.diff(h.edges_mm[0, i])[0] * np.diff(h.edges_mm[0, j])[0]
        assert np.isclose(h.density(0, name).sum() * area, inside / n)
    df = h.to_frame()
    assert len(df) == 3 and np.all((df.fraction_outside >= 0) & (df.fraction_outside <= 1))


def test_default_histogram_window_holds_nearly_everything(model):
    res = run_mc(model, model.robot.poses("working")[:2], 20000, seed=0, hist_bins=40)
    # 6 linear standard deviations per axis: a Gaussian-like cloud leaves < 0.1 % outside
    assert np.all(res.hist.outside / res.n < 1e-3)
    assert res.hist.counts.shape == (2, 3, 40, 40)


def test_streamed_statistics_do_not_depend_on_chunks_or_threads(model):
    q = model.robot.poses("working")[:2]
    n = 3 * BLOCK_SIZE + 17
    kw = dict(radii_mm=(0.3,), angle_radii_rad=(0.003,), hist_bins=16)
    a = run_mc(model, q, n, seed=8, n_jobs=1, **kw)
    b = run_mc(model, q, n, seed=8, n_jobs=2, chunk_size=3 * BLOCK_SIZE, scheduler="sync", **kw)
    for f in ("mean_mm", "cov_mm2", "norm_mm", "reach_mm", "angle_mean_rad", "rotvec_std_rad", "dp_max_mm"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), f
    assert np.array_equal(a.hist.counts, b.hist.counts)
    assert np.array_equal(a.p_within_angle[0.003], b.p_within_angle[0.003])


def test_memory_is_bounded(model):
    """16 blocks of samples would need > 90 MB of features; streaming stays far below."""
    n = 16 * BLOCK_SIZE
    tracemalloc.start()
    try:
        res = run_mc(model, model.robot.q_nominal, n, seed=0, n_jobs=1, hist_bins=50)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert res.n == n and res.hist.counts.sum() + res.hist.outside.sum() == 3 * n
    assert peak < 40e6


def test_progress_bar(model, capsys):
    run_mc(model, model.robot.q_nominal, 2000, seed=0, progress=True)
    assert "Monte Carlo" in capsys.readouterr().err
    run_mc(model, model.robot.q_nominal, 2000, seed=0)  # short run, stderr not a terminal: silent
    assert capsys.readouterr().err == ""
