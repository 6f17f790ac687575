"""What a design must meet: requirement objects, built and checked once, handed to the jobs.

A job takes one requirement or a list of them (at most one of each :attr:`Requirement.kind`)::

    import tolalloc
    tolalloc.allocate_tolerances("tool_changer", requirement=[
        tolalloc.PositionRequirement(radius_mm=0.25, prob=0.95),
        tolalloc.OrientationRequirement(radius_deg=0.02, prob=0.95),
    ])

Every requirement derives from :class:`Requirement`, which names the hooks an allocation and a verification read:
what kind of error it bounds (one requirement per kind), how it is written (:meth:`~Requirement.text`,
:meth:`~Requirement.to_dict`, :meth:`~Requirement.cli_arguments`), the keywords it gives the allocation problem
(:meth:`~Requirement.problem_arguments`) and the verification estimators that can judge it
(:meth:`~Requirement.estimators`). A new kind of requirement is a new frozen dataclass that implements them.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import ClassVar

from tolalloc.exceptions import ArgumentError
from tolalloc.workflows.checks import check_positive, check_probability, shown

__all__ = ["Requirement", "PositionRequirement", "OrientationRequirement", "check_requirements",
           "DEFAULT_RADIUS_MM", "DEFAULT_PROB", "ESTIMATORS", "CALIBRATED_ESTIMATORS"]

#: the requirement when none is given: ``P(|dP| < 0.25 mm) >= 0.95`` (the command line's defaults too)
DEFAULT_RADIUS_MM = 0.25
DEFAULT_PROB = 0.95
#: probability estimators of the verification (see :func:`tolalloc.verify.verify_design`)
ESTIMATORS = ("auto", "plain", "paired", "importance")
#: those of the calibration-aware allocation's end-to-end Monte Carlo (it has no importance sampler)
CALIBRATED_ESTIMATORS = ("auto", "plain", "paired")


class Requirement:
    """Base of the requirements on the tool-pose error; subclasses are frozen dataclasses.

    Class attributes
    ----------------
    kind : str
        The error the requirement bounds (``"position"``, ``"orientation"``); a job takes one requirement of each
        kind at most.
    calibration_aware : bool
        Whether the calibration-aware allocation (``allocate_tolerances(calibration=...)``) handles it.

    A subclass checks its fields in :meth:`check` (called at construction: a bad value is an
    :class:`~tolalloc.exceptions.ArgumentError` naming ``ClassName.field``) and implements :meth:`text`,
    :meth:`problem_arguments` and :meth:`cli_arguments`; :meth:`estimators` and :meth:`to_dict` have defaults.
    """

    kind: ClassVar[str] = ""
    calibration_aware: ClassVar[bool] = False

    def __post_init__(self):
        self.check()

    def check(self) -> None:  # pragma: no cover - every subclass overrides it
        """Refuse a bad field (an :class:`ArgumentError` naming ``ClassName.field``)."""
        raise NotImplementedError

    def text(self) -> str:  # pragma: no cover
        """The requirement as a formula with its units, e.g. ``P(|dP| < 0.25 mm) >= 0.95``."""
        raise NotImplementedError

    def problem_arguments(self) -> dict:  # pragma: no cover
        """Keyword arguments of :func:`tolalloc.allocate.build_problem` that state this requirement."""
        raise NotImplementedError

    def cli_arguments(self) -> list[str]:  # pragma: no cover
        """The command-line flags that state this requirement (``["--radius-mm", "0.25", ...]``)."""
        raise NotImplementedError

    def estimators(self, calibrated: bool = False) -> tuple[str, ...]:
        """Verification estimators that can judge this requirement (``calibrated``: in the calibration-aware
        allocation's end-to-end Monte Carlo)."""
        return CALIBRATED_ESTIMATORS if calibrated else ESTIMATORS

    def to_dict(self) -> dict:
        """The fields (their units in their names) and the kind, for JSON records."""
        return {"kind": self.kind, **asdict(self)}

    def _field(self, name: str) -> str:
        return f"{type(self).__name__}.{name}"

    def __str__(self) -> str:
        return self.text()


@dataclass(frozen=True)
class PositionRequirement(Requirement):
    """``P(|dP| < radius_mm) >= prob``: the tool-position error lies within a ball of radius ``radius_mm``.

    Parameters
    ----------
    radius_mm : float
        Radius r of the ball [mm] (default 0.25).
    prob : float
        Probability p, strictly between 0 and 1 (default 0.95).

    Examples
    --------
    >>> import tolalloc
    >>> tolalloc.PositionRequirement(radius_mm=0.1, prob=0.99).text()
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
        return {"radius_mm": float(self.radius_mm), "prob": float(self.prob)}

    def cli_arguments(self) -> list[str]:
        return ["--radius-mm", f"{self.radius_mm:g}", "--prob", f"{self.prob:g}"]


@dataclass(frozen=True)
class OrientationRequirement(Requirement):
    """``P(|dw| < radius_deg) >= prob``: the tool's rotation error (the angle of the rotation from the nominal to the
    actual tool frame) stays below ``radius_deg``.

    Parameters
    ----------
    radius_deg : float
        Largest rotation angle [deg].
    prob : float, optional
        Probability p in (0, 1); default: the probability of the job's position requirement.

    Examples
    --------
    >>> import tolalloc
    >>> tolalloc.OrientationRequirement(radius_deg=0.02).text()
    'P(|dw| < 0.02 deg) >= p of the position requirement'
    """

    radius_deg: float
    prob: float | None = None
    kind: ClassVar[str] = "orientation"
    calibration_aware: ClassVar[bool] = False

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


def check_requirements(value, argument: str = "requirement", *, need: tuple = ("position",)) -> tuple:
    """One :class:`Requirement` or a list / tuple of them -> a tuple, at most one of each kind, the kinds in
    ``need`` present; sorted position first."""
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    bad = [v for v in items if not isinstance(v, Requirement)]
    if not items or bad:
        raise ArgumentError(argument, "expected a requirement or a list of them, e.g. "
                            "tolalloc.PositionRequirement(radius_mm=0.25, prob=0.95) or [PositionRequirement(...), "
                            f"OrientationRequirement(radius_deg=0.02)], got {shown(bad[0] if bad else value)}.")
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
    order = {"position": 0, "orientation": 1}
    return tuple(sorted(items, key=lambda r: order.get(r.kind, 2)))
