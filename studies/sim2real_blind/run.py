"""Independent blind benchmark of the sim-to-real diagnosis (issue 15, point 6).

The cases come from :mod:`cases` / :mod:`physics` in this folder: their own frame-walking kinematics (the
UR10 from its DH table with Hayati beta angles, the tool_changer from its link/axis chain), geometric errors
on every description parameter, their own mass model, beam sag with a telescopic stage, lagged or warm-up
thermal growth, gravity-held or approach-set backlash, once- or twice-per-revolution transmission error,
mixed effects, outliers and 40-pose cases (30 training poses). They import nothing from
``tolalloc.diagnose.effects`` or ``tolalloc.diagnose.synth``: the fitted bases never generate the data.

Per case, 75 % of the poses train (with the diagnosis's own cross-validation), 25 % are the test file. The
diagnosis sees only the tables. Scores: top-1 (first selected effect is the withheld one; for mixed cases one
of the two), top-2 (withheld effect among the first selected effect and the best-ranked candidates), false
claims on ``none``, and the final test RMS against a truth-aware reference fit (see :mod:`cases`).
Writes reports/sim2real_blind/: report.md, cases.csv, confusion.csv, confusion.png.

    python studies/sim2real_blind/run.py [--quick] [--per-label N] [--seed S]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import tolalloc  # noqa: E402
from tolalloc.diagnose import diagnose, measurements_from_frame  # noqa: E402
from tolalloc.diagnose.calibrate import fit_model  # noqa: E402
from tolalloc.report.plots.diagnose import plot_confusion  # noqa: E402

from cases import generate  # noqa: E402
from physics import EFFECT_NAMES  # noqa: E402

OUT = Path(__file__).resolve().parents[2] / "reports" / "sim2real_blind"
LABELS = (*EFFECT_NAMES, "none")
MIXED = ("joint_compliance+thermal", "backlash+link_deflection", "transmission+joint_compliance")
SMALL = ("none", "joint_compliance", "transmission")
POSES = 120


def _rms(e):
    return float(np.sqrt(np.mean(np.sum(e ** 2, axis=1))))


def score_case(robot, case, rng, folds: int = 5) -> dict:
    """Diagnose one case; scores and the reference fit."""
    P = len(case.frame)
    idx = rng.permutation(P)
    te, tr = np.sort(idx[: int(round(0.25 * P))]), np.sort(idx[int(round(0.25 * P)):])
    ftr, fte = case.frame.iloc[tr].reset_index(drop=True), case.frame.iloc[te].reset_index(drop=True)
    mtr, mte = measurements_from_frame(ftr, robot, "train"), measurements_from_frame(fte, robot, "test")
    t0 = time.perf_counter()
    d = diagnose(robot, mtr, mte, folds=folds)
    dt = time.perf_counter() - t0
    geo = d.calibration.geometric
    B = case.ref_B
    ref = fit_model(geo, mtr.q, mtr.xyz_mm, geo_index=geo.geo_index, B=B[tr] if B.shape[-1] else None)
    ref_err = mte.xyz_mm - ref.predict(mte.q, B[te] if B.shape[-1] else None)
    truth = set(case.label.split("+"))
    ranked = [c.effect for c in d.ranking if c.applicable]
    top2 = ([d.effect] if d.effect != "none" else []) + [e for e in ranked if e != d.effect]
    ba = d.before_after("test")
    return {"true": case.label, "diagnosed": d.effect, "sequence": "+".join(d.effects) or "none",
            "top1": d.effect in truth, "top2": (case.label == "none" and d.effect == "none") or bool(truth & set(top2[:2])),
            "detail": case.detail, "poses": P, "outliers": case.outliers, "magnitude_mm": case.magnitude_mm,
            "noise_mm": case.noise_mm, "noise_floor_mm": float(np.sqrt(3) * case.noise_mm), "test_rms_nominal_mm": ba["rms_mm"].iloc[0],
            "test_rms_geometric_mm": ba["rms_mm"].iloc[1], "test_rms_final_mm": ba["rms_mm"].iloc[2],
            "test_rms_reference_mm": _rms(ref_err), "seconds": dt}


def _erd_robot():
    """The Panda of example-robot-data (a URDF robot, tool link ``panda_hand``), or None when not installed."""
    import site

    from tolalloc.robot.io.urdf import load_urdf

    for base in [*site.getsitepackages(), *sys.path]:
        path = Path(base) / "cmeel.prefix/share/example-robot-data/robots/panda_description/urdf/panda.urdf"
        if path.is_file():
            return load_urdf(path, tool="panda_hand")
    return None


def _plan(per_label: int, quick: bool) -> list:
    """(label, poses) of one robot's cases: every label, mixed pairs, and 30-pose cases."""
    plan = [(lab, POSES) for lab in (*LABELS, "none") for _ in range(per_label)]
    plan += [(lab, POSES) for lab in (MIXED[:1] if quick else MIXED)]
    plan += [(lab, 30) for lab in (("none",) if quick else SMALL)]
    return plan


