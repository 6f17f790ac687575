"""Effect variants (issue 15 item 2) recover known parameters from data made by independent functions.

The data are never built from the basis being fitted: joint-type effects move the joints of the exact forward
kinematics (``robot.fk_internal`` at ``q + dq``), gravity torques come from finite differences of the potential energy
(not the cross-product formula of ``gravity_torques``), the thermal lag from its closed-form step response, and
the beam from the textbook cantilever formulas on hand-computed horizontal poses. Tolerances are stated per test
(first-order bases against exact kinematics: ~1e-3 relative at these amplitudes).
"""

from dataclasses import replace

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose.calibrate import fixed_jacobian, initial_fit
from tolalloc.diagnose.effects import effect_basis, effect_reference, target_points, variants
from tolalloc.physics.thermal_history import lagged
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.physics.loads import G, gravity_torques, robot_masses
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import choose_variant
from tolalloc.robot.kinematics import poe_prefix


def _q(robot, P, seed):
    rng = np.random.default_rng(seed)
    lo, hi = np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi)
    return rng.uniform(lo, hi, (P, robot.n_joints))


def _lsq(basis, d):
    return np.linalg.lstsq(basis.B.reshape(-1, basis.B.shape[-1]), d.ravel(), rcond=None)[0]


def _potential_torque(robot, q, tip_mm_fn=None, tip_kg=0.0, h=1e-6):
    """Gravity load per joint as -dV/dq by central differences of the potential energy [N m] / [N]."""
    g = np.asarray(robot.gravity, float)

    def V(qq):
        P = poe_prefix(robot.screws, qq)
        v = np.zeros(len(qq))
        for m in robot_masses(robot):
            c = P[:, m.body, :3, :3] @ m.com_mm + P[:, m.body, :3, 3]
            v -= m.mass_kg * G * (c @ g) / 1000.0
        if tip_mm_fn is not None:
            v -= tip_kg * G * (tip_mm_fn(qq) @ g) / 1000.0
        return v

    tau = np.zeros_like(q)
    for j in range(robot.n_joints):
        e = np.zeros(robot.n_joints)
        e[j] = h * (1.0 if robot.joints[j].is_revolute else 1000.0)  # prismatic: mm, force in N
        tau[:, j] = -(V(q + e) - V(q - e)) / (2 * e[j]) * (1.0 if robot.joints[j].is_revolute else 1000.0)
    return tau


@pytest.mark.parametrize("name", ["ur10", "tool_changer"])
def test_gravity_torque_with_payload_matches_potential_energy(name):
    robot = tolalloc.load_robot(name)
    q = _q(robot, 12, 3)
    t = np.array([10.0, -30.0, 80.0])
    tip = target_points(robot, q, t)
    got = gravity_torques(robot, q, tip, 2.5)
    exp = _potential_torque(robot, q, lambda qq: target_points(robot, qq, t), 2.5)
    np.testing.assert_allclose(got, exp, atol=1e-5 * np.abs(exp).max())


def test_transmission_once_per_revolution_recovered():
    robot = tolalloc.load_robot("ur10")
    q = _q(robot, 60, 1)
    t = np.array([0.0, 0.0, 100.0])
    a, b = 2e-5, -1.5e-5  # rad: joint 3 error a sin q3 + b cos q3
    dq = np.zeros_like(q)
    dq[:, 2] = a * np.sin(q[:, 2]) + b * np.cos(q[:, 2])
    d = target_points(robot, q + dq, t) - target_points(robot, q, t)
    basis = effect_basis("transmission", robot, Measurements(q, np.zeros((60, 3))), t, {}, "1x")
    beta = _lsq(basis, d)
    k = basis.names.index("s1x_elbow_joint [rad]"), basis.names.index("c1x_elbow_joint [rad]")
    np.testing.assert_allclose(beta[list(k)], [a, b], rtol=1e-3)
    assert np.abs(np.delete(beta, k)).max() < 1e-3 * abs(a)


