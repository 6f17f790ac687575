"""Benchmark: tolerance allocation of the tool_changer's 22 parameters (goals, issue 5).

* 1 pose: under 0.1 s for either solver, problem construction included;
* 200 poses: under 3 s;
* region allocation (issue 13, cutting planes over a box): tool_changer ``working`` box < 10 s, ur10 joint
  limits < 30 s; coverage check of 1e5 fresh poses < 2 s.

Prints medians of repeated runs (after one warm-up that pays the imports and CasADi's derivative
generation) and ratios against a peer measured in the same run: one Gaussian-probability evaluation
of all poses (`problem.probabilities`), the unit of the exact solver's feasibility check.

Run ``python benchmarks/bench_allocate.py`` (``--region-only``: the region rows only). The region rows
are written to ``reports/benchmarks/region_allocation.md`` / ``.csv`` with wall-clock and CPU time.

Standard design over a region (issue 24: grades chosen by the optimiser, the discrete step inside the cutting
planes): tool_changer ``working`` box, continuous loop plus standard loop < 30 s wall on 2 cores; the peer is
the continuous loop of the same run (the standard step's time as a multiple of it). ``--standard-only``: these
rows only, written to ``reports/benchmarks/region_standard.md`` / ``.csv``.
"""

from __future__ import annotations

import datetime
import os
import sys
import time
from pathlib import Path

import numpy as np

from tolalloc import load_robot
from tolalloc.allocate.problem import build_problem
from tolalloc.allocate.convex import solve_rule
from tolalloc.allocate.exact import solve_exact
from tolalloc.errormodel import build_error_model

ROOT = Path(__file__).resolve().parents[1]


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


def region_rows(out_dir: Path | None = ROOT / "reports" / "benchmarks") -> list[dict]:
    """Region allocation and coverage timings (single runs: each takes seconds).

    Wall-clock and CPU time (``time.process_time``, all threads of this process) are both recorded: on a
    shared machine the wall clock includes waiting for a core, the CPU time does not. Writes
    ``region_allocation.csv`` / ``.md`` to ``out_dir`` (None: print only).
    """
    from tolalloc.allocate.region import allocate_region, box_region, coverage

    load0 = os.getloadavg()
    rows = []
    print(f"\n{'region':>22s} {'wall [s]':>8s} {'cpu [s]':>7s} {'rounds':>6s} {'active':>6s} {'evals':>6s} "
          f"{'worst P':>8s} {'cov wall':>8s} {'cov cpu':>7s}  goal (wall)")
    for name, region_of, goal in (("tool_changer working", lambda r: r.regions["working"], 10.0),
                                  ("ur10 limits", lambda r: (r.lower, r.upper), 30.0)):
        robot = load_robot(name.split()[0])
        model = build_error_model(robot)
        box = box_region(robot, *region_of(robot), name)
        allocate_region(model, box, max_rounds=1)  # warm-up: CasADi derivative generation, compiled kernels
        c0 = time.process_time()
        ra = allocate_region(model, box)
        cpu = time.process_time() - c0
        coverage(ra.result.problem, ra.result.design.t, box, n=1000)  # warm-up
        c0, t0 = time.process_time(), time.perf_counter()
        cov = coverage(ra.result.problem, ra.result.design.t, box)
        t_cov, c_cov = time.perf_counter() - t0, time.process_time() - c0
        ok = ra.time_s < goal and t_cov < 2.0
        print(f"{name:>22s} {ra.time_s:8.2f} {cpu:7.2f} {ra.rounds:6d} {len(ra.active_q):6d} {ra.evaluations:6d} "
              f"{ra.worst_p:8.5f} {t_cov:8.2f} {c_cov:7.2f}  <{goal:g}s / <2s {'ok' if ok else 'MISSED'}"
              f"{'' if ra.converged else ' (not converged)'}; {cov.n_below} of {cov.n} fresh poses below p "
              f"({cov.n_exact} evaluated exactly)")
        rows.append({"region": name, "wall_s": ra.time_s, "cpu_s": cpu, "goal_wall_s": goal, "rounds": ra.rounds,
                     "active_poses": len(ra.active_q), "search_evaluations": ra.evaluations,
                     "converged": ra.converged, "worst_p_linear": ra.worst_p, "cost": ra.result.design.cost,
                     "coverage_n": cov.n, "coverage_wall_s": t_cov, "coverage_cpu_s": c_cov, "coverage_goal_s": 2.0,
                     "coverage_n_exact": cov.n_exact, "coverage_n_below": cov.n_below,
                     "goals_met_wall": bool(ok)})
    if out_dir is not None:
        _write_region(rows, load0, Path(out_dir))
    return rows


def _write_md(rows, load0, out_dir: Path, stem: str, title: str, how: str, notes: str) -> None:
    """``<stem>.csv`` and ``<stem>.md`` (the machine, the load before and after, the rows) in ``out_dir``."""
    import pandas as pd

    out_dir.mkdir(parents=True, exist_ok=True)
    f = pd.DataFrame(rows)
    f.to_csv(out_dir / f"{stem}.csv", index=False, float_format="%.6g")
    load1 = os.getloadavg()
    md = [f"# {title}", "", f"Generated by {how}; single runs after a warm-up.", "",
          f"- date: {datetime.datetime.now().isoformat(timespec='seconds')}",
          f"- cores usable: {len(os.sched_getaffinity(0))}",
          f"- load average (1, 5, 15 min) at start: {' '.join(f'{x:.2f}' for x in load0)}; at end: "
          f"{' '.join(f'{x:.2f}' for x in load1)}", "", notes, "",
          f.to_markdown(index=False, floatfmt=".4g"), ""]
    (out_dir / f"{stem}.md").write_text("\n".join(md))
    print(f"wrote {out_dir}/{stem}.md, {stem}.csv")


