"""Importance sampling of the paired difference, for rare-event requirements (``p`` up to 0.99999).

At ``p = 0.99999`` the nonlinear and linear indicators disagree on a shell near the sphere ``|dP| = r`` that
plain sampling of the error parameters almost never reaches, so the paired interval of
:mod:`tolalloc.montecarlo.paired` is as wide as its zero-count limit ``+-z^2 / n``. Here the draws come from a
*defensive mixture* (Hesterberg 1995)

    q(z) = alpha N(0, I) + (1 - alpha) N(0, I + (s^2 - 1) Q Q^T)

in the whitened parameters ``z`` (``e = sigma z``): the second component scales by ``s`` only the ``d <= 3``
directions ``Q`` that the linear map ``x = A z`` sees (the row space of ``A``), chosen so that the sphere is
the scaled output's median radius (``s = r / r_median``). The weight depends on ``rho = |Q^T z|`` alone,

    w = phi / q = 1 / (alpha + (1 - alpha) s^-d exp(rho^2 (1 - 1/s^2) / 2)) <= 1 / alpha,

and decreases in ``rho``. The estimate is ``P_lin + mean(w (1{nonlinear in} - 1{linear in}))``.

Interval: the weighted discordant sums ``b_w``, ``c_w`` are treated as scaled counts (the weights of the
discordant samples replaced by their second-moment mean ``w_bar = sum w^2 / sum w``, so the variance is
preserved): Tango's score interval of ``(b_w / w_bar, c_w / w_bar)`` out of ``n / w_bar``, scaled back. With
fewer than :data:`MIN_DISCORDANT` discordant samples ``w_bar`` is not estimable and the largest weight a
discordant sample can have is used instead: discordance needs ``| |x| - r | <= |dP_nl| - |x| |``, so
``|A z| >= r - delta`` and ``rho >= (r - delta) / sigma_1`` (``delta`` twice the largest deviation between the
nonlinear and linear radii seen in the run, ``sigma_1`` the largest singular value of ``A``), where ``w`` is at
most ``w((r - delta) / sigma_1)``. The coverage of this interval is checked over seeds in
``tests/test_montecarlo_importance.py`` and in ``studies/rare_event``.
"""

from __future__ import annotations

import threading

import numpy as np

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.errormodel.chain import FastChain
from tolalloc.linear.probability import p_within_radius, radius_for_prob
from tolalloc.montecarlo.blocks import BLOCK_SIZE, SUB_BLOCK, KernelSpec
from tolalloc.montecarlo.intervals import paired_difference_ci
from tolalloc.montecarlo.estimate import ProbabilityEstimate
from tolalloc.montecarlo.paired import _check_budget, control_fallback_reason
from tolalloc.montecarlo.parallel import check_scheduler, default_jobs, ordered_map

__all__ = ["importance_probability", "DEFENSIVE_ALPHA", "MIN_DISCORDANT", "proposal_scale"]

#: Weight of the nominal component of the defensive mixture.
DEFENSIVE_ALPHA = 0.1
#: Discordant samples below which the weight bound replaces the second-moment mean weight.
MIN_DISCORDANT = 10
#: Sums accumulated per pose: n, b_w, c_w, sum w^2 |D|, count D = +1, count D = -1, max deviation [mm].
_NSUM = 7


def proposal_scale(C: np.ndarray, radius_mm: float) -> float:
    """Scale ``s`` of the proposal: the sphere ``r`` is the median radius of ``N(0, s^2 C)`` (1 <= s <= 30)."""
    r_med = float(radius_for_prob(C, 0.5))
    return float(np.clip(radius_mm / max(r_med, 1e-300), 1.0, 30.0))


def _weight(rho2, s: float, d: int, alpha: float):
    return 1.0 / (alpha + (1.0 - alpha) * s ** (-d) * np.exp(0.5 * rho2 * (1.0 - 1.0 / s**2)))


class _IsSpec(KernelSpec):
    def __init__(self, model, q, n, seed, radius, alpha):
        self.model, self.q, self.n, self.seed, self.radius, self.alpha = model, q, int(n), int(seed), radius, alpha
        self._lock = threading.Lock()

    def _build(self):
        chain, mult, progs = self._chain_and_programs()
        per_pose = []
        for qi in self.q:
            A = self.model.jacobian(qi)[:3] * mult  # (3, K) on standard-normal rows
            U, S, Vt = np.linalg.svd(A, full_matrices=False)
            d = int(np.sum(S > 1e-12 * max(S[0], 1e-300)))
            s = proposal_scale(A @ A.T, self.radius)
            per_pose.append((A, np.ascontiguousarray(Vt[:d]), d, s, float(S[0]),
                             self.model.robot.fk_internal(qi)[:3, 3].copy()))
        return chain, progs, per_pose


