"""The report's "command to reproduce" gives back the call that made the result.

The command line is parsed by the real parser and handed to the real `allocate` command, which is stopped where
it calls :func:`allocate_tolerances`; the Python call is run with a stand-in for it. Both must give the same settings
as the original call (its defaults filled in: :func:`allocation_settings`), every option that decides a number
included.
"""

from __future__ import annotations

import shlex
import warnings

import pytest

import tolalloc
import tolalloc.workflows
from tolalloc.cli import build_parser
from tolalloc.workflows import allocate_tolerances
from tolalloc.workflows.allocation_settings import allocation_settings
from tolalloc.workflows.reproduce import allocation_command
from tolalloc.workflows.keywords import fold_moved


class _Called(Exception):
    """Raised by the stand-in for allocate_tolerances: the command got as far as the call."""


def reproduced_arguments(job, monkeypatch, tmp_path) -> tuple[dict, dict]:
    """``(command line, Python call)`` of ``job``'s reproduce command, each as the arguments it passes to
    :func:`allocate_tolerances`."""
    cli, python, _ = allocation_command(job)
    argv = shlex.split(cli)
    assert argv[:2] == ["tolalloc", "allocate"] and argv[-2:] == ["--report", "DIR"]
    argv[-1] = str(tmp_path / "again")
    seen = {}

    def called(robot, **kwargs):
        seen.clear()
        seen.update(kwargs, robot=robot)
        raise _Called

    # the top-level name resolved first: tolalloc loads it lazily from tolalloc.workflows and keeps what it found, so
    # resolving it while that is patched would keep the stand-in after the test
    tolalloc.allocate_tolerances  # noqa: B018
    monkeypatch.setattr(tolalloc.workflows, "allocate_tolerances", called)
    args = build_parser().parse_args(argv[1:])
    with pytest.raises(_Called):
        args.func(args)
    cli_seen = dict(seen)
    monkeypatch.setattr(tolalloc, "allocate_tolerances", called, raising=False)
    with warnings.catch_warnings(), pytest.raises(_Called):
        warnings.simplefilter("error", DeprecationWarning)  # the report's call is written without old keywords
        exec(python, {})
    return cli_seen, dict(seen)


def effective(kwargs: dict, job) -> dict:
    """The settings of a call with every default filled in, in comparable form (:func:`allocation_settings`).
    ``scheduler`` never changes a number and is not reproduced; ``coverage_n`` is compared only where a box region
    made a coverage sample; the default sigma set and region are the ones the call resolved to."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        kw = fold_moved("allocate_tolerances", {k: v for k, v in kwargs.items()
                                                if k not in ("robot", "tool", "trust_units", "progress")})
    s = allocation_settings(**kw)
    out = {"requirements": [r.to_dict() for r in s.requirements], "costs": s.costs.to_dict(),
           "error_model": {**s.error_model.to_dict(), "sigma_set": s.error_model.sigma_set or job.problem.model.sigma_set},
           "solver": s.solver.to_dict(), "verification": s.verification.to_dict(),
           "correction": s.correction, "correction_rounds": s.correction_rounds,
           "calibration": None if s.calibration is None else str(s.calibration), "robot": kwargs["robot"]}
    region = s.region.to_dict()
    if region["where"] is None and region["poses"] is None:
        region["where" if job.region is not None else "poses"] = job.label
    if job.region is None:
        region.pop("coverage_n")
    out["region"] = region
    if out["requirements"][-1]["kind"] == "orientation" and out["requirements"][-1]["prob"] is None:
        out["requirements"][-1]["prob"] = out["requirements"][0]["prob"]
    return out


def assert_reproduced(job, original: dict, monkeypatch, tmp_path) -> None:
    cli, py = reproduced_arguments(job, monkeypatch, tmp_path)
    want = effective(original, job)
    assert effective(cli, job) == want
    assert effective(py, job) == want


def test_allocation_options_are_reproduced(monkeypatch, tmp_path):
    original = dict(robot="tool_changer", radius_mm=0.3, prob=0.9, region=tolalloc.Region(poses="nominal"),
                    costs=tolalloc.Costs(z=2.5), solver=tolalloc.Solver(method="certified", snap=False,
                                                                        angle_step_deg=0.001),
                    verification=tolalloc.Verification(n_mc=200, seed=5, estimator="plain", correction_rounds=1))
    job = allocate_tolerances(**original)
    assert job.inputs["correction_rounds"] == 1 and job.inputs["snap"] is False
    assert_reproduced(job, original, monkeypatch, tmp_path)


def test_allocation_without_verification_or_correction_is_reproduced(monkeypatch, tmp_path):
    original = dict(robot="tool_changer", region=tolalloc.Region(poses="nominal"),
                    verification=tolalloc.Verification(n_mc=None, correction=False, seed=2))
    assert_reproduced(allocate_tolerances(**original), original, monkeypatch, tmp_path)


def test_calibrated_options_are_reproduced(plan_path, monkeypatch, tmp_path):
    original = dict(robot="tool_changer", calibration=plan_path, region=tolalloc.Region(poses="nominal"),
                    solver=tolalloc.Solver(method="certified", snap=False),
                    verification=tolalloc.Verification(n_mc=200, seed=4, estimator="plain", correction=False))
    job = allocate_tolerances(**original)
    assert job.inputs["correction_rounds"] is None  # no correction loop after calibration
    assert_reproduced(job, original, monkeypatch, tmp_path)
