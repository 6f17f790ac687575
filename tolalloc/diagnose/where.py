"""Where the gap lies: breakdown of the residual after geometric calibration.

Residuals are rotated into the robot base frame (``e_base = R^T e``). For every pose feature -- joint
values (interface units), reach (horizontal distance of the target from the base origin), elevation
(height against gravity), extension (distance from the second joint's point to the target), gravity
load at each joint, and the covariates (temperature, time, payload, approach directions) -- the table
gives the Spearman correlation of the error norm with the feature, the largest absolute Pearson
correlation of a residual component with it, and the RMS in the feature's quartile bins.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.stats import spearmanr

from tolalloc.robot.model import Robot
from tolalloc.diagnose.calibrate import Fit
from tolalloc.physics.loads import gravity_torques
from tolalloc.diagnose.measurements import WRENCH_COLUMNS, Measurements

__all__ = ["WhereBreakdown", "where_breakdown", "pose_features"]


@dataclass(frozen=True, eq=False)
class WhereBreakdown:
    """Residual breakdown.

    Attributes
    ----------
    residual_base_mm : array, shape (P, 3)   residuals in the robot base frame
    features : DataFrame, (P, F)             pose features and covariates
    per_axis : DataFrame                     RMS, mean, std per base axis and of the norm [mm]
    trends : DataFrame                       one row per feature, strongest first
    worst : DataFrame                        the poses with the largest error
    regions : DataFrame                      RMS per (reach, elevation) tercile cell
    """

    residual_base_mm: np.ndarray
    features: pd.DataFrame
    per_axis: pd.DataFrame
    trends: pd.DataFrame
    worst: pd.DataFrame
    regions: pd.DataFrame

    @property
    def norm_mm(self) -> np.ndarray:
        return np.linalg.norm(self.residual_base_mm, axis=1)


def pose_features(robot: Robot, meas: Measurements, points_base_mm: np.ndarray) -> pd.DataFrame:
    """Pose features of every measured pose (see the module docstring), one column each."""
    g = np.asarray(robot.gravity, dtype=float)
    qi = robot.q_to_interface(meas.q)
    cols = {f"q{j + 1}_{robot.joints[j].unit}": qi[:, j] for j in range(robot.n_joints)}
    horiz = points_base_mm - np.outer(points_base_mm @ g, g)
    cols["reach_mm"] = np.linalg.norm(horiz, axis=1)
    cols["elevation_mm"] = -(points_base_mm @ g)
    shoulder = robot.joint_points_mm[min(1, robot.n_joints - 1)]
    from tolalloc.robot.kinematics import poe_prefix

    k = min(1, robot.n_joints - 1)
    Pj = poe_prefix(robot.screws[:k], meas.q[:, :k])[:, k]  # only the prefix needed (memory of large files)
    sh = Pj[:, :3, :3] @ shoulder + Pj[:, :3, 3]
    cols["extension_mm"] = np.linalg.norm(points_base_mm - sh, axis=1)
    step = 20_000  # chunks bound the prefix products' memory for large files
    tau = np.concatenate([gravity_torques(robot, meas.q[a:a + step]) for a in range(0, meas.n_poses, step)])
    for j in range(robot.n_joints):
        cols[f"gravity_load_j{j + 1}_{'Nm' if robot.joints[j].is_revolute else 'N'}"] = tau[:, j]
    for key, v in meas.covariates().items():
        cols[key] = v
    if meas.wrench is not None:
        for k, name in enumerate(name for names in WRENCH_COLUMNS for name in names):
            cols[name] = meas.wrench[:, k]
        cols["force_n"] = np.linalg.norm(meas.wrench[:, :3], axis=1)
    if meas.direction is not None:
        for j in range(robot.n_joints):
            cols[f"dir{j + 1}"] = meas.direction[:, j]
    return pd.DataFrame(cols)


def where_breakdown(robot: Robot, meas: Measurements, fit: Fit, n_worst: int = 10) -> WhereBreakdown:
    """Break the residual of ``fit`` on the poses of ``meas`` down by axis, feature and region."""
    res = fit.residual_mm @ fit.R  # base frame
    norm = np.linalg.norm(res, axis=1)
    feats = pose_features(robot, meas, fit.base_points(meas.q))
    per_axis = pd.DataFrame({
        "axis": ["x (base)", "y (base)", "z (base)", "norm"],
        "rms_mm": [*np.sqrt(np.mean(res ** 2, axis=0)), np.sqrt(np.mean(norm ** 2))],
        "mean_mm": [*res.mean(0), norm.mean()],
        "std_mm": [*res.std(0), norm.std()],
    })
    rows = []
    for name in feats.columns:
        v = feats[name].to_numpy()
        if np.ptp(v) <= 1e-12 * max(1.0, np.abs(v).max()):
            continue
        rho = spearmanr(v, norm).statistic
        comp = [abs(np.corrcoef(v, res[:, a])[0, 1]) if res[:, a].std() > 0 else 0.0 for a in range(3)]
        edges = np.unique(np.quantile(v, [0, 0.25, 0.5, 0.75, 1.0]))
        idx = np.clip(np.searchsorted(edges, v, side="right") - 1, 0, len(edges) - 2)
        bins = [float(np.sqrt(np.mean(norm[idx == b] ** 2))) if np.any(idx == b) else np.nan for b in range(len(edges) - 1)]
        rows.append({"feature": name, "spearman_norm": float(rho), "max_abs_corr_component": float(max(comp)),
                     "axis_of_max_corr": "xyz"[int(np.argmax(comp))], "bin_rms_mm": np.round(bins, 4).tolist(),
                     "bin_ratio": float(np.nanmax(bins) / max(np.nanmin(bins), 1e-12))})
    trends = pd.DataFrame(rows)
    if len(trends):
        trends["strength"] = np.maximum(trends["spearman_norm"].abs(), trends["max_abs_corr_component"])
        trends = trends.sort_values("strength", ascending=False).reset_index(drop=True)
    order = np.argsort(-norm)[:n_worst]
    worst = pd.DataFrame({"row": meas.rows[order] if len(meas.rows) else order + 1, "error_mm": norm[order],
                          "ex_mm": res[order, 0], "ey_mm": res[order, 1], "ez_mm": res[order, 2]})
    for c in feats.columns[: robot.n_joints]:
        worst[c] = feats[c].to_numpy()[order]
    worst["reach_mm"] = feats["reach_mm"].to_numpy()[order]
    worst["elevation_mm"] = feats["elevation_mm"].to_numpy()[order]
    reg = []
    r_edges = np.quantile(feats["reach_mm"], [0, 1 / 3, 2 / 3, 1])
    z_edges = np.quantile(feats["elevation_mm"], [0, 1 / 3, 2 / 3, 1])
    ri = np.clip(np.searchsorted(r_edges, feats["reach_mm"], side="right") - 1, 0, 2)
    zi = np.clip(np.searchsorted(z_edges, feats["elevation_mm"], side="right") - 1, 0, 2)
    for a in range(3):
        for b in range(3):
            m = (ri == a) & (zi == b)
            reg.append({"reach_mm": f"{r_edges[a]:.0f}-{r_edges[a + 1]:.0f}",
                        "elevation_mm": f"{z_edges[b]:.0f}-{z_edges[b + 1]:.0f}", "poses": int(m.sum()),
                        "rms_mm": float(np.sqrt(np.mean(norm[m] ** 2))) if m.any() else np.nan})
    regions = pd.DataFrame(reg).sort_values("rms_mm", ascending=False).reset_index(drop=True)
    return WhereBreakdown(res, feats, per_axis, trends, worst, regions)
