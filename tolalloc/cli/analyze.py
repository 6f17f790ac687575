"""`tolalloc analyze ROBOT ...`: linear variance map, P(|dp| < r), radius for a probability, error budget."""

from __future__ import annotations

from tolalloc.cli.argtypes import count, nonnegative_int, seed
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, check_distinct_outputs, check_output,
                                 error_model_options, parse_q, reserve_directory, robot_kwargs)
from tolalloc.workflows import defaults as D


def register(sub) -> None:
    p = sub.add_parser(
        "analyze", help="linear variance map, probabilities and error budget",
        description="First-order (linear) tool-position error: covariance J S Jᵀ from the analytic error-screw "
        "Jacobian, standard deviations [mm], P(|dp| < r) and the radius for a probability under the Gaussian "
        "approximation, and the error budget (each parameter's and kind's share of the variance of x, y, z and "
        "of |dp|², dominant first). Clearance enters by its second moments only (it is not Gaussian); check "
        "with `tolalloc mc` when it matters.")
    add_robot_arg(p)
    add_error_model_args(p)
    g = p.add_mutually_exclusive_group()
    g.add_argument("--pose", "--q", dest="pose", metavar="Q_DEG_MM",
                   help='joint values in deg / mm, e.g. "15,30,-10,0,-20,-5" (default: nominal; --q is the same flag, '
                   "as in fk)")
    g.add_argument("--poses", "--pose-set", dest="poses", metavar="SET",
                   help="a pose set of the robot file (e.g. working), or 'nominal'")
    p.add_argument("--radius-mm", type=float, action="append", default=[], metavar="R",
                   help="radius for P(|dp| < r) [mm]; repeatable")
    p.add_argument("--prob", type=float, action="append", default=[], metavar="P",
                   help="probability in (0, 1) for the radius with P(|dp| < r) = P [mm]; repeatable")
    p.add_argument("--top", type=count, default=D.TOP, help=f"budget rows printed (default {D.TOP})")
    p.add_argument("--sobol-n", type=nonnegative_int, default=0, metavar="N",
                   help="also Sobol' first-order and total indices of |dp| (and of the pass/fail indicator for the "
                   "first --radius-mm) at the worst pose from the nonlinear model, N base samples (N (K + 2) chain "
                   "evaluations; e.g. 4096), beside the linear variance shares; default 0: none")
    p.add_argument("--seed", type=seed, default=D.SEED, help=f"seed of the Sobol' samples (default {D.SEED})")
    p.add_argument("--json", metavar="OUT", help="write the results as JSON to OUT ('-' for stdout)")
    p.add_argument("--out", metavar="DIR", help="write linear_table.csv, budget.csv, budget_kinds.csv, budget.md, "
                   "budget.png and analyze.json to DIR")
    p.set_defaults(func=cmd_analyze)


def cmd_analyze(args) -> int:
    from tolalloc.workflows import analyze_errors

    reserve_directory(args.out, "--out")
    check_output(args.json, "--json")
    check_distinct_outputs([("--out", args.out), ("--json", args.json)])
    res = analyze_errors(args.robot, q_deg_mm=parse_q(args.pose, "--pose") if args.pose else None, poses=args.poses,
                         radius_mm=args.radius_mm, prob=args.prob, top=args.top, sobol_n=args.sobol_n,
                         seed=args.seed, error_model=error_model_options(args), **robot_kwargs(args))
    if args.out or args.json:
        res.save(args.out, json=args.json)
    if args.json != "-":
        print(res.text())
    return 0
