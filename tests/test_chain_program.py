"""One perturbed-chain program for every consumer (issue 11, item 2).

The program of each model is built once (``ErrorModel.program``); every consumer -- the generic path
(``perturbed_chain`` + ``fk_poe``, its numpy and compiled walks), the numpy engine (``FastChain``), the numba
engine (the compiled chain loop and the fused statistics kernel), the error Jacobian (numpy and numba) -- is
checked on the same random samples against a reference written here from the parameters' insertion rules with
``exp_se3`` alone (exact consumers to 1e-9 mm / rad; Jacobians against central differences of the reference to 1e-6
relative).
A second test edits a program and checks that every consumer follows the edit.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from conftest import random_chain, random_q

from tolalloc import load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.chain import ERROR, JOINT, FastChain, chain_program
from tolalloc.errormodel.features import N_BUF, ErrorFeatures, features_to_dict
from tolalloc.exceptions import TolallocError
from tolalloc.montecarlo.engines import numba_engine
from tolalloc.robot.kinematics import fk_poe
from tolalloc.robot.lie import exp_se3, rotvec

ATOL = 1e-9


def prismatic_chain():
    """A random 5-joint chain with two prismatic joints on skew axes (general-rotation and translation branches)."""
    rng = np.random.default_rng(11)
    while True:
        r = random_chain(rng, 5, p_prismatic=0.4)
        if 2 <= int((~r.revolute_mask).sum()) < 5:
            return r


def cases():
    tc, ur = load_robot("tool_changer"), load_robot("ur10")  # tool_changer: joint 4 is prismatic
    out = []
    for robot in (tc, ur, prismatic_chain()):
        for opts in (dict(), dict(link_mode="axes_only", deflection_mode="tilt", clearance=True)):
            out.append(pytest.param(robot, opts, id=f"{robot.name}-{'-'.join(map(str, opts.values())) or 'default'}"))
    return out


def pose_of(robot, seed=0):
    rng = np.random.default_rng(seed)
    if robot.name == "random":
        return random_q(rng, robot)
    return rng.uniform(np.maximum(robot.lower, -3.0), np.minimum(robot.upper, 3.0))


def reference_T(model, q, V):
    """``G_0 E_1 G_1 ... E_n G_n M`` from the parameters directly: at each site the undos (later parameters
    first), then the insertions in parameter order, then the joint with its drives; shape (N, 4, 4)."""
    robot, N = model.robot, V.shape[0]
    n = robot.n_joints
    T = np.broadcast_to(np.eye(4), (N, 4, 4)).copy()
    for s in range(n + 1):
        undos = [k for k, p in enumerate(model.params) if p.kind != "joint_drive" and p.undo_site == s][::-1]
        direct = [k for k, p in enumerate(model.params) if p.kind != "joint_drive" and p.site == s]
        for k, sign in [(k, -1.0) for k in undos] + [(k, 1.0) for k in direct]:
            T = T @ exp_se3(sign * V[:, k, None] * model.params[k].twist)
        if s < n:
            dq = sum(V[:, k] for k, p in enumerate(model.params) if p.kind == "joint_drive" and p.joint_index == s)
            T = T @ exp_se3((q[s] + dq)[:, None] * robot.screws[s])
    return T @ robot.home


def numba_chain(model, q, V):
    """The numba engine's compiled chain loop on ``V`` (N, K), N <= CHUNK: tool poses as rows (N, 3, 4)."""
    from tolalloc.montecarlo.engines import _kernel_nb as nb

    chain = FastChain(model)
    fi, fk, fcf, fd, endoff, _, home = numba_engine.compile_programs([chain.program(q)], [ErrorFeatures(np.eye(4))],
                                                                     chain.home)
    Vt = np.ascontiguousarray(V.T)
    X, Y = np.empty((3, 4, nb.CHUNK)), np.empty((3, 4, nb.CHUNK))
    th, S, C = np.empty(nb.CHUNK), np.empty(nb.CHUNK), np.empty(nb.CHUNK)
    nb._chain(Vt, 0, len(V), fi[0], fk[0], fcf[0], fd[0], endoff[0], home, X, Y, th, S, C)
    return np.moveaxis(X[:, :, :len(V)], -1, 0)


