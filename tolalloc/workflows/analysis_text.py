"""``analyze.json`` of an :class:`~tolalloc.workflows.analysis.ErrorAnalysis`."""

from __future__ import annotations

import numpy as np

__all__ = ["analyze_dict"]


def _pose_dict(res, b, i, radii, probs, robot) -> dict:
    frame = b.to_frame(pose=i)
    kinds = b.to_frame(pose=i, by="kind")
    keep = [c for c in frame.columns if c != "pose"]
    d = {
        "pose": i + 1,
        "q_deg_mm": robot.q_to_interface(res.q[i]),
        "std_mm": res.std_mm[i],
        "covariance_mm2": res.cov_mm2[i],
        "rms_mm": float(res.rms_mm[i]),
        "std_rot_deg": np.rad2deg(res.std_rot_rad[i]),
        "covariance_rot_rad2": res.cov_rot_rad2[i],
    }
    if radii:
        d["p_within_radius"] = {f"{r:g}": float(res.p_within(r)[i]) for r in radii}
    if probs:
        d["radius_mm_for_prob"] = {f"{p:g}": float(res.radius_for(p)[i]) for p in probs}
    d["budget"] = {
        # sigma_mm / sigma_deg: the pair's other entry is null on each row
        "parameters": [{k: None if isinstance(v, float) and np.isnan(v) else v for k, v in row.items()}
                       for row in frame[keep].to_dict(orient="records")],
        "kinds": kinds[[c for c in kinds.columns if c != "pose"]].to_dict(orient="records"),
    }
    return d


def analyze_dict(res, b, radii, probs) -> dict:
    """JSON-ready results: the worst pose's values at top level, every pose under ``poses`` if several."""
    robot = res.model.robot
    worst = b.worst_pose
    out = {"robot": robot.name, "labels": res.model.labels, "method": "linear (first order), Gaussian approximation",
           "n_poses": res.n_poses, "worst_pose": worst + 1, "pose_numbering": "1-based, in the order of the pose set",
           "budget_columns": "sigma_mm / sigma_deg: the parameter's sigma on length / angle rows (null on the "
                             "others); var_*_mm2: contribution to the variance [mm^2]; share_*_pct: its share [%]; "
                             "norm = trace",
           **_pose_dict(res, b, worst, radii, probs, robot)}
    if res.n_poses > 1:
        out["poses"] = [_pose_dict(res, b, i, radii, probs, robot) for i in range(res.n_poses)]
    return out
