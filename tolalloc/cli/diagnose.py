"""`tolalloc diagnose ROBOT --train TRAIN.csv [--test TEST.csv] [--json OUT] [--predictions PRED.csv] [--report DIR]`."""

from __future__ import annotations

import argparse

import numpy as np
import pandas as pd

from tolalloc.cli.argtypes import count, finite_float, seed
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
                   "and target offset are re-estimated on --register-n test poses, and only the other test poses "
                   "are scored (default: same)")
    p.add_argument("--register-n", type=finite_float, metavar="N",
                   help="with --test-frame refit: how many test poses register the frame -- a count (>= 5, default 30) "
                   "or, below 1, a fraction of the test file; chosen spread in joint space (seeded by --seed), "
                   "used for the registration only and never scored")
    p.add_argument("--json", metavar="OUT.json", help="write the result as JSON ('-' for stdout)")
    p.add_argument("--predictions", metavar="PRED.csv",
                   help="final model's prediction x_mm,y_mm,z_mm for every test row, in order, with its predicted "
                   "1-sigma sigma_mm and 95 %% radius radius95_mm (noise included), registration (1: row used to "
                   "register the frame, not scored) and extrapolation (1: outside the training data) (needs --test)")
    p.add_argument("--report", metavar="DIR", help="write report.md, CSV tables and figures into DIR")
    p.add_argument("--folds", type=count, default=5, help="cross-validation folds (default 5)")
    p.add_argument("--alpha", type=float, default=0.01, help="family-wise significance level (default 0.01)")
    p.add_argument("--seed", type=seed, default=0, help="seed of the fold assignment and of the cross-validation "
                   "subsample of large files (default 0)")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bars on stderr (default: when stderr is a terminal)")
    p.add_argument("--cv-rows", type=count, default=None, metavar="N",
                   help="training files with more rows cross-validate and select effects on a seeded random "
                   "subsample of N rows; the final fits use all rows (default 10000)")
    p.add_argument("--gap-split", action="store_true",
                   help="split the held-out test error into removed by geometry / by the effect / systematic but "
                        "unnamed (a Gaussian process on the joint values) / noise floor (needs --test; adds about a "
                        "minute for 1000 training poses)")
    p.set_defaults(func=cmd_diagnose)


def cmd_diagnose(args) -> int:
    from tolalloc.exceptions import TolallocError
    from tolalloc.diagnose import diagnose, read_measurements
    from tolalloc.diagnose.measurements import check_train_test
    from tolalloc.diagnose.pipeline import MIN_SUBSAMPLE_ROWS
    from tolalloc.diagnose.scale import progress_bar, progress_scope
    from tolalloc.diagnose.register import REGISTER_N
    from tolalloc.report.diagnosis import test_predictions, write_report

    if args.predictions is not None and not args.test:
        raise TolallocError("--predictions needs --test: predictions are written for the rows of the test file.")
    if not 0 < args.alpha < 1:
        raise TolallocError(f"--alpha: expected a level in (0, 1), got {args.alpha}.")
    if args.folds < 2:
        raise TolallocError(f"--folds: expected at least 2 cross-validation folds, got {args.folds}.")
    if args.cv_rows is not None and args.cv_rows < MIN_SUBSAMPLE_ROWS:
        raise TolallocError(f"--cv-rows: expected at least {MIN_SUBSAMPLE_ROWS} rows for the cross-validation subsample, "
                            f"got {args.cv_rows}.")
    if args.gap_split and not args.test:
        raise TolallocError("--gap-split needs --test: it splits the error on the held-out test poses.")
    if args.register_n is not None and args.test_frame != "refit":
        raise TolallocError("--register-n needs --test-frame refit: only a test file in another frame is re-registered.")
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
    if args.folds > train.n_poses // 2:
        raise TolallocError(f"--folds: expected at most {train.n_poses // 2} cross-validation folds for "
                            f"{train.n_poses} training poses (at least 2 poses held out per fold), got {args.folds}.")
    if test is not None:
        check_train_test(train, test, args.train, args.test)
    d = diagnose(robot, train, test, folds=args.folds, alpha=args.alpha, seed=args.seed, test_frame=args.test_frame,
                 register_n=REGISTER_N if args.register_n is None else args.register_n, progress=args.progress,
                 **({} if args.cv_rows is None else {"subsample_rows": args.cv_rows}))
    gap = None
    if args.gap_split:
        from tolalloc.diagnose.gap import diagnosis_gap_split

        bar = progress_bar("residual Gaussian process (--gap-split)")
        try:
            gap = diagnosis_gap_split(d)
        finally:
            bar.close()
    result = d.to_dict() | ({} if gap is None else {"gap_split": gap.to_dict()})
    with output_group() as out:
        # all outputs are produced in temporaries and moved into place together at the end
        if args.predictions is not None:
            tmp_pred = out.file(args.predictions)
            frame = test_predictions(d)
            if test.n_skipped:
                # skipped rows (empty cells) get empty predictions, so rows still line up with the test file
                full = pd.DataFrame({"row": range(1, test.n_poses + test.n_skipped + 1)})
                frame = full.merge(frame, on="row", how="left")
            frame.drop(columns="row").to_csv(tmp_pred, index=False, float_format="%.6f")
        if args.report is not None:
            tmp_dir = out.directory(args.report)
            write_report(d, tmp_dir)
            if gap is not None:
                gap.to_frame().to_csv(tmp_dir / "gap_split.csv", index=False, float_format="%.6g")
        if args.json is not None and args.json != "-":
            tmp_json = out.file(args.json)
            write_json(result, tmp_json)
    if args.json == "-":
        write_json(result, "-")
    _print_summary(d, args.folds)
    if gap is not None:
        _print_gap(gap)
    return 0


