"""How-to: a robot of your own, from a DH table or built in Python, analysed and allocated like a built-in one.

    python docs/howto/own_robot.py [--quick]

``--quick`` uses small sample counts (the test suite runs it so).
"""

# %% setup
import argparse

parser = argparse.ArgumentParser(description="own-robot how-to")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the test suite runs)")
args = parser.parse_args()
N_MC = 2_000 if args.quick else 100_000

# %% from a DH table
import numpy as np

import tolalloc

rows = [  # the UR10's nominal standard DH table, one row per joint (lengths in m here, angles in rad)
    {"name": "shoulder_pan_joint", "d_m": 0.1273, "a_m": 0.0, "alpha_rad": np.pi / 2},
    {"name": "shoulder_lift_joint", "d_m": 0.0, "a_m": -0.612, "alpha_rad": 0.0},
    {"name": "elbow_joint", "d_m": 0.0, "a_m": -0.5723, "alpha_rad": 0.0},
    {"name": "wrist_1_joint", "d_m": 0.163941, "a_m": 0.0, "alpha_rad": np.pi / 2},
    {"name": "wrist_2_joint", "d_m": 0.1157, "a_m": 0.0, "alpha_rad": -np.pi / 2},
    {"name": "wrist_3_joint", "d_m": 0.0922, "a_m": 0.0, "alpha_rad": 0.0},
]
arm = tolalloc.Robot.from_dh(rows, convention="standard", name="my_ur10")
print(arm)
print(arm.links_frame())                           # every non-zero DH length is a named link: d1, a2, a3, d4 ...
print(arm.fk([0, -90, 0, -90, 0, 0])[:3, 3].round(3))   # tool position [mm] at joint values in deg

# %% built in Python
from tolalloc import Joint, Link, Robot

chain = (                                          # link vectors in mm; joint limits and nominal value in deg / mm
    Link("base", np.array([0.0, 0.0, 400.0])),
    Joint.from_interface("shoulder", "revolute", np.array([0.0, 1.0, 0.0]), -90, 90, 20),
    Link("upper_arm", np.array([600.0, 0.0, 0.0])),
    Joint.from_interface("slide", "prismatic", np.array([1.0, 0.0, 0.0]), 0, 300, 100),
    Link("forearm", np.array([250.0, 0.0, 0.0])),
)                                                  # Joint(...) itself takes rad / mm: np.deg2rad(-90), ...
demo = Robot("demo_arm", chain, tool_offset_mm=np.array([0.0, 0.0, -50.0]))
print(demo)
print(demo.fk([0, 100])[:3, 3])                    # (950, 0, 350) mm: the slide adds 100 mm along x

# %% use it
working = [[20, 100], [0, 0], [45, 300]]           # poses in deg / mm
analysis = tolalloc.analyze_errors(demo, q_deg_mm=working, radius_mm=0.25)
print(analysis)
res = tolalloc.allocate_tolerances(demo, region=working, radius_mm=0.25, prob=0.95, n_mc=N_MC)
print(res)
print(res.to_frame()[["parameter", "nominal_mm", "tol_mm", "tol_deg", "grade"]].to_string(index=False, na_rep=""))
