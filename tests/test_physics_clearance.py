"""Joint bearing clearance taken up by the gravity load (:mod:`tolalloc.physics.clearance`) and the mount's rocking
(``play`` of :func:`tolalloc.physics.compliance.mount_columns`).

The loads are checked against the joint torques of :func:`~tolalloc.physics.loads.gravity_torques` and a hand
computation; the displaced points are made by exact rigid motions (``scipy.spatial.transform.Rotation`` about the
joint's point), never from the basis.
"""

import numpy as np
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.effects import target_points, variants
from tolalloc.diagnose.measurements import Measurements
from tolalloc.physics.clearance import clearance_columns
from tolalloc.physics.loads import joint_wrenches
from tolalloc.physics.compliance import mount_columns
from tolalloc.physics.loads import G, base_moment, gravity_torques
from tolalloc.robot.model import Joint, Link, Mass, Robot

T_MM = np.array([0.0, 0.0, 100.0])


def _q(robot, P, seed):
    rng = np.random.default_rng(seed)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    return rng.uniform(lo, hi, (P, robot.n_joints))


def test_the_moment_about_each_axis_is_the_joint_torque():
    """The wrench through every joint, projected on its axis, is the gravity load the compliance model uses (a
    prismatic joint's: the force along it), with a payload at the target."""
    for name in ("ur10", "tool_changer"):
        robot = tolalloc.load_robot(name)
        q = _q(robot, 40, 1)
        tip = target_points(robot, q, T_MM)
        kg = np.linspace(0.0, 5.0, 40)
        F, M, o, w = joint_wrenches(robot, q, tip, kg)
        along = np.where(robot.revolute_mask, np.einsum("pji,pji->pj", M, w), np.einsum("pji,pji->pj", F, w))
        tau = gravity_torques(robot, q, tip, kg)
        np.testing.assert_allclose(along, tau, atol=1e-9 * np.abs(tau).max())


def _arm():
    """Joint 1 about z, a 500 mm link along x, joint 2 about x (along the link), a 10 kg mass 300 mm beyond it along
    x and 200 mm along y; the target 100 mm further along x."""
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0]), -np.pi, np.pi),
             Link("l1", np.array([500.0, 0.0, 0.0])),
             Joint("j2", "revolute", np.array([1.0, 0.0, 0.0]), -np.pi, np.pi),
             Link("l2", np.array([400.0, 0.0, 0.0])))
    masses = (Mass("m2", 2, 10.0, np.array([800.0, 200.0, 0.0])),)
    return Robot("arm", chain, masses=masses, trust_units=True)


def test_joint_two_carries_the_weight_and_its_moment_by_hand():
    """At j1 = 0, j2 = 0 the 10 kg mass hangs 300 mm beyond joint 2 along its axis and 200 mm across: the force
    is (0, 0, -98.1) N, the moment about joint 2's point (300, 200, 0) mm x F: (-19.62, 29.43, 0) N m, of which
    the part along the axis (x) is the torque, and the tilt moment is along y."""
    robot = _arm()
    F, M, o, w = joint_wrenches(robot, np.zeros((1, 2)))
    np.testing.assert_allclose(F[0, 1], [0.0, 0.0, -10 * G])
    np.testing.assert_allclose(M[0, 1], np.cross([0.3, 0.2, 0.0], [0.0, 0.0, -10 * G]), atol=1e-12)
    np.testing.assert_allclose(o[0, 1], [500.0, 0.0, 0.0])


def test_exact_tilt_in_the_clearance_is_spanned():
    """Joint 2's body turns by 0.4 mrad about the direction of its tilt moment through the joint's point (an exact
    rotation): the tilt column with that amplitude gives the same points to second order."""
    robot = _arm()
    q = _q(robot, 30, 2)
    p = target_points(robot, q, T_MM)
    F, M, o, w = joint_wrenches(robot, q)
    Mt = M[:, 1] - np.einsum("pi,pi->p", M[:, 1], w[:, 1])[:, None] * w[:, 1]
    axis = Mt / np.linalg.norm(Mt, axis=1, keepdims=True)
    moved = o[:, 1] + Rotation.from_rotvec(0.4e-3 * axis).apply(p - o[:, 1])
    B, names, groups = clearance_columns(robot, q, p)
    beta = np.zeros(len(names))
    beta[names.index("ct_j2 [mrad]")] = 0.4
    np.testing.assert_allclose(p + B @ beta, moved, atol=1e-6)
    assert groups[names.index("ct_j2 [mrad]")] == 3


