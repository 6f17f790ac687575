"""Every list of known names in an error message names each once, in the order the user meets them.

The source is scanned for ``raise`` statements whose message offers the known names (``known: ...``,
``known sets: ...`` or a ``{known...}`` list); each such site has a trigger below that makes it raise, and the
test checks that the trigger really lands in that site and that its list has no repeats. A new site without a
trigger fails :func:`test_every_known_list_has_a_trigger`.
"""

from __future__ import annotations

import ast
import re
import traceback
from pathlib import Path

import numpy as np
import pytest

import tolalloc
from tolalloc.robot.model import Joint, Link, Robot

ROOT = Path(tolalloc.__file__).resolve().parent
KNOWN = re.compile(r"\bknown[a-z ]*:|\{known")


def _sites() -> set:
    """``(module path, enclosing function)`` of every raise whose message offers known names."""
    out = set()

    class Visitor(ast.NodeVisitor):
        def __init__(self, text, rel):
            self.text, self.rel, self.func = text, rel, None

        def visit_FunctionDef(self, node):
            outer, self.func = self.func, node.name
            self.generic_visit(node)
            self.func = outer

        visit_AsyncFunctionDef = visit_FunctionDef

        def visit_Raise(self, node):
            if node.exc is not None and self.func and KNOWN.search(ast.get_source_segment(self.text, node) or ""):
                out.add((self.rel, self.func))

    for path in sorted(ROOT.rglob("*.py")):
        text = path.read_text()
        if "known" in text:
            Visitor(text, str(path.relative_to(ROOT))).visit(ast.parse(text))
    return out


def _crowded_robot() -> Robot:
    """A robot whose names overlap across groups: a box region and a pose set both called ``working``, and a
    second pose set ``reach`` that is also a region."""
    chain = (Link("l1", np.array([0.0, 0.0, 300.0])), Joint("j1", "revolute", np.array([0.0, 0.0, 1.0]), -2.0, 2.0),
             Link("l2", np.array([0.0, 400.0, 0.0])), Joint("j2", "revolute", np.array([1.0, 0.0, 0.0]), -2.0, 2.0),
             Link("l3", np.array([0.0, 300.0, 0.0])))
    q = np.array([[0.1, 0.2], [0.3, -0.4]])
    box = (np.array([-1.0, -1.0]), np.array([1.0, 1.0]))
    plain = Robot("crowded", chain)
    params = _model(plain).params
    sigmas = {f"sigma_{u}": {p.name: p.sigma for p in params if p.unit == u} for u in ("mm", "rad")}
    return Robot("crowded", chain, pose_sets={"working": q, "reach": q[:1]}, regions={"working": box, "reach": box},
                 sigma_sets={"tight": sigmas, "loose": sigmas})


def _listed(message: str) -> list[str]:
    """The names after ``known...:`` (up to the sentence's end) or inside ``(...)`` of a built-in robot list."""
    m = re.search(r"known[a-z ]*: (.*?)(?:\.$|\. |;|, or give| \(|$)", message) or \
        re.search(r"not a built-in robot \((.*?)\)", message)
    assert m, message
    return [x.strip() for x in m.group(1).split(",") if x.strip()]


def _plan_with_unknown_parameter(tmp_path) -> Path:
    """A plan CSV (the layout of ``CalibrationPlanDesign.save``) whose ``estimate`` names a parameter ``nope``."""
    robot = tolalloc.load_robot("tool_changer")
    rows = robot.q_to_interface(robot.random_q(np.random.default_rng(0), 12))
    head = "# measurement = position\n# noise_mm = 0.02\n# noise_deg = 0.001\n# estimate = dl1 nope\n" \
           "# registration = true\n"
    cols = ",".join(f"{j.name}_{j.unit}" for j in robot.joints)
    path = tmp_path / "plan.csv"
    path.write_text(head + cols + "\n" + "\n".join(",".join(f"{v:.6f}" for v in r) for r in rows) + "\n")
    return path


