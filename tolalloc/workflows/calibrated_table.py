"""The tolerance table of a calibration-aware allocation, in the columns of the allocation without calibration.

:func:`calibrated_frame` gives one row per parameter with the core columns of
:meth:`tolalloc.workflows.ToleranceAllocation.to_frame` (same names, same meaning: the core describes the design
to build -- the standard design when there is one, else the continuous calibration-aware design, exact when its
stage was run and accepted, else certified -- every quantity in mm or deg in a ``<name>_mm`` / ``<name>_deg`` pair;
``tol_continuous_*`` / ``cost_continuous`` the continuous design for comparison), then the columns only a
calibration has, for the design to build: ``status``, ``tol_no_calibration_*`` (the design without calibration),
``sigma_post_calibration_*``, ``sigma_random_*`` (and ``tol_certified_*`` when the exact stage's design is shown,
the repeatability grades ``repeatability_grade_*``). The files go through the same writer as the plain table
(:func:`tolalloc.report.tables.write_tables`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.allocate.result import parameter_columns
from tolalloc.exceptions import TolallocError

__all__ = ["calibrated_frame", "CALIBRATED_TEXT_COLUMNS", "status_groups", "unidentifiable_groups",
           "unidentifiable_fractions", "with_fractions", "UNIDENTIFIABLE_NOTE"]

#: columns printed after the core ones (:data:`tolalloc.report.tables.TABLE_COLUMNS`)
CALIBRATED_TEXT_COLUMNS = ["tol_no_calibration_mm", "tol_no_calibration_deg", "sigma_post_calibration_mm",
                           "sigma_post_calibration_deg", "status"]

#: what "not identifiable" means, and what the number after each name is (the printed texts' heading)
UNIDENTIFIABLE_NOTE = ("not identifiable individually by the plan (each enters a combination of parameters the plan "
                       "cannot see, or no measurement sees it); in brackets its post-calibration sigma as a fraction "
                       "of the manufactured one, 1.00 = left as manufactured")


def _baseline(res):
    """The design without calibration at the stage of the chosen design (as ``cost_no_calibration``), or None."""
    b = res.baseline_exact if res.exact_accepted and res.baseline_exact is not None else res.baseline
    if b is None or not b.ok or (res.exact_accepted and b.fallback_from is not None):
        return None
    return b


def _worst_pose(pr, post) -> int:
    """Index of the pose of ``pr`` with the lowest post-calibration ``P`` under ``post``."""
    from tolalloc.linear.probability import p_within_radius

    return int(np.argmin(p_within_radius(post.tool_covariance(pr.q), pr.radius_mm)))


def _coarsest_grade(status: list, params, b, std) -> list:
    """``loose (coarsest grade)`` for a part of the standard design ``b`` left at the coarsest standard value its
    catalogue offers (its continuous tolerance lies above it): the grade range, not manufacturing, holds it there."""
    if b is None or std is None or std.rounded is None or std.rounded.t is None:
        return status
    capped = set(getattr(std, "range_limited", ()))
    return ["loose (coarsest grade)" if st == "must be held" and p.name in capped
            and b.design.t[k] >= std.rounded.t[k] * (1 - 1e-9) else st
            for k, (st, p) in enumerate(zip(status, params))]


def _built(job) -> tuple:
    """``(design, posterior)`` of the design to build: the standard one when found, else the continuous one."""
    b, res = job.built, job.result
    return (b.design, b.post) if b is not None and b.post is not None else (res.design, res.post)


def unidentifiable_fractions(job) -> dict:
    """``{parameter: post-calibration sigma / manufactured sigma}`` of the design to build, for the parameters the
    plan cannot identify (:attr:`tolalloc.calibration.posterior.Posterior.sigma_fraction`)."""
    names = job.result.summary().get("unidentifiable") or []
    post = _built(job)[1]
    if post is None:
        return {}
    frac = dict(zip(job.problem.model.names, post.sigma_fraction))
    return {n: float(frac[n]) for n in names}


def with_fractions(names, fractions: dict) -> str:
    """``dl1 (1.00), dd4 (0.39)``: the names, each with its sigma fraction."""
    return ", ".join(f"{n} ({fractions[n]:.2f})" if n in fractions else n for n in names)


def calibrated_frame(job) -> pd.DataFrame:
    """Tolerance table of a :class:`~tolalloc.workflows.CalibratedToleranceAllocation` (module docstring)."""
    from tolalloc.allocate.calibrated.certified import parameter_status
    from tolalloc.linear.covariance import variance_share

    res = job.result
    d, post = res.design, res.post
    if not d.ok or post is None:
        raise TolallocError(f"to_frame: the calibration-aware allocation has no design ({d.message}).")
    pr = res.problem
    params = pr.model.params
    K = len(params)
    nan = np.full(K, np.nan)
    b, std = job.built, job.standard
    build, build_post = _built(job)
    rounded = std.rounded if std is not None else None
    base = _baseline(res)
    cols = parameter_columns(pr)
    cols.update(pr.model.interface_columns("tol", build.t))
    cols.update({"grade": list(b.grade) if b is not None else [""] * K,
                 "process": list(b.process) if b is not None else [""] * K})
    cols.update(pr.model.interface_columns("sigma", pr.sigma(build.t)))
    share = variance_share(pr.J[_worst_pose(pr, build_post), :3, :], build_post.cov_total)
    cols.update({"cost": b.param_cost if b is not None else pr.param_costs(d.t), "variance_share_pct": 100.0 * share,
                 "at_limit": list(build.at_limit)})
    cols.update({**pr.model.interface_columns("t_min", pr.t_min), **pr.model.interface_columns("t_max", pr.t_max)})
    cols.update(pr.model.interface_columns("tol_continuous", d.t))
    cols["cost_continuous"] = pr.param_costs(d.t)
    rnd = rounded.t if rounded is not None and rounded.t is not None else nan
    cols.update(pr.model.interface_columns("tol_rounded", rnd))
    cols["status"] = _coarsest_grade(parameter_status(build, build_post), params, b, std)
    if res.exact_accepted:
        cols.update(pr.model.interface_columns("tol_certified", res.certified.design.t))
    cols.update(pr.model.interface_columns("tol_no_calibration", (base.t if base is not None else nan)))
    cols.update(pr.model.interface_columns("sigma_post_calibration", build_post.sigma_post))
    cols.update(pr.model.interface_columns("sigma_random", np.sqrt(build_post.random_var)))
    cert = res.certified.to_frame()
    if "repeatability_grade_cost" in cert:
        for col in ("repeatability_grade_mm", "repeatability_grade_deg", "repeatability_grade_cost"):
            cols[col] = cert[col].to_numpy()
    return pd.DataFrame(cols)


def status_groups(frame: pd.DataFrame, names=None) -> dict:
    """``{status: [parameter, ...]}`` in table order (of ``names`` only, when given)."""
    keep = frame if names is None else frame[frame["parameter"].isin(list(names))]
    out: dict = {}
    for name, status in zip(keep["parameter"], keep["status"]):
        out.setdefault(status, []).append(name)
    return out


def unidentifiable_groups(frame: pd.DataFrame, names) -> tuple[list, list, list]:
    """The parameters the plan cannot identify, split by what the allocation did with them:
    ``(held, loose, other)`` -- allocated tight (must be held), left loose (at the process's loosest tolerance,
    ``loose (at t_max)``, or at the coarsest standard grade, ``loose (coarsest grade)``), and any other status."""
    groups = status_groups(frame, names)
    held = [n for s, ns in groups.items() if s.startswith("must be held") for n in ns]
    loose = [n for s, ns in groups.items() if s.startswith("loose") for n in ns]
    other = [n for s, ns in groups.items() if not s.startswith(("must be held", "loose")) for n in ns]
    return held, loose, other
