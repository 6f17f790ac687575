"""Sim-to-real diagnosis in one call: :func:`diagnose_measurements`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import check_distinct_outputs, json_native, output_group, write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["diagnose_measurements", "MeasurementDiagnosis"]


@inputs.job_entry
def diagnose_measurements(robot, train, test=None, *, test_frame: str = "same", register_n=None, folds: int = 5,
                          alpha: float = 0.01, seed: int = 0, cv_rows: int | None = None, gap_split: bool = False,
                          progress: bool | None = None, robust_loss: str = "tukey", target_offset_mm=None,
                          target_offset_sd_mm=None, register_update: str | None = None, register_rows=None,
                          tool: str | None = None, trust_units: bool = False) -> "MeasurementDiagnosis":
    """Where a measured robot misses its model, which unmodelled effect explains it, how far the error shrinks.

    Calibrates the tracker registration, target offset and identifiable geometric errors on ``train``, breaks the
    residual down, selects the unmodelled effect that lowers the held-out error significantly (or none), and
    scores the final model on ``test`` (held out, never fitted).

    Parameters
    ----------
    robot : Robot, str or path
    train, test : str, path or DataFrame
        Measurements: columns q1..qN (deg / mm), x_mm, y_mm, z_mm; optional temperature_c, dir1..dirN (+1 / -1),
        payload_kg, time_s. Rows with empty cells are skipped and counted.
    test_frame : {"same", "refit"}
        ``refit`` (needs ``test``): the test file is another session in another tracker frame; its registration and
        target offset are re-estimated on ``register_n`` test poses (a count >= 5, default 30, or a fraction below
        1), which are then not scored.
    register_rows : sequence of int, optional
        With ``refit``, instead of ``register_n``: the test file's rows that register the frame (e.g. a registration
        set measured first, ``range(1, 61)``), its data rows from 1 as its error messages and the JSON's
        ``registration_rows`` number them (a DataFrame's by position); every other test row is scored.
    register_update : {"frame", "calibration"}, optional
        With ``refit``: what the registration poses re-fit -- ``frame`` (default): tracker frame and probe offset,
        the trained model frozen; ``calibration``: also a correction of the trained geometric and effect
        parameters, the training fit as the prior, its training data discounted as far as the registration
        poses' marginal likelihood says they moved (:mod:`tolalloc.diagnose.recalibrate`).
    folds : int
        Cross-validation folds (a minimum: more when the training file has few poses).
    alpha : float
        Family-wise significance level of the effect selection.
    seed : int
        Seed of the fold assignment and of the cross-validation subsample of large files.
    cv_rows : int, optional
        Training files with more rows cross-validate on a seeded subsample of this many rows (default 10000).
    gap_split : bool
        Split the held-out test error into geometry / effect / systematic but unnamed / noise floor (needs ``test``).
    progress : bool, optional
        Progress on stderr: bars on a terminal or in a notebook, one line per finished stage with its duration in
        a pipe or log (:mod:`tolalloc.progress`); default on, False: off.
    robust_loss : {"tukey", "huber", "soft_l1"}
        M-estimator of the fits (IRLS on each pose's 3-D residual); ``tukey`` gives gross outliers no weight and
        lists them.
    target_offset_mm, target_offset_sd_mm : array (3,) and float, optional
        Prior mean [mm] (flange frame, relative to the robot's tool point) and sd [mm] of the probe / target offset,
        used by every fit; without them each fold borrows the full training fit's offset as its prior.

    The test file is sealed: the model is chosen on the training file alone (selection, variants, fold counts,
    thresholds) and the test file is scored once afterwards. The verdict (``effect``, ``none``, ``ambiguous``,
    ``inconclusive``) says how far the data decide.

    Returns
    -------
    MeasurementDiagnosis

    Examples
    --------
    Synthetic measurements of a tool_changer with joint backlash, split into training and test poses:

    >>> import numpy as np, tolalloc
    >>> from tolalloc.diagnose import generate
    >>> case = generate(tolalloc.load_robot("tool_changer"), "backlash", 120, np.random.default_rng(5))
    >>> train, test = case.frame.iloc[:90], case.frame.iloc[90:]
    >>> d = tolalloc.diagnose_measurements("tool_changer", train, test, folds=3)
    >>> d.effect
    'backlash'
    """
    from tolalloc.diagnose import diagnose

    alpha, folds, seed, cv_rows, rows = _check_args(test, test_frame, register_n, folds, alpha, seed, cv_rows,
                                                    gap_split, progress, register_rows)
    _check_fit(robust_loss, target_offset_mm, target_offset_sd_mm, register_update, test_frame, test)
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    tr, te = _read(rob, train, test, progress, folds)
    d = diagnose(rob, tr, te, folds=folds, alpha=alpha, seed=seed, test_frame=test_frame,
                 register_n=register_n, register_rows=rows, progress=progress,
                 robust_loss=robust_loss, target_offset_mm=target_offset_mm, target_offset_sd_mm=target_offset_sd_mm,
                 register_update=register_update or "frame", **({} if cv_rows is None else {"subsample_rows": cv_rows}))
    gap = _gap_split(d, progress) if gap_split else None
    record = {"robot": rob.name, "train": tr.source, "test": None if te is None else te.source, "test_frame": test_frame,
              "register_n": register_n, **({} if rows is None else {"register_rows": rows}),
              "register_update": register_update, "folds": folds, "alpha": alpha, "seed": seed, "cv_rows": cv_rows,
              "gap_split": bool(gap_split), "tool": tool, "trust_units": bool(trust_units), "robust_loss": robust_loss,
              "target_offset_mm": None if target_offset_mm is None else [float(v) for v in target_offset_mm],
              "target_offset_sd_mm": target_offset_sd_mm}
    return MeasurementDiagnosis(d, gap, folds, record)


def _gap_split(d, progress):
    """Where the held-out gap lies (a Gaussian process on the training residual), with a progress bar."""
    from tolalloc.diagnose.gap import diagnosis_gap_split
    from tolalloc.progress import progress_bar, progress_scope

    with progress_scope(progress), progress_bar("residual Gaussian process (gap_split)"):
        return diagnosis_gap_split(d)


def _check_fit(robust_loss, target_offset_mm, target_offset_sd_mm, register_update=None, test_frame="same",
               test=None) -> None:
    inputs.check_choice(robust_loss, "robust_loss", ("tukey", "huber", "soft_l1"))
    if register_update is not None and test_frame == "refit" and test is None:
        raise ArgumentError("register_update", "needs `test`: only a test file in another frame is re-registered, "
                            "and none was given; pass the test file or leave this option out.")
    if register_update is not None:
        inputs.check_choice(register_update, "register_update", ("frame", "calibration"))
        if test_frame != "refit":
            raise ArgumentError("register_update", "needs `test_frame` refit: only a test file in another frame is "
                                "re-registered.")
    if test_frame == "refit" and test is None:
        raise ArgumentError("test_frame", "needs `test`: 'refit' re-registers a test file measured in another tracker "
                            "frame, and none was given; pass the test file or leave this option out.")
    if target_offset_mm is not None and target_offset_sd_mm is None:
        raise ArgumentError("target_offset_mm", "a prior mean needs its standard deviation: give `target_offset_sd_mm` "
                            "too (e.g. 5 for a tool drawing good to a few mm).")
    if target_offset_sd_mm is not None:
        inputs.check_positive(target_offset_sd_mm, "target_offset_sd_mm", "mm", "5")


def _read(robot, train, test, progress, folds):
    """The training and test measurements (paths or DataFrames), with a progress bar for large files; refuses more
    ``folds`` than the training file holds and a test file that shares poses with it."""
    from tolalloc.diagnose.measurements import check_train_test
    from tolalloc.progress import progress_bar, progress_scope

    names = [str(x) for x in (train, test) if isinstance(x, (str, bytes)) or hasattr(x, "__fspath__")]
    with progress_scope(progress), progress_bar("reading " + " and ".join(names) if names else
                                                "reading the measurements"):
        tr = inputs.as_measurements(train, robot, "train")
        te = None if test is None else inputs.as_measurements(test, robot, "test")
    if folds > tr.n_poses // 2:
        raise ArgumentError("folds", f"expected at most {tr.n_poses // 2} cross-validation folds for {tr.n_poses} "
                            f"training poses (at least 2 poses held out per fold), got {folds}.")
    if te is not None:
        check_train_test(tr, te, tr.source, te.source)
    return tr, te


def _check_args(test, test_frame, register_n, folds, alpha, seed, cv_rows, gap_split, progress,
                register_rows=None) -> tuple:
    """The options of :func:`diagnose_measurements` checked by name; returns ``(alpha, folds, seed, cv_rows,
    register_rows)``, the rows as a list of int or None (whether the test file has them is checked once it is
    read)."""
    from tolalloc.diagnose.pipeline import MIN_SUBSAMPLE_ROWS
    from tolalloc.diagnose.register import check_register_rows

    inputs.check_choice(test_frame, "test_frame", ("same", "refit"))
    alpha = inputs.check_probability(alpha, "alpha", example="0.01")
    folds = inputs.check_count(folds, "folds", minimum=2, example="5")
    seed = inputs.check_seed(seed)
    if cv_rows is not None:
        cv_rows = inputs.check_count(cv_rows, "cv_rows", minimum=MIN_SUBSAMPLE_ROWS, example="10000")
    inputs.check_flag(gap_split, "gap_split")
    inputs.check_optional_flag(progress, "progress")
    if register_n is not None:
        _check_register_n(register_n)
    rows = check_register_rows(register_rows, register_n, test_given=test is not None, test_frame=test_frame)
    if gap_split and test is None:
        raise ArgumentError("gap_split", "needs `test`: it splits the error on the held-out test poses.")
    if register_n is not None and test_frame != "refit":
        raise ArgumentError("register_n", "needs `test_frame` refit: only a test file in another frame is re-registered.")
    if register_n is not None and test is None:
        raise ArgumentError("register_n", "needs `test`: only a test file in another frame is re-registered, and none "
                            "was given; pass the test file or leave this option out.")
    return alpha, folds, seed, cv_rows, rows


def _check_register_n(value) -> float:
    """A count of registration poses (a whole number >= 5) or a fraction of the test poses (0 < f < 1)."""
    from tolalloc.diagnose.register import MIN_REGISTER

    x = inputs.number(value, "register_n")
    if not (np.isfinite(x) and 0 < x and (x < 1 or (x == int(x) and x >= MIN_REGISTER))):
        raise ArgumentError("register_n", f"expected a count of registration poses (a whole number >= {MIN_REGISTER}, "
                            f"e.g. 30) or a fraction of the test poses (0 < f < 1, e.g. 0.2), got {inputs.shown(value)}.")
    return x


def _not_applicable_null(obj):
    """``obj`` with the NaN scores of entries marked ``applicable: False`` as None (JSON null: not scored)."""
    if isinstance(obj, dict):
        out = {k: _not_applicable_null(v) for k, v in obj.items()}
        if out.get("applicable") is False:
            out = {k: None if isinstance(v, float) and not np.isfinite(v) else v for k, v in out.items()}
        return out
    if isinstance(obj, list):
        return [_not_applicable_null(v) for v in obj]
    return obj


@dataclass(frozen=True, eq=False, repr=False)
class MeasurementDiagnosis(JobResult):
    """A sim-to-real diagnosis and, optionally, where the held-out gap lies.

    Attributes
    ----------
    diagnosis : Diagnosis
        Registration, geometric calibration, selected effect(s), ranking, guards, held-out scores.
    gap : GapSplit or None
        The held-out test error split into geometry / effect / systematic but unnamed / noise floor.
    folds : int
    inputs : dict
        The call's inputs that decide the numbers (robot, files, test_frame, folds, alpha, seed, ...).

    See :func:`diagnose_measurements` for an example; ``to_frame()`` is the before / after table
    (nominal, geometric, final model; RMS, p95, max [mm]).
    """

    diagnosis: object
    gap: object = None
    folds: int = 5
    inputs: dict = field(default_factory=dict)

    @property
    def robot(self):
        return self.diagnosis.robot

    @property
    def effect(self) -> str:
        return self.diagnosis.effect

    @property
    def verdict(self) -> str:
        """``effect``, ``none``, ``ambiguous`` or ``inconclusive``: how far the data decide."""
        v = self.diagnosis.verdict
        return "effect" if v is None and self.effect != "none" else ("none" if v is None else v.verdict)

    @property
    def ok(self) -> bool:
        return True

    def headline(self) -> list[str]:
        d = self.diagnosis
        v = d.verdict
        lines = [f"robot: {self.robot.name}   {d.train.n_poses} training poses"
                 + ("" if d.test is None else f", {d.test.n_poses} test poses"),
                 f"verdict: {self.verdict}   effect: {d.effect}"
                 + ("" if v is None or not v.candidates else f"   candidates: {', '.join(v.candidates)}")]
        # the JSON's test_rms_mm with a test file, else its cv_rms_mm
        block = d.before_after("test" if d.test is not None else "cv")
        lines.append(("test" if d.test is not None else "cross-validation") + " RMS [mm]: "
                     + ", ".join(f"{m} {r:.4f}" for m, r in zip(block["model"], block["rms_mm"])))
        if d.guards:
            lines.append(f"guards fired: {len(d.guards)}")
        return lines

    def to_frame(self) -> pd.DataFrame:
        """Held-out RMS, p95 and max error of the nominal, geometric and final models [mm]."""
        d = self.diagnosis
        return d.before_after("test" if d.test is not None else "cv")

    def ranking_frame(self) -> pd.DataFrame:
        """Candidate effects with their held-out RMS, p-value and gain."""
        return self.diagnosis.ranking_frame()

    def summary(self) -> dict:
        """The JSON result (``--json``); the scores of an effect the data cannot carry (``applicable`` false) are null."""
        return json_native(_not_applicable_null(self.diagnosis.to_dict() | ({} if self.gap is None else
                                                                            {"gap_split": self.gap.to_dict()})))

    def text(self) -> str:
        """What the command line prints."""
        from tolalloc.workflows.diagnosis_text import summary_lines

        return "\n".join(summary_lines(self.diagnosis, self.folds, self.gap))

    def predictions_frame(self) -> pd.DataFrame:
        """The final model's prediction for every test row, in order (skipped rows empty; ``row``: the data row of the
        test file, from 1, to join on), with its 1-sigma and 95 % radius, the registration flag and the extrapolation
        flag."""
        from tolalloc.report.diagnosis import test_predictions

        d = self.diagnosis
        if d.test is None:
            raise ArgumentError("predictions", "needs `test`: predictions are made for the rows of the test file.")
        frame = test_predictions(d)
        if d.test.n_skipped:  # skipped rows get empty predictions, so rows still line up with the test file
            full = pd.DataFrame({"row": range(1, d.test.n_poses + d.test.n_skipped + 1)})
            frame = full.merge(frame, on="row", how="left")
        return frame

    def save(self, report=None, *, json=None, predictions=None) -> list[str]:
        """Write the report directory (report.md, report.html, CSV tables, figures), the JSON result and / or the predictions
        CSV; all published together, nothing if any fails. Returns the paths written."""
        self.check_out(report, "report")
        self.check_out(json, "json", directory=False)
        self.check_out(predictions, "predictions", directory=False)
        check_distinct_outputs([("json", json), ("predictions", predictions), ("report", report)])
        if predictions is not None and self.diagnosis.test is None:
            raise ArgumentError("predictions", "needs `test`: predictions are made for the rows of the test file.")
        with output_group() as group:
            if predictions is not None:
                self.predictions_frame().to_csv(group.file(predictions), index=False, float_format="%.6f")
            if report is not None:
                self.write_report(group.directory(report))
            if json is not None:
                write_json(self.summary(), group.file(json))
        return [str(p) for p in (predictions, report, json) if p is not None]

    def write_report(self, folder) -> None:
        """report.md, report.html, the CSV tables and the figures into an existing ``folder`` (not atomic)."""
        from tolalloc.report.diagnosis import write_report
        from tolalloc.report.html_diagnosis import write_diagnosis_report

        write_report(self.diagnosis, folder)
        if self.gap is not None:
            self.gap.to_frame().to_csv(folder / "gap_split.csv", index=False, float_format="%.6g")
        write_diagnosis_report(self, folder)
