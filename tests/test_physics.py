"""The physical effect models (tolalloc/physics) against closed forms: the catalogue's torque-torsion curve, the
hardening law, the mount's tilt, a cantilever's deflection, the strain-wave orders, lags, link growth."""

import numpy as np
import pytest

import tolalloc
from tolalloc.errormodel import build_error_model
from tolalloc.physics.thermal_history import PAUSE_STEPS, active_time
from tolalloc.physics import (base_moment, beam_sag, compliance_columns, flank, gear_orders, joint_loads, lag_filter,
                              link_growth, lost_motion_basis, motor_heat, mount_columns, transmission_error)
from tolalloc.physics.loads import G
from tolalloc.robot import Joint, Link, Robot
from tolalloc.robot.components import Components, LinkSection, Reducer
from tolalloc.robot.components_file import parse_components


def test_catalogue_curve_and_its_columns():
    """Harmonic Drive's three-band curve: T/K1 to T1, then 1/K2 to T2, then 1/K3; the catalogue columns with
    (1/K1, 1/K2, 1/K3) reproduce it, odd in the torque."""
    red = Reducer(stiffness=(5.0e4, 7.0e4, 1.0e5), torque_bands=(30.0, 100.0))
    tau = np.array([-150.0, -20.0, 0.0, 20.0, 60.0, 150.0])
    phi = red.deflection(tau)
    expect = lambda t: min(t, 30) / 5e4 + np.clip(t - 30, 0, 70) / 7e4 + max(t - 100, 0) / 1e5  # noqa: E731
    np.testing.assert_allclose(phi, [np.sign(t) * expect(abs(t)) for t in tau], rtol=1e-12)
    robot = tolalloc.load_robot("ur10")
    parts = parse_components({"joints": {"elbow_joint": {"reducer": {"stiffness_Nm_per_rad": [5e4, 7e4, 1e5],
                                                                      "torque_bands_Nm": [30, 100]}}}},
                             {j.name: True for j in robot.joints}, [lk.name for lk in robot.links])
    object.__setattr__(robot, "components", parts)
    T = np.zeros((len(tau), 6))
    T[:, 2] = tau
    A, names = compliance_columns(robot, T, np.zeros_like(T), "catalogue")
    assert names == ["c1_elbow_joint [rad/(N m)]", "c2_elbow_joint [rad/(N m)]", "c3_elbow_joint [rad/(N m)]"]
    np.testing.assert_allclose(A[:, 2, :] @ [1 / 5e4, 1 / 7e4, 1 / 1e5], phi, rtol=1e-12)


def test_hardening_law_is_soft_near_zero_and_stiff_beyond_t0():
    robot = tolalloc.load_robot("ur10")
    tau = np.zeros((5, 6))
    tau[:, 1] = [-200.0, -1e-3, 0.0, 1e-3, 200.0]
    A, names = compliance_columns(robot, tau, np.zeros_like(tau), "hardening_0.25")
    assert names == ["c_shoulder_lift_joint [rad/(N m)]", "s_shoulder_lift_joint [rad/(N m)]"]
    c, s = 1e-5, 3e-5
    dq = A[:, 1, :] @ [c, s]
    assert (dq[3] - dq[1]) / 2e-3 == pytest.approx(c + s, rel=1e-6)  # the soft zone's slope at zero torque
    t0 = 0.25 * 200.0
    assert dq[4] == pytest.approx(c * 200 + s * t0 * np.tanh(4.0), rel=1e-12)  # stiff beyond T0, offset s T0


def test_mount_tilts_about_the_base_under_the_moment_of_a_point_mass():
    """One 10 kg mass 1 m out along x: the base carries M = r x m g = (0, 98.1, 0) N m; an isotropic mount of
    compliance c turns by c M and moves a point p by (c M) x p."""
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([1000.0, 0.0, 0.0])))
    robot = Robot("arm", chain)
    object.__setattr__(robot, "masses", (tolalloc.robot.Mass("m", 1, 10.0, np.array([1000.0, 0.0, 0.0])),))
    q = np.array([[0.0]])
    M = base_moment(robot, q)
    np.testing.assert_allclose(M, [[0.0, 10 * G, 0.0]], atol=1e-12)
    p = np.array([[1000.0, 0.0, 500.0]])
    B, names = mount_columns(robot, q, p, variant="isotropic")
    np.testing.assert_allclose(B[:, :, 0], np.cross(M, p), atol=1e-9)
    assert names == ["c_mount [rad/(N m)]"]


