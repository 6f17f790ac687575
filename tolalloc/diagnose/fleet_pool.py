"""A fleet of diagnosed robots pooled: per identifiable parameter the achieved mean and spread, with intervals.

**Per robot** (:func:`robot_estimate`): the diagnosis's final fit is a MAP estimate (Gaussian priors on the
geometric parameters, ridge priors on some effect columns) -- it shrinks every parameter toward 0 by its own amount,
which would bias a fleet's mean toward 0 and its spread down. From the fit's information (the training data's
``J^T J / noise^2`` and the prior precisions, :meth:`~tolalloc.diagnose.model_use.IdentifiedModel.information`)
the registration and probe offset (set-up, not robot) are profiled out (Schur complement ``S``), and the linearised
likelihood estimate ``theta_ML = theta_MAP + S^-1 P theta_MAP`` (``P`` the parameters' prior precision: ``(S + P)
theta_MAP = S theta_ML`` for a prior centred at 0) is taken with its covariance ``S^-1``. Only the parameters the
diagnosis fitted are estimated -- the identifiable ones, each standing for the combination of the unidentifiable
parameters its column absorbs (:mod:`.identify`); the unidentifiable parameters are reported with the reason.

**Across robots** (:func:`random_effects`, per parameter): ``theta_r ~ N(mu, tau^2)`` and ``theta_ML,r ~
N(theta_r, v_r)``: the normal-normal hierarchical model of a random-effects meta-analysis. ``tau^2`` by restricted
maximum likelihood; the interval of ``mu`` by Hartung-Knapp-Sidik-Jonkman (``t_{N-1}`` with the weighted residual
variance, not below the model's own: Roever, Knapp & Friede 2015); the interval of ``tau`` by the Q-profile method
(Viechtbauer 2007: the generalised ``Q(tau^2) = sum (y - mu(tau^2))^2 / (v + tau^2)`` is chi-square with ``N - 1``
degrees of freedom at the true ``tau^2``; robots more alike than their sampling variances allow, ``Q(0)`` below the
lower quantile, give the interval ``{0}``). The between-robot covariance of all parameters together (for maps to other
parameterisations) is the moment estimate ``cov(theta_ML) - mean(v_r)``, projected onto the positive semi-definite
matrices.

**One parameter set.** The fleet's identifiable geometric parameters are the set most robots fitted (of sets
fitted equally often, the first robot's). A robot whose
poses chose other representatives of the same combinations (column pivoting near a tie) is re-expressed in the
fleet's set (:func:`in_parameters`: the values that move its target points as its own do, the registration and probe
offset absorbing what they can, the covariance carried along); one whose poses identify other combinations is left
out. Effect columns are pooled where every robot fitted them; the others are listed (``FleetPool.unpooled``).

**Outliers.** The pooling assumes none. A robot far outside the others on a parameter (leave one out,
:func:`fleet_outliers`) is flagged, not removed: a robot built or measured apart, or a diagnosis to check.

Bad input (:func:`pool_fleet`): fewer than two robots, duplicate names, robots of different models (refused);
robots whose verdict was ``inconclusive`` or whose poses identify other combinations (left out, each with its
reason; refused when fewer than two remain).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd
from scipy.optimize import brentq, minimize_scalar
from scipy.stats import chi2, t as student_t

from tolalloc.exceptions import TolallocError
from tolalloc.diagnose.model_use import IdentifiedModel
from tolalloc.diagnose.uncertainty import point_jacobian, scaled_pinv

__all__ = ["RobotEstimate", "robot_estimate", "random_effects", "FleetPool", "pool_fleet", "in_parameters", "LEVEL",
           "fleet_outliers", "OUTLIER_ALPHA"]

#: Default two-sided confidence level of the intervals.
LEVEL = 0.95
#: Columns of the registration and probe offset in the information matrix (profiled out).
NUISANCE = 9
#: Family-wise level of the outlier flag (:func:`fleet_outliers`), over every robot and parameter.
OUTLIER_ALPHA = 0.05
#: Largest relative residual of a robot's geometric columns re-expressed in the fleet's parameters.
TRANSFER_TOL = 1e-3


@dataclass(frozen=True, eq=False)
class RobotEstimate:
    """One robot's de-shrunk parameter estimates (module docstring).

    Attributes
    ----------
    name : str
    model : IdentifiedModel
    names : tuple of str          geometric parameters (fitted), then effect columns (``effect:column [unit]``)
    units : tuple of str          ``mm`` / ``rad`` / the effect column's unit
    values : array, shape (p,)    likelihood estimates [mm, rad, effect units]
    cov : array, shape (p, p)     their covariance
    map_values : array, shape (p,)  the fit's own (MAP) values
    n_geometric : int             the first ``n_geometric`` entries are geometric
    """

    name: str
    model: IdentifiedModel
    names: tuple
    units: tuple
    values: np.ndarray
    cov: np.ndarray
    map_values: np.ndarray
    n_geometric: int


def _unit_of(column: str) -> str:
    return column[column.rindex("[") + 1:column.rindex("]")] if "[" in column and column.endswith("]") else ""


def robot_estimate(model: IdentifiedModel, name: str) -> RobotEstimate:
    """The de-shrunk estimates of ``model``'s fitted geometric and effect parameters (module docstring)."""
    fit = model.fit
    data, prior, _ = model.information()
    n = NUISANCE
    Hnn = data[:n, :n] + np.diag(prior[:n])
    Hnt = data[:n, n:]
    S = data[n:, n:] - Hnt.T @ np.linalg.solve(Hnn, Hnt)
    S = 0.5 * (S + S.T)
    cov = scaled_pinv(S)
    theta_map = np.concatenate([fit.delta[fit.geo_index], fit.beta])
    values = theta_map + cov @ (prior[n:] * theta_map)
    geo = [fit.model.params[k] for k in fit.geo_index]
    names = tuple([p.name for p in geo] + list(fit.effect_names))
    units = tuple([p.unit for p in geo] + [_unit_of(c) for c in fit.effect_names])
    return RobotEstimate(name, model, names, units, values, 0.5 * (cov + cov.T), theta_map, len(geo))


