"""How many re-measured poses a new session needs, and which: the across-session runs at several registration counts.

A test file from another session is re-registered on ``register_n`` of its poses and scored on the others
(:mod:`tolalloc.diagnose.register`). The selection uses the training file only, so it is the same at every count;
what changes is how well the registration poses pin the new session -- the tracker frame and probe offset alone
(``frame``), or also a correction of the trained parameters (``calibration``, :mod:`tolalloc.diagnose.recalibrate`).
The scored poses differ between counts (the registration poses are never scored), so each row is its own held-out
figure.

Two ways of taking the registration poses: ``kmeans`` -- the poses nearest k-means centres in joint space, spread
over the whole test session in time (the library's default); ``first rows`` -- the first ``n`` rows of the test
session (``register_rows``), what a new session measured before the others gives: a forward prediction in time.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.diagnose import diagnose, measurements_from_frame
from tolalloc.diagnose.register import registration_split
from tolalloc.diagnose.scores import rms

#: registration counts run here besides the study's own 30
COUNTS = (60, 100)
#: the across-session target of issue 25 [mm]
TARGET_MM = 0.50
#: how the registration poses are taken
FROM = ("kmeans", "first rows")


def fresh_calibration(robot, te: pd.DataFrame, register_index: np.ndarray, name: str) -> dict:
    """The baseline without the other session: a diagnosis trained on the registration poses ``register_index``
    (0-based rows of ``te``) alone, scored on the other rows of ``te``."""
    score_index = np.setdiff1d(np.arange(len(te)), register_index)
    d = diagnose(robot, measurements_from_frame(te.iloc[register_index].reset_index(drop=True), robot,
                                                f"{name}:registration poses"),
                 measurements_from_frame(te.iloc[score_index].reset_index(drop=True), robot, f"{name}:scored"),
                 folds=3)
    return {"fresh_test_rms_geometric_mm": rms(d.geometric.test_mm), "fresh_test_rms_final_mm": rms(d.final.test_mm),
            "fresh_verdict": d.verdict.verdict}


def span_pct(q_deg: np.ndarray, index: np.ndarray) -> float:
    """Joint range the poses ``index`` span, as a share of the whole session's range, mean over joints [%]."""
    full = np.ptp(q_deg, axis=0)
    part = np.ptp(q_deg[index], axis=0)
    return float(100.0 * np.mean(part[full > 0] / full[full > 0]))


def update_k(d) -> float:
    """The prior widening ``k`` the registration poses chose for the final model (NaN without the update)."""
    cu = d.calibration_update
    return float("nan") if cu is None else float(cu.inflation_k.get("final", float("nan")))


def _record(d) -> dict:
    """Verdict, guards and coverage of one run, as in the study's summary."""
    unc = d.uncertainty
    return {"verdict": d.verdict.verdict, "update_k_final": update_k(d),
            "guard_kinds": "; ".join(sorted({g.split(":")[0] for g in d.guards})) or "none",
            "coverage95_pct": 100.0 * float(np.mean(unc.inside)),
            "median_sigma_mm": float(np.median(unc.sigma_mm)),
            "extrapolating_pct": 100.0 * float(np.mean(d.extrapolation.flagged))}


def _runs(robot, tr, te, direction: str, counts) -> list:
    """(registration_from, register_update, n, diagnosis, 0-based registration rows) of one direction."""
    out = []
    for n in counts:
        for update in ("frame", "calibration"):
            d = diagnose(robot, measurements_from_frame(tr, robot, f"{direction}:train"),
                         measurements_from_frame(te, robot, f"{direction}:test"), test_frame="refit",
                         register_n=n, register_update=update)
            out.append(("kmeans", update, n, d, d.registration.register_index))
    for n in (30, *counts):
        d = diagnose(robot, measurements_from_frame(tr, robot, f"{direction}:train"),
                     measurements_from_frame(te, robot, f"{direction}:test"), test_frame="refit",
                     register_rows=np.arange(1, n + 1), register_update="calibration")
        out.append(("first rows", "calibration", n, d, np.arange(n)))
    return out


