"""Rare-event requirements: cost against p, and what it takes to demonstrate each p with plain, paired and IS.

For the tool_changer (its working region, a box: cutting-plane allocation over it) and the ur10 (its working
pose set; the robot file has no region), at r = 0.25 mm and p in 0.9 ... 0.99999:

1. allocate (exact design, no snapping) and record the cost;
2. run the correction loop with importance-sampling verification (:func:`tolalloc.verify.correct.correct_design`,
   ``estimator="importance"``) until every active pose is *demonstrated* (lower bound of the 95 % simultaneous
   intervals over the active poses >= p), and record the
   premium and the wall time;
3. at the demonstrated design's pose with the least margin ``P_hat - p``, measure each estimator's per-sample
   variance and throughput (plain and paired from one paired run, importance sampling from its own run) and give
   the samples ``n = z^2 v / (P_hat - p)^2`` and the wall time each would need to demonstrate that pose (``z`` of
   each interval of the verification, simultaneous over the active poses: Bonferroni).

Then two checks of the estimators themselves:

* agreement: paired against plain Monte Carlo with ``--big-n`` (10^8) samples at the three lowest-P poses of
  the quick-start design of both robots (the plain and paired estimates of the same draws, each within the
  other's interval);
* coverage: the paired 95 % interval over ``--seeds`` seeds of ``2^18`` samples at a pose whose nonlinearity is
  large (tool_changer, process limits widened 40x, r = 10 mm), against a reference paired run of ``2^26``
  samples; and the importance-sampling interval over the same seeds.

Writes reports/rare_event/: cost_vs_p.csv, demonstrate.csv, agreement.csv, coverage.csv, report.md.
Usage: ``nice python studies/rare_event/run.py [--quick]``.
"""

from __future__ import annotations

import argparse
import copy
import os
import platform
import time
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc import load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.costs import DEFAULT_COSTS
from tolalloc.allocate.region import allocate_region, box_region
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.importance import importance_probability
from tolalloc.montecarlo.intervals import simultaneous_level, z_of_level
from tolalloc.montecarlo.paired import estimate_probabilities
from tolalloc.verify.correct import CONFIRM_SEED_OFFSET, correct_design
from tolalloc.report.tables import markdown_table

OUT = Path(__file__).resolve().parents[2] / "reports" / "rare_event"
PROBS = (0.9, 0.95, 0.99, 0.999, 0.9999, 0.99999)
R_MM = 0.25
LEVEL = 0.95  # family level of the verification's simultaneous intervals


def z_of_poses(n_poses: int) -> float:
    """Normal quantile of each of the verification's intervals, simultaneous over ``n_poses`` poses."""
    return z_of_level(simultaneous_level(LEVEL, n_poses))


def poses_of(robot):
    """Active poses for the allocation: cutting planes over the tool_changer's region, the ur10's pose set."""
    model = build_error_model(robot)
    if "working" in robot.regions:
        lo, hi = robot.regions["working"]
        return model, box_region(robot, lo, hi, "working")
    return model, None


def allocate_at(model, robot, region, p):
    t0 = time.perf_counter()
    if region is not None:
        q0 = robot.poses("working") if "working" in robot.pose_sets else None
        reg = allocate_region(model, region, q0, prob=p, radius_mm=R_MM)
        q, conv = reg.active_q, reg.converged
    else:
        q, conv = robot.poses("working"), True
    res = allocate(build_problem(model, q, radius_mm=R_MM, prob=p), snap=False)
    return res, q, conv, time.perf_counter() - t0


def n_for_half_width(rate_d: float, margin: float, Z: float) -> float:
    """Samples at which a paired interval's half-width ``z sqrt(rate_d / n) + z^2 / n`` equals ``margin``.

    ``rate_d``: discordant samples per sample (variance of the indicator difference); the ``z^2 / n`` term is the
    score interval's width with no discordant sample, which dominates when the discordance is rarer than ``1/n``;
    ``Z`` the normal quantile of the interval.
    """
    if margin <= 0:
        return np.inf
    u = (-Z * np.sqrt(rate_d) + np.sqrt(Z**2 * rate_d + 4 * Z**2 * margin)) / (2 * Z**2)  # u = 1 / sqrt(n)
    return float(1.0 / u**2)


