"""Hypothesis strategies and the outcome check shared by the property tests of the public API and the CLI.

Every generated call must either return a valid result or raise a :class:`tolalloc.TolallocError` whose message
names what was wrong -- a keyword that was passed, or ``ClassName.field`` of a field given to a settings object that
was passed -- and says what would work (:func:`check_refusal`); any other exception fails the test, and so does a
``DeprecationWarning`` (:func:`outcome`: the jobs are called as their documentation says). Settings objects are drawn
as :class:`Draft` and built by :func:`call_job`, which checks a refusal at construction the same way.

Profiles (``tests/conftest.py``): ``ci`` (default, derandomised, the example counts given per test), ``long``
(``TOLALLOC_HYPOTHESIS_PROFILE=long``: 10^4 examples per public call; the runs that do real work are scaled,
see :func:`examples`) and ``deep`` (``TOLALLOC_HYPOTHESIS_PROFILE=deep``: fresh random examples, the ``deep`` counts
of the method and constructor tests, together over 10^4 generated calls; ``TOLALLOC_DEEP_SCALE`` scales them).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import weakref
from pathlib import Path

import numpy as np
import pandas as pd
from hypothesis import strategies as st

import tolalloc

PROFILE = os.environ.get("TOLALLOC_HYPOTHESIS_PROFILE", "ci")
#: per-call examples of the long profile (the issue's 10^4); ``TOLALLOC_LONG_EXAMPLES`` scales it
LONG_EXAMPLES = int(os.environ.get("TOLALLOC_LONG_EXAMPLES", "10000"))


def examples(ci: int, long_fraction: float = 1.0, *, deep: int | None = None) -> int:
    """Examples of a test: ``ci`` in the ci profile; in the long profile ``LONG_EXAMPLES`` times ``long_fraction``
    (below 1 for tests whose every example runs a full job); in the deep profile ``deep`` (times
    ``TOLALLOC_DEEP_SCALE``), or ``ci`` for a test without a deep count."""
    if PROFILE == "deep":
        return ci if deep is None else max(ci, int(deep * float(os.environ.get("TOLALLOC_DEEP_SCALE", "1"))))
    return ci if PROFILE != "long" else max(ci, int(LONG_EXAMPLES * long_fraction))


# ------------------------------------------------------------------------------------------------ values
#: values no argument of a number, count, name, path or flag accepts as they are (or accepts at its bound)
ODD_VALUES = [None, 0, 1, -1, 1.5, 1e12, 10**30, -1e-300, 1e-300, math.nan, math.inf, -math.inf, 1 - 1e-15, "x", "",
              " ", "0.5", b"abc", [], [0.5], [[1, 2], [3]], (), {}, {"a": 1}, True, False, np.float32(0.5),
              np.int64(3), np.array(0.3), np.array([0.1, 0.2]), np.array([]), np.bool_(True), pd.Series([1.0]),
              complex(1, 1), object(), np.nan, np.float64(2.0), np.array(["a"]), Path("no/such/file.csv")]


def odd_values():
    return st.sampled_from(ODD_VALUES)


def numbers_near_bounds():
    """Numbers at and beyond the bounds of probabilities, radii and counts."""
    return st.sampled_from([0.0, 1.0, -0.0, 1 - 1e-15, 1e-15, 1 + 1e-15, -1.0, 0.5, 0.999, 1e-9, 1e-6, 1e6, 1e9,
                            1e12, 2.0**53, 1.5, 100.0, 99.9, 2.5, 5.0]) | st.floats(allow_nan=True, allow_infinity=True)


def counts():
    return st.sampled_from([0, 1, 2, 5, 99, 100, 1.5, 1e12, 10**13, -3, 100.0, np.int64(200), np.int32(3),
                            np.float64(100.0), "100", True])


# ------------------------------------------------------------------------------------------------ robots
@st.composite
def dh_rows(draw, min_joints: int = 1, max_joints: int = 8):
    """Rows of a DH table: zero lengths, parallel and coincident axes, prismatic joints, limits excluding zero."""
    n = draw(st.integers(min_joints, max_joints))
    rows = []
    for i in range(n):
        prismatic = draw(st.integers(0, 4)) == 0
        row = {"name": f"q{i + 1}", "type": "prismatic" if prismatic else "revolute",
               "d_mm": draw(st.sampled_from([0.0, 0.0, 100.0, -250.0]) | st.floats(-800, 800)),
               "a_mm": draw(st.sampled_from([0.0, 0.0, 300.0]) | st.floats(-800, 800)),
               # 0: parallel (and with a = d = 0 coincident) axes; +-90: the usual twists
               "alpha_deg": draw(st.sampled_from([0.0, 90.0, -90.0, 180.0]) | st.floats(-180, 180))}
        limits = draw(st.sampled_from(["none", "wide", "positive", "negative"]))
        if limits != "none":
            span = (400.0 if prismatic else 150.0) if limits == "wide" else (300.0 if prismatic else 60.0)
            lo = -span if limits == "wide" else (10.0 if limits == "positive" else -10.0 - span)
            row.update(lower_deg_mm=lo, upper_deg_mm=lo + 2 * span if limits == "wide" else lo + span)
            if draw(st.integers(0, 5)) < 5:  # sometimes no nominal value: 0, outside limits that exclude zero
                row["nominal_deg_mm"] = lo + span * draw(st.floats(0.1, 0.9))
        rows.append(row)
    return rows


@st.composite
def generated_robots(draw, min_joints: int = 1, max_joints: int = 8):
    """A Robot from DH rows (standard or modified), or the TolallocError that explains why the rows are none."""
    rows = draw(dh_rows(min_joints, max_joints))
    convention = draw(st.sampled_from(["standard", "modified"]))
    tool = draw(st.sampled_from([(0.0, 0.0, 0.0), (0.0, 0.0, 100.0), (50.0, -20.0, 80.0)]))
    try:
        return tolalloc.Robot.from_dh(rows, convention=convention, name="gen", tool_offset_mm=tool)
    except tolalloc.TolallocError as exc:
        check_refusal(exc, {"table": rows, "convention": convention, "tool_offset_mm": tool})
        return None


def robots_or_none(min_joints: int = 1, max_joints: int = 8):
    return generated_robots(min_joints, max_joints)


def interface_poses(robot, rng: np.random.Generator, n_poses: int) -> np.ndarray:
    """Joint values in deg / mm inside the limits (revolute joints within +-180 deg)."""
    return robot.q_to_interface(robot.random_q(rng, n_poses))


@st.composite
def joint_values(draw, robot):
    """Joint values for ``robot`` [deg / mm]: valid ones, and NaN, inf, 1e12, empty, wrong lengths, radians for
    degrees, text, nested and DataFrames with misspelt columns."""
    n = robot.n_joints
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    q = interface_poses(robot, rng, draw(st.integers(1, 4)))
    kind = draw(st.sampled_from(["valid", "one", "nan", "inf", "huge", "empty", "short", "long", "radians", "text",
                                 "frame", "misspelt", "int", "object", "nested", "odd"]))
    if kind == "valid":
        return q
    if kind == "one":
        return q[0].tolist()
    if kind in ("nan", "inf", "huge"):
        bad = q.copy()
        bad[0, draw(st.integers(0, n - 1))] = {"nan": np.nan, "inf": np.inf, "huge": 1e12}[kind]
        return bad
    if kind == "empty":
        return draw(st.sampled_from([[], np.empty((0, n)), np.empty(0)]))
    if kind == "short":
        return q[:, :-1] if n > 1 else []
    if kind == "long":
        return np.hstack([q, q[:, :1]])
    if kind == "radians":
        return np.where(robot.revolute_mask, np.deg2rad(q), q)
    if kind == "text":
        return [str(v) for v in q[0]]
    if kind == "frame":
        return pd.DataFrame(q, columns=[f"q{j + 1}" for j in range(n)])
    if kind == "misspelt":
        return pd.DataFrame(q, columns=[f"Q{j + 1}" if j == 0 else f"q{j + 1}" for j in range(n)])
    if kind == "int":
        return np.round(q).astype(int)
    if kind == "object":
        return q.astype(object)
    if kind == "nested":
        return [q.tolist()]
    return draw(odd_values())


def robot_arguments(robot_strategy=None):
    """The ``robot`` argument: a built-in name, a generated Robot, a result's robot, or an odd value."""
    gen = generated_robots(1, 4) if robot_strategy is None else robot_strategy
    return st.one_of(st.sampled_from(["tool_changer", "ur10"]), gen.filter(lambda r: r is not None),
                     st.sampled_from(["no_such_robot", "", "tool_changer.toml", "/", "a\x00b", Path("nope.urdf"), 7,
                                      None, ["tool_changer"], np.array("ur10")]))


