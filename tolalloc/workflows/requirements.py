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
(:meth:`~Requirement.estimators`). A new kind of requirement is a new frozen dataclass that implements them. The
classes are defined once, in :mod:`tolalloc.acceptance.requirements` (below the allocation, beside the ISO 9283 kinds
that derive from the same base), and re-exported here as the jobs' settings objects.
"""

from __future__ import annotations

from tolalloc.acceptance.requirements import (CALIBRATED_ESTIMATORS, DEFAULT_PROB, DEFAULT_RADIUS_MM, ESTIMATORS,
                                               OrientationRequirement, PositionRequirement, Requirement)
from tolalloc.exceptions import ArgumentError
from tolalloc.workflows.checks import shown

__all__ = ["Requirement", "PositionRequirement", "OrientationRequirement", "check_requirements",
           "DEFAULT_RADIUS_MM", "DEFAULT_PROB", "ESTIMATORS", "CALIBRATED_ESTIMATORS"]

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
