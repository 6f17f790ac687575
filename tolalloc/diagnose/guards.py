"""Guards of the diagnosis: implausible parameters, extrapolating test poses, fits worse than nominal.

* :func:`parameter_checks` (:func:`prior_flags` returns its guard lines) -- every fitted geometric parameter
  against the plausibility level ``b`` of the robot (:func:`.geometry.plausibility_levels`: the as-built
  accuracy of the robot class, ~1 mm per metre of size and 0.1 deg, or the MAP prior sigma if larger) and
  its posterior standard deviation ``s`` (Gauss-Newton with the prior, see :func:`.uncertainty.parameter_covariance`). A
  guard fires when a value is **implausible** (``|v| > 3 b``: an unidentifiable combination drifting, a
  wrong robot or probe, gross outliers) or **weakly identified** (``|v| > b`` while ``s > |v| / 2``: larger
  than the robot makes likely, on a direction the poses barely resolve -- prior-data tension under a weak
  prior), and when a probe-offset component (no prior) is pinned down only to more than the as-built
  position level (the flange axis hardly changed direction). A well-identified deviation (``|v| >= 3 s`` and
  ``|v| >= b / 2``) is a **finding**, reported but not a guard: a real UR10's 1 mm elbow offset is as built.
* :func:`extrapolation_flags` -- per test pose: a joint value outside the training range by more than a
  margin (5 deg / 5 mm; revolute angles modulo 360 deg, and a joint whose training angles go round the turn has no
  outside), or a joint-space distance to the nearest training pose
  (each joint divided by its training standard deviation; revolute ones wrapping around) beyond ``far_factor``
  x the 95th percentile of the training poses' leave-one-out nearest-neighbour distances. Such predictions are extrapolations.
* :func:`cv_fallback` -- a fitted model that does worse than a simpler one on cross-validation (out-of-fold RMS
  larger by more than ``FALLBACK_MARGIN``, 1 %) is not used: final worse than nominal -> nominal; final (with
  effects) worse than geometric -> geometric. Geometry alone worse than nominal while the final model wins
  is reported as a note, without fallback.
* the predicted uncertainty of the test poses and its coverage check (:func:`.uncertainty.prediction_uncertainty`)
  is in :mod:`.uncertainty`.

Every guard returns plain messages; the pipeline lists them in ``Diagnosis.guards`` (JSON ``guards``) and the
CLI prints them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from tolalloc.exceptions import ArgumentError, describe
from tolalloc.robot.model import Robot
from tolalloc.diagnose.scores import rms
from tolalloc.diagnose.geometry import as_built_levels, plausibility_levels
from tolalloc.diagnose.uncertainty import parameter_covariance

__all__ = ["Extrapolation", "extrapolation_flags", "outside_range", "prior_flags", "ParameterCheck", "parameter_checks", "reading",
           "FINDING_FRACTION", "cv_fallback", "RANGE_MARGIN_DEG", "RANGE_MARGIN_MM", "FAR_FACTOR", "PRIOR_N_SIGMA",
           "FALLBACK_MARGIN", "noise_guard", "NOISE_FACTOR", "instrument_noise"]

RANGE_MARGIN_DEG = 5.0
RANGE_MARGIN_MM = 5.0
#: The largest gap between training angles of a revolute joint is its outside only when it is more than this many
#: times the second largest; otherwise the training angles go round the turn (:func:`_outside_arc`).
GAP_DISTINCT = 2.0
FAR_FACTOR = 1.5
PRIOR_N_SIGMA = 3.0
#: A well-identified deviation of at least this fraction of the plausibility level is reported as a finding.
FINDING_FRACTION = 0.5
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
        parts = []
        if self.outside_range.any():
            parts.append(f"{int(self.outside_range.sum())} outside the training range of {', '.join(self.joints_outside)} "
                         f"by more than {RANGE_MARGIN_DEG:g} deg / {RANGE_MARGIN_MM:g} mm")
        if self.far.any():
            parts.append(f"{int(self.far.sum())} farther from every training pose than {self.threshold:.3g} "
                         "(normalised joint space)")
        return (f"extrapolation: {n} of {len(self.flagged)} test poses lie outside the training data "
                f"({'; '.join(parts)}); their predictions are extrapolations")

    def to_dict(self) -> dict:
        return {"flagged": self.flagged.tolist(), "outside_range": self.outside_range.tolist(), "far": self.far.tolist(),
                "distance": self.distance.tolist(), "threshold": self.threshold, "joints_outside": list(self.joints_outside)}


def _outside_arc(a_train: np.ndarray, a_test: np.ndarray, margin: float) -> np.ndarray:
    """Test angles (T,) [rad] farther than ``margin`` from the shortest arc holding every training angle (P,):
    the circle minus its largest gap between training angles (angles modulo 2 pi).

    Training angles that go round the whole turn have no outside: when the largest gap is not clearly the largest
    (at most :data:`GAP_DISTINCT` x the second largest, as among angles spread over the turn), it is a gap inside
    the range like the others, and no test angle is outside."""
    two_pi = 2.0 * np.pi
    a = np.sort(np.mod(a_train, two_pi))
    gaps = np.diff(np.append(a, a[0] + two_pi))
    i = int(np.argmax(gaps))
    if len(gaps) > 1 and gaps[i] <= GAP_DISTINCT * np.partition(gaps, -2)[-2]:
        return np.zeros(len(a_test), bool)
    start, length = a[(i + 1) % len(a)], two_pi - gaps[i]
    fwd = np.mod(a_test - start, two_pi)  # 0 .. 2 pi past the arc's start
    dist = np.where(fwd <= length, 0.0, np.minimum(fwd - length, two_pi - fwd))
    return dist > margin


def outside_range(robot: Robot, q_train: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(T, n) bool: joint ``k`` of pose ``q[t]`` lies outside the training range by more than the margin (revolute
    angles on the shortest arc holding the training angles)."""
    rev = robot.revolute_mask
    margin = np.where(rev, np.deg2rad(RANGE_MARGIN_DEG), RANGE_MARGIN_MM)
    out_j = (q < q_train.min(0) - margin) | (q > q_train.max(0) + margin)
    for k in np.flatnonzero(rev):
        out_j[:, k] = _outside_arc(q_train[:, k], q[:, k], margin[k])
    return out_j


