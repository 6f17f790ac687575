"""The workflow layer: each job is one Python call, and the command line writes exactly what that call writes.

Every CLI = API test runs the command and the Python call with the same inputs into two folders and compares
every file byte for byte (``summary.json`` parsed, timings left out).
"""

from __future__ import annotations

import json
import re
from pathlib import Path
import warnings

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.units import in_row_unit
from tolalloc.cli import main
from tolalloc.progress import PROGRESS_LINE
from tolalloc.diagnose import generate
from tolalloc.diagnose.synth import split_frame
from tolalloc.outputs import MANIFEST

ROOT = Path(__file__).resolve().parents[1]

#: The README's Python example (tests/test_readme.py checks that the README holds it verbatim).
PYTHON_EXAMPLE = '''\
import tolalloc

res = tolalloc.allocate_tolerances(
    "tool_changer",        # built-in robot, a robot file (.toml, DH .csv, .urdf) or a Robot
    radius_mm=0.25,        # requirement: P(|dP| < 0.25 mm) >= 0.95 ...
    prob=0.95,
    region="working",      # ... over the robot's working region
)                          # the rest: the command line's defaults (10^6 Monte Carlo samples per pose ...)
print(res)                 # robot, requirement, cost, verdict
table = res.to_frame()     # the design to build: tol_mm / tol_deg per parameter, ISO 286 grade, cost, variance share
res.save("reports/python_quickstart")   # the files of `tolalloc allocate tool_changer --out DIR`, the same design
'''


def _timeless(obj):
    """``obj`` without the keys that hold wall-clock times (they differ between two runs)."""
    if isinstance(obj, dict):
        return {k: _timeless(v) for k, v in obj.items() if k not in ("times_s", "time_s")}
    if isinstance(obj, list):
        return [_timeless(v) for v in obj]
    return obj


def assert_same_files(a: Path, b: Path) -> list[str]:
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir())
    for name in names:
        if name.endswith(".json"):
            assert _timeless(json.loads((a / name).read_text())) == _timeless(json.loads((b / name).read_text())), name
        else:
            assert (a / name).read_bytes() == (b / name).read_bytes(), name
    return names


@pytest.mark.slow
def test_python_example_runs_and_prints_the_verdict(tmp_path, monkeypatch, capsys):
    """The README's example as written, its verification shortened for time (20 000 samples per pose instead of the
    default 10^6 the command line uses too: tests/test_settings.py checks that both read the same defaults)."""
    job = tolalloc.allocate_tolerances

    def shortened(*args, **kwargs):
        assert "n_mc" not in kwargs and "verification" not in kwargs  # the example takes the defaults
        return job(*args, **kwargs, n_mc=20_000)

    monkeypatch.setattr(tolalloc, "allocate_tolerances", shortened)
    monkeypatch.chdir(tmp_path)
    exec(compile(PYTHON_EXAMPLE, "README example", "exec"), {})
    out = capsys.readouterr().out
    assert "verification: demonstrated" in out and "tool_changer" in out and "cost:" in out
    assert (tmp_path / "reports" / "python_quickstart" / "tolerances.csv").is_file()


@pytest.mark.slow
def test_allocate_cli_equals_api(tmp_path, capsys):
    # at the nominal pose: the command only parses into the same call (the working region's search is the README
    # example's and test_cli_allocate's)
    argv = ["allocate", "tool_changer", "--region", "nominal", "--n-mc", "2000", "--seed", "3"]
    assert main([*argv, "--out", str(tmp_path / "cli")]) == 0
    printed = capsys.readouterr().out
    res = tolalloc.allocate_tolerances("tool_changer", region=tolalloc.Region("nominal"),
                                       verification=tolalloc.Verification(n_mc=2000, seed=3))
    names = [p.name for p in res.save(tmp_path / "api")]
    assert "verification.csv" in names and res.ok
    assert_same_files(tmp_path / "cli", tmp_path / "api")
    assert res.text() in printed  # the command prints the result's text, then what it wrote