# ------------------------------------------------------------------------------------------------ measurements
_FRAMES: dict = {}


def measurement_frame(rows: int = 48):
    """Synthetic tool_changer measurements (joint backlash), cached: columns q1..q6, x_mm, y_mm, z_mm, dir1..dir6,
    temperature_c, payload_kg, time_s."""
    if rows not in _FRAMES:
        from tolalloc.diagnose import generate

        case = generate(tolalloc.load_robot("tool_changer"), "backlash", rows, np.random.default_rng(11))
        _FRAMES[rows] = case.frame
    return _FRAMES[rows].copy()


@st.composite
def measurement_frames(draw, rows: int = 48):
    """Measurement frames as notebooks hold them: missing, misspelt or duplicated columns, text in numeric columns,
    unsorted or repeated time_s, one row, radians for degrees, integer and object dtypes."""
    df = measurement_frame(rows)
    kind = draw(st.sampled_from(["valid", "drop", "misspell", "duplicate", "text", "unsorted_time", "repeated_time",
                                 "one_row", "radians", "int", "object", "extra", "nan_cell", "inf_cell", "empty",
                                 "no_optional", "numbered_columns"]))
    col = draw(st.sampled_from(["q1", "q4", "x_mm", "time_s", "temperature_c", "dir2"]))
    if kind == "drop":
        df = df.drop(columns=[col])
    elif kind == "misspell":
        df = df.rename(columns={col: draw(st.sampled_from([col.upper(), col + " ", " " + col, col.replace("_", "")]))})
    elif kind == "duplicate":
        df = pd.concat([df, df[[col]]], axis=1)
    elif kind == "text":
        df = df.astype({col: object})
        df.loc[df.index[draw(st.integers(0, len(df) - 1))], col] = draw(st.sampled_from(["abc", "1,5", "", "nan"]))
    elif kind == "unsorted_time":
        df = df.sample(frac=1.0, random_state=draw(st.integers(0, 99)))
    elif kind == "repeated_time":
        df["time_s"] = 0.0
    elif kind == "one_row":
        df = df.iloc[:1]
    elif kind == "radians":
        for c in ("q1", "q2", "q3", "q5", "q6"):
            df[c] = np.deg2rad(df[c])
    elif kind == "int":
        df = df.round().astype({c: int for c in ("q1", "q2", "q3", "q4", "q5", "q6")})
    elif kind == "object":
        df = df.astype(object)
    elif kind == "extra":
        df["comment"] = "ok"
    elif kind in ("nan_cell", "inf_cell"):
        df.loc[df.index[draw(st.integers(0, len(df) - 1))], col] = np.nan if kind == "nan_cell" else np.inf
    elif kind == "empty":
        df = df.iloc[:0]
    elif kind == "no_optional":
        df = df[[f"q{j}" for j in range(1, 7)] + ["x_mm", "y_mm", "z_mm"]]
    elif kind == "numbered_columns":
        df.columns = range(df.shape[1])
    return df