def _print_summary(d, folds: int) -> None:
    """Test-file figures first, then cross-validation, the worst test poses, every guard, the ranking."""
    from tolalloc.report.diagnosis import worst_test_poses

    cols = ["model", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct"]
    print(f"effect: {d.effect}" + (f" (sequence: {' -> '.join(d.effects)})" if len(d.effects) > 1 else ""))
    if d.subsample is not None:
        s = d.subsample
        print(f"subsample: cross-validation and effect selection on {s['cv_rows']:,} of {s['rows']:,} training rows "
              f"(seed {s['seed']}), identifiability on {s['identifiability_rows']:,}; final fits on all rows")
    if d.test is not None:
        reg = d.registration
        how = (f"{len(reg.score_index)} scored poses; {len(reg.register_index)} other test poses registered the "
               "tracker frame and probe offset and are not scored" if reg is not None
               else f"{d.test.n_poses} poses, training tracker frame")
        print(f"test file {d.test.source} ({how}) [mm]:")
        print(d.before_after("test")[cols].to_string(index=False, float_format="%.4f"))
    print(f"cross-validation on the training file ({d.train.n_poses} poses, {folds} folds, out-of-fold) [mm]:")
    print(d.before_after("cv")[cols].to_string(index=False, float_format="%.4f"))
    if d.test is not None:
        print("worst test poses (final model; joints in deg / mm; extrapolation 1: outside the training data):")
        print(worst_test_poses(d).to_string(index=False, float_format="%.3f"))
        u = d.uncertainty
        print(f"predicted uncertainty: median 1-sigma {np.median(u.sigma_mm):.4f} mm (noise {u.noise_mm:.4f} mm per "
              f"coordinate); {100 * u.coverage:.0f} % of {len(u.inside)} scored test residuals within the predicted "
              "95 % radius (95 % expected when the model's uncertainty is right)")
    for g in d.guards:
        print(f"GUARD: {g}")
    if not d.guards:
        print("guards: none fired")
    for f in d.findings:
        print(f"note: {f}")
    print("ranking (held-out RMS: cross-validation + scored test poses):")
    for c in d.ranking:
        if c.applicable:
            print(f"  {c.effect:17s} held-out RMS {c.heldout_rms_mm:.4f} mm  p={c.p_value:.2e}  gain {c.gain_pct:+.1f} %")
        else:
            print(f"  {c.effect:17s} not testable: {c.reason}")


def _print_gap(gap) -> None:
    """Where the held-out gap lies (:class:`tolalloc.diagnose.gap.GapSplit`)."""
    print("where the test error lies (mean squares of the 3-D error, adding up to the nominal model's):")
    print(gap.to_frame().to_string(index=False, float_format="%.4f"))
    print(f"  systematic_unnamed: what a Gaussian process on the joint values, trained on the training residual, "
          f"predicts on the test poses ({100 * gap.gp_test_explained:.0f} % of the final model's test error); "
          f"noise floor from the {gap.noise_source}")
