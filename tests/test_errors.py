"""Error model structure: names, sigma sets, exact perturbed chains vs closed forms, Jacobian vs finite differences."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.model import CLEARANCE_SIGMA, GENERIC_SIGMA, KINDS
from tolalloc.robot.lie import exp_se3, rot_x, rot_z, rotvec, transform
from tolalloc.robot.kinematics import fk_poe

TC_NAMES = ["dl1", "dl2", "dl3", "dl4", "dl5", "dl6", "dth1", "dth2", "dth3", "dd4", "dth5", "dth6",
            "e1x", "e1y", "e2y", "e2z", "e3y", "e3z", "e5y", "e5z", "e6x", "e6y"]
D = np.deg2rad


@pytest.fixture(scope="module")
def tc():
    return load_robot("tool_changer")


@pytest.fixture(scope="module")
def ur10():
    return load_robot("ur10")


def exact_pose(model, values, q):
    screws, home, dq = model.perturbed_chain(values)
    return fk_poe(screws, home, q + dq)


def fd_error_jacobian(model, q, h=1e-6):
    """Central differences of the exact perturbed chain: rows dp [mm], then space-frame dw [rad]."""
    K = len(model.params)
    T0 = model.robot.fk_internal(q)
    V = np.vstack([np.eye(K) * h, -np.eye(K) * h])
    T = exact_pose(model, V, q)
    Tp, Tm = T[:K], T[K:]
    dp = (Tp[:, :3, 3] - Tm[:, :3, 3]) / (2 * h)
    R0t = T0[:3, :3].T
    dw = (rotvec(Tp[:, :3, :3] @ R0t) - rotvec(Tm[:, :3, :3] @ R0t)) / (2 * h)
    return np.vstack([dp.T, dw.T])


def test_tool_changer_parameter_names_and_order(tc):
    model = build_error_model(tc)
    assert model.names == TC_NAMES
    kinds = model.kinds.tolist()
    assert kinds == ["link_length"] * 6 + ["joint_drive"] * 6 + ["axis_deflection"] * 10
    assert [p.unit for p in model.params] == ["mm"] * 6 + ["rad"] * 3 + ["mm"] + ["rad"] * 12
    assert [p.site for p in model.params[:6]] == [0, 1, 2, 3, 4, 5]
    assert model.sigma_set == "table2"  # the file's first set is the default
    df = model.to_frame()
    assert list(df.columns) == ["parameter", "kind", "element", "unit", "sigma_mm", "sigma_deg", "distribution"]
    assert df["parameter"].tolist() == TC_NAMES and df["unit"].tolist()[6:10] == ["deg", "deg", "deg", "mm"]
    # each sigma in its own unit's column, the other one empty
    mm = (df["unit"] == "mm").to_numpy()
    assert df["sigma_mm"][mm].notna().all() and df["sigma_mm"][~mm].isna().all()
    assert df["sigma_deg"][~mm].notna().all() and df["sigma_deg"][mm].isna().all()
    np.testing.assert_allclose(df.loc[6, "sigma_deg"], np.rad2deg(model.params[6].sigma))


def test_sigma_sets_table1_table2(tc):
    """NOTES_SEED.md: Table 2 per-link / per-joint sigma with Table 1's deflection sigma; Table 1 one sigma per kind."""
    t2 = build_error_model(tc, "table2").sigma
    expected2 = [0.17, 0.15, 0.2, 0.25, 0.15, 0.15, D(0.3), D(0.3), D(0.1548), 0.25, D(0.5), D(0.3)] + [0.00435] * 10
    np.testing.assert_allclose(t2, expected2, rtol=1e-12)
    t1 = build_error_model(tc, "table1").sigma
    expected1 = [0.2] * 6 + [0.0087] * 3 + [0.3] + [0.0087] * 2 + [0.00435] * 10
    np.testing.assert_allclose(t1, expected1, rtol=1e-12)
    df = build_error_model(tc, "table2").to_frame()
    assert df.loc[df.parameter == "dth3", "sigma_deg"].item() == pytest.approx(0.1548)