# ------------------------------------------------------------------------------------------------ costs files
@st.composite
def costs_texts(draw):
    """Costs files: negative, zero and odd coefficients, limits in the wrong order, unknown names, units."""
    lines = []
    if draw(st.booleans()):
        z = draw(st.sampled_from(["3", "0", "-1", "1e-300", "1e300", '"three"', "nan", "2.5"]))
        lines.append(f"z = {z}")
    for _ in range(draw(st.integers(0, 3))):
        section = draw(st.sampled_from(["kinds.link_length", "kinds.joint_drive", "kinds.axis_deflection",
                                        "kinds.nope", "parameters.dl1", "parameters.dth2", "parameters.nope",
                                        "parameters.e1x", "calibration.kinds.link_length"]))
        lines.append(f"[{section}]")
        unit = "deg" if ("joint_drive" in section or "deflection" in section or "th" in section or "e1x" in section) \
            else "mm"
        for key in draw(st.lists(st.sampled_from(["model", "a", "b", "k", "t_ref", "t_min", "t_max", "fixed", "exclude",
                                                  "tol", "bogus"]), max_size=4, unique=True)):
            value = draw(st.sampled_from(["0", "-1", "1", "0.5", "1e-9", "1e9", "nan", "inf", "true", '"x"']))
            if key == "model":
                value = draw(st.sampled_from(['"reciprocal"', '"reciprocal_power"', '"exponential"', '"linear"']))
            if key in ("fixed", "exclude"):
                value = draw(st.sampled_from(["true", "false", "1"]))
            name = f"{key}_{draw(st.sampled_from([unit, unit, 'm', 'rad', 'deg']))}" \
                if key in ("t_ref", "t_min", "t_max", "tol") else key
            if section.startswith("calibration"):
                name = draw(st.sampled_from(["systematic", "identifiable", "bogus"]))
            lines.append(f"{name} = {value}")
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------------------ settings objects
class Draft:
    """A settings object a strategy drew, still to be built: its class and the fields given. Its repr is the call that
    builds it, so a falsifying example reads as the documented call (``tolalloc.Region(where='nominal')``)."""

    __slots__ = ("cls", "fields")

    def __init__(self, cls, /, **fields):
        self.cls, self.fields = cls, fields

    def __repr__(self) -> str:
        return f"tolalloc.{self.cls.__name__}(" + ", ".join(f"{k}={v!r}" for k, v in self.fields.items()) + ")"


