"""Computations of the workspace-allocation study: both designs of one robot, their coverage, their
nonlinear Monte Carlo checks and the 2-D slices of the linear P through the worst sampled pose.

Only the public API is used (``tolalloc``, ``tolalloc.allocate``, ``tolalloc.allocate.region``,
``tolalloc.verify``); designs are read through ``cost``, ``t`` and ``AllocationResult.to_frame()``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc import load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.problem import make_design
from tolalloc.allocate.region import allocate_region, box_region, coverage, pose_probability
from tolalloc.errormodel import build_error_model
from tolalloc.verify.designs import verify_design


@dataclass(frozen=True, eq=False)
class DesignRun:
    """One design of one robot with everything the report needs.

    Attributes
    ----------
    label : {"pose set", "region"}
    result : AllocationResult
        The design is ``result.design`` (exact solver, unsnapped).
    wall_s, cpu_s : float
        Time to obtain the design (the whole cutting-plane loop for the region design) [s].
    active_q : array, shape (A, n) [rad, mm]
        Poses the allocation was solved on.
    coverage : Coverage
        Linear P on the fresh sample of the region.
    verification : Verification
        Nonlinear Monte Carlo at ``check_q``.
    check_q : array, shape (C, n) [rad, mm]
        The active poses followed by the worst poses of the fresh sample.
    region_run : RegionAllocation or None
        Rounds, search effort and history (region design only).
    """

    label: str
    result: object
    wall_s: float
    cpu_s: float
    active_q: np.ndarray
    coverage: object
    verification: object
    check_q: np.ndarray
    region_run: object = None

    @property
    def cost(self) -> float:
        return float(self.result.design.cost)

    @property
    def t(self) -> np.ndarray:
        return self.result.design.t


@dataclass(frozen=True, eq=False)
class RobotStudy:
    """Both designs of one robot over one region."""

    name: str
    robot: object
    model: object
    region: object
    pose_set: str
    designs: tuple  # (DesignRun pose set, DesignRun region)


def _timed(fn):
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn()
    return out, time.perf_counter() - w0, time.process_time() - c0


def _verify(model, result, check_q, n_mc, seed):
    """Monte Carlo of ``result.design`` at ``check_q`` (same requirement and costs as the allocation)."""
    pr = build_problem(model, check_q, radius_mm=result.problem.radius_mm, prob=result.problem.prob)
    d = make_design(pr, result.design.solver, result.design.t)  # the solver label is passed through, not read
    return verify_design(pr, d, criterion="exact", n_mc=n_mc, seed=seed, keep_samples=0)


def run_robot(name: str, region_spec: str, *, n_cov: int, n_mc: int, seed: int, k_worst: int = 3) -> RobotStudy:
    """Pose-set design (the robot's ``working`` pose set) and region design over ``region_spec``.

    ``region_spec`` is ``"limits"`` or the name of a box of the robot file. Both designs are checked on the
    same fresh sample of the region (``n_cov`` poses, seed ``seed``) and by nonlinear Monte Carlo
    (``n_mc`` samples per pose) at their active poses and their ``k_worst`` worst sampled poses.
    """
    robot = load_robot(name)
    model = build_error_model(robot)
    lo, hi = (robot.lower, robot.upper) if region_spec == "limits" else robot.regions[region_spec]
    region = box_region(robot, lo, hi, region_spec, f"region {region_spec}")
    W = robot.poses("working")
    pr = build_problem(model, W)
    res_set, w_set, c_set = _timed(lambda: allocate(pr, snap=False))
    inside = np.all((W >= region.q_min - 1e-12) & (W <= region.q_max + 1e-12))
    ra, w_reg, c_reg = _timed(lambda: allocate_region(model, region, W if inside else None, solver="exact"))
    runs = []
    for k, (label, res, active, w, c, rr) in enumerate((("pose set", res_set, W, w_set, c_set, None),
                                                         ("region", ra.result, ra.active_q, w_reg, c_reg, ra))):
        cov = coverage(res.problem, res.design.t, region, n=n_cov, seed=seed, k_worst=k_worst)
        check_q = np.vstack([active, cov.worst_q])
        ver = _verify(model, res, check_q, n_mc, seed + 1 + k)
        runs.append(DesignRun(label, res, w, c, np.asarray(active), cov, ver, check_q, rr))
    return RobotStudy(name, robot, model, region, "working", tuple(runs))


# ----------------------------------------------------------------------------------- 2-D slices
def slice_joints(study: RobotStudy, q_centre: np.ndarray, design: DesignRun, *, n_line: int = 41) -> tuple:
    """The two joints along which the linear P of ``design`` varies most through ``q_centre``.

    Each joint is swept alone over its slice span (:func:`slice_span`), the others held at ``q_centre``;
    the two with the largest range of P are returned (0-based, in joint order).
    """
    spread = []
    for j in range(len(q_centre)):
        lo, hi = slice_span(study, q_centre, j)
        Q = np.repeat(q_centre[None], n_line, 0)
        Q[:, j] = np.linspace(lo, hi, n_line)
        P = pose_probability(design.result.problem, design.t, Q)
        spread.append(float(P.max() - P.min()))
    a, b = sorted(np.argsort(spread)[::-1][:2])
    return int(a), int(b)


def slice_span(study: RobotStudy, q_centre: np.ndarray, j: int, frac: float = 0.25) -> tuple:
    """Range of joint ``j`` on the slice: ``q_centre`` +- ``frac`` of the region's range (revolute: at most
    +- 90 deg), clipped to the region."""
    lo, hi = study.region.q_min[j], study.region.q_max[j]
    half = frac * (hi - lo)
    if study.robot.revolute_mask[j]:
        half = min(half, np.pi / 2)
    return float(max(lo, q_centre[j] - half)), float(min(hi, q_centre[j] + half))


def p_slice(study: RobotStudy, design: DesignRun, q_centre, joints, n_grid: int = 61) -> dict:
    """Linear P of ``design`` on an ``n_grid`` x ``n_grid`` grid of two joints through ``q_centre``.

    Returns
    -------
    dict
        ``x``, ``y`` (n_grid,) joint values [rad or mm], ``P`` (n_grid, n_grid) with ``P[i, k]`` at
        ``(x[k], y[i])``, ``joints``, ``q_centre``.
    """
    a, b = joints
    x = np.linspace(*slice_span(study, q_centre, a), n_grid)
    y = np.linspace(*slice_span(study, q_centre, b), n_grid)
    X, Y = np.meshgrid(x, y)
    Q = np.repeat(np.asarray(q_centre, float)[None], X.size, 0)
    Q[:, a], Q[:, b] = X.ravel(), Y.ravel()
    P = pose_probability(design.result.problem, design.t, Q).reshape(X.shape)
    return {"x": x, "y": y, "P": P, "joints": (a, b), "q_centre": np.asarray(q_centre, float)}


# ----------------------------------------------------------------------------------- tables
def summary_rows(study: RobotStudy) -> list:
    """One row per design: cost, premium, time, search, coverage and Monte Carlo verdict."""
    base = study.designs[0].cost
    rows = []
    for d in study.designs:
        cov, ver, rr = d.coverage, d.verification, d.region_run
        i = int(np.argmin(ver.p_mc))
        rows.append({
            "robot": study.name, "region": study.region.name, "design": d.label, "cost": d.cost,
            "cost_premium_pct": 100 * (d.cost - base) / base, "time_wall_s": d.wall_s, "time_cpu_s": d.cpu_s,
            "rounds": rr.rounds if rr is not None else np.nan,
            "converged": bool(rr.converged) if rr is not None else np.nan,
            "active_poses": len(d.active_q),
            "search_evaluations": rr.evaluations if rr is not None else np.nan,
            "search_worst_p": rr.worst_p if rr is not None else np.nan,
            "coverage_n": cov.n, "coverage_min_p": cov.min_p, "coverage_n_below": cov.n_below,
            "coverage_frac_below": cov.frac_below, "coverage_frac_below_upper95": cov.frac_below_upper95,
            "mc_poses": len(d.check_q), "mc_n_per_pose": int(ver.n.min()), "mc_verdict": ver.verdict,
            "mc_n_failed": int(np.sum(ver.verdicts == "failed")),
            "mc_n_consistent": int(np.sum(ver.verdicts == "consistent")),
            "mc_n_demonstrated": int(np.sum(ver.verdicts == "demonstrated")),
            "mc_lowest_p_hat": float(ver.p_mc[i]), "mc_lowest_ci_low": float(ver.ci_low[i]),
            "mc_lowest_ci_high": float(ver.ci_high[i])})
    return rows


def verification_rows(study: RobotStudy) -> pd.DataFrame:
    """Per design and checked pose: which pose, q [deg / mm], linear P, P_hat with its interval, verdict."""
    frames = []
    for d in study.designs:
        f = d.verification.to_frame()
        n_act = len(d.active_q)
        kind = ["active"] * n_act + [f"worst sampled {k + 1}" for k in range(len(d.check_q) - n_act)]
        qi = study.robot.q_to_interface(d.check_q)
        cols = {"robot": study.name, "design": d.label, "pose": f["pose"], "kind": kind}
        cols.update({f"q{j + 1}_deg_mm": qi[:, j] for j in range(qi.shape[1])})
        cols.update({c: f[c] for c in ("p_linear", "p_mc", "ci_low", "ci_high", "n", "verdict", "reason")})
        frames.append(pd.DataFrame(cols))
    return pd.concat(frames, ignore_index=True)


def history_rows(study: RobotStudy) -> pd.DataFrame:
    """The cutting-plane rounds of the region design: cost and the worst linear P the search found."""
    rr = study.designs[1].region_run
    return pd.DataFrame([{"robot": study.name, "round": r, "cost": c, "search_worst_p": p} for r, c, p in rr.history])
