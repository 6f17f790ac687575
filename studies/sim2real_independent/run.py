"""Independent sim-to-real benchmark (issue 40, part 7): generate, label with the truth-aware oracle, diagnose.

Physics written from the literature (generator.py and its modules import nothing of tolalloc); the diagnosis is
called only through the public API ``tolalloc.diagnose_measurements(robot, train_df, test_df)``. Writes
reports/sim2real_independent/: report.md and cases.csv (the measurement tables are regenerated from the seeds,
never stored).

Usage: python studies/sim2real_independent/run.py [--set A|B|...|M|both|all] [--quick] [--jobs N] [--out DIR]
[--oracle-only]
(``both``: sets A and B; ``all``: every set, A-M. With
``--oracle-only`` the cases are generated and labelled, not diagnosed: oracle_<sets>.csv beside cases.csv, which
it leaves alone, and no report.)
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_v, "1")  # one thread per worker: the pool runs the cases in parallel

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from concurrent.futures import ProcessPoolExecutor  # noqa: E402
from functools import partial  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from sim2real_indep import cases as cs  # noqa: E402
import generator as gen  # noqa: E402
import oracle as orc  # noqa: E402
from sim2real_indep.scoring import score  # noqa: E402
from sim2real_indep.report_text import write_report  # noqa: E402

OUT = HERE.parents[1] / "reports" / "sim2real_independent"


def _diagnose(case):
    import tolalloc

    robot = gen.ROBOT_FILES[case.robot_key]
    tr, te = case.frame.iloc[case.train], case.frame.iloc[case.test]
    kw = {"folds": 3} if len(case.frame) <= 60 else {}
    t = time.perf_counter()
    try:
        s = tolalloc.diagnose_measurements(robot, tr, te, progress=False, **kw).summary()
    except Exception as exc:  # a diagnosis that fails is a recorded miss, not a crash of the benchmark
        return {"verdict": "error", "effects": [], "candidates": [], "error": f"{type(exc).__name__}: {exc}"[:300],
                "diag_s": time.perf_counter() - t}
    rms = s.get("test_rms_mm") or {}
    if isinstance(rms, dict):
        rms = [rms.get("nominal"), rms.get("geometric"), rms.get("final")]
    effects = s.get("effects") or ([] if s.get("effect") in (None, "none") else str(s["effect"]).split("+"))
    return {"verdict": s.get("verdict"), "effects": list(effects), "candidates": list(s.get("candidates") or []),
            "diag_nominal_mm": rms[0], "diag_geometric_mm": rms[1], "diag_final_mm": rms[2], "error": "",
            "diag_s": time.perf_counter() - t}


def run_case(spec, diagnose=True):
    set_name, index, (cid, robot, physics, n, split) = spec
    t = time.perf_counter()
    case = gen.generate(cid, robot, physics, n, cs.case_seed(set_name, index), split)
    o = orc.run_oracle(case)
    t_oracle = time.perf_counter() - t
    d = _diagnose(case) if diagnose else {"verdict": "", "effects": [], "candidates": [], "error": "", "diag_s": 0.0}
    e = case.truth["effect_mm"]
    row = {"set": set_name, "case": cid, "robot": robot, "physics": "+".join(physics) or "none",
           "truth": case.label_truth, "poses": n, "split": split, "noise_mm": case.truth["noise_mm"],
           "effect_rms_mm": float(np.sqrt(np.mean(np.sum(e ** 2, axis=1)))), "label": o.label,
           "named": "+".join(o.named), "oracle_geom_mm": o.rms_geom, "oracle_true_mm": o.rms_true,
           "oracle_gain": o.gain, **{f"rms_{f}_mm": o.rms_family[f] for f in orc.FAMILIES},
           **{f"variant_{f}": o.variant[f] for f in orc.FAMILIES},
           "rms_without": ";".join(f"{k}={v:.4f}" for k, v in o.rms_without.items()), "oracle_s": t_oracle, **d}
    row["effects"] = "+".join(row["effects"])
    row["candidates"] = "+".join(row["candidates"])
    return (row | score(row)) if diagnose else row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    letters = sorted(cs.SETS)
    ap.add_argument("--set", choices=[*letters, "both", "all"], default="A",
                    help="one set, both (A and B) or all (every set of cases.SETS)")
    ap.add_argument("--quick", action="store_true", help="the first four cases of each set, 40 poses each")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--oracle-only", action="store_true",
                    help="generate and label the cases without diagnosing them (writes oracle_<sets>.csv only)")
    args = ap.parse_args(argv)
    names = {"both": ["A", "B"], "all": letters}.get(args.set, [args.set])
    specs = []
    for name in names:
        cases = cs.SETS[name][0]
        for i, c in enumerate(cases[:4] if args.quick else cases):
            specs.append((name, i, c[:3] + (40, c[4]) if args.quick else c))
    t0 = time.perf_counter()
    work = partial(run_case, diagnose=False) if args.oracle_only else run_case
    if args.jobs > 1:
        with ProcessPoolExecutor(args.jobs) as pool:
            rows = list(pool.map(work, specs))
    else:
        rows = [work(s) for s in specs]
    wall = time.perf_counter() - t0
    frame = pd.DataFrame(rows)
    args.out.mkdir(parents=True, exist_ok=True)
    name = f"oracle_{''.join(names)}.csv" if args.oracle_only else "cases.csv"
    tmp = args.out / f"{name}.tmp"
    frame.to_csv(tmp, index=False, float_format="%.5g")
    os.replace(tmp, args.out / name)
    if args.oracle_only:
        cols = ["set", "case", "robot", "physics", "poses", "split", "label", "oracle_gain"]
        print(frame[cols].to_string(index=False))
        return
    write_report(frame, args.out / "report.md", wall=wall, jobs=args.jobs, quick=args.quick)
    print(f"{len(frame)} cases in {wall:.0f} s -> {args.out}")
    for name, part in frame.groupby("set"):
        print(f"set {name}: right {int(part.right.sum())}/{len(part)} (lenient {int(part.right_lenient.sum())})")


if __name__ == "__main__":
    main()
