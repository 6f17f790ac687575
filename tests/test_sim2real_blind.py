"""The independent blind generator of studies/sim2real_blind: independent, faithful, and no false claims on `none`.

* independence: ``physics.py`` / ``cases.py`` import nothing of the diagnosis's effect bases, the synthetic
  generator, the error model or the POE kinematics (checked on their import statements);
* its own frame-walking kinematics reproduces ``Robot.fk_internal`` at zero geometric error (two independent
  implementations agree to 1e-9 mm) and every geometric parameter it perturbs moves the probe;
* a small fixed-seed sample of ``none`` cases (both built-in robots, 60 poses, with outliers forced in one)
  is diagnosed ``none``; a wrist-still session (issue 25) gets no claim;
* the motion-history thermal physics is the two-stage lag's closed form at constant speed.
"""

import ast
import sys
from pathlib import Path

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose import diagnose, measurements_from_frame

STUDY = Path(__file__).resolve().parents[1] / "studies" / "sim2real_blind"
sys.path.insert(0, str(STUDY))

from cases import generate  # noqa: E402
from physics import _perturbed_ops, describe, motion_temperatures, walk  # noqa: E402


def _imports(path: Path) -> set:
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            out.add(node.module or "")
    return out


@pytest.mark.parametrize("name", ["physics.py", "cases.py"])
def test_generator_imports_nothing_of_the_fitted_models(name):
    mods = _imports(STUDY / name)
    assert not [m for m in mods if m.startswith("tolalloc")], mods


@pytest.mark.parametrize("name", ["ur10", "tool_changer"])
def test_walk_reproduces_robot_fk_and_every_error_moves_the_probe(name):
    robot = tolalloc.load_robot(name)
    desc = describe(robot)
    q = np.random.default_rng(0).uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (8, robot.n_joints))
    x0 = walk(_perturbed_ops(desc, np.zeros(len(desc.geo_names))), q, desc.tool_mm)[0]
    np.testing.assert_allclose(x0, robot.fk_internal(q)[:, :3, 3], atol=1e-9)
    for k in np.flatnonzero(desc.geo_scale > 0):
        geo = np.zeros(len(desc.geo_names))
        geo[k] = desc.geo_scale[k]
        x = walk(_perturbed_ops(desc, geo), q, desc.tool_mm + np.array([0.0, 30.0, 60.0]))[0]
        ref = walk(_perturbed_ops(desc, np.zeros(len(desc.geo_names))), q, desc.tool_mm + np.array([0.0, 30.0, 60.0]))[0]
        assert np.abs(x - ref).max() > 1e-3, desc.geo_names[k]


@pytest.mark.parametrize("name,seed", [("tool_changer", 11), ("ur10", 12)])
def test_none_cases_get_no_effect(name, seed):
    robot = tolalloc.load_robot(name)
    rng = np.random.default_rng(seed)
    case = generate(robot, "none", 60, rng)
    frame = case.frame.copy()
    if name == "ur10":  # two gross outliers (2 mm) must not fake an effect
        frame.loc[[7, 40], "x_mm"] += 2.0
    d = diagnose(robot, measurements_from_frame(frame, robot), folds=2)
    assert d.effect == "none", d.ranking_frame()[["effect", "variant", "gain_pct", "p_value"]]


def test_motion_temperatures_two_stage_lag_closed_form():
    t = 30.0 * np.arange(400)
    q = np.column_stack([0.002 * t, np.zeros_like(t)])  # joint 1 at constant speed from t = 0
    tm, tl = 900.0, 2400.0
    T = motion_temperatures(q, t, np.array([2.0, 1.0]), tm, tl, [[0], [0, 1]])
    h = 2.0 * 0.002  # heat input of joint 1
    link0 = h * (1 - (tl * np.exp(-t / tl) - tm * np.exp(-t / tm)) / (tl - tm))  # step through two lags
    # the sampled second stage holds the motor value over each 30 s step: within a few % of dt / tau of the input
    np.testing.assert_allclose(T[:, 0], link0, atol=0.03 * h)
    np.testing.assert_allclose(T[:, 1], 0.5 * T[:, 0], atol=1e-15)  # link 1: mean of joints 1 (moving) and 2


def test_wrist_still_session_gets_no_claim():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "none", 60, np.random.default_rng(21), "wrist_still")
    n = int(round(0.75 * 60))
    tr, te = case.frame.iloc[:n].reset_index(drop=True), case.frame.iloc[n:].reset_index(drop=True)
    d = diagnose(robot, measurements_from_frame(tr, robot), measurements_from_frame(te, robot), folds=2,
                 max_effects=1)
    assert d.verdict.verdict in ("none", "inconclusive") and d.effect == "none", d.verdict.reasons
