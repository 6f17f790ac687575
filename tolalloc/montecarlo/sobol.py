"""Global sensitivity from the nonlinear model: Sobol' first-order and total indices per error parameter.

Saltelli's sampling scheme with Jansen's estimators (Saltelli et al. 2010, Comput. Phys. Commun. 181: 259-270,
Table 2, estimators (c) and (f)): two independent samples ``A``, ``B`` of the parameters (``N`` rows each,
:meth:`ErrorModel.sample`, so clearances and uniform errors keep their distributions) and, per factor ``i``,
``A_B^i`` = ``A`` with factor ``i``'s columns taken from ``B``; with ``V`` the variance of ``f`` over ``A`` and ``B``,

    S_i  = (V - mean((f(B) - f(A_B^i))^2) / 2) / V,        S_Ti = mean((f(A) - f(A_B^i))^2) / 2 / V.

A factor is one parameter, or the two components of a radial clearance together (they are dependent). Zero-sigma
parameters are left out. ``N (F + 2)`` exact chain evaluations for ``F`` factors.

Outputs: the position-error magnitude ``|dP|`` [mm] and, with a radius, the pass/fail indicator
``1{|dP| < r}``. The same indices of the *linear* map ``|J e|`` are computed on the same draws (a matrix product),
so :meth:`SobolResult.to_frame` sets the nonlinear share beside the linear one and the linear variance budget,
and flags parameters whose total index differs from the linear model's by more than ``flag_diff``. SALib is the
test-only reference (``tests/test_montecarlo_sobol.py``: Ishigami and one pose).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, whole_number
from tolalloc.errormodel.chain import FastChain
from tolalloc.linear.covariance import input_covariance, variance_share

__all__ = ["jansen_indices", "factor_groups", "SobolResult", "sobol_indices", "check_sobol_budget"]


def jansen_indices(fA: np.ndarray, fB: np.ndarray, fAB: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First-order and total Sobol' indices from Saltelli's matrices (Jansen's estimators).

    Parameters
    ----------
    fA, fB : array, shape (N,)
    fAB : array, shape (F, N)
        ``f(A_B^i)`` for every factor ``i``.

    Returns
    -------
    first, total : arrays, shape (F,) (NaN when the output does not vary)
    """
    V = np.var(np.concatenate([fA, fB]), ddof=1)
    if not V > 0:
        return np.full(len(fAB), np.nan), np.full(len(fAB), np.nan)
    first = (V - 0.5 * np.mean((fB[None] - fAB) ** 2, axis=1)) / V
    total = 0.5 * np.mean((fA[None] - fAB) ** 2, axis=1) / V
    return first, total


def factor_groups(model) -> list[list[int]]:
    """Factors of the analysis: varying parameters, the two components of a radial clearance as one."""
    sig = model.sigma
    out, seen = [], {}
    for k, p in enumerate(model.params):
        if sig[k] <= 0:
            continue
        if p.distribution == "ring" and p.group:
            if p.group in seen:
                out[seen[p.group]].append(k)
                continue
            seen[p.group] = len(out)
        out.append([k])
    return out


@dataclass(frozen=True, eq=False)
class SobolResult:
    """Sobol' indices per factor at one pose.

    Attributes
    ----------
    names : tuple of str
        Factor names (a clearance pair as ``"a+b"``).
    n : int
        Base sample size ``N``.
    first_norm, total_norm : arrays, shape (F,)
        Indices of ``|dP|`` (exact kinematics).
    first_norm_linear, total_norm_linear : arrays, shape (F,)
        Indices of ``|J e|`` on the same draws.
    linear_share : array, shape (F,)
        Share of the factor in the linear variance budget ``trace(J S J^T)`` (position rows).
    first_pass, total_pass, first_pass_linear, total_pass_linear : arrays, shape (F,) or None
        Indices of the indicator ``1{|dP| < r}`` (``radius_mm`` given).
    radius_mm : float or None
    flag_diff : float
    """

    names: tuple
    n: int
    first_norm: np.ndarray
    total_norm: np.ndarray
    first_norm_linear: np.ndarray
    total_norm_linear: np.ndarray
    linear_share: np.ndarray
    first_pass: np.ndarray | None = None
    total_pass: np.ndarray | None = None
    first_pass_linear: np.ndarray | None = None
    total_pass_linear: np.ndarray | None = None
    radius_mm: float | None = None
    flag_diff: float = 0.05

    @property
    def flagged(self) -> np.ndarray:
        """Factors whose nonlinear total index of ``|dP|`` differs from the linear model's by more than ``flag_diff``."""
        return np.abs(self.total_norm - self.total_norm_linear) > self.flag_diff

    def to_frame(self) -> pd.DataFrame:
        """One row per factor: linear budget share, nonlinear and linear indices, the difference and the flag."""
        cols = {"parameter": list(self.names), "linear_variance_share": self.linear_share,
                "S1_norm": self.first_norm, "ST_norm": self.total_norm,
                "S1_norm_linear": self.first_norm_linear, "ST_norm_linear": self.total_norm_linear,
                "ST_norm_diff": self.total_norm - self.total_norm_linear}
        if self.first_pass is not None:
            cols.update({"S1_pass": self.first_pass, "ST_pass": self.total_pass,
                         "S1_pass_linear": self.first_pass_linear, "ST_pass_linear": self.total_pass_linear})
        cols["flagged"] = self.flagged
        return pd.DataFrame(cols)

    def message(self) -> str:
        bad = [self.names[i] for i in np.flatnonzero(self.flagged)]
        head = f"Sobol' indices of |dP| ({self.n} base samples)"
        if not bad:
            return head + f": every parameter's nonlinear total index within {self.flag_diff:g} of the linear model's"
        return head + f": nonlinear total index differs from the linear model's by > {self.flag_diff:g} for " + ", ".join(bad)


