"""``summary.json`` and the printed text of a :class:`~tolalloc.workflows.allocation_result.ToleranceAllocation`."""

from __future__ import annotations

import numpy as np

from tolalloc.report.html_allocation import worst_p_text

__all__ = ["summary_dict", "report_text"]


def summary_dict(job) -> dict:
    """summary.json: the allocation, the region search, the coverage check, the verification and the correction."""
    res, robot, reg_info, cov, ver, corr = (job.result, job.robot, job.region_search, job.coverage, job.verification,
                                            job.correction)
    summary = res.summary()
    summary["pose_set"] = job.label
    summary["tables_design"] = job.design_note()
    summary["verified"] = job.verified
    summary["built"] = {"solver": str(job.design.solver), "label": job.design.label, "cost": float(job.design.cost),
                        "standard": job.standard}
    summary["correction"] = None if corr is None else corr.to_dict()
    if reg_info is not None:
        region = job.region
        summary["region"] = {"name": region.name, "q_min_deg_mm": robot.q_to_interface(region.q_min),
                             "q_max_deg_mm": robot.q_to_interface(region.q_max), "rounds": reg_info.rounds,
                             "converged": reg_info.converged, "active_poses": len(reg_info.active_q),
                             "search_evaluations": reg_info.evaluations,
                             "worst_p_linear": float(reg_info.worst_p) if np.isfinite(reg_info.worst_p) else None,
                             "worst_p_angle_linear": _finite(reg_info.worst_p_angle),
                             "why_not_converged": None if reg_info.converged else region_stop(reg_info),
                             "static_joints": [int(j) + 1 for j in np.flatnonzero(reg_info.static)],
                             "time_s": reg_info.time_s}
    if cov is not None:
        summary["coverage"] = {"n": cov.n, "min_p": cov.min_p, "n_below": cov.n_below,
                               "frac_below": cov.frac_below, "frac_below_upper95": cov.frac_below_upper95,
                               "min_p_angle": cov.min_p_angle, "n_below_angle": cov.n_below_angle,
                               "frac_below_angle": cov.frac_below_angle,
                               "frac_below_upper95_angle": cov.frac_below_upper95_angle}
    if ver is not None:
        summary["verification"] = {"criterion": ver.criterion, "ok": ver.ok, "message": ver.message(),
                                   "n_per_pose": ver.n, "seed": ver.seed, "family_level": ver.family_level,
                                   "n_intervals": ver.n_intervals, "second_looks": ver.second_looks,
                                   "level_per_interval": ver.level_per_interval,
                                   "intervals": ver.interval_text(), **ver.estimator_summary()}
        for i, row in enumerate(summary["poses"]):
            row.update({"p_mc": float(ver.p_mc[i]), "p_mc_ci": [float(ver.ci_low[i]), float(ver.ci_high[i])],
                        "p_mc_ci_level": ver.level_per_interval})
            if ver.angle is not None:
                row.update({"p_mc_angle": float(ver.angle["p_mc"][i]),
                            "p_mc_angle_ci": [float(ver.angle["ci_low"][i]), float(ver.angle["ci_high"][i])]})
            row.update({"n_mc": int(ver.n[i]), "passed": bool(ver.passed[i]), "verdict": str(ver.verdicts[i]),
                        "reason": ver.reason[i]})
        summary["verification"]["verdict"] = ver.verdict
        summary["verification"]["verdicts"] = ver.verdicts.tolist()
        summary["verification"].update(ver.requirements_summary())
    return summary


def report_text(job) -> str:
    """The lines the command line prints: region search, coverage, requirement, costs, table, checks."""
    lines = []
    reg_info, cov = job.region_search, job.coverage
    if job.infeasible is not None:
        return ""
    if reg_info is not None:
        worst = worst_p_text(reg_info.worst_p if np.isfinite(reg_info.worst_p) else None)
        if reg_info.worst_p_angle is not None:
            worst += f" (position), {worst_p_text(_finite(reg_info.worst_p_angle))} (orientation)"
        lines.append(f"region {job.region.name}: {reg_info.rounds} round(s), {len(reg_info.active_q)} active poses, "
                     f"{reg_info.evaluations} search evaluations, worst linear P found {worst}"
                     + ("" if reg_info.converged else f" (NOT converged: {region_stop(reg_info)})"))
    if cov is not None:
        lines.append(cov.message(job.problem.prob))
    lines += _design_lines(job)
    return "\n".join(lines)


