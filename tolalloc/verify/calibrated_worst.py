"""End-to-end Monte Carlo of a calibration-aware design at its worst poses (over a box: the region's worst).

:func:`verify_calibrated_design` runs :func:`tolalloc.verify.calibrated.verify_calibration` (manufacture with the
design's sigmas, simulate the plan's measurements, calibrate each robot by nonlinear least squares, compensate, use)
at the lowest-``P`` poses of a :class:`~tolalloc.allocate.calibrated.design.CalibratedDesign` -- for a box the last
search's worst pose, the worst poses of the fresh coverage sample and the lowest active poses -- and states per pose,
with the criteria of :mod:`tolalloc.verify.designs` on the interval simultaneous over those poses (Bonferroni):

* **demonstrated**: the whole interval at or above ``p``; **consistent**: it reaches ``p``; **failed**: wholly below;
* a certified design passes a pose only when demonstrated, an exact design (which sits at ``p`` at its binding
  poses by construction) and a standard-grade design of it (``standard=``, held at ``p`` by the same exact
  probability) pass a consistent pose; all also need the linear prediction not above the interval (the
  linear post-calibration model the design was allocated on is not optimistic there). Whether the linear prediction
  lies inside the interval (:attr:`CalibrationCheck.agree`) is reported beside it: a Monte Carlo above the linear
  prediction means the design is conservative there, not that it fails.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.verify.calibrated import CalibrationCheck, verify_calibration
from tolalloc.verify.designs import overall_verdict, pose_verdicts
from tolalloc.verify.verdicts import interval_words

__all__ = ["EndToEnd", "verify_calibrated_design"]


@dataclass(frozen=True, eq=False)
class EndToEnd:
    """Result of :func:`verify_calibrated_design`.

    Attributes
    ----------
    check : CalibrationCheck
    prob : float
        The requirement ``p``.
    design : str
        ``certified``, ``exact`` or ``standard`` (the design checked).
    verdicts : array of str, shape (m,)
        Per pose ``demonstrated``, ``consistent`` or ``failed``.
    """

    check: CalibrationCheck
    prob: float
    design: str
    verdicts: np.ndarray

    @property
    def verdict(self) -> str:
        return overall_verdict(self.verdicts)

    @property
    def optimistic(self) -> np.ndarray:
        """Per pose: the linear prediction lies above the Monte Carlo interval (the linear model is optimistic)."""
        return self.check.p_linear > self.check.ci_high

    @property
    def passed(self) -> bool:
        """Certified: demonstrated at every pose; exact and standard: no pose failed; all: the linear prediction
        nowhere above the interval."""
        need = ("demonstrated",) if self.design == "certified" else ("demonstrated", "consistent")
        return bool(np.all(np.isin(self.verdicts, need)) and not np.any(self.optimistic))

    def to_frame(self) -> pd.DataFrame:
        df = self.check.to_frame()
        df["verdict"] = self.verdicts
        return df

    def interval_label(self) -> str:
        """The intervals' name: ``simultaneous 95% interval over the 7 poses`` (``95% interval`` at one pose)."""
        c = self.check
        return interval_words(c.family_level, len(c.q)) + " interval" + (f" over the {len(c.q)} poses"
                                                                         if len(c.q) > 1 else "")

    def to_dict(self) -> dict:
        c = self.check
        return {"design": self.design, "n_robots": c.n_robots, "poses": len(c.q), "verdict": self.verdict,
                "passed": self.passed, "agree": bool(np.all(c.agree)), "linear_optimistic": bool(np.any(self.optimistic)), "p_mc_min": float(c.p_mc.min()),
                "ci_low_min": float(c.ci_low.min()), "family_level": c.family_level, "n_intervals": c.n_intervals,
                "level_per_interval": c.level_per_interval, "intervals": self.interval_label(),
                "p_linear_min": float(c.p_linear.min()),
                "fits_converged": c.converged_share}

    def message(self) -> str:
        c = self.check
        i = int(np.argmin(c.p_mc))
        return (f"end-to-end Monte Carlo of the {self.design} design at its {len(c.q)} worst poses ({c.n_robots} "
                f"simulated calibrations): {self.verdict}; lowest P_hat {c.p_mc[i]:.4f} [{c.ci_low[i]:.4f}, "
                f"{c.ci_high[i]:.4f}] ({self.interval_label()}) against linear {c.p_linear[i]:.4f}; "
                + ("linear prediction inside every interval" if np.all(c.agree) else
                   f"linear prediction outside the interval at {int(np.sum(~c.agree))} pose(s), above it at "
                   f"{int(np.sum(self.optimistic))}")
                + ("" if c.converged_share == 1.0 else f"; {100 * c.converged_share:.1f} % of the fits converged")
                + ("; passed" if self.passed else "; NOT passed"))


