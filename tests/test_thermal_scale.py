"""A position scale the robot file declares (``scale_expansion_um_per_m_K`` on an encoder): the diagnosis's thermal
``scale`` variants, offered for it only, name it from the logged air; the design's thermal term of it."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.diagnose.effects import variants
from tolalloc.diagnose.measurements import measurements_from_frame
from tolalloc.errormodel.parts import PartEffects, with_parts
from tolalloc.physics.loads import target_points
from tolalloc.physics.thermal_scale import joint_scale, scale_joints
from tolalloc.robot.io.load import _builtin_dir

C = 30e-6            # the wheel's expansion less the ring's [1/K]
WHEEL = 'encoder = { side = "output", accuracy_arcsec = 20, scale_expansion_um_per_m_K = 30 }'


@pytest.fixture(scope="module")
def declared(tmp_path_factory):
    text = (_builtin_dir() / "ur10.toml").read_text()
    line = 'encoder = { part = "MOTOR-ENC-STD" }'
    head, tail = text.split("[components.joints.shoulder_pan_joint]", 1)
    path = tmp_path_factory.mktemp("scale") / "ur10_wheel.toml"
    path.write_text(head + "[components.joints.shoulder_pan_joint]" + tail.replace(line, WHEEL, 1))
    return tolalloc.load_robot(str(path)), path


def _session(robot, P=160, seed=3):
    """Poses in time order while the air drifts by +-4 K; joint 1 read off by ``C q1 dT``; noise 0.02 mm."""
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (P, 6))
    t = np.arange(P) * 90.0
    T = 20.0 + 4.0 * np.sin(2 * np.pi * t / t[-1]) + 0.5 * t / t[-1]
    dq = np.zeros_like(q)
    dq[:, 0] = C * q[:, 0] * (T - T.mean())
    x = target_points(robot, q + dq, np.array([0.0, 0.0, 50.0])) + rng.normal(0, 0.02, (P, 3))
    df = pd.DataFrame(np.degrees(q), columns=[f"q{i + 1}_deg" for i in range(6)])
    df[["x_mm", "y_mm", "z_mm"]] = x
    df["temperature_c"], df["time_s"] = T, t
    test = np.arange(P) % 4 == 0
    return df[~test], df[test]


def test_the_key_the_columns_and_the_design_term(declared):
    robot, _ = declared
    assert robot.components.joint("shoulder_pan_joint").encoder.scale_expansion == pytest.approx(C)
    assert list(scale_joints(robot)) == [0] and not len(scale_joints(tolalloc.load_robot("ur10")))
    q = np.array([[0.8, -1.0, 0.5, 0.2, 0.3, 0.0], [-1.2, -0.5, 1.0, 0.0, 0.1, 0.4]])
    p = target_points(robot, q, np.zeros(3))
    B, names = joint_scale(robot, q, p)
    assert names == ("scale_shoulder_pan_joint [1e-6/K]",) and B.shape == (2, 3, 1)
    # 1e-6 of scale: joint 1 off by 1e-6 q1, the target moved by the forward kinematics
    moved = target_points(robot, q + np.outer(1e-6 * q[:, 0], [1, 0, 0, 0, 0, 0]), np.zeros(3))
    np.testing.assert_allclose(B[:, :, 0], moved - p, rtol=1e-5, atol=1e-12)
    rp = with_parts(robot, {k: s.options[0].name for k, s in robot.components.slots.items()})
    fx = PartEffects(rp, q, 0.0, 30.0)
    row = fx.terms().to_frame(point=0).set_index("term").loc["scale_shoulder_pan_joint"]
    col = np.linalg.norm(fx.J[0, :, fx.pm.drive[0]])
    assert row["effect"] == "thermal" and row["mean_mm"] == pytest.approx(C * 0.8 * 10.0 * col, rel=1e-9)


def test_the_diagnosis_names_a_declared_scale_and_offers_it_for_nothing_else(declared):
    robot, path = declared
    train, test = _session(robot)
    meas = measurements_from_frame(train, robot)
    assert "scale" in variants("thermal", meas, robot=robot)
    assert not any(v.startswith("scale") for v in variants("thermal", meas, robot=tolalloc.load_robot("ur10")))
    s = tolalloc.diagnose_measurements(str(path), train, test, folds=3).summary()
    assert s["verdict"] == "effect" and s["candidates"] == ["thermal"], s["reasons"]
    top = max((c for c in s["ranking"] if c["effect"] == "thermal"), key=lambda c: c["probability"] or 0.0)
    assert top["variant"].startswith("scale")
    assert s["test_rms_mm"]["final"] < 0.5 * s["test_rms_mm"]["geometric"]
