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
                                               OrientationRequirement, PositionRequirement, Requirement,
                                               check_requirements)

__all__ = ["Requirement", "PositionRequirement", "OrientationRequirement", "check_requirements",
           "DEFAULT_RADIUS_MM", "DEFAULT_PROB", "ESTIMATORS", "CALIBRATED_ESTIMATORS"]
