"""The compiled Jacobian kernels (tolalloc/_jacobian_nb.py) against the numpy reference, and the dispatch."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import random_chain, random_q

import tolalloc.robot.kinematics as kinematics_mod
from tolalloc import TolallocError, engine, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.robot.kinematics import JAC_KERNEL_MIN_POSES, space_jacobian

RTOL = 1e-12
OPTIONS = [dict(link_mode=lm, deflection_mode=dm, clearance=c)
           for lm in ("consistent", "axes_only") for dm in ("screw", "tilt") for c in (False, True)]


def assert_close(a, b):
    """Equal to ``RTOL`` relative to each pose's largest entry (rows mix mm and rad: per row block too)."""
    assert a.shape == b.shape and np.all(np.isfinite(a))
    for rows in (slice(0, 3), slice(3, 6)):
        scale = np.max(np.abs(b[..., rows, :]), axis=(-2, -1), keepdims=True)
        err = np.abs(a[..., rows, :] - b[..., rows, :])
        assert np.all(err <= RTOL * np.maximum(scale, 1e-300)), float(np.max(err / np.maximum(scale, 1e-300)))


def robots():
    rng = np.random.default_rng(7)
    return [load_robot("tool_changer"), load_robot("ur10")] + [random_chain(rng, n) for n in (1, 3, 6, 7, 9)]


def poses(robot, P, seed=0):
    rng = np.random.default_rng(seed)
    if robot.name == "random":
        return random_q(rng, robot, P)
    return rng.uniform(robot.lower, robot.upper, (P, robot.n_joints))


@pytest.mark.parametrize("robot", robots(), ids=lambda r: f"{r.name}{r.n_joints}")
def test_space_jacobian_equals_numpy(robot):
    q = poses(robot, 200)
    ref = space_jacobian(robot.screws, q, engine="numpy")
    from tolalloc.robot import _jacobian_nb

    assert_close(_jacobian_nb.space_jacobian(robot.screws, q), ref)  # the kernel itself, called directly
    assert_close(robot.space_jacobian_internal(q), ref)  # dispatched (P >= JAC_KERNEL_MIN_POSES)
    assert_close(robot.space_jacobian_internal(q[:3], engine="numba"), ref[:3])
    # independent check: finite difference of the spatial twist, T(q + h e_j) T(q)^-1 ~ exp([J_j] h)
    h = 1e-6
    for j in range(robot.n_joints):
        dq = np.zeros(robot.n_joints)
        dq[j] = h
        T0, T1, T2 = robot.fk_internal(q[:5]), robot.fk_internal(q[:5] + dq), robot.fk_internal(q[:5] - dq)
        dT = (T1 - T2) / (2 * h) @ np.linalg.inv(T0)
        tw = np.stack([dT[:, 2, 1], dT[:, 0, 2], dT[:, 1, 0], dT[:, 0, 3], dT[:, 1, 3], dT[:, 2, 3]], axis=-1)
        J = robot.space_jacobian_internal(q[:5], engine="numba")[:, :, j]
        assert np.allclose(J, tw, rtol=1e-5, atol=1e-5 * (1 + np.max(np.abs(tw))))


@pytest.mark.parametrize("opts", OPTIONS, ids=lambda o: "-".join(str(v) for v in o.values()))
@pytest.mark.parametrize("robot", robots()[:4], ids=lambda r: f"{r.name}{r.n_joints}")
def test_error_jacobian_equals_numpy(robot, opts):
    model = build_error_model(robot, "generic", **opts)
    assert any(p.undo_site is not None for p in model.params) == (
        opts["link_mode"] == "axes_only" or (opts["deflection_mode"] == "tilt" and robot.revolute_mask.any()))
    q = poses(robot, 150, seed=3)
    ref = model.jacobian(q, engine="numpy")
    assert_close(model.jacobian(q), ref)
    assert_close(model.jacobian(q[:2], engine="numba"), ref[:2])


def test_dispatch_rules(monkeypatch):
    """Kernel for one chain at many poses; numpy for single poses, stacked chains, general screws."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    calls = []
    from tolalloc.robot import _jacobian_nb

    for name in ("space_jacobian", "error_jacobian"):
        orig = getattr(_jacobian_nb, name)
        monkeypatch.setattr(_jacobian_nb, name, lambda *a, _f=orig, _n=name: calls.append(_n) or _f(*a))
    q = poses(robot, JAC_KERNEL_MIN_POSES)
    robot.space_jacobian_internal(q)
    model.jacobian(q)
    assert calls == ["space_jacobian", "error_jacobian"]
    calls.clear()
    robot.space_jacobian_internal(q[:-1])  # below the threshold
    robot.space_jacobian_internal(q[0])  # one pose
    model.jacobian(q[0])
    model.jacobian(q[None])  # (1, P, n): not 2-D
    space_jacobian(np.broadcast_to(robot.screws, (len(q),) + robot.screws.shape), q)  # a stack of chains
    space_jacobian(robot.screws * 1.5, q)  # not joint screws: general exponential
    monkeypatch.setenv("TOLALLOC_NUMBA", "0")
    robot.space_jacobian_internal(q)
    model.jacobian(q)
    assert calls == []
    with pytest.raises(TolallocError, match="engine"):
        robot.space_jacobian_internal(q, engine="fortran")


def test_numba_absent(monkeypatch):
    """Without numba (as if not installed) every call takes the numpy path with the same results."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot, clearance=True)
    q = poses(robot, 100)
    monkeypatch.setattr(engine, "NUMBA_AVAILABLE", False)
    assert kinematics_mod.jacobian_kernel(robot.screws, q, None) is None
    with pytest.raises(TolallocError, match="numba"):
        robot.space_jacobian_internal(q, engine="numba")
    J, E = robot.space_jacobian_internal(q), model.jacobian(q)
    assert np.array_equal(J, robot.space_jacobian_internal(q, engine="numpy"))
    assert np.array_equal(E, model.jacobian(q, engine="numpy"))
    assert J.shape == (100, 6, robot.n_joints) and E.shape == (100, 6, len(model.params))