def numba_features(model, q, V):
    """Per-sample features kept by the numba engine's fused block kernel (``block_stats``) at pose ``q``."""
    chain = FastChain(model)
    compiled = numba_engine.compile_programs([chain.program(q)], [ErrorFeatures(model.robot.fk_internal(q))], chain.home)
    out = numba_engine.block_stats(compiled, np.ascontiguousarray(V.T), 128, [], [], None, len(V))
    assert out is not None
    return features_to_dict(out[2])


def features_of(T, T0):
    X = np.ascontiguousarray(np.moveaxis(T[:, :3, :], 0, -1))
    N = X.shape[2]
    return features_to_dict(ErrorFeatures(T0).compute(X, np.empty((N_BUF, N)), np.empty((2, N))))


def fd_jacobian(pose_fn, K, h=1e-6):
    """Central differences of ``pose_fn(values (N, K)) -> T (N, 4, 4)`` at zero: rows dp [mm], dw [rad] (6, K)."""
    E = np.eye(K) * h
    Tp, Tm = pose_fn(E), pose_fn(-E)
    dp = (Tp[:, :3, 3] - Tm[:, :3, 3]) / (2 * h)
    dw = rotvec(Tp[:, :3, :3] @ np.swapaxes(Tm[:, :3, :3], 1, 2)) / (2 * h)
    return np.concatenate([dp, dw], axis=1).T


def assert_jacobian(J, ref):
    for rows in (slice(0, 3), slice(3, 6)):
        scale = max(np.max(np.abs(ref[rows])), 1e-12)
        assert np.allclose(J[rows], ref[rows], rtol=0, atol=1e-6 * scale), float(np.max(np.abs(J[rows] - ref[rows])))


def test_program_structure_matches_parameters():
    model = build_error_model(load_robot("tool_changer"), "table2", link_mode="axes_only", deflection_mode="tilt",
                              clearance=True)
    prog = model.program
    assert prog is model.program  # built once per model
    n, K = model.robot.n_joints, len(model.params)
    assert prog.coef.shape == (prog.n_factors, K) and list(prog.joint[prog.kind == JOINT]) == list(range(n))
    assert np.all(np.diff(prog.site) >= 0) and np.all(prog.site[prog.kind == JOINT] == np.arange(n))
    for k, p in enumerate(model.params):
        rows = np.flatnonzero(prog.coef[:, k])
        if p.kind == "joint_drive":
            assert len(rows) == 1 and prog.kind[rows[0]] == JOINT and prog.joint[rows[0]] == p.joint_index
            continue
        want = [(p.site, 1.0)] + ([] if p.undo_site is None else [(p.undo_site, -1.0)])
        assert [(int(prog.site[f]), float(prog.coef[f, k])) for f in rows] == want, p.name
        assert all(prog.kind[f] == ERROR and np.array_equal(prog.twist[f], p.twist) for f in rows)
    ptr, site, coef, _ = prog.param_entries()
    assert ptr[-1] == np.count_nonzero(prog.coef) and np.all(np.diff(ptr) >= 1)


@pytest.mark.parametrize("robot,opts", cases())
def test_every_consumer_equals_reference(robot, opts):
    model = build_error_model(robot, "generic", **opts)
    K = len(model.params)
    q = pose_of(robot)
    V = model.sample(200, np.random.default_rng(3)) * 30.0  # errors of order 0.5 mm / 0.003 rad and more
    ref = reference_T(model, q, V)
    for engine in ("numpy", "numba"):  # generic path, both walks over the program
        screws, home, dq = model.perturbed_chain(V, engine=engine)
        assert np.allclose(fk_poe(screws, home, q + dq), ref, rtol=0, atol=ATOL), engine
    X = FastChain(model).pose(q, V)  # numpy engine
    assert np.allclose(np.moveaxis(X, -1, 0), ref[:, :3], rtol=0, atol=ATOL)
    assert np.allclose(numba_chain(model, q, V), ref[:, :3], rtol=0, atol=ATOL)  # numba engine, chain loop
    want, got = features_of(ref, robot.fk_internal(q)), numba_features(model, q, V)  # numba engine, fused kernel
    for key in want:
        assert np.allclose(got[key], want[key], rtol=0, atol=ATOL), key
    Jref = fd_jacobian(lambda E: reference_T(model, q, E), K)
    assert_jacobian(model.jacobian(q, engine="numpy"), Jref)
    assert_jacobian(model.jacobian(q[None], engine="numba")[0], Jref)


