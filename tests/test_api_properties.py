"""Property tests of every name in ``tolalloc.__all__``: whatever a notebook passes, a call returns a valid result
(a verdict, finite numbers) or raises a :class:`tolalloc.TolallocError` naming the argument, what arrived and what
would work -- never an exception from numpy, pandas, SciPy, cvxpy or CasADi, never a NaN, never a partial file.

The jobs are called as their documentation tells users to: the settings objects (:class:`tolalloc.Region`,
:class:`tolalloc.Verification`, :class:`tolalloc.MonteCarlo` ...) and the short keywords that remain (``radius_mm``,
``region="nominal"``, ``verification=False`` ...), never the deprecated flat keywords (a ``DeprecationWarning`` fails
the call, :func:`property_strategies.outcome`; :func:`test_the_deprecated_keywords_still_work_and_warn` keeps them).

Each job has two tests: ``*_refuses_or_runs`` perturbs one or two keywords or fields of a settings object with values
from the odd pools (:mod:`property_strategies`) around otherwise valid, cheap arguments (:func:`perturbed`); a wrong
field is refused when its object is built or when the job runs, naming ``ClassName.field`` (or the keyword of its
short form); ``*_valid_runs_are_finite`` draws only valid arguments (generated robots, poses, requirements) and checks
the result. Examples per test: see :func:`property_strategies.examples` (``TOLALLOC_HYPOTHESIS_PROFILE=long`` for the
long run).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import tolalloc
from property_strategies import (REFUSED, Draft, build, call_job, check_refusal, check_result,
                                 costs_texts, count, counts, examples, generated_robots, interface_poses, joint_values,
                                 measurement_frame, measurement_frames, numbers_near_bounds, odd_values, outcome)
from tolalloc import (Costs, ErrorModelOptions, FitOptions, Measurement, MonteCarlo, OrientationRequirement,
                      PositionRequirement, Refit, Region, Solver, Verification)

#: argument left at its default
OMIT = object()
TC = tolalloc.load_robot("tool_changer")
UR10 = tolalloc.load_robot("ur10")
SCRATCH = Path(tempfile.mkdtemp(prefix="tolalloc_props_"))
_RESULTS: dict = {}


def two_link():
    return tolalloc.Robot.from_dh([{"name": "j1", "d_mm": 400, "a_mm": 0, "alpha_deg": 90,
                                    "lower_deg_mm": -170, "upper_deg_mm": 170},
                                   {"name": "j2", "d_mm": 0, "a_mm": 600, "alpha_deg": 0,
                                    "lower_deg_mm": -120, "upper_deg_mm": 120}], convention="standard", name="two_link")


def earlier_results() -> dict:
    """Results of earlier calls (and their parts), which notebooks pass on as inputs."""
    if not _RESULTS:
        from tolalloc.diagnose import generate

        arm = two_link()
        a = tolalloc.analyze_errors(TC, radius_mm=0.25)
        al = tolalloc.allocate_tolerances(arm, region="nominal", verification=False)
        plan = tolalloc.plan_calibration(arm, 4, n_candidates=8)
        plan.save_plan(SCRATCH / "plan.csv")
        case = generate(arm, "none", 30, np.random.default_rng(2))
        _RESULTS.update(analysis=a, allocation=al, frame=al.to_frame(), summary=a.summary(),
                        linear=a.linear, budget=a.budget_frame(), plan=plan,
                        simulation=tolalloc.simulate_errors(arm, 100),
                        calibrated=tolalloc.allocate_tolerances(arm, region="nominal", calibration=SCRATCH / "plan.csv",
                                                                n_mc=200),
                        diagnosis=tolalloc.diagnose_measurements(arm, case.frame.iloc[:22], case.frame.iloc[22:],
                                                                 folds=2))
    return _RESULTS


def results():
    return st.sampled_from(["analysis", "allocation", "frame", "summary", "linear", "budget", "plan", "simulation",
                            "calibrated", "diagnosis"]).map(
        lambda k: earlier_results()[k])


def bad(*extra):
    """Odd values, earlier results and the given strategies."""
    return st.one_of(odd_values(), results(), *extra)


class Obj:
    """A settings object in a job's valid arguments: its class, a strategy per field (valid values; ``st.just(OMIT)``:
    left at its default) and the wrong values of some fields (the others: :func:`bad`). Each field is a place
    :func:`perturbed` may put a wrong value."""

    def __init__(self, cls, valid: dict, wrong: dict | None = None):
        self.cls, self.valid, self.wrong = cls, valid, wrong or {}

    def __repr__(self) -> str:
        return f"Obj({self.cls.__name__})"


def _objects(shape) -> list:
    """The :class:`Obj` of a drawn valid value: itself, the ones of a list (requirements), or none."""
    if isinstance(shape, Obj):
        return [shape]
    return [o for o in shape if isinstance(o, Obj)] if isinstance(shape, list) else []


@st.composite
def perturbed(draw, valid, wrong: dict, n_bad=(1, 1, 1, 2)):
    """Keyword arguments of a job: valid ones (``valid``: a dict of strategies, or a list of such dicts -- the forms
    of a call, e.g. short keywords or their objects), with one or two places given a wrong value: a keyword (from its
    ``wrong`` strategy, else :func:`bad`) or a field of a settings object drawn for the call (from the
    :class:`Obj`'s). Settings objects come as :class:`~property_strategies.Draft` (built by
    :func:`~property_strategies.call_job`, so a refusal at construction is checked too)."""
    forms = valid if isinstance(valid, list) else [valid]
    form = forms[draw(st.integers(0, len(forms) - 1))]
    shapes = {name: draw(strategy) for name, strategy in form.items()}  # a value, OMIT, an Obj or a list of Obj
    places = [(name,) for name in shapes] + [(name, i, f) for name, shape in shapes.items()
                                             for i, o in enumerate(_objects(shape)) for f in o.valid]
    k = min(draw(st.sampled_from(n_bad)), len(places))
    chosen = {places[i] for i in draw(st.lists(st.integers(0, len(places) - 1), min_size=k, max_size=k, unique=True))}

    def drafted(name, i, o):
        fields = {f: draw(o.wrong.get(f, bad()) if (name, i, f) in chosen else s) for f, s in o.valid.items()}
        return Draft(o.cls, **{f: v for f, v in fields.items() if v is not OMIT})

    kwargs = {}
    for name, shape in shapes.items():
        if (name,) in chosen:
            value = draw(wrong.get(name, bad()))
        elif isinstance(shape, Obj):
            value = drafted(name, 0, shape)
        elif isinstance(shape, list) and _objects(shape):
            value = [drafted(name, i, o) for i, o in enumerate(shape)]
        else:
            value = shape
        if value is not OMIT:
            kwargs[name] = value
    return kwargs


def omit_or(*strategies):
    return st.one_of(st.just(OMIT), *strategies)


def costs_file(text: str) -> Path:
    path = SCRATCH / f"costs_{abs(hash(text))}.toml"
    path.write_text(text)
    return path


def other_objects(*classes):
    """Settings objects of other classes (where one class is expected)."""
    return st.sampled_from(classes).map(lambda cls: cls())


SETTINGS = dict(deadline=None)
ALL_CLASSES = (Costs, ErrorModelOptions, MonteCarlo, Measurement, Region, Solver, Verification, Refit, FitOptions,
               PositionRequirement)

# ------------------------------------------------------------------------------------------------ settings objects
EXCLUDE_WRONG = ["dl1", ("dl1", "nope"), ["link_length"], ("axis_deflection", "link_length", "joint_drive",
                                                            "clearance_axial")]


def error_model_options(sigma=st.just(OMIT), exclude=omit_or(st.just(())), exclude_wrong=EXCLUDE_WRONG) -> Obj:
    """An :class:`ErrorModelOptions`: sigma set, link and deflection model, clearance, exclusions, overrides."""
    return Obj(ErrorModelOptions,
               {"sigma_set": st.just(OMIT), "link_mode": omit_or(st.sampled_from(["consistent", "axes_only"])),
                "deflection_mode": omit_or(st.sampled_from(["screw", "tilt"])), "clearance": omit_or(st.booleans()),
                "clearance_tilt_literal": st.just(OMIT), "sigma": sigma, "exclude": exclude},
               {"sigma_set": bad(st.sampled_from(["table1", "table2", "generic", "nope"])),
                "exclude": bad(st.sampled_from(exclude_wrong)),
                "clearance_tilt_literal": bad(st.booleans()),
                "sigma": bad(st.just({"link_length": 0.1}),
                             st.dictionaries(st.sampled_from(["dl1", "link_length", "nope", "dth2", 3]),
                                             odd_values() | numbers_near_bounds(), max_size=3))})


def costs_options(z=omit_or(st.sampled_from([2.0, 3.0])), uniform=omit_or(st.just(False))) -> Obj:
    """A :class:`Costs`: a costs file (none, or one of the generated odd ones), ``z``, uniform errors."""
    return Obj(Costs, {"file": st.just(OMIT), "z": z, "uniform": uniform},
               {"file": bad(costs_texts().map(costs_file), st.sampled_from([Path("no/such.toml"), SCRATCH])),
                "z": bad(numbers_near_bounds()), "uniform": bad(st.booleans())})


# ------------------------------------------------------------------------------------------------ allocate
POSITION = Obj(PositionRequirement, {"radius_mm": st.floats(0.05, 2.0), "prob": st.floats(0.5, 0.999)},
               {"radius_mm": bad(numbers_near_bounds()), "prob": bad(numbers_near_bounds())})
ORIENTATION = Obj(OrientationRequirement, {"radius_deg": st.floats(0.01, 1.0), "prob": omit_or(st.floats(0.5, 0.999))},
                  {"radius_deg": bad(numbers_near_bounds()), "prob": bad(numbers_near_bounds())})


def not_none(strategy):
    """``strategy`` without None: the default region, the tool_changer's working box, whose search is its own test
    (the examples below), would only take long here."""
    return strategy.filter(lambda v: v is not None)


_REGION_WRONG = {"where": not_none(bad(st.sampled_from(["limits", "nope", "", "traj.csv", "working "]),
                                       joint_values(TC), st.just(np.zeros((3, 6))))),
                 "poses": not_none(bad(st.sampled_from(["nope", "working", "nominal"]))), "coverage_n": bad(counts())}
#: pose sets (the tool_changer's box search, region="working", is its own test): a Region's where, or its poses
REGIONS = [Obj(Region, {"where": st.just("nominal"), "poses": st.just(OMIT),
                        "coverage_n": omit_or(st.just(100))}, _REGION_WRONG),
           Obj(Region, {"where": st.just(OMIT), "poses": st.sampled_from(["nominal", "working"]),
                        "coverage_n": omit_or(st.just(100))}, _REGION_WRONG)]


def _slow_step(value) -> bool:
    """A valid angle step far below any drawing's (1e-9 .. 1e-5 deg, under 0.04 arc-second): accepted, and the
    standard search then takes seconds (up to 8 s on the tool_changer with an orientation requirement)."""
    return isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and 1e-9 <= value < 1e-5


SOLVER = Obj(Solver, {"method": omit_or(st.sampled_from(["exact", "certified"])), "snap": omit_or(st.booleans()),
                      "angle_step_deg": omit_or(st.just(0.001))},
             {"method": bad(st.sampled_from(["EXACT", "ipopt"])),
              # the slow valid steps only take long here
              "angle_step_deg": bad(numbers_near_bounds()).filter(lambda v: not _slow_step(v))})
#: no Monte Carlo (n_mc None): the verification's other fields are still checked (a correction loop without it, or
#: rounds of a loop that is off, are refused)
VERIFICATION = Obj(Verification, {"n_mc": st.just(None), "seed": omit_or(st.integers(0, 2**31)),
                                  "estimator": omit_or(st.just("auto")), "correction": omit_or(st.booleans()),
                                  "correction_rounds": omit_or(st.just(1)), "scheduler": st.just(OMIT)},
                   {"n_mc": bad(counts()), "seed": bad(counts()), "correction_rounds": bad(counts()),
                    "estimator": bad(st.sampled_from(["paired", "is"])), "correction": bad(st.booleans()),
                    "scheduler": bad(st.sampled_from(["threads", "bogus", "tcp://"]))})
_ALLOCATE_COMMON = {
    "robot": st.sampled_from([TC, "tool_changer"]) | st.builds(two_link),
    "region": st.just("nominal") | st.sampled_from(REGIONS),
    "costs": omit_or(st.just(costs_options())), "error_model": omit_or(st.just(error_model_options())),
    "solver": omit_or(st.sampled_from(["exact", "certified", SOLVER])),
    "verification": st.sampled_from([False, VERIFICATION]), "n_mc": st.just(OMIT),
    "calibration": st.just(OMIT), "tool": st.just(OMIT), "trust_units": omit_or(st.booleans()),
    "progress": omit_or(st.just(False)),
}
ALLOCATE_VALID = [
    # the short keywords of the position requirement
    {**_ALLOCATE_COMMON, "radius_mm": st.floats(0.05, 2.0), "prob": st.floats(0.5, 0.999),
     "requirement": st.just(OMIT)},
    # the requirement objects: a position requirement, with an orientation requirement
    {**_ALLOCATE_COMMON, "requirement": st.sampled_from([POSITION, [POSITION, ORIENTATION]])},
]
ALLOCATE_WRONG = {
    "robot": bad(generated_robots(1, 8)),
    "radius_mm": bad(numbers_near_bounds()), "prob": bad(numbers_near_bounds()),
    "requirement": bad(other_objects(*ALL_CLASSES), st.just([PositionRequirement(), PositionRequirement()]),
                       st.just([OrientationRequirement()]), st.just(PositionRequirement(0.1, 0.9))),
    "n_mc": bad(counts()),
    "region": not_none(bad(st.sampled_from(["limits", "nope", "", "traj.csv", "working "]),
                           joint_values(TC), st.just(np.zeros((3, 6))), other_objects(Solver, Costs))),
    "costs": bad(costs_texts().map(costs_file), st.sampled_from([Path("no/such.toml"), SCRATCH]),
                 other_objects(Region, ErrorModelOptions)),
    "error_model": bad(st.sampled_from(["table1", "generic"]), st.just({"sigma_set": "table1"}),
                       other_objects(Costs, MonteCarlo)),
    "calibration": bad(st.sampled_from([Path("no/such/plan.csv"), SCRATCH])),
    "solver": bad(st.sampled_from(["EXACT", "ipopt"]), other_objects(Verification, Region)),
    # None and True are the full verification (10^6 samples per pose, with the correction loop: seconds): not here
    "verification": bad(st.just(False), other_objects(MonteCarlo, Solver)).filter(
        lambda v: v is not None and not (isinstance(v, (bool, np.bool_)) and v)),
    "tool": bad(st.sampled_from(["tool0", "flange"])),
}


@settings(max_examples=examples(24), **SETTINGS)
@example(kwargs={"robot": TC, "radius_mm": 0.0625, "prob": 0.5, "region": "working", "verification": False,
                 "costs": Draft(Costs, z=1.0)})
@example(kwargs={"robot": TC, "radius_mm": 0.0546875, "prob": 0.5, "region": "working", "verification": False,
                 "costs": Draft(Costs, z=1.0)})
@given(perturbed(ALLOCATE_VALID, ALLOCATE_WRONG))
def test_allocate_tolerances_refuses_or_runs(kwargs):
    # the examples (found by the long profile): no standard design meets P on the region, so the standard search has
    # no worst P (the summary said NaN, not JSON, and the text "round limit reached"); no design at all covers the
    # region (the text was empty)
    res = call_job(tolalloc.allocate_tolerances, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)


@settings(max_examples=examples(3, 0.02), **SETTINGS)
@example(robot=two_link(), seed=3, radius_mm=0.5, prob=0.95, verify=True, solver="exact", region="given",
         clearance=True)
@given(robot=generated_robots(1, 5), seed=st.integers(0, 1000), radius_mm=st.floats(0.2, 5.0),
       prob=st.floats(0.5, 0.99), verify=st.booleans(), solver=st.sampled_from(["exact", "certified"]),
       region=st.sampled_from([None, "nominal", "given", "limits"]), clearance=st.booleans())
def test_allocate_tolerances_valid_runs_are_finite(robot, seed, radius_mm, prob, verify, solver, region, clearance):
    if robot is None:
        return
    if region == "given":
        region = interface_poses(robot, np.random.default_rng(seed), 3)
    elif region == "limits" and not np.all(np.isfinite(robot.lower) & np.isfinite(robot.upper)):
        region = None
    kwargs = dict(robot=robot, requirement=Draft(PositionRequirement, radius_mm=radius_mm, prob=prob),
                  region=Draft(Region, where=region, coverage_n=100), solver=solver,
                  verification=Draft(Verification, n_mc=200 if verify else None, seed=seed, correction_rounds=1),
                  error_model=Draft(ErrorModelOptions, clearance=clearance))
    res = call_job(tolalloc.allocate_tolerances, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)
        assert res.verdict in (None, "demonstrated", "consistent", "failed")
        assert (res.verdict is None) == (not verify or res.status != "optimal"), (res.verdict, res.status)


# ------------------------------------------------------------------------------------------------ analyze
ANALYZE_VALID = {
    "robot": st.sampled_from([TC, UR10, "ur10"]) | st.builds(two_link),
    "q_deg_mm": st.just(OMIT), "poses": omit_or(st.sampled_from(["nominal"])),
    "radius_mm": omit_or(st.floats(0.01, 5.0), st.lists(st.floats(0.01, 5.0), max_size=3)),
    "prob": omit_or(st.floats(0.01, 0.999), st.lists(st.floats(0.01, 0.999), max_size=3)),
    "error_model": omit_or(st.just(error_model_options(sigma=omit_or(st.just({"link_length": 0.1})),
                                                       exclude=omit_or(st.just("clearance_tilt")),
                                                       exclude_wrong=EXCLUDE_WRONG[:3]))),
    "top": omit_or(st.integers(1, 30)), "tool": st.just(OMIT),
    "trust_units": omit_or(st.booleans()), "sobol_n": omit_or(st.just(0)), "seed": omit_or(st.integers(0, 99)),
}
ANALYZE_WRONG = {
    "robot": bad(generated_robots(1, 8)),
    "q_deg_mm": bad(joint_values(TC), st.builds(lambda: measurement_frame())),
    "radius_mm": bad(numbers_near_bounds(), st.lists(numbers_near_bounds(), max_size=3)),
    "prob": bad(numbers_near_bounds(), st.lists(numbers_near_bounds(), max_size=3)),
    "top": bad(counts()), "poses": bad(st.sampled_from(["nope", "working", "nominal"])),
    "error_model": bad(st.sampled_from(["table1", "generic"]), st.just({"clearance": True}),
                       other_objects(Costs, MonteCarlo)),
    "sobol_n": bad(counts(), st.just(16)), "seed": bad(counts()),
}


@settings(max_examples=examples(30), **SETTINGS)
@given(perturbed(ANALYZE_VALID, ANALYZE_WRONG))
def test_analyze_errors_refuses_or_runs(kwargs):
    res = call_job(tolalloc.analyze_errors, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)


@settings(max_examples=examples(10, 0.1), **SETTINGS)
@given(robot=generated_robots(1, 8), data=st.data())
def test_analyze_errors_valid_runs_are_finite(robot, data):
    if robot is None:
        return
    q = data.draw(joint_values(robot))
    kwargs = dict(robot=robot, q_deg_mm=q, radius_mm=data.draw(st.floats(0.01, 10.0)),
                  prob=data.draw(st.floats(0.01, 0.999)),
                  error_model=Draft(ErrorModelOptions, clearance=data.draw(st.booleans())))
    res = call_job(tolalloc.analyze_errors, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)
        assert np.all(np.isfinite(res.linear.std_mm)) and np.all(res.linear.std_mm >= 0)


# ------------------------------------------------------------------------------------------------ simulate
MONTE_CARLO = Obj(MonteCarlo, {
    "n_mc": st.sampled_from([1, 2, 100]), "seed": omit_or(st.integers(0, 2**31)),
    "ci": omit_or(st.sampled_from(["wilson", "exact"])), "estimator": omit_or(st.sampled_from(["plain", "paired"])),
    "keep_samples": omit_or(st.sampled_from([0, 10])), "hist_bins": omit_or(st.sampled_from([0, 2, 8])),
    "hist_range_mm": st.just(OMIT), "scheduler": st.just(OMIT), "jobs": omit_or(st.integers(1, 2)),
    "chunk_size": st.just(OMIT)}, {
    "n_mc": bad(counts()), "seed": bad(counts()), "ci": bad(st.sampled_from(["WILSON", "clopper-pearson"])),
    "jobs": bad(counts()), "chunk_size": bad(counts()), "hist_bins": bad(counts()),
    "hist_range_mm": bad(numbers_near_bounds()), "keep_samples": bad(counts()),
    "estimator": bad(st.sampled_from(["importance", "auto", "Paired"])),
    "scheduler": bad(st.sampled_from(["threads", "bogus", "sync"]))})
_SIMULATE_COMMON = {
    "robot": st.sampled_from([TC, UR10]) | st.builds(two_link),
    "q_deg_mm": st.just(OMIT), "poses": omit_or(st.just("nominal")),
    "radius_mm": omit_or(st.floats(0.01, 5.0)), "angle_radius_deg": omit_or(st.floats(0.006, 5.7)),
    "error_model": omit_or(st.just(error_model_options())),
    "progress": omit_or(st.just(False)), "trust_units": omit_or(st.booleans()),
}
SIMULATE_VALID = [
    # the short keywords n_mc and seed
    {**_SIMULATE_COMMON, "n_mc": st.sampled_from([1, 2, 100]), "seed": omit_or(st.integers(0, 2**31)),
     "monte_carlo": st.just(OMIT)},
    # the MonteCarlo object
    {**_SIMULATE_COMMON, "n_mc": st.just(OMIT), "seed": st.just(OMIT), "monte_carlo": st.just(MONTE_CARLO)},
]
SIMULATE_WRONG = {
    "robot": bad(generated_robots(1, 8)), "n_mc": bad(counts()), "seed": bad(counts()),
    "q_deg_mm": bad(joint_values(TC)), "radius_mm": bad(numbers_near_bounds()),
    "angle_radius_deg": bad(numbers_near_bounds()), "progress": bad(st.booleans()),
    "monte_carlo": bad(st.just({"n_mc": 100}), other_objects(Verification, ErrorModelOptions)),
    "error_model": bad(st.sampled_from(["table1"]), other_objects(MonteCarlo)),
}


def _huge(value) -> bool:
    return isinstance(value, (int, float)) and value >= 1e12


def _affordable(kwargs: dict) -> dict:
    """A huge ``n_mc`` (or ``keep_samples``) is streamed (test_memory_is_bounded); here it would only take long: the
    call gets n_mc = 100 instead."""
    mc = kwargs.get("monte_carlo")
    fields = mc.fields if isinstance(mc, Draft) else {}
    if not any(_huge(v) for v in (kwargs.get("n_mc"), fields.get("n_mc"), fields.get("keep_samples"))):
        return kwargs
    if isinstance(mc, Draft):
        return {**kwargs, "monte_carlo": Draft(MonteCarlo, **{**fields, "n_mc": 100})}
    return {**kwargs, "n_mc": 100}


@settings(max_examples=examples(30), **SETTINGS)
@given(perturbed(SIMULATE_VALID, SIMULATE_WRONG))
def test_simulate_errors_refuses_or_runs(kwargs):
    res = call_job(tolalloc.simulate_errors, _affordable(kwargs), tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)


@settings(max_examples=examples(4, 0.05), **SETTINGS)
@example(robot=UR10, data=None)
@given(robot=generated_robots(1, 8), data=st.data())
def test_simulate_errors_valid_runs_are_finite(robot, data):
    if robot is None:
        return
    if data is None:  # the explicit example: every option at once
        data = _Fixed([100, 7, 5, 2, 0.5, "paired", True, 4])
    n, seed = data.draw(st.sampled_from([1, 2, 100])), data.draw(st.integers(0, 99))
    q = interface_poses(robot, np.random.default_rng(data.draw(st.integers(0, 99))), data.draw(st.integers(1, 3)))
    radius, estimator = data.draw(st.floats(0.01, 10.0)), data.draw(st.sampled_from([None, "paired"]))
    clearance, bins = data.draw(st.booleans()), data.draw(st.sampled_from([0, 4]))
    kwargs = dict(robot=robot, q_deg_mm=q, radius_mm=radius,
                  monte_carlo=Draft(MonteCarlo, n_mc=n, seed=seed, estimator=estimator, hist_bins=bins),
                  error_model=Draft(ErrorModelOptions, clearance=clearance))
    res = call_job(tolalloc.simulate_errors, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)
        assert res.mc.n == n


class _Fixed:
    """Stands in for ``st.data()`` in an explicit example: ``draw`` returns the given values in order."""

    def __init__(self, values):
        self.values = list(values)

    def draw(self, strategy):
        return self.values.pop(0)


# ------------------------------------------------------------------------------------------------ calibration plan
_MEASUREMENT_WRONG = {"kind": bad(st.sampled_from(["orientation", "Position"])), "noise_mm": bad(numbers_near_bounds()),
                      "noise_deg": bad(numbers_near_bounds())}
MEASUREMENTS = [Obj(Measurement, {"kind": omit_or(st.just("position")), "noise_mm": omit_or(st.floats(0.005, 0.1)),
                                  "noise_deg": st.just(OMIT), "registration": omit_or(st.booleans())},
                    _MEASUREMENT_WRONG),
                Obj(Measurement, {"kind": st.just("pose"), "noise_mm": omit_or(st.floats(0.005, 0.1)),
                                  "noise_deg": omit_or(st.floats(1e-4, 0.01)), "registration": omit_or(st.booleans())},
                    _MEASUREMENT_WRONG)]
CALPLAN_VALID = {
    "robot": st.builds(two_link), "n_poses": st.sampled_from([2, 3]), "n_candidates": st.sampled_from([8, 12]),
    "region": omit_or(st.just("limits")), "eval_poses": omit_or(st.just("nominal")),
    "measurement": omit_or(st.sampled_from(["position", "pose"]), st.sampled_from(MEASUREMENTS)),
    "costs": omit_or(st.just(costs_options(z=st.just(OMIT), uniform=st.just(OMIT)))),
    "error_model": omit_or(st.just(Obj(ErrorModelOptions, {"sigma_set": st.just(OMIT)},
                                       {"sigma_set": bad(st.sampled_from(["table1", "generic", "nope"]))}))),
    "seed": omit_or(st.integers(0, 2**31)), "random_plans": st.just(OMIT), "trust_units": omit_or(st.booleans()),
    "progress": omit_or(st.just(False)),
}
CALPLAN_WRONG = {
    "robot": bad(generated_robots(1, 8), st.just(TC)), "n_poses": bad(counts()), "n_candidates": bad(counts()),
    "region": bad(st.sampled_from(["nope", "working", "nominal"])), "eval_poses": bad(st.sampled_from(["nope"])),
    "measurement": bad(st.sampled_from(["orientation", "Position"]), other_objects(Costs, MonteCarlo)),
    "seed": bad(counts()), "random_plans": bad(counts()),
    "costs": bad(costs_texts().map(costs_file), other_objects(Measurement)),
    "error_model": bad(st.sampled_from(["table1", "generic", "nope"]), other_objects(Costs)),
}


@settings(max_examples=examples(20, 0.3), **SETTINGS)
@given(perturbed(CALPLAN_VALID, CALPLAN_WRONG))
def test_plan_calibration_refuses_or_runs(kwargs):
    if isinstance(kwargs.get("robot"), tolalloc.Robot) and kwargs["robot"].n_joints > 3:
        kwargs = {**kwargs, "n_candidates": 8}  # a design over a long chain's candidates takes seconds
    res = call_job(tolalloc.plan_calibration, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)
        assert res.design.score_mm2 >= res.design.floor_mm2 - 1e-9


@settings(max_examples=examples(2, 0.02), **SETTINGS)
@example(robot=two_link(), n_poses=3, measurement="position", seed=1)
@given(robot=generated_robots(1, 4), n_poses=st.integers(1, 4), measurement=st.sampled_from(["position", "pose"]),
       seed=st.integers(0, 99))
def test_plan_calibration_valid_runs_feed_the_calibrated_allocation(robot, n_poses, measurement, seed):
    """A plan is designed, saved, and read back by the calibration-aware allocation (a result passed on)."""
    if robot is None or not np.all(np.isfinite(robot.lower) & np.isfinite(robot.upper)):
        return
    design = call_job(tolalloc.plan_calibration, dict(robot=robot, n_poses=n_poses, n_candidates=12, seed=seed,
                                                      measurement=Draft(Measurement, kind=measurement)),
                      tolerate_known=True)
    if design is None:
        return
    check_result(design, tolerate_known=True)
    path = Path(tempfile.mkdtemp(dir=SCRATCH)) / "plan.csv"
    assert design.save_plan(path) == [path] and path.is_file()
    res = call_job(tolalloc.allocate_tolerances, dict(robot=robot, calibration=path,
                                                      verification=Draft(Verification, n_mc=200, seed=seed)),
                   tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)


# ------------------------------------------------------------------------------------------------ diagnosis
REFIT = Obj(Refit, {"register_n": st.just(OMIT), "register_rows": st.just(OMIT), "update": st.just(OMIT)},
            {"register_n": bad(numbers_near_bounds()), "register_rows": bad(st.lists(st.integers(-1, 40), max_size=12)),
             "update": bad(st.sampled_from(["calibration", "Frame", "registration"]))})
FIT = Obj(FitOptions, {"robust_loss": omit_or(st.sampled_from(["auto", "huber"])), "target_offset_mm": st.just(OMIT),
                       "target_offset_sd_mm": st.just(OMIT)},
          {"robust_loss": bad(st.sampled_from(["Tukey", "l2", "soft_l1"])),
           "target_offset_mm": bad(st.sampled_from([(0.0, 0.0, 50.0), (np.nan, 0.0, 0.0), (1.0, 2.0)])),
           "target_offset_sd_mm": bad(numbers_near_bounds())})
DIAGNOSE_VALID = {
    "robot": st.just(TC), "train": st.builds(lambda: measurement_frame().iloc[:36]),
    "test": omit_or(st.builds(lambda: measurement_frame().iloc[36:])), "folds": st.just(2),
    "alpha": omit_or(st.sampled_from([0.01, 0.05])), "seed": omit_or(st.integers(0, 100)),
    "test_frame": omit_or(st.just("same"), st.just(REFIT)), "cv_rows": st.just(OMIT), "gap_split": st.just(OMIT),
    "fit": omit_or(st.just(FIT)), "progress": omit_or(st.just(False)), "trust_units": omit_or(st.booleans()),
}
DIAGNOSE_WRONG = {
    "robot": bad(st.just(UR10), generated_robots(1, 6)), "train": bad(measurement_frames()),
    "test": bad(measurement_frames()), "folds": bad(counts()), "alpha": bad(numbers_near_bounds()),
    "seed": bad(counts()), "test_frame": bad(st.sampled_from(["refit", "other"]), other_objects(FitOptions)),
    "cv_rows": bad(counts()), "gap_split": bad(st.booleans()),
    "fit": bad(st.sampled_from(["huber"]), other_objects(Refit)),
}


@settings(max_examples=examples(24, 0.1), **SETTINGS)
@given(perturbed(DIAGNOSE_VALID, DIAGNOSE_WRONG))
def test_diagnose_measurements_refuses_or_runs(kwargs):
    res = call_job(tolalloc.diagnose_measurements, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)
        assert isinstance(res.effect, str)


@settings(max_examples=examples(1, 0.01), **SETTINGS)
@example(robot=two_link(), effect="backlash", seed=4, with_test=True)
@given(robot=generated_robots(2, 6), effect=st.sampled_from(["none", "backlash", "joint_compliance"]),
       seed=st.integers(0, 99), with_test=st.booleans())
def test_diagnose_measurements_valid_runs_on_generated_robots(robot, effect, seed, with_test):
    from tolalloc.diagnose import generate

    if robot is None:
        return
    try:
        frame = generate(robot, effect, 40, np.random.default_rng(seed)).frame
    except tolalloc.TolallocError:
        return  # an effect this robot cannot carry (no masses, no revolute joint ...)
    kwargs = dict(robot=robot, train=frame.iloc[:30], folds=2, seed=seed)
    if with_test:
        kwargs["test"] = frame.iloc[30:]
    res = outcome(tolalloc.diagnose_measurements, kwargs, tolerate_known=True)
    if res is not None:
        check_result(res, tolerate_known=True)


def test_diagnosis_of_a_robot_without_link_deflection_answers():
    """A one-joint prismatic robot has no link-deflection basis: its variants without columns are scored by the
    evidence of the noise alone, and points on a line cannot decide an effect (the registration absorbs them)."""
    import warnings

    from tolalloc.diagnose import generate

    robot = tolalloc.Robot.from_dh([{"name": "q1", "type": "prismatic", "d_mm": 300, "a_mm": 200, "alpha_deg": 90}],
                                   convention="standard")
    frame = generate(robot, "none", 40, np.random.default_rng(1)).frame
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # collinear points: the free rotation about their line is a guard, no warning
        d = tolalloc.diagnose_measurements(robot, frame.iloc[:30], frame.iloc[30:], folds=2)
    assert d.effect == "none" and d.summary()["verdict"] in ("none", "inconclusive")
    assert any("on one straight line" in g for g in d.diagnosis.guards)


# ------------------------------------------------------------------------------------------------ Robot & co
@settings(max_examples=examples(40), **SETTINGS)
@given(robot=generated_robots(1, 8), data=st.data())
def test_robot_methods_take_any_joint_values(robot, data):
    if robot is None:
        return
    q = data.draw(joint_values(robot))
    for method in (robot.fk, robot.space_jacobian, robot.body_jacobian):
        out = outcome(method, {"q_deg_mm": q})
        if out is not None:
            assert np.all(np.isfinite(out))
    n = data.draw(counts() | odd_values())
    out = outcome(robot.random_q, {"rng": np.random.default_rng(0), "n": n})
    if out is not None:
        assert out.shape == (int(n), robot.n_joints) and np.all((out >= robot.lower) & (out <= robot.upper))
    name = data.draw(st.sampled_from(["nominal", "working", "", "nope"]) | odd_values())
    out = outcome(robot.poses, {"pose_set": name})
    if out is not None:
        assert out.shape[1] == robot.n_joints


@settings(max_examples=examples(40), **SETTINGS)
@given(rows=st.lists(st.dictionaries(st.sampled_from(["name", "type", "d_mm", "d_m", "a_mm", "alpha_deg",
                                                      "alpha_rad", "theta_offset_deg", "lower_deg_mm",
                                                      "upper_deg_mm", "nominal_deg_mm", "d_inch"]),
                                     odd_values() | numbers_near_bounds() | st.sampled_from(["j", "prismatic"]),
                                     max_size=8), max_size=4) | odd_values(),
       convention=st.sampled_from(["standard", "modified", "dh", None]),
       tool=st.sampled_from([(0, 0, 0), (1, 2), (np.nan, 0, 0), "x"]))
@example(rows=[{"name": 0, "alpha_deg": None}], convention="standard", tool="x")  # the long profile's: ValueError
def test_robot_from_dh_refuses_or_builds(rows, convention, tool):
    kwargs = {"table": rows, "convention": convention, "tool_offset_mm": tool}
    robot = outcome(tolalloc.Robot.from_dh, kwargs)
    if robot is not None:
        assert np.all(np.isfinite(robot.screws)) and np.all(np.isfinite(robot.home))
    if isinstance(rows, list) and rows and all(isinstance(r, dict) for r in rows):
        outcome(tolalloc.Robot.from_dh, {"table": pd.DataFrame(rows), "convention": convention})


@settings(max_examples=examples(30), **SETTINGS)
@given(name=odd_values() | st.sampled_from(["tool_changer", "ur10", "nope", "nope.urdf", "x.csv", "/", "."]),
       tool=st.sampled_from([None, "tool0", 3]))
def test_load_robot_refuses_or_loads(name, tool):
    robot = outcome(tolalloc.load_robot, {"robot": name, "tool": tool})
    if robot is not None:
        assert isinstance(robot, tolalloc.Robot)


@settings(max_examples=examples(30), **SETTINGS)
@given(axis=st.sampled_from([(0, 0, 1), (0, 0, 2), (np.nan, 0, 1), (0, 0), "z"]),
       vector=st.sampled_from([(0, 0, 100), (0, 0, 0), (np.inf, 0, 0), (1, 2)]),
       kind=st.sampled_from(["revolute", "prismatic", "rotary", None]),
       limits=st.sampled_from([(-1.0, 1.0), (1.0, -1.0), (np.nan, 1.0), (-np.inf, np.inf), (0.5, 1.0)]),
       pose_set=st.sampled_from([None, "nominal", "working"]))
def test_robot_from_joints_and_links_refuses_or_builds(axis, vector, kind, limits, pose_set):
    def build(axis, vector, kind, limits):
        chain = (tolalloc.Link("l1", np.asarray(vector, dtype=float) if not isinstance(vector, str) else vector),
                 tolalloc.Joint("j1", kind, np.asarray(axis) if not isinstance(axis, str) else axis, *limits),
                 tolalloc.Link("l2", np.array([0.0, 300.0, 0.0])))
        sets = {} if pose_set is None else {pose_set: np.zeros((1, 1))}
        return tolalloc.Robot("r", chain, pose_sets=sets)

    robot = outcome(build, {"axis": axis, "vector": vector, "kind": kind, "limits": limits})
    if robot is not None:
        assert robot.n_joints == 1 and np.all(np.isfinite(robot.home))
    assert sorted(tolalloc.builtin_robots()) == ["tool_changer", "ur10"]


# ------------------------------------------------------------------------------------------------ results
def listing(root: Path) -> dict:
    """Every file and folder below ``root`` with its bytes (None for a folder)."""
    return {str(p.relative_to(root)): None if p.is_dir() else p.read_bytes() for p in sorted(root.rglob("*"))}


#: the output argument of each result's save()
#: every result saves as save(directory, *, report=False, json=None)
SAVE_ARGUMENT = {name: "directory" for name in ("analysis", "allocation", "simulation", "calibrated", "plan",
                                                 "diagnosis")}


@settings(max_examples=examples(24, 0.1), **SETTINGS)
@given(which=st.sampled_from(sorted(SAVE_ARGUMENT)),
       path=st.sampled_from(["", "/", "out", "out/sub", "afile", "afile/sub", 5, None, Path("deep/er/dir"), "a\x00b"]),
       pose=st.sampled_from(["worst", 0, 1, -1, 99, 1.5, "x", None]), by=st.sampled_from(["parameter", "kind", "x", 3]))
def test_result_methods_refuse_or_save_whole(which, path, pose, by):
    """``save`` writes everything or nothing; table and figure methods refuse bad arguments by name."""
    import matplotlib.pyplot as plt

    res = earlier_results()[which]
    check_result(res)
    work = Path(tempfile.mkdtemp(dir=SCRATCH))
    (work / "afile").write_text("keep\n")
    target = path if not isinstance(path, (str, Path)) or str(path) in ("", "/", "a\x00b") else work / path
    before = listing(work)
    names = outcome(res.save, {SAVE_ARGUMENT[which]: target})
    after = listing(work)
    if names is None or target is None:
        assert after == before, (target, sorted(after))
    else:
        assert after != before and Path(target).exists()
    if which == "analysis":
        frame = outcome(res.budget_frame, {"pose": pose, "by": by})
        if frame is not None:
            pair = ["sigma_mm", "sigma_deg"]  # one of the pair per row (the row's unit), the other NaN
            assert np.all(np.isfinite(frame.select_dtypes("number").drop(columns=pair, errors="ignore").to_numpy(float)))
            if by == "parameter":
                assert (frame[pair].notna().sum(axis=1) == 1).all()
        outcome(res.plot_budget, {"pose": pose, "by": by})
        plt.close("all")


def test_error_classes_carry_their_argument():
    exc = tolalloc.ArgumentError("radius_mm", "expected a finite number > 0 [mm], got -1.")
    assert isinstance(exc, tolalloc.TolallocError) and isinstance(exc, ValueError)
    assert str(exc) == "radius_mm: expected a finite number > 0 [mm], got -1." and exc.argument == "radius_mm"
    missing = tolalloc.InputFileError("robot 'x.toml': no such file.")
    assert isinstance(missing, FileNotFoundError) and str(missing) == "robot 'x.toml': no such file."
    check_refusal(exc, {"radius_mm": -1})


def test_a_refusal_names_what_was_given():
    """The oracle: a refusal names a keyword that was passed, or ``ClassName.field`` of a field given to an object that
    was passed (or set by the keyword's short form) -- not a bare field, not a field left at its default."""
    verification = build(Draft(Verification, n_mc=None, seed=3))
    check_refusal(tolalloc.ArgumentError("Verification.seed", "expected a whole number >= 0, got -1."),
                  {"verification": verification}, "allocate_tolerances")
    check_refusal(tolalloc.ArgumentError("verification", "expected a tolalloc.Verification(...), got 1."),
                  {"verification": verification}, "allocate_tolerances")
    for named in ("seed", "Verification.estimator", "MonteCarlo.seed"):  # bare, left at its default, another class
        with pytest.raises(AssertionError, match="which was not given"):
            check_refusal(tolalloc.ArgumentError(named, "expected a whole number >= 0, got -1."),
                          {"verification": verification}, "allocate_tolerances")
    # a short form names its keyword or the field it sets; another job's short form is no short form
    check_refusal(tolalloc.ArgumentError("Region.where", "expected a pose set, got 'nope'."), {"region": "nope"},
                  "allocate_tolerances")
    with pytest.raises(AssertionError, match="which was not given"):
        check_refusal(tolalloc.ArgumentError("MonteCarlo.n_mc", "expected a whole number >= 1, got 0."), {"n_mc": 0},
                      "allocate_tolerances")
    # a construction names ClassName.field of a field given
    assert build(Draft(Verification, n_mc=5)) is REFUSED
    with pytest.raises(AssertionError, match="which was not given"):
        check_refusal(tolalloc.ArgumentError("n_mc", "expected at least 100, got 5."), {"n_mc": 5},
                      names={"Verification.n_mc"})


#: run-time refusals of a settings object's field: each names ``ClassName.field`` of the object passed
RUN_TIME_REFUSALS = {
    "Region.poses": lambda: tolalloc.allocate_tolerances(TC, region=Region(poses="nope"), verification=False),
    "Region.coverage_n":
        lambda: tolalloc.allocate_tolerances(TC, region=Region(where="working", coverage_n=10**12), verification=False),
    "Verification.n_mc":
        lambda: tolalloc.allocate_tolerances(TC, region="nominal", verification=Verification(n_mc=10**12)),
    "ErrorModelOptions.sigma_set": lambda: tolalloc.analyze_errors(TC, error_model=ErrorModelOptions(sigma_set="nope")),
    "ErrorModelOptions.exclude":
        lambda: tolalloc.simulate_errors(TC, 10, error_model=ErrorModelOptions(exclude="nope")),
    "ErrorModelOptions.sigma": lambda: tolalloc.analyze_errors(TC, error_model=ErrorModelOptions(sigma={"nope": 0.1})),
    "MonteCarlo.estimator":
        lambda: tolalloc.simulate_errors(TC, monte_carlo=MonteCarlo(n_mc=100, estimator="importance"),
                                         error_model=ErrorModelOptions(clearance=True)),
    "Verification.estimator":
        lambda: tolalloc.allocate_tolerances(two_link(), region="nominal", error_model=ErrorModelOptions(clearance=True),
                                             verification=Verification(n_mc=1000, estimator="paired")),
    "Refit.register_rows":
        lambda: tolalloc.diagnose_measurements(TC, measurement_frame().iloc[:36], measurement_frame().iloc[36:],
                                               folds=2, test_frame=Refit(register_rows=[1, 2, 3, 4, 5, 40])),
}


@pytest.mark.parametrize("should", sorted(RUN_TIME_REFUSALS))
def test_run_time_refusals_name_the_field_of_the_object_passed(should):
    """A value refused only when the job runs (a pose set the robot lacks, a sample count over the time budget, an
    estimator the model's parameters cannot use) names ``ClassName.field`` of the settings object it came in."""
    with pytest.raises(tolalloc.ArgumentError) as info:
        RUN_TIME_REFUSALS[should]()
    assert info.value.argument == should, str(info.value)
    assert str(info.value).startswith(should), str(info.value)


def test_run_time_refusals_name_a_keyword_as_it_was_given():
    """The same refusals of a short keyword, or of a keyword the job took before its settings objects, name it."""
    with pytest.raises(tolalloc.ArgumentError, match="^n_mc"):
        tolalloc.allocate_tolerances(TC, region="nominal", n_mc=10**12)
    with pytest.warns(DeprecationWarning), pytest.raises(tolalloc.ArgumentError, match="^poses") as info:
        tolalloc.allocate_tolerances(TC, poses="nope", verify=False)
    assert info.value.argument == "poses"


def test_a_large_z_gives_a_finite_allocation_table():
    """``Costs(z=Z)`` up to 100: the diameter factor of the tilt callouts stays finite (its tail probability is taken
    in logarithms) and tends to 1 as the Rayleigh quantile meets the one-dimensional one."""
    from tolalloc.allocate.drawing import diameter_factor

    res = tolalloc.allocate_tolerances(two_link(), radius_mm=1.0, prob=0.5, region="nominal", costs=Costs(z=100.0),
                                       verification=False)
    assert len(res.to_frame())
    assert diameter_factor(3.0) == pytest.approx(1.1464, abs=1e-4)
    assert diameter_factor(8.0) == pytest.approx(math.sqrt(-2 * math.log(math.erfc(8 / math.sqrt(2)))) / 8, rel=1e-9)
    assert 1.0 < diameter_factor(100.0) < diameter_factor(8.0)


def test_plot_scatter_draws_into_four_axes_or_refuses():
    import matplotlib.pyplot as plt

    sim = earlier_results()["simulation"]
    try:
        fig = plt.figure()
        four = [fig.add_subplot(1, 4, 1, projection="3d")] + [fig.add_subplot(1, 4, k) for k in (2, 3, 4)]
        assert list(sim.plot_scatter(ax=four)) == four
        for bad in (plt.subplots()[1], "ax", list(plt.subplots(1, 4)[1])):
            with pytest.raises(tolalloc.ArgumentError, match="^ax"):
                sim.plot_scatter(ax=bad)
    finally:
        plt.close("all")


def test_random_plans_of_an_array_is_refused():
    with pytest.raises(tolalloc.ArgumentError, match="^random_plans"):
        tolalloc.plan_calibration(two_link(), 2, n_candidates=8, random_plans=np.array([0.1, 0.2]))


def test_save_shows_a_bad_report_flag_short(tmp_path):
    with pytest.raises(tolalloc.ArgumentError) as info:
        earlier_results()["analysis"].save(tmp_path / "out", report=object())
    assert "object at 0x" not in str(info.value) and str(info.value).startswith("report"), str(info.value)


def _same(a, b) -> None:
    """Two results with the same summary (their timings aside)."""
    def numbers(res):
        return json.dumps({k: v for k, v in res.summary().items() if k != "times_s"}, default=str, sort_keys=True)

    assert numbers(a) == numbers(b)


def test_the_deprecated_keywords_still_work_and_warn():
    """The flat keywords the jobs took before their settings objects give the same answer as the objects for one more
    release, with a DeprecationWarning naming what replaces them (the allocation's: tests/test_settings.py). Every
    other call in this module is made without them: :func:`property_strategies.outcome` fails a call that warns."""
    from tolalloc.diagnose import generate

    arm = two_link()
    frame = generate(arm, "none", 30, np.random.default_rng(2)).frame
    calls = [
        ("analyze_errors", lambda: tolalloc.analyze_errors(TC, sigma_set="table1", clearance=True, exclude="dl1"),
         lambda: tolalloc.analyze_errors(TC, error_model=ErrorModelOptions(sigma_set="table1", clearance=True,
                                                                           exclude="dl1"))),
        ("simulate_errors", lambda: tolalloc.simulate_errors(arm, n=100, seed=3, ci="exact", hist_bins=4,
                                                             link_mode="axes_only"),
         lambda: tolalloc.simulate_errors(arm, monte_carlo=MonteCarlo(n_mc=100, seed=3, ci="exact", hist_bins=4),
                                          error_model=ErrorModelOptions(link_mode="axes_only"))),
        ("plan_calibration", lambda: tolalloc.plan_calibration(arm, 4, n_candidates=8, noise_mm=0.05,
                                                               registration=False),
         lambda: tolalloc.plan_calibration(arm, 4, n_candidates=8,
                                           measurement=Measurement(noise_mm=0.05, registration=False))),
        ("diagnose_measurements", lambda: tolalloc.diagnose_measurements(arm, frame.iloc[:22], frame.iloc[22:], folds=2,
                                                                         robust_loss="huber"),
         lambda: tolalloc.diagnose_measurements(arm, frame.iloc[:22], frame.iloc[22:], folds=2,
                                                fit=FitOptions(robust_loss="huber"))),
    ]
    for job, old, new in calls:
        with pytest.warns(DeprecationWarning, match=rf"^{job}\(\): the keyword\(s\) .* are deprecated .* -> "):
            before = old()
        with warnings.catch_warnings():
            warnings.simplefilter("error", DeprecationWarning)
            _same(before, new())


# ------------------------------------------------------------------------------------------------ every result method
def _axes(count):
    """Matplotlib axes to draw into: the right number, too few, or not axes at all."""
    import matplotlib.pyplot as plt

    def make(k):
        fig, ax = plt.subplots(1, k)
        return ax if k == 1 else list(ax)

    return st.sampled_from([count, 1, 2, 3, 4]).map(make) | st.sampled_from([None, 0, "ax", [None, None]])


def _out_paths():
    return st.sampled_from(["dir", "dir/sub", "afile", "afile/sub", "file.json", "", "/", "a\x00b", None, 5,
                            Path("x")])


def result_calls(which: str) -> list:
    """(method name, keyword arguments strategy) of every public method of an earlier result ``which``."""
    from property_strategies import some_of

    pose = st.sampled_from(["worst", 0, 1, -1, 99, 1.5, -np.inf, np.nan, np.inf, "x", None, [0, 1], np.array([0]),
                            10**30, True]) | odd_values()
    by = st.sampled_from(["parameter", "kind", "x", 3, None])
    common = [("to_frame", st.just({})), ("summary", st.just({})), ("text", st.just({})),
              ("_repr_html_", st.just({})), ("__repr__", st.just({}))]
    save = ("save", some_of(directory=_out_paths(), json=_out_paths(), report=st.booleans() | odd_values(),
                            optional=("json", "report")))
    return common + {
        "analysis": [("budget_frame", some_of(pose=pose, by=by, optional=("pose", "by"))),
                     ("plot_budget", some_of(ax=_axes(1), pose=pose, by=by, optional=("ax", "pose", "by"))), save],
        "allocation": [("verification_frame", st.just({})),
                       ("plot_budget", some_of(ax=_axes(2), title=st.sampled_from(["t", None, 3, b"x"]),
                                               optional=("ax", "title"))),
                       ("plot_pose_probabilities", some_of(ax=_axes(1), optional=("ax",))),
                       ("plot_cloud", some_of(ax=_axes(3), optional=("ax",))), save],
        "simulation": [("probability_frame", st.just({})), ("plot_scatter", some_of(ax=_axes(4), optional=("ax",))),
                       save],
        "plan": [("plan_for", some_of(robot=st.sampled_from(["ur10", "tool_changer", "nope"]) | st.builds(two_link)
                                      | odd_values())),
                 ("save_plan", some_of(path=_out_paths())), save],
        "calibrated": [("verification_frame", st.just({})), save],
        "diagnosis": [("ranking_frame", st.just({})), ("predictions_frame", st.just({})),
                      ("save", some_of(directory=_out_paths(), json=_out_paths(), predictions=_out_paths(),
                                       # a folder as `report` is the deprecated save(report=DIR)
                                       report=st.booleans() | odd_values().filter(
                                           lambda v: not isinstance(v, (str, os.PathLike))),
                                       optional=("json", "predictions", "report")))],
    }[which]


def test_a_refused_diagnosis_save_leaves_nothing(tmp_path):
    """A file output below another file output is refused before anything is written."""
    with pytest.raises(tolalloc.TolallocError):
        earlier_results()["diagnosis"].save(json=tmp_path / "dir", predictions=tmp_path / "dir" / "sub")
    assert list(tmp_path.iterdir()) == []


def test_a_save_whose_outputs_overlap_leaves_nothing(tmp_path):
    res = earlier_results()["analysis"]
    with pytest.raises(tolalloc.TolallocError):
        res.save(tmp_path / "dir", json=tmp_path / "dir")
    assert list(tmp_path.iterdir()) == []


def _in_scratch(kwargs: dict, work: Path) -> dict:
    """Relative output paths of a save() call placed in the scratch folder ``work``."""
    return {k: work / v if isinstance(v, (str, Path)) and str(v) not in ("", "/", "a\x00b") and k in
            ("directory", "out", "json", "path", "report", "predictions") else v for k, v in kwargs.items()}


@settings(max_examples=examples(40, deep=2500), **SETTINGS)
@given(which=st.sampled_from(["analysis", "allocation", "simulation", "plan", "calibrated", "diagnosis"]),
       data=st.data())
def test_every_result_method_answers_or_refuses(which, data):
    """Any arguments to any public method of a result: a finite answer, a figure, files written whole, or a refusal
    by name that leaves no file behind."""
    import json

    import matplotlib.pyplot as plt
    from property_strategies import _json_default, check_method_output, finite_json

    res = earlier_results()[which]
    name, kwargs = data.draw(st.sampled_from(result_calls(which)).flatmap(lambda t: st.tuples(st.just(t[0]), t[1])))
    work = Path(tempfile.mkdtemp(dir=SCRATCH))
    (work / "afile").write_text("keep\n")
    kwargs = _in_scratch(kwargs, work) if name in ("save", "save_plan") else kwargs
    before = listing(work)
    try:
        out = outcome(getattr(res, name), kwargs, label=f"{type(res).__name__}.{name}", tolerate_known=True)
    finally:
        plt.close("all")
    if name == "save":
        whole = (out is None) == (listing(work) == before) or not any(v is not None for v in kwargs.values())
        assert whole, (kwargs, out, sorted(listing(work)))
    elif name == "summary" and out is not None:
        json.dumps(out, default=_json_default, allow_nan=False)
        finite_json(out)
    elif name.startswith("plot_") and out is not None:
        from matplotlib.axes import Axes

        assert all(isinstance(a, Axes) for a in np.ravel(np.asarray(out, dtype=object)))  # the protocol: the axes
    elif name not in ("verification_frame", "to_frame", "predictions_frame"):  # their NaN cells mean 'none'
        check_method_output(name, out, kwargs)
