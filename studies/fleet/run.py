"""From a measured robot back to the design (issue 45): a simulated fleet pooled against its known factory, and the
real UR10 data used as the diagnosis's model is meant to be used.

1. **Simulated fleet** (``generator.py``: UR10-like robots with known shifts and spreads of their DH parameters, its
   own kinematics, no code shared with the fit): N robots measured on one pose plan, each diagnosed
   (``tolalloc.diagnose_measurements``, two worker processes), pooled (``tolalloc.fleet``) against an allocation of
   the UR10 (certified, r = 0.5 mm, p = 0.95). The known per-parameter shifts and spreads are carried onto the
   identifiable combinations through the generator's own Jacobian (finite differences of its kinematics) and the
   diagnosis's identification Jacobian; the pooled means and spreads are compared with them -- and with the values of
   the robots actually drawn (sampling). Replications with other robot draws give the intervals' coverage. The
   allocation is re-solved with the capability the fleet shows (shift kept / removed by a design change).
2. **UR10** (``../shared/data/ipa-ur10``, read as ``studies/sim2real_ur10`` reads it; nothing copied):
   a. compensation on the random 75/25 split of series C (every second row, seed 7: the sim2real study's random_C
      run): the held-out poses'
      programs (their joint values) compensated to the nominal robot's positions there, and to the measured points;
      the landing error of the compensated joints estimated from the held-out measurement (the measured point moved
      by the model's Jacobian times the joint correction: first order in a sub-degree correction); the exported robot
      files' forward kinematics against the identified geometry;
   b. the two sessions (series A every 12th row, C every second row, as the sim2real study reads them) as repeated
      measurements of one robot: each diagnosed on those poses,
      pooled as a fleet of two; per parameter the session difference against its sampling sd (what is stable between
      sessions and what is not).

Writes reports/fleet/: report.md, sim_fleet.csv, sim_coverage.csv, sim_reallocation.csv, ur10_compensation.csv,
ur10_sessions.csv, run_info.json, spread.png (``--report-only`` rewrites report.md from them).

    python studies/fleet/run.py [--quick] [--robots N] [--replications R]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
import generator  # noqa: E402

OUT = ROOT / "reports" / "fleet"
N_POSES = 60
#: Every STEP-th row of series A and C, as ``studies/sim2real_ur10/run.py`` reads the sessions (its full run).
STEP_A, STEP_C = 12, 2
RADIUS_MM = 0.5


def _diagnose(df: pd.DataFrame):
    """One robot's diagnosis (a worker process: one BLAS thread)."""
    import tolalloc

    return tolalloc.diagnose_measurements("ur10", df, folds=3, progress=False).diagnosis


def diagnose_fleet(frames: list, workers: int) -> list:
    with ProcessPoolExecutor(max_workers=workers) as ex:
        return list(ex.map(_diagnose, frames))


