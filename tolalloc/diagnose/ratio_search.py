"""Gear ratios the robot file does not give, searched on the training residual: the strain-wave orders ``N`` and
``2N`` of :mod:`tolalloc.physics.transmission`.

For every revolute joint without a known ratio and every candidate ``N`` of a band -- first the reducers'
:data:`~tolalloc.physics.transmission.PLAUSIBLE_RATIOS`, then, where none is found there, a stage's before the output
(:data:`~tolalloc.physics.transmission.STAGE_RATIOS`: a pinion on a ring gear, a spur or belt stage) -- the four
columns ``sin/cos(N q_j)``, ``sin/cos(2N q_j)`` (mapped to the target point, turned into the tracker frame and
projected off the registration, offset and geometric columns, as :mod:`.choice` does) are fitted to the geometric
fit's training residual; the drop of the residual sum of squares, scaled by the noise variance, is ``chi^2_4`` for a
ratio the data do not carry. The noise variance is the robust (MAD) estimate of the residual's, raised where the bulk
of the candidates says it is larger (their median drop above the ``chi^2_4`` median: a residual with structure the
noise estimate misses, which would inflate every candidate's drop; each band calibrates its own). A joint's ratio is
**found** when its best candidate exceeds the ``1 - alpha / m`` quantile of ``chi^2_4`` (Bonferroni over the ``m``
candidates of every band and searched joint), the poses resolve it -- no other candidate (other than ``N/2`` and
``2N``, which share a column with it) comes within ``2 log(20)`` (a likelihood ratio of 20) of its fit -- **and** it
replicates: fitted on each half of the training poses alone, its drop exceeds the single-test ``1 - alpha`` quantile
in both (the search picks the best of many frequencies on the whole file; a frequency the noise favoured there does
not come back in both halves, and the selection's cross-validation, which sees the chosen frequency, could not tell).
Otherwise the joint gets no gear term, with the reason -- no claim at a frequency the poses cannot tell.
Files with fewer than :data:`MIN_DOF` residual degrees of freedom are not searched.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from tolalloc.physics.loads import point_jacobian, target_points
from tolalloc.physics.transmission import PLAUSIBLE_RATIOS, STAGE_RATIOS, ratio_columns
from tolalloc.diagnose.choice import projected_residual

__all__ = ["search_ratios", "RatioNote", "RESOLVE_LR"]

#: Likelihood ratio by which the best ratio must beat every unrelated candidate to count as resolved.
RESOLVE_LR = 20.0
#: Residual degrees of freedom (coordinates beyond the fixed columns) a search needs: the robust noise estimate
#: behind its chi^2 scale must rest on more than a handful of numbers.
MIN_DOF = 60


@dataclass(frozen=True)
class RatioNote:
    """What the search found for one joint (or why it could not search).

    ``telling`` is False where no band's frequency stood out (nothing a reader needs); True for a find, a frequency
    the poses cannot resolve or that does not replicate, and a file too small to search."""

    text: str
    telling: bool


def _drops(X: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Residual sum-of-squares drop of each candidate's columns ``X`` (K, n, 4) fitted to ``r`` (n,), shape (K,)."""
    Xt = X.transpose(0, 2, 1)
    G, h = Xt @ X, Xt @ r
    G = G + 1e-12 * np.trace(G, axis1=1, axis2=2)[:, None, None] * np.eye(X.shape[2])
    return np.einsum("ki,ki->k", h, np.linalg.solve(G, h[..., None])[..., 0])