def needed(model, q, p, n_paired, n_is, Z):
    """Samples and wall time each estimator needs to demonstrate the pose (lower bound >= p), intervals at ``Z``."""
    t0 = time.perf_counter()
    e = estimate_probabilities(model, q[None], n_paired, 7, radius_mm=R_MM)["position"]
    t_paired = (time.perf_counter() - t0) / n_paired
    t0 = time.perf_counter()
    s = importance_probability(model, q[None], n_is, 7, radius_mm=R_MM)
    t_is = (time.perf_counter() - t0) / n_is
    P = float(s.p_hat[0])
    margin = P - p
    # discordance per sample; importance sampling: effective counts per effective sample (n_eff = n / w_bar), and
    # the same half-width law in effective samples, n = n_eff w_bar
    w_bar = float(s.details["w_bar"][0])
    rate = {"plain": P * (1 - P), "paired": float(e.n_discordant[0]) / n_paired,
            "importance": float(s.n_discordant[0]) * w_bar / n_is}
    n_need = {"plain": Z**2 * rate["plain"] / margin**2 if margin > 0 else np.inf,
              "paired": n_for_half_width(rate["paired"], margin, Z),
              "importance": n_for_half_width(rate["importance"], margin, Z) * w_bar}
    t = {"plain": t_paired, "paired": t_paired, "importance": t_is}  # plain counts come from the paired pass
    rows = []
    for k in ("plain", "paired", "importance"):
        rows.append({"estimator": k, "p_hat": P, "margin": margin, "discordance_per_sample": rate[k] if k != "plain"
                     else np.nan, "n_needed": n_need[k], "wall_s_needed": n_need[k] * t[k], "s_per_sample": t[k],
                     "discordant_seen": float(e.n_discordant[0]) if k == "paired" else
                     float(s.details["n_discordant_raw"][0]) if k == "importance" else np.nan})
    return rows


def rare_rows(quick):
    costs, demo = [], []
    for name in ("tool_changer", "ur10"):
        robot = load_robot(name)
        model, region = poses_of(robot)
        for p in PROBS:
            res, q, conv, t_alloc = allocate_at(model, robot, region, p)
            t0 = time.perf_counter()
            corr = correct_design(model, q, estimator="importance", n_mc=2**15 if quick else 2**17, result=res,
                                  radius_mm=R_MM, prob=p, snap=False, max_rounds=3, seed=1)
            t_demo = time.perf_counter() - t0
            v = corr.verification
            costs.append({"robot": name, "p": p, "active_poses": len(q), "region_converged": conv, "status": res.status,
                          "cost": corr.costs[0], "cost_demonstrated": corr.costs[-1], "premium_pct": corr.premium_pct,
                          "rounds": corr.rounds, "verdict": v.verdict, "min_ci_low_minus_p": float((v.ci_low - p).min()),
                          "alloc_s": t_alloc, "demonstrate_s": t_demo})
            i = int(np.argmin(v.ci_low - p))
            m = corr.result.problem.model_for(corr.result.design.t)
            for row in needed(m, q[i], p, 2**18 if quick else 2**20, 2**15 if quick else 2**17, z_of_poses(len(q))):
                demo.append({"robot": name, "p": p, "pose": i + 1, **row})
            print(costs[-1])
    return pd.DataFrame(costs), pd.DataFrame(demo)


def agreement_rows(big_n):
    rows = []
    for name in ("tool_changer", "ur10"):
        robot = load_robot(name)
        q = robot.poses("working")
        res = allocate(build_problem(build_error_model(robot), q, radius_mm=R_MM, prob=0.95), snap=False)
        worst = np.argsort(res.design.p_linear["position"])[:3]
        m = res.problem.model_for(res.design.t)
        t0 = time.perf_counter()
        e = estimate_probabilities(m, q[worst], big_n, 2024, radius_mm=R_MM)["position"]
        wall = time.perf_counter() - t0
        for j, i in enumerate(worst):
            rows.append({"robot": name, "pose": int(i) + 1, "n": big_n, "p_linear": e.p_linear[j],
                         "p_paired": e.p_hat[j], "paired_low": e.ci_low[j], "paired_high": e.ci_high[j],
                         "p_plain": e.p_plain[j], "plain_low": e.plain_low[j], "plain_high": e.plain_high[j],
                         "n_discordant": e.n_discordant[j], "variance_reduction": e.variance_reduction[j],
                         "paired_in_plain_ci": bool(e.plain_low[j] <= e.p_hat[j] <= e.plain_high[j]),
                         "plain_in_paired_ci": bool(e.ci_low[j] <= e.p_plain[j] <= e.ci_high[j]),
                         "wall_s": wall})
        print(rows[-1])
    return pd.DataFrame(rows)


