"""Region sections of the design-for-calibration study (issue 26): calibration-aware allocation over the working
region, the exact stage, the end-to-end Monte Carlo at the region's worst poses and plans designed for the
allocation against the distribution of random plans. Imported by run.py; every number comes from the library calls
named beside it."""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.allocate.calibrated.design import allocate_with_calibration, resolve_region
from tolalloc.allocate.calibrated.plan import compare_with_random_plans, design_plan_for_allocation
from tolalloc.allocate.region import coverage
from tolalloc.calibration import make_plan
from tolalloc.calibration.design import design_plan
from tolalloc.verify.calibrated_worst import verify_calibrated_design
from tolalloc.report.tables import markdown_table

#: Margin of the design probability over p for the strictly demonstrated variant.
MARGIN = 0.008


def _cov_row(label, where, cost, cov, prob):
    return {"design": label, "allocated_on": where, "cost": cost, "min_p_region": cov.min_p,
            "poses_below_p": cov.n_below, "fraction_below_upper95": cov.frac_below_upper95, "none_below_p": cov.ok,
            "p": prob}


def designs_over_region(pr, split, plan, box, n_cov, seed):
    """Pose-set and region designs (certified, exact, no calibration), each covered on the same fresh sample."""
    prob = pr.prob
    poses = allocate_with_calibration(pr, plan, split=split, coverage_n=0, seed=seed)
    reg = allocate_with_calibration(pr, plan, split=split, region=box, coverage_n=n_cov, seed=seed)
    kw = dict(n=n_cov, seed=seed + 12345)
    rows = [_cov_row("certified, calibrated", "working poses", poses.cost_certified,
                     coverage(pr, None, box, pose_cov=poses.certified.post.tool_covariance, **kw), prob),
            _cov_row("exact, calibrated", "working poses", poses.cost_exact,
                     coverage(pr, None, box, pose_cov=poses.exact.post.tool_covariance, **kw), prob),
            _cov_row("certified, calibrated", "region", reg.cost_certified,
                     coverage(reg.certified.problem, None, box, pose_cov=reg.certified.post.tool_covariance, **kw),
                     prob),
            _cov_row("exact, calibrated", "region", reg.cost_exact, reg.coverage, prob)]
    for label, d in (("certified (LMI), no calibration", reg.baseline), ("exact, no calibration", reg.baseline_exact)):
        c = coverage(pr, d.t, box, **kw)
        rows.append(_cov_row(label, "region", float(d.cost + reg.certified.grade_cost_loosest), c, prob))
    return poses, reg, pd.DataFrame(rows)


def search_table(reg) -> pd.DataFrame:
    rows = []
    for stage, s in (("certified", reg.search), ("exact", reg.search_exact)):
        rows.append({"stage": stage, "rounds": s.rounds, "active_poses": len(s.active_q), "evaluations": s.evaluations,
                     "worst_p_found": s.worst_p, "converged": s.converged, "time_s": s.time_s})
    return pd.DataFrame(rows)


def end_to_end(reg, margin_reg, n_robots, n_margin, seed):
    """Monte Carlo at the worst poses of the certified, exact and margin designs: summary rows and per-pose frames."""
    rows, frames = [], []
    for label, res, which, n in (("certified, region", reg, "certified", n_robots),
                                 ("exact, region", reg, "chosen", n_robots),
                                 (f"exact, region, designed for p + {MARGIN:g}", margin_reg, "chosen", n_margin)):
        e = verify_calibrated_design(res, which=which, n_robots=n, seed=seed)
        d = e.to_dict()
        keys = ("n_robots", "poses", "verdict", "passed", "agree", "linear_optimistic", "p_linear_min", "p_mc_min",
                "ci_low_min", "fits_converged")
        rows.append({"design": label, **{k: d[k] for k in keys}})
        f = e.to_frame()
        f.insert(0, "design", label)
        frames.append(f)
    return pd.DataFrame(rows), pd.concat(frames, ignore_index=True)


