"""The test suite's own time, from a fresh state and warm, with a per-worker timeline (not a test).

    python benchmarks/bench_suite.py [--warm-only]

Runs the README's test command (``python -m pytest -q``, pyproject's ``-n auto``) twice in this checkout: first from a
fresh state (every ``__pycache__`` outside ``.venv``, ``.pytest_cache`` and ``.hypothesis`` removed, so numba's kernels
are compiled and the test modules rewritten again, as on a fresh clone), then warm. A small pytest plugin
(``suite_timeline.py`` beside this file) stamps each test's start and end, wall and CPU, per xdist worker. Printed:

* the wall time of each run and their ratio (fresh / warm: what a fresh clone adds), and the CPU time of the run's
  processes with the share of the cores it kept busy (near 100 %: only less work makes the suite faster),
* per worker: when its first test starts (collection), when its last one ends (the balance between workers), and the
  wall time its tests spent waiting on other processes (subprocesses, notebook kernels, a compile lock),
* the files with the most summed test time,
* the goal: 180 s for the fresh run on 2 cores (issue 41).

The machine may be shared: the load average before each run is printed; compare runs made in the same invocation.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
try:
    import resource  # POSIX: the CPU time of the suite's processes
except ImportError:  # pragma: no cover - Windows
    resource = None
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GOAL_S = 180.0


def _fresh_state() -> None:
    """Remove what a fresh clone lacks: compiled modules (numba's caches live beside them) and pytest's caches."""
    for d in ROOT.rglob("__pycache__"):
        if ".venv" not in d.parts:
            shutil.rmtree(d, ignore_errors=True)
    for name in (".pytest_cache", ".hypothesis"):
        shutil.rmtree(ROOT / name, ignore_errors=True)


def _run(label: str, fresh: bool) -> dict:
    if fresh:
        _fresh_state()
    out = Path(tempfile.mkdtemp(prefix="suite-timeline-"))
    env = {**os.environ, "TOLALLOC_SUITE_TIMELINE": str(out),
           "PYTHONPATH": os.pathsep.join([str(ROOT / "benchmarks"), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep)}
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    before = resource.getrusage(resource.RUSAGE_CHILDREN) if resource else None
    t0 = time.time()
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-rf", "-p", "suite_timeline"], cwd=ROOT, env=env,
                         capture_output=True, text=True)
    wall = time.time() - t0
    cpu = None
    if resource:
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = run.stdout.strip().splitlines()
    tail = "; ".join([*(x for x in lines if x.startswith("FAILED")), lines[-1]]) if lines else run.stderr.strip()[-200:]
    events = [json.loads(line) for f in sorted(out.glob("*.jsonl")) for line in f.read_text().splitlines()]
    shutil.rmtree(out, ignore_errors=True)
    return {"label": label, "wall_s": wall, "load": load, "result": tail, "events": events, "t0": t0,
            "returncode": run.returncode, "cpu_s": cpu}


def _workers(res: dict) -> list[str]:
    by = collections.defaultdict(list)
    for e in res["events"]:
        by[e["worker"]].append(e)
    lines = []
    for w, evs in sorted(by.items()):
        first = min(e["start"] for e in evs) - res["t0"]
        last = max(e["end"] for e in evs) - res["t0"]
        waiting = sum(max(0.0, (e["end"] - e["start"]) - (e["cpu_end"] - e["cpu_start"])) for e in evs)
        lines.append(f"  {w}: first test at {first:6.1f} s, last ends at {last:6.1f} s, {len(evs)} tests, "
                     f"{waiting:6.1f} s waiting on other processes")
    return lines


def _files(res: dict, n: int = 12) -> list[str]:
    per = collections.Counter()
    for e in res["events"]:
        per[e["nodeid"].split("::")[0]] += e["end"] - e["start"]
    return [f"  {t:6.1f} s  {f}" for f, t in per.most_common(n)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--warm-only", action="store_true", help="one warm run, no fresh state")
    args = ap.parse_args(argv)
    runs = [] if args.warm_only else [_run("fresh", True)]
    runs.append(_run("warm", False))
    for r in runs:
        print(f"{r['label']:5s} run: {r['wall_s']:6.1f} s wall (load average before: {r['load']:.2f}); {r['result']}")
        if r["cpu_s"] is not None:  # the suite is CPU-bound: its CPU over the cores is the wall it cannot go below
            cores = os.cpu_count() or 1
            print(f"  CPU of the run and its subprocesses: {r['cpu_s']:.1f} s, {r['cpu_s'] / (cores * r['wall_s']):.1%}"
                  f" of {cores} cores busy")
        print("\n".join(_workers(r)))
    if len(runs) == 2:
        fresh, warm = runs
        verdict = "within" if fresh["wall_s"] <= GOAL_S else "over"
        print(f"fresh / warm: {fresh['wall_s'] / warm['wall_s']:.3f}; fresh run {verdict} the {GOAL_S:.0f} s goal "
              f"by {abs(GOAL_S - fresh['wall_s']):.1f} s")
    print("files with the most test time (last run):")
    print("\n".join(_files(runs[-1])))
    return 0 if all(r["returncode"] == 0 for r in runs) else 1


if __name__ == "__main__":
    sys.exit(main())
