"""`tolalloc mc ROBOT --n-mc N --seed S ...`: nonlinear Monte Carlo of the tool-pose error."""

from __future__ import annotations

import argparse

from tolalloc.cli.argtypes import count, nonnegative_int, positive_float, seed
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, add_scheduler_arg, check_distinct_outputs,
                                 check_output, error_model_options, parse_q, reserve_directory, robot_kwargs)
from tolalloc.workflows import defaults as D


def register(sub) -> None:
    p = sub.add_parser(
        "mc", help="nonlinear Monte Carlo of the tool-pose error",
        description="Sample N robots with random errors (error screws, optional joint clearance), compute their exact "
        "tool poses and summarise the error: mean/std/max/min of dx, dy, dz [mm], |dp| [mm], the reach change "
        "|p'|-|p| (the paper's Table-3 'Δp'), X-Y-Z fixed Euler-angle errors [rad], and P(|dp| < r) with 95 % CIs.")
    add_robot_arg(p)
    add_error_model_args(p)
    p.add_argument("--n-mc", "--n", dest="n_mc", type=count, default=D.SIMULATION_N_MC,
                   help=f"number of sampled robots (>= 1; 1e6 and 1_000_000 accepted; default {D.SIMULATION_N_MC:,}, "
                   "as in Python; --n is the former name)")
    p.add_argument("--seed", type=seed, default=D.SEED, help="random seed (same seed, same numbers)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--pose", "--q", dest="pose", metavar="Q_DEG_MM",
                   help='joint values in deg / mm, e.g. "15,30,-10,0,-20,-5" (default: nominal; --q is the same flag, '
                   "as in fk)")
    g.add_argument("--pose-set", "--poses", dest="pose_set", metavar="NAME", help="a pose set of the robot file (e.g. working)")
    p.add_argument("--radius-mm", type=float, action="append", default=None, help="radius for P(|dp| < r) [mm]; repeatable (default "
                   + ", ".join(f"{r:g}" for r in D.SIMULATION_RADII_MM) + ")")
    p.add_argument("--angle-radius-rad", type=positive_float, action="append", default=None, help="radius for P(|rotation error| < r) [rad]; repeatable (default 0.002)")
    p.add_argument("--angle-radius-deg", type=float, action="append", default=None, help="the same in degrees, not with --angle-radius-rad; repeatable")
    p.add_argument("--estimator", default=None, choices=["auto", "plain", "paired", "importance"],
                   help="also estimate each P(|dp| < r) with this estimator (paired: exact linear P plus the mean "
                   "difference of nonlinear and linear indicators on the same draws), with its interval, discordant "
                   "samples and variance reduction against plain Monte Carlo")
    p.add_argument("--ci", default=D.CI, choices=["wilson", "exact"], help="95%% interval: Wilson (default) or Clopper-Pearson")
    add_scheduler_arg(p)
    p.add_argument("--jobs", type=count, default=None, help="local threads / Dask local workers (default: usable CPUs, at most 8)")
    p.add_argument("--chunk-size", type=count, default=D.CHUNK_SIZE, help="samples per Dask task (default 1048576); never changes the numbers")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr: a bar on a terminal, one line when done in a pipe or log (default: for "
                   "runs of 10^7 samples or more)")
    p.add_argument("--hist-bins", type=nonnegative_int, default=0,
                   help="accumulate BINSxBINS x-y, x-z, y-z histograms of the position error over all samples "
                   "(with --out: mc_density.png and mc_hist.npz)")
    p.add_argument("--hist-range-mm", type=positive_float, default=None, help="half-width of the histogram window [mm] (default: 6 linear std per axis)")
    p.add_argument("--json", metavar="OUT", help="write the summary as JSON to OUT ('-' for stdout)")
    p.add_argument("--out", metavar="DIR", help="write mc_table.csv, mc_summary.json and mc_scatter.png to DIR")
    p.set_defaults(func=cmd_mc)


def cmd_mc(args) -> int:
    import math

    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows import MonteCarlo, simulate_errors

    reserve_directory(args.out, "--out")
    check_output(args.json, "--json")
    check_distinct_outputs([("--out", args.out), ("--json", args.json)])
    if args.angle_radius_rad and args.angle_radius_deg:
        raise ArgumentError("angle_radius_deg", f"{args.angle_radius_deg} and `angle_radius_rad` "
                            f"{args.angle_radius_rad} both give the radii of the rotation error; give one of them (a "
                            "list gives several radii).")
    angles = args.angle_radius_deg or ([math.degrees(r) for r in args.angle_radius_rad] if args.angle_radius_rad
                                       else None)
    mc = MonteCarlo(args.n_mc, args.seed, args.ci, args.estimator, None if args.out else 0, args.hist_bins,
                    args.hist_range_mm, args.scheduler, args.jobs, args.chunk_size)
    res = simulate_errors(
        args.robot, q_deg_mm=parse_q(args.pose, "--pose") if args.pose else None, poses=args.pose_set,
        radius_mm=args.radius_mm if args.radius_mm else D.SIMULATION_RADII_MM, angle_radius_deg=angles,
        error_model=error_model_options(args), monte_carlo=mc, progress=args.progress, **robot_kwargs(args))
    if args.out or args.json:
        res.save(args.out, json=args.json)
    if args.json != "-":
        print(res.text())
    return 0
