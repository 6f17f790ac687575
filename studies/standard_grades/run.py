"""Study: standard grades chosen by the optimiser against rounding (tool_changer and ur10).

Writes reports/standard_grades/: README.md and CSV tables.

1. For the quick-start requirement P(|dP| < 0.25 mm) >= 0.95 with the built-in (assumed) cost laws:
   the tool_changer over its ``working`` box (cutting planes from the 12 working poses, then the standard loop,
   :func:`tolalloc.allocate.region_standard.allocate_region_standard`), the ur10 at its 6 working poses (its
   quick-start default) and over its joint limits: continuous exact design, standard design (grades and steps
   chosen by the optimiser under the exact probability), the rounding it replaces, and the certified
   eigenvalue rule's discrete optimum with its proven bound; nonlinear Monte Carlo of the standard design.
2. Why the premium is not zero: the proven integrality gap of the certified rule, and the premium against the
   angle resolution and the grade range (tool_changer, 12 working poses).
3. Processes: the example table ``processes.toml`` (assumed costs): which link takes which process.

Usage: python studies/standard_grades/run.py [--quick]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc import load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.costs import cost_set, read_costs_file
from tolalloc.units import in_row_unit
from tolalloc.allocate.problem import make_design
from tolalloc.allocate.region import box_region, coverage
from tolalloc.allocate.region_standard import allocate_region_standard
from tolalloc.errormodel import build_error_model
from tolalloc.verify.correct import CONFIRM_SEED_OFFSET, needed_targets
from tolalloc.verify.designs import verify_design
from tolalloc.report.tables import markdown_table

HERE = Path(__file__).resolve().parent
OUT = HERE.parents[1] / "reports" / "standard_grades"
RADIUS_MM, PROB, SEED = 0.25, 0.95, 2024


def md(df: pd.DataFrame, floatfmt=".4g") -> str:
    return markdown_table(df, floatfmt)


def case(name: str, robot, model, where: str):
    """(result, region allocation or None, verification poses q, time [s])."""
    t0 = time.perf_counter()
    if where == "pose set":
        res = allocate(build_problem(model, robot.poses("working"), radius_mm=RADIUS_MM, prob=PROB),
                       discrete_certified=True)
        return res, None, res.problem.q, time.perf_counter() - t0
    lo, hi = robot.regions["working"] if where == "working box" else (robot.lower, robot.upper)
    box = box_region(robot, lo, hi, where)
    q0 = robot.poses("working") if where == "working box" else None
    ra = allocate_region_standard(model, box, q0, radius_mm=RADIUS_MM, prob=PROB, discrete_certified=True)
    cov = coverage(ra.result.problem, ra.result.standard.t, box, n=100_000, seed=SEED)
    return ra.result, (ra, cov), np.vstack([ra.result.problem.q, cov.worst_q]), time.perf_counter() - t0


def verify_standard(model, res, q, n_mc: int):
    """Monte Carlo of the standard design at ``q``; one correction round (targets raised where it falls short)."""
    pr = build_problem(model, q, radius_mm=RADIUS_MM, prob=PROB)
    d = make_design(pr, res.standard.solver, res.standard.t)
    ver = verify_design(pr, d, n_mc=n_mc, seed=SEED, keep_samples=0)
    if ver.verdict in ("demonstrated", "consistent"):
        return ver, None, None
    target = needed_targets(ver, np.full(len(q), PROB))
    res2 = allocate(build_problem(model, q, radius_mm=RADIUS_MM, prob=PROB, target=target))
    pr2 = build_problem(model, q, radius_mm=RADIUS_MM, prob=PROB)
    # judged on fresh draws: the targets were raised from the draws of ``ver``
    ver2 = verify_design(pr2, make_design(pr2, res2.standard.solver, res2.standard.t), n_mc=n_mc,
                         seed=SEED + CONFIRM_SEED_OFFSET, keep_samples=0)
    return ver, res2, ver2


def section1(n_mc: int) -> tuple[list, list]:
    rows, lines = [], []
    for name, where in (("tool_changer", "working box"), ("ur10", "pose set"), ("ur10", "joint limits")):
        robot = load_robot(name)
        model = build_error_model(robot)
        res, reg, q, dt = case(name, robot, model, where)
        disc = res.discrete
        lmi = next((o for o in disc.outcomes if o.rule == "lmi"), None)
        cont_lmi = next(d for d in (res.certified, res.certified_other) if d.solver == "certified-lmi")
        ver, res2, ver2 = verify_standard(model, res, q, n_mc)
        rows.append({
            "robot": name, "where": where, "poses": res.problem.n_poses, "cost_continuous": res.design.cost,
            "cost_standard": res.standard.cost, "standard_premium_pct": disc.gap_pct,
            "cost_rounded": res.rounded.cost, "rounded_premium_pct": disc.rounded_premium_pct,
            "cost_lmi_continuous": cont_lmi.cost, "cost_lmi_standard": lmi.cost if lmi else np.nan,
            "lmi_bound": lmi.bound if lmi else np.nan, "lmi_status": lmi.status if lmi else "",
            "lmi_premium_pct": 100 * (lmi.cost / cont_lmi.cost - 1) if lmi else np.nan,
            "lmi_premium_lower_bound_pct": 100 * (max(lmi.bound, cont_lmi.cost) / cont_lmi.cost - 1) if lmi else np.nan,
            "time_s": dt, "mc_poses": len(q), "mc_verdict": ver.verdict,
            "corrected_cost": res2.standard.cost if res2 is not None else np.nan,
            "corrected_verdict": ver2.verdict if ver2 is not None else ""})
        table = _grades_table(res)[["parameter", "unit", "tolerance", "tolerance_std", "grade", "tolerance_rounded",
                                    "cost", "cost_std"]]
        table.insert(6, "grade_rounded", [g for g in res.rounded_grade])
        tag = f"{name}_{where.replace(' ', '_')}"
        table.to_csv(OUT / f"grades_{tag}.csv", index=False, float_format="%.6g")
        lines += [f"### {name}, {where}", "",
                  disc.message_line() + ".", ""]
        if reg is not None:
            ra, cov = reg
            lines += [f"Region: continuous cutting planes {ra.continuous.rounds} round(s), then {ra.rounds} round(s) "
                      f"with the standard design ({'converged' if ra.converged else 'NOT converged'}; "
                      f"{len(ra.active_q)} active poses; worst linear P of the standard design found "
                      f"{ra.worst_p:.5f}); {ra.time_s:.1f} s in all. Standard design on 10^5 fresh poses of the box "
                      f"(seed {SEED}): {cov.message(PROB)}.", ""]
        lines += [f"Nonlinear Monte Carlo of the standard design ({n_mc:.0e} samples per pose, {len(q)} poses: the "
                  "active ones and, for a box, the 3 lowest of the fresh sample): " + ver.message() + ".", ""]
        if res2 is not None:
            lines += [f"One correction round (targets raised by the measured shortfall + z + 3 standard errors, the "
                      f"standard design re-chosen, then judged on fresh draws, seed {SEED + CONFIRM_SEED_OFFSET}): "
                      f"cost {res.standard.cost:.4f} -> {res2.standard.cost:.4f} "
                      f"({100 * (res2.standard.cost / res.standard.cost - 1):+.2f} %); " + ver2.message() + ".", ""]
        lines += [f"Grades (`grades_{tag}.csv`; tolerances in mm or deg):", "",
                  md(table, ".4g"), ""]
    return rows, lines


def section2() -> tuple[pd.DataFrame, pd.DataFrame]:
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    q = robot.poses("working")
    steps = []
    for label, step in (("0.1 arcsec", 0.1 / 3600), ("1 arcsec (default)", 1 / 3600), ("0.001 deg (3.6 arcsec)", 0.001),
                        ("10 arcsec", 10 / 3600)):
        res = allocate(build_problem(model, q, radius_mm=RADIUS_MM, prob=PROB), angle_step_deg=step)
        steps.append({"angle_step": label, "cost_continuous": res.design.cost, "cost_standard": res.standard.cost,
                      "standard_premium_pct": res.discrete.gap_pct, "cost_rounded": res.rounded.cost,
                      "rounded_premium_pct": res.discrete.rounded_premium_pct,
                      "rounded_meets": res.rounded.status == "optimal"})
    grades = []
    for g in ("IT5-IT12", "IT7-IT10", "IT3-IT14"):
        costs = cost_set(model, {"kinds": {"link_length": {"grades": g}}})
        res = allocate(build_problem(model, q, radius_mm=RADIUS_MM, prob=PROB, costs=costs))
        grades.append({"grade_range": g, "cost_continuous": res.design.cost, "cost_standard": res.standard.cost,
                       "standard_premium_pct": res.discrete.gap_pct,
                       "grades": " ".join(res.grade[:6])})
    return pd.DataFrame(steps), pd.DataFrame(grades)


def section3():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    costs = cost_set(model, read_costs_file(HERE / "processes.toml"), source="studies/standard_grades/processes.toml")
    res = allocate(build_problem(model, robot.poses("working"), radius_mm=RADIUS_MM, prob=PROB, costs=costs),
                   discrete_certified=True)
    f = _grades_table(res)
    return res, f.loc[f.kind == "link_length", ["parameter", "tolerance", "tolerance_std", "grade", "process",
                                                 "cost_std"]]


def _grades_table(res) -> pd.DataFrame:
    """The study's table: continuous (``tolerance``, ``cost``), standard (``tolerance_std``, ``cost_std``) and rounded
    tolerances in the row's own unit (``unit``), from ``AllocationResult.to_frame()`` of the standard design."""
    f = res.to_frame(res.standard)

    return pd.DataFrame({"parameter": f["parameter"], "kind": f["kind"], "unit": f["unit"],
                         "tolerance": in_row_unit(f, "tol_continuous"), "tolerance_std": in_row_unit(f, "tol"), "grade": f["grade"],
                         "process": f["process"], "tolerance_rounded": in_row_unit(f, "tol_rounded"),
                         "cost": f["cost_continuous"], "cost_std": f["cost"]})


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="10^4 Monte Carlo samples per pose instead of 2 10^5")
    args = ap.parse_args()
    n_mc = 10**4 if args.quick else 2 * 10**5
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows, lines1 = section1(n_mc)
    summary = pd.DataFrame(rows)
    summary.to_csv(OUT / "summary.csv", index=False, float_format="%.6g")
    steps, grades = section2()
    steps.to_csv(OUT / "angle_step.csv", index=False, float_format="%.6g")
    grades.to_csv(OUT / "grade_range.csv", index=False, float_format="%.6g")
    res3, proc = section3()
    proc.to_csv(OUT / "processes.csv", index=False, float_format="%.6g")
    text = report(summary, lines1, steps, grades, res3, proc, n_mc, time.perf_counter() - t0)
    (OUT / "README.md").write_text(text)
    print(f"wrote {OUT}/README.md ({time.perf_counter() - t0:.0f} s)")