def _one(job):
    name, k, label, poses, seed, folds = job
    robot = ROBOTS[name]
    rng = np.random.default_rng([seed, list(ROBOTS).index(name), k])  # per case: order and jobs do not matter
    case = generate(robot, label, poses, rng)
    try:
        row = {"robot": name, **score_case(robot, case, rng, folds)}
    except tolalloc.TolallocError as exc:  # e.g. too few poses for the robot's identifiable parameters
        row = {"robot": name, "true": label, "diagnosed": "error", "sequence": "error", "top1": False, "top2": False,
               "poses": poses, "detail": str(exc).splitlines()[0]}
    row["_k"] = k
    print(f"{name:12s} {label:30s} {poses:4d} -> {row['diagnosed']:17s} final/ref "
          f"{row.get('test_rms_final_mm', np.nan) / row.get('test_rms_reference_mm', np.nan):.2f} "
          f"({row.get('seconds', np.nan):.1f} s)", flush=True)
    return row


ROBOTS = {}


def run(per_label: int, seed: int, quick: bool, folds: int, jobs: int) -> pd.DataFrame:
    ROBOTS.update({name: tolalloc.load_robot(name) for name in ("tool_changer", "ur10")})
    panda = _erd_robot()
    if panda is not None:
        ROBOTS["panda"] = panda
    todo = [(name, k, lab, poses, seed, folds) for name in ROBOTS for k, (lab, poses) in enumerate(_plan(per_label, quick))]
    if jobs > 1:
        import multiprocessing as mp

        with mp.get_context("fork").Pool(jobs) as pool:
            rows = []
            for row in pool.imap_unordered(_one, todo, chunksize=1):
                rows.append(row)
                pd.DataFrame(rows).to_csv(OUT / "cases_partial.csv", index=False, float_format="%.5g")
    else:
        rows = [_one(job) for job in todo]
    (OUT / "cases_partial.csv").unlink(missing_ok=True)
    key = {job[:2]: i for i, job in enumerate(todo)}  # back to plan order
    rows.sort(key=lambda r: key.get((r["robot"], r.pop("_k", 0)), 0))
    return pd.DataFrame(rows)


def summary_lines(df: pd.DataFrame) -> tuple[list, dict]:
    """Headline figures (top-1, top-2, false claims on none, RMS ratio) as report lines and a dict."""
    ratio = df["test_rms_final_mm"] / df["test_rms_reference_mm"]
    none = df[df["true"] == "none"]
    eff = df[df["true"] != "none"]
    fig = {"cases": len(df), "top1": float(df["top1"].mean()), "top2": float(df["top2"].mean()),
           "top1_effects": float(eff["top1"].mean()), "none_cases": len(none),
           "false_claims_on_none": int((none["diagnosed"] != "none").sum()),
           "median_final_over_reference": float(ratio.median()), "p90_final_over_reference": float(ratio.quantile(0.9))}
    checks = [("top-1 >= 85 %", fig["top1"] >= 0.85), ("no false claim on none", fig["false_claims_on_none"] == 0),
              ("median final RMS <= 1.3x reference", fig["median_final_over_reference"] <= 1.3)]
    lines = [f"* cases: {fig['cases']} ({len(none)} with no effect)",
             f"* top-1: {df['top1'].sum()}/{len(df)} = {fig['top1']:.1%} (effect cases only: {fig['top1_effects']:.1%})",
             f"* top-2: {df['top2'].sum()}/{len(df)} = {fig['top2']:.1%}",
             f"* false claims on `none`: {fig['false_claims_on_none']}/{len(none)}",
             f"* final test RMS / truth-aware reference: median {fig['median_final_over_reference']:.2f}, "
             f"90th percentile {fig['p90_final_over_reference']:.2f}", "",
             "Targets of issue 15: " + "; ".join(f"{t}: **{'met' if ok else 'NOT met'}**" for t, ok in checks)]
    return lines, fig


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="1 case per label and robot, fewer mixed / small cases")
    ap.add_argument("--per-label", type=int, default=1)
    ap.add_argument("--seed", type=int, default=20261123)
    ap.add_argument("--folds", type=int, default=3, help="CV folds per blocked scheme (time and joint space)")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes")
    ap.add_argument("--report-only", action="store_true", help="rewrite report.md from the existing cases.csv")
    a = ap.parse_args(argv)
    per = 1 if a.quick else a.per_label
    if a.report_only:
        df = pd.read_csv(OUT / "cases.csv")
    else:
        t0 = time.perf_counter()
        df = run(per, a.seed, a.quick, a.folds, a.jobs)
        df["wall_s_total"] = time.perf_counter() - t0
        OUT.mkdir(parents=True, exist_ok=True)
        for old in ("shrink.csv",):
            (OUT / old).unlink(missing_ok=True)
        df.to_csv(OUT / "cases.csv", index=False, float_format="%.5g")
    return write_report(df, a)


