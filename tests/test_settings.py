"""The settings objects: checked when built, errors naming the field; combinations no job can honour refused by
name; the short keyword forms; the old keywords folded in with a DeprecationWarning; the command line and Python
reading their defaults from one place (tolalloc.workflows.defaults)."""

from __future__ import annotations

import inspect
import re
import warnings
from pathlib import Path

import pytest

import tolalloc
from tolalloc.cli import build_parser, main
from tolalloc.workflows import defaults as D
from tolalloc.workflows.allocation_settings import allocation_settings

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("build, match", [
    (lambda: tolalloc.Verification(n_mc=0), r"^Verification.n_mc: expected at least 100 samples per pose \(a whole "
                                            r"number, e.g. 1000000\), got 0; or switch the verification off"),
    (lambda: tolalloc.Verification(n_mc=1.5), r"^Verification.n_mc: expected at least 100 samples per pose"),
    (lambda: tolalloc.Verification(estimator="magic"), r"^Verification.estimator: expected one of 'auto', 'plain', "
                                                       r"'paired', 'importance', got 'magic'\.$"),
    (lambda: tolalloc.Verification(correction=False, correction_rounds=3),
     r"^Verification.correction_rounds 3 rounds of a correction loop that is off \(`correction` False\); leave out "
     r"one of them\.$"),
    (lambda: tolalloc.Verification(n_mc=None, correction=True),
     r"^Verification.correction: True needs the Monte Carlo verification the loop re-runs, but `n_mc` is None"),
    (lambda: tolalloc.Verification(correction_rounds=51), r"^Verification.correction_rounds: expected a whole number "
                                                          r"from 0 to 50"),
    (lambda: tolalloc.PositionRequirement(radius_mm=0), r"^PositionRequirement.radius_mm: expected a finite number > "
                                                        r"0 \[mm\]"),
    (lambda: tolalloc.PositionRequirement(prob=1.0), r"^PositionRequirement.prob: expected a probability strictly "
                                                     r"between 0 and 1"),
    (lambda: tolalloc.OrientationRequirement(radius_deg=-1), r"^OrientationRequirement.radius_deg: expected a finite "
                                                             r"number > 0 \[deg\]"),
    (lambda: tolalloc.ErrorModelOptions(link_mode="straight"), r"^ErrorModelOptions.link_mode: expected one of "
                                                               r"'consistent', 'axes_only'"),
    (lambda: tolalloc.ErrorModelOptions(clearance_tilt_literal=True), r"^ErrorModelOptions.clearance_tilt_literal: "
                                                                      r"changes the clearance tilt sigma, but "
                                                                      r"clearance is off"),
    (lambda: tolalloc.Costs(z=3, uniform=True), r"^Costs.uniform and `z` both set sigma = t / z; give one of them\.$"),
    (lambda: tolalloc.Costs(file="no/such/costs.toml").file.is_file() or tolalloc.Costs(z=0),
     r"^Costs.z: expected a number > 0"),
    (lambda: tolalloc.Region("working", poses="working"), r"^Region.where: 'working' and `poses` 'working' both say "
                                                           r"where the requirement holds"),
    (lambda: tolalloc.Region(coverage_n=0), r"^Region.coverage_n: expected a whole number >= 1"),
    (lambda: tolalloc.Solver(method="fast"), r"^Solver.method: expected one of 'exact', 'certified'"),
    (lambda: tolalloc.MonteCarlo(hist_bins=1), r"^MonteCarlo.hist_bins: expected 0 \(no histogram\) or a whole number "
                                               r"of bins from 2 to 2000"),
    (lambda: tolalloc.MonteCarlo(hist_range_mm=1.0), r"^MonteCarlo.hist_range_mm 1 sets the histogram window, but no "
                                                     r"histogram is made"),
    (lambda: tolalloc.Measurement(noise_deg=0.01), r"^Measurement.noise_deg 0.01 is the orientation noise of pose "
                                                   r"measurements, but `kind` is position"),
    (lambda: tolalloc.Refit(register_n=3), r"^Refit.register_n: expected a count of registration poses \(a whole "
                                           r"number >= 5"),
    (lambda: tolalloc.Refit(register_n=30, register_rows=[1, 2, 3]), r"^Refit.register_rows and `register_n` are "
                                                                      r"exclusive"),
    (lambda: tolalloc.FitOptions(target_offset_mm=[0, 0, 10]), r"^FitOptions.target_offset_mm: a prior mean needs its "
                                                                r"standard deviation"),
    (lambda: tolalloc.FitOptions(target_offset_mm=(1, 2), target_offset_sd_mm=5),
     r"^FitOptions.target_offset_mm: expected three finite numbers \(x, y, z in the flange frame"),
])
def test_a_bad_setting_is_refused_when_built_naming_the_field(build, match):
    with pytest.raises(tolalloc.ArgumentError, match=match) as info:
        build()
    assert "\n" not in str(info.value) and "." in info.value.argument


