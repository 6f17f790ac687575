"""The report of a calibration-aware allocation: the template context of ``calibrated.html.j2`` (the table, cards,
plan, end-to-end check and figures of a :class:`~tolalloc.workflows.CalibratedToleranceAllocation`)."""

from __future__ import annotations

from pathlib import Path

from tolalloc.report.html import Column, figure_item, html_table, pretty, render_report, write_html
from tolalloc.report.html_allocation import SECTIONS, _f4, _inputs_pairs, joint_columns, with_joints

__all__ = ["write_calibrated_report", "calibrated_context", "CALIBRATED_COLUMNS"]


def write_calibrated_report(job, folder) -> Path:
    """Write ``report.html`` of a :class:`~tolalloc.workflows.calibrated.CalibratedToleranceAllocation` into the
    existing directory ``folder``."""
    return write_html(render_report("calibrated.html.j2", calibrated_context(job)), folder)


CALIBRATED_COLUMNS = [Column("parameter", "parameter", "text"), Column("unit", "unit", "text"),
                      Column("tol_mm", "tolerance ± [mm]", "pm"), Column("tol_deg", "tolerance ± [deg]", "pm"),
                      Column("grade", "grade", "text"), Column("process", "process", "text", optional=True),
                      Column("tol_no_calibration_mm", "without calibration ± [mm]", "pm"),
                      Column("tol_no_calibration_deg", "without calibration ± [deg]", "pm"),
                      Column("sigma_mm", "σ manufactured [mm]", "g4"), Column("sigma_deg", "σ manufactured [deg]", "g4"),
                      Column("sigma_post_calibration_mm", "σ after calibration [mm]", "g4"),
                      Column("sigma_post_calibration_deg", "σ after calibration [deg]", "g4"),
                      Column("sigma_random_mm", "σ random [mm]", "g4"), Column("sigma_random_deg", "σ random [deg]", "g4"),
                      Column("status", "status", "text", badge=True), Column("cost", "cost", "f3"),
                      Column("tol_continuous_mm", "continuous optimum ± [mm]", "pm", optional=True),
                      Column("tol_continuous_deg", "continuous optimum ± [deg]", "pm", optional=True),
                      Column("repeatability_grade_mm", "repeatability grade ± [mm]", "pm", optional=True),
                      Column("repeatability_grade_deg", "repeatability grade ± [deg]", "pm", optional=True),
                      Column("repeatability_grade_cost", "grade cost", "f3", optional=True)]


