"""`tolalloc diagnose`: outputs, bad input -> exit 2 and nothing written."""

import json

import numpy as np
import pandas as pd

import tolalloc
from tolalloc.cli import main
from tolalloc.diagnose import generate
from tolalloc.diagnose.synth import split_frame


def _files(tmp_path, effect="backlash", seed=5):
    robot = tolalloc.load_robot("tool_changer")
    case = generate(robot, effect, 160, np.random.default_rng(seed))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    tr.to_csv(tmp_path / "train.csv", index=False)
    te.to_csv(tmp_path / "test.csv", index=False)
    return te


def test_end_to_end(tmp_path, capsys):
    te = _files(tmp_path)
    rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
               "--json", str(tmp_path / "out.json"), "--predictions", str(tmp_path / "pred.csv"),
               "--report", str(tmp_path / "rep"), "--folds", "3"])
    assert rc == 0
    js = json.loads((tmp_path / "out.json").read_text())
    assert js["effect"] == "backlash"
    assert js["rms_mm"]["final"] < js["rms_mm"]["geometric"] < js["rms_mm"]["nominal"]
    pred = pd.read_csv(tmp_path / "pred.csv")
    assert list(pred.columns) == ["x_mm", "y_mm", "z_mm"] and len(pred) == len(te)
    err = np.linalg.norm(pred.to_numpy() - te[["x_mm", "y_mm", "z_mm"]].to_numpy(), axis=1)
    assert np.sqrt(np.mean(err ** 2)) == __import__("pytest").approx(js["test_rms_mm"]["final"], rel=1e-6)
    assert (tmp_path / "rep" / "report.md").exists() and (tmp_path / "rep" / "where.png").exists()
    assert "effect: backlash" in capsys.readouterr().out


def test_bad_input_exit_2_nothing_written(tmp_path, capsys):
    _files(tmp_path)
    df = pd.read_csv(tmp_path / "train.csv")
    df[["x_mm", "y_mm", "z_mm"]] /= 1000
    df.to_csv(tmp_path / "metres.csv", index=False)
    args = ["--json", str(tmp_path / "o.json"), "--report", str(tmp_path / "r")]
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "metres.csv"), *args]) == 2
    assert "metres" in capsys.readouterr().err
    df = pd.read_csv(tmp_path / "train.csv").rename(columns={"q2": "joint2"})
    df.to_csv(tmp_path / "bad.csv", index=False)
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "bad.csv"), *args]) == 2
    assert "missing column" in capsys.readouterr().err
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--predictions",
                 str(tmp_path / "p.csv")]) == 2
    assert "--predictions needs --test" in capsys.readouterr().err
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "r").exists() and not (tmp_path / "p.csv").exists()
