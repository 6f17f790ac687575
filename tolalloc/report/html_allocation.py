"""``report.html`` of the workflow results: the context of each template, taken from the result objects.

Every number comes from the result (its tables, ``summary()`` and messages); the figures are the result's own plots.
The templates and the rendering live in :mod:`tolalloc.report.html`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.report.handover import handover_html
from tolalloc.report.html import Column, figure_item, file_figure_item, html_table, pretty, render_report, write_html

__all__ = ["write_allocation_report", "allocation_context", "verdict_legend", "worst_p_text"]


def worst_p_text(worst_p: float | None) -> str:
    """The region search's worst linear P as printed (None: the search had no design to search with)."""
    return "none (no design to search with)" if worst_p is None else f"{worst_p:.5f}"



def _label(ver) -> str:
    """The verification's intervals named for the report (``simultaneous 95 % interval``)."""
    return "95 % interval" if ver is None else ver.interval_label().replace("%", " %")


def verdict_legend(ver) -> str:
    """The words of the per-pose verdicts, as the verification defines them, on its intervals (``ver`` None: none)."""
    label = _label(ver)
    family = "" if ver is None or ver.n_intervals <= 1 else f" Intervals: {ver.interval_text()}."
    return (f"demonstrated: the whole {label} of P̂ is at or above p; consistent: the interval reaches p but its "
            f"lower bound is below; failed: the whole interval lies below p.{family}")


def write_allocation_report(job, folder) -> Path:
    """Write ``report.html`` of a :class:`~tolalloc.workflows.allocation_result.ToleranceAllocation` into the
    existing directory ``folder``."""
    return write_html(render_report("allocation.html.j2", allocation_context(job, folder)), folder)


# ---------------------------------------------------------------------------------------------- shared pieces
SECTIONS = [{"id": "summary", "title": "Requirement and verdict"}, {"id": "tolerances", "title": "Tolerance table"},
            {"id": "poses", "title": "Verification per pose"}, {"id": "figures", "title": "Figures"},
            {"id": "reproduce", "title": "Inputs, versions, reproduce"}]


def _f4(x) -> str:
    return "n/a" if x is None or not np.isfinite(x) else f"{x:.4f}"


def joint_columns(robot) -> list[Column]:
    """``q1..qN`` columns with the joint names and units (deg / mm)."""
    return [Column(f"q{k + 1}", f"{j.name} [{j.unit}]", "f2") for k, j in enumerate(robot.joints)]


def with_joints(frame: pd.DataFrame, robot, q) -> pd.DataFrame:
    """``frame`` with columns ``q1..qN`` (interface units) from ``q`` (P, n) [rad, mm] inserted after ``pose``."""
    qi = np.atleast_2d(robot.q_to_interface(q))
    at = list(frame.columns).index("pose") + 1 if "pose" in frame.columns else 0
    out = frame.copy()
    for k in range(qi.shape[1]):
        out.insert(at + k, f"q{k + 1}", qi[:, k])
    return out


def _inputs_pairs(record: dict, extra: list) -> list:
    """The inputs as (name, text) pairs: the call's record, then ``extra`` (what the run used); a name in both is
    shown once, in the record's place, with the value the run used."""
    merged = dict(record)
    merged.update(extra)
    return [(k, "—" if v is None else (", ".join(map(str, v)) if isinstance(v, (list, tuple)) else str(v)))
            for k, v in merged.items()]


# ---------------------------------------------------------------------------------------------- allocation
TOLERANCE_COLUMNS = [Column("parameter", "parameter", "text"), Column("kind", "kind", "text"),
                     Column("role", "role", "text"), Column("nominal_mm", "nominal [mm]", "g4", optional=True),
                     Column("tol_mm", "tolerance ± [mm]", "pm"), Column("tol_deg", "tolerance ± [deg]", "pm"),
                     Column("grade", "grade", "text", optional=True),
                     Column("process", "process", "text", optional=True),
                     Column("sigma_mm", "σ [mm]", "g4"), Column("sigma_deg", "σ [deg]", "g4"),
                     Column("cost", "cost", "f3"), Column("variance_share_pct", "variance share [%]", "pct1"),
                     Column("at_limit", "at limit", "text")]