def calibrated_context(job) -> dict:
    """The template context of a :class:`~tolalloc.workflows.calibrated.CalibratedToleranceAllocation`'s report."""
    res, pr, plan, chk = job.result, job.problem, job.plan, job.end_to_end
    s = job.summary()
    requirement = pretty(f"P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after calibration")
    cert, std, built = res.certified, job.standard, job.built
    word = (chk.verdict.upper() if chk is not None else "NOT VERIFIED" if built is not None else
            ("CERTIFIED" if cert.certified else "NOT CERTIFIED") if res.design.ok else "INFEASIBLE")
    verdict = {"cls": "ok" if job.ok else ("warn" if res.design.ok else "fail"), "word": word,
               "lead": pretty(res.message()).replace("\n", "; "),
               "lines": ([] if std is None else ["Standard grades: " + pretty(std.message_line())])
               + ([] if chk is None else ["End-to-end Monte Carlo: " + pretty(chk.message())])}
    cards = [] if built is None else [  # the design to build, and the rounding it replaces
        {"label": "cost (to build)", "value": _f4(built.cost), "note": f"standard grades, {built.premium_pct:+.2f} %"},
        {"label": "rounding down", "value": _f4(built.rounded_cost), "note": f"{built.rounded_premium_pct:+.2f} %"}]
    cont = res.summary()  # the continuous calibration-aware design's own numbers, whatever the job's summary leads with
    cards += [{"label": "cost" if built is None else "continuous design", "value": _f4(cont["cost"]),
               "note": f"{cont['design']} design"},
             {"label": "certified design", "value": _f4(s["cost_certified"]),
              "note": "certified" if cert.certified else "NOT certified"},
             {"label": "exact design", "value": _f4(s["cost_exact"]), "note": "post-calibration probability"},
             {"label": "without calibration", "value": _f4(s["cost_no_calibration"]), "note": "same requirement"},
             {"label": "saving", "value": "n/a" if s["saving_pct"] is None else f"{s['saving_pct']:.2f} %",
              "note": "" if s["saving"] is None else f"{s['saving']:.4f} cost units"}]
    if cert.grade_t is not None:
        cards.append({"label": "repeatability grades", "value": _f4(cert.grade_cost),
                      "note": f"of the certified design's {s['cost_certified']:.4f}"})
    if chk is not None:
        cards.append({"label": "lowest P̂ (end to end)", "value": f"{chk.check.p_mc.min():.4f}",
                      "note": f"{job.n_robots} simulated calibrations"})
    table = job.to_frame()
    classes = ["hl" if st.startswith("must be held") else "" for st in table["status"]]
    columns = [c for c in CALIBRATED_COLUMNS if built is not None or not c.key.startswith("tol_continuous")]
    tol = html_table(table, columns, table_id="tolerance-table", row_classes=classes,
                     caption=f"Tolerances of {job.robot.name} after the calibration plan: the design to build",
                     note="Tolerances, σ and status are those of the design to build"
                          + (" (standard grades); the continuous optimum for comparison." if built is not None else ".")
                          + " Highlighted: must be held in manufacturing.")
    cli, python, rnotes = job.reproduce_command()
    return {"kicker": "calibration-aware tolerance allocation", "title": "Tolerance allocation report",
            "subtitle": f"{job.robot.name}: {requirement}",
            "meta": [("robot", job.robot.name), ("poses", job.label), ("verdict", verdict["word"].lower()),
                     ("plan", job.plan_source)],
            "sections": SECTIONS, "requirement": requirement, "verdict": verdict, "cards": cards,
            "where": (f"Over the region {job.label!r} (cutting planes and a coverage sample), after the calibration plan "
                      "below." if res.region is not None else
                      f"At the {pr.n_poses} pose(s) of {job.label!r}, after the calibration plan below."),
            "plan": [("file", job.plan_source), ("measurement poses", plan.n_poses), ("measurement", plan.measurement),
                     ("tracker noise", f"{plan.noise_mm:g} mm per coordinate")],
            "tolerance_table": tol, "unidentifiable": ", ".join(s["unidentifiable"]),
            "grade_note": pretty(job.grade_note()),
            "end_to_end": None if chk is None else {"text": pretty(chk.message()), "table": _end_to_end_table(job)},
            "no_end_to_end": "The end-to-end Monte Carlo did not run (verification=False, or a pose-measurement plan): "
                             + ("the standard design rests on the linear post-calibration probability alone."
                                if built is not None else "the design rests on its certificate alone."),
            "figures": _calibrated_figures(job), "inputs": _inputs_pairs(job.inputs, []),
            "reproduce": {"cli": cli, "python": python, "notes": rnotes}}


def _end_to_end_table(job) -> dict:
    chk = job.end_to_end.check
    frame = with_joints(job.end_to_end.to_frame(), job.robot, chk.q)
    frame["ci"] = list(zip(frame["ci_low"], frame["ci_high"]))
    cols = [Column("pose", "pose", "int"), *joint_columns(job.robot), Column("p_linear", "P linear", "f4"),
            Column("p_mc", "P̂ Monte Carlo", "f4"), Column("ci", job.end_to_end.interval_label(), "ci", numeric=True),
            Column("agree", "linear inside the interval", "bool", badge=True)]
    return html_table(frame, cols, table_id="pose-table", row_classes=["" if a else "bad" for a in frame["agree"]],
                      caption=f"End-to-end check per pose: P(|dP| < {chk.radius_mm:g} mm) after calibration",
                      note=f"{job.n_robots} simulated robots, each calibrated nonlinearly at the plan's poses and "
                           "then checked at the working poses; P linear: the post-calibration Gaussian prediction.")


def _calibrated_figures(job) -> list:
    from tolalloc.report.html import plot_calibrated_tolerances

    figs = [figure_item(plot_calibrated_tolerances(job.to_frame()), figure_id="fig-calibrated",
                        caption="Tolerance per parameter with and without the calibration plan (log scale).")]
    chk = None if job.end_to_end is None else job.end_to_end.check
    if chk is not None:
        from types import SimpleNamespace

        from tolalloc.report.plots.allocate import plot_pose_probabilities

        view = SimpleNamespace(p_linear=chk.p_linear, p_mc=chk.p_mc, ci_low=chk.ci_low, ci_high=chk.ci_high,
                               prob=job.problem.prob, radius_mm=chk.radius_mm)
        label = job.end_to_end.interval_label()
        figs.append(figure_item(plot_pose_probabilities(view, interval=label), figure_id="fig-poses",
                                caption="Post-calibration linear prediction and end-to-end Monte Carlo estimate with "
                                        f"its {label} per pose, against the required p = {job.problem.prob:g}."))
    return figs