def _posterior_of(path: Path):
    """The post-calibration statistics of the tool_changer after the plan in ``path`` (read from the file)."""
    from tolalloc.calibration import read_plan
    from tolalloc.calibration.posterior import posterior
    from tolalloc.calibration.split import split_errors

    robot = tolalloc.load_robot("tool_changer")
    return posterior(split_errors(_model(robot)), read_plan(path, robot))


def _costs(tmp_path, text: str) -> Path:
    path = tmp_path / "costs.toml"
    path.write_text(text)
    return path


def _model(robot="tool_changer"):
    from tolalloc.errormodel import build_error_model

    return build_error_model(tolalloc.load_robot(robot) if isinstance(robot, str) else robot)


#: site -> (trigger(tmp_path), expected first names of the list, in order)
TRIGGERS = {
    ("robot/model.py", "poses"): (lambda tmp: _crowded_robot().poses("nope"), ["nominal", "working", "reach"]),
    ("robot/io/load.py", "load_robot"): (lambda tmp: tolalloc.load_robot("no_such_robot"), ["tool_changer", "ur10"]),
    ("errormodel/model.py", "index"): (lambda tmp: _model().index("nope"), ["dl1", "dl2"]),
    ("errormodel/build.py", "build_error_model"): (
        lambda tmp: __import__("tolalloc.errormodel", fromlist=["x"]).build_error_model(
            tolalloc.load_robot("tool_changer"), sigma={"nope": 1.0}), ["dl1", "dl2"]),
    ("errormodel/build.py", "_sigma_from_set"): (
        lambda tmp: __import__("tolalloc.errormodel", fromlist=["x"]).build_error_model(_crowded_robot(), "nope"),
        ["generic", "tight", "loose"]),
    ("workflows/checks.py", "check_name"): (
        lambda tmp: tolalloc.analyze_errors(
            _crowded_robot(), error_model=tolalloc.ErrorModelOptions(sigma_set="nope")), ["generic", "tight", "loose"]),
    ("workflows/inputs.py", "resolve_poses"): (
        lambda tmp: tolalloc.analyze_errors(_crowded_robot(), poses="nope"), ["nominal", "working", "reach"]),
    ("workflows/inputs.py", "sigma_overrides"): (
        lambda tmp: tolalloc.analyze_errors(
            "tool_changer", error_model=tolalloc.ErrorModelOptions(sigma={"nope": 0.1})), ["dl1", "dl2"]),
    ("workflows/inputs.py", "error_model"): (
        lambda tmp: tolalloc.analyze_errors(
            "tool_changer", error_model=tolalloc.ErrorModelOptions(exclude=["nope"])), ["dl1", "dl2"]),
    ("workflows/inputs.py", "resolve_region"): (
        lambda tmp: tolalloc.allocate_tolerances(_crowded_robot(), region="nope", verification=False),
        ["limits", "working", "reach", "nominal"]),
    ("allocate/calibrated/design.py", "resolve_region"): (
        lambda tmp: __import__("tolalloc.allocate.calibrated.design", fromlist=["x"]).resolve_region(
            _crowded_robot(), "nope"), ["limits", "working", "reach"]),
    ("workflows/calplan.py", "_check_region"): (
        lambda tmp: tolalloc.plan_calibration(_crowded_robot(), 4, region="nope"), ["limits", "working", "reach"]),
    ("allocate/costs.py", "_entries"): (
        lambda tmp: tolalloc.allocate_tolerances("tool_changer", costs=_costs(tmp, "[parameters.nope]\na = 1\n"),
                                                 verification=False), ["dl1", "dl2"]),
    ("calibration/split.py", "split_errors"): (
        lambda tmp: tolalloc.plan_calibration("tool_changer", 4, n_candidates=16,
                                              costs=_costs(tmp, "[calibration.kinds.nope]\nsystematic = 0.5\n")),
        ["link_length"]),
    ("calibration/posterior.py", "estimated_index"): (
        lambda tmp: _posterior_of(_plan_with_unknown_parameter(tmp)), ["dl1", "dl2"]),
    ("diagnose/effects.py", "effect_basis"): (
        lambda tmp: __import__("tolalloc.diagnose.effects", fromlist=["x"]).effect_basis(
            "nope", tolalloc.load_robot("tool_changer"), None, np.zeros(3), {}), ["joint_compliance"]),
    ("acceptance/requirement_file.py", "_requirement"): (
        lambda tmp: __import__("tolalloc.acceptance.requirement_file", fromlist=["x"]).parse_requirements(
            {"requirement": [{"kind": "nope"}]}), ["position", "orientation", "pose_accuracy"]),
}


