"""Progress on stderr, never on stdout: bars on a terminal, widgets in a notebook, one line per finished stage with its
duration in a pipe or a log (one module for every job: tolalloc.progress)."""

import io
import re
import sys

import pytest

import tolalloc
from tolalloc.progress import (NoBar, StageBar, count_fit, fit_counter, new_bar, progress_bar, progress_mode,
                               progress_scope, show_progress)

STAGE_LINE = r"^{job}: (.+): \d+\.\d+ s$"


class _Stream(io.StringIO):
    """A stand-in for stderr: a terminal or not, as asked."""

    def __init__(self, tty: bool):
        super().__init__()
        self._tty = tty

    def isatty(self):
        return self._tty


def _log(monkeypatch) -> _Stream:
    """stderr as a pipe or a CI log (not a terminal), outside a notebook (set in the test itself: pytest puts its
    own capture back between a fixture and the test)."""
    stream = _Stream(tty=False)
    monkeypatch.setattr(sys, "stderr", stream)
    monkeypatch.delitem(sys.modules, "ipykernel", raising=False)
    return stream


def test_the_mode_follows_the_flag_then_the_stream(monkeypatch):
    monkeypatch.delitem(sys.modules, "ipykernel", raising=False)
    assert show_progress(True) is True and show_progress(None) is True and show_progress(False) is False
    assert progress_mode(False, _Stream(tty=True)) is None
    assert progress_mode(None, _Stream(tty=True)) == "bars" and progress_mode(True, _Stream(tty=True)) == "bars"
    assert progress_mode(None, _Stream(tty=False)) == "lines"  # a pipe, a CI log: on, as lines
    assert progress_mode(None, object()) == "lines"  # a stream without isatty
    monkeypatch.setitem(sys.modules, "ipykernel", object())  # a Jupyter kernel ...
    monkeypatch.setitem(sys.modules, "ipywidgets", None)  # ... without ipywidgets: lines, not a widget error
    assert progress_mode(None, _Stream(tty=False)) == "lines"
    monkeypatch.setitem(sys.modules, "ipywidgets", object())
    assert progress_mode(None, _Stream(tty=False)) == "notebook"


def test_a_notebook_gets_tqdm_auto_bars(monkeypatch):
    import tqdm.auto

    monkeypatch.setattr(sys, "stderr", _Stream(tty=False))
    bar = new_bar("x", 3, mode="notebook")
    try:
        assert isinstance(bar, tqdm.auto.tqdm)
    finally:
        bar.close()


def test_in_a_log_each_stage_is_one_line_with_its_duration(monkeypatch):
    log = _log(monkeypatch)
    with StageBar(True, "job") as bar:
        bar.stage("first")
        bar.stage("second")
    with pytest.raises(RuntimeError), StageBar(True, "job") as bar:
        bar.stage("third")
        raise RuntimeError("cut short")  # a stage that did not finish writes no line
    assert re.findall(STAGE_LINE.format(job="job"), log.getvalue(), re.M) == ["first", "second"]
    assert "\r" not in log.getvalue() and log.getvalue().count("\n") == 2
    with StageBar(False, "job") as bar:
        bar.stage("silent")
    assert log.getvalue().count("\n") == 2


def test_in_a_log_a_counting_bar_is_one_line_when_done(monkeypatch):
    log = _log(monkeypatch)
    with progress_scope(None):
        with fit_counter("cross-validation (500 rows)"):
            for _ in range(3):
                count_fit()
        bar = progress_bar("final fit", unit="pass", detail=True)  # inside a stage that writes its own line
        bar.update()
        bar.close()
        with pytest.raises(KeyError), fit_counter("selection"):
            raise KeyError("cut short")
    with progress_scope(False):
        assert isinstance(progress_bar("off"), NoBar)
    lines = log.getvalue().splitlines()
    assert len(lines) == 1 and re.fullmatch(r"cross-validation \(500 rows\): 3 fits, \d+\.\d+ s", lines[0]), lines


def test_on_a_terminal_the_bars_are_tqdm_and_cleared(monkeypatch):
    from tqdm import tqdm

    term = _Stream(tty=True)
    monkeypatch.setattr(sys, "stderr", term)
    with StageBar(True, "job") as bar:
        bar.stage("first")
        assert isinstance(bar._bar, tqdm)
    assert "job: first" in term.getvalue() and "\r" in term.getvalue()  # redrawn in place, no line per stage
    assert not re.search(STAGE_LINE.format(job="job"), term.getvalue(), re.M)


def test_the_allocation_names_its_stages_by_default_when_stderr_is_a_log(capsys):
    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=500)
    out, err = capsys.readouterr()  # pytest's capture: not a terminal
    assert out == "" and res.ok
    stages = re.findall(STAGE_LINE.format(job="allocate tool_changer"), err, re.M)
    assert stages[:2] == ["exact design and standard grades", "Monte Carlo verification (500 samples per pose)"]
    assert len(stages) == err.count("\n") and "\r" not in err  # nothing else: no bar
    tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False, progress=False)
    assert capsys.readouterr().err == ""


def test_a_monte_carlo_run_is_one_line_in_a_log(monkeypatch):
    log = _log(monkeypatch)
    from tolalloc.errormodel import build_error_model
    from tolalloc.montecarlo.run import run_mc

    model = build_error_model(tolalloc.load_robot("tool_changer"))
    run_mc(model, model.robot.q_nominal, 2000, seed=0, progress=True)
    run_mc(model, model.robot.q_nominal, 2000, seed=0)  # a short run: nothing by default
    assert re.fullmatch(r"Monte Carlo: 2,000 samples, \d+\.\d+ s\n", log.getvalue())


def test_progress_must_be_a_flag():
    with pytest.raises(tolalloc.TolallocError, match="progress"):
        tolalloc.allocate_tolerances("tool_changer", region="nominal", progress="yes")
    with pytest.raises(tolalloc.TolallocError, match=r"^progress: expected True or False, got 'yes'"):
        tolalloc.plan_calibration("tool_changer", 8, n_candidates=64, progress="yes")
