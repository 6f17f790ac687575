"""Benchmark: post-calibration covariance (goal, issue 14).

* 22 parameters (tool_changer), a 50-pose position plan with registration, 1000 evaluation poses:
  posterior + tool covariance at every pose under 0.1 s.

Prints the median of repeated runs after one warm-up (numba compilation of the error Jacobian) and the
ratio against a peer measured in the same run: today's linear map (`linear_map`) at the same 1000 poses.

Run ``python benchmarks/bench_calibration.py``.
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc import load_robot
from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.errormodel.model import build_error_model
from tolalloc.linear.covariance import linear_map


def median_time(fn, repeat):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return float(np.median(ts))


def main() -> None:
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    split = split_errors(model)
    rng = np.random.default_rng(0)
    span = robot.upper - robot.lower
    plan = make_plan(robot, robot.lower + span * rng.random((50, robot.n_joints)))
    qe = robot.lower + span * rng.random((1000, robot.n_joints))
    run = lambda: posterior(split, plan).tool_covariance(qe)  # noqa: E731
    peer = lambda: linear_map(model, qe)  # noqa: E731
    run(), peer()
    t, tp = median_time(run, 9), median_time(peer, 9)
    print(f"{'case':44s} {'time [s]':>9s} {'goal [s]':>9s} {'linear_map [s]':>15s} {'ratio':>6s}")
    print(f"{'posterior 22 par, 50-pose plan, 1000 poses':44s} {t:9.4f} {0.1:9.1f} {tp:15.4f} {t / tp:6.2f}"
          f"  {'met' if t < 0.1 else 'MISSED'}")


if __name__ == "__main__":
    main()
