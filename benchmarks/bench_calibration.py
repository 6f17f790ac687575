"""Benchmark: design for calibration (goals, issue 14), tool_changer (22 parameters):

* posterior + tool covariance, 50-pose position plan with registration, 1000 evaluation poses: < 0.1 s;
* calibration-aware allocation at the 12 working poses (12-pose plan): < 2 s;
* plan design over 2000 candidate poses (12 poses): < 30 s;
* end-to-end Monte Carlo: >= 200 simulated calibrations per second (each a nonlinear least-squares fit).

Prints medians of repeated runs after one warm-up (numba compilation of the error Jacobian) and, for the first,
the ratio against a peer measured in the same run: today's linear map (`linear_map`) at the same 1000 poses.

Run ``python benchmarks/bench_calibration.py``.
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc import load_robot
from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.errormodel import build_error_model
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
    from tolalloc.allocate.calibrated import allocate_calibrated
    from tolalloc.allocate.problem import build_problem
    from tolalloc.calibration.design import candidate_poses, design_plan
    from tolalloc.verify.calibrated import verify_calibration

    work = robot.poses("working")
    problem = build_problem(model, work)
    plan12 = make_plan(robot, robot.lower + span * rng.random((12, robot.n_joints)))
    ta = median_time(lambda: allocate_calibrated(problem, plan12), 3)
    print(f"{'calibration-aware allocation, 12 poses':44s} {ta:9.4f} {2.0:9.1f} {'':15s} {'':6s}"
          f"  {'met' if ta < 2.0 else 'MISSED'}")
    cand = candidate_poses(robot, 2000)
    td = median_time(lambda: design_plan(split, 12, cand, work), 3)
    print(f"{'plan design, 2000 candidates, 12 poses':44s} {td:9.4f} {30.0:9.1f} {'':15s} {'':6s}"
          f"  {'met' if td < 30.0 else 'MISSED'}")
    small = split_errors(model.with_sigma(0.1 * model.sigma))
    chk = verify_calibration(small, plan, work, 1.0, n_robots=2000)
    print(f"{'end-to-end MC, 50-pose plan [calibrations/s]':44s} {chk.fits_per_s:9.0f} {'>= 200':>9s} {'':15s} "
          f"{'':6s}  {'met' if chk.fits_per_s >= 200 else 'MISSED'}")


if __name__ == "__main__":
    main()