def _design_lines(job) -> list[str]:
    from tolalloc.report.tables import format_text

    res, ver, corr = job.result, job.verification, job.correction
    pr = res.problem
    table = job.to_frame()
    out = [f"robot: {pr.model.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} at "
           f"{pr.n_poses} {job.label} pose(s)" + ("" if pr.angle_radius_rad is None else
                                                 f", P(|dw| < {np.rad2deg(pr.angle_radius_rad):g} deg) >= {pr.angle_prob:g}"),
           f"costs: {pr.costs.source}; sigma = t / {pr.costs.z:.4g}"
           + ("; errors uniform over +-t" if pr.costs.distribution == "uniform" else "")]
    if res.status == "not_converged":
        return out + [f"\nstatus: NOT CONVERGED   design: {res.design.label}   cost: {res.design.cost:.4f}\n{res.message}",
                      "\nthe non-converged design (for reference only):", format_text(table)]
    if res.status != "optimal":
        return out + [f"\nstatus: INFEASIBLE. {res.message}", "\ntightest design the process limits allow (for reference):",
                      format_text(table)]
    s = res.summary()["costs"]

    def c(x, d=None):
        if x is not None:
            return f"{x:.4f}"
        return "n/a" if d is None or not d.message else f"n/a, {d.status}: {d.message}"

    d, cont = job.design, f"continuous design: {res.design.label}"
    if job.standard:
        out.append(f"status: optimal   design to build: {d.label} (standard grades)   cost: {d.cost:.4f}   {cont}, "
                   f"cost {res.design.cost:.4f} ({100 * (d.cost / res.design.cost - 1):+.2f} %)")
    else:
        why = ("no standard values asked for" if res.standard is None else
               "the standard design does not meet the requirement")
        out.append(f"status: optimal   design to build: the {cont} ({why})   cost: {d.cost:.4f}")
    out.append(f"continuous designs: certified {c(s['certified'], res.certified)} ({s['certified_rule']}; "
               f"{s['certified_other_rule']}: {c(s['certified_other'], res.certified_other)})   exact {c(s['exact'])}"
               + ("" if s["saving"] is None else f"   saving {s['saving']:.4f} ({s['saving_pct']:.2f}%)"))
    if res.design.message:
        out.append(f"note: {res.design.message}")
    out += ["", f"table: {job.design_note()}", format_text(table)]
    if res.discrete is not None:
        out.append("\n" + res.discrete.message_line())
    elif res.standard is not None:
        out.append(f"\nstandard grades: cost {res.standard.cost:.4f}; {res.standard.message}")
    if job.standard:
        checks = [c for c, done in (("the coverage check", job.coverage is not None),
                                    ("the Monte Carlo verification", job.verification is not None)) if done]
        out.append((f"{' and '.join(checks)} below {'are' if len(checks) > 1 else 'is'} the standard design's: "
                    if checks else "no check below: ") + "the standard design is the design that will be built")
    p = job.design.p_linear["position"]
    out.append(f"\nlinear P per pose ({job.design.label}): min {p.min():.4f} (pose {int(np.argmin(p)) + 1}), "
               f"max {p.max():.4f}")
    if ver is not None:
        out.append(ver.message())
        out.append(ver.estimator_message())
        out.append("verdict per pose: " + ", ".join(f"{i + 1} {v}" for i, v in enumerate(ver.verdicts))
                   + f"; overall: {ver.verdict}")
    if corr is not None:
        out.append(f"correction: {corr.message()}")
        if corr.rounds:
            out.append("the tolerance table above is the corrected design's")
    return out


def region_stop(reg_info) -> str:
    """Why a region search stopped without converging: the search's own message, else the round limit."""
    return getattr(reg_info, "message", None) or "round limit reached"


def _finite(x) -> float | None:
    return None if x is None or not np.isfinite(x) else float(x)
