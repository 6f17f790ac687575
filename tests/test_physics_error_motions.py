"""Error motions of a linear axis along its stroke (:mod:`tolalloc.physics.error_motions`).

The data are made by exact rigid motions of the target point (``scipy.spatial.transform.Rotation`` about the axis
line, translations along directions found by finite differences of the forward kinematics), never from the basis.
"""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.effects import target_points, variants
from tolalloc.diagnose.measurements import Measurements
from tolalloc.physics.error_motions import STROKE_ORDER, stroke_columns, stroke_position
from tolalloc.robot.kinematics import poe_prefix

T_MM = np.array([0.0, 0.0, 100.0])


def _q(robot, P, seed):
    rng = np.random.default_rng(seed)
    rev = robot.revolute_mask
    lo = np.where(rev, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(rev, np.minimum(robot.upper, np.pi), robot.upper)  # a prismatic joint over its whole stroke [mm]
    return rng.uniform(lo, hi, (P, robot.n_joints))


def _legendre(s, k):
    return {1: s, 2: 0.5 * (3 * s ** 2 - 1), 3: 0.5 * (5 * s ** 3 - 3 * s)}[k]


def _guided(robot, q, j, roll_mrad, pitch_mrad, lateral_mm):
    """Target points with the carriage of prismatic joint ``j`` rolled about its axis line by ``roll_mrad(s)``,
    pitched about an axis across it through the carriage's point by ``pitch_mrad(s)``, and shifted across the axis by
    ``lateral_mm(s)``, each exact."""
    p = target_points(robot, q, T_MM)
    h = 1e-3
    dq = np.zeros(robot.n_joints)
    dq[j] = h
    u = (target_points(robot, q + dq, T_MM) - p) / h  # a prismatic joint moves every later point along its axis
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    Pm = poe_prefix(robot.screws, q)
    o = Pm[:, j + 1, :3, :3] @ robot.joint_points_mm[j] + Pm[:, j + 1, :3, 3]
    across = np.cross(u, [0.0, 0.0, 1.0]) if abs(robot.joints[j].axis[2]) < 0.9 else np.cross(u, [1.0, 0.0, 0.0])
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    s = stroke_position(robot, q, j)
    out = p.copy()
    for i in range(len(q)):
        rot = (Rotation.from_rotvec(1e-3 * roll_mrad(s[i]) * u[i])
               * Rotation.from_rotvec(1e-3 * pitch_mrad(s[i]) * across[i]))
        out[i] = o[i] + rot.apply(p[i] - o[i]) + lateral_mm(s[i]) * np.cross(u[i], across[i])
    return out, p


def test_stroke_columns_reproduce_exact_rigid_error_motions_of_the_telescopic_stage():
    """A roll, a pitch and a straightness along the stroke (quadratic and cubic, tenths of a mrad and hundredths of a
    mm), made exactly: the basis spans the displacement to first order (residual under 1e-3 of it) and the fitted roll
    amplitudes equal the ones put in."""
    robot = tolalloc.load_robot("tool_changer")
    j = next(i for i, jt in enumerate(robot.joints) if not jt.is_revolute)
    q = _q(robot, 60, 3)
    roll = lambda s: 0.2 * _legendre(s, 2) - 0.1 * _legendre(s, 3)  # noqa: E731
    xyz, p = _guided(robot, q, j, roll, lambda s: 0.15 * _legendre(s, 1) + 0.1 * _legendre(s, 2),
                     lambda s: 0.03 * _legendre(s, 3))
    d = xyz - p
    B, names, groups = stroke_columns(robot, q, p)
    assert B.shape == (60, 3, len(names)) and len(names) == STROKE_ORDER + 2 * (STROKE_ORDER - 1) + 3 * STROKE_ORDER
    beta, *_ = np.linalg.lstsq(B.reshape(-1, B.shape[2]), d.ravel(), rcond=None)
    fit = (B @ beta) - d
    assert np.sqrt(np.mean(fit ** 2)) < 1e-3 * np.sqrt(np.mean(d ** 2))
    name = robot.joints[j].name
    got = dict(zip(names, beta))
    assert got[f"eru2_{name} [mrad]"] == pytest.approx(0.2, rel=2e-3)
    assert got[f"eru3_{name} [mrad]"] == pytest.approx(-0.1, rel=2e-3)
    assert got[f"eru1_{name} [mrad]"] == pytest.approx(0.0, abs=1e-3)
    assert set(groups) == {2 * j, 2 * j + 1}
    assert all(g == 2 * j + 1 for g, nm in zip(groups, names) if nm.startswith("er"))


def test_no_stroke_columns_or_variant_for_a_robot_without_prismatic_joints():
    robot = tolalloc.load_robot("ur10")
    q = _q(robot, 8, 1)
    B, names, groups = stroke_columns(robot, q, target_points(robot, q, T_MM))
    assert B.shape == (8, 3, 0) and names == [] and groups.shape == (0,)
    meas = Measurements(q, np.zeros((8, 3)), None, None, None, None)
    assert "stroke" not in variants("transmission", meas, {}, robot)
    tc = tolalloc.load_robot("tool_changer")
    assert "stroke" in variants("transmission", Measurements(_q(tc, 8, 1), np.zeros((8, 3)), None, None, None, None),
                                {}, tc)


def test_a_guideway_with_pitch_and_yaw_along_the_stroke_is_named_transmission_stroke():
    """The telescopic stage of the tool changer pitches by 0.3 mrad x P2(s) and yaws by 0.2 mrad x P3(s) along its
    stroke (a bent rail, exact rotations): the diagnosis names transmission in the ``stroke`` variant."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("tool_changer")
    j = next(i for i, jt in enumerate(robot.joints) if not jt.is_revolute)
    P = 90
    q = _q(robot, P, 31)
    xyz, _ = _guided(robot, q, j, lambda s: 0.2 * _legendre(s, 3), lambda s: 0.3 * _legendre(s, 2), lambda s: 0.0)
    xyz = xyz + np.random.default_rng(31).normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, None, None), folds=3, max_effects=1)
    assert d.effect == "transmission", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "transmission") == "stroke"
    # the identified model, written to its file and read back, predicts the guided stage alike at new poses, and the
    # error motions are in its prediction: it is nearer the true points than the geometric model alone
    import json

    from tolalloc.diagnose.model_export import identified_section, model_from_identified
    from tolalloc.diagnose.model_use import identified_model

    m = identified_model(d)
    back = model_from_identified(json.loads(json.dumps(identified_section(m))), robot)
    q_new = _q(robot, 20, 32)
    a, b = (x.points(x.measurements(q_new), "tracker") for x in (m, back))
    np.testing.assert_allclose(b, a, atol=1e-9)
    true, _ = _guided(robot, q_new, j, lambda s: 0.2 * _legendre(s, 3), lambda s: 0.3 * _legendre(s, 2),
                      lambda s: 0.0)
    geo = m.geometric_points(q_new)
    assert np.sqrt(np.mean((a - true) ** 2)) < 0.5 * np.sqrt(np.mean((geo - true) ** 2))


def test_a_prismatic_joint_without_limits_gets_no_error_motions():
    """The stroke is normalised by the joint's limits: an unbounded one has no stroke to normalise by, so no columns
    and no ``stroke`` variant (rather than NaN columns)."""
    chain = (tolalloc.robot.Joint("x", "prismatic", np.array([1.0, 0.0, 0.0]), -np.inf, np.inf),
             tolalloc.robot.Link("l", np.array([0.0, 0.0, 100.0])))
    robot = tolalloc.robot.Robot("rail", chain, trust_units=True)
    q = np.linspace(0.0, 300.0, 5)[:, None]
    B, names, _ = stroke_columns(robot, q, target_points(robot, q, T_MM))
    assert B.shape == (5, 3, 0) and names == []
    assert "stroke" not in variants("transmission", Measurements(q, np.zeros((5, 3)), None, None, None, None), {},
                                    robot)