@pytest.mark.slow
def test_calibrated_allocate_cli_equals_api(tmp_path, capsys):
    plan = tmp_path / "plan.csv"
    assert main(["calplan", "tool_changer", "--n-poses", "8", "--n-candidates", "64", "--out", str(plan)]) == 0
    capsys.readouterr()
    api_plan = tolalloc.plan_calibration("tool_changer", 8, n_candidates=64)
    stages = re.findall(r"^plan_calibration tool_changer: (.+): \d+\.\d+ s$", capsys.readouterr().err, re.M)
    assert stages == ["64 candidate poses", "A-optimal 8-pose plan"]  # stderr is no terminal: one line each
    api_plan.save_plan(tmp_path / "plan_api.csv")
    assert plan.read_bytes() == (tmp_path / "plan_api.csv").read_bytes()
    # at the working poses without the standard-grade search (the region path and the standard grades of the same call
    # are the tutorial's and the report test's)
    rc = main(["allocate", "tool_changer", "--calibration", str(plan), "--poses", "working", "--no-snap", "--n-mc",
               "200", "--out", str(tmp_path / "cli")])
    res = tolalloc.allocate_tolerances("tool_changer", calibration=plan, region=tolalloc.Region(poses="working"),
                                       solver=tolalloc.Solver(snap=False), n_mc=200)
    assert isinstance(res, tolalloc.CalibratedToleranceAllocation) and rc == (0 if res.ok else 1)
    res.save(tmp_path / "api")
    assert_same_files(tmp_path / "cli", tmp_path / "api")


def test_analyze_cli_equals_api(tmp_path):
    argv = ["analyze", "ur10", "--poses", "working", "--radius-mm", "0.5", "--prob", "0.9", "--clearance"]
    assert main([*argv, "--out", str(tmp_path / "cli"), "--json", str(tmp_path / "cli.json")]) == 0
    res = tolalloc.analyze_errors("ur10", poses="working", radius_mm=0.5, prob=0.9,
                                  error_model=tolalloc.ErrorModelOptions(clearance=True))
    res.save(tmp_path / "api", json=tmp_path / "api.json")
    assert_same_files(tmp_path / "cli", tmp_path / "api")
    assert (tmp_path / "cli.json").read_bytes() == (tmp_path / "api.json").read_bytes()


def test_mc_cli_equals_api(tmp_path):
    argv = ["mc", "tool_changer", "--n", "3000", "--seed", "7", "--pose", "15,30,-10,0,-20,-5", "--hist-bins", "20"]
    assert main([*argv, "--out", str(tmp_path / "cli")]) == 0
    res = tolalloc.simulate_errors("tool_changer", q_deg_mm=[15, 30, -10, 0, -20, -5],
                                   monte_carlo=tolalloc.MonteCarlo(n_mc=3000, seed=7, hist_bins=20))
    assert {p.name for p in res.save(tmp_path / "api")} | {MANIFEST} == {p.name for p in (tmp_path / "api").iterdir()}
    assert_same_files(tmp_path / "cli", tmp_path / "api")