@pytest.mark.parametrize("kwargs, match", [
    (dict(requirement=[tolalloc.PositionRequirement(), tolalloc.PositionRequirement(0.1)]),
     r"^requirement: expected at most one requirement of each kind, got 2 position requirements"),
    (dict(requirement=tolalloc.OrientationRequirement(radius_deg=0.1)),
     r"^requirement needs a position requirement \(the allocation is built on the tool's position error\), got only "
     r"P\(\|dw\| < 0.1 deg\)"),
    (dict(requirement="P < 0.25"), r"^requirement: expected a requirement or a list of them"),
    (dict(requirement=tolalloc.PositionRequirement(), radius_mm=0.3),
     r"^radius_mm 0.3 and `requirement` both state the position requirement"),
    (dict(n_mc=2000, verification=tolalloc.Verification()),
     r"^n_mc 2000 and `verification` both set the Monte Carlo samples; give one of them"),
    (dict(n_mc=10), r"^n_mc: expected at least 100 samples per pose"),           # the short form names itself
    (dict(radius_mm=-1), r"^radius_mm: expected a finite number > 0 \[mm\]"),
    (dict(costs=tolalloc.Costs(), solver="fast"), r"^solver: expected one of 'exact', 'certified'"),
    (dict(error_model=tolalloc.ErrorModelOptions(sigma={"dl1": 0.1})),
     r"^ErrorModelOptions.sigma: is not read by an allocation \(it chooses the sigmas"),
    (dict(error_model={"clearance": True}), r"^error_model: expected a tolalloc.ErrorModelOptions\(...\), got dict"),
])
def test_combinations_an_allocation_cannot_honour_are_refused_before_any_work(kwargs, match):
    with pytest.raises(tolalloc.ArgumentError, match=match):
        allocation_settings(**kwargs)


@pytest.mark.parametrize("verification, match", [
    (tolalloc.Verification(estimator="importance"),
     r"^Verification.estimator: expected one of 'auto', 'plain', 'paired' with `calibration` \(the end-to-end Monte "
     r"Carlo of the calibration-aware allocation has no importance sampler\), got 'importance'"),
    (tolalloc.Verification(correction=True), r"^Verification.correction: expected False or nothing with `calibration`"),
])
def test_an_estimator_or_loop_the_calibrated_path_cannot_use_is_refused(verification, match):
    with pytest.raises(tolalloc.ArgumentError, match=match):
        allocation_settings(calibration="plan.csv", verification=verification)
    with pytest.raises(tolalloc.ArgumentError, match=r"^requirement: P\(\|dw\| < 0.1 deg\) >= 0.9 is not handled by "
                                                     r"the calibration-aware allocation"):
        allocation_settings(calibration="plan.csv", requirement=[tolalloc.PositionRequirement(),
                                                                 tolalloc.OrientationRequirement(0.1, 0.9)])


