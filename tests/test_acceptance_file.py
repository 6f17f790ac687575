"""Requirement files (tolalloc.acceptance.requirement_file), the ISO 9283 job (tolalloc.allocate_acceptance) and
`tolalloc allocate --requirement FILE`: the example parses, units convert, bad files are refused with one error
naming the key; the job writes its datasheet."""

import json
from pathlib import Path

import pandas as pd
import pytest

from iso_setup import ur10_test
from tolalloc.exceptions import TolallocError
from tolalloc.acceptance import PoseAccuracy, PoseRepeatability
from tolalloc.acceptance.requirement_file import parse_requirements, read_requirement_file
from tolalloc.cli import main

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "requirements_iso9283.toml"


def test_example_file_parses():
    f = read_requirement_file(EXAMPLE)
    assert [r.kind for r in f.requirements] == ["pose_accuracy", "pose_repeatability"]
    assert f.requirements[1].limit_mm == 0.05 and f.requirements[1].share == 0.95
    assert f.test["cycles"] == 30 and f.test["tracker"].mpe_mm == pytest.approx(0.027)


def test_units_convert():
    f = parse_requirements({"requirement": [
        {"kind": "pose_repeatability", "limit_um": 40, "load_pct": 10},
        {"kind": "orientation_repeatability", "limit_arcsec": 36},
        {"kind": "position", "radius_um": 250, "prob": 0.99}],
        "test": {"tracker_mpe_a_um": 10, "tracker_mpe_b_um_per_m": 2}})
    pos, orr, rp = (next(r for r in f.requirements if r.kind == k)
                    for k in ("position", "orientation_repeatability", "pose_repeatability"))
    assert rp.limit_mm == pytest.approx(0.04) and rp.conditions.load_pct == 10
    assert orr.limit_deg == pytest.approx(0.01) and pos.radius_mm == pytest.approx(0.25)
    tracker = f.test["tracker"]
    assert tracker.mpe_a_mm == pytest.approx(0.01) and tracker.mpe_b_mm_per_m == pytest.approx(0.002)


@pytest.mark.parametrize("data, match", [
    ({"requirement": [{"kind": "pose_acuracy", "limit_mm": 0.5}]},
     r"f: requirement\[1\]\.kind: unknown kind 'pose_acuracy'; known: position, orientation, pose_accuracy"),
    ({"requirement": [{"kind": "pose_accuracy", "limit": 0.5}]},
     r"f: requirement\[1\]\.limit: a value needs its unit in its key; write limit_mm or limit_um = 0\.5"),
    ({"requirement": [{"kind": "position", "radius": 0.25}]},
     r"requirement\[1\]\.radius: a value needs its unit in its key; write radius_mm or radius_um = 0\.25"),
    ({"requirement": [{"kind": "pose_accuracy", "limit_mm": 0.5, "share": 1.5}]},
     r"requirement\[1\]: PoseAccuracy\.share: expected a probability"),
    ({"requirement": [{"kind": "pose_accuracy", "limit_mm": 0.5, "limt_deg": 1}]},
     r"requirement\[1\]: unknown key\(s\) limt_deg for kind 'pose_accuracy'"),
    ({"requirement": [{"kind": "pose_accuracy", "limit_mm": 0.5}], "test": {"cube_edge": 100}},
     r"\[test\]: unknown key\(s\) cube_edge; expected .*; a value needs its unit in its key"),
    ({"requirements": []}, r"f: unknown top-level key\(s\) requirements"),
])
def test_bad_files_refused(data, match):
    with pytest.raises(TolallocError, match=match):
        parse_requirements(data, "f")


def test_cli_requirement_file_bad_input(tmp_path, capsys):
    bad = tmp_path / "r.toml"
    bad.write_text('[[requirement]]\nkind = "pose_repeatability"\nlimit = 0.05\n')
    assert main(["allocate", "ur10", "--requirement", str(bad)]) == 2
    assert "requirement[1].limit: a value needs its unit in its key; write limit_mm or limit_um" in \
        capsys.readouterr().err
    assert main(["allocate", "ur10", "--requirement", str(EXAMPLE), "--prob", "0.9"]) == 2
    assert "--requirement: not with --prob" in capsys.readouterr().err


def test_job_writes_the_datasheet(tmp_path):
    import tolalloc
    from tolalloc.errormodel import build_error_model

    robot, test = ur10_test()
    others = tuple(p.name for p in build_error_model(robot).params if p.kind != "joint_drive")
    reqs = [PoseAccuracy(limit_mm=0.05), PoseRepeatability(limit_mm=0.05)]
    res = tolalloc.allocate_acceptance(robot, reqs, error_model=tolalloc.ErrorModelOptions(exclude=others), test=test,
                                       solver=tolalloc.Solver(snap=False), n_robots=300)
    assert res.ok and not res.demonstrated  # RP_l: the tracker's noise alone is of the order of the limit
    names = {p.name for p in res.save(tmp_path / "out")}
    assert {"datasheet.csv", "summary.json", "acceptance.png", "tolerances.csv"} <= names
    ds = pd.read_csv(tmp_path / "out" / "datasheet.csv")
    assert list(ds.statistic.unique()) == ["AP_P", "RP_l"] and (ds.p_meets >= 0.95 - 1e-5).all()
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["met"] and s["inputs"]["test"]["cycles"] == 30 and len(s["simulated_share_meeting"]["AP_P"]) == 5
    assert set(s["allocation"]["diagnosis"]["radius_best_max"]) == {"AP_P_mm", "RP_l_mm"}  # units of the blocks