def test_every_consumer_follows_an_edited_program():
    """Double one parameter's coefficient (also at its undo site) and move a joint drive's amount into another
    joint: the generic path, both engines and both Jacobians change together (no consumer keeps its own table)."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2", deflection_mode="tilt", clearance=True)
    prog = chain_program(model)
    coef = prog.coef.copy()
    coef[:, model.index("e2y")] *= 2.0
    j5 = np.flatnonzero((prog.kind == JOINT) & (prog.joint == 4))[0]
    coef[j5, model.index("dth3")] = 0.5
    edited = replace(prog, coef=coef)
    object.__setattr__(model, "program", edited)  # what a changed insertion rule would build
    assert model.program is edited
    q = robot.poses("working")[3]
    V = model.sample(100, np.random.default_rng(4)) * 30.0
    screws, home, dq = model.perturbed_chain(V, engine="numpy")
    T = fk_poe(screws, home, q + dq)
    assert np.allclose(dq[:, 4], 0.5 * V[:, model.index("dth3")] + V[:, model.index("dth5")], rtol=0, atol=1e-15)
    s_nb, h_nb, dq_nb = model.perturbed_chain(V, engine="numba")
    assert np.allclose(dq_nb, dq, rtol=0, atol=1e-15)
    assert np.allclose(fk_poe(s_nb, h_nb, q + dq_nb), T, rtol=0, atol=ATOL)
    assert not np.allclose(T, reference_T(model, q, V), rtol=0, atol=1e-6)  # the edit is visible
    assert np.allclose(np.moveaxis(FastChain(model).pose(q, V), -1, 0), T[:, :3], rtol=0, atol=ATOL)
    assert np.allclose(numba_chain(model, q, V), T[:, :3], rtol=0, atol=ATOL)

    def generic(E):
        s, h, d = model.perturbed_chain(E)
        return fk_poe(s, h, q + d)

    Jref = fd_jacobian(generic, len(model.params))
    assert_jacobian(model.jacobian(q, engine="numpy"), Jref)
    assert_jacobian(model.jacobian(q[None], engine="numba")[0], Jref)


@pytest.mark.parametrize("engine", ["numpy", "numba"])
def test_values_of_another_width_are_refused(engine):
    """Parameter values or joint values of another shape, and sample counts that are not whole numbers, are refused
    with the expected shape (they were ignored or ended in a numpy error); a single row as a 1-D array is accepted."""
    model = build_error_model(load_robot("ur10"), "generic")
    K = len(model.params)
    V = model.sample(3, np.random.default_rng(5))
    for bad in (np.hstack([V, V[:, :1]]), V[:, :-1], V[..., None]):
        with pytest.raises(TolallocError, match=rf"expected shape \(N, {K}\).*got shape"):
            model.perturbed_chain(bad, engine=engine)
    with pytest.raises(TolallocError, match=rf"values: expected shape \({K}, N\) with transposed=True, got shape"):
        FastChain(model).pose(np.zeros(6), V[:, :-1].T, transposed=True)
    with pytest.raises(TolallocError, match=rf"values: expected shape \(N, {K}\), got shape \(3, {K + 1}\)"):
        FastChain(model).pose(np.zeros(6), np.hstack([V, V[:, :1]]))
    with pytest.raises(TolallocError, match=r"q: expected shape \(6,\), got shape \(2, 6\); one value per joint"):
        FastChain(model).pose(np.zeros((2, 6)), V)
    with pytest.raises(TolallocError, match=r"q: expected shape \(6,\) or \(\.\.\., 6\), got shape \(4, 5\)"):
        model.jacobian(np.zeros((4, 5)), engine=engine)
    for n in (-1, 2.5, True):
        with pytest.raises(TolallocError, match=r"n: expected a whole number of samples >= 0"):
            model.sample(n, np.random.default_rng(0))
    s1, h1, d1 = model.perturbed_chain(V[0], engine=engine)
    s3, h3, d3 = model.perturbed_chain(V, engine=engine)
    assert s1.shape == (1, 6, 6) and np.array_equal(h1[0], h3[0]) and np.array_equal(d1[0], d3[0])