def test_generic_sigma_for_robots_without_sets(ur10):
    model = build_error_model(ur10)
    assert model.sigma_set == "generic"
    assert model.names[:6] == ["dd1", "da2", "da3", "dd4", "dd5", "dd6"]
    assert model.names[6:12] == [f"dth{j}" for j in range(1, 7)]
    sig = dict(zip(model.names, model.sigma))
    assert sig["da2"] == GENERIC_SIGMA["link_length"]
    assert sig["dth4"] == GENERIC_SIGMA["joint_drive_revolute"]
    assert len(model.names) == 6 + 6 + 12


def test_zero_values_give_nominal_chain(tc):
    model = build_error_model(tc, clearance=True)
    screws, home, dq = model.perturbed_chain(np.zeros((1, len(model.params))))
    np.testing.assert_allclose(screws[0], tc.screws, atol=1e-15)
    np.testing.assert_allclose(home[0], tc.home, atol=1e-15)
    assert np.all(dq == 0)


def test_single_link_error_closed_form_consistent(tc):
    """dl3 = delta (consistent): the tool moves by delta along l3 as rotated by j1 (15 deg, z) and j2 (30 deg, x)."""
    model = build_error_model(tc)
    q = tc.q_nominal
    delta = 0.7
    v = np.zeros(len(TC_NAMES))
    v[TC_NAMES.index("dl3")] = delta
    T = exact_pose(model, v[None], q)[0]
    T0 = tc.fk_internal(q)
    np.testing.assert_allclose(T[:3, 3] - T0[:3, 3], delta * rot_z(D(15)) @ rot_x(D(30)) @ [0, 1, 0], atol=1e-10)
    np.testing.assert_allclose(T[:3, :3], T0[:3, :3], atol=1e-14)
    # dl1 lifts everything by delta, dl6 extends along the arm direction at the tool
    v[:] = 0
    v[0] = delta
    np.testing.assert_allclose(exact_pose(model, v[None], q)[0][:3, 3] - T0[:3, 3], [0, 0, delta], atol=1e-10)


def test_single_link_error_closed_form_axes_only(tc):
    """Paper-literal Eq. 24: dl3 moves axes 3..6 by delta (home frame) while M stays:
    shift = delta R12 (I - R_B) y, with R12 = Rz(15) Rx(30), R_B the rotation of joints 3..6."""
    model = build_error_model(tc, link_mode="axes_only")
    q = tc.q_nominal
    delta = 0.7
    v = np.zeros(len(TC_NAMES))
    v[TC_NAMES.index("dl3")] = delta
    screws, home, _ = model.perturbed_chain(v[None])
    np.testing.assert_allclose(home[0], tc.home, atol=1e-14)  # the home pose does not move
    np.testing.assert_allclose(screws[0, :2], tc.screws[:2], atol=1e-14)  # upstream axes stay
    np.testing.assert_allclose(screws[0, 2, 3:], -np.cross(tc.screws[2, :3], tc.joint_points_mm[2] + [0, delta, 0]))
    T = fk_poe(screws[0], home[0], q)
    R12 = rot_z(D(15)) @ rot_x(D(30))
    R_B = rot_x(D(-10)) @ rot_x(D(-20)) @ rot_z(D(-5))
    expected = delta * R12 @ (np.eye(3) - R_B) @ [0, 1, 0]
    np.testing.assert_allclose(T[:3, 3] - tc.fk_internal(q)[:3, 3], expected, atol=1e-10)
    # at the zero configuration a link error has no effect at all in this mode
    np.testing.assert_allclose(model.jacobian(np.zeros(6))[:, :6], 0, atol=1e-12)


