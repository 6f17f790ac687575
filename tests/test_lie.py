"""SO(3)/SE(3) algebra: closed forms, scipy's matrix exponential, and hypothesis round trips."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from tolalloc.robot.lie import (adjoint, euler_xyz_fixed, exp_se3, exp_so3, hat, inv_transform, rot_x, rot_y, rot_z,
                          rotvec, transform)

finite = st.floats(-10.0, 10.0, allow_nan=False, allow_infinity=False)
vec3 = arrays(float, 3, elements=finite)
twist = arrays(float, 6, elements=st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False))
SETTINGS = settings(max_examples=60, deadline=None)


def se3_matrix(xi):
    X = np.zeros((4, 4))
    X[:3, :3] = hat(xi[:3])
    X[:3, 3] = xi[3:]
    return X


@SETTINGS
@given(vec3, vec3)
def test_hat_is_cross_product(w, x):
    np.testing.assert_allclose(hat(w) @ x, np.cross(w, x), atol=1e-12)
    np.testing.assert_allclose(hat(w), -hat(w).T)


@SETTINGS
@given(vec3)
def test_exp_so3_is_rotation_and_matches_expm(w):
    R = exp_so3(w)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(R, expm(hat(w)), atol=1e-11)
    np.testing.assert_allclose(R @ w, w, atol=1e-10)  # the axis is fixed


@SETTINGS
@given(twist)
def test_exp_se3_matches_expm(xi):
    np.testing.assert_allclose(exp_se3(xi), expm(se3_matrix(xi)), atol=1e-10 * max(1, np.abs(xi).max()))


@pytest.mark.parametrize("theta", [0.0, 1e-12, 1e-8, 9.99e-5, 1e-4, 1.0001e-4, 1e-3])
def test_exp_small_angles_continuous(theta):
    """The Taylor branch near 0 and the closed form agree with expm on both sides of the switch."""
    rng = np.random.default_rng(0)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    xi = np.concatenate([theta * axis, [300.0, -200.0, 100.0]])
    np.testing.assert_allclose(exp_se3(xi), expm(se3_matrix(xi)), atol=1e-12)
    np.testing.assert_allclose(exp_so3(theta * axis), expm(hat(theta * axis)), atol=1e-15)


def test_pure_translation_and_screw_closed_form():
    np.testing.assert_allclose(exp_se3([0, 0, 0, 1, 2, 3]), transform(None, [1, 2, 3]))
    # rotation by a about z through the point (1, 0, 0): v = -w x p = (0, -1, 0)
    a = 0.7
    T = exp_se3(np.array([0, 0, 1, 0, -1, 0]) * a)
    np.testing.assert_allclose(T[:3, :3], rot_z(a), atol=1e-15)
    np.testing.assert_allclose(T[:3, 3], [1 - np.cos(a), -np.sin(a), 0], atol=1e-15)


def test_elementary_rotations():
    a = 0.3
    c, s = np.cos(a), np.sin(a)
    np.testing.assert_allclose(rot_x(a), [[1, 0, 0], [0, c, -s], [0, s, c]], atol=1e-15)
    np.testing.assert_allclose(rot_y(a), [[c, 0, s], [0, 1, 0], [-s, 0, c]], atol=1e-15)
    np.testing.assert_allclose(rot_z(a), [[c, -s, 0], [s, c, 0], [0, 0, 1]], atol=1e-15)


@SETTINGS
@given(twist, twist)
def test_adjoint_conjugation_and_inverse(xi_T, xi):
    T = exp_se3(xi_T)
    # Ad_T xi is the twist of T [xi] T^-1
    np.testing.assert_allclose(se3_matrix(adjoint(T) @ xi), T @ se3_matrix(xi) @ inv_transform(T),
                               atol=1e-9 * max(1, np.abs(xi_T).max()) ** 2 * max(1, np.abs(xi).max()))
    # exp(Ad_T xi) = T exp(xi) T^-1
    np.testing.assert_allclose(exp_se3(adjoint(T) @ xi), T @ exp_se3(xi) @ inv_transform(T), atol=1e-8)
    np.testing.assert_allclose(inv_transform(T) @ T, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(adjoint(inv_transform(T)) @ adjoint(T), np.eye(6), atol=1e-9)


@SETTINGS
@given(twist, twist)
def test_adjoint_is_homomorphism(a, b):
    A, B = exp_se3(a), exp_se3(b)
    np.testing.assert_allclose(adjoint(A @ B), adjoint(A) @ adjoint(B), atol=1e-9)


@SETTINGS
@given(twist)
def test_exp_inverse(xi):
    np.testing.assert_allclose(exp_se3(-xi), inv_transform(exp_se3(xi)), atol=1e-10)


@SETTINGS
@given(arrays(float, 3, elements=st.floats(-1.0, 1.0)))
def test_rotvec_roundtrip(w):
    # keep |w| < pi (unique rotation vector)
    np.testing.assert_allclose(rotvec(exp_so3(w)), w, atol=1e-12)


@SETTINGS
@given(st.floats(-3.1, 3.1), st.floats(-1.5, 1.5), st.floats(-3.1, 3.1))
def test_euler_xyz_fixed_roundtrip(alpha, beta, gamma):
    R = rot_z(gamma) @ rot_y(beta) @ rot_x(alpha)
    np.testing.assert_allclose(euler_xyz_fixed(R), [alpha, beta, gamma], atol=1e-9)
    # independent: scipy's extrinsic xyz
    np.testing.assert_allclose(R, Rotation.from_euler("xyz", [alpha, beta, gamma]).as_matrix(), atol=1e-12)


def test_broadcasting_over_stacks():
    rng = np.random.default_rng(1)
    xi = rng.normal(size=(4, 5, 6))
    T = exp_se3(xi)
    assert T.shape == (4, 5, 4, 4)
    np.testing.assert_allclose(T[2, 3], exp_se3(xi[2, 3]))
    Ad = adjoint(T)
    assert Ad.shape == (4, 5, 6, 6)
    np.testing.assert_allclose(Ad[1, 4], adjoint(T[1, 4]))
    np.testing.assert_allclose(inv_transform(T)[0, 1], inv_transform(T[0, 1]))
    assert rotvec(T[..., :3, :3]).shape == (4, 5, 3)
    assert euler_xyz_fixed(T[..., :3, :3]).shape == (4, 5, 3)
    assert exp_so3(xi[..., :3]).shape == (4, 5, 3, 3)


def test_cross_equals_numpy_cross_and_broadcasts():
    """lie.cross against numpy.cross on stacks of different shapes, broadcasting a single vector and a stack."""
    from tolalloc.robot.lie import cross

    rng = np.random.default_rng(0)
    for sa, sb in (((3,), (3,)), ((7, 3), (7, 3)), ((4, 5, 3), (5, 3)), ((6, 3), (3,)), ((2, 1, 3), (1, 4, 3))):
        a, b = rng.normal(size=sa), rng.normal(size=sb)
        assert np.array_equal(cross(a, b), np.cross(a, b)), (sa, sb)
    assert np.array_equal(cross([1, 0, 0], [0, 1, 0]), [0.0, 0.0, 1.0])
    # the 3-vectors as columns (axis=-2): a vector across a stack of K columns, as the error model's Jacobian uses it
    a, B = rng.normal(size=(4, 3)), rng.normal(size=(4, 3, 7))
    assert np.array_equal(cross(a[..., :, None], B, axis=-2), np.cross(a[..., :, None], B, axisa=-2, axisb=-2, axisc=-2))
