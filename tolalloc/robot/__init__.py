"""The robot model: a POE chain of named links and joints, its kinematics, and its file formats."""

from tolalloc.robot.model import Joint, Link, Mass, Robot
from tolalloc.robot.kinematics import fk_poe, space_jacobian, body_jacobian, poe_prefix
from tolalloc.robot.io import load_robot, builtin_robots

__all__ = ["Joint", "Link", "Mass", "Robot", "fk_poe", "space_jacobian", "body_jacobian", "poe_prefix", "load_robot", "builtin_robots"]
