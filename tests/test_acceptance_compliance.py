"""ISO 9283 static compliance predicted from the bought parts (tolalloc.acceptance.static_load): one linear gear
against the closed form through a finite-difference Jacobian, a hardening gear's curve and its gravity preload, the
mount's linearity, and the refusals."""

import copy
from dataclasses import replace

import numpy as np
import pytest

import tolalloc
from tolalloc.acceptance import static_compliance
from tolalloc.acceptance.static_load import LOAD_DIRECTIONS
from tolalloc.errormodel.parts import with_parts
from tolalloc.exceptions import TolallocError
from tolalloc.physics.compliance import joint_loads
from tolalloc.robot.components import JointComponents, Mount, Reducer

Q = np.deg2rad([10.0, -60.0, 80.0, -100.0, -90.0, 20.0])


def _ur10(joints=None, mount=None, rated_kg=10.0):
    """The UR10 whose only parts are ``joints`` ({name: JointComponents}) and ``mount``."""
    robot = tolalloc.load_robot("ur10")
    comps = replace(robot.components, joints=dict(joints or {}), mount=mount or Mount(), slots={}, links={},
                    payload=replace(robot.components.payload, rated_kg=rated_kg))
    out = copy.copy(robot)
    object.__setattr__(out, "components", comps)
    return out


def _column(robot, j: int, h: float = 1e-7) -> np.ndarray:
    """The tool point's move per radian of joint ``j`` [mm/rad], central differences of the forward kinematics."""
    dq = np.zeros(robot.n_joints)
    dq[j] = h
    return (robot.fk_internal(Q + dq)[:3, 3] - robot.fk_internal(Q - dq)[:3, 3]) / (2 * h)


def test_one_linear_gear_is_the_closed_form():
    """Elbow gear of stiffness K alone: a force F at the tool twists it by (c . F) / K (c in m/rad), the tool moves
    by c times that, in every direction and at every step; the displacement is linear in the load."""
    K = 5.0e4                                                                  # N m/rad
    r = _ur10({"elbow_joint": JointComponents(reducer=Reducer(ratio=100.0, stiffness=(K,)))})
    sc = static_compliance(r, Q, load_n=100.0, steps=4)
    c = _column(r, 2)
    for d, name in enumerate(LOAD_DIRECTIONS):
        axis = np.zeros(3)
        axis["xyz".index(name[1])] = 1.0 if name[0] == "+" else -1.0
        for s, load in enumerate(sc.loads_n):
            expect = c * (1e-3 * c @ (load * axis)) / K
            np.testing.assert_allclose(sc.displacement_mm[d, s], expect, atol=1e-6 * np.abs(c).max() ** 2 / K)
    np.testing.assert_allclose(sc.loads_n, [25, 50, 75, 100])
    per_n = 1e-3 * np.linalg.norm(c) * np.abs(np.repeat(c, 2)) / K            # |c| |c . e| / K per direction
    np.testing.assert_allclose(sc.compliance_mm_per_n, per_n, rtol=1e-6)
    frame = sc.to_frame()
    assert len(frame) == 24 and np.allclose(frame["compliance_pct"], 100.0)