def _evaluate(chain, prog, p0, A, vals: np.ndarray, chunk: int = 8192):
    """``|dP|`` by the exact chain and ``|A e|`` by the linear map for values (N, K)."""
    N = len(vals)
    nl, li = np.empty(N), np.empty(N)
    work = FastChain.workspace(chunk)
    X = np.empty((3, 4, chunk))
    for s0 in range(0, N, chunk):
        s1 = min(N, s0 + chunk)
        V = np.ascontiguousarray(vals[s0:s1].T)
        Xs = X[:, :, : s1 - s0]
        chain.run(prog, V, Xs, work)
        nl[s0:s1] = np.sqrt(sum((Xs[a, 3] - p0[a]) ** 2 for a in range(3)))
        x = A @ V
        li[s0:s1] = np.sqrt(np.einsum("in,in->n", x, x))
    return nl, li


def _bytes_per_sample(model) -> float:
    """Memory of one base sample [bytes]: A, B, one A_B per factor and the outputs (5 K + 4 numbers, 16 bytes each)."""
    return 16.0 * (5 * len(model.params) + 4)


def check_sobol_budget(model, n: int, *, argument: str = "n", announce: bool = False):
    """Refuse ``n`` base samples whose chain evaluations (``n (F + 2)``, ``F`` the factor groups) cannot run within
    the time budget or whose samples do not fit in memory (:func:`tolalloc.budget.check_count`); returns the
    estimate."""
    from tolalloc.budget import chain_scale, check_count

    evals = len(factor_groups(model)) + 2
    return check_count(int(n), argument, "Sobol' base samples", {"sobol": evals},
                       scale=chain_scale(len(model.params), model.robot.n_joints),
                       bytes_each=_bytes_per_sample(model), example="4096", announce=announce)


def sobol_indices(model, q, n: int = 2**13, seed: int = 0, *, radius_mm: float | None = None,
                  flag_diff: float = 0.05) -> SobolResult:
    """Sobol' indices of the position error at one pose from the nonlinear model (see the module docstring).

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (n_joints,) [rad, mm]
    n : int
        Base sample size ``N`` (cost ``N (F + 2)`` chain evaluations).
    seed : int
    radius_mm : float, optional
        Also the indices of the pass/fail indicator ``1{|dP| < r}``.
    flag_diff : float
        Flag a factor whose nonlinear total index of ``|dP|`` differs from the linear model's by more than this.
    """
    q = np.asarray(model.robot.check_q(q, "q"), float)
    if q.ndim != 1:
        raise TolallocError(f"q: expected one pose of shape ({model.robot.n_joints},), got {q.shape}.")
    whole = whole_number(n)
    if whole is None or whole < 16:
        raise TolallocError(f"n: expected a whole number of base samples >= 16 (e.g. 8192), got {n!r}.")
    if radius_mm is not None and not (np.isfinite(radius_mm) and radius_mm > 0):
        raise TolallocError(f"radius_mm: expected a finite radius > 0 [mm], got {radius_mm!r}.")
    groups = factor_groups(model)
    if not groups:
        raise TolallocError("model: every error parameter has sigma 0; nothing varies, no Sobol' indices.")
    n = int(n)
    check_sobol_budget(model, n)
    rng = np.random.default_rng(seed)
    Amat, Bmat = model.sample(n, rng), model.sample(n, rng)
    chain = FastChain(model)
    prog = chain.program(q)
    p0 = model.robot.fk_internal(q)[:3, 3]
    J = model.jacobian(q)[:3]
    outs = [_evaluate(chain, prog, p0, J, Amat), _evaluate(chain, prog, p0, J, Bmat)]
    for g in groups:
        AB = Amat.copy()
        AB[:, g] = Bmat[:, g]
        outs.append(_evaluate(chain, prog, p0, J, AB))
    nl = np.array([o[0] for o in outs])  # (F + 2, N)
    li = np.array([o[1] for o in outs])
    share_k = variance_share(J, np.diag(input_covariance(model)))
    share = np.array([share_k[g].sum() for g in groups])

    def idx(f):
        return jansen_indices(f[0], f[1], f[2:])

    names = tuple("+".join(model.names[k] for k in g) for g in groups)
    s_nl, s_li = idx(nl), idx(li)
    extra = {}
    if radius_mm is not None:
        p_nl, p_li = idx((nl < radius_mm).astype(float)), idx((li < radius_mm).astype(float))
        extra = dict(first_pass=p_nl[0], total_pass=p_nl[1], first_pass_linear=p_li[0], total_pass_linear=p_li[1],
                     radius_mm=float(radius_mm))
    return SobolResult(names, n, s_nl[0], s_nl[1], s_li[0], s_li[1], share, flag_diff=float(flag_diff), **extra)