#: the continuous optimum beside the standard design to build (only when they differ)
CONTINUOUS_COLUMNS = [Column("tol_continuous_mm", "continuous optimum ± [mm]", "pm"),
                      Column("tol_continuous_deg", "continuous optimum ± [deg]", "pm")]

#: the interval of each estimator of the verification (:mod:`tolalloc.montecarlo`)
INTERVALS = {"plain": "plain Monte Carlo: Wilson score interval",
             "paired": "paired: Tango's score interval of the paired difference",
             "importance": "importance sampling: Tango's score interval of the weighted discordant counts"}


def _verdict(job) -> dict:
    res, ver = job.result, job.verification
    lines = []
    if res.status != "optimal":
        word = "NOT CONVERGED" if res.status == "not_converged" else "INFEASIBLE"
        return {"cls": "fail", "word": word, "lead": pretty(res.message),
                "lines": ["The tolerance table holds the design for reference only; it does not meet the requirement."]}
    if job.coverage is not None:
        lines.append(pretty(job.coverage.message(job.problem.prob)))
    if job.correction is not None:
        lines.append("Correction: " + pretty(job.correction.message()))
    if ver is None:
        return {"cls": "warn" if job.ok else "fail", "word": "NOT VERIFIED",
                "lead": "No nonlinear Monte Carlo verification was run; the linear prediction meets the requirement "
                        "at every pose of the allocation.", "lines": lines}
    cls = "ok" if job.ok and ver.verdict == "demonstrated" else ("warn" if job.ok else "fail")
    return {"cls": cls, "word": ver.verdict.upper(), "lead": pretty(ver.message()), "lines": lines}


def _cards(job, s: dict) -> list:
    ver, cov, corr = job.verification, job.coverage, job.correction
    c = s["costs"]
    cards = [{"label": "cost of the design to build", "value": _f4(job.cost),
              "note": f"{job.design.label} design" + (" (standard grades)" if job.standard else "")},
             {"label": "certified cost (continuous)", "value": _f4(c["certified"]), "note": c["certified_rule"]},
             {"label": "exact cost (continuous)", "value": _f4(c["exact"]),
              "note": f"{c['saving_pct']:.2f} % below certified" if c["saving_pct"] is not None else
              ("not computed" if c["exact_status"] is None else f"none: {c['exact_status']}")}]
    if c["standard"] is not None and not job.standard:
        cards.append({"label": "standard-grade cost", "value": _f4(c["standard"]),
                      "note": "meets the requirement" if s["standard"]["meets"] else "requirement NOT met"})
    if c.get("rounded") is not None:
        cards.append({"label": "cost if rounded down", "value": _f4(c["rounded"]),
                      "note": f"what the optimiser's standard grades replace ({c['rounded_premium_pct']:+.2f} %)"
                      if c.get("rounded_premium_pct") is not None else "what the standard grades replace"})
    if ver is not None:
        k = ver.worst_pose
        cards.append({"label": "lowest P̂ (Monte Carlo)", "value": f"{ver.p_mc[k]:.4f}",
                      "note": f"pose {k + 1}, {_label(ver)} [{ver.ci_low[k]:.4f}, {ver.ci_high[k]:.4f}]"
                      + _paired_note(ver, k)})
    worst = s["poses"][s["worst_pose"] - 1]
    cards.append({"label": "lowest linear P", "value": f"{worst['p_linear']:.4f}",
                  "note": f"pose {worst['pose']}, the design to build"})
    if cov is not None:
        cards.append({"label": "coverage of the region", "value": f"{cov.min_p:.4f}",
                      "note": f"lowest linear P on {cov.n} fresh poses; {cov.n_below} below p"})
        if getattr(cov, "min_p_angle", None) is not None:
            cards.append({"label": "coverage, orientation", "value": f"{cov.min_p_angle:.4f}",
                          "note": f"lowest linear P of the orientation on the same poses; {cov.n_below_angle} below "
                                  "its p"})
    if corr is not None and corr.rounds:
        cards.append({"label": "cost of the correction", "value": f"{corr.premium_pct:+.3g} %",
                      "note": f"{corr.rounds} round(s)"})
    return cards