def test_drive_and_deflection_closed_form(tc):
    model = build_error_model(tc)
    q = tc.q_nominal
    T0 = tc.fk_internal(q)
    d = 0.01
    v = np.zeros(len(TC_NAMES))
    v[TC_NAMES.index("dth1")] = d  # the whole arm turns by d about z
    np.testing.assert_allclose(exact_pose(model, v[None], q)[0], transform(rot_z(d)) @ T0, atol=1e-10)
    v[:] = 0
    v[TC_NAMES.index("e1x")] = d  # rotation by d about x through (0, 0, l1), before joint 1
    G = exp_se3(np.array([1, 0, 0, 0, 315.0, 0]) * d)
    np.testing.assert_allclose(G[:3, 3], [0, 315 * np.sin(d), 315 * (1 - np.cos(d))], atol=1e-12)
    np.testing.assert_allclose(exact_pose(model, v[None], q)[0], G @ T0, atol=1e-10)
    v[:] = 0
    v[TC_NAMES.index("dd4")] = 2.0  # equals moving joint 4 by 2 mm
    q2 = q.copy()
    q2[3] += 2.0
    np.testing.assert_allclose(exact_pose(model, v[None], q)[0], tc.fk_internal(q2), atol=1e-10)


def test_tilt_deflection_has_no_effect_at_home(tc):
    model = build_error_model(tc, deflection_mode="tilt")
    J = model.jacobian(np.zeros(6))
    np.testing.assert_allclose(J[:, 12:], 0, atol=1e-12)
    screw = build_error_model(tc).jacobian(np.zeros(6))
    assert np.abs(screw[:, 12:]).max() > 100  # the screw reading does move the tool at home


OPTIONS = [
    dict(),
    dict(link_mode="axes_only"),
    dict(deflection_mode="tilt"),
    dict(link_mode="axes_only", deflection_mode="tilt", clearance=True),
    dict(clearance=True),
]


@pytest.mark.parametrize("robot_name", ["tool_changer", "ur10"])
@pytest.mark.parametrize("opts", OPTIONS, ids=lambda o: "-".join(f"{k}={v}" for k, v in o.items()) or "default")
def test_jacobian_matches_finite_differences(robot_name, opts):
    robot = load_robot(robot_name)
    model = build_error_model(robot, **opts)
    rng = np.random.default_rng(11)
    Q = np.vstack([robot.q_nominal, robot.poses("working")[rng.choice(len(robot.poses("working")), 2, replace=False)]])
    J_all = model.jacobian(Q)
    assert J_all.shape == (3, 6, len(model.params))
    for q, J in zip(Q, J_all):
        J_fd = fd_error_jacobian(model, q)
        scale = np.abs(J).max(axis=1, keepdims=True)
        np.testing.assert_allclose(J, J_fd, atol=1e-6 * scale.max(), rtol=1e-6)
        np.testing.assert_allclose(J, model.jacobian(q), atol=1e-12)


def test_clearance_parameters(tc):
    model = build_error_model(tc, clearance=True)
    names = model.names
    assert names[:22] == TC_NAMES
    rev = [1, 2, 3, 5, 6]
    expected = []
    for j, (a, b) in zip(rev, ["xy", "yz", "yz", "yz", "xy"]):
        expected += [f"ca{j}", f"cr{j}{a}", f"cr{j}{b}", f"cw{j}{a}", f"cw{j}{b}"]
    assert names[22:] == expected
    sig = dict(zip(names, model.sigma))
    assert sig["ca2"] == CLEARANCE_SIGMA["axial_mm"] == 0.2
    assert sig["cr2y"] == pytest.approx(0.5 / np.sqrt(2))
    assert sig["cw2y"] == 0.0087
    assert {p.distribution for p in model.params if p.kind == "clearance_radial"} == {"ring"}
    lit = build_error_model(tc, clearance=True, clearance_sigma={"tilt_rad": 0.087})
    assert dict(zip(lit.names, lit.sigma))["cw5z"] == 0.087


