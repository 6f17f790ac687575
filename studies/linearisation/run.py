"""Linear-Gaussian map versus nonlinear Monte Carlo for the tool_changer.

For each error case (Table 2 sigma; Table 2 plus joint clearance; radial clearance alone) and each
sigma scale (x1, x3, x10, x30, x100 of the case's sigma), at three working poses, compare

* standard deviations of dx, dy, dz and the rms |dp| (linear ``J S Jᵀ`` vs exact MC),
* correlations (xy, xz, yz),
* probabilities P(|dp| < r) at the radii where the MC gives about 0.5, 0.9 and 0.99
  (linear: Gaussian with the linear covariance, exact integral),
* the MC mean (the linear map predicts zero).

Writes reports/linearisation/: report.md, comparison.csv, summary.csv, linearisation.png.
Usage: ``python studies/linearisation/run.py [--quick]``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc import load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.linear.covariance import linear_map
from tolalloc.montecarlo.run import run_mc
from tolalloc.report.plots.linear import linearisation_figure

OUT = Path(__file__).resolve().parents[2] / "reports" / "linearisation"
SCALES = (1, 3, 10, 30, 100)
POSES = (1, 6, 11)  # pose numbers in the working set (from 1, as in every table)
PROBS = (0.5, 0.9, 0.99)


def cases(robot):
    return {
        "table2": build_error_model(robot, "table2"),
        "table2+clearance": build_error_model(robot, "table2", clearance=True),
        "radial clearance only": build_error_model(
            robot, "table2", clearance=True,
            exclude=("link_length", "joint_drive", "axis_deflection", "clearance_axial", "clearance_tilt")),
    }


def mc_radii(model, q, n, seed):
    """Radii where the MC probability is about PROBS: quantiles of |dp| from a pilot run."""
    pilot = run_mc(model, q, min(n, 20000), seed + 1, keep_samples=min(n, 20000))
    d = np.asarray(pilot.samples["norm_mm"])
    return [float(np.quantile(d, p)) for p in PROBS]


def compare(model, q, n, seed):
    lin = linear_map(model, q)
    radii = []
    for i in range(len(q)):
        radii.append(mc_radii(model, q[i], n, seed + 10 * i))
    flat = sorted({r for rs in radii for r in rs})
    mc = run_mc(model, q, n, seed, radii_mm=flat)
    rows = []
    se_std = mc.std_mm / np.sqrt(2 * (n - 1))
    rms_mc = np.sqrt(mc.norm_mm[:, 0] ** 2 + mc.norm_mm[:, 1] ** 2)
    for i in range(len(q)):
        def add(quantity, linear, mcv, se, r=np.nan):
            rows.append({"pose": POSES[i], "quantity": quantity, "r_mm": r, "linear": float(linear), "mc": float(mcv),
                         "mc_se": float(se)})
        for a, ax in enumerate("xyz"):
            add(f"std_{ax}_mm", lin.std_mm[i, a], mc.std_mm[i, a], se_std[i, a])
        add("rms_mm", lin.rms_mm[i], rms_mc[i], rms_mc[i] / np.sqrt(2 * n))
        c_mc = mc.cov_mm2[i] / np.outer(mc.std_mm[i], mc.std_mm[i])
        c_lin = lin.corr[i]
        for a, b, nm in ((0, 1, "xy"), (0, 2, "xz"), (1, 2, "yz")):
            add(f"corr_{nm}", c_lin[a, b], c_mc[a, b], (1 - c_mc[a, b] ** 2) / np.sqrt(n))
        for a, ax in enumerate("xyz"):
            add(f"mean_{ax}_mm", 0.0, mc.mean_mm[i, a], mc.std_mm[i, a] / np.sqrt(n))
        for r in radii[i]:
            p, lo, hi = mc.p_within[r][i]
            add("p_within", lin.p_within(r)[i], p, (hi - lo) / 3.92, r)
    return pd.DataFrame(rows)


def summarise(table):
    out = []
    for (case, scale), d in table.groupby(["case", "scale"], sort=False):
        s = d[d["quantity"].str.match(r"std_|rms")]
        c = d[d["quantity"].str.startswith("corr_")]
        p = d[d["quantity"] == "p_within"]
        m = d[d["quantity"].str.startswith("mean_")]
        std_mc = d[d["quantity"].str.startswith("std_")].set_index(["pose", "quantity"])["mc"]
        mean_rel = [abs(row.mc) / std_mc[(row.pose, row.quantity.replace("mean", "std"))] for row in m.itertuples()]
        rel = (s["linear"] / s["mc"] - 1).abs()
        out.append({
            "case": case, "scale": scale,
            "rms_mc_mm": d[d["quantity"] == "rms_mm"]["mc"].max(),
            "max_rel_std_err_pct": 100 * rel.max(),
            "max_std_err_in_se": ((s["linear"] - s["mc"]).abs() / s["mc_se"]).max(),
            "max_corr_abs_err": (c["linear"] - c["mc"]).abs().max(),
            "max_p_abs_err": (p["linear"] - p["mc"]).abs().max(),
            "max_p_err_in_se": ((p["linear"] - p["mc"]).abs() / p["mc_se"]).max(),
            "max_mean_over_std": max(mean_rel),
        })
    return pd.DataFrame(out)


def verdict(row):
    ok = row.max_rel_std_err_pct < 2 and row.max_p_abs_err < 0.01
    return "trust" if ok else ("approximate" if row.max_rel_std_err_pct < 10 and row.max_p_abs_err < 0.05 else "breaks")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="20k samples instead of 200k (noisier)")
    args = ap.parse_args(argv)
    n = 20_000 if args.quick else 200_000
    seed = 2024
    t0 = time.perf_counter()
    robot = load_robot("tool_changer")
    q = robot.poses("working")[[i - 1 for i in POSES]]
    frames = []
    for case, model in cases(robot).items():
        # pure translations are exactly linear: the radial-clearance case does not change with scale
        for scale in (SCALES if case != "radial clearance only" else (1,)):
            df = compare(model.with_sigma(model.sigma * scale), q, n, seed)
            df.insert(0, "scale", scale)
            df.insert(0, "case", case)
            frames.append(df)
            print(f"{case:24s} x{scale:<4d} done ({time.perf_counter() - t0:.0f} s)", flush=True)
    table = pd.concat(frames, ignore_index=True)
    summary = summarise(table)
    summary["verdict"] = [verdict(r) for r in summary.itertuples()]
    OUT.mkdir(parents=True, exist_ok=True)
    table.to_csv(OUT / "comparison.csv", index=False, float_format="%.6g")
    summary.to_csv(OUT / "summary.csv", index=False, float_format="%.5g")
    import matplotlib.pyplot as plt

    fig = linearisation_figure(table, OUT / "linearisation.png", dpi=90)
    plt.close(fig)
    write_report(table, summary, n, seed, q, robot, time.perf_counter() - t0)
    print(f"wrote {OUT} in {time.perf_counter() - t0:.0f} s")


def write_report(table, summary, n, seed, q, robot, elapsed):
    fmt = lambda x: f"{x:.3g}"  # noqa: E731
    s = summary.copy()
    nominal = table[(table["scale"] == 1) & (table["pose"] == POSES[0])]
    lines = [
        "# Linear-Gaussian map versus nonlinear Monte Carlo (tool_changer)",
        "",
        f"Generated by `python studies/linearisation/run.py{' --quick' if n < 200_000 else ''}` "
        f"(n = {n} MC samples per case and scale, seed {seed}, {elapsed:.0f} s). Poses: working-set poses "
        f"{list(POSES)} (q = {'; '.join(', '.join(f'{v:g}' for v in row) for row in np.round(robot.q_to_interface(q), 1))} deg/mm).",
        "",
        "Linear: `linear_map` (analytic error Jacobian, covariance J S Jᵀ; inputs by their second moments) and "
        "`p_within_radius` (exact Gaussian ball probability). MC: `run_mc` (exact perturbed forward kinematics). "
        "Radii for the probabilities are where the MC gives about 0.5, 0.9, 0.99 (pilot-run quantiles). "
        "`*_in_se` columns divide the difference by the MC standard error; `max_mean_over_std` is the largest "
        "|MC mean| / MC std (the linear map predicts zero mean). Verdict: *trust* = std within 2 % and "
        "P within 0.01; *approximate* = within 10 % and 0.05; else *breaks*.",
        "",
        "## Summary (worst over poses and directions)",
        "",
        s.to_markdown(index=False, floatfmt=".3g"),
        "",
        "## Table 2 sigma, nominal working pose: linear vs MC",
        "",
        nominal[["case", "quantity", "r_mm", "linear", "mc", "mc_se"]].to_markdown(index=False, floatfmt=".4g"),
        "",
        "Full per-pose numbers: `comparison.csv`. Figure: `linearisation.png` (left: worst relative std error; "
        "middle: worst correlation error; right: probability error with 2-s.e. bars).",
        "",
        "![linear vs MC](linearisation.png)",
        "",
        "## Why and where it breaks",
        "",
    ]
    t2 = s[(s["case"] == "table2")].set_index("scale")
    rc = s[(s["case"] == "radial clearance only")].set_index("scale")
    t2c = s[(s["case"] == "table2+clearance")].set_index("scale")
    ex = table[(table["case"] == "table2") & (table["pose"] == POSES[-1])].set_index(["scale", "quantity"])
    lines += [
        f"* **At the paper's sigma the linear map is exact for practical purposes**: the largest std error is "
        f"{fmt(t2.loc[1, 'max_rel_std_err_pct'])} % (within {fmt(t2.loc[1, 'max_std_err_in_se'])} MC standard errors), "
        f"correlations agree to {fmt(t2.loc[1, 'max_corr_abs_err'])} and probabilities to {fmt(t2.loc[1, 'max_p_abs_err'])}. "
        "The angular errors are a few tenths of a degree, so the neglected second-order terms "
        "(~ L·θ²/2 against L·θ) are of order 1e-3 of the first-order ones or less.",
        f"* **Growth with sigma**: the neglected second-order terms grow like sigma² while the first-order ones grow "
        f"like sigma, so the relative std error grows roughly like sigma²: ×3 gives "
        f"{fmt(t2.loc[3, 'max_rel_std_err_pct'])} %, ×10 {fmt(t2.loc[10, 'max_rel_std_err_pct'])} % (P still within "
        f"{fmt(t2.loc[10, 'max_p_abs_err'])}), ×30 {fmt(t2.loc[30, 'max_rel_std_err_pct'])} % and "
        f"{fmt(t2.loc[30, 'max_p_abs_err'])} on P, ×100 (drive errors of 15-50°) "
        f"{fmt(t2.loc[100, 'max_rel_std_err_pct'])} % and {fmt(t2.loc[100, 'max_p_abs_err'])}. "
        "The rotations bend the Gaussian cloud into a banana: points move on arcs, not on tangent lines, so the "
        "linear map overestimates the spread across the arm (sin θ < θ) and misses the pull back towards the joint "
        "axes along the arm (L(1 - cos θ), second order; the arm points along +y). "
        f"At pose {POSES[-1]} (arm along y) and ×100: std y linear {fmt(ex.loc[(100, 'std_y_mm'), 'linear'])} mm vs "
        f"MC {fmt(ex.loc[(100, 'std_y_mm'), 'mc'])} mm, std x {fmt(ex.loc[(100, 'std_x_mm'), 'linear'])} vs "
        f"{fmt(ex.loc[(100, 'std_x_mm'), 'mc'])} mm, MC mean y {fmt(ex.loc[(100, 'mean_y_mm'), 'mc'])} mm "
        f"(up to {fmt(t2.loc[100, 'max_mean_over_std'])} std over the poses; {fmt(t2.loc[1, 'max_mean_over_std'])} at ×1); "
        "correlations drift the same way.",
        f"* **Joint clearance** (Table 4, tilt sigma 0.0087 rad = 0.5°, twice the deflections) makes the nonlinearity "
        f"appear earlier: at ×10 the std error is {fmt(t2c.loc[10, 'max_rel_std_err_pct'])} % "
        f"(vs {fmt(t2.loc[10, 'max_rel_std_err_pct'])} % without clearance); at ×1 it is "
        f"{fmt(t2c.loc[1, 'max_rel_std_err_pct'])} % and P is within {fmt(t2c.loc[1, 'max_p_abs_err'])}. "
        "The **radial clearance alone** is the case where the Gaussian assumption, not the "
        "linearisation, fails: its rods are pure translations, so the map is exactly linear (the std agrees within "
        f"MC noise, {fmt(rc.loc[1, 'max_rel_std_err_pct'])} %, at any scale), but each rod has a ring-shaped "
        "(non-Gaussian) distribution and the probabilities "
        f"from a Gaussian with that covariance are off by up to {fmt(rc.loc[1, 'max_p_abs_err'])} "
        f"({fmt(rc.loc[1, 'max_p_err_in_se'])} MC standard errors) -- only a few ring-shaped sources add up, so the "
        "central limit theorem has not taken over. Geometric errors mixed in (table2+clearance) dilute it.",
        "* **When to trust it**: rotation-type sigma up to about 1° (×3 here) keeps the std within 2 % and P within "
        "0.01 -- the whole regime of tolerance allocation, where the target is sub-millimetre and the allocated "
        "sigma are far below Table 2's. Beyond that, or when a "
        "few non-Gaussian (ring, uniform) sources dominate and a probability is needed, verify with `tolalloc mc`.",
        "",
    ]
    (OUT / "report.md").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
