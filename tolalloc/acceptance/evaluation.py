"""The poses an acceptance test's statistics read: P1-P5, the registration poses, the path points and the directional
visits of a multi-directional test (:func:`evaluation_poses`, :func:`requirement_poses`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["EvaluationPoses", "evaluation_poses", "requirement_poses"]


@dataclass(frozen=True, eq=False)
class EvaluationPoses:
    """The poses a test's statistics read: P1-P5, the registration poses and the path points.

    Attributes
    ----------
    q : array, shape (M, n) [rad, mm]
    test, registration, path : arrays of int
        Rows of ``q``.
    points_mm : array, shape (M, 3)
        Command positions.
    tangents : array, shape (len(path), 3)
        Unit tangents of the command path.
    directional : array of int, shape (V, 3)
        Rows of a multi-directional test: pose ``v`` approached along each of the three directions (``V = 0``
        without one).
    approach : array, shape (M, n), optional
        Each joint's direction of motion into the pose (+1 / -1, 0 unknown), known at the directional rows only;
        ``None`` without them.
    """

    q: np.ndarray
    test: np.ndarray
    registration: np.ndarray
    path: np.ndarray
    points_mm: np.ndarray
    tangents: np.ndarray
    directional: np.ndarray = None
    approach: np.ndarray | None = None


def evaluation_poses(test, path_points: int = 0, multidirectional=None) -> EvaluationPoses:
    """The evaluation poses of an :class:`~tolalloc.acceptance.layout.AcceptanceTest` (with a path of
    ``path_points`` points when > 0, and the directional visits of a
    :class:`~tolalloc.acceptance.requirements.MultiDirectionalAccuracy` ``multidirectional``)."""
    parts = [test.q_test, test.q_registration]
    tang = np.zeros((0, 3))
    if path_points:
        if not test.placement.cube.edge_mm > 0:
            raise TolallocError("path_accuracy: the test has no cube to run the path along (a test at given poses, "
                                "acceptance_test_at, has a nominal cube of edge 0); lay the test out with "
                                "acceptance_test to require a path accuracy.")
        tp = test.path(path_points)
        parts.append(tp.q)
        tang = tp.tangents
    if multidirectional is not None:
        if max(multidirectional.poses) > len(test.q_test):
            raise TolallocError(f"{multidirectional.kind}: poses {list(multidirectional.poses)} but the test has "
                                f"{len(test.q_test)} test poses; name poses 1-{len(test.q_test)}.")
        qv = test.q_test[[i - 1 for i in multidirectional.poses]]
        parts.append(np.repeat(qv, 3, axis=0))
    sizes = np.cumsum([0] + [len(p) for p in parts])
    q = np.vstack(parts)
    rng = [np.arange(sizes[i], sizes[i + 1]) for i in range(len(parts))]
    path = rng[2] if path_points else np.zeros(0, int)
    directional, approach = np.zeros((0, 3), int), None
    if multidirectional is not None:
        directional = rng[-1].reshape(-1, 3)
        approach = np.zeros_like(q)
        approach[directional] = test.joint_directions(q[directional[:, 0]], multidirectional.directions())
    return EvaluationPoses(q, rng[0], rng[1], path, test.commanded(q), tang, directional, approach)


def requirement_poses(test, requirements) -> EvaluationPoses:
    """:func:`evaluation_poses` for the requirements' statistics (the path and the directional visits they read)."""
    path = next((r for r in requirements if r.kind == "path_accuracy"), None)
    vap = [r for r in requirements if r.kind.startswith("multidirectional")]
    if len(vap) == 2 and (vap[0].poses, vap[0].approach) != (vap[1].poses, vap[1].approach):
        raise TolallocError(f"multidirectional requirements: one test approaches each pose one way for the position "
                            f"and the orientation, but they name poses {list(vap[0].poses)} and "
                            f"{list(vap[1].poses)}, approaches {list(vap[0].approach)} and {list(vap[1].approach)}; "
                            "give both the same.")
    return evaluation_poses(test, path.points if path is not None else 0, vap[0] if vap else None)