def test_sampling_moments_and_ring(tc):
    model = build_error_model(tc, clearance=True)
    rng = np.random.default_rng(0)
    X = model.sample(20000, rng)
    assert X.shape == (20000, len(model.params))
    # seeded Monte Carlo, 20000 draws: the sample std is within 3 % of sigma (its own s.e. is 0.5 %)
    np.testing.assert_allclose(X.std(axis=0), model.sigma, rtol=0.03)
    i, k = model.index("cr3y"), model.index("cr3z")
    radius = np.hypot(X[:, i], X[:, k])
    # the rod length s ~ N(0, 0.5 mm) (Table 4): rms radius 0.5 mm, each component 0.5 / sqrt(2)
    np.testing.assert_allclose(np.sqrt(np.mean(radius**2)), 0.5, rtol=0.03)
    assert abs(np.corrcoef(X[:, i], X[:, k])[0, 1]) < 0.03
    uni = build_error_model(tc, distribution="uniform").sample(20000, rng)
    np.testing.assert_allclose(uni.std(axis=0), build_error_model(tc).sigma, rtol=0.03)
    assert np.all(np.abs(uni[:, 0]) <= np.sqrt(3) * 0.17 + 1e-12)
    tn = build_error_model(tc, distribution={"link_length": "truncnormal"}).sample(5000, rng)
    assert np.all(np.abs(tn[:, :6]) <= 3 * np.array([0.17, 0.15, 0.2, 0.25, 0.15, 0.15]) + 1e-12)


def test_batched_perturbed_chain_equals_one_by_one(tc):
    model = build_error_model(tc, clearance=True, link_mode="axes_only", deflection_mode="tilt")
    rng = np.random.default_rng(2)
    V = model.sample(6, rng) * 50  # large values: the exact chain is nonlinear
    screws, home, dq = model.perturbed_chain(V)
    assert screws.shape == (6, 6, 6) and home.shape == (6, 4, 4) and dq.shape == (6, 6)
    for i in range(6):
        s1, h1, d1 = model.perturbed_chain(V[i])
        np.testing.assert_allclose(s1[0], screws[i], atol=1e-12)
        np.testing.assert_allclose(h1[0], home[i], atol=1e-12)
        np.testing.assert_allclose(d1[0], dq[i])
    q = tc.q_nominal
    T = fk_poe(screws, home, q + dq)
    for i in range(6):
        np.testing.assert_allclose(T[i], exact_pose(model, V[i:i + 1], q)[0], atol=1e-10)


def test_sigma_overrides_and_exclude(tc):
    model = build_error_model(tc, sigma={"link_length": 0.05, "dl3": 0.01, "e2y": 0.001})
    sig = dict(zip(model.names, model.sigma))
    assert sig["dl1"] == 0.05 and sig["dl3"] == 0.01 and sig["e2y"] == 0.001 and sig["e2z"] == 0.00435
    ex = build_error_model(tc, exclude=("dl1", "axis_deflection"))
    assert ex.names == TC_NAMES[1:12]
    np.testing.assert_allclose(ex.sigma, build_error_model(tc).sigma[1:12])
    # excluding one component of a ring leaves a sampleable model
    one = build_error_model(tc, clearance=True, exclude=("cr1x",))
    assert one.sample(10, np.random.default_rng(0)).shape == (10, len(one.params))
    w = model.with_sigma(np.ones(22))
    assert np.all(w.sigma == 1) and w.names == model.names


