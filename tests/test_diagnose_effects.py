"""Effect bases against independent computations (exact forward kinematics, closed forms)."""

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose.effects import effect_basis, joint_effect_dq, point_jacobian, target_points
from tolalloc.physics.loads import gravity_torques
from tolalloc.diagnose.measurements import Measurements
from tolalloc.errormodel import build_error_model
from tolalloc.robot.kinematics import fk_poe


def _meas(robot, P=15, seed=0):
    rng = np.random.default_rng(seed)
    lo, hi = np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi)
    q = rng.uniform(lo, hi, (P, robot.n_joints))
    return Measurements(q, np.zeros((P, 3)), 20 + rng.uniform(0, 5, P), rng.choice([-1.0, 1.0], (P, robot.n_joints)))


@pytest.mark.parametrize("effect", ["joint_compliance", "backlash", "transmission"])
def test_joint_effects_match_exact_fk(effect):
    robot = tolalloc.load_robot("ur10")
    m = _meas(robot)
    t = np.array([20.0, -40.0, 90.0])
    basis = effect_basis(effect, robot, m, t, {"temperature_c": 20.0})
    A, _ = joint_effect_dq(effect, robot, m.q, m.direction)
    beta = np.random.default_rng(1).normal(size=A.shape[-1])
    beta *= 1e-6 / np.abs(A @ beta).max()
    dq = A @ beta
    exact = target_points(robot, m.q + dq, t) - target_points(robot, m.q, t)
    np.testing.assert_allclose(basis.B @ beta, exact, atol=1e-8)  # first order: O(dq^2 L) remainder


def test_gravity_torque_closed_form():
    robot = tolalloc.load_robot("tool_changer")
    q = np.array([[0.3, 0.0, 0.0, 100.0, 0.0, 0.0]])
    tau = gravity_torques(robot, q)[0]
    assert abs(tau[0]) < 1e-9  # vertical base axis carries no gravity torque
    # j2 (axis x at z=525) with everything horizontal: sum m g * (y-distance of each mass from the axis) [N m]
    exp = sum(m.mass_kg * 9.81 * (m.com_mm[1] + (100.0 if m.body > 3 else 0.0)) for m in robot.masses) / 1000
    # torque about +x of a weight -z at +y is (y e_y) x (-m g e_z) = -m g y e_x
    assert tau[1] == pytest.approx(-exp, rel=1e-9)
    # the prismatic joint along y carries no axial gravity force when horizontal
    assert abs(tau[3]) < 1e-9


def test_thermal_matches_exact_link_growth():
    robot = tolalloc.load_robot("tool_changer")
    m = _meas(robot)
    t = np.array([0.0, 50.0, 30.0])
    basis = effect_basis("thermal", robot, m, t, {"temperature_c": 22.0})
    alpha = 23.0  # 1e-6/K
    model = build_error_model(robot, "generic")
    vals = np.zeros((m.n_poses, len(model.params)))
    for k, p in enumerate(model.params):
        if p.kind == "link_length":
            L = next(lk.length_mm for lk in robot.links if lk.name == p.element)
            vals[:, k] = alpha * 1e-6 * (m.temperature_c - 22.0) * L
    s, h, dq = model.perturbed_chain(vals)
    T = fk_poe(s, h, m.q + dq)
    exact = T[:, :3, 3] + T[:, :3, :3] @ t - target_points(robot, m.q, t)
    np.testing.assert_allclose(basis.B[:, :, 0] * alpha, exact, atol=1e-9)


def test_link_deflection_cantilever():
    robot = tolalloc.load_robot("tool_changer")
    q = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    m = Measurements(q, np.zeros((1, 3)))
    basis = effect_basis("link_deflection", robot, m, np.zeros(3), {})
    # segment j2 -> j3 is horizontal, 796 mm: tip drop k h^3 plus slope 1.5 k h^2 times the 965 mm beyond it
    h, beyond = 0.796, 1761.0 - 796.0
    col = basis.B[0, :, 0]
    np.testing.assert_allclose(col, [0, 0, -(h ** 3 + 1.5e-3 * h ** 2 * beyond)], atol=1e-12)
    # the telescopic segment j3 -> j5 (560 + 240 mm at zero stroke), then 165 mm to the flange
    h2 = 0.8
    np.testing.assert_allclose(basis.B[0, :, 1], [0, 0, -(h2 ** 3 + 1.5e-3 * h2 ** 2 * 165.0)], atol=1e-12)
    assert basis.B.shape[-1] == 2  # the vertical base segment and the short wrist segment are not candidates


def test_point_jacobian_fd():
    robot = tolalloc.load_robot("tool_changer")
    m = _meas(robot, 4)
    t = np.array([10.0, 20.0, 30.0])
    J = point_jacobian(robot, m.q, target_points(robot, m.q, t))
    h = 1e-6
    for j in range(6):
        e = np.zeros(6)
        e[j] = h
        fd = (target_points(robot, m.q + e, t) - target_points(robot, m.q - e, t)) / (2 * h)
        np.testing.assert_allclose(J[:, :, j], fd, atol=1e-5)