def _is_block(spec: _IsSpec, task):
    """Weighted discordance sums of block ``b`` at pose ``i``: array (_NSUM,)."""
    i, b = task
    chain, progs, per_pose = spec.kernel()
    A, Qt, d, s, _, p0 = per_pose[i]
    K = len(spec.model.params)
    m = min(BLOCK_SIZE, spec.n - b * BLOCK_SIZE)
    rng = np.random.default_rng(np.random.SeedSequence(spec.seed, spawn_key=(1_000_003, i, b)))
    Z = rng.standard_normal((K, m))
    scaled = rng.random(m) >= spec.alpha
    y = Qt @ Z  # (d, m)
    Z[:, scaled] += (s - 1.0) * (Qt.T @ y[:, scaled])
    y[:, scaled] *= s
    w = _weight(np.einsum("im,im->m", y, y), s, d, spec.alpha)
    out = np.zeros(_NSUM)
    out[0] = m
    work = FastChain.workspace(SUB_BLOCK)
    X = np.empty((3, 4, SUB_BLOCK))
    r = spec.radius
    for s0 in range(0, m, SUB_BLOCK):
        s1 = min(m, s0 + SUB_BLOCK)
        Xs = X[:, :, : s1 - s0]
        chain.run(progs[i], Z[:, s0:s1], Xs, work)
        nl = np.sqrt(sum((Xs[a, 3] - p0[a]) ** 2 for a in range(3)))
        x = A @ Z[:, s0:s1]
        li = np.sqrt(np.einsum("im,im->m", x, x))
        D = (nl < r).astype(np.int8) - (li < r).astype(np.int8)
        ws = w[s0:s1]
        out[1] += ws[D > 0].sum()
        out[2] += ws[D < 0].sum()
        out[3] += (ws[D != 0] ** 2).sum()
        out[4] += np.count_nonzero(D > 0)
        out[5] += np.count_nonzero(D < 0)
        near = li < 2 * r
        if np.any(near):
            out[6] = max(out[6], float(np.abs(nl[near] - li[near]).max()))
    return out


def _is_blocks(spec, task):
    return _is_block(spec, task)


def importance_probability(model, q, n: int, seed: int = 0, *, radius_mm: float, level: float = 0.95,
                           alpha: float = DEFENSIVE_ALPHA, scheduler=None, n_jobs: int | None = None) -> ProbabilityEstimate:
    """Paired estimate of ``P(|dP| < r)`` at every pose with importance sampling (see the module docstring).

    Parameters
    ----------
    model : ErrorModel
        Every parameter with non-zero sigma must be normal.
    q : array, shape (P, n_joints) [rad, mm]
    n : int
        Samples per pose (each pose has its own draws: the proposal follows the pose's linear map).
    radius_mm : float
    level : float
    alpha : float
        Weight of the nominal component (the weights are at most ``1 / alpha``).

    Returns
    -------
    ProbabilityEstimate
        ``estimator == "importance"``; the plain columns are NaN (the draws are not the nominal ones);
        ``details`` holds the proposal scale ``s``, the weight bound used and the largest deviation.
    """
    from threadpoolctl import threadpool_limits

    reason = control_fallback_reason(model)
    if reason:
        raise ArgumentError("estimator", f"'importance' needs Gaussian parameters; {reason.split(':')[0]}. Use "
                            "estimator='auto' or 'plain' (and more samples) for this model.")
    if not (0 < alpha < 1):
        raise TolallocError(f"alpha: expected the defensive weight strictly between 0 and 1 (e.g. 0.1), got {alpha!r}.")
    q = np.atleast_2d(model.robot.check_q(q, "q"))
    P = len(q)
    _check_budget(model, P, n, "importance", n_jobs)
    spec = _IsSpec(model, q, n, seed, float(radius_mm), float(alpha))
    n_blocks = -(-int(n) // BLOCK_SIZE)
    tasks = ((i, b) for i in range(P) for b in range(n_blocks))
    sums = np.zeros((P, _NSUM))
    with threadpool_limits(limits=1, user_api="blas"):
        for k, o in enumerate(ordered_map(_is_blocks, tasks, spec, scheduler=check_scheduler(scheduler),
                                          n_jobs=n_jobs or default_jobs())):
            i = k // n_blocks
            sums[i, :6] += o[:6]
            sums[i, 6] = max(sums[i, 6], o[6])
    _, _, per_pose = spec.kernel()
    return _estimate(model, q, spec, sums, per_pose, level)


def _estimate(model, q, spec, sums, per_pose, level) -> ProbabilityEstimate:
    r, alpha = spec.radius, spec.alpha
    P = len(q)
    n = sums[:, 0]
    bw, cw, w2, nb, nc, dev = (sums[:, k] for k in range(1, 7))
    count = nb + nc
    w_band = np.array([_weight(max(0.0, r - 2 * dev[i]) ** 2 / pp[4] ** 2, pp[3], pp[2], alpha)
                       for i, pp in enumerate(per_pose)])
    with np.errstate(divide="ignore", invalid="ignore"):
        w_ratio = np.where(bw + cw > 0, w2 / (bw + cw), w_band)
    w_bar = np.where(count >= MIN_DISCORDANT, w_ratio, np.maximum(w_ratio, w_band))
    w_bar = np.maximum(w_bar, 1e-300)
    d = paired_difference_ci(bw / w_bar, cw / w_bar, n / w_bar, level)
    J = model.jacobian(q)[:, :3]
    C = np.einsum("pik,k,pjk->pij", J, model.sigma**2, J)
    p_lin = np.asarray(p_within_radius(C, r))
    delta = (bw - cw) / n
    p_hat = p_lin + delta
    var = (np.maximum(w2, np.where(count > 0, 0.0, w_band**2)) / n - delta**2) / n
    plain_var = np.clip(p_hat, 0, 1) * (1 - np.clip(p_hat, 0, 1)) / n
    vr = np.where(var > 0, plain_var / np.maximum(var, 1e-300), np.inf)
    nan = np.full(P, np.nan)
    details = {"scale": np.array([pp[3] for pp in per_pose]), "alpha": alpha, "w_bar": w_bar, "w_band": w_band,
               "max_deviation_mm": dev, "n_discordant_raw": count}
    return ProbabilityEstimate("position", r, "importance", np.full(P, "importance"), tuple("" for _ in range(P)),
                               n.astype(int), p_lin, p_hat, np.clip(p_lin + d[:, 1], 0, 1),
                               np.clip(p_lin + d[:, 2], 0, 1), nan, nan, nan, bw / w_bar, cw / w_bar, vr, level, details)
