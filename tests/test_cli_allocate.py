"""`tolalloc allocate`: outputs, summary keys, infeasible message, bad input."""

import json
from pathlib import Path

import pandas as pd
import pytest

from tolalloc.cli import main


def test_allocate_writes_everything(tmp_path, capsys):
    out = tmp_path / "alloc"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--n-mc", "100000", "--seed", "3", "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 0, text
    assert "status: optimal" in text and "dth2" in text and "verified: " in text
    names = {p.name for p in out.iterdir()}
    assert {"tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json", "error_budget.png",
            "error_cloud.png", "verification.csv", "pose_probabilities.png"} <= names
    s = json.loads((out / "summary.json").read_text())
    # the summary's cost, solver and per-pose linear P are the design to build's; the continuous one's are named so
    assert s["status"] == "optimal" and s["solver"] == "discrete-exact" and s["pose_set"] == "nominal"
    assert s["solver_continuous"] == "exact" and s["cost"] == s["built"]["cost"] == s["costs"]["standard"]
    assert s["cost_continuous"] == s["costs"]["continuous"] < s["cost"] and s["standard_built"] and s["verified"]
    assert s["costs"]["exact"] <= s["costs"]["certified"]
    pose = s["poses"][0]
    for key in ("q_deg_mm", "p_linear", "p_mc", "p_mc_ci"):
        assert key in pose
    assert "q" not in pose  # joint values only under their unit-carrying key
    assert pose["p_mc_ci"][0] <= pose["p_mc"] <= pose["p_mc_ci"][1]
    assert pose["p_mc_ci_level"] == s["verification"]["level_per_interval"]  # the interval names its level
    # the exact design sits on P = 0.95, so its interval straddles p: the correction loop raises the target
    corr = s["correction"]
    assert corr["verdict_before"] == "consistent" and corr["rounds"] >= 1 and corr["poses_tightened"] == [1]
    assert pose["p_linear_continuous"] == pytest.approx(corr["target_per_pose"][0], abs=1e-5)
    assert pose["p_linear"] >= corr["target_per_pose"][0] - 1e-9  # the standard design to build meets it too
    assert corr["cost_after"] > corr["cost_before"] and s["built"]["cost"] == pytest.approx(corr["cost_after"])
    assert s["verification"]["verdict"] == corr["verdict"] == pose["verdict"] == "demonstrated"
    # the corrected design is judged on fresh draws, not on the seed-3 draws its target was raised from
    assert corr["confirm_seed"] == s["verification"]["seed"] == 3 + 1_000_000 and corr["verdict_tuned"] == "demonstrated"
    assert "correction: verified: demonstrated after" in text and "verdict per pose: 1 demonstrated" in text
    md = (out / "tolerances.md").read_text().splitlines()
    assert md[0].startswith("design: standard grades (discrete-exact), the design to build; verified by nonlinear")
    assert "corrected for the nonlinear Monte Carlo" in md[0] and md[0] == f"design: {s['tables_design']}"
    assert md[2] == "**Tolerances of tool_changer: P(|dP| < 0.25 mm) >= 0.95 at the 1 pose(s) of 'nominal'**"
    assert f"table: {s['tables_design']}" in text
    tab = pd.read_csv(out / "tolerances.csv")
    for col in ("parameter", "kind", "unit", "role", "nominal_mm", "tol_mm", "tol_deg", "sigma_mm", "sigma_deg",
                "grade", "cost", "variance_share_pct", "tol_continuous_mm", "tol_continuous_deg"):
        assert col in tab.columns
    assert not {"design", "tolerance", "it_grade", "variance_share"} & set(tab.columns)
    assert set(tab["unit"]) == {"mm", "deg"} and len(tab) == 22
    assert tab.loc[tab.parameter == "dl3", "grade"].item().startswith("IT")
    assert tab["cost"].sum() == pytest.approx(s["cost"]) and tab["variance_share_pct"].sum() == pytest.approx(100)
    ver = pd.read_csv(out / "verification.csv")  # one meaning of p_linear: the design to build
    assert ver["p_linear"].tolist() == pytest.approx([row["p_linear"] for row in s["poses"]])


