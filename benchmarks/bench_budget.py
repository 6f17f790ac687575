"""The throughput figures of :mod:`tolalloc.budget`: measured here, beside the estimate the module makes (not a test).

    nice python benchmarks/bench_budget.py [--quick]

For every kind of work in ``tolalloc.budget.WORK`` one run of known size is timed on one thread (tool_changer, its
default error model), and the table prints

* ``measured_s_per_unit``: its time over its units,
* ``probe_units``: that over the probe workload's time in the same run (:func:`tolalloc.budget.probe_seconds`):
  the figure ``WORK`` states (update it from here when a kernel changes),
* ``estimate_s`` and ``measured / estimate``: what :func:`tolalloc.budget.estimate_seconds` predicts for the run
  with the stated figures, and the ratio of the measured time to it (1 = exact; the budget aims at a factor of 2).

The machine may be shared: the load average is printed, and the probe (timed in the same run) carries the load into
the estimate.

``--flags`` times instead every count flag of the command line given a count far too large (refused) or large but
within the budget (started with its estimate: the ``warning:`` line), in a fresh process each: the seconds until the
refusal or the estimate, and what the command said (the goal: within 5 s, imports included).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
import pandas as pd

import tolalloc
from tolalloc import budget
from tolalloc.errormodel import build_error_model


def runs(quick: bool) -> dict:
    """Kind -> (function running the work, units of work, scale of a unit)."""
    from tolalloc.allocate import allocate, build_problem
    from tolalloc.calibration.design_worst import random_plan_worst_p
    from tolalloc.allocate.region import box_region
    from tolalloc.allocate.region_coverage import coverage
    from tolalloc.calibration.design import candidate_poses
    from tolalloc.calibration.split import split_errors
    from tolalloc.montecarlo.importance import importance_probability
    from tolalloc.montecarlo.paired import paired_counts
    from tolalloc.montecarlo.run import run_mc
    from tolalloc.montecarlo.sobol import sobol_indices

    robot = tolalloc.load_robot("tool_changer")
    model = build_error_model(robot)
    q = robot.poses("working")[:4]
    n = 2**16 if quick else 2**18
    K = len(model.params)
    res = allocate(build_problem(model, q, radius_mm=0.25, prob=0.95), snap=False)
    m = res.problem.model_for(res.design.t)
    box = box_region(robot, *robot.regions["working"], "working", "region 'working'")
    n_cand = 300 if quick else 1000
    split = split_errors(model)
    cand = candidate_poses(robot, 500, "limits", seed=0)
    n_plans = 20 if quick else 100
    scale = budget.chain_scale(K, robot.n_joints)
    return {  # kind -> (run of a count, counts timed: two where the work has a fixed part, scale of a unit)
        "mc": (lambda c: run_mc(m, q, c, 0, n_jobs=1, progress=False, keep_samples=0), [n], len(q), scale),
        "paired": (lambda c: paired_counts(m, q, c, 0, radii_mm=(0.25,), n_jobs=1), [n], len(q), scale),
        "importance": (lambda c: importance_probability(m, q, c, 0, radius_mm=0.25, n_jobs=1), [n], len(q), scale),
        "sobol": (lambda c: sobol_indices(m, q[0], c, 0, radius_mm=0.25), [n // 16], K + 2, scale),
        "coverage": (lambda c: coverage(res.problem, res.design.t, box, n=c), [20 * n // 16], 1, 1.0),
        "candidate": (lambda c: tolalloc.plan_calibration(robot, 30, n_candidates=c), [n_cand // 4, n_cand], 1, 1.0),
        "random_plan": (lambda c: random_plan_worst_p(split, cand, 30, q, 0.25, count=c, seed=0), [n_plans], len(q),
                        1.0),
    }


#: (argv, what the count does): every count flag, too large and (where a count can be) large but within the budget
FLAGS = [
    (["mc", "tool_changer", "--n", "1e20"], "refused"), (["mc", "tool_changer", "--n", "1e10"], "estimate"),
    (["mc", "tool_changer", "--n", "1000", "--jobs", "1e15"], "refused"),
    (["mc", "tool_changer", "--n", "1000", "--chunk-size", "1e15"], "runs"),
    (["mc", "tool_changer", "--n", "1000", "--hist-bins", "1000000000000000"], "refused"),
    (["allocate", "tool_changer", "--n-mc", "1e15"], "refused"),
    (["allocate", "tool_changer", "--n-mc", "1e9"], "estimate"),
    (["allocate", "tool_changer", "--coverage-n", "1e15"], "refused"),
    (["allocate", "tool_changer", "--coverage-n", "1e8", "--no-verify"], "estimate"),
    (["allocate", "tool_changer", "--correction-rounds", "1000000000"], "refused"),
    (["analyze", "tool_changer", "--sobol-n", "1000000000000000"], "refused"),
    (["analyze", "tool_changer", "--sobol-n", "6000000"], "runs"),  # the memory cap keeps it under ~1 min
    (["analyze", "tool_changer", "--top", "1e15"], "runs"),
    (["calplan", "ur10", "--n-poses", "1e15", "--out", "{tmp}/p.csv"], "refused"),
    (["calplan", "ur10", "--n-poses", "30", "--n-candidates", "1e15", "--out", "{tmp}/p.csv"], "refused"),
    (["calplan", "ur10", "--n-poses", "30", "--n-candidates", "150000", "--out", "{tmp}/p.csv"], "estimate"),
    (["calplan", "tool_changer", "--n-poses", "30", "--for-allocation", "--random-plans", "1e15", "--out",
      "{tmp}/p.csv"], "refused"),
    (["calplan", "tool_changer", "--n-poses", "30", "--for-allocation", "--random-plans", "1e7", "--out",
      "{tmp}/p.csv"], "estimate"),
    (["diagnose", "tool_changer", "--train", "{tmp}/train.csv", "--folds", "1e15"], "refused"),
    (["diagnose", "tool_changer", "--train", "{tmp}/train.csv", "--cv-rows", "1e15"], "runs"),
    (["diagnose", "tool_changer", "--train", "{tmp}/train.csv", "--test", "{tmp}/test.csv", "--test-frame", "refit",
      "--register-n", "1e15"], "refused"),
]


def time_flags() -> pd.DataFrame:
    """Seconds from the start of a fresh ``tolalloc`` process to its refusal, its estimate line, or its first
    second of work (``runs``: the flag needs no budget; stopped after 20 s)."""
    import subprocess
    import sys
    import tempfile
    from pathlib import Path

    from tolalloc.diagnose import generate

    tmp = Path(tempfile.mkdtemp(prefix="bench_flags_"))
    frame = generate(tolalloc.load_robot("tool_changer"), "none", 60, np.random.default_rng(0)).frame
    frame.iloc[:40].to_csv(tmp / "train.csv", index=False)
    frame.iloc[40:].to_csv(tmp / "test.csv", index=False)
    rows = []
    for argv, expect in FLAGS:
        argv = [a.format(tmp=tmp) for a in argv]
        t0 = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "tolalloc", *argv], stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, text=True)
        first = ""
        for line in proc.stderr:  # the refusal or the estimate is the first line on stderr
            first = line.strip()
            break
        seconds = time.perf_counter() - t0
        try:
            proc.wait(timeout=0 if first.startswith("warning:") else 20)
        except subprocess.TimeoutExpired:
            pass
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        said = "refused" if first.startswith("error:") else "estimate" if first.startswith("warning:") else "runs"
        rows.append({"flags": " ".join(argv[2:]).replace(str(tmp) + "/", ""), "command": argv[0], "expected": expect,
                     "outcome": said, "seconds": seconds if said != "runs" else float("nan"),
                     "first_line": first[:110]})
    return pd.DataFrame(rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="smaller runs")
    ap.add_argument("--flags", action="store_true", help="time the refusal or estimate of every count flag instead")
    args = ap.parse_args()
    if args.flags:
        pd.set_option("display.width", 250)
        pd.set_option("display.max_colwidth", 110)
        print(time_flags().to_string(index=False, float_format=lambda x: f"{x:.2f}"))
        print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
        return
    rows = []
    for kind, (fn, sizes, per_count, scale) in runs(args.quick).items():
        fn(sizes[0])  # compiled kernels, caches and thread pools outside the timing
        budget.probe_seconds.cache_clear()
        probe = budget.probe_seconds()
        walls = []
        for c in sizes:
            t0 = time.perf_counter()
            fn(c)
            walls.append(time.perf_counter() - t0)
        # one size: all of the time per unit; two: the slope per unit and the intercept (the fixed part)
        slope = walls[-1] / sizes[-1] if len(sizes) == 1 else (walls[1] - walls[0]) / (sizes[1] - sizes[0])
        fixed = 0.0 if len(sizes) == 1 else max(0.0, walls[1] - slope * sizes[1])
        each = slope / per_count / scale
        est = budget.estimate_seconds(sizes[-1], kind, per_count=per_count, scale=scale)
        rows.append({"kind": kind, "count": sizes[-1], "measured_s": walls[-1], "measured_s_per_unit": each,
                     "probe_s": probe, "probe_units": each / probe, "fixed_probe_units": fixed / probe,
                     "stated_probe_units": budget.WORK[kind].probe_units,
                     "stated_fixed": budget.WORK[kind].fixed_probe_units, "estimate_s": est,
                     "measured / estimate": walls[-1] / est})
    pd.set_option("display.width", 200)
    print(pd.DataFrame(rows).to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
