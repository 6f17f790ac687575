"""`tolalloc calplan ROBOT ...`: choose calibration poses for `allocate --calibration PLAN`."""

from __future__ import annotations

import argparse

from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import add_robot_arg, check_output, robot_kwargs
from tolalloc.workflows import defaults as D


def register(sub) -> None:
    p = sub.add_parser(
        "calplan", help="calibration-plan design: N measurement poses minimising the post-calibration error",
        description="Choose N laser-tracker measurement poses among scrambled-Sobol candidates (in the joint limits "
        "or in the box of a pose set) that minimise the mean post-calibration position variance of the systematic "
        "errors over the evaluation poses (task-weighted A-optimal design: convex relaxation solved by SciPy's "
        "interior-point method, the cvxpy SDP with Clarabel or Frank-Wolfe if that fails; rounding, greedy exchange), compared with N random candidates. "
        "Writes the plan CSV that "
        "`tolalloc allocate --calibration` reads.")
    add_robot_arg(p)
    p.add_argument("--n-poses", type=count, required=True, help="number of measurement poses N")
    p.add_argument("--region", default="limits", help="candidate region: 'limits' or a pose set's box (default limits)")
    p.add_argument("--eval-poses", default=None, metavar="SET",
                   help="evaluation pose set (default: 'working' if the robot has it, else nominal)")
    p.add_argument("--n-candidates", type=count, default=D.N_CANDIDATES,
                   help=f"candidate poses (default {D.N_CANDIDATES})")
    p.add_argument("--measurement", default="position", choices=["position", "pose"])
    p.add_argument("--noise-mm", type=float, default=D.NOISE_MM,
                   help=f"tracker noise sigma per coordinate [mm] (default {D.NOISE_MM:g})")
    p.add_argument("--noise-deg", type=float, default=D.NOISE_DEG, help="orientation noise sigma [deg] (pose only)")
    p.add_argument("--no-registration", action="store_true",
                   help="the tracker frame and tool offset are known (not estimated)")
    p.add_argument("--costs", metavar="FILE", help="costs file whose [calibration] table overrides the split")
    p.add_argument("--sigma-set", default=None, help="manufacturing sigma set of the robot file (the prior)")
    p.add_argument("--seed", type=seed, default=D.SEED, help="seed of the candidates and the random comparison plan")
    p.add_argument("--for-allocation", action="store_true",
                   help="design the plan for the calibration-aware allocation it serves (--radius-mm, --prob, --costs; "
                   "over the robot's working box if it has one): alternate allocation and a re-design that maximises "
                   "the worst post-calibration P at the design's binding poses, keep a plan only when the allocation "
                   "gets cheaper; compare it with --random-plans random plans of the same size")
    p.add_argument("--radius-mm", type=float, default=None,
                   help=f"with --for-allocation: required radius r [mm] (default {D.RADIUS_MM:g})")
    p.add_argument("--prob", type=float, default=None,
                   help=f"with --for-allocation: required probability p (default {D.PROB:g})")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="the stage on stderr (default: when stderr is a terminal)")
    p.add_argument("--random-plans", type=count, default=D.RANDOM_PLANS,
                   help="with --for-allocation: random plans of the same size compared (default 100)")
    p.add_argument("--out", metavar="FILE", required=True, help="plan CSV to write")
    p.set_defaults(func=cmd_calplan)


def cmd_calplan(args) -> int:
    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows import Costs, ErrorModelOptions, Measurement, PositionRequirement, plan_calibration

    check_output(args.out, "--out")
    target = args.for_allocation
    given = {k: v for k, v in (("radius_mm", args.radius_mm), ("prob", args.prob)) if v is not None}
    if given and not args.for_allocation:
        name, value = next(iter(given.items()))
        raise ArgumentError(name, f"{value!r} is read only for a plan designed for an allocation, but "
                            "`for_allocation` is off; add `for_allocation` (or leave out this option).")
    if args.for_allocation:
        target = PositionRequirement(**given)
    res = plan_calibration(args.robot, args.n_poses, region=args.region, eval_poses=args.eval_poses,
                           n_candidates=args.n_candidates,
                           measurement=Measurement(args.measurement, args.noise_mm, args.noise_deg,
                                                   not args.no_registration),
                           costs=Costs(args.costs), error_model=ErrorModelOptions(sigma_set=args.sigma_set),
                           seed=args.seed, for_allocation=target, random_plans=args.random_plans,
                           progress=args.progress, **robot_kwargs(args))
    print(res.text())
    res.save_plan(args.out)
    print(f"wrote {args.out}")
    return 0
