# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # The sim-to-real diagnosis
#
# A commissioning engineer has laser-tracker measurements of a built robot and a model that misses them. This
# tutorial runs the whole diagnosis on a *generated* measurement set of the tool-changing robot whose unmodelled
# effect (joint compliance under gravity) is withheld from the diagnosis, so you can see each step and check the
# answer. The next tutorial does the same on [real UR10 data](ur10.py). Concept:
# [the diagnosis](../concepts/diagnosis.md).
#
# This page is the script `docs/tutorials/diagnose.py` (`python docs/tutorials/diagnose.py`), executed when the
# documentation was built with `--quick`: 120 poses instead of 400.
#
# ```{note}
# The generator (`tolalloc.diagnose.synth.generate`) draws the effect from the very basis the diagnosis fits, so
# finding it here shows that the machinery works — a **self-consistency** check, not evidence that the physics is
# right. The independent blind benchmark (`studies/sim2real_blind`, own kinematics and effect physics, importing
# nothing of `tolalloc`) is in `reports/sim2real_blind/report.md`.
# ```
#

# %% setup
import argparse
import os
import shlex
import sys
from pathlib import Path

parser = argparse.ArgumentParser(description="diagnosis tutorial")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the documentation build runs)")
parser.add_argument("--out", default=os.path.join(os.environ.get("TOLALLOC_TUTORIAL_OUT", "tutorial_output"), "diagnose"),
                    help="folder for the result files")
# run as a notebook (the documentation build executes this page so), the arguments are TOLALLOC_TUTORIAL_ARGS
args = parser.parse_args(shlex.split(os.environ.get("TOLALLOC_TUTORIAL_ARGS", "")) if "ipykernel" in sys.modules
                         else None)
N_POSES = 120 if args.quick else 400             # measured poses (training and test)
out = Path(args.out)

# %% [markdown]
# ## The measurements

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

# %% [markdown]
# A case has random geometric errors (the robot's sigma set), an arbitrary tracker frame, a target 50–200 mm off
# the flange, tracker noise and the withheld effect. The table has the columns of a real measurement file: `q1..q6`
# (deg / mm), `x_mm, y_mm, z_mm` in the tracker frame, `temperature_c`, `dir1..dir6` (approach directions),
# `payload_kg`, `time_s`. It is split 75 / 25 into training and test poses and written as two CSV files — what you
# would have from a tracker after converting its export.
#
# ## Diagnose

# %% diagnose
d = tolalloc.diagnose_measurements(robot, out / "train.csv", out / "test.csv", folds=3)
print(d.text())

# %% [markdown]
# `d.text()` is what `tolalloc diagnose tool_changer --train train.csv --test test.csv` prints:
#
# - `effect:` the selected effect (or `none`);
# - the **test** block: RMS, 95th percentile and maximum of the 3-D error of the nominal model (registration and
#   target offset only), the geometric model (plus the identifiable geometric errors) and the final model (plus
#   the effect), with the shrink against nominal — on poses that were never fitted;
# - the same from the blocked cross-validation of the training file;
# - the worst test poses with their predicted 1-σ and 95 % radius and the extrapolation flag, and the
#   predicted-uncertainty check (the share of test residuals inside their 95 % radius);
# - `GUARD:` lines for fits not to trust, `note: finding:` lines for well-identified deviations from nominal;
# - the ranking of the candidates by their clipped held-out RMS (the selection's score: 3-D errors clipped at 2.5 x
#   the geometric model's median, so a few gross errors cannot decide), the unclipped RMS beside it, the Wilcoxon
#   p-value, the gain, and why a candidate is not significant.
#
# ## Read the result

# %% read
print("selected effect:", d.effect, "   (withheld:", case.effect + ")")
print(d.to_frame().to_string(index=False, float_format=lambda x: f"{x:.4f}"))
print(d.ranking_frame().to_string(index=False, float_format=lambda x: f"{x:.4g}"))
print("guards:", list(d.diagnosis.guards) or "none fired")
ax = d.plot_before_after()                      # held-out RMS, p95 and max of the three models (log scale)

# %% [markdown]
# The geometric calibration removes nearly all of the nominal model's millimetres (the geometric errors and the
# unknown target offset); the effect removes much of what is left. More than one candidate can be significant
# against the geometric model on its own (the ranking shows each one's p-value and gain); the one with the lowest
# clipped held-out RMS is selected, the others are then tested *on top of it* and kept only if they still help. The ranking frame has each candidate's cross-validation and test RMS, its
# p-value, gain, number of parameters and the variant chosen on the training residual.
#
# ## Save

# %% save
written = d.save(out / "report", report=True, json=out / "diagnosis.json", predictions=out / "predictions.csv")
print("wrote", ", ".join(str(path.relative_to(out)) for path in written))

# %% [markdown]
# The same as `tolalloc diagnose … --report DIR --json diagnosis.json --predictions predictions.csv`: a report
# folder (`report.md`, CSV tables, figures, and with `report=True` the self-contained `report.html`,
# [shown here](../howto/html-reports.md)), the JSON result and the final model's predictions for every test row
# with their 1-σ and 95 % radius. [Reading the report](../howto/read-report.md) lists the keys.