def _costs_table(job, s: dict) -> dict:
    res = job.result
    c = s["costs"]
    rows = [("certified, cheaper rule", res.certified, c["certified"], ""),
            ("certified, other rule", res.certified_other, c["certified_other"], ""),
            ("exact (IPOPT)", res.exact, c["exact"], "" if c["saving"] is None else
             f"saving {c['saving']:.4f} ({c['saving_pct']:.2f} %) against certified"),
            ("standard grades", res.standard, c["standard"], "" if s["standard"] is None else s["standard"]["message"])]
    rows = [r for r in rows if r[1] is not None]
    frame = pd.DataFrame({"design": [r[0] for r in rows], "method": [str(r[1].solver) for r in rows],
                          "status": [r[1].status for r in rows], "cost": [r[2] for r in rows],
                          "time_s": [r[1].time_s for r in rows],
                          "note": [pretty(r[3] or r[1].message or "") for r in rows]})
    chosen = ["chosen" if d is job.design else "" for _, d, _, _ in rows]
    cols = [Column("design", "design", "text"), Column("method", "method", "text"),
            Column("status", "status", "text", badge=True), Column("cost", "cost", "f4"),
            Column("time_s", "time [s]", "f2"), Column("note", "note", "text")]
    return html_table(frame, cols, table_id="costs", row_classes=chosen,
                      caption="Costs of the designs (relative cost units of the cost laws)",
                      note="Certified: convex upper bounds on the variance (cvxpy + Clarabel), a design that meets the "
                           "requirement by construction; exact: the Gaussian probability itself (CasADi + IPOPT), "
                           "never dearer; standard grades: the standard values chosen by the optimiser. Bold: the "
                           "design to build, the one of the tolerance table.")


def _pose_frame(job, s: dict):
    """Per pose: joint values, linear P and (when verified) P̂ with its interval, samples, verdict, reason."""
    ver, robot, pr, cov = job.verification, job.robot, job.problem, job.coverage
    if ver is None:
        frame = pd.DataFrame({"pose": [r["pose"] for r in s["poses"]], "p_linear": [r["p_linear"] for r in s["poses"]]})
        if "p_linear_angle" in s["poses"][0]:
            frame["p_linear_angle"] = [r["p_linear_angle"] for r in s["poses"]]
        return with_joints(frame, robot, pr.q), None
    frame = ver.to_frame()
    frame["ci"] = list(zip(frame["ci_low"], frame["ci_high"]))
    if "ci_low_angle" in frame:
        frame["ci_angle"] = list(zip(frame["ci_low_angle"], frame["ci_high_angle"]))
    n = len(frame)
    q = None
    if len(pr.q) == n:
        q = pr.q
    elif cov is not None and len(pr.q) + len(cov.worst_q) == n:  # the coverage's worst poses were verified too
        q = np.vstack([pr.q, cov.worst_q])
    if job.region_search is not None:
        n_active = len(job.region_search.active_q)
        frame.insert(1, "origin", ["active" if i < n_active else "coverage" for i in range(n)])
    return (frame if q is None else with_joints(frame, robot, q)), ["" if ok else "bad" for ok in frame["passed"]]


def _pose_table(job, s: dict) -> dict:
    frame, classes = _pose_frame(job, s)
    pr = job.problem
    label = _label(job.verification)
    cols = [Column("pose", "pose", "int"), Column("origin", "origin", "text"), *joint_columns(job.robot),
            Column("p_linear", "P linear", "f4"), Column("p_mc", "P̂ Monte Carlo", "f4"),
            Column("ci", label, "ci", numeric=True), Column("p_linear_angle", "P linear, angle", "f4"),
            Column("p_mc_angle", "P̂ angle", "f4"), Column("ci_angle", f"{label}, angle", "ci", numeric=True),
            Column("n", "samples", "int"), Column("verdict", "verdict", "text", badge=True),
            Column("reason", "reason", "text", optional=True)]
    what = (f"P(|dP| < {pr.radius_mm:g} mm) per pose" + ("" if pr.angle_radius_rad is None else
                                                         f" and P(|dw| < {np.rad2deg(pr.angle_radius_rad):g} deg)"))
    return html_table(frame, cols, table_id="pose-table", row_classes=classes,
                      caption=f"Verification per pose: {what}, required p = {pr.prob:g}",
                      note=_pose_note(job))


