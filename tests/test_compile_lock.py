"""The lock around a process's first use of the numba kernels (:func:`tolalloc.engine.first_compile`)."""

from __future__ import annotations

import threading

import numpy as np

import tolalloc.engine as engine
from tolalloc.montecarlo.engines import numba_engine


def test_a_second_process_waits_for_the_first(tmp_path, monkeypatch):
    # two holders of the same module's lock never overlap (threads stand in for processes: flock is per open file)
    monkeypatch.setattr(engine.tempfile, "gettempdir", lambda: str(tmp_path))
    inside, overlaps = [], []

    def hold():
        with engine.first_compile("/some/module.py"):
            overlaps.append(len(inside))
            inside.append(1)
            threading.Event().wait(0.2)
            inside.pop()

    threads = [threading.Thread(target=hold) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert overlaps == [0, 0, 0]
    assert len(list(tmp_path.glob("tolalloc-numba-*.lock"))) == 1


def test_no_lock_possible_still_runs(tmp_path, monkeypatch):
    # a temporary folder that does not exist: the block runs without the lock instead of failing
    monkeypatch.setattr(engine.tempfile, "gettempdir", lambda: str(tmp_path / "missing"))
    ran = []
    with engine.first_compile("/some/module.py"):
        ran.append(True)
    assert ran == [True]


def test_kernels_called_from_threads_at_once_agree_with_numpy():
    # the first calls of both kernels from two threads at once: each waits its turn and returns numpy's draws
    numba_engine._READY.clear()
    outs = [np.empty((3, 5)) for _ in range(2)]

    def draw(k):
        numba_engine.fill_standard_normal(np.random.default_rng(7), outs[k])

    threads = [threading.Thread(target=draw, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    expected = np.random.default_rng(7).standard_normal((3, 5))
    assert np.array_equal(outs[0], expected) and np.array_equal(outs[1], expected)
    assert "fill_standard_normal" in numba_engine._READY
