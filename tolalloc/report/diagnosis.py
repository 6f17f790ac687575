"""Markdown report of a diagnosis with CSV tables and figures."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.diagnose.diagnosis import Diagnosis
from tolalloc.diagnose.verdict import MAX_ERROR_RATIO, UNSTABLE_RATIO
from tolalloc.diagnose.scores import scheme_text
from tolalloc.report.tables import markdown_table
from tolalloc.robot.columns import joint_column_names

__all__ = ["safe_max_note", "write_report", "markdown_table", "worst_test_poses", "test_predictions", "summary_lines", "verdict_lines"]


def test_predictions(d: Diagnosis) -> pd.DataFrame:
    """Per test pose: file row, final prediction [mm] (test frame), predicted 1-sigma and 95 % radius [mm],
    whether the pose registered the frame (``refit``; then it is not scored) and whether it extrapolates."""
    t = d.test
    pred = d.final.test_pred_mm
    reg = np.zeros(t.n_poses, bool)
    if d.registration is not None:
        reg[d.registration.register_index] = True
    df = pd.DataFrame({"row": t.rows if len(t.rows) else np.arange(1, t.n_poses + 1),
                       "x_mm": pred[:, 0], "y_mm": pred[:, 1], "z_mm": pred[:, 2]})
    if d.uncertainty is not None:
        df["sigma_mm"] = d.uncertainty.sigma_mm
        df["radius95_mm"] = d.uncertainty.radius95_mm
    df["registration"] = reg.astype(int)
    if d.extrapolation is not None:
        df["extrapolation"] = d.extrapolation.flagged.astype(int)
    return df


def worst_test_poses(d: Diagnosis, n: int = 5) -> pd.DataFrame:
    """The ``n`` scored test poses with the largest final 3-D error: row, joint values, nominal / final error [mm],
    predicted 1-sigma and 95 % radius [mm], extrapolation flag."""
    idx = d.scored_index
    err_f = np.linalg.norm(d.final.test_mm, axis=1)
    err_n = np.linalg.norm(d.nominal.test_mm, axis=1)
    order = np.argsort(err_f)[::-1][:n]
    rows = test_predictions(d).iloc[idx[order]].reset_index(drop=True)
    q = pd.DataFrame(d.robot.q_to_interface(d.test.q[idx[order]]), columns=joint_column_names(d.robot))
    out = pd.concat([rows[["row"]], q], axis=1)
    out["error_nominal_mm"] = err_n[order]
    out["error_final_mm"] = err_f[order]
    for c in ("sigma_mm", "radius95_mm", "extrapolation"):
        if c in rows:
            out[c] = rows[c].to_numpy()
    return out


def safe_max_note(d: Diagnosis) -> str:
    """A note when the safe model's largest test error exceeds the nominal model's (it held: within
    :data:`~tolalloc.diagnose.verdict.MAX_ERROR_RATIO` x, and its RMS no worse); empty otherwise."""
    if d.test is None:
        return ""
    t = d.before_after("test")
    rows = t[t["label"] == d.verdict.safe_model]
    if not len(rows) or d.verdict.safe_model == "nominal":
        return ""
    m, n = float(rows["max_mm"].iloc[-1]), float(t["max_mm"].iloc[0])
    if not m > n:
        return ""
    return (f"; its largest test error, {m:.4g} mm, is above the nominal model's {n:.4g} mm (it held: at most "
            f"{MAX_ERROR_RATIO:g} x the nominal model's, with an RMS no higher) -- check the worst test poses before relying "
            "on it at single poses")


def verdict_lines(d: Diagnosis) -> list:
    """The verdict block: headline, candidates, reasons, the model safe to use, separating poses, outliers."""
    v = d.verdict
    lines = [v.headline()]
    if v.candidates:
        lines.append(f"candidates: {', '.join(v.candidates)}")
    lines.append("reasons:")
    lines += [f"  - {r}" for r in v.reasons]
    safe = {"nominal": "registration + probe offset only", "geometric": "registration, probe offset and geometry"}
    if v.safe_model == "none":
        lines.append("safe to use: none -- even the nominal model misses the test poses by more than "
                     f"{UNSTABLE_RATIO:g} x its out-of-fold error")
    else:
        lines.append(f"safe to use: the {v.safe_model} model ({safe.get(v.safe_model, 'geometry and the effects')})"
                     + safe_max_note(d))
    if v.suggestions is not None and len(v.suggestions):
        lines.append("poses that would separate the ambiguous effects (joints in deg / mm; predicted difference of "
                     "the two fitted models):")
        lines += ["  " + ln for ln in v.suggestions.to_string(index=False, float_format="%.3f").splitlines()]
    loss = d.settings['robust_loss'] if d.settings else 'robust'
    for stage in ("nominal", "geometric", "final"):
        rows = [o for o in d.outliers if o.get("stage") == stage]
        if rows:
            shown = ", ".join(f"{o['row']} ({o['error_mm']:.3g} mm, weight {o['weight']:.2f})" for o in rows[:10])
            more = f" and {len(rows) - 10} more" if len(rows) > 10 else ""
            lines.append(f"down-weighted by the {stage} fit ({loss} loss): {len(rows)} training rows: {shown}{more}")
    return lines


def _final_name(d: Diagnosis) -> str:
    """``final model``, marked as not claimed when the verdict is ``inconclusive`` (its effects do not hold)."""
    if d.verdict is not None and d.verdict.verdict == "inconclusive" and d.effects:
        return "final model, selected on the training file but not claimed"
    return "final model"


def _prob(p: float) -> str:
    """A family's posterior probability as printed (``n/a`` when the residual cannot weigh the families)."""
    return f"{p:.2f}" if np.isfinite(p) else "n/a"


