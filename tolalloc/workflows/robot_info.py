"""What ``tolalloc robots``, ``show`` and ``fk`` print: the built-in robots, a robot's description, a pose."""

from __future__ import annotations

import numpy as np

from tolalloc.robot.io import builtin_robots
from tolalloc.robot.lie import euler_xyz_fixed
from tolalloc.workflows.inputs import as_robot, joint_values

__all__ = ["robots_text", "robot_text", "pose_text", "pose_dict"]


def robots_text() -> str:
    """One line per built-in robot: name and description."""
    return "\n".join(f"{name:14s} {desc}" for name, desc in builtin_robots().items())


def robot_text(robot) -> str:
    """Joints (limits and nominal values in deg / mm), links [mm], pose sets and the nominal end-effector pose."""
    robot = as_robot(robot)
    out = [f"robot: {robot.name}"]
    if robot.description:
        out.append(robot.description.strip())
    out += ["\njoints:", robot.joints_frame().to_string(index=False), "\nlinks:",
            robot.links_frame().to_string(index=False)]
    sets = "".join(f", {k} ({len(v)} pose{'s' if len(v) != 1 else ''})" for k, v in robot.pose_sets.items())
    out.append(f"\npose sets: nominal (1 pose){sets}")
    if robot.sigma_sets:
        out.append(f"sigma sets: {', '.join(robot.sigma_sets)}")
    out += ["\nnominal pose:", pose_text(robot.fk_internal(robot.q_nominal))]
    return "\n".join(out)


def pose_text(T) -> str:
    """A pose ``T`` (4, 4) [mm] (or the dict of :func:`pose_dict`): position, X-Y-Z fixed Euler angles [deg] and
    the rotation matrix."""
    if isinstance(T, dict):
        T = np.vstack([np.column_stack([T["rotation"], T["position_mm"]]), [0.0, 0.0, 0.0, 1.0]])
    e = np.rad2deg(euler_xyz_fixed(T[:3, :3]))
    p = T[:3, 3]
    rows = "\n".join("  [" + "  ".join(f"{v: .6f}" for v in row) + "]" for row in T[:3, :3])
    return (f"position_mm: [{p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}]\n"
            f"euler_xyz_fixed_deg: [{e[0]:.6f}, {e[1]:.6f}, {e[2]:.6f}]\nrotation:\n{rows}")


def pose_dict(robot, q_deg_mm) -> dict:
    """``{"robot", "q_deg_mm", "position_mm", "rotation"}`` of the pose at ``q_deg_mm`` (deg / mm)."""
    robot = as_robot(robot)
    q = joint_values(robot, q_deg_mm)[0]
    T = robot.fk_internal(q)
    # rounded to 1e-9 deg / mm so that "15" comes back as 15.0, not 14.999999999999998
    return {"robot": robot.name, "q_deg_mm": np.round(robot.q_to_interface(q), 9).tolist(),
            "position_mm": T[:3, 3].tolist(), "rotation": T[:3, :3].tolist()}
