"""ISO 9283 requirements as chance constraints of the allocation: per statistic, the covariance of its vector per
unit variance of each parameter's tolerance.

The allocation (:func:`tolalloc.allocate.build_problem` with ``acceptance=``) decides the tolerance ``t_k`` of
each parameter, ``sigma_k = t_k / z``. A parameter with a systematic part (:mod:`tolalloc.calibration.split`) puts
that variance into the robot's systematic error -- which carries the accuracies (``AP``, ``AD``, ``AT``) -- and
keeps its repeatability (a fixed random part); a random-only parameter (clearance) puts it into the random error,
which carries the repeatabilities and enters the accuracies only through the mean of the cycles. So each statistic
``i`` of :mod:`tolalloc.acceptance.model` has, per parameter, one 3 x 3 covariance per unit tolerance variance, and
its constraint is of the allocation's form ``C_i(u) = C0_i + sum_k u_k A_ik``: the same certified (trace and
eigenvalue rules) and exact (IPOPT on the statistic's law) solvers, standard grades and region search serve it,
with the statistic's own law (:mod:`tolalloc.acceptance.measures`) in place of the ball's.

With ``guard_band`` the requirement is allocated for conformance *demonstrated* by the test (ISO 14253-1): the
tracker's share enters ``C0`` (the statistic as measured) and the limit shrinks by the expanded uncertainty ``U`` of
the measurement.

Bought-part effects with a mean (the wind-up under the test load, :mod:`tolalloc.acceptance.parts`) give an
accuracy's vector a mean ``mu`` every robot shares. The allocation holds the row to ``r - |mu|`` instead of ``r``
(``P(|x| < r) >= P(|x - mu| < r - |mu|)``, a lower bound), by scaling the row's covariances by
``(r / (r - |mu|))^2``, as the parts allocation does; ``bias`` keeps ``|mu|`` for the reports.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.acceptance.measures import expanded_uncertainty
from tolalloc.acceptance.model import effects_at, requirement_poses, statistic_models
from tolalloc.acceptance.requirements import IsoRequirement, check_requirements
from tolalloc.acceptance.statistics import PAIRS

__all__ = ["AcceptanceSpec", "StatisticTerms", "statistic_terms"]


@dataclass(frozen=True, eq=False)
class AcceptanceSpec:
    """ISO 9283 requirements and the test they are judged by, for the allocation.

    Attributes
    ----------
    requirements : tuple of IsoRequirement
    test : AcceptanceTest
    split : dict or ErrorSplit, optional
        Systematic / random split of the parameters: the costs file's ``[calibration]`` table (a dict), a split
        (matched by parameter name), or None for the defaults of :mod:`tolalloc.calibration.split`.
    effects : ErrorEffects, optional
        Bought-part effects (:class:`tolalloc.acceptance.model.ErrorEffects`).
    """

    requirements: tuple
    test: object
    split: object = None
    effects: object = None

    def __post_init__(self):
        reqs = check_requirements(self.requirements, "acceptance.requirements")
        bad = [r for r in reqs if not isinstance(r, IsoRequirement)]
        if bad:
            raise TolallocError(f"acceptance.requirements: expected ISO 9283 requirements (the balls go to radius_mm / "
                                f"angle_radius_deg), got {bad[0].text()}.")
        object.__setattr__(self, "requirements", reqs)


@dataclass(frozen=True, eq=False)
class StatisticTerms:
    """One statistic's constraint data for the allocation.

    Attributes
    ----------
    name, measure, cycles, labels
        As :class:`tolalloc.acceptance.model.StatisticModel`.
    radius : float
        The limit the statistic is held to [mm or rad] (the requirement's, less ``U`` with a guard band).
    requirement : IsoRequirement
    target : array, shape (P,)
    q : array, shape (P, n) [rad, mm]
        The poses of the rows (P1-P5, the first pose of a distance, the path points, a multi-directional test's
        poses once per pair of directions).
    per_tolerance : array, shape (P, K, 3, 3)
        Covariance per unit variance of each parameter's tolerance (systematic or random part, by its split).
    repeatability : array, shape (P, 3, 3)
        The fixed random parts of the parameters with a systematic part (their repeatabilities).
    const : array, shape (P, 3, 3)
        Bought-part effects and, with a guard band, the tracker.
    U : array, shape (P,)
        Expanded uncertainty of the measurement at each row.
    bias : array, shape (P,)
        Length of the effects' mean at each row [mm or rad] (zeros without one; module docstring).
    """

    name: str
    measure: str
    cycles: int
    labels: tuple
    radius: float
    requirement: IsoRequirement
    target: np.ndarray
    q: np.ndarray
    per_tolerance: np.ndarray
    repeatability: np.ndarray
    const: np.ndarray
    U: np.ndarray = field(default=None)
    bias: np.ndarray = field(default=None)


def _split_of(spec: AcceptanceSpec, model):
    from tolalloc.calibration.split import ErrorSplit, split_errors

    if spec.split is None or isinstance(spec.split, dict):
        return split_errors(model, spec.split)
    if not isinstance(spec.split, ErrorSplit):
        raise TolallocError(f"acceptance.split: expected the costs file's [calibration] table (a dict) or an "
                            f"ErrorSplit, got {spec.split!r}.")
    idx = [spec.split.model.index(nm) for nm in model.names]
    return ErrorSplit(model, spec.split.systematic[idx], spec.split.random_sigma[idx])


def statistic_terms(spec: AcceptanceSpec, model) -> list[StatisticTerms]:
    """The allocation's terms of every statistic of ``spec`` for the parameters of ``model`` (module docstring).

    Raises
    ------
    TolallocError
        An accuracy requirement with no systematic part in the model (every parameter random-only or zero, no
        systematic bought-part effect), or a guard band the tracker's uncertainty alone fills.
    """
    from tolalloc.linear.covariance import VARIANCE_FACTOR

    split = _split_of(spec, model)
    reqs = spec.requirements
    ev = requirement_poses(spec.test, reqs)
    J = model.jacobian(ev.q)
    fac = np.array([VARIANCE_FACTOR[p.distribution] for p in model.params])
    rep_var = np.where(split.systematic, fac * split.random_sigma**2, 0.0)
    out = []
    for sm in statistic_models(reqs, spec.test, ev):
        G = sm.systematic_map(J)  # (P, 3, K)
        R = sm.random_units(J)  # (P, K, 3, 3)
        S = np.einsum("pak,pbk->pkab", G, G)
        per_tol = np.where(split.systematic[None, :, None, None], S, R) * fac[None, :, None, None]
        eff = effects_at(spec.effects, spec.test.robot, ev, sm.requirement.conditions)
        const = np.zeros((sm.n_rows, 3, 3))
        if eff is not None:
            const = const + sm.joint_covariance(eff.systematic) + sm.pose_covariance(eff.random)
        if sm.systematic and not sm.name.startswith("vAP"):  # vAP compares one robot's poses: what it keeps cancels
            _check_systematic(sm, split, S, eff)
        C_inst = sm.instrument_covariance(spec.test.tracker)
        U = expanded_uncertainty(sm.measure, C_inst, sm.cycles, spec.test.tracker.k)
        radius = sm.limit
        if sm.requirement.guard_band:
            const = const + C_inst
            radius = sm.limit - float(U.max())
            _check_guard_band(sm, radius, U, const, spec.test.tracker)
        rows_q = ev.q[_row_poses(sm, ev)]
        rep = np.einsum("pkab,k->pab", R, rep_var)
        mu = sm.effect_mean(eff)
        bias = np.zeros(sm.n_rows) if mu is None else np.linalg.norm(mu, axis=1)
        if np.any(bias > 0):
            _check_bias(sm, radius, bias)
            s = (radius / (radius - bias)) ** 2
            per_tol, rep, const = per_tol * s[:, None, None, None], rep * s[:, None, None], const * s[:, None, None]
        out.append(StatisticTerms(sm.name, sm.measure, sm.cycles, sm.labels, float(radius), sm.requirement,
                                  sm.target, rows_q, per_tol, rep, const, U, bias))
    return out


def _check_bias(sm, radius: float, bias) -> None:
    """Refuse a row whose effects' mean alone reaches the limit."""
    if np.all(bias < radius):
        return
    f, u = (180 / np.pi, "deg") if sm.unit == "deg" else (1.0, "mm")
    i = int(np.argmax(bias))
    if sm.name.startswith("vAP"):
        what, advice = ("the gears' lost motion, on the flank each approach direction leaves", "Choose reducers with "
                        "less lost motion, or close the position loop on the output (an output-side encoder).")
    else:
        what, advice = ("the wind-up under the test load, the sag, the thermal growth", "Choose stiffer parts, "
                        "compensate the mean, or test at a lower load.")
    raise TolallocError(
        f"{sm.requirement.kind}: at {sm.labels[i]} the bought parts' mean error alone ({bias[i] * f:.4g} {u}: "
        f"{what}) reaches the limit {radius * f:.4g} {u}; no tolerance can meet it. {advice}")


def _check_guard_band(sm, radius, U, const, tracker) -> None:
    """Refuse a guard band the instrument fills: the limit less U is used up, or the measured statistic of a robot
    with no error of its own (the tracker and the bought-part effects alone) exceeds it already."""
    from tolalloc.acceptance.measures import measure_quantile

    f, u = (180 / np.pi, "deg") if sm.unit == "deg" else (1.0, "mm")
    alone = float(measure_quantile(sm.measure, const, sm.target, sm.cycles).max()) if radius > 0 else np.inf
    if radius > 0 and alone < radius:
        return
    what = ("nothing is left for the robot" if radius <= 0 else
            f"the measured {sm.name} of a robot without errors of its own is already {alone * f:.4g} {u} at the share "
            f"{sm.requirement.share:g}, above that")
    raise TolallocError(
        f"{sm.requirement.kind}: with guard_band the limit {sm.limit * f:g} {u} less the expanded uncertainty of the "
        f"measurement, U = {U.max() * f:.4g} {u}, leaves {max(radius, 0.0) * f:.4g} {u}, and {what} "
        f"({tracker.text()}): conformance can never be demonstrated. Use a more accurate instrument (a smaller MPE, "
        "a shorter tracker distance, the tracker's noise rather than its MPE), a larger limit, or guard_band=False.")


def _row_poses(sm, ev) -> np.ndarray:
    """The evaluation-pose index of each row: P1-P5, the path points, or a distance's first pose."""
    if sm.name == "AT_P":
        return ev.path
    if sm.name == "AD_P":
        return ev.test[[sm.requirement.poses[0] - 1]]
    if sm.name.startswith("vAP"):
        return np.repeat(ev.directional[:, 0], len(PAIRS))          # a pose's row per pair of directions
    return ev.test


def _check_systematic(sm, split, S, eff) -> None:
    """Refuse an accuracy requirement that no systematic part carries."""
    has = np.einsum("pkaa->pk", S)[:, split.systematic & (split.model.sigma > 0)].sum() > 0
    if has or (eff is not None and np.any(eff.systematic)):
        return
    raise TolallocError(
        f"{sm.requirement.kind}: no systematic part is left to allocate for {sm.name} (every parameter is random-only "
        f"or has a zero sigma, and no bought-part effect is systematic): the accuracy is then only the mean of the "
        f"random parts over {sm.cycles} cycles. State a repeatability requirement instead (PoseRepeatability, "
        "OrientationRepeatability), or give parameters a systematic part (the costs file's [calibration] table).")
