"""`tolalloc allocate ROBOT ...`: cheapest tolerances meeting P(|dP| < r) >= p at every working pose."""

from __future__ import annotations

import sys

from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, add_scheduler_arg, check_distinct_outputs,
                                 error_model_kwargs, flag_text, reserve_directory, robot_kwargs)


def register(sub) -> None:
    p = sub.add_parser(
        "allocate", help="tolerance allocation: cheapest tolerances meeting P(|dP| < r) >= p at every working pose",
        description="Allocate symmetric tolerances +-t (sigma = t/z) to the error parameters at least cost so that "
        "P(|dP| < r) >= p at every pose of a working-pose set. Certified designs (cvxpy + Clarabel: trace rule and "
        "eigenvalue/LMI rule, the cheaper kept) and the exact design (CasADi + IPOPT on the Gaussian probability, "
        "warm-started, never dearer); nonlinear Monte Carlo verification at every pose; ISO 286 grades. "
        "Prints the tolerance table; --out DIR writes tolerances.csv/.md/.tex, summary.json, verification.csv "
        "and figures. Cost laws and process limits: built-in assumed defaults or --costs FILE (TOML). With "
        "--calibration PLAN.csv the requirement holds after that calibration: certified stage, then exact stage "
        "(not with --solver certified), then standard grades (not with --no-snap), then an end-to-end Monte Carlo of "
        "simulated calibrations (not with --no-verify); no correction loop.")
    add_robot_arg(p)
    p.add_argument("--radius-mm", type=float, default=0.25, help="required radius r [mm] (default 0.25)")
    p.add_argument("--prob", type=float, default=0.95, help="required probability p (default 0.95)")
    p.add_argument("--poses", "--pose-set", dest="poses", default=None, metavar="SET",
                   help="pose set of the robot file, used without --region (default: 'working' if the robot has it, "
                   "else nominal); --region takes pose sets too")
    p.add_argument("--region", default=None, metavar="SPEC",
                   help="where the requirement must hold: a pose set of the robot file, 'limits' (the joint limits), "
                   "a region (box) of the robot file, or a trajectory CSV (a pose per row, deg / mm; with a header, "
                   "joint columns q1_deg / q4_mm ... or q1..qN). Boxes are "
                   "searched for their worst pose (cutting planes) and checked on a fresh sample. Default: the "
                   "robot's 'working' region if it has one, else the pose set (--poses)")
    p.add_argument("--coverage-n", type=count, default=100_000,
                   help="fresh poses for the coverage check of a box region, of the continuous and (with "
                   "--calibration) the standard design (default 1e5)")
    p.add_argument("--solver", default="exact", choices=["exact", "certified"],
                   help="design to report: exact (IPOPT, default) or certified (cvxpy + Clarabel); with "
                   "--calibration, certified stops after the certified stage (no exact stage)")
    p.add_argument("--costs", metavar="FILE", help="costs file (TOML): cost laws, process limits, fixed/excluded parameters")
    p.add_argument("--z", type=float, default=None, help="sigma = t / z (default 3, or the costs file's z)")
    p.add_argument("--uniform", action="store_true", help="uniform tolerance distribution: sigma = t / sqrt(3)")
    add_error_model_args(p, allocation=True)
    p.add_argument("--angle-radius-deg", type=float, default=None,
                   help="also require P(|rotation error| < this) >= --angle-prob [deg]")
    p.add_argument("--angle-prob", type=float, default=None, help="probability of the orientation requirement (default --prob)")
    p.add_argument("--n-mc", type=count, default=10**6,
                   help="Monte Carlo samples per pose for the verification (default 1e6); with --calibration the "
                   "simulated calibrations of the end-to-end check, clipped to 200 .. 4000")
    p.add_argument("--estimator", default="auto", choices=["auto", "plain", "paired", "importance"],
                   help="how P(|dP| < r) is estimated in the verification: paired = the exact linear P plus the mean "
                   "difference of nonlinear and linear indicators on shared draws; importance = that difference by "
                   "importance sampling (rare events); auto (default) = paired where the parameters are Gaussian, "
                   "plain Monte Carlo otherwise, importance sampling where the tail is too thin for --n-mc; "
                   "with --calibration auto, plain or paired")
    p.add_argument("--no-verify", action="store_true", help="skip the Monte Carlo verification")
    p.add_argument("--no-correction", action="store_true",
                   help="do not run the correction loop (by default, when a verified pose is not demonstrated - its "
                   "interval of P_hat (95%% simultaneous over the verified poses and requirements) not wholly >= p "
                   "- or demonstrated by less than 3 standard errors - its probability target is raised by the "
                   "shortfall of P_hat below the linear P plus z + 3 standard errors (z of each simultaneous "
                   "interval) and the allocation re-solved; the corrected design is then judged on fresh draws; "
                   "--calibration has no correction loop)")
    p.add_argument("--correction-rounds", type=int, default=None, metavar="N",
                   help="largest number of correction rounds before the loop stops and says so (default 2; not with "
                   "--calibration)")
    p.add_argument("--seed", type=seed, default=0, help="random seed of the verification")
    add_scheduler_arg(p, "the verification's Monte Carlo samples (not with --calibration)")
    p.add_argument("--angle-step-deg", type=float, default=None, help="snapping step for angles [deg] (default 1 arcsec)")
    p.add_argument("--no-snap", action="store_true", help="do not snap to ISO 286 grades / angle steps")
    p.add_argument("--calibration", metavar="PLAN.csv", default=None,
                   help="allocate for the accuracy after this calibration plan (from `tolalloc calplan`): the "
                   "certified calibration-aware design (eigenvalue rule on the post-calibration covariance), then "
                   "the exact stage on the post-calibration probability (skipped with --solver certified), then "
                   "standard grades; per parameter 'calibrated away', 'loose (at t_max)', 'loose (coarsest grade)' or 'must "
                   "be held'. Position "
                   "requirement only; refuses --correction-rounds, --scheduler and --estimator importance")
    p.add_argument("--out", metavar="DIR", help="write tables, summary.json and figures to DIR")
    p.add_argument("--report", metavar="DIR", help="write the same files and a self-contained report.html to DIR")
    p.set_defaults(func=cmd_allocate)


def cmd_allocate(args) -> int:
    from tolalloc.workflows import allocate_tolerances

    reserve_directory(args.out, "--out")
    reserve_directory(args.report, "--report")
    check_distinct_outputs([("--out", args.out), ("--report", args.report)])
    res = allocate_tolerances(
        args.robot, radius_mm=args.radius_mm, prob=args.prob, region=args.region, poses=args.poses, costs=args.costs,
        z=args.z, uniform=args.uniform, angle_radius_deg=args.angle_radius_deg, angle_prob=args.angle_prob,
        solver=args.solver, snap=not args.no_snap, angle_step_deg=args.angle_step_deg, calibration=args.calibration,
        verify=not args.no_verify, n_mc=args.n_mc, seed=args.seed, estimator=args.estimator,
        correction=False if args.no_correction else None, correction_rounds=args.correction_rounds,
        coverage_n=args.coverage_n, scheduler=args.scheduler,
        **error_model_kwargs(args), **robot_kwargs(args))
    if getattr(res, "infeasible", None) is not None:  # a region no design can cover: nothing to print or write
        print(f"error: {flag_text(res.infeasible, args)}", file=sys.stderr)
        return 1
    print(res.text())
    if not res.writable:
        return 1
    for folder, report in ((args.out, False), (args.report, True)):
        if folder is not None:
            names = res.save(folder, report=report)
            print(f"\nwrote {folder}/: {', '.join(names)}")
    return 0 if res.ok else 1
