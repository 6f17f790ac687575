"""Summary (JSON-ready dict) and printed lines of a :class:`~tolalloc.allocate.calibrated.design.CalibratedDesign`."""

from __future__ import annotations

import numpy as np

__all__ = ["summary", "message"]


def _search(s) -> dict | None:
    if s is None:
        return None
    return {"rounds": s.rounds, "active_poses": len(s.active_q), "evaluations": s.evaluations,
            "worst_p": _finite(s.worst_p), "converged": s.converged,
            "why_not_converged": None if s.converged else s.stop_reason, "time_s": s.time_s}


def _coverage(c) -> dict | None:
    if c is None:
        return None
    return {"n": c.n, "min_p": c.min_p, "n_below": c.n_below, "frac_below": c.frac_below,
            "frac_below_upper95": c.frac_below_upper95, "ok": c.ok}


def _finite(x):
    """``x`` as a float, or None when it is missing or not finite (JSON has no inf / NaN)."""
    return None if x is None or not np.isfinite(x) else float(x)


def _design_cost(d, extra=0.0):
    """Cost of a design without calibration (None unless it is a converged design of its own solver)."""
    return None if d is None or not d.ok or d.fallback_from is not None else float(d.cost + extra)


def summary(res) -> dict:
    """Keys: costs (chosen, certified, exact, without calibration, saving), verdicts, region, coverage, plan."""
    ok = res.design.ok
    base = res.cost_no_calibration if ok else None
    out = {
        "design": res.design.label, "status": res.design.status, "message": res.design.message,
        "cost": _finite(res.cost) if ok else None, "cost_certified": _finite(res.cost_certified) if ok else None,
        "cost_exact": res.cost_exact, "exact_message": None if res.exact is None else res.exact.design.message,
        "certified": res.certified.certified, "ratio_certified": _finite(res.certified.ratio),
        "cost_no_calibration": base, "saving": None if base is None else base - res.cost,
        "saving_pct": None if base is None else 100 * (base - res.cost) / base,
        "cost_no_calibration_certified": _design_cost(res.baseline, res.certified.grade_cost_loosest),
        "cost_no_calibration_exact": _design_cost(res.baseline_exact, res.certified.grade_cost_loosest),
        "worst_p_post": res.worst_p() if ok else None,
        "ok": res.ok, "region_kind": res.region_kind,
        "unidentifiable": list(res.post.unidentifiable) if res.post is not None else [],
        "plan": {"n_poses": res.plan.n_poses, "measurement": res.plan.measurement, "noise_mm": res.plan.noise_mm,
                 "registration": res.plan.registration, "robot": res.plan.robot},
        "time_s": res.time_s,
    }
    if res.region is not None:
        robot = res.problem.model.robot
        out["region"] = {"name": res.region.name, "q_min_deg_mm": robot.q_to_interface(res.region.q_min).tolist(),
                         "q_max_deg_mm": robot.q_to_interface(res.region.q_max).tolist(),
                         "static_joints": [int(j) + 1 for j in np.flatnonzero(res.static)]
                         if res.static is not None else [],
                         "search_certified": _search(res.search), "search_exact": _search(res.search_exact)}
    out["coverage"] = _coverage(res.coverage)
    return out


def summary_search_lines(region_name: str, searches: dict) -> list[str]:
    """One printed line per region search (``{name: RegionSearch or None}``): rounds, poses, worst ``P`` and, for
    a search that did not converge, why it stopped."""
    return [f"region {region_name} ({name}): {s.rounds} round(s), {len(s.active_q)} active poses, "
            f"{s.evaluations} search evaluations, worst post-calibration P found {s.worst_p:.5f}"
            + ("" if s.converged else f" (NOT converged: {s.stop_reason})")
            for name, s in searches.items() if s is not None]


def message(res) -> str:
    """Printed lines: region search, coverage, designs and costs."""
    pr = res.problem
    lines = summary_search_lines(getattr(res.region, "name", ""), {"certified": res.search, "exact": res.search_exact})
    c = res.coverage
    if c is not None:
        what = (f"{c.n} fresh poses of the box" if res.region_kind == "box"
                else f"all {c.n} poses of the {'trajectory' if res.region_kind == 'trajectory' else 'pose set'}")
        lines.append(f"coverage (post-calibration P): {what}, min P = {c.min_p:.5f}, {c.n_below} below "
                     f"{pr.prob:g}" + (f" (95% upper bound on the fraction {c.frac_below_upper95:.2e})"
                                        if res.region_kind == "box" else "") + ("; none below p" if c.ok else ""))
    if not res.certified.design.ok:
        lines.append(f"status: INFEASIBLE. {res.certified.design.message}"
                     + (f" (at the active poses of round {res.search.rounds} of the region search)"
                        if res.search is not None else ""))
        return "\n".join(lines)
    verdict = "certified" if res.certified.certified else f"NOT certified (ratio {res.certified.ratio:.6f})"
    lines.append(f"certified calibrated design: cost {res.cost_certified:.4f} ({verdict})")
    if res.exact is not None:
        if res.exact_accepted:
            lines.append(f"exact calibrated design: cost {res.cost_exact:.4f} ({res.exact.design.message})")
        else:
            lines.append(f"exact stage not used: {res.exact.design.message}")
    base = res.cost_no_calibration
    if base is not None:
        lines.append(f"design: {res.design.label}   cost {res.cost:.4f}   without calibration {base:.4f}   saving "
                     f"{base - res.cost:.4f} ({100 * (base - res.cost) / base:.2f}%)")
    else:
        lines.append(f"design: {res.design.label}   cost {res.cost:.4f}")
    return "\n".join(lines)
