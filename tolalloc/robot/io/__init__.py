"""Robot files: TOML (chain or DH layout), DH CSV tables and URDF."""

from tolalloc.robot.io.load import builtin_robots, load_robot, robot_from_dict

__all__ = ["load_robot", "builtin_robots", "robot_from_dict"]
