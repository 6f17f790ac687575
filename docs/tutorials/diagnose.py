"""Tutorial: the sim-to-real diagnosis on a generated measurement set whose effect is withheld.

    python docs/tutorials/diagnose.py [--quick] [--out DIR]

``--quick`` uses fewer measured poses (the test suite runs it so).
"""

# %% setup
import argparse
from pathlib import Path

parser = argparse.ArgumentParser(description="diagnosis tutorial")
parser.add_argument("--quick", action="store_true", help="fewer poses (what the test suite runs)")
parser.add_argument("--out", default="tutorial_output/diagnose", help="folder for the result files")
args = parser.parse_args()
N_POSES = 120 if args.quick else 400             # measured poses (training and test)
out = Path(args.out)

# %% measurements
import numpy as np

import tolalloc
from tolalloc.diagnose import generate
from tolalloc.diagnose.synth import split_frame

robot = tolalloc.load_robot("tool_changer")
case = generate(robot, "joint_compliance", N_POSES, np.random.default_rng(11))
train, test = split_frame(case.frame, 0.25, np.random.default_rng(0))   # 75 % train, 25 % test, row order kept
print(train.head(3).round(3).to_string(index=False))
out.mkdir(parents=True, exist_ok=True)
train.to_csv(out / "train.csv", index=False)
test.to_csv(out / "test.csv", index=False)

# %% diagnose
d = tolalloc.diagnose_measurements(robot, out / "train.csv", out / "test.csv", folds=3)
print(d.text())

# %% read
print("selected effect:", d.effect, "   (withheld:", case.effect + ")")
print(d.to_frame().to_string(index=False, float_format=lambda x: f"{x:.4f}"))
print(d.ranking_frame().to_string(index=False, float_format=lambda x: f"{x:.4g}"))
print("guards:", list(d.diagnosis.guards) or "none fired")

# %% save
written = d.save(out / "report", json=out / "diagnosis.json", predictions=out / "predictions.csv")
print("wrote", ", ".join(written))
