"""pytest plugin of ``bench_suite.py``: one JSON line per test (worker, node id, start and end on the clock and in the
process's CPU time) into ``$TOLALLOC_SUITE_TIMELINE/<worker>.jsonl``. Does nothing without that variable."""

from __future__ import annotations

import json
import os
import time

_OUT = os.environ.get("TOLALLOC_SUITE_TIMELINE")
_STARTED: dict = {}
_ACTIVE = [False]


def pytest_configure(config):
    """Record in the process that runs the tests: an xdist worker, or pytest itself without xdist (the xdist
    controller sees every worker's tests too, and would count them twice)."""
    controller = not hasattr(config, "workerinput") and bool(getattr(config.option, "numprocesses", None))
    _ACTIVE[0] = bool(_OUT) and not controller


def pytest_runtest_logstart(nodeid, location):
    if _ACTIVE[0]:
        _STARTED[nodeid] = (time.time(), time.process_time())


def pytest_runtest_logfinish(nodeid, location):
    if not _ACTIVE[0] or nodeid not in _STARTED:
        return
    start, cpu = _STARTED.pop(nodeid)
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    record = {"worker": worker, "nodeid": nodeid, "start": start, "end": time.time(), "cpu_start": cpu,
              "cpu_end": time.process_time()}
    with open(os.path.join(_OUT, f"{worker}.jsonl"), "a") as f:
        f.write(json.dumps(record) + "\n")