def report(summary, lines1, steps, grades, res3, proc, n_mc, dt) -> str:
    cols = ["robot", "where", "poses", "cost_continuous", "cost_standard", "standard_premium_pct", "cost_rounded",
            "rounded_premium_pct", "mc_verdict", "time_s"]
    lmi = ["robot", "where", "cost_lmi_continuous", "cost_lmi_standard", "lmi_status", "lmi_premium_pct",
           "lmi_bound", "lmi_premium_lower_bound_pct"]
    d = res3.discrete
    return "\n".join([
        "# Standard grades chosen by the optimiser", "",
        "Generated by `python studies/standard_grades/run.py`" + (" --quick" if n_mc < 10**5 else "") +
        f" ({dt:.0f} s). Requirement P(|ΔP| < {RADIUS_MM} mm) ≥ {PROB} (the quick start's). Cost laws and process "
        "limits: the built-in defaults of `tolalloc.allocate.costs` (**assumed** relative costs). Standard values: "
        "link lengths ISO 286 IT5-IT12 (±IT/2 at the link's nominal length), angles multiples of 1 arcsec, other "
        "lengths multiples of 1 µm.", "",
        "The *standard* design is chosen by the optimiser (`tolalloc.allocate.discretize`): under the exact "
        "Gaussian probability, an outer approximation (mixed-integer linear programs over the grades and step "
        "multiples, HiGHS through cvxpy) followed by a local search; it meets the requirement at every pose by the "
        "exact probability but is not a proven optimum. The *rounded* design is what the tool did before: the "
        "continuous design rounded down to the standard values. For the certified eigenvalue rule the discrete "
        "optimum is proven (relative gap ≤ 1e-3), which bounds from below what any standard design meeting that "
        "rule costs.", "",
        "## 1. Premium over the continuous optimum", "",
        md(summary[cols]), "",
        "Certified eigenvalue rule, standard values (proven by the MILP; `lmi_premium_lower_bound_pct`: no standard "
        "design meeting the rule costs less than this over the continuous rule optimum):", "",
        md(summary[lmi]), "",
        *lines1,
        "## 2. Why the premium is not zero", "",
        why(summary, steps, grades), "",
        md(steps), "",
        md(grades), "",
        "## 3. Processes (example table, assumed costs)", "",
        "`studies/standard_grades/processes.toml`: link lengths by grinding (IT6-IT9, a cost per grade, a set-up "
        "per link) or by milling (IT10-IT12 only, the default cost law); each link chooses its process with its "
        "grade (tool_changer, 12 working poses). With processes the standard design's costs come from the process "
        "table, so its premium over the continuous design (priced with the default laws) compares two cost "
        "models. " + d.message_line() + ".", "",
        md(proc), ""])


