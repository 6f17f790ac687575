"""The whole diagnosis: calibrate, break the residual down, select effects on the training file, then score the
chosen model once on the sealed test file and state a verdict (:mod:`.verdict`)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Robot
from tolalloc.diagnose.calibrate import (DEFAULT_LOSS, DEFAULT_TOL, Calibration, calibrate, fit_model, initial_fit,
                                        is_collinear, offset_prior, outlier_rows, small_file_min_gain)
from tolalloc.diagnose.diagnosis import Diagnosis
from tolalloc.diagnose.effects import effect_basis
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.misfit import check_nominal_misfit
from tolalloc.diagnose.effect_checks import compliance_sign_flags
from tolalloc.diagnose.guards import (cv_fallback, extrapolation_flags, instrument_noise, noise_guard,
                                      parameter_checks)
from tolalloc.diagnose.uncertainty import prediction_uncertainty
from tolalloc.diagnose.measurements import Measurements, file_rows
from tolalloc.diagnose.recalibrate import REGISTER_UPDATES, UNCERTAINTY_SCOPE, CalibrationUpdate, update_loss
from tolalloc.diagnose.register import MIN_REGISTER, REGISTER_N, check_register_rows, register_count, split_from_rows
from tolalloc.progress import fit_counter, progress_bar, progress_scope
from tolalloc.diagnose.scale import CHUNK_ROWS, SUBSAMPLE_ROWS, point_kinematics, subsample_index
from tolalloc.diagnose.scores import Evaluation, clip_level, error_stats, rms
from tolalloc.diagnose.select import align_basis, evaluate, kept_basis, make_context, score_test
from tolalloc.diagnose.stepwise import select_effects
from tolalloc.diagnose.steps import step_check
from tolalloc.diagnose.families import family_log_evidence, posterior_probabilities
from tolalloc.diagnose.verdict import (PRACTICAL_MARGIN, compare_alternatives, inconclusive_reasons, safe_model,
                                       scored_test_stats, separating_poses, tied)
from tolalloc.diagnose.verdict_text import verdict_of
from tolalloc.diagnose.where import where_breakdown

__all__ = ["Diagnosis", "diagnose", "MIN_SUBSAMPLE_ROWS", "LOSS_CHOICES"]

#: Smallest cross-validation subsample of a large training file.
MIN_SUBSAMPLE_ROWS = 200
#: The final fit on all rows of a large file holds the effect basis when it needs at most this many bytes,
#: else it recomputes it chunk by chunk on every pass.
BASIS_CACHE_BYTES = 256 * 2**20
#: Robust losses ``robust_loss`` accepts.
LOSS_CHOICES = ("auto", "tukey", "huber", "soft_l1")


def _line_guard(robot: Robot, train: Measurements) -> str | None:
    """A guard when the training poses put the nominal tool point on one line: the tracker frame's rotation about
    that line is then not determined by the data (the registration takes the smallest rotation)."""
    pts, _ = point_kinematics(robot.screws, robot.home, train.q, np.zeros(3))
    if not is_collinear(pts):
        return None
    return (f"registration: the {train.n_poses} training poses put the tool point on one straight line, so the "
            "tracker frame's rotation about that line is not determined by them (the smallest rotation is used): "
            "predictions for poses off that line are not supported; measure poses that span a plane or a volume")


def _check_args(robot, train, test, test_frame, folds, register_n, subsample_rows, robust_loss, target_offset_mm,
                target_offset_sd_mm, register_update="frame", register_rows=None):
    """Validate the arguments of :func:`diagnose`; returns the target-offset prior (mean, sd) or None."""
    if test_frame not in ("same", "refit"):
        raise TolallocError(f"test_frame: expected 'same' or 'refit', got {test_frame!r}.")
    if register_update not in REGISTER_UPDATES:
        raise TolallocError(f"register_update: expected one of {', '.join(REGISTER_UPDATES)}, got {register_update!r}.")
    if register_update != "frame" and (test is None or test_frame != "refit"):
        raise TolallocError(f"register_update={register_update!r} needs a test file with test_frame='refit' (got "
                            f"{'no test file' if test is None else 'test_frame=' + repr(test_frame)}): only a test "
                            "file in another frame is re-registered; pass one, or leave register_update='frame'.")
    if folds < 2:
        raise TolallocError(f"folds: expected at least 2 cross-validation folds, got {folds}.")
    if folds > train.n_poses // 2:
        raise TolallocError(f"folds: expected at most {train.n_poses // 2} cross-validation folds for "
                            f"{train.n_poses} training poses (at least 2 poses held out per fold), got {folds}.")
    for name, m in (("train", train), ("test", test)):
        if m is not None and m.q.shape[1] != robot.n_joints:
            raise TolallocError(f"{name}: the measurements have {m.q.shape[1]} joint columns but robot "
                                f"{robot.name!r} has {robot.n_joints} joints; is it a file of another robot?")
    check_register_rows(register_rows, register_n, test_given=test is not None, test_frame=test_frame)
    if test is not None and test_frame == "refit":  # a bad --register-n or --register-rows fails before any fit
        if register_rows is None:
            register_count(test.n_poses, REGISTER_N if register_n is None else register_n)
        else:
            split_from_rows(register_rows, test.n_poses, test.rows, test.source)
    if subsample_rows < MIN_SUBSAMPLE_ROWS:
        raise TolallocError(f"subsample_rows: expected at least {MIN_SUBSAMPLE_ROWS} rows for the cross-validation "
                            f"subsample, got {subsample_rows}.")
    if robust_loss not in LOSS_CHOICES:
        raise TolallocError(f"robust_loss: expected one of {', '.join(LOSS_CHOICES)}, got {robust_loss!r}.")
    return offset_prior(target_offset_mm, target_offset_sd_mm)


def diagnose(robot: Robot, train: Measurements, test: Measurements | None = None, *, folds: int = 5,
             alpha: float = 0.01, min_gain: float = 0.02, max_effects: int = 3, seed: int = 0,
             test_frame: str = "same", tol: float = DEFAULT_TOL, threads: int | None = 1,
             register_n: float | None = None, cv: str = "blocked", progress: bool | None = False,
             subsample_rows: int = SUBSAMPLE_ROWS, robust_loss: str = "auto",
             target_offset_mm=None, target_offset_sd_mm=None, register_update: str = "frame",
             register_rows=None, instrument_noise_mm: float | None = None) -> Diagnosis:
    """Diagnose the gap between a robot model and its measurements.

    The **test file is sealed**: the variants, fold counts, clip level, significance tests, effect selection and
    the ambiguity comparisons use the training file only; the test file is scored once, for the nominal,
    geometric and final models, after everything is chosen. Its figures feed only the guards and the verdict
    (a final model worse than nominal on it makes the verdict ``inconclusive``), never the choice.

    Parameters
    ----------
    robot : Robot
    train : Measurements        fitted (and cross-validated with at least ``folds`` folds, more on few poses:
                                :func:`tolalloc.diagnose.folds.fold_count`)
    test : Measurements, optional  scored only, after the selection
    alpha : float               family-wise significance level of the selection
    min_gain : float            minimum relative held-out RMS reduction of a selected effect
    test_frame : {"same", "refit"}
        ``refit``: the test file is in another tracker frame (another session); its registration and
        target offset are re-estimated on ``register_n`` test poses spread in joint space
        (:mod:`.register`), or on the ``register_rows``, and only the other test poses are scored.
    register_n : float, optional  ``refit``: registration poses, a count (>= 1, None: 30) or a fraction (< 1)
    register_rows : sequence of int, optional
        ``refit``, instead of ``register_n``: the test rows that register the frame (and fit the update), numbered
        as ``test.rows`` and the JSON's ``registration_rows`` number them (:func:`.register.split_from_rows`);
        every other test row is scored.
    register_update : {"frame", "calibration"}
        ``refit``: what the registration poses re-fit. ``frame`` (default): the tracker frame and the probe offset,
        the trained model frozen. ``calibration``: also a correction of the trained geometric and effect
        parameters, with the training fit as the prior (a power prior: its training data counting 1/k, k as the
        registration poses' marginal likelihood chooses it, at least the out-of-fold / in-sample residual ratio of
        the training file; :mod:`.recalibrate`). No effect without ``refit``.
    threads : int or None       BLAS threads during the fits (1 is fastest for these small problems)
    cv : {"blocked", "time", "joint", "random"}  cross-validation folds (see :func:`select.make_folds`)
    progress : bool or None     progress on stderr (:func:`tolalloc.progress.progress_scope`; None: on)
    subsample_rows : int
        Training files with more rows cross-validate and select effects on a seeded random subsample (``seed``)
        of this many rows; the nominal, geometric and final models are then fitted on all rows
        (``Diagnosis.subsample`` says so).
    robust_loss : {"auto", "tukey", "huber", "soft_l1"}
        M-estimator of every fit (registration, geometry, effects; :func:`~.calibrate.fit_model`). Tukey's
        biweight gives gross outliers no weight; ``auto`` (default) is Tukey's, or Huber's bounded-influence loss on a
        small training file (fewer than 10 poses per fitted parameter, :func:`~.calibrate.calibrate`). Down-weighted
        rows are listed per stage in ``Diagnosis.outliers``.
    target_offset_mm : array (3,) [mm], optional
        Prior mean of the target (probe) offset in the flange frame, relative to the robot's tool point
        (default 0: the robot's tool definition). Needs ``target_offset_sd_mm``.
    target_offset_sd_mm : float or array (3,) [mm], optional
        Prior sd of the target offset: every fit (training, folds, test re-registration) uses the prior. Without
        it the training fits leave the offset free and the folds borrow the training fit's (:mod:`.select`).
    instrument_noise_mm : float [mm], optional
        The instrument's stated noise, one sd per axis: only for the guard :func:`~.guards.noise_guard`.
    """
    instrument_noise_mm = instrument_noise(instrument_noise_mm)
    t_prior = _check_args(robot, train, test, test_frame, folds, register_n, subsample_rows, robust_loss,
                          target_offset_mm, target_offset_sd_mm, register_update, register_rows)
    with threadpool_limits(threads), progress_scope(progress):
        model = build_geometry_model(robot)
        cal = calibrate(robot, train, model=model, tol=tol, loss=robust_loss, t_prior=t_prior)
        robust_loss = cal.loss  # Huber in place of Tukey on a small file (Calibration.loss_note)
        check_nominal_misfit(robot, train, cal.nominal)
        sub = subsample_index(train.n_poses, subsample_rows, seed)
        cv_train = train if sub is None else train.subset(sub)
        ctx = make_context(cal, cv_train, test, folds=folds, seed=seed, test_frame=test_frame, tol=tol,
                           register_n=register_n, cv=cv, t_prior=t_prior, loss=robust_loss,
                           register_update=register_update, register_rows=register_rows)
        sel = _select(ctx, alpha, min_gain, max_effects, seed, train.n_poses)
        subsample = None
        if sub is not None:
            sel["nominal"], sel["geometric"], sel["final"] = _all_rows(ctx, train, cal, sel["nominal"],
                                                                       sel["geometric"], sel["final"], robust_loss,
                                                                       t_prior)
            sel["chosen"] = {"nominal": sel["nominal"], "geometric": sel["geometric"]}.get(sel["chosen"].label,
                                                                                        sel["final"])
            subsample = {"rows": train.n_poses, "cv_rows": len(sub), "seed": seed,
                         "identifiability_rows": cal.identifiability_rows,
                         "subsampled": "cross-validation (out-of-fold errors, p-values), effect selection, "
                                       "identifiability of geometric and effect parameters",
                         "all_rows": "nominal, geometric and final fits (parameters, training RMS, test-file scores)"}
        with progress_bar("residual breakdown"):
            where = where_breakdown(robot, train, cal.geometric)
        scored = _score_sealed_test(ctx, sel["nominal"], sel["geometric"], sel["final"], sel["chosen"])
        sel["nominal"], sel["geometric"], sel["final"], sel["chosen"] = scored
    return _conclude(ctx, robot, train, test, cal, sel, where, sub, cv_train, subsample, threads, t_prior, robust_loss,
                     alpha, min_gain, instrument_noise_mm)


def _select(ctx, alpha, min_gain, max_effects, seed, n_poses) -> dict:
    """Cross-validated selection on the training file, the CV fallback and the ambiguity comparisons.

    A selection step asks for ``min_gain``, raised on a small file of ``n_poses`` training poses
    (:func:`~.calibrate.small_file_min_gain`); the comparisons keep ``min_gain``, so that a small file's alternatives
    are not dropped from a tie by the stricter step."""
    step_gain, gain_note = small_file_min_gain(n_poses, 9 + len(ctx.cal.geometric.geo_index), min_gain)
    with fit_counter(f"cross-validation ({ctx.train.n_poses:,} rows)"):
        nominal = evaluate(ctx, nominal=True)
        geometric = evaluate(ctx)
        logml = family_log_evidence(ctx)
        stages, evals, final = select_effects(ctx, geometric, alpha=alpha, min_gain=step_gain,
                                              max_effects=max_effects, logml=logml)
        clip = clip_level(geometric.selection_mm)
        chosen, msgs = cv_fallback(nominal, geometric, final)
        comparisons = (compare_alternatives(ctx, final, stages, evals, evaluate, clip, alpha, min_gain, logml=logml)
                       if chosen is final and final.effects else ())
    probs = posterior_probabilities(logml)
    if stages:
        stages[0] = replace(stages[0], candidates=tuple(replace(c, probability=probs.get(c.effect, float("nan")))
                                                        for c in stages[0].candidates))
    swap = (lambda c: "+".join(("geometric", *(c.alternative if x == c.effect else x for x in final.effects))))
    pairs = [(final, evals[swap(c)], c.effect, c.alternative) for c in tied(comparisons)]
    return {"nominal": nominal, "geometric": geometric, "final": final, "chosen": chosen, "stages": stages,
            "step_gain": step_gain, "gain_note": gain_note, "messages": msgs, "comparisons": comparisons,
            "suggestions": separating_poses(ctx, pairs, evals, seed=seed) if pairs else None}


def _conclude(ctx, robot, train, test, cal, sel, where, sub, cv_train, subsample, threads, t_prior, loss,
              alpha, min_gain, noise_mm=None) -> Diagnosis:
    """Guards, the CV fallback, the verdict and the result."""
    nominal, geometric, final, chosen = sel["nominal"], sel["geometric"], sel["final"], sel["chosen"]
    effects = final.effects  # forward selection, then backward elimination (stepwise._backward)
    geo = cal.geometric if sub is None else replace(cal.geometric, residual_mm=cal.geometric.residual_mm[sub])
    check = parameter_checks(geo, cv_train.q)  # large files: posterior sd from the subsample (conservative)
    guards = list(check.guards())
    line = _line_guard(robot, train)
    if line is not None:
        guards.append(line)
    if chosen is final and "joint_compliance" in final.effects:
        Btr = kept_basis(ctx.bases, final)
        fit_cv = final.fit if sub is None else replace(final.fit, residual_mm=final.fit.residual_mm[sub])
        guards.extend(compliance_sign_flags(fit_cv, ctx.train.q, Btr, final.param_names))
    guards.extend(sel["messages"])
    fallback = None
    if chosen is not final:
        fallback, final, effects = chosen.label, chosen, ()
    update = _calibration_update(ctx, nominal, geometric, final)
    guards.extend(_kept_gross_errors(ctx, final))
    noisy = noise_guard(final, noise_mm)
    if noisy is not None:
        guards.append(noisy)
    extrap, unc, reg = _test_guards(ctx, robot, train, nominal, geometric, final, threads, guards)
    ctx.robust_notes = _robust_baseline(ctx, cal, nominal, t_prior, sel["gain_note"])
    tstats = scored_test_stats(nominal, geometric, final)
    untestable = tuple(e for e in final.effects if e in ctx.untestable)
    inconc = inconclusive_reasons(check, {"nominal": nominal, "geometric": geometric, "final": final}, cal, tstats,
                                  alpha=alpha, min_gain=min_gain, untestable=untestable)
    verdict = verdict_of(ctx, sel["stages"], final, fallback, sel["comparisons"], inconc, sel["messages"],
                         safe_model(nominal, geometric, final, tstats, bool(inconc)), sel["suggestions"], alpha,
                         sel["step_gain"])
    settings = {"robust_loss": loss, "cv": ctx.cv, "folds_per_scheme": len(ctx.folds),
                "selection_min_gain": sel["step_gain"],
                "target_offset_prior_mm": None if t_prior is None else {"mean": t_prior[0].tolist(),
                                                                        "sd": t_prior[1].tolist()},
                "fold_target_offset_sd_mm": ctx.fold_t_sd.tolist(),
                "register_update": ctx.register_update if ctx.registration is not None else None,
                "register_update_robust_loss": None if update is None else update.robust_loss,
                "instrument_noise_mm": noise_mm}
    clip = clip_level(geometric.selection_mm)
    step = None if fallback else step_check(ctx, final, evaluate, clip, PRACTICAL_MARGIN)
    findings = check.findings(cal.identifiability.aliases) + (() if step is None else (step.line(),))
    return Diagnosis(robot, train, test, cal, tuple(sel["stages"]), effects, nominal, geometric, final, where,
                     ctx.test_frame, tuple(guards), extrap, fallback, ctx.registration, unc, reg, subsample, check,
                     findings, verdict, _downweighted(train, nominal, geometric, final), settings, update, ctx.ref)


def _downweighted(train, nominal: Evaluation, geometric: Evaluation, final: Evaluation) -> tuple:
    """The training rows every stage's fit down-weighted or left far out (:func:`~.calibrate.outlier_rows`)."""
    stages = [("nominal", nominal), ("geometric", geometric)] + ([("final", final)] if final is not geometric else [])
    return tuple(o for name, ev in stages for o in outlier_rows(ev.fit, train.rows, stage=name))


#: Robust weighting that moves the nominal model's test RMS by more than this fraction is reported.
BASELINE_MOVE = 0.10


def _robust_baseline(ctx, cal, nominal: Evaluation, t_prior, gain_note: str) -> list:
    """A guard when robust weighting moved the nominal baseline's test RMS by more than :data:`BASELINE_MOVE`
    against plain least squares (the improvements the summary prints are measured from that baseline), and the
    notes of a small file (the robust loss that fell back, the raised minimum gain)."""
    out = [n for n in (cal.loss_note, gain_note) if n]
    if ctx.test is None or cal.nominal.loss == "none":
        return out
    plain = fit_model(cal.nominal, ctx.train.q, ctx.train.xyz_mm, robust=False, t_prior=t_prior)
    r_ls, r = rms(score_test(ctx, plain, (), np.zeros(0, int)).residual_mm), rms(nominal.test_mm)
    if abs(r - r_ls) > BASELINE_MOVE * r_ls:
        out.append(f"robust weighting moved the nominal baseline: its test RMS is {r:.4g} mm with the robust fit and "
                   f"{r_ls:.4g} mm by least squares ({100 * (r / r_ls - 1):+.0f} %, more than "
                   f"{100 * BASELINE_MOVE:g} %); the improvements over nominal are measured from the robust baseline "
                   "-- see the down-weighted rows")
    return out


def _calibration_update(ctx, nominal: Evaluation, geometric: Evaluation, final: Evaluation):
    """The record of a ``register_update="calibration"`` re-registration (None otherwise): the prior of each model
    it updated (a model with parameters beyond the frame) and its robust loss."""
    if ctx.registration is None or ctx.register_update != "calibration":
        return None
    priors = {label: ev.test_prior for label, ev in (("nominal", nominal), ("geometric", geometric), ("final", final))
              if ev.test_prior is not None}
    return CalibrationUpdate({m: pr.inflation for m, pr in priors.items()},
                             {m: pr.inflation_floor for m, pr in priors.items()},
                             {m: pr.set_aside for m, pr in priors.items()}, update_loss(ctx.loss))


def _kept_gross_errors(ctx, final: Evaluation) -> list:
    """A guard when the calibration update kept gross registration errors (too few poses to set them aside)."""
    kept = () if final.test_prior is None else final.test_prior.gross_kept
    if not kept:
        return []
    rows = file_rows(ctx.test.rows, ctx.test.n_poses)
    return [f"registration: {len(kept)} registration pose(s) with a gross error (test rows "
            f"{', '.join(str(int(rows[i])) for i in kept)}) kept in the calibration update: setting them aside would "
            f"leave fewer than {MIN_REGISTER} registration poses; measure more registration poses or check these rows"]


def _score_sealed_test(ctx, nominal: Evaluation, geometric: Evaluation, final: Evaluation, chosen: Evaluation):
    """Score the three models on the test file -- once, after the choice; refuse a test file the nominal robot,
    registered on the test file itself, misses by more than manufacturing errors can explain (another robot,
    other units: :func:`~.misfit.check_nominal_misfit`)."""
    if ctx.test is None:
        return nominal, geometric, final, chosen

    def scored(ev):
        reg = score_test(ctx, ev.fit, ev.effects, ev.keep, ev.oof_mm)
        refit = ctx.test_frame == "refit"
        return replace(ev, test_mm=reg.residual_mm, test_pred_mm=reg.pred_mm, registered=reg if refit else None)

    n2, g2 = scored(nominal), scored(geometric)
    f2 = g2 if final is geometric else scored(final)
    test = ctx.test
    if test.n_poses >= 5:  # the test file against the robot on its own (not the training fit's probe offset)
        own = fit_model(initial_fit(ctx.cal.nominal.model, test.q, test.xyz_mm), test.q, test.xyz_mm, loss=ctx.loss)
        try:
            check_nominal_misfit(ctx.cal.nominal.model.robot, test, own)
        except TolallocError as exc:
            raise TolallocError(f"test file: {exc}") from None
    c2 = {id(nominal): n2, id(geometric): g2, id(final): f2}.get(id(chosen), f2)
    return n2, g2, f2, c2


def _test_guards(ctx, robot, train, nominal: Evaluation, geometric: Evaluation, final: Evaluation, threads,
                 guards: list) -> tuple:
    """Test-file guards (appended to ``guards``): predicted uncertainty, extrapolation, a geometric or final model
    worse than nominal."""
    test = ctx.test
    if test is None:
        return None, None, None
    with threadpool_limits(threads):
        unc, reg = _uncertainty(ctx, final)
    if unc.message():
        weak_probe = any(g.startswith("weakly identified probe offset") for g in guards)
        guards.append(unc.message() + ("; or the weakly identified probe offset, whose uncertainty the predicted radius "
                                       "leaves out, used at other flange directions" if weak_probe else "")
                      + ("" if final.test_cov is None else f" ({UNCERTAINTY_SCOPE})"))
    extrap = extrapolation_flags(robot, train.q, test.q)
    if extrap.message():
        guards.append(extrap.message())
    if (train.wrench is None) != (test.wrench is None):
        has, lacks = ("training", "test") if test.wrench is None else ("test", "training")
        guards.append(f"{lacks} file: no force / torque columns while the {has} file has them; the {lacks} poses are "
                      "taken as without a process force")
    models = [("geometric", geometric), ("final", final)] if final is not geometric else [("geometric", geometric)]
    for name, ev in models:
        worse = {k: (error_stats(ev.test_mm)[k], error_stats(nominal.test_mm)[k]) for k in ("rms_mm", "max_mm")}
        for k, (f, nmn) in worse.items():
            if f > nmn:
                guards.append(f"test file: the {name} model's {k[:-3]} error is larger than the nominal model's "
                              f"({f:.4g} vs {nmn:.4g} mm); the safe model (see the verdict) does not use it")
    return extrap, unc, reg


def _all_rows(ctx, train, cal: Calibration, nominal: Evaluation, geometric: Evaluation, final: Evaluation, loss,
              t_prior):
    """The three models of a subsampled diagnosis refitted on every training row (effect bases chunk by chunk)."""
    robot, t = cal.geometric.model.robot, cal.geometric.t_mm

    def rescore(ev, fit):
        return replace(ev, fit=fit)

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
                    n_effects=len(final.keep), effect_names=final.param_names, label="final fit", loss=loss,
                    t_prior=t_prior, beta_prior_w=final.fit.beta_prior_w)
    return nominal, geometric, rescore(final, fit)


def _uncertainty(ctx, final: Evaluation) -> tuple:
    """Predicted uncertainty of ``final`` on the test poses and, with ``refit``, the re-registered final fit."""
    Btr, Bte = kept_basis(ctx.bases, final), kept_basis(ctx.bases_test, final)
    unc = prediction_uncertainty(final.fit, ctx.train.q, ctx.test.q, final.test_mm, B_train=Btr, B_test=Bte,
                                 registered=final.test_fit, split=ctx.registration, posterior_cov=final.test_cov)
    return unc, final.test_fit