#: The final model's out-of-fold error above this many times the instrument's stated 3-D noise gets :func:`noise_guard`.
NOISE_FACTOR = 3.0


def extrapolation_flags(robot: Robot, q_train: np.ndarray, q_test: np.ndarray, *, far_factor: float = FAR_FACTOR) -> Extrapolation:
    """Flag test poses that extrapolate from the training poses (see the module docstring).

    Revolute joint values count modulo 360 deg (every fitted model is periodic in them): the range check uses the
    shortest arc holding the training angles, and joint-space distances wrap around.

    Parameters
    ----------
    robot : Robot
    q_train : array, shape (P, n) [rad, mm]
    q_test : array, shape (T, n) [rad, mm]
    """
    rev = robot.revolute_mask
    out_j = outside_range(robot, q_train, q_test)
    floor = np.where(rev, np.deg2rad(1.0), 1.0)  # a joint held still in training: 1 deg / 1 mm scale
    scale = np.maximum(q_train.std(0), floor)
    # a torus in the revolute coordinates (period 2 pi / scale); prismatic ones in a box too long to wrap
    both = np.vstack([q_train, q_test])
    base = np.where(rev, 0.0, both.min(0))
    span = np.where(rev, 2.0 * np.pi, 3.0 * (both.max(0) - both.min(0)) + 1.0) / scale

    def wrap(q):
        w = np.mod((q - base) / scale, span)
        return np.where(w < span, w, 0.0)  # np.mod of a tiny negative value can round up to the period itself

    tree = cKDTree(wrap(q_train), boxsize=span)
    loo = tree.query(wrap(q_train), k=2)[0][:, 1] if len(q_train) > 1 else np.zeros(1)
    threshold = float(far_factor * np.percentile(loo, 95))
    dist = tree.query(wrap(q_test), k=1)[0]
    joints = tuple(j.name for k, j in enumerate(robot.joints) if out_j[:, k].any())
    return Extrapolation(out_j.any(1), dist > threshold, dist, threshold, joints)


