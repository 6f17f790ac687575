"""Every result class answers the result protocol (docs/api/results.md) the same way: ``save(directory, *,
report=False, json=None) -> list[Path]``, ``to_frame()``, ``summary()``, ``text()``, ``plot_*(ax=None)`` returning the
axes, a compact ``_repr_html_`` card, paths as ``str`` or ``os.PathLike``.

One small result of each job is made once (module scope); one parametrized test runs the same checks over all six.
"""

from __future__ import annotations

import inspect
import json
import re
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import tolalloc  # noqa: E402
from tolalloc.outputs import MANIFEST  # noqa: E402

CLASSES = ["ToleranceAllocation", "CalibratedToleranceAllocation", "ErrorAnalysis", "ErrorSimulation",
           "CalibrationPlanDesign", "MeasurementDiagnosis", "AcceptanceAllocation", "DrawingReview",
           "PartsToleranceAllocation"]


@pytest.fixture(scope="module")
def results(plan_path, tmp_path_factory):
    """One result of each class, small."""
    from tolalloc.diagnose import generate
    from tolalloc.diagnose.synth import split_frame

    case = generate(tolalloc.load_robot("tool_changer"), "backlash", 60, np.random.default_rng(5))
    train, test = split_frame(case.frame, 0.25, np.random.default_rng(0))
    out = {
        "ToleranceAllocation": tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=500,
                                                            solver=tolalloc.Solver(snap=False)),
        "CalibratedToleranceAllocation": tolalloc.allocate_tolerances(
            "tool_changer", calibration=plan_path, region=tolalloc.Region(poses="nominal"),
            solver=tolalloc.Solver(method="certified", snap=False), n_mc=200),
        "ErrorAnalysis": tolalloc.analyze_errors("tool_changer", radius_mm=25.0),
        "ErrorSimulation": tolalloc.simulate_errors("tool_changer", 500, seed=1),
        "CalibrationPlanDesign": tolalloc.plan_calibration("tool_changer", 6, n_candidates=24),
        "MeasurementDiagnosis": tolalloc.diagnose_measurements("tool_changer", train, test, folds=2),
    }
    out["AcceptanceAllocation"] = _acceptance()
    drawing = tmp_path_factory.mktemp("drawing")
    out["ToleranceAllocation"].save(drawing)
    out["DrawingReview"] = tolalloc.review_drawing("tool_changer", drawing / "drawing.csv", region="nominal")
    out["PartsToleranceAllocation"] = _parts(tmp_path_factory.mktemp("arm"))
    assert sorted(out) == sorted(CLASSES) and all(type(v).__name__ == k for k, v in out.items())
    return out


def _parts(folder):
    """The small arm of the bought-parts tests with its catalogue slots, over its box, 0-1 kg and 15-30 degC; the
    angles machined to five listed classes (a small program: the default continuous costs take 20x longer to solve
    and exercise nothing more of the result protocol)."""
    from parts_robot import arm, write_classes

    return tolalloc.allocate_tolerances(arm(folder), radius_mm=0.5, region="work", n_mc=500,
                                        costs=write_classes(folder / "classes.toml"),
                                        parts={"payload_kg": (0.0, 1.0), "ambient_c": (15.0, 30.0),
                                               "after": "compensation"})


def _acceptance():
    """A small ISO 9283 allocation: the UR10's drives only, its test laid out once, 100 simulated robots."""
    from iso_setup import ur10_test
    from tolalloc.acceptance import PoseAccuracy, PoseRepeatability
    from tolalloc.errormodel import build_error_model

    robot, test = ur10_test()
    others = tuple(p.name for p in build_error_model(robot).params if p.kind != "joint_drive")
    return tolalloc.allocate_acceptance(robot, [PoseAccuracy(limit_mm=0.05), PoseRepeatability(limit_mm=0.05)],
                                        error_model=tolalloc.ErrorModelOptions(exclude=others), test=test,
                                        solver=tolalloc.Solver(snap=False), n_robots=100)


def _files(folder: Path) -> set[Path]:
    return {p for p in folder.rglob("*") if p.is_file() and p.name != MANIFEST and ".lock" not in p.name}


