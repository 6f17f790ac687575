"""How many Monte Carlo samples a verification needs to resolve each requirement's tail, and which estimator runs.

An interval at level ``1 - alpha`` can lie wholly above ``p`` only when the samples can tell ``P`` from ``p``:
plain Monte Carlo and the paired estimator with no discordant sample need ``n >= z^2 p / (1 - p)``
(:func:`resolvable_n`). Every requirement of a verification -- the position one and, when stated, the orientation
one -- goes through the same rule (:func:`choose_estimator`): switch to importance sampling where it applies, or
refuse with the samples needed (:func:`check_resolvable`).
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.montecarlo.intervals import z_of_level
from tolalloc.montecarlo.paired import control_fallback_reason

__all__ = ["resolvable_n", "check_resolvable", "choose_estimator", "IMPORTANCE_REQUIREMENTS", "RARE_TAIL"]


#: requirements that importance sampling can estimate (the others run as ``auto`` when it is requested)
IMPORTANCE_REQUIREMENTS = ("position",)

#: Tails ``1 - p`` at or below which ``auto`` runs importance sampling from the first look: there the nonlinear and
#: linear indicators almost never disagree on the nominal draws (no discordant draw in 2^20 at p = 0.999 and beyond,
#: for the tool_changer and the ur10: ``reports/rare_event/report.md``), so the paired interval is its zero-count
#: width ``+-z^2 / n``, too wide for the margins such designs have.
RARE_TAIL = 1e-3


def resolvable_n(prob: float, level: float = 0.95) -> int:
    """Smallest sample size whose plain (or zero-discordance paired) interval at ``level`` can lie above ``prob``.

    ``level`` is the level of each interval: for ``m`` simultaneous intervals ``1 - (1 - family level) / m``
    (:func:`tolalloc.montecarlo.intervals.simultaneous_level`; ``m`` counts the possible second looks,
    :func:`tolalloc.verify.verdicts.verification_family`), whose larger ``z`` needs more samples: 171 at
    ``p = 0.95`` over 18 poses judged once, 195 with a possible second look at each (36 intervals).
    """
    return int(np.ceil(z_of_level(level) ** 2 * prob / (1.0 - prob)))


def check_resolvable(model, prob: float, n: int, estimator: str, name: str = "n_mc", level: float = 0.95,
                     what: str = "95% interval", requirement: str = "position") -> None:
    """Refuse a sample size that cannot resolve the tail ``1 - prob`` with the estimator that would run.

    Plain Monte Carlo with no failure at all has a lower bound ``n / (n + z^2)``: below ``p`` unless
    ``n >= z^2 p / (1 - p)``. The paired interval with no discordant sample is ``+-z^2 / (n + z^2)``: wider than
    the whole tail unless ``n >= z^2 p / (1 - p)`` too. ``z`` is the normal quantile of ``level``, the level of
    each interval (for simultaneous intervals the Bonferroni one); ``what`` names the interval in the message.
    Importance sampling is not limited this way; it estimates the position requirement only (``requirement``).
    """
    importance_applies = requirement in IMPORTANCE_REQUIREMENTS
    if estimator == "importance" and importance_applies:
        return
    need = resolvable_n(prob, level)
    if n >= need:
        return
    gauss = not control_fallback_reason(model)
    how = "plain Monte Carlo" if (estimator == "plain" or not gauss) else "the paired estimator"
    if not importance_applies:
        alt = f" (importance sampling estimates the position requirement only, not the {requirement} one)"
    elif gauss:
        alt = " or `estimator` importance (importance sampling of the paired difference)"
    else:
        alt = " (the model has non-Gaussian parameters, so neither the paired estimator nor importance sampling applies)"
    tail = "tail" if requirement == "position" else f"{requirement} tail"
    default = (f" (`n_max` defaults to 4 x `n_mc`, as in allocate_tolerances and the command line: `n_mc` >= "
               f"{int(np.ceil(need / 4))} gives it)" if name == "n_max" else "")
    raise ArgumentError(name, f"{n} samples per pose cannot resolve the {tail} 1 - p = {1 - prob:.3g} with {how}: "
                        f"even with no miss the {what} reaches below p = {prob:g}; give `{name}` >= {need}{default}"
                        f"{alt}.")


def choose_estimator(model, requirements, n_mc: int, n_max: int, second_look: bool, estimator: str, level: float,
                     what: str) -> str:
    """The estimator of a verification, every requirement checked against its tail by one rule.

    For each requirement ``(name, p)`` (position first): with ``auto`` on a Gaussian model a sample size too small
    for the paired interval to resolve ``1 - p`` (:func:`resolvable_n` at ``level``, the level of each interval), or
    a rare-event tail ``1 - p <=`` :data:`RARE_TAIL`, switches to importance sampling where it applies
    (:data:`IMPORTANCE_REQUIREMENTS`); anything else still
    unresolvable is refused with the samples needed (:func:`check_resolvable`). ``second_look`` is the family's
    decision (:func:`tolalloc.verify.verdicts.verification_family`: ``second_looks > 0``): with it the position
    requirement is judged at ``n_max`` (its straddling poses are re-run with that many samples), every other
    requirement, and the position one without it, at ``n_mc``.
    """
    gauss = not control_fallback_reason(model)
    for req, prob in requirements:
        redo = second_look and req == "position"
        n, name = (int(n_max), "n_max") if redo else (int(n_mc), "n_mc")
        applies = req in IMPORTANCE_REQUIREMENTS
        if estimator == "auto" and gauss and applies and (n < resolvable_n(prob, level) or 1 - prob <= RARE_TAIL):
            estimator = "importance"  # the paired interval could not resolve this tail with n samples
        runs = estimator if applies or estimator != "importance" else "auto"
        check_resolvable(model, prob, n, runs, name, level, what, req)
    return estimator
