"""allocate_tolerances(..., calibration=PLAN): every option honoured or refused, the result shaped like the plain one.

solver="certified" stops after the certified stage; the options the calibration-aware allocation has no use for
(the correction loop, a scheduler, the importance sampler, an orientation requirement) are refused by name, in
Python and on the command line; the result has status, ok, verification_frame and the plain table's core columns,
writes the plain file names, and says truthfully what became of the parameters the plan cannot identify.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.units import in_row_unit
from tolalloc.cli import main
from tolalloc.workflows import allocate_tolerances


@pytest.fixture(scope="module")
def certified(plan_path):
    """Certified stage only, no standard grades, a small end-to-end Monte Carlo; correction=False is honoured."""
    return allocate_tolerances("tool_changer", calibration=plan_path, region=tolalloc.Region(poses="nominal"),
                               solver=tolalloc.Solver(method="certified", snap=False),
                               verification=tolalloc.Verification(n_mc=200, seed=4, estimator="plain",
                                                                  correction=False))


@pytest.fixture(scope="module")
def plain():
    return allocate_tolerances("tool_changer", region=tolalloc.Region(poses="nominal"),
                               solver=tolalloc.Solver(snap=False), verification=False)


def test_solver_certified_stops_after_the_certified_stage(certified):
    res = certified.result
    assert res.exact is None and res.design is res.certified.design
    s = certified.summary()
    assert s["design"] == "calibrated-lmi" and s["solver_requested"] == "certified" and s["cost_exact"] is None
    assert s["end_to_end"]["design"] == "certified"  # judged as a certified design: demonstrated at every pose
    assert certified.stages() == "certified -> exact (not run: solver='certified')"
    text = certified.text()
    assert "exact stage: not run (solver='certified')" in text and "design: exact" not in text
    assert "stages: certified -> exact (not run: solver='certified')" in repr(certified)


def test_solver_exact_runs_both_stages(plan_path):
    job = allocate_tolerances("tool_changer", calibration=plan_path, region=tolalloc.Region(poses="nominal"),
                              solver=tolalloc.Solver(snap=False), verification=False)
    assert job.result.exact_accepted and job.summary()["design"] == "exact"
    assert job.stages() == "certified -> exact" and "exact stage: not run" not in job.text()
    assert "end-to-end Monte Carlo: not run (verification=False)" in job.text()
    frame = job.to_frame()
    f = np.array([p.to_interface for p in job.problem.model.params])
    np.testing.assert_allclose(in_row_unit(frame, "tol_certified"), job.result.certified.design.t * f)
    np.testing.assert_allclose(in_row_unit(frame, "tol_continuous"), job.result.exact.design.t * f)
    np.testing.assert_allclose(in_row_unit(frame, "tol"), job.result.exact.design.t * f)  # snap=False: built = exact



@pytest.mark.parametrize("kw, match", [
    (dict(verification=tolalloc.Verification(correction=True)),
     r"^Verification.correction: expected False or nothing with `calibration` \(the calibration-aware allocation "
     r"\(`calibration`\) has no correction loop"),
    (dict(verification=tolalloc.Verification(correction_rounds=3)),
     r"^Verification.correction_rounds: expected nothing with `calibration` .*, got 3; leave out `correction_rounds`\.$"),
    (dict(verification=tolalloc.Verification(scheduler="threads")),
     r"^Verification.scheduler: expected nothing with `calibration` .*takes no scheduler\), got 'threads'; leave out "
     r"`scheduler`\.$"),
    (dict(verification=tolalloc.Verification(estimator="importance")),
     r"^Verification.estimator: expected one of 'auto', 'plain', 'paired' with `calibration` .*no importance "
     r"sampler\), got 'importance'"),
    (dict(requirement=[tolalloc.PositionRequirement(), tolalloc.OrientationRequirement(radius_deg=0.02)]),
     r"^requirement: P\(\|dw\| < 0.02 deg\) >= p of the position requirement is not handled by the "
     r"calibration-aware allocation \(`calibration`: the position requirement only\)"),
])
def test_options_the_calibrated_path_cannot_honour_are_refused(plan_path, kw, match):
    with pytest.raises(tolalloc.ArgumentError, match=match):
        allocate_tolerances("tool_changer", calibration=plan_path, **kw)


@pytest.mark.parametrize("argv, flag", [(["--correction-rounds", "3"], "--correction-rounds"),
                                        (["--scheduler", "threads"], "--scheduler"),
                                        (["--estimator", "importance"], "--estimator")])
def test_cli_refuses_them_with_one_line(plan_path, tmp_path, capsys, argv, flag):
    out = tmp_path / "res"
    rc = main(["allocate", "tool_changer", "--calibration", str(plan_path), *argv, "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith(f"error: {flag}: expected") and "with --calibration" in err
    assert err.count("\n") == 1 and not out.exists()


def test_same_interface_as_the_plain_allocation(certified, plain):
    assert certified.status == "optimal" and certified.ok
    # the plain table's handover columns (callout, cost_source) are not in the calibration-aware table yet
    core = [c for c in plain.to_frame().columns if c not in ("design", "callout", "cost_source")]
    frame = certified.to_frame()
    assert list(frame.columns[:len(core)]) == core  # the plain table's columns, in its order, then the calibrated
    assert {"status", "tol_no_calibration_mm", "sigma_post_calibration_deg", "sigma_random_mm"} <= set(frame.columns)
    for col in ("parameter", "kind", "element", "unit", "role"):
        assert list(frame[col]) == list(plain.to_frame()[col])
    z = certified.problem.costs.z
    np.testing.assert_allclose(in_row_unit(frame, "sigma"), in_row_unit(frame, "tol") / z)
    assert frame["variance_share_pct"].sum() == pytest.approx(100.0)
    loose = frame["status"] == "loose (at t_max)"
    assert loose.any() and (frame.loc[loose, "at_limit"] == "t_max").all()
    ver = certified.verification_frame()
    chk = certified.end_to_end.check
    joints = [f"{j.name}_{j.unit}" for j in certified.robot.joints]
    assert list(ver.columns[:1 + len(joints)]) == ["pose", *joints] and len(ver) == len(chk.p_mc)
    assert {"p_linear", "p_mc", "ci_low", "ci_high", "n", "verdict"} <= set(ver.columns)
    assert (ver["n"] == certified.n_robots).all()
    # the intervals' level, as in the plain verification.csv: each one's and the family's, then the sample count
    cols = list(ver.columns)
    assert cols[cols.index("ci_high") + 1:cols.index("n") + 1] == ["level_per_interval", "family_level", "n"]
    assert (ver["family_level"] == 0.95).all()
    np.testing.assert_allclose(ver["level_per_interval"], 1 - 0.05 / len(chk.p_mc))
    np.testing.assert_allclose(ver[joints].to_numpy(), certified.robot.q_to_interface(chk.q))


def test_save_writes_the_plain_file_names(certified, tmp_path):
    paths = certified.save(tmp_path / "res")
    assert paths == [tmp_path / "res" / n for n in ("tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json",
                                                     "verification.csv")]
    frame = pd.read_csv(tmp_path / "res" / "tolerances.csv", keep_default_na=False)
    assert list(frame.columns) == list(certified.to_frame().columns)
    md = (tmp_path / "res" / "tolerances.md").read_text().splitlines()[0]
    assert md.startswith("design to build: the continuous calibrated-lmi calibration-aware design in tol_mm / tol_deg")
    assert "Status after the plan -- " in md and "calibrated away: " in md
    legend = (tmp_path / "res" / "tolerances.md").read_text().rstrip().splitlines()[-1]
    assert legend.startswith("Tolerances are symmetric ± half-widths of the design to build.") and "status:" in legend
    ver = pd.read_csv(tmp_path / "res" / "verification.csv")
    assert list(ver.columns) == list(certified.verification_frame().columns)
    s = json.loads((tmp_path / "res" / "summary.json").read_text())
    assert s["end_to_end"]["n_robots"] == 200 and s["solver_requested"] == "certified"
    e2e = s["end_to_end"]
    assert e2e["n_intervals"] == e2e["poses"] and e2e["family_level"] == 0.95
    assert e2e["level_per_interval"] == pytest.approx(1 - 0.05 / e2e["poses"])


def test_unidentifiable_parameters_are_split_by_what_the_allocation_did(certified):
    s, frame = certified.summary(), certified.to_frame()
    status = dict(zip(frame["parameter"], frame["status"]))
    held, loose = s["unidentifiable_held"], s["unidentifiable_loose"]
    assert held and loose and sorted(held + loose) == sorted(s["unidentifiable"])
    assert {status[n] for n in held} == {"must be held"} and {status[n] for n in loose} == {"loose (at t_max)"}
    # not identifiable individually: each with its post-calibration sigma as a fraction of the manufactured one
    frac = s["unidentifiable_sigma_fraction"]
    assert list(frac) == s["unidentifiable"]
    ratio = in_row_unit(frame, "sigma_post_calibration") / in_row_unit(frame, "sigma")  # Gaussian: prior = sigma
    for name, f in frac.items():
        assert f == pytest.approx(ratio[list(frame["parameter"]).index(name)], rel=1e-9) and 0 < f <= 1 + 1e-9
    words = lambda names: ", ".join(f"{n} ({frac[n]:.2f})" for n in names)  # noqa: E731
    text = certified.text()
    assert "not identifiable individually by the plan (each enters a combination" in text
    assert "as manufactured):" not in text  # the old heading, untrue for parameters reduced in combination
    assert f"allocated tight, must be held in manufacturing: {words(held)}" in text
    assert f"loose (at the process limit t_max or the coarsest standard grade), which suffices: {words(loose)}" in text


def test_verified_means_the_end_to_end_monte_carlo_ran_and_passed(certified, plan_path):
    assert certified.end_to_end is not None and certified.end_to_end.passed
    assert certified.verified is True and certified.ok
    unverified = allocate_tolerances("tool_changer", calibration=plan_path, region=tolalloc.Region(poses="nominal"),
                                     solver=tolalloc.Solver(method="certified", snap=False), verification=False)
    assert unverified.ok and unverified.verified is False  # as ToleranceAllocation.verified: False when none ran


@pytest.fixture(scope="module")
def designed():
    return tolalloc.plan_calibration("tool_changer", 8, n_candidates=48)


def test_the_plan_calibration_result_is_a_calibration(designed, tmp_path):
    """The CalibrationPlanDesign itself is taken (its plan, no file), with the same result as its saved CSV."""
    from tolalloc.workflows.calibrated import PLAN_IN_MEMORY
    from tolalloc.workflows.reproduce import allocation_command

    kw = dict(region=tolalloc.Region(poses="nominal"), solver=tolalloc.Solver(method="certified", snap=False),
              verification=False)
    job = allocate_tolerances("tool_changer", calibration=designed, **kw)
    assert job.plan is designed.plan and job.plan_source == PLAN_IN_MEMORY and job.plan_file is None
    assert job.summary()["plan_file"] is None and PLAN_IN_MEMORY in job.text()
    designed.save_plan(tmp_path / "plan.csv")
    from_file = allocate_tolerances("tool_changer", calibration=tmp_path / "plan.csv", **kw)
    assert from_file.plan_file == str(tmp_path / "plan.csv")
    assert job.cost == pytest.approx(from_file.cost, rel=1e-9)
    cli, python, notes = allocation_command(job)  # the reproduce command asks for the plan saved to a file
    assert "--calibration PLAN.csv" in cli and "calibration='PLAN.csv'" in python
    assert any("plan.save_plan('PLAN.csv')" in n for n in notes)


def test_a_plan_designed_for_another_robot_is_refused_in_one_line(designed):
    from dataclasses import replace

    other = replace(designed, robot=tolalloc.load_robot("ur10"))
    with pytest.raises(tolalloc.TolallocError, match="designed for the robot 'ur10', but the allocation is for "
                                                     "'tool_changer'") as err:
        allocate_tolerances("tool_changer", calibration=other, region=tolalloc.Region(poses="nominal"),
                            verification=False)
    assert "\n" not in str(err.value)
    with pytest.raises(tolalloc.TolallocError, match="expected the CalibrationPlanDesign plan_calibration returns"):
        allocate_tolerances("tool_changer", calibration=3, region=tolalloc.Region(poses="nominal"), verification=False)
