"""The base of the requirement objects (:mod:`tolalloc.acceptance.requirements` has the module's story): the
:class:`Requirement` protocol, the common fields of the ISO 9283 requirements (:class:`IsoRequirement`) and the
defaults the jobs share."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import ClassVar

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.acceptance.conditions import Conditions
from tolalloc.units import check_positive, check_probability

__all__ = ["Requirement", "IsoRequirement", "POPULATIONS", "AXES", "DEFAULT_RADIUS_MM", "DEFAULT_PROB",
           "ESTIMATORS", "CALIBRATED_ESTIMATORS"]

POPULATIONS = ("fleet", "robot")
#: directions of motion along the base frame's axes (the approach directions of a multi-directional test)
AXES = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0), "+z": (0, 0, 1), "-z": (0, 0, -1)}


#: the requirement when none is given: ``P(|dP| < 0.25 mm) >= 0.95`` (the command line's defaults too)
DEFAULT_RADIUS_MM = 0.25
DEFAULT_PROB = 0.95
#: probability estimators of the verification (see :func:`tolalloc.verify.verify_design`)
ESTIMATORS = ("auto", "plain", "paired", "importance")
#: those of the calibration-aware allocation's end-to-end Monte Carlo (it has no importance sampler)
CALIBRATED_ESTIMATORS = ("auto", "plain", "paired")


class Requirement:
    """Base of the requirements on the tool-pose error; subclasses are frozen dataclasses.

    A subclass checks its fields in :meth:`check` (called at construction) and implements :meth:`text`.

    Attributes
    ----------
    kind : str
        What the requirement bounds; a job takes one requirement of each kind at most.
    clause : str
        Where the statistic is defined (``""`` for the balls). Both are class attributes.
    """

    kind: ClassVar[str] = ""
    clause: ClassVar[str] = ""
    calibration_aware: ClassVar[bool] = False

    def __post_init__(self):
        self.check()

    def check(self) -> None:  # pragma: no cover - every subclass overrides it
        raise NotImplementedError

    def text(self) -> str:  # pragma: no cover
        """The requirement as a formula with its units."""
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
        """The fields (units in their names) and the kind, for JSON records and requirement files."""
        out = {"kind": self.kind}
        for k, v in asdict(self).items():
            if isinstance(v, dict):  # the test conditions, flattened as in a requirement file
                out.update(v)
            elif isinstance(v, np.ndarray):
                out[k] = v.tolist()
            elif v is not None:
                out[k] = list(v) if isinstance(v, tuple) else v
        return out

    def _field(self, name: str) -> str:
        return f"{type(self).__name__}.{name}"

    def __str__(self) -> str:
        return self.text()


@dataclass(frozen=True, kw_only=True)
class IsoRequirement(Requirement):
    """Common fields of the ISO 9283 requirements (a base class; use its subclasses).

    Attributes
    ----------
    share : float
        Share of the built robots that meet the limit (``population="fleet"``), or the probability that the robot
        at hand meets it (``"robot"``); in (0, 1).
    population : {"fleet", "robot"}
    conditions : Conditions
    guard_band : bool
        Allocate for conformance *demonstrated* by the acceptance test (ISO 14253-1), not only met.
    """

    share: float = 0.95
    population: str = "fleet"
    conditions: Conditions = field(default_factory=Conditions)
    guard_band: bool = False
    #: statistic symbol, unit of the limit, whether the limit bounds a signed value's magnitude
    symbol: ClassVar[str] = ""
    unit: ClassVar[str] = "mm"

    @property
    def limit(self) -> float:
        """The limit in internal units [mm or rad]."""
        v = getattr(self, f"limit_{self.unit}")
        return float(np.deg2rad(v)) if self.unit == "deg" else float(v)

    def check(self) -> None:
        check_positive(getattr(self, f"limit_{self.unit}"), self._field(f"limit_{self.unit}"), self.unit,
                  "0.05" if self.unit == "mm" else "0.01")
        check_probability(self.share, self._field("share"))
        if self.population not in POPULATIONS:
            raise ArgumentError(self._field("population"), f"expected one of {', '.join(POPULATIONS)} (a share of "
                                f"the built robots, or the robot at hand), got {self.population!r}.")
        if not isinstance(self.conditions, Conditions):
            raise ArgumentError(self._field("conditions"), "expected tolalloc.acceptance.Conditions(load_pct=..., "
                                f"speed_pct=...), got {self.conditions!r}.")
        if not isinstance(self.guard_band, (bool, np.bool_)):
            raise ArgumentError(self._field("guard_band"), f"expected True or False, got {self.guard_band!r}.")

    def who(self) -> str:
        """``for 95 % of built robots`` / ``for the robot with probability 0.95``."""
        if self.population == "fleet":
            return f"for {100 * self.share:g} % of built robots"
        return f"for the robot, with probability {self.share:g}"

    def text(self) -> str:
        lim = getattr(self, f"limit_{self.unit}")
        guard = "; demonstrated with the measurement uncertainty" if self.guard_band else ""
        return (f"{self.symbol} <= {lim:g} {self.unit} {self.who()} (ISO 9283 {self.clause}; "
                f"{self.conditions.text()}{guard})")
