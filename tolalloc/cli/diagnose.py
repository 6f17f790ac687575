"""`tolalloc diagnose ROBOT --train TRAIN.csv [--test TEST.csv] [--json OUT] [--predictions PRED.csv] [--report DIR]`."""

from __future__ import annotations

import argparse

import pandas as pd

from tolalloc.cli.argtypes import count, seed
from tolalloc.cli.common import add_robot_arg, check_distinct_outputs, check_output, robot_from_args, write_json
from tolalloc.cli.output import output_group


def register(sub) -> None:
    p = sub.add_parser(
        "diagnose", help="sim-to-real diagnosis from laser-tracker measurements",
        description="Calibrate the tracker registration, target offset and identifiable geometric errors on "
        "the training measurements, break the residual down, select the unmodelled effect that lowers the "
        "held-out error (cross-validation + test file) significantly, or 'none'. CSV columns: q1..qN (deg / mm), "
        "x_mm, y_mm, z_mm; optional temperature_c, dir1..dirN (+1/-1), payload_kg, time_s. Rows with empty "
        "cells are skipped and counted.")
    add_robot_arg(p)
    p.add_argument("--train", required=True, metavar="TRAIN.csv", help="measurements to fit (and cross-validate)")
    p.add_argument("--test", metavar="TEST.csv", help="held-out measurements, scored only")
    p.add_argument("--test-frame", choices=("same", "refit"), default="same",
                   help="'refit': the test file is another session in another tracker frame; its registration "
                   "and target offset are re-estimated (two-fold) before scoring (default: same)")
    p.add_argument("--json", metavar="OUT.json", help="write the result as JSON ('-' for stdout)")
    p.add_argument("--predictions", metavar="PRED.csv",
                   help="final model's prediction x_mm,y_mm,z_mm for every test row, in order (needs --test)")
    p.add_argument("--report", metavar="DIR", help="write report.md, CSV tables and figures into DIR")
    p.add_argument("--folds", type=count, default=5, help="cross-validation folds (default 5)")
    p.add_argument("--alpha", type=float, default=0.01, help="family-wise significance level (default 0.01)")
    p.add_argument("--seed", type=seed, default=0, help="seed of the fold assignment and of the cross-validation "
                   "subsample of large files (default 0)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bars on stderr (default: when stderr is a terminal)")
    p.add_argument("--cv-rows", type=count, default=None, metavar="N",
                   help="training files with more rows cross-validate and select effects on a seeded random "
                   "subsample of N rows; the final fits use all rows (default 20000)")
    p.set_defaults(func=cmd_diagnose)


def cmd_diagnose(args) -> int:
    from tolalloc.exceptions import TolallocError
    from tolalloc.diagnose import diagnose, read_measurements
    from tolalloc.diagnose.measurements import check_train_test
    from tolalloc.diagnose.pipeline import MIN_SUBSAMPLE_ROWS
    from tolalloc.diagnose.scale import progress_bar, progress_scope
    from tolalloc.report.diagnosis import write_report

    if args.predictions is not None and not args.test:
        raise TolallocError("--predictions needs --test: predictions are written for the rows of the test file.")
    if not 0 < args.alpha < 1:
        raise TolallocError(f"--alpha: expected a level in (0, 1), got {args.alpha}.")
    if args.folds < 2:
        raise TolallocError(f"--folds: expected at least 2 cross-validation folds, got {args.folds}.")
    if args.cv_rows is not None and args.cv_rows < MIN_SUBSAMPLE_ROWS:
        raise TolallocError(f"--cv-rows: expected at least {MIN_SUBSAMPLE_ROWS} rows for the cross-validation subsample, "
                            f"got {args.cv_rows}.")
    # every output path is checked before any computation, so a late failure cannot leave some written
    check_output(args.json, "--json")
    check_output(args.predictions, "--predictions")
    check_output(args.report, "--report", directory=True)
    check_distinct_outputs([("--json", args.json), ("--predictions", args.predictions), ("--report", args.report)],
                           inputs=[("--train", args.train), ("--test", args.test)])
    robot = robot_from_args(args)
    with progress_scope(args.progress):  # large files take a while to read: say so on stderr
        bar = progress_bar(f"reading {args.train}" + (f" and {args.test}" if args.test else ""))
        try:
            train = read_measurements(args.train, robot)
            test = read_measurements(args.test, robot) if args.test else None
        finally:
            bar.close()
    if test is not None:
        check_train_test(train, test, args.train, args.test)
    extra = {} if args.cv_rows is None else {"subsample_rows": args.cv_rows}
    d = diagnose(robot, train, test, folds=args.folds, alpha=args.alpha, seed=args.seed, test_frame=args.test_frame,
                 progress=args.progress, **extra)
    with output_group() as out:
        # all outputs are produced in temporaries and moved into place together at the end
        if args.predictions is not None:
            tmp_pred = out.file(args.predictions)
            pred = d.final.test_pred_mm
            frame = pd.DataFrame({"row": test.rows, "x_mm": pred[:, 0], "y_mm": pred[:, 1], "z_mm": pred[:, 2]})
            if test.n_skipped:
                # skipped rows (empty cells) get empty predictions, so rows still line up with the test file
                full = pd.DataFrame({"row": range(1, test.n_poses + test.n_skipped + 1)})
                frame = full.merge(frame, on="row", how="left")
            frame[["x_mm", "y_mm", "z_mm"]].to_csv(tmp_pred, index=False, float_format="%.6f")
        if args.report is not None:
            tmp_dir = out.directory(args.report)
            write_report(d, tmp_dir)
        if args.json is not None and args.json != "-":
            tmp_json = out.file(args.json)
            write_json(d.to_dict(), tmp_json)
    if args.json == "-":
        write_json(d.to_dict(), "-")
    ba = d.before_after()
    print(f"effect: {d.effect}" + (f" (sequence: {' -> '.join(d.effects)})" if len(d.effects) > 1 else ""))
    for g in d.guards:
        print(f"GUARD: {g}")
    if d.subsample is not None:
        s = d.subsample
        print(f"subsample: cross-validation and effect selection on {s['cv_rows']:,} of {s['rows']:,} training rows "
              f"(seed {s['seed']}), identifiability on {s['identifiability_rows']:,}; final fits on all rows")
    print("held-out error [mm]:")
    print(ba[["model", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct"]].to_string(index=False, float_format="%.4f"))
    print("ranking:")
    for c in d.ranking:
        if c.applicable:
            print(f"  {c.effect:17s} held-out RMS {c.heldout_rms_mm:.4f} mm  p={c.p_value:.2e}  gain {c.gain_pct:+.1f} %")
        else:
            print(f"  {c.effect:17s} not testable: {c.reason}")
    return 0
