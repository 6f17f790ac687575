"""Study: ISO 9283 requirements allocated, and their acceptance test predicted and simulated (issue 43).

Writes reports/iso9283/: README.md, datasheet_<robot>.csv, simulation_<robot>.csv, acceptance_<robot>.png,
instrument.csv, summary.json.

1. The example requirement file (examples/requirements_iso9283.toml: RP_l <= 0.05 mm and AP_P <= 0.5 mm for 95 % of
   the built robots, 30 cycles, laser tracker 15 um + 6 um/m at 2 m) allocated for the built-in robots with
   :func:`tolalloc.allocate_acceptance` (test laid out, exact and standard designs, prediction, 2000 simulated
   robots): times per stage, the datasheet with the ISO 14253-1 verdicts, the simulated share of robots meeting each
   limit.
2. The prediction against the simulation: per statistic and test pose, the predicted value at 95 % beside the
   simulated quantile and its distribution-free 99.9 % interval (robot and measured).
3. A design whose random parts are all zero: its predicted measured RP_l is the tracker's alone (the law of RP_l
   at the tracker's covariance), beside the simulation.
4. What the test can demonstrate: for the ur10 design, the measured RP_l at 95 % and its expanded uncertainty U
   for trackers of other MPE and distance; the smallest RP limit the test would demonstrate (measured + U).
5. Allocating for a demonstrated conformance (guard band, ISO 14253-1): AP_P <= 0.5 mm with the guard band (cost,
   verdict), and RP_l <= 0.05 mm with the guard band, which the standard tracker makes impossible (the refusal).

Usage: python studies/iso9283/run.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import tolalloc  # noqa: E402
from tolalloc.acceptance import PoseAccuracy, PoseRepeatability, Tracker, predict_acceptance  # noqa: E402
from tolalloc.acceptance.layout import AcceptanceTest  # noqa: E402
from tolalloc.acceptance.simulate import quantile_interval, simulate_acceptance  # noqa: E402
from tolalloc.acceptance.terms import AcceptanceSpec  # noqa: E402
from tolalloc.allocate import allocate, build_problem  # noqa: E402
from tolalloc.calibration.split import split_errors  # noqa: E402
from tolalloc.errormodel import build_error_model  # noqa: E402
from tolalloc.exceptions import TolallocError  # noqa: E402
from tolalloc.linear.repeatability import rp_quantile  # noqa: E402
from tolalloc.report.plots.acceptance import plot_acceptance  # noqa: E402
from tolalloc.report.tables import markdown_table  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
OUT = ROOT / "reports" / "iso9283"
EXAMPLE = ROOT / "examples" / "requirements_iso9283.toml"
ROBOTS = ("tool_changer", "ur10")
SEED = 43


def md(df: pd.DataFrame, floatfmt=".4g") -> str:
    return markdown_table(df, floatfmt)


def part1(n_robots: int) -> dict:
    """The example file allocated for each built-in robot."""
    out = {}
    for name in ROBOTS:
        t0, c0 = time.perf_counter(), time.process_time()
        res = tolalloc.allocate_acceptance(name, str(EXAMPLE), n_robots=n_robots,
                                           verification=tolalloc.Verification(seed=SEED))
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        ds = res.datasheet()
        ds.to_csv(OUT / f"datasheet_{name}.csv", index=False, float_format="%.6g")
        res.simulation.to_frame().to_csv(OUT / f"simulation_{name}.csv", index=False, float_format="%.6g")
        axes = plot_acceptance(res.prediction, res.simulation)
        fig = np.atleast_1d(axes)[0].figure
        fig.suptitle(f"{name}: ISO 9283 acceptance test of the standard design (predicted, {n_robots} simulated)",
                     fontsize=9)
        fig.tight_layout()
        fig.savefig(OUT / f"acceptance_{name}.png", dpi=100)
        plt.close(fig)
        out[name] = {"res": res, "wall_s": wall, "cpu_s": cpu}
    return out


def agreement(res) -> pd.DataFrame:
    """Predicted value at the share beside the simulated quantile and its 99.9 % interval, per statistic and pose."""
    rows = []
    for s in res.prediction.statistics:
        m = s.model
        for i, lab in enumerate(m.labels):
            for kind, pred, sim in (("robot", s.robot, res.simulation.robot), ("measured", s.measured,
                                                                               res.simulation.measured)):
                est, lo, hi = quantile_interval(sim[m.name][:, i], m.target[i], 0.999)
                rows.append({"statistic": m.name, "pose": lab, "what": kind, "share": m.target[i],
                             "predicted_mm": pred[i],
                             "simulated_mm": est, "sim_low_mm": lo, "sim_high_mm": hi,
                             "inside": bool(lo <= pred[i] <= hi)})
    return pd.DataFrame(rows)


def every_statistic(res, n_robots: int):
    """The ur10 design of part 1 under every ISO 9283 requirement kind: prediction and simulation (no allocation)."""
    from tolalloc.acceptance import DistanceAccuracy, OrientationAccuracy, OrientationRepeatability, PathAccuracy

    reqs = [PoseAccuracy(limit_mm=0.5), PoseRepeatability(limit_mm=0.05), OrientationAccuracy(limit_deg=0.05),
            OrientationRepeatability(limit_deg=0.01), DistanceAccuracy(limit_mm=0.3), PathAccuracy(limit_mm=0.5)]
    model = res.result.problem.model_for(res.result.built.t)
    pred = predict_acceptance(res.test, reqs, model)
    sim = simulate_acceptance(res.test, reqs, model, n_robots=n_robots, seed=SEED + 2)
    return type("R", (), {"prediction": pred, "simulation": sim})()


def law_check(n_sim: int) -> pd.DataFrame:
    """The law of RP_l (tolalloc.linear.repeatability) against n_sim simulated tests per covariance shape."""
    from tolalloc.acceptance.statistics import pose_repeatability

    rows = []
    rng = np.random.default_rng(SEED)
    for n in (30, 10):
        for name, C in (("isotropic", np.eye(3)), ("anisotropic", np.diag([1.0, 0.3, 0.05])),
                        ("rank two", np.diag([1.0, 1.0, 0.0])), ("rank one", np.diag([1.0, 0.0, 0.0]))):
            lam, V = np.linalg.eigh(C)
            rp = np.concatenate([pose_repeatability(rng.standard_normal((20_000, n, 3)) @ (V * np.sqrt(lam)).T)
                                 for _ in range(n_sim // 20_000)])
            for p in (0.5, 0.9, 0.95, 0.99):
                est = np.quantile(rp, p)
                rows.append({"cycles": n, "covariance": name, "p": p, "law": float(rp_quantile(C, p, n)),
                             "simulated": est, "relative_error_pct": 100 * (float(rp_quantile(C, p, n)) / est - 1)})
    return pd.DataFrame(rows)


def part3(res, n_robots: int) -> dict:
    """The same ur10 design with every random part zero: RP_l is the tracker's alone."""
    pr = res.result.problem
    model = pr.model_for(res.result.built.t)
    split = split_errors(model).with_random_sigma(np.zeros(len(model.params)))
    req = [PoseRepeatability(limit_mm=0.05)]
    s = predict_acceptance(res.test, req, model, split).statistics[0]
    sim = simulate_acceptance(res.test, req, model, split, n_robots=n_robots, seed=SEED + 1)
    tr = res.test.tracker
    alone = float(rp_quantile(np.eye(3) * tr.sigma_mm**2, 0.95, res.test.cycles))
    q = [quantile_interval(sim.measured["RP_l"][:, i], 0.95, 0.999) for i in range(5)]
    return {"predicted_robot_mm": s.robot.tolist(), "predicted_measured_mm": s.measured.tolist(),
            "tracker_alone_mm": alone, "simulated_measured_mm": [x[0] for x in q],
            "simulated_low_mm": [x[1] for x in q], "simulated_high_mm": [x[2] for x in q],
            "simulated_robot_max_mm": float(sim.robot["RP_l"].max())}


