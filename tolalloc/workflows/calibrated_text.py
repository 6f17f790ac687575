"""The printed text of a :class:`~tolalloc.workflows.calibrated.CalibratedToleranceAllocation` (its
:meth:`~tolalloc.workflows.calibrated.CalibratedToleranceAllocation.text`): the requirement and the plan, the
stages, the standard design, the tolerance table, the parameters the plan cannot identify and the end-to-end Monte
Carlo.
"""

from __future__ import annotations

__all__ = ["report_text"]


def report_text(job) -> str:
    """What the command line prints: the requirement and the plan, the stages, the table, the unidentifiable
    parameters and the end-to-end Monte Carlo."""
    from tolalloc.report.tables import TABLE_COLUMNS, format_text
    from tolalloc.workflows.calibrated_table import CALIBRATED_TEXT_COLUMNS

    res, pr, plan = job.result, job.problem, job.plan
    out = [f"robot: {job.robot.name}   requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} after "
           f"calibration over {job.label}; plan {job.plan_source}: {plan.n_poses} {plan.measurement} "
           f"measurements, noise {plan.noise_mm:g} mm", res.message()]
    if not res.design.ok:
        return "\n".join(out)
    if res.exact is None:
        out.append("exact stage: not run (solver='certified'): the certified design is the continuous design")
    cert = res.certified
    if cert.grade_t is not None:
        out.append(f"  certified design: of which repeatability grades {cert.grade_cost:.4f} (parts "
                   f"{cert.design.cost:.4f}); without calibration: the loosest grades, {cert.grade_cost_loosest:.4f}")
    out += _standard_lines(job)
    frame = job.to_frame()
    out += ["", format_text(frame, [*TABLE_COLUMNS, *CALIBRATED_TEXT_COLUMNS])]
    out += _unidentifiable_lines(job, frame)
    out.append("\n" + (job.end_to_end.message() if job.end_to_end is not None else
                       f"end-to-end Monte Carlo: not run ({job._no_end_to_end()})"))
    return "\n".join(out)


def _standard_lines(job) -> list[str]:
    """The standard design's lines: cost and premium, its region search and coverage, what is built."""
    from tolalloc.allocate.calibrated.summary import summary_search_lines

    res, pr, std = job.result, job.problem, job.standard
    if std is None:
        return []
    out = [std.message_line()]
    out += summary_search_lines(getattr(res.region, "name", ""), {"standard": std.search})
    c = std.coverage
    if c is not None and res.region_kind == "box":
        out.append(f"coverage of the standard design (post-calibration P): {c.n} fresh poses of the box, min P = "
                   f"{c.min_p:.5f}, {c.n_below} below {pr.prob:g}" + ("; none below p" if c.ok else ""))
    if job.built is not None:
        out.append("the design to build is the standard one (tol_mm / tol_deg, grade); the end-to-end Monte Carlo "
                   "below is its check")
        if res.exact is None:
            out.append("solver='certified' covers the continuous design only: the standard grades are chosen "
                       "under the exact post-calibration probability, so the design to build is not certified")
    return out


def _unidentifiable_lines(job, frame) -> list[str]:
    """The parameters the plan cannot identify, by what the allocation did with them, each with its post-calibration
    sigma as a fraction of the manufactured one."""
    from tolalloc.workflows.calibrated_table import (UNIDENTIFIABLE_NOTE, unidentifiable_fractions,
                                                     unidentifiable_groups, with_fractions)

    unid = job.result.summary().get("unidentifiable") or []
    if not unid:
        return []
    held, loose, other = unidentifiable_groups(frame, unid)
    frac = unidentifiable_fractions(job)
    out = ["", f"{UNIDENTIFIABLE_NOTE}:"]
    if held:
        out.append(f"  allocated tight, must be held in manufacturing: {with_fractions(held, frac)}")
    if loose:
        out.append(f"  loose (at the process limit t_max or the coarsest standard grade), which suffices: "
                   f"{with_fractions(loose, frac)}")
    if other:
        named = zip(frame["parameter"], frame["status"])
        out.append(f"  other: {', '.join(f'{n} ({s}, {frac[n]:.2f})' if n in frac else f'{n} ({s})' for n, s in named if n in other)}")
    return out
