"""`tolalloc diagnose`: outputs, bad input -> exit 2 and nothing written."""

import contextlib
import io
import json

import numpy as np
import pandas as pd
import pytest

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


@pytest.fixture(scope="module")
def full_run(tmp_path_factory):
    """One ``tolalloc diagnose`` with every output (JSON, predictions, report, gap split): the folder, the test frame,
    the return code and what it printed (two tests read its outputs)."""
    tmp_path = tmp_path_factory.mktemp("diagnose_cli")
    te = _files(tmp_path)
    with contextlib.redirect_stdout(io.StringIO()) as out:
        rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test",
                   str(tmp_path / "test.csv"), "--json", str(tmp_path / "out.json"), "--predictions",
                   str(tmp_path / "pred.csv"), "--report", str(tmp_path / "rep"), "--folds", "3", "--gap-split"])
    return tmp_path, te, rc, out.getvalue()


def test_end_to_end(full_run):
    tmp_path, te, rc, out = full_run
    assert rc == 0
    js = json.loads((tmp_path / "out.json").read_text())
    assert js["effect"] == "backlash"
    # each figure under its own key: the test file's and the cross-validation's; no pooled one
    assert js["test_rms_mm"]["final"] < js["test_rms_mm"]["geometric"] < js["test_rms_mm"]["nominal"]
    assert not {"rms_mm", "p95_mm", "max_mm", "shrink_pct"} & set(js)
    pred = pd.read_csv(tmp_path / "pred.csv")
    assert list(pred.columns) == ["row", "x_mm", "y_mm", "z_mm", "sigma_mm", "radius95_mm", "registration",
                                  "extrapolation"]
    assert len(pred) == len(te) and (pred["sigma_mm"] > 0).all() and (pred["registration"] == 0).all()
    assert (pred["radius95_mm"] > pred["sigma_mm"]).all()  # the radius adds the measurement noise
    err = np.linalg.norm(pred[["x_mm", "y_mm", "z_mm"]].to_numpy() - te[["x_mm", "y_mm", "z_mm"]].to_numpy(), axis=1)
    assert np.sqrt(np.mean(err ** 2)) == __import__("pytest").approx(js["test_rms_mm"]["final"], rel=1e-6)
    assert (tmp_path / "rep" / "report.md").exists() and (tmp_path / "rep" / "where.png").exists()
    assert out.startswith("verdict: effect -- backlash")
    # order: test-file figures, then cross-validation, worst test poses, guards, ranking
    heads = ["test file", "cross-validation on the training file", "worst test poses", "predicted uncertainty",
             "ranking"]
    pos = [out.index(h) for h in heads]
    assert pos == sorted(pos)
    test_block = out[pos[0]:pos[1]]
    final_rms = float(test_block.split("final")[1].split()[0])
    assert final_rms == __import__("pytest").approx(js["test"]["rms_mm"]["final"], abs=1e-4)
    assert js["test"]["rms_mm"] == js["test_rms_mm"] and set(js["cv"]["rms_mm"]) == {"nominal", "geometric", "final"}
    assert js["cv"]["rms_mm"] == js["cv_rms_mm"] != js["test_rms_mm"]
    cv_block = out[pos[1]:pos[2]]
    assert float(cv_block.split("final")[1].split()[0]) == __import__("pytest").approx(js["cv_rms_mm"]["final"], abs=1e-4)
    shrink = js["test"]["shrink_pct"]["final_vs_nominal"]
    assert shrink == __import__("pytest").approx(100 * (1 - js["test_rms_mm"]["final"] / js["test_rms_mm"]["nominal"]))
    assert 0 <= js["uncertainty"]["coverage95"] <= 1 and len(js["uncertainty"]["sigma_mm"]) == len(te)


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
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
                 "--register-n", "10", *args]) == 2
    assert "--register-n needs --test-frame refit" in capsys.readouterr().err
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
                 "--register-update", "calibration", *args]) == 2
    assert "--register-update needs --test-frame refit" in capsys.readouterr().err
    assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test", str(tmp_path / "test.csv"),
                 "--test-frame", "refit", "--register-n", "38", *args]) == 2  # the test file has 40 poses
    err = capsys.readouterr().err
    assert "error: --register-n 38 gives 38 registration and 2 scored poses" in err and "`" not in err
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "r").exists() and not (tmp_path / "p.csv").exists()


def test_gap_split_adds_up_to_the_test_errors(full_run):
    tmp_path, _, rc, out = full_run
    assert rc == 0
    js = json.loads((tmp_path / "out.json").read_text())
    g, rms = js["gap_split"], js["test"]["rms_mm"]
    parts = ["removed_by_geometry", "removed_by_effect", "systematic_unnamed", "noise_floor", "rest"]
    assert sum(g[p] for p in parts) == __import__("pytest").approx(g["ms_nominal"], rel=1e-9)
    # mean squares of the 3-D error are the squared RMS figures of the same test poses
    assert g["ms_nominal"] == __import__("pytest").approx(rms["nominal"] ** 2, rel=1e-6)
    assert g["removed_by_geometry"] == __import__("pytest").approx(rms["nominal"] ** 2 - rms["geometric"] ** 2, rel=1e-6)
    assert g["removed_by_effect"] == __import__("pytest").approx(rms["geometric"] ** 2 - rms["final"] ** 2, rel=1e-6)
    assert 0 <= g["systematic_unnamed"] <= rms["final"] ** 2 and g["noise_floor"] > 0
    assert pd.read_csv(tmp_path / "rep" / "gap_split.csv")["part"].tolist() == parts
    assert "where the test error lies" in out


def test_gap_split_needs_a_test_file(tmp_path, capsys):
    _files(tmp_path)
    rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--gap-split",
               "--json", str(tmp_path / "o.json")])
    assert rc == 2 and "--gap-split needs --test" in capsys.readouterr().err
    assert not (tmp_path / "o.json").exists()


def test_refit_options_need_a_test_file(tmp_path, capsys):
    _files(tmp_path)
    for option in (["--register-update", "calibration"], ["--register-n", "10"]):
        rc = main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test-frame", "refit",
                   *option, "--json", str(tmp_path / "o.json"), "--report", str(tmp_path / "r")])
        err = capsys.readouterr().err
        assert rc == 2 and err.startswith(f"error: {option[0]} needs --test: only a test file in another frame")
        assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "r").exists()


def test_register_update_reaches_the_fit_and_the_json(tmp_path, capsys):
    _files(tmp_path)
    runs = {}
    for update in ("frame", "calibration"):
        out = tmp_path / f"{update}.json"
        assert main(["diagnose", "tool_changer", "--train", str(tmp_path / "train.csv"), "--test",
                     str(tmp_path / "test.csv"), "--test-frame", "refit", "--register-n", "12",
                     "--register-update", update, "--folds", "3", "--json", str(out)]) == 0
        runs[update] = json.loads(out.read_text())
    capsys.readouterr()
    assert runs["calibration"]["settings"]["register_update"] == "calibration"
    assert runs["frame"]["settings"]["register_update"] == "frame"
    reg = runs["calibration"]["test"]["registration"]
    assert reg["update"] == "calibration" and reg["robust_loss"] == "huber" and reg["inflation_k"]["geometric"] >= 1
    assert runs["calibration"]["settings"]["register_update_robust_loss"] == "huber"
    frame, upd = (runs[k]["test"]["rms_mm"]["final"] for k in ("frame", "calibration"))
    # one session on both sides: the update has nothing to correct and stays at the frame-only figure
    assert upd == __import__("pytest").approx(frame, rel=0.15)
