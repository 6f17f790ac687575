"""Property tests of every CLI command: generated command lines (robot files from generated DH tables, flags with
values at and beyond their bounds, measurement CSVs as notebooks write them) end with exit 0 or 1 and their
output, or exit 2 with one ``error:`` line naming the flag or file -- never a traceback, never a partial file.

The radian trajectory of the issue is checked explicitly: refused with a hint, accepted with ``--trust-units``.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import tolalloc
from property_strategies import count, dh_rows, examples, measurement_frame, measurement_frames
from tolalloc.cli import main
from tolalloc.progress import PROGRESS_LINE

SCRATCH = Path(tempfile.mkdtemp(prefix="tolalloc_cli_props_"))
SETTINGS = dict(deadline=None)
#: values of a numeric flag: valid, at the bounds, beyond them, not numbers
NUMBERS = ["0", "1", "-1", "1.5", "0.5", "0.95", "1e-300", "1e12", "nan", "inf", "-inf", "x", "", "1,2", "1_000",
           "0.999999999999999", "100", "2e2", "1e-15"]


def _write(name: str, text: str) -> str:
    path = SCRATCH / name
    path.write_text(text)
    return str(path)


def dh_csv(rows, convention: str) -> str:
    """A DH CSV robot file of ``rows``."""
    cols = ["name", "type", "d_mm", "a_mm", "alpha_deg", "lower_deg_mm", "upper_deg_mm", "nominal_deg_mm"]
    lines = [f"# convention: {convention}", "# name: gen", ",".join(cols)]
    lines += [",".join("" if r.get(c) is None else str(r.get(c)) for c in cols) for r in rows]
    return _write(f"dh_{abs(hash(tuple(lines)))}.csv", "\n".join(lines) + "\n")


@st.composite
def robot_tokens(draw, max_joints: int = 4):
    kind = draw(st.sampled_from(["builtin", "builtin", "file", "file", "file", "bad"]))
    if kind == "builtin":
        return draw(st.sampled_from(["tool_changer", "ur10"]))
    if kind == "file":
        return dh_csv(draw(dh_rows(1, max_joints)), draw(st.sampled_from(["standard", "modified"])))
    return draw(st.sampled_from(["nope", "", "/", str(SCRATCH), str(SCRATCH / "none.toml"),
                                 _write("garbage.toml", "[[[\n"), _write("garbage.csv", "a;b\n1;2\n"),
                                 _write("garbage.urdf", "<robot"), "tool_changer.toml"]))


def flag_values(draw, flags: dict) -> list:
    """Some of ``flags`` (flag -> strategy of its value, or None for a switch), in a drawn order."""
    chosen = draw(st.lists(st.sampled_from(sorted(flags)), max_size=5, unique=True))
    argv = []
    for flag in chosen:
        argv.append(flag)
        if flags[flag] is not None:
            argv.append(draw(flags[flag]))
    return argv


def numbers(*extra):
    return st.sampled_from(NUMBERS + list(extra))


def _pose_text(robot_token: str, draw) -> str:
    try:
        robot = tolalloc.load_robot(robot_token)
    except tolalloc.TolallocError:
        return draw(st.sampled_from(["0", "0,0,0,0,0,0", "x"]))
    q = robot.q_to_interface(robot.random_q(np.random.default_rng(draw(st.integers(0, 99))), 1))[0]
    kind = draw(st.sampled_from(["valid", "valid", "valid", "radians", "short", "nan", "text", "huge"]))
    if kind == "radians":
        q = np.where(robot.revolute_mask, np.deg2rad(q), q)
    elif kind == "short":
        q = q[:-1]
    values = [f"{v:.6g}" for v in q]
    if kind == "nan":
        values[0] = "nan"
    elif kind == "text":
        values[0] = "abc"
    elif kind == "huge":
        values[-1] = "1e12"
    return ",".join(values)


@st.composite
def command_lines(draw):
    """A command line of one of the commands, with flags from its pools."""
    cmd = draw(st.sampled_from(["robots", "show", "fk", "mc", "analyze", "allocate", "calplan", "diagnose"]))
    if cmd == "robots":
        return [cmd] + draw(st.sampled_from([[], ["extra"], ["--help-me"]]))
    robot = "tool_changer" if cmd == "diagnose" and draw(st.integers(0, 3)) else draw(robot_tokens())
    argv = [cmd, robot]
    if not draw(st.integers(0, 9)):
        argv += ["--tool", draw(st.sampled_from(["tool0", ""]))]
    common = {"--trust-units": None}
    model = {"--sigma-set": st.sampled_from(["table1", "generic", "nope"]), "--clearance": None,
             "--link-mode": st.sampled_from(["consistent", "axes_only", "x"]),
             "--deflection-mode": st.sampled_from(["screw", "tilt", "x"]),
             "--exclude": st.sampled_from(["dl1", "link_length", "nope", ""])}
    if cmd == "fk":
        argv += ["--q", _pose_text(robot, draw)] + flag_values(draw, {**common, "--json": None})
    elif cmd == "show":
        argv += flag_values(draw, common)
    elif cmd == "mc":
        argv += ["--n", draw(st.sampled_from(["1", "2", "50", "0", "-1", "1.5", "x", "nan", "1e2"]))]
        argv += flag_values(draw, {**common, **model, "--seed": numbers(), "--pose": st.just(_pose_text(robot, draw)),
                                   "--pose-set": st.sampled_from(["nominal", "working", "nope"]),
                                   "--radius-mm": numbers(), "--angle-radius-deg": numbers(),
                                   "--angle-radius-rad": numbers(), "--ci": st.sampled_from(["wilson", "exact", "x"]),
                                   "--hist-bins": numbers("4", "2001"), "--hist-range-mm": numbers(),
                                   "--estimator": st.sampled_from(["plain", "paired", "x"]),
                                   "--jobs": numbers(), "--chunk-size": numbers(), "--sigma": st.sampled_from(
                                       ["dl1=0.1", "dl1", "nope=1", "dl1=-1", "link_length=nan", "=3"]),
                                   "--json": st.sampled_from(["-", "out.json", "", "adir"]),
                                   "--out": st.sampled_from(["res", "afile", "afile/x", ""])})
    elif cmd == "analyze":
        argv += flag_values(draw, {**common, **model, "--pose": st.just(_pose_text(robot, draw)),
                                   "--poses": st.sampled_from(["nominal", "working", "nope"]),
                                   "--radius-mm": numbers(), "--prob": numbers(), "--top": numbers(),
                                   "--clearance-tilt-literal": None, "--sobol-n": numbers("16", "32"),
                                   "--seed": numbers(),
                                   "--json": st.sampled_from(["-", "out.json", "adir"]),
                                   "--out": st.sampled_from(["res", "afile", ""])})
    elif cmd == "allocate":
        region = draw(st.sampled_from(["nominal", "nominal", "working", "nope", "traj.csv", "traj_rad.csv"]))
        argv += ["--region", region] + flag_values(draw, {
            **common, **model, "--radius-mm": numbers(), "--prob": numbers(), "--z": numbers(), "--uniform": None,
            "--angle-radius-deg": numbers(), "--angle-prob": numbers(), "--solver": st.sampled_from(["exact", "x"]),
            "--n-mc": st.sampled_from(["200", "99", "1.5", "x", "0"]), "--no-verify": None, "--no-correction": None,
            "--correction-rounds": numbers(), "--seed": numbers(), "--no-snap": None,
            "--angle-step-deg": numbers(), "--coverage-n": numbers(),
            "--costs": st.sampled_from([_write("c1.toml", "z = 2\n"), _write("c2.toml", "[kinds.link_length]\nb = -1\n"),
                                        _write("c3.toml", "[parameters.nope]\na = 1\n"), "none.toml"]),
            "--calibration": st.sampled_from(["none.csv", _write("plan.csv", "# measurement = position\nx\n")]),
            "--out": st.sampled_from(["res", "afile", ""]), "--report": st.sampled_from(["rep", "afile", "res"]),
            "--estimator": st.sampled_from(["auto", "plain", "paired", "importance", "x"]),
            "--poses": st.sampled_from(["nominal", "working", "nope"])})
        if "--no-verify" not in argv and "--n-mc" not in argv:
            argv += ["--n-mc", "200"]
    elif cmd == "calplan":
        argv += ["--n-poses", draw(st.sampled_from(["2", "3", "2", "3", "0", "x", "1.5"])), "--n-candidates",
                 draw(st.sampled_from(["8", "12", "8", "12", "1", "0", "1e12"])), "--out",
                 draw(st.sampled_from(["plan.csv", "plan.csv", "plan.csv", "afile", "adir", ""]))]
        argv += flag_values(draw, {**common, "--region": st.sampled_from(["limits", "working", "nope"]),
                                   "--measurement": st.sampled_from(["position", "pose", "x"]),
                                   "--noise-mm": numbers(), "--noise-deg": numbers(), "--no-registration": None,
                                   "--seed": numbers(), "--sigma-set": st.sampled_from(["table1", "nope"]),
                                   "--eval-poses": st.sampled_from(["nominal", "working", "nope"]),
                                   "--costs": st.sampled_from([_write("c4.toml", "[calibration.kinds.link_length]\n"
                                                                                 "systematic = 0.5\n"), "none.toml"])})
    else:
        frame = draw(st.one_of(st.builds(measurement_frame), measurement_frames()))
        train = _write(f"train_{abs(hash(frame.to_csv()))}.csv", frame.iloc[:36].to_csv(index=False))
        test = _write("test.csv", measurement_frame().iloc[36:].to_csv(index=False))
        argv += ["--train", train, "--folds", "2"] + flag_values(draw, {
            "--test": st.sampled_from([test, train, "none.csv"]), "--test-frame": st.sampled_from(["same", "refit"]),
            "--register-n": numbers(), "--register-rows": st.sampled_from(["1-10", "1-5,5", "3-1", "x", "30-99"]),
            "--alpha": numbers(), "--seed": numbers(), "--cv-rows": numbers(),
            "--json": st.sampled_from(["-", "d.json", "adir"]), "--predictions": st.sampled_from(["p.csv", "adir"]),
            "--report": st.sampled_from(["rep", "afile"]), "--trust-units": None, "--gap-split": None,
            "--progress": None, "--no-progress": None})
    return argv


def _listing(root: Path) -> dict:
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in dirnames + filenames:
            p = Path(dirpath) / n
            out[str(p.relative_to(root))] = None if p.is_dir() else p.read_bytes()
    return out


def run_cli(argv, workdir: Path, capsys):
    """Run ``argv`` in ``workdir``: ``(exit code, stdout, stderr lines but the progress lines, written)``."""
    old = Path.cwd()
    os.chdir(workdir)
    try:
        before = _listing(workdir)
        code = main(argv)
        after = _listing(workdir)
    finally:
        os.chdir(old)
    out, err = capsys.readouterr()
    written = {k for k in after if before.get(k, 0) != after[k]}
    return code, out, [line for line in err.strip().splitlines() if not PROGRESS_LINE.match(line)], written


def _workdir() -> Path:
    work = Path(tempfile.mkdtemp(dir=SCRATCH))
    (work / "afile").write_text("keep me\n")
    (work / "adir").mkdir()
    robot = tolalloc.load_robot("tool_changer")
    q = robot.q_to_interface(robot.poses("working"))
    np.savetxt(work / "traj.csv", q, delimiter=",", header="q1,q2,q3,q4,q5,q6", comments="")
    np.savetxt(work / "traj_rad.csv", np.where(robot.revolute_mask, np.deg2rad(q), q), delimiter=",")
    return work


def check_run(code, out, err, written, argv):
    count("cli_exit_codes", f"{argv[0]} {code}")
    assert code in (0, 1, 2), (code, argv)
    assert not any("Traceback" in line for line in err), err
    if "--progress" in argv:  # the progress bars asked for go to stderr before the outcome
        err = [line for line in err if line.startswith("error: ")][-1:] or err
    if code == 2:
        assert len(err) == 1 and err[0].startswith("error: "), (argv, err)
        assert not written, (argv, written)
        line = err[0]
        tokens = [t for t in argv[1:] if len(t) > 1] + [Path(t).name for t in argv[1:] if len(Path(t).name) > 1]
        assert "--" in line or any(t in line for t in tokens) or "robot" in line or "argument" in line, line
    else:
        assert out.strip() or written, (argv, code)


TWO_LINK = dh_csv([{"name": "j1", "d_mm": 400, "a_mm": 0, "alpha_deg": 90},
                  {"name": "j2", "d_mm": 0, "a_mm": 600, "alpha_deg": 0}], "standard")
# the valid measurement files of the examples below: named at import, written by the test (the measurements are
# simulated, which needs compiled kernels; at import both workers would compile them at once on a fresh checkout)
TRAIN, TEST = str(SCRATCH / "train_valid.csv"), str(SCRATCH / "test_valid.csv")


def _write_valid_measurements() -> None:
    if not Path(TEST).exists():
        _write("train_valid.csv", measurement_frame().iloc[:36].to_csv(index=False))
        _write("test_valid.csv", measurement_frame().iloc[36:].to_csv(index=False))


@settings(max_examples=examples(30, 0.1), **SETTINGS)
@example(argv=["allocate", "tool_changer", "--region", "nominal", "--n-mc", "200", "--out", "res"])
@example(argv=["mc", "ur10", "--n", "50", "--hist-bins", "4", "--estimator", "paired", "--out", "res", "--json", "-"])
@example(argv=["calplan", TWO_LINK, "--n-poses", "2", "--n-candidates", "8", "--out", "plan.csv"])
@example(argv=["diagnose", "tool_changer", "--train", TRAIN, "--test", TEST, "--folds", "2", "--json", "d.json",
               "--predictions", "p.csv"])
@example(argv=["fk", TWO_LINK, "--q", "10,20", "--json"])
@given(argv=command_lines())
def test_every_command_exits_cleanly(argv, capsys):
    _write_valid_measurements()
    if argv[0] == "calplan" and argv[1] in ("tool_changer", "ur10"):
        argv = [argv[0], TWO_LINK, *argv[2:]]  # a design over the tool_changer's candidates takes seconds
    if argv[0] == "allocate" and argv[1] == "tool_changer" and "working" in argv and "--no-verify" not in argv:
        argv = [*argv, "--no-verify"]  # the working box's search and its coverage check take seconds
    code, out, err, written = run_cli(argv, _workdir(), capsys)
    check_run(code, out, err, written, argv)


# ------------------------------------------------------------------------------------------------ unit slips
def test_radian_trajectory_is_refused_with_a_hint_and_accepted_with_trust_units(capsys):
    """The issue's example: a trajectory CSV of the tool_changer written in radians (q4 in mm)."""
    work = _workdir()
    code, out, err, written = run_cli(["allocate", "tool_changer", "--region", "traj_rad.csv", "--no-verify"], work,
                                      capsys)
    assert code == 2 and len(err) == 1 and not written, err
    assert err[0].startswith("error: --region: 'traj_rad.csv': every revolute joint value lies within +-2 pi"), err
    assert "look like radians" in err[0] and "robot.q_to_interface(q)" in err[0] and "--trust-units" in err[0], err
    code, out, err, written = run_cli(["allocate", "tool_changer", "--region", "traj_rad.csv", "--no-verify",
                                       "--trust-units"], work, capsys)
    assert code == 0, err
    assert "traj_rad.csv" in out
    # in degrees, the same trajectory runs without --trust-units
    code, out, err, written = run_cli(["allocate", "tool_changer", "--region", "traj.csv", "--no-verify"], work, capsys)
    assert code == 0, err
    # measurement files follow the same rule, in the same words
    frame = measurement_frame()
    for c in ("q1", "q2", "q3", "q5", "q6"):
        frame[c] = np.deg2rad(frame[c])
    frame.to_csv(work / "rad.csv", index=False)
    code, out, err, written = run_cli(["diagnose", "tool_changer", "--train", "rad.csv"], work, capsys)
    assert code == 2 and err[0].startswith("error: --train: 'rad.csv' (q1..q6): every revolute joint value lies "
                                           "within +-2 pi"), err
    code, out, err, written = run_cli(["diagnose", "tool_changer", "--train", "rad.csv", "--trust-units"], work, capsys)
    # trusted, the radians pass the unit rule and meet the physics: the model's points do not fit the measured ones
    assert code == 2 and "every revolute joint value" not in err[0] and "joint columns" in err[0], err


