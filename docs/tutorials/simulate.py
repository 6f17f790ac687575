"""Tutorial: nonlinear Monte Carlo of the error model, against the linear map, and the paired estimator.

    python docs/tutorials/simulate.py [--quick] [--out DIR]

``--quick`` uses small sample counts (the test suite runs it so).
"""

# %% setup
import argparse

parser = argparse.ArgumentParser(description="Monte Carlo tutorial")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the test suite runs)")
parser.add_argument("--out", default="tutorial_output/simulate", help="folder for the result files")
args = parser.parse_args()
N = 20_000 if args.quick else 1_000_000           # sampled robots

# %% simulate
import tolalloc

sim = tolalloc.simulate_errors("tool_changer", N, seed=1, radius_mm=[25.0, 35.0])
print(sim)                                          # P(|dP| < r) with 95 % intervals at the nominal pose
print(sim.to_frame().to_string(index=False, na_rep="", float_format=lambda x: f"{x:.4g}"))
probs = sim.probability_frame()                    # pose x radius: radius_mm / radius_deg, p, ci_low, ci_high
print(probs.to_string(index=False, float_format=lambda x: f"{x:.4g}"))

# %% linear
lin = tolalloc.analyze_errors("tool_changer", radius_mm=[25.0, 35.0]).linear
for r in (25.0, 35.0):
    p_mc, low, high = sim.mc.p_within[r][0]
    print(f"r = {r:g} mm: linear {lin.p_within(r)[0]:.4f}   Monte Carlo {p_mc:.4f} [{low:.4f}, {high:.4f}]")
print("std x, y, z [mm]: linear", lin.std_mm[0].round(3), " Monte Carlo", sim.mc.std_mm[0].round(3))

# %% clearance
ring = tolalloc.simulate_errors("tool_changer", N, seed=1, clearance=True, exclude=("clearance_tilt",),
                                sigma={"link_length": 0, "joint_drive": 0, "axis_deflection": 0},
                                radius_mm=[0.5, 1.0])
ring_lin = tolalloc.analyze_errors("tool_changer", clearance=True, exclude=("clearance_tilt",),
                                   sigma={"link_length": 0, "joint_drive": 0, "axis_deflection": 0}).linear
for r in (0.5, 1.0):
    print(f"radial + axial clearance only, r = {r:g} mm: linear-Gaussian {ring_lin.p_within(r)[0]:.4f}   "
          f"Monte Carlo {ring.mc.p_within[r][0][0]:.4f}")

# %% paired
design = tolalloc.allocate_tolerances("tool_changer", region="nominal", verify=False).to_frame()
sigma = dict(zip(design["parameter"], design["sigma_mm"].fillna(design["sigma_deg"])))  # sigma = t / 3, mm or deg
tight = tolalloc.simulate_errors("tool_changer", N, seed=2, sigma=sigma, radius_mm=0.25, estimator="paired")
est = tight.mc.p_estimates[0.25]
print(f"plain:  {est.p_plain[0]:.6f} [{est.plain_low[0]:.6f}, {est.plain_high[0]:.6f}]")
print(f"paired: {est.p_hat[0]:.6f} [{est.ci_low[0]:.6f}, {est.ci_high[0]:.6f}]   linear {est.p_linear[0]:.6f}")
print(est.message())

# %% save
files = sim.save(args.out)
print("wrote", ", ".join(files))
