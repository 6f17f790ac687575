"""Speed and memory of the sim-to-real diagnosis at scale (issue 12): 10^3 .. 10^6 training rows.

    python benchmarks/bench_diagnose.py            # 10^3, 10^4, 10^5 rows (a few minutes)
    python benchmarks/bench_diagnose.py --big      # also 10^6 rows (~10 minutes)
    python benchmarks/bench_diagnose.py --rows 20000 --robot tool_changer

Every size runs in a fresh process: a synthetic measurement table (random poses, a random complete geometric
error, tracker frame and probe offset, joint compliance of 0.3 mm RMS, 0.02 mm tracker noise, temperature and
dir columns so all five candidate effects are tested) is written as CSV, then the measured run is the CLI's
work: read the CSV and diagnose (default options: 5 folds, cross-validation on a 20,000-row subsample above
that size, final fits on all rows). Prints wall time (read + diagnose), peak RSS, time per 1,000 rows and the
ratio of the time to the goal of issue 12 (< 60 s for 10^5 rows, < 10 min for 10^6 rows; ratio < 1 meets it).
Goals assume the 2-core machine the issue names; the load average is printed because the machine may be shared,
and the process's CPU time (``cpu_s``, all threads) is printed next to the wall time: on a loaded machine it is the
better estimate of the unloaded wall time (the fits run single-threaded).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

GOALS_S = {10**5: 60.0, 10**6: 600.0}


def synth_frame(robot, n: int, seed: int = 0, chunk: int = 100_000) -> pd.DataFrame:
    """A measurement table of ``n`` rows (see the module docstring), generated chunk by chunk."""
    from scipy.spatial.transform import Rotation

    from tolalloc.diagnose.calibrate import Fit
    from tolalloc.diagnose.effects import effect_basis
    from tolalloc.diagnose.geometry import PRIOR_SCALE, build_geometry_model
    from tolalloc.diagnose.measurements import Measurements

    rng = np.random.default_rng(seed)
    model = build_geometry_model(robot)
    delta = rng.normal(0.0, model.sigma / PRIOR_SCALE)  # the robot's own sigma set
    R, p = Rotation.random(random_state=rng).as_matrix(), rng.uniform(-3000, 3000, 3)
    t = rng.normal(size=3)
    t *= 120.0 / np.linalg.norm(t)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    frames, beta = [], None
    for a in range(0, n, chunk):
        m = min(chunk, n - a)
        q = rng.uniform(lo, hi, (m, robot.n_joints))
        direction = rng.choice([-1.0, 1.0], (m, robot.n_joints))
        temp = 20.0 + 5.0 * (a + np.arange(m)) / n + rng.normal(0, 0.05, m)
        B = effect_basis("joint_compliance", robot, Measurements(q, np.zeros((m, 3)), temp, direction), t,
                         {"temperature_c": 22.5}).B
        if beta is None:
            beta = 1.0 / np.sqrt(np.mean(np.sum(B ** 2, axis=1), axis=0))
            beta *= 0.3 / np.sqrt(np.mean(np.sum((B @ beta) ** 2, axis=1)))
        fit = Fit(model, R, p, t, delta, np.arange(len(delta)), beta)
        xyz = fit.predict(q, B) + rng.normal(0, 0.02, (m, 3))
        cols = {f"q{j + 1}": robot.q_to_interface(q)[:, j] for j in range(robot.n_joints)}
        cols.update({"x_mm": xyz[:, 0], "y_mm": xyz[:, 1], "z_mm": xyz[:, 2], "temperature_c": temp})
        cols.update({f"dir{j + 1}": direction[:, j] for j in range(robot.n_joints)})
        frames.append(pd.DataFrame(cols))
    return pd.concat(frames, ignore_index=True)


def child(robot_name: str, n: int, csv: str) -> None:
    """Measured part, in a fresh process: read the CSV and diagnose; prints one machine-readable line."""
    import tolalloc
    from tolalloc.diagnose import diagnose, read_measurements

    robot = tolalloc.load_robot(robot_name)
    t0, c0 = time.perf_counter(), time.process_time()
    m = read_measurements(csv, robot)
    t_read = time.perf_counter() - t0
    d = diagnose(robot, m, progress=None)
    t_all, cpu = time.perf_counter() - t0, time.process_time() - c0
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"RESULT {t_all:.3f} {t_read:.3f} {cpu:.3f} {rss_mb:.1f} {d.effect} {d.final.fit.rms_mm:.5f}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--big", action="store_true", help="also 10^6 rows (~10 minutes)")
    ap.add_argument("--rows", type=int, nargs="*", help="row counts instead of the default sizes")
    ap.add_argument("--robot", default="ur10")
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args.robot, int(args.child[0]), args.child[1])
        return
    import tolalloc

    robot = tolalloc.load_robot(args.robot)
    sizes = args.rows or [10**3, 10**4, 10**5] + ([10**6] if args.big else [])
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cpus; robot {args.robot}")
    print(f"{'rows':>9s} {'total_s':>9s} {'read_s':>8s} {'cpu_s':>8s} {'peak_rss_MB':>12s} {'s_per_1k_rows':>14s} "
          f"{'goal_s':>7s} {'time/goal':>9s}  effect  train_rms_mm")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            csv = str(Path(tmp) / f"train_{n}.csv")
            synth_frame(robot, n).to_csv(csv, index=False, float_format="%.6f")
            out = subprocess.run([sys.executable, __file__, "--robot", args.robot, "--child", str(n), csv],
                                 capture_output=True, text=True)
            line = next((x for x in out.stdout.splitlines() if x.startswith("RESULT")), None)
            if line is None:
                print(f"{n:9d} failed: {out.stderr.strip().splitlines()[-1:]}")
                continue
            t_all, t_read, cpu, rss, effect, rms_mm = line.split()[1:]
            goal = GOALS_S.get(n, np.nan)
            ratio = float(t_all) / goal if np.isfinite(goal) else np.nan
            print(f"{n:9d} {float(t_all):9.1f} {float(t_read):8.1f} {float(cpu):8.1f} {float(rss):12.0f} "
                  f"{1000 * float(t_all) / n:14.3f} {goal:7.0f} {ratio:9.2f}  {effect}  {rms_mm}", flush=True)
            os.remove(csv)


if __name__ == "__main__":
    main()
