"""The acceptance test predicted: each ISO 9283 statistic as a distribution over the built robots, and the verdict.

For a design (an error model with its sigmas and their systematic / random split, optionally after a calibration)
:func:`predict_acceptance` gives, per statistic and test pose, from the linear model of
:mod:`tolalloc.acceptance.model`:

* the robot's statistic (what the robot does) and the *measured* statistic (what the test reports: the tracker's
  noise and the registration included) at the requirement's share of the built robots, and its median;
* the share of the robots that meet the limit;
* the expanded uncertainty ``U`` of the measurement (:func:`tolalloc.acceptance.measures.expanded_uncertainty`) and
  the ISO 14253-1 verdict on the predicted measured value (:mod:`tolalloc.acceptance.decision`): "conformance
  demonstrated" only when it plus ``U`` is within the limit.

Path accuracy ``AT_P`` is the largest over the path points: each point is held at ``1 - (1 - share) / m``, so the
row ``AT_P`` (the largest of the points' values) bounds its share-quantile from above (Bonferroni).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.acceptance.decision import Decision, decide
from tolalloc.acceptance.measures import expanded_uncertainty, measure_cdf, measure_quantile
from tolalloc.acceptance.model import (StatisticModel, design_variances, effects_at, requirement_poses,
                                      statistic_models)
from tolalloc.acceptance.requirements import IsoRequirement, check_requirements

__all__ = ["StatisticPrediction", "AcceptancePrediction", "predict_acceptance", "NO_SYSTEMATIC_SHARE", "MET_TOL"]

#: a share short of its target by no more than this counts as met (the exact allocation's accuracy, FEAS_TOL)
MET_TOL = 1e-5
#: an accuracy statistic whose systematic share of variance is below this has "no systematic part left"
NO_SYSTEMATIC_SHARE = 1e-3


@dataclass(frozen=True, eq=False)
class StatisticPrediction:
    """One statistic predicted at its rows (P1-P5, a pose pair, or the path points).

    Attributes
    ----------
    model : StatisticModel
    cov_robot, cov_instrument : arrays, shape (P, 3, 3)
        Covariance of the statistic vector over the built robots, and the tracker's share of the measured one.
    systematic_share : array, shape (P,)
        Share of ``tr cov_robot`` from the systematic parts (accuracy statistics; 0 for repeatabilities).
    robot, measured, median_measured : arrays, shape (P,) [mm or rad]
        The robot's statistic and the measured one at the row's target share; the measured median.
    p_robot : array, shape (P,)
        Share of the built robots whose statistic meets the limit at that row.
    U : array, shape (P,)
        Expanded uncertainty of the measurement.
    decisions : tuple of Decision
        ISO 14253-1 verdict on ``measured`` per row.
    mean : array, shape (P, 3), optional [mm or rad]
        Mean of the statistic vector that every built robot shares (the bought parts' effects), None without.
    """

    model: StatisticModel
    cov_robot: np.ndarray
    cov_instrument: np.ndarray
    systematic_share: np.ndarray
    robot: np.ndarray
    measured: np.ndarray
    median_measured: np.ndarray
    p_robot: np.ndarray
    U: np.ndarray
    decisions: tuple
    mean: np.ndarray | None = None

    @property
    def met(self) -> bool:
        """Whether every row's robot statistic meets the limit at its target share (within :data:`MET_TOL`)."""
        return bool(np.all(self.p_robot >= self.model.target - MET_TOL))

    @property
    def demonstrated(self) -> bool:
        """Whether the test demonstrates conformance at every row (ISO 14253-1)."""
        return all(d.demonstrated for d in self.decisions)

    def p_meets_path(self) -> float:
        """Share of the robots whose largest row (``AT_P`` over the path points) meets the limit, from below:
        ``1 - sum(1 - p_i)`` (Bonferroni), 0 at worst. The smallest row's share would bound it from above."""
        return float(max(0.0, 1.0 - np.sum(1.0 - self.p_robot)))


@dataclass(frozen=True, eq=False)
class AcceptancePrediction:
    """The predicted acceptance test of a design.

    Attributes
    ----------
    test : AcceptanceTest
    statistics : tuple of StatisticPrediction
    notes : tuple of str
        Facts a reader must know (an accuracy with no systematic part left ...).
    """

    test: object
    statistics: tuple
    notes: tuple = ()

    @property
    def demonstrated(self) -> bool:
        return all(s.demonstrated for s in self.statistics)

    @property
    def met(self) -> bool:
        return all(s.met for s in self.statistics)

    def to_frame(self) -> pd.DataFrame:
        """The datasheet: one row per statistic and test pose (path accuracy: its largest point as ``AT_P``).

        Columns: ``statistic``, ``where``, ``unit`` and, in that unit (``_mm`` / ``_deg`` pairs), ``limit``,
        ``robot`` (the robot's statistic at the share), ``measured`` (what the test reports at the share),
        ``median_measured``, ``U``, ``margin`` (``limit - measured - U``); ``share`` (the requirement's),
        ``target`` (the share the row is held to: the requirement's, or for a pair of a multi-directional
        statistic ``1 - (1 - share) / 3``, so that a pose's largest pair meets the share), ``p_meets`` (share of
        robots meeting the limit; for ``AT_P`` a lower bound, :meth:`StatisticPrediction.p_meets_path`),
        ``decision``.
        """
        rows = []
        for s in self.statistics:
            m = s.model
            f = 180 / np.pi if m.unit == "deg" else 1.0
            idx = range(m.n_rows) if m.name != "AT_P" else [int(np.argmax(s.measured + s.U))]
            for i in idx:
                d = s.decisions[i]
                rows.append({"statistic": m.name, "where": m.labels[i] if m.name != "AT_P" else
                             f"largest of {m.n_rows} points ({m.labels[i]})", "unit": m.unit,
                             "limit": m.limit * f, "robot": (s.robot.max() if m.name == "AT_P" else s.robot[i]) * f,
                             "measured": s.measured[i] * f, "median_measured": s.median_measured[i] * f,
                             "U": s.U[i] * f, "margin": d.margin * f, "share": m.requirement.share,
                             "target": m.requirement.share if m.name == "AT_P" else float(m.target[i]),
                             "p_meets": s.p_meets_path() if m.name == "AT_P" else float(s.p_robot[i]),
                             "decision": d.outcome})
        df = pd.DataFrame(rows)
        out = df[["statistic", "where", "unit"]].copy()
        mm = (df["unit"] == "mm").to_numpy()
        for col in ("limit", "robot", "measured", "median_measured", "U", "margin"):
            out[f"{col}_mm"] = np.where(mm, df[col], np.nan)
            out[f"{col}_deg"] = np.where(mm, np.nan, df[col])
        for col in ("share", "target", "p_meets", "decision"):
            out[col] = df[col]
        return out

    def text(self) -> str:
        """A short report: the test, then one line per statistic (its worst row)."""
        t = self.test.summary()
        lines = [f"ISO 9283 acceptance test (predicted): cube {t['cube_edge_mm']:.4g} mm at "
                 f"{np.round(t['cube_centre_mm'], 1).tolist()} mm, plane {t['plane']}, {t['cycles']} cycles, "
                 f"registration {t['registration']}; {self.test.tracker.text()}"]
        for s in self.statistics:
            m = s.model
            f, u = (180 / np.pi, "deg") if m.unit == "deg" else (1.0, "mm")
            i = int(np.argmin([d.margin for d in s.decisions]))
            lines.append(f"  {m.name} ({m.requirement.who()}) at {m.labels[i]}: robot {s.robot[i] * f:.4g} {u}, "
                         f"measured {s.measured[i] * f:.4g} {u}; {s.decisions[i].text(u, f)}")
        return "\n".join(lines + [f"  note: {n}" for n in self.notes])


def predict_acceptance(test, requirements, model, split=None, *, posterior=None, effects=None) -> AcceptancePrediction:
    """Predict the ISO 9283 acceptance test of a design.

    Parameters
    ----------
    test : AcceptanceTest
    requirements : IsoRequirement or sequence
        The ISO 9283 requirements (ball requirements are skipped: they are not statistics of the test).
    model : ErrorModel
        The design's error model (its sigmas are the design's).
    split : ErrorSplit, optional
        Systematic / random split of the parameters (default :func:`tolalloc.calibration.split.split_errors`); the
        sigmas are ``model``'s (a split made on other sigmas keeps its flags and repeatabilities).
    posterior : Posterior, optional
        After a calibration: its remaining systematic covariance and random variances replace the split's.
    effects : ErrorEffects, optional
        Bought-part effects (:class:`tolalloc.acceptance.model.ErrorEffects`).

    Returns
    -------
    AcceptancePrediction
    """
    reqs = [r for r in check_requirements(requirements) if isinstance(r, IsoRequirement)]
    if not reqs:
        raise TolallocError("requirements: expected at least one ISO 9283 requirement (PoseAccuracy, "
                            "PoseRepeatability, ...); the ball requirements are not statistics of the test.")
    split = _split_for(model, split)
    ev = requirement_poses(test, reqs)
    J = model.jacobian(ev.q)
    S, V = design_variances(split, posterior)
    out, notes = [], []
    for sm in statistic_models(reqs, test, ev):
        eff = effects_at(effects, test.robot, ev, sm.requirement.conditions)
        pred = _predict_one(sm, J, S, V, eff, test.tracker)
        out.append(pred)
        if sm.name.startswith("AP") and np.all(pred.systematic_share < NO_SYSTEMATIC_SHARE):
            notes.append(f"{sm.name}: no systematic part left (every systematic error calibrated away or zero); the "
                         f"accuracy is set by the mean of the random parts over {sm.cycles} cycles and the "
                         "registration alone")
    return AcceptancePrediction(test, tuple(out), tuple(dict.fromkeys(notes)))


def _split_for(model, split):
    """``split`` on ``model``'s sigmas (the systematic flags and repeatabilities of ``split``); default the standard
    split of ``model``."""
    from tolalloc.calibration.split import split_errors

    if split is None:
        return split_errors(model)
    if split.model.names != model.names:
        raise TolallocError("split: the split was made for another error model (other parameters); split this "
                            "model's parameters (tolalloc.calibration.split.split_errors).")
    return split if split.model is model else split.with_model(model)


def _predict_one(sm: StatisticModel, J, S, V, eff, tracker) -> StatisticPrediction:
    C = sm.covariance(J, S, V, effects=eff)
    C_sys = sm.covariance(J, S, np.zeros_like(V))
    if eff is not None:
        C_sys = C_sys + sm.joint_covariance(eff.systematic)
    C_inst = sm.instrument_covariance(tracker)
    mu = sm.effect_mean(eff)
    tr = np.einsum("pii->p", C)
    share = np.where(tr > 0, np.einsum("pii->p", C_sys) / np.where(tr > 0, tr, 1.0), 0.0)
    tgt, n = sm.target, sm.cycles
    robot = measure_quantile(sm.measure, C, tgt, n, mu)
    measured = measure_quantile(sm.measure, C + C_inst, tgt, n, mu)
    median = measure_quantile(sm.measure, C + C_inst, 0.5, n, mu)
    p = measure_cdf(sm.measure, C, sm.limit, n, mu)
    U = expanded_uncertainty(sm.measure, C_inst, n, tracker.k)
    decisions = tuple(decide(y, sm.limit, u) for y, u in zip(measured, U))
    return StatisticPrediction(sm, C, C_inst, share, robot, measured, median, p, U, decisions, mu)