def verify_calibrated_design(res, *, which: str = "chosen", standard=None, n_robots: int = 4000, seed: int = 0,
                             k_worst: int = 3, level: float = 0.95, estimator: str = "plain") -> EndToEnd:
    """End-to-end Monte Carlo of a calibration-aware design at its worst poses (module docstring).

    Parameters
    ----------
    res : CalibratedDesign
        From :func:`tolalloc.allocate.calibrated.design.allocate_with_calibration` (position plan).
    which : {"chosen", "certified"}
        The design checked: the result's chosen design (exact when accepted) or the certified one.
    standard : CalibratedStandard, optional
        Check this standard-grade design of ``res`` instead
        (:func:`tolalloc.allocate.calibrated.standard.standardize_calibrated`): its tolerances, repeatability grades
        and worst poses (:meth:`~tolalloc.allocate.calibrated.standard.CalibratedStandard.check_poses`); ``which`` is
        then unused. Judged like the exact design (a consistent pose passes): it is held at ``p`` by the exact
        post-calibration probability, not by a certificate.
    n_robots : int
        Simulated robots (= trials per pose).
    k_worst : int
        Worst poses per source (see :meth:`CalibratedDesign.check_poses`).
    estimator : {"plain", "auto", "paired"}
        Estimator of the end-to-end probability (:func:`tolalloc.verify.calibrated.verify_calibration`).
    """
    if which not in ("chosen", "certified"):
        raise TolallocError(f"which: expected 'chosen' or 'certified', got {which!r}.")
    if isinstance(n_robots, bool) or not isinstance(n_robots, (int, np.integer)) or n_robots < 10:
        raise TolallocError(f"n_robots: expected a whole number >= 10, got {n_robots!r}.")
    if not res.design.ok:
        raise TolallocError("verify_calibrated_design: the allocation has no design to check "
                            f"({res.design.message}).")
    if res.plan.measurement != "position":
        raise TolallocError("verify_calibrated_design: the end-to-end Monte Carlo simulates position measurements; "
                            "the plan measures poses (measurement = pose).")
    if standard is not None:
        same = (hasattr(standard, "end_to_end_inputs") and standard.plan is res.plan
                and list(standard.problem.model.names) == list(res.problem.model.names))
        if not same:
            raise TolallocError("standard: expected the CalibratedStandard of this allocation (tolalloc.allocate."
                                "calibrated.standard.standardize_calibrated(res)), got a "
                                f"{type(standard).__name__}" + (" of another allocation (another plan)."
                                                                 if hasattr(standard, "end_to_end_inputs") else "."))
        if not standard.design.ok:
            raise TolallocError(f"standard: the standard-grade design has no design to check "
                                f"({standard.design.message}).")
        kw, label = standard.end_to_end_inputs(k_worst), "standard"
    else:
        kw = res.end_to_end_inputs(k_worst, which)
        label = "exact" if which == "chosen" and res.exact_accepted else "certified"
    chk = verify_calibration(n_robots=int(n_robots), seed=seed, level=level, estimator=estimator, **kw)
    return EndToEnd(chk, float(res.problem.prob), label, pose_verdicts(chk.ci_low, chk.ci_high, res.problem.prob))