def _columns(fit, Jpj: np.ndarray, qj: np.ndarray, cand: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """The candidates' ``N``, ``2N`` columns at the target in the tracker frame, projected off ``Q``, (K, 3P, 4)."""
    cols = np.stack([ratio_columns(qj, N) for N in cand])  # (K, P, 4)
    X = ((Jpj @ fit.R.T)[None, :, :, None] * cols[:, :, None, :]).reshape(len(cand), -1, 4)
    return X - Q @ (Q.T @ X)


def search_ratios(robot, q: np.ndarray, fit, J_fixed: np.ndarray, residual_mm: np.ndarray, known=None,
                  alpha: float = 0.01, bands=(PLAUSIBLE_RATIOS, STAGE_RATIOS)) -> tuple:
    """Gear ratios (n,) -- ``known`` where given, the found ratio, else NaN -- and one :class:`RatioNote` per searched
    joint.

    Parameters
    ----------
    q : array, shape (P, n) [rad, mm]       training poses
    fit : Fit                                the geometric fit (its rotation ``R`` and target offset ``t_mm``)
    J_fixed : array, shape (3P, k)           its fixed columns (registration, offset, geometry)
    residual_mm : array, shape (P, 3)        its training residual
    known : array, shape (n,), optional      ratios from the robot file (NaN where unknown)
    bands : sequence of sequences of int     candidate ratios, searched band after band until one is found (the
                                             reducers', then a stage's before the output); the Bonferroni count is
                                             every band's candidates
    """
    n = robot.n_joints
    out = np.full(n, np.nan) if known is None else np.array(known, float)
    todo = [j for j in range(n) if robot.joints[j].is_revolute and not np.isfinite(out[j])]
    if not todo:
        return out, []
    Q, r, dof = projected_residual(fit, J_fixed, residual_mm)
    s2 = (1.4826 * np.median(np.abs(r - np.median(r)))) ** 2
    if dof < MIN_DOF or not s2 > 0:
        return out, [RatioNote(f"gear ratio search: too few training poses ({len(q)}) to search a frequency", True)]
    bands = [np.asarray(b, float) for b in bands]
    limit = chi2.isf(alpha / (sum(len(b) for b in bands) * len(todo)), 4)
    Jp = point_jacobian(robot, q, target_points(robot, q, fit.t_mm))  # (P, 3, n)
    order = np.random.default_rng(0).permutation(len(q))  # two halves of the poses (rows of 3 coordinates each)
    halves_of = [np.concatenate([3 * i + np.arange(3) for i in np.sort(h)]) for h in np.array_split(order, 2)]
    notes = []
    for j in todo:
        name = robot.joints[j].name
        why, telling = [], False
        for cand in bands:
            N, note, stood_out = _search_joint(fit, Jp[:, :, j], q[:, j], cand, Q, r, s2, limit, halves_of, alpha)
            telling |= stood_out
            if np.isfinite(N):
                out[j] = N
                why = [note]
                break
            why.append(note)
        notes.append(RatioNote(f"gear ratio of {name}: " + "; ".join(why)
                               + ("" if np.isfinite(out[j]) else "; no gear term"), telling))
    return out, notes


def _search_joint(fit, Jpj, qj, cand, Q, r, s2, limit, halves_of, alpha) -> tuple:
    """``(N found or NaN, why, whether a frequency stood out)`` of one joint's search over the candidate ratios
    ``cand`` (K,)."""
    step = max(1, int(2e6 // (12 * len(qj))))  # candidates per block: at most ~16 MB of columns
    stat = np.concatenate([_drops(_columns(fit, Jpj, qj, cand[a:a + step], Q), r)
                           for a in range(0, len(cand), step)]) / s2
    s2j = s2 * max(1.0, float(np.median(stat)) / chi2.median(4))  # the bulk of candidates calibrates the null
    stat = stat * s2 / s2j
    b = int(np.argmax(stat))
    N = cand[b]
    related = np.isin(cand, (N, 2 * N, N / 2))
    other = np.max(np.where(related, -np.inf, stat))
    X = _columns(fit, Jpj, qj, np.array([N]), Q)[0]
    halves = min(_drops(X[None, rows], r[rows])[0] / s2j for rows in halves_of)
    replicate = chi2.isf(alpha, 4)
    resolved = stat[b] >= limit and stat[b] - other >= 2 * np.log(RESOLVE_LR)
    if resolved and halves < replicate:
        return np.nan, (f"N = {N:g} stands out in the training residual (chi2 = {stat[b]:.3g}, limit {limit:.3g}) but "
                        f"does not replicate in both halves of the training poses (chi2 {halves:.3g} < "
                        f"{replicate:.3g} in one)"), True
    if resolved:
        return N, (f"N = {N:g} found in the training residual (chi2 = {stat[b]:.3g}, limit {limit:.3g}; the next "
                   f"unrelated frequency {other:.3g})"), True
    if other >= limit:
        N2 = cand[int(np.argmax(np.where(related, -np.inf, stat)))]
        return np.nan, (f"the poses cannot resolve the frequency (N = {N:g} and N = {N2:g} fit about equally well, "
                        f"chi2 {stat[b]:.3g} vs {other:.3g}, both above the limit {limit:.3g})"), True
    return np.nan, (f"no frequency N = {cand[0]:g}-{cand[-1]:g} stands out in the training residual (best N = {N:g}, "
                    f"chi2 = {stat[b]:.3g}, limit {limit:.3g}, next unrelated {other:.3g})"), False
