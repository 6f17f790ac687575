# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Nonlinear Monte Carlo
#
# The linear map is a model of a model. The Monte Carlo samples robots with random errors and evaluates their
# exact tool poses through the perturbed chain, so it needs no linearisation and no Gaussian assumption. This
# tutorial compares the two on the paper's σ, shows where they part (a ring-shaped clearance), and estimates the
# probability of an allocated design with the paired estimator. Concepts: [variance map](../concepts/variance-map.md),
# [verification and estimators](../concepts/verification.md).
#
# This page is the script `docs/tutorials/simulate.py` (`python docs/tutorials/simulate.py`), executed when the
# documentation was built with `--quick`: 20 000 samples instead of $10^6$.

# %% setup
import argparse
import os
import shlex
import sys

parser = argparse.ArgumentParser(description="Monte Carlo tutorial")
parser.add_argument("--quick", action="store_true", help="small sample counts (what the documentation build runs)")
parser.add_argument("--out", default=os.path.join(os.environ.get("TOLALLOC_TUTORIAL_OUT", "tutorial_output"), "simulate"),
                    help="folder for the result files")
# run as a notebook (the documentation build executes this page so), the arguments are TOLALLOC_TUTORIAL_ARGS
args = parser.parse_args(shlex.split(os.environ.get("TOLALLOC_TUTORIAL_ARGS", "")) if "ipykernel" in sys.modules
                         else None)
N = 20_000 if args.quick else 1_000_000           # sampled robots

# %% [markdown]
# ## Simulate

# %% simulate
import tolalloc

