"""Progress on stderr when a person is watching: a terminal or a Jupyter kernel; never on stdout."""

import sys

import pytest

import tolalloc
from tolalloc.progress import show_progress


def test_show_progress_follows_the_flag_then_the_terminal_or_notebook(monkeypatch):
    assert show_progress(True) is True and show_progress(False) is False
    monkeypatch.setattr(sys.stderr, "isatty", lambda: False, raising=False)
    monkeypatch.delitem(sys.modules, "ipykernel", raising=False)
    assert show_progress(None) is False
    monkeypatch.setitem(sys.modules, "ipykernel", object())  # running in a Jupyter kernel
    assert show_progress(None) is True


def test_allocation_names_its_stages_on_stderr(capsys):
    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=500, progress=True)
    out, err = capsys.readouterr()
    assert out == "" and res.ok
    for stage in ("allocate tool_changer: exact design and standard grades",
                  "allocate tool_changer: Monte Carlo verification (500 samples per pose)"):
        assert stage in err
    tolalloc.allocate_tolerances("tool_changer", region="nominal", verify=False, progress=False)
    assert capsys.readouterr().err == ""


def test_progress_must_be_a_flag():
    with pytest.raises(tolalloc.TolallocError, match="progress"):
        tolalloc.allocate_tolerances("tool_changer", region="nominal", progress="yes")
