"""CLI `tolalloc analyze`: JSON keys and values against the library, output files, bad input -> exit 2, nothing written."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from tolalloc import load_robot
from tolalloc.cli import main
from tolalloc.errormodel import build_error_model
from tolalloc.linear.covariance import budget, linear_map
from tolalloc.linear.probability import p_within_radius, radius_for_prob
from tolalloc.outputs import MANIFEST


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_analyze_nominal_json_matches_library(capsys, tmp_path):
    out = tmp_path / "a.json"
    code, text, err = run(capsys, "analyze", "tool_changer", "--sigma-set", "table2", "--radius-mm", "25",
                          "--prob", "0.95", "--json", str(out))
    assert code == 0 and err == ""
    d = json.loads(out.read_text())
    robot = load_robot("tool_changer")
    res = linear_map(build_error_model(robot, "table2"), robot.q_nominal)
    np.testing.assert_allclose(d["std_mm"], res.std_mm[0], rtol=1e-12)
    C = np.array(d["covariance_mm2"])
    assert C.shape == (3, 3)
    np.testing.assert_allclose(C, res.cov_mm2[0], rtol=1e-12)
    assert d["p_within_radius"]["25"] == pytest.approx(float(p_within_radius(C, 25.0)), abs=1e-12)
    r95 = d["radius_mm_for_prob"]["0.95"]
    assert p_within_radius(C, r95) == pytest.approx(0.95, abs=1e-9)
    shares = [row["share_norm_pct"] for row in d["budget"]["parameters"]]
    assert shares == sorted(shares, reverse=True) and sum(shares) == pytest.approx(100.0)
    assert {row["kind"] for row in d["budget"]["kinds"]} == {"link_length", "joint_drive", "axis_deflection"}
    assert "poses" not in d and d["n_poses"] == 1
    assert "error budget" in text and "P(|dp| < 25 mm)" in text


def test_analyze_pose_set_worst_and_out_dir(capsys, tmp_path):
    code, out, err = run(capsys, "analyze", "tool_changer", "--poses", "working", "--clearance", "--radius-mm", "30",
                         "--prob", "0.9", "--json", "-", "--out", str(tmp_path / "o"))
    assert code == 0 and err == ""
    assert json.loads(out)["worst_pose"] == json.loads((tmp_path / "o" / "analyze.json").read_text())["worst_pose"]
    d = json.loads((tmp_path / "o" / "analyze.json").read_text())
    robot = load_robot("tool_changer")
    res = linear_map(build_error_model(robot, "table2", clearance=True), robot.poses("working"))
    assert len(d["poses"]) == res.n_poses
    # the CLI numbers poses from 1; the library index is 0-based
    assert d["worst_pose"] - 1 == int(np.argmax(res.rms_mm)) == budget(res).worst_pose
    np.testing.assert_allclose(d["std_mm"], res.std_mm[d["worst_pose"] - 1], rtol=1e-12)
    for i, pose in enumerate(d["poses"]):
        np.testing.assert_allclose(pose["covariance_mm2"], res.cov_mm2[i], rtol=1e-12)
        assert pose["radius_mm_for_prob"]["0.9"] == pytest.approx(float(radius_for_prob(res.cov_mm2[i], 0.9)), rel=1e-9)
    kinds = {row["kind"] for row in d["budget"]["kinds"]}
    assert {"clearance_radial", "clearance_axial", "clearance_tilt"} <= kinds
    files = sorted(p.name for p in (tmp_path / "o").iterdir())
    assert files == [MANIFEST, "analyze.json", "budget.csv", "budget.md", "budget.png", "budget_kinds.csv",
                     "linear_table.csv"]
    tab = pd.read_csv(tmp_path / "o" / "budget.csv")
    assert len(tab) == res.n_poses * len(res.model.params)
    # every column carries one unit: sigma in a mm / deg pair, blank where not the row's unit
    assert "sigma" not in tab and {"sigma_mm", "sigma_deg"} <= set(tab.columns)
    assert (tab["sigma_mm"].notna() == (tab["unit"] == "mm")).all()
    assert (tab["sigma_deg"].notna() == (tab["unit"] == "deg")).all()
    row = d["budget"]["parameters"][0]
    assert (row["sigma_mm"] is None) != (row["sigma_deg"] is None) and "sigma" not in row
    assert (tmp_path / "o" / "budget.png").stat().st_size > 5000


def test_analyze_single_pose_and_overrides(capsys, tmp_path):
    code, out, _ = run(capsys, "analyze", "tool_changer", "--pose", "15,30,-10,0,-20,-5", "--sigma", "joint_drive=0.01",
                       "--exclude", "axis_deflection", "--json", "-")
    assert code == 0
    d = json.loads(out)
    robot = load_robot("tool_changer")
    # a kind's sigma is in each parameter's own unit: 0.01 deg for the revolute drives, 0.01 mm for dd4
    model = build_error_model(robot, "table2", sigma={"joint_drive": np.deg2rad(0.01), "dd4": 0.01},
                              exclude=("axis_deflection",))
    np.testing.assert_allclose(d["std_mm"], linear_map(model, robot.q_nominal).std_mm[0], rtol=1e-12)


@pytest.mark.parametrize("argv,msg", [
    (["--radius-mm", "-1"], "--radius-mm"),
    (["--prob", "1.5"], "--prob"),
    (["--poses", "nope"], "pose set"),
    (["--pose", "1,2,3"], "6 values"),
    (["--sigma-set", "table9"], "sigma set"),
    (["--sigma", "dth9=1"], "unknown parameter"),
])
def test_analyze_bad_input_exit_2_no_files(capsys, tmp_path, argv, msg):
    out = tmp_path / "o"
    js = tmp_path / "a.json"
    code, text, err = run(capsys, "analyze", "tool_changer", *argv, "--out", str(out), "--json", str(js))
    assert code == 2
    assert err.startswith("error:") and msg in err and err.count("\n") == 1
    assert not out.exists() and not js.exists()
    assert list(tmp_path.iterdir()) == []


def test_analyze_bad_outputs_and_sigma_units_exit_2(capsys, tmp_path):
    # regressions: an unwritable --out / --json gave a traceback (after the work); a negative --sigma in deg was
    # reported in rad; --pose-set (the mc spelling) is accepted
    blocker = tmp_path / "f"
    blocker.write_text("x")
    for argv, msg in [(["--out", str(blocker)], "--out"), (["--json", str(tmp_path)], "--json"),
                      (["--sigma", "dth1=-0.01"], "--sigma: dth1: expected a finite sigma >= 0 in deg, got -0.01")]:
        code, _, err = run(capsys, "analyze", "tool_changer", *argv)
        assert code == 2 and err.startswith("error:") and msg in err and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f"]
    code, out, _ = run(capsys, "analyze", "tool_changer", "--pose-set", "working", "--json", "-")
    assert code == 0 and json.loads(out)["n_poses"] == 12
