"""POE robot model: closed-form pose of the tool_changer, Pinocchio oracle on random chains, batching."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import (pin_jacobian_to_ours, pinocchio_model, random_chain, random_q, to_pin_q, twist_fd)

import tolalloc
from tolalloc import Joint, Link, Robot, TolallocError, load_robot
from tolalloc.robot.lie import exp_se3, rot_z
from tolalloc.robot.kinematics import body_jacobian, fk_poe, poe_prefix, space_jacobian

L = dict(l1=315.0, l2=210.0, l3=796.0, l4=560.0, l5=240.0, l6=165.0)


def closed_form_tool_changer():
    """NOTES_SEED.md: rho = l3 cos30 + (l4+l5) cos20 + l6, p = (-rho sin15, rho cos15, l1+l2+l3 sin30+(l4+l5) sin20)."""
    d = np.deg2rad
    rho = L["l3"] * np.cos(d(30)) + (L["l4"] + L["l5"]) * np.cos(d(20)) + L["l6"]
    p = np.array([-rho * np.sin(d(15)), rho * np.cos(d(15)),
                  L["l1"] + L["l2"] + L["l3"] * np.sin(d(30)) + (L["l4"] + L["l5"]) * np.sin(d(20))])
    return p, rot_z(d(10))


def test_tool_changer_nominal_pose_closed_form():
    robot = load_robot("tool_changer")
    np.testing.assert_allclose(robot.q_to_interface(robot.q_nominal), [15, 30, -10, 0, -20, -5], atol=1e-12)
    T = robot.fk_internal(robot.q_nominal)
    p, R = closed_form_tool_changer()
    np.testing.assert_allclose(p, [-415.692, 1551.383, 1196.616], atol=1e-3)
    assert np.linalg.norm(T[:3, 3] - p) <= 1e-9 * np.linalg.norm(p)
    assert np.max(np.abs(T[:3, :3] - R)) <= 1e-9
    np.testing.assert_array_equal(T[3], [0, 0, 0, 1])


def test_tool_changer_geometry_matches_notes():
    robot = load_robot("tool_changer")
    l1, l2, l3, l4, l5, l6 = L.values()
    np.testing.assert_allclose(robot.home[:3, 3], [0, l3 + l4 + l5 + l6, l1 + l2])
    np.testing.assert_allclose(robot.home[:3, :3], np.eye(3))
    pts = robot.joint_points_mm
    np.testing.assert_allclose(pts[[0, 1, 2, 4, 5]], [[0, 0, l1], [0, 0, l1 + l2], [0, l3, l1 + l2],
                                                     [0, l3 + l4 + l5, l1 + l2], [0, l3 + l4 + l5 + l6, l1 + l2]])
    axes = [j.axis for j in robot.joints]
    np.testing.assert_allclose(axes, [[0, 0, 1], [1, 0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0], [0, 0, 1]])
    assert [j.kind for j in robot.joints] == ["revolute"] * 3 + ["prismatic"] + ["revolute"] * 2
    np.testing.assert_allclose(robot.screws[3], [0, 0, 0, 0, 1, 0])
    # revolute screw: v = -w x p
    for j in (0, 1, 2, 4, 5):
        np.testing.assert_allclose(robot.screws[j, 3:], -np.cross(robot.screws[j, :3], pts[j]), atol=1e-12)
    assert [lk.name for lk in robot.links] == list(L)
    np.testing.assert_array_equal(robot.link_sites, [0, 1, 2, 3, 4, 5])


def test_tool_changer_prismatic_moves_along_arm():
    robot = load_robot("tool_changer")
    q = robot.q_nominal.copy()
    T0 = robot.fk_internal(q)
    q[3] = 100.0
    T1 = robot.fk_internal(q)
    d = np.deg2rad
    # arm direction after j1 (15 deg about z) and j2+j3 (20 deg about x)
    u = np.array([-np.sin(d(15)) * np.cos(d(20)), np.cos(d(15)) * np.cos(d(20)), np.sin(d(20))])
    np.testing.assert_allclose(T1[:3, 3] - T0[:3, 3], 100.0 * u, atol=1e-9)


@pytest.mark.parametrize("seed", range(60))
def test_fk_and_jacobians_match_pinocchio(seed):
    """60 random chains of 2-8 joints, 3 random configurations each, to 1e-9 (relative to scale)."""
    import pinocchio as pin

    rng = np.random.default_rng(1000 + seed)
    n = int(rng.integers(2, 9))
    robot = random_chain(rng, n)
    model, fid = pinocchio_model(robot, rng if seed % 2 else None)
    data = model.createData()
    for q in random_q(rng, robot, 3):
        qp = to_pin_q(robot, q)
        pin.computeJointJacobians(model, data, qp)
        pin.updateFramePlacements(model, data)
        oMf = data.oMf[fid]
        T = robot.fk_internal(q)
        scale = max(1.0, np.linalg.norm(T[:3, 3]))
        assert np.max(np.abs(T[:3, 3] - 1000.0 * oMf.translation)) <= 1e-9 * scale
        assert np.max(np.abs(T[:3, :3] - oMf.rotation)) <= 1e-9
        Js_pin = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.WORLD)
        Jb_pin = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL)
        Js, Jb = robot.space_jacobian_internal(q), robot.body_jacobian_internal(q)
        jscale = max(1.0, np.max(np.abs(Js)))
        assert np.max(np.abs(Js - pin_jacobian_to_ours(robot, Js_pin))) <= 1e-9 * jscale
        assert np.max(np.abs(Jb - pin_jacobian_to_ours(robot, Jb_pin))) <= 1e-9 * max(1.0, np.max(np.abs(Jb)))


@pytest.mark.parametrize("seed", range(5))
def test_jacobians_match_finite_differences(seed):
    rng = np.random.default_rng(seed)
    robot = random_chain(rng, int(rng.integers(2, 9)))
    q = random_q(rng, robot)
    for frame, J in (("space", robot.space_jacobian_internal(q)), ("body", robot.body_jacobian_internal(q))):
        Jfd = twist_fd(robot.fk_internal, q, frame=frame)
        np.testing.assert_allclose(J, Jfd, atol=1e-5 * max(1.0, np.max(np.abs(J))))


def test_batched_fk_equals_loop():
    rng = np.random.default_rng(3)
    robot = random_chain(rng, 6)
    Q = random_q(rng, robot, 7)
    T = robot.fk_internal(Q)
    assert T.shape == (7, 4, 4)
    for i in range(7):
        np.testing.assert_allclose(T[i], robot.fk_internal(Q[i]), atol=1e-12)
    Js, Jb = robot.space_jacobian_internal(Q), robot.body_jacobian_internal(Q)
    assert Js.shape == Jb.shape == (7, 6, 6)
    for i in range(7):
        np.testing.assert_allclose(Js[i], robot.space_jacobian_internal(Q[i]), atol=1e-10)
        np.testing.assert_allclose(Jb[i], robot.body_jacobian_internal(Q[i]), atol=1e-10)
    # 2-D batch
    T2 = robot.fk_internal(Q.reshape(7, 1, 6))
    np.testing.assert_allclose(T2[:, 0], T, atol=1e-12)


def test_batched_perturbed_chains():
    """N chains with per-sample screws and home poses, at one or N configurations."""
    rng = np.random.default_rng(4)
    robots = [random_chain(rng, 5) for _ in range(4)]
    screws = np.stack([r.screws for r in robots])
    homes = np.stack([r.home for r in robots])
    q = random_q(rng, robots[0])
    T = fk_poe(screws, homes, q)
    Q = random_q(rng, robots[0], 4)
    TQ = fk_poe(screws, homes, Q)
    Js = space_jacobian(screws, Q)
    Jb = body_jacobian(screws, homes, Q)
    for i, r in enumerate(robots):
        # random_chain draws prismatic joints at random: q is valid for any chain since limits are wide
        np.testing.assert_allclose(T[i], r.fk_internal(q), atol=1e-10)
        np.testing.assert_allclose(TQ[i], r.fk_internal(Q[i]), atol=1e-10)
        np.testing.assert_allclose(Js[i], r.space_jacobian_internal(Q[i]), atol=1e-10)
        np.testing.assert_allclose(Jb[i], r.body_jacobian_internal(Q[i]), atol=1e-10)


def test_poe_prefix():
    rng = np.random.default_rng(5)
    robot = random_chain(rng, 4)
    q = random_q(rng, robot)
    P = poe_prefix(robot.screws, q)
    assert P.shape == (5, 4, 4)
    np.testing.assert_allclose(P[0], np.eye(4))
    expected = np.eye(4)
    for j in range(4):
        expected = expected @ exp_se3(robot.screws[j] * q[j])
        np.testing.assert_allclose(P[j + 1], expected, atol=1e-12)
    np.testing.assert_allclose(P[-1] @ robot.home, robot.fk_internal(q), atol=1e-12)


def test_interface_units_roundtrip():
    robot = load_robot("tool_changer")
    q_if = np.array([15, 30, -10, 120, -20, -5.0])
    q = robot.q_from_interface(q_if)
    np.testing.assert_allclose(q[[0, 1, 2, 4, 5]], np.deg2rad(q_if[[0, 1, 2, 4, 5]]))
    assert q[3] == 120.0
    np.testing.assert_allclose(robot.q_to_interface(q), q_if)
    assert [j.unit for j in robot.joints] == ["deg"] * 3 + ["mm"] + ["deg"] * 2


def test_radians_hint_names_q_to_interface_for_a_robot_with_a_slide():
    """Internal values (rad, mm) given to fk are refused with the conversion that keeps the slide in mm; the hint
    names numpy.degrees only for an all-revolute robot."""
    robot = load_robot("tool_changer")
    slide_5mm = robot.q_from_interface([15, 30, -10, 5, -20, -5])
    for q in (robot.poses("working"), robot.q_nominal, robot.random_q(np.random.default_rng(0), 3), slide_5mm):
        with pytest.raises(TolallocError, match=r"look like radians; expected degrees for the revolute joints and mm "
                                                r"for the prismatic q4: convert with robot\.q_to_interface\(q\)") as info:
            robot.fk(q)
        assert "numpy.degrees would also multiply q4 by 57.3" in str(info.value)
        np.testing.assert_allclose(robot.fk(robot.q_to_interface(q)), robot.fk_internal(q), atol=1e-9)
    slip = robot.fk(np.degrees(slide_5mm))[:3, 3] - robot.fk(robot.q_to_interface(slide_5mm))[:3, 3]
    assert np.linalg.norm(slip) == pytest.approx(np.degrees(5) - 5)  # numpy.degrees moves the slide 5 -> 286 mm
    ur10 = load_robot("ur10")
    with pytest.raises(TolallocError, match=r"look like radians; expected degrees: convert with numpy\.degrees or "
                                            r"robot\.q_to_interface\(q\)"):
        ur10.fk(ur10.random_q(np.random.default_rng(1), 2))

def test_check_q_count_limits_and_finiteness():
    robot = load_robot("tool_changer")
    np.testing.assert_allclose(robot.check_q([15, 30, -10, 0, -20, -5], interface=True), robot.q_nominal)
    with pytest.raises(TolallocError, match=r"has 6 joints .*expected 6 values \(deg, deg, deg, mm, deg, deg\), got 5"):
        robot.check_q([1, 2, 3, 4, 5], interface=True)
    with pytest.raises(TolallocError, match=r"expected 6 values \(rad, rad, rad, mm, rad, rad\), got 5"):
        robot.check_q([1, 2, 3, 4, 5])  # internal units: the message names them
    with pytest.raises(TolallocError, match=r"joint j4 = 600 mm is outside its limits \[0, 500\] mm"):
        robot.check_q([15, 30, -10, 600, -20, -5], interface=True)
    with pytest.raises(TolallocError, match=r"\(pose 2\): joint j2 = 70 deg is outside its limits \[-10, 60\] deg"):
        robot.check_q([[15, 30, -10, 0, -20, -5], [15, 70, -10, 0, -20, -5]], interface=True)
    with pytest.raises(TolallocError, match="expected finite numbers"):
        robot.check_q([15, np.nan, -10, 0, -20, -5], interface=True)
    with pytest.raises(TolallocError, match="expected finite numbers"):
        robot.check_q([15, np.inf, -10, 0, -20, -5], interface=True)


def test_pose_sets():
    robot = load_robot("tool_changer")
    np.testing.assert_allclose(robot.poses(), robot.q_nominal[None])
    W = robot.poses("working")
    assert W.shape[1] == 6 and W.shape[0] >= 5
    assert np.all(W >= robot.lower - 1e-12) and np.all(W <= robot.upper + 1e-12)
    with pytest.raises(TolallocError, match="pose set 'nope' is not defined .* known sets: nominal, working"):
        robot.poses("nope")


@pytest.mark.parametrize("axis,match", [
    ([0, 0, 0], "not a finite unit"),
    ([0, np.nan, 1], "not a finite unit"),
    ([0, 0, 2], "not a finite unit"),
    ([0, 1], "not a finite unit"),
])
def test_robot_rejects_bad_axes(axis, match):
    with pytest.raises(TolallocError, match=match):
        Robot("r", (Link("l1", np.array([0, 0, 100.0])), Joint("j1", "revolute", np.array(axis, float))))


def test_robot_rejects_bad_structure():
    with pytest.raises(TolallocError, match="has no joint"):
        Robot("r", (Link("l1", np.array([0, 0, 100.0])),))
    with pytest.raises(TolallocError, match=r"duplicate element names \['a'\]"):
        Robot("r", (Link("a", np.ones(3)), Joint("a", "revolute", np.array([0, 0, 1.0]))))
    with pytest.raises(TolallocError, match="kind 'spherical'"):
        Robot("r", (Joint("j", "spherical", np.array([0, 0, 1.0])),))


def test_link_properties_and_readonly():
    link = Link("l", np.array([3.0, 4.0, 0.0]))
    assert link.length_mm == 5.0
    np.testing.assert_allclose(link.direction, [0.6, 0.8, 0])
    np.testing.assert_array_equal(Link("z", np.zeros(3)).direction, np.zeros(3))
    robot = load_robot("tool_changer")
    with pytest.raises(ValueError):
        robot.screws[0, 0] = 1.0
    assert tolalloc.load_robot(robot) is robot


def test_check_q_non_numeric_is_a_tolalloc_error():
    # regression: a string among the joint values gave a numpy ValueError traceback
    robot = load_robot("tool_changer")
    with pytest.raises(TolallocError, match=r"joints: expected numbers \(deg, deg, deg, mm, deg, deg\)"):
        robot.check_q([15, "a", -10, 0, -20, -5], "joints", interface=True)


@pytest.mark.parametrize("q", [np.ones(6, bool), np.array(["1"] * 6), [True] * 6, np.array([1.0] * 5 + [True], object)],
                         ids=["bool_array", "str_array", "bool_list", "object_array_with_a_bool"])
def test_joint_array_refuses_bools_and_strings_of_every_container(q):
    # numeric arrays skip the value-by-value scan: a bool or string array must still be caught by its dtype
    with pytest.raises(TolallocError, match="q: expected numbers"):
        load_robot("ur10").joint_array(q)
    assert load_robot("ur10").joint_array(np.arange(6)).dtype == float


def _arm(shoulder, upper_arm=(600.0, 0.0, 0.0), base=(0.0, 0.0, 400.0), **kwargs):
    return Robot("demo_arm", (Link("base", np.array(base)), shoulder, Link("upper_arm", np.array(upper_arm))), **kwargs)


def test_robot_from_objects_refuses_degrees_and_metres_like_the_files():
    """Joint takes rad / mm and Link mm: degrees and metres are refused with the files' rule and a hint."""
    y = np.array([0.0, 1.0, 0.0])
    with pytest.raises(TolallocError, match=r"robot 'demo_arm', joint shoulder: limits \[-90, 90\] rad and nominal value "
                                            r"20 rad go beyond 2 turns .* look like degrees: convert them with "
                                            r"numpy.deg2rad, or build the joint with Joint.from_interface\(.*\) \(if the "
                                            r"values really are meant so, pass trust_units=True\)\.$"):
        _arm(Joint("shoulder", "revolute", y, -90, 90, 20))
    with pytest.raises(TolallocError, match=r"joint shoulder: .* nominal value 20 rad"):  # the nominal value alone
        _arm(Joint("shoulder", "revolute", y, -np.inf, np.inf, 20))
    ok = Joint("shoulder", "revolute", y, np.deg2rad(-90), np.deg2rad(90), np.deg2rad(20))
    with pytest.raises(TolallocError, match=r"robot 'demo_arm': the link lengths add up to 1 mm; that looks like metres: "
                                            r"Link vectors are in mm, multiply them by 1000 \(.*trust_units=True\)"):
        _arm(ok, upper_arm=(0.6, 0.0, 0.0), base=(0.0, 0.0, 0.4))
    with pytest.raises(TolallocError, match=r"link upper_arm is 0.6 mm long while link base is 400 mm; that looks like "
                                            r"a length in metres: Link vectors are in mm, multiply it by 1000"):
        _arm(ok, upper_arm=(0.6, 0.0, 0.0))
    # kept as given when meant so
    assert _arm(Joint("shoulder", "revolute", y, -90, 90, 20), trust_units=True).joints[0].upper == 90
    with tolalloc.units.trusting_units():
        assert _arm(ok, upper_arm=(0.6, 0.0, 0.0)).links[1].length_mm == 0.6
    with pytest.raises(TolallocError, match="trust_units expected True or False, got 'yes'"):
        _arm(ok, trust_units="yes")
    # a continuous joint's two turns each way (the files' default) and no limits are fine
    assert _arm(Joint("shoulder", "revolute", y, -4 * np.pi, 4 * np.pi, 0.0)).n_joints == 1
    # so is any range within two turns: +-10 read as rad (a multi-turn joint) cannot be told from +-10 deg
    assert _arm(Joint("shoulder", "revolute", y, -10, 10, 0.0)).joints[0].upper == 10
    assert _arm(Joint("shoulder", "revolute", y, -np.inf, np.inf, 0.0)).n_joints == 1


