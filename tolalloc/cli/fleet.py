"""`tolalloc fleet ROBOT TRAIN.csv TRAIN.csv ... --out DIR [--tolerances tolerances.csv] [--json OUT]`."""

from __future__ import annotations

from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import add_robot_arg, check_distinct_outputs, check_output, robot_from_args, trusting


def register(sub) -> None:
    p = sub.add_parser(
        "fleet", help="pool a fleet of measured robots: achieved mean and spread per parameter, Cpk",
        description="Diagnose every robot's measurement file (one robot each, one model, ideally one pose plan) and "
        "pool them: per identifiable parameter the fleet's mean and robot-to-robot spread with intervals "
        "(random-effects model on the de-shrunk estimates), the shared (systematic) error a design change would "
        "remove, and with --tolerances the allocated spread of every combination, its Cpk and the tolerances over- "
        "or under-achieved. Robots whose verdict is inconclusive, or whose poses identify other combinations, are "
        "left out with the reason. Writes fleet.csv, robots.csv (and tolerance_parameters.csv), spread.png.")
    add_robot_arg(p)
    p.add_argument("measurements", nargs="+", metavar="TRAIN.csv", help="one measurement file per robot (>= 2)")
    p.add_argument("--out", required=True, metavar="DIR", help="directory to write the tables and the figure into")
    p.add_argument("--tolerances", metavar="TOL.csv", default=None,
                   help="the tolerances.csv of `tolalloc allocate --out` the robots were built to (default error "
                   "model)")
    p.add_argument("--level", type=float, default=0.95, help="two-sided confidence level of the intervals (0.95)")
    p.add_argument("--folds", type=count, default=5, help="cross-validation folds of each diagnosis (default 5)")
    p.add_argument("--seed", type=seed, default=0, help="seed of each diagnosis's folds (default 0)")
    p.add_argument("--json", metavar="OUT.json", help="write the summary as JSON ('-' for stdout)")
    p.set_defaults(func=cmd_fleet)


def cmd_fleet(args) -> int:
    from tolalloc.workflows.fleet import fleet

    check_output(args.json, "--json")
    check_output(args.out, "--out", directory=True)
    check_distinct_outputs([("--out", args.out), ("--json", args.json)],
                           inputs=[(f"TRAIN {i + 1}", m) for i, m in enumerate(args.measurements)]
                           + [("--tolerances", args.tolerances)])
    with trusting(args):
        res = fleet(args.measurements, robot=robot_from_args(args), tolerances=args.tolerances, level=args.level,
                    folds=args.folds, seed=args.seed, trust_units=args.trust_units)
    res.save(args.out, json=args.json)
    print(res.text())
    return 0
