"""CLI helpers (tolalloc/cli/common.py): all-or-nothing output, early output checks, negative joint lists, --sigma."""

from __future__ import annotations

import os
import stat

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.cli import main
from tolalloc.cli.common import check_output, sigma_items, write_json
from tolalloc.outputs import atomic_output
from tolalloc.workflows.inputs import sigma_overrides
from tolalloc.errormodel import build_error_model


def test_atomic_file_gets_the_usual_permissions(tmp_path):
    # regression: mkstemp made summary.json / analyze.json readable by the owner only (0o600)
    path = tmp_path / "a.json"
    write_json({"x": 1}, path)
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask
    assert [p.name for p in tmp_path.iterdir()] == ["a.json"]


def test_unwritable_places_raise_tolalloc_error(tmp_path):
    # regression: an OSError (a file where a directory should be ...) came out as a traceback
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(TolallocError, match="cannot write an output directory"):
        with atomic_output(blocker / "sub", directory=True) as tmp:
            (tmp / "x.txt").write_text("never")
    with pytest.raises(TolallocError, match="cannot write an output file"):
        with atomic_output(tmp_path, directory=False) as tmp:  # the target is a directory
            tmp.write_text("never")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


@pytest.mark.parametrize("kind, directory, match", [
    ("file_as_dir", True, "expected a directory path, but .* is a file"),
    ("dir_as_file", False, "expected a file path, but .* is a directory"),
    ("below_file", False, "expected a path below a directory, but .* is a file"),
])
def test_check_output_refuses_before_any_work(tmp_path, kind, directory, match):
    blocker = tmp_path / "f"
    blocker.write_text("x")
    path = {"file_as_dir": blocker, "dir_as_file": tmp_path, "below_file": blocker / "deeper" / "x.json"}[kind]
    with pytest.raises(TolallocError, match="--out .*" + match):
        check_output(path, "--out", directory=directory)
    check_output(tmp_path / "new" / "dir", "--out", directory=True)  # a new place is fine
    check_output("-", "--json")
    assert not (tmp_path / "new").exists()


def test_joint_list_starting_with_a_minus_is_a_value(capsys):
    # regression: argparse took "-15,30,..." for an unknown option ("expected one argument")
    assert main(["fk", "tool_changer", "--q", "-15,30,-10,0,-20,-5"]) == 0
    out = capsys.readouterr().out
    assert "position_mm: [415.691939, 1551.383436, 1196.616115]" in out  # the mirror image of the nominal pose


def test_sigma_overrides_units_per_parameter():
    model = build_error_model(load_robot("tool_changer"))
    got = sigma_overrides(model.params, sigma_items(["joint_drive=0.01", "dd4=0.2", "dl1=0.05"]))
    # a kind sets each parameter in its own unit (deg for revolute drives, mm for the prismatic one); names win
    assert got["dth1"] == pytest.approx(np.deg2rad(0.01)) and got["dd4"] == 0.2 and got["dl1"] == 0.05
    assert sigma_overrides(model.params, sigma_items(["dd4=0.2", "joint_drive=0.01"]))["dd4"] == 0.2
    with pytest.raises(TolallocError, match=r"sigma: dth1: expected a finite sigma >= 0 in deg, got -0.01"):
        sigma_overrides(model.params, sigma_items(["dth1=-0.01"]))
    with pytest.raises(TolallocError, match=r"sigma: joint_drive: expected a finite sigma >= 0 in deg / mm"):
        sigma_overrides(model.params, sigma_items(["joint_drive=nan"]))
    with pytest.raises(TolallocError, match=r"--sigma: expected NAME=VALUE"):
        sigma_items(["dth1"])


@pytest.mark.parametrize("argv, near", [
    (["allocate", "tool_changer", "--radius", "0.25"], "--radius-mm"),
    (["allocate", "tool_changer", "--angle-radius", "0.1"], "--angle-radius-deg"),
    (["mc", "tool_changer", "--n", "10", "--angle-radius=0.1"], "--angle-radius-deg or --angle-radius-rad"),
])
def test_abbreviated_flags_are_refused_with_the_full_flag(tmp_path, capsys, argv, near):
    out = tmp_path / "o"
    assert main([*argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and not out.exists(), err
    flag = argv[-2] if "=" not in argv[-1] else argv[-1].split("=")[0]
    assert err[0].startswith(f"error: tolalloc {argv[0]}: unrecognized arguments: {flag}"), err
    assert err[0].endswith(f"; did you mean {near}? Flags are written in full, with their unit "
                           f"(see 'tolalloc {argv[0]} --help')."), err


def test_no_parser_abbreviates():
    import argparse

    from tolalloc.cli import build_parser

    top = build_parser()
    subs = next(a for a in top._actions if isinstance(a, argparse._SubParsersAction)).choices
    assert not top.allow_abbrev and subs and all(not p.allow_abbrev for p in subs.values())


def test_json_flag_takes_an_output_in_every_command_and_joint_values_both_spellings(tmp_path, capsys):
    import json

    q = "15,30,-10,0,-20,-5"
    assert main(["fk", "tool_changer", "--q", q, "--json", "-"]) == 0  # the documented form
    first = json.loads(capsys.readouterr().out)
    assert main(["fk", "tool_changer", "--pose", q, "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == first
    assert main(["fk", "tool_changer", "--q", q, "--json", str(tmp_path / "p.json")]) == 0
    assert json.loads((tmp_path / "p.json").read_text()) == first and capsys.readouterr().out == ""
    assert main(["analyze", "tool_changer", "--q", q, "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["std_mm"]