def summary_lines(d: Diagnosis) -> list:
    """The whole printed summary of a diagnosis, one string per line: the verdict first (:func:`verdict_lines`),
    then test-file figures, cross-validation, the worst test poses, every guard, the ranking."""
    cols = ["model", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct"]
    lines = verdict_lines(d) if d.verdict is not None else [f"effect: {d.effect}"]
    if len(d.effects) > 1 or _final_name(d) != "final model":
        lines.append(f"{_final_name(d)}: {d.final.label}")
    if d.subsample is not None:
        s = d.subsample
        lines.append(f"subsample: cross-validation and effect selection on {s['cv_rows']:,} of {s['rows']:,} training "
                     f"rows (seed {s['seed']}), identifiability on {s['identifiability_rows']:,}; final fits on all rows")
    if d.test is not None:
        reg = d.registration
        how = (f"{len(reg.score_index)} scored poses; {len(reg.register_index)} other test poses"
               f"{' (the given registration rows)' if reg.chosen_by == 'given rows' else ''} fitted "
               f"{d.registration_fitted()} and are not scored" if reg is not None
               else f"{d.test.n_poses} poses, training tracker frame")
        lines.append(f"test file {d.test.source} ({how}; sealed: scored once, after the choice) [mm]:")
        lines += d.before_after("test")[cols].to_string(index=False, float_format="%.4f").splitlines()
    folds = len(d.nominal.oof_mm)
    lines.append(f"cross-validation on the training file ({d.train.n_poses} poses, {folds} out-of-fold "
                 f"predictions, {scheme_text(d.settings.get('cv', 'blocked') if d.settings else 'blocked', False)}) "
                 "[mm]:")
    lines += d.before_after("cv")[cols].to_string(index=False, float_format="%.4f").splitlines()
    if d.test is not None:
        lines.append(f"worst test poses ({_final_name(d)}; joints in deg / mm; extrapolation 1: outside the training "
                     "data):")
        lines += worst_test_poses(d).to_string(index=False, float_format="%.3f").splitlines()
        u = d.uncertainty
        lines.append(f"predicted uncertainty: median 1-sigma {np.median(u.sigma_mm):.4f} mm (noise {u.noise_mm:.4f} mm "
                     f"per coordinate); {100 * u.coverage:.0f} % of {len(u.inside)} scored test residuals within the "
                     "predicted 95 % radius (95 % expected when the model's uncertainty is right)"
                     + (f"; {d.uncertainty_scope()}" if d.uncertainty_scope() else ""))
    lines += [f"GUARD: {g}" for g in d.guards] or ["guards: none fired"]
    lines += [f"note: {f}" for f in d.findings]
    cv = scheme_text(d.settings.get("cv", "blocked") if d.settings else "blocked")
    lines.append(f"ranking (by the clipped out-of-fold RMS of the training file over {cv}, the selection's score; unclipped "
                 "beside it; posterior probability from the marginal likelihood; the test file is sealed):")
    for c in d.ranking:
        if c.applicable:
            flag = "" if c.significant else "  not significant" + (f": {c.reason}" if c.reason else "")
            lines.append(f"  {c.effect:17s} clipped RMS {c.robust_rms_mm:.4f} mm (unclipped {c.heldout_rms_mm:.4f})  "
                         f"P={_prob(c.probability)}  p={c.p_value:.2e}  gain {c.gain_pct:+.1f} %  ({c.variant}){flag}")
        else:
            lines.append(f"  {c.effect:17s} not testable: {c.reason}")
    p_none = d.family_probability_none
    if p_none is not None:
        lines.append(f"  {'(no effect)':17s} P={p_none:.2f}")
    return lines


def write_report(d: Diagnosis, out: Path, title: str = "Sim-to-real diagnosis", prefix: str = "") -> Path:
    """Write ``{prefix}report.md``, CSV tables and PNG figures of ``d`` into directory ``out``; returns the report path."""
    from tolalloc.report.plots.diagnose import plot_before_after, plot_ranking, plot_where

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ba = d.before_after("test" if d.test is not None else "cv")
    ba.to_csv(out / f"{prefix}before_after.csv", index=False)
    d.sequence_frame().to_csv(out / f"{prefix}ranking.csv", index=False)
    d.where.trends.to_csv(out / f"{prefix}where_trends.csv", index=False)
    d.where.worst.to_csv(out / f"{prefix}worst_poses.csv", index=False)
    d.calibration.identifiability.to_frame().to_csv(out / f"{prefix}identifiability.csv", index=False)
    d.final.fit.parameters_frame().to_csv(out / f"{prefix}parameters.csv", index=False)
    plot_where(d.where, out / f"{prefix}where.png")
    plot_ranking(d, out / f"{prefix}ranking.png")
    plot_before_after(ba, out / f"{prefix}before_after.png")
    ident = d.calibration.identifiability
    lines = [f"# {title}", "",
             f"Robot `{d.robot.name}`; training file `{d.train.source}` ({d.train.n_poses} poses, "
             f"{d.train.n_skipped} rows with empty cells skipped)"
             + (f"; test file `{d.test.source}` ({d.test.n_poses} poses, frame: {d.test_frame})" if d.test is not None else "")
             + ".", "",
             *_verdict_section(d, out, prefix),
             "", "Calibration model: the complete, minimal geometric model (4 line errors per revolute joint, 2 per "
             "prismatic joint, joint offsets, tracker registration, probe offset; `tolalloc.diagnose.geometry`), MAP "
             "with priors 10x the robot's sigma set. The paper's error-screw model is the tolerance model "
             "(allocation, Monte Carlo), not used here.", ""]
    lines += _figures_section(d, prefix, out)
    lines += ["## Which: candidate effects", "",
              "Each candidate is fitted on training poses only and scored on the training file's out-of-fold poses (the "
              "test file is sealed until the model is chosen); p: one-sided Wilcoxon signed-rank test of the per-pose "
              "squared-error reduction (Bonferroni over the candidates of a step).", ""]
    seq = d.sequence_frame()
    cols = ["step", "base", "effect", "variant", "heldout_rms_mm", "gain_pct", "p_value", "n_params", "significant",
            "selected", "reason"]
    lines += [markdown_table(seq[cols]), "", f"![ranking]({prefix}ranking.png)", ""]
    lines += ["## Where: residual after geometric calibration (training poses, robot base frame)", "",
              markdown_table(d.where.per_axis), "", "Strongest trends (Spearman of |e|, largest |Pearson| of a component, "
              "RMS per quartile bin of the feature):", "",
              markdown_table(d.where.trends.head(10)[["feature", "spearman_norm", "max_abs_corr_component",
                                                     "axis_of_max_corr", "bin_rms_mm", "bin_ratio"]]), "",
              "Worst regions:", "", markdown_table(d.where.regions.head(4)), "",
              "Worst poses:", "", markdown_table(d.where.worst.head(5)), "", f"![where]({prefix}where.png)", ""]
    lines += ["## Identifiability of the geometric parameters", "",
              f"rank {ident.rank} (9 registration/offset + {len(ident.identifiable)} geometric), condition number "
              f"{ident.condition_number:.3g}, observability index O1 {ident.observability_index:.3g}; minimum poses "
              f"{ident.min_poses}.", "",
              f"Not identifiable (not fitted): {', '.join(ident.unidentifiable) or 'none'}.", "",
              *[f"- `{k}`: {v}" for k, v in ident.reasons.items()], "",
              "Combinations the data cannot separate (normalised columns): "
              + ("; ".join(f"`{c}`" for c in ident.null_combinations) or "none") + ".", ""]
    path = out / f"{prefix}report.md"
    path.write_text("\n".join(lines) + "\n")
    (out / f"{prefix}diagnosis.json").write_text(json.dumps(d.to_dict(), indent=2, default=_default) + "\n")
    return path


def _verdict_section(d: Diagnosis, out: Path, prefix: str) -> list:
    """Verdict, candidates, reasons, the safe model, separating poses and outliers (CSV beside the report)."""
    if d.verdict is None:
        return [f"**Diagnosed effect: `{d.effect}`**"]
    v = d.verdict
    lines = [f"**{v.headline()}**", ""]
    if v.candidates:
        lines += [f"Candidates: {', '.join(f'`{c}`' for c in v.candidates)}.", ""]
    lines += ["Reasons:", "", *[f"- {r}" for r in v.reasons], "",
              f"Safe to use: the `{v.safe_model}` model (the last of nominal -> geometric -> final that held on "
              f"cross-validation and, with a test file, on the test file){safe_max_note(d)}.", ""]
    if v.suggestions is not None and len(v.suggestions):
        v.suggestions.to_csv(out / f"{prefix}separating_poses.csv", index=False)
        lines += ["Poses that would separate the ambiguous effects (where the two fitted models' predictions differ "
                  "most, within the joint limits; joints in deg / mm):", "", markdown_table(v.suggestions), ""]
    if d.outliers:
        d.outliers_frame().to_csv(out / f"{prefix}outliers.csv", index=False)
        lines += [f"Down-weighted training rows ({len(d.outliers)} rows over the nominal, geometric and final fits, "
                  "each with its error and robust weight; `outliers.csv`):",
                  "", markdown_table(d.outliers_frame().head(20)), ""]
    if len(d.effects) > 1:
        lines += [f"Final model: `{d.final.label}`.", ""]
    return lines


def _figures_section(d: Diagnosis, prefix: str, out: Path) -> list:
    """Test-file figures first, cross-validation separately, worst test poses, uncertainty check, guards."""
    cols = ["model", "label", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct", "rms_shrink_vs_geometric_pct"]
    lines = []
    if d.test is not None:
        reg = d.registration
        how = (f"{len(reg.score_index)} scored poses; {len(reg.register_index)} test poses {reg.chosen_text()} "
               f"fitted {d.registration_fitted()} and are **not** scored (rows in the JSON, "
               "`registration` column of the predictions)" if reg is not None else
               f"{d.test.n_poses} poses in the training tracker frame")
        worst = worst_test_poses(d)
        test_predictions(d).to_csv(out / f"{prefix}test_predictions.csv", index=False)
        worst.to_csv(out / f"{prefix}worst_test_poses.csv", index=False)
        u = d.uncertainty
        lines += ["## Test file", "", f"{how}. Error [mm] of the 3-D position:", "",
                  markdown_table(d.before_after("test")[cols]), "", f"![before/after]({prefix}before_after.png)", "",
                  f"Worst test poses ({_final_name(d)}; joints in deg / mm; extrapolation 1: outside the training "
                  "data):", "",
                  markdown_table(worst, ".4g"), "",
                  f"Predicted uncertainty (parameter covariance of the final fit): median 1-sigma "
                  f"{np.median(u.sigma_mm):.4f} mm, noise {u.noise_mm:.4f} mm per coordinate; "
                  f"{100 * u.coverage:.1f} % of the {len(u.inside)} scored test residuals lie within the predicted "
                  "95 % radius (95 % when the model's uncertainty is right)"
                  + (f"; {d.uncertainty_scope()}." if d.uncertainty_scope() else "."), ""]
    lines += ["## Cross-validation on the training file (out-of-fold)", "",
              markdown_table(d.before_after("cv")[cols]), "",
              *([f"![before/after]({prefix}before_after.png)", ""] if d.test is None else [])]
    lines += (["## Guards", "", *[f"- {g}" for g in d.guards], ""] if d.guards else ["Guards: none fired.", ""])
    if d.findings:  # well-identified deviations from nominal: results, not warnings
        lines += ["## Findings", "", *[f"- {f}" for f in d.findings], ""]
    return lines


def _default(o):
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer, np.bool_)):
        return o.item()
    raise TypeError(type(o))