def _cantilever(section):
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([1000.0, 0.0, 0.0])))
    robot = Robot("beam", chain)
    object.__setattr__(robot, "masses", (tolalloc.robot.Mass("tip", 1, 20.0, np.array([1000.0, 0.0, 0.0])),))
    object.__setattr__(robot, "components", Components(links={"l1": section}))
    return robot


def test_cantilever_end_drop_from_bending_and_shear():
    """A horizontal 1 m steel tube (D 100, t 5 mm) with 20 kg at its end and a 5 kg payload there:
    drop = F L^3 / 3EI + F L / (kappa G A), straight down."""
    sec = parse_components({"links": {"l1": {"section": "tube", "outer_diameter_mm": 100, "wall_mm": 5,
                                              "material": "steel"}}}, {"j1": True}, ["l1"]).links["l1"]
    assert isinstance(sec, LinkSection) and sec.inertia_mm4 == pytest.approx(np.pi / 64 * (100**4 - 90**4))
    robot = _cantilever(sec)
    q = np.zeros((1, 1))
    p = np.array([[1000.0, 0.0, 0.0]])
    F, L = 25 * G, 1000.0
    expect = F * L**3 / (3 * sec.EI_Nmm2) + F * L / sec.shear_stiffness_N
    np.testing.assert_allclose(beam_sag(robot, q, p, payload_kg=np.array([5.0])), [[0.0, 0.0, -expect]], rtol=1e-9)
    q90 = np.array([[np.pi / 2]])  # turned about the vertical axis: the same drop
    np.testing.assert_allclose(beam_sag(robot, q90, np.array([[0.0, 1000.0, 0.0]]), np.array([5.0])),
                               [[0.0, 0.0, -expect]], rtol=1e-9, atol=1e-12)


def _box(**extra):
    table = {"section": "box", "width_mm": 100, "height_mm": 200, "wall_mm": 5, "material": "steel", **extra}
    return parse_components({"links": {"l1": table}}, {"j1": True}, ["l1"],
                            link_vectors={"l1": np.array([1000.0, 0.0, 0.0])}).links["l1"]


@pytest.mark.parametrize("height, I_key", [([0, 0, 1], "inertia_mm4"), ([0, 1, 0], "inertia_side_mm4")])
def test_a_box_bends_with_the_second_moment_of_the_plane_its_load_lies_in(height, I_key):
    """The 1 m cantilever as a 100 x 200 x 5 mm steel box, 20 kg at its end: height vertical, it drops by
    F L^3 / (3 E I_strong); turned on its side, by F L^3 / (3 E I_side), I about each axis by the box formula."""
    sec = _box(height_direction=height)
    b, h, t = 100.0, 200.0, 5.0
    assert sec.inertia_mm4 == pytest.approx((b * h**3 - (b - 2 * t) * (h - 2 * t) ** 3) / 12)
    assert sec.inertia_side_mm4 == pytest.approx((h * b**3 - (h - 2 * t) * (b - 2 * t) ** 3) / 12)
    robot, F, L = _cantilever(sec), 20 * G, 1000.0
    drop = F * L**3 / (3 * sec.youngs_modulus_MPa * getattr(sec, I_key)) + F * L / sec.shear_stiffness_N
    np.testing.assert_allclose(beam_sag(robot, np.zeros((1, 1)), np.array([[1000.0, 0.0, 0.0]])),
                               [[0.0, 0.0, -drop]], rtol=1e-9, atol=1e-12)