@dataclass(frozen=True, eq=False)
class ParameterCheck:
    """Fitted geometric parameters and probe offset against the plausibility level and their posterior sd.

    Attributes
    ----------
    names, units : tuple of str        fitted geometric parameters, then ``probe_offset_x/y/z`` (flange frame)
    value, sd, level : arrays, shape (k + 3,)   value, posterior sd, plausibility level [interface units: mm, deg]
    status : tuple of str              ``implausible``, ``weak``, ``finding`` or ``ok`` per row
    n_sigma : float                    implausible beyond ``n_sigma`` x level
    """

    names: tuple
    units: tuple
    value: np.ndarray
    sd: np.ndarray
    level: np.ndarray
    status: tuple
    n_sigma: float = PRIOR_N_SIGMA

    def to_frame(self):
        import pandas as pd
        return pd.DataFrame({"parameter": self.names, "unit": self.units, "value": self.value,
                             "posterior_sd": self.sd, "plausibility_level": self.level, "status": self.status})

    def _line(self, i) -> str:
        return f"{self.names[i]} = {self.value[i]:.3g} +- {self.sd[i]:.2g} {self.units[i]}"

    def guards(self) -> tuple:
        """Guard lines: implausible and weakly identified parameters, weakly identified probe offset."""
        out = []
        for i, st in enumerate(self.status):
            ratio = abs(self.value[i]) / self.level[i] if self.level[i] > 0 else float("inf")
            if st == "implausible":
                out.append(f"implausible parameter: {self._line(i)} is {ratio:.1f} x the plausibility level "
                           f"({self.level[i]:.3g} {self.units[i]}: the robot class's as-built accuracy or the prior, if larger; "
                           f"fires beyond {self.n_sigma:g}); an unidentifiable "
                           "combination drifting, a wrong robot model or probe, or outliers -- check them")
            elif st == "weak" and self.names[i].startswith("probe_offset"):
                out.append(f"weakly identified probe offset: {self._line(i)}: the poses pin it down only to "
                           f"+-{self.sd[i]:.2g} {self.units[i]}, more than the as-built position level {self.level[i]:.3g} "
                           f"{self.units[i]} (the flange axes hardly changed direction) -- move the wrist joints more")
            elif st == "weak":
                out.append(f"weakly identified parameter: {self._line(i)} is {ratio:.1f} x the plausibility level "
                           f"({self.level[i]:.3g} {self.units[i]}) but the data pin it down only to +-{self.sd[i]:.2g} "
                           f"{self.units[i]}: its value rests on a direction the poses barely resolve -- spread the "
                           "poses of the joints involved")
        return tuple(out)

    def findings(self, aliases: dict | None = None) -> tuple:
        """Informational lines: well-identified deviations of at least half the plausibility level (not guards).

        ``aliases`` (:attr:`~tolalloc.diagnose.identify.Identifiability.aliases`): a fitted parameter that also stands
        for dropped ones is reported as the combination, with every physical reading (they mean different repairs).
        """
        out = []
        for i, st in enumerate(self.status):
            if st != "finding":
                continue
            head = f"finding: {self._line(i)}"
            tail = f"{abs(self.value[i]) / self.level[i]:.2g} x the plausibility level {self.level[i]:.3g} {self.units[i]}"
            alias = (aliases or {}).get(self.names[i], ())
            if not alias:
                out.append(f"{head} (well identified; {tail})")
                continue
            combo = " + ".join([self.names[i]] + [f"{c:.3g} x {n}" for n, c in alias])
            readings = ", or ".join(reading(n) for n in (self.names[i], *(n for n, _ in alias)))
            out.append(f"{head} is one combination, {combo}, well identified as such ({tail}); the poses cannot tell "
                       f"its readings apart: {readings}")
        return tuple(out)


def reading(name: str) -> str:
    """The physical reading (and repair) of a geometric calibration parameter, from its name."""
    for key, what in (("_offset", "joint {j}'s zero is off (re-master the joint)"),
                      ("_tilt_", "joint {j}'s axis is tilted (bearing seat or housing misaligned)"),
                      ("_shift_", "joint {j}'s axis is displaced (a link length or axis position off)")):
        if key in name:
            return what.format(j=name.split(key)[0])
    return name