def test_a_hardening_gear_is_stiffer_once_the_arm_weight_preloads_it():
    """K1 < K2 < K3 over torque bands: the displacement is the curve's wind-up at the gravity load plus the test load
    less that at the gravity load alone (the indicator zeroed at the unloaded pose), so the two senses of one axis
    differ, and each is below what the softest band K1 gives."""
    red = Reducer(ratio=100.0, stiffness=(2.0e4, 4.0e4, 6.0e4), torque_bands=(30.0, 120.0))
    r = _ur10({"elbow_joint": JointComponents(reducer=red)})
    sc = static_compliance(r, Q, load_n=150.0, steps=3)
    c = _column(r, 2)
    tau_g = joint_loads(r, Q[None])[0][0, 2]
    for d, name in enumerate(LOAD_DIRECTIONS):
        axis = np.zeros(3)
        axis["xyz".index(name[1])] = 1.0 if name[0] == "+" else -1.0
        tau = 1e-3 * c @ (sc.loads_n[-1] * axis)
        expect = c * (red.deflection(tau_g + tau) - red.deflection(tau_g))
        np.testing.assert_allclose(sc.displacement_mm[d, -1], expect, atol=1e-9)
    up, down = (np.linalg.norm(sc.displacement_mm[LOAD_DIRECTIONS.index(k), -1]) for k in ("+z", "-z"))
    assert abs(up - down) > 0.02 * max(up, down)
    soft = static_compliance(_ur10({"elbow_joint": JointComponents(reducer=Reducer(ratio=100.0,
                                                                                    stiffness=(2.0e4,)))}), Q,
                             load_n=150.0, steps=3)
    assert np.all(sc.compliance_mm_per_n <= soft.compliance_mm_per_n * (1 + 1e-9))


def test_mount_alone_is_linear_and_the_catalogue_robot_names_its_sources():
    r = _ur10(mount=Mount(tilt_stiffness=(2.0e6, 2.0e6)))
    sc = static_compliance(r, Q, load_n=100.0, steps=5)
    assert np.abs(sc.displacement_mm).max() > 1e-3
    np.testing.assert_allclose(sc.displacement_mm, sc.displacement_mm[:, :1] * np.arange(1, 6)[None, :, None],
                               atol=1e-9)
    robot = tolalloc.load_robot("ur10")
    full = static_compliance(with_parts(robot, {k: s.options[0].name for k, s in robot.components.slots.items()}), Q)
    assert full.loads_n[-1] == pytest.approx(robot.components.payload.rated_kg * 9.80665)
    assert "um/N" in full.text() and len(full.text().splitlines()) == 7


def test_a_joint_bearing_tilts_by_the_moment_across_its_axis():
    """Only the base joint's bearing, moment stiffness K: a force F at the mechanical interface p turns the arm
    about the joint point o by ((p - o) x F)_perp / K (the part across the vertical axis), which moves p by that
    rotation x (p - o); linear in the load, and filed under compliance."""
    from tolalloc.robot.components import Bearing

    K = 2.0e6
    r = _ur10({"shoulder_pan_joint": JointComponents(bearing=Bearing("P5", 60.0, None, K, "", 90.0, 0.005))})
    sc = static_compliance(r, Q, load_n=100.0, steps=2)
    T = r.fk_internal(Q)
    p = T[:3, 3]
    o, w = r.joint_points_mm[0], r.joints[0].axis          # the base joint does not move with the pose
    for d, name in enumerate(LOAD_DIRECTIONS):
        F = np.zeros(3)
        F["xyz".index(name[1])] = 100.0 if name[0] == "+" else -100.0
        M = np.cross((p - o) / 1000.0, F)
        expect = np.cross((M - (M @ w) * w) / K, p - o)
        np.testing.assert_allclose(sc.by_effect_mm["compliance"][d, -1], expect, atol=1e-12)
        np.testing.assert_allclose(sc.displacement_mm[d, -1], expect, atol=1e-12)
    np.testing.assert_allclose(sc.displacement_mm[:, 0], sc.displacement_mm[:, 1] / 2, atol=1e-12)


def test_refusals():
    r = _ur10(rated_kg=None)
    with pytest.raises(TolallocError, match="rated payload"):
        static_compliance(r, Q)
    with pytest.raises(TolallocError, match="load > 0"):
        static_compliance(r, Q, load_n=-5.0)
    with pytest.raises(TolallocError, match="load steps"):
        static_compliance(r, Q, load_n=10.0, steps=0)
    with pytest.raises(TolallocError, match="one pose"):
        static_compliance(r, np.stack([Q, Q]), load_n=10.0)
    robot = tolalloc.load_robot("ur10")
    with pytest.raises(TolallocError, match="no chosen part"):
        static_compliance(robot, Q, load_n=10.0)