def test_a_tilted_box_deflects_towards_its_weak_plane_and_its_height_turns_with_the_joint():
    """Height at 30 deg from the vertical: the end load splits into the two planes, d = L^3 / 3E (u u.F / I +
    w w.F / I_side) (u the height, w the width axis: bending along the height is resisted by I about the width axis),
    so the end also moves sideways, to the side the weak plane leans. Turned 90 deg about the
    vertical joint, the box's height turns with it and the same deflection turns too. Without an orientation the box
    bends with I in both planes, as before."""
    a = np.radians(30.0)
    u = np.array([0.0, np.sin(a), np.cos(a)])
    sec = _box(height_direction=list(u))
    robot, F, L = _cantilever(sec), 20 * G, 1000.0
    w = np.cross([1.0, 0.0, 0.0], u)
    g = np.array([0.0, 0.0, -F])
    E = sec.youngs_modulus_MPa
    d = (L**3 / (3 * E) * (u * (u @ g) / sec.inertia_mm4 + w * (w @ g) / sec.inertia_side_mm4)
         + g * L / sec.shear_stiffness_N)
    got = beam_sag(robot, np.zeros((1, 1)), np.array([[1000.0, 0.0, 0.0]]))[0]
    np.testing.assert_allclose(got, d, rtol=1e-9, atol=1e-12)
    assert got[1] > 1e-2   # sideways: sin a cos a (1 / I_side - 1 / I) F L^3 / 3E
    Rz = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    turned = beam_sag(robot, np.array([[np.pi / 2]]), np.array([[0.0, 1000.0, 0.0]]))[0]
    np.testing.assert_allclose(turned, Rz @ d, rtol=1e-9, atol=1e-12)
    plain = beam_sag(_cantilever(_box()), np.zeros((1, 1)), np.array([[1000.0, 0.0, 0.0]]))[0]
    drop = F * L**3 / (3 * E * sec.inertia_mm4) + F * L / sec.shear_stiffness_N
    np.testing.assert_allclose(plain, [0.0, 0.0, -drop], rtol=1e-9, atol=1e-12)


_BOX = {"section": "box", "width_mm": 100, "height_mm": 200, "wall_mm": 5}


@pytest.mark.parametrize("table, match", [
    ({"section": "tube", "outer_diameter_mm": 60, "wall_mm": 3, "height_direction": [0, 0, 1]}, "for section = \"box\""),
    ({**_BOX, "height_direction": [0, 1]}, "3 finite"),
    ({**_BOX, "height_direction": [0, 0, 0]}, "not all zero"),
    ({**_BOX, "height_direction": "up"}, "3 finite"),
    ({**_BOX, "height_direction": [1, 0, 0.2]}, "deg off the plane across the link"),
])
def test_a_box_height_direction_is_checked_where_it_is_read(table, match):
    with pytest.raises(ValueError, match=match):
        parse_components({"links": {"l1": {**table, "material": "steel"}}}, {"j1": True}, ["l1"],
                         link_vectors={"l1": np.array([1000.0, 0.0, 0.0])})


def test_strain_wave_error_repeats_at_n_and_2n_per_output_turn():
    N = 101.0
    orders = gear_orders(N)
    assert orders == (1.0, 101.0, 202.0)
    q = np.linspace(0, 0.3, 50)
    amps, phases = [0.0, 2e-4, 1e-4], [0.0, 0.3, 1.1]
    e = transmission_error(q, orders, amps, phases)
    np.testing.assert_allclose(transmission_error(q + 2 * np.pi / N, orders, amps, phases), e, atol=1e-15)
    assert np.ptp(e) <= 2 * sum(amps) + 1e-12


def test_lag_heats_and_cools_as_a_first_order_system():
    t = np.arange(0.0, 7200.0, 60.0)
    u = np.where((t > 0) & (t <= 3600.0), 1.0, 0.0)  # heat input for an hour, then a pause
    y = lag_filter(t, u[:, None], 900.0)[:, 0]
    on = t <= 3600.0
    np.testing.assert_allclose(y[on], 1 - np.exp(-t[on] / 900.0), atol=1e-12)
    np.testing.assert_allclose(y[~on], y[t == 3600.0] * np.exp(-(t[~on] - 3600.0) / 900.0), atol=1e-12)