#: id of a built settings object -> the fields it was given (an entry lives as long as its object)
_GIVEN: dict = {}
#: a construction that was refused (and checked)
REFUSED = object()


def remember(obj, fields) -> None:
    """Record the fields ``obj`` (a settings object or requirement) was built with: a refusal may name them."""
    _GIVEN[id(obj)] = tuple(fields)
    weakref.finalize(obj, _GIVEN.pop, id(obj), None)


def is_settings(value) -> bool:
    """A settings object or a requirement (the jobs' configuration objects)."""
    from tolalloc.workflows.settings import Settings

    return isinstance(value, (Settings, tolalloc.Requirement))


def fields_given(obj) -> tuple:
    """The fields a settings object was given: as recorded by :func:`remember`, else those away from their
    defaults (an object built elsewhere)."""
    if id(obj) in _GIVEN:
        return _GIVEN[id(obj)]
    out = []
    for f in dataclasses.fields(obj):
        default = f.default if f.default is not dataclasses.MISSING else None
        try:
            same = bool(getattr(obj, f.name) == default) or getattr(obj, f.name) is default
        except Exception:  # an array field: not a default
            same = False
        if not same:
            out.append(f.name)
    return tuple(out)


def build(value, *, tolerate_known: bool = False):
    """``value`` with its :class:`Draft` objects built (a list of them too), or :data:`REFUSED` when a construction
    was refused: the refusal is checked by :func:`outcome` and must name ``ClassName.field`` of a field given."""
    if isinstance(value, Draft):
        cls = value.cls
        obj = outcome(cls, value.fields, tolerate_known=tolerate_known,
                      names={f"{cls.__name__}.{k}" for k in value.fields})
        if obj is None:
            return REFUSED
        remember(obj, value.fields)
        return obj
    if isinstance(value, list) and any(isinstance(v, Draft) for v in value):
        items = [build(v, tolerate_known=tolerate_known) for v in value]
        return REFUSED if any(v is REFUSED for v in items) else items
    return value


