"""Benchmark: tolerance allocation of the tool_changer's 22 parameters (goals, issue 5).

* 1 pose: under 0.1 s for either solver, problem construction included;
* 200 poses: under 3 s;
* region allocation (issue 13, cutting planes over a box): tool_changer ``working`` box < 10 s, ur10 joint
  limits < 30 s; coverage check of 1e5 fresh poses < 2 s.

Prints medians of repeated runs (after one warm-up that pays the imports and CasADi's derivative
generation) and ratios against a peer measured in the same run: one Gaussian-probability evaluation
of all poses (`problem.probabilities`), the unit of the exact solver's feasibility check.

Run ``python benchmarks/bench_allocate.py``.
"""

from __future__ import annotations

import time

import numpy as np

from tolalloc import load_robot
from tolalloc.allocate.problem import build_problem
from tolalloc.allocate.convex import solve_rule
from tolalloc.allocate.exact import solve_exact
from tolalloc.errormodel import build_error_model


def median_time(fn, repeat):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return float(np.median(ts)), out


def main() -> None:
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    rng = np.random.default_rng(0)
    work = robot.poses("working")
    lo, hi = work.min(0), work.max(0)
    sets = {1: work[:1], 12: work, 100: rng.uniform(lo, hi, (100, 6)), 200: rng.uniform(lo, hi, (200, 6))}
    # warm-up
    pr = build_problem(model, work[:1])
    solve_exact(pr, solve_rule(pr, "lmi"))
    goals = {1: 0.1, 200: 3.0}
    print(f"{'poses':>5s} {'trace [s]':>10s} {'lmi [s]':>10s} {'exact [s]':>10s} {'P eval [s]':>11s} "
          f"{'lmi/P':>8s} {'exact/P':>8s}  goal   costs trace / lmi / exact")
    for P, q in sets.items():
        rep = 7 if P <= 12 else 3
        t_tr, d_tr = median_time(lambda: solve_rule(build_problem(model, q), "trace"), rep)
        t_lmi, d_lmi = median_time(lambda: solve_rule(build_problem(model, q), "lmi"), rep)
        start = min((d_tr, d_lmi), key=lambda d: d.cost)

        def exact():
            p = build_problem(model, q)
            return solve_exact(p, solve_rule(p, start.solver.split("-")[1]))

        t_ex, d_ex = median_time(exact, rep)
        pr = build_problem(model, q)
        t_p, _ = median_time(lambda: pr.probabilities(d_ex.t), rep)
        goal = goals.get(P)
        worst = max(t_tr, t_lmi, t_ex)
        flag = "" if goal is None else (f"<{goal:g}s {'ok' if worst < goal else 'MISSED'}")
        print(f"{P:5d} {t_tr:10.4f} {t_lmi:10.4f} {t_ex:10.4f} {t_p:11.5f} {t_lmi / t_p:8.0f} {t_ex / t_p:8.0f}  "
              f"{flag:9s} {d_tr.cost:.3f} / {d_lmi.cost:.3f} / {d_ex.cost:.3f}  ({d_ex.solver})")
    print("exact includes building the problem and solving the certified rule it starts from (the full pipeline).")
    region_rows()


def region_rows() -> None:
    """Region allocation and coverage timings (single runs: each takes seconds)."""
    from tolalloc.allocate.region import allocate_region, box_region, coverage

    print(f"\n{'region':>22s} {'time [s]':>9s} {'rounds':>6s} {'active':>6s} {'evals':>6s} {'worst P':>8s} "
          f"{'cov 1e5 [s]':>11s}  goal")
    for name, region_of, goal in (("tool_changer working", lambda r: r.regions["working"], 10.0),
                                  ("ur10 limits", lambda r: (r.lower, r.upper), 30.0)):
        robot = load_robot(name.split()[0])
        model = build_error_model(robot)
        box = box_region(robot, *region_of(robot), name)
        ra = allocate_region(model, box)
        coverage(ra.result.problem, ra.result.design.t, box, n=1000)  # warm-up
        t0 = time.perf_counter()
        cov = coverage(ra.result.problem, ra.result.design.t, box)
        t_cov = time.perf_counter() - t0
        ok = ra.time_s < goal and t_cov < 2.0
        print(f"{name:>22s} {ra.time_s:9.2f} {ra.rounds:6d} {len(ra.active_q):6d} {ra.evaluations:6d} "
              f"{ra.worst_p:8.5f} {t_cov:11.2f}  <{goal:g}s / <2s {'ok' if ok else 'MISSED'}"
              f"{'' if ra.converged else ' (not converged)'}; {cov.n_below} fresh poses below p")


if __name__ == "__main__":
    main()
