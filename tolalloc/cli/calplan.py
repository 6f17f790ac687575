"""`tolalloc calplan ROBOT ...`: choose calibration poses; and the `allocate --calibration PLAN` branch."""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.cli.common import add_robot_arg, atomic_output, check_output, robot_from_args, write_json


def register(sub) -> None:
    p = sub.add_parser(
        "calplan", help="calibration-plan design: N measurement poses minimising the post-calibration error",
        description="Choose N laser-tracker measurement poses among scrambled-Sobol candidates (in the joint limits "
        "or in the box of a pose set) that minimise the mean post-calibration position variance of the systematic "
        "errors over the evaluation poses (task-weighted A-optimal design: convex relaxation as a cvxpy SDP solved "
        "by Clarabel, Frank-Wolfe if that fails; rounding, greedy exchange), compared with N random candidates. "
        "Writes the plan CSV that "
        "`tolalloc allocate --calibration` reads.")
    add_robot_arg(p)
    p.add_argument("--n-poses", type=int, required=True, help="number of measurement poses N")
    p.add_argument("--region", default="limits", help="candidate region: 'limits' or a pose set's box (default limits)")
    p.add_argument("--eval-poses", default=None, metavar="SET",
                   help="evaluation pose set (default: 'working' if the robot has it, else nominal)")
    p.add_argument("--n-candidates", type=int, default=2000, help="candidate poses (default 2000)")
    p.add_argument("--measurement", default="position", choices=["position", "pose"])
    p.add_argument("--noise-mm", type=float, default=0.02, help="tracker noise sigma per coordinate [mm] (default 0.02)")
    p.add_argument("--noise-deg", type=float, default=0.001, help="orientation noise sigma [deg] (pose only)")
    p.add_argument("--no-registration", action="store_true",
                   help="the tracker frame and tool offset are known (not estimated)")
    p.add_argument("--costs", metavar="FILE", help="costs file whose [calibration] table overrides the split")
    p.add_argument("--sigma-set", default=None, help="manufacturing sigma set of the robot file (the prior)")
    p.add_argument("--seed", type=int, default=0, help="seed of the candidates and the random comparison plan")
    p.add_argument("--out", metavar="FILE", required=True, help="plan CSV to write")
    p.set_defaults(func=cmd_calplan)


def split_from_costs(model, path):
    """The error split with the costs file's ``[calibration]`` overrides (defaults without a file)."""
    from tolalloc.calibration.split import split_errors

    if path is None:
        return split_errors(model)
    from tolalloc.allocate.costs import cost_set, read_costs_file

    data = read_costs_file(path)
    cost_set(model, data, source=str(path))  # the whole file is checked, not only its [calibration] table
    return split_errors(model, data.get("calibration"))


def cmd_calplan(args) -> int:
    from tolalloc.calibration.design import candidate_poses, design_plan
    from tolalloc.calibration.plan import write_plan
    from tolalloc.errormodel import build_error_model

    robot = robot_from_args(args)
    if args.n_candidates < 1:
        raise TolallocError(f"--n-candidates: expected a whole number >= 1, got {args.n_candidates}.")
    for flag, v in (("--noise-mm", args.noise_mm), ("--noise-deg", args.noise_deg)):
        if not (np.isfinite(v) and v > 0):
            raise TolallocError(f"{flag}: expected a finite noise standard deviation > 0, got {v!r}.")
    check_output(args.out, "--out")
    model = build_error_model(robot, args.sigma_set)
    split = split_from_costs(model, args.costs)
    ev = args.eval_poses or ("working" if "working" in robot.pose_sets else "nominal")
    cand = candidate_poses(robot, args.n_candidates, args.region, seed=args.seed)
    d = design_plan(split, args.n_poses, cand, robot.poses(ev), measurement=args.measurement, noise_mm=args.noise_mm,
                    noise_deg=args.noise_deg, registration=not args.no_registration, seed=args.seed)
    from tolalloc.calibration.posterior import posterior

    unid = posterior(split, d.plan).unidentifiable
    print(f"robot: {robot.name}   {args.n_poses} poses of {len(cand)} candidates ({args.region}), evaluated at the "
          f"{ev} poses; {args.measurement} measurement, noise {args.noise_mm:g} mm")
    print(f"mean post-calibration variance of the systematic part [mm^2]: designed {d.score_mm2:.6g}, "
          f"random {d.random_score_mm2:.6g}; all {len(cand)} candidates {d.floor_mm2:.6g}; "
          f"relaxation lower bound {d.relaxation_bound_mm2:.6g}")
    print(f"relaxation: {d.relaxation_method} ({d.relaxation_note}); value {d.relaxation_value_mm2:.6g} mm^2")
    print(f"above the all-candidates floor: designed {d.score_mm2 - d.floor_mm2:.4g}, random "
          f"{d.random_score_mm2 - d.floor_mm2:.4g} mm^2   ({d.time_s:.2f} s)")
    if unid:
        print(f"not identifiable with this plan (keep their manufacturing tolerance): {', '.join(unid)}")
    with atomic_output(args.out) as tmp:
        write_plan(d.plan, robot, tmp)
    print(f"wrote {args.out}")
    return 0