@pytest.mark.slow
def test_diagnose_cli_equals_api_with_a_dataframe(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1795000000")  # report.html carries its date
    robot = tolalloc.load_robot("tool_changer")
    case = generate(robot, "backlash", 80, np.random.default_rng(5))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    tr.to_csv(tmp_path / "train.csv", index=False)
    te.to_csv(tmp_path / "test.csv", index=False)
    argv = ["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
            "--folds", "3"]
    assert main([*argv, "--report", str(tmp_path / "cli"), "--json", str(tmp_path / "cli.json"),
                 "--predictions", str(tmp_path / "cli_pred.csv")]) == 0
    res = tolalloc.diagnose_measurements("tool_changer", tmp_path / "train.csv", tmp_path / "test.csv", folds=3)
    res.save(tmp_path / "api", report=True, json=tmp_path / "api.json", predictions=tmp_path / "api_pred.csv")
    assert_same_files(tmp_path / "cli", tmp_path / "api")
    assert (tmp_path / "cli_pred.csv").read_bytes() == (tmp_path / "api_pred.csv").read_bytes()
    cli_js, api_js = json.loads((tmp_path / "cli.json").read_text()), json.loads((tmp_path / "api.json").read_text())
    assert cli_js == api_js
    # the headline's RMS is the JSON's test_rms_mm (the test file's, not the cross-validation's)
    rms = api_js["test_rms_mm"]
    assert res.headline()[2] == f"test RMS [mm]: nominal {rms['nominal']:.4f}, geometric {rms['geometric']:.4f}, " \
                                f"final {rms['final']:.4f}"
    # the same measurements as DataFrames give the same diagnosis (the sources are named differently)
    frames = tolalloc.diagnose_measurements("tool_changer", pd.read_csv(tmp_path / "train.csv"),
                                            pd.read_csv(tmp_path / "test.csv"), folds=3)
    assert frames.effect == res.effect
    np.testing.assert_allclose(frames.to_frame()["rms_mm"], res.to_frame()["rms_mm"], rtol=1e-12)


# ---------------------------------------------------------------------------------------------- results
def test_results_have_a_compact_repr_a_table_and_html():
    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=2000)
    text = repr(res)
    assert len(text.splitlines()) <= 6 and "tool_changer" in text and "cost" in text and res.verdict in text
    assert "<table" in res._repr_html_() and "dl1" in res._repr_html_()
    card = res._repr_html_()  # the note is the table's caption, once, not a column repeated on every row
    assert card.count("the design to build;") == 1 and "tol_continuous_mm" not in card and "<th>tol</th>" in card
    assert "NaN" not in card and "<th>tol_deg</th>" not in card  # a tolerance in its row's unit, no empty cells
    frame = res.to_frame()
    tol = in_row_unit(frame, "tol")
    assert list(frame["parameter"])[:3] == ["dl1", "dl2", "dl3"] and tol.gt(0).all() and "design" not in frame
    s = res.summary()
    assert s["verification"]["verdict"] == res.verdict and s["built"]["cost"] == pytest.approx(res.cost)
    assert res.standard and res.cost >= res.continuous_design.cost  # the standard design is the one to build
    assert s["cost"] == pytest.approx(res.cost) and s["cost_continuous"] == pytest.approx(res.continuous_design.cost)
    assert res.ok and res.verified and s["tables_design"] == res.design_note()
    with pytest.raises(Exception):
        res.cost = 1.0  # frozen
    ax = res.plot_pose_probabilities()
    assert len(ax.figure.axes) == 1 and ax.get_xlabel() == "pose"
    import matplotlib.pyplot as plt

    plt.close("all")
    robot_text = repr(tolalloc.load_robot("ur10"))
    assert len(robot_text.splitlines()) == 1 and "6 joints" in robot_text


def test_a_certified_verification_says_its_second_looks_are_counted_everywhere():
    from tolalloc.report.html_allocation import verdict_legend

    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", solver="certified", n_mc=2000)
    v = res.summary()["verification"]
    words = ("95% simultaneous over 1 pose (Bonferroni: 2 intervals at 97.5% each, a possible second look at each "
             "position interval counted)")
    assert v["criterion"] == "certified" and (v["n_intervals"], v["second_looks"]) == (2, 1)
    assert v["level_per_interval"] == pytest.approx(0.975) and v["intervals"] == words
    assert v["message"].endswith(f"; intervals: {words}") and f"intervals: {words}" in res.text()
    assert verdict_legend(res.verification).endswith(f" Intervals: {words}.")  # the HTML report's legend