def _reml_tau2(y: np.ndarray, v: np.ndarray) -> float:
    """Restricted maximum-likelihood ``tau^2`` of the normal-normal model."""

    def nll(t2):
        w = 1.0 / (v + t2)
        mu = np.sum(w * y) / np.sum(w)
        return 0.5 * (np.sum(np.log(v + t2)) + np.log(np.sum(w)) + np.sum(w * (y - mu) ** 2))

    hi = 10.0 * (np.var(y) + np.max(v)) + 1e-300
    res = minimize_scalar(nll, bounds=(0.0, hi), method="bounded", options={"xatol": 1e-10 * hi})
    return 0.0 if nll(0.0) <= res.fun else float(res.x)


def _q_stat(y: np.ndarray, v: np.ndarray, t2: float) -> float:
    w = 1.0 / (v + t2)
    mu = np.sum(w * y) / np.sum(w)
    return float(np.sum(w * (y - mu) ** 2))


def _pooled(y: np.ndarray, v: np.ndarray) -> tuple:
    """``(mu, tau^2, w, v)``: the REML spread, the inverse-variance weights ``1 / (v + tau^2)`` and the weighted mean
    of estimates ``y`` with sampling variances ``v`` (floored at a tiny fraction of their scale)."""
    v = np.maximum(v, 1e-30 * max(np.max(v), np.var(y), 1e-300))
    t2 = _reml_tau2(y, v)
    w = 1.0 / (v + t2)
    return float(np.sum(w * y) / np.sum(w)), t2, w, v