def test_every_known_list_has_a_trigger():
    assert _sites() == set(TRIGGERS), "a message lists known names without a trigger here (or a trigger is stale)"


@pytest.mark.parametrize("site", sorted(TRIGGERS), ids=["::".join(s) for s in sorted(TRIGGERS)])
def test_known_list_is_free_of_repeats_and_in_order(site, tmp_path):
    trigger, first = TRIGGERS[site]
    with pytest.raises((tolalloc.TolallocError, ValueError)) as info:
        trigger(tmp_path)
    frames, exc = [], info.value
    while exc is not None:  # a message re-raised by the workflow layer (naming the argument) keeps its origin here
        frames += traceback.extract_tb(exc.__traceback__)
        exc = exc.__context__
    here = [(str(Path(f.filename).resolve().relative_to(ROOT)), f.name) for f in frames
            if Path(f.filename).resolve().is_relative_to(ROOT)]
    assert site in here, f"{site} not reached: {here[-3:]}"
    names = _listed(str(info.value))
    assert len(names) == len(set(names)), str(info.value)
    if first is not None:
        assert names[:len(first)] == first, str(info.value)


def test_region_list_of_the_tool_changer_names_working_once():
    """The tool_changer has a box region and a pose set both called ``working``: one name to type, listed once,
    after the built-in box and before the built-in pose set."""
    with pytest.raises(tolalloc.ArgumentError) as info:
        tolalloc.allocate_tolerances("tool_changer", region="nonexistent_box", verification=False)
    assert _listed(str(info.value)) == ["limits", "working", "nominal"]
    assert "or give a path to a .csv file" in str(info.value)


def test_cli_region_list_names_working_once(capsys):
    from tolalloc.cli import main

    assert main(["allocate", "tool_changer", "--region", "nonexistent_box", "--no-verify"]) == 2
    line = capsys.readouterr().err.strip()
    assert line.startswith("error: --region: 'nonexistent_box'") and line.count("working") == 1, line


@pytest.mark.parametrize("key, name", [("pose_sets", "nominal"), ("regions", "limits"), ("sigma_sets", "generic")])
def test_robot_files_cannot_shadow_built_in_names(tmp_path, key, name):
    """A robot file's pose set ``nominal``, region ``limits`` or sigma set ``generic`` would never be used (the
    built-in one wins), so it is refused with a hint instead of being listed twice."""
    body = {"pose_sets": "q_deg_mm = [[10]]", "regions": "q_min_deg_mm = [-10]\nq_max_deg_mm = [10]",
            "sigma_sets": 'description = "x"'}[key]
    path = tmp_path / "r.toml"
    path.write_text('name = "t"\n[[chain]]\njoint = "j1"\ntype = "revolute"\naxis = [0, 0, 1]\n'
                    'limits_deg = [-170, 170]\n[[chain]]\nlink = "l1"\nvector_mm = [0, 0, 400]\n'
                    f"[{key}.{name}]\n{body}\n")
    with pytest.raises(tolalloc.TolallocError, match=rf"{key}\.{name}: the .* name '{name}' is built in"):
        tolalloc.load_robot(path)