def _pose_note(job) -> str:
    """The pose table's legend: what P linear and P̂ are (the interval of the estimator that ran), the origins."""
    design = f"the design to build ({job.design.label})"
    if job.verification is None:
        return f"P linear: the Gaussian prediction of the first-order model for {design} (no Monte Carlo verification)."
    ver = job.verification
    used = "; ".join(INTERVALS[e] for e in INTERVALS if e in set(map(str, ver.estimator)))
    family = "" if ver.n_intervals <= 1 else f"; {ver.interval_text()}"
    return (f"All of {design}. P linear: the Gaussian prediction of the first-order model; P̂: the nonlinear Monte "
            f"Carlo estimate (exact perturbed kinematics) with its {_label(ver)} ({used}{family}). "
            "Joint values in deg / mm." + ("" if job.region_search is None else " Origin: active, a pose of the region "
                                            "search the design is allocated at; coverage, one of the lowest-P poses of "
                                            "the fresh coverage sample."))


def _region(job, s: dict):
    if job.region_search is None:
        return None
    r = s["region"]
    rounds = f"{r['rounds']} ({'converged' if r['converged'] else 'NOT converged: ' + r['why_not_converged']})"
    pairs = [("region", r["name"]), ("search rounds", rounds),
             ("active poses", r["active_poses"]), ("search evaluations", r["search_evaluations"]),
             ("worst linear P found", worst_p_text(r["worst_p_linear"])),
             ("static joints", ", ".join(map(str, r["static_joints"])) or "none"),
             ("search time", f"{r['time_s']:.1f} s")]
    frame = pd.DataFrame({"joint": [j.name for j in job.robot.joints], "unit": [j.unit for j in job.robot.joints],
                          "q_min": r["q_min_deg_mm"], "q_max": r["q_max_deg_mm"]})
    box = html_table(frame, [Column("joint", "joint", "text"), Column("unit", "unit", "text"),
                             Column("q_min", "lower", "f2"), Column("q_max", "upper", "f2")],
                     table_id="region-box", caption=f"Box of region {r['name']!r}", compact=True)
    return {"pairs": pairs, "box": box}


def _correction(job):
    corr = job.correction
    if corr is None:
        return None
    frame = pd.DataFrame({"round": range(len(corr.costs)), "cost": list(corr.costs)})
    table = html_table(frame, [Column("round", "round", "int"), Column("cost", "design cost", "f4")],
                       table_id="correction-rounds", caption="Design cost per correction round (0: uncorrected)",
                       compact=True)
    return {"text": pretty(corr.message()), "table": table}


def _figures(job, folder=None) -> list:
    """Budget and pose probabilities as SVG; the point cloud as PNG (the copy saved in ``folder`` when there)."""
    ver = job.verification
    figs = [figure_item(job.plot_budget(), figure_id="fig-budget",
                        caption=f"Error budget of the design to build ({job.design.label}): tolerance per parameter "
                                f"(log scale) and its share of tr Σ of the position error at its worst pose "
                                f"(pose {job.worst_pose + 1}); labels: tolerances at a process limit.")]
    if ver is not None:
        figs.append(figure_item(job.plot_pose_probabilities(), figure_id="fig-poses",
                                caption=f"Linear prediction and Monte Carlo estimate P̂ with its {_label(ver)} per "
                                        f"pose, against the required p = {ver.prob:g}."))
        if ver.samples_mm is not None and len(ver.samples_mm):
            caption = (f"Position errors of {len(ver.samples_mm)} Monte Carlo samples at pose {ver.samples_pose + 1} "
                       f"(the lowest linear prediction), three projections, with the r = {ver.radius_mm:g} mm circle.")
            saved = None if folder is None else Path(folder) / "error_cloud.png"
            figs.append(file_figure_item(saved, figure_id="fig-cloud", caption=caption) if saved and saved.is_file()
                        else figure_item(job.plot_cloud(), figure_id="fig-cloud", fmt="png", caption=caption))
    return figs


