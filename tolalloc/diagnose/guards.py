"""Guards of the diagnosis: implausible parameters, extrapolating test poses, fits worse than nominal.

* :func:`prior_flags` -- a fitted geometric parameter beyond ``n_sigma`` (3) prior standard deviations of the
  MAP calibration (:mod:`.geometry`): the data pulled it far past what the robot's sigma set makes plausible
  (an unidentifiable combination drifting, a wrong robot or probe, gross outliers).
* :func:`extrapolation_flags` -- per test pose: a joint value outside the training range by more than a
  margin (5 deg / 5 mm), or a joint-space distance to the nearest training pose (each joint divided by its
  training standard deviation) beyond ``far_factor`` x the 95th percentile of the training poses'
  leave-one-out nearest-neighbour distances. Such predictions are extrapolations.
* :func:`cv_fallback` -- a fitted model that does worse than a simpler one on cross-validation (out-of-fold RMS
  larger by more than ``FALLBACK_MARGIN``, 1 %) is not used: final worse than nominal -> nominal; final (with
  effects) worse than geometric -> geometric. Geometry alone worse than nominal while the final model wins
  is reported as a note, without fallback.

Every guard returns plain messages; the pipeline lists them in ``Diagnosis.guards`` (JSON ``guards``) and the
CLI prints them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from tolalloc.robot.model import Robot

__all__ = ["Extrapolation", "extrapolation_flags", "prior_flags", "cv_fallback", "RANGE_MARGIN_DEG",
           "RANGE_MARGIN_MM", "FAR_FACTOR", "PRIOR_N_SIGMA", "FALLBACK_MARGIN"]

RANGE_MARGIN_DEG = 5.0
RANGE_MARGIN_MM = 5.0
FAR_FACTOR = 1.5
PRIOR_N_SIGMA = 3.0
FALLBACK_MARGIN = 0.01


@dataclass(frozen=True, eq=False)
class Extrapolation:
    """Extrapolation flags of test poses.

    Attributes
    ----------
    outside_range : array of bool, shape (T,)   some joint outside the training range by more than the margin
    far : array of bool, shape (T,)             nearest training pose farther than ``threshold``
    distance : array, shape (T,)                normalised joint-space distance to the nearest training pose
    threshold : float                           ``FAR_FACTOR`` x 95th percentile of training LOO distances
    joints_outside : tuple of str               joints some test pose leaves the training range of
    """

    outside_range: np.ndarray
    far: np.ndarray
    distance: np.ndarray
    threshold: float
    joints_outside: tuple

    @property
    def flagged(self) -> np.ndarray:
        return self.outside_range | self.far

    def message(self) -> str | None:
        """One guard line, or None when no pose extrapolates."""
        n = int(self.flagged.sum())
        if n == 0:
            return None
        return (f"extrapolation: {n} of {len(self.flagged)} test poses lie outside the training data "
                f"({int(self.outside_range.sum())} outside the training range of {', '.join(self.joints_outside) or '-'} "
                f"by more than {RANGE_MARGIN_DEG:g} deg / {RANGE_MARGIN_MM:g} mm; {int(self.far.sum())} farther from every "
                f"training pose than {self.threshold:.3g} (normalised joint space)); their predictions are extrapolations")

    def to_dict(self) -> dict:
        return {"flagged": self.flagged.tolist(), "outside_range": self.outside_range.tolist(), "far": self.far.tolist(),
                "distance": self.distance.tolist(), "threshold": self.threshold, "joints_outside": list(self.joints_outside)}


def extrapolation_flags(robot: Robot, q_train: np.ndarray, q_test: np.ndarray, *, far_factor: float = FAR_FACTOR) -> Extrapolation:
    """Flag test poses that extrapolate from the training poses (see the module docstring).

    Parameters
    ----------
    robot : Robot
    q_train : array, shape (P, n) [rad, mm]
    q_test : array, shape (T, n) [rad, mm]
    """
    rev = robot.revolute_mask
    margin = np.where(rev, np.deg2rad(RANGE_MARGIN_DEG), RANGE_MARGIN_MM)
    lo, hi = q_train.min(0), q_train.max(0)
    out_j = (q_test < lo - margin) | (q_test > hi + margin)
    floor = np.where(rev, np.deg2rad(1.0), 1.0)  # a joint held still in training: 1 deg / 1 mm scale
    scale = np.maximum(q_train.std(0), floor)
    tree = cKDTree(q_train / scale)
    loo = tree.query(q_train / scale, k=2)[0][:, 1] if len(q_train) > 1 else np.zeros(1)
    threshold = float(far_factor * np.percentile(loo, 95))
    dist = tree.query(q_test / scale, k=1)[0]
    joints = tuple(j.name for k, j in enumerate(robot.joints) if out_j[:, k].any())
    return Extrapolation(out_j.any(1), dist > threshold, dist, threshold, joints)


def prior_flags(fit, n_sigma: float = PRIOR_N_SIGMA) -> tuple:
    """Messages for fitted geometric parameters beyond ``n_sigma`` prior standard deviations.

    Parameters
    ----------
    fit : :class:`tolalloc.diagnose.calibrate.Fit` (its model's ``sigma`` is the prior)
    """
    out = []
    for k in fit.geo_index:
        prm = fit.model.params[k]
        if prm.sigma > 0 and abs(fit.delta[k]) > n_sigma * prm.sigma:
            f, u = prm.to_interface, prm.interface_unit
            out.append(f"implausible parameter: {prm.name} = {fit.delta[k] * f:.3g} {u} is {abs(fit.delta[k]) / prm.sigma:.1f} "
                       f"prior sigma ({prm.sigma * f:.3g} {u}); check the probe offset, the robot model and outliers")
    return tuple(out)


def cv_fallback(nominal, geometric, final, margin: float = FALLBACK_MARGIN) -> tuple:
    """Which evaluation to report as final, and the guard messages.

    Parameters
    ----------
    nominal, geometric, final : :class:`tolalloc.diagnose.select.Evaluation`
    margin : float   relative CV RMS excess that counts as worse

    Returns
    -------
    chosen : Evaluation
    messages : tuple of str   empty when nothing fired
    """
    cv = {name: float(np.sqrt(np.mean(np.sum(ev.oof_mm ** 2, axis=1))))
          for name, ev in (("nominal", nominal), ("geometric", geometric), ("final", final))}

    def pct(a, b):
        return f"{cv[a]:.4g} vs {cv[b]:.4g} mm RMS, {100 * (cv[a] / cv[b] - 1):+.1f} %"

    if cv["final"] > (1 + margin) * cv["nominal"]:
        return nominal, (f"fallback: the fitted model ({final.label}) does worse than the nominal model on "
                         f"cross-validation ({pct('final', 'nominal')}); reporting the nominal model "
                         "(registration + probe offset only) as final, no effect",)
    if final is not geometric and cv["final"] > (1 + margin) * cv["geometric"]:
        return geometric, (f"fallback: the model with effects ({final.label}) does worse than the geometric model on "
                           f"cross-validation ({pct('final', 'geometric')}); reporting the geometric model as final, "
                           "no effect",)
    if cv["geometric"] > (1 + margin) * cv["nominal"]:
        return final, (f"note: the geometric calibration alone does worse than the nominal model on cross-validation "
                       f"({pct('geometric', 'nominal')}); the final model ({final.label}) does better",)
    return final, ()
