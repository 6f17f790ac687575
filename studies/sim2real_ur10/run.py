"""Sim-to-real diagnosis of the real UR10 laser-tracker data (IPA, ../shared/data/ipa-ur10).

Four runs, each a full `diagnose` (registration + target offset + identifiable geometry, then the five
candidate effects scored on held-out poses):

* within session C (random poses): 75 % train / 25 % test, same tracker frame;
* within session A (grid, every k-th row): 75 % / 25 %;
* across sessions A -> C and C -> A: train on one session, test on the other; the test session's tracker
  registration and probe offset are re-estimated on one half of it and scored on the other (two-fold),
  because the tracker and probe were set up anew.

Writes reports/sim2real_ur10/: report.md, summary.csv and per-run tables and figures (prefix = run name).
The data are read from ../shared/data and never copied.

    python studies/sim2real_ur10/run.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import tolalloc
from tolalloc.diagnose import diagnose, measurements_from_frame
from tolalloc.report.diagnosis import write_report
from tolalloc.diagnose.synth import split_frame

sys.path.insert(0, str(Path(__file__).resolve().parent))
from convert_ur10 import DATA, series  # noqa: E402

OUT = Path(__file__).resolve().parents[2] / "reports" / "sim2real_ur10"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="subsample both sessions more strongly")
    a = ap.parse_args(argv)
    if not DATA.is_dir():
        print(f"data folder {DATA} not found; nothing to do", file=sys.stderr)
        return 1
    robot = tolalloc.load_robot("ur10")
    step_a, step_c = (24, 4) if a.quick else (6, 1)
    A_all, C_all = series("A"), series("C")
    A = A_all.iloc[::step_a].reset_index(drop=True)
    C = C_all.iloc[::step_c].reset_index(drop=True)
    rng = np.random.default_rng(7)
    runs = {}
    for name, df in (("within_C", C), ("within_A", A)):
        tr, te = split_frame(df, 0.25, rng)
        runs[name] = (tr, te, "same")
    runs["across_A_to_C"] = (A, C, "refit")
    runs["across_C_to_A"] = (C, A, "refit")
    OUT.mkdir(parents=True, exist_ok=True)
    rows, sections = [], []
    for name, (tr, te, frame) in runs.items():
        t0 = time.perf_counter()
        d = diagnose(robot, measurements_from_frame(tr, robot, f"{name}:train"),
                     measurements_from_frame(te, robot, f"{name}:test"), test_frame=frame)
        dt = time.perf_counter() - t0
        write_report(d, OUT, title=f"UR10 {name}", prefix=f"{name}_")
        bt = d.before_after("test")
        bh = d.before_after("heldout")
        rows.append({"run": name, "train_poses": len(tr), "test_poses": len(te), "test_frame": frame,
                     "effects": "+".join(d.effects) or "none",
                     "test_mean_nominal_mm": bt["mean_mm"].iloc[0], "test_mean_geometric_mm": bt["mean_mm"].iloc[1],
                     "test_mean_final_mm": bt["mean_mm"].iloc[2],
                     "test_rms_nominal_mm": bt["rms_mm"].iloc[0], "test_rms_geometric_mm": bt["rms_mm"].iloc[1],
                     "test_rms_final_mm": bt["rms_mm"].iloc[2], "test_max_nominal_mm": bt["max_mm"].iloc[0],
                     "test_max_final_mm": bt["max_mm"].iloc[2],
                     "cv_rms_geometric_mm": d.before_after("cv")["rms_mm"].iloc[1],
                     "heldout_rms_final_mm": bh["rms_mm"].iloc[2],
                     "test_shrink_geometric_vs_nominal_pct": bt["rms_shrink_pct"].iloc[1],
                     "test_shrink_final_vs_nominal_pct": bt["rms_shrink_pct"].iloc[2],
                     "seconds": dt})
        rk = d.ranking_frame()[["effect", "heldout_rms_mm", "gain_pct", "p_value", "significant", "reason"]]
        top = d.where.trends.head(3)
        sections += [f"### {name}", "",
                     f"Train {len(tr)} poses, test {len(te)} poses (test frame: {frame}); {dt:.0f} s. Selected: "
                     f"**{'+'.join(d.effects) or 'none'}**. Full report: [{name}_report.md]({name}_report.md).", "",
                     bt[["model", "label", "rms_mm", "mean_mm", "p95_mm", "max_mm", "rms_shrink_pct"]].to_markdown(index=False, floatfmt=".4g"),
                     "", "Candidates (first step, held-out = CV + test):", "", rk.to_markdown(index=False, floatfmt=".4g"), "",
                     "Strongest residual trends after geometric calibration: "
                     + "; ".join(f"{r.feature} (Spearman {r.spearman_norm:+.2f}, |r| of a component {r.max_abs_corr_component:.2f})"
                                 for r in top.itertuples()) + ".", "", f"![where]({name}_where.png)", ""]
        print(f"{name}: {'+'.join(d.effects) or 'none'} ({dt:.0f} s)", flush=True)
    summary = pd.DataFrame(rows)
    summary.to_csv(OUT / "summary.csv", index=False, float_format="%.5g")
    s = summary.set_index("run")
    tA, tC = A_all["temperature_c"], C_all["temperature_c"]
    wc, xa = s.loc["within_C"], s.loc["across_A_to_C"]
    unexplained = 100 * s["test_rms_final_mm"] / s["test_rms_nominal_mm"]
    lines = ["# Sim-to-real diagnosis of a real UR10 (IPA laser-tracker data)", "",
             f"Generated by `python studies/sim2real_ur10/run.py{' --quick' if a.quick else ''}`. Data: "
             f"Series A (grid, every {step_a}. row of {len(A_all):,}) and Series C (random poses, every {step_c}. row of {len(C_all):,}), "
             "converted by `convert_ur10.py` (joints rad -> deg; `dir` columns from the row order, an assumption). "
             f"Temperature: A {tA.min():.2f}-{tA.max():.2f} degC, C {tC.min():.2f}-{tC.max():.2f} degC.", "",
             "Mean / RMS / max are of the 3-D position error on the **test** poses [mm].", "",
             summary[["run", "train_poses", "test_poses", "effects", "test_mean_nominal_mm", "test_mean_geometric_mm",
                      "test_mean_final_mm", "test_rms_nominal_mm", "test_rms_geometric_mm", "test_rms_final_mm",
                      "test_max_nominal_mm", "test_max_final_mm"]].to_markdown(index=False, floatfmt=".3g"), "",
             "## What is and is not explained", "",
             f"* Nominal model with only the tracker registration and probe offset fitted: mean error "
             f"{s['test_mean_nominal_mm'].min():.2f}-{s['test_mean_nominal_mm'].max():.2f} mm on the test poses (the data's "
             "README quotes 0.7-1.0 mm).",
             f"* Geometric calibration within a session: test RMS {s.loc['within_C', 'test_rms_nominal_mm']:.3f} -> "
             f"{wc['test_rms_geometric_mm']:.3f} mm (C) and {s.loc['within_A', 'test_rms_nominal_mm']:.3f} -> "
             f"{s.loc['within_A', 'test_rms_geometric_mm']:.3f} mm (A): "
             f"{s.loc['within_C', 'test_shrink_geometric_vs_nominal_pct']:.0f} % and "
             f"{s.loc['within_A', 'test_shrink_geometric_vs_nominal_pct']:.0f} % shrink.",
             f"* Across sessions (model of A scored on C after re-registering C): test RMS "
             f"{xa['test_rms_nominal_mm']:.3f} -> {xa['test_rms_geometric_mm']:.3f} mm (geometric) -> "
             f"{xa['test_rms_final_mm']:.3f} mm (final); C -> A: {s.loc['across_C_to_A', 'test_rms_nominal_mm']:.3f} -> "
             f"{s.loc['across_C_to_A', 'test_rms_geometric_mm']:.3f} -> {s.loc['across_C_to_A', 'test_rms_final_mm']:.3f} mm.",
             "* Selected effects per run: " + "; ".join(f"{r}: {e}" for r, e in s["effects"].items()) + ".",
             "* Test-RMS shrink from adding the selected effect(s) on top of the geometric model: "
             + ", ".join(f"{r} {100 * (1 - v.test_rms_final_mm / v.test_rms_geometric_mm):.0f} %" for r, v in s.iterrows())
             + ". Where the geometric model of one session does not transfer to the other (geometric test RMS not "
             "below nominal), the gravity-type effect is the part that does transfer.",
             "* Left unexplained after the final model (test RMS as % of nominal): "
             + ", ".join(f"{r} {u:.0f} %" for r, u in unexplained.items()) + ". None of the five candidate effects "
             "removes the bulk of the remaining error; what remains is not a gravity, backlash, thermal or "
             "2nd/3rd-harmonic pattern this library can model (candidates: pose-dependent errors of higher order, "
             "probe orientation/measurement effects, session-to-session changes of the robot).",
             "* Thermal growth cannot be tested within a session with confidence: the temperature varies by less "
             "than 1 K; across sessions a constant temperature offset is absorbed by the re-registration.",
             "* `dir` (approach direction) columns are reconstructed from the row order, not recorded, so the "
             "backlash test is only indicative.", "",
             "## Runs", "", *sections]
    (OUT / "report.md").write_text("\n".join(lines) + "\n")
    print(f"-> {OUT / 'report.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
