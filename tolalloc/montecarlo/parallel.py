"""Where independent tasks run: local threads (default), Dask's local schedulers, or a Dask cluster.

:func:`ordered_map` runs ``fn(shared, task)`` for every task and yields the results **in task order**
with a bounded number of tasks in flight (bounded memory whatever the number of tasks). Callers that
merge results in that order get the same numbers whatever the scheduler.

Schedulers
----------
``None`` or ``"local"``
    A thread pool in this process (numpy releases the GIL in its array loops).
``"sync"``
    One task after the other in this thread (debugging).
``"threads"``, ``"processes"``
    Dask's local threaded / multiprocessing schedulers (``dask`` installed).
``"tcp://HOST:PORT"`` (any ``scheme://`` address), or a ``distributed.Client``
    A Dask distributed cluster: ``shared`` is scattered once to every worker, tasks are submitted as
    futures. Start one with ``dask scheduler`` on one machine and ``dask worker tcp://HOST:8786`` on
    each of the others (every worker needs ``tolalloc`` importable, same version).
``"distributed"``
    The Dask client already active in this process (``distributed.get_client()``).
"""

from __future__ import annotations

import os
from collections import deque
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Callable, Iterable, Iterator

from tolalloc.exceptions import TolallocError

__all__ = ["ordered_map", "check_scheduler", "default_jobs", "LOCAL_SCHEDULERS"]

LOCAL_SCHEDULERS = ("local", "sync", "threads", "processes", "distributed")


def default_jobs() -> int:
    """Default local worker threads: the CPUs this process may use, at most 8."""
    try:
        n = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        n = os.cpu_count() or 1
    return max(1, min(n, 8))


def check_scheduler(scheduler) -> Any:
    """Validate a scheduler argument (see the module docstring); returns it unchanged."""
    if scheduler is None or scheduler in LOCAL_SCHEDULERS:
        return scheduler
    if isinstance(scheduler, str) and "://" in scheduler:
        return scheduler
    if type(scheduler).__name__ == "Client" and hasattr(scheduler, "submit"):
        return scheduler
    raise TolallocError(f"scheduler: expected None, 'local', 'sync', 'threads', 'processes', 'distributed', a "
                        f"Dask scheduler address such as 'tcp://10.0.0.5:8786' or a distributed.Client; got {scheduler!r}.")


def _need(module: str):
    try:
        return __import__(module)
    except ImportError:
        raise TolallocError(f"scheduler: this scheduler needs the '{module}' package; install it with "
                            f"pip install 'dask[distributed]' (or use the default local scheduler).") from None


def ordered_map(fn: Callable, tasks: Iterable, shared: Any = None, *, scheduler=None, n_jobs: int | None = None,
                window: int | None = None) -> Iterator:
    """Yield ``fn(shared, task)`` for each task, in task order.

    Parameters
    ----------
    fn : callable
        A module-level function (it is pickled for process and cluster schedulers).
    tasks : iterable
        Task descriptions (small, picklable).
    shared : object
        Read-only data every task needs (sent once per worker on a cluster).
    scheduler : see the module docstring
    n_jobs : int, optional
        Local threads (``None``/``"local"``) or Dask local workers; default :func:`default_jobs`.
    window : int, optional
        Tasks in flight at most (default: 4 per local job, 4 per cluster thread).
    """
    scheduler = check_scheduler(scheduler)
    jobs = max(1, int(n_jobs or default_jobs()))
    if scheduler == "sync":
        for t in tasks:
            yield fn(shared, t)
        return
    if scheduler is None or scheduler == "local":
        if jobs == 1:
            for t in tasks:
                yield fn(shared, t)
            return
        win = window or 4 * jobs
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            yield from _windowed((pool.submit(fn, shared, t) for t in tasks), win, lambda f: f.result())
        return
    if scheduler in ("threads", "processes"):
        dask = _need("dask")
        win = window or 4 * jobs
        batch: list = []
        it = iter(tasks)
        while True:
            batch = [t for _, t in zip(range(win), it)]
            if not batch:
                return
            delayed = [dask.delayed(fn, pure=True)(shared, t) for t in batch]
            yield from dask.compute(*delayed, scheduler=scheduler, num_workers=jobs)
    _need("distributed")
    from distributed import Client, get_client

    own = False
    if scheduler == "distributed":
        client = get_client()
    elif isinstance(scheduler, str):
        try:
            client = Client(scheduler, set_as_default=False)
        except (OSError, TimeoutError) as exc:
            raise TolallocError(f"scheduler: could not connect to the Dask scheduler at {scheduler!r} ({exc}); "
                                "start one with 'dask scheduler' and workers with 'dask worker ADDRESS'.") from None
        own = True
    else:
        client = scheduler
    try:
        threads = sum(client.nthreads().values()) or 1
        win = window or 4 * threads
        shared_f = client.scatter(shared, broadcast=True, hash=False) if shared is not None else None
        futs = (client.submit(fn, shared_f, t, pure=False) for t in tasks)
        yield from _windowed(futs, win, lambda f: f.result())
    finally:
        if own:
            client.close()


def _windowed(futures: Iterator, window: int, get: Callable) -> Iterator:
    """Keep at most ``window`` futures pending; yield their results in submission order."""
    q: deque = deque()
    try:
        for f in futures:
            q.append(f)
            if len(q) >= window:
                yield get(q.popleft())
        while q:
            yield get(q.popleft())
    finally:
        for f in q:
            f.cancel()