def random_effects(y, v, level: float = LEVEL) -> dict:
    """The normal-normal hierarchical model of one parameter (module docstring).

    Parameters
    ----------
    y : array, shape (N,)   per-robot estimates
    v : array, shape (N,)   their sampling variances
    level : float           two-sided confidence level

    Returns
    -------
    dict
        ``mean``, ``mean_lo``, ``mean_hi``, ``spread`` (``tau``), ``spread_lo``, ``spread_hi``, ``robots`` (N),
        ``q`` (Cochran's Q at ``tau = 0``).
    """
    y, v = np.asarray(y, float), np.maximum(np.asarray(v, float), 0.0)
    N = len(y)
    if N < 2:
        raise TolallocError(f"random_effects: expected estimates of at least two robots, got {N}.")
    mu, t2, w, v = _pooled(y, v)
    q_hk = max(_q_stat(y, v, t2) / (N - 1), 1.0)
    half = float(student_t.ppf(0.5 + level / 2, N - 1) * np.sqrt(q_hk / np.sum(w)))
    a = 1.0 - level
    q_hi, q_lo = chi2.ppf(1 - a / 2, N - 1), chi2.ppf(a / 2, N - 1)

    def bound(target):
        if _q_stat(y, v, 0.0) <= target:
            return 0.0
        hi = max(np.var(y), np.max(v), 1e-300)
        while _q_stat(y, v, hi) > target:
            hi *= 4.0
        return brentq(lambda t: _q_stat(y, v, t) - target, 0.0, hi, xtol=1e-14 * hi)

    return {"robots": N, "mean": mu, "mean_lo": mu - half, "mean_hi": mu + half, "spread": float(np.sqrt(t2)),
            "spread_lo": float(np.sqrt(bound(q_hi))), "spread_hi": float(np.sqrt(bound(q_lo))),
            "q": _q_stat(y, v, 0.0)}


@dataclass(frozen=True, eq=False)
class FleetPool:
    """A pooled fleet (:func:`pool_fleet`).

    Attributes
    ----------
    robots : tuple of RobotEstimate   the robots pooled
    excluded : dict                   robot name -> why it was left out
    names, units : tuple of str       the pooled parameters (the geometric ones first)
    n_geometric : int
    table : DataFrame                 per parameter (:func:`random_effects` and ``unit``, ``kind``)
    mean : array, shape (p,)          ``mu`` per parameter
    between_cov : array, shape (p, p) moment estimate of the between-robot covariance (PSD)
    unidentifiable : dict             geometric parameters not estimated -> why (the first robot's diagnosis)
    level : float
    values : array, shape (N, p)      the pooled robots' estimates
    unpooled : dict                   effect columns not every robot fitted -> the robots that did (not pooled)
    outliers : DataFrame              robots far outside the others on a parameter (:func:`fleet_outliers`); they
                                      stay in the pool, which assumes there are none
    """

    robots: tuple
    excluded: dict
    names: tuple
    units: tuple
    n_geometric: int
    table: pd.DataFrame
    mean: np.ndarray
    between_cov: np.ndarray
    unidentifiable: dict = field(default_factory=dict)
    level: float = LEVEL
    values: np.ndarray | None = None
    unpooled: dict = field(default_factory=dict)
    outliers: pd.DataFrame | None = None


def fleet_outliers(Y: np.ndarray, V: np.ndarray, names, robots, alpha: float = OUTLIER_ALPHA) -> pd.DataFrame:
    """Robots far outside the others, per parameter (leave one out; at least three robots).

    For robot ``r`` and parameter ``k`` the others' random-effects mean ``mu`` and spread ``tau`` (the estimates of
    :func:`random_effects`, without its intervals) predict a new robot as ``mu +- t_(N-2) sqrt(tau^2 + 1/sum w + v_r)``; the robot is
    flagged where ``|z| = |y - mu| / sqrt(...)`` exceeds the two-sided ``t_(N-2)`` quantile at ``alpha / (N p)``
    (Bonferroni over robots and parameters). Returns a frame (``robot``, ``parameter``, ``value``, ``others_mean``,
    ``others_spread``, ``z``), empty when none is flagged or fewer than three robots are pooled. The level holds
    over the whole fleet (a clean fleet of 6 or 10 robots and 20 parameters is flagged in 1-5 % of draws); the price
    is power: with 6 robots a robot 10 spreads out is flagged in about a third of draws, with 10 in nearly all."""
    N, p = Y.shape
    cols = ["robot", "parameter", "value", "others_mean", "others_spread", "z"]
    if N < 3:
        return pd.DataFrame(columns=cols)
    limit = float(student_t.ppf(1 - alpha / (2 * N * p), N - 2))
    rows = []
    for k in range(p):
        for r in range(N):
            rest = np.arange(N) != r
            mu, t2, w, _ = _pooled(Y[rest, k], np.maximum(V[rest, k], 0.0))
            z = (Y[r, k] - mu) / np.sqrt(t2 + 1.0 / np.sum(w) + V[r, k] + 1e-300)
            if abs(z) > limit:
                rows.append(dict(zip(cols, (robots[r], names[k], float(Y[r, k]), mu, float(np.sqrt(t2)), float(z)))))
    return pd.DataFrame(rows, columns=cols)