def call_job(job, kwargs: dict, **options):
    """``job(**kwargs)`` as the documentation writes it: the settings objects (:class:`Draft`) built first (a
    refusal at construction checked, then None), then :func:`outcome` of the call (``options``: its keywords)."""
    built = {}
    for key, value in kwargs.items():
        value = build(value, tolerate_known=options.get("tolerate_known", False))
        if value is REFUSED:
            return None
        built[key] = value
    return outcome(job, built, **options)


# ------------------------------------------------------------------------------------------------ the oracle
#: words of a message that says what would work
_REMEDY = re.compile(r"expected|give |use |known|add |pass |convert|choose|must|needs|leave (?:it |them )?out|remove"
                     r"|rename|e\.g\."
                     r"|at least|at most|between|fill |measure |lower |relax|widen|drop |exclude fewer|check |install",
                     re.IGNORECASE)

#: the short keyword forms of the settings objects, per job: keyword -> the field(s) its value sets
#: (``region="limits"`` is ``Region(where="limits")``): a refusal of the value may name either
SHORT_FORMS = {
    "allocate_tolerances": {"radius_mm": ("PositionRequirement.radius_mm",), "prob": ("PositionRequirement.prob",),
                            "region": ("Region.where",), "costs": ("Costs.file",), "solver": ("Solver.method",),
                            "n_mc": ("Verification.n_mc",), "verification": ("Verification.n_mc",)},
    "simulate_errors": {"n_mc": ("MonteCarlo.n_mc",), "seed": ("MonteCarlo.seed",)},
    "plan_calibration": {"measurement": ("Measurement.kind",), "costs": ("Costs.file",)},
}


def given_names(kwargs: dict, call: str = "") -> set:
    """What a refusal of ``call(**kwargs)`` may name: a keyword that was passed, ``ClassName.field`` of a field given
    to a settings object that was passed (alone or in a list), or the field a short keyword form sets."""
    short = SHORT_FORMS.get(call.rsplit(".", 1)[-1], {})
    names = set()
    for key, value in kwargs.items():
        names.add(key)
        objects = [v for v in (value if isinstance(value, (list, tuple)) else [value]) if is_settings(v)]
        for obj in objects:
            names.update(f"{type(obj).__name__}.{f}" for f in fields_given(obj))
        if not objects and value is not None:
            names.update(short.get(key, ()))
    return names


def _mentions(message: str, kwargs: dict, names=()) -> bool:
    """The message names one of the call's arguments (or fields), or a file it was given, or the robot."""
    text = message.lower()
    for key in [*kwargs, *names]:
        if key.lower() in text or key.replace("_", " ") in text:
            return True
    for value in kwargs.values():
        if isinstance(value, (str, Path)) and str(value) and str(value).lower() in text:
            return True
    return any(w in text for w in ("robot", "costs", "measurement", "pose", "joint", "column", "row", "file",
                                   "calibration", "region", "sigma", "chain", "link", "table"))


def _misnamed(argument: str, names) -> str | None:
    """The name a refusal naming ``argument`` should have used, where that is a known fault."""
    return next((n for n in sorted(names) if ("names", argument, n) in KNOWN_FAULTS), None)


