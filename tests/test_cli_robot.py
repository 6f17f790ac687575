"""CLI: `tolalloc robots`, `show`, `fk`, --help everywhere, and bad input -> one error line, exit 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from test_robot import closed_form_tool_changer
from test_robotfile import BASE

from tolalloc.cli import COMMAND_MODULES, build_parser, main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_robots(capsys):
    code, out, err = run(capsys, "robots")
    assert code == 0 and err == ""
    lines = out.strip().splitlines()
    assert [ln.split()[0] for ln in lines] == ["tool_changer", "ur10"]


def test_show_builtin(capsys):
    code, out, _ = run(capsys, "show", "tool_changer")
    assert code == 0
    for word in ("joints:", "links:", "nominal pose:", "j1", "j6", "l3", "prismatic", "working"):
        assert word in out
    assert "position_mm: [-415.691939, 1551.383436, 1196.616115]" in out


def test_show_path(capsys, tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(BASE)
    code, out, _ = run(capsys, "show", str(path))
    assert code == 0
    assert "robot: two" in out and "position_mm: [98.480775, 17.364818, 80.000000]" in out  # j1 nominal 10 deg


def test_fk_json(capsys):
    code, out, _ = run(capsys, "fk", "tool_changer", "--q", "15,30,-10,0,-20,-5", "--json")
    assert code == 0
    data = json.loads(out)
    assert len(data["position_mm"]) == 3
    assert np.shape(data["rotation"]) == (3, 3)
    p, R = closed_form_tool_changer()
    np.testing.assert_allclose(data["position_mm"], p, rtol=1e-12)
    np.testing.assert_allclose(data["rotation"], R, atol=1e-12)


def test_fk_text_matches_json(capsys):
    code, out, _ = run(capsys, "fk", "ur10", "--q", "0,-90,0,-90,0,0")
    assert code == 0
    assert "position_mm: [-0.000000, -256.141000, 1427.300000]" in out or "position_mm: [0.000000, -256.141000, 1427.300000]" in out


def all_subcommands():
    parser = build_parser()
    action = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    return sorted(action.choices)


def test_help_everywhere(capsys):
    assert {"robots", "show", "fk"} <= set(all_subcommands())
    assert "robot_cmds" in COMMAND_MODULES
    for argv in [["--help"], *[[c, "--help"] for c in all_subcommands()]]:
        with pytest.raises(SystemExit) as info:
            main(argv)
        assert info.value.code == 0
        out = capsys.readouterr().out
        assert "usage: tolalloc" in out


@pytest.mark.parametrize("argv,match", [
    (["fk", "tool_changer", "--q", "15,30,-10,0,-20"], "--q: robot 'tool_changer' has 6 joints .* got 5"),
    (["fk", "tool_changer", "--q", "15,30,-10,900,-20,-5"], r"--q: joint j4 = 900 mm is outside its limits \[0, 500\] mm"),
    (["fk", "tool_changer", "--q", "15,30,x,0,-20,-5"], "--q: expected comma-separated numbers"),
    (["fk", "tool_changer", "--q", "15,30,nan,0,-20,-5"], "--q: expected finite numbers"),
    (["show", "no_such_robot"], "not a built-in robot .* and no such file"),
])
def test_cli_bad_input(capsys, argv, match):
    import re

    code, out, err = run(capsys, *argv)
    assert code == 2
    assert err.startswith("error: ") and len(err.strip().splitlines()) == 1
    assert re.search(match, err), err
    assert "Traceback" not in err


@pytest.mark.parametrize("old,new,match", [
    ("axis = [0, 0, 1]", "axis = [0, 0, 0]", r"chain\[1\]\.axis: axis is the zero vector"),
    ("axis = [0, 0, 1]", "axis = [0, 1, 1]", r"expected a unit vector"),
    ("axis = [0, 0, 1]", "axis = [nan, 0, 1]", r"axis must be finite"),
    ("vector_mm = [0, 0, 100]", "vector_in = [0, 0, 100]", r"unknown unit 'in' in key 'vector_in'"),
    ('type = "prismatic"\n', "", r"chain\[3\]\.type: Field required"),
    ('name = "two"', 'name = two"', r"not valid TOML"),
])
def test_cli_bad_robot_file(capsys, tmp_path, old, new, match):
    import re

    path = tmp_path / "bad.toml"
    path.write_text(BASE.replace(old, new, 1))
    for argv in (["show", str(path)], ["fk", str(path), "--q", "0,0"]):
        code, _, err = run(capsys, *argv)
        assert code == 2
        assert re.search(match, err) and str(path) in err, err
        assert "Traceback" not in err


def test_console_script_subprocess(tmp_path):
    """The installed console script: exit codes and no traceback on bad input."""
    exe = Path(sys.executable).with_name("tolalloc")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "tolalloc"]
    ok = subprocess.run([*cmd, "fk", "tool_changer", "--q", "15,30,-10,0,-20,-5", "--json"],
                        capture_output=True, text=True, timeout=120)
    assert ok.returncode == 0, ok.stderr
    assert len(json.loads(ok.stdout)["position_mm"]) == 3
    bad = tmp_path / "bad.toml"
    bad.write_text(BASE.replace("axis = [0, 0, 1]", "axis = [0, 0, 0]"))
    res = subprocess.run([*cmd, "show", str(bad)], capture_output=True, text=True, timeout=120)
    assert res.returncode != 0
    assert "Traceback" not in res.stderr and "zero vector" in res.stderr


def test_fk_json_echoes_clean_joint_values_and_show_lists_pose_sets(capsys, tmp_path):
    # regressions: q_deg_mm came back as 14.999999999999998; show printed "pose sets: nominal, none"
    code, out, _ = run(capsys, "fk", "tool_changer", "--q", "15,30,-10,0,-20,-5", "--json")
    assert code == 0 and json.loads(out)["q_deg_mm"] == [15.0, 30.0, -10.0, 0.0, -20.0, -5.0]
    path = tmp_path / "one.csv"
    path.write_text("# convention: standard\nname,d_mm,alpha_deg\nq1,100,0\n")
    code, out, _ = run(capsys, "show", str(path))
    assert code == 0 and "pose sets: nominal (1 pose)\n" in out and "none" not in out
