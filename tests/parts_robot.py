"""A small arm with catalogue slots for the bought-parts tests: two horizontal revolute joints (gravity loads), a wrist
about the vertical, link sections, a payload and a mount."""

import textwrap

import tolalloc

ARM = """
name = "arm3"
gravity = [0, 0, -1]
[[chain]]
link = "base"
vector_mm = [0, 0, 200]
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 1, 0]
limits_deg = [-60, 60]
[[chain]]
link = "upper"
vector_mm = [300, 0, 0]
[[chain]]
joint = "j2"
type = "revolute"
axis = [0, 1, 0]
limits_deg = [-90, 90]
[[chain]]
link = "fore"
vector_mm = [250, 0, 0]
[[chain]]
joint = "j3"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-180, 180]
[[chain]]
link = "tool"
vector_mm = [0, 0, -50]

[[masses]]
link = "upper"
mass_kg = 2.0
com_mm = [150, 0, 200]
[[masses]]
link = "fore"
mass_kg = 1.5
com_mm = [425, 0, 200]

[regions.work]
q_min_deg_mm = [-30, -60, -90]
q_max_deg_mm = [30, 30, 90]

[components.payload]
rated_kg = 1.0
[components.mount]
tilt_stiffness_Nm_per_rad = 1.0e6
[components.links.upper]
section = "tube"
outer_diameter_mm = 50
wall_mm = 3
material = "aluminium"
[components.joints.j1]
reducer = { family = "HD-CSG-17-100" }
bearing = { options = ["ISO492-P0", "ISO492-P5"], bore_mm = 40, span_mm = 40 }
motor = { part = "SERVO-200W" }
[components.joints.j2]
reducer = { family = "HD-CSG-14-100" }
encoder = { part = "MOTOR-ENC-STD" }
"""


def arm(tmp_path, extra: str = "", name: str = "arm3.toml"):
    p = tmp_path / name
    p.write_text(ARM + textwrap.dedent(extra))
    return tolalloc.load_robot(str(p))


#: Standard classes for the angles (listed options: a small program, quick to solve and to enumerate), as a costs
#: mapping; :func:`write_classes` writes the same classes as a costs file for the jobs.
CLASSES = {"kinds": {k: {"classes_deg": {"A": 0.002, "B": 0.005, "C": 0.01, "D": 0.03, "E": 0.1}}
                     for k in ("joint_drive", "axis_deflection")}}


def write_classes(path):
    """:data:`CLASSES` as a costs file (TOML) at ``path``; returns the path."""
    tables = [f"[kinds.{kind}.classes_deg]\n" + "".join(f"{g} = {v}\n" for g, v in c["classes_deg"].items())
              for kind, c in CLASSES["kinds"].items()]
    path.write_text("".join(tables))
    return path
