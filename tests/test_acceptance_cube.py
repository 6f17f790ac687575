"""The ISO 9283 test cube (tolalloc.acceptance.cube, .test): P1-P5 where the standard puts them, the inverse
kinematics reaching them inside the region, and a cube that does not fit refused with the largest that does."""

import numpy as np
import pytest

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.acceptance import TestCube, acceptance_test
from tolalloc.acceptance.cube import PLANES, place_cube, solve_ik
from iso_setup import ur10_test


@pytest.fixture(scope="module")
def ur10():
    return ur10_test()[0]


@pytest.mark.parametrize("plane", sorted(PLANES))
def test_test_points_on_the_diagonal_plane(plane):
    cube = TestCube(np.array([100.0, -50.0, 400.0]), 200.0, np.eye(3), plane)
    P = cube.test_points()
    c = cube.plane_corners()
    np.testing.assert_allclose(P[0], cube.centre_mm)
    diag = np.linalg.norm(c[2] - c[0])
    assert diag == pytest.approx(200.0 * np.sqrt(3))  # a space diagonal of the cube
    for k in range(4):  # 10 % of the diagonal from its corner, on that diagonal
        assert np.linalg.norm(P[k + 1] - c[k]) == pytest.approx(0.1 * diag)
        assert np.linalg.norm(np.cross(P[k + 1] - c[k], cube.centre_mm - c[k])) == pytest.approx(0, abs=1e-9)
    # the plane holds two opposite edges: its corners are coplanar with the centre
    n = np.cross(c[1] - c[0], c[3] - c[0])
    assert abs(n @ (c[2] - c[0])) < 1e-6 and abs(n @ (cube.centre_mm - c[0])) < 1e-6


def test_ik_reaches_poses_inside_the_box(ur10):
    rng = np.random.default_rng(0)
    q_true = rng.uniform(-1, 1, (6, 6))
    T = ur10.fk_internal(q_true)
    q, ok = solve_ik(ur10, T, q_true + 0.05, np.full(6, -1.2), np.full(6, 1.2))
    assert ok.all()
    np.testing.assert_allclose(ur10.fk_internal(q), T, atol=1e-6)


def test_given_cube_checked_and_too_large_refused(ur10):
    test = ur10_test()[1]
    c = test.placement.cube
    q = test.q_test
    lo, hi = test.placement.q_min, test.placement.q_max
    assert np.all((q >= lo - 1e-12) & (q <= hi + 1e-12))
    np.testing.assert_allclose(test.commanded(q), c.test_points(), atol=1e-5)
    np.testing.assert_allclose(ur10.fk_internal(q)[:, :3, :3], np.broadcast_to(c.rotation, (5, 3, 3)), atol=1e-8)
    small = place_cube(ur10, lo, hi, centre_mm=c.centre_mm, edge_mm=0.5 * c.edge_mm)
    assert not small.searched and small.cube.edge_mm == pytest.approx(0.5 * c.edge_mm)
    with pytest.raises(TolallocError, match=r"cube_edge_mm: a cube of edge 10000 mm at .* does not fit the working "
                                            r"region .*; the largest that fits there has an edge of [0-9.]+ mm with "
                                            r"the tool orientation held; [0-9.]+ mm with the tool orientation free\. "
                                            r"Give cube_edge_mm <= "):
        place_cube(ur10, lo, hi, centre_mm=c.centre_mm, edge_mm=1e4)


def test_bad_test_settings(ur10):
    with pytest.raises(TolallocError, match=r"cycles: expected a whole number of cycles of at least 2 .* got 1"):
        acceptance_test(ur10, cycles=1)
    with pytest.raises(ArgumentError, match=r"registration: expected one of corners, none"):
        acceptance_test(ur10, registration="best_fit")
