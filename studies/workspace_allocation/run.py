"""Study: allocation over the working region against allocation at a pose set (issue 13, item 5).

Writes reports/workspace_allocation/: report.md, CSV tables and PNG figures.

For each robot, two designs at the same requirement P(|dP| < 0.25 mm) >= 0.95, exact solver (CasADi + IPOPT),
default costs:

* **pose set**: allocated at the robot's ``working`` pose set (today's default when a robot has no region);
* **region**: cutting planes over a box (``tolalloc.allocate.region.allocate_region``), started from the
  same pose set.

Regions: tool_changer its ``working`` box (robot file; an assumption: the box spanned by the 12 working
poses); ur10 its joint limits (``limits``: the robot file has no working box, and its 6 working poses are a
generic spread, so a box spanned by them would be arbitrary; the limits are every configuration the arm can
take). Both designs are checked on the same fresh seeded sample of the region (coverage: min P, fraction
below p and its one-sided 95 % upper bound) and by nonlinear Monte Carlo at their active poses and at the
worst poses of that sample. Figure: P on a 2-D slice through the worst sampled pose.

Usage: python studies/workspace_allocation/run.py [--quick] [--n-mc N] [--n-cov N] [--seed S]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.units import in_row_unit
from tolalloc.report.tables import markdown_table

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compute import history_rows, p_slice, run_robot, slice_joints, summary_rows, verification_rows  # noqa: E402
from figures import plot_slices  # noqa: E402

OUT = Path(__file__).resolve().parents[2] / "reports" / "workspace_allocation"
ROBOTS = (("tool_changer", "working"), ("ur10", "limits"))
WHY = {"working": "the robot file's `working` box (an assumption of the project: each joint between its min and "
                  "max over the 12 working poses)",
       "limits": "the joint limits (`--region limits`): the robot file has no working box and its 6 working poses "
                 "are a generic spread, so a box spanned by them would be arbitrary; the limits are every "
                 "configuration the arm can take (±360° per joint is two full turns, and P is 2π-periodic in "
                 "every revolute joint, so the uniform sample covers every configuration evenly)"}


def md(df: pd.DataFrame, floatfmt=".4g") -> str:
    return markdown_table(df, floatfmt)


def deg_mm(robot, q) -> str:
    return "(" + ", ".join(f"{v:.1f}" for v in robot.q_to_interface(q)) + ")"


def tolerance_rows(study) -> pd.DataFrame:
    """Both designs' tolerance and sigma per parameter (interface units), from ``AllocationResult.to_frame()``."""
    a, b = (d.result.to_frame(d.result.design) for d in study.designs)

    return pd.DataFrame({"robot": study.name, "parameter": a["parameter"], "unit": a["unit"],
                         "tolerance_pose_set": in_row_unit(a, "tol"), "tolerance_region": in_row_unit(b, "tol"),
                         "sigma_pose_set": in_row_unit(a, "sigma"), "sigma_region": in_row_unit(b, "sigma"),
                         "ratio_pose_set_over_region": in_row_unit(a, "tol") / in_row_unit(b, "tol"),
                         "at_limit_region": b["at_limit"]})


def figure(study, prob) -> tuple:
    """P slices through each design's worst sampled pose over the same two joints; returns (file, lines)."""
    ds, dr = study.designs
    joints = slice_joints(study, ds.coverage.worst_q[0], ds)
    slices = [p_slice(study, d, d.coverage.worst_q[0], joints) for d in study.designs]
    name = f"p_slice_{study.name}.png"
    titles = [f"{study.name}, {d.label} design\nslice through its worst sampled pose (star)" for d in study.designs]
    plot_slices(study.robot, slices, titles, prob, OUT / name)
    a, b = joints
    lines = [f"![P slice {study.name}]({name})", "",
             f"Slice over joints q{a + 1} and q{b + 1} (the two along which the pose-set design's P varies most "
             "through its worst sampled pose), ± a quarter of the region's range (at most ± 90°) around each "
             "design's worst sampled pose (star), the other joints held there, 61 × 61 grid; black line: P = p:", ""]
    for d, s in zip(study.designs, slices):
        lines.append(f"- {d.label} design, centre {deg_mm(study.robot, s['q_centre'])} deg / mm: min P on the slice "
                     f"{s['P'].min():.5f}, {100 * np.mean(s['P'] < prob - 1e-4):.1f} % of the grid below {prob:g} "
                     "(P < p − 1e-4, as in the coverage).")
    return name, lines + [""]


def robot_section(study, n_mc) -> list:
    ds, dr = study.designs
    rr, prob = dr.region_run, ds.result.problem.prob
    lines = [f"## {study.name} over {study.region.name}", "",
             f"Region: {WHY[study.region.name]}; q_min = {deg_mm(study.robot, study.region.q_min)}, "
             f"q_max = {deg_mm(study.robot, study.region.q_max)} (deg / mm). Joints held fixed by the search (they "
             f"cannot change the position error): {', '.join(f'q{j + 1}' for j in np.flatnonzero(rr.static)) or 'none'}.",
             ""]
    for d in study.designs:
        cov, ver = d.coverage, d.verification
        lines.append(f"- **{d.label} design** (cost {d.cost:.4f}, {len(d.active_q)} active poses): "
                     f"{cov.message(prob)}. Nonlinear Monte Carlo ({n_mc:.0e} samples per pose) at its "
                     f"{len(d.active_q)} active and {len(d.check_q) - len(d.active_q)} worst sampled poses: "
                     f"{ver.message()}.")
    prem = 100 * (dr.cost - ds.cost) / ds.cost
    lines += ["", f"The region design costs {prem:+.2f} % against the pose-set design; the search "
              f"{'converged' if rr.converged else 'did NOT converge'} in {rr.rounds} round(s) "
              f"({rr.evaluations} pose evaluations, {dr.wall_s:.1f} s wall, {dr.cpu_s:.1f} s CPU) and added "
              f"{len(dr.active_q) - len(ds.active_q)} pose(s) to the {len(ds.active_q)} of the pose set.", ""]
    lines += _verdict_note(study, prob)
    return lines