def test_transmission_gear_orders_with_gear_ratio():
    robot = tolalloc.load_robot("ur10")
    q = _q(robot, 200, 2)
    t = np.array([0.0, 0.0, 100.0])
    N = np.array([101.0, 101.0, 101.0, 121.0, 121.0, 121.0])
    dq = np.zeros_like(q)
    dq[:, 1] = 1e-5 * np.sin(N[1] * q[:, 1])  # motor-side ripple on joint 2
    d = target_points(robot, q + dq, t) - target_points(robot, q, t)
    meas = Measurements(q, np.zeros((200, 3)))
    ref = effect_reference(meas, gear_ratio=N)
    assert "gear" in variants("transmission", meas, ref)
    basis = effect_basis("transmission", robot, meas, t, ref, "gear")
    beta = _lsq(basis, d)
    assert beta[basis.names.index("sN_shoulder_lift_joint [rad]")] == pytest.approx(1e-5, rel=1e-3)
    assert "s2N_shoulder_lift_joint [rad]" in basis.names and "s1x_shoulder_lift_joint [rad]" in basis.names


def _sampled_step(t, jump, tau, dt):
    """The lag of a log sampled every ``dt`` that reads 0 at t = 0 and ``jump`` from the next sample on: the log runs
    linearly between samples, so the jump arrives as a ramp over the first step, then the lag closes on it."""
    y_dt = jump * (1 - tau / dt * (1 - np.exp(-dt / tau)))
    return np.where(t > 0, jump - (jump - y_dt) * np.exp(-(t - dt) / tau), 0.0)


def test_lag_filter_step_response_closed_form():
    t = np.arange(0.0, 7200.0, 30.0)
    T = np.where(t > 0, 23.0, 20.0)
    y = lagged(t, T, 900.0)
    np.testing.assert_allclose(y, 20.0 + _sampled_step(t, 3.0, 900.0, 30.0), atol=1e-12)
    perm = np.random.default_rng(0).permutation(len(t))  # row order does not matter, time does
    np.testing.assert_allclose(lagged(t[perm], T[perm], 900.0), y[perm], atol=1e-12)


def _fit_with_residual(robot, q, t, d):
    """A fit at the nominal geometry whose training residual is the displacement ``d`` (registration identity)."""
    model = build_geometry_model(robot)
    xyz = target_points(robot, q, t)
    fit = replace(initial_fit(model, q, xyz), R=np.eye(3), p_mm=np.zeros(3), t_mm=t, residual_mm=d)
    return fit, fixed_jacobian(fit, q, xyz + d)


def test_thermal_lag_variant_chosen_and_alpha_recovered():
    robot = tolalloc.load_robot("tool_changer")
    P = 120
    q = _q(robot, P, 4)
    t_s = 30.0 * np.arange(P)
    temp = np.where(t_s > 0, 24.0, 20.0)  # a step in the log: the structure lags it by 30 min
    t = np.array([0.0, 40.0, 60.0])
    alpha = 40.0  # 1e-6/K
    meas = Measurements(q, np.zeros((P, 3)), temp, None, None, t_s)
    ref = effect_reference(meas)
    dT = 20.0 + _sampled_step(t_s, 4.0, 1800.0, 30.0) - ref["temperature_c"]  # closed-form lag
    # exact growth of every link vector by alpha dT: scale the chain's links (independent of the error model)
    d = np.stack([_grown_point(robot, q[i], t, 1e-6 * alpha * dT[i]) for i in range(P)]) - target_points(robot, q, t)
    fit, J = _fit_with_residual(robot, q, t, d)
    cands = [effect_basis("thermal", robot, meas, t, ref, v) for v in variants("thermal", meas, ref)]
    best = choose_variant(cands, fit, J)
    assert best.variant == "lag_30min"  # on the grid 5 min .. 4 h
    assert _lsq(best, d)[0] == pytest.approx(alpha, rel=2e-3)


def _grown_point(robot, q1, t, eps):
    from tolalloc.robot.model import Link, Robot

    chain = tuple(Link(el.name, np.asarray(el.vector_mm) * (1 + eps)) if hasattr(el, "vector_mm") else el
                  for el in robot.chain)
    grown = Robot(robot.name, chain, tool_offset_mm=robot.tool_offset_mm, tool_rotation=robot.tool_rotation)
    return target_points(grown, q1[None], t)[0]


def test_backlash_gravity_side_recovered_without_dir_columns():
    robot = tolalloc.load_robot("ur10")
    q = _q(robot, 80, 5)
    t = np.array([0.0, 0.0, 120.0])
    side = np.sign(_potential_torque(robot, q))
    b = np.array([0.0, 3e-5, 2e-5, 1e-5, 0.0, 0.0])  # rad, half backlash of j2, j3, j4
    d = target_points(robot, q + side * b, t) - target_points(robot, q, t)
    meas = Measurements(q, np.zeros((80, 3)))  # no dir columns: only the gravity-held variant applies
    # gravity-held sides only, and the bearings' clearance (also held by gravity)
    assert variants("backlash", meas) == ("gravity", "gravity_soft", "clearance")
    basis = effect_basis("backlash", robot, meas, t, effect_reference(meas))
    beta = dict(zip(basis.names, _lsq(basis, d)))
    for j in (1, 2, 3):
        assert beta[f"b_{robot.joints[j].name} [rad]"] == pytest.approx(b[j], rel=2e-3)


