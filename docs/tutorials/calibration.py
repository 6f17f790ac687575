"""Tutorial: design a calibration plan, then allocate the manufacturing tolerances for the accuracy after it.

    python docs/tutorials/calibration.py [--quick] [--out DIR]

``--quick`` uses fewer candidate poses and simulated calibrations (the test suite runs it so).
"""

# %% setup
import argparse
from pathlib import Path

parser = argparse.ArgumentParser(description="design-for-calibration tutorial")
parser.add_argument("--quick", action="store_true", help="small counts (what the test suite runs)")
parser.add_argument("--out", default="tutorial_output/calibration", help="folder for the result files")
args = parser.parse_args()
N_CANDIDATES = 128 if args.quick else 2_000      # scrambled-Sobol candidate poses for the plan
N_MC = 500 if args.quick else 20_000             # simulated calibrations of the end-to-end check
COVERAGE_N = 5_000 if args.quick else 100_000    # fresh poses of the working box checked after the design
out = Path(args.out)

# %% plan
import tolalloc

plan = tolalloc.plan_calibration("tool_changer", 12, n_candidates=N_CANDIDATES, noise_mm=0.02)
print(plan.text())
print(plan.to_frame().round(2).to_string(index=False))     # the 12 measurement poses, deg / mm

# %% write the plan
plan_file = out / "plan.csv"
plan.save(plan_file)
print(plan_file.read_text().splitlines()[:6])               # settings in '#' header lines, then the poses

# %% allocate after calibration
res = tolalloc.allocate_tolerances("tool_changer", calibration=plan_file, n_mc=N_MC, coverage_n=COVERAGE_N)
print(res)

# %% table
table = res.to_frame()
print(table[["parameter", "unit", "tol_mm", "tol_deg", "tol_no_calibration_mm", "tol_no_calibration_deg",
             "sigma_post_calibration_mm", "sigma_post_calibration_deg", "status"]].to_string(
    index=False, float_format=lambda x: f"{x:.4g}", na_rep=""))
print(table["status"].value_counts().to_string())

# %% save
files = res.save(out / "allocation")
print("wrote", ", ".join(files))
