"""A joint compliance clearly below zero is flagged as non-physical (diagnose/effect_checks.py)."""

import numpy as np

import tolalloc
from tolalloc.diagnose import diagnose, generate, measurements_from_frame
from tolalloc.diagnose.effects import joint_effect_dq
from tolalloc.diagnose.synth import split_frame
from tolalloc.errormodel import build_error_model
from tolalloc.robot import fk_poe


def _flipped(robot, case):
    """The case's measurements with the compliance displacement reversed: joints that lean into gravity."""
    df = case.frame.copy()
    q = robot.q_from_interface(df[[f"q{j + 1}" for j in range(robot.n_joints)]].to_numpy())
    direction = df[[f"dir{j + 1}" for j in range(robot.n_joints)]].to_numpy()
    screws, home, dq0 = build_error_model(robot).perturbed_chain(case.truth["geometric"][None, :])
    A, _ = joint_effect_dq("joint_compliance", robot, q, direction)
    t, R = case.truth["t_mm"], case.truth["R"]

    def points(dq):
        T = fk_poe(screws[0], home[0], q + dq0[0] + dq)
        return T[:, :3, 3] + T[:, :3, :3] @ t

    effect = (points(A @ case.truth["beta"]) - points(0.0)) @ R.T
    df[["x_mm", "y_mm", "z_mm"]] -= 2 * effect
    return df


def _run(robot, df):
    tr, te = split_frame(df, 0.25, np.random.default_rng(0))
    return diagnose(robot, measurements_from_frame(tr, robot), measurements_from_frame(te, robot), folds=3)


def test_negative_compliance_is_flagged_and_a_true_one_is_not():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "joint_compliance", 200, np.random.default_rng(3), magnitude_mm=0.5)
    d = _run(robot, case.frame)
    assert d.effect == "joint_compliance"
    assert not [g for g in d.guards if g.startswith("non-physical")]
    d = _run(robot, _flipped(robot, case))
    assert d.effect == "joint_compliance"  # it still lowers the held-out error ...
    flags = [g for g in d.guards if g.startswith("non-physical effect parameter: c_")]
    assert flags and all("sd below zero" in g for g in flags)  # ... but is not a physical stiffness