def random_plan_costs(pr, split, cand, n, box, count, seed):
    """Region allocation (certified + exact) with ``count`` random ``n``-pose plans: their exact costs."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        plan = make_plan(pr.model.robot, cand[np.sort(rng.choice(len(cand), n, replace=False))])
        r = allocate_with_calibration(pr, plan, split=split, region=box, baseline=False, coverage_n=0, seed=seed)
        out.append(r.cost if r.design.ok else np.nan)
    return np.array(out)


def plan_rows(pr, split, cand, box, ns, n_rand_cost, n_cov, seed):
    """Per plan size: start (A-optimal) and designed plan costs, P against 200 random plans, random-plan costs."""
    rows, costs = [], []
    for n in ns:
        pa = design_plan_for_allocation(pr, n, cand, split=split, region=box, coverage_n=n_cov, seed=seed,
                                        baseline=False)
        start = allocate_with_calibration(pr, pa.start_plan, split=split, region=box, baseline=False, coverage_n=0,
                                          seed=seed)
        rc = random_plan_costs(pr, split, cand, n, box, n_rand_cost, seed + n)
        costs.append(pd.DataFrame({"n_poses": n, "random_plan": np.arange(1, len(rc) + 1), "cost_exact": rc}))
        for at, res in (("designed plan's design", pa.result), ("A-optimal plan's design", start)):
            q = res.problem.q  # the binding (active) poses of that design
            cmp = compare_with_random_plans(res, cand, count=200, seed=seed + 7, q_eval=q)
            d = cmp.to_dict()
            d["designed_worst_p"] = float(_worst(res, pa.plan, q))
            d["a_optimal_worst_p"] = float(_worst(res, pa.start_plan, q))
            d["better_than_share"] = float(np.mean(cmp.random < d["designed_worst_p"]))
            rows.append({"n_poses": n, "evaluated_at": at, **d, "cost_designed": pa.result.cost,
                         "cost_a_optimal": start.cost, "cost_random_median": float(np.nanmedian(rc)),
                         "cost_random_p10": float(np.nanquantile(rc, 0.1)),
                         "cost_below_share": float(np.mean(rc > pa.result.cost)),
                         "rounds": len(pa.history) - 1})
    return pd.DataFrame(rows), pd.concat(costs, ignore_index=True)


def _worst(res, plan, q):
    from tolalloc.calibration.design_worst import plan_worst_p

    return plan_worst_p(res.post.split, plan, q, res.problem.radius_mm).min()


def region_study(name, robot, pr, split, cand, out, quick, seed=0) -> dict:
    """All region sections for one robot; writes CSVs with the robot's name as prefix; returns the tables."""
    region = "working" if "working" in robot.regions else "limits"
    _, box, _ = resolve_region(robot, region)
    n_cov = 20_000 if quick else 100_000
    plan12 = design_plan(split, 12, cand, pr.q).plan  # what `tolalloc calplan --n-poses 12` writes
    poses, reg, designs = designs_over_region(pr, split, plan12, box, n_cov, seed)
    margin = allocate_with_calibration(pr, plan12, split=split, region=box, coverage_n=n_cov, seed=seed,
                                       design_prob=pr.prob + MARGIN, baseline=False)
    e2e, e2e_poses = end_to_end(reg, margin, 1000 if quick else 4000, 2000 if quick else 20_000, seed + 3)
    plans, rcosts = plan_rows(pr, split, cand, box, [12] if quick else [12, 30], 6 if quick else 40, n_cov, seed)
    tables = {"region_designs": designs, "region_search": search_table(reg), "region_end_to_end": e2e,
              "region_end_to_end_poses": e2e_poses, "plans": plans, "plan_random_costs": rcosts}
    for key, df in tables.items():
        df.to_csv(out / f"{name}_{key}.csv", index=False, float_format="%.6g")
    return {"region": region, "box": box, "poses": poses, "reg": reg, "margin": margin, "n_cov": n_cov, **tables}


def _md(df, floatfmt=".4g"):
    return markdown_table(df, floatfmt)


