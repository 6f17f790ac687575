"""The ISO 9283 test cube in the working region, its test poses P1-P5, and the inverse kinematics that reaches them.

ISO 9283:1998 6.8: the tests use a cube in the working space, of the largest volume the working space allows,
its edges parallel to the base coordinate system, placed where the robot works most. The pose characteristics
are measured at five points P1-P5 on one of the cube's four *diagonal planes* (a plane through two opposite
edges): P1 at the intersection of the diagonals (the cube's centre), P2-P5 on the diagonals at 10 % of the
diagonal's length from the corners. The tool keeps one orientation at all five (the orientation of the
centre pose here).

The diagonal planes, by ``plane`` (``h`` half the edge, ``c`` the centre)::

    1: through the edge y = z = -h and the edge y = z = +h   (rising towards +y, edges along x)
    2: through the edge y = +h, z = -h and the edge y = -h, z = +h   (rising towards -y, edges along x)
    3: through the edge x = z = -h and the edge x = z = +h   (rising towards +x, edges along y)
    4: through the edge x = +h, z = -h and the edge x = -h, z = +h   (rising towards -x, edges along y)

P2-P5 are numbered around the plane: P2 near its first lower corner, P3 the other lower corner, P4 the upper
corner opposite P2, P5 the upper corner opposite P3; so P2-P4 and P3-P5 are the diagonals through P1.

*In the working region* means here: every point of the cube's 3 x 3 x 3 lattice (corners, edge midpoints, face
centres, centre) and P1-P5 is reached at the tool orientation with joint values inside the region's box, by
damped-least-squares inverse kinematics continued from the centre pose. :func:`place_cube` finds the largest
such cube by bisection on the edge at candidate centres (the tool positions of the box's middle and of a
scrambled Sobol sample of it); it is the largest *found*, not a proven maximum.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import qmc

from tolalloc.exceptions import TolallocError, check_vector
from tolalloc.robot.lie import rotvec

__all__ = ["TestCube", "CubePlacement", "place_cube", "solve_ik", "PLANES", "TEST_POINT_SHARE", "MIN_FIXED_EDGE_MM"]

#: P2-P5 lie on the diagonals at this share of the diagonal's length from the corners (ISO 9283 6.8: 10 %)
TEST_POINT_SHARE = 0.10
#: corner signs (x, y, z) of each diagonal plane, in the order P2, P3, P4, P5 take them
PLANES = {
    1: ((-1, -1, -1), (1, -1, -1), (1, 1, 1), (-1, 1, 1)),
    2: ((-1, 1, -1), (1, 1, -1), (1, -1, 1), (-1, -1, 1)),
    3: ((-1, -1, -1), (-1, 1, -1), (1, 1, 1), (1, -1, 1)),
    4: ((1, -1, -1), (1, 1, -1), (-1, 1, 1), (-1, -1, 1)),
}
#: ``orientation="auto"`` holds the tool orientation unless the largest such cube is smaller than this [mm]
MIN_FIXED_EDGE_MM = 10.0
_IK_TOL_MM = 1e-6
_IK_TOL_RAD = 1e-9


@dataclass(frozen=True, eq=False)
class TestCube:
    """A test cube: centre, edge, the tool orientation at its points and the diagonal plane of P1-P5.

    Attributes
    ----------
    centre_mm : array, shape (3,) [mm]
        Centre in the base frame.
    edge_mm : float
    rotation : array, shape (3, 3)
        Tool orientation (base frame) at every test point (with ``fixed_orientation``; else at the centre).
    plane : int
        Diagonal plane 1-4 (module docstring).
    fixed_orientation : bool
        The tool keeps ``rotation`` at every point (the standard's test); False: the positions alone are commanded
        and the orientation follows the least joint motion from the centre pose (for a robot that cannot hold one
        orientation over a cube, such as a 5R + 1P arm whose wrist only compensates its pitch).
    """

    __test__ = False  # not a pytest class

    centre_mm: np.ndarray
    edge_mm: float
    rotation: np.ndarray
    plane: int = 1
    fixed_orientation: bool = True

    def corners(self) -> np.ndarray:
        """The 8 corners, shape (8, 3) [mm]."""
        s = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)
        return self.centre_mm + 0.5 * self.edge_mm * s

    def plane_corners(self) -> np.ndarray:
        """The 4 corners of the diagonal plane in the order of P2-P5, shape (4, 3) [mm]."""
        return self.centre_mm + 0.5 * self.edge_mm * np.array(PLANES[self.plane], float)

    def test_points(self) -> np.ndarray:
        """P1-P5, shape (5, 3) [mm]: the centre, then 10 % of the diagonal from each plane corner."""
        c = self.plane_corners()
        return np.vstack([self.centre_mm, c + 2 * TEST_POINT_SHARE * (self.centre_mm - c)])

    def lattice(self) -> np.ndarray:
        """The 27 points of the 3 x 3 x 3 lattice (corners, edge midpoints, face centres, centre), shape (27, 3)."""
        s = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)], float)
        return self.centre_mm + 0.5 * self.edge_mm * s

    def frames(self, points) -> np.ndarray:
        """Tool poses at ``points`` (M, 3) with the cube's orientation, shape (M, 4, 4)."""
        pts = np.atleast_2d(points)
        T = np.tile(np.eye(4), (len(pts), 1, 1))
        T[:, :3, :3] = self.rotation
        T[:, :3, 3] = pts
        return T

    def with_edge(self, edge_mm: float) -> "TestCube":
        return TestCube(self.centre_mm, float(edge_mm), self.rotation, self.plane, self.fixed_orientation)


@dataclass(frozen=True, eq=False)
class CubePlacement:
    """A cube placed in a joint-space box, with the joint values of its points.

    Attributes
    ----------
    cube : TestCube
    q_test : array, shape (5, n) [rad, mm]
        Joint values of P1-P5.
    q_corners : array, shape (8, n) [rad, mm]
        Joint values of the 8 corners (the default registration poses of the test).
    q_min, q_max : arrays, shape (n,) [rad, mm]
        The box.
    searched : bool
        Whether the cube was searched for (False: it was given).
    """

    cube: TestCube
    q_test: np.ndarray
    q_corners: np.ndarray
    q_min: np.ndarray
    q_max: np.ndarray
    searched: bool = True


def _rot_error(R_d, R):
    """``vee`` of the skew part of ``R_d R^T`` (the rotation vector to first order; zero only where R = R_d near it)."""
    E = R_d @ np.swapaxes(R, -1, -2)
    return 0.5 * np.stack([E[:, 2, 1] - E[:, 1, 2], E[:, 0, 2] - E[:, 2, 0], E[:, 1, 0] - E[:, 0, 1]], axis=1)


def solve_ik(robot, targets, q0, q_min, q_max, *, iters: int = 40, position_only: bool = False):
    """Damped-least-squares inverse kinematics of many tool poses at once, inside a joint box.

    Parameters
    ----------
    robot : Robot
    targets : array, shape (M, 4, 4)
        Tool poses in the base frame [mm].
    q0 : array, shape (M, n) or (n,) [rad, mm]
        Start joint values.
    q_min, q_max : arrays, shape (n,)
    iters : int
        At most this many Newton steps; the iteration also stops when the largest error has not halved in the last
        four steps (a pose outside the box's reach).
    position_only : bool
        Match the position only (the orientation follows the least joint motion).

    Returns
    -------
    q : array, shape (M, n) [rad, mm]
    ok : array of bool, shape (M,)
        Whether the pose was reached (1e-6 mm, 1e-9 rad) within the box.
    """
    T_d = np.asarray(targets, float)
    n = robot.n_joints
    q = np.broadcast_to(np.clip(np.asarray(q0, float), q_min, q_max), (len(T_d), n)).copy()
    rows = slice(3, 6) if position_only else slice(0, 6)
    scale = np.r_[np.full(3, _IK_TOL_MM / _IK_TOL_RAD), np.ones(3)][rows]  # errors in units of their tolerance
    history = []
    for it in range(iters):
        T = robot.fk_internal(q)
        p = T[:, :3, 3]
        e_p = T_d[:, :3, 3] - p
        w = _rot_error(T_d[:, :3, :3], T[:, :3, :3])
        V = np.concatenate([w, e_p - np.cross(w, p)], axis=1)  # space twist carrying T to T_d
        err = np.abs(np.concatenate([w, e_p], axis=1)[:, rows] * scale).max(axis=1) / _IK_TOL_MM
        done = err < 1.0
        if done.all():
            break
        history.append(err.max())
        if it >= 8 and history[-1] > 0.5 * history[-5]:
            break
        J = robot.space_jacobian_internal(q, engine="numpy")
        if position_only:  # the tool point's velocity v + w x p
            J, V = J[:, 3:] - np.cross(p[:, :, None], J[:, :3], axisa=1, axisb=1, axisc=1), e_p
        else:
            J = J[:, rows, :]
        JJt = J @ np.swapaxes(J, -1, -2) + 1e-6 * np.eye(J.shape[1])
        dq = (np.swapaxes(J, -1, -2) @ np.linalg.solve(JJt, V[..., None]))[..., 0]
        q = np.where(done[:, None], q, np.clip(q + dq, q_min, q_max))
    T = robot.fk_internal(q)
    ok = np.linalg.norm(T_d[:, :3, 3] - T[:, :3, 3], axis=1) < 10 * _IK_TOL_MM
    if not position_only:
        ok &= np.linalg.norm(rotvec(T_d[:, :3, :3] @ np.swapaxes(T[:, :3, :3], -1, -2)), axis=1) < 10 * _IK_TOL_RAD
    return q, ok


def _reach(robot, cube: TestCube, q_centre, q_min, q_max, q_start=None):
    """Joint values of the lattice and P1-P5 ((32, n)), or None if a point is not reached inside the box."""
    pts = np.vstack([cube.lattice(), cube.test_points()[1:]])
    start = q_centre if q_start is None else q_start
    q, ok = solve_ik(robot, cube.frames(pts), start, q_min, q_max, position_only=not cube.fixed_orientation)
    return q if ok.all() else None


def _largest_at(robot, cube: TestCube, q_centre, q_min, q_max, edge_max: float, rel_tol: float = 0.01):
    """Bisection on the edge at a fixed centre: ``(edge, q (32, n))`` of the largest cube reached (edge 0: none)."""
    lo, q_lo, hi = 0.0, None, float(edge_max)
    while hi - lo > rel_tol * max(hi, 1e-9) and hi > 1e-3:
        mid = 0.5 * (lo + hi)
        q = _reach(robot, cube.with_edge(mid), q_centre, q_min, q_max, q_lo)
        if q is None:
            hi = mid
        else:
            lo, q_lo = mid, q
    return lo, q_lo


def _placement(cube, q, q_min, q_max, searched) -> CubePlacement:
    """Split the 32 reached joint rows into P1-P5 (P1 is the lattice centre, row 13) and the 8 corners."""
    corner_rows = [0, 2, 6, 8, 18, 20, 24, 26]  # lattice rows whose signs are all +-1, in corners() order
    return CubePlacement(cube, np.vstack([q[13], q[27:31]]), q[corner_rows], q_min, q_max, searched)


def place_cube(robot, q_min, q_max, *, centre_mm=None, edge_mm=None, plane: int = 1, orientation: str = "auto",
               candidates: int = 8, seed: int = 0) -> CubePlacement:
    """The test cube in a joint-space box: the largest found, or the one given (checked).

    Parameters
    ----------
    robot : Robot
    q_min, q_max : arrays, shape (n,) [rad, mm]
        The working region (a box in joint space).
    centre_mm : array, shape (3,), optional
        Cube centre [mm]; default: searched.
    edge_mm : float, optional
        Cube edge [mm]; default: the largest that fits (at ``centre_mm`` if given).
    plane : int
        Diagonal plane of P1-P5, 1-4 (module docstring).
    orientation : {"auto", "fixed", "free"}
        ``fixed``: the tool keeps one orientation (the standard's test); ``free``: positions only
        (:attr:`TestCube.fixed_orientation`); ``auto``: fixed, unless the largest such cube found is below
        :data:`MIN_FIXED_EDGE_MM`, then free.
    candidates : int
        Candidate centres besides the box's middle (a scrambled Sobol sample of the box, seeded by ``seed``).

    Returns
    -------
    CubePlacement

    Raises
    ------
    TolallocError
        A given cube that does not fit the region (the message gives the largest edge that fits there), or a
        region in which no cube is reached at all.
    """
    if plane not in PLANES:
        raise TolallocError(f"plane: expected a diagonal plane 1, 2, 3 or 4, got {plane!r}.")
    if orientation not in ("auto", "fixed", "free"):
        raise TolallocError(f"orientation: expected 'auto', 'fixed' or 'free', got {orientation!r}.")
    q_min, q_max = np.asarray(q_min, float), np.asarray(q_max, float)
    centre = None if centre_mm is None else check_vector(centre_mm, "cube_centre_mm", 3)
    if edge_mm is not None:
        if isinstance(edge_mm, bool) or not isinstance(edge_mm, (int, float, np.integer, np.floating)) \
                or not np.isfinite(edge_mm) or edge_mm <= 0:
            raise TolallocError(f"cube_edge_mm: expected the cube's edge as a number > 0 [mm], got {edge_mm!r}.")
        edge_mm = float(edge_mm)
    largest = {}
    for mode in (("fixed", "free") if orientation == "auto" else (orientation,)):
        pl, largest[mode] = _place(robot, q_min, q_max, centre, edge_mm, plane, mode == "fixed", candidates, seed)
        if pl is not None and (orientation != "auto" or mode == "free" or pl.cube.edge_mm >= MIN_FIXED_EDGE_MM):
            return pl
    found = "; ".join(f"{e:.4g} mm with the tool orientation {'held' if m == 'fixed' else 'free'}"
                      for m, e in largest.items())
    where = (f"at {np.round(centre, 3).tolist()} mm" if centre is not None else
             f"in the working region (joint box {np.round(robot.q_to_interface(q_min), 3).tolist()} .. "
             f"{np.round(robot.q_to_interface(q_max), 3).tolist()} deg / mm, {candidates + 1} candidate centres)")
    if edge_mm is not None:
        best = max(largest.values())
        raise TolallocError(f"cube_edge_mm: a cube of edge {edge_mm:g} mm {where} does not fit the working region (a "
                            f"lattice point or test pose is not reached inside the joint box); the largest that fits "
                            f"there has an edge of {found}. Give cube_edge_mm <= {np.floor(best * 100) / 100:g}, or "
                            "leave it out for the largest.")
    raise TolallocError(f"cube: no cube fits {where} (largest found: {found}); "
                        + ("give another cube_centre_mm, or leave it out to search" if centre is not None else
                           "widen the region, or give more candidate centres"))


def _place(robot, q_min, q_max, centre, edge_mm, plane, fixed, candidates, seed):
    """``(placement or None, largest edge found)`` with the orientation held (``fixed``) or free: the cube given
    (None if it does not fit) or the largest found."""
    mid = 0.5 * (q_min + q_max)
    corners = q_min + np.array([[i >> j & 1 for j in range(len(mid))] for i in range(2 ** min(len(mid), 8))]) * (
        q_max - q_min)[None, :]
    edge_max = 2.0 * float(np.linalg.norm(robot.fk_internal(corners)[:, :3, 3], axis=1).max()) + 2.0
    if centre is not None:
        R = robot.fk_internal(mid)[:3, :3]
        q_c, ok = solve_ik(robot, TestCube(centre, 0.0, R, plane).frames(centre), mid, q_min, q_max,
                           position_only=not fixed)
        if not ok[0]:
            return None, 0.0
        starts = [(TestCube(centre, 0.0, R if fixed else robot.fk_internal(q_c[0])[:3, :3], plane, fixed), q_c[0])]
    else:
        seeds = [mid]
        if candidates:
            s = qmc.Sobol(len(mid), scramble=True, seed=seed).random(int(candidates))
            seeds += list(q_min + s * (q_max - q_min))
        starts = []
        for qs in seeds:
            T = robot.fk_internal(qs)
            starts.append((TestCube(T[:3, 3].copy(), 0.0, T[:3, :3].copy(), plane, fixed), qs))
    if edge_mm is not None:
        for cube, qs in starts:
            q = _reach(robot, cube.with_edge(edge_mm), qs, q_min, q_max)
            if q is not None:
                return _placement(cube.with_edge(edge_mm), q, q_min, q_max, centre is None), float(edge_mm)
    best = (0.0, None, None)
    for cube, qs in starts:
        e, q = _largest_at(robot, cube, qs, q_min, q_max, edge_max)
        if e > best[0] and q is not None:
            best = (e, cube.with_edge(e), q)
    if edge_mm is not None or best[1] is None:
        return None, best[0]
    return _placement(best[1], best[2], q_min, q_max, centre is None), best[0]
