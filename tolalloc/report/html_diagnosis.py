"""``report.html`` of a :class:`~tolalloc.workflows.diagnosis.MeasurementDiagnosis`: the template context."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tolalloc.report.html import (Column, file_figure_item, html_table, pretty, render_report, write_html,
                                  writer_figure_item)
from tolalloc.report.diagnosis import safe_max_note

__all__ = ["diagnosis_context", "write_diagnosis_report"]

SECTIONS = [{"id": "summary", "title": "Diagnosis and verdict"}, {"id": "before-after", "title": "Before and after"},
            {"id": "guards", "title": "Guards and findings"}, {"id": "ranking", "title": "Candidate effects"},
            {"id": "figures", "title": "Figures"}, {"id": "reproduce", "title": "Inputs, versions, reproduce"}]

BEFORE_AFTER_COLUMNS = [Column("model", "model", "text"), Column("label", "what it fits", "text"),
                        Column("rms_mm", "RMS [mm]", "f4"), Column("p95_mm", "p95 [mm]", "f4"),
                        Column("max_mm", "max [mm]", "f4"), Column("rms_shrink_pct", "RMS shrink vs nominal [%]", "f1")]

RANKING_COLUMNS = [Column("step", "step", "int"), Column("base", "on top of", "text"),
                   Column("effect", "candidate effect", "text"),
                   Column("robust_rms_mm", "clipped held-out RMS [mm] (ranked by)", "f4"),
                   Column("heldout_rms_mm", "unclipped held-out RMS [mm]", "f4"),
                   Column("gain_pct", "gain [%]", "f1"), Column("p_value", "p-value", "sci"),
                   Column("n_params", "parameters", "int"), Column("significant", "significant", "bool"),
                   Column("selected", "selected", "bool"), Column("reason", "reason", "text", optional=True)]

GAP_COLUMNS = [Column("part", "part", "text"), Column("ms_mm2", "mean square [mm²]", "f4"),
               Column("rms_equiv_mm", "RMS equivalent [mm]", "f4"),
               Column("share_of_nominal_pct", "share of the nominal error [%]", "f2")]


def write_diagnosis_report(job, folder) -> Path:
    """Write ``report.html`` of a :class:`~tolalloc.workflows.diagnosis.MeasurementDiagnosis` into the existing
    directory ``folder``."""
    return write_html(render_report("diagnosis.html.j2", diagnosis_context(job, folder)), folder)


def _verdict(d, block, which: str) -> dict:
    """The banner: the verdict word (``effect``, ``none``, ``ambiguous``, ``inconclusive``) with the effects it names,
    the held-out figures, the reasons and the model that is safe to use -- as the verdict states them."""
    v = d.verdict
    rms = dict(zip(block["model"], block["rms_mm"]))
    shrink = float(block["rms_shrink_pct"].iloc[2])
    where = "on the held-out test file" if which == "test" else "out-of-fold on the training file (cross-validation)"
    lead = (f"Held-out RMS error {where}: nominal {rms['nominal']:.4f} mm → geometric calibration "
            f"{rms['geometric']:.4f} mm → final model {rms['final']:.4f} mm ({shrink:.1f} % below nominal).")
    head = v.headline().split(" -- ", 1)
    lines = [f"Verdict: {head[-1]}."] + [f"{r[0].upper()}{r[1:]}." for r in v.reasons]
    lines.append(f"Safe to use: the {v.safe_model} model{safe_max_note(d)}." if v.safe_model != "none"
                 else "Safe to use: no fitted model transfers to the test poses.")
    if d.fallback is not None:
        lines.append(f"The fitted model lost on cross-validation; the final model falls back to {d.fallback}.")
    lines.append(f"{len(d.guards)} guard(s) fired: see 'Guards and findings'." if d.guards else "No guard fired.")
    further = f" + ({v.further_terms()})" if v.verdict == "effect" and v.further else ""
    word = {"effect": f"EFFECT: {' + '.join(v.candidates)}{further}", "none": "NO EFFECT FOUND",
            "ambiguous": "AMBIGUOUS: " + head[-1].split(";")[0], "inconclusive": "INCONCLUSIVE"}[v.verdict]
    cls = "ok" if v.verdict in ("effect", "none") and not d.guards and d.fallback is None else "warn"
    return {"cls": cls, "word": word, "lead": lead, "lines": lines}


def _cards(d, block, which: str) -> list:
    final = block.iloc[2]
    cards = [{"label": f"final RMS ({which})", "value": f"{final['rms_mm']:.4f} mm",
              "note": f"p95 {final['p95_mm']:.4f} mm, max {final['max_mm']:.4f} mm"},
             {"label": "shrink vs nominal", "value": f"{final['rms_shrink_pct']:.1f} %",
              "note": f"{final['rms_shrink_vs_geometric_pct']:.1f} % vs geometric"},
             {"label": "training poses", "value": str(d.train.n_poses), "note": f"{d.train.n_skipped} rows skipped"}]
    if d.test is not None:
        cards.append({"label": "scored test poses", "value": str(len(d.scored_index)),
                      "note": f"of {d.test.n_poses}; frame: {d.test_frame}"})
    if d.uncertainty is not None:
        u = d.uncertainty
        cards.append({"label": "inside predicted 95 % radius", "value": f"{100 * u.coverage:.0f} %",
                      "note": f"of {len(u.inside)} scored test residuals"
                              + (f"; {d.uncertainty_scope()}" if d.uncertainty_scope() else "")})
    cards.append({"label": "guards fired", "value": str(len(d.guards)), "note": "see below" if d.guards else "none"})
    return cards


def _test_part(d) -> dict:
    """Test-file table, how it was scored, worst poses and the uncertainty check (empty without a test file)."""
    from tolalloc.report.diagnosis import worst_test_poses

    if d.test is None:
        return {"test_table": None, "test_how": "", "worst_table": None, "uncertainty": None}
    reg = d.registration
    given = "(the given registration rows) " if reg is not None and reg.chosen_by == "given rows" else ""
    how = (f"Test file {d.test.source}: {len(reg.score_index)} scored poses; {len(reg.register_index)} other test poses "
           f"{given}fitted {d.registration_fitted()} and are not scored." if reg is not None else
           f"Test file {d.test.source}: {d.test.n_poses} poses in the training tracker frame, all scored.")
    test = html_table(d.before_after("test"), BEFORE_AFTER_COLUMNS, table_id="test-table",
                      caption="Test file (held out, never fitted): error of the 3-D position")
    worst = worst_test_poses(d)
    joints = [Column(f"q{k + 1}_{j.unit}", f"{j.name} [{j.unit}]", "f2") for k, j in enumerate(d.robot.joints)]
    cols = [Column("row", "file row", "int"), *joints,
            Column("error_nominal_mm", "error nominal [mm]", "f3"), Column("error_final_mm", "error final [mm]", "f3"),
            Column("sigma_mm", "predicted 1σ [mm]", "f3"), Column("radius95_mm", "predicted 95 % radius [mm]", "f3"),
            Column("extrapolation", "extrapolation", "int")]
    worst_t = html_table(worst, cols, table_id="worst-table",
                         caption=f"The {len(worst)} scored test poses with the largest final error",
                         note="Joint values in deg / mm; extrapolation 1: the pose lies outside the training data.")
    u = d.uncertainty
    unc = None if u is None else (
        f"median predicted 1σ {np.median(u.sigma_mm):.4f} mm (measurement noise {u.noise_mm:.4f} mm per coordinate); "
        f"{100 * u.coverage:.0f} % of the {len(u.inside)} scored test residuals lie within the predicted 95 % radius "
        "(95 % expected when the model's uncertainty is right)"
        + (f"; {d.uncertainty_scope()}." if d.uncertainty_scope() else "."))
    return {"test_table": test, "test_how": how, "worst_table": worst_t, "uncertainty": unc}


def _gap(gap):
    if gap is None:
        return None
    note = (f"Mean squares of the 3-D test error, adding up to the nominal model's. systematic_unnamed: what a Gaussian "
            f"process on the joint values, trained on the training residual, predicts on the test poses "
            f"({100 * gap.gp_test_explained:.0f} % of the final model's test error); noise floor from the "
            f"{gap.noise_source}.")
    return {"table": html_table(gap.to_frame(), GAP_COLUMNS, table_id="gap-table",
                                caption="Where the test error lies", note=note)}


def _figures(d, folder=None) -> list:
    """Before / after and ranking as SVG; the residual breakdown as PNG (``where.png`` in ``folder`` when there)."""
    from tolalloc.report.plots.diagnose import plot_before_after, plot_ranking, plot_where

    which = "test" if d.test is not None else "cv"
    block = d.before_after(which)
    where_caption = ("Residual after geometric calibration on the training poses: against the strongest features, per "
                     "axis (robot base frame) and per region.")
    saved = None if folder is None else Path(folder) / "where.png"
    held_out = "test file" if which == "test" else "cross-validation"
    return [writer_figure_item(lambda f: plot_before_after(block, f), figure_id="fig-before-after",
                               caption=f"RMS, p95 and max held-out error ({held_out}) of the nominal, geometric "
                                       "and final models (log scale)."),
            writer_figure_item(lambda f: plot_ranking(d, f), figure_id="fig-ranking",
                               caption="Held-out RMS of every candidate effect on top of the geometric calibration "
                                       "(green: significant)."),
            file_figure_item(saved, figure_id="fig-where", caption=where_caption) if saved and saved.is_file() else
            writer_figure_item(lambda f: plot_where(d.where, f, dpi=100), figure_id="fig-where", fmt="png",
                               caption=where_caption)]


def diagnosis_context(job, folder=None) -> dict:
    """The template context of a :class:`MeasurementDiagnosis`'s report (``folder``: where its figures were saved)."""
    d = job.diagnosis
    which = "test" if d.test is not None else "cv"
    block = d.before_after(which)
    ident = d.calibration.identifiability
    data = (f"Training file {d.train.source} ({d.train.n_poses} poses, {d.train.n_skipped} rows with empty cells "
            "skipped)" + ("" if d.test is None else f"; test file {d.test.source} ({d.test.n_poses} poses, "
                                                     f"tracker frame: {d.test_frame})") + ".")
    subsample = None
    if d.subsample is not None:
        s = d.subsample
        subsample = (f"Cross-validation and effect selection ran on {s['cv_rows']:,} of {s['rows']:,} training rows "
                     f"(seed {s['seed']}), identifiability on {s['identifiability_rows']:,}; the final fits use all rows.")
    seq = d.sequence_frame()
    cli, python, notes = job.reproduce_command()
    verdict = _verdict(d, block, which)
    return {"kicker": "sim-to-real diagnosis", "title": "Sim-to-real diagnosis report",
            "subtitle": f"{d.robot.name}: {verdict['word'].lower()}",
            "meta": [("robot", d.robot.name), ("training file", d.train.source),
                     ("test file", "none" if d.test is None else d.test.source), ("guards fired", len(d.guards))],
            "sections": SECTIONS, "requirement": data, "verdict": verdict, "cards": _cards(d, block, which),
            "subsample": subsample, **_test_part(d),
            "cv_table": html_table(d.before_after("cv"), BEFORE_AFTER_COLUMNS, table_id="cv-table",
                                   caption=f"Cross-validation on the training file ({d.train.n_poses} poses, "
                                           f"{d.settings.get('folds_per_scheme', job.folds)} folds per scheme, "
                                           "out-of-fold): error of the 3-D position"),
            "gap": _gap(job.gap), "guards": [pretty(g) for g in d.guards], "findings": [pretty(f) for f in d.findings],
            "identifiability": [("rank", f"{ident.rank} (9 registration / offset + {len(ident.identifiable)} geometric)"),
                                ("condition number", f"{ident.condition_number:.3g}"),
                                ("observability index O1", f"{ident.observability_index:.3g}"),
                                ("minimum poses", ident.min_poses),
                                ("not identifiable (not fitted)", ", ".join(ident.unidentifiable) or "none")],
            "ranking_how": "Each candidate is fitted on training poses only and scored on held-out poses; p: one-sided "
                           "Wilcoxon signed-rank test of the per-pose squared-error reduction (Bonferroni over the "
                           "candidates of a step).",
            "ranking_table": html_table(seq, RANKING_COLUMNS, table_id="ranking-table",
                                        caption="Candidate effects per selection step",
                                        row_classes=["chosen" if s else "" for s in seq["selected"]]),
            "figures": _figures(d, folder), "inputs": _inputs(job),
            "reproduce": {"cli": cli, "python": python, "notes": notes}}


def _inputs(job) -> list:
    d, inp = job.diagnosis, job.inputs
    pairs = [("robot", d.robot.name), ("train", d.train.source), ("test", None if d.test is None else d.test.source),
             ("test_frame", d.test_frame), ("folds", job.folds)]
    pairs += [(k, v) for k, v in inp.items() if k not in {"robot", "train", "test", "test_frame", "folds"}]
    return [(k, "—" if v is None else row_ranges_text(v) if k == "register_rows" else str(v)) for k, v in pairs]


def row_ranges_text(rows) -> str:
    """Row numbers as ``--register-rows`` reads them: sorted, runs of consecutive rows as inclusive ranges
    (``[1, 2, 3, 7, 9, 10]`` -> ``"1-3,7,9-10"``)."""
    rows = sorted({int(r) for r in rows})
    runs, start = [], None
    for i, r in enumerate(rows):
        start = r if start is None else start
        if i + 1 == len(rows) or rows[i + 1] != r + 1:
            runs.append(str(r) if r == start else f"{start}-{r}")
            start = None
    return ",".join(runs)
