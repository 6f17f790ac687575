"""Linear variance map: error Jacobian vs finite differences and CasADi AD, covariance vs Monte Carlo, budget."""

import casadi as ca
import numpy as np
import pandas as pd
import pytest
from conftest import random_chain, random_q

from tolalloc import TolallocError, load_robot
from tolalloc.robot import fk_poe
from tolalloc.errormodel import build_error_model
from tolalloc.linear.covariance import VARIANCE_FACTOR, budget, input_covariance, linear_map
from tolalloc.robot.lie import rotvec

OPTIONS = [(lm, dm, cl) for lm in ("consistent", "axes_only") for dm in ("screw", "tilt") for cl in (False, True)]


# ---------------------------------------------------------------- oracles
def _fd_jacobian(model, q, h=1e-6):
    """Central differences of the exact perturbed chain (rows dp [mm], space-frame dw [rad])."""
    K = len(model.params)
    E = np.vstack([np.eye(K) * h, -np.eye(K) * h])
    screws, home, dq = model.perturbed_chain(E)
    T = fk_poe(screws, home, q + dq)
    T0 = model.robot.fk_internal(q)
    dp = (T[:K, :3, 3] - T[K:, :3, 3]) / (2 * h)
    dw = (rotvec(T[:K, :3, :3] @ T0[:3, :3].T) - rotvec(T[K:, :3, :3] @ T0[:3, :3].T)) / (2 * h)
    return np.vstack([dp.T, dw.T])