def test_an_unverified_allocation_never_says_verified(tmp_path):
    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False)
    assert res.ok and not res.verified  # ok: nothing that was checked failed; verified: nothing was run
    note = res.design_note()
    assert note.startswith("standard grades (discrete-exact), the design to build; NOT verified by Monte Carlo")
    assert "verified" not in note.replace("NOT verified", "")
    res.save(tmp_path / "o")
    assert (tmp_path / "o" / "tolerances.md").read_text().splitlines()[0] == f"design: {note}"
    assert r"NOT verified by Monte Carlo" in (tmp_path / "o" / "tolerances.tex").read_text()
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["tables_design"] == note and s["verified"] is False and "verification" not in s
    assert "verification: not run" in repr(res)
    # the budget figure draws the table of the design to build, the one its title names
    import matplotlib.pyplot as plt

    axes = res.plot_budget()
    frame = res.to_frame()
    widths = [bar.get_width() for bar in axes[0].patches]
    assert widths == pytest.approx(in_row_unit(frame, "tol").tolist())
    assert f"{res.design.label} design, worst pose {res.worst_pose + 1}" in axes[0].figure._suptitle.get_text()
    plt.close(axes[0].figure)


def test_robot_methods_take_interface_units_and_from_dh_builds_a_chain():
    tc = tolalloc.load_robot("tool_changer")
    q = [15, 30, -10, 0, -20, -5]
    # the seed paper's closed form (NOTES_SEED.md): rho = l3 cos30 + (l4 + l5) cos20 + l6
    rho = 796 * np.cos(np.deg2rad(30)) + 800 * np.cos(np.deg2rad(20)) + 165
    z = 525 + 796 * np.sin(np.deg2rad(30)) + 800 * np.sin(np.deg2rad(20))
    np.testing.assert_allclose(tc.fk(q)[:3, 3], [-rho * np.sin(np.deg2rad(15)), rho * np.cos(np.deg2rad(15)), z],
                               atol=1e-9)
    np.testing.assert_allclose(tc.space_jacobian(q), tc.space_jacobian_internal(tc.q_from_interface(q)))
    with pytest.raises(tolalloc.TolallocError, match="q_deg_mm.*outside its limits"):
        tc.fk([0.2, 0.5, -0.1, 0, 200, 0])  # q5 = 200 deg
    table = pd.DataFrame({"name": ["j1", "j2"], "d_mm": [300.0, 0.0], "a_mm": [0.0, 500.0], "alpha_deg": [-90.0, 0.0],
                          "lower_deg_mm": [-170, -120], "upper_deg_mm": [170, 120]})
    arm = tolalloc.Robot.from_dh(table, convention="standard", name="arm", tool_offset_mm=(50, 0, 0))
    # q = (0, 90 deg): the second link points down the first joint's z after the -90 deg twist
    np.testing.assert_allclose(arm.fk([0, 0])[:3, 3], [550, 0, 300], atol=1e-9)
    assert arm.joints[1].upper == pytest.approx(np.deg2rad(120))
    with pytest.raises(tolalloc.TolallocError, match="unknown"):
        tolalloc.Robot.from_dh([{"name": "j", "d_inch": 3, "alpha_deg": 0}], convention="standard")


