"""The worst point of a design with bought parts: joints, payload and ambient temperature searched together.

A design (machining half-widths and a part for every slot) is checked on the box of the joint region times the
payload and ambient ranges. Its certified ratio at a point -- ``tr C / (r - |m|)^2 chi2_1^-1(p)`` (trace rule) or
``lambda_max(C) / (r - |m|)^2 chi2_3^-1(p)`` (eigenvalue rule), ``C`` the machining and parts covariance and ``m`` the
parts' mean -- is searched for its largest value by multistart bounded L-BFGS-B from a scrambled Sobol sample of the
extended box (each step evaluates the point and a central difference along every free coordinate in one batch, as
:func:`tolalloc.allocate.region.worst_pose`). Joints that cannot change the ratio (the rule's invariants are unchanged
when they move, e.g. a base joint about the vertical) are held at their mid-range.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.optimize import minimize
from scipy.stats import chi2, qmc

from tolalloc.allocate.parts_problem import Points
from tolalloc.errormodel.parts import PartEffects, parts_error_model

__all__ = ["PointRatio", "WorstPoint", "worst_point"]


@dataclass(frozen=True, eq=False)
class PointRatio:
    """The certified ratio of one design at arbitrary points.

    ``robot`` carries the chosen parts; ``model`` the machining error model at the design's sigmas (the problem's
    ``model_for(t)``); ``after``/``residual`` as :meth:`~tolalloc.errormodel.parts.EffectTerms.moments`."""

    robot: object
    model: object
    conditions: object
    radius_mm: float
    prob: float
    rule: str
    after: str = "none"
    residual: object = 0.1

    @cached_property
    def _pm(self):
        return parts_error_model(self.model, self.robot)

    def moments(self, points: Points) -> tuple:
        """``(mean (M, 3), covariance (M, 3, 3))`` of the tool error at ``points`` [mm, mm^2]."""
        fx = PartEffects(self.robot, points.q, points.payload_kg, points.ambient_c, self.conditions, pm=self._pm)
        m, C = fx.terms().moments(self.after, self.residual)
        J = fx.J[:, :, :len(self.model.params)]  # the parts' model extends the machining one: its columns first
        return m, C + np.einsum("pik,k,pjk->pij", J, self.model.sigma ** 2, J)

    def __call__(self, points: Points) -> np.ndarray:
        """The ratio at every point, shape (M,) (a large finite value where the mean alone reaches the radius)."""
        m, C = self.moments(points)
        room = self.radius_mm - np.linalg.norm(m, axis=1)
        if self.rule == "trace":
            v, c = np.einsum("pii->p", C), chi2.ppf(self.prob, 1)
        else:
            v, c = np.linalg.eigvalsh(C)[:, -1], chi2.ppf(self.prob, 3)
        safe = np.where(room > 0, room, 1.0)
        return np.where(room > 0, v * c / safe ** 2, 1e6 * (1 - room / self.radius_mm))


@dataclass(frozen=True, eq=False)
class WorstPoint:
    """The largest ratio found: ``point`` (a one-point :class:`Points`), ``ratio``, ``evaluations``, ``static``
    (joints held at mid-range)."""

    point: Points
    ratio: float
    evaluations: int
    static: np.ndarray


def _static(f, lo, hi, n_joints, seed, rtol=1e-7) -> np.ndarray:
    """Coordinates whose mirror image inside the box never changes the ratio (probed at 8 Sobol points)."""
    X = lo + qmc.Sobol(len(lo), scramble=True, seed=seed).random(8) * (hi - lo)
    base = f(X)
    out = np.zeros(len(lo), bool)
    for k in range(n_joints):
        X2 = X.copy()
        X2[:, k] = lo[k] + hi[k] - X[:, k]
        out[k] = hi[k] == lo[k] or np.abs(f(X2) - base).max() <= rtol * np.abs(base).max()
    out[n_joints:] = hi[n_joints:] == lo[n_joints:]
    return out


def worst_point(ratio: PointRatio, q_min, q_max, *, n_seed: int = 256, n_starts: int = 3, seed: int = 0,
                static: np.ndarray | None = None) -> WorstPoint:
    """Largest ratio over ``[q_min, q_max]`` x the payload and ambient ranges of ``ratio.conditions``."""
    cond = ratio.conditions
    n = len(q_min)
    lo = np.concatenate([q_min, [cond.payload_kg[0], cond.ambient_c[0]]])
    hi = np.concatenate([q_max, [cond.payload_kg[1], cond.ambient_c[1]]])

    def f(X):
        return ratio(Points(X[:, :n], X[:, n], X[:, n + 1]))

    fixed = _static(f, lo, hi, n, seed) if static is None else static
    free = np.flatnonzero(~fixed)
    mid = 0.5 * (lo + hi)
    span = np.where(hi > lo, hi - lo, 1.0)
    X = lo + qmc.Sobol(len(lo), scramble=True, seed=seed).random(n_seed) * (hi - lo)
    X[:, fixed] = mid[fixed]
    R = f(X)
    evals = len(X)
    best_x, best_r = X[int(np.argmax(R))].copy(), float(R.max())
    m, h = len(free), 1e-6
    B = np.repeat(mid[None], 2 * m + 1, axis=0)
    step = np.zeros((2 * m + 1, m))
    step[1:m + 1], step[m + 1:] = h * np.eye(m), -h * np.eye(m)

    def f_and_grad(y):  # minimise -ratio in unit coordinates of the free variables
        B[:, free] = lo[free] + (y + step) * span[free]
        r = f(B)
        return -float(r[0]), -(r[1:m + 1] - r[m + 1:]) / (2 * h)

    for i in np.argsort(R)[::-1][:n_starts]:
        y0 = (X[i, free] - lo[free]) / span[free]
        res = minimize(f_and_grad, y0, jac=True, method="L-BFGS-B", bounds=[(0.0, 1.0)] * m,
                       options={"maxiter": 30})
        evals += int(res.nfev) * (2 * m + 1)
        if -res.fun > best_r:
            best_r = -float(res.fun)
            best_x = mid.copy()
            best_x[free] = lo[free] + res.x * span[free]
    return WorstPoint(Points(best_x[None, :n], best_x[n:n + 1], best_x[n + 1:n + 2]), best_r, evals, fixed)