def region_markdown(name, r, prob) -> str:
    """The region part of the report for one robot (statements computed from the tables)."""
    d, e2e, plans = r["region_designs"], r["region_end_to_end"], r["plans"]
    pose_rows = d[d.allocated_on == "working poses"]
    reg_rows = d[(d.allocated_on == "region") & d.design.str.contains("calibrated")]
    poses, reg = r["poses"], r["reg"]
    p_work = float(poses.exact.p_post.min())
    gap = "; ".join(f"{row.design}: {row.poses_below_p} poses below p (min P {row.min_p_region:.4f})"
                    for row in pose_rows.itertuples())
    ok = "none" if reg_rows.none_below_p.all() else "SOME"
    same = (" The certified design allocated at the working poses already meets p over the region: the search added "
            "no pose to them." if reg.search.rounds == 1 and len(reg.search.active_q) == len(poses.problem.q) else "")
    robot = reg.problem.model.robot
    span = ", ".join(f"{lo:.4g}..{hi:.4g}" for lo, hi in zip(robot.q_to_interface(r["box"].q_min),
                                                            robot.q_to_interface(r["box"].q_max)))
    lines = [f"""## Over the working region

Region `{r['region']}` (q1..q{robot.n_joints} in deg / mm: {span}). Each design's post-calibration P on the same {r['n_cov']} fresh uniform poses of the region
(`tolalloc.allocate.region.coverage` with the post-calibration covariance; a pose counts as below when
P < p - 1e-4). Designs allocated at the working poses with the 12-pose plan `tolalloc calplan` writes (p =
{prob:g}): {gap}. Allocated over the region (cutting planes, `allocate_with_calibration(..., region=...)`) with the
same plan: {ok} of the fresh poses below p.{same}

{_md(d)}

Cutting-plane search over the region:

{_md(r['region_search'])}

Exact stage at the working poses: cost {poses.cost_exact:.4f} against the certified {poses.cost_certified:.4f}, worst
post-calibration P {p_work:.5f} (|P - p| = {abs(p_work - prob):.1e}). Over the region: exact {reg.cost_exact:.4f},
certified {reg.cost_certified:.4f}, without calibration {reg.cost_no_calibration:.4f} (exact), saving
{100 * (reg.cost_no_calibration - reg.cost) / reg.cost_no_calibration:.1f} %.

## End-to-end Monte Carlo at the region's worst poses

`tolalloc.verify.calibrated_worst.verify_calibrated_design`: manufacture with the design's sigmas, simulate the
12-pose plan's measurements, calibrate each robot by nonlinear least squares, compensate, measure at the design's
worst poses (the last search's worst pose, the 3 worst of the fresh coverage sample, the 3 lowest active poses).
Simultaneous 95 % Wilson intervals (the same robots at every pose, so the poses' estimates move together). A
certified design passes a pose when demonstrated (interval at or above p), an exact design -- which sits at p at its
binding poses by construction -- when consistent (interval reaches p); both need the linear prediction not above the
interval (`linear_optimistic`); `agree`: the linear prediction inside every interval. The third design is the exact region design solved for
p + {MARGIN:g}, checked with more robots, to show the demonstration in the strict sense.

{_md(e2e)}
"""]
    lines.append(plan_markdown(plans))
    return "\n".join(lines)


def plan_markdown(plans) -> str:
    """The plan-design part: designed against random plans of the same size."""
    show = plans[["n_poses", "evaluated_at", "designed_worst_p", "a_optimal_worst_p", "random_median", "random_p10",
                  "random_p90", "random_max", "better_than_share", "all_candidates_worst_p"]]
    cost = plans[plans.evaluated_at == "designed plan's design"][
        ["n_poses", "cost_designed", "cost_a_optimal", "cost_random_median", "cost_random_p10", "cost_below_share",
         "rounds"]]
    verdicts = []
    for row in plans[plans.evaluated_at == "designed plan's design"].itertuples():
        p_ok = row.designed_worst_p > row.random_p90
        c_ok = row.cost_designed < row.cost_random_p10
        verdicts.append(f"{row.n_poses} poses: worst-pose P {'above' if p_ok else 'NOT above'} the 90th percentile of "
                        f"200 random plans ({row.designed_worst_p:.5f} against {row.random_p90:.5f}); exact region cost "
                        f"{'below' if c_ok else 'NOT below'} the 10th percentile of the random plans' costs "
                        f"({row.cost_designed:.4f} against {row.cost_random_p10:.4f}). Headroom: every candidate "
                        f"measured reaches {row.all_candidates_worst_p:.5f} at this design, "
                        f"{row.all_candidates_worst_p - row.random_median:.4f} above the random median; no plan of "
                        "these candidates can pass it")
    return f"""## Plans designed for the allocation

`design_plan_for_allocation`: start from the A-optimal plan under the robot file's sigmas (what `calplan` writes),
allocate over the region, re-design the plan for that design (prior = the design's sigmas, evaluation poses = its
active poses, criterion = worst post-calibration P there), keep it if the allocation gets cheaper, repeat.
Worst-pose post-calibration P at a design's active poses, for the designed plan, the A-optimal plan and 200 random
plans of the same size from the same candidates (`compare_with_random_plans`); `all_candidates_worst_p`: every
candidate measured, a bound no plan from these candidates passes. At the designed plan's design the tolerances
are tuned to that plan; at the A-optimal plan's design they are not.

{_md(show, ".5g")}

Cost of the exact region design with each plan (each plan gets its own allocation: cost at equal P), against random
plans of the same size (`cost_below_share`: share of the random plans that are dearer):

{_md(cost, ".5g")}

""" + "\n".join(f"- {v}" for v in verdicts) + "\n"
