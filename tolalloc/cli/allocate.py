"""`tolalloc allocate ROBOT ...`: cheapest tolerances meeting P(|dP| < r) >= p at every working pose."""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, add_scheduler_arg, atomic_output, check_output,
                                 error_model_from_args, robot_from_args, write_json)


def register(sub) -> None:
    p = sub.add_parser(
        "allocate", help="tolerance allocation: cheapest tolerances meeting P(|dP| < r) >= p at every working pose",
        description="Allocate symmetric tolerances +-t (sigma = t/z) to the error parameters at least cost so that "
        "P(|dP| < r) >= p at every pose of a working-pose set. Certified designs (cvxpy + Clarabel: trace rule and "
        "eigenvalue/LMI rule, the cheaper kept) and the exact design (CasADi + IPOPT on the Gaussian probability, "
        "warm-started, never dearer); nonlinear Monte Carlo verification at every pose; ISO 286 grades. "
        "Prints the tolerance table; --out DIR writes tolerances.csv/.md/.tex, summary.json, verification.csv "
        "and figures. Cost laws and process limits: built-in assumed defaults or --costs FILE (TOML).")
    add_robot_arg(p)
    p.add_argument("--radius-mm", type=float, default=0.25, help="required radius r [mm] (default 0.25)")
    p.add_argument("--prob", type=float, default=0.95, help="required probability p (default 0.95)")
    p.add_argument("--poses", "--pose-set", dest="poses", default=None, metavar="SET",
                   help="pose set of the robot file (default: 'working' if the robot has it, else nominal)")
    p.add_argument("--region", default=None, metavar="SPEC",
                   help="where the requirement must hold: a pose set of the robot file, 'limits' (the joint limits), "
                   "a region (box) of the robot file, or a trajectory CSV (q1..qN per row, deg / mm). Boxes are "
                   "searched for their worst pose (cutting planes) and checked on a fresh sample. Default: the "
                   "robot's 'working' region if it has one, else the pose set (--poses)")
    p.add_argument("--coverage-n", type=count, default=100_000,
                   help="fresh poses for the coverage check of a box region (default 1e5)")
    p.add_argument("--solver", default="exact", choices=["exact", "certified"],
                   help="design to report: exact (IPOPT, default) or certified (cvxpy + Clarabel)")
    p.add_argument("--costs", metavar="FILE", help="costs file (TOML): cost laws, process limits, fixed/excluded parameters")
    p.add_argument("--z", type=float, default=None, help="sigma = t / z (default 3, or the costs file's z)")
    p.add_argument("--uniform", action="store_true", help="uniform tolerance distribution: sigma = t / sqrt(3)")
    add_error_model_args(p, allocation=True)
    p.add_argument("--angle-radius-deg", type=float, default=None,
                   help="also require P(|rotation error| < this) >= --angle-prob [deg]")
    p.add_argument("--angle-prob", type=float, default=None, help="probability of the orientation requirement (default --prob)")
    p.add_argument("--n-mc", type=count, default=10**6, help="Monte Carlo samples per pose for the verification (default 1e6)")
    p.add_argument("--no-verify", action="store_true", help="skip the Monte Carlo verification")
    p.add_argument("--no-correction", action="store_true",
                   help="do not run the correction loop (by default, when a verified pose is not demonstrated - its "
                   "95%% interval of P_hat not wholly >= p - its probability target is raised by the shortfall of "
                   "P_hat below the linear P plus 3 standard errors and the allocation re-solved)")
    p.add_argument("--correction-rounds", type=int, default=2, metavar="N",
                   help="largest number of correction rounds before the loop stops and says so (default 2)")
    p.add_argument("--seed", type=seed, default=0, help="random seed of the verification")
    add_scheduler_arg(p, "the verification's Monte Carlo samples")
    p.add_argument("--angle-step-deg", type=float, default=None, help="snapping step for angles [deg] (default 1 arcsec)")
    p.add_argument("--no-snap", action="store_true", help="do not snap to ISO 286 grades / angle steps")
    p.add_argument("--calibration", metavar="PLAN.csv", default=None,
                   help="allocate for the accuracy after this calibration plan (from `tolalloc calplan`): certified "
                   "calibration-aware design, per parameter 'calibrated away' or 'must be held'")
    p.add_argument("--out", metavar="DIR", help="write tables, summary.json and figures to DIR")
    p.set_defaults(func=cmd_allocate)


