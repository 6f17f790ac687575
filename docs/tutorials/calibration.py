# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Design for calibration
#
# A laser-tracker calibration after assembly removes most static geometric errors; only what it cannot see, and
# what changes between calibration and use, has to be held by manufacturing. This tutorial designs a 12-pose
# calibration plan for the tool-changing robot and allocates the manufacturing tolerances for the accuracy *after*
# that calibration. Concept: [design for calibration](../concepts/calibration.md).
#
# This page is the script `docs/tutorials/calibration.py` (`python docs/tutorials/calibration.py`), executed when the
# documentation was built with `--quick`: 128 candidate poses instead of 2 000, 500 simulated calibrations instead of
# 20 000 and a coverage check on 5 000 fresh poses of the working box instead of 100 000.

# %% setup
import argparse
import os
import shlex
import sys
from pathlib import Path

parser = argparse.ArgumentParser(description="design-for-calibration tutorial")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the documentation build runs)")
parser.add_argument("--out", default=os.path.join(os.environ.get("TOLALLOC_TUTORIAL_OUT", "tutorial_output"), "calibration"),
                    help="folder for the result files")
# run as a notebook (the documentation build executes this page so), the arguments are TOLALLOC_TUTORIAL_ARGS
args = parser.parse_args(shlex.split(os.environ.get("TOLALLOC_TUTORIAL_ARGS", "")) if "ipykernel" in sys.modules
                         else None)
N_CANDIDATES = 128 if args.quick else 2_000      # scrambled-Sobol candidate poses for the plan
N_MC = 500 if args.quick else 20_000             # simulated calibrations of the end-to-end check
COVERAGE_N = 5_000 if args.quick else 100_000    # fresh poses of the working box checked after the design
out = Path(args.out)

# %% [markdown]
# ## The plan

# %% plan
import tolalloc

plan = tolalloc.plan_calibration("tool_changer", 12, n_candidates=N_CANDIDATES,
                                 measurement=tolalloc.Measurement(noise_mm=0.02))    # tracker noise per coordinate
print(plan.text())
print(plan.to_frame().round(2).to_string(index=False))     # the 12 measurement poses, deg / mm
ax = plan.plot_scores()                                     # designed against random plan, no calibration, floor

# %% [markdown]
# The plan minimises the mean post-calibration position variance of the systematic errors over the 12 working
# poses (the prior is the robot's default sigma set, the paper's `table2`). The text gives, in mm², the designed
# plan's score, a random plan's, the score without calibration, the relaxation's certified lower bound and the
# floor: what measuring every candidate once would leave, with the part of it in parameter combinations no candidate
# identifies (the rest is tracker noise and joint repeatability). When that part is nearly the whole floor, as
# here, every plan leaves almost the same variance, and the designed plan's gain shows only above the floor. The
# text also **names the parameters the plan cannot identify individually**: with the tracker registration and the
# target offset estimated, a base-joint offset and base-axis tilts look exactly like a moved tracker (here `dth1`,
# `e1x`, `e1y` among them), and the three translations along the telescopic arm (`dl4`, `dl5`, `dd4`) act
# identically on every measurement, so no plan can tell them apart. Each keeps its prior along the combinations the
# plan cannot see: the number after its name is its post-calibration σ as a fraction of the manufactured one, 1.00
# for a parameter left as manufactured (`dth1`), less for one whose combinations with others are calibrated (the
# sum of the arm translations is, so `dl4`, `dl5` and `dd4` come out below 1).
#
# ## The plan file

# %% write the plan
plan_file = plan.save(out / "plan")[0]                      # plan.csv (and summary.json) in the folder
print(plan_file.read_text().splitlines()[:6])               # settings in '#' header lines, then the poses

# %% [markdown]
# A plain CSV: the settings in `#` header lines (`measurement`, `noise_mm`, `noise_deg`, `estimate`,
# `registration`), then one row per pose in deg / mm. This is what the laser-tracker operator measures, and what
# `tolalloc calplan tool_changer --n-poses 12 --out plan.csv` writes (`plan.save_plan("plan.csv")` writes that
# file alone).
#
# ## Allocate for the accuracy after calibration

# %% allocate after calibration
res = tolalloc.allocate_tolerances("tool_changer", calibration=plan_file, n_mc=N_MC,
                                   region=tolalloc.Region(coverage_n=COVERAGE_N))