def test_settings_are_frozen_reusable_and_normalised():
    v = tolalloc.Verification(n_mc=1e6, seed=3)
    assert v.n_mc == 1_000_000 and isinstance(v.n_mc, int) and v == tolalloc.Verification(n_mc=10**6, seed=3)
    with pytest.raises(AttributeError):
        v.seed = 4
    assert v.replace(seed=4).seed == 4 and v.seed == 3
    with pytest.raises(tolalloc.ArgumentError, match=r"^Verification.seed: expected a whole number >= 0"):
        v.replace(seed=-1)
    assert tolalloc.ErrorModelOptions(exclude="e1x").exclude == ("e1x",)
    assert v.to_dict() == {"n_mc": 1_000_000, "seed": 3, "estimator": "auto", "correction": None,
                           "correction_rounds": None}  # the scheduler never changes a number
    req = tolalloc.PositionRequirement(radius_mm=0.1, prob=0.99)
    assert req.text() == "P(|dP| < 0.1 mm) >= 0.99" and req.to_dict() == {"kind": "position", "radius_mm": 0.1,
                                                                         "prob": 0.99}
    assert req.problem_arguments() == {"radius_mm": 0.1, "prob": 0.99} and req.cli_arguments()[:2] == ["--radius-mm",
                                                                                                      "0.1"]
    orient = tolalloc.OrientationRequirement(radius_deg=0.05)
    assert isinstance(orient, tolalloc.Requirement) and orient.problem_arguments() == {"angle_radius_deg": 0.05,
                                                                                       "angle_prob": None}
    assert "importance" in req.estimators() and "importance" not in req.estimators(calibrated=True)