def _same_robot(a, b) -> bool:
    return (a.name == b.name and a.screws.shape == b.screws.shape and np.allclose(a.screws, b.screws, atol=1e-9)
            and np.allclose(a.home, b.home, atol=1e-9))


def _common_geometry(estimates: list) -> tuple[list, dict]:
    """The robots to pool, each in the fleet's identifiable geometric parameters (the most frequent set; a robot whose
    poses chose other representatives of the same combinations is re-expressed, :func:`in_parameters`), and the
    robots left out with the reason: an ``inconclusive`` verdict, or other identifiable combinations."""
    out = {}
    for e in estimates:
        if e.model.verdict == "inconclusive":
            out[e.name] = ("its diagnosis's verdict is inconclusive (the data do not decide its model; see its "
                           "report's reasons)")
    left = [e for e in estimates if e.name not in out]
    sets = [e.names[:e.n_geometric] for e in left]
    if not sets:
        return [], out
    common = max(sets, key=sets.count)  # the most frequent set; a tie goes to the first robot's, never to hash order
    kept = []
    for e, own in zip(left, sets):
        if own == common:
            kept.append(e)
            continue
        try:
            kept.append(in_parameters(e, common))
        except TolallocError as exc:
            out[e.name] = str(exc).split(": ", 1)[1] + " (diagnose every robot on the same pose plan)"
    return kept, out


def in_parameters(est: RobotEstimate, geometric: tuple) -> RobotEstimate:
    """``est`` expressed in another set of identifiable geometric parameters ``geometric`` (names): the values that
    move the target points at its own poses as its own parameters do, the registration and probe offset absorbing
    what they can (least squares), with the covariance carried along; refused (TolallocError) when its parameters
    move the points in a way the other set cannot (another identifiable subspace)."""
    m = est.model
    model_names = list(m.fit.model.names)
    own = [model_names.index(nm) for nm in est.names[:est.n_geometric]]
    unknown = [nm for nm in geometric if nm not in model_names]
    if unknown:
        raise TolallocError(f"{est.name}: {', '.join(unknown[:3])} not among the geometric parameters of its model")
    other = [model_names.index(nm) for nm in geometric]
    union = sorted(set(own) | set(other))
    J = point_jacobian(replace(m.fit, geo_index=np.array(union, int)), m.train.q).reshape(3 * len(m.train.q), -1)
    col = {k: NUISANCE + i for i, k in enumerate(union)}
    A = J[:, list(range(NUISANCE)) + [col[k] for k in other]]
    B = J[:, [col[k] for k in own]]
    scale = np.linalg.norm(A, axis=0)
    T, *_ = np.linalg.lstsq(A / scale, B, rcond=None)
    T = T / scale[:, None]
    left = np.linalg.norm(A @ T - B, axis=0) / np.maximum(np.linalg.norm(B, axis=0), 1e-300)
    if left.max() > TRANSFER_TOL:
        k = int(np.argmax(left))
        raise TolallocError(f"{est.name}: its parameter {est.names[k]} moves the target in a way the fleet's "
                            f"identifiable parameters cannot ({left[k]:.1e} of it left over); its poses identify other "
                            "combinations")
    g = est.n_geometric
    Tg = T[NUISANCE:]
    n_eff = len(est.values) - g
    full = np.zeros((len(geometric) + n_eff, len(est.values)))
    full[:len(geometric), :g] = Tg
    full[len(geometric):, g:] = np.eye(n_eff)
    cov = full @ est.cov @ full.T
    return replace(est, names=tuple(geometric) + est.names[g:],
                    units=tuple(m.fit.model.params[k].unit for k in other) + est.units[g:],
                    values=full @ est.values, cov=0.5 * (cov + cov.T), map_values=full @ est.map_values,
                    n_geometric=len(geometric))


