"""`tolalloc allocate ROBOT ...`: cheapest tolerances meeting P(|dP| < r) >= p at every working pose."""

from __future__ import annotations

import sys

from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import (add_error_model_args, add_robot_arg, add_scheduler_arg, check_distinct_outputs,
                                 error_model_options, flag_text, reserve_directory, robot_kwargs)
from tolalloc.workflows import defaults as D


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
    p.add_argument("--radius-mm", type=float, default=None, help=f"required radius r [mm] (default {D.RADIUS_MM:g})")
    p.add_argument("--prob", type=float, default=None, help=f"required probability p (default {D.PROB:g})")
    p.add_argument("--requirement", metavar="FILE", default=None,
                   help="requirements from a TOML file (schema: tolalloc.acceptance.requirement_file; example: "
                   "examples/requirements_iso9283.toml): ISO 9283 pose accuracy and repeatability (AP, RP, position "
                   "and orientation), distance and path accuracy, each for a share of the built robots at a load and "
                   "velocity, beside the error balls; its [test] table lays out the acceptance test (cube in the "
                   "working region --region, P1-P5, cycles, laser tracker, registration). The design is allocated for "
                   "all of them, the acceptance test predicted (datasheet with ISO 14253-1 verdicts) and simulated on "
                   "--n-robots robots (not with --no-verify); --out writes tolerances, datasheet.csv/.md, "
                   "simulation.csv, summary.json and acceptance.png. Not with --radius-mm / --prob / --angle-* (the "
                   "file states the balls), --calibration or --report; --n-mc, --estimator, --coverage-n, "
                   "--correction-rounds, --no-correction and --scheduler do not apply")
    p.add_argument("--n-robots", type=count, default=2000,
                   help="with --requirement: robots of the simulated acceptance test (default 2000)")
    p.add_argument("--poses", "--pose-set", dest="poses", default=None, metavar="SET",
                   help="pose set of the robot file, used without --region (default: 'working' if the robot has it, "
                   "else nominal); --region takes pose sets too")
    p.add_argument("--region", default=None, metavar="SPEC",
                   help="where the requirement must hold: a pose set of the robot file, 'limits' (the joint limits), "
                   "a region (box) of the robot file, or a trajectory CSV (a pose per row, deg / mm; with a header, "
                   "joint columns q1_deg / q4_mm ... or q1..qN). Boxes are "
                   "searched for their worst pose (cutting planes) and checked on a fresh sample. Default: the "
                   "robot's 'working' region if it has one, else the pose set (--poses)")
    p.add_argument("--coverage-n", type=count, default=D.COVERAGE_N,
                   help="fresh poses for the coverage check of a box region, of the continuous and (with "
                   "--calibration) the standard design (default 1e5)")
    p.add_argument("--solver", default=D.SOLVER, choices=["exact", "certified"],
                   help="design to report: exact (IPOPT, default) or certified (cvxpy + Clarabel); with "
                   "--calibration, certified stops after the certified stage (no exact stage)")
    p.add_argument("--costs", metavar="FILE", help="costs file (TOML): cost laws, process limits, fixed/excluded parameters")
    p.add_argument("--z", type=float, default=None, help="sigma = t / z (default 3, or the costs file's z)")
    p.add_argument("--uniform", action="store_true", help="uniform tolerance distribution: sigma = t / sqrt(3)")
    add_error_model_args(p, allocation=True)
    p.add_argument("--angle-radius-deg", type=float, default=None,
                   help="also require P(|rotation error| < this) >= --angle-prob [deg]")
    p.add_argument("--angle-prob", type=float, default=None, help="probability of the orientation requirement (default --prob)")
    p.add_argument("--n-mc", type=count, default=D.N_MC,
                   help=f"Monte Carlo samples per pose for the verification (default {D.N_MC:.0e}, as in Python); "
                   "with --calibration the "
                   "simulated calibrations of the end-to-end check, clipped to 200 .. 4000")
    p.add_argument("--estimator", default=D.ESTIMATOR, choices=["auto", "plain", "paired", "importance"],
                   help="how P(|dP| < r) is estimated in the verification: paired = the exact linear P plus the mean "
                   "difference of nonlinear and linear indicators on shared draws; importance = that difference by "
                   "importance sampling (rare events); auto (default) = paired where the parameters are Gaussian, "
                   "plain Monte Carlo otherwise, importance sampling for a rare tail (1 - p <= 0.001), where the "
                   "tail is too thin for --n-mc, and as the second look at a pose whose interval straddles p; "
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
    p.add_argument("--seed", type=seed, default=D.SEED, help="random seed of the verification, the coverage sample "
                   "and the region search")
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
    _add_parts_args(p)
    p.add_argument("--out", metavar="DIR", help="write tables, summary.json and figures to DIR")
    p.add_argument("--report", metavar="DIR", help="write the same files and a self-contained report.html to DIR")
    p.set_defaults(func=cmd_allocate)


def _add_parts_args(p) -> None:
    """The flags of the design with bought parts."""
    parts = p.add_argument_group("bought parts (robot files whose [components] name catalogue slots)")
    parts.add_argument("--parts", action="store_true",
                       help="choose the catalogue parts (reducer grades, bearings, encoders) with the machining "
                       "tolerances, over a payload and an ambient range; the worst point checked by the physical "
                       "Monte Carlo (--n-mc draws). Position requirement only; not with --calibration")
    parts.add_argument("--part", action="append", metavar="JOINT.KIND=NAME", default=None,
                       help="with --requirement: the catalogue part of one slot in the ISO 9283 acceptance test (e.g. "
                       "elbow_joint.encoder=RING-100-STD), repeated per slot; slots of one part need none. With "
                       "--requirement, --parts alone takes the parts the robot file names")
    parts.add_argument("--parts-file", metavar="PARTS.csv", default=None,
                       help="with --requirement: the parts a design with bought parts chose (the parts.csv of "
                       "`allocate ROBOT --parts --out DIR`) in the ISO 9283 acceptance test; --part overrides a slot")
    parts.add_argument("--payload-kg", type=float, nargs=2, metavar=("LOW", "HIGH"), default=None,
                       help="with --parts: payload range [kg] (default 0 to the robot's rated payload)")
    parts.add_argument("--ambient-c", type=float, nargs=2, metavar=("LOW", "HIGH"), default=None,
                       help="with --parts: ambient temperature range [degC] (default the 20 degC reference)")
    parts.add_argument("--duty", type=float, default=None, metavar="FRACTION",
                       help="with --parts: share of the time the drives work, for their heat (default 0.5)")
    parts.add_argument("--process-force-n", type=float, nargs=3, metavar=("FX", "FY", "FZ"), default=None,
                       help="with --parts: a process force [N] at the tool point in the tool frame, at every pose (a "
                       "drill's thrust, a cutting force): the joints, beams and mount carry it beside gravity")
    parts.add_argument("--process-torque-nm", type=float, nargs=3, metavar=("MX", "MY", "MZ"), default=None,
                       help="with --parts: a process moment [N m] at the tool point in the tool frame, at every pose")
    parts.add_argument("--after-compensation", action="store_true",
                       help="with --parts: the requirement holds after the compensation models (stiffness given the "
                       "payload, thermal growth given the temperature) remove their share of the parts' errors")


def settings(args) -> dict:
    """The settings objects of the command's flags (the keyword arguments of ``allocate_tolerances``)."""
    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows import (Costs, OrientationRequirement, PositionRequirement, Region, Solver,
                                    Verification)

    if args.angle_prob is not None and args.angle_radius_deg is None:
        raise ArgumentError("angle_prob", f"{args.angle_prob:g} needs an orientation requirement: add "
                            "`angle_radius_deg` A.")
    requirement = [PositionRequirement(D.RADIUS_MM if args.radius_mm is None else args.radius_mm,
                                       D.PROB if args.prob is None else args.prob)]
    if args.angle_radius_deg is not None:
        requirement.append(OrientationRequirement(args.angle_radius_deg, args.angle_prob))
    for flag, value in (("part", args.part), ("parts_file", args.parts_file)):
        if value:
            raise ArgumentError(flag, "applies to --requirement (the parts in the ISO 9283 acceptance test); the "
                                "design with --parts chooses the parts itself.")
    kw = {"parts": _parts(args) or True} if args.parts else {}
    for flag, value in (("payload_kg", args.payload_kg), ("ambient_c", args.ambient_c), ("duty", args.duty),
                        ("process_force_n", args.process_force_n), ("process_torque_nm", args.process_torque_nm),
                        ("after_compensation", args.after_compensation or None)):
        if value is not None and not args.parts:
            shown = "".join(f"{v:g} " for v in value) if isinstance(value, list) else (
                "" if value is True else f"{value:g} ")
            raise ArgumentError(flag, f"{shown}needs `parts`: it sets the design with bought parts.")
    return dict(kw, requirement=requirement, region=Region(args.region, args.poses, args.coverage_n),
                costs=Costs(args.costs, args.z, args.uniform), error_model=error_model_options(args),
                solver=Solver(args.solver, not args.no_snap, args.angle_step_deg),
                verification=Verification(None if args.no_verify else args.n_mc, args.seed, args.estimator,
                                          False if args.no_correction else None, args.correction_rounds,
                                          args.scheduler),
                calibration=args.calibration)


def _parts(args) -> dict:
    """The options of the bought-parts design (:func:`tolalloc.verify.parts.verified_parts`) from the flags."""
    opts = {"payload_kg": args.payload_kg, "ambient_c": args.ambient_c, "duty": args.duty,
            "process_force_n": args.process_force_n, "process_torque_nm": args.process_torque_nm,
            "after": "compensation" if args.after_compensation else None}
    return {k: tuple(v) if isinstance(v, list) else v for k, v in opts.items() if v is not None}


def _acceptance_parts(args):
    """``parts`` of the ISO 9283 job: ``{(joint, kind): name}`` from ``--parts-file`` and ``--part`` (which overrides
    the file's slot), True with ``--parts`` alone, else None. The design's conditions (payload, ambient, duty, process
    wrench) do not apply: the test load is the requirement's."""
    from tolalloc.exceptions import ArgumentError

    extra = _parts(args)
    if extra:
        key = next(iter(extra))
        raise ArgumentError({"after": "after_compensation"}.get(key, key), "does not apply to --requirement: the "
                            "acceptance test's load is the requirement's (its conditions' load_pct of the rated "
                            "payload).")
    if not args.part and args.parts_file is None:
        return True if args.parts else None
    from tolalloc.workflows.parts import read_parts_choice

    choice = {} if args.parts_file is None else read_parts_choice(args.parts_file, "parts_file")
    for text in args.part or ():
        slot, _, name = text.partition("=")
        joint, _, kind = slot.rpartition(".")
        if not (joint and kind and name):
            raise ArgumentError("part", f"expected JOINT.KIND=NAME (e.g. elbow_joint.encoder=RING-100-STD), got "
                                f"{text!r}.")
        choice[(joint, kind)] = name
    return choice


def cmd_allocate(args) -> int:
    from tolalloc.workflows import allocate_tolerances

    reserve_directory(args.out, "--out")
    reserve_directory(args.report, "--report")
    check_distinct_outputs([("--out", args.out), ("--report", args.report)])
    if args.requirement is not None:
        return _cmd_requirement_file(args)
    res = allocate_tolerances(args.robot, **settings(args), **robot_kwargs(args))
    if getattr(res, "infeasible", None) is not None:  # a region no design can cover: nothing to print or write
        print(f"error: {flag_text(res.infeasible, args)}", file=sys.stderr)
        return 1
    print(res.text())
    if not getattr(res, "writable", True):
        return 1
    for folder, report in ((args.out, False), (args.report, True)):
        if folder is not None:
            paths = res.save(folder, report=report)
            print(f"\nwrote {folder}/: {', '.join(p.name for p in paths)}")
    return 0 if res.ok else 1


def _cmd_requirement_file(args) -> int:
    """``allocate --requirement FILE``: the ISO 9283 job (:func:`tolalloc.workflows.acceptance.allocate_acceptance`)."""
    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows.acceptance import allocate_acceptance

    given = [f for f, v in (("--radius-mm", args.radius_mm), ("--prob", args.prob),
                            ("--angle-radius-deg", args.angle_radius_deg), ("--angle-prob", args.angle_prob),
                            ("--calibration", args.calibration), ("--report", args.report)) if v is not None]
    if given:
        raise ArgumentError("requirement", f"not with {', '.join(given)}: the requirement file states every "
                            "requirement (add a [[requirement]] kind = \"position\" table for the ball), and its job "
                            "writes --out only.")
    from tolalloc.workflows import Costs, Region, Solver, Verification

    res = allocate_acceptance(
        args.robot, args.requirement, region=Region(args.region, args.poses) if args.region is None or args.poses is None
        else Region(args.region), costs=Costs(args.costs, args.z, args.uniform), error_model=error_model_options(args),
        solver=Solver(args.solver, not args.no_snap, args.angle_step_deg),
        verification=False if args.no_verify else Verification(seed=args.seed), n_robots=args.n_robots,
        parts=_acceptance_parts(args), **robot_kwargs(args))
    print(res.text())
    if args.out is not None and res.prediction is not None:
        paths = res.save(args.out)
        print(f"\nwrote {args.out}/: {', '.join(p.name for p in paths)}")
    return 0 if res.ok else 1
