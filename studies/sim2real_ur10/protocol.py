"""How many re-measured poses a new session needs: the across-session runs at several registration counts.

A test file from another session is re-registered on ``register_n`` of its poses (spread in joint space) and scored
on the others (:mod:`tolalloc.diagnose.register`). The selection uses the training file only, so it is the same at
every count; what changes is how well the registration poses pin the new session -- the tracker frame and probe
offset alone (``frame``), or also a correction of the trained parameters (``calibration``,
:mod:`tolalloc.diagnose.recalibrate`). The scored poses differ between counts (the registration poses are never
scored), so each row is its own held-out figure.
"""

from __future__ import annotations

import pandas as pd

from tolalloc.diagnose import diagnose, measurements_from_frame
from tolalloc.diagnose.register import registration_split
from tolalloc.diagnose.scores import rms

#: registration counts run here besides the study's own 30
COUNTS = (60, 100)
#: the across-session target of issue 25 [mm]
TARGET_MM = 0.50



def fresh_calibration(robot, te: pd.DataFrame, n: int, name: str) -> dict:
    """The baseline without the other session: a diagnosis trained on the ``n`` registration poses of ``te`` alone
    (the same poses :func:`tolalloc.diagnose.register.registration_split` picks), scored on the others."""
    m = measurements_from_frame(te, robot, f"{name}:test")
    split = registration_split(m.q, robot.revolute_mask, n)
    d = diagnose(robot, measurements_from_frame(te.iloc[split.register_index].reset_index(drop=True), robot,
                                                f"{name}:registration poses"),
                 measurements_from_frame(te.iloc[split.score_index].reset_index(drop=True), robot, f"{name}:scored"),
                 folds=3)
    return {"fresh_test_rms_geometric_mm": rms(d.geometric.test_mm), "fresh_test_rms_final_mm": rms(d.final.test_mm),
            "fresh_verdict": d.verdict.verdict}


def registration_table(robot, A: pd.DataFrame, C: pd.DataFrame, summary: pd.DataFrame, counts=COUNTS) -> pd.DataFrame:
    """Final and geometric test RMS per direction, registration update and count (30 from ``summary``), beside a
    fresh calibration on the registration poses alone (:func:`fresh_calibration`)."""
    s = summary.set_index("run")
    rows = []
    for direction, (tr, te) in {"A_to_C": (A, C), "C_to_A": (C, A)}.items():
        fresh = {n: fresh_calibration(robot, te, n, direction) for n in (30, *counts)}
        for update in ("frame", "calibration"):
            run = f"across_{direction}" + ("_update" if update == "calibration" else "")
            rows.append({"direction": direction, "register_update": update, "register_n": 30,
                         "scored_poses": int(s.loc[run, "scored_poses"]),
                         "test_rms_geometric_mm": float(s.loc[run, "test_rms_geometric_mm"]),
                         "test_rms_final_mm": float(s.loc[run, "test_rms_final_mm"])} | fresh[30])
            for n in counts:
                d = diagnose(robot, measurements_from_frame(tr, robot, f"{direction}:train"),
                             measurements_from_frame(te, robot, f"{direction}:test"), test_frame="refit",
                             register_n=n, register_update=update)
                rows.append({"direction": direction, "register_update": update, "register_n": n,
                             "scored_poses": len(d.final.test_mm), "test_rms_geometric_mm": rms(d.geometric.test_mm),
                             "test_rms_final_mm": rms(d.final.test_mm)} | fresh[n])
                print(f"  registration {direction} {update} n={n}: final {rows[-1]['test_rms_final_mm']:.3f} mm",
                      flush=True)
    return pd.DataFrame(rows).sort_values(["direction", "register_update", "register_n"], ignore_index=True)


def section(table: pd.DataFrame) -> list:
    """The report section (statements computed from ``table``)."""
    lines = ["## Registration poses a new session needs", "",
             "`fresh_*`: the baseline without the other session -- a diagnosis trained on the registration poses "
             "alone (3 folds), scored on the same scored poses: what re-calibrating from scratch on those poses "
             "gives.", "",
             "The across-session runs with 30, " + ", ".join(str(n) for n in COUNTS) + " registration poses (the "
             "registration poses are never scored, so each count scores its own rest of the test file; the effect "
             "selection is made on the training file and is the same at every count). `frame`: tracker frame and "
             "probe offset re-fitted, the trained model frozen; `calibration`: also a correction of the trained "
             "parameters with the training posterior as the prior (`register_update=\"calibration\"`). The "
             "registration poses are chosen in joint space, so they are spread over the whole test session in time "
             "(a real new session would be re-measured at its start); one registration split per count, no interval. "
             "(registration_poses.csv)", "", table.to_markdown(index=False, floatfmt=".3f"), ""]
    for update, g in table.groupby("register_update"):
        ok = g[g["test_rms_final_mm"] <= TARGET_MM].groupby("register_n")["direction"].nunique()
        both = [int(n) for n, k in ok.items() if k == g["direction"].nunique()]
        lines.append(f"* `{update}`: both directions at or below {TARGET_MM:.2f} mm final test RMS "
                     + (f"with {', '.join(map(str, both))} registration poses (of the counts run)." if both
                        else "at none of the counts run.") + " Final RMS by count: "
                     + "; ".join(f"{dname} " + ", ".join(f"{int(r.register_n)}: {r.test_rms_final_mm:.3f}"
                                                         for r in dg.itertuples())
                                 for dname, dg in g.groupby("direction")) + " mm.")
    beats = table["test_rms_final_mm"] < table["fresh_test_rms_final_mm"]
    lines.append("* The model trained on the other session beats a fresh calibration on the same registration poses "
                 f"in {int(beats.sum())} of {len(table)} rows: "
                 + "; ".join(f"{r.direction} {r.register_update} {int(r.register_n)}: {r.test_rms_final_mm:.3f} vs "
                             f"{r.fresh_test_rms_final_mm:.3f}" for r in table.itertuples()) + " mm.")
    return lines + [""]