def coverage_rows(seeds, n_ref, n_run):
    robot = load_robot("tool_changer")
    costs = copy.deepcopy(DEFAULT_COSTS)
    for kind in costs["kinds"].values():
        for key in [k for k in kind if k.startswith("t_max")]:
            kind[key] *= 40
    q = robot.poses("working")[[11]]
    res = allocate(build_problem(build_error_model(robot), q, radius_mm=10.0, costs=costs), snap=False)
    m = res.problem.model_for(res.design.t)
    ref = estimate_probabilities(m, q, n_ref, 999, radius_mm=10.0)["position"]
    rows = []
    for s in range(seeds):
        e = estimate_probabilities(m, q, n_run, s, radius_mm=10.0)["position"]
        w = importance_probability(m, q, n_run // 8, s, radius_mm=10.0)
        rows.append({"seed": s, "reference": ref.p_hat[0], "reference_half_width": 0.5 * (ref.ci_high[0] - ref.ci_low[0]),
                     "paired_low": e.ci_low[0], "paired_high": e.ci_high[0], "paired_discordant": e.n_discordant[0],
                     "is_low": w.ci_low[0], "is_high": w.ci_high[0], "is_discordant_raw": w.details["n_discordant_raw"][0]})
    df = pd.DataFrame(rows)
    df["paired_covers"] = (df.paired_low <= df.reference) & (df.reference <= df.paired_high)
    df["is_covers"] = (df.is_low <= df.reference) & (df.reference <= df.is_high)
    return df


def report(cost, demo, agree, cov, args, wall):
    def md(df):
        return markdown_table(df, ".6g")

    load = os.getloadavg()
    text = [f"# Rare-event requirements: cost against p, and demonstrating p with plain, paired and importance "
            f"sampling\n\nGenerated by `studies/rare_event/run.py{' --quick' if args.quick else ''}` on "
            f"{platform.node()} ({os.cpu_count()} CPUs, load average {load[0]:.2f} at the end), {wall:.0f} s"
            + (" (agreement and coverage tables from the earlier full run, `--reuse-checks`)" if args.reuse_checks
               else "") + ".\n",
            "## Cost against p (r = 0.25 mm; tool_changer over its working region, ur10 over its working poses)\n",
            "Each design is allocated (exact, unsnapped), then corrected until every active pose is demonstrated by "
            "importance-sampling verification (lower bound of the 95 % simultaneous intervals over the active poses "
            ">= p); a corrected design's verdict, `verdict` and `min_ci_low_minus_p` are from fresh draws (seed "
            f"{1 + CONFIRM_SEED_OFFSET}), not from the draws its targets were raised on.\n", md(cost),
            "\n## Samples and wall time to demonstrate the least-margin pose\n",
            "`z`: the normal quantile of each of the verification's intervals, simultaneous over the active poses "
            "(Bonferroni: level 1 - 0.05 / poses each). Plain: `n = z^2 P (1 - P) / (P_hat - p)^2`. Paired: the "
            "`n` at which the score interval's half-width `z sqrt(d / n) + z^2 / n` equals the margin `P_hat - p` "
            "(`d` = discordant samples per sample, measured with 2^20 samples; the `z^2 / n` term is the "
            "interval's width with no discordant sample, which rules when discordance is rarer than 1/n). "
            "Importance sampling: the same law in effective samples (`n_eff = n / w_bar`). Times: `n` x the "
            "measured time per sample (plain counts come from the paired pass, so plain's time per sample is the "
            "paired pass's). The margin is that of the demonstrated design at its least-margin pose.\n", md(demo),
            f"\n## Paired against plain Monte Carlo, {args.big_n:.0e} samples\n",
            "The same draws give both: the paired estimate should lie in the plain interval (`paired_in_plain_ci`); "
            "the plain estimate lies in the far narrower paired interval only by chance (`plain_in_paired_ci`).\n",
            md(agree),
            f"\n## Interval coverage over {len(cov)} seeds\n",
            f"Paired 95 % interval: covers the reference in {cov.paired_covers.mean():.1%} of the runs; importance "
            f"sampling (n/8 samples): {cov.is_covers.mean():.1%}. Reference: paired, 2^26 samples, half-width "
            f"{cov.reference_half_width.iloc[0]:.2g} (not added to the intervals).\n"]
    (OUT / "report.md").write_text("\n".join(text))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--big-n", type=float, default=1e8)
    ap.add_argument("--seeds", type=int, default=200)
    ap.add_argument("--reuse-checks", action="store_true",
                    help="take agreement.csv and coverage.csv from an earlier run of reports/rare_event/")
    args = ap.parse_args()
    if args.quick:
        args.big_n, args.seeds = min(args.big_n, 1e6), min(args.seeds, 20)
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    cost, demo = rare_rows(args.quick)
    cost.to_csv(OUT / "cost_vs_p.csv", index=False)
    demo.to_csv(OUT / "demonstrate.csv", index=False)
    if args.reuse_checks:
        agree, cov = pd.read_csv(OUT / "agreement.csv"), pd.read_csv(OUT / "coverage.csv")
        args.big_n = float(agree.n.iloc[0])
    else:
        agree = agreement_rows(int(args.big_n))
        agree.to_csv(OUT / "agreement.csv", index=False)
        cov = coverage_rows(args.seeds, 2**20 if args.quick else 2**26, 2**18)
        cov.to_csv(OUT / "coverage.csv", index=False)
    report(cost, demo, agree, cov, args, time.perf_counter() - t0)
    print((OUT / "report.md").read_text())


if __name__ == "__main__":
    main()
