"""`tolalloc diagnose ROBOT --train TRAIN.csv [--test TEST.csv] [--json OUT] [--predictions PRED.csv] [--report DIR]`."""

from __future__ import annotations

import argparse

from tolalloc.exceptions import TolallocError
from tolalloc.cli.argtypes import count, finite_float, row_ranges, seed
from tolalloc.cli.common import (add_robot_arg, check_distinct_outputs, check_output, reserve_directory, robot_kwargs)
from tolalloc.workflows import defaults as D


def register(sub) -> None:
    p = sub.add_parser(
        "diagnose", help="sim-to-real diagnosis from laser-tracker measurements",
        description="Calibrate the tracker registration, target offset and identifiable geometric errors on "
        "the training measurements, break the residual down, select the unmodelled effect that lowers the "
        "held-out error (cross-validation + test file) significantly, or 'none'. CSV columns: one per joint, "
        "q1_deg / q4_mm ... (deg / mm; a calibration plan's joint names and plain q1..qN are read too), x_mm, y_mm, "
        "z_mm; optional temperature_c, dir1..dirN (+1/-1), payload_kg, time_s, and a process wrench at the target in "
        "the base frame (force_x_n..force_z_n [N], torque_x_nm..torque_z_nm [N m]). Rows with empty cells are skipped "
        "and counted.")
    add_robot_arg(p)
    p.add_argument("--train", required=True, metavar="TRAIN.csv", help="measurements to fit (and cross-validate)")
    p.add_argument("--test", metavar="TEST.csv", help="held-out measurements, scored only")
    p.add_argument("--test-frame", choices=("same", "refit"), default="same",
                   help="'refit': the test file is another session in another tracker frame; its registration "
                   "and target offset are re-estimated on --register-n test poses (or the --register-rows), and only "
                   "the other test poses are scored (default: same)")
    p.add_argument("--register-n", type=finite_float, metavar="N",
                   help="with --test-frame refit: how many test poses register the frame -- a count (>= 5, default 30) "
                   "or, below 1, a fraction of the test file; chosen spread in joint space (seeded by --seed), "
                   "used for the registration only and never scored")
    p.add_argument("--register-rows", type=row_ranges, metavar="SPEC",
                   help="with --test-frame refit, instead of --register-n: the rows of the test file that register the "
                   "frame, e.g. 1-60 for a registration set measured at the start of the session, or 1-60,75,80-90 "
                   "(data rows from 1, header not counted, ranges inclusive; the numbers the JSON's "
                   "registration_rows reports); every other test row is scored")
    p.add_argument("--register-update", choices=("frame", "calibration"), default=None,
                   help="with --test-frame refit: what the registration poses re-fit -- 'frame' (default): the tracker "
                   "frame and probe offset, the trained model frozen; 'calibration': also a correction of the trained "
                   "geometric and effect parameters, with the training fit as the prior (the same robot, re-measured), "
                   "its training data discounted as far as the registration poses' marginal likelihood says they "
                   "moved")
    p.add_argument("--json", metavar="OUT.json", help="write the result as JSON ('-' for stdout)")
    p.add_argument("--predictions", metavar="PRED.csv",
                   help="final model's prediction x_mm,y_mm,z_mm for every test row, in order (row: its data row in "
                   "the test file, from 1), with its predicted "
                   "1-sigma sigma_mm and 95 %% radius radius95_mm (noise included), registration (1: row used to "
                   "register the frame, not scored) and extrapolation (1: outside the training data) (needs --test)")
    p.add_argument("--report", metavar="DIR", help="write report.md, report.html (one self-contained file), CSV tables and figures into DIR")
    p.add_argument("--export-model", metavar="DIR", help="write the identified model into DIR: identified.toml (chain "
                   "layout with an [identified] section of the fitted parameters and effects, what `tolalloc compensate` "
                   "reads) and identified.urdf")
    p.add_argument("--folds", type=count, default=D.FOLDS, help=f"cross-validation folds (default {D.FOLDS})")
    p.add_argument("--alpha", type=float, default=D.ALPHA,
                   help=f"family-wise significance level (default {D.ALPHA:g})")
    p.add_argument("--seed", type=seed, default=D.SEED, help="seed of the fold assignment and of the cross-validation "
                   "subsample of large files (default 0)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr: bars on a terminal, one line per finished stage with its duration in a "
                   "pipe or log (default: on)")
    p.add_argument("--cv-rows", type=count, default=None, metavar="N",
                   help="training files with more rows cross-validate and select effects on a seeded random "
                   "subsample of N rows; the final fits use all rows (default 10000)")
    p.add_argument("--gap-split", action="store_true",
                   help="split the held-out test error into removed by geometry / by the effect / systematic but "
                        "unnamed (a Gaussian process on the joint values) / noise floor (needs --test; adds about a "
                        "minute for 1000 training poses)")
    p.add_argument("--robust-loss", default=D.ROBUST_LOSS, choices=["auto", "tukey", "huber", "soft_l1"],
                   help="M-estimator of the fits: auto (default) is tukey, or huber on a small training file (fewer "
                   "than 10 poses per fitted parameter); tukey gives gross outliers no weight; huber bounds their "
                   "weight; soft_l1 is the former smooth loss; down-weighted rows are listed per stage")
    p.add_argument("--target-offset-mm", type=finite_float, nargs=3, metavar=("X", "Y", "Z"), default=None,
                   help="prior mean of the probe / target offset in the flange frame, relative to the robot's tool "
                   "point [mm] (needs --target-offset-sd-mm)")
    p.add_argument("--target-offset-sd-mm", type=finite_float, nargs="+", default=None, metavar="SD",
                   help="prior standard deviation of the probe / target offset [mm], one value or one each for x, y "
                   "and z; every fit uses it (default: each fold borrows the full training fit's offset)")
    p.add_argument("--instrument-noise-mm", type=finite_float, default=None, metavar="SD",
                   help="the measuring instrument's stated noise [mm, one sd per axis]: a final model whose "
                   "out-of-fold error lies far above it gets a guard (a disturbance no column carries); choices "
                   "and verdicts do not use it")
    p.set_defaults(func=cmd_diagnose)