def parameter_checks(fit, q: np.ndarray, *, level: np.ndarray | None = None,
                     n_sigma: float = PRIOR_N_SIGMA) -> ParameterCheck:
    """Check the fitted geometric parameters and probe offset of ``fit`` (see the module docstring).

    Parameters
    ----------
    fit : :class:`tolalloc.diagnose.calibrate.Fit`   a geometric fit (its model's ``sigma`` is the MAP prior)
    q : array, shape (P, n) [rad, mm]   the poses ``fit`` was fitted on
    level : array, shape (K,), optional  plausibility level per model parameter [mm, rad]; default
        :func:`~tolalloc.diagnose.geometry.plausibility_levels` (the larger of the prior sigma and the as-built level)
    """
    model = fit.model
    level = plausibility_levels(model) if level is None else np.asarray(level, float)
    cov, _ = parameter_covariance(fit, q, unresolved="inflate")
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    prm = [model.params[k] for k in fit.geo_index]
    f = np.array([p.to_interface for p in prm] + [1.0] * 3)
    value = np.concatenate([fit.delta[fit.geo_index], fit.t_mm]) * f
    sd = np.concatenate([sd[9:9 + len(prm)], sd[6:9]]) * f
    lev = np.concatenate([level[fit.geo_index], np.full(3, as_built_levels(model.robot)[0])]) * f
    v = np.abs(value)
    is_geo = np.arange(len(v)) < len(prm)
    implausible = is_geo & (v > n_sigma * lev)
    weak = np.where(is_geo, (v > lev) & (sd > v / 2), sd > lev)
    finding = is_geo & (v >= 3 * sd) & (v >= FINDING_FRACTION * lev)
    status = tuple("implausible" if a else "weak" if b else "finding" if c else "ok"
                   for a, b, c in zip(implausible, weak, finding))
    return ParameterCheck(tuple(p.name for p in prm) + ("probe_offset_x", "probe_offset_y", "probe_offset_z"),
                          tuple(p.interface_unit for p in prm) + ("mm",) * 3, value, sd, lev, status, n_sigma)


def prior_flags(fit, q: np.ndarray, **kw) -> tuple:
    """Guard lines of :func:`parameter_checks` (implausible / weakly identified parameters and probe offset)."""
    return parameter_checks(fit, q, **kw).guards()


def instrument_noise(noise_mm) -> float | None:
    """The instrument's stated noise [mm, one sd per axis] as a float, None for None; refuses anything but a positive
    finite number."""
    if noise_mm is None:
        return None
    try:
        value = float(noise_mm) if not isinstance(noise_mm, (bool, str)) else np.nan
    except (TypeError, ValueError):
        value = np.nan
    if not np.isfinite(value) or value <= 0:
        raise ArgumentError("instrument_noise_mm", "expected the measuring instrument's noise in mm, one standard "
                            "deviation per axis (e.g. 0.01 for a laser tracker at a few metres), got "
                            f"{describe(noise_mm)}.")
    return value


def noise_guard(final, noise_mm: float | None, factor: float = NOISE_FACTOR) -> str | None:
    """A guard when the final model's out-of-fold error is more than ``factor`` times the measuring instrument's stated
    noise (``noise_mm``, one sd per axis; None: no guard): what is left is neither noise nor a fitted effect."""
    if noise_mm is None:
        return None
    r = rms(final.oof_mm)
    floor = float(np.sqrt(3.0)) * noise_mm
    if r <= factor * floor:
        return None
    return (f"the final model's out-of-fold error, {r:.3g} mm RMS, is {r / floor:.1f} times the instrument's stated "
            f"noise ({noise_mm:g} mm per axis, {floor:.3g} mm in 3-D): about {np.sqrt(r * r - floor * floor):.3g} mm "
            "RMS is neither noise nor a fitted effect -- a load or disturbance no column of the data carries (a "
            "process force, a loose fixture or target, a tracker that moved) or physics outside the candidate families")


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
    cv = {name: rms(ev.oof_mm)
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
