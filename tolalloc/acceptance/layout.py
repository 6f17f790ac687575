"""The acceptance test as ISO 9283 lays it out: cube, test poses, cycles, instrument, registration, test path.

:func:`acceptance_test` places the cube in the working region (:func:`tolalloc.acceptance.cube.place_cube`: the
largest found, or the one given and checked) and collects what a simulation of the test needs:

* P1-P5 (ISO 9283 6.8), each approached ``cycles`` times from the same side (6.9: 30 cycles for pose and distance
  characteristics);
* the registration poses (the cube's corners, :mod:`tolalloc.acceptance.instrument`) and the tracker;
* for path accuracy, a straight command path from P2 through P1 to P4 in the test plane, ``path_cycles`` cycles
  (6.9: 10), sampled at the path accuracy requirement's points; the attained point at a command point is where
  the attained path crosses the plane normal to the command path there (8.2), so only the error across the path
  counts.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.acceptance.cube import CubePlacement, TestCube, place_cube, solve_ik
from tolalloc.acceptance.instrument import REGISTRATIONS, Tracker
from tolalloc.acceptance.statistics import check_cycles

__all__ = ["AcceptanceTest", "acceptance_test", "acceptance_test_at", "default_region", "TestPath",
           "joint_directions", "MOVING_SHARE"]

#: a joint whose share of the tool's motion in an approach is below this is not said to move (its flank is unknown)
MOVING_SHARE = 1e-3


@dataclass(frozen=True, eq=False)
class TestPath:
    """A command path of ``m`` points: joint values, positions and unit tangents.

    Attributes
    ----------
    q : array, shape (m, n) [rad, mm]
    points_mm : array, shape (m, 3) [mm]
    tangents : array, shape (m, 3)
    """

    __test__ = False

    q: np.ndarray
    points_mm: np.ndarray
    tangents: np.ndarray


@dataclass(frozen=True, eq=False)
class AcceptanceTest:
    """An ISO 9283 acceptance test of one robot.

    Attributes
    ----------
    robot : Robot
    placement : CubePlacement
        The cube and the joint values of P1-P5 and of its corners.
    cycles : int
        Cycles per test pose (pose and distance characteristics).
    path_cycles : int
        Cycles of the test path (path characteristics).
    tracker : Tracker
    registration : {"corners", "none"}
    registration_visits : int
        Measurements averaged at each registration pose.
    """

    __test__ = False

    robot: object
    placement: CubePlacement
    cycles: int = 30
    path_cycles: int = 10
    tracker: Tracker = field(default_factory=Tracker)
    registration: str = "corners"
    registration_visits: int = 1

    @property
    def q_test(self) -> np.ndarray:
        """Joint values of P1-P5, shape (5, n) [rad, mm]."""
        return self.placement.q_test

    @property
    def q_registration(self) -> np.ndarray:
        """Joint values of the registration poses, shape (R, n) (R = 0 without registration)."""
        if self.registration == "none":
            return np.zeros((0, self.robot.n_joints))
        return self.placement.q_corners

    def commanded(self, q) -> np.ndarray:
        """Command tool positions of joint values ``q`` (M, n), shape (M, 3) [mm] (the nominal kinematics)."""
        return self.robot.fk_internal(np.atleast_2d(q))[:, :3, 3]

    def path(self, points: int) -> TestPath:
        """The straight command path P2 -> P1 -> P4 at ``points`` evenly spaced points (inverse kinematics
        continued from P2, the cube's orientation rule)."""
        cube, pl = self.placement.cube, self.placement
        ends = cube.test_points()[[1, 3]]
        s = np.linspace(0.0, 1.0, int(points))
        pts = ends[0] + s[:, None] * (ends[1] - ends[0])
        q, prev = np.zeros((len(pts), self.robot.n_joints)), pl.q_test[1]
        for i, pt in enumerate(pts):
            qi, ok = solve_ik(self.robot, cube.frames(pt), prev, pl.q_min, pl.q_max,
                              position_only=not cube.fixed_orientation)
            if not ok[0]:  # pragma: no cover - the segment lies in the cube, whose lattice was reached
                raise TolallocError(f"path: point {i + 1} of the path P2-P4 is not reached inside the region.")
            q[i], prev = qi[0], qi[0]
        t = (ends[1] - ends[0]) / np.linalg.norm(ends[1] - ends[0])
        return TestPath(q, pts, np.tile(t, (len(pts), 1)))

    def joint_directions(self, q, directions) -> np.ndarray:
        """Each joint's direction of motion (+1 / -1, 0 where it hardly moves) when the tool approaches the poses
        ``q`` (P, n) along ``directions`` (D, 3), the cube's orientation held or free: shape (P, D, n)
        (:func:`joint_directions`)."""
        return joint_directions(self.robot, q, directions, self.placement.cube.fixed_orientation)

    def summary(self) -> dict:
        """The test's settings for reports (JSON-ready)."""
        c = self.placement.cube
        return {"cube_centre_mm": np.round(c.centre_mm, 4).tolist(), "cube_edge_mm": round(float(c.edge_mm), 4),
                "plane": c.plane, "orientation": "fixed" if c.fixed_orientation else "free",
                "cube_searched": self.placement.searched, "cycles": self.cycles, "path_cycles": self.path_cycles,
                "registration": self.registration, "registration_visits": self.registration_visits,
                "tracker_mpe_a_mm": self.tracker.mpe_a_mm, "tracker_mpe_b_mm_per_m": self.tracker.mpe_b_mm_per_m,
                "tracker_distance_m": self.tracker.distance_m, "tracker_angle_mpe_deg": self.tracker.angle_mpe_deg,
                "coverage_factor_k": self.tracker.k,
                "q_test_deg_mm": np.round(self.robot.q_to_interface(self.q_test), 4).tolist()}


def joint_directions(robot, q, directions, fixed_orientation: bool = True) -> np.ndarray:
    """Each joint's direction of motion while the tool moves along ``directions`` into the poses ``q``.

    The joint rates of a straight approach are ``J^+ (u, 0)`` with the tool's orientation held (``J`` the 6 x n
    Jacobian of the tool point and frame), or ``Jp^+ u`` with it free (the least-norm rates a resolved-rate
    controller takes). A joint whose share ``|Jp_j qdot_j|`` of the tool's unit motion is below
    :data:`MOVING_SHARE` gets 0: the flank it rests on is then the one its last motion before the approach left.

    Parameters
    ----------
    robot : Robot
    q : array, shape (P, n) [rad, mm]
    directions : array, shape (D, 3)
        Unit directions of the tool's motion.
    fixed_orientation : bool

    Returns
    -------
    array, shape (P, D, n) of +1., -1. or 0.
    """
    q = np.atleast_2d(np.asarray(q, float))
    Js = robot.space_jacobian_internal(q)                         # (P, 6, n): rows angular, linear
    p = robot.fk_internal(q)[:, :3, 3]
    Jw = Js[:, :3]
    Jp = Js[:, 3:] - np.cross(p[:, :, None], Jw, axis=1)          # the tool point: v + w x p
    J = np.concatenate([Jp, Jw], axis=1) if fixed_orientation else Jp
    u = np.asarray(directions, float)
    rhs = np.concatenate([u, np.zeros_like(u)], axis=1) if fixed_orientation else u
    qd = np.einsum("pnr,dr->pdn", np.linalg.pinv(J), rhs)
    share = np.abs(qd) * np.linalg.norm(Jp, axis=1)[:, None, :]
    return np.where(share >= MOVING_SHARE, np.sign(qd), 0.0)


def default_region(robot) -> tuple[np.ndarray, np.ndarray, str]:
    """The working region of a robot: its ``working`` box, else the box spanned by its ``working`` pose set, else
    its joint limits; ``(q_min, q_max, label)`` [rad, mm]."""
    if "working" in robot.regions:
        lo, hi = robot.regions["working"]
        return np.asarray(lo, float), np.asarray(hi, float), "working region"
    if "working" in robot.pose_sets:
        Q = robot.poses("working")
        return Q.min(axis=0), Q.max(axis=0), "box of the working pose set"
    return np.asarray(robot.lower, float), np.asarray(robot.upper, float), "joint limits"


def acceptance_test(robot, region=None, *, cube_edge_mm=None, cube_centre_mm=None, plane: int = 1,
                    orientation: str = "auto", cycles: int = 30, path_cycles: int = 10, tracker: Tracker | None = None,
                    registration: str = "corners", registration_visits: int = 1, candidates: int = 8,
                    seed: int = 0) -> AcceptanceTest:
    """Lay out the ISO 9283 acceptance test of ``robot`` in its working region.

    Parameters
    ----------
    robot : Robot
    region : (q_min, q_max) or object with ``q_min``, ``q_max``, optional
        Joint-space box [rad, mm]; default :func:`default_region`.
    cube_edge_mm, cube_centre_mm : optional
        A given cube (checked: one that does not fit is refused, naming the largest that does); default the largest
        cube found in the region (:func:`tolalloc.acceptance.cube.place_cube`).
    plane, orientation, candidates, seed
        As :func:`tolalloc.acceptance.cube.place_cube`.
    cycles, path_cycles : int
        Cycles per test pose (>= 2; the standard: 30) and of the test path (>= 2; the standard: 10).
    tracker : Tracker, optional
    registration : {"corners", "none"}
    registration_visits : int
        Measurements averaged at each registration pose (>= 1).
    """
    cycles = check_cycles(cycles, "cycles")
    path_cycles = check_cycles(path_cycles, "path_cycles")
    if registration not in REGISTRATIONS:
        raise ArgumentError("registration", f"expected one of {', '.join(REGISTRATIONS)} (the cube's corners "
                            f"measured to fit the base frame, or a base frame known beforehand), got {registration!r}.")
    tracker, registration_visits = _instrument(tracker, registration_visits)
    if region is None:
        lo, hi, _ = default_region(robot)
    elif hasattr(region, "q_min"):
        lo, hi = region.q_min, region.q_max
    else:
        lo, hi = region
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    robot.check_q(np.stack([lo, hi]), "region")
    pl = place_cube(robot, lo, hi, centre_mm=cube_centre_mm, edge_mm=cube_edge_mm, plane=plane,
                    orientation=orientation, candidates=candidates, seed=seed)
    return AcceptanceTest(robot, pl, cycles, path_cycles, tracker, registration, registration_visits)


def _instrument(tracker, registration_visits) -> tuple:
    """``(tracker, registration_visits)`` checked: a :class:`Tracker` (default ``Tracker()``), a whole number >= 1."""
    if isinstance(registration_visits, bool) or not isinstance(registration_visits, (int, np.integer)) \
            or registration_visits < 1:
        raise ArgumentError("registration_visits", f"expected a whole number >= 1, got {registration_visits!r}.")
    tracker = Tracker() if tracker is None else tracker
    if not isinstance(tracker, Tracker):
        raise ArgumentError("tracker", f"expected tolalloc.acceptance.Tracker(...), got {tracker!r}.")
    return tracker, int(registration_visits)


def acceptance_test_at(robot, q_test, q_registration=None, *, cycles: int = 30, tracker: Tracker | None = None,
                  registration_visits: int = 1) -> AcceptanceTest:
    """A test at given poses rather than the cube's P1-P5 (e.g. the poses a data set repeats), registered on
    ``q_registration`` (none: a base frame known beforehand). Its cube is nominal only: centre the mean command
    position, edge 0.

    Parameters
    ----------
    robot : Robot
    q_test : array, shape (P, n) [rad, mm]
    q_registration : array, shape (R, n) [rad, mm], optional
        At least 3 poses.
    """
    q_test = np.atleast_2d(robot.check_q(q_test, "q_test"))
    cycles = check_cycles(cycles, "cycles")
    tracker, registration_visits = _instrument(tracker, registration_visits)
    reg = "none" if q_registration is None else "corners"
    q_reg = np.zeros((0, robot.n_joints)) if q_registration is None else np.atleast_2d(
        robot.check_q(q_registration, "q_registration"))
    if reg != "none" and len(q_reg) < 3:
        raise ArgumentError("q_registration", f"expected at least 3 registration poses to fit the base frame, got "
                            f"{len(q_reg)}.")
    T = robot.fk_internal(q_test)
    cube = TestCube(T[:, :3, 3].mean(axis=0), 0.0, T[0, :3, :3], 1, False)
    both = np.vstack([q_test, q_reg])
    lo, hi = both.min(axis=0), both.max(axis=0)
    pl = CubePlacement(cube, q_test, q_reg, lo, hi, searched=False)
    return AcceptanceTest(robot, pl, cycles, 10, tracker, reg, registration_visits)