def registration_table(robot, A: pd.DataFrame, C: pd.DataFrame, summary: pd.DataFrame, counts=COUNTS) -> pd.DataFrame:
    """Final and geometric test RMS, verdict, guards and coverage per direction, way of taking the registration
    poses, registration update and count (k-means 30 from ``summary``), beside a fresh calibration on the same
    registration poses alone (:func:`fresh_calibration`)."""
    s = summary.set_index("run")
    rows = []
    for direction, (tr, te) in {"A_to_C": (A, C), "C_to_A": (C, A)}.items():
        m = measurements_from_frame(te, robot, f"{direction}:test")
        kmeans = {n: registration_split(m.q, robot.revolute_mask, n).register_index for n in (30, *counts)}
        q_deg = te[[f"q{j + 1}" for j in range(robot.n_joints)]].to_numpy(float)
        fresh = {("kmeans", n): fresh_calibration(robot, te, idx, direction) for n, idx in kmeans.items()}
        for update in ("frame", "calibration"):
            run = s.loc[f"across_{direction}" + ("_update" if update == "calibration" else "")]
            rows.append({"direction": direction, "registration_from": "kmeans", "register_update": update,
                         "register_n": 30, "span_pct": span_pct(q_deg, kmeans[30]),
                         "scored_poses": int(run["scored_poses"]),
                         "test_rms_geometric_mm": float(run["test_rms_geometric_mm"]),
                         "test_rms_final_mm": float(run["test_rms_final_mm"]), "verdict": run["verdict"],
                         "update_k_final": float(run["update_k_final"]),
                         "guard_kinds": run["guard_kinds"], "coverage95_pct": float(run["coverage95_pct"]),
                         "median_sigma_mm": float(run["median_sigma_mm"]),
                         "extrapolating_pct": 100.0 * run["extrapolating_test_poses"] / run["test_poses"]}
                        | fresh[("kmeans", 30)])
        for how, update, n, d, reg in _runs(robot, tr, te, direction, counts):
            if (how, n) not in fresh:
                fresh[(how, n)] = fresh_calibration(robot, te, reg, direction)
            rows.append({"direction": direction, "registration_from": how, "register_update": update,
                         "register_n": n, "span_pct": span_pct(q_deg, reg), "scored_poses": len(d.final.test_mm),
                         "test_rms_geometric_mm": rms(d.geometric.test_mm), "test_rms_final_mm": rms(d.final.test_mm)}
                        | _record(d) | fresh[(how, n)])
            print(f"  registration {direction} {how} {update} n={n}: final {rows[-1]['test_rms_final_mm']:.3f} mm",
                  flush=True)
    return pd.DataFrame(rows).sort_values(["direction", "registration_from", "register_update", "register_n"],
                                          ignore_index=True)


def _target_line(g: pd.DataFrame, label: str) -> str:
    """Whether both directions reach :data:`TARGET_MM`, and the final RMS by count, for one way and update."""
    ok = g[g["test_rms_final_mm"] <= TARGET_MM].groupby("register_n")["direction"].nunique()
    both = [int(n) for n, k in ok.items() if k == g["direction"].nunique()]
    return (f"* {label}: both directions at or below {TARGET_MM:.2f} mm final test RMS "
            + (f"with {', '.join(map(str, both))} registration poses (of the counts run)." if both
               else "at none of the counts run.") + " Final RMS by count: "
            + "; ".join(f"{dname} " + ", ".join(f"{int(r.register_n)}: {r.test_rms_final_mm:.3f}"
                                                for r in dg.itertuples())
                        for dname, dg in g.groupby("direction")) + " mm.")


def value_range(v: pd.Series, fmt: str = ".0f") -> str:
    """``min-max`` of ``v``, one number where they agree."""
    lo, hi = format(v.min(), fmt), format(v.max(), fmt)
    return lo if lo == hi else f"{lo}-{hi}"