def write_report(df: pd.DataFrame, a) -> int:
    """report.md, confusion.csv and confusion.png from the case table."""
    single = df[~df["true"].str.contains(r"\+")]
    labels = list(LABELS)
    conf = pd.crosstab(pd.Categorical(single["true"], labels), pd.Categorical(single["diagnosed"], labels), dropna=False)
    conf.index.name, conf.columns.name = "true", "diagnosed"
    conf.to_csv(OUT / "confusion.csv")
    plot_confusion(conf.to_numpy(), labels, OUT / "confusion.png",
                   f"{len(single)} independent blind cases (single effect / none), top-1 {single['top1'].mean():.0%}")
    head, fig = summary_lines(df)
    per_robot = df.groupby("robot")[["top1", "top2"]].mean()
    df["final_over_reference"] = df["test_rms_final_mm"] / df["test_rms_reference_mm"]
    by_label = df.groupby("true").agg(cases=("top1", "size"), top1=("top1", "mean"), top2=("top2", "mean"),
                                      median_final_over_reference=("final_over_reference", "median"))
    lines = ["# Independent blind benchmark of the sim-to-real diagnosis", "",
             f"Generated by `python studies/sim2real_blind/run.py{' --quick' if a.quick else ''}` (seed {a.seed}).", "",
             "**Independence.** The measurement tables come from `studies/sim2real_blind/physics.py` and `cases.py`, "
             "which import nothing from `tolalloc.diagnose.effects`, `tolalloc.diagnose.synth`, the error model or "
             "the POE kinematics: their own frame-walking forward kinematics (UR10 from its DH table with Hayati beta "
             "angles; tool_changer from its link vectors and joint axes), geometric errors on every description "
             "parameter (0.3 mm / 0.05 deg sigma), their own mass model (rods 6-14 kg/m, motors, 0-5 kg payload), "
             "beam sag with L^4/L^3 load terms and a telescopic stage, thermal growth through a first-order lag of the "
             "logged temperature or a motor warm-up the log does not show, gravity-held or approach-set backlash, "
             "once- or twice-per-revolution transmission error, mixed effects, outliers (1-3 mm on 2 % of the poses in "
             "a quarter of the cases) and 40-pose cases. Noise sigma U(0.02, 0.05) mm.", "",
             "**Reference** (truth-aware): the diagnosis's geometric calibration model plus the first-order columns "
             "of the true effect's own amplitudes (true lag, harmonic order, side rule and masses known, values "
             "fitted), fitted on the training poses, scored on the test poses.", "",
             "## Headline", "", *head, "",
             "Per robot (top-1 / top-2): " + ", ".join(f"{r}: {v.top1:.0%} / {v.top2:.0%}" for r, v in per_robot.iterrows())
             + f". Median time per diagnosis {df['seconds'].median():.1f} s (this machine, shared).", "",
             "## Per withheld label", "", by_label.to_markdown(floatfmt=".3g"), "",
             "## Confusion (single-effect and none cases; rows: withheld, columns: diagnosed)", "", conf.to_markdown(), "",
             "![confusion](confusion.png)", "", "## All cases", "",
             df[["robot", "true", "detail", "poses", "outliers", "diagnosed", "sequence", "magnitude_mm", "noise_mm",
                 "test_rms_geometric_mm", "test_rms_final_mm", "test_rms_reference_mm"]].to_markdown(index=False, floatfmt=".3g"), ""]
    (OUT / "report.md").write_text("\n".join(lines) + "\n")
    print("\n".join(head))
    return 0


if __name__ == "__main__":
    sys.exit(main())
