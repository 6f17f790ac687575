"""tolalloc: tolerance allocation, verification and sim-to-real diagnosis for serial robots.

Units inside the library: lengths in mm, angles in rad. Joint values at the
interface (robot files, CLI, CSV) are in degrees (revolute) and mm (prismatic).
"""

from tolalloc.exceptions import TolallocError
from tolalloc.robot import Joint, Link, Mass, Robot, body_jacobian, builtin_robots, fk_poe, load_robot, space_jacobian

__version__ = "0.1.0"

__all__ = [
    "TolallocError",
    "Joint",
    "Link",
    "Mass",
    "Robot",
    "load_robot",
    "builtin_robots",
    "fk_poe",
    "space_jacobian",
    "body_jacobian",
]
