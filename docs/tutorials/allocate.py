"""Tutorial: tolerances for the tool-changing robot over its working region, verified, and how to read them.

    python docs/tutorials/allocate.py [--quick] [--out DIR]

``--quick`` uses small sample counts (the test suite runs it so); the page docs/tutorials/allocate.md explains
each cell.
"""

# %% setup
import argparse

parser = argparse.ArgumentParser(description="tolerance allocation tutorial")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the test suite runs)")
parser.add_argument("--out", default="tutorial_output/allocate", help="folder for the result files")
args = parser.parse_args()
N_MC = 2_000 if args.quick else 200_000          # nonlinear Monte Carlo samples per verified pose
COVERAGE_N = 2_000 if args.quick else 100_000    # fresh poses of the region for the coverage check

# %% robot
import tolalloc

robot = tolalloc.load_robot("tool_changer")
print(robot)                       # joints, links, pose sets, the working region, sigma sets
print(robot.joints_frame())        # axes, limits and nominal pose in deg / mm

# %% allocate
res = tolalloc.allocate_tolerances(
    robot,
    radius_mm=0.25,                # requirement: P(|dP| < 0.25 mm) >= 0.95 ...
    prob=0.95,                     # ... over the robot's `working` box (the default region)
    n_mc=N_MC,
    coverage_n=COVERAGE_N,
    seed=1,
)
print(res)                         # requirement, status, design, cost, verdict

# %% table
table = res.to_frame()                           # the design to build: lengths in *_mm, angles in *_deg
print(table.round({"variance_share_pct": 1})[["parameter", "nominal_mm", "tol_mm", "tol_deg", "grade",
      "variance_share_pct", "at_limit", "tol_continuous_mm", "tol_continuous_deg"]]
      .to_string(index=False, na_rep="", float_format=lambda x: f"{x:.4g}"))
print("the table holds:", res.design_note())

# %% solvers
costs = res.summary()["costs"]
print(f"certified ({costs['certified_rule']}): {costs['certified']:.4f}   "
      f"other rule ({costs['certified_other_rule']}): {costs['certified_other']:.4f}   "
      f"exact: {costs['exact']:.4f}   saving {costs['saving_pct']:.2f} %")
print(f"standard design ({costs['standard_solver']}): {costs['standard']:.4f} (+{costs['standard_premium_pct']:.2f} %)   "
      f"rounded down instead: {costs['rounded']:.4f} (+{costs['rounded_premium_pct']:.2f} %)")
print(res.summary()["standard"]["message"])

# %% region
search = res.region_search
print(f"cutting planes: {search.rounds} rounds, {len(search.active_q)} active poses, "
      f"worst linear P found {search.worst_p:.5f}, converged: {search.converged}")
print(res.coverage.message(0.95))

# %% verification
print(res.verification_frame()[["pose", "p_linear", "p_mc", "ci_low", "ci_high", "estimator", "verdict"]]
      .to_string(index=False))
print(res.verification.message())
if res.correction is not None:
    print("correction:", res.correction.message())
print("ok:", res.ok)

# %% save
files = res.save(args.out)
print("wrote", ", ".join(files))
