"""`tolalloc review ROBOT --drawing FILE`: tolerance analysis of an existing drawing (the reverse of `allocate`)."""

from __future__ import annotations

from tolalloc.cli.argtypes import seed
from tolalloc.cli.common import add_robot_arg, check_output, robot_kwargs, write_json


def register(sub) -> None:
    p = sub.add_parser(
        "review", help="tolerance analysis of an existing drawing: P at the worst pose, each feature's share",
        description="Design review of an existing drawing: its zones, fits, grades and bought parts (the drawing "
        "exchange CSV that `allocate --out` writes as drawing.csv, or one written by hand in its schema) are mapped "
        "back to the error parameters' sigmas; prints P(|dp| < r) under the linear Gaussian map at every pose and "
        "at the worst pose of the region, and each feature's share of the error variance there. A zone or grade "
        "finer than every process of the built-in table, a fit that is not ISO 286 or a span of zero is one error "
        "naming the row.")
    add_robot_arg(p)
    p.add_argument("--drawing", required=True, metavar="FILE", help="drawing exchange CSV (drawing.csv)")
    p.add_argument("--radius-mm", type=float, default=0.25, help="required radius r [mm] (default 0.25)")
    p.add_argument("--prob", type=float, default=0.95, help="required probability p (default 0.95)")
    p.add_argument("--region", default=None, metavar="SPEC",
                   help="where the requirement holds: a box of the robot file, 'limits', a pose set or a trajectory "
                   "CSV (default: the robot's working box, else its working pose set)")
    p.add_argument("--z", type=float, default=None,
                   help="sigma = t / z (default: the z the drawing file records, else 3; a value that disagrees "
                        "with the file is refused)")
    p.add_argument("--uniform", action="store_true", help="errors uniform over +-t: sigma = t / sqrt(3)")
    p.add_argument("--sigma-set", default=None, help="sigma set for parameters the drawing does not bound "
                   "(with --others model)")
    p.add_argument("--others", default="error", choices=["error", "model"],
                   help="a parameter no row bounds: an error (default), or the error model's own sigma")
    p.add_argument("--seed", type=seed, default=0, help="seed of the worst-pose search (default 0)")
    p.add_argument("--json", metavar="OUT", help="write the review as JSON to OUT ('-' for stdout)")
    p.add_argument("--out", metavar="DIR", help="write review_features.csv, review_poses.csv and review.json to DIR")
    p.set_defaults(func=cmd_review)


def cmd_review(args) -> int:
    from tolalloc.workflows.review import review_drawing

    check_output(args.out, "--out", directory=True)
    check_output(args.json, "--json")
    from tolalloc.workflows import Costs, ErrorModelOptions

    res = review_drawing(args.robot, args.drawing, radius_mm=args.radius_mm, prob=args.prob, region=args.region,
                         costs=Costs(z=args.z, uniform=args.uniform),
                         error_model=ErrorModelOptions(sigma_set=args.sigma_set), others=args.others,
                         seed=args.seed, **robot_kwargs(args))
    if args.out:
        res.save(args.out)
    if args.json == "-":
        write_json(res.summary(), "-")
    else:
        if args.json:
            write_json(res.summary(), args.json)
        print(res.text())
    return 0
