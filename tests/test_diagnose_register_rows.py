"""Registration rows named by the user (``register_rows`` / ``--register-rows``): a refit test file is registered
on exactly those rows and scored on every other row.

Known answers: the given rows are the JSON's ``registration_rows`` and the predictions' ``registration`` rows, and
the scored count is T - r; the rows a k-means run reports, given back, reproduce its split and its figures (also
in a test file with a skipped row, whose later rows keep their file numbers); every refusal names its rule.
"""

import argparse
import json
import shlex

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.cli import build_parser, main
from tolalloc.cli.argtypes import row_ranges
from tolalloc.diagnose import diagnose, generate
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.register import registration_split, split_from_rows
from tolalloc.diagnose.synth import split_frame
from tolalloc.exceptions import TolallocError
from tolalloc.progress import PROGRESS_LINE
from tolalloc.workflows import diagnose_measurements
from tolalloc.report.html_diagnosis import row_ranges_text
from tolalloc.workflows.reproduce import diagnosis_command


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A tool_changer session with backlash: 120 training rows, 40 test rows; and the test file with row 3
    emptied (skipped: 39 poses, rows 1-2 and 4-40)."""
    folder = tmp_path_factory.mktemp("rows")
    case = generate(tolalloc.load_robot("tool_changer"), "backlash", 160, np.random.default_rng(5))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    tr.to_csv(folder / "train.csv", index=False)
    te.to_csv(folder / "test.csv", index=False)
    gap = te.copy()
    gap.iloc[2, gap.columns.get_loc("x_mm")] = np.nan
    gap.to_csv(folder / "gap.csv", index=False)
    return folder


def _run(files, test="test.csv", **refit):
    """The diagnosis of ``test`` re-registered on the fields ``refit`` of its :class:`tolalloc.Refit`."""
    return diagnose_measurements("tool_changer", files / "train.csv", files / test, folds=3,
                                 test_frame=tolalloc.Refit(**refit))


def test_given_rows_register_the_frame_and_are_never_scored(files):
    given = [*range(1, 9), 17, 30]
    job = _run(files, register_rows=given)
    d, js = job.diagnosis, job.summary()
    reg = js["test"]["registration"]
    assert reg["registration_rows"] == given and reg["registration_poses"] == 10
    assert js["test"]["scored_poses"] == reg["scored_poses"] == 40 - 10 == len(d.final.test_mm)
    assert reg["register_n_requested"] is None and d.registration.chosen_by == "given rows"
    assert "k-means" not in reg["method"] and reg["method"].startswith("the rows given as registration rows")
    pred = job.predictions_frame()
    assert pred.loc[pred["registration"] == 1, "row"].tolist() == given
    assert not set(np.asarray(d.test.rows)[d.scored_index]) & set(given)
    assert "12 other" not in job.text() and "10 other test poses (the given registration rows) fitted" in job.text()
    assert job.inputs["register_rows"] == given and job.inputs["register_n"] is None


def test_rows_of_a_previous_run_reproduce_its_split_and_figures(files):
    first = _run(files, test="gap.csv", register_n=12)
    rows = first.summary()["test"]["registration"]["registration_rows"]
    assert first.diagnosis.test.n_poses == 39 and 3 not in first.diagnosis.test.rows  # row 3 skipped, 4.. kept
    again = _run(files, test="gap.csv", register_rows=rows)
    a, b = first.summary(), again.summary()
    assert b["test"]["registration"]["registration_rows"] == rows
    np.testing.assert_array_equal(again.diagnosis.registration.register_index,
                                  first.diagnosis.registration.register_index)
    for block in ("rms_mm", "p95_mm", "max_mm"):
        assert b["test"][block] == a["test"][block]
    for key in ("rotation", "translation_mm", "target_offset_mm"):
        assert b["test"]["registration"][key] == a["test"]["registration"][key]
    assert b["uncertainty"]["coverage95"] == a["uncertainty"]["coverage95"]
    # the report's command line gives the rows back
    cli, python, _ = diagnosis_command(again)
    ns = build_parser().parse_args(shlex.split(cli)[1:])
    assert ns.register_rows == rows and ns.register_n is None and f"register_rows={rows!r}" in python


def test_calibration_update_on_given_rows_says_so(files):
    job = _run(files, register_rows=list(range(1, 13)), update="calibration")
    reg = job.summary()["test"]["registration"]
    assert reg["update"] == "calibration" and reg["registration_rows"] == list(range(1, 13))
    assert reg["method"].startswith("the rows given as registration rows") and "k-means" not in reg["method"]


def test_split_from_rows_numbers_rows_as_measurements_do():
    robot = tolalloc.load_robot("ur10")
    q = np.random.default_rng(0).uniform(-3.0, 3.0, (40, 6))
    sp = registration_split(q, robot.revolute_mask, 10, seed=0)
    for rows in (np.zeros(0, int), np.arange(2, 42), np.r_[1:5, 7:43]):  # no rows, header-like offset, a skipped row
        again = split_from_rows(sp.to_dict(rows)["registration_rows"], 40, rows)
        np.testing.assert_array_equal(again.register_index, sp.register_index)
        np.testing.assert_array_equal(again.score_index, sp.score_index)
    assert split_from_rows(range(1, 11), 40).to_dict()["registration_rows"] == list(range(1, 11))


@pytest.mark.parametrize("kw, match", [
    (dict(register_n=10, register_rows=range(1, 11)),
     r"register_rows and `register_n` are exclusive: expected either the rows .* got both \(`register_n` 10\)"),
    (dict(register_rows=[1, 2, 3, 4, 5, 5, 6, 6]), r"expected each registration row once, got row 5 2 times "
                                                   r"\(2 rows repeated: 5, 6\); remove the repeats"),
    (dict(register_rows=[*range(1, 8), 41, 99]),
     r"register_rows: row 41 is not among the test poses of .*test.csv \(2 of the rows given are not: 41, 99\): "
     r"its 40 poses are rows 1..40 \(rows with empty cells are skipped\); expected"),
    (dict(register_rows=[1, 2, 3]), r"the 3 rows given leave 37 of the 40 test poses to score; re-registering needs "
                                    r"at least 5 registration and 5 scored poses -- give more rows"),
    (dict(register_rows=range(1, 37)), r"the 36 rows given leave 4 of the 40 test poses to score; .* -- give fewer "
                                       r"rows or use a larger test file"),
    (dict(register_rows=[1, 2.5, 3]),
     r"expected data rows of the test file, numbered from 1 .*: whole numbers .* got 2.5 among the 3 rows given"),
    (dict(register_rows=[0, 1, 2, 3, 4]), r"numbered from 1 .*: whole numbers .* got 0 among the 5 rows given"),
    (dict(register_rows="1-10"), r"expected a list of data rows of the test file, .* got '1-10'"),
])
def test_refusals(files, kw, match):
    with pytest.raises(TolallocError, match=match):
        _run(files, **kw)


def test_the_old_keyword_without_a_refit_is_refused(files):
    """``register_rows``, the keyword before :class:`tolalloc.Refit` (deprecated), is refused with the test file in
    the same frame (only a Refit re-registers)."""
    with pytest.raises(TolallocError, match=r"register_rows needs `test_frame` refit"), \
            pytest.warns(DeprecationWarning, match=r"register_rows -> test_frame=tolalloc.Refit\(register_rows=...\)"):
        diagnose_measurements("tool_changer", files / "train.csv", files / "test.csv", folds=3, test_frame="same",
                              register_rows=range(1, 11))


def test_library_refusals_before_any_fit(files):
    robot = tolalloc.load_robot("tool_changer")
    m = Measurements(np.zeros((20, 6)), np.zeros((20, 3)))
    with pytest.raises(TolallocError, match=r"register_rows needs `test`: only a test file in another frame"):
        diagnose(robot, m, None, test_frame="refit", register_rows=range(1, 6))
    with pytest.raises(TolallocError, match=r"register_rows and `register_n` are exclusive"):
        diagnose(robot, m, m, test_frame="refit", register_n=30, register_rows=range(1, 6))
    with pytest.raises(TolallocError, match=r"row 21 is not among the test poses of <frame>: its 20 poses are rows 1..20"):
        diagnose(robot, m, m, test_frame="refit", register_rows=range(17, 22))
    skipped = Measurements(np.zeros((20, 6)), np.zeros((20, 3)), rows=np.r_[1:3, 4:22], source="s.csv")
    with pytest.raises(TolallocError, match=r"row 3 is not among the test poses of s.csv: its 20 poses are rows 1..21 without 3"):
        diagnose(robot, m, skipped, test_frame="refit", register_rows=range(1, 6))


def test_row_ranges_syntax():
    assert row_ranges("1-3,7, 9 - 10") == [1, 2, 3, 7, 9, 10]
    assert row_ranges_text([10, 9, 1, 2, 3, 7]) == "1-3,7,9-10"
    assert row_ranges(row_ranges_text([5, 1, 2, 40])) == [1, 2, 5, 40]
    for bad, extra in (("1-a", ""), ("", ""), ("1,,2", ""), ("1-2-3", ""), ("0-4", "; rows count from 1"),
                       ("9-5", r"; a range runs upwards \(5-9, not 9-5\)"),
                       ("1-99999999999", "; a range spans at most")):
        with pytest.raises(argparse.ArgumentTypeError, match="expected data rows of the test file from 1 as numbers "
                                                             "and inclusive ranges separated by commas, e.g. "
                                                             f"1-60,75,80-90, got '{bad}'{extra}"):
            row_ranges(bad)


def test_cli_register_rows(files, capsys, tmp_path):
    base = ["diagnose", "tool_changer", "--train", str(files / "train.csv"), "--test", str(files / "test.csv"),
            "--folds", "3", "--json", str(tmp_path / "o.json"), "--predictions", str(tmp_path / "p.csv")]
    for extra, said in ((["--test-frame", "refit", "--register-rows", "1-x"],
                         "argument --register-rows: expected data rows of the test file from 1 as numbers and "
                         "inclusive ranges separated by commas, e.g. 1-60,75,80-90, got '1-x'"),
                        (["--test-frame", "refit", "--register-rows", "1-10", "--register-n", "10"],
                         "error: --register-rows and --register-n are exclusive"),
                        (["--register-rows", "1-10"], "error: --register-rows needs --test-frame refit"),
                        (["--test-frame", "refit", "--register-rows", "5,1-10"], "got row 5 2 times"),
                        (["--test-frame", "refit", "--register-rows", "1-10,41"],
                         "error: --register-rows: row 41 is not among the test poses of")):
        assert main(base + extra) == 2
        err = capsys.readouterr().err
        assert said in err and len([s for s in err.strip().splitlines() if not PROGRESS_LINE.match(s)]) == 1
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "p.csv").exists()
    assert main(base + ["--test-frame", "refit", "--register-rows", "1-10,20"]) == 0
    capsys.readouterr()
    js = json.loads((tmp_path / "o.json").read_text())
    assert js["test"]["registration"]["registration_rows"] == [*range(1, 11), 20] and js["test"]["scored_poses"] == 29
    pred = pd.read_csv(tmp_path / "p.csv")
    assert pred.loc[pred["registration"] == 1, "row"].tolist() == [*range(1, 11), 20]