def test_lost_motion_held_by_load_with_a_hysteresis_loss_chosen_and_recovered():
    """A gear that trails its last motion by b/2 where its load is inside the friction band, rests on the flank the
    load presses outside it, and loses h/2 to hysteresis against the motion at every load: the
    ``preload+hysteresis`` variant is chosen and returns b/2 and h/2 on the loaded joints."""
    robot = tolalloc.load_robot("ur10")
    P = 150
    q = _q(robot, P, 6)
    d_dir = np.random.default_rng(7).choice([-1.0, 1.0], q.shape)
    tau = _potential_torque(robot, q)
    held = np.abs(tau) > 0.1 * np.ptp(tau, axis=0)
    flank = np.where(held, np.sign(tau), -d_dir)
    half_b, half_h = 4e-5, 1.5e-5  # rad, on the shoulder, elbow and wrist-1 joints
    b = np.array([0.0, half_b, half_b, half_b, 0.0, 0.0])
    h = np.array([0.0, half_h, half_h, half_h, 0.0, 0.0])
    t = np.array([0.0, 0.0, 120.0])
    d = target_points(robot, q + flank * b - d_dir * h, t) - target_points(robot, q, t)
    meas = Measurements(q, np.zeros((P, 3)), None, d_dir)
    ref = effect_reference(meas)
    assert "preload+hysteresis" in variants("backlash", meas)
    fit, J = _fit_with_residual(robot, q, t, d)
    best = choose_variant([effect_basis("backlash", robot, meas, t, ref, v) for v in variants("backlash", meas)],
                          fit, J)
    assert best.variant == "preload+hysteresis"
    beta = dict(zip(best.names, _lsq(best, d)))
    for j in (1, 2, 3):
        name = robot.joints[j].name
        assert beta[f"b_{name} [rad]"] == pytest.approx(half_b, rel=5e-3)
        assert beta[f"h_{name} [rad]"] == pytest.approx(half_h, rel=5e-3)


def test_compliance_with_payload_and_with_unknown_tip_mass():
    robot = tolalloc.load_robot("ur10")
    P = 80
    q = _q(robot, P, 6)
    t = np.array([0.0, 0.0, 150.0])
    kg = 4.0
    tau = _potential_torque(robot, q, lambda qq: target_points(robot, qq, t), kg)
    c = np.array([0.0, 2e-7, 3e-7, 4e-7, 0.0, 0.0])  # rad/(N m) on j2..j4
    d = target_points(robot, q + tau * c, t) - target_points(robot, q, t)
    known = effect_basis("joint_compliance", robot, Measurements(q, np.zeros((P, 3)), payload_kg=np.full(P, kg)),
                         t, {}, "masses")
    beta = dict(zip(known.names, _lsq(known, d)))
    nm = [jt.name for jt in robot.joints]
    for j in (1, 2, 3):
        assert beta[f"c_{nm[j]} [rad/(N m)]"] == pytest.approx(c[j], rel=5e-3)
    unknown = effect_basis("joint_compliance", robot, Measurements(q, np.zeros((P, 3))), t, {}, "masses+tip")
    beta = dict(zip(unknown.names, _lsq(unknown, d)))
    for j in (1, 2, 3):  # d_j = c_j * tip mass
        assert beta[f"d_{nm[j]} [rad/kg]"] / beta[f"c_{nm[j]} [rad/(N m)]"] == pytest.approx(kg, rel=1e-2)