def test_certified_solver_no_verify(capsys):
    # at the nominal pose: the flags' effect on the printed design and legend does not depend on the region
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--solver", "certified", "--no-verify", "--uniform"])
    text = capsys.readouterr().out
    assert rc == 0 and "design: certified-" in text and "sigma = t / 1.732" in text


def test_infeasible_is_said_plainly(tmp_path, capsys):
    costs = tmp_path / "c.toml"
    costs.write_text("[kinds.joint_drive]\nt_min_deg = 0.05\n")
    out = tmp_path / "o"
    # on a pose set the infeasible design is reported and written (a region: tests/test_cli_correction.py)
    rc = main(["allocate", "tool_changer", "--poses", "working", "--costs", str(costs), "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 1
    assert "INFEASIBLE" in text and "radius achievable at p = 0.95" in text and "dth" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "infeasible" and s["diagnosis"]["p_best_min"]["position"] < 0.95


@pytest.mark.parametrize("args, match", [(["--prob", "1.2"], "prob"), (["--poses", "nope"], "pose set"),
                                         (["--uniform", "--z", "2"], "--uniform"), (["--n-mc", "5"], "--n-mc")])
def test_bad_input_exits_2(args, match, capsys):
    assert main(["allocate", "tool_changer", *args]) == 2
    assert match in capsys.readouterr().err


@pytest.mark.parametrize("args, match", [
    (["--radius-mm", "0"], "--radius-mm: expected a finite number > 0 [mm]"),
    (["--radius-mm", "nan"], "--radius-mm: expected a finite number > 0 [mm]"),
    (["--prob", "0"], "--prob: expected a probability strictly between 0 and 1"),
    (["--z", "-3"], "--z: expected a number > 0"),
    (["--angle-radius-deg", "-1"], "--angle-radius-deg: expected a finite number > 0 [deg]"),
    (["--angle-prob", "0.9"], "--angle-prob 0.9 needs an orientation requirement"),
    (["--angle-step-deg", "0"], "--angle-step-deg: expected a finite number > 0 [deg]"),
])
def test_bad_numbers_are_named_by_their_flag(args, match, capsys, tmp_path):
    # regression: the messages named library arguments (radius_mm, prob, angle step, "costs defaults: z")
    out = tmp_path / "o"
    assert main(["allocate", "tool_changer", "--no-verify", "--out", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and match in err and err.count("\n") == 1 and not out.exists()


def test_unwritable_out_is_refused_before_the_work(tmp_path, capsys):
    blocker = tmp_path / "f"
    blocker.write_text("x")
    assert main(["allocate", "tool_changer", "--out", str(blocker)]) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and "--out" in cap.err and "is a file" in cap.err


def test_trace_rule_not_applicable_says_why(capsys):
    assert main(["allocate", "tool_changer", "--poses", "nominal", "--prob", "0.7", "--no-verify"]) == 0
    assert "certified-trace: n/a, not_applicable: the trace rule is valid only for p >= 0.785" in capsys.readouterr().out


def test_orientation_verification_and_uniform_errors_are_reported(tmp_path, capsys):
    out = tmp_path / "o"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--angle-radius-deg", "0.02", "--uniform",
               "--n-mc", "20000", "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 0, text
    assert "errors uniform over +-t" in text and "orientation: lowest P_hat" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["distribution"] == "uniform" and s["z"] == pytest.approx(3 ** 0.5)
    pose = s["poses"][0]
    assert pose["p_mc_angle_ci"][0] <= pose["p_mc_angle"] <= pose["p_mc_angle_ci"][1]
    assert set(s["diagnosis"]["radius_best_max"]) == {"position_mm", "orientation_deg"}
    ver = pd.read_csv(out / "verification.csv")
    assert {"p_linear_angle", "p_mc_angle", "ci_low_angle", "ci_high_angle"} <= set(ver.columns)
    assert ver["p_mc_angle"].iloc[0] == pytest.approx(pose["p_mc_angle"])
    # the hand-over tables state both requirements; the legend says sigma for uniform errors
    md, tex = (out / "tolerances.md").read_text(), (out / "tolerances.tex").read_text()
    assert "P(|dP| < 0.25 mm) >= 0.95, P(|dw| < 0.02 deg) >= 0.95 at the 1 pose(s) of 'nominal'" in md
    assert r"P($|$dw$|$ $<$ 0.02 deg) $\geq$ 0.95" in tex and "errors uniform over" in md


def test_region_default_and_trajectory(tmp_path, capsys):
    traj = tmp_path / "traj.csv"
    traj.write_text("q1,q2,q3,q4,q5,q6\n15,30,-10,0,-20,-5\n0,20,0,200,-20,0\n")
    assert main(["allocate", "tool_changer", "--region", str(traj), "--no-verify"]) == 0
    assert f"at 2 {traj} pose(s)" in capsys.readouterr().out
    out = tmp_path / "reg"
    assert main(["allocate", "tool_changer", "--no-verify", "--coverage-n", "20000", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "region working:" in text and "none below p" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["region"]["converged"] and s["region"]["static_joints"] == [6] and s["coverage"]["n_below"] == 0
    tex = (out / "tolerances.tex").read_text()
    assert "over the box region 'working'" in tex and "working poses" not in tex


@pytest.mark.parametrize("rows,match", [
    ("1,2,3\n", "rows of 6 joint values"),
    ("15,30,-10,0,-20,-5\n15,30,nan,0,-20,-5\n", "row 2 has a missing or non-finite"),
    ("15,30,-10,0,-20,-500\n", "outside its limits"),
])
def test_bad_trajectory_exits_2(tmp_path, capsys, rows, match):
    traj = tmp_path / "t.csv"
    traj.write_text(rows)
    out = tmp_path / "o"
    assert main(["allocate", "tool_changer", "--region", str(traj), "--no-verify", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert match in err and str(traj) in err and not out.exists()


def test_unknown_region_exits_2(capsys):
    assert main(["allocate", "tool_changer", "--region", "nowhere", "--no-verify"]) == 2
    assert "--region: 'nowhere'" in capsys.readouterr().err


def test_parts_flags_reach_the_parts_design(tmp_path, capsys):
    """`--parts` with its ranges gives allocate_tolerances the options the Python call takes; a design whose parts'
    mean error alone exceeds the radius (no compensation) is refused with the reason, and nothing is written."""
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from parts_robot import arm

    from tolalloc.cli import build_parser
    from tolalloc.cli.allocate import settings

    arm(tmp_path)
    robot = str(tmp_path / "arm3.toml")
    args = build_parser().parse_args(["allocate", robot, "--parts", "--payload-kg", "0", "1", "--ambient-c", "15",
                                      "30", "--duty", "0.3", "--after-compensation"])
    assert settings(args)["parts"] == {"payload_kg": (0.0, 1.0), "ambient_c": (15.0, 30.0), "duty": 0.3,
                                       "after": "compensation"}
    assert "parts" not in settings(build_parser().parse_args(["allocate", robot]))
    assert settings(build_parser().parse_args(["allocate", robot, "--parts"]))["parts"] is True  # the defaults
    rc = main(["allocate", robot, "--radius-mm", "0.5", "--region", "work", "--no-verify", "--parts",
               "--payload-kg", "0", "1", "--ambient-c", "15", "30", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert rc == 2 and "the bought parts' mean error alone is" in err
    assert "compensate it (--after-compensation, or a smaller residual)" in err and "after='" not in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("flags, message", [
    (["--payload-kg", "0", "5"], "error: --payload-kg 0 5 needs --parts: it sets the design with bought parts."),
    (["--duty", "0.2"], "error: --duty 0.2 needs --parts: it sets the design with bought parts."),
    (["--after-compensation"], "error: --after-compensation needs --parts: it sets the design with bought parts."),
])
def test_parts_options_without_parts_are_refused(flags, message, capsys):
    assert main(["allocate", "ur10", *flags]) == 2
    assert capsys.readouterr().err.strip() == message
