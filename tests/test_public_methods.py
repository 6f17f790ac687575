"""Property tests of the robot's public methods and constructors, the kinematics functions and the error classes
(issue 46): whatever arrives, a call returns a valid answer (finite, not empty) or raises a
:class:`tolalloc.TolallocError` naming what was wrong and what would work (:func:`property_strategies.check_refusal`);
an error class takes any arguments and formats its message without failing.

Each test draws one call per example: a target (a method or constructor) and its arguments, each either valid or
from the odd pools. Examples per test: :func:`property_strategies.examples` (``TOLALLOC_HYPOTHESIS_PROFILE=deep``
for the on-demand deep run, thousands of calls per test; ``TOLALLOC_PROPERTY_COUNTS=FILE`` writes the counts).
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pandas as pd
from hypothesis import given, settings
from hypothesis import strategies as st

import tolalloc
from property_strategies import (check_method_output, examples, generated_robots, joint_values, odd_values, outcome,
                                 some_of)
from tolalloc.robot import Joint, Link, Mass, Robot, body_jacobian, fk_poe, poe_prefix, space_jacobian

TC = tolalloc.load_robot("tool_changer")
UR10 = tolalloc.load_robot("ur10")
Z = np.array([0.0, 0.0, 1.0])


def robots():
    return st.sampled_from([TC, UR10]) | generated_robots(1, 5).filter(lambda r: r is not None)


def internal_q(robot):
    """Joint values [rad, mm]: valid ones (limits not checked by the internal methods), NaN, inf, wrong shapes."""
    n = robot.n_joints
    good = st.integers(1, 3).map(lambda k: robot.random_q(np.random.default_rng(k), k))
    return st.one_of(good, good.map(lambda q: q[0]), st.just(np.full(n, np.nan)), st.just(np.full((2, n), np.inf)),
                     st.just(np.zeros(n + 1)), st.just(np.zeros((0, n))), st.just([0.0] * n), odd_values())


def vectors():
    return st.sampled_from([Z, np.array([0.0, 100.0, 0.0]), [0, 0, 1], (1.0, 0.0, 0.0), np.array([0.0, 0.0, 2.0]),
                            np.zeros(3), np.array([np.nan, 0, 1]), np.array([np.inf, 0, 0]), [0, 1], "z",
                            np.array([0.0, 0.0, 1.0 + 1e-9])]) | odd_values()


def numbers():
    return st.sampled_from([0.0, -1.0, 1.0, np.pi, -np.inf, np.inf, np.nan, 1e300, 10**400, 3, np.float32(0.5)]) \
        | odd_values()


# ------------------------------------------------------------------------------------------------ Robot methods
def robot_calls(robot):
    """(label, callable, keyword arguments strategy) for every public method of ``robot``."""
    qi = joint_values(robot)
    qq = internal_q(robot)
    return [
        ("Robot.fk", robot.fk, some_of(q_deg_mm=qi)),
        ("Robot.space_jacobian", robot.space_jacobian, some_of(q_deg_mm=qi)),
        ("Robot.body_jacobian", robot.body_jacobian, some_of(q_deg_mm=qi)),
        ("Robot.fk_internal", robot.fk_internal, some_of(q=qq)),
        ("Robot.space_jacobian_internal", robot.space_jacobian_internal,
         some_of(q=qq, engine=st.sampled_from([None, "numpy", "numba", "auto", "fast"]) | odd_values(),
                 optional=("engine",))),
        ("Robot.body_jacobian_internal", robot.body_jacobian_internal, some_of(q=qq)),
        ("Robot.q_from_interface", robot.q_from_interface, some_of(q_deg_mm=qi)),
        ("Robot.q_to_interface", robot.q_to_interface, some_of(q=qq)),
        ("Robot.check_q", robot.check_q, some_of(q=qi | qq, name=st.sampled_from(["q", "poses"]) | odd_values(),
                                                 interface=st.booleans() | odd_values(),
                                                 optional=("name", "interface"))),
        ("Robot.joint_array", robot.joint_array, some_of(q=qq, name=st.just("q"), units=st.just("rad / mm"),
                                                         finite=st.booleans(), optional=("name", "units", "finite"))),
        ("Robot.poses", robot.poses, some_of(pose_set=st.sampled_from([None, "nominal", "working", "nope", ""])
                                             | odd_values(), optional=("pose_set",))),
        ("Robot.random_q", robot.random_q, some_of(rng=st.just(np.random.default_rng(1)) | odd_values(),
                                                   n=st.sampled_from([0, 1, 5, 2.0, -1, 10**13]) | odd_values())),
        ("Robot.joints_frame", robot.joints_frame, st.just({})),
        ("Robot.links_frame", robot.links_frame, st.just({})),
        ("Robot.__repr__", robot.__repr__, st.just({})),
        ("Robot._repr_html_", robot._repr_html_, st.just({})),
    ]


@settings(max_examples=examples(60, deep=3000), deadline=None)
@given(robot=robots(), data=st.data())
def test_robot_methods_answer_or_refuse(robot, data):
    label, method, kwargs = data.draw(st.sampled_from(robot_calls(robot)).flatmap(
        lambda t: st.tuples(st.just(t[0]), st.just(t[1]), t[2])))
    out = outcome(method, kwargs, label=label)
    check_method_output(label, out, kwargs)


# ------------------------------------------------------------------------------------------------ constructors
def _joint(**kw):
    args = {"name": "j1", "kind": "revolute", "axis": Z, "lower": -1.0, "upper": 1.0, "nominal": 0.0, **kw}
    return Joint(**args)


def _robot(**kw):
    chain = (Link("l1", np.array([0.0, 0.0, 100.0])), _joint(), Link("l2", np.array([0.0, 300.0, 0.0])))
    return Robot(**{"name": "r", "chain": chain, **kw})


CONSTRUCTORS = [
    ("Joint", Joint, some_of(name=st.sampled_from(["j1", ""]) | odd_values(),
                             kind=st.sampled_from(["revolute", "prismatic", "rotary"]) | odd_values(), axis=vectors(),
                             lower=numbers(), upper=numbers(), nominal=numbers(),
                             optional=("lower", "upper", "nominal"))),
    ("Joint.from_interface", Joint.from_interface,
     some_of(name=st.just("j1"), kind=st.sampled_from(["revolute", "prismatic"]) | odd_values(), axis=vectors(),
             lower_deg_mm=numbers(), upper_deg_mm=numbers(), nominal_deg_mm=numbers(),
             optional=("nominal_deg_mm",))),
    ("Link", Link, some_of(name=st.sampled_from(["l1", ""]) | odd_values(), vector_mm=vectors())),
    ("Mass", Mass, some_of(name=st.just("m"), body=st.sampled_from([0, 1, 2, -1, 1.5]) | odd_values(),
                           mass_kg=numbers(), com_mm=vectors())),
    ("Robot", _robot, some_of(
        name=st.sampled_from(["r", ""]) | odd_values(),
        chain=st.sampled_from([(_joint(),), [_joint(), Link("l", np.ones(3))], (), (Link("l", np.ones(3)),),
                               (_joint(), _joint())]) | odd_values(),
        tool_offset_mm=vectors(),
        tool_rotation=st.sampled_from([np.eye(3), -np.eye(3), np.ones((3, 3))]) | odd_values(),
        masses=st.sampled_from([(), (Mass("m", 1, 2.0, np.zeros(3)),), (Mass("m", 5, 2.0, np.zeros(3)),)])
        | odd_values(),
        gravity=vectors(), pose_sets=st.sampled_from([{}, {"working": [[0.5]]}, {"working": [[5.0]]}, {"": [[0.0]]},
                                                      {"nominal": [[0.0]]}, {3: [[0.0]]}]) | odd_values(),
        description=st.sampled_from(["", "a robot"]) | odd_values(),
        sigma_sets=st.sampled_from([{}, {"s": {}}, {"s": 3}]) | odd_values(),
        regions=st.sampled_from([{}, {"w": ([-0.5], [0.5])}, {"w": ([0.5], [-0.5])}, {"w": [[np.nan], [1]]}])
        | odd_values(), trust_units=st.booleans() | odd_values(),
        optional=("name", "chain", "tool_offset_mm", "tool_rotation", "masses", "gravity", "pose_sets", "description",
                  "sigma_sets", "regions", "trust_units"))),
    ("Robot.from_dh", Robot.from_dh, some_of(
        table=st.lists(st.fixed_dictionaries({"name": st.sampled_from(["q1", "q2", 0, ""])},
                                             optional={"d_mm": numbers(), "a_mm": numbers(), "alpha_deg": numbers(),
                                                       "type": st.sampled_from(["revolute", "prismatic", "x"]),
                                                       "lower_deg_mm": numbers(), "upper_deg_mm": numbers()}),
                       max_size=3) | st.builds(lambda: pd.DataFrame([{"name": "q1", "d_mm": np.nan, "alpha_deg": 0.0}]))
        | odd_values(),
        convention=st.sampled_from(["standard", "modified", "dh"]) | odd_values(),
        name=st.sampled_from(["arm", ""]) | odd_values(), tool_offset_mm=vectors(), tool_rpy_deg=vectors(),
        description=st.just("") | odd_values(), trust_units=st.booleans() | odd_values(),
        optional=("name", "tool_offset_mm", "tool_rpy_deg", "description", "trust_units"))),
    ("load_robot", tolalloc.load_robot, some_of(
        robot=st.sampled_from(["tool_changer", "ur10", "nope", "nope.urdf", "x.csv", "/", "."]) | odd_values(),
        tool=st.sampled_from([None, "tool0"]) | odd_values(), optional=("tool",))),
    ("builtin_robots", tolalloc.builtin_robots, st.just({})),
]


@settings(max_examples=examples(60, deep=3000), deadline=None)
@given(data=st.data())
def test_constructors_build_valid_objects_or_refuse(data):
    label, make, kwargs = data.draw(st.sampled_from(CONSTRUCTORS).flatmap(
        lambda t: st.tuples(st.just(t[0]), st.just(t[1]), t[2])))
    out = outcome(make, kwargs, label=label)
    check_method_output(label, out, kwargs)


# ------------------------------------------------------------------------------------------------ kinematics
def screws_of(robot):
    return st.sampled_from([robot.screws, robot.screws[None].repeat(2, 0), robot.screws[:, :5], np.zeros((0, 6)),
                            np.full_like(robot.screws, np.nan)]) | odd_values()


@settings(max_examples=examples(40, deep=2000), deadline=None)
@given(robot=robots(), data=st.data())
def test_kinematics_functions_answer_or_refuse(robot, data):
    q, screws = internal_q(robot), screws_of(robot)
    homes = st.sampled_from([robot.home, robot.home[None].repeat(2, 0), np.eye(3), np.full((4, 4), np.nan)]) \
        | odd_values()
    calls = [("fk_poe", fk_poe, some_of(screws=screws, home=homes, q=q)),
             ("space_jacobian", space_jacobian, some_of(screws=screws, q=q,
                                                        engine=st.sampled_from([None, "numpy"]) | odd_values(),
                                                        optional=("engine",))),
             ("body_jacobian", body_jacobian, some_of(screws=screws, home=homes, q=q)),
             ("poe_prefix", poe_prefix, some_of(screws=screws, q=q))]
    label, fn, kwargs = data.draw(st.sampled_from(calls).flatmap(
        lambda t: st.tuples(st.just(t[0]), st.just(t[1]), t[2])))
    out = outcome(fn, kwargs, label=label)
    check_method_output(label, out, kwargs)


# ------------------------------------------------------------------------------------------------ error classes
ERRORS = [tolalloc.TolallocError, tolalloc.ArgumentError, tolalloc.UnknownArgumentError, tolalloc.InputFileError]


class _BadStr:
    def __str__(self):
        raise RuntimeError("no text")


@settings(max_examples=examples(40, deep=2000), deadline=None)
@given(cls=st.sampled_from(ERRORS), args=st.lists(odd_values() | st.text(max_size=20) | st.just(_BadStr()),
                                                  max_size=3))
def test_error_classes_take_any_arguments(cls, args):
    from property_strategies import count

    count("calls", f"{cls.__name__}()")
    exc = cls(*args)
    text = str(exc)
    assert isinstance(text, str) and isinstance(repr(exc), str)
    assert isinstance(exc, tolalloc.TolallocError) and isinstance(exc, ValueError)
    if isinstance(exc, tolalloc.ArgumentError):
        assert isinstance(exc.argument, str) and isinstance(exc.detail, str)
        if exc.argument:
            assert text.startswith(exc.argument)
    if not any(isinstance(a, (_BadStr, object)) and type(a) in (object, _BadStr) for a in args):
        again = pickle.loads(pickle.dumps(exc))  # exceptions cross process boundaries (Dask workers)
        assert type(again) is cls and str(again) == text
    try:
        raise exc
    except tolalloc.TolallocError as caught:
        assert caught is exc


def test_error_classes_keep_their_documented_text():
    assert str(tolalloc.ArgumentError("n", "expected a whole number >= 1, got 0.")) == \
        "n: expected a whole number >= 1, got 0."
    assert str(tolalloc.ArgumentError("angle_prob", "needs `angle_radius_deg`.")) == \
        "angle_prob needs `angle_radius_deg`."
    assert str(tolalloc.ArgumentError(None, b"bytes")) == "None: bytes" and str(tolalloc.ArgumentError()) == ""
    assert str(tolalloc.TolallocError("a", 2)) == "a; 2" and str(tolalloc.InputFileError()) == ""
    assert str(tolalloc.InputFileError(b"x.csv")) == "x.csv" and math.isnan(float("nan"))
    assert str(tolalloc.TolallocError(_BadStr())).startswith("<test_public_methods._BadStr object at")
