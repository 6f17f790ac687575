"""Requirement objects: today's error balls and the characteristics robot makers state (ISO 9283).

Each requirement is a frozen dataclass, checked at construction (a bad field is a
:class:`~tolalloc.exceptions.ArgumentError` naming ``ClassName.field``), with one kind of error it bounds
(:attr:`Requirement.kind`: a job takes one requirement of each kind), its statement as a formula
(:meth:`Requirement.text`) and a JSON record (:meth:`Requirement.to_dict`).

* :class:`PositionRequirement` (kind ``position``): ``P(|dP| < r) >= p`` at every working pose (the ball);
* :class:`OrientationRequirement` (``orientation``): ``P(|dw| < a) >= p`` at every working pose;
* :class:`PoseAccuracy` (``pose_accuracy``): ``AP_P`` at P1-P5 (ISO 9283:1998 7.2.1);
* :class:`PoseRepeatability` (``pose_repeatability``): ``RP_l`` at P1-P5 (7.2.2);
* :class:`OrientationAccuracy` (``orientation_accuracy``): ``AP_a, AP_b, AP_c`` at P1-P5 (7.2.1);
* :class:`OrientationRepeatability` (``orientation_repeatability``): ``RP_a, RP_b, RP_c`` at P1-P5 (7.2.2);
* :class:`MultiDirectionalAccuracy` (``multidirectional_accuracy``): ``vAP_P`` at P1, P2, P4, each approached from
  three orthogonal directions (7.2.3); :class:`MultiDirectionalOrientation` (``multidirectional_orientation``):
  ``vAP_a, vAP_b, vAP_c``;
* :class:`DistanceAccuracy` (``distance_accuracy``): ``AD_P`` between two of P1-P5 (7.3);
* :class:`PathAccuracy` (``path_accuracy``): ``AT_P`` along a command path (8.2).

An ISO 9283 requirement states a **limit** on its statistic (``AP_P <= limit_mm``; the repeatabilities, which
datasheets write ``+-0.05 mm``, by their half-width), the **population** it holds for and the **test conditions**:

* ``population="fleet"``: a share ``share`` of the robots built meet it ("95 % of built robots meet
  ``AP_P <= 0.5 mm``"); ``population="robot"``: the robot at hand meets it with probability ``share``. For a robot
  not yet built, made like every other, the two are the same number (each robot is one draw of the manufacturing
  errors and of its test); they differ in what the report says, and for a robot whose own errors are known.
* :class:`Conditions`: load (ISO 9283 6.6: 100 % of the rated load, also 10 %) and velocity (6.7: 100 %, 50 %,
  10 % of the rated velocity). They select the state in which bought-part effects (compliance under load, ...)
  are evaluated; the geometric error model does not depend on them.
* ``guard_band``: allocate so that the acceptance test *demonstrates* conformance (ISO 14253-1: the predicted
  measured statistic plus the expanded uncertainty of its measurement within the limit), not only that the
  robots meet the limit.

The statistic is evaluated at the poses of the acceptance test (:class:`tolalloc.acceptance.layout.AcceptanceTest`):
P1-P5 of the test cube, ``cycles`` cycles each approached from the same side.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from tolalloc.exceptions import ArgumentError, describe
from tolalloc.acceptance.conditions import Conditions
from tolalloc.acceptance.requirement_base import (AXES, CALIBRATED_ESTIMATORS, DEFAULT_PROB, DEFAULT_RADIUS_MM,
                                                  ESTIMATORS, POPULATIONS, IsoRequirement, Requirement)
from tolalloc.units import check_positive, check_probability

__all__ = ["Requirement", "Conditions", "PositionRequirement", "OrientationRequirement", "IsoRequirement",
           "PoseAccuracy", "PoseRepeatability", "OrientationAccuracy", "OrientationRepeatability",
           "MultiDirectionalAccuracy", "MultiDirectionalOrientation", "DistanceAccuracy", "PathAccuracy",
           "check_requirements", "split_requirements", "REQUIREMENT_KINDS", "POPULATIONS", "AXES", "DEFAULT_RADIUS_MM",
           "DEFAULT_PROB", "ESTIMATORS", "CALIBRATED_ESTIMATORS"]


@dataclass(frozen=True)
class PositionRequirement(Requirement):
    """``P(|dP| < radius_mm) >= prob`` at every working pose: the tool-position error within a ball.

    Examples
    --------
    >>> PositionRequirement(radius_mm=0.1, prob=0.99).text()
    'P(|dP| < 0.1 mm) >= 0.99'
    """

    radius_mm: float = DEFAULT_RADIUS_MM
    prob: float = DEFAULT_PROB
    kind: ClassVar[str] = "position"
    calibration_aware: ClassVar[bool] = True

    def check(self) -> None:
        check_positive(self.radius_mm, self._field("radius_mm"), "mm", "0.25")
        check_probability(self.prob, self._field("prob"))

    def text(self) -> str:
        return f"P(|dP| < {self.radius_mm:g} mm) >= {self.prob:g}"

    def problem_arguments(self) -> dict:
        """Keywords of :func:`tolalloc.allocate.build_problem` stating this requirement."""
        return {"radius_mm": float(self.radius_mm), "prob": float(self.prob)}

    def cli_arguments(self) -> list[str]:
        return ["--radius-mm", f"{self.radius_mm:g}", "--prob", f"{self.prob:g}"]


@dataclass(frozen=True)
class OrientationRequirement(Requirement):
    """``P(|dw| < radius_deg) >= prob`` at every working pose (default ``prob``: the position requirement's).

    Examples
    --------
    >>> OrientationRequirement(radius_deg=0.02, prob=0.95).text()
    'P(|dw| < 0.02 deg) >= 0.95'
    """

    radius_deg: float = 0.02
    prob: float | None = None
    kind: ClassVar[str] = "orientation"

    def check(self) -> None:
        check_positive(self.radius_deg, self._field("radius_deg"), "deg", "0.02")
        if self.prob is not None:
            check_probability(self.prob, self._field("prob"))

    def text(self) -> str:
        p = "p of the position requirement" if self.prob is None else f"{self.prob:g}"
        return f"P(|dw| < {self.radius_deg:g} deg) >= {p}"

    def problem_arguments(self) -> dict:
        return {"angle_radius_deg": float(self.radius_deg),
                "angle_prob": None if self.prob is None else float(self.prob)}

    def cli_arguments(self) -> list[str]:
        return ["--angle-radius-deg", f"{self.radius_deg:g}"] + ([] if self.prob is None else
                                                                  ["--angle-prob", f"{self.prob:g}"])


@dataclass(frozen=True, kw_only=True)
class PoseAccuracy(IsoRequirement):
    """Position accuracy ``AP_P <= limit_mm`` at every test pose P1-P5 (ISO 9283 7.2.1): the distance from the
    command position to the barycentre of the ``cycles`` attained positions.

    Examples
    --------
    >>> PoseAccuracy(limit_mm=0.5).text()
    'AP_P <= 0.5 mm for 95 % of built robots (ISO 9283 7.2.1; 100 % rated load, 100 % rated velocity)'
    """

    limit_mm: float = 0.5
    kind: ClassVar[str] = "pose_accuracy"
    clause: ClassVar[str] = "7.2.1"
    symbol: ClassVar[str] = "AP_P"


@dataclass(frozen=True, kw_only=True)
class PoseRepeatability(IsoRequirement):
    """Position repeatability ``RP_l <= limit_mm`` at every test pose (ISO 9283 7.2.2; the datasheet's
    ``+-limit_mm``): ``RP_l = lb + 3 S_l`` of the distances of the attained positions to their barycentre."""

    limit_mm: float = 0.05
    kind: ClassVar[str] = "pose_repeatability"
    clause: ClassVar[str] = "7.2.2"
    symbol: ClassVar[str] = "RP_l"


@dataclass(frozen=True, kw_only=True)
class OrientationAccuracy(IsoRequirement):
    """Orientation accuracy ``|AP_a|, |AP_b|, |AP_c| <= limit_deg`` at every test pose (ISO 9283 7.2.1), each angle
    on its own: the mean attained angle minus the command angle."""

    limit_deg: float = 0.05
    kind: ClassVar[str] = "orientation_accuracy"
    clause: ClassVar[str] = "7.2.1"
    symbol: ClassVar[str] = "|AP_a|, |AP_b|, |AP_c|"
    unit: ClassVar[str] = "deg"


@dataclass(frozen=True, kw_only=True)
class OrientationRepeatability(IsoRequirement):
    """Orientation repeatability ``RP_a, RP_b, RP_c <= limit_deg`` at every test pose (ISO 9283 7.2.2; the
    datasheet's ``+-limit_deg``), each angle on its own: ``3 S`` of the attained angles."""

    limit_deg: float = 0.01
    kind: ClassVar[str] = "orientation_repeatability"
    clause: ClassVar[str] = "7.2.2"
    symbol: ClassVar[str] = "RP_a, RP_b, RP_c"
    unit: ClassVar[str] = "deg"


@dataclass(frozen=True, kw_only=True)
class MultiDirectional(IsoRequirement):
    """Common fields of the multi-directional requirements (ISO 9283 7.2.3; a base class): each pose approached
    ``cycles`` times from each of three orthogonal directions. What one robot keeps at a pose cancels between the
    directions; what the approach direction changes (the flank a gear's lost motion rests on) and the random parts
    remain.

    Attributes
    ----------
    poses : tuple of int
        The test poses, numbered 1-5 as P1-P5 (default P1, P2, P4).
    approach : tuple of three str
        The tool's direction of motion into the pose along the base frame's axes (``"-z"``: coming down from above),
        three mutually orthogonal ones.
    """

    poses: tuple = (1, 2, 4)
    approach: tuple = ("-x", "-y", "-z")
    clause: ClassVar[str] = "7.2.3"

    def check(self) -> None:
        super().check()
        p, a = self.poses, self.approach
        ok = (isinstance(p, (tuple, list)) and 0 < len(p) == len(set(p)) and all(
            isinstance(i, (int, np.integer)) and not isinstance(i, bool) and 1 <= i <= 5 for i in p))
        if not ok:
            raise ArgumentError(self._field("poses"), f"expected different test poses numbered 1-5 (P1-P5), e.g. "
                                f"(1, 2, 4), got {p!r}.")
        axes = [str(x).strip() for x in a] if isinstance(a, (tuple, list)) else []
        if len(axes) != 3 or any(x not in AXES for x in axes) or len({x[1] for x in axes}) != 3:
            raise ArgumentError(self._field("approach"), f"expected three mutually orthogonal directions of the base "
                                f"frame's axes among {', '.join(AXES)}, one per axis (e.g. ('-x', '-y', '-z')), got "
                                f"{a!r}.")
        object.__setattr__(self, "poses", tuple(int(i) for i in p))
        object.__setattr__(self, "approach", tuple(axes))

    def directions(self) -> np.ndarray:
        """Unit directions of motion of the three approaches, shape (3, 3), rows in the order of :attr:`approach`."""
        return np.array([AXES[x] for x in self.approach], float)


@dataclass(frozen=True, kw_only=True)
class MultiDirectionalAccuracy(MultiDirectional):
    """Multi-directional pose accuracy variation ``vAP_P <= limit_mm`` (ISO 9283 7.2.3): the largest distance between
    the barycentres of the three directions' cycles (:class:`MultiDirectional`).

    Examples
    --------
    >>> MultiDirectionalAccuracy(limit_mm=0.1).text()
    'vAP_P <= 0.1 mm for 95 % of built robots (ISO 9283 7.2.3; 100 % rated load, 100 % rated velocity)'
    """

    limit_mm: float = 0.1
    kind: ClassVar[str] = "multidirectional_accuracy"
    symbol: ClassVar[str] = "vAP_P"


@dataclass(frozen=True, kw_only=True)
class MultiDirectionalOrientation(MultiDirectional):
    """Multi-directional orientation accuracy variation ``vAP_a, vAP_b, vAP_c <= limit_deg`` (ISO 9283 7.2.3), each
    angle on its own: the largest difference between the three directions' mean angles (:class:`MultiDirectional`)."""

    limit_deg: float = 0.02
    kind: ClassVar[str] = "multidirectional_orientation"
    symbol: ClassVar[str] = "vAP_a, vAP_b, vAP_c"
    unit: ClassVar[str] = "deg"


@dataclass(frozen=True, kw_only=True)
class DistanceAccuracy(IsoRequirement):
    """Distance accuracy ``|AD_P| <= limit_mm`` between two test poses (ISO 9283 7.3; default P2 and P4): the mean
    attained distance minus the command distance.

    Attributes
    ----------
    poses : tuple of two int
        The two test poses, numbered 1-5 as P1-P5.
    """

    limit_mm: float = 0.5
    poses: tuple = (2, 4)
    kind: ClassVar[str] = "distance_accuracy"
    clause: ClassVar[str] = "7.3"
    symbol: ClassVar[str] = "|AD_P|"

    def check(self) -> None:
        super().check()
        p = self.poses
        ok = (isinstance(p, (tuple, list)) and len(p) == 2 and all(
            isinstance(i, (int, np.integer)) and not isinstance(i, bool) and 1 <= i <= 5 for i in p) and p[0] != p[1])
        if not ok:
            raise ArgumentError(self._field("poses"), f"expected two different test poses numbered 1-5 (P1-P5), "
                                f"e.g. (2, 4), got {p!r}.")
        object.__setattr__(self, "poses", (int(p[0]), int(p[1])))

    def text(self) -> str:
        return super().text().replace("AD_P|", f"AD_P| (P{self.poses[0]}-P{self.poses[1]})", 1)


@dataclass(frozen=True, kw_only=True)
class PathAccuracy(IsoRequirement):
    """Path accuracy ``AT_P <= limit_mm`` along a command path (ISO 9283 8.2): the largest distance from a command
    point to the barycentre of the attained points of the cycles (ISO 9283 6.9: 10 cycles).

    Attributes
    ----------
    points : int
        Command points along the path at which the attained path is measured (>= 2).
    """

    limit_mm: float = 0.5
    points: int = 11
    kind: ClassVar[str] = "path_accuracy"
    clause: ClassVar[str] = "8.2"
    symbol: ClassVar[str] = "AT_P"

    def check(self) -> None:
        super().check()
        if isinstance(self.points, bool) or not isinstance(self.points, (int, np.integer)) or self.points < 2:
            raise ArgumentError(self._field("points"), f"expected a whole number of path points >= 2 (e.g. 11), "
                                f"got {self.points!r}.")


#: every requirement class by its kind
REQUIREMENT_KINDS = {c.kind: c for c in (PositionRequirement, OrientationRequirement, PoseAccuracy,
                                         PoseRepeatability, OrientationAccuracy, OrientationRepeatability,
                                         MultiDirectionalAccuracy, MultiDirectionalOrientation, DistanceAccuracy,
                                         PathAccuracy)}


def check_requirements(value, argument: str = "requirement", *, need: tuple = ()) -> tuple:
    """One :class:`Requirement` or a list / tuple of them -> a tuple, at most one of each kind, the kinds in
    ``need`` present, in the order of :data:`REQUIREMENT_KINDS` (position first)."""
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    bad = [v for v in items if not isinstance(v, Requirement)]
    if not items or bad:
        raise ArgumentError(argument, "expected a requirement or a list of them, e.g. "
                            "tolalloc.PositionRequirement(radius_mm=0.25, prob=0.95) or [PositionRequirement(...), "
                            f"tolalloc.acceptance.PoseAccuracy(limit_mm=0.5)], got {describe((bad or [value])[0])}.")
    kinds = [r.kind for r in items]
    twice = sorted({k for k in kinds if kinds.count(k) > 1})
    if twice:
        raise ArgumentError(argument, f"expected at most one requirement of each kind, got {kinds.count(twice[0])} "
                            f"{twice[0]} requirements ({'; '.join(r.text() for r in items if r.kind == twice[0])}); "
                            "keep the one that must hold.")
    missing = [k for k in need if k not in kinds]
    if missing:
        raise ArgumentError(argument, f"needs a {missing[0]} requirement (the allocation is built on the tool's "
                            f"{missing[0]} error), got only {', '.join(r.text() for r in items)}; add "
                            "tolalloc.PositionRequirement(radius_mm=..., prob=...).")
    order = list(REQUIREMENT_KINDS)
    return tuple(sorted(items, key=lambda r: order.index(r.kind)))


def split_requirements(requirements) -> tuple:
    """``(position, orientation, iso)``: the ball requirements (or None) and the ISO 9283 ones (a tuple)."""
    reqs = check_requirements(requirements)
    pos = next((r for r in reqs if r.kind == "position"), None)
    ori = next((r for r in reqs if r.kind == "orientation"), None)
    return pos, ori, tuple(r for r in reqs if isinstance(r, IsoRequirement))