def test_joint_value_inputs_share_one_unit_rule(tmp_path):
    """The same radians are refused with the same words as q_deg_mm, region (array or CSV), measurement frame
    or file, and a robot file's pose set; trust_units=True accepts them."""
    from tolalloc.units import TRUST_HINT, radians_fix

    robot = tolalloc.load_robot("tool_changer")
    q = robot.q_to_interface(robot.poses("working"))
    rad = np.where(robot.revolute_mask, np.deg2rad(q), q)
    frame = measurement_frame()
    for c in ("q1", "q2", "q3", "q5", "q6"):
        frame[c] = np.deg2rad(frame[c])
    frame.to_csv(tmp_path / "train.csv", index=False)
    np.savetxt(tmp_path / "traj.csv", rad, delimiter=",")
    calls = {
        "q_deg_mm": lambda **kw: tolalloc.analyze_errors(robot, q_deg_mm=rad, **kw),
        "region": lambda **kw: tolalloc.allocate_tolerances(robot, region=rad, verification=False, **kw),
        "region ": lambda **kw: tolalloc.allocate_tolerances(robot, region=tmp_path / "traj.csv",
                                                             verification=False, **kw),
        "train": lambda **kw: tolalloc.diagnose_measurements(robot, frame, folds=2, **kw),
        "train ": lambda **kw: tolalloc.diagnose_measurements(robot, tmp_path / "train.csv", folds=2, **kw),
    }
    for argument, call in calls.items():
        with pytest.raises(tolalloc.ArgumentError) as info:
            call()
        assert info.value.argument == argument.strip()
        text = str(info.value)
        assert "every revolute joint value lies within +-2 pi" in text and "look like radians" in text, text
        assert text.endswith(f"{radians_fix(robot.revolute_mask)} ({TRUST_HINT}).") , text
    calls["q_deg_mm"](trust_units=True)
    calls["region"](trust_units=True)
    # the diagnosis, trusted, then fails on the physics (the radians do not fit the measured points), not on units
    with pytest.raises(tolalloc.TolallocError) as info:
        calls["train"](trust_units=True)
    assert "look like radians" not in str(info.value).split(";")[0]
    toml = (Path(tolalloc.__file__).parent / "data" / "robots" / "tool_changer.toml").read_text()
    rows = ", ".join("[" + ", ".join(f"{v:.6g}" for v in r) + "]" for r in rad)
    (tmp_path / "r.toml").write_text(toml.split("[pose_sets")[0] + f"\n[pose_sets.rad]\nq_deg_mm = [{rows}]\n"
                                     if "[pose_sets" in toml else toml + f"\n[pose_sets.rad]\nq_deg_mm = [{rows}]\n")
    with pytest.raises(tolalloc.TolallocError, match=r"pose_sets\.rad\.q_deg_mm: every revolute joint value lies "
                                                     r"within \+-2 pi.*look like radians"):
        tolalloc.load_robot(tmp_path / "r.toml")
