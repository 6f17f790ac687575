"""`tolalloc mc`: JSON keys, output directory, reproducibility, bad input."""

import json

import numpy as np
import pytest

from tolalloc.cli import main
from tolalloc.outputs import MANIFEST


def _run_json(tmp_path, *extra):
    out = tmp_path / "mc.json"
    assert main(["mc", "tool_changer", "--n", "3000", "--seed", "4", "--json", str(out), *extra]) == 0
    return json.loads(out.read_text())


def test_json_keys_and_reproducibility(tmp_path):
    d = _run_json(tmp_path)
    for key in ("n", "mean_mm", "std_mm", "norm_mm", "angle_std_rad", "p_within"):
        assert key in d
    assert d["n"] == 3000 and len(d["mean_mm"]) == 3 and len(d["std_mm"]) == 3 and len(d["norm_mm"]) == 4
    assert len(d["angle_std_rad"]) == 3
    assert set(d["p_within"]) == {"0.15", "0.25"}
    pw = d["p_within"]["0.25"]
    assert 0 <= pw["ci_low"] <= pw["p"] <= pw["ci_high"] <= 1
    assert d["labels"]["sigma_set"] == "table2" and d["labels"]["link_mode"] == "consistent"
    assert d == _run_json(tmp_path)
    assert d["std_mm"] != _run_json(tmp_path, "--sigma-set", "table1")["std_mm"]


def test_options_and_pose_set(tmp_path):
    d = _run_json(tmp_path, "--pose-set", "working", "--clearance", "--link-mode", "axes_only",
                  "--radius-mm", "5", "--sigma", "dth5=0.1", "--exclude", "dl1")
    assert np.array(d["mean_mm"]).shape == (12, 3)
    assert d["labels"]["clearance"] is True and d["labels"]["link_mode"] == "axes_only"
    assert d["labels"]["clearance_tilt_rad"] == 0.0087
    assert list(d["p_within"]) == ["5"]


def test_out_directory(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["mc", "tool_changer", "--n", "2000", "--seed", "1", "--out", str(out), "--pose", "0,20,0,200,-20,0"]) == 0
    assert {p.name for p in out.iterdir()} == {"mc_table.csv", "mc_summary.json", "mc_scatter.png", MANIFEST}
    text = capsys.readouterr().out
    assert "dp_reach" in text and "mean_mm" in text and "std_deg" in text and "P(|dp| < 0.25 mm)" in text
    import pandas as pd

    table = pd.read_csv(out / "mc_table.csv")  # angles in their own deg columns, never beside mm values
    assert set(table.loc[table["unit"] == "deg", "quantity"]) == {"dalpha", "dbeta", "dgamma"}
    assert table.loc[table["unit"] == "deg", "mean_mm"].isna().all()


@pytest.mark.parametrize("args", [
    ["--n", "0"],
    ["--n", "10", "--sigma", "dl1=-1"],
    ["--n", "10", "--sigma", "dl1=nan"],
    ["--n", "10", "--sigma", "dl99=1"],
    ["--n", "10", "--sigma-set", "table7"],
    ["--n", "10", "--pose", "15,30,-10,0,-20,500"],
    ["--n", "10", "--exclude", "nothing"],
])
def test_bad_input_exit_2_no_files(tmp_path, capsys, args):
    out, js = tmp_path / "out", tmp_path / "x.json"
    assert main(["mc", "tool_changer", *args, "--out", str(out), "--json", str(js)]) == 2
    assert "error:" in capsys.readouterr().err
    assert not out.exists() and not js.exists()
    assert list(tmp_path.iterdir()) == []


def test_sigma_override_by_kind_uses_each_parameters_unit(tmp_path):
    """``--sigma joint_drive=0.01`` is 0.01 deg for revolute drives and 0.01 mm for the prismatic dd4."""
    from tolalloc import load_robot
    from tolalloc.errormodel import build_error_model
    from tolalloc.montecarlo.run import run_mc

    d = _run_json(tmp_path, "--n", "3000", "--sigma", "joint_drive=0.01", "--exclude", "link_length",
                  "--exclude", "axis_deflection")
    robot = load_robot("tool_changer")
    sigma = {p: (0.01 if p == "dd4" else np.deg2rad(0.01)) for p in ("dth1", "dth2", "dth3", "dd4", "dth5", "dth6")}
    model = build_error_model(robot, sigma=sigma, exclude=("link_length", "axis_deflection"))
    ref = run_mc(model, robot.q_nominal, 3000, seed=4)
    np.testing.assert_allclose(d["std_mm"], ref.std_mm[0], rtol=1e-10)


def test_angle_radius_in_degrees_equals_radians(tmp_path):
    a = _run_json(tmp_path, "--n", "2000", "--angle-radius-deg", "0.1")
    b = _run_json(tmp_path, "--n", "2000", "--angle-radius-rad", str(np.deg2rad(0.1)))
    assert list(a["p_within_angle"].values())[0]["p"] == list(b["p_within_angle"].values())[0]["p"]


def test_output_piped_into_a_closed_pipe_is_not_an_error():
    import subprocess
    import sys

    cmd = f"{sys.executable} -m tolalloc show tool_changer | head -1"
    proc = subprocess.run(["bash", "-c", "set -o pipefail; " + cmd], capture_output=True, text=True, timeout=60)
    assert "Traceback" not in proc.stderr
    assert proc.stdout.startswith("robot: tool_changer")
