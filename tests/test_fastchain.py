"""FastChain kernel branches and ErrorFeatures against independent computations."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tolalloc import load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.features import FEATURES, N_BUF, ErrorFeatures
from tolalloc.robot.lie import euler_xyz_fixed
from tolalloc.montecarlo.run import generic_pose_errors, pose_errors
from tolalloc.robot.kinematics import fk_poe


@pytest.fixture(scope="module")
def model():
    return build_error_model(load_robot("tool_changer"), "table2", clearance=True)


@pytest.mark.parametrize("scale", [1.0, 400.0])  # 400 sigma: angles beyond 1 rad take the np.cos branch
def test_pose_equals_fk_poe(model, scale):
    V = model.sample(300, np.random.default_rng(5)) * scale
    q = model.robot.poses("working")[3]
    X = FastChain(model).pose(q, V)
    screws, home, dq = model.perturbed_chain(V)
    T = fk_poe(screws, home, q + dq)
    assert np.allclose(np.moveaxis(X, -1, 0), T[:, :3, :], rtol=0, atol=1e-9 * max(1.0, scale))


def test_program_drops_zero_sigma_and_folds_multipliers(model):
    chain = FastChain(model)
    q = model.robot.q_nominal
    mult = model.sigma.copy()
    mult[model.index("dl3")] = 0.0
    prog = chain.program(q, mult)
    used = {k for _, coefs, _, _, _ in prog.steps for k, _ in coefs}
    assert model.index("dl3") not in used and model.index("dl4") in used
    Z = np.random.default_rng(0).standard_normal((len(model.params), 50))
    X = np.empty((3, 4, 50))
    chain.run(prog, Z, X, chain.workspace(50))
    V = (Z * mult[:, None]).T
    assert np.allclose(X, chain.pose(q, V), rtol=0, atol=1e-10)


def test_features_against_scipy_and_euler(model):
    rng = np.random.default_rng(2)
    T0 = model.robot.fk_internal(model.robot.poses("working")[5])
    R = Rotation.from_rotvec(rng.normal(0, 0.3, (200, 3))).as_matrix() @ T0[:3, :3]
    p = T0[:3, 3] + rng.normal(0, 2.0, (200, 3))
    X = np.ascontiguousarray(np.moveaxis(np.concatenate([R, p[:, :, None]], axis=2), 0, -1))
    buf = np.empty((N_BUF, 200))
    F = ErrorFeatures(T0).compute(X, buf, np.empty((2, 200)))
    f = dict(zip(FEATURES, F))
    assert np.allclose(np.stack([f["dx"], f["dy"], f["dz"]], 1), p - T0[:3, 3], atol=1e-12)
    assert np.allclose(f["reach"], np.linalg.norm(p, axis=1) - np.linalg.norm(T0[:3, 3]), atol=1e-9)
    rv = Rotation.from_matrix(R @ T0[:3, :3].T).as_rotvec()
    assert np.allclose(np.stack([f["rvx"], f["rvy"], f["rvz"]], 1), rv, atol=1e-12)
    assert np.allclose(ErrorFeatures.angle_row(buf, 200), np.linalg.norm(rv, axis=1), atol=1e-12)
    d = euler_xyz_fixed(R) - euler_xyz_fixed(T0[:3, :3])
    d = (d + np.pi) % (2 * np.pi) - np.pi
    assert np.allclose(np.stack([f["alpha"], f["beta"], f["gamma"]], 1), d, atol=1e-12)


def test_rotation_near_pi_uses_fallback(model):
    T0 = np.eye(4)
    R = Rotation.from_rotvec([[0, 0, np.pi - 1e-9], [0.0, 3.0, 0.0], [0.1, 0, 0]]).as_matrix()
    X = np.ascontiguousarray(np.moveaxis(np.concatenate([R, np.zeros((3, 3, 1))], axis=2), 0, -1))
    buf = np.empty((N_BUF, 3))
    F = ErrorFeatures(T0).compute(X, buf, np.empty((2, 3)))
    assert np.allclose(np.linalg.norm(F[3:6], axis=0), [np.pi - 1e-9, 3.0, 0.1], atol=1e-7)


def test_pose_errors_generic_large_joint_angles(model):
    q = np.deg2rad([89.0, 60.0, -45.0, 0.0, 90.0, -175.0])  # |angles| > 1 rad: the np.cos branch
    q[3] = 450.0
    V = model.sample(200, np.random.default_rng(1)) * 20
    a, b = pose_errors(model, q, V), generic_pose_errors(model, q, V)
    for k in a:
        assert np.allclose(a[k], b[k], rtol=0, atol=1e-9), k