# ---------------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("call, exc, pattern", [
    (lambda: tolalloc.allocate_tolerances("no_such_robot"), FileNotFoundError, "not a built-in robot"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", prob=1.2), ValueError, r"^prob: expected a probability"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", prob=0), ValueError, r"^prob: expected a probability"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", radius_mm=-1), ValueError, r"^radius_mm: expected"),
    (lambda: tolalloc.analyze_errors("tool_changer", q_deg_mm=[1, 2, 3]), ValueError,
     r"^q_deg_mm: robot 'tool_changer' has 6 joints"),
    (lambda: tolalloc.analyze_errors("tool_changer", q_deg_mm=[0.2, 0.5, -0.1, 0, 3.5, -0.1]), ValueError,
     r"^q_deg_mm: .* look like radians; expected degrees .*trust_units=True"),
    (lambda: tolalloc.analyze_errors("tool_changer", q_deg_mm=[0, 0, 0, 0, 200, 0]), ValueError,
     r"^q_deg_mm: joint j5 = 200 deg is outside its limits"),
    (lambda: tolalloc.simulate_errors("tool_changer", 0), ValueError, r"^n_mc: expected a whole number >= 1"),
    (lambda: tolalloc.simulate_errors("tool_changer", 10, radius_mm=[0.1, -2]), ValueError, r"^radius_mm:"),
    (lambda: tolalloc.plan_calibration("tool_changer", 10, n_candidates=5), ValueError, r"^n_poses:"),
    (lambda: tolalloc.diagnose_measurements("tool_changer", pd.DataFrame({"q1": [0.0], "x_mm": [1.0]})), ValueError,
     r"missing column"),
    (lambda: tolalloc.diagnose_measurements("tool_changer", "no/such/file.csv"), FileNotFoundError, "does not exist"),
])
def test_bad_input_raises_project_errors_naming_the_argument(call, exc, pattern):
    with pytest.raises(tolalloc.TolallocError, match=pattern) as info:
        call()
    assert isinstance(info.value, exc)


Q1 = [15, 30, -10, 0, -20, -5]


def _old(call):
    """``call``, made with a deprecated keyword, with its DeprecationWarning asserted."""
    def run():
        with pytest.warns(DeprecationWarning, match="are deprecated"):
            return call()
    return run


@pytest.mark.parametrize("call, argument, pattern", [
    (lambda: tolalloc.allocate_tolerances("tool_changer", region=tolalloc.Region(where="working", poses="working"),
                                          verification=False), "Region.where",
     r"^Region.where: 'working' and `poses` 'working' both say where the requirement holds; give one of them"),
    (lambda: tolalloc.analyze_errors("tool_changer", poses="working", q_deg_mm=Q1), "q_deg_mm",
     r"^q_deg_mm: list \[15, .*\] and `poses` 'working' both give the poses; give one of them"),
    (lambda: tolalloc.simulate_errors("tool_changer", 10, poses="working", q_deg_mm=Q1), "q_deg_mm",
     r"^q_deg_mm: .* and `poses` 'working' both give the poses; give one of them"),
    # the old keywords (DeprecationWarning asserted): each meets the argument that replaced it, or reads nothing
    (_old(lambda: tolalloc.allocate_tolerances("tool_changer", poses="working", region="working", verification=False)),
     "region", r"^region: 'working' and `poses` 'working' both say where the requirement holds; give one of them"),
    (_old(lambda: tolalloc.simulate_errors("tool_changer", 10, angle_radius_deg=0.1, angle_radius_rad=0.002)),
     "angle_radius_rad", r"^angle_radius_rad 0.002 and `angle_radius_deg` 0.1 both give the radii of the rotation "
                         r"error; give angle_radius_deg only"),
    (_old(lambda: tolalloc.plan_calibration("tool_changer", 8, n_candidates=64, radius_mm=0.1)), "radius_mm",
     r"^radius_mm 0.1 is read only for a plan designed for an allocation, but `for_allocation` is off"),
    (lambda: tolalloc.plan_calibration("tool_changer", 8, n_candidates=64, random_plans=5), "random_plans",
     r"^random_plans 5 is read only .* add `for_allocation`"),
    (lambda: tolalloc.plan_calibration("tool_changer", 8, n_candidates=64,
                                       measurement=tolalloc.Measurement(noise_deg=0.01)), "Measurement.noise_deg",
     r"^Measurement.noise_deg 0.01 is the orientation noise of pose measurements, but `kind` is position"),
    (lambda: tolalloc.diagnose_measurements("tool_changer", pd.DataFrame(), test_frame="refit"), "test_frame",
     r"^test_frame needs `test`: 'refit' re-registers a test file"),
])
def test_arguments_one_of_which_would_be_ignored_are_refused(call, argument, pattern):
    """Two arguments that say the same thing, or an option nothing reads, are refused before any computation."""
    with pytest.raises(tolalloc.ArgumentError, match=pattern) as info:
        call()
    assert info.value.argument == argument and "\n" not in str(info.value)