def test_motor_heat_holds_the_previous_pose_load_squared():
    t = np.array([0.0, 60.0, 120.0])
    q = np.array([[0.0], [0.6], [0.6]])
    load = np.array([[2.0], [3.0], [5.0]])
    h = motor_heat(t, q, load, 1e-9)  # a lag much faster than the poses: the inputs themselves
    np.testing.assert_allclose(h[:, 0], [0.0, 0.01, 0.0], atol=1e-12)  # speed over the interval before each pose
    np.testing.assert_allclose(h[:, 1], [0.0, 4.0, 9.0], atol=1e-12)  # the load held before it, squared


def test_motor_heat_cools_during_a_pause():
    """Poses every 60 s, then a 3600 s gap: the robot works for 5 median intervals (300 s) of it, then the links
    cool for the remaining 3300 s (closed form of the first-order lag)."""
    tau = 900.0
    t = np.r_[np.arange(0.0, 1200.0, 60.0), 1140.0 + 3600.0]
    q = np.zeros((len(t), 1))
    load = np.ones((len(t), 1))  # the same load held throughout
    h = motor_heat(t, q, load, tau)[:, 1]
    np.testing.assert_allclose(h[:-1], 1 - np.exp(-t[:-1] / tau), atol=1e-12)
    warm = 1 - np.exp(-(1140.0 + 300.0) / tau)  # heated 300 s into the gap, then cooled
    np.testing.assert_allclose(h[-1], warm * np.exp(-3300.0 / tau), atol=1e-12)
    assert active_time(t)[-1] == PAUSE_STEPS * 60.0 and np.all(active_time(t)[1:-1] == 60.0)


def test_motor_heat_speed_is_the_move_over_the_working_time():
    t = np.r_[np.arange(0.0, 660.0, 60.0), 600.0 + 3600.0]  # poses every 60 s, then a pause
    q = 0.6 * np.arange(len(t), dtype=float)[:, None]  # 0.6 rad before every pose
    fast = motor_heat(t, q, np.zeros((len(t), 1)), 1e-9)[:, 0]  # a lag much faster than the poses: the inputs
    np.testing.assert_allclose(fast[1:-1], 0.01, atol=1e-12)  # 0.6 rad in 60 s
    assert fast[-1] == 0.0  # the move before the last pose heated, then the pause cooled the links down again
    slow = motor_heat(t, q, np.zeros((len(t), 1)), 1e12)[:, 0]  # no cooling: the heat is speed x working time
    np.testing.assert_allclose(slow[-1] / slow[-2], 1.0 + 0.6 / 300.0 * 300.0 / (0.01 * 600.0), rtol=1e-6)


def test_link_growth_agrees_with_the_error_models_link_length_jacobian():
    robot = tolalloc.load_robot("tool_changer")
    q = robot.random_q(np.random.default_rng(0), 20)
    grow, names = link_growth(robot, q)
    J = build_error_model(robot, "generic", exclude=("joint_drive", "axis_deflection")).jacobian(q)[:, :3, :]
    L = np.array([lk.length_mm for lk in robot.links])
    np.testing.assert_allclose(grow, 1e-6 * J * L, atol=1e-12)
    assert names == tuple(lk.name for lk in robot.links)