def why(summary, steps, grades) -> str:
    """The explanation of section 2, from the numbers of this run."""
    s = summary.iloc[0]
    fine, dflt = steps.iloc[0], steps.iloc[1]
    same = grades.standard_premium_pct.max() - grades.standard_premium_pct.min() < 0.01
    return (
        "A continuous optimum sets every tolerance where its marginal cost equals its marginal contribution to the "
        "budget; standard values are a lattice (IT grades step by x1.5-1.6; an angle of 14 arcsec by 7 % per "
        "arcsec), so some parameters must sit off their continuous values. Choosing the values jointly recovers "
        f"most of the rounding's loss ({s.rounded_premium_pct:.2f} % -> {s.standard_premium_pct:.2f} % on the "
        f"{s.robot} {s['where']}): a link loosened by a grade is paid for by angles tightened by an arcsec or two. "
        "What is left is mostly the link grades' coarse lattice, not the angle resolution: with 0.1 arcsec "
        f"instead of 1 arcsec the premium only moves from {dflt.standard_premium_pct:.2f} % to "
        f"{fine.standard_premium_pct:.2f} %, while coarser angle steps raise it (table below)"
        + ("; the grade range does not matter here (the chosen grades lie inside every range tried)" if same
           else "") + ". For the certified eigenvalue rule the MILP proves the floor: no standard design meeting "
        f"that rule costs less than {s.lmi_premium_lower_bound_pct:.2f} % over the rule's continuous optimum "
        f"({s.robot}, {s['where']}), of the same order as the exact design's premium ({s.standard_premium_pct:.2f} %).")


if __name__ == "__main__":
    main()
