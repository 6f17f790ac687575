"""`tolalloc compensate MODEL PROGRAM.csv --out DIR [--robot ROBOT] [--frame base|tracker] [--json OUT]`."""

from __future__ import annotations

from tolalloc.cli.argtypes import finite_float
from tolalloc.cli.common import check_distinct_outputs, check_output


def register(sub) -> None:
    p = sub.add_parser(
        "compensate", help="compensate a program's joint values with an identified model",
        description="Joint values that put the target point where the nominal robot would have put it (or on the "
        "program's x_mm, y_mm, z_mm targets) under the model a diagnosis identified (the identified.toml that "
        "`tolalloc diagnose --export-model DIR` writes). PROGRAM.csv: one row per pose, a column per joint "
        "(q1_deg / q4_mm ..., deg / mm: the seeds), optional x_mm, y_mm, z_mm targets and the covariates the "
        "model's effects read (payload_kg, temperature_c, time_s, dir1..dirN, a process wrench "
        "force_x_n..torque_z_nm). "
        "Writes compensated.csv into DIR: "
        "the compensated joint values, their corrections, the model's point, status and reason; rows outside the "
        "reachable space or whose correction leaves the joint limits are refused and listed.")
    p.add_argument("model", metavar="MODEL.toml", help="identified model exported by a diagnosis (identified.toml)")
    p.add_argument("program", metavar="PROGRAM.csv", help="the program: joint values (deg / mm) per row")
    p.add_argument("--out", required=True, metavar="DIR", help="directory to write compensated.csv into")
    p.add_argument("--robot", metavar="ROBOT", default=None,
                   help="the nominal robot the model was identified on (default: the built-in robot the file names)")
    p.add_argument("--frame", choices=("base", "tracker"), default="base",
                   help="frame of the targets: the robot's base frame (default) or the training file's tracker frame")
    p.add_argument("--tol-mm", type=finite_float, default=1e-6, metavar="MM",
                   help="distance below which a target counts as reached [mm] (default 1e-6)")
    p.add_argument("--without", action="append", default=[], metavar="EFFECT",
                   help="leave an effect of the model file out (repeatable): one bound to the training session (a "
                        "thermal history variant, a creeping mount) can only be used so; its part of the error is then "
                        "not compensated")
    p.add_argument("--json", metavar="OUT.json", help="write the summary as JSON ('-' for stdout)")
    p.set_defaults(func=cmd_compensate)


def cmd_compensate(args) -> int:
    from tolalloc.workflows.model_use import compensate_program

    check_output(args.json, "--json")
    check_output(args.out, "--out", directory=True)
    check_distinct_outputs([("--out", args.out), ("--json", args.json)],
                           inputs=[("MODEL", args.model), ("PROGRAM", args.program)])
    res = compensate_program(args.model, args.program, robot=args.robot, frame=args.frame, tol_mm=args.tol_mm,
                             without=tuple(args.without))
    res.save(args.out, json=args.json)
    print(res.text())
    return 0 if res.ok else 1