def check_refusal(exc: BaseException, kwargs: dict, call: str = "", *, names=None,
                  tolerate_known: bool = False) -> None:
    """A refusal names what was wrong, says what arrived and what would work, on one line.

    An :class:`~tolalloc.ArgumentError` names one of ``names``: by default :func:`given_names` (a keyword that was
    passed, or ``ClassName.field`` of a field given to a settings object that was passed, or set by a short keyword);
    a construction passes ``{"ClassName.field", ...}``. A refusal naming another argument fails, unless it is one of
    the :data:`KNOWN_FAULTS` and ``tolerate_known``. Any refusal names an argument, field, file or the robot (or the
    method ``call`` refused when no argument is: ``plot_cloud`` of a result that has no Monte Carlo samples)."""
    assert isinstance(exc, tolalloc.TolallocError), f"{type(exc).__name__}: {exc}"
    message = str(exc)
    assert message.strip() and "Traceback" not in message, repr(message)
    if "\n" in message.strip() or "object at 0x" in message:  # the value shown as its raw repr
        argument = getattr(exc, "argument", "")
        assert tolerate_known and ("shows", argument) in KNOWN_FAULTS, repr(message)
        count("known_faults", f"{call} shows {argument} raw")
    accepted = given_names(kwargs, call) if names is None else set(names)
    if isinstance(exc, tolalloc.ArgumentError) and exc.argument not in accepted:
        should = _misnamed(exc.argument, accepted)
        assert should is not None and tolerate_known, (
            f"{call or 'the call'} refused {exc.argument!r}, which was not given; given: {sorted(accepted)}; "
            f"message: {message}")
        count("known_faults", f"{call} names {exc.argument} for {should}")
    method = call.rsplit(".", 1)[-1]
    if not (_mentions(message, kwargs, accepted) or (method and message.startswith(f"{method}:"))):
        named = message.split(":", 1)[0].strip()  # a refusal that is no ArgumentError, naming a bare field
        should = _misnamed(named, accepted)
        assert should is not None and tolerate_known, message
        count("known_faults", f"{call} names {named} for {should}")
    assert _REMEDY.search(message), message


