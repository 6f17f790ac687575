"""From a pooled fleet (:mod:`.fleet_pool`) back to the design's tolerance model: which spread and shift the
allocation assumed for every identifiable combination, the capability the fleet achieved (Cpk), the fleet's shared
(systematic) error, and the per-parameter capability a re-allocation can use.

**The map.** The diagnosis fits its own complete, minimal geometric model (:mod:`.geometry`); the allocation
tolerances the paper's error-screw model (:mod:`tolalloc.errormodel`). On the poses the fleet was measured on, a
tolerance parameter ``e_k`` moves the measured target by the column ``J_tol[:, k]``; the least-squares fit of that
column by the registration, probe offset and identifiable geometric columns ``[J_nuis | J_geo]`` gives row ``k``
of the map ``G`` (identifiable combinations x tolerance parameters; the nuisance part dropped): what a robot built with
the error ``e`` shows as its identified parameters, ``theta = G e`` (to first order; the fit's residual is
reported, ~0 since the geometric model is complete).

**Allocation -> combinations.** Tolerances ``t`` (sigma ``t / z``) imply the combination covariance ``G diag(sigma^2)
G^T``; the allocated standard deviation of combination ``j`` is the square root of its diagonal.

**Capability.** ``Cpk_j = (z sigma_alloc,j - |mu_j|) / (3 tau_j)``: the combination's implied tolerance
``+-z sigma_alloc`` against the fleet's mean ``mu`` and spread ``tau``. A fleet exactly as allocated and centred has
``Cpk = z / 3``: 1 at the normal model's ``z = 3``, 0.58 at a uniform model's ``z = sqrt 3`` (a tolerance held by
its own range, not by three standard deviations). ``cpk_lo`` takes the interval ends that make it smallest. The
spread is *tighter than asked* when the upper end of its interval is below the allocated standard deviation, *looser
than asked* when the lower end is above it; *shifted* when the mean's interval excludes 0.

**Shared error.** The fleet's mean geometric error ``mu`` displaces the target by ``J_geo mu`` at every pose, the same
on every robot: what a design change (a corrected nominal) would remove; the spread displaces it by ``sqrt(tr J_geo
Sigma_between J_geo^T)``. :func:`shared_error` gives both at the fleet's poses and the shared share of the mean
square.

**Per tolerance parameter** (:func:`parameter_capability`, for a re-allocation). A combination is *budgeted* when
its achieved spread is at most :data:`MAX_RATIO` times its allocated sd (beyond that the tolerance model lacks the
error source, or holds it far too small: listed, not attributed). The spread factor ``a_k`` (achieved / allocated sd)
of tolerance parameter ``k`` is the geometric mean of the budgeted combinations' ratios ``tau_j / s_j``, each weighted
by the share of combination ``j``'s allocated variance that ``k`` explains (``G_jk^2 sigma_k^2 / s_j^2``); a parameter
explaining less than :data:`OBSERVED_SHARE` of them in total is not observed and keeps ``a = 1``. The shift ``m`` is
the smallest in allocated sigmas that reproduces the budgeted combinations' means (``G m = mu``, minimum norm of
``m / sigma``). Both are a reading of the fleet in the tolerance model's terms, as far as its combinations reach.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import ErrorModel
from tolalloc.diagnose.fleet_pool import FleetPool
from tolalloc.diagnose.uncertainty import point_jacobian

__all__ = ["combination_map", "allocated_sd", "capability_frame", "shared_error", "parameter_capability",
           "MAX_RATIO"]

#: A combination whose achieved spread exceeds its allocated sd by more than this factor is not budgeted by the
#: tolerance model (an error source the model lacks, or one it holds far too small); ratios are clipped to
#: [1 / MAX_RATIO, MAX_RATIO].
MAX_RATIO = 10.0
#: A tolerance parameter counts as observed when it explains at least this share of the allocated variance of the
#: budgeted combinations, summed.
OBSERVED_SHARE = 0.05


def _fleet_poses(pool: FleetPool) -> np.ndarray:
    return np.vstack([r.model.train.q for r in pool.robots])


def combination_map(pool: FleetPool, error_model: ErrorModel) -> tuple[np.ndarray, np.ndarray]:
    """``(G (k, K), residual (K,))``: the map from the tolerance model's parameters to the fleet's identifiable
    geometric combinations on the first robot's poses, and the relative residual of each column's fit (module
    docstring)."""
    ref = pool.robots[0].model
    if error_model.robot.name != ref.robot.name or not np.allclose(error_model.robot.screws, ref.robot.screws):
        raise TolallocError(f"fleet: the tolerance model is of robot {error_model.robot.name!r}, the fleet of "
                            f"{ref.robot.name!r}; build the error model of the fleet's robot.")
    fit, q = ref.fit, ref.train.q
    k = pool.n_geometric
    A = point_jacobian(fit, q)[:, :, :9 + k].reshape(3 * len(q), -1)
    J = error_model.jacobian(q)
    T = error_model.robot.fk_internal(q)
    arm = T[:, :3, :3] @ fit.t_mm
    Jt = np.einsum("ij,pjk->pik", fit.R, J[:, :3, :] + np.cross(J[:, 3:, :], arm[:, :, None], axis=1))
    Jt = Jt.reshape(3 * len(q), -1)
    scale = np.linalg.norm(A, axis=0)
    coef, *_ = np.linalg.lstsq(A / scale, Jt, rcond=None)
    coef = coef / scale[:, None]
    resid = np.linalg.norm(A @ coef - Jt, axis=0) / np.maximum(np.linalg.norm(Jt, axis=0), 1e-300)
    return coef[9:], resid


def allocated_sd(G: np.ndarray, sigma) -> np.ndarray:
    """Standard deviation of every combination under the tolerance sigmas ``sigma`` (K,), shape (k,)."""
    return np.sqrt(np.einsum("jk,k,jk->j", G, np.asarray(sigma, float) ** 2, G))


def capability_frame(pool: FleetPool, G: np.ndarray, sigma, z: float) -> pd.DataFrame:
    """The geometric rows of ``pool.table`` with ``allocated_sd``, ``allocated_tol`` (``z`` x it), ``cpk``,
    ``cpk_lo`` and ``status`` (module docstring)."""
    tab = pool.table.iloc[:pool.n_geometric].copy()
    s = allocated_sd(G, sigma)
    tol = z * s
    mu, lo, hi = tab["mean"].to_numpy(), tab["mean_lo"].to_numpy(), tab["mean_hi"].to_numpy()
    tau, tau_lo, tau_hi = tab["spread"].to_numpy(), tab["spread_lo"].to_numpy(), tab["spread_hi"].to_numpy()
    far = np.maximum(np.abs(lo), np.abs(hi))
    with np.errstate(divide="ignore", invalid="ignore"):
        cpk = np.where(tau > 0, (tol - np.abs(mu)) / (3 * tau), np.inf)
        cpk_lo = np.where(tau_hi > 0, (tol - far) / (3 * tau_hi), np.inf)
    status = []
    for j in range(len(tab)):
        st = "tighter than asked" if tau_hi[j] < s[j] else ("looser than asked" if tau_lo[j] > s[j] else "as asked")
        status.append(st + ("; shifted" if lo[j] > 0 or hi[j] < 0 else ""))
    tab["allocated_sd"], tab["allocated_tol"], tab["cpk"], tab["cpk_lo"], tab["status"] = s, tol, cpk, cpk_lo, status
    return tab


def shared_error(pool: FleetPool) -> dict:
    """The fleet's shared and robot-to-robot geometric error at its poses [mm] (module docstring): ``shared_rms_mm``,
    ``spread_rms_mm`` and ``shared_share`` (of the mean square)."""
    ref = pool.robots[0].model
    q = _fleet_poses(pool)
    k = pool.n_geometric
    J = np.einsum("ji,pjk->pik", ref.fit.R, point_jacobian(ref.fit, q)[:, :, 9:9 + k])  # base frame
    m = J @ pool.mean[:k]
    spread2 = np.einsum("pik,kl,pil->p", J, pool.between_cov[:k, :k], J)
    a, b = float(np.mean(np.sum(m ** 2, axis=1))), float(np.mean(spread2))
    return {"shared_rms_mm": np.sqrt(a), "spread_rms_mm": np.sqrt(b), "shared_share": a / (a + b) if a + b > 0 else 0.0,
            "poses": len(q)}


def parameter_capability(pool: FleetPool, G: np.ndarray, sigma) -> dict:
    """Per tolerance parameter the spread factor ``a`` (K,), shift ``mean`` (K,) [mm, rad] and ``observed`` (K,), and
    per combination ``budgeted`` (k,) (module docstring)."""
    sigma = np.asarray(sigma, float)
    k, K = G.shape
    s = allocated_sd(G, sigma)
    tau = pool.table["spread"].to_numpy()[:k]
    budgeted = s * MAX_RATIO >= tau
    ratio = np.clip(tau / np.maximum(s, 1e-300), 1.0 / MAX_RATIO, MAX_RATIO)
    w = (G * sigma[None, :]) ** 2 / np.maximum(s, 1e-300)[:, None] ** 2  # share of combination j's variance from k
    w = np.where(budgeted[:, None], w, 0.0)
    total = w.sum(axis=0)
    observed = total >= OBSERVED_SHARE
    a = np.where(observed, np.exp((w * np.log(ratio)[:, None]).sum(axis=0) / np.maximum(total, 1e-300)), 1.0)
    Gs = (G * sigma[None, :])[budgeted] / s[budgeted, None]  # per allocated sigma, per allocated sd
    d = pool.mean[:k][budgeted] / s[budgeted]
    m = sigma * (np.linalg.pinv(Gs, rcond=1e-6) @ d) if len(d) else np.zeros(K)
    return {"spread_factor": a, "mean": np.where(observed, m, 0.0), "observed": observed, "budgeted": budgeted}
