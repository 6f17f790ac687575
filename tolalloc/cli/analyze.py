"""`tolalloc analyze ROBOT ...`: linear variance map, P(|dp| < r), radius for a probability, error budget."""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.linear.covariance import budget, linear_map
from tolalloc.cli.argtypes import count
from tolalloc.cli.output import output_group
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, check_distinct_outputs, check_output, error_model_from_args,
                     format_labels, parse_q, robot_from_args, write_json)


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
    g.add_argument("--pose", metavar="Q_DEG_MM", help='joint values in deg / mm, e.g. "15,30,-10,0,-20,-5" (default: nominal)')
    g.add_argument("--poses", "--pose-set", dest="poses", metavar="SET",
                   help="a pose set of the robot file (e.g. working), or 'nominal'")
    p.add_argument("--radius-mm", type=float, action="append", default=[], metavar="R",
                   help="radius for P(|dp| < r) [mm]; repeatable")
    p.add_argument("--prob", type=float, action="append", default=[], metavar="P",
                   help="probability in (0, 1) for the radius with P(|dp| < r) = P [mm]; repeatable")
    p.add_argument("--top", type=count, default=10, help="budget rows printed (default 10)")
    p.add_argument("--json", metavar="OUT", help="write the results as JSON to OUT ('-' for stdout)")
    p.add_argument("--out", metavar="DIR", help="write linear_table.csv, budget.csv, budget_kinds.csv, budget.md, "
                   "budget.png and analyze.json to DIR")
    p.set_defaults(func=cmd_analyze)


def _pose_dict(res, b, i, radii, probs, robot) -> dict:
    frame = b.to_frame(pose=i)
    kinds = b.to_frame(pose=i, by="kind")
    keep = [c for c in frame.columns if c != "pose"]
    d = {
        "pose": i + 1,
        "q_deg_mm": robot.q_to_interface(res.q[i]),
        "std_mm": res.std_mm[i],
        "covariance_mm2": res.cov_mm2[i],
        "rms_mm": float(res.rms_mm[i]),
        "std_rot_deg": np.rad2deg(res.std_rot_rad[i]),
        "covariance_rot_rad2": res.cov_rot_rad2[i],
    }
    if radii:
        d["p_within_radius"] = {f"{r:g}": float(res.p_within(r)[i]) for r in radii}
    if probs:
        d["radius_mm_for_prob"] = {f"{p:g}": float(res.radius_for(p)[i]) for p in probs}
    d["budget"] = {
        "parameters": frame[keep].to_dict(orient="records"),
        "kinds": kinds[[c for c in kinds.columns if c != "pose"]].to_dict(orient="records"),
    }
    return d


def analyze_dict(res, radii, probs) -> dict:
    """JSON-ready results: the worst pose's values at top level, every pose under ``poses`` if several."""
    robot = res.model.robot
    b = budget(res)
    worst = b.worst_pose
    out = {"robot": robot.name, "labels": res.model.labels, "method": "linear (first order), Gaussian approximation",
           "n_poses": res.n_poses, "worst_pose": worst + 1, "pose_numbering": "1-based, in the order of the pose set",
           "budget_columns": "var_*_mm2: contribution to the variance [mm^2]; share_*: fraction of it; norm = trace",
           **_pose_dict(res, b, worst, radii, probs, robot)}
    if res.n_poses > 1:
        out["poses"] = [_pose_dict(res, b, i, radii, probs, robot) for i in range(res.n_poses)]
    return out


def cmd_analyze(args) -> int:
    check_output(args.out, "--out", directory=True)
    check_output(args.json, "--json")
    check_distinct_outputs([("--out", args.out), ("--json", args.json)])
    robot = robot_from_args(args)
    for r in args.radius_mm:
        if not np.isfinite(r) or r <= 0:
            raise TolallocError(f"--radius-mm: expected a radius > 0 [mm], got {r!r}.")
    for p in args.prob:
        if not np.isfinite(p) or not 0 < p < 1:
            raise TolallocError(f"--prob: expected a probability strictly between 0 and 1 (e.g. 0.95), got {p!r}.")
    if args.top < 1:
        raise TolallocError(f"--top: expected a number of rows >= 1, got {args.top}.")
    model = error_model_from_args(robot, args)
    q = parse_q(args.pose, robot, "--pose") if args.pose else robot.poses(args.poses)
    res = linear_map(model, q)
    summary = analyze_dict(res, args.radius_mm, args.prob)
    summary["labels"] = {**summary["labels"], "clearance": bool(args.clearance)}
    b = budget(res)
    with output_group() as out:  # --out and --json are published together
        if args.out is not None:
            import matplotlib.pyplot as plt

            from tolalloc.report.plots.linear import budget_bars

            tmp = out.directory(args.out)
            res.to_frame().to_csv(tmp / "linear_table.csv", index=False, float_format="%.6g")
            b.write_csv(tmp / "budget.csv")
            b.write_csv(tmp / "budget_kinds.csv", by="kind")
            with open(tmp / "budget.md", "w") as fh:
                fh.write(f"# Error budget of {robot.name} (worst pose {b.worst_pose + 1}), {format_labels(model.labels)}\n\n")
                fh.write(b.to_markdown(pose="worst", by="kind") + "\n\n" + b.to_markdown(pose="worst") + "\n")
            fig = budget_bars(b, tmp / "budget.png", top=args.top)
            plt.close(fig)
            write_json(summary, tmp / "analyze.json")
        if args.json is not None and args.json != "-":
            write_json(summary, out.file(args.json))
    if args.json == "-":
        write_json(summary, "-")
    if args.json != "-":
        print(f"robot {robot.name}, {format_labels(model.labels)}, clearance={bool(args.clearance)}; linear map, Gaussian approximation")
        print(res.to_frame().to_string(index=False, float_format=lambda x: f"{x:.5g}"))
        for r in args.radius_mm:
            print(f"P(|dp| < {r:g} mm) = " + ", ".join(f"{v:.6g}" for v in res.p_within(r)))
        for p in args.prob:
            print(f"radius for P = {p:g}: " + ", ".join(f"{v:.5g}" for v in res.radius_for(p)) + " mm")
        print(f"\nerror budget at the worst pose ({b.worst_pose + 1}), top {args.top}:")
        print(b.to_markdown(pose="worst", top=args.top))
    return 0
