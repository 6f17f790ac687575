"""Study: design with the parts that are bought as well as the parts that are machined (issue 42).

Writes reports/bought_components/: report.md and CSV / JSON tables.

1. The UR10-class design (tolalloc/data/robots/ur10.toml: catalogue slots per joint) over its ``work_cell`` box, a
   payload of 0-10 kg and an ambient of 15-30 degC (duty 0.5), for P(|dP| < 0.6 mm) >= 0.95 after the controller's
   stiffness and temperature models (after="compensation", residual 10 % of compliance, thermal growth, bending and
   mount tilt; no error tables: gear, encoder and bearing errors count in full): the joint allocation of machining
   standard values and catalogue parts (certified, the mixed-integer program's gap), its time, the parts to buy, the
   variance budget, the cost split; the machining allocation with these parts (continuous and exact standard).
2. Which joints need a precision gear: the same arm with motor-side encoders only (no output encoder to buy),
   over a range of radii, and with the uncompensated requirement.
3. What payload and temperature do: the UR10-class design for payload ranges 0 / 0-5 / 0-10 kg times ambient ranges
   20 / 15-30 / 5-40 degC.
4. The tool changer (tolalloc/data/robots/tool_changer.toml) over its ``working`` box, 0-20 kg, 5-35 degC.
5. Verification: the nonlinear Monte Carlo (physical draws through the exact chain, paired estimator with the linear
   map as control) at the worst point the region search found and at every active point; an independent
   simulation (studies/bought_components/independent.py, its own code) of the same parts at the worst point.
6. The design against the real UR10: the design's catalogue wind-up against the joint compliance the sim-to-real
   diagnosis measured on the IPA laser-tracker data (ur10_compare.py; skipped without ../shared/data).

Usage: python studies/bought_components/run.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

import tolalloc
from tolalloc.allocate.parts import allocate_parts
from tolalloc.allocate.region import box_region
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.parts import Conditions, PartEffects, parts_error_model, with_parts
from tolalloc.report.tables import markdown_table
from tolalloc.robot.part_catalogue import builtin_catalogue
from tolalloc.verify.parts import draw_errors, verify_parts

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from independent import UR10Sim, wilson  # noqa: E402
from ur10_compare import DATA, compare  # noqa: E402

OUT = HERE.parents[1] / "reports" / "bought_components"
PROB, SEED = 0.95, 42
#: The controller's models: stiffness given the payload, temperature (link growth), bending, mount; 10 % left.
MODELS = {"compliance": 0.1, "thermal": 0.1, "beam": 0.1, "mount": 0.1}
UR10 = dict(radius_mm=0.75, conditions=Conditions((0.0, 10.0), (15.0, 30.0), 20.0, 0.5), after="compensation",
            residual=MODELS)
TOOL_CHANGER = dict(radius_mm=2.0, conditions=Conditions((0.0, 20.0), (5.0, 35.0), 20.0, 0.5),
                    after="compensation", residual=MODELS)


def md(df: pd.DataFrame, fmt=".4g") -> str:
    return markdown_table(df, fmt)


def motor_encoders_only(robot):
    """The robot with every encoder slot reduced to the motor-side encoder."""
    slots = dict(robot.components.slots)
    motor = builtin_catalogue().get("encoder", "MOTOR-ENC-STD")
    for k in slots:
        if k[1] == "encoder":
            slots[k] = replace(slots[k], options=(motor,))
    object.__setattr__(robot, "components", replace(robot.components, slots=slots))
    return robot


def run(robot, region: str, quick: bool, **kw):
    model = build_error_model(robot)
    lo, hi = robot.regions[region]
    opts = dict(n_seed=64, n_starts=1, max_rounds=4) if quick else {}
    return allocate_parts(model, box_region(robot, lo, hi, region), seed=SEED, **opts, **kw)


def bought(res) -> str:
    """The parts bought beyond the cheapest option of each slot, as one line."""
    out = []
    for key, slot in res.problem.model.robot.components.slots.items():
        cheapest = min(slot.options, key=lambda p: (p.cost or 0.0, p.name)).name
        if res.choice[key] != cheapest:
            out.append(f"{key[0]}: {res.choice[key]}")
    return "; ".join(out) or "the cheapest option of every slot"


def row(label: str, res) -> dict:
    s = res.summary()
    w = res.worst_point
    return {"case": label, "cost": s["cost"], "machining_cost": s["machining_cost"], "parts_cost": s["parts_cost"],
            "parts_share_pct": 100 * s["parts_cost"] / s["cost"], "rule": s["rule"], "mip_status": s["mip_status"],
            "mip_gap": s["mip_gap"], "converged": s["converged"], "rounds": s["rounds"],
            "worst_payload_kg": float(w.payload_kg[0]), "worst_ambient_c": float(w.ambient_c[0]),
            "time_s": s["time_s"], "cpu_s": s["cpu_s"], "bought_beyond_cheapest": bought(res)}


def design(name: str, res, files: list) -> dict:
    """Write one design's tables; returns its summary."""
    res.parts_table().to_csv(OUT / f"{name}_parts.csv", index=False)
    res.tolerances().to_csv(OUT / f"{name}_tolerances.csv", index=False)
    res.variance_shares().to_csv(OUT / f"{name}_variance.csv", index=False)
    s = res.summary()
    if res.machining is not None:
        m = res.machining
        s["machining_with_these_parts"] = {
            "continuous_certified_cost": m.certified.cost, "continuous_exact_cost": getattr(m.exact, "cost", None),
            "standard_cost": m.standard.cost, "standard_solver": str(m.standard.label)}
    (OUT / f"{name}_summary.json").write_text(json.dumps(s, indent=2, default=float))
    files += [f"{name}_parts.csv", f"{name}_tolerances.csv", f"{name}_variance.csv", f"{name}_summary.json"]
    return s


