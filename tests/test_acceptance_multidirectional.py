"""ISO 9283 7.2.3 multi-directional pose accuracy variation (vAP_P): the statistic's known answer, the joints'
directions of an approach against a finite-difference Jacobian, the lost motion's offset between two approaches
against the forward kinematics, the prediction against the simulated test, the requirement file, the allocation
and its refusals."""

import copy
import tomllib
from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.acceptance import (MultiDirectionalAccuracy, MultiDirectionalOrientation, PoseAccuracy,
                                 multidirectional_accuracy, multidirectional_orientation, parts_effects,
                                 predict_acceptance)
from tolalloc.acceptance.layout import acceptance_test_at, joint_directions
from tolalloc.acceptance.model import requirement_poses, statistic_models
from tolalloc.acceptance.requirement_file import parse_requirements
from tolalloc.acceptance.simulate import simulate_acceptance
from tolalloc.acceptance.statistics import barycentre_distances
from tolalloc.calibration.split import split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.parts import with_parts
from tolalloc.exceptions import TolallocError
from tolalloc.robot.components import JointComponents, Reducer
from iso_setup import ur10_test

ARCMIN = np.deg2rad(1 / 60)
VAP = MultiDirectionalAccuracy(limit_mm=0.5)
VAP_ANGLES = MultiDirectionalOrientation(limit_deg=0.05)


def _catalogue(robot):
    return with_parts(robot, {k: s.options[0].name for k, s in robot.components.slots.items()})


def test_statistic_is_the_largest_distance_between_the_directions_barycentres():
    rng = np.random.default_rng(0)
    centres = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.2, 0.0]])
    noise = rng.standard_normal((3, 30, 3)) * 0.01
    x = centres[:, None, :] + noise - noise.mean(axis=1, keepdims=True)       # barycentres exactly the centres
    np.testing.assert_allclose(barycentre_distances(x), [0.1, 0.2, np.hypot(0.1, 0.2)], atol=1e-12)
    assert multidirectional_accuracy(x) == pytest.approx(np.hypot(0.1, 0.2), abs=1e-12)
    R = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()                    # a rigid motion changes nothing
    assert multidirectional_accuracy(x @ R.T + [5.0, 1.0, -2.0]) == pytest.approx(np.hypot(0.1, 0.2), abs=1e-12)
    with pytest.raises(TolallocError, match="three approach directions"):
        multidirectional_accuracy(x[:2])
    np.testing.assert_allclose(multidirectional_orientation(x), [0.1, 0.2, 0.0], atol=1e-12)   # per angle


@pytest.mark.parametrize("fixed", [True, False])
def test_joint_directions_are_those_of_the_jacobian_by_finite_differences(fixed):
    """The joints' rates of a straight approach from a central-difference Jacobian of the forward kinematics (tool
    point, and the rotation vector when the orientation is held), solved by least squares: the same signs."""
    robot, test = ur10_test()
    q = test.q_test
    u = VAP.directions()
    h = 1e-6
    for qi, signs in zip(q, joint_directions(robot, q, u, fixed)):
        cols = []
        for j in range(robot.n_joints):
            dq = np.zeros(robot.n_joints)
            dq[j] = h
            Tp, Tm = robot.fk_internal(np.stack([qi + dq, qi - dq]))
            dp = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
            dw = Rotation.from_matrix(Tp[:3, :3] @ Tm[:3, :3].T).as_rotvec() / (2 * h)
            cols.append(np.concatenate([dp, dw]) if fixed else dp)
        J = np.array(cols).T
        rhs = np.hstack([u, np.zeros((3, 3))]) if fixed else u
        qd = np.linalg.lstsq(J, rhs.T, rcond=None)[0].T                      # (3 directions, n)
        moving = signs != 0
        assert moving.sum() >= 8
        np.testing.assert_array_equal(signs[moving], np.sign(qd[moving]))


def _one_gear(robot, joint: str, b: float):
    """``robot`` whose only part is a gear with lost motion ``b`` [rad] on ``joint`` (motor-side encoder)."""
    comps = replace(robot.components, joints={joint: JointComponents(reducer=Reducer(ratio=100.0, lost_motion=b))},
                    slots={})
    out = copy.copy(robot)
    object.__setattr__(out, "components", comps)
    return out


