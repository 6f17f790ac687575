"""The step check (tolalloc.diagnose.steps): a single step at a pause in place of a thermal variant driven by the time
alone -- its columns against closed forms and finite differences, and on sessions of four blocks with a base shifted
at one pause, a joint's zero slipping at another, and a gradual drift."""

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose import diagnose
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.steps import StepCheck, step_basis
from tolalloc.physics.loads import target_points
from tolalloc.robot.lie import exp_so3

T_MM = np.array([0.0, 30.0, 50.0])


def _session(seed: int = 21, P: int = 120):
    """UR10 poses in four blocks of 30, 15 s apart within a block, with 30 min pauses between the blocks."""
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(seed)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 15.0 * np.arange(P) + 1800.0 * (np.arange(P) // 30)
    return robot, q, ts, rng


def test_a_frame_step_is_a_rigid_shift_of_the_later_poses_and_a_zeros_step_their_joints_turning():
    robot, q, ts, _ = _session(P=8)
    meas = Measurements(q, np.zeros((8, 3)), None, None, None, ts)
    after = np.arange(8) >= 5
    v, w = np.array([0.1, -0.2, 0.3]), np.array([1e-4, -2e-4, 3e-4])
    p = target_points(robot, q, T_MM)
    frame = step_basis(robot, meas, T_MM, after, "frame")
    np.testing.assert_allclose(frame.B @ np.concatenate([v, w]), np.where(after[:, None], v + np.cross(w, p), 0.0),
                               atol=1e-12)
    zeros = step_basis(robot, meas, T_MM, after, "zeros")
    dq = np.array([1e-6, -2e-6, 1.5e-6, 0.0, 1e-6, -1e-6])
    moved = target_points(robot, q + dq, T_MM) - p
    np.testing.assert_allclose(zeros.B @ dq, np.where(after[:, None], moved, 0.0), atol=1e-3 * np.abs(moved).max())
    assert len(zeros.names) == robot.n_joints and zeros.variant == "step_zeros"


@pytest.mark.parametrize("step, course, says", [(0.05, 0.10, "better, by more than the practical margin"),
                                                (0.102, 0.10, "within the practical margin"),
                                                (0.12, 0.10, "the change is gradual")])
def test_the_finding_names_the_comparison_its_numbers_show(step, course, says):
    line = StepCheck("drift_240min", "frame", 1, 4, 5400.0, step, course, 6, 0.05, "time blocks").line()
    assert says in line and f"{step:.4g} against {course:.4g} mm" in line and "best of 6 steps" in line
    assert "t = 1.5 h (after block 2 of 4" in line


@pytest.mark.parametrize("kind", ["frame", "zeros", "gradual"])
def test_an_event_at_a_pause_is_told_from_a_gradual_course(kind):
    """The base shifted against the tracker after block 2 (0.14 mm and 0.2 mrad), or the shoulder's zero slipping by
    0.02 deg there, or a drift of 0.17 mm rising over the session: the diagnosis names heat through a variant
    driven by the time alone each time (a time-only course fits a step roughly), and the step check says which."""
    robot, q, ts, rng = _session()
    P = len(q)
    x = target_points(robot, q, T_MM)
    if kind == "frame":
        moved = x @ exp_so3(np.array([0.0, 0.0, 2e-4])).T + np.array([0.10, -0.08, 0.05])
        xyz = np.where((np.arange(P) >= 60)[:, None], moved, x)
    elif kind == "zeros":
        slip = np.zeros(robot.n_joints)
        slip[1] = np.radians(0.02)
        xyz = np.where((np.arange(P) >= 60)[:, None], target_points(robot, q + slip, T_MM), x)
    else:
        xyz = x + np.outer(1 - np.exp(-ts / 5400.0), [0.12, -0.09, 0.08])
    xyz = xyz + rng.normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, None, ts), folds=3, max_effects=1)
    assert d.effect == "thermal", d.verdict
    line = next(f for f in d.findings if "single step" in f)
    if kind == "gradual":
        assert line.startswith("finding: no single step") and "the change is gradual" in line
    else:
        assert "explains the training file better" in line and "after block 2 of 4" in line, line
        assert ("base shifted" if kind == "frame" else "zeros stepped") in line