def part4(res) -> pd.DataFrame:
    """The ur10 design's RP_l as trackers of other MPE and distance would measure it."""
    model = res.result.problem.model_for(res.result.built.t)
    rows = []
    for label, a, b, d in (("tracker 15 um + 6 um/m", 0.015, 0.006, 1.0), ("tracker 15 um + 6 um/m", 0.015, 0.006, 2.0),
                           ("tracker 15 um + 6 um/m", 0.015, 0.006, 4.0), ("tracker noise 5 um", 0.005, 0.0, 2.0),
                           ("interferometric 1 um", 0.001, 0.0, 2.0)):
        test = AcceptanceTest(res.test.robot, res.test.placement, tracker=Tracker(mpe_a_mm=a, mpe_b_mm_per_m=b,
                                                                                   distance_m=d))
        s = predict_acceptance(test, [PoseRepeatability(limit_mm=0.05)], model).statistics[0]
        i = int(np.argmax(s.measured + s.U))
        rows.append({"instrument": label, "distance_m": d, "mpe_um": 1000 * test.tracker.mpe_mm,
                     "robot_RP_l_um": 1000 * s.robot[i], "measured_RP_l_um": 1000 * s.measured[i],
                     "U_um": 1000 * s.U[i], "smallest_demonstrable_limit_um": 1000 * (s.measured[i] + s.U[i]),
                     "verdict_at_50_um": s.decisions[i].outcome})
    return pd.DataFrame(rows)