def test_a_constant_side_force_at_the_tool_is_the_force_variant():
    """A hose pulling the tool sideways with a constant 30 N / -20 N (base x / y) while the joints wind up under
    gravity too: its joint loads come from finite differences of the force's work (not from ``wrench_load``); the
    ``masses+force`` columns hold the displacement and give the force back as ``h_j / c_j``, while the tip-mass
    variant, vertical only, leaves most of it. Axis 1, vertical on every pose, gets no side-force column."""
    robot = tolalloc.load_robot("ur10")
    P = 80
    q = _q(robot, P, 7)
    t = np.array([0.0, 0.0, 150.0])
    F = np.array([30.0, -20.0, 0.0])

    def work(qq):
        return target_points(robot, qq, t) @ F / 1000.0  # [N m]

    tau_f = np.zeros_like(q)
    for j in range(robot.n_joints):
        e = np.zeros(robot.n_joints)
        e[j] = 1e-6
        tau_f[:, j] = (work(q + e) - work(q - e)) / 2e-6
    tau = _potential_torque(robot, q) + tau_f
    c = np.array([0.0, 2e-7, 3e-7, 4e-7, 0.0, 0.0])  # rad/(N m) on j2..j4
    d = target_points(robot, q + tau * c, t) - target_points(robot, q, t)
    meas = Measurements(q, np.zeros((P, 3)))
    force = effect_basis("joint_compliance", robot, meas, t, {}, "masses+force")
    beta = dict(zip(force.names, _lsq(force, d)))
    r = d.ravel() - force.B.reshape(-1, force.B.shape[-1]) @ _lsq(force, d)
    assert np.linalg.norm(r) < 1e-2 * np.linalg.norm(d)
    nm = [jt.name for jt in robot.joints]
    for j in (1, 2, 3):
        cj = beta[f"c_{nm[j]} [rad/(N m)]"]
        assert cj == pytest.approx(c[j], rel=1e-2)
        # h1 along base x, h2 along base y (ur10: gravity along -z)
        assert beta[f"h1_{nm[j]} [rad/N]"] / cj == pytest.approx(F[0], rel=2e-2)
        assert beta[f"h2_{nm[j]} [rad/N]"] / cj == pytest.approx(F[1], rel=2e-2)
    tip = effect_basis("joint_compliance", robot, meas, t, {}, "masses+tip")
    r = d.ravel() - tip.B.reshape(-1, tip.B.shape[-1]) @ _lsq(tip, d)
    assert np.linalg.norm(r) > 0.3 * np.linalg.norm(d - target_points(robot, q + _potential_torque(robot, q) * c, t)
                                                      + target_points(robot, q, t))
    assert "masses+force" in variants("joint_compliance", meas)
    # axis 1 stays vertical: a side force's moment about it is once per turn, transmission's signature, not a column
    assert not any(n.startswith(("h1_" + nm[0], "h2_" + nm[0])) for n in force.names)
    assert any(n.startswith("h1_" + nm[1]) for n in force.names)


def test_beam_deflection_telescopic_lever_arm():
    """The tool changer's telescopic segment j3 -> j5 (560 + 240 mm + stroke), horizontal: the bending column of its
    mass model is the textbook superposition -- l4 (45 kg) 280 mm out and l5 (30 kg) 680 mm + stroke out on the
    segment, P a^2 (3L - a) / 6 at the end and P a^2 / 2 of slope each; l6 (120 kg) 165 mm beyond the end as a force
    and a moment at the end, P L^3 / 3 + P d L^2 / 2 and P L^2 / 2 + P d L -- and the tool point, 165 mm beyond the
    end, drops by the end's drop plus 165 mm of its slope."""
    robot = tolalloc.load_robot("tool_changer")
    strokes = np.array([0.0, 100.0, 200.0, 300.0])
    q = np.zeros((4, robot.n_joints))
    q[:, 3] = strokes  # the arm stays horizontal; only the telescopic stage extends
    basis = effect_basis("link_deflection", robot, Measurements(q, np.zeros((4, 3))), np.zeros(3), {}, "beam")
    G = 9.81
    L, d = 800.0 + strokes, 165.0
    drop, slope = np.zeros(4), np.zeros(4)
    for kg, a in ((45.0, np.full(4, 280.0)), (30.0, 680.0 + strokes)):
        drop += kg * G * a ** 2 * (3 * L - a) / 6
        slope += kg * G * a ** 2 / 2
    P6 = 120.0 * G
    drop += P6 * L ** 3 / 3 + P6 * d * L ** 2 / 2
    slope += P6 * L ** 2 / 2 + P6 * d * L
    expect = np.zeros((4, 3))
    expect[:, 2] = -1e-12 * (drop + d * slope)  # per unit 1/EI in 1/(MN m^2)
    np.testing.assert_allclose(basis.B[:, :, basis.names.index("e_j3 [1/(MN m^2)]")], expect, rtol=1e-9, atol=1e-15)