@pytest.mark.parametrize("kwargs,match", [
    (dict(sigma_set="table9"), r"unknown sigma set 'table9' for robot 'tool_changer'; known: generic, table2, table1"),
    (dict(link_mode="paper"), r"link_mode: expected 'consistent' or 'axes_only'"),
    (dict(deflection_mode="bend"), r"deflection_mode: expected 'screw' or 'tilt'"),
    (dict(sigma={"dl1": -0.1}), r"sigma of dl1: expected a finite value >= 0 \[mm\], got -0.1"),
    (dict(sigma={"dl1": float("nan")}), r"sigma of dl1: expected a finite value >= 0"),
    (dict(sigma={"dl1": "big"}), r"sigma of dl1: expected a number, got 'big'"),
    (dict(sigma={"dl9": 0.1}), r"sigma: unknown parameter or kind \['dl9'\]"),
    (dict(exclude=("dl9",)), r"exclude: 'dl9' is neither a parameter .* nor a kind"),
    (dict(distribution="cauchy"), r"distribution of dl1: expected normal, uniform or truncnormal, got 'cauchy'"),
])
def test_bad_error_model_arguments(tc, kwargs, match):
    with pytest.raises(TolallocError, match=match):
        build_error_model(tc, **kwargs)


def test_bad_sigma_sets_in_robot_file(tc):
    def with_sets(sets):
        return dataclasses.replace(tc, sigma_sets=sets)

    good = dict(tc.sigma_sets["table2"])
    bad_unit = {**good, "sigma_deg": {**good["sigma_deg"], "dl1": 0.1}}
    bad_unit["sigma_mm"] = {k: v for k, v in good["sigma_mm"].items() if k != "dl1"}
    with pytest.raises(TolallocError, match=r"sigma set 's': dl1 is in mm, but was given under sigma_deg"):
        build_error_model(with_sets({"s": bad_unit}), "s")
    missing = {**good, "sigma_mm": {k: v for k, v in good["sigma_mm"].items() if k != "dl4"}}
    with pytest.raises(TolallocError, match=r"sigma set 's' has no sigma for dl4"):
        build_error_model(with_sets({"s": missing}), "s")
    with pytest.raises(TolallocError, match=r"sigma set 's': unknown key 'sigma_in'"):
        build_error_model(with_sets({"s": {**good, "sigma_in": {}}}), "s")
    with pytest.raises(TolallocError, match=r"sigma set 's': unknown error parameter 'dq7'"):
        build_error_model(with_sets({"s": {**good, "sigma_rad": {**good["sigma_rad"], "dq7": 1.0}}}), "s")


def test_model_helpers(tc):
    model = build_error_model(tc)
    assert model.index("dd4") == 9
    with pytest.raises(TolallocError, match="unknown error parameter 'x'"):
        model.index("x")
    with pytest.raises(TolallocError, match="sigma: expected 22 finite values >= 0"):
        model.with_sigma(np.ones(3))
    with pytest.raises(TolallocError, match="sigma: expected 22 finite values >= 0"):
        model.with_sigma(-np.ones(22))
    assert model.labels == {"sigma_set": "table2", "link_mode": "consistent", "deflection_mode": "screw"}
    assert set(KINDS) >= set(model.kinds)


def test_sigma_set_values_and_exclusions_are_checked(tc):
    # regressions: a non-numeric or non-table sigma set entry gave a traceback; a negative sigma_deg was
    # reported in rad; excluding every parameter crashed the Jacobian
    good = dict(tc.sigma_sets["table2"])
    cases = [({**good, "sigma_deg": {**good["sigma_deg"], "dth1": "a"}}, r"sigma_deg\.dth1 expected a finite sigma >= 0 in deg, got 'a'"),
             ({**good, "sigma_deg": {**good["sigma_deg"], "dth1": -0.1}}, r"sigma_deg\.dth1 expected a finite sigma >= 0 in deg, got -0\.1"),
             ({**good, "sigma_mm": 3}, r"sigma set 's': sigma_mm expected a table")]
    for entry, match in cases:
        with pytest.raises(TolallocError, match=match):
            build_error_model(dataclasses.replace(tc, sigma_sets={"s": entry}), "s")
    with pytest.raises(TolallocError, match="leaves no error parameter"):
        build_error_model(tc, exclude=("link_length", "joint_drive", "axis_deflection"))