def finite_json(obj, path: str = "summary") -> None:
    """No NaN or inf anywhere in a summary (JSON numbers)."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            finite_json(v, f"{path}.{k}")
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            finite_json(v, f"{path}[{i}]")
    elif isinstance(obj, (float, np.floating)):
        assert math.isfinite(float(obj)), f"{path} = {obj}"
    elif isinstance(obj, np.ndarray) and obj.dtype.kind in "fc":
        assert np.all(np.isfinite(obj)), path


def finite_frame(frame: pd.DataFrame, allow_missing: tuple = ()) -> None:
    """Every numeric column finite (``allow_missing``: columns where an empty cell means 'not applicable')."""
    for col in frame.select_dtypes("number").columns:
        values = frame[col].to_numpy(dtype=float)
        if col in allow_missing:
            values = values[~np.isnan(values)]
        assert np.all(np.isfinite(values)), f"column {col}: {frame[col].tolist()[:8]}"


#: results checked whole by :func:`check_result` (frozen: checked once, however often a test passes them on)
_CHECKED = weakref.WeakSet()


def check_result(res, *, tolerate_known: bool = False) -> None:
    """A returned job result: a verdict, a finite summary and table, text and a repr (``tolerate_known``: an exception
    of one of the :data:`KNOWN_FAULTS` ends the check, counted)."""
    if res in _CHECKED:
        return
    try:
        _check_result(res)
    except Exception as exc:
        where = _innermost(exc)
        if not (tolerate_known and where in KNOWN_FAULTS) or isinstance(exc, AssertionError):
            raise
        count("known_faults", f"{type(res).__name__} {where[0]}:{where[1]}")
        return
    _CHECKED.add(res)


def _check_result(res) -> None:
    import json

    assert isinstance(res.ok, bool)
    summary = res.summary()
    json.dumps(summary, default=_json_default, allow_nan=False)
    finite_json(summary)
    # the standard and rounded designs' columns are empty where there is none (snap off, an infeasible requirement);
    # a quantity in mm or deg has its value in the row's unit column and nothing in the other one
    frame = res.to_frame()
    split = tuple(c for c in frame.columns if c.endswith(("_mm", "_deg")))
    finite_frame(frame, allow_missing=("tolerance_std", "cost_std", "tolerance_rounded", *split))
    if "tol_mm" in frame:
        mm = (frame["unit"] == "mm").to_numpy()
        for name in ("tol", "sigma", "t_min", "t_max", "tol_continuous"):
            a, b = frame[f"{name}_mm"].to_numpy(float), frame[f"{name}_deg"].to_numpy(float)
            assert np.isfinite(np.where(mm, a, b)).all() and np.isnan(np.where(mm, b, a)).all(), name
    assert res.text().strip() and repr(res).startswith("<")


def _json_default(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.integer, np.floating, np.bool_)):
        return obj.item()
    return str(obj)


#: library faults, reported for the integrator (not fixed by the tests), that a test may meet; a test meets them only
#: with ``tolerate_known`` (then counted), and each has a strict xfail reproducer in the test module that meets it:
#: * (module, function) of the innermost tolalloc frame -> what goes wrong (an exception that is no refusal);
#: * ("names", argument named, what it should name) -> what goes wrong (a refusal of a settings object's field at run
#:   time that names the bare field, not ``ClassName.field``);
#: * ("shows", argument) -> what goes wrong (a refusal of the argument that shows the value as its raw repr: an
#:   address, several lines);
#: * ("partial", "Result.save") -> what goes wrong (a refused save that leaves files behind).
KNOWN_FAULTS: dict = {}
#: generated calls per public call, known faults met, and other exceptions (must stay 0) -- written to the file
#: named by TOLALLOC_PROPERTY_COUNTS at exit
COUNTS = {"calls": {}, "refused": {}, "known_faults": {}, "non_project_exceptions": {}, "cli_exit_codes": {}}
#: the unit-slip warnings (radians or metres where deg / mm were expected, :func:`tolalloc.units.check_joint_units`):
#: an answer, not a fault, so a call may give them
UNIT_SLIP = r".*(the revolute joint values are all small|the prismatic joint values are all within)"


def _innermost(exc: BaseException):
    import traceback

    frames = [f for f in traceback.extract_tb(exc.__traceback__) if "/tolalloc/" in f.filename.replace("\\", "/")]
    if not frames:
        return None
    f = frames[-1]
    return f.filename.replace("\\", "/").split("/tolalloc/")[-1], f.name


def count(table: str, name: str) -> None:
    COUNTS[table][name] = COUNTS[table].get(name, 0) + 1


def outcome(call, kwargs: dict, *, tolerate_known: bool = False, label: str | None = None, names=None):
    """Run ``call(**kwargs)``: the result, or None after a checked refusal (:func:`check_refusal`, ``names``: what it
    may name, default :func:`given_names`). Any other exception propagates, unless ``tolerate_known`` and it is one of
    :data:`KNOWN_FAULTS`: then None as well. A call that gives a ``DeprecationWarning`` fails (the tests call the
    jobs as the documentation does); the unit-slip warnings (:data:`UNIT_SLIP`) are an answer and ignored, other
    warnings pass on to pytest. ``label`` names the call in the counts (default its qualified name)."""
    import warnings

    name = label or getattr(call, "__qualname__", str(call))
    count("calls", name)
    refusal = None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", message=UNIT_SLIP, category=UserWarning)
        try:
            result = call(**kwargs)
        except tolalloc.TolallocError as exc:
            result, refusal = None, exc
        except Exception as exc:
            where = _innermost(exc)
            if not (tolerate_known and where in KNOWN_FAULTS):
                count("non_project_exceptions", f"{name} {type(exc).__name__} at {where}")
                raise
            count("known_faults", f"{name} {where[0]}:{where[1]}")
            result = None
    deprecated = [str(w.message) for w in caught if issubclass(w.category, DeprecationWarning)]
    assert not deprecated, f"{name}({', '.join(kwargs)}) is a deprecated call: {deprecated[0]}"
    for w in caught:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
    if refusal is not None:
        count("refused", name)
        check_refusal(refusal, kwargs, name, names=names, tolerate_known=tolerate_known)
    return result


# ------------------------------------------------------------------------------------------------ methods
@st.composite
def some_of(draw, optional=(), **strategies):
    """Keyword arguments: each of ``strategies`` drawn (valid or odd, as its strategy offers); the ``optional`` ones
    sometimes left out (their defaults)."""
    return {name: draw(strategy) for name, strategy in strategies.items()
            if name not in optional or draw(st.integers(0, 4)) > 0}


def _no_nan_array(label: str, out, kwargs) -> None:
    arr = np.asarray(out, dtype=float)
    n = kwargs.get("n")
    q = kwargs.get("q")
    empty_asked = (label.endswith("random_q") and isinstance(n, (int, np.integer)) and not isinstance(n, bool)
                   and n == 0) or (label in ("fk_poe", "space_jacobian", "body_jacobian", "poe_prefix")
                                   and np.size(q) == 0)  # an empty stack of poses: the stack of their answers
    assert arr.size > 0 or empty_asked, f"{label}: an empty answer to {sorted(kwargs)}"
    assert not np.isnan(arr).any(), f"{label}: NaN in the answer"
    if not label.endswith(("q_to_interface", "q_from_interface", "joint_array")):  # they convert open limits (inf)
        assert np.all(np.isfinite(arr)), f"{label}: inf in the answer"


def check_method_output(label: str, out, kwargs: dict) -> None:
    """A method's answer: no NaN, not empty (unless asked for none), its objects usable (0 silent NaN or empty
    results). ``None`` (a refusal, checked by :func:`outcome`) passes."""
    from tolalloc.robot import Joint, Link, Mass, Robot

    if out is None:
        return
    if isinstance(out, np.ndarray):
        _no_nan_array(label, out, kwargs)
    elif isinstance(out, pd.DataFrame):
        # a robot without links (DH rows of zero length) has an empty table of links
        assert (len(out) or label.endswith("links_frame")) and len(out.columns), f"{label}: an empty table"
        numeric = out.select_dtypes("number")
        # a quantity in mm or deg has its value in one column of the pair (the row's unit), NaN in the other
        pairs = [(c, c[:-3] + "_deg") for c in numeric.columns if c.endswith("_mm") and c[:-3] + "_deg" in numeric]
        for a, b in pairs:
            assert (numeric[[a, b]].notna().sum(axis=1) == 1).all(), f"{label}: {a} / {b} not one per row"
        rest = numeric.drop(columns=[c for pair in pairs for c in pair])
        assert not np.isnan(rest.to_numpy(dtype=float)).any(), f"{label}: NaN in the table"
    elif isinstance(out, Robot):
        assert np.all(np.isfinite(out.screws)) and np.all(np.isfinite(out.home)) and out.n_joints >= 1
        assert np.all(np.isfinite(out.fk_internal(out.q_nominal))) and repr(out) and out._repr_html_()
        assert np.all(np.isfinite(out.gravity)) and abs(np.linalg.norm(out.gravity) - 1) < 1e-9
        for name, q in out.pose_sets.items():
            assert np.all(np.isfinite(q)) and q.shape[1] == out.n_joints, name
    elif isinstance(out, (Joint, Link, Mass)):
        for value in vars(out).values():
            if not isinstance(value, str):
                assert not np.isnan(np.asarray(value, dtype=float)).any(), f"{label}: NaN in {out}"
    elif isinstance(out, str):
        assert out.strip(), f"{label}: empty text"
    elif isinstance(out, (list, tuple)):
        assert len(out), f"{label}: an empty list"


def _write_counts() -> None:
    import json

    path = os.environ.get("TOLALLOC_PROPERTY_COUNTS")
    if path:
        Path(path).write_text(json.dumps({"profile": PROFILE, "long_examples": LONG_EXAMPLES, **COUNTS}, indent=1,
                                         sort_keys=True))


import atexit  # noqa: E402 - the counts are written when the test process ends

atexit.register(_write_counts)