def _poses_of(robot, name):
    if name is None:
        name = "working" if "working" in robot.pose_sets else "nominal"
    return name, robot.poses(name)


def _region_of(robot, args):
    """``(name, box Region or None, poses (P, n) [rad, mm])`` from --region / --poses."""
    from pathlib import Path

    from tolalloc.allocate.region import box_region

    regions = robot.regions
    spec = args.region
    if spec is None:
        if args.poses is None and "working" in regions:
            spec = "working"
        else:
            name, q = _poses_of(robot, args.poses)
            return name, None, q
    if spec == "limits":
        return spec, box_region(robot, robot.lower, robot.upper, "limits", "--region limits"), None
    if spec in regions:
        lo, hi = regions[spec]
        return spec, box_region(robot, lo, hi, spec, f"--region {spec}"), None
    if spec in robot.pose_sets or spec == "nominal":
        return spec, None, robot.poses(spec)
    if spec.lower().endswith(".csv") or Path(spec).is_file():
        return spec, None, _trajectory(robot, spec)
    known = ", ".join(["limits", *regions, "nominal", *robot.pose_sets])
    raise TolallocError(f"--region: {spec!r} is neither a region, a pose set nor a trajectory CSV file; "
                        f"known: {known}, or give a path to a .csv file.")


def _trajectory(robot, path):
    """Rows q1..qN [deg / mm] of a CSV file -> (P, n) [rad, mm]; header line optional."""
    from pathlib import Path

    p = Path(path)
    if not p.is_file():
        raise TolallocError(f"--region {path}: no such trajectory file; give a CSV with one pose (q1..qN, deg / mm) per row.")
    try:
        rows = np.genfromtxt(p, delimiter=",", dtype=float, skip_header=0)
    except ValueError as exc:
        raise TolallocError(f"--region {path}: cannot read the trajectory ({exc}); expected {robot.n_joints} "
                            "comma-separated numbers per row.") from None
    rows = np.atleast_2d(rows)
    if rows.size and np.all(np.isnan(rows[0])):  # a header line
        rows = rows[1:]
    if rows.ndim != 2 or rows.shape[0] == 0 or rows.shape[1] != robot.n_joints:
        raise TolallocError(f"--region {path}: expected rows of {robot.n_joints} joint values (deg / mm), got shape "
                            f"{rows.shape}.")
    if not np.all(np.isfinite(rows)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(rows), axis=1))[0]) + 1
        raise TolallocError(f"--region {path}: row {bad} has a missing or non-finite value; every joint value must "
                            "be a finite number (deg / mm).")
    return robot.check_q(rows, f"--region {path}", interface=True)


def cmd_allocate(args) -> int:
    from tolalloc.allocate import allocate, build_problem
    from tolalloc.allocate.costs import cost_set, load_costs
    from tolalloc.report.tables import format_text

    _check_args(args)
    robot = robot_from_args(args)
    dist = "uniform" if args.uniform else None
    model = error_model_from_args(robot, args)
    costs = (load_costs(args.costs, model, z=args.z, distribution=dist) if args.costs
             else cost_set(model, None, z=args.z, distribution=dist))
    set_name, region, q = _region_of(robot, args)
    if args.calibration is not None:
        from tolalloc.cli.calplan import run_calibrated

        if region is not None:
            if args.region is not None:
                raise TolallocError(f"--calibration: the calibration-aware allocation works on a pose set, got the "
                                    f"box region {set_name!r}; give --poses SET (or --region SET with a pose set).")
            set_name, q = _poses_of(robot, None)  # the robot's default pose set instead of its default box
        problem = build_problem(model, q, radius_mm=args.radius_mm, prob=args.prob, costs=costs,
                                angle_radius_deg=args.angle_radius_deg, angle_prob=args.angle_prob)
        return run_calibrated(args, problem, set_name)
    kw = dict(radius_mm=args.radius_mm, prob=args.prob, costs=costs, angle_radius_deg=args.angle_radius_deg,
              angle_prob=args.angle_prob)
    reg_info = None
    if region is not None:
        from tolalloc.allocate.region import allocate_region

        q0 = robot.poses("working") if "working" in robot.pose_sets else None
        if q0 is not None and not np.all((q0 >= region.q_min - 1e-12) & (q0 <= region.q_max + 1e-12)):
            q0 = None
        reg_info = allocate_region(model, region, q0, solver=args.solver, **kw)
        q = reg_info.active_q
    res = allocate(build_problem(model, q, **kw), solver=args.solver, snap=not args.no_snap,
                   angle_step_deg=args.angle_step_deg)
    if region is not None and res.status == "infeasible":
        return _region_infeasible(args, region, reg_info, res)
    res, cov, ver, corr = _verify_and_correct(args, model, kw, res, region)
    table = res.to_frame()
    table["design"] = _design_note(res, corr)
    summary = _summary(res, robot, set_name, region, reg_info, cov, ver, corr)
    if reg_info is not None:
        print(f"region {region.name}: {reg_info.rounds} round(s), {len(reg_info.active_q)} active poses, "
              f"{reg_info.evaluations} search evaluations, worst linear P found {reg_info.worst_p:.5f}"
              + ("" if reg_info.converged else " (NOT converged: round limit reached)"))
    if cov is not None:
        print(cov.message(args.prob))
    _print(res, table, ver, set_name, format_text, corr)
    if args.out is not None:
        _write_outputs(args, robot, set_name, res, table, summary, ver, corr)
    if res.status != "optimal" or (cov is not None and not cov.ok):
        return 1
    return 0 if ver is None or ver.ok else 1