def test_region_and_poses_together_read_as_flags(capsys):
    assert main(["allocate", "tool_changer", "--region", "working", "--poses", "working", "--no-verify"]) == 2
    assert capsys.readouterr().err.strip() == ("error: --region: 'working' and --poses 'working' both say where the "
                                               "requirement holds; give one of them (--region also takes a pose set "
                                               "name).")

def test_radians_are_accepted_when_trusted():
    q = [0.2, 0.5, -0.1, 0, 0.35, -0.1]
    a = tolalloc.analyze_errors("tool_changer", q_deg_mm=q, trust_units=True)
    np.testing.assert_allclose(a.linear.q[0], np.deg2rad(q))


def test_argument_errors_read_as_flags_on_the_command_line(capsys):
    assert main(["allocate", "tool_changer", "--prob", "1.5", "--no-verify"]) == 2
    assert capsys.readouterr().err.startswith("error: --prob: expected a probability strictly between 0 and 1")
    with pytest.raises(tolalloc.ArgumentError) as info, pytest.warns(DeprecationWarning, match="angle_prob"):
        tolalloc.allocate_tolerances("tool_changer", angle_prob=0.9)  # the old keyword, named as given
    assert info.value.argument == "angle_prob" and "`angle_radius_deg`" in str(info.value)
    assert main(["allocate", "tool_changer", "--angle-prob", "0.9", "--no-verify"]) == 2
    assert "--angle-prob 0.9 needs an orientation requirement: add --angle-radius-deg" in capsys.readouterr().err


def test_public_surface_is_stated_once_and_documented():
    for name in tolalloc.__all__:
        obj = getattr(tolalloc, name)
        assert obj.__doc__ and len(obj.__doc__.strip()) > 20, name
    for fn in (tolalloc.allocate_tolerances, tolalloc.analyze_errors, tolalloc.simulate_errors,
               tolalloc.plan_calibration, tolalloc.diagnose_measurements):
        doc = fn.__doc__
        assert "Parameters" in doc and "Returns" in doc, fn.__name__
        assert re.search(r"\[mm\]|_mm|deg", doc), fn.__name__
    assert not hasattr(tolalloc, "fk_poe")  # the POE kernel lives in tolalloc.robot (its signature is not a robot's)


def test_analyze_with_sobol_indices_beside_the_linear_budget(tmp_path):
    a = tolalloc.analyze_errors("tool_changer", poses="working", sobol_n=256, radius_mm=2.0)
    frame = a.sobol.to_frame()
    assert set(frame["parameter"]) <= set(a.model.names) and frame["ST_norm"].between(-0.1, 1.1).all()
    # dominant linear contributors are the dominant nonlinear ones at these small errors
    top_lin = set(a.budget_frame().head(3)["parameter"])
    assert top_lin & set(frame.sort_values("ST_norm", ascending=False).head(4)["parameter"])
    assert "sobol" in a.summary() and "Sobol' indices" in a.text()
    assert tmp_path / "out" / "sobol.csv" in a.save(tmp_path / "out")
    with pytest.raises(tolalloc.ArgumentError, match="sobol_n"):
        tolalloc.analyze_errors("tool_changer", sobol_n=8)