def part5(res) -> dict:
    """Guard-banded allocations on the ur10 (same test and model as part 1)."""
    robot = res.test.robot
    model = build_error_model(robot)
    out = {}
    spec = AcceptanceSpec((PoseAccuracy(limit_mm=0.5, guard_band=True), PoseRepeatability(limit_mm=0.05)), res.test)
    r = allocate(build_problem(model, radius_mm=None, acceptance=spec), solver="exact")
    pred = predict_acceptance(res.test, spec.requirements, r.problem.model_for(r.built.t))
    ap = pred.statistics[0]
    out["ap_guarded"] = {"cost": r.built.cost, "cost_unguarded": res.result.built.cost, "design": r.built.label,
                         "verdict_ap": sorted({d.outcome for d in ap.decisions}),
                         "measured_plus_U_max_mm": float((ap.measured + ap.U).max())}
    try:
        build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(
            (PoseRepeatability(limit_mm=0.05, guard_band=True),), res.test))
        out["rp_guarded"] = "accepted"
    except TolallocError as exc:
        out["rp_guarded"] = str(exc)
    quiet = AcceptanceTest(robot, res.test.placement, tracker=Tracker(mpe_a_mm=0.005, mpe_b_mm_per_m=0.0))
    spec = AcceptanceSpec((PoseAccuracy(limit_mm=0.5, guard_band=True),
                           PoseRepeatability(limit_mm=0.05, guard_band=True)), quiet)
    r = allocate(build_problem(model, radius_mm=None, acceptance=spec), solver="exact")
    pred = predict_acceptance(quiet, spec.requirements, r.problem.model_for(r.built.t))
    out["both_guarded_quiet_tracker"] = {"cost": r.built.cost, "design": r.built.label,
                                         "demonstrated": pred.demonstrated,
                                         "rp_measured_plus_U_max_mm": float((pred.statistics[1].measured
                                                                             + pred.statistics[1].U).max())}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="400 simulated robots instead of 2000")
    args = ap.parse_args()
    n_robots = 400 if args.quick else 2000
    OUT.mkdir(parents=True, exist_ok=True)
    p1 = part1(n_robots)
    full = every_statistic(p1["ur10"]["res"], n_robots)
    agree = pd.concat([agreement(p1[n]["res"]).assign(robot=n) for n in ROBOTS]
                      + [agreement(full).assign(robot="ur10, every statistic")])
    at = full.prediction.statistics[-1]
    at_sim = quantile_interval(full.simulation.robot["AT_P"].max(axis=1), 0.95, 0.999)
    at_largest = {"predicted_bound_mm": float(at.robot.max()), "simulated_mm": at_sim[0],
                  "simulated_low_mm": at_sim[1], "simulated_high_mm": at_sim[2]}
    law = law_check(40_000 if n_robots < 2000 else 200_000)
    law.to_csv(OUT / "rp_law.csv", index=False, float_format="%.6g")
    agree.to_csv(OUT / "agreement.csv", index=False, float_format="%.6g")
    p3 = part3(p1["ur10"]["res"], n_robots)
    p4 = part4(p1["ur10"]["res"])
    p4.to_csv(OUT / "instrument.csv", index=False, float_format="%.6g")
    p5 = part5(p1["ur10"]["res"])
    summary = {"n_robots": n_robots, "seed": SEED, "cpu_count": os.cpu_count(),
               "load_average_1min": os.getloadavg()[0],
               "robots": {n: {"wall_s": p1[n]["wall_s"], "cpu_s": p1[n]["cpu_s"], "stages_s": p1[n]["res"].times_s,
                              "cost": p1[n]["res"].result.built.cost, "design": p1[n]["res"].result.built.label,
                              "met": p1[n]["res"].ok, "demonstrated": p1[n]["res"].demonstrated,
                              "test": p1[n]["res"].test.summary(),
                              "simulated_share_meeting_min": {k: float(v.min()) for k, v in
                                                              p1[n]["res"]._sim_share().items()}}
                        for n in ROBOTS},
               "agreement_inside": int(agree.inside.sum()), "agreement_rows": len(agree),
               "zero_random": p3, "guard_band": p5, "at_p_largest": at_largest,
               "rp_law_max_abs_error_pct": {f"p={p:g}": float(law[law.p == p].relative_error_pct.abs().max())
                                            for p in (0.5, 0.9, 0.95, 0.99)}}
    (OUT / "summary.json").write_text(json.dumps(summary, indent=2, default=float))
    write_readme(p1, agree, p3, p4, p5, summary, law)
    print((OUT / "README.md").read_text())


