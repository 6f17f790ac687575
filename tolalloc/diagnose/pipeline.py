"""The whole diagnosis: calibrate, break the residual down, select effects, score before/after."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
from threadpoolctl import threadpool_limits

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Robot
from tolalloc.diagnose.calibrate import DEFAULT_TOL, Calibration, Fit, calibrate, fit_model
from tolalloc.diagnose.effects import effect_basis
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.misfit import check_nominal_misfit
from tolalloc.diagnose.effect_checks import compliance_sign_flags
from tolalloc.diagnose.guards import (Extrapolation, ParameterCheck, PoseUncertainty, cv_fallback,
                                     extrapolation_flags, parameter_checks, prediction_uncertainty)
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.register import REGISTER_N, RegistrationSplit, register_and_score, register_count
from tolalloc.diagnose.scale import CHUNK_ROWS, SUBSAMPLE_ROWS, fit_counter, progress_bar, progress_scope, subsample_index
from tolalloc.diagnose.select import (Evaluation, align_basis, error_stats, evaluate, kept_basis, make_context, score_test,
                                      select_effects)
from tolalloc.diagnose.where import WhereBreakdown, where_breakdown

__all__ = ["Diagnosis", "diagnose", "MIN_SUBSAMPLE_ROWS"]

#: Smallest cross-validation subsample of a large training file.
MIN_SUBSAMPLE_ROWS = 200
#: The final fit on all rows of a large file holds the effect basis when it needs at most this many bytes,
#: else it recomputes it chunk by chunk on every pass.
BASIS_CACHE_BYTES = 256 * 2**20


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """Result of :func:`diagnose`.

    Attributes
    ----------
    robot : Robot
    train, test : Measurements (test may be None)
    calibration : Calibration      registration + offset (+ identifiable geometry) on all training poses
    stages : tuple of Stage        sequential selection; ``stages[0].candidates`` is the ranking
    effects : tuple of str         selected effects in order (empty: ``none``)
    nominal, geometric, final : Evaluation   held-out evaluations of the three models
    where : WhereBreakdown         residual breakdown after geometric calibration (training poses)
    test_frame : {"same", "refit"}
    guards : tuple of str          guards that fired (implausible or weakly identified parameters, extrapolating
                                   test poses, fallback)
    extrapolation : Extrapolation or None   per test pose flags (None without a test file)
    fallback : str or None         ``nominal`` / ``geometric`` when the fitted model lost on cross-validation
    registration : RegistrationSplit or None   ``refit``: test poses used to register the frame (never scored)
    uncertainty : PoseUncertainty or None      per test pose predicted 1-sigma and 95 % radius, coverage check
    registered : Fit or None       ``refit``: the final fit with the test frame's registration and probe offset
    subsample : dict or None       large training files: what ran on a seeded subsample (cross-validation,
                                   effect selection, identifiability) and what on all rows (the final fits)
    parameter_check : ParameterCheck or None   geometric parameters and probe offset vs the plausibility level
    findings : tuple of str        well-identified deviations from nominal (informational, not guards)
    """

    robot: Robot
    train: Measurements
    test: Measurements | None
    calibration: Calibration
    stages: tuple
    effects: tuple
    nominal: Evaluation
    geometric: Evaluation
    final: Evaluation
    where: WhereBreakdown
    test_frame: str = "same"
    guards: tuple = ()
    extrapolation: Extrapolation | None = None
    fallback: str | None = None
    registration: RegistrationSplit | None = None
    uncertainty: PoseUncertainty | None = None
    registered: Fit | None = None
    subsample: dict | None = None
    parameter_check: ParameterCheck | None = None
    findings: tuple = ()

    @property
    def scored_index(self) -> np.ndarray:
        """Test poses (0-based) the test figures are computed on: all, or the non-registration ones."""
        return self.registration.score_index if self.registration is not None else np.arange(self.test.n_poses)

    @property
    def effect(self) -> str:
        """The first selected effect or ``none``."""
        return self.effects[0] if self.effects else "none"

    @property
    def ranking(self) -> tuple:
        return self.stages[0].candidates

    def before_after(self, which: str = "heldout") -> pd.DataFrame:
        """RMS / p95 / max / mean error [mm] of nominal, geometric and final models with the shrink in percent.

        ``which``: ``heldout`` (CV + test), ``cv`` (out-of-fold training poses) or ``test``.
        """
        rows = []
        for name, ev in (("nominal", self.nominal), ("geometric", self.geometric), ("final", self.final)):
            res = {"heldout": ev.heldout_mm, "cv": ev.oof_mm, "test": ev.test_mm}[which]
            if res is None:
                raise TolallocError("no test file was given; use which='heldout' or 'cv'.")
            rows.append({"model": name, "label": ev.label, **error_stats(res)})
        df = pd.DataFrame(rows)
        for col in ("rms_mm", "p95_mm", "max_mm"):
            base = df[col].iloc[0]
            df[col.replace("_mm", "_shrink_pct")] = 100.0 * (1.0 - df[col] / base)
        df["rms_shrink_vs_geometric_pct"] = 100.0 * (1.0 - df["rms_mm"] / df["rms_mm"].iloc[1])
        return df

    def ranking_frame(self) -> pd.DataFrame:
        return pd.DataFrame([c.to_dict() for c in self.ranking])

    def sequence_frame(self) -> pd.DataFrame:
        rows = []
        for i, st in enumerate(self.stages):
            for c in st.candidates:
                rows.append({"step": i + 1, "base": "+".join(("geometric", *st.base)), "base_rms_mm": st.base_rms_mm,
                             **c.to_dict(), "selected": c.effect == st.selected, "removed": c.effect == st.removed})
        return pd.DataFrame(rows)

    def to_dict(self) -> dict:
        ba = self.before_after()
        out = {
            "robot": self.robot.name,
            "effect": self.effect,
            "effects": list(self.effects),
            "ranking": [c.to_dict() for c in self.ranking],
            "sequence": [{"base": list(st.base), "base_rms_mm": st.base_rms_mm, "selected": st.selected or "none", "removed": st.removed,
                          "candidates": [c.to_dict() for c in st.candidates]} for st in self.stages],
            "rms_mm": dict(zip(ba["model"], ba["rms_mm"])),
            "p95_mm": dict(zip(ba["model"], ba["p95_mm"])),
            "max_mm": dict(zip(ba["model"], ba["max_mm"])),
            "shrink_pct": {"final_vs_nominal": float(ba["rms_shrink_pct"].iloc[2]),
                           "final_vs_geometric": float(ba["rms_shrink_vs_geometric_pct"].iloc[2]),
                           "geometric_vs_nominal": float(ba["rms_shrink_pct"].iloc[1])},
            "heldout": {"cv_poses": len(self.nominal.oof_mm), "test_poses": 0 if self.test is None else len(self.scored_index),
                        "test_frame": self.test_frame},
            "train": {"poses": self.train.n_poses, "skipped_rows": self.train.n_skipped, "source": self.train.source,
                      "rms_mm": {"nominal": self.calibration.nominal.rms_mm, "geometric": self.calibration.geometric.rms_mm,
                                 "final": self.final.fit.rms_mm}},
            "identifiability": self.calibration.identifiability.to_dict(),
            "registration": {"rotation": self.calibration.geometric.R, "translation_mm": self.calibration.geometric.p_mm,
                             "target_offset_mm": self.calibration.geometric.t_mm},
            "parameters": self.final.fit.parameters_frame().to_dict(orient="records"),
            "guards": list(self.guards),
            "findings": list(self.findings),
            "fallback": self.fallback,
            "subsample": self.subsample,
            "models": {"calibration": "complete minimal geometric model (diagnose.geometry): 4 line errors per "
                                      "revolute joint, 2 per prismatic joint, joint offsets, registration, probe offset",
                       "tolerance": "the paper's error-screw model (errormodel.model), not used by the diagnosis"},
        }
        out["cv"] = self._block("cv") | {"poses": self.train.n_poses}
        if self.extrapolation is not None:
            out["extrapolation"] = self.extrapolation.to_dict()
        if self.test is not None:
            bt = self.before_after("test")
            out["test_rms_mm"] = dict(zip(bt["model"], bt["rms_mm"]))
            out["test"] = {"poses": self.test.n_poses, "skipped_rows": self.test.n_skipped, "source": self.test.source,
                           "scored_poses": len(self.scored_index), **self._block("test"),
                           "registration": None if self.registration is None else self.registration.to_dict(self.test.rows)}
            if self.registered is not None:
                out["test"]["registration"] |= {"rotation": self.registered.R, "translation_mm": self.registered.p_mm,
                                                "target_offset_mm": self.registered.t_mm}
        if self.uncertainty is not None:
            out["uncertainty"] = self.uncertainty.to_dict()
        if self.parameter_check is not None:
            out["parameter_check"] = self.parameter_check.to_frame().to_dict(orient="records")
        return out

    def _block(self, which: str) -> dict:
        b = self.before_after(which)
        return {k: dict(zip(b["model"], b[k])) for k in ("rms_mm", "p95_mm", "max_mm")}


def diagnose(robot: Robot, train: Measurements, test: Measurements | None = None, *, folds: int = 5,
             alpha: float = 0.01, min_gain: float = 0.02, max_effects: int = 3, seed: int = 0,
             test_frame: str = "same", tol: float = DEFAULT_TOL, threads: int | None = 1,
             register_n: float = REGISTER_N, cv: str = "blocked", progress: bool | None = False,
             subsample_rows: int = SUBSAMPLE_ROWS) -> Diagnosis:
    """Diagnose the gap between a robot model and its measurements.

    Parameters
    ----------
    robot : Robot
    train : Measurements        fitted (and cross-validated with at least ``folds`` folds, more on few poses:
                                :func:`tolalloc.diagnose.folds.fold_count`)
    test : Measurements, optional  scored only
    alpha : float               family-wise significance level of the selection
    min_gain : float            minimum relative held-out RMS reduction of a selected effect
    test_frame : {"same", "refit"}
        ``refit``: the test file is in another tracker frame (another session); its registration and
        target offset are re-estimated on ``register_n`` test poses spread in joint space
        (:mod:`.register`), and only the other test poses are scored.
    register_n : float          ``refit``: registration poses, a count (>= 1, default 30) or a fraction (< 1)
    threads : int or None       BLAS threads during the fits (1 is fastest for these small problems)
    cv : {"blocked", "time", "joint", "random"}  cross-validation folds (see :func:`select.make_folds`)
    progress : bool or None     progress bars on stderr (None: when stderr is a terminal)
    subsample_rows : int
        Training files with more rows cross-validate and select effects on a seeded random subsample (``seed``)
        of this many rows; the nominal, geometric and final models are then fitted on all rows
        (``Diagnosis.subsample`` says so).
    """
    if test_frame not in ("same", "refit"):
        raise TolallocError(f"test_frame: expected 'same' or 'refit', got {test_frame!r}.")
    if folds < 2:
        raise TolallocError(f"folds: expected at least 2 cross-validation folds, got {folds}.")
    if folds > train.n_poses // 2:
        raise TolallocError(f"folds: expected at most {train.n_poses // 2} cross-validation folds for "
                            f"{train.n_poses} training poses (at least 2 poses held out per fold), got {folds}.")
    if test is not None and test_frame == "refit":
        register_count(test.n_poses, register_n)  # a bad --register-n fails before any fit
    if subsample_rows < MIN_SUBSAMPLE_ROWS:
        raise TolallocError(f"subsample_rows: expected at least {MIN_SUBSAMPLE_ROWS} rows for the cross-validation "
                            f"subsample, got {subsample_rows}.")
    with threadpool_limits(threads), progress_scope(progress):
        model = build_geometry_model(robot)
        cal = calibrate(robot, train, model=model, tol=tol)
        check_nominal_misfit(robot, train, cal.nominal)
        sub = subsample_index(train.n_poses, subsample_rows, seed)
        cv_train = train if sub is None else train.subset(sub)
        ctx = make_context(cal, cv_train, test, folds=folds, seed=seed, test_frame=test_frame, tol=tol,
                           register_n=register_n, cv=cv)
        with fit_counter(f"cross-validation ({cv_train.n_poses:,} rows)"):
            nominal = evaluate(ctx, nominal=True)
            geometric = evaluate(ctx)
            stages, _, final = select_effects(ctx, geometric, alpha=alpha, min_gain=min_gain, max_effects=max_effects)
        subsample = None
        if sub is not None:
            nominal, geometric, final = _all_rows(ctx, train, cal, nominal, geometric, final)
            subsample = {"rows": train.n_poses, "cv_rows": len(sub), "seed": seed,
                         "identifiability_rows": cal.identifiability_rows,
                         "subsampled": "cross-validation (out-of-fold errors, p-values), effect selection, "
                                       "identifiability of geometric and effect parameters",
                         "all_rows": "nominal, geometric and final fits (parameters, training RMS, test-file scores)"}
        bar = progress_bar("residual breakdown")
        where = where_breakdown(robot, train, cal.geometric)
        bar.close()
    effects = final.effects  # forward selection, then backward elimination (select._backward)
    geo = cal.geometric if sub is None else replace(cal.geometric, residual_mm=cal.geometric.residual_mm[sub])
    check = parameter_checks(geo, cv_train.q)  # large files: posterior sd from the subsample (conservative)
    guards = list(check.guards())
    chosen, msgs = cv_fallback(nominal, geometric, final)
    if chosen is final and "joint_compliance" in final.effects:
        Btr = kept_basis(ctx.bases, final)
        fit_cv = final.fit if sub is None else replace(final.fit, residual_mm=final.fit.residual_mm[sub])
        guards.extend(compliance_sign_flags(fit_cv, ctx.train.q, Btr, final.param_names))
    guards.extend(msgs)
    fallback = None
    if chosen is not final:
        fallback, final, effects = chosen.label, chosen, ()
    extrap, unc, reg = _test_guards(ctx, robot, train, nominal, final, threads, guards)
    return Diagnosis(robot, train, test, cal, tuple(stages), effects, nominal, geometric, final, where, test_frame,
                     tuple(guards), extrap, fallback, ctx.registration, unc, reg, subsample, check, check.findings())


def _test_guards(ctx, robot, train, nominal: Evaluation, final: Evaluation, threads, guards: list) -> tuple:
    """Test-file guards (appended to ``guards``): predicted uncertainty, extrapolation, final worse than nominal."""
    test = ctx.test
    if test is None:
        return None, None, None
    with threadpool_limits(threads):
        unc, reg = _uncertainty(ctx, final)
    if unc.message():
        guards.append(unc.message())
    extrap = extrapolation_flags(robot, train.q, test.q)
    if extrap.message():
        guards.append(extrap.message())
    worse = {k: (error_stats(final.test_mm)[k], error_stats(nominal.test_mm)[k]) for k in ("rms_mm", "max_mm")}
    for k, (f, nmn) in worse.items():
        if f > nmn:
            guards.append(f"test file: the final model's {k[:-3]} error is larger than the nominal model's "
                          f"({f:.4g} vs {nmn:.4g} mm)")
    return extrap, unc, reg


def _all_rows(ctx, train, cal: Calibration, nominal: Evaluation, geometric: Evaluation, final: Evaluation):
    """The three models of a subsampled diagnosis refitted on every training row (effect bases chunk by chunk)."""
    robot, t = cal.geometric.model.robot, cal.geometric.t_mm

    def rescore(ev, fit):
        test_res, test_pred = score_test(ctx, fit, ev.effects, ev.keep)
        return replace(ev, fit=fit, test_mm=test_res, test_pred_mm=test_pred)

    def basis(sl):
        part = train.subset(np.arange(sl.start, sl.stop))
        B = np.concatenate([align_basis(effect_basis(e, robot, part, t, ctx.ref), ctx.bases[e].names).B
                            for e in final.effects], axis=2)
        return B[:, :, final.keep]

    nominal, geometric = rescore(nominal, cal.nominal), rescore(geometric, cal.geometric)
    if not final.effects:
        return nominal, geometric, geometric  # no effect selected: the final model is the geometric one
    B, P = basis, train.n_poses
    if P * 3 * len(final.keep) * 8 <= BASIS_CACHE_BYTES:  # small enough: build it once, not on every pass
        B = np.empty((P, 3, len(final.keep)))
        for a in range(0, P, CHUNK_ROWS):
            B[a:a + CHUNK_ROWS] = basis(slice(a, min(a + CHUNK_ROWS, P)))
    fit = fit_model(cal.geometric, train.q, train.xyz_mm, geo_index=cal.geometric.geo_index, B=B,
                    n_effects=len(final.keep), effect_names=final.param_names, label="final fit")
    return nominal, geometric, rescore(final, fit)


def _uncertainty(ctx, final: Evaluation) -> tuple:
    """Predicted uncertainty of ``final`` on the test poses and, with ``refit``, the re-registered final fit."""
    fit, test = final.fit, ctx.test
    Btr, Bte = kept_basis(ctx.bases, final), kept_basis(ctx.bases_test, final)
    if ctx.registration is None:
        return prediction_uncertainty(fit, ctx.train.q, test.q, final.test_mm, B_train=Btr, B_test=Bte), None
    extra = np.zeros((test.n_poses, 3)) if Bte is None else Bte @ fit.beta
    reg = register_and_score(fit, test.q, test.xyz_mm, extra, ctx.registration)
    unc = prediction_uncertainty(fit, ctx.train.q, test.q, final.test_mm, B_train=Btr, B_test=Bte,
                                 registered=reg.fit, split=ctx.registration)
    return unc, reg.fit


