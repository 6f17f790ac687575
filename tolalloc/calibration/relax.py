"""The convex relaxation of the calibration-plan design, in cvxpy (Clarabel) with Frank-Wolfe as the fallback.

Over weights ``lambda`` on ``C`` candidate poses (``0 <= lambda_c <= 1``, ``sum lambda = n``)::

    minimise  f(lambda) = trace(B^T M(lambda)^-1 B),     M(lambda) = diag(prior) + sum_c lambda_c G_c^T G_c + ridge

(prior-normalised coordinates: ``prior`` is 1 on the estimated parameters, 0 on the flat nuisance block; ``B B^T``
the task weight). ``f`` is convex, so at any ``lambda >= 0`` the linear-oracle value
``f + min_s grad . (s - lambda)`` over the feasible ``s`` (the ``n`` most negative gradients) is a lower bound on
the optimum; every result carries it, whichever method produced the weights.

cvxpy form (:func:`cvxpy_relaxation`): ``cp.matrix_frac(B', M'(lambda))`` -- the Schur-complement SDP
``[[M', B'], [B'^T, T]] >= 0``, minimise ``trace T``. Written naively (``M`` as is) Clarabel fails on the
tool_changer: the information spans ~1e7 against the prior; main's first attempt ended in NumericalError, and on
200 candidates (tracker frame known) it returns ``optimal_inaccurate`` at a value far above the optimum
(``benchmarks/bench_calibration.py`` prints both). Well scaled it solves: congruence by ``T0`` with
``T0^T M0 T0 = I`` for the uniform design ``M0`` (so ``M'`` is O(1) at every sensible design; ``B' = T0^T B``)
and the objective divided by its value at ``M0``. Each Clarabel iteration is dominated by the
``(D + Ke)``-sized PSD cone, and the KKT system carries a dense ``svec(M) x C`` block, so the relaxation over
all C candidates is solved by column generation: the SDP over a working set (seeded with the largest weights
of Frank-Wolfe and the most negative gradients there), then the optimality gap over *all* candidates; the
candidates with the most negative gradient join the set until the gap is below ``tol * f``. The answer is the
relaxation over all candidates (certified by that gap), not over a subset.

Fallback (:func:`frank_wolfe`): used when cvxpy does not report ``optimal``, raises, or the column generation
does not close the gap; :attr:`Relaxation.method` and :attr:`Relaxation.note` say which ran and why.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import interruptible

__all__ = ["Relaxation", "relax", "frank_wolfe", "cvxpy_relaxation", "METHODS"]

METHODS = ("auto", "cvxpy", "frank-wolfe")
#: Relative optimality gap at which a relaxation counts as solved.
GAP_TOL = 1e-4
#: Working-set size of the cvxpy column generation (whole problem when C is at most this).
WORKING_SET = 240


@dataclass(frozen=True, eq=False)
class Relaxation:
    """Solution of the relaxed design.

    Attributes
    ----------
    lam : array, shape (C,)
        Candidate weights.
    value : float
        ``f(lam)`` [mm^2].
    bound : float
        Lower bound on the relaxation's optimum, hence on every n-pose plan's score [mm^2].
    method : str
        ``"cvxpy/Clarabel"`` or ``"Frank-Wolfe"``.
    note : str
        How it ended (iterations, gap; for a fallback, what failed).
    """

    lam: np.ndarray
    value: float
    bound: float
    method: str
    note: str

    @property
    def gap(self) -> float:
        """Relative optimality gap ``(value - bound) / value``."""
        return (self.value - self.bound) / self.value if self.value > 0 else 0.0


def _ridge(G: np.ndarray, n: int) -> np.ndarray:
    C, D = G.shape[0], G.shape[2]
    return 1e-9 * max(np.einsum("cri,cri->i", G, G).max() * n / C, 1.0) * np.eye(D)  # flat nuisance block


def _state(G, B, n, prior, ridge, lam):
    """``f(lam)``, its gradient (C,), the linear-oracle vertex ``s`` and the lower bound ``f - grad . (lam - s)``."""
    C, rows, D = G.shape
    Gf = G.reshape(C * rows, D)
    M = np.diag(prior) + Gf.T @ (np.repeat(lam, rows)[:, None] * Gf) + ridge
    X = np.linalg.solve(M, B)  # (D, Ke)
    fval = float(np.sum(B * X))
    grad = -np.sum((Gf @ X) ** 2, axis=1).reshape(C, rows).sum(axis=1)
    s = np.zeros(len(lam))
    s[np.argsort(grad)[:n]] = 1.0
    return fval, grad, s, fval - float(grad @ (lam - s))


def frank_wolfe(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, iters: int = 300) -> Relaxation:
    """Frank-Wolfe on the relaxation (linear oracle: the n candidates of largest ``|G_c M^-1 B|_F^2``).

    Parameters
    ----------
    G : array, shape (C, rows, D)
        Whitened, normalised information blocks.
    B : array, shape (D, Ke)
        Task-weight factor.
    n : int
    prior : array, shape (D,)
    """
    C = G.shape[0]
    ridge = _ridge(G, n)
    lam = np.full(C, n / C)
    bound, it = -np.inf, 0
    for it in range(iters):
        fval, grad, s, b = _state(G, B, n, prior, ridge, lam)
        bound = max(bound, b)
        if fval - b <= GAP_TOL * fval:
            break
        lam = lam + 2.0 / (it + 3.0) * (s - lam)
    fval = _state(G, B, n, prior, ridge, lam)[0]
    return Relaxation(lam, fval, bound, "Frank-Wolfe", f"{it + 1} iterations, gap {(fval - bound) / fval:.2e}")


def _sdp(G, B, n, prior, ridge, S):
    """The scaled cvxpy SDP over the working set ``S``: (weights on S, status, iterations)."""
    import cvxpy as cp

    F = np.einsum("cri,crj->cij", G[S], G[S])
    D = F.shape[1]
    w, V = np.linalg.eigh(np.diag(prior) + ridge + (n / len(S)) * F.sum(0))
    T0 = V / np.sqrt(w)  # T0^T M0 T0 = I
    Fw = np.einsum("ia,cij,jb->cab", T0, F, T0)
    Fw = 0.5 * (Fw + np.swapaxes(Fw, 1, 2))
    P0 = T0.T @ (np.diag(prior) + ridge) @ T0
    Bw = T0.T @ B
    Bw = Bw / np.sqrt(np.sum(Bw * Bw))  # objective 1 at the uniform design
    lam = cp.Variable(len(S))
    M = P0 + cp.reshape(Fw.reshape(len(S), D * D).T @ lam, (D, D), order="C")
    prob = cp.Problem(cp.Minimize(cp.matrix_frac(Bw, 0.5 * (M + M.T))),
                      [lam >= 0, lam <= 1, cp.sum(lam) == n])
    interruptible(prob.solve, solver="CLARABEL")
    return (None if lam.value is None else np.clip(lam.value, 0.0, 1.0)), prob.status, prob.solver_stats.num_iters


def cvxpy_relaxation(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, *, rounds: int = 6,
                     seed_lam: np.ndarray | None = None) -> Relaxation:
    """The relaxation as a cvxpy SDP (Clarabel), by column generation over the candidates (module docstring).

    Raises
    ------
    RuntimeError
        If the solver does not report ``optimal`` or the gap over all candidates stays above :data:`GAP_TOL`
        (the message says which, and by how much).
    """
    C = G.shape[0]
    ridge = _ridge(G, n)
    if C <= WORKING_SET:
        S = np.arange(C)
    else:
        seed_lam = frank_wolfe(G, B, n, prior, iters=30).lam if seed_lam is None else seed_lam
        grad = _state(G, B, n, prior, ridge, seed_lam)[1]
        S = np.unique(np.r_[np.argsort(-seed_lam)[: WORKING_SET // 2], np.argsort(grad)[: WORKING_SET // 2]])
    iters = []
    for r in range(rounds):
        lam_s, status, it = _sdp(G, B, n, prior, ridge, S)
        iters.append(it)
        if status != "optimal":
            raise RuntimeError(f"cvxpy/Clarabel status {status!r} on {len(S)} candidates (round {r + 1})")
        lam = np.zeros(C)
        lam[S] = lam_s
        fval, grad, _, bound = _state(G, B, n, prior, ridge, lam)
        if fval - bound <= GAP_TOL * fval:
            return Relaxation(lam, fval, bound, "cvxpy/Clarabel",
                              f"{r + 1} round(s) over {len(S)} of {C} candidates, Clarabel iterations "
                              f"{'+'.join(map(str, iters))}, gap {(fval - bound) / fval:.2e}")
        out = np.setdiff1d(np.argsort(grad)[: 2 * n + WORKING_SET // 4], S)
        S = np.union1d(S, out[: WORKING_SET // 4])
    raise RuntimeError(f"cvxpy/Clarabel: the optimality gap over all {C} candidates is still "
                       f"{(fval - bound) / fval:.2e} > {GAP_TOL:g} after {rounds} rounds")


def relax(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, method: str = "auto") -> Relaxation:
    """Solve the relaxation: ``auto`` (cvxpy, Frank-Wolfe if that fails), ``cvxpy`` (raise if it fails) or
    ``frank-wolfe``. The bound is the best certified one of the methods that ran."""
    fw = frank_wolfe(G, B, n, prior) if method in ("auto", "frank-wolfe") else None
    if method == "frank-wolfe":
        return fw
    from cvxpy.error import SolverError

    try:
        cv = cvxpy_relaxation(G, B, n, prior, seed_lam=None if fw is None else fw.lam)
    except (SolverError, RuntimeError, np.linalg.LinAlgError) as exc:  # NumericalError, not optimal, gap open
        if method == "cvxpy":
            raise
        return Relaxation(fw.lam, fw.value, fw.bound, fw.method, f"{fw.note}; cvxpy not used: {exc}")
    if fw is not None and fw.bound > cv.bound:
        return Relaxation(cv.lam, cv.value, fw.bound, cv.method, cv.note + "; bound from Frank-Wolfe")
    return cv