def test_joint_from_interface_takes_deg_mm():
    y = np.array([0.0, 1.0, 0.0])
    j = Joint.from_interface("shoulder", "revolute", y, -90, 90, 20)
    np.testing.assert_allclose([j.lower, j.upper, j.nominal], np.deg2rad([-90, 90, 20]))
    s = Joint.from_interface("slide", "prismatic", np.array([1.0, 0.0, 0.0]), 0, 300, 100)
    assert (s.lower, s.upper, s.nominal) == (0.0, 300.0, 100.0)
    frame = _arm(j).joints_frame()
    assert list(frame.columns[-4:]) == ["unit", "lower_deg_mm", "upper_deg_mm", "nominal_deg_mm"]
    np.testing.assert_allclose(frame.loc[0, ["lower_deg_mm", "upper_deg_mm", "nominal_deg_mm"]].to_numpy(float),
                               [-90, 90, 20])


def test_from_dh_accepts_the_trust_units_its_message_names():
    rows = [{"name": "shoulder", "d_m": 400, "a_m": 0, "alpha_deg": 90},   # millimetres under a metre key
            {"name": "elbow", "d_m": 0, "a_m": 0.6, "alpha_deg": 0}]
    with pytest.raises(TolallocError, match=r"d_m = 400.0 is 400 m; that looks like millimetres.*trust_units=True in "
                                            r"Python"):
        Robot.from_dh(rows, convention="standard")
    arm = Robot.from_dh(rows, convention="standard", trust_units=True)
    assert arm.links[0].length_mm == 400_000.0
    with pytest.raises(TolallocError, match="trust_units: expected True or False"):
        Robot.from_dh(rows, convention="standard", trust_units=1.5)


def test_kinematics_refuse_joint_values_that_do_not_match_the_screws():
    """fk_poe, the Jacobians and the prefix products name the shapes they expected when q and the screws disagree
    (they were numpy broadcasting errors); batched screws with one q still broadcast."""
    robot = load_robot("ur10")
    S, M = robot.screws, robot.home
    for call in (lambda q: fk_poe(S, M, q), lambda q: space_jacobian(S, q), lambda q: body_jacobian(S, M, q),
                 lambda q: poe_prefix(S, q), lambda q: space_jacobian(S, q, engine="numba")):
        for q in (np.zeros(5), np.zeros((3, 7)), 0.0):
            with pytest.raises(TolallocError, match=r"q: expected shape \(\.\.\., 6\) with joint screws of shape "
                                                    r"\(\.\.\., 6, 6\), got q of shape"):
                call(q)
    assert fk_poe(np.broadcast_to(S, (4, 6, 6)), M, np.zeros(6)).shape == (4, 4, 4)
    np.testing.assert_allclose(fk_poe(S, M, np.zeros((2, 6)))[1], M, atol=1e-12)