def _common_columns(kept: list) -> tuple[list, dict]:
    """Indices (into the first robot's estimates) of the parameters every kept robot fitted -- its geometric ones and
    the effect columns they share -- and the effect columns left unpooled (column -> robots that fitted it)."""
    first = kept[0]
    shared = set.intersection(*[set(e.names) for e in kept])
    idx = [i for i, nm in enumerate(first.names) if i < first.n_geometric or nm in shared]
    unpooled = {}
    for e in kept:
        for nm in e.names[e.n_geometric:]:
            if nm not in shared:
                unpooled.setdefault(nm, []).append(e.name)
    return idx, unpooled


def pool_fleet(estimates, level: float = LEVEL) -> FleetPool:
    """Pool per-robot estimates (:func:`robot_estimate`) into the fleet's means and spreads (module docstring)."""
    estimates = list(estimates)
    if len(estimates) < 2:
        raise TolallocError(f"a fleet needs at least two robots to estimate a spread; got {len(estimates)}.")
    names = [e.name for e in estimates]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise TolallocError(f"fleet: robot names must be unique; {', '.join(dup)} appear more than once.")
    ref = estimates[0].model.robot
    other = [e.name for e in estimates if not _same_robot(e.model.robot, ref)]
    if other:
        raise TolallocError(f"fleet: every robot must be the same model; {', '.join(other)} "
                            f"{'is' if len(other) == 1 else 'are'} not robot {ref.name!r} (the first one's). Pool each "
                            "model separately.")
    kept, excluded = _common_geometry(estimates)
    if len(kept) < 2:
        why = "; ".join(f"{k}: {v}" for k, v in excluded.items())
        raise TolallocError(f"fleet: {len(kept)} robot(s) left to pool after leaving out {len(excluded)} ({why}); "
                            "a spread needs at least two.")
    idx, unpooled = _common_columns(kept)
    first = kept[0]
    pos = [[list(e.names).index(first.names[i]) for i in idx] for e in kept]
    Y = np.array([e.values[p] for e, p in zip(kept, pos)])
    covs = np.array([e.cov[np.ix_(p, p)] for e, p in zip(kept, pos)])
    V = np.array([np.diag(c) for c in covs])
    names = tuple(first.names[i] for i in idx)
    units = tuple(first.units[i] for i in idx)
    rows = []
    for k, (nm, unit) in enumerate(zip(names, units)):
        rows.append({"parameter": nm, "unit": unit, "kind": "geometric" if k < first.n_geometric else "effect",
                     **random_effects(Y[:, k], V[:, k], level), "sampling_sd": float(np.sqrt(np.mean(V[:, k])))})
    table = pd.DataFrame(rows)
    C = np.cov(Y, rowvar=False).reshape(Y.shape[1], Y.shape[1]) - covs.mean(axis=0)
    w, U = np.linalg.eigh(0.5 * (C + C.T))
    between = (U * np.maximum(w, 0.0)) @ U.T
    outliers = fleet_outliers(Y, V, names, [e.name for e in kept])
    return FleetPool(tuple(kept), excluded, names, units, first.n_geometric, table, table["mean"].to_numpy(), between,
                     dict(first.model.unidentifiable or {}), level, Y, unpooled, outliers)
