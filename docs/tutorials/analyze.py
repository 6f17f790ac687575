"""Tutorial: the linear variance map and the error budget of the seed paper's tolerances, and of a UR10.

    python docs/tutorials/analyze.py [--quick] [--out DIR]

The linear analysis is fast, so ``--quick`` changes nothing here; the option is accepted like in every tutorial.
"""

# %% setup
import argparse

parser = argparse.ArgumentParser(description="linear analysis tutorial")
parser.add_argument("--quick", action="store_true", help="accepted for symmetry with the other tutorials")
parser.add_argument("--out", default="tutorial_output/analyze", help="folder for the result files")
args = parser.parse_args()

# %% analyze
import tolalloc

a = tolalloc.analyze_errors(
    "tool_changer",
    poses="working",           # the 12 working poses of the robot file
    radius_mm=[0.25, 25.0],    # P(|dP| < r) for these radii
    prob=0.95,                 # and the radius holding 95 %
)
print(a)
print(a.to_frame().to_string(index=False, float_format=lambda x: f"{x:.4g}"))

# %% probabilities
lin = a.linear
print("P(|dP| < 0.25 mm) per pose:", lin.p_within(0.25).round(8))
print("P(|dP| < 25 mm) per pose:  ", lin.p_within(25.0).round(4))
print("radius for P = 0.95 [mm]:  ", lin.radius_for(0.95).round(2))

# %% budget
print(a.budget_frame(by="kind").to_string(index=False, float_format=lambda x: f"{x:.4g}"))
top = a.budget_frame().head(6)
print(top[["parameter", "kind", "share_norm_pct"]].to_string(index=False, float_format=lambda x: f"{x:.1f}"))

# %% clearance
c = tolalloc.analyze_errors("tool_changer", poses="working", clearance=True)
print(c.budget_frame(by="kind")[["kind", "share_norm_pct"]].to_string(index=False, float_format=lambda x: f"{x:.1f}"))

# %% ur10
u = tolalloc.analyze_errors("ur10", poses="working", radius_mm=0.25)
print(u)
print(u.model.to_frame().groupby("kind")[["sigma_mm", "sigma_deg"]].first())

# %% save
files = a.save(args.out)
print("wrote", ", ".join(files))