def allocation_context(job, folder=None) -> dict:
    """The template context of a :class:`~tolalloc.workflows.allocation_result.ToleranceAllocation`'s report (``folder``: where its figures were saved)."""
    s = job.summary()
    res, pr = job.result, job.problem
    where = (f"Over the box region {job.label!r}: its worst poses were found by a cutting-plane search; the design "
             f"is allocated at {pr.n_poses} poses." if job.region is not None else
             f"At the {pr.n_poses} pose(s) of the pose set {job.label!r}.")
    notes = [pretty(x) for x in (res.message, res.design.message) if x and res.status == "optimal"]
    cli, python, rnotes = job.reproduce_command()
    verdict = _verdict(job)
    return {"kicker": "tolerance allocation", "title": "Tolerance allocation report",
            "subtitle": f"{job.robot.name}: {pretty(job.requirement())}",
            "meta": [("robot", job.robot.name), ("where", job.label), ("verdict", verdict["word"].lower()),
                     ("costs", pr.costs.source)],
            "sections": SECTIONS[:2] + [{"id": "handover", "title": "Drawing and purchase list"},
                                        {"id": "assumptions", "title": "Assumptions"}] + SECTIONS[2:],
            "requirement": pretty(job.requirement()), "where": where, "verdict": verdict,
            "cards": _cards(job, s), "costs_table": _costs_table(job, s), "notes": notes,
            "design_note": job.design_note(), "z_text": f"{pr.costs.z:.4g}"
            + (" (errors uniform over ±t)" if pr.costs.distribution == "uniform" else ""),
            "tolerance_table": _tolerance_table(job, s), "handover": handover_html(job.handover()),
            "standard_note": None if s["standard"] is None else pretty(s["standard"]["message"]),
            "region": _region(job, s),
            "coverage_text": None if job.coverage is None else pretty(job.coverage.message(pr.prob)),
            "verification": None if job.verification is None else {"text": pretty(job.verification.message())},
            "legend": verdict_legend(job.verification) + _pass_rule(job), "pose_table": _pose_table(job, s),
            "correction": _correction(job), "figures": _figures(job, folder),
            "inputs": _inputs_pairs(job.inputs, [("sigma_set", s["sigma_set"]), ("z", f"{pr.costs.z:.4g}"),
                                                 ("distribution", pr.costs.distribution),
                                                 *[(k, v) for k, v in pr.model.labels.items() if k != "sigma_set"],
                                                 ("coverage_n", None if job.coverage is None else job.coverage.n)]),
            "reproduce": {"cli": cli, "python": python, "notes": rnotes}}


def _paired_note(ver, k: int) -> str:
    """Why a paired estimate can equal the linear P: the samples on which the nonlinear chain and the linear map
    disagree at pose ``k`` (empty for the other estimators)."""
    if str(ver.estimator[k]) != "paired":
        return ""
    n = np.broadcast_to(np.asarray(ver.n), np.shape(ver.p_mc))[k]
    return (f"; paired estimator: the nonlinear chain and the linear map disagree on {ver.n_discordant[k]:,.0f} of "
            f"{n:,.0f} samples here (P̂ = linear P + their balance)")


def _pass_rule(job) -> str:
    ver = job.verification
    if ver is None:
        return ""
    return (" A certified design passes a pose when demonstrated." if ver.criterion == "certified" else
            " An exact design passes a pose when demonstrated or consistent (upper bound ≥ p).")


def _tolerance_table(job, s: dict) -> dict:
    table = job.to_frame()
    cols = TOLERANCE_COLUMNS + (CONTINUOUS_COLUMNS if job.standard else [])
    classes = ["hl" if lim else "" for lim in table["at_limit"]]
    return html_table(table, cols, table_id="tolerance-table", row_classes=classes,
                      caption=f"Tolerances of {job.robot.name}: the design to build ({job.design.label})",
                      note="Units in the headers: a length row has its values in the [mm] columns, an angle row in "
                           "the [deg] columns. Grade: the ISO 286 IT grade of a link length at its nominal size, a "
                           "class name, or empty (a multiple of the resolution step). Variance share: share of tr Σ "
                           f"of the position error at the worst pose (pose {s['worst_pose']}). At limit (highlighted): "
                           "the tolerance sits at a process limit of the costs (t_min or t_max; the limits are in "
                           "tolerances.csv) or is fixed by the costs file."
                           + (" Continuous optimum: the continuous design the standard values were chosen from, for "
                              "comparison only." if job.standard else ""))


# ---------------------------------------------------------------------------------------------- calibrated allocation