def _write_region(rows, load0, out_dir: Path) -> None:
    _write_md(rows, load0, out_dir, "region_allocation", "Region allocation benchmark (issue 13)",
              "`python benchmarks/bench_allocate.py --region-only` (or the full `bench_allocate.py`)",
              "Goals (wall clock on 2 cores): tool_changer `working` box < 10 s, ur10 joint limits < 30 s, coverage "
              "of 10^5 fresh poses < 2 s. The machine may be shared: `cpu_s` (process CPU time, all threads) is "
              "the part that does not depend on other jobs; with a load average above the core count the wall "
              "clock includes waiting for a core.")


def standard_rows(out_dir: Path | None = ROOT / "reports" / "benchmarks") -> list[dict]:
    """Standard design over a box: the continuous cutting planes (the peer), then the loop with the discrete step.

    The tool_changer box starts from its 12 working poses (as ``tolalloc allocate tool_changer`` does), the ur10
    joint-limit box from its centre. Single runs after a warm-up; wall clock and CPU time.
    """
    from tolalloc.allocate.region import allocate_region, box_region, coverage
    from tolalloc.allocate.region_standard import allocate_region_standard

    load0 = os.getloadavg()
    rows = []
    print(f"\n{'region (standard)':>22s} {'cont wall':>9s} {'std wall':>8s} {'total':>7s} {'cpu':>6s} {'std/cont':>8s} "
          f"{'rounds':>6s} {'cost cont':>9s} {'standard':>9s} {'rounded':>9s}  goal (total wall)")
    for name, region_of, q0_of, goal in (
            ("tool_changer working", lambda r: r.regions["working"], lambda r: r.poses("working"), 30.0),
            ("ur10 limits", lambda r: (r.lower, r.upper), lambda r: None, None)):
        robot = load_robot(name.split()[0])
        model = build_error_model(robot)
        box = box_region(robot, *region_of(robot), name)
        allocate_region_standard(model, box, q0_of(robot), max_rounds=1)  # warm-up (imports, CasADi, HiGHS)
        c0, t0 = time.process_time(), time.perf_counter()
        ra = allocate_region(model, box, q0_of(robot))
        t_cont, c_cont = time.perf_counter() - t0, time.process_time() - c0
        sa = allocate_region_standard(model, box, continuous=ra)
        t_tot, c_tot = time.perf_counter() - t0, time.process_time() - c0
        res = sa.result
        cov = coverage(res.problem, res.standard.t, box)
        ok = goal is None or t_tot < goal
        pct = res.discrete.gap_pct
        rnd = res.discrete.rounded_premium_pct
        print(f"{name:>22s} {t_cont:9.2f} {t_tot - t_cont:8.2f} {t_tot:7.2f} {c_tot:6.2f} "
              f"{(t_tot - t_cont) / t_cont:8.2f} {sa.rounds:6d} {res.design.cost:9.4f} {res.standard.cost:9.4f} "
              f"{res.rounded.cost:9.4f}  {'' if goal is None else f'<{goal:g}s ' + ('ok' if ok else 'MISSED')}"
              f"{'' if sa.converged else ' (not converged)'}; standard {pct:+.2f} %, rounding {rnd:+.2f} %; coverage "
              f"{cov.n_below} of {cov.n} below p")
        rows.append({"region": name, "continuous_wall_s": t_cont, "continuous_cpu_s": c_cont,
                     "standard_wall_s": t_tot - t_cont, "total_wall_s": t_tot, "total_cpu_s": c_tot,
                     "standard_over_continuous": (t_tot - t_cont) / t_cont, "goal_total_wall_s": goal,
                     "continuous_rounds": ra.rounds, "standard_rounds": sa.rounds, "converged": sa.converged,
                     "active_poses": len(sa.active_q), "worst_p_linear": sa.worst_p,
                     "cost_continuous": res.design.cost, "cost_standard": res.standard.cost,
                     "cost_rounded": res.rounded.cost, "standard_premium_pct": pct, "rounded_premium_pct": rnd,
                     "standard_solver": res.standard.label, "coverage_n": cov.n, "coverage_n_below": cov.n_below,
                     "coverage_min_p": cov.min_p, "goal_met_wall": bool(ok)})
    if out_dir is not None:
        _write_standard(rows, load0, Path(out_dir))
    return rows


def _write_standard(rows, load0, out_dir: Path) -> None:
    _write_md(rows, load0, out_dir, "region_standard", "Standard design over a region: benchmark (issue 24)",
              "`python benchmarks/bench_allocate.py --standard-only`",
              "The continuous cutting planes (`allocate_region`, the peer) and then the standard loop "
              "(`allocate_region_standard`: standard design on the active set, worst-pose search of that design, "
              "repeat). Goal: tool_changer `working` box, both together < 30 s wall on 2 cores. `cost_rounded`: the "
              "continuous design on the final active set rounded down (what the standard design replaces). "
              "Coverage: linear P of the standard design on 10^5 fresh uniform poses of the box.")


if __name__ == "__main__":
    if "--region-only" in sys.argv[1:]:
        region_rows()
    elif "--standard-only" in sys.argv[1:]:
        standard_rows()
    else:
        main()
        standard_rows()
