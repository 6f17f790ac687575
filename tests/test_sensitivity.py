"""Control-variable sensitivity curves and trajectory errors."""

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import pose_errors, run_mc
from tolalloc.montecarlo.sensitivity import (PAPER_JOINT_GRID_DEG, PAPER_LINK_GRID_MM, quintic_trajectory, sensitivity,
                                  trajectory_errors)


@pytest.fixture(scope="module")
def model():
    return build_error_model(load_robot("tool_changer"), "table2")


def test_link_curves_are_exact_and_linear(model):
    q = model.robot.q_nominal
    links = [f"dl{i}" for i in range(1, 7)]
    res = sensitivity(model, q, links, PAPER_LINK_GRID_MM)
    assert res.dp_mm.shape == (6, 7, 3) and res.grid.shape == (6, 7)
    zero = list(PAPER_LINK_GRID_MM).index(0.0)
    assert np.all(res.norm_mm[:, zero] < 1e-9)
    # a link error is a pure translation: |dp| equals |value| exactly (consistent model) and dp is linear in it
    assert np.allclose(res.norm_mm, np.abs(PAPER_LINK_GRID_MM)[None, :], atol=1e-9)
    J = model.jacobian(q)
    for i, name in enumerate(links):
        assert np.allclose(res.dp_mm[i], PAPER_LINK_GRID_MM[:, None] * J[:3, model.index(name)], atol=1e-9)
    assert np.all(res.rot_rad < 1e-15)


def test_joint_curves_match_jacobian_to_first_order(model):
    q = model.robot.q_nominal
    joints = ["dth1", "dth2", "dth3", "dth5", "dth6"]
    grid = np.deg2rad(PAPER_JOINT_GRID_DEG)
    res = sensitivity(model, q, joints, grid)
    J = model.jacobian(q)
    for i, name in enumerate(joints):
        lin = grid[:, None] * J[:3, model.index(name)]
        # second-order remainder: |dp - J e| <= |e|^2 * reach
        assert np.all(np.linalg.norm(res.dp_mm[i] - lin, axis=1) <= grid**2 * 2000 + 1e-12)
        assert np.allclose(res.dp_mm[i], 0, atol=1e-9) == (name == "dth6")  # the tool lies on axis 6
    # joint 1 turns about base z: it changes gamma only (the paper: theta1 has no effect on beta)
    i1 = joints.index("dth1")
    assert np.allclose(res.euler_rad[i1, :, :2], 0, atol=1e-14)
    assert np.allclose(res.euler_rad[i1, :, 2], grid, atol=1e-14)
    df = res.to_frame()
    assert len(df) == 5 * grid.size and set(df.unit) == {"deg"}
    assert np.allclose(df.value_mm_or_deg.to_numpy()[: grid.size], PAPER_JOINT_GRID_DEG)


def test_trajectory_errors(model):
    r = model.robot
    P = r.poses("working")
    t, Q = quintic_trajectory(P[1], P[11], 10.0, 21)
    assert np.allclose(Q[0], P[1]) and np.allclose(Q[-1], P[11])
    mc = run_mc(model, Q, 2000, seed=0)
    tr = trajectory_errors(model, t, Q, ["dth2", "dth3", "dd4"], mc=mc)
    assert tr.dp_mm.shape == (21, 3, 3)
    V = np.zeros((1, len(model.params)))
    V[0, model.index("dth3")] = model.sigma[model.index("dth3")]
    assert np.allclose(tr.dp_mm[7, 1], pose_errors(model, Q[7], V)["dp_mm"][0])
    # a prismatic drive error moves the tool along the telescopic arm: |dp| = sigma at every step
    assert np.allclose(np.linalg.norm(tr.dp_mm[:, 2], axis=1), 0.25)
    assert len(tr.to_frame()) == 21 * 3


def test_bad_input(model):
    q = model.robot.q_nominal
    with pytest.raises(TolallocError):
        sensitivity(model, q, ["dl99"], [0.1])
    with pytest.raises(TolallocError):
        sensitivity(model, q, ["dl1"], [np.nan])
    with pytest.raises(TolallocError):
        sensitivity(model, q, [], [0.1])
    with pytest.raises(TolallocError):
        sensitivity(model, np.full(6, 3.0), ["dl1"], [0.1])
