"""`tolalloc robots`, `tolalloc show ROBOT`, `tolalloc fk ROBOT --q ...`."""

from __future__ import annotations

import json

import numpy as np

from tolalloc.robot.lie import euler_xyz_fixed
from tolalloc.robot.io import builtin_robots
from tolalloc.cli.common import add_robot_arg, json_default, parse_q, robot_from_args


def register(sub) -> None:
    p = sub.add_parser("robots", help="list the built-in robots", description="List the built-in robots, one line each.")
    p.set_defaults(func=cmd_robots)

    p = sub.add_parser("show", help="joints, links and nominal pose of a robot",
                       description="Show a robot's joints (limits and nominal values in deg / mm), links [mm], "
                       "pose sets and its nominal end-effector pose.")
    add_robot_arg(p)
    p.set_defaults(func=cmd_show)

    p = sub.add_parser("fk", help="forward kinematics at given joint values",
                       description="End-effector pose T(q) by the product of exponentials.")
    add_robot_arg(p)
    p.add_argument("--q", required=True, metavar="Q_DEG_MM",
                   help='joint values, comma-separated, deg (revolute) / mm (prismatic), e.g. "15,30,-10,0,-20,-5"')
    p.add_argument("--json", action="store_true", help="print JSON with position_mm and rotation (3x3)")
    p.set_defaults(func=cmd_fk)


def cmd_robots(args) -> int:
    for name, desc in builtin_robots().items():
        print(f"{name:14s} {desc}")
    return 0


def _pose_text(T) -> str:
    e = np.rad2deg(euler_xyz_fixed(T[:3, :3]))
    p = T[:3, 3]
    rows = "\n".join("  [" + "  ".join(f"{v: .6f}" for v in row) + "]" for row in T[:3, :3])
    return (f"position_mm: [{p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}]\n"
            f"euler_xyz_fixed_deg: [{e[0]:.6f}, {e[1]:.6f}, {e[2]:.6f}]\nrotation:\n{rows}")


def cmd_show(args) -> int:
    robot = robot_from_args(args)
    print(f"robot: {robot.name}")
    if robot.description:
        print(robot.description.strip())
    print("\njoints:")
    print(robot.joints_frame().to_string(index=False))
    print("\nlinks:")
    print(robot.links_frame().to_string(index=False))
    sets = "".join(f", {k} ({len(v)} pose{'s' if len(v) != 1 else ''})" for k, v in robot.pose_sets.items())
    print(f"\npose sets: nominal (1 pose){sets}")
    if robot.sigma_sets:
        print(f"sigma sets: {', '.join(robot.sigma_sets)}")
    print("\nnominal pose:")
    print(_pose_text(robot.fk_internal(robot.q_nominal)))
    return 0


def cmd_fk(args) -> int:
    robot = robot_from_args(args)
    q = robot.check_q(parse_q(args.q), "--q", interface=True)
    T = robot.fk_internal(q)
    if args.json:
        # rounded to 1e-9 deg / mm so that "15" comes back as 15.0, not 14.999999999999998
        print(json.dumps({"robot": robot.name, "q_deg_mm": np.round(robot.q_to_interface(q), 9), "position_mm": T[:3, 3],
                          "rotation": T[:3, :3]}, default=json_default))
    else:
        print(_pose_text(T))
    return 0