def test_lost_motion_flanks():
    tau = np.array([[5.0], [-5.0], [0.1], [-0.1]])
    d = np.array([[1.0], [1.0], [-1.0], [1.0]])
    # moving along +axis the motor pushes the output from behind: it trails by b/2 (s = -dir); a load above the
    # band holds it on the flank the load presses (s = sign(tau)), both in the convention dq = s b / 2
    np.testing.assert_array_equal(flank(tau, d, "approach"), -d)
    np.testing.assert_array_equal(flank(tau, d, "gravity"), np.sign(tau))
    np.testing.assert_array_equal(flank(tau, d, "preload"), [[1.0], [-1.0], [1.0], [-1.0]])
    with pytest.raises(ValueError, match="needs the approach directions"):
        flank(tau, None, "preload")
    with pytest.raises(ValueError, match="unknown flank rule 'preloaded'"):
        flank(tau, d, "preloaded")
    # a joint no load reaches (rounding of 1e-14 N m on a vertical axis) has no gravity flank: it trails the motion
    tau2 = np.hstack([tau, 1e-14 * np.array([[1.0], [-1.0], [1.0], [-1.0]])])
    d2 = np.hstack([d, d])
    np.testing.assert_array_equal(flank(tau2, d2, "gravity")[:, 1], 0.0)
    np.testing.assert_array_equal(flank(tau2, d2, "gravity_soft")[:, 1], 0.0)
    np.testing.assert_array_equal(flank(tau2, d2, "preload")[:, 1], -d[:, 0])


def test_lost_motion_with_hysteresis_loss_recovers_both_widths():
    # a gear held on its flank by a load above the band, trailing the motion below it, and a hysteresis loss that
    # trails the motion at every load: dq = b/2 s_preload - h/2 dir, with b = 3 arcmin and h = 1 arcmin
    robot = tolalloc.load_robot("ur10")
    rng = np.random.default_rng(5)
    q = rng.uniform(-np.pi, np.pi, (80, robot.n_joints))
    d = rng.choice([-1.0, 1.0], q.shape)
    tau = joint_loads(robot, q)[0]
    arcmin = np.pi / 180 / 60
    dq = 1.5 * arcmin * flank(tau, d, "preload") - 0.5 * arcmin * d
    A, names = lost_motion_basis(robot, tau, d, "preload+hysteresis")
    n = robot.n_joints
    assert names[:n] == [f"b_{jt.name} [rad]" for jt in robot.joints]
    assert names[n:] == [f"h_{jt.name} [rad]" for jt in robot.joints]
    beta, *_ = np.linalg.lstsq(A.reshape(-1, A.shape[-1]), dq.ravel(), rcond=None)
    np.testing.assert_allclose(A @ beta, dq, atol=1e-12)
    # where a load holds the flank the two widths separate; on a joint no load reaches (the vertical base axis, the
    # last wrist axis) both columns trail the motion and only b/2 + h/2 is determined
    held = (flank(tau, d, "preload") != -d).any(0)
    assert held.sum() >= 3 and not held[0]
    np.testing.assert_allclose(beta[:n][held], 1.5 * arcmin, rtol=1e-9)
    np.testing.assert_allclose(beta[n:][held], 0.5 * arcmin, rtol=1e-9)
    np.testing.assert_allclose((beta[:n] + beta[n:])[~held], 2.0 * arcmin, rtol=1e-9)
    # the approach variant alone cannot carry the held flank: it leaves a residual of the lost motion's size
    A1, _ = lost_motion_basis(robot, tau, d, "approach")
    b1, res, *_ = np.linalg.lstsq(A1.reshape(-1, A1.shape[-1]), dq.ravel(), rcond=None)
    assert np.sqrt(res[0] / dq.size) > 0.5 * arcmin


def test_joint_loads_add_the_payload_at_the_target():
    robot = tolalloc.load_robot("ur10")
    q = robot.random_q(np.random.default_rng(1), 4)
    p = robot.fk_internal(q)[:, :3, 3]
    tau0, tip = joint_loads(robot, q, p)
    tau5, _ = joint_loads(robot, q, p, np.full(4, 5.0))
    np.testing.assert_allclose(tau5 - tau0, 5.0 * tip, atol=1e-9)