def sweep_conditions(quick: bool) -> pd.DataFrame:
    rows = []
    payloads = ((0.0, 0.0), (0.0, 10.0)) if quick else ((0.0, 0.0), (0.0, 5.0), (0.0, 10.0))
    ambients = ((20.0, 20.0), (5.0, 40.0)) if quick else ((20.0, 20.0), (15.0, 30.0), (5.0, 40.0))
    for pl in payloads:
        for amb in ambients:
            kw = dict(UR10, conditions=Conditions(pl, amb, 20.0, 0.5))
            try:
                res = run(tolalloc.load_robot("ur10"), "work_cell", quick, exact=False, **kw)
                r = row(f"payload {pl[1]:g} kg, ambient {amb[0]:g}-{amb[1]:g} degC", res)
            except tolalloc.TolallocError as exc:
                r = {"case": f"payload {pl[1]:g} kg, ambient {amb[0]:g}-{amb[1]:g} degC", "infeasible": str(exc)}
            rows.append(r)
    return pd.DataFrame(rows)


def sweep_precision(quick: bool) -> pd.DataFrame:
    rows = []
    cases = [("compensation", r) for r in ((1.0,) if quick else (1.0, 1.1, 1.2, 1.5))]
    cases += [("none", r) for r in ((6.0,) if quick else (5.0, 6.0, 7.0))]
    for after, radius in cases:
        kw = dict(UR10, radius_mm=radius, after=after)
        try:
            res = run(motor_encoders_only(tolalloc.load_robot("ur10")), "work_cell", quick, exact=False, **kw)
            rows.append({**row(f"{after}, r = {radius:g} mm", res),
                         "special_accuracy_gears": ", ".join(k[0] for k, v in res.choice.items()
                                                             if k[1] == "reducer" and v.endswith("-SA")) or "none"})
        except tolalloc.TolallocError as exc:
            rows.append({"case": f"{after}, r = {radius:g} mm", "infeasible": str(exc)})
    return pd.DataFrame(rows)