def test_an_allocation_takes_the_objects_and_their_short_forms_alike():
    """The same settings as objects, as short keywords or as the old keywords give the same allocation (linear, no
    standard grades, no Monte Carlo: a fraction of a second)."""
    region, check = tolalloc.Region(poses="nominal"), tolalloc.Verification(n_mc=None, seed=2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")   # the short forms are current, not deprecated
        short = allocation_settings(radius_mm=0.3, prob=0.9, region="limits", solver="certified", n_mc=2000)
    objects = allocation_settings(tolalloc.PositionRequirement(0.3, 0.9), region=tolalloc.Region("limits"),
                                  solver=tolalloc.Solver(method="certified"), verification=tolalloc.Verification(2000))
    assert short.requirements == objects.requirements and short.solver == objects.solver
    assert short.verification == objects.verification and short.region.to_dict() == objects.region.to_dict()
    solver = tolalloc.Solver(method="certified", snap=False)
    by_objects = tolalloc.allocate_tolerances("tool_changer", tolalloc.PositionRequirement(0.3, 0.9), region=region,
                                              verification=check, solver=solver)
    assert by_objects.inputs["requirements"] == [{"kind": "position", "radius_mm": 0.3, "prob": 0.9}]
    with pytest.warns(DeprecationWarning, match=r"allocate_tolerances\(\): the keyword\(s\) poses, seed, verify, snap "
                                                r"are deprecated .*poses -> region=tolalloc.Region\(poses=...\); "
                                                r"verify=False -> verification=False; seed -> verification="
                                                r"tolalloc.Verification\(seed=...\)"):
        old = tolalloc.allocate_tolerances("tool_changer", radius_mm=0.3, prob=0.9, poses="nominal", seed=2,
                                           verify=False, solver="certified", snap=False)
    assert old.cost == by_objects.cost and old.inputs == by_objects.inputs


def test_old_keywords_are_refused_by_their_own_names():
    with pytest.warns(DeprecationWarning), pytest.raises(tolalloc.ArgumentError, match=r"^estimator: expected one"):
        tolalloc.allocate_tolerances("tool_changer", estimator="magic")
    with pytest.warns(DeprecationWarning, match=r"n -> n_mc"), \
            pytest.raises(tolalloc.ArgumentError, match=r"^n: expected a whole number >= 1"):
        tolalloc.simulate_errors("tool_changer", n=0)   # named as given
    with pytest.warns(DeprecationWarning), pytest.raises(tolalloc.ArgumentError,
                                                         match=r"^angle_prob 0.9 needs an orientation requirement"):
        tolalloc.allocate_tolerances("tool_changer", angle_prob=0.9)


def test_every_job_takes_at_most_about_twelve_keywords():
    for job in (tolalloc.allocate_tolerances, tolalloc.analyze_errors, tolalloc.simulate_errors,
                tolalloc.plan_calibration, tolalloc.diagnose_measurements, tolalloc.allocate_acceptance,
                tolalloc.review_drawing, tolalloc.fleet, tolalloc.compensate_program):
        params = inspect.signature(job).parameters
        keywords = [p for p in params if p not in ("robot", "train", "test", "tool", "trust_units")]
        assert len(keywords) <= 12, (job.__name__, keywords)


def _parsed(argv):
    args = build_parser().parse_args(argv)
    return args


def test_the_command_line_and_python_read_the_same_defaults():
    """The defaults live in tolalloc.workflows.defaults: the command's flags with nothing given build the settings
    the Python call takes with nothing given (the README's example and `tolalloc allocate` give the same design)."""
    from tolalloc.cli.allocate import settings

    cli = settings(_parsed(["allocate", "tool_changer"]))
    python = allocation_settings()
    assert cli["requirement"] == list(python.requirements) == [tolalloc.PositionRequirement(D.RADIUS_MM, D.PROB)]
    assert cli["verification"] == python.verification and python.verification.n_mc == D.N_MC == 10**6
    assert cli["solver"] == python.solver and cli["costs"] == python.costs
    assert cli["error_model"] == python.error_model and cli["region"].to_dict() == python.region.to_dict()
    mc = _parsed(["mc", "tool_changer"])
    sim = inspect.signature(tolalloc.simulate_errors).parameters
    assert (mc.n_mc, mc.seed, mc.ci, mc.chunk_size) == (tolalloc.MonteCarlo().n_mc, tolalloc.MonteCarlo().seed,
                                                        tolalloc.MonteCarlo().ci, tolalloc.MonteCarlo().chunk_size)
    assert tuple(sim["radius_mm"].default) == D.SIMULATION_RADII_MM and mc.radius_mm is None   # None: the default
    for command, job, names in (
            (["analyze", "tool_changer"], tolalloc.analyze_errors, ("top", "seed")),
            (["calplan", "tool_changer", "--n-poses", "3", "--out", "p.csv"], tolalloc.plan_calibration,
             ("n_candidates", "seed", "random_plans")),
            (["diagnose", "tool_changer", "--train", "t.csv"], tolalloc.diagnose_measurements, ("folds", "alpha",
                                                                                               "seed"))):
        args, params = _parsed(command), inspect.signature(job).parameters
        for name in names:
            assert getattr(args, name) == params[name].default, (command[0], name)
    meas = _parsed(["calplan", "tool_changer", "--n-poses", "3", "--out", "p.csv"])
    assert (meas.noise_mm, meas.noise_deg) == (tolalloc.Measurement().noise_mm, tolalloc.Measurement().noise_deg)
    assert _parsed(["diagnose", "tool_changer", "--train", "t.csv"]).robust_loss == tolalloc.FitOptions().robust_loss


def test_the_readme_example_uses_the_defaults_the_command_uses():
    """The README's Python example states no sample count, seed or region size: it runs on the defaults of
    tolalloc.workflows.defaults, which `tolalloc allocate` reads too (the test above), so both give the same design
    (at 1e6 samples per pose a run takes half a minute: too long to repeat here)."""
    from test_workflows import PYTHON_EXAMPLE

    call = PYTHON_EXAMPLE.split("allocate_tolerances(", 1)[1].split("\n)", 1)[0]
    given = set(re.findall(r"^\s*(\w+)=", call, flags=re.M))
    assert given == {"radius_mm", "prob", "region"}
    assert "n_mc" not in PYTHON_EXAMPLE and "verification" not in PYTHON_EXAMPLE


def test_argument_errors_of_settings_read_as_flags(capsys):
    assert main(["allocate", "tool_changer", "--n-mc", "50"]) == 2
    assert capsys.readouterr().err.startswith("error: --n-mc: expected at least 100 samples per pose")
    assert main(["allocate", "tool_changer", "--z", "3", "--uniform", "--no-verify"]) == 2
    assert capsys.readouterr().err.startswith("error: --uniform and --z both set sigma = t / z")
    assert main(["mc", "tool_changer", "--n-mc", "100", "--hist-range-mm", "2"]) == 2
    assert capsys.readouterr().err.startswith("error: --hist-range-mm 2 sets the histogram window")