def write_readme(p1, agree, p3, p4, p5, summary, law) -> None:
    L = ["# ISO 9283 requirements: allocation and the acceptance test (issue 43)", "",
         "Generated by `python studies/iso9283/run.py` (do not edit). Requirement file: "
         "`examples/requirements_iso9283.toml` (RP_l <= 0.05 mm and AP_P <= 0.5 mm for 95 % of the built robots, "
         "rated load and velocity; 30 cycles; laser tracker MPE 15 um + 6 um/m at 2 m, read as a uniform error per "
         "coordinate, u = MPE / sqrt 3; base frame registered on the cube's 8 corners). Error models: the built-in "
         "defaults (tool_changer: sigma set table2, no clearance; ur10: generic sigmas); systematic / random split "
         "of `tolalloc.calibration.split` (joint drives: random repeatability 0.0003 deg).", "",
         f"Machine: {summary['cpu_count']} cores, 1-minute load average {summary['load_average_1min']:.1f} at the end "
         f"of the run (other jobs shared the cores); {summary['n_robots']} simulated robots, seed {summary['seed']}.",
         "", "## 1. Allocated and tested", ""]
    rows = []
    for n in ROBOTS:
        r = p1[n]["res"]
        st = r.times_s
        t = r.test.summary()
        rows.append({"robot": n, "cube_edge_mm": t["cube_edge_mm"], "orientation": t["orientation"],
                     "design": r.result.built.label, "cost": r.result.built.cost, "met": r.ok,
                     "demonstrated": r.demonstrated, "layout_s": st["test_layout_s"],
                     "allocation_s": st["allocation_s"],
                     "prediction_s": st["prediction_s"], "simulation_s": st["simulation_s"],
                     "total_wall_s": p1[n]["wall_s"], "total_cpu_s": p1[n]["cpu_s"]})
    L += [md(pd.DataFrame(rows)), "",
          "Each job is within the 120 s goal (wall time measured here, with the cores shared; `total_cpu_s` is the "
          "process's CPU time). The tool_changer cannot hold one tool orientation over a cube in its working box "
          "(its wrist only compensates the pitch), so its test commands positions only (`orientation` free).", ""]
    for n in ROBOTS:
        r = p1[n]["res"]
        ds = pd.read_csv(OUT / f"datasheet_{n}.csv")
        keep = ["statistic", "where", "limit_mm", "robot_mm", "measured_mm", "U_mm", "margin_mm", "p_meets",
                "decision"]
        sim = r._sim_share()
        L += [f"### {n}", "", r.prediction.text().replace("\n", "  \n"), "", md(ds[keep]), "",
              f"Simulated ({r.simulation.n_robots} robots): share meeting the limit at each pose: " + "; ".join(
                  f"{k} " + ", ".join(f"{v:.3f}" for v in s) for k, s in sim.items()) + ".", "",
              f"![acceptance test {n}](acceptance_{n}.png)", ""]
    L += ["The robots meet AP_P <= 0.5 mm at 95 % by construction (the exact design holds the limit at its worst "
          "pose) and RP_l <= 0.05 mm with room, yet the test demonstrates neither: the measured AP_P sits on the "
          "limit with U above it, and the tracker's noise alone makes the measured RP_l larger than the limit. "
          "ISO 14253-1 counts the uncertainty against the supplier; section 5 allocates for it.", "",
          "## 2. Prediction against the simulated test", "",
          f"{summary['agreement_inside']} of {summary['agreement_rows']} predicted values lie inside the "
          "distribution-free 99.9 % interval of the simulated quantile at the share (`agreement.csv`: per robot, "
          "statistic, test pose or path point, robot and measured; the ur10 design of section 1 also under every "
          "requirement kind: AP_P, RP_l, AP_a-c, RP_a-c (<= 0.05 / 0.01 deg), AD_P (P2-P4), AT_P (11 points of "
          "P2-P1-P4, 10 cycles, each at 1 - 0.05 / 11)). Those outside:", ""]
    out_rows = agree[~agree.inside]
    a = summary["at_p_largest"]
    L += [md(out_rows) if len(out_rows) else "(none)", "",
          f"AT_P itself (the largest over the 11 points, robot, ur10 design): the prediction's bound "
          f"{a['predicted_bound_mm']:.4g} mm (each point at 1 - 0.05 / 11) against the simulated 95 % quantile "
          f"{a['simulated_mm']:.4g} mm [{a['simulated_low_mm']:.4g}, {a['simulated_high_mm']:.4g}]: the Bonferroni "
          "bound is conservative by the difference.", "",
          "The independent check with its own kinematics, cycles, registration and statistics is "
          "`tests/test_acceptance_predict.py`.", "",
          "The law of RP_l (`tolalloc.linear.repeatability`) against simulated tests "
          f"({'200,000' if summary['n_robots'] >= 2000 else '40,000'} per shape, `rp_law.csv`): largest relative "
          "error of the quantile over isotropic, anisotropic, rank-two and rank-one covariances at 30 and 10 "
          "cycles: " + ", ".join(f"{k} {v:.2f} %" for k, v in summary["rp_law_max_abs_error_pct"].items()) + ".",
          "",
          "## 3. A design with no random part: RP_l is the instrument's", "",
          f"The ur10 design with every random part set to zero: predicted robot RP_l "
          f"{max(p3['predicted_robot_mm']):.3g} mm at every pose; predicted measured RP_l "
          f"{1000 * p3['predicted_measured_mm'][0]:.2f} um = the law of RP_l at the tracker's covariance alone "
          f"({1000 * p3['tracker_alone_mm']:.2f} um); simulated: " + ", ".join(
              f"{1000 * v:.2f} [{1000 * lo:.2f}, {1000 * hi:.2f}]" for v, lo, hi in zip(
                  p3["simulated_measured_mm"], p3["simulated_low_mm"], p3["simulated_high_mm"])) +
          f" um at P1-P5 (largest simulated robot RP_l {p3['simulated_robot_max_mm']:.2g} mm).", "",
          "## 4. What the test can demonstrate", "",
          "The ur10 design of section 1 measured by other instruments (worst pose): the smallest RP limit a test "
          "would demonstrate is the measured RP_l at 95 % plus U.", "", md(p4), "",
          "Reading the whole MPE as noise per measurement is conservative for repeatabilities (a tracker's "
          "short-term noise is usually well below its MPE): give the tracker's noise as `mpe_a_mm` when it is "
          "known (row 'tracker noise 5 um').", "",
          "## 5. Allocating for a demonstrated conformance (guard band)", ""]
    g = p5["ap_guarded"]
    L += [f"AP_P <= 0.5 mm with `guard_band=True` (and RP_l <= 0.05 mm without): design {g['design']}, cost "
          f"{g['cost']:.4g} against {g['cost_unguarded']:.4g} without the guard band; AP_P verdicts "
          f"{', '.join(g['verdict_ap'])} (largest measured + U {g['measured_plus_U_max_mm']:.4g} mm).", "",
          "RP_l <= 0.05 mm with `guard_band=True` and the standard tracker is refused: " + p5["rp_guarded"], ""]
    q = p5["both_guarded_quiet_tracker"]
    L += [f"With a tracker whose noise is 5 um (its MPE not read as noise), both guard-banded: design {q['design']}, "
          f"cost {q['cost']:.4g}, conformance {'demonstrated' if q['demonstrated'] else 'NOT demonstrated'} (largest "
          f"measured RP_l + U {1000 * q['rp_measured_plus_U_max_mm']:.4g} um).", ""]
    (OUT / "README.md").write_text("\n".join(L) + "\n")


if __name__ == "__main__":
    main()