def test_frame(args):
    """``"same"``, or the :class:`~tolalloc.workflows.Refit` of the registration flags."""
    from tolalloc.exceptions import ArgumentError
    from tolalloc.workflows import Refit

    given = [(n, v) for n, v in (("register_n", args.register_n), ("register_rows", args.register_rows),
                                 ("register_update", args.register_update)) if v is not None]
    if given and args.test is None:
        raise ArgumentError(given[0][0], "needs `test`: only a test file in another frame is re-registered, and none "
                            "was given; pass the test file or leave this option out.")
    if args.test_frame == "same":
        if given:
            raise ArgumentError(given[0][0], "needs `test_frame` refit: only a test file in another frame is "
                                "re-registered.")
        return "same"
    return Refit(args.register_n, args.register_rows, args.register_update or "frame")


def cmd_diagnose(args) -> int:
    from tolalloc.workflows import FitOptions, diagnose_measurements

    if args.predictions is not None and not args.test:
        raise TolallocError("--predictions needs --test: predictions are written for the rows of the test file.")
    # every output path is checked before any computation, so a late failure cannot leave some written
    check_output(args.json, "--json")
    check_output(args.predictions, "--predictions")
    reserve_directory(args.report, "--report")
    reserve_directory(args.export_model, "--export-model")
    check_distinct_outputs([("--json", args.json), ("--predictions", args.predictions), ("--report", args.report),
                            ("--export-model", args.export_model)],
                           inputs=[("--train", args.train), ("--test", args.test)])
    sd = args.target_offset_sd_mm
    fit = FitOptions(args.robust_loss, args.target_offset_mm, sd[0] if sd is not None and len(sd) == 1 else sd,
                     args.instrument_noise_mm)
    res = diagnose_measurements(args.robot, args.train, args.test, test_frame=test_frame(args), folds=args.folds,
                                alpha=args.alpha, seed=args.seed, cv_rows=args.cv_rows, gap_split=args.gap_split,
                                fit=fit, progress=args.progress, **robot_kwargs(args))
    if args.report or args.json or args.predictions:
        res.save(args.report, report=args.report is not None, json=args.json, predictions=args.predictions)
    if args.export_model is not None:
        res.export_model(args.export_model)
    print(res.text())
    for line in res.export_notes() if args.export_model is not None else ():
        print(line)
    return 0
