"""`tolalloc mc ROBOT --n N --seed S ...`: nonlinear Monte Carlo of the tool-pose error."""

from __future__ import annotations

import argparse

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import CLEARANCE_SIGMA, CLEARANCE_TILT_LITERAL_RAD
from tolalloc.montecarlo.run import run_mc
from tolalloc.cli.argtypes import count, nonnegative_int, positive_float, seed
from tolalloc.cli.output import output_group
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, add_scheduler_arg, check_distinct_outputs, check_output,
                     error_model_from_args, format_labels, parse_q, robot_from_args, write_json)


def register(sub) -> None:
    p = sub.add_parser(
        "mc", help="nonlinear Monte Carlo of the tool-pose error",
        description="Sample N robots with random errors (error screws, optional joint clearance), compute their exact "
        "tool poses and summarise the error: mean/std/max/min of dx, dy, dz [mm], |dp| [mm], the reach change "
        "|p'|-|p| (the paper's Table-3 'Δp'), X-Y-Z fixed Euler-angle errors [rad], and P(|dp| < r) with 95%% CIs.")
    add_robot_arg(p)
    add_error_model_args(p)
    p.add_argument("--n", type=count, required=True, help="number of samples (>= 1; 1e6 and 1_000_000 accepted)")
    p.add_argument("--seed", type=seed, default=0, help="random seed (same seed, same numbers)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--pose", metavar="Q_DEG_MM", help='joint values in deg / mm, e.g. "15,30,-10,0,-20,-5" (default: nominal)')
    g.add_argument("--pose-set", "--poses", dest="pose_set", metavar="NAME", help="a pose set of the robot file (e.g. working)")
    p.add_argument("--radius-mm", type=float, action="append", default=None, help="radius for P(|dp| < r) [mm]; repeatable (default 0.15, 0.25)")
    p.add_argument("--angle-radius-rad", type=float, action="append", default=None, help="radius for P(|rotation error| < r) [rad]; repeatable (default 0.002)")
    p.add_argument("--angle-radius-deg", type=float, action="append", default=None, help="the same in degrees; repeatable")
    p.add_argument("--ci", default="wilson", choices=["wilson", "exact"], help="95%% interval: Wilson (default) or Clopper-Pearson")
    add_scheduler_arg(p)
    p.add_argument("--jobs", type=count, default=None, help="local threads / Dask local workers (default: usable CPUs, at most 8)")
    p.add_argument("--chunk-size", type=count, default=2**20, help="samples per Dask task (default 1048576); never changes the numbers")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: for runs of 10^7 samples or more when stderr is a terminal)")
    p.add_argument("--hist-bins", type=nonnegative_int, default=0,
                   help="accumulate BINSxBINS x-y, x-z, y-z histograms of the position error over all samples "
                   "(with --out: mc_density.png and mc_hist.npz)")
    p.add_argument("--hist-range-mm", type=positive_float, default=None, help="half-width of the histogram window [mm] (default: 6 linear std per axis)")
    p.add_argument("--json", metavar="OUT", help="write the summary as JSON to OUT ('-' for stdout)")
    p.add_argument("--out", metavar="DIR", help="write mc_table.csv, mc_summary.json and mc_scatter.png to DIR")
    p.set_defaults(func=cmd_mc)


def summary_dict(res, robot) -> dict:
    """JSON-ready summary; per-pose arrays are flattened when there is one pose."""
    one = res.q.shape[0] == 1

    def f(a):
        a = np.asarray(a)
        return a[0].tolist() if one else a.tolist()

    def pw(d, key):
        return {f"{r:g}": {"p": f(v[:, 0]), "ci_low": f(v[:, 1]), "ci_high": f(v[:, 2]), key: r} for r, v in d.items()}

    return {
        "robot": robot.name, "n": res.n, "seed": res.seed, "labels": res.labels, "ci": res.ci,
        "q_deg_mm": f(robot.q_to_interface(res.q)),
        "mean_mm": f(res.mean_mm), "std_mm": f(res.std_mm), "cov_mm2": f(res.cov_mm2),
        "max_mm": f(res.dp_max_mm), "min_mm": f(res.dp_min_mm),
        "norm_mm": f(res.norm_mm), "reach_mm": f(res.reach_mm),
        "angle_mean_rad": f(res.angle_mean_rad), "angle_std_rad": f(res.angle_std_rad),
        "rotvec_std_rad": f(res.rotvec_std_rad),
        "p_within": pw(res.p_within, "radius_mm"), "p_within_angle": pw(res.p_within_angle, "radius_rad"),
        "stats_order": "norm_mm and reach_mm are [mean, std, max, min]; angles are X-Y-Z fixed [alpha, beta, gamma]",
    }


