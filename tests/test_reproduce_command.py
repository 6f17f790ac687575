"""The report's "command to reproduce" gives back the call that made the result.

The command line is parsed by the real parser and handed to the real `allocate` command, which is stopped where
it calls :func:`allocate_tolerances`; the Python call is parsed with :mod:`ast`. Both must give the same arguments
as the original call (its defaults filled in), every option that decides a number included.
"""

from __future__ import annotations

import ast
import inspect
import shlex

import pytest

import tolalloc
import tolalloc.workflows
from tolalloc.cli import build_parser
from tolalloc.workflows import allocate_tolerances
from tolalloc.report.html_command import allocation_command

PARAMS = inspect.signature(allocate_tolerances).parameters


class _Called(Exception):
    """Raised by the stand-in for allocate_tolerances: the command got as far as the call."""


def reproduced_arguments(job, monkeypatch, tmp_path) -> tuple[dict, dict]:
    """``(command line, Python call)`` of ``job``'s reproduce command, each as the keyword arguments (and
    ``robot``) it passes to :func:`allocate_tolerances`."""
    cli, python, _ = allocation_command(job)
    argv = shlex.split(cli)
    assert argv[:2] == ["tolalloc", "allocate"] and argv[-2:] == ["--report", "DIR"]
    argv[-1] = str(tmp_path / "again")
    seen = {}

    def called(robot, **kwargs):
        seen.update(kwargs, robot=robot)
        raise _Called

    monkeypatch.setattr(tolalloc.workflows, "allocate_tolerances", called)
    args = build_parser().parse_args(argv[1:])
    with pytest.raises(_Called):
        args.func(args)
    call = next(n for n in ast.walk(ast.parse(python)) if isinstance(n, ast.Call)
                and getattr(n.func, "attr", "") == "allocate_tolerances")
    py = {k.arg: ast.literal_eval(k.value) for k in call.keywords}
    py["robot"] = ast.literal_eval(call.args[0])
    return seen, py


def effective(kwargs: dict, job) -> dict:
    """The arguments of a call with every default filled in, in comparable form. ``scheduler`` never changes a
    number and is not reproduced; ``coverage_n`` is compared only where a box region made a coverage sample; the
    default sigma set and region are the ones the call resolved to."""
    out = {k: p.default for k, p in PARAMS.items() if p.default is not inspect.Parameter.empty}
    out.update(kwargs)
    out.pop("scheduler")
    out["exclude"] = tuple(out["exclude"] or ())
    out["sigma_set"] = out["sigma_set"] or job.problem.model.sigma_set
    if out["region"] is None and out["poses"] is None:
        out["region"] = job.label
    if out["calibration"] is not None:
        out["calibration"] = str(out["calibration"])
    if job.region is None:
        out.pop("coverage_n")
    return out


def assert_reproduced(job, original: dict, monkeypatch, tmp_path) -> None:
    cli, py = reproduced_arguments(job, monkeypatch, tmp_path)
    want = effective(original, job)
    assert effective(cli, job) == want
    assert effective(py, job) == want


def test_allocation_options_are_reproduced(monkeypatch, tmp_path):
    original = dict(robot="tool_changer", poses="nominal", radius_mm=0.3, prob=0.9, z=2.5, solver="certified",
                    snap=False, angle_step_deg=0.001, n_mc=200, seed=5, estimator="plain", correction_rounds=1)
    job = allocate_tolerances(**original)
    assert job.inputs["correction_rounds"] == 1 and job.inputs["snap"] is False
    assert_reproduced(job, original, monkeypatch, tmp_path)


def test_allocation_without_verification_or_correction_is_reproduced(monkeypatch, tmp_path):
    original = dict(robot="tool_changer", poses="nominal", verify=False, correction=False, seed=2)
    assert_reproduced(allocate_tolerances(**original), original, monkeypatch, tmp_path)


def test_calibrated_options_are_reproduced(plan_path, monkeypatch, tmp_path):
    original = dict(robot="tool_changer", calibration=plan_path, poses="nominal", solver="certified", snap=False,
                    n_mc=200, seed=4, estimator="plain", correction=False)
    job = allocate_tolerances(**original)
    assert job.inputs["correction_rounds"] is None  # no correction loop after calibration
    assert_reproduced(job, original, monkeypatch, tmp_path)