def run_calibrated(args, problem, set_name) -> int:
    """The `allocate --calibration PLAN` branch: certified calibration-aware design, table and summary."""
    from tolalloc.allocate.calibrated import allocate_calibrated
    from tolalloc.calibration.plan import read_plan

    robot = problem.model.robot
    plan = read_plan(args.calibration, robot)
    split = split_from_costs(problem.model, args.costs)
    res = allocate_calibrated(problem, plan, split=split)
    print(f"robot: {robot.name}   requirement: P(|dP| < {problem.radius_mm:g} mm) >= {problem.prob:g} after "
          f"calibration at {problem.n_poses} {set_name} pose(s); plan {args.calibration}: {plan.n_poses} "
          f"{plan.measurement} measurements, noise {plan.noise_mm:g} mm")
    if not res.design.ok:
        print(f"status: INFEASIBLE. {res.design.message}")
        return 1
    s = res.summary()
    verdict = "certified" if res.certified else f"NOT certified (lambda_max / bound = {res.ratio:.6f} > 1)"
    base = "n/a" if s["cost_no_calibration"] is None else f"{s['cost_no_calibration']:.4f}"
    print(f"design: {res.design.solver} ({verdict}; {res.design.message})   cost {s['cost']:.4f}   "
          f"without calibration {base}" + ("" if s["saving"] is None else
                                           f"   saving {s['saving']:.4f} ({s['saving_pct']:.2f}%)"))
    if res.grade_t is not None:
        print(f"  of which repeatability grades {s['cost_repeatability_grades']:.4f} (parts {s['cost_parts']:.4f}); "
              f"without calibration: the loosest grades, {res.grade_cost_loosest:.4f}")
    table = res.to_frame()
    print()
    print(table.to_string(index=False, float_format=lambda x: f"{x:.5g}"))
    if s["unidentifiable"]:
        print(f"\nnot identifiable by the plan (must be held in manufacturing): {', '.join(s['unidentifiable'])}")
    chk = None
    if not args.no_verify and plan.measurement == "position":
        from tolalloc.verify.calibrated import verify_calibration

        n = max(200, min(args.n_mc, 4000))
        chk = verify_calibration(res.post.split, plan, problem.q, problem.radius_mm, n_robots=n, seed=args.seed)
        p_ok = bool(np.all(chk.ci_high >= problem.prob))
        print(f"\nend-to-end Monte Carlo ({n} simulated robots, nonlinear calibration each): {chk.message()}; "
              f"smallest P_hat {chk.p_mc.min():.4f}" + ("" if p_ok else f" -- below p = {problem.prob:g} beyond "
                                                       "its interval at some pose"))
        s["end_to_end"] = {"n_robots": n, "agree": bool(np.all(chk.agree)), "p_mc_min": float(chk.p_mc.min()),
                           "p_linear_min": float(chk.p_linear.min())}
    if args.out:
        with atomic_output(args.out, directory=True) as tmp:
            table.to_csv(tmp / "calibrated_tolerances.csv", index=False, float_format="%.8g")
            if chk is not None:
                chk.to_frame().to_csv(tmp / "end_to_end.csv", index=False, float_format="%.8g")
            write_json({**s, "pose_set": set_name, "plan": str(args.calibration)}, tmp / "summary.json")
        print(f"\nwrote {args.out}/: calibrated_tolerances.csv, summary.json"
              + (", end_to_end.csv" if chk is not None else ""))
    return 0 if res.certified and (chk is None or bool(np.all(chk.agree))) else 1