def _ca_exp(twist, x):
    """exp([twist] x) for a numeric unit-rotation or pure-translation twist and a CasADi scalar x."""
    w, v = np.asarray(twist[:3]), np.asarray(twist[3:])
    T = ca.SX.eye(4)
    if np.linalg.norm(w) > 0.5:
        assert abs(np.linalg.norm(w) - 1) < 1e-12
        W = ca.DM([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        W2 = ca.mtimes(W, W)
        R = ca.DM.eye(3) + ca.sin(x) * W + (1 - ca.cos(x)) * W2
        V = ca.DM.eye(3) * x + (1 - ca.cos(x)) * W + (x - ca.sin(x)) * W2
        T[:3, :3] = R
        T[:3, 3] = ca.mtimes(V, ca.DM(v))
    else:
        T[:3, 3] = ca.DM(v) * x
    return T


def _ca_jacobian(model, q):
    """AD oracle: T(e) = G_0 e^{S1 (q1+dq1)} G_1 ... e^{Sn (qn+dqn)} G_n M written symbolically."""
    robot = model.robot
    n, K = robot.n_joints, len(model.params)
    e = ca.SX.sym("e", K)
    site_ops = [[] for _ in range(n + 1)]
    dq = [0] * n
    for k, p in enumerate(model.params):
        if p.kind == "joint_drive":
            dq[p.joint_index] = dq[p.joint_index] + e[k]
            continue
        site_ops[p.site].append(_ca_exp(p.twist, e[k]))
        if p.undo_site is not None:
            site_ops[p.undo_site].insert(0, _ca_exp(p.twist, -e[k]))
    T = ca.SX.eye(4)
    for s in range(n + 1):
        for G in site_ops[s]:
            T = ca.mtimes(T, G)
        if s < n:
            T = ca.mtimes(T, _ca_exp(robot.screws[s], q[s] + dq[s]))
    T = ca.mtimes(T, ca.DM(robot.home))
    p = T[:3, 3]
    R = T[:3, :3]
    Jp = ca.jacobian(p, e)
    f = ca.Function("f", [e], [Jp, ca.jacobian(ca.vec(R), e), R, p])
    Jp, dR, R0, p0 = (np.array(a) for a in f(np.zeros(K)))
    T0 = robot.fk_internal(q)
    np.testing.assert_allclose(p0.ravel(), T0[:3, 3], atol=1e-9)  # the oracle's nominal FK is right
    Jw = np.zeros((3, K))
    for k in range(K):
        dRk = dR[:, k].reshape(3, 3, order="F")  # casadi vec is column-major
        X = dRk @ R0.T
        Jw[:, k] = [X[2, 1], X[0, 2], X[1, 0]]
    return np.vstack([Jp, Jw])


@pytest.mark.parametrize("link_mode,deflection_mode,clearance", OPTIONS)
def test_jacobian_vs_finite_differences_and_casadi(link_mode, deflection_mode, clearance):
    rng = np.random.default_rng(100 + OPTIONS.index((link_mode, deflection_mode, clearance)))
    for n_joints in (2, 4, 6, 8):
        robot = random_chain(rng, n_joints, p_prismatic=0.35)
        model = build_error_model(robot, "generic", link_mode=link_mode, deflection_mode=deflection_mode, clearance=clearance)
        q = random_q(rng, robot)
        J = model.jacobian(q)
        scale = np.abs(J).max()
        J_ad = _ca_jacobian(model, q)
        np.testing.assert_allclose(J, J_ad, atol=1e-9 * scale, rtol=0)
        J_fd = _fd_jacobian(model, q)
        np.testing.assert_allclose(J, J_fd, atol=1e-5 * scale, rtol=0)
        # the stacked (many-pose) Jacobian equals the one-pose one
        qs = random_q(rng, robot, size=3)
        Js = model.jacobian(qs)
        for i in range(3):
            np.testing.assert_allclose(Js[i], model.jacobian(qs[i]), atol=1e-12 * scale)


def test_linear_map_shapes_and_formula():
    rng = np.random.default_rng(1)
    robot = random_chain(rng, 5)
    model = build_error_model(robot, "generic", clearance=True)
    qs = random_q(rng, robot, size=4)
    res = linear_map(model, qs)
    K = len(model.params)
    assert res.J.shape == (4, 6, K) and res.cov_mm2.shape == (4, 3, 3) and res.std_mm.shape == (4, 3)
    S = np.diag(model.sigma**2)
    for i in range(4):
        C = res.J[i] @ S @ res.J[i].T
        np.testing.assert_allclose(res.cov_mm2[i], C[:3, :3], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(res.cov_rot_rad2[i], C[3:, 3:], rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(res.std_mm, np.sqrt(np.diagonal(res.cov_mm2, axis1=1, axis2=2)))
    one = linear_map(model, qs[2])
    np.testing.assert_allclose(one.cov_mm2[0], res.cov_mm2[2], rtol=1e-12)
    # identity correlation == independent; a full covariance is used as given
    same = linear_map(model, qs, correlation=np.eye(K))
    np.testing.assert_allclose(same.cov_mm2, res.cov_mm2, rtol=1e-12)
    A = rng.normal(size=(K, K)) * model.sigma
    Sfull = A @ A.T / K
    corr = linear_map(model, qs, cov=Sfull)
    assert corr.correlated
    np.testing.assert_allclose(corr.cov_mm2[1], (res.J[1] @ Sfull @ res.J[1].T)[:3, :3], rtol=1e-10)
    df = res.to_frame()
    assert list(df["std_x_mm"]) == pytest.approx(list(res.std_mm[:, 0]))
    np.testing.assert_allclose(res.rms_mm, np.linalg.norm(res.std_mm, axis=1))


def test_truncnormal_second_moment_factor():
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2", distribution="truncnormal")
    x = model.sample(100_000, np.random.default_rng(3))
    ratio = x.var(axis=0) / model.sigma**2
    # a sample variance's relative standard error is sqrt((kurtosis - 1) / n); kurtosis 2.83 for a normal truncated
    # at +-3 sigma: 0.43 % per parameter at n = 1e5, 0.09 % for the mean of the 22 ratios, so 3e-3 is 3.3 of them
    # (and a ninth of the factor's distance from 1)
    assert abs(ratio.mean() - VARIANCE_FACTOR["truncnormal"]) < 3e-3
    np.testing.assert_allclose(np.diag(input_covariance(model)), VARIANCE_FACTOR["truncnormal"] * model.sigma**2)


def _mc_errors(model, q, values, chain=None):
    """Exact position errors at ``q`` of the sampled ``values``; ``chain``: their perturbed chain, if computed."""
    screws, home, dq = model.perturbed_chain(values) if chain is None else chain
    T = fk_poe(screws, home, q + dq)
    return T[:, :3, 3] - model.robot.fk_internal(q)[:3, 3]


@pytest.mark.parametrize("clearance", [False, True])
def test_linear_std_matches_nonlinear_monte_carlo_table2(clearance):
    """Table 2 sigma (plus Table 4 clearance): linear std within 2 % of the exact MC std (n = 20000: the std's
    relative standard error is about 1 / sqrt(2 n) = 0.5 %, so 2 % is four of them)."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2", clearance=clearance)
    qs = np.vstack([robot.q_nominal, robot.poses("working")[[1, -1]]])
    res = linear_map(model, qs)
    values = model.sample(20_000, np.random.default_rng(42))
    chain = model.perturbed_chain(values)  # the same draws at every pose
    for i, q in enumerate(qs):
        dp = _mc_errors(model, q, values, chain)
        std = dp.std(axis=0, ddof=1)
        np.testing.assert_allclose(res.std_mm[i], std, rtol=0.02)
        np.testing.assert_allclose(res.rms_mm[i], np.sqrt((dp**2).sum(1).mean()), rtol=0.02)


def test_correlated_inputs_match_monte_carlo():
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    K = len(model.params)
    rng = np.random.default_rng(8)
    R = np.full((K, K), 0.0)
    R[6:12, 6:12] = 0.6  # correlated drive errors
    np.fill_diagonal(R, 1.0)
    res = linear_map(model, robot.q_nominal, correlation=R)
    S = res.cov_eps
    values = rng.multivariate_normal(np.zeros(K), S, size=40_000)
    dp = _mc_errors(model, robot.q_nominal, values)
    np.testing.assert_allclose(res.cov_mm2[0], np.cov(dp.T), rtol=0.03, atol=0.03 * np.abs(res.cov_mm2[0]).max())
    assert not np.allclose(res.cov_mm2, linear_map(model, robot.q_nominal).cov_mm2, rtol=0.05)


def test_budget_sums_order_and_kinds(tmp_path):
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2", clearance=True)
    res = linear_map(model, robot.poses("working"))
    b = budget(res)
    np.testing.assert_allclose(b.var.sum(axis=1)[:, :3], np.diagonal(res.cov_mm2, axis1=1, axis2=2), rtol=1e-12)
    np.testing.assert_allclose(b.total[:, 3], np.trace(res.cov_mm2, axis1=1, axis2=2), rtol=1e-12)
    np.testing.assert_allclose(b.share.sum(axis=1), 1.0, rtol=1e-12)
    assert np.all(b.var >= 0)
    # independent inputs: contribution = J_ik^2 sigma_k^2
    k = model.index("dth2")
    np.testing.assert_allclose(b.var[:, k, 0], res.J[:, 0, k] ** 2 * model.sigma[k] ** 2, rtol=1e-12)
    df = b.to_frame(pose="worst")
    # tables number poses from 1; the library index is 0-based
    assert df["pose"].unique().tolist() == [b.worst_pose + 1] == [int(np.argmax(res.rms_mm)) + 1]
    assert df["share_norm_pct"].is_monotonic_decreasing
    kinds = b.to_frame(by="kind", pose=0)
    assert kinds["share_norm_pct"].sum() == pytest.approx(100.0)
    assert set(kinds["kind"]) == set(model.kinds)
    jd = kinds.set_index("kind").loc["joint_drive", "var_x_mm2"]
    assert jd == pytest.approx(b.var[0, model.kinds == "joint_drive", 0].sum())
    b.write_csv(tmp_path / "b.csv")
    back = pd.read_csv(tmp_path / "b.csv")
    assert len(back) == res.n_poses * len(model.params)
    # sigma in a unit pair: mm on length rows, deg on angle rows, the other one blank
    assert "sigma" not in back and list(back.columns[3:6]) == ["unit", "sigma_mm", "sigma_deg"]
    mm = (back["unit"] == "mm").to_numpy()
    assert back["sigma_mm"][mm].notna().all() and back["sigma_mm"][~mm].isna().all()
    assert back["sigma_deg"][~mm].notna().all() and back["sigma_deg"][mm].isna().all()
    row = back[(back["pose"] == 1) & (back["parameter"] == "dth2")].iloc[0]
    assert row["sigma_deg"] == pytest.approx(np.rad2deg(model.sigma[k]), rel=1e-5)
    b.write_markdown(tmp_path / "b.md", top=5)
    text = (tmp_path / "b.md").read_text()
    assert "share_norm_pct" in text and text.count("\n") == 5 + 2
    assert "sigma_mm" in text and "sigma_deg" in text and "nan" not in text  # the empty one of each pair is blank
    rot = budget(res, "rotation")
    np.testing.assert_allclose(rot.total[:, 3], np.trace(res.cov_rot_rad2, axis1=1, axis2=2), rtol=1e-12)


def test_budget_correlated_euler_allocation_sums():
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    K = len(model.params)
    R = np.eye(K)
    R[6, 7] = R[7, 6] = -0.8
    res = linear_map(model, robot.q_nominal, correlation=R)
    b = budget(res)
    np.testing.assert_allclose(b.total[0, :3], np.diag(res.cov_mm2[0]), rtol=1e-12)


def test_bad_input():
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    K = len(model.params)
    with pytest.raises(TolallocError, match="6 values"):
        linear_map(model, np.zeros(5))
    with pytest.raises(TolallocError, match="outside its limits"):
        linear_map(model, np.full(6, 3.0))
    with pytest.raises(TolallocError, match="positive semi-definite"):
        linear_map(model, robot.q_nominal, cov=-np.eye(K))
    with pytest.raises(TolallocError, match="ones on the diagonal"):
        linear_map(model, robot.q_nominal, correlation=2 * np.eye(K))
    with pytest.raises(TolallocError, match=f"\\({K}, {K}\\)"):
        linear_map(model, robot.q_nominal, cov=np.eye(3))
    with pytest.raises(TolallocError, match="either"):
        linear_map(model, robot.q_nominal, cov=np.eye(K), correlation=np.eye(K))
    b = budget(linear_map(model, robot.q_nominal))
    with pytest.raises(TolallocError, match="pose"):
        b.to_frame(pose=3)
    with pytest.raises(TolallocError, match="by"):
        b.to_frame(by="joint")
    with pytest.raises(TolallocError, match="quantity"):
        budget(linear_map(model, robot.q_nominal), "speed")


def test_budget_refuses_what_is_not_a_linear_result():
    # regression: budget(model, q) ended in a numpy "truth value of an array is ambiguous" error
    model = build_error_model(load_robot("tool_changer"))
    with pytest.raises(TolallocError, match=r"result: expected a LinearResult \(from linear_map\(model, q\)\), got "
                                            r"ErrorModel"):
        budget(model, np.zeros(6))