def _region_infeasible(args, region, reg_info, res) -> int:
    """One ``error:`` line for a region infeasible even at the tightest process limits; exit 1, nothing written."""
    import sys

    from tolalloc.allocate.region import worst_pose

    pr = res.problem
    robot = pr.model.robot
    q, p_best, _ = worst_pose(pr, res.design.t, region, seed=args.seed, fixed=reg_info.static)
    p_set = float(res.diagnosis.p_best["position"].min())
    if p_set < p_best:  # an active pose is worse than what the search found
        q, p_best = pr.q[int(np.argmin(res.diagnosis.p_best["position"]))], p_set
    qi = robot.q_to_interface(q)
    joints = ", ".join(f"{j.name} = {v:.4g} {j.unit}"
                       for j, v in zip(robot.joints, qi))
    flag = f"--region {args.region}" if args.region is not None else f"--region {region.name} (the robot's default)"
    binding = ", ".join(f"{n} ({s:.0%})" for n, s in res.diagnosis.binding[:4])
    print(f"error: {flag}: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} is infeasible over the region even with every "
          f"tolerance at its tightest process limit: at the worst pose found ({joints}) the best achievable P is "
          f"{p_best:.4f}" + (f"; limits that bind: {binding}" if binding else "")
          + ". Lower these t_min in a costs file (--costs), relax --radius-mm / --prob, or use a smaller region; "
          "nothing written.", file=sys.stderr)
    return 1


def _verify_and_correct(args, model, kw, res, region):
    """Coverage of a box region, Monte Carlo verification and the correction loop.

    Returns ``(result, coverage, verification, correction)``: the final (corrected) allocation and its checks.
    """
    from tolalloc.allocate.problem import build_problem, make_design
    from tolalloc.allocate.region import coverage

    if res.status != "optimal":
        return res, None, None, None
    cov, vproblem, vdesign = None, res.problem, res.design
    if region is not None:
        cov = coverage(res.problem, res.design.t, region, n=args.coverage_n, seed=args.seed + 12345)
        vproblem = build_problem(model, np.vstack([res.problem.q, cov.worst_q]), **kw)
        vdesign = make_design(vproblem, res.design.solver, res.design.t, fallback_from=res.design.fallback_from)
    if args.no_verify:
        return res, cov, None, None
    from tolalloc.verify.designs import verify_design

    ver = verify_design(vproblem, vdesign, n_mc=args.n_mc, seed=args.seed, scheduler=args.scheduler)
    if ver.verdict == "demonstrated" or args.no_correction:
        return res, cov, ver, None
    from tolalloc.verify.correct import correct_design

    corr = correct_design(model, vproblem.q, solver=args.solver, n_mc=args.n_mc, seed=args.seed,
                          max_rounds=args.correction_rounds, result=res, verification=ver, snap=not args.no_snap,
                          angle_step_deg=args.angle_step_deg, scheduler=args.scheduler, keep_samples=4000, **kw)
    if corr.rounds and region is not None:  # the corrected design, checked over the region again
        cov = coverage(corr.result.problem, corr.result.design.t, region, n=args.coverage_n, seed=args.seed + 12345)
    return corr.result, cov, corr.verification, corr


