"""Benchmark: error Jacobians and covariances of 1000 tool_changer poses (goal < 50 ms), P(|x|<r) cost, and a mean
near the ball's surface (a multi-directional accuracy's lost-motion offset) against the nested quadrature alone.

Run ``python benchmarks/bench_linear.py``. Prints medians of repeated runs and ratios against
peers measured in the same run (the robot's own space Jacobian, a per-pose Python loop).
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc import load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.linear.covariance import linear_map
from tolalloc.linear.probability import p_within_radius, radius_for_prob
from tolalloc.linear.probability_casadi import p_within_radius_lebedev
from tolalloc.linear.probability_mean import _p_mean_nested


def timeit(fn, repeat=15):
    fn()
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def main() -> None:
    robot = load_robot("tool_changer")
    rng = np.random.default_rng(0)
    q = rng.uniform(robot.lower, robot.upper, (1000, robot.n_joints))
    rows = []
    for clearance in (False, True):
        model = build_error_model(robot, "table2", clearance=clearance)
        t_lin = timeit(lambda: linear_map(model, q))
        t_jac = timeit(lambda: model.jacobian(q))
        t_space = timeit(lambda: robot.space_jacobian_internal(q))
        t_loop = timeit(lambda: [model.jacobian(qi) for qi in q[:100]], repeat=3) * 10
        rows.append((f"K={len(model.params)}", t_lin, t_jac, t_space, t_loop))
    print("1000 poses                 linear_map   jacobian   space_jacobian(peer)   per-pose loop(peer)")
    for name, a, b, c, d in rows:
        print(f"  {name:6s} table2{'+clear' if name != 'K=22' else '      '}   {a * 1e3:8.1f} ms {b * 1e3:8.1f} ms {c * 1e3:12.1f} ms {d * 1e3:14.1f} ms"
              f"   (linear_map / space_jacobian = {a / c:.1f}x, loop / linear_map = {d / a:.0f}x)")
    res = linear_map(build_error_model(robot, "table2"), q)
    one = res.cov_mm2[0]
    t1 = timeit(lambda: p_within_radius(one, 30.0), repeat=200)
    tb = timeit(lambda: p_within_radius(res.cov_mm2, 30.0))
    tl = timeit(lambda: p_within_radius_lebedev(res.cov_mm2, 30.0))
    ti = timeit(lambda: radius_for_prob(res.cov_mm2, 0.95), repeat=5)
    tm = timeit(lambda: p_within_radius(one, 30.0, mean=np.array([1.0, 2.0, 0.5])), repeat=20)
    print(f"p_within_radius: one cov {t1 * 1e6:.0f} us; 1000 covs {tb * 1e3:.1f} ms "
          f"(Lebedev-65 rule as peer: {tl * 1e3:.1f} ms); radius_for_prob 1000 covs {ti * 1e3:.1f} ms; "
          f"with a mean, one cov {tm * 1e3:.2f} ms")
    # a mean 20 standard deviations out, the ball's surface a fraction of one beyond it: Imhof's integral (the
    # rule p_within_radius takes there) against the nested quadrature (the rule it took before)
    lam, m, r = np.array([6.2e-5, 1e-6, 4e-8]), np.array([1e-4, 0.02, 0.1726]), 0.1728
    tg = timeit(lambda: p_within_radius(np.diag(lam), r, m), repeat=20)
    tn = timeit(lambda: _p_mean_nested(lam, m, r), repeat=3)
    tq = timeit(lambda: radius_for_prob(np.diag(lam), 0.9833, m), repeat=3)
    print(f"grazing mean: p_within_radius {tg * 1e3:.2f} ms, nested quadrature (peer) {tn * 1e3:.0f} ms "
          f"({tn / tg:.0f}x); radius_for_prob {tq * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