@pytest.mark.slow
def test_plan_designed_for_the_allocation_against_random_plans(tmp_path):
    d = tolalloc.plan_calibration("ur10", 10, n_candidates=60, for_allocation=True, random_plans=12)
    s = d.summary()
    fa, rnd = s["for_allocation"], s["random_plans"]
    assert fa["cost"] <= fa["start_cost"] + 1e-9  # a plan is kept only when the allocation gets cheaper
    assert rnd["n_random"] == 12 and rnd["designed_worst_p"] >= rnd["random_p90"]
    assert rnd["designed_worst_p"] <= rnd["all_candidates_worst_p"] + 1e-9  # no plan beats measuring every candidate
    assert "random 10-pose plans" in d.text()
    d.save_plan(tmp_path / "plan.csv")
    res = tolalloc.allocate_tolerances("ur10", calibration=tmp_path / "plan.csv", solver=tolalloc.Solver(snap=False),
                                       verification=False)
    assert res.continuous_cost == pytest.approx(fa["cost"], rel=1e-6)


def test_a_robot_without_a_working_set_is_allocated_at_the_nominal_pose_with_a_warning(tmp_path, capsys):
    arm = tolalloc.Robot.from_dh([{"name": "j1", "d_mm": 400, "a_mm": 0, "alpha_deg": 90},
                                  {"name": "j2", "d_mm": 0, "a_mm": 600, "alpha_deg": 0}], convention="standard",
                                 name="arm")
    with pytest.warns(UserWarning, match=r"^robot 'arm' has no working region or pose set: allocated at the nominal "
                                         r"pose only \(1 pose\); for the working region pass region='limits' "
                                         r"\(--region limits"):
        res = tolalloc.allocate_tolerances(arm, verification=False)
    assert res.problem.n_poses == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # asked for, or a robot with a working set: no warning
        from tolalloc.workflows.inputs import resolve_region

        assert resolve_region(arm, "nominal")[0] == "nominal" and resolve_region(arm, None, "nominal")[0] == "nominal"
        assert resolve_region(tolalloc.load_robot("ur10"))[0] == "working"
    path = tmp_path / "arm.csv"
    path.write_text("# convention: standard\nname,d_mm,a_mm,alpha_deg\nj1,400,0,90\nj2,0,600,0\n")
    assert main(["allocate", str(path), "--no-verify"]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if not PROGRESS_LINE.match(line)]  # no terminal
    assert err == ["warning: robot 'arm' has no working region or pose set: allocated at the nominal pose only (1 pose); "
                   "for the working region pass region='limits' (--region limits: the box of the joint limits), a pose "
                   "set or a trajectory, or add a [regions.working] box to the robot file."], err


@pytest.mark.parametrize("call, name, suggestion", [
    (lambda: tolalloc.allocate_tolerances("tool_changer", radius=0.25), "radius", "radius_mm"),
    (lambda: tolalloc.simulate_errors("tool_changer", n_m=100), "n_m", "n_mc"),
    (lambda: tolalloc.analyze_errors("tool_changer", q_deg=[0] * 6), "q_deg", "q_deg_mm"),
    (lambda: tolalloc.diagnose_measurements("ur10", "absent.csv", fold=3), "fold", "folds"),
    (lambda: tolalloc.plan_calibration("tool_changer", n_pose=3), "n_pose", "n_poses"),
])
def test_a_keyword_the_call_does_not_have_names_the_closest(call, name, suggestion):
    with pytest.raises(tolalloc.UnknownArgumentError) as info:
        call()
    err = info.value
    assert isinstance(err, TypeError) and isinstance(err, tolalloc.TolallocError) and err.argument == name
    assert f"has no argument {name!r}; did you mean {suggestion}? help(tolalloc." in str(err)
    assert "\n" not in str(err)


def test_an_unknown_keyword_with_nothing_close_lists_no_guess():
    with pytest.raises(TypeError, match=r"^xyz: allocate_tolerances\(\) has no argument 'xyz'; "
                                        r"help\(tolalloc.allocate_tolerances\) lists them all\.$"):
        tolalloc.allocate_tolerances("tool_changer", xyz=1)