def section(table: pd.DataFrame) -> list:
    """The report section (statements computed from ``table``)."""
    lines = ["## Registration poses a new session needs", "",
             "`fresh_*`: the baseline without the other session -- a diagnosis trained on the registration poses "
             "alone (3 folds), scored on the same scored poses: what re-calibrating from scratch on those poses "
             "gives.", "",
             "The across-session runs with 30, " + ", ".join(str(n) for n in COUNTS) + " registration poses (the "
             "registration poses are never scored, so each row scores its own rest of the test file; the effect "
             "selection is made on the training file and is the same in every row). `frame`: tracker frame and "
             "probe offset re-fitted, the trained model frozen; `calibration`: also a correction of the trained "
             "parameters with the training posterior as the prior (`register_update=\"calibration\"`). "
             "`registration_from`: `kmeans` -- the poses nearest k-means centres in joint space, spread over the "
             "whole test session in time; `first rows` -- the first rows of the test session (`register_rows`), as "
             "a new session measured at its start would give them: the other rows are then a forward prediction "
             "in time. `span_pct`: the joint range the registration poses span, as a share of the test session's "
             "range (mean over the joints). `coverage95_pct`: scored residuals inside the predicted 95 % radius (for "
             "`calibration`, the update's posterior); `update_k_final`: the k the registration poses' marginal "
             "likelihood chose for the final model's update, its training data counting 1/k in the prior (`nan` in "
             "the `frame` rows: no update); `median_sigma_mm`: median predicted 1-sigma of the test "
             "poses; `extrapolating_pct`: test poses flagged as extrapolations. One registration split per row, no "
             "interval. (registration_poses.csv)", "",
             table.to_markdown(index=False, floatfmt=".3f"), ""]
    for (how, update), g in table.groupby(["registration_from", "register_update"]):
        lines.append(_target_line(g, f"`{update}`, `{how}`"))
    lines.append("* Joint range spanned by the registration poses (`span_pct`, by count): "
                 + "; ".join(f"{d} {how} " + ", ".join(f"{int(r.register_n)}: {r.span_pct:.0f} %"
                                                    for r in g.drop_duplicates("register_n").itertuples())
                             for (d, how), g in table.groupby(["direction", "registration_from"])) + ".")
    fires = table["guard_kinds"].str.contains("uncertainty")
    lines.append("* Coverage of the predicted 95 % radius on the scored poses: "
                 + "; ".join(f"`{u}` {value_range(g['coverage95_pct'])} %"
                             for u, g in table.groupby("register_update"))
                 + f"; the `uncertainty` guard fires in {int(fires.sum())} of {len(table)} rows. Median predicted "
                 "1-sigma of the test poses (`median_sigma_mm`): "
                 + "; ".join(f"`{u}` {value_range(g['median_sigma_mm'], '.3f')} mm"
                             for u, g in table.groupby("register_update"))
                 + f". Test poses flagged as extrapolations from the training session (`extrapolating_pct`): "
                 f"{value_range(table['extrapolating_pct'])} %. The k the registration poses chose for the final "
                 "model (`update_k_final`; its training data count 1/k in the prior): "
                 + value_range(table["update_k_final"].dropna(), ".3g") + ".")
    beats = table["test_rms_final_mm"] < table["fresh_test_rms_final_mm"]
    lines.append("* The model trained on the other session beats a fresh calibration on the same registration poses "
                 f"in {int(beats.sum())} of {len(table)} rows (final test RMS, this model vs the fresh one, every row): "
                 + "; ".join(f"{r.direction} {r.registration_from} {r.register_update} {int(r.register_n)}: "
                             f"{r.test_rms_final_mm:.3f} vs {r.fresh_test_rms_final_mm:.3f}"
                             for r in table.itertuples()) + " mm.")
    return lines + [""]
