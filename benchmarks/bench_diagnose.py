"""Speed of the sim-to-real diagnosis: a 200-pose file, all five candidates (goal: < 60 s on 2 cores).

Prints the wall time of a full `diagnose` per robot and its ratio to one geometric calibration measured
in the same run.    python benchmarks/bench_diagnose.py
"""

import time

import numpy as np

import tolalloc
from tolalloc.diagnose import calibrate, diagnose, generate, measurements_from_frame

for name in ("tool_changer", "ur10"):
    robot = tolalloc.load_robot(name)
    m = measurements_from_frame(generate(robot, "joint_compliance", 200, np.random.default_rng(0)).frame, robot)
    t0 = time.perf_counter()
    calibrate(robot, m)
    t_cal = time.perf_counter() - t0
    t0 = time.perf_counter()
    d = diagnose(robot, m)
    t_diag = time.perf_counter() - t0
    print(f"{name:12s} 200 poses: diagnose {t_diag:.2f} s (goal < 60 s), calibrate {t_cal:.2f} s, "
          f"ratio {t_diag / t_cal:.1f}; effect {d.effect}")