def _verdict_note(study, prob) -> list:
    """What the verdicts mean here, from the numbers (no sentence claims what the data do not show)."""
    out = []
    for d in study.designs:
        v = d.verification
        fail = np.flatnonzero(v.verdicts == "failed")
        if fail.size:
            out.append(f"- {d.label}: Monte Carlo **failed** at {fail.size} checked pose(s): "
                       + "; ".join(f"pose {i + 1} P̂ = {v.p_mc[i]:.5f} [{v.ci_low[i]:.5f}, {v.ci_high[i]:.5f}], "
                                   f"p is {prob - v.ci_high[i]:.5f} above its upper bound" for i in fail[:4])
                       + ("" if fail.size <= 4 else " …") + ".")
        cons = int(np.sum(v.verdicts == "consistent"))
        if cons:
            tight = int(np.sum((v.verdicts == "consistent") & (v.p_linear < prob + 1e-3)))
            out.append(f"- {d.label}: {cons} pose(s) consistent but not demonstrated ({tight} of them have a linear "
                       f"P within 0.001 of {prob:g}: a design that is tight at a pose cannot be demonstrated there "
                       "without a margin; the correction loop of `tolalloc.verify.correct` adds one, not run here).")
    return out + [""]


def write_tables(studies) -> dict:
    summary = pd.DataFrame([r for s in studies for r in summary_rows(s)])
    ver = pd.concat([verification_rows(s) for s in studies], ignore_index=True)
    hist = pd.concat([history_rows(s) for s in studies], ignore_index=True)
    tol = pd.concat([tolerance_rows(s) for s in studies], ignore_index=True)
    for name, f in (("summary", summary), ("verification", ver), ("region_history", hist), ("tolerances", tol)):
        f.to_csv(OUT / f"{name}.csv", index=False, float_format="%.8g")
    return {"summary": summary, "verification": ver, "history": hist, "tolerances": tol}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="10^4 coverage poses and 10^5 Monte Carlo samples per pose")
    ap.add_argument("--n-mc", type=int, default=None, help="Monte Carlo samples per pose (default 4e5; --quick 1e5)")
    ap.add_argument("--n-cov", type=int, default=None, help="fresh coverage poses (default 1e5; --quick 1e4)")
    ap.add_argument("--seed", type=int, default=2026, help="seed of the coverage sample and the Monte Carlo")
    args = ap.parse_args(argv)
    n_mc = args.n_mc or (10**5 if args.quick else 4 * 10**5)
    n_cov = args.n_cov or (10**4 if args.quick else 10**5)
    t0 = time.perf_counter()
    OUT.mkdir(parents=True, exist_ok=True)
    studies = [run_robot(name, spec, n_cov=n_cov, n_mc=n_mc, seed=args.seed) for name, spec in ROBOTS]
    prob = studies[0].designs[0].result.problem.prob
    tabs = write_tables(studies)
    cols = ["robot", "design", "cost", "cost_premium_pct", "time_wall_s", "time_cpu_s", "rounds", "active_poses",
            "search_evaluations", "coverage_min_p", "coverage_n_below", "coverage_frac_below",
            "coverage_frac_below_upper95", "mc_verdict", "mc_lowest_p_hat"]
    lines = ["# Allocation over the working region against allocation at a pose set", "",
             "Generated by `python studies/workspace_allocation/run.py" + (" --quick" if args.quick else "") + "`; "
             "every number below comes from that run (tables: `summary.csv`, `verification.csv`, "
             "`region_history.csv`, `tolerances.csv`).", "",
             f"Requirement P(|ΔP| < {studies[0].designs[0].result.problem.radius_mm:g} mm) ≥ {prob:g}; exact solver "
             "(CasADi + IPOPT), unsnapped, default cost laws and process limits (relative cost units, assumptions "
             "of `tolalloc.allocate.costs`). The **pose-set design** is allocated at the robot's `working` pose set; "
             "the **region design** by cutting planes over a box, started from the same poses (worst-pose search: "
             "512 scrambled-Sobol seeds and 6 bounded L-BFGS-B starts per round, stop when the shortfall is below "
             f"1e-4). Coverage: the linear P of each design on the same fresh uniform sample of the region "
             f"({n_cov:.0e} poses, seed {args.seed}); a pose counts as below when P < p − 1e-4; the bound on the "
             "fraction below is the one-sided 95 % Clopper-Pearson bound. Nonlinear Monte Carlo: "
             f"{n_mc:.0e} samples per pose (seed {args.seed + 1} / {args.seed + 2}) at each design's active poses and "
             "its 3 worst sampled poses, 95 % Wilson interval; a pose is *demonstrated* when the interval's lower "
             "bound is ≥ p, *consistent* when only its upper bound reaches p, else *failed*.", "",
             "## Summary", "", md(tabs["summary"][cols]), ""]
    for s in studies:
        lines += robot_section(s, n_mc)
        _, fig_lines = figure(s, prob)
        lines += fig_lines
    lines += ["## Cutting-plane rounds of the region designs", "", md(tabs["history"], ".6g"), "",
              "## Monte Carlo at the checked poses", "",
              md(tabs["verification"].drop(columns=["reason"]), ".5g"), "",
              f"Runtime of this study: {time.perf_counter() - t0:.0f} s (wall clock, 2 shared cores).", ""]
    (OUT / "report.md").write_text("\n".join(lines))
    print(f"wrote {OUT}/report.md ({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