def test_a_tool_tilting_on_a_compliant_mount_is_named_link_deflection_in_the_flange_variant():
    """A UR10 whose tool (4 kg, its centre of mass halfway to the target) sits on a compliant mount turning 150 and
    100 urad per N m about the tool's x and y axes (a force-torque sensor, a tool changer): the poses turned exactly
    about the flange point (scipy's rotation, not the effect's columns). The diagnosis names link deflection in the
    ``flange`` variant, before joint compliance, and removes most of the error."""
    from scipy.spatial.transform import Rotation

    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("ur10")
    P = 100
    rng = np.random.default_rng(21)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    t = np.array([0.0, 20.0, 180.0])
    p_t = target_points(robot, q, t)
    Pm = poe_prefix(robot.screws, q)
    R = Pm[:, -1, :3, :3] @ robot.tool_rotation
    pf = np.einsum("pij,j->pi", Pm[:, -1, :3, :3], robot.home[:3, 3] - robot.tool_offset_mm) + Pm[:, -1, :3, 3]
    com = pf + 0.5 * (p_t - pf)
    M = np.cross((com - pf) / 1000.0, np.broadcast_to(4.0 * G * np.asarray(robot.gravity), com.shape))
    turn = np.einsum("pij,pj->pi", R, np.array([150e-6, 100e-6, 0.0]) * np.einsum("pji,pj->pi", R, M))
    xyz = pf + Rotation.from_rotvec(turn).apply(p_t - pf) + rng.normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, None, None), folds=3, max_effects=1)
    assert d.effect == "link_deflection", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "link_deflection") == "flange"
    assert d.final.heldout_rms_mm < 0.5 * d.geometric.heldout_rms_mm


def test_coupling_columns_are_the_other_joints_positions_on_each_revolute_joint():
    """coupling_columns: for every revolute joint j one column per joint k holding q_k (rad; a prismatic stroke in m)
    in joint j's slot, grouped by j; the tool_changer's prismatic joint 4 has no columns of its own."""
    from tolalloc.physics.transmission import coupling_columns

    robot = tolalloc.load_robot("tool_changer")
    q = _q(robot, 7, 2)
    A, names, groups = coupling_columns(robot, q)
    rev = [j for j in range(robot.n_joints) if robot.joints[j].is_revolute]
    assert A.shape == (7, robot.n_joints, len(rev) * robot.n_joints) and len(names) == A.shape[2]
    for m, (j, k) in enumerate((j, k) for j in rev for k in range(robot.n_joints)):
        expect = np.zeros((7, robot.n_joints))
        expect[:, j] = q[:, k] / (1.0 if robot.joints[k].is_revolute else 1000.0)
        np.testing.assert_array_equal(A[:, :, m], expect)
        assert groups[m] == j and names[m].startswith(f"k_{robot.joints[j].name}_{robot.joints[k].name} [rad/")
    assert names[rev.index(4) * robot.n_joints + 3].endswith("[rad/m]")


def test_a_coupled_wrist_with_a_wrong_coupling_factor_is_named_transmission_coupling():
    """A UR10 whose wrist 3 turns by 0.002 rad per rad of wrist 2 (a coupled wrist's factor off in the controller;
    the poses from the forward kinematics at q6 + 0.002 q5): the diagnosis names transmission in the ``coupling``
    variant and recovers the factor within 10 %."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("ur10")
    P = 90
    rng = np.random.default_rng(22)
    q = _q(robot, P, 22)
    t = np.array([0.0, 40.0, 120.0])
    qt = q.copy()
    qt[:, 5] += 0.002 * q[:, 4]
    xyz = target_points(robot, qt, t) + rng.normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, None, None), folds=3, max_effects=1)
    assert d.effect == "transmission", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "transmission") == "coupling"
    params = d.final.fit.parameters_frame().set_index("parameter")["value"]
    k = params["transmission:k_wrist_3_joint_wrist_2_joint [rad/rad]"]
    assert abs(k - 0.002) < 2e-4, k


def test_coupling_columns_of_a_robot_without_revolute_joints_are_empty():
    from tolalloc.physics.transmission import coupling_columns

    chain = (tolalloc.robot.Joint("x", "prismatic", np.array([1.0, 0.0, 0.0]), 0.0, 500.0),
             tolalloc.robot.Link("l", np.array([0.0, 0.0, 100.0])))
    robot = tolalloc.robot.Robot("gantry", chain, trust_units=True)
    A, names, groups = coupling_columns(robot, np.zeros((4, 1)))
    assert A.shape == (4, 1, 0) and names == [] and groups.shape == (0,)
