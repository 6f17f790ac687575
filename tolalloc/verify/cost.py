"""What a verification's sample size costs, checked before it runs (:mod:`tolalloc.budget`).

A verification runs its estimator at every pose (``n_mc`` samples each); the correction loop may run it again after
each round and once more on fresh draws. :func:`check_verification_budget` refuses an ``n_mc`` whose first
verification alone cannot finish within the time budget of a call, and announces a long one with what the loop may
add.
"""

from __future__ import annotations

import numpy as np

__all__ = ["verification_poses", "check_verification_budget", "check_allocation_budgets"]

#: poses a box region adds to its active set for the verification (the worst poses of the coverage sample)
COVERAGE_WORST = 3


def verification_poses(model, q=None) -> int:
    """Poses a verification will run at: those of ``q`` (P, n); for a box region (``q`` None) about one active pose
    per allocated parameter, plus the coverage check's worst poses (an upper estimate: the tool_changer's working
    box has 12 active poses for 22 parameters)."""
    if q is not None:
        return int(np.atleast_2d(q).shape[0])
    return len(model.params) + COVERAGE_WORST


def check_verification_budget(model, n_poses: int, n_mc: int, *, estimator: str = "auto", rounds: int = 0,
                              n_jobs: int | None = None, argument: str = "n_mc", announce: bool = True):
    """Refuse ``n_mc`` samples per pose at ``n_poses`` poses that one verification cannot run within the time budget
    (:func:`tolalloc.budget.check_count`); announce a long one, with the verifications the correction loop may add
    (``rounds``: its round limit; each round is verified, and a corrected design once more on fresh draws).
    Returns the estimate of one verification."""
    from tolalloc.budget import chain_scale, check_count
    from tolalloc.montecarlo.parallel import default_jobs

    kinds = {"mc": n_poses} if estimator == "plain" else {"paired": n_poses}
    if estimator == "importance":
        kinds = {"importance": n_poses}
    note = "one verification" + (f", of up to {rounds + 2} with the correction loop" if rounds else "")
    return check_count(n_mc, argument, f"samples per pose at {n_poses} pose{'s' if n_poses != 1 else ''}", kinds,
                       scale=chain_scale(len(model.params), model.robot.n_joints), threads=n_jobs or default_jobs(),
                       example="1000000", announce=announce, note=note,
                       remedy="or switch the verification off")


def check_allocation_budgets(model, box: bool, q, *, n_mc: int | None, estimator: str, coverage_n: int,
                             rounds: int) -> None:
    """The counts of an allocation checked before any work (:func:`tolalloc.workflows.allocate_tolerances`): the
    verification's ``n_mc`` (None: no verification) at the poses ``q`` or, for a box region (``box``), the poses its
    search may find; the coverage sample ``coverage_n`` of a box region, checked once more when ``rounds`` > 0 (a
    corrected design, or the standard design of a calibration-aware allocation). Long runs are announced."""
    from tolalloc.allocate.region_coverage import check_coverage_budget

    if n_mc is not None:
        check_verification_budget(model, verification_poses(model, None if box else q), n_mc, estimator=estimator,
                                  rounds=rounds, announce=True)
    if box:
        check_coverage_budget(coverage_n, runs=2 if rounds else 1, argument="coverage_n", announce=True)
