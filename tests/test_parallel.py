"""Schedulers: ordered results, bounded look-ahead, Dask local schedulers and a loopback Dask cluster."""

import json
import threading
import time

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.cli import main
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import BLOCK_SIZE, run_mc
from tolalloc.montecarlo.parallel import check_scheduler, ordered_map

STATS = ("mean_mm", "std_mm", "cov_mm2", "norm_mm", "reach_mm", "angle_mean_rad", "angle_std_rad", "rotvec_std_rad",
         "dp_max_mm", "dp_min_mm", "angle_max_rad", "angle_min_rad")


def _square(shared, t):
    time.sleep(0.001 * ((7 * t) % 5))  # finish out of order
    return shared * t * t


@pytest.mark.parametrize("scheduler", [None, "local", "sync", "threads"])
def test_ordered_map_keeps_task_order(scheduler):
    if scheduler == "threads":
        pytest.importorskip("dask")
    out = list(ordered_map(_square, range(40), 2, scheduler=scheduler, n_jobs=3))
    assert out == [2 * t * t for t in range(40)]


def test_ordered_map_bounded_lookahead():
    pulled, lock = [], threading.Lock()

    def tasks():
        for t in range(100):
            with lock:
                pulled.append(t)
            yield t

    it = ordered_map(_square, tasks(), 1, n_jobs=2, window=5)
    first = next(it)
    assert first == 0 and len(pulled) <= 6  # never more than the window ahead of the consumer
    assert list(it) == [t * t for t in range(1, 100)]


@pytest.mark.parametrize("bad", ["gpu", "proccesses", 3, "127.0.0.1:8786"])
def test_bad_scheduler_raises(bad):
    with pytest.raises(TolallocError):
        check_scheduler(bad)
    model = build_error_model(load_robot("tool_changer"), "table2")
    with pytest.raises(TolallocError):
        run_mc(model, model.robot.q_nominal, 10, scheduler=bad)


def _assert_same(a, b):
    for f in STATS:
        assert np.array_equal(getattr(a, f), getattr(b, f)), f
    for d in ("p_within", "p_within_angle"):
        assert all(np.array_equal(getattr(a, d)[r], getattr(b, d)[r]) for r in getattr(a, d))
    assert np.array_equal(a.hist.counts, b.hist.counts) and np.array_equal(a.hist.outside, b.hist.outside)
    assert np.array_equal(a.samples["dp_mm"], b.samples["dp_mm"])


def test_loopback_dask_cluster_equals_local_run():
    distributed = pytest.importorskip("distributed")
    model = build_error_model(load_robot("tool_changer"), "table2", clearance=True)
    q = model.robot.poses("working")[:2]
    n = 3 * BLOCK_SIZE + 101
    kw = dict(radii_mm=(5.0, 20.0), angle_radii_rad=(0.01,), hist_bins=20, keep_samples=500)
    local = run_mc(model, q, n, seed=21, **kw)
    threads = run_mc(model, q, n, seed=21, scheduler="threads", n_jobs=2, chunk_size=1, **kw)
    _assert_same(local, threads)
    # spawned workers (the default), not forked: like a remote cluster they hold nothing of this process's state
    with distributed.LocalCluster(host="127.0.0.1", n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        remote = run_mc(model, q, n, seed=21, scheduler=cluster.scheduler_address, chunk_size=2 * BLOCK_SIZE, **kw)
        with distributed.Client(cluster) as client:
            via_client = run_mc(model, q, n, seed=21, scheduler=client, **kw)
    _assert_same(local, remote)
    _assert_same(local, via_client)
    assert not np.array_equal(local.mean_mm, run_mc(model, q, n, seed=22, **kw).mean_mm)


def test_unreachable_cluster_is_a_clear_error():
    pytest.importorskip("distributed")
    model = build_error_model(load_robot("tool_changer"), "table2")
    import dask

    with (dask.config.set({"distributed.comm.timeouts.connect": "0.5s"}),
          pytest.raises(TolallocError, match="could not connect")):
        run_mc(model, model.robot.q_nominal, 10, scheduler="tcp://127.0.0.1:9")


def test_cli_scheduler_flag_same_numbers(tmp_path):
    outs = []
    pytest.importorskip("dask")
    for extra in ([], ["--scheduler", "threads", "--jobs", "2", "--chunk-size", "1"]):
        js = tmp_path / f"mc{len(outs)}.json"
        assert main(["mc", "tool_changer", "--n", "70000", "--seed", "3", "--json", str(js), *extra]) == 0
        outs.append(json.loads(js.read_text()))
    assert outs[0] == outs[1]


def test_cli_bad_scheduler_exit_2(tmp_path, capsys):
    js = tmp_path / "x.json"
    assert main(["mc", "tool_changer", "--n", "10", "--scheduler", "gpu", "--json", str(js)]) == 2
    assert "scheduler" in capsys.readouterr().err and not js.exists()


def test_cli_histograms_written(tmp_path):
    out = tmp_path / "run"
    assert main(["mc", "tool_changer", "--n", "5000", "--hist-bins", "30", "--out", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"mc_density.png", "mc_hist.npz", "mc_summary.json"} <= names
    with np.load(out / "mc_hist.npz") as z:
        assert z["counts"].shape == (1, 3, 30, 30) and int(z["counts"][0, 0].sum() + z["outside"][0, 0]) == 5000
    assert (out / "mc_density.png").read_bytes()[:4] == b"\x89PNG"
