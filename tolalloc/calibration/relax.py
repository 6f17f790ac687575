"""The convex relaxation of the calibration-plan design: SciPy's interior-point method, the cvxpy (Clarabel) SDP
and Frank-Wolfe.

Over weights ``lambda`` on ``C`` candidate poses (``0 <= lambda_c <= 1``, ``sum lambda = n``)::

    minimise  f(lambda) = trace(B^T M(lambda)^-1 B),     M(lambda) = diag(prior) + sum_c lambda_c G_c^T G_c + ridge

(prior-normalised coordinates: ``prior`` is 1 on the estimated parameters, 0 on the flat nuisance block; ``B B^T``
the task weight). ``f`` is convex, so at any ``lambda >= 0`` the linear-oracle value
``f + min_s grad . (s - lambda)`` over the feasible ``s`` (the ``n`` most negative gradients) is a lower bound on
the optimum; every result carries it, whichever method produced the weights.

Scaling: written naively (``M`` as is) the problem is badly conditioned on the tool_changer -- the information spans
~1e7 against the prior; main's first cvxpy attempt ended in NumericalError, and on 200 candidates (tracker frame
known) Clarabel returned ``optimal_inaccurate`` at a value far above the optimum (``benchmarks/bench_calibration.py``
prints both). Well scaled it solves: congruence by ``T0`` with ``T0^T M0 T0 = I`` for the uniform design ``M0`` (so
``M'`` is O(1) at every sensible design; ``B' = T0^T B``) and the objective divided by its value at ``M0``.

Column generation: both solvers work on a working set of candidates (seeded with the largest weights of
Frank-Wolfe and the most negative gradients there); then the optimality gap is taken over *all* candidates, and
the candidates with the most negative gradient join the set until the gap is below ``tol * f``. The answer is the
relaxation over all candidates (certified by that gap), not over a subset.

Interior point (:func:`interior_point_relaxation`, the first choice): SciPy's ``trust-constr`` on ``f`` itself,
with its exact gradient and Hessian (``C x C``, from ``M'^-1``). cvxpy form (:func:`cvxpy_relaxation`):
``cp.matrix_frac(B', M'(lambda))`` -- the Schur-complement SDP ``[[M', B'], [B'^T, T]] >= 0``, minimise
``trace T``; each Clarabel iteration is dominated by the ``(D + Ke)``-sized PSD cone and a dense ``svec(M) x C``
block of the KKT system, which makes it several times slower on the same working set (``benchmarks/
bench_calibration.py``). Both end at the same certificate, so the faster one runs first.

Fallbacks: cvxpy when the interior-point method does not converge or does not close the gap, Frank-Wolfe
(:func:`frank_wolfe`) when cvxpy does not either; :attr:`Relaxation.method` and :attr:`Relaxation.note` say which
ran and why."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import interruptible

__all__ = ["Relaxation", "relax", "frank_wolfe", "interior_point_relaxation", "cvxpy_relaxation", "METHODS"]

METHODS = ("auto", "interior-point", "cvxpy", "frank-wolfe")
#: Relative optimality gap at which a relaxation counts as solved.
GAP_TOL = 1e-4
#: Working-set size of the column generation (whole problem when C is at most this).
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


def _whitened(G, B, n, prior, ridge, S):
    """The working set's problem in scaled coordinates: ``(H (|S| rows, D), P0 (D, D), Bw (D, Ke))`` with
    ``M'(lambda) = P0 + sum_c lambda_c H_c^T H_c``, ``M' = I`` at the uniform design and objective 1 there."""
    F = np.einsum("cri,crj->ij", G[S], G[S])
    w, V = np.linalg.eigh(np.diag(prior) + ridge + (n / len(S)) * F)
    T0 = V / np.sqrt(w)  # T0^T M0 T0 = I
    H = (G[S] @ T0).reshape(-1, T0.shape[1])
    P0 = T0.T @ (np.diag(prior) + ridge) @ T0
    P0 = 0.5 * (P0 + P0.T)
    Bw = T0.T @ B
    return H, P0, Bw / np.sqrt(np.sum(Bw * Bw))


def _sdp(G, B, n, prior, ridge, S):
    """The scaled cvxpy SDP over the working set ``S``: (weights on S, status, iterations)."""
    import cvxpy as cp

    H, P0, Bw = _whitened(G, B, n, prior, ridge, S)
    D, rows = P0.shape[0], H.shape[0] // len(S)
    Hc = H.reshape(len(S), rows, D)
    Fw = np.einsum("cri,crj->cij", Hc, Hc)
    lam = cp.Variable(len(S))
    M = P0 + cp.reshape(Fw.reshape(len(S), D * D).T @ lam, (D, D), order="C")
    prob = cp.Problem(cp.Minimize(cp.matrix_frac(Bw, 0.5 * (M + M.T))),
                      [lam >= 0, lam <= 1, cp.sum(lam) == n])
    interruptible(prob.solve, solver="CLARABEL")
    return (None if lam.value is None else np.clip(lam.value, 0.0, 1.0)), prob.status, prob.solver_stats.num_iters


def _interior_point(G, B, n, prior, ridge, S):
    """The scaled relaxation over the working set ``S`` by SciPy's interior-point method (``trust-constr``) with
    the exact gradient and Hessian: (weights on S, status, iterations).

    With ``X = M'^-1 Bw`` and ``U = H X``: ``f = trace(Bw^T X)``, ``df/dlambda_c = -|U_c|^2`` and
    ``d2f/dlambda_c dlambda_d = 2 trace(U_c^T (H_c M'^-1 H_d^T) U_d)``.
    """
    from scipy.optimize import Bounds, LinearConstraint, minimize

    H, P0, Bw = _whitened(G, B, n, prior, ridge, S)
    C = len(S)
    rows = H.shape[0] // C
    if n >= C:  # the only feasible point
        return np.ones(C), "optimal", 0
    last = {}

    def state(lam):
        if last.get("lam") is None or not np.array_equal(last["lam"], lam):
            M = P0 + H.T @ (np.repeat(lam, rows)[:, None] * H)
            X = np.linalg.solve(M, Bw)
            last.update(lam=lam.copy(), M=M, U=H @ X, f=float(np.sum(Bw * X)))
        return last

    def grad(lam):
        U = state(lam)["U"]
        return -np.sum(U * U, axis=1).reshape(C, rows).sum(axis=1)

    def hess(lam):
        st = state(lam)
        P = H @ np.linalg.solve(st["M"], H.T)
        return 2.0 * ((st["U"] @ st["U"].T) * P).reshape(C, rows, C, rows).sum(axis=(1, 3))

    res = minimize(lambda lam: state(lam)["f"], np.full(C, n / C), jac=grad, hess=hess, method="trust-constr",
                   constraints=[LinearConstraint(np.ones((1, C)), n, n)], bounds=Bounds(0.0, 1.0),
                   options={"gtol": 1e-10, "xtol": 1e-12, "barrier_tol": 1e-10, "maxiter": 1000})
    status = "optimal" if res.status in (1, 2) else f"not converged ({res.message})"
    return np.clip(res.x, 0.0, 1.0), status, res.nit


def _column_generation(G, B, n, prior, solve, name, *, rounds, seed_lam):
    """The relaxation over all candidates from solves over a growing working set (module docstring)."""
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
        lam_s, status, it = solve(G, B, n, prior, ridge, S)
        iters.append(it)
        if status != "optimal":
            raise RuntimeError(f"{name} status {status!r} on {len(S)} candidates (round {r + 1})")
        lam = np.zeros(C)
        lam[S] = lam_s
        fval, grad, _, bound = _state(G, B, n, prior, ridge, lam)
        if fval - bound <= GAP_TOL * fval:
            return Relaxation(lam, fval, bound, name,
                              f"{r + 1} round(s) over {len(S)} of {C} candidates, iterations "
                              f"{'+'.join(map(str, iters))}, gap {(fval - bound) / fval:.2e}")
        out = np.setdiff1d(np.argsort(grad)[: 2 * n + WORKING_SET // 4], S)
        S = np.union1d(S, out[: WORKING_SET // 4])
    raise RuntimeError(f"{name}: the optimality gap over all {C} candidates is still "
                       f"{(fval - bound) / fval:.2e} > {GAP_TOL:g} after {rounds} rounds")


def cvxpy_relaxation(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, *, rounds: int = 6,
                     seed_lam: np.ndarray | None = None) -> Relaxation:
    """The relaxation as a cvxpy SDP (Clarabel), by column generation over the candidates (module docstring).

    Raises
    ------
    RuntimeError
        If the solver does not report ``optimal`` or the gap over all candidates stays above :data:`GAP_TOL`
        (the message says which, and by how much).
    """
    return _column_generation(G, B, n, prior, _sdp, "cvxpy/Clarabel", rounds=rounds, seed_lam=seed_lam)


def interior_point_relaxation(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, *, rounds: int = 6,
                              seed_lam: np.ndarray | None = None) -> Relaxation:
    """The relaxation by SciPy's interior-point method on ``f(lambda)`` itself (exact Hessian), by the same column
    generation as :func:`cvxpy_relaxation`; raises ``RuntimeError`` in the same cases."""
    return _column_generation(G, B, n, prior, _interior_point, "SciPy trust-constr", rounds=rounds,
                              seed_lam=seed_lam)


def relax(G: np.ndarray, B: np.ndarray, n: int, prior: np.ndarray, method: str = "auto") -> Relaxation:
    """Solve the relaxation: ``auto`` (interior point, then cvxpy if that fails, then Frank-Wolfe),
    ``interior-point`` or ``cvxpy`` (raise if it fails) or ``frank-wolfe``. The bound is the best certified one of
    the methods that ran."""
    fw = frank_wolfe(G, B, n, prior) if method in ("auto", "frank-wolfe") else None
    if method == "frank-wolfe":
        return fw
    from cvxpy.error import SolverError

    seed = None if fw is None else fw.lam
    failed = []
    for name, solve in (("interior-point", interior_point_relaxation), ("cvxpy", cvxpy_relaxation)):
        if method not in ("auto", name):
            continue
        try:
            res = solve(G, B, n, prior, seed_lam=seed)
        except (SolverError, RuntimeError, ValueError, np.linalg.LinAlgError) as exc:  # not optimal, gap open
            if method == name:
                raise
            failed.append(f"{name} not used: {exc}")
            continue
        note = "; ".join([res.note, *failed])
        if fw is not None and fw.bound > res.bound:
            return Relaxation(res.lam, res.value, fw.bound, res.method, note + "; bound from Frank-Wolfe")
        return Relaxation(res.lam, res.value, res.bound, res.method, note)
    return Relaxation(fw.lam, fw.value, fw.bound, fw.method, "; ".join([fw.note, *failed]))