def truth_on_combinations(pool, shift, spread) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The generator's population shift and spread on the pool's identifiable combinations, and the map ``G``."""
    from dataclasses import replace

    from tolalloc.diagnose.uncertainty import point_jacobian

    m, k = pool.robots[0].model, pool.n_geometric
    fit = replace(m.fit, geo_index=np.array([m.fit.model.index(nm) for nm in pool.names[:k]]))
    A = np.einsum("ji,pjk->pik", fit.R, point_jacobian(fit, m.train.q)).reshape(3 * len(m.train.q), -1)
    scale = np.linalg.norm(A, axis=0)
    coef, *_ = np.linalg.lstsq(A / scale, generator.truth_map(m.train.q), rcond=None)
    G = (coef / scale[:, None])[9:9 + k]
    return G @ shift, np.sqrt(np.einsum("jk,k,jk->j", G, spread ** 2, G)), G


def simulated(n_robots: int, workers: int, allocation, seed: int = 2) -> dict:
    import tolalloc

    fl = generator.make_fleet(n_robots, N_POSES, seed=seed)
    t0 = time.perf_counter()
    diags = diagnose_fleet(fl["frames"], workers)
    res = tolalloc.fleet(diags, names=[f"robot {i + 1}" for i in range(n_robots)], allocation=allocation)
    seconds = time.perf_counter() - t0
    pool = res.pool
    mu, tau, G = truth_on_combinations(pool, fl["shift"], fl["spread"])
    k = pool.n_geometric
    idx = [int(r.name.split()[-1]) - 1 for r in pool.robots]
    drawn = fl["errors"][idx] @ G.T
    tab = res.to_frame().iloc[:k].copy()
    tab["true_mean"], tab["true_spread"] = mu, tau
    tab["drawn_mean"], tab["drawn_spread"] = drawn.mean(0), drawn.std(0, ddof=1)
    tab["spread_ratio"] = tab["spread"] / tau
    tab["spread_within_20pct"] = np.abs(tab["spread_ratio"] - 1) <= 0.2
    tab["true_mean_in_interval"] = (tab["mean_lo"] <= mu) & (mu <= tab["mean_hi"])
    tab["true_spread_in_interval"] = (tab["spread_lo"] <= tau) & (tau <= tab["spread_hi"])
    tab["drawn_spread_ratio"] = tab["spread"] / tab["drawn_spread"]
    verdicts = pd.Series([d.verdict.verdict if d.verdict is not None else "none" for d in diags]).value_counts()
    return {"res": res, "table": tab, "seconds": seconds, "verdicts": {k: int(v) for k, v in verdicts.items()},
            "n": n_robots}


def reallocation(res, allocation) -> pd.DataFrame:
    rows = [{"design": "as allocated (centred, sigma = t / 3)", "cost": allocation.cost, "status": allocation.status,
             "min_probability": float(np.min(allocation.design.p_linear["position"])), "probability": "centred"}]
    for keep, label in ((True, "re-allocated, fleet spread and shift"), (False, "re-allocated, fleet spread, shift "
                                                                                 "removed by a design change")):
        r = res.reallocate(keep_shift=keep)
        rows.append({"design": label, "cost": r.design.cost, "status": r.design.status,
                     "min_probability": float(r.probability.min()) if r.probability is not None else np.nan,
                     "probability": r.kind})
    return pd.DataFrame(rows)


def ur10_compensation() -> tuple[pd.DataFrame, dict]:
    """Diagnosis of random_C (the sim2real study's split), compensation of its held-out poses, export check."""
    import tempfile

    import tolalloc
    from tolalloc.diagnose.compensate import compensate, solve_targets
    from tolalloc.diagnose.synth import split_frame
    from tolalloc.robot.io.urdf import load_urdf

    sys.path.insert(0, str(ROOT / "studies" / "sim2real_ur10"))
    from convert_ur10 import series

    C = series("C").iloc[::STEP_C].reset_index(drop=True)
    train, test = split_frame(C, 0.25, np.random.default_rng(7))
    t0 = time.perf_counter()
    md = tolalloc.diagnose_measurements("ur10", train, test, progress=False)
    d = md.diagnosis
    m = md.identified_model()
    te = d.test
    meas = m.measurements(te.q, temperature_c=te.temperature_c, time_s=te.time_s, direction=te.direction,
                          payload_kg=te.payload_kg if m.payload_in_training else None)
    test_rms = float(np.sqrt(np.mean(np.sum(d.final.test_mm ** 2, axis=1))))
    rows, extra = [], {"diagnosis_seconds": time.perf_counter() - t0, "effects": "+".join(d.effects) or "none",
                       "verdict": d.verdict.verdict, "test_rms_final_mm": test_rms}
    for label, targets in (("nominal positions of the program", None), ("measured points", te.xyz_mm)):
        c = compensate(m, te.q, targets, meas, frame="tracker", tol_mm=1e-9) if targets is None else \
            solve_targets(m, targets, te.q, meas, frame="tracker", tol_mm=1e-9)
        ok = c.ok
        J = m.joint_jacobian(te.q, "tracker")
        land = te.xyz_mm + np.einsum("pin,pn->pi", J, c.q - te.q)  # first-order move from the measured pose
        err = np.linalg.norm(land - c.targets_mm, axis=1)[ok]
        before = np.linalg.norm(te.xyz_mm - c.targets_mm, axis=1)[ok]
        rms = float(np.sqrt(np.mean(err ** 2)))
        rows.append({"targets": label, "poses": len(ok), "compensated": int(ok.sum()),
                     "model_error_max_mm": float(c.error_mm[ok].max()),
                     "largest_correction_deg": float(np.rad2deg(np.abs(c.q - te.q)[ok].max())),
                     "uncompensated_rms_mm": float(np.sqrt(np.mean(before ** 2))), "compensated_rms_mm": rms,
                     "final_model_test_rms_mm": test_rms, "ratio_to_test_rms": rms / test_rms})
    with tempfile.TemporaryDirectory() as tmp:
        md.export_model(Path(tmp) / "exp")
        x = m.geometric_points(te.q)
        for fmt, rob in (("toml", tolalloc.load_robot(Path(tmp) / "exp" / "identified.toml")),
                         ("urdf", load_urdf(Path(tmp) / "exp" / "identified.urdf"))):
            extra[f"export_{fmt}_max_fk_difference_mm"] = float(np.abs(rob.fk_internal(te.q)[:, :3, 3] - x).max())
    return pd.DataFrame(rows), extra


def ur10_sessions() -> tuple[pd.DataFrame, dict]:
    """Series A and C as two measurements of one robot: each diagnosed on all poses, pooled as a fleet of two."""
    import tolalloc

    sys.path.insert(0, str(ROOT / "studies" / "sim2real_ur10"))
    from convert_ur10 import series

    t0 = time.perf_counter()
    frames = {s: series(s).iloc[::step].reset_index(drop=True) for s, step in (("A", STEP_A), ("C", STEP_C))}
    diags = {s: tolalloc.diagnose_measurements("ur10", df, progress=False) for s, df in frames.items()}
    res = tolalloc.fleet(list(diags.values()), names=["session A", "session C"])
    pool = res.pool
    (a, c), (ca, cc) = pool.values, [np.diag(r.cov) for r in pool.robots]
    sd = np.sqrt([ca[list(pool.robots[0].names).index(n)] + cc[list(pool.robots[1].names).index(n)]
                  for n in pool.names])
    tab = pd.DataFrame({"parameter": pool.names, "unit": pool.units, "session_A": a, "session_C": c,
                        "difference": c - a, "difference_sd": sd, "z": (c - a) / sd})
    tab["stable"] = np.abs(tab["z"]) < 3.0
    info = {"seconds": time.perf_counter() - t0, "excluded": pool.excluded, "unpooled": list(pool.unpooled),
            "effects": {s: "+".join(d.diagnosis.effects) or "none" for s, d in diags.items()},
            "verdicts": {s: d.verdict for s, d in diags.items()}}
    return tab, info


def coverage(n_robots: int, workers: int, replications: int, allocation) -> pd.DataFrame:
    rows = []
    for r in range(replications):
        out = simulated(n_robots, workers, allocation, seed=100 + r)
        t = out["table"]
        rows.append({"replication": r + 1, "robots": n_robots, "combinations": len(t),
                     "true_mean_in_interval": int(t["true_mean_in_interval"].sum()),
                     "true_spread_in_interval": int(t["true_spread_in_interval"].sum()),
                     "spread_within_20pct": int(t["spread_within_20pct"].sum()), "seconds": out["seconds"]})
    return pd.DataFrame(rows)


def _md(df: pd.DataFrame, digits: int = 4) -> str:
    return df.to_markdown(index=False, floatfmt=f".{digits}g")


def _sessions_section(tab: pd.DataFrame, info: dict) -> list[str]:
    """The sessions' comparison: every geometric and compliance parameter, the transmission's many columns summed up."""
    trans = tab["parameter"].str.startswith("transmission:")
    other, tr = tab[~trans], tab[trans]
    lines = ["## 2b. UR10: the two sessions as repeated measurements of one robot", "",
             f"Each session diagnosed on its poses (A every {STEP_A}th row, C every {STEP_C}nd; "
             f"{info['seconds']:.0f} s); "
             "effects: " + ", ".join(f"{s} {e}" for s, e in info["effects"].items())
             + f"; verdicts {info['verdicts']}. Left out: {info['excluded'] or 'none'}; effect columns not in both "
             f"sessions (not pooled): {len(info['unpooled'])}.", "",
             f"**{int(tab['stable'].sum())} of {len(tab)}** pooled parameters agree between the sessions within 3 "
             "sampling sd (stable); the others moved between the sessions by more than their noise allows. The "
             "geometric and compliance parameters:", "",
             _md(other.sort_values("z", key=np.abs, ascending=False)), ""]
    if len(tr):
        top = tr.reindex(tr["z"].abs().sort_values(ascending=False).index).head(5)
        lines += [f"The transmission's {len(tr)} harmonic columns: {int(tr['stable'].sum())} stable; the five that "
                  "moved most:", "", _md(top), "", "All rows: `ur10_sessions.csv`.", ""]
    return lines


def report() -> str:
    """report.md from the files of the run (``run_info.json`` and the CSV tables)."""
    info = json.loads((OUT / "run_info.json").read_text())
    sim, t = info["sim"], pd.read_csv(OUT / "sim_fleet.csv")
    cov, realloc = pd.read_csv(OUT / "sim_coverage.csv"), pd.read_csv(OUT / "sim_reallocation.csv")
    k, level = len(t), 100 * sim["level"]

    def share(col):
        return 100 * cov[col].sum() / cov["combinations"].sum()

    lines = ["# From a measured robot back to the design", "",
             "Generated by `studies/fleet/run.py`; every number below is computed there.", "",
             f"## 1. Simulated fleet: {sim['n']} robots, {N_POSES} poses each, one pose plan", "",
             f"Diagnosed and pooled in **{sim['seconds']:.0f} s** with {info['workers']} worker processes "
             f"(verdicts: {', '.join(f'{v} {n}' for v, n in sim['verdicts'].items())}). {k} identifiable "
             "combinations are estimated; the others are reported as not identifiable with the diagnosis's reason.",
             "",
             f"* spread within 20 % of the factory's (population) spread: **{int(t['spread_within_20pct'].sum())} of "
             f"{k}** combinations; the factory's shift inside the mean's {level:.0f} % interval: "
             f"**{int(t['true_mean_in_interval'].sum())} of {k}**; the factory's spread inside the spread's interval: "
             f"{int(t['true_spread_in_interval'].sum())} of {k}.",
             f"* against the robots actually drawn (the sample the fleet is): pooled spread / drawn spread between "
             f"{t['drawn_spread_ratio'].min():.3f} and {t['drawn_spread_ratio'].max():.3f}; what remains between the "
             "pooled and the factory's values is the sampling of 50 robots from the factory, which the intervals "
             "are for.", "",
             _md(t[["parameter", "unit", "mean", "mean_lo", "mean_hi", "true_mean", "spread", "spread_lo", "spread_hi",
                    "true_spread", "spread_ratio", "drawn_spread_ratio", "cpk", "status"]]), "",
             "### Coverage over replications (other robot draws from the same factory)", "", _md(cov), "",
             f"Overall: the factory's shift inside the interval for {share('true_mean_in_interval'):.1f} % of the "
             f"combinations, its spread inside the interval for {share('true_spread_in_interval'):.1f} %, spread "
             f"within 20 % for {share('spread_within_20pct'):.1f} % (nominal level {level:.0f} %).", "",
             "### Against the allocation, and re-allocated", "",
             f"Allocation of the UR10 for P(|dP| < {RADIUS_MM} mm) >= 0.95 (certified, continuous). "
             + "; ".join(sim["headline"][1:]) + ".", "", _md(realloc), "", "![spread](spread.png)", ""]
    if "compensation" in info:
        tab, extra = pd.read_csv(OUT / "ur10_compensation.csv"), info["compensation"]
        lines += ["## 2a. UR10: compensation of the held-out poses (series C every second row, random 75/25 split, "
                  "seed 7: the sim2real study's random_C run)", "",
                  f"Diagnosis: verdict {extra['verdict']}, effects {extra['effects']}, final model test RMS "
                  f"{extra['test_rms_final_mm']:.4f} mm ({extra['diagnosis_seconds']:.0f} s).", "", _md(tab), "",
                  "The landing error of the compensated joint values is the held-out measurement moved by the model's "
                  "Jacobian times the correction (first order; the corrections are below a degree). Exported robot "
                  "files against the identified forward kinematics: TOML "
                  f"{extra['export_toml_max_fk_difference_mm']:.2g} mm, URDF "
                  f"{extra['export_urdf_max_fk_difference_mm']:.2g} mm (largest difference over the test poses).", ""]
    if "sessions" in info:
        lines += _sessions_section(pd.read_csv(OUT / "ur10_sessions.csv"), info["sessions"])
    return "\n".join(lines)


def _ur10_data() -> bool:
    sys.path.insert(0, str(ROOT / "studies" / "sim2real_ur10"))
    from convert_ur10 import DATA

    return DATA.is_dir()


def main(argv=None) -> int:
    import matplotlib.pyplot as plt

    import tolalloc

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="10 robots, one replication of 10, no UR10 part")
    ap.add_argument("--robots", type=int, default=50)
    ap.add_argument("--replications", type=int, default=4)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--report-only", action="store_true", help="rewrite report.md from the files of the last run")
    args = ap.parse_args(argv)
    if args.report_only:
        (OUT / "report.md").write_text(report() + "\n")
        return 0
    n, reps = (10, 1) if args.quick else (args.robots, args.replications)
    OUT.mkdir(parents=True, exist_ok=True)
    allocation = tolalloc.allocate_tolerances("ur10", radius_mm=RADIUS_MM, prob=0.95, verification=False,
                                              solver=tolalloc.Solver(method="certified", snap=False), progress=False)
    sim = simulated(n, args.workers, allocation)
    sim["table"].to_csv(OUT / "sim_fleet.csv", index=False, float_format="%.6g")
    ax = sim["res"].plot_spread()
    ax.figure.savefig(OUT / "spread.png", dpi=90)
    plt.close(ax.figure)
    reallocation(sim["res"], allocation).to_csv(OUT / "sim_reallocation.csv", index=False, float_format="%.6g")
    coverage(n, args.workers, reps, allocation).to_csv(OUT / "sim_coverage.csv", index=False)
    info = {"workers": args.workers, "sim": {"n": sim["n"], "seconds": sim["seconds"], "verdicts": sim["verdicts"],
                                             "level": sim["res"].pool.level, "headline": sim["res"].headline()}}
    if not args.quick and _ur10_data():
        tab, info["compensation"] = ur10_compensation()
        tab.to_csv(OUT / "ur10_compensation.csv", index=False, float_format="%.6g")
        tab, info["sessions"] = ur10_sessions()
        tab.to_csv(OUT / "ur10_sessions.csv", index=False, float_format="%.6g")
    (OUT / "run_info.json").write_text(json.dumps(info, indent=2, default=str) + "\n")
    (OUT / "report.md").write_text(report() + "\n")
    print((OUT / "report.md").read_text())
    return 0


if __name__ == "__main__":
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    sys.exit(main())