def independent(res, n: int) -> pd.DataFrame:
    """The parts alone (no machining errors) at the worst point: the library's draws against the independent
    simulation's, P(|dP| < r) at several radii with Wilson intervals (95 %)."""
    robot = with_parts(res.problem.model.robot, res.choice)
    w = res.worst_point
    q, m, t = w.q[0], float(w.payload_kg[0]), float(w.ambient_c[0])
    mm = res.problem.model_for(np.zeros_like(res.design.t))
    fx = PartEffects(robot, w.q, w.payload_kg, w.ambient_c, res.conditions, pm=parts_error_model(mm, robot))
    lib, _ = draw_errors(fx, 0, mm, FastChain(fx.pm.model), n, np.random.default_rng(SEED), after=res.after,
                         residual=res.residual)
    parts = {jt.name: {k: getattr(robot.components.joint(jt.name), k) for k in ("reducer", "encoder", "bearing",
                                                                                "motor")} for jt in robot.joints}
    ind = UR10Sim(parts, res.conditions, res.after, res.residual).errors(q, m, t, n, SEED + 1)
    d_lib, d_ind = np.linalg.norm(lib, axis=1), np.linalg.norm(ind, axis=1)
    rows = []
    for label, r in [(f"quantile {a:g} of the library's", float(np.quantile(d_lib, a))) for a in (0.5, 0.9, 0.95, 0.99)]:
        a, alo, ahi = wilson(int((d_lib < r).sum()), n)
        b, blo, bhi = wilson(int((d_ind < r).sum()), n)
        rows.append({"radius": label, "radius_mm": r, "p_library": a, "library_low": alo, "library_high": ahi,
                     "p_independent": b, "independent_low": blo, "independent_high": bhi,
                     "intervals_overlap": bool(alo <= bhi and blo <= ahi)})
    mean = pd.DataFrame({"axis": list("xyz"), "mean_library_mm": lib.mean(0), "mean_independent_mm": ind.mean(0),
                         "sd_library_mm": lib.std(0), "sd_independent_mm": ind.std(0)})
    return pd.DataFrame(rows), mean


def main(quick: bool = False) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    files: list = []
    n_mc = 2000 if quick else 20000
    ur = run(tolalloc.load_robot("ur10"), "work_cell", quick, exact=True, **UR10)
    s_ur = design("ur10", ur, files)
    ver = verify_parts(ur, points="active", n_mc=n_mc, seed=SEED)
    ver.to_frame().to_csv(OUT / "ur10_verification.csv", index=False)
    ver_std = verify_parts(ur, which="standard", n_mc=n_mc, seed=SEED + 1)
    ver_std.to_frame().to_csv(OUT / "ur10_verification_standard.csv", index=False)
    ind, ind_mean = independent(ur, 20000 if quick else 200000)
    ind.to_csv(OUT / "ur10_independent.csv", index=False)
    ind_mean.to_csv(OUT / "ur10_independent_moments.csv", index=False)
    tc = run(tolalloc.load_robot("tool_changer"), "working", quick, exact=True, **TOOL_CHANGER)
    try:  # the quick start's radius with these parts
        run(tolalloc.load_robot("tool_changer"), "working", True, exact=False, **dict(TOOL_CHANGER, radius_mm=0.25))
        tc_quick = "met"
    except tolalloc.TolallocError as exc:
        tc_quick = str(exc)
    s_tc = design("tool_changer", tc, files)
    ver_tc = verify_parts(tc, n_mc=n_mc, seed=SEED)
    ver_tc.to_frame().to_csv(OUT / "tool_changer_verification.csv", index=False)
    cond = sweep_conditions(quick)
    cond.to_csv(OUT / "conditions_sweep.csv", index=False)
    prec = sweep_precision(quick)
    prec.to_csv(OUT / "precision_sweep.csv", index=False)
    comp = compare(ur.choice) if DATA.is_dir() else None
    if comp is not None:
        comp.to_csv(OUT / "ur10_compliance_vs_diagnosis.csv", index=False)
    files += ["ur10_verification.csv", "ur10_verification_standard.csv", "ur10_independent.csv",
              "ur10_independent_moments.csv", "tool_changer_verification.csv", "conditions_sweep.csv",
              "precision_sweep.csv"] + (["ur10_compliance_vs_diagnosis.csv"] if comp is not None else [])
    from report import write_report

    write_report(OUT, quick, dict(ur=ur, s_ur=s_ur, ver=ver, ver_std=ver_std, ind=ind, ind_mean=ind_mean, tc=tc,
                                  s_tc=s_tc, ver_tc=ver_tc, tc_quick=tc_quick, cond=cond, prec=prec, comp=comp, files=files,
                                  time_s=time.perf_counter() - t_start, n_mc=n_mc, ur_radius_mm=UR10["radius_mm"]))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small searches and samples (a smoke run)")
    main(ap.parse_args().quick)