def test_constant_sides_and_the_first_joints_tilt_get_no_column():
    """A side the load never leaves is a constant offset (the geometry's), and the first joint's tilt is the mount's
    rocking: neither gets a clearance column. Joint 2's axis stays horizontal: the weight is always radial and
    downward (no ``cr`` column), never axial (no ``ca`` column from rounding)."""
    robot = _arm()
    q = _q(robot, 30, 3)
    _, names, _ = clearance_columns(robot, q, target_points(robot, q, T_MM))
    assert not any(n.endswith("_j1 [mrad]") for n in names if n.startswith("ct"))
    assert "ca_j2 [mm]" not in names and "cr_j2 [mm]" not in names
    assert "ct_j2 [mrad]" in names


def test_mount_play_rocks_in_the_direction_of_the_moment():
    """``play``: beside the linear compliance, the rocking column is the unit horizontal gravity moment x p [mm per
    mrad], whatever the moment's size."""
    robot = tolalloc.load_robot("ur10")
    q = _q(robot, 20, 4)
    p = target_points(robot, q, T_MM)
    B, names = mount_columns(robot, q, p, p, None, "play")
    lin, _ = mount_columns(robot, q, p, p, None, "isotropic")
    assert names == ["c_mount [rad/(N m)]", "r_mount [mrad]"]
    np.testing.assert_allclose(B[:, :, 0], lin[:, :, 0])
    Mh = base_moment(robot, q) * np.array([1.0, 1.0, 0.0])  # the ur10's gravity is -z
    np.testing.assert_allclose(B[:, :, 1], 1e-3 * np.cross(Mh / np.linalg.norm(Mh, axis=1, keepdims=True), p),
                               atol=1e-12)


def test_clearance_is_a_backlash_variant_and_play_a_mount_variant():
    robot = tolalloc.load_robot("ur10")
    meas = Measurements(_q(robot, 10, 5), np.zeros((10, 3)), None, None, None, None)
    assert "clearance" in variants("backlash", meas, robot=robot)
    assert "play" in variants("mount_compliance", meas, robot=robot)


def test_a_wrist_bearing_with_tilt_play_is_named_backlash_clearance():
    """The UR10's wrist 2 bearing tilts 0.5 mrad and wrist 1's 0.3 mrad in the direction of their tilt moments
    (a 3 kg tool), exact rotations: the diagnosis names backlash in the ``clearance`` variant."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("ur10")
    P = 100
    q = _q(robot, P, 6)
    kg = np.full(P, 3.0)
    p = target_points(robot, q, T_MM)
    F, M, o, w = joint_wrenches(robot, q, p, kg)
    xyz = p.copy()
    for j, tilt_mrad in ((3, 0.3), (4, 0.5)):
        Mt = M[:, j] - np.einsum("pi,pi->p", M[:, j], w[:, j])[:, None] * w[:, j]
        axis = Mt / np.linalg.norm(Mt, axis=1, keepdims=True)
        xyz = o[:, j] + Rotation.from_rotvec(tilt_mrad * 1e-3 * axis).apply(xyz - o[:, j])
    xyz = xyz + np.random.default_rng(6).normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, kg, None), folds=3, max_effects=1)
    assert d.effect == "backlash", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "backlash") == "clearance"
    # the identified model, written to its file and read back, predicts alike at new poses (with the same tool)
    import json

    from tolalloc.diagnose.model_export import identified_section, model_from_identified
    from tolalloc.diagnose.model_use import identified_model

    m = identified_model(d)
    back = model_from_identified(json.loads(json.dumps(identified_section(m))), robot)
    q_new = _q(robot, 20, 7)
    a, b = (x.points(x.measurements(q_new, payload_kg=3.0), "tracker") for x in (m, back))
    np.testing.assert_allclose(b, a, atol=1e-9)