def test_a_mass_beside_the_beam_axis_twists_it():
    """A 1 m steel tube along x carries, through a rigid 300 mm arm, 20 kg beside its axis: the end drops by
    P L^3 / 3EI + P L / kGA and the torque P d twists it by P d L / GJ, lowering the mass by a further d times that;
    the tube (no robot mass on it) also sags under its own weight, w L^4 / 8EI + w L^2 / 2kGA."""
    sec = parse_components({"links": {"l1": {"section": "tube", "outer_diameter_mm": 100, "wall_mm": 5,
                                              "material": "steel"}}}, {"j1": True, "j2": True}, ["l1", "l2"]).links["l1"]
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([1000.0, 0.0, 0.0])),
             Joint("j2", "revolute", np.array([1.0, 0.0, 0.0])), Link("l2", np.array([0.0, 300.0, 0.0])))
    robot = Robot("arm", chain)
    object.__setattr__(robot, "masses", (tolalloc.robot.Mass("m", 2, 20.0, np.array([1000.0, 300.0, 0.0])),))
    object.__setattr__(robot, "components", Components(links={"l1": sec}))
    P, L, d = 20 * G, 1000.0, 300.0
    GJ = sec.shear_modulus_MPa * np.pi / 32 * (100**4 - 90**4)  # polar moment of the round tube
    w = sec.area_mm2 * sec.density_kg_per_mm3 * G  # [N/mm]
    drop = (P * L**3 / (3 * sec.EI_Nmm2) + P * L / sec.shear_stiffness_N + P * d * L / GJ * d
            + w * L**4 / (8 * sec.EI_Nmm2) + w * L**2 / (2 * sec.shear_stiffness_N))
    np.testing.assert_allclose(beam_sag(robot, np.zeros((1, 2)), np.array([[1000.0, 300.0, 0.0]])),
                               [[0.0, 0.0, -drop]], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("q1_deg", [0.0, 90.0])
def test_a_tool_on_a_compliant_mount_drops_by_the_torsion_spring_closed_form(q1_deg):
    """flange_columns on a one-joint arm (link 500 mm along x, tool 200 mm beyond the flange along the tool axis x,
    gravity -z): a unit mass at the target is a moment 0.2 G N m about the tool's y axis, so a turn compliance c_y
    drops the target by c_y 0.2 G x 200 um per urad/(N m); the shear compliance s_z lowers it by G um per um/N; the
    other columns of this load are zero (no moment about x or z, no force along x or y) -- at any turn of the joint.
    The known load: the link's default mass (5 kg at its midpoint, 250 mm behind the flange, on the last body) tips the
    tool up, a logged payload of 3 kg at the target down."""
    from tolalloc.physics.beams import flange_columns

    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([500.0, 0.0, 0.0])))
    robot = Robot("mount", chain, tool_offset_mm=np.array([200.0, 0.0, 0.0]), trust_units=True)
    q = np.array([[np.deg2rad(q1_deg)]])
    p_t = robot.fk_internal(q)[:, :3, 3]
    for payload, known_lift in ((None, 250.0), (np.array([3.0]), 250.0 - 3 * 0.2 * 200.0)):
        B, names = flange_columns(robot, q, p_t, payload)
        col = dict(zip(names, B[0].T))
        assert [n for n in names if n.endswith("_tool [urad/(N m)]") or n.endswith("_tool [um/N]")] == [
            "cx_tool [urad/(N m)]", "cy_tool [urad/(N m)]", "cz_tool [urad/(N m)]", "sx_tool [um/N]",
            "sy_tool [um/N]", "sz_tool [um/N]"] and len(names) == 12
        np.testing.assert_allclose(col["cy_tool [urad/(N m)]"], [0.0, 0.0, -1e-6 * 0.2 * G * 200.0], atol=1e-15)
        np.testing.assert_allclose(col["sz_tool [um/N]"], [0.0, 0.0, -1e-3 * G], atol=1e-15)
        np.testing.assert_allclose(col["cy_known [urad/(N m)]"], [0.0, 0.0, 1e-6 * G * known_lift], atol=1e-15)
        for ax in "xz":
            np.testing.assert_allclose(col[f"c{ax}_tool [urad/(N m)]"], 0.0, atol=1e-15)
            np.testing.assert_allclose(col[f"c{ax}_known [urad/(N m)]"], 0.0, atol=1e-15)
        for ax in "xy":
            np.testing.assert_allclose(col[f"s{ax}_tool [um/N]"], 0.0, atol=1e-15)