print(res)

# %% [markdown]
# `calibration=plan` (the `plan_calibration` result itself) gives the same allocation without writing a file; the
# file is what the measurement team and `tolalloc allocate --calibration` need. With `calibration=` the allocation
# changes meaning: the requirement $P(|\delta p| < 0.25\ \mathrm{mm}) \ge 0.95$
# must hold after the plan is measured, the systematic errors estimated and compensated, with the random parts
# (joint repeatability, 0.0003° by default) still there. Over the robot's working box, in this order:
#
# 1. the **certified stage**: the eigenvalue rule on the post-calibration covariance, a certified local optimum (the
#    cost laws are concave in the variables the LMI is linear in);
# 2. the **exact stage**: IPOPT on the post-calibration probability itself, started from the certified design and
#    kept only when it converged, meets every pose and is not dearer — the continuous design reported
#    (`design: exact`); `solver="certified"` (`--solver certified`) stops after the certified stage;
# 3. the **standard grades** (unless `solver=tolalloc.Solver(snap=False)`): ISO 286 grades and standard steps chosen under the exact
#    post-calibration probability — the design to build;
# 4. the **end-to-end Monte Carlo** of the design to build (unless `verification=False`): simulated robots manufactured,
#    measured, calibrated by nonlinear least squares, compensated and used at its worst poses.
#
# `print(res)` says which stages ran (`stages: certified -> exact -> standard grades`), the saving against the
# design without calibration and the end-to-end verdict. There is no correction loop after calibration, so
# `correction=True`, `correction_rounds` and `scheduler` are refused rather than ignored.
#
# ## What must be held

# %% table
table = res.to_frame()
print(table[["parameter", "unit", "tol_mm", "tol_deg", "tol_no_calibration_mm", "tol_no_calibration_deg",
             "sigma_post_calibration_mm", "sigma_post_calibration_deg", "status"]].to_string(
    index=False, float_format=lambda x: f"{x:.4g}", na_rep=""))
print(table["status"].value_counts().to_string())

# %% [markdown]
# The table has the columns of the allocation without calibration, for the design to build (`tol_mm` / `tol_deg`
# and `grade` the standard one, `cost`, `variance_share_pct` of the post-calibration error, `at_limit`, the process
# limits; `tol_continuous_mm` / `_deg` the continuous design), then per parameter the tolerance without calibration,
# the σ left after calibration (each in a `_mm` / `_deg` pair) and a status — *calibrated away* (the post-calibration σ is a small share of the manufactured one:
# the calibration finds the error, so the tolerance can be loose), *loose (at t_max)* (not calibrated, but the
# process's loosest tolerance suffices; *loose (coarsest grade)*: the coarsest standard grade suffices), else *must be held* (manufacturing has to hold it; `(random)` for a part no
# calibration removes). `res.text()` (what `tolalloc allocate` prints) lists the parameters the plan cannot
# identify in two groups: those allocated tight (*must be held*; in the `--quick` run `dl1`, `dl2`, `dth1`, `dth5`,
# `e1x`, `e1y`, `e2z`) and those left loose because that suffices (there the telescopic stage's `dl4`, `dl5` at the
# coarsest ISO 286 grade of their catalogue, *loose (coarsest grade)*, and `dd4` and the wrist's `dth6`, `e6x`, `e6y`
# at their process limit, *loose (at t_max)*).
# The full study (`reports/design_for_calibration/README.md`, 2 000 candidates) gives for the designed 12-pose
# plan a certified cost of 32.6592 against 49.5630 without calibration (certified too), a saving of 34.1 %; over the
# working region the exact stage costs 31.4768 against 48.7605 without calibration (exact), a saving of 35.4 %.
# `print(res)` shows the stages of your own run (exact, then the standard grades), so its figures are of the exact
# stage, not the certified one.
#
# ## Save

# %% save
files = res.save(out / "allocation")
print("wrote", ", ".join(path.name for path in files))

# %% [markdown]
# The same files as `tolalloc allocate tool_changer --calibration plan.csv --out DIR`, with the names of the
# allocation without calibration: `tolerances.csv`, `.md`, `.tex`, `summary.json` and `verification.csv` (the
# end-to-end Monte Carlo per pose); `report=True` (`--report DIR`) adds `report.html`. What each holds:
# [reading the report](../howto/read-report.md#the-calibration-aware-allocation).