def cmd_mc(args) -> int:
    check_output(args.out, "--out", directory=True)
    check_output(args.json, "--json")
    check_distinct_outputs([("--out", args.out), ("--json", args.json)])
    robot = robot_from_args(args)
    model = error_model_from_args(robot, args)
    if args.pose:
        q = parse_q(args.pose, robot, "--pose")
    else:
        q = robot.poses(args.pose_set)
    radii = args.radius_mm if args.radius_mm else [0.15, 0.25]
    aradii = list(args.angle_radius_rad or []) + [np.deg2rad(a) for a in (args.angle_radius_deg or [])] or [0.002]
    for r in [*radii, *aradii]:
        if not np.isfinite(r) or r <= 0:
            raise TolallocError(f"--radius-mm / --angle-radius-*: expected radii > 0, got {r}.")
    keep = min(args.n, 20000) if args.out else 0
    if args.hist_range_mm is not None and not args.hist_bins:
        raise TolallocError(f"--hist-range-mm {args.hist_range_mm:g} sets the histogram window, but no histogram is "
                            "made; add --hist-bins BINS (e.g. --hist-bins 100) or leave out --hist-range-mm.")
    res = run_mc(model, q, args.n, args.seed, radii_mm=radii, angle_radii_rad=aradii, keep_samples=keep, ci=args.ci,
                 n_jobs=args.jobs, scheduler=args.scheduler, chunk_size=args.chunk_size, progress=args.progress,
                 hist_bins=args.hist_bins, hist_range_mm=args.hist_range_mm)
    summary = summary_dict(res, robot)
    if res.hist is not None:
        summary["hist_fraction_outside"] = (res.hist.outside / res.n).tolist()
    summary["labels"] = {**summary["labels"], "clearance_tilt_rad": (CLEARANCE_TILT_LITERAL_RAD if args.clearance_tilt_literal
                                                                     else CLEARANCE_SIGMA["tilt_rad"]) if args.clearance else None}
    with output_group() as out:  # --out and --json are published together
        if args.out is not None:
            from tolalloc.report.plots.mc import scatter_density
            import matplotlib.pyplot as plt

            tmp = out.directory(args.out)
            res.to_frame().to_csv(tmp / "mc_table.csv", index=False)
            write_json(summary, tmp / "mc_summary.json")
            fig = scatter_density(res, tmp / "mc_scatter.png")
            plt.close(fig)
            if res.hist is not None:
                from tolalloc.report.plots.mc import hist_density

                plt.close(hist_density(res, tmp / "mc_density.png"))
                np.savez_compressed(tmp / "mc_hist.npz", counts=res.hist.counts, edges_mm=res.hist.edges_mm,
                                    outside=res.hist.outside, n=res.hist.n, planes=np.array(res.hist.planes))
        if args.json is not None and args.json != "-":
            write_json(summary, out.file(args.json))
    if args.json == "-":
        write_json(summary, "-")
    if not args.json or args.json != "-":
        tab = res.to_frame()
        print(f"robot {robot.name}, n={res.n}, seed={res.seed}, {format_labels(res.labels)}")
        print(tab.to_string(index=False, float_format=lambda x: f"{x:.6g}"))
        for r, v in res.p_within.items():
            print(f"P(|dp| < {r:g} mm) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v))
    return 0
