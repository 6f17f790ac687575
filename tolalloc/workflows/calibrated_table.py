"""The tolerance table of a calibration-aware allocation, in the columns of the allocation without calibration.

:func:`calibrated_frame` gives one row per parameter with the core columns of
:meth:`tolalloc.workflows.ToleranceAllocation.to_frame` (same names, same meaning: ``tolerance`` is the continuous
design, exact when its stage was run and accepted, else certified; ``tolerance_std`` / ``grade`` the standard design
to build), then the columns only a calibration has: ``status``, ``tolerance_no_calibration``,
``sigma_post_calibration``, ``sigma_random`` (and the certified stage's tolerance when the exact one is shown, the
standard design's post-calibration sigma, the repeatability grades). Every tolerance and sigma is in the row's
``unit`` (mm or deg). The files go through the same writer as the plain table
(:func:`tolalloc.report.tables.write_tables`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

__all__ = ["calibrated_frame", "CALIBRATED_TEXT_COLUMNS", "status_groups", "unidentifiable_groups"]

#: columns printed after the core ones (:data:`tolalloc.report.tables.TABLE_COLUMNS`)
CALIBRATED_TEXT_COLUMNS = ["tolerance_no_calibration", "sigma_post_calibration", "status"]


def _baseline(res):
    """The design without calibration at the stage of the chosen design (as ``cost_no_calibration``), or None."""
    b = res.baseline_exact if res.exact_accepted and res.baseline_exact is not None else res.baseline
    if b is None or not b.ok or (res.exact_accepted and b.fallback_from is not None):
        return None
    return b


def _worst_pose(res) -> int:
    """Index of the pose of the chosen design's problem with the lowest post-calibration ``P``."""
    from tolalloc.linear.probability import p_within_radius

    pr = res.problem
    return int(np.argmin(p_within_radius(res.post.tool_covariance(pr.q), pr.radius_mm)))


def calibrated_frame(job) -> pd.DataFrame:
    """Tolerance table of a :class:`~tolalloc.workflows.CalibratedToleranceAllocation` (module docstring)."""
    from tolalloc.allocate.calibrated import parameter_status
    from tolalloc.linear.covariance import variance_share

    res = job.result
    d, post = res.design, res.post
    if not d.ok or post is None:
        raise TolallocError(f"to_frame: the calibration-aware allocation has no design ({d.message}).")
    pr = res.problem
    params = pr.model.params
    K = len(params)
    f = np.array([p.to_interface for p in params])
    nan = np.full(K, np.nan)
    b, std = job.built, job.standard
    grade = list(b.grade) if b is not None else [""] * K
    rounded = std.rounded if std is not None else None
    base = _baseline(res)
    frame = pd.DataFrame({
        "parameter": [p.name for p in params],
        "kind": [p.kind for p in params],
        "element": [p.element for p in params],
        "unit": [p.interface_unit for p in params],
        "role": list(pr.costs.role),
        "tolerance": d.t * f,
        "sigma": pr.sigma(d.t) * f,
        "tolerance_std": b.design.t * f if b is not None else nan,
        "it_grade": [g if g.startswith("IT") else "" for g in grade],
        "grade": grade,
        "process": list(b.process) if b is not None else [""] * K,
        "cost_std": b.param_cost if b is not None else nan,
        "tolerance_rounded": rounded.t * f if rounded is not None and rounded.t is not None else nan,
        "cost": pr.param_costs(d.t),
        "variance_share": variance_share(pr.J[_worst_pose(res), :3, :], post.cov_total),
        "at_limit": list(d.at_limit),
        "t_min": pr.t_min * f,
        "t_max": pr.t_max * f,
        "status": parameter_status(d, post),
    })
    if res.exact_accepted:
        frame["tolerance_certified"] = res.certified.design.t * f
    frame["tolerance_no_calibration"] = base.t * f if base is not None else nan
    frame["sigma_post_calibration"] = post.sigma_post * f
    frame["sigma_random"] = np.sqrt(post.random_var) * f
    if b is not None:
        frame["sigma_post_calibration_std"] = b.post.sigma_post * f
    cert = res.certified.to_frame()
    for col in ("repeatability_grade", "repeatability_grade_cost"):
        if col in cert:
            frame[col] = cert[col].to_numpy()
    return frame


def status_groups(frame: pd.DataFrame, names=None) -> dict:
    """``{status: [parameter, ...]}`` in table order (of ``names`` only, when given)."""
    keep = frame if names is None else frame[frame["parameter"].isin(list(names))]
    out: dict = {}
    for name, status in zip(keep["parameter"], keep["status"]):
        out.setdefault(status, []).append(name)
    return out


def unidentifiable_groups(frame: pd.DataFrame, names) -> tuple[list, list, list]:
    """The parameters the plan cannot identify, split by what the allocation did with them:
    ``(held, loose, other)`` -- allocated tight (must be held), left at the process's loosest tolerance (loose
    (at t_max)), and any other status."""
    groups = status_groups(frame, names)
    held = [n for s, ns in groups.items() if s.startswith("must be held") for n in ns]
    loose = groups.get("loose (at t_max)", [])
    other = [n for s, ns in groups.items() if not s.startswith("must be held") and s != "loose (at t_max)" for n in ns]
    return held, loose, other
