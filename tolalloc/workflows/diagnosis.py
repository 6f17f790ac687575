"""Sim-to-real diagnosis in one call: :func:`diagnose_measurements`."""

from __future__ import annotations

import os

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import json_native, output_group
from tolalloc.workflows import defaults as D
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["diagnose_measurements", "MeasurementDiagnosis"]


@inputs.job_entry
def diagnose_measurements(robot, train, test=None, *, test_frame="same", folds: int = D.FOLDS, alpha: float = D.ALPHA,
                          seed: int = D.SEED, cv_rows: int | None = None, gap_split: bool = False, fit=None,
                          progress: bool | None = None, tool: str | None = None,
                          trust_units: bool = False) -> "MeasurementDiagnosis":
    """Where a measured robot misses its model, which unmodelled effect explains it, how far the error shrinks.

    Calibrates the tracker registration, target offset and identifiable geometric errors on ``train``, breaks the
    residual down, selects the unmodelled effect that lowers the held-out error significantly (or none), and
    scores the final model on ``test`` (held out, never fitted).

    Parameters
    ----------
    robot : Robot, str or path
    train, test : str, path or DataFrame
        Measurements: columns q1..qN (deg / mm), x_mm, y_mm, z_mm; optional temperature_c, dir1..dirN (+1 / -1),
        payload_kg, time_s, and a process wrench at the target in the robot's base frame (force_x_n, force_y_n,
        force_z_n [N]; torque_x_nm, torque_y_nm, torque_z_nm [N m]). Rows with empty cells are skipped and counted.
    test_frame : {"same", "refit"} or Refit
        ``"same"``: the test file shares the training file's tracker frame. ``"refit"`` or a
        :class:`~tolalloc.workflows.Refit` (needs ``test``): the test file is another session in another tracker
        frame; its registration and target offset are re-estimated on some of its poses (``Refit.register_n``, a
        count >= 5, default 30, or a fraction below 1; or the rows ``Refit.register_rows``), which are then not
        scored; ``Refit.update="calibration"`` also corrects the trained geometric and effect parameters.
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
    fit : FitOptions, optional
        The fits' M-estimator (``auto`` by default: Tukey's biweight, which gives gross outliers no weight, or Huber's
        bounded-influence loss on a small training file -- fewer than 10 poses per fitted parameter; down-weighted
        rows are listed per stage) and the prior of the probe / target offset (:class:`~tolalloc.workflows.FitOptions`).

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

    refit, fit = _settings(test_frame, fit, test)
    alpha, folds, seed, cv_rows = _check_args(test, folds, alpha, seed, cv_rows, gap_split, progress)
    frame = "same" if refit is None else "refit"
    register_n = None if refit is None else refit.register_n
    rows = None if refit is None or refit.register_rows is None else list(refit.register_rows)
    update = None if refit is None else refit.update
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    tr, te = _read(rob, train, test, progress, folds)
    d = diagnose(rob, tr, te, folds=folds, alpha=alpha, seed=seed, test_frame=frame, register_n=register_n,
                 register_rows=rows, progress=progress, robust_loss=fit.robust_loss,
                 target_offset_mm=fit.target_offset_mm, target_offset_sd_mm=fit.target_offset_sd_mm,
                 instrument_noise_mm=fit.instrument_noise_mm,
                 register_update=update or "frame", **({} if cv_rows is None else {"subsample_rows": cv_rows}))
    gap = _gap_split(d, progress) if gap_split else None
    record = {"robot": rob.name, "train": tr.source, "test": None if te is None else te.source, "test_frame": frame,
              "register_n": register_n, **({} if rows is None else {"register_rows": rows}),
              "register_update": None if refit is None or update == "frame" else update, "folds": folds,
              "alpha": alpha, "seed": seed, "cv_rows": cv_rows, "gap_split": bool(gap_split), "tool": tool,
              "trust_units": bool(trust_units), **fit.to_dict()}
    return MeasurementDiagnosis(d, gap, folds, record)


def _settings(test_frame, fit, test) -> tuple:
    """``(Refit or None, FitOptions)`` of the call; a refit needs a test file."""
    from tolalloc.workflows.diagnosis_settings import FitOptions, Refit
    from tolalloc.workflows.settings import as_settings

    if isinstance(test_frame, Refit):
        refit = test_frame
    else:
        inputs.check_choice(test_frame, "test_frame", ("same", "refit"))
        refit = Refit() if test_frame == "refit" else None
    if refit is not None and test is None:
        raise ArgumentError("test_frame", "needs `test`: 'refit' re-registers a test file measured in another tracker "
                            "frame, and none was given; pass the test file or leave this option out.")
    return refit, as_settings(fit, FitOptions, "fit")


def _gap_split(d, progress):
    """Where the held-out gap lies (a Gaussian process on the training residual), with a progress bar."""
    from tolalloc.diagnose.gap import diagnosis_gap_split
    from tolalloc.progress import progress_bar, progress_scope

    with progress_scope(progress), progress_bar("residual Gaussian process (gap_split)"):
        return diagnosis_gap_split(d)


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


def _check_args(test, folds, alpha, seed, cv_rows, gap_split, progress) -> tuple:
    """The options of :func:`diagnose_measurements` checked by name; returns ``(alpha, folds, seed, cv_rows)``."""
    from tolalloc.diagnose.pipeline import MIN_SUBSAMPLE_ROWS

    alpha = inputs.check_probability(alpha, "alpha", example="0.01")
    folds = inputs.check_count(folds, "folds", minimum=2, example="5")
    seed = inputs.check_seed(seed)
    if cv_rows is not None:
        cv_rows = inputs.check_count(cv_rows, "cv_rows", minimum=MIN_SUBSAMPLE_ROWS, example="10000")
    inputs.check_flag(gap_split, "gap_split")
    inputs.check_optional_flag(progress, "progress")
    if gap_split and test is None:
        raise ArgumentError("gap_split", "needs `test`: it splits the error on the held-out test poses.")
    return alpha, folds, seed, cv_rows


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

    def reproduce_command(self) -> tuple:
        """``(command line, Python call, notes)`` that reproduce this result (:mod:`tolalloc.workflows.reproduce`)."""
        from tolalloc.workflows.reproduce import diagnosis_command

        return diagnosis_command(self)

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
                 + ("" if v is None or not v.candidates else f"   candidates: {', '.join(v.candidates)}")
                 + ("" if v is None or not v.further else f"   further, family not claimed: {v.further_terms()}")]
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

    @cached_property
    def _identified(self):
        from tolalloc.diagnose.model_use import identified_model

        return identified_model(self.diagnosis)

    def identified_model(self):
        """The final model, ready to evaluate at new poses (:class:`~tolalloc.diagnose.model_use.IdentifiedModel`)."""
        return self._identified

    def predict(self, q, *, payload_kg=None, temperature_c=None, time_s=None, dir=None, wrench=None,
                frame: str = "base") -> pd.DataFrame:
        """The final model's target points at joint values ``q`` [deg / mm] (an array (P, n), or a CSV path /
        DataFrame with a column per joint and the covariate columns), with the covariates its effects read
        (``wrench`` (P, 6): a process force [N] and moment [N m] at the target, base frame).

        Returns one row per pose: ``x_mm, y_mm, z_mm`` in ``frame`` (``base``: the robot's base frame; ``tracker``: the
        training file's measurement frame), ``sigma_mm`` (1-sigma of the 3-D prediction error from the parameter
        covariance) and ``radius95_mm`` (the radius holding a measured point with 95 % probability)."""
        from tolalloc.diagnose.model_use import FRAMES
        from tolalloc.workflows.model_use import predict_frame

        inputs.check_choice(frame, "frame", FRAMES)
        return predict_frame(self.identified_model(), q, frame=frame, payload_kg=payload_kg,
                             temperature_c=temperature_c, time_s=time_s, dir=dir, wrench=wrench)

    def compensate(self, program, *, frame: str = "base", tol_mm: float = 1e-6):
        """Joint values that put the target point where the nominal robot would (or on the program's ``x_mm, y_mm,
        z_mm``) under the final model: :func:`~tolalloc.workflows.model_use.compensate_program`."""
        from tolalloc.workflows.model_use import compensate_program

        return compensate_program(self, program, frame=frame, tol_mm=tol_mm)

    def export_model(self, directory, *, name: str | None = None) -> list:
        """Write ``identified.toml`` (chain layout: the identified geometry, and the ``[identified]`` section with the
        fitted parameters and effects) and ``identified.urdf`` into ``directory`` (created; both or neither);
        the paths written (:mod:`tolalloc.diagnose.model_export`)."""
        from tolalloc.workflows.model_use import export_files

        directory = self.check_out(directory, "directory", required=True)
        with output_group() as group:
            names = export_files(self.identified_model(), group.directory(directory), name)
        return [directory / nm for nm in names]

    def export_notes(self) -> list[str]:
        """One line per effect of the final model that an exported file cannot carry (it needs this training
        session), with what to do instead; empty where the file holds the whole model."""
        from tolalloc.diagnose.model_export import leave_out_advice, session_bound

        model = self.identified_model()
        notes = [(e, model.variants[e], session_bound(e, model.variants[e])) for e in model.effects]
        return [f"identified.toml: its {e} effect (variant {v}) {why}; compensate with this diagnosis, or "
                f"{leave_out_advice(e)}" for e, v, why in notes if why is not None]

    def plot_where(self, ax=None):
        """Where the geometric model's training residual lies (the strongest features, per axis, per region); draws
        into ``ax`` (a sequence of Axes, one per panel) or a new figure and returns the Axes (an array)."""
        from tolalloc.report.plots.diagnose import draw_where, where_figure, where_panels

        where = self.diagnosis.where
        if ax is None:
            fig, ax = where_figure(where)
            fig.suptitle("Residual after geometric calibration: where")
        axes = np.ravel(np.asarray(ax, dtype=object))
        if len(axes) < where_panels(where):
            raise ArgumentError("ax", f"expected at least {where_panels(where)} Axes (one per panel), got {len(axes)}.")
        draw_where(where, axes)
        return axes[:where_panels(where)]  # the panels drawn (a new figure's spare cells are switched off)

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

    def plot_before_after(self, ax=None):
        """Held-out RMS, p95 and max error of the nominal, geometric and final models [mm]; draws into ``ax`` or a new
        figure and returns the Axes."""
        from tolalloc.report.plots.diagnose import plot_before_after

        return plot_before_after(self.to_frame(), None, ax=ax)

    def plot_ranking(self, ax=None):
        """Clipped out-of-fold RMS of every candidate effect against the geometric model; draws into ``ax`` or a new
        figure and returns the Axes."""
        from tolalloc.report.plots.diagnose import plot_ranking

        return plot_ranking(self.diagnosis, None, ax=ax)

    has_report = True

    def save(self, directory=None, *, report: bool = False, json=None, predictions=None, **old) -> list:
        """Write the report files (``report.md``, CSV tables, figures, ``diagnosis.json``; ``report=True`` adds the
        self-contained ``report.html``) into ``directory``, the JSON result to ``json`` (``"-"``: standard output)
        and / or the test predictions CSV to ``predictions``; all published together, nothing if any fails. Returns
        the paths written. ``save(report=DIR)``, the former form (the folder was called ``report``), still writes
        the folder with ``report.html``, with a DeprecationWarning."""
        import warnings

        if isinstance(report, (str, os.PathLike)):
            warnings.warn("MeasurementDiagnosis.save(report=DIR) is deprecated: use save(DIR, report=True) (every "
                          "result saves as save(directory, *, report=False, json=None)).", DeprecationWarning,
                          stacklevel=2)
            if directory is not None:
                raise ArgumentError("report", "a folder and `directory` both given; give save(directory, report=True).")
            directory, report = report, True
        directory, report = self._old_save_keywords(directory, report, old)
        self.check_out(predictions, "predictions", directory=False)
        if predictions is not None and self.diagnosis.test is None:
            raise ArgumentError("predictions", "needs `test`: predictions are made for the rows of the test file.")
        extra = [("predictions", predictions,
                  lambda path: self.predictions_frame().to_csv(path, index=False, float_format="%.6f"))]
        return self._save(directory, report=report, json=json, extra=extra)

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """report.md, the CSV tables, the figures, diagnosis.json (and ``report``: report.html) into an existing
        ``folder`` (not atomic; :meth:`save` stages through this); returns the file names."""
        from pathlib import Path

        folder = Path(folder)
        before = {p.name for p in folder.iterdir()}
        self.write_report(folder, html=report)
        return sorted(p.name for p in folder.iterdir() if p.name not in before)

    def write_report(self, folder, *, html: bool = True) -> None:
        """report.md, the CSV tables and the figures (and ``html``: report.html) into an existing ``folder`` (a
        ``str`` or ``os.PathLike``; not atomic)."""
        from pathlib import Path

        from tolalloc.report.diagnosis import write_report

        folder = Path(folder)
        write_report(self.diagnosis, folder)
        if self.gap is not None:
            self.gap.to_frame().to_csv(folder / "gap_split.csv", index=False, float_format="%.6g")
        if html:
            from tolalloc.report.html_diagnosis import write_diagnosis_report

            write_diagnosis_report(self, folder)