def test_lost_motion_offset_between_two_approaches_is_that_of_the_forward_kinematics():
    """One gear with 1 arcmin of lost motion: the mean of each pair's barycentre difference is the tool move between
    the two trailing flanks, fk(q - dir_h b/2) - fk(q - dir_k b/2), from the forward kinematics."""
    robot, test = ur10_test()
    joint, j, b = "elbow_joint", 2, 1.0 * ARCMIN
    r = _one_gear(robot, joint, b)
    t = replace(test, robot=r)
    ev = requirement_poses(t, [VAP])
    sm = statistic_models([VAP], t, ev)[0]
    eff = parts_effects()(r, ev.q, VAP.conditions, approach=ev.approach)
    mu = sm.effect_mean(eff)                                                  # (9, 3)
    dirs = joint_directions(r, t.q_test[[0, 1, 3]], VAP.directions())         # P1, P2, P4
    expect, turn = [], []
    for v, qv in enumerate(t.q_test[[0, 1, 3]]):
        T0, p, w = r.fk_internal(qv), [], []
        for h in range(3):
            dq = np.zeros(r.n_joints)
            dq[j] = -dirs[v, h, j] * b / 2
            T = r.fk_internal(qv + dq)
            p.append(T[:3, 3])
            w.append(Rotation.from_matrix(T[:3, :3] @ T0[:3, :3].T).as_rotvec())
        expect += [p[0] - p[1], p[0] - p[2], p[1] - p[2]]
        turn += [w[0] - w[1], w[0] - w[2], w[1] - w[2]]
    np.testing.assert_allclose(mu, expect, atol=2e-6 * np.abs(expect).max())
    assert np.abs(expect).max() > 0.05                                        # a tenth of a millimetre, not a zero
    angles = statistic_models([VAP_ANGLES], t, ev)                            # vAP_a, vAP_b, vAP_c: the rotation
    mu_w = np.stack([sm_a.effect_mean(eff)[:, 0] for sm_a in angles], axis=1)
    np.testing.assert_allclose(mu_w, turn, atol=1e-3 * np.abs(turn).max())
    G = sm.systematic_map(build_error_model(r).jacobian(ev.q))
    assert np.abs(G).max() < 1e-9                                             # what a robot keeps cancels


@pytest.mark.slow
def test_prediction_agrees_with_the_simulated_test_with_and_without_parts():
    """The UR10 with its catalogue parts (harmonic drives' lost motion, encoders ...) and without them (the error
    model's random parts alone): the predicted vAP_P at each pair's share inside the simulated test's 95 %
    interval (2 % slack), and the share of robots meeting the limit within 0.02."""
    robot, test = ur10_test()
    r = _catalogue(robot)
    t = replace(test, robot=r)
    model = build_error_model(r)
    split = split_errors(model)
    for fx, limit, angle in ((None, 0.006, 0.001), (parts_effects(), 0.3, 0.025)):
        reqs = [replace(VAP, limit_mm=limit), replace(VAP_ANGLES, limit_deg=angle)]
        pred = predict_acceptance(t, reqs, model, split, effects=fx).to_frame().set_index(["statistic", "where"])
        sim = simulate_acceptance(t, reqs, model, split, effects=fx, n_robots=2000, seed=2).to_frame().set_index(
            ["statistic", "where"])
        assert list(pred.index) == list(sim.index) and len(pred) == 4 * 9
        for w in pred.index:
            got = pred.loc[w, "robot_mm"] if w[0] == "vAP_P" else pred.loc[w, "robot_deg"]
            lo, hi = sim.loc[w, "robot_low"], sim.loc[w, "robot_high"]
            assert 0.98 * lo <= got <= 1.02 * hi, (w, got, lo, hi)
            assert abs(pred.loc[w, "p_meets"] - sim.loc[w, "p_meets"]) < 0.02, w
    assert pred["robot_mm"].max() > 0.1 and pred["robot_deg"].max() > 0.02   # the lost motion shows
    # each pair is held to 1 - (1 - share) / 3 so that a pose's largest pair meets the share: the table says so
    assert pred["target"].to_numpy() == pytest.approx(1 - (1 - pred["share"].to_numpy()) / 3)


