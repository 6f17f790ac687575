"""`tolalloc mc`: JSON keys, output directory, reproducibility, bad input."""

import json

import numpy as np
import pytest

from tolalloc.cli import main


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
    assert {p.name for p in out.iterdir()} == {"mc_table.csv", "mc_summary.json", "mc_scatter.png"}
    text = capsys.readouterr().out
    assert "dp_reach_mm" in text and "P(|dp| < 0.25 mm)" in text


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