@pytest.mark.parametrize("name", CLASSES)
def test_every_result_follows_the_protocol(results, name, tmp_path, capsys, monkeypatch):
    res = results[name]
    assert name in tolalloc.__all__ and isinstance(res, getattr(tolalloc, name))
    # save: every file it reports, and nothing else, in the directory; a str path; the JSON beside it. report.html is
    # asked for where it is cheap (the calibrated allocation's); tests/test_report_html.py checks the others'.
    signature = inspect.signature(type(res).save).parameters
    assert list(signature)[1:4] == ["directory", "report", "json"] and signature["report"].default is False
    directory = tmp_path / "out"
    report = name == "CalibratedToleranceAllocation"
    paths = res.save(str(directory), report=report, json=tmp_path / "summary.json")
    assert all(isinstance(p, Path) for p in paths)
    assert set(paths) == _files(directory) | {tmp_path / "summary.json"}
    assert ((directory / "report.html") in paths) == report
    summary = res.summary()
    assert json.loads((tmp_path / "summary.json").read_text()) == json.loads(json.dumps(summary, default=str))
    # json="-": standard output, as on the command line; no file named "-"
    monkeypatch.chdir(tmp_path)
    capsys.readouterr()
    assert res.save(json="-") == []
    assert json.loads(capsys.readouterr().out) == json.loads((tmp_path / "summary.json").read_text())
    assert not (tmp_path / "-").exists()
    # refusals: nothing to write; a report where there is none
    with pytest.raises(tolalloc.ArgumentError, match=r"^directory: nothing to save: expected a directory"):
        res.save()
    if not res.has_report:
        with pytest.raises(tolalloc.ArgumentError, match=rf"^report: {name} has no HTML report"):
            res.save(tmp_path / "other", report=True)
    assert not (tmp_path / "other").exists()
    if name in ("ErrorAnalysis", "CalibrationPlanDesign"):  # write_files takes a str folder, writes what save did
        folder = tmp_path / "plain"
        folder.mkdir()
        assert sorted(res.write_files(str(folder))) == sorted(p.name for p in paths if p.parent == directory)
    # the tables and texts
    assert isinstance(res.to_frame(), pd.DataFrame) and len(res.to_frame())
    assert isinstance(summary, dict) and isinstance(res.text(), str) and res.text().strip()
    assert isinstance(res.ok, bool) and repr(res).startswith(f"<{name}\n")
    # the notebook card: the headline, a table, no NaN and no column empty in every row
    card = res._repr_html_()
    assert res.headline()[0].split()[0] in card and "<table" in card
    assert "NaN" not in card and ">nan<" not in card
    header = re.findall(r"<th>(.*?)</th>", card)
    rows = re.findall(r"<tr>(.*?)</tr>", card.split("<tbody>", 1)[1], flags=re.S)
    cells = [re.findall(r"<td>(.*?)</td>", r, flags=re.S) for r in rows]
    assert header and all(any(row[i].strip() for row in cells) for i in range(len(header))), header


@pytest.mark.parametrize("name", CLASSES)
def test_every_plot_takes_ax_and_returns_the_axes(results, name):
    res = results[name]
    methods = [m for m in dir(res) if m.startswith("plot_")]
    assert methods, f"{name} has no plot_* method"
    for method in methods:
        assert list(inspect.signature(getattr(res, method)).parameters)[0] == "ax", method
        drawn = getattr(res, method)()
        axes = list(np.ravel(np.asarray(drawn, dtype=object)))
        assert axes and all(isinstance(a, matplotlib.axes.Axes) for a in axes), (method, drawn)
        fig = axes[0].figure
        # into given axes: the same kind and number of panels, in one figure, drawn there and returned
        other = plt.figure()
        given = [other.add_subplot(1, len(axes), i + 1, projection=a.name if a.name != "rectilinear" else None)
                 for i, a in enumerate(axes)]
        again = getattr(res, method)(ax=given if len(given) > 1 else given[0])
        assert list(np.ravel(np.asarray(again, dtype=object))) == given, method
        assert all(a.has_data() or a.collections or a.patches for a in given), method
        plt.close("all")
        del fig


def test_old_save_forms_still_work_with_a_warning(results, tmp_path, monkeypatch):
    analysis, diagnosis, plan = (results[k] for k in ("ErrorAnalysis", "MeasurementDiagnosis",
                                                      "CalibrationPlanDesign"))
    with pytest.warns(DeprecationWarning, match=r"ErrorAnalysis.save\(out=...\) is deprecated: use save\(directory\)"):
        assert (tmp_path / "a" / "analyze.json") in analysis.save(out=tmp_path / "a")
    asked = []  # the diagnosis's former save(report=DIR): the folder, with report.html (not rendered here)
    monkeypatch.setattr(type(diagnosis), "write_files", lambda self, folder, *, report=False: asked.append(report) or [])
    with pytest.warns(DeprecationWarning, match=r"save\(report=DIR\) is deprecated: use save\(DIR, report=True\)"):
        diagnosis.save(report=tmp_path / "d")
    assert asked == [True] and (tmp_path / "d").is_dir()
    with pytest.warns(DeprecationWarning, match=r"save\(FILE.csv\) is deprecated"):
        assert plan.save(tmp_path / "plan.csv") == [tmp_path / "plan.csv"]
    assert plan.save_plan(str(tmp_path / "again.csv")) == [tmp_path / "again.csv"]
    assert (tmp_path / "again.csv").read_text() == (tmp_path / "plan.csv").read_text()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(DeprecationWarning, match=r"plot_budget\(axes=...\) is deprecated"):
            results["ToleranceAllocation"].plot_budget(axes=plt.subplots(1, 2)[1])
    plt.close("all")