def test_requirement_file_and_bad_input():
    text = """
[[requirement]]
kind = "multidirectional_accuracy"
limit_um = 200
poses = [1, 3]
approach = ["+x", "-y", "+z"]
"""
    req = parse_requirements(tomllib.loads(text)).requirements[0]
    assert isinstance(req, MultiDirectionalAccuracy)
    assert (req.limit_mm, req.poses, req.approach) == (0.2, (1, 3), ("+x", "-y", "+z"))
    assert req.to_dict()["approach"] == ["+x", "-y", "+z"]
    with pytest.raises(TolallocError, match="approach.*mutually orthogonal"):
        MultiDirectionalAccuracy(limit_mm=0.1, approach=("-x", "+x", "-z"))
    with pytest.raises(TolallocError, match="poses.*1-5"):
        MultiDirectionalAccuracy(limit_mm=0.1, poses=(1, 6))
    angles = parse_requirements(tomllib.loads(text.replace("accuracy", "orientation").replace(
        "limit_um = 200", "limit_arcsec = 36"))).requirements[0]
    assert isinstance(angles, MultiDirectionalOrientation) and angles.limit_deg == pytest.approx(0.01)
    robot, test = ur10_test()
    r = _one_gear(robot, "elbow_joint", ARCMIN)
    t = replace(test, robot=r)

    def old_style(robot, q, conditions):                                     # an effects callable of before
        return None

    with pytest.raises(TolallocError, match="approach directions"):
        predict_acceptance(t, [VAP], build_error_model(r), effects=old_style)
    with pytest.raises(TolallocError, match="one test approaches each pose one way"):
        predict_acceptance(t, [VAP, replace(VAP_ANGLES, poses=(1, 2))], build_error_model(r))
    three = acceptance_test_at(r, t.q_test[:3])                              # a test at three given poses
    with pytest.raises(TolallocError, match=r"poses \[1, 2, 4\] but the test has 3 test poses"):
        predict_acceptance(three, [VAP], build_error_model(r))


def test_allocation_meets_it_or_names_the_lost_motion():
    """The UR10 with its catalogue parts: a vAP limit above the lost motion's offset is met by the allocated design,
    predicted and in the simulated test; one below the offset is refused, naming the lost motion."""
    robot = tolalloc.load_robot("ur10")
    choice = {k: s.options[0].name for k, s in robot.components.slots.items()}
    res = tolalloc.allocate_acceptance("ur10", [PoseAccuracy(limit_mm=1.0), MultiDirectionalAccuracy(limit_mm=0.8)],
                                       parts=choice, n_robots=400)
    assert res.prediction.met, res.text()
    vap = [s for s in res.prediction.statistics if s.model.name == "vAP_P"][0]
    assert vap.robot.max() <= 0.8 and vap.robot.max() > 0.2
    sim = res.simulation.to_frame()
    assert (sim.loc[sim.statistic == "vAP_P", "p_meets"] >= 0.95).all()
    assert "vAP_P <= 0.8 mm" in res.text() and "vAP_P 1.000" in res.text()
    assert "static compliance at P1" in res.text()                            # the parts' stiffness, at P1
    stiff = res.summary()["static_compliance_mm_per_N"]
    np.testing.assert_allclose(list(stiff.values()), res.compliance.compliance_mm_per_n)
    np.testing.assert_array_equal(res.compliance.q, res.test.q_test[0])
    ax = res.plot_acceptance()                                                # the pairs named on the figure
    assert [t.get_text() for t in ax[1].get_xticklabels()][:2] == ["P1 -x/-y", "P1 -x/-z"]
    import matplotlib.pyplot as plt
    plt.close(ax[0].figure)
    with pytest.raises(TolallocError, match="lost motion"):
        tolalloc.allocate_acceptance("ur10", [PoseAccuracy(limit_mm=1.0), MultiDirectionalAccuracy(limit_mm=0.15)],
                                     parts=choice, verification=False)