def _design_note(res, corr) -> str:
    """What the tables hold: the design's label, and whether it is the corrected one."""
    note = f"{res.design.label}"
    if corr is not None and corr.rounds:
        note += (f", corrected for the nonlinear Monte Carlo ({corr.rounds} round(s), poses "
                 f"{', '.join(str(i + 1) for i in corr.tightened)} tightened, {corr.premium_pct:+.2f}% cost)")
    return note


def _summary(res, robot, set_name, region, reg_info, cov, ver, corr) -> dict:
    """summary.json: the allocation, the region search, the coverage check, the verification and the correction."""
    summary = res.summary()
    summary["pose_set"] = set_name
    summary["tables_design"] = _design_note(res, corr)
    summary["correction"] = None if corr is None else corr.to_dict()
    if reg_info is not None:
        summary["region"] = {"name": region.name, "q_min_deg_mm": robot.q_to_interface(region.q_min),
                             "q_max_deg_mm": robot.q_to_interface(region.q_max), "rounds": reg_info.rounds,
                             "converged": reg_info.converged, "active_poses": len(reg_info.active_q),
                             "search_evaluations": reg_info.evaluations, "worst_p_linear": reg_info.worst_p,
                             "static_joints": [int(j) + 1 for j in np.flatnonzero(reg_info.static)],
                             "time_s": reg_info.time_s}
    if cov is not None:
        summary["coverage"] = {"n": cov.n, "min_p": cov.min_p, "n_below": cov.n_below,
                               "frac_below": cov.frac_below, "frac_below_upper95": cov.frac_below_upper95}
    if ver is not None:
        summary["verification"] = {"criterion": ver.criterion, "ok": ver.ok, "message": ver.message(),
                                   "n_per_pose": ver.n, "seed": ver.seed}
        for i, row in enumerate(summary["poses"]):
            row.update({"p_mc": float(ver.p_mc[i]), "p_mc_ci": [float(ver.ci_low[i]), float(ver.ci_high[i])]})
            if ver.angle is not None:
                row.update({"p_mc_angle": float(ver.angle["p_mc"][i]),
                            "p_mc_angle_ci": [float(ver.angle["ci_low"][i]), float(ver.angle["ci_high"][i])]})
            row.update({"n_mc": int(ver.n[i]), "passed": bool(ver.passed[i]), "verdict": str(ver.verdicts[i]),
                        "reason": ver.reason[i]})
        summary["verification"]["verdict"] = ver.verdict
        summary["verification"]["verdicts"] = ver.verdicts.tolist()
    return summary


def _write_outputs(args, robot, set_name, res, table, summary, ver, corr) -> None:
    """The --out directory: tables, summary.json, verification.csv and figures, published all at once."""
    from tolalloc.report.tables import write_tables

    with atomic_output(args.out, directory=True) as tmp:
        write_tables(table, tmp, caption=f"Tolerances of {robot.name}: P(|dP| < {args.radius_mm:g} mm) >= "
                     f"{args.prob:g} at the {set_name} poses", note=f"design: {_design_note(res, corr)}")
        write_json(summary, tmp / "summary.json")
        from tolalloc.report.plots.allocate import plot_budget, plot_cloud, plot_pose_probabilities

        plot_budget(table, tmp / "error_budget.png",
                    title=f"{robot.name}: {res.design.label} design, worst pose {res.worst_pose + 1}")
        if ver is not None:
            ver.to_frame().to_csv(tmp / "verification.csv", index=False, float_format="%.8g")
            plot_pose_probabilities(ver, tmp / "pose_probabilities.png")
            if ver.samples_mm is not None:
                plot_cloud(ver, tmp / "error_cloud.png")
    print(f"\nwrote {args.out}/: tolerances.csv, tolerances.md, tolerances.tex, summary.json, error_budget.png"
          + (", verification.csv, pose_probabilities.png, error_cloud.png" if ver is not None else ""))


