"""Bad-input table: every command refuses every row with exit 2, one `error:` line naming the flag or file
and field, no traceback, and nothing written.

Each row is ``(argv, pattern)``: ``{F}`` in an argument is the folder of prepared input files (read
only), outputs go to the test's own working directory, whose listing must not change. ``pattern``
is a regular expression the error line must match (it names the flag, or the file and field).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.cli import main
from tolalloc.progress import PROGRESS_LINE

TC = "tool_changer"

ROBOT_TOML = """name = "t"
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 0, 1]
LIMITS
[[chain]]
link = "l1"
VECTOR
[[chain]]
joint = "j2"
type = "revolute"
axis = [0, 1, 0]
[[chain]]
link = "l2"
vector_mm = [300, 0, 0]
TOOL
"""


def _robot_text(limits='limits_deg = [-170, 170]', vector='vector_mm = [0, 0, 400]', tool=""):
    return ROBOT_TOML.replace("LIMITS", limits).replace("VECTOR", vector).replace("TOOL", tool)


URDF_HEAD = '<?xml version="1.0"?>\n<robot name="r">\n'
URDF_LINKS = "".join(f'<link name="{n}"/>' for n in ("base", "l1", "l2", "tool0", "finger"))
URDF_BRANCH = URDF_HEAD + URDF_LINKS + """
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
<joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
<joint name="fix" type="fixed"><parent link="l2"/><child link="tool0"/><origin xyz="0.3 0 0"/></joint>
<joint name="fin" type="prismatic"><parent link="l2"/><child link="finger"/><origin xyz="0.3 0 0.02"/><axis xyz="0 1 0"/>
<limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
</robot>
"""
XACRO = ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
         '<xacro:property name="l" value="0.4"/><link name="base"/><link name="l1"/>\n'
         '<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 ${l}"/>'
         '<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>\n')


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """The prepared (read-only) input files of the table."""
    F = tmp_path_factory.mktemp("inputs")
    robots = {
        "metres_under_m.toml": _robot_text(vector="vector_m = [0, 0, 400]"),
        "metres_under_mm.toml": _robot_text(vector="vector_mm = [0, 0, 0.4]").replace("[300, 0, 0]", "[0.3, 0, 0]"),
        "one_link_metres.toml": _robot_text(vector="vector_mm = [0, 0, 0.4]"),
        "deg_under_rad.toml": _robot_text(limits="limits_rad = [-90, 90]"),
        "beyond_turn.toml": _robot_text(limits="limits_deg = [-400, 400]"),
        "nan_tool.toml": _robot_text(tool="[tool]\noffset_mm = [nan, 0, 0]"),
        "inf_link.toml": _robot_text(vector="vector_mm = [0, 0, inf]"),
        "zero_link.toml": _robot_text(vector="vector_mm = [0, 0, 0]"),
        "text_number.toml": _robot_text(vector='vector_mm = [0, 0, "three"]'),
        "not_toml.toml": "this is = = not toml\n",
        "no_joint.toml": 'name = "x"\n[[chain]]\nlink = "l1"\nvector_mm = [100, 0, 0]\n',
        "bad_axis.toml": _robot_text().replace("axis = [0, 0, 1]", "axis = [0, 0, 2]"),
        "nominal_out.toml": _robot_text(limits="limits_deg = [-10, 10]\nnominal_deg = 50"),
        "dh_mm_under_m.toml": ('name = "d"\nconvention = "standard"\n[[dh]]\nname = "q1"\nd_m = 400\nalpha_deg = 90\n'
                               '[[dh]]\nname = "q2"\na_m = 0.3\nalpha_deg = 0\n'),
        "no_alpha.csv": "# convention: standard\nname,d_mm,a_mm\nq1,400,0\nq2,0,300\n",
        "no_convention.csv": "name,d_mm,a_mm,alpha_deg\nq1,400,0,90\n",
        "branch.urdf": URDF_BRANCH,
        "xacro.urdf": XACRO,
        "broken.urdf": "<robot><link name=",
    }
    for name, text in robots.items():
        (F / name).write_text(text)
    (F / "adir").mkdir()
    costs = {"z_text.toml": 'z = "three"\n', "neg_a.toml": "[kinds.link_length]\na = -1\n",
             "bad_unit.toml": "[kinds.link_length]\nt_min_deg = 0.1\n", "unknown.toml": "foo = 1\n",
             "not_toml_costs.toml": "[[[\n"}
    for name, text in costs.items():
        (F / name).write_text(text)
    robot = tolalloc.load_robot(TC)
    from tolalloc.diagnose import generate

    frame = generate(robot, "none", 60, np.random.default_rng(3)).frame
    frame.iloc[:40].to_csv(F / "train.csv", index=False)
    frame.iloc[40:].to_csv(F / "test.csv", index=False)
    pd.concat([frame.iloc[:40], frame.iloc[[5]]]).to_csv(F / "dup_row.csv", index=False)
    pd.DataFrame([frame.iloc[0]] * 60).to_csv(F / "identical.csv", index=False)
    pd.concat([frame.iloc[40:], frame.iloc[[3]]]).to_csv(F / "shares_train.csv", index=False)
    metres = frame.iloc[:40].copy()
    metres[["x_mm", "y_mm", "z_mm"]] /= 1000.0
    metres.to_csv(F / "metres.csv", index=False)
    frame.iloc[:40].rename(columns={"q6": "joint6"}).to_csv(F / "no_q6.csv", index=False)
    frame.iloc[:40].drop(columns=["q6"]).to_csv(F / "five_joints.csv", index=False)
    frame.iloc[:40].assign(q7=0.0).to_csv(F / "seven_joints.csv", index=False)
    frame.iloc[:40].rename(columns={"q1": "q1_mm"}).to_csv(F / "q1_mm.csv", index=False)
    text = frame.iloc[:40].astype(object)
    text.iloc[2, 0] = "abc"
    text.to_csv(F / "text_cell.csv", index=False)
    (F / "semicolon.csv").write_text("q1;q2;q3;q4;q5;q6;x_mm;y_mm;z_mm\n1;2;3;4;5;6;7;8;9\n")
    radians = frame.iloc[:40].copy()
    radians["q2"] = np.radians(radians["q2"])
    radians.to_csv(F / "radians.csv", index=False)
    (F / "empty_plan.csv").write_text("")
    (F / "header_only.csv").write_text(",".join([f"q{i}" for i in range(1, 7)] + ["x_mm", "y_mm", "z_mm"]) + "\n")
    for p in F.iterdir():
        if p.is_file():
            p.chmod(0o444)
    return F


def _rows():
    rows = []

    def add(argv, pattern):
        rows.append((argv, pattern))

    # ----------------------------------------------------------- robots for every robot-taking command
    bad_robots = [
        ("no_such_robot", "not a built-in robot"),
        ("{F}/adir", "is a directory"),
        ("{F}/missing.toml", "no such file"),
        ("{F}/metres_under_m.toml", r"chain\[1\] \(l1\): vector_m .* looks like millimetres"),
        ("{F}/metres_under_mm.toml", "lengths: .* looks like metres"),
        ("{F}/one_link_metres.toml", "link l1 is 0.4 mm long while link l2 is 300 mm; .* metres under a _mm key"),
        ("{F}/deg_under_rad.toml", r"chain\[0\] \(j1\): limits_rad .* looks like degrees"),
        ("{F}/beyond_turn.toml", r"limits_deg .* beyond \+-360 deg"),
        ("{F}/nan_tool.toml", "tool: expected offset_mm .* finite"),
        ("{F}/inf_link.toml", r"chain\[1\] \(l1\): vector must be 3 finite numbers"),
        ("{F}/zero_link.toml", r"chain\[1\] \(l1\): the vector is zero"),
        ("{F}/text_number.toml", r"chain\[1\] \(l1\): vector_mm expected numbers, got .*three"),
        ("{F}/not_toml.toml", "not_toml.toml.*not valid TOML"),
        ("{F}/no_joint.toml", "no joint"),
        ("{F}/bad_axis.toml", r"chain\[0\].*axis"),
        ("{F}/nominal_out.toml", "nominal value 50"),
        ("{F}/dh_mm_under_m.toml", r"dh\[0\]: d_m = 400.* looks like millimetres"),
        ("{F}/no_alpha.csv", "no_alpha.csv.*no alpha_deg or alpha_rad column"),
        ("{F}/no_convention.csv", "no_convention.csv.*convention"),
        ("{F}/branch.urdf", "branch.urdf.*tool link is ambiguous.*--tool"),
        ("{F}/xacro.urdf", "xacro.urdf.*unexpanded xacro.*xacro robot.urdf.xacro"),
        ("{F}/broken.urdf", "broken.urdf.*not valid XML"),
    ]
    for cmd, extra in (("show", []), ("fk", ["--q", "0,0"]), ("mc", ["--n", "10"]), ("analyze", []),
                       ("allocate", ["--no-verify"]), ("diagnose", ["--train", "{F}/train.csv"])):
        for robot, pattern in bad_robots:
            if cmd in ("show", "mc") or robot in ("{F}/adir", "{F}/nan_tool.toml", "{F}/branch.urdf",
                                                   "{F}/metres_under_m.toml", "{F}/deg_under_rad.toml"):
                add([cmd, robot, *extra], pattern)
    add(["show", TC, "--tool", "tool0"], "--tool 'tool0': the tool link can only be chosen for a URDF")
    add(["show", "{F}/branch.urdf", "--tool", "nope"], r"the tool link 'nope' \(--tool\) is not a link of the URDF")
    add(["robots", "extra"], "unrecognized arguments: extra")
    add(["nocommand"], "invalid choice: 'nocommand'")
    add([], "required: COMMAND")
    # ----------------------------------------------------------- fk
    for q, pattern in [("15,30,-10,0,-20", "--q: robot 'tool_changer' has 6 joints"),
                       ("15,30,-10,900,-20,-5", r"--q: joint j4 = 900 mm is outside its limits"),
                       ("15,30,x,0,-20,-5", "--q: expected comma-separated numbers"),
                       ("15,30,nan,0,-20,-5", "--q: expected finite numbers"),
                       ("15,30,inf,0,-20,-5", "--q: expected finite numbers"), ("", "--q")]:
        add(["fk", TC, "--q", q], pattern)
    add(["fk", TC], "the following arguments are required: --q")
    # ----------------------------------------------------------- mc
    mc = ["mc", TC, "--n", "100"]
    for argv, pattern in [
        (["mc", TC, "--n-mc", "0"], "argument --n-mc/--n: expected a whole number >= 1"),
        (["mc", TC, "--n", "-5"], "argument --n-mc/--n: expected a whole number >= 1"),
        (["mc", TC, "--n-mc", "x"], "argument --n-mc/--n: expected a number, got 'x'"),
        (["mc", TC, "--n", "1.5"], "argument --n-mc/--n: expected a whole number >= 1"),
        (["mc", TC, "--n-mc", "nan"], "argument --n-mc/--n: expected a whole number >= 1"),
        ([*mc, "--seed", "-1"], "argument --seed: expected a whole number >= 0"),
        ([*mc, "--seed", "1.5"], "argument --seed: expected a whole number >= 0"),
        ([*mc, "--out", ""], "--out: expected a directory path, got an empty string"),
        ([*mc, "--out", "afile"], "--out 'afile': expected a directory path, but 'afile' is a file"),
        ([*mc, "--out", "afile/sub"], "--out 'afile/sub': expected a path below a directory"),
        ([*mc, "--json", ""], "--json: expected a file path, got an empty string"),
        ([*mc, "--json", "adir"], "--json 'adir': expected a file path, but 'adir' is a directory"),
        ([*mc, "--hist-bins", "10", "--hist-range-mm", "0"], "argument --hist-range-mm: expected a finite number > 0"),
        ([*mc, "--hist-bins", "10", "--hist-range-mm", "-1"], "argument --hist-range-mm: expected a finite number > 0"),
        ([*mc, "--hist-bins", "10", "--hist-range-mm", "nan"], "argument --hist-range-mm: expected a finite number > 0"),
        ([*mc, "--hist-range-mm", "5"], "--hist-range-mm 5 sets the histogram window, but no histogram"),
        ([*mc, "--hist-bins", "-1"], "argument --hist-bins: expected a whole number >= 0"),
        ([*mc, "--clearance-tilt-literal"], "--clearance-tilt-literal: .* add --clearance"),
        ([*mc, "--radius-mm", "0"], "--radius-mm: expected a finite number > 0 \\[mm\\]"),
        ([*mc, "--radius-mm", "nan"], "--radius-mm: expected a finite number > 0 \\[mm\\]"),
        ([*mc, "--angle-radius-deg", "-1"], "--angle-radius-deg: expected a finite number > 0 \\[deg\\]"),
        ([*mc, "--jobs", "0"], "argument --jobs: expected a whole number >= 1"),
        ([*mc, "--chunk-size", "0"], "argument --chunk-size: expected a whole number >= 1"),
        ([*mc, "--pose", "1,2"], "--pose: robot 'tool_changer' has 6 joints"),
        ([*mc, "--pose", "15,30,-10,900,-20,-5"], "--pose: joint j4 = 900 mm is outside"),
        ([*mc, "--pose-set", "nope"], "pose set 'nope' is not defined"),
        ([*mc, "--pose", "0,0,0,0,0,0", "--pose-set", "working"], "not allowed with argument"),
        ([*mc, "--sigma", "dth1"], "--sigma: expected NAME=VALUE"),
        ([*mc, "--sigma", "nope=1"], "--sigma: unknown parameter or kind 'nope'"),
        ([*mc, "--sigma", "dth1=-1"], "--sigma: dth1: expected a finite sigma >= 0"),
        ([*mc, "--sigma-set", "nope"], "sigma set 'nope'|nope"),
        ([*mc, "--exclude", "nope"], "nope"),
        ([*mc, "--scheduler", "bogus"], "scheduler: expected None, 'local'"),
        ([*mc, "--ci", "bogus"], "argument --ci: invalid choice: 'bogus'"),
        ([*mc, "--link-mode", "bogus"], "argument --link-mode: invalid choice"),
        ([*mc, "--deflection-mode", "bogus"], "argument --deflection-mode: invalid choice"),
        ([*mc, "--bogus"], "unrecognized arguments: --bogus"),
    ]:
        add(argv, pattern)
    # ----------------------------------------------------------- analyze
    an = ["analyze", TC]
    for argv, pattern in [
        ([*an, "--radius-mm", "0"], "--radius-mm: expected a finite number > 0 \\[mm\\]"),
        ([*an, "--radius-mm", "-0.1"], "--radius-mm: expected a finite number > 0 \\[mm\\]"),
        ([*an, "--prob", "1"], "--prob: expected a probability strictly between 0 and 1"),
        ([*an, "--prob", "0"], "--prob: expected a probability strictly between 0 and 1"),
        ([*an, "--prob", "nan"], "--prob: expected a probability strictly between 0 and 1"),
        ([*an, "--top", "0"], "argument --top: expected a whole number >= 1"),
        ([*an, "--out", ""], "--out: expected a directory path, got an empty string"),
        ([*an, "--json", "adir"], "--json 'adir': expected a file path"),
        ([*an, "--pose", "1,2,3"], "--pose: robot 'tool_changer' has 6 joints"),
        ([*an, "--poses", "nope"], "pose set 'nope' is not defined"),
        ([*an, "--clearance-tilt-literal"], "--clearance-tilt-literal: .* add --clearance"),
        ([*an, "--sigma", "x=y"], "--sigma: unknown parameter or kind 'x'"),
    ]:
        add(argv, pattern)
    # ----------------------------------------------------------- allocate
    al = ["allocate", TC, "--no-verify"]
    for argv, pattern in [
        ([*al, "--radius-mm", "0"], "--radius-mm: expected a finite number > 0"),
        ([*al, "--radius-mm", "inf"], "--radius-mm: expected a finite number > 0"),
        ([*al, "--prob", "1.5"], "--prob: expected a probability strictly between 0 and 1"),
        ([*al, "--prob", "0"], "--prob: expected a probability strictly between 0 and 1"),
        ([*al, "--z", "0"], "--z: expected a number > 0"),
        ([*al, "--uniform", "--z", "3"], "--uniform and --z both set sigma"),
        (["allocate", TC, "--n-mc", "10"], "--n-mc: expected at least 100 samples per pose"),
        (["allocate", TC, "--n-mc", "1.5"], "argument --n-mc: expected a whole number >= 1"),
        (["allocate", TC, "--seed", "-1"], "argument --seed: expected a whole number >= 0"),
        ([*al, "--angle-prob", "0.9"], "--angle-prob 0.9 needs an orientation requirement"),
        ([*al, "--angle-radius-deg", "0"], "--angle-radius-deg: expected a finite number > 0"),
        ([*al, "--angle-step-deg", "-1"], "--angle-step-deg: expected a finite number > 0"),
        ([*al, "--costs", "{F}/nope.toml"], "costs file .*nope.toml' not found"),
        ([*al, "--costs", "{F}/adir"], "costs file .*adir' is a directory"),
        ([*al, "--costs", "{F}/z_text.toml"], r"z_text.toml: z \(sigma = t / z\) expected a finite number > 0.*'three'.*not a number"),
        ([*al, "--costs", "{F}/neg_a.toml"], r"neg_a.toml \[kinds.link_length\] \(dl\d\): expected a finite fixed cost a >= 0"),
        ([*al, "--costs", "{F}/bad_unit.toml"], "bad_unit.toml .*t_min_deg.*wrong unit"),
        ([*al, "--costs", "{F}/unknown.toml"], "unknown.toml: unknown top-level key 'foo'"),
        ([*al, "--costs", "{F}/not_toml_costs.toml"], "not_toml_costs.toml: not valid TOML"),
        ([*al, "--out", ""], "--out: expected a directory path, got an empty string"),
        ([*al, "--out", "afile"], "--out 'afile': expected a directory path"),
        ([*al, "--poses", "nope"], "pose set 'nope' is not defined"),
        ([*al, "--solver", "bogus"], "argument --solver: invalid choice"),
        ([*al, "--link-mode", "bogus"], "argument --link-mode: invalid choice"),
    ]:
        add(argv, pattern)
    # ----------------------------------------------------------- diagnose
    dg = ["diagnose", TC, "--train", "{F}/train.csv"]
    for argv, pattern in [
        (["diagnose", TC], "the following arguments are required: --train"),
        (["diagnose", TC, "--train", "{F}/none.csv"], "measurement file .*none.csv' does not exist"),
        (["diagnose", TC, "--train", "{F}/adir"], "measurement file .*adir' is a directory"),
        (["diagnose", TC, "--train", "{F}/identical.csv"], "identical.csv: row 2 repeats row 1 exactly"),
        (["diagnose", TC, "--train", "{F}/dup_row.csv"], "dup_row.csv: row 41 repeats row 6 exactly"),
        (["diagnose", TC, "--train", "{F}/metres.csv"], "metres.csv: the measured positions look like metres"),
        (["diagnose", TC, "--train", "{F}/no_q6.csv"], r"no_q6.csv: missing column\(s\) for joint\(s\) q6_deg \(j6\)"),
        (["diagnose", TC, "--train", "{F}/five_joints.csv"], "five_joints.csv: missing column.*The file has joint "
         "columns q1..q5 but robot 'tool_changer' has 6 joints: is it a file of another robot\\?"),
        (["diagnose", TC, "--train", "{F}/seven_joints.csv"], "seven_joints.csv: the file has joint columns q1..q7 but "
         "robot 'tool_changer' has 6 joints"),
        (["diagnose", TC, "--train", "{F}/q1_mm.csv"], "q1_mm.csv: column 'q1_mm': joint 1 \\(j1\\) is revolute, its "
         "values are read in deg, not mm: name the column q1_deg"),
        (["diagnose", TC, "--train", "{F}/text_cell.csv"], "text_cell.csv: column 'q1', row 3: expected a number"),
        (["diagnose", TC, "--train", "{F}/semicolon.csv"], "semicolon.csv: looks ';'-separated"),
        (["diagnose", TC, "--train", "{F}/header_only.csv"], "header_only.csv: no data rows"),
        (["diagnose", "ur10", "--train", "{F}/train.csv"], "train.csv: .*wrong robot\\?"),
        ([*dg, "--test", "{F}/train.csv"], "--test .*train.csv' is the training file"),
        ([*dg, "--test", "{F}/shares_train.csv"], "--test .*shares_train.csv': 1 of its 21 poses are also in --train"),
        ([*dg, "--test", "{F}/identical.csv"], "identical.csv: row 2 repeats row 1"),
        ([*dg, "--predictions", "p.csv"], "--predictions needs --test"),
        ([*dg, "--test", "{F}/test.csv", "--predictions", "adir"], "--predictions 'adir': expected a file path"),
        ([*dg, "--report", "afile"], "--report 'afile': expected a directory path"),
        ([*dg, "--report", ""], "--report: expected a directory path, got an empty string"),
        ([*dg, "--json", "adir"], "--json 'adir': expected a file path"),
        ([*dg, "--json", "j.json", "--report", "afile"], "--report 'afile': expected a directory path"),
        ([*dg, "--json", "same.json", "--test", "{F}/test.csv", "--predictions", "same.json"],
         "--predictions 'same.json': the same path as --json"),
        ([*dg, "--json", "{F}/train.csv"], "--json .*train.csv': the input --train; an output would overwrite it"),
        ([*dg, "--alpha", "0"], "--alpha: expected a probability strictly between 0 and 1"),
        ([*dg, "--alpha", "1"], "--alpha: expected a probability strictly between 0 and 1"),
        ([*dg, "--folds", "1"], "--folds: expected a whole number >= 2"),
        ([*dg, "--folds", "0"], "argument --folds: expected a whole number >= 1"),
        ([*dg, "--seed", "-3"], "argument --seed: expected a whole number >= 0"),
        ([*dg, "--test-frame", "other"], "argument --test-frame: invalid choice"),
        ([*dg, "--folds", "1000"], "--folds: expected at most 20 cross-validation folds for 40 training poses"),
        (["diagnose", TC, "--train", "{F}/radians.csv"],
         "radians.csv: .*misses the measured points by .* mm RMS.*Column\\(s\\) q2 look like radians"),
        (["allocate", TC, "--no-verify", "--coverage-n", "0"], "argument --coverage-n: expected a whole number >= 1"),
        (["allocate", TC, "--no-verify", "--coverage-n", "-1"], "argument --coverage-n: expected a whole number >= 1"),
        (["allocate", TC, "--no-verify", "--out", "/"], "--out '/': refusing to write results into the filesystem root"),
        (["allocate", TC, "--no-verify", "--calibration", "{F}/empty_plan.csv"],
         "calibration plan empty_plan.csv: cannot be read as CSV"),
        (["calplan", TC, "--n-poses", "8", "--costs", "{F}/unknown.toml", "--out", "plan.csv"], "unknown.toml"),
    ]:
        add(argv, pattern)
    return rows


ROWS = _rows()


def _listing(root: Path) -> dict:
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in dirnames + filenames:
            p = Path(dirpath) / n
            out[str(p.relative_to(root))] = None if p.is_dir() else p.read_bytes()
    return out


def test_the_table_is_large():
    assert len(ROWS) >= 100
    assert {r[0][0] for r in ROWS if r[0]} >= {"robots", "show", "fk", "mc", "analyze", "allocate", "diagnose"}


@pytest.mark.parametrize("argv, pattern", ROWS, ids=[" ".join(r[0])[:80] or "<empty>" for r in ROWS])
def test_bad_input(files, tmp_path, monkeypatch, capsys, argv, pattern):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("keep me\n")
    (tmp_path / "adir").mkdir()
    (tmp_path / "adir" / "old.txt").write_text("old\n")
    before, inputs_before = _listing(tmp_path), _listing(files)
    code = main([a.replace("{F}", str(files)) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, (code, out, err)
    lines = [line for line in err.strip().splitlines() if not PROGRESS_LINE.match(line)]  # stderr is no terminal
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert "Traceback" not in err and "Warning" not in err
    assert re.search(pattern, lines[0]), lines[0]
    assert _listing(tmp_path) == before
    assert _listing(files) == inputs_before


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs /dev/full (Linux)")
def test_outputs_to_devices_are_written_through_never_replaced(tmp_path, monkeypatch, capsys):
    """--json /dev/full: the write error (disk full) is one error line and the device stays a device;
    --json /dev/null works (a device is written through, not replaced by a file)."""
    import stat

    monkeypatch.chdir(tmp_path)
    assert main(["analyze", TC, "--json", "/dev/full"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "/dev/full" in err[0] and "No space left" in err[0]
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)
    assert main(["analyze", TC, "--json", "/dev/null"]) == 0
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    assert list(tmp_path.iterdir()) == []


def test_every_table_a_job_reads_is_refused_the_same_way(tmp_path):
    """The parts choice, a program to predict or compensate and a fleet's tolerance table are read by one reader
    (``inputs.read_table``): a path to nothing is an InputFileError naming the argument and what the file should be,
    a folder or bytes that are no CSV an ArgumentError naming it -- never pandas' own error."""
    from tolalloc.workflows import inputs
    from tolalloc.workflows.model_use import read_program
    from tolalloc.workflows.parts import read_parts_choice

    robot = tolalloc.load_robot("ur10")
    garbage = tmp_path / "garbage.csv"
    garbage.write_bytes(b"\xff\xfe\x00\x81" * 64)
    calls = {"parts": lambda src: read_parts_choice(src),
             "program": lambda src: read_program(robot, src),
             "tolerances": lambda src: inputs.read_table(src, "tolerances", "the tolerances.csv an allocation wrote")}
    for argument, call in calls.items():
        with pytest.raises(tolalloc.InputFileError, match=rf"^{argument}: '.*absent.csv' does not exist; expected "):
            call(tmp_path / "absent.csv")
        with pytest.raises(tolalloc.ArgumentError, match=rf"^{argument}: '.*garbage.csv': cannot read the CSV"):
            call(str(garbage))
        with pytest.raises(tolalloc.ArgumentError, match=rf"^{argument}: '.*' is a folder; expected "):
            call(tmp_path)
    frame = pd.DataFrame({" joint ": ["j1"], "kind": ["reducer"]})
    assert list(inputs.read_table(frame, "x", "a table").columns) == ["joint", "kind"]
    assert inputs.read_table(np.zeros((2, 3)), "x", "a table") is None