sim = tolalloc.simulate_errors("tool_changer", N, seed=1, radius_mm=[25.0, 35.0])
print(sim)                                          # the sigma set sampled; P(|dP| < r) with 95 % intervals
print(sim.to_frame().to_string(index=False, na_rep="", float_format=lambda x: f"{x:.4g}"))
probs = sim.probability_frame()                    # pose x radius: radius_mm / radius_deg, p, ci_low, ci_high
print(probs.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
try:
    sim.mc.p_within[0.3]                            # a radius that was not simulated
except tolalloc.TolallocError as exc:
    print("refused:", exc)
axes = sim.plot_scatter()                           # the error cloud and its x-y, x-z, y-z densities

# %% [markdown]
# At the nominal pose (no pose given), with the `table2` σ — the robot file's default sigma set, the one every job
# uses; the first line of the printout names it, so millimetre errors are not mistaken for a broken robot (radii of
# a fraction of a millimetre would all give $P \approx 0$, and the printout would say why). The table is Table 3 of the seed paper, recomputed:
# mean, standard deviation, maximum and minimum of `dx, dy, dz`, the error norm `dp_norm`, the reach
# change `dp_reach` $= |p'| - |p|$ (what the paper calls "Δp": its mean 0.0112 and negative minima rule out the
# norm, `../shared/NOTES_SEED.md`), all in mm (`mean_mm` ... `min_mm`), and the X-Y-Z fixed Euler-angle errors
# `dalpha, dbeta, dgamma` in deg (`mean_deg` ... `min_deg`; the `unit` column says which pair a row fills). The same seed gives the same
# numbers whatever the chunk size, the number of threads or the scheduler.
#
# The probabilities are computed for the radii asked for: `probability_frame()` lists them, one row per pose and
# radius (`pose`, `error`, `radius_mm` or `radius_deg`, `p`, `ci_low`, `ci_high`), and `sim.mc.p_within[r]`
# gives one radius [mm] as an array (pose, p / CI low / CI high). A radius that was not simulated is refused with
# the simulated ones and how to ask for it (the `refused:` line); the same seed gives the same samples, so the other
# radii keep their numbers.
#
# ## Against the linear map

# %% linear
lin = tolalloc.analyze_errors("tool_changer", radius_mm=[25.0, 35.0]).linear
for r in (25.0, 35.0):
    p_mc, low, high = sim.mc.p_within[r][0]
    print(f"r = {r:g} mm: linear {lin.p_within(r)[0]:.4f}   Monte Carlo {p_mc:.4f} [{low:.4f}, {high:.4f}]")
print("std x, y, z [mm]: linear", lin.std_mm[0].round(3), " Monte Carlo", sim.mc.std_mm[0].round(3))

# %% [markdown]
# With the paper's σ (an RMS error near 18 mm) the linear-Gaussian probabilities lie inside the Monte Carlo
# intervals and the standard deviations agree to a fraction of a per cent — the regime that
# `reports/linearisation/report.md` calls *trust* (its summary: standard deviations within 0.474 %, probabilities
# within 0.00129 at 1 × the Table 2 σ).
#
# ## Where they part: a ring

# %% clearance
ring_model = tolalloc.ErrorModelOptions(clearance=True, exclude=("clearance_tilt",),
                                        sigma={"link_length": 0, "joint_drive": 0, "axis_deflection": 0})
ring = tolalloc.simulate_errors("tool_changer", N, seed=1, error_model=ring_model, radius_mm=[0.5, 1.0])
ring_lin = tolalloc.analyze_errors("tool_changer", error_model=ring_model).linear    # the same errors, linear
for r in (0.5, 1.0):
    print(f"radial + axial clearance only, r = {r:g} mm: linear-Gaussian {ring_lin.p_within(r)[0]:.4f}   "
          f"Monte Carlo {ring.mc.p_within[r][0][0]:.4f}")

# %% [markdown]
# Only the axial and radial joint clearances are left (every other σ set to 0, the clearance tilt excluded: one
# `ErrorModelOptions`, built once and given to both jobs). A
# radial clearance is a rod of random direction: its two components are uncorrelated but not Gaussian, the pair
# lies on a ring. The linear map has their second moments right but the probability wrong, and the Monte Carlo
# differs from the linear-Gaussian value by far more than its standard error. This is why the verification never
# uses the paired estimator on non-Gaussian parameters (`Verification(estimator="auto")` falls back to plain Monte Carlo there
# and says why).
#
# ## The paired estimator on an allocated design

# %% paired
design = tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False)
tight = tolalloc.simulate_errors("tool_changer", error_model=design.error_model_options(),   # the design's sigmas
                                 monte_carlo=tolalloc.MonteCarlo(n_mc=N, seed=2, estimator="paired"), radius_mm=0.25)
est = tight.mc.p_estimates[0.25]
print(f"plain:  {est.p_plain[0]:.6f} [{est.plain_low[0]:.6f}, {est.plain_high[0]:.6f}]")
print(f"paired: {est.p_hat[0]:.6f} [{est.ci_low[0]:.6f}, {est.ci_high[0]:.6f}]   linear {est.p_linear[0]:.6f}")
print(est.message())

# %% [markdown]
# The design allocated at the nominal pose puts the linear probability exactly at 0.95;
# `error_model_options()` gives its sigmas (t / 3 of each tolerance) to the simulation. Plain Monte Carlo of these
# samples has an interval several thousandths wide; the paired estimator — the exact linear $P$ plus the mean
# difference of the nonlinear and linear indicators on the same draws — an interval about ±$z^2/(n + z^2)$ when no
# sample is discordant: the variance reduction against plain Monte Carlo is printed.
#
# ## Save

# %% save
files = sim.save(args.out)
print("wrote", ", ".join(path.name for path in files))

# %% [markdown]
# The same files as `tolalloc mc tool_changer --n-mc N --seed 1 --radius-mm 25 --radius-mm 35 --out DIR`:
# `mc_table.csv`, `mc_summary.json` (keys in [the CLI reference](../cli.md#tolalloc-mc)) and `mc_scatter.png`; with
# `MonteCarlo(hist_bins=...)` also density histograms.
#
# For $10^8$ samples and more, and for a cluster, see [a cluster via Dask](../howto/dask.md).