def _check_args(args) -> None:
    """Refuse bad numbers by their flag names before any computation, and an output that cannot be written."""
    def positive(value, flag, unit, example):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise TolallocError(f"{flag}: expected a finite number > 0 [{unit}] (e.g. {flag} {example}), got {value!r}.")

    def probability(value, flag):
        if value is not None and not (np.isfinite(value) and 0 < value < 1):
            raise TolallocError(f"{flag}: expected a probability strictly between 0 and 1 (e.g. {flag} 0.95), got {value!r}.")

    positive(args.radius_mm, "--radius-mm", "mm", "0.25")
    probability(args.prob, "--prob")
    positive(args.angle_radius_deg, "--angle-radius-deg", "deg", "0.02")
    probability(args.angle_prob, "--angle-prob")
    if args.angle_prob is not None and args.angle_radius_deg is None:
        raise TolallocError(f"--angle-prob {args.angle_prob:g} needs an orientation requirement: add --angle-radius-deg A.")
    positive(args.angle_step_deg, "--angle-step-deg", "deg", "0.001")
    if args.uniform and args.z is not None:
        raise TolallocError("--uniform and --z both set sigma = t / z; give one of them.")
    if args.z is not None and not (np.isfinite(args.z) and args.z > 0):
        raise TolallocError(f"--z: expected a number > 0 (sigma = t / z, e.g. --z 3), got {args.z!r}.")
    if args.correction_rounds < 0:
        raise TolallocError(f"--correction-rounds: expected a whole number >= 0 (rounds of the correction loop, e.g. "
                            f"--correction-rounds 2), got {args.correction_rounds}; or use --no-correction.")
    if args.n_mc < 100 and not args.no_verify:
        raise TolallocError(f"--n-mc: expected at least 100 samples per pose, got {args.n_mc}; or use --no-verify.")
    check_output(args.out, "--out", directory=True)


def _print(res, table, ver, set_name, format_text, corr=None) -> None:
    pr = res.problem
    print(f"robot: {pr.model.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} at "
          f"{pr.n_poses} {set_name} pose(s)" + ("" if pr.angle_radius_rad is None else
                                               f", P(|dw| < {np.rad2deg(pr.angle_radius_rad):g} deg) >= {pr.angle_prob:g}"))
    print(f"costs: {pr.costs.source}; sigma = t / {pr.costs.z:.4g}"
          + ("; errors uniform over +-t" if pr.costs.distribution == "uniform" else ""))
    if res.status == "not_converged":
        print(f"\nstatus: NOT CONVERGED   design: {res.design.label}   cost: {res.design.cost:.4f}\n{res.message}")
        print("\nthe non-converged design (for reference only):")
        print(format_text(table))
        return
    if res.status != "optimal":
        print(f"\nstatus: INFEASIBLE. {res.message}")
        print("\ntightest design the process limits allow (for reference):")
        print(format_text(table))
        return
    s = res.summary()["costs"]

    def c(x, d=None):
        if x is not None:
            return f"{x:.4f}"
        return "n/a" if d is None or not d.message else f"n/a, {d.status}: {d.message}"

    print(f"status: optimal   design: {res.design.label}   cost: {res.design.cost:.4f}")
    print(f"cost: certified {c(s['certified'], res.certified)} ({s['certified_rule']}; {s['certified_other_rule']}: "
          f"{c(s['certified_other'], res.certified_other)})   exact {c(s['exact'])}"
          + ("" if s["saving"] is None else f"   saving {s['saving']:.4f} ({s['saving_pct']:.2f}%)"))
    if res.design.message:
        print(f"note: {res.design.message}")
    print()
    print(format_text(table))
    if res.standard is not None:
        print(f"\nstandard grades (tolerance_std, it_grade): cost {res.standard.cost:.4f}; {res.standard.message}")
    p = res.design.p_linear["position"]
    print(f"\nlinear P per pose: min {p.min():.4f} (pose {int(np.argmin(p)) + 1}), max {p.max():.4f}")
    if ver is not None:
        print(ver.message())
        print("verdict per pose: " + ", ".join(f"{i + 1} {v}" for i, v in enumerate(ver.verdicts))
              + f"; overall: {ver.verdict}")
    if corr is not None:
        print(f"correction: {corr.message()}")
        if corr.rounds:
            print("the tolerance table above is the corrected design's")
