"""Mixed-integer programs over the standard values: the outer approximation that every discrete solve uses.

Each allocatable parameter picks one option of the catalogue (:mod:`tolalloc.allocate.catalogue`): binaries
``y_o``, one per parameter. A listed option (a grade, a class) brings a fixed scaled variance ``u_o`` and
cost ``c_o``; a stepped option a general integer ``n`` (the half-width is ``n * step``) with
``u = alpha n^2`` and the cost law ``c(n)``, both convex in ``n``. They enter through variables ``v >= u(n)``
and ``w >= c(n)``, written as *integer chords*: the line through the values at ``m`` and ``m + 1``, which at
every integer lies at or below a convex function and is exact at ``m`` and ``m + 1`` (with all chords the
relaxation is the convex hull of the integer points). Perspective form (``v >= alpha ((2m + 1) n - m (m + 1)
y)``, ``w >= c(m) y + (c(m+1) - c(m)) (n - m y)``), so an unchosen option costs nothing. Chords start dense
near the continuous optimum and are added where a solution needs them (:meth:`OuterApproximation.tighten`), so
at the end every chosen value has its exact variance and cost. Processes add a binary per part and process (a
part uses at most one; its setup cost is paid once). The requirement enters as linear rows ``A u <= s`` (the
rules and their cuts: :mod:`tolalloc.allocate.discrete_rules`; linearised probabilities:
:mod:`tolalloc.allocate.discrete_exact`).

The programs go to HiGHS through cvxpy (MIT licence, installed with cvxpy >= 1.6; branch-and-cut for
mixed-integer *linear* programs, which is all the outer approximation needs). Rows carry a margin of
:data:`ROW_MARGIN` (relative budget) so that HiGHS' feasibility tolerance cannot leave a design a hair outside
the rule; every design is re-checked in numpy.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from tolalloc.allocate.catalogue import Catalogue
from tolalloc.exceptions import interruptible

__all__ = ["MipOutcome", "RuleOutcome", "OuterApproximation", "repair", "MIP_REL_GAP", "COARSE_GAP", "ROW_MARGIN"]

#: Relative optimality gap HiGHS must close (its default is 1e-4).
MIP_REL_GAP = 1e-3
#: Gap of the cutting-plane rounds before a design meets the rule (they only place cuts and chords).
COARSE_GAP = 5e-3
#: Margin on every row's right-hand side (rows are relative budgets of order 1).
ROW_MARGIN = 1e-8
_HIGHS = {"mip_rel_gap": MIP_REL_GAP, "mip_abs_gap": 1e-6, "primal_feasibility_tolerance": 1e-9,
          "mip_feasibility_tolerance": 1e-9}
_QUIET: list = []  # set once HiGHS has written its banner (to /dev/null)


def _quiet_highs() -> None:
    """Create the process's first HiGHS instance with file descriptor 1 on /dev/null: HiGHS writes its copyright
    banner to stdout once per process, at the first instance (before cvxpy can switch its output off), and the
    command line's stdout carries tables. Nothing else of this program writes while it runs."""
    if _QUIET:
        return
    import os
    import sys

    import highspy

    _QUIET.append(True)
    try:
        sys.stdout.flush()
        saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    except (OSError, ValueError):  # no file descriptor 1 (embedded interpreters): the banner is harmless there
        return
    try:
        os.dup2(null, 1)
        highspy.Highs()
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


_TIGHT = 1e-9  # relative: chords are exact enough at a solution when v >= u(n) (1 - _TIGHT)


@dataclass(frozen=True)
class MipOutcome:
    """One MILP solve: the choice ``(opt, n)`` or None, HiGHS' value and dual bound, the relaxed ``v``, ``w``."""

    opt: np.ndarray | None
    n: np.ndarray | None
    value: float
    bound: float
    status: str  # optimal, infeasible, not_converged, failed
    time_s: float
    v: np.ndarray | None = None
    w: np.ndarray | None = None
    message: str = ""
    part: np.ndarray | None = None  # chosen part option per slot (with part_slot), indices into the options


@dataclass(frozen=True)
class RuleOutcome:
    """Discrete optimum of one rule over the catalogue.

    Attributes
    ----------
    rule : str
        ``trace``, ``lmi`` or ``exact``.
    status : {"optimal", "infeasible", "not_converged", "failed"}
        ``optimal``: proven (for ``exact``: the outer approximation converged, see
        :mod:`tolalloc.allocate.discrete_exact`). ``not_converged``: a feasible design was kept, not proven.
    opt, n : arrays of int (Ka,) or None
        The choice.
    cost : float
    bound : float
        Lower bound on the cost of every catalogue design that meets the rule (valid for ``trace``/``lmi``).
    mips : int
        Programs solved.
    time_s : float
    message : str
    """

    rule: str
    status: str
    opt: np.ndarray | None
    n: np.ndarray | None
    cost: float
    bound: float
    mips: int
    time_s: float
    message: str = ""


@dataclass
class OuterApproximation:
    """Rows ``A u <= s`` and chord points of the stepped options; solves the MILP they define.

    Parameters
    ----------
    cat : Catalogue
    A : array, shape (R, Ka)
    s : array, shape (R,)
    hint_t : array (Ka,) [mm or rad], optional
        Values near which chords start dense (the continuous optimum).
    part_slot, part_cost : arrays, shape (Z,), optional
        Bought parts (:mod:`tolalloc.allocate.parts_discrete`): the slot of each part option (one option per slot
        is bought: binaries ``z``) and its cost; the rows become ``A u + R z <= s``.
    R : array, shape (R, Z), optional
        The part options' row coefficients.
    """

    cat: Catalogue
    A: np.ndarray
    s: np.ndarray
    hint_t: np.ndarray | None = None
    chords: dict = field(default_factory=dict)
    part_slot: np.ndarray | None = None
    part_cost: np.ndarray | None = None
    R: np.ndarray | None = None

    def __post_init__(self):
        cat = self.cat
        for o in np.flatnonzero(cat.stepped):
            lo, hi = int(cat.n_lo[o]), int(cat.n_hi[o])
            pts = set(np.round(np.geomspace(lo, hi, 12)).astype(int).tolist())
            if self.hint_t is not None:  # every integer within +-20 % of the hint (at most ~60 chords)
                x = self.hint_t[cat.param[o]] / cat.step[o]
                pts |= set(np.unique(np.round(np.geomspace(max(lo, 0.8 * x), max(lo, min(hi, 1.25 * x)), 60))).astype(int).tolist())
            self.chords[int(o)] = {int(np.clip(m, lo, max(lo, hi - 1))) for m in pts}

    @property
    def _u_scale(self) -> np.ndarray:
        """Largest scaled variance of each option, (M,): stepped ``v`` are in units of it."""
        cat = self.cat
        return np.where(cat.stepped, (np.nan_to_num(cat.n_hi * cat.step) / cat.t_ref[cat.param]) ** 2, 1.0)

    def add_rows(self, A, s, R=None) -> None:
        self.A, self.s = np.vstack([self.A, A]), np.concatenate([self.s, s])
        if self.part_slot is not None:
            self.R = np.vstack([self.R, np.zeros((len(s), len(self.part_slot))) if R is None else R])

    def tighten(self, opt, n, out: MipOutcome) -> bool:
        """Add chords where the solution's relaxed variance or cost is below the exact one; True if any."""
        cat, added = self.cat, False
        S = np.flatnonzero(cat.stepped)
        pos = {int(o): i for i, o in enumerate(S)}
        for a, o in enumerate(opt):
            if not cat.stepped[o]:
                continue
            i, m = pos[int(o)], int(n[a])
            u_true = (m / cat.n_hi[o]) ** 2  # v is in units of the largest variance
            c_true = float(cat.law[o].cost(m * cat.step[o]))
            if out.v[i] < u_true * (1 - _TIGHT) or out.w[i] < c_true - _TIGHT * max(1.0, abs(c_true)):
                lo, hi = int(cat.n_lo[o]), max(int(cat.n_lo[o]), int(cat.n_hi[o]) - 1)
                near = {int(np.clip(k, lo, hi)) for k in (m - 2, m - 1, m, m + 1)}
                added |= not near <= self.chords[int(o)]
                self.chords[int(o)] |= near
        return added

    def solve(self, *, cost_cap: float | None = None, time_limit: float = 120.0, gap: float = MIP_REL_GAP) -> MipOutcome:
        """Minimise the cost subject to the rows (a relaxation while chords are missing)."""
        import cvxpy as cp

        t0 = time.perf_counter()
        _quiet_highs()
        prob, y, nv, v, w, z = self._program(cost_cap)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                interruptible(prob.solve, solver="HIGHS", time_limit=float(time_limit), **{**_HIGHS, "mip_rel_gap": gap})
        except cp.error.SolverError as exc:  # pragma: no cover - solver failure
            return MipOutcome(None, None, np.nan, np.nan, "failed", time.perf_counter() - t0, message=f"HiGHS: {exc}")
        dt = time.perf_counter() - t0
        if prob.status in ("infeasible", "infeasible_inaccurate", "infeasible_or_unbounded"):
            return MipOutcome(None, None, np.inf, np.inf, "infeasible", dt, message="no option combination meets the rows")
        if prob.status != "optimal" or y.value is None:
            return MipOutcome(None, None, np.nan, np.nan, "not_converged" if prob.status == "user_limit" else "failed",
                              dt, message=f"HiGHS status {prob.status} after {dt:.1f} s")
        cat = self.cat
        yv = np.asarray(y.value)
        opt = np.array([cat.start[a] + int(np.argmax(yv[cat.start[a]:cat.start[a + 1]])) for a in range(cat.n_params)])
        S = np.flatnonzero(cat.stepped)
        pos = {int(o): i for i, o in enumerate(S)}
        nn = np.zeros(cat.n_params, int)
        vv = np.zeros(len(S)) if nv is None else np.asarray(v.value, float)
        ww = np.zeros(len(S)) if nv is None else np.asarray(w.value, float)
        for a, o in enumerate(opt):
            if cat.stepped[o]:
                nn[a] = int(np.clip(np.round(nv.value[pos[int(o)]]), cat.n_lo[o], cat.n_hi[o]))
        bound = float(getattr(prob.solver_stats.extra_stats, "mip_dual_bound", prob.value))
        part = None
        if z is not None:
            zv, sl = np.asarray(z.value), self.part_slot
            part = np.array([int(np.flatnonzero(sl == g)[np.argmax(zv[sl == g])]) for g in range(sl.max() + 1)])
        return MipOutcome(opt, nn, float(prob.value), min(bound, float(prob.value)), "optimal", dt, vv, ww, part=part)

    def _program(self, cost_cap):
        import cvxpy as cp
        import scipy.sparse as sp

        cat = self.cat
        M, Ka = len(cat.param), cat.n_params
        S = np.flatnonzero(cat.stepped)
        y = cp.Variable(M, boolean=True)
        one_hot = sp.csr_matrix((np.ones(M), (cat.param, np.arange(M))), shape=(Ka, M))
        cons = [one_hot @ y == 1]
        listed = ~cat.stepped
        u_listed = np.where(listed, (np.nan_to_num(cat.t) / cat.t_ref[cat.param]) ** 2, 0.0)
        U = sp.csr_matrix((u_listed, (cat.param, np.arange(M))), shape=(Ka, M)) @ y
        cost = np.where(listed, np.nan_to_num(cat.cost), 0.0) @ y
        nv = v = w = None
        if len(S):
            nv, v, w = cp.Variable(len(S), integer=True), cp.Variable(len(S)), cp.Variable(len(S))
            yS = y[S]
            cons += [nv >= cp.multiply(cat.n_lo[S], yS), nv <= cp.multiply(cat.n_hi[S], yS), v >= 0, w >= 0]
            I, Mv, alpha, c0, c1 = [], [], [], [], []
            for i, o in enumerate(S):
                st, a = cat.step[o], cat.param[o]
                single = cat.n_lo[o] == cat.n_hi[o]
                for m in sorted(self.chords[int(o)]):
                    I.append(i)
                    Mv.append(m)
                    alpha.append((st / cat.t_ref[a]) ** 2)
                    cm = float(cat.law[o].cost(m * st))
                    c0.append(cm)
                    c1.append(0.0 if single else float(cat.law[o].cost((m + 1) * st)) - cm)
            I, Mv, alpha, c0, c1 = map(np.asarray, (I, Mv, alpha, c0, c1))
            alpha = alpha / self._u_scale[S][I]  # v is the variance over its largest value (entries of order 1)
            E = sp.csr_matrix((np.ones(len(I)), (np.arange(len(I)), I)), shape=(len(I), len(S)))
            # chords through (m, f(m)) and (m + 1, f(m + 1)), perspective in the option's binary
            cons += [E @ v >= cp.multiply(alpha * (2 * Mv + 1), E @ nv) - cp.multiply(alpha * Mv * (Mv + 1), E @ yS),
                     E @ w >= cp.multiply(c0 - c1 * Mv, E @ yS) + cp.multiply(c1, E @ nv)]
            U = U + sp.csr_matrix((self._u_scale[S], (cat.param[S], np.arange(len(S)))), shape=(Ka, len(S))) @ v
            cost = cost + cp.sum(w)
        if cat.groups:
            g = cp.Variable(len(cat.groups), boolean=True)
            has = np.flatnonzero(cat.group >= 0)
            G = sp.csr_matrix((np.ones(len(has)), (np.arange(len(has)), cat.group[has])), shape=(len(has), len(cat.groups)))
            cons.append(y[has] <= G @ g)
            parts: dict = {}
            for gi, (part, _, _) in enumerate(cat.groups):
                parts.setdefault(part, []).append(gi)
            cons += [cp.sum(g[gs]) <= 1 for gs in parts.values() if len(gs) > 1]
            cost = cost + np.array([gr[2] for gr in cat.groups]) @ g
        z = None
        lhs = self.A @ U
        if self.part_slot is not None:
            Z = len(self.part_slot)
            z = cp.Variable(Z, boolean=True)
            cons.append(sp.csr_matrix((np.ones(Z), (self.part_slot, np.arange(Z)))) @ z == 1)
            cost = cost + self.part_cost @ z
            lhs = lhs + self.R @ z
        if len(self.s):
            cons.append(lhs <= self.s - ROW_MARGIN)
        if cost_cap is not None:
            cons.append(cost <= cost_cap)
        return cp.Problem(cp.Minimize(cost), cons), y, nv, v, w, z


def repair(cat: Catalogue, opt, n, violation, max_steps: int = 200):
    """A design near ``(opt, n)`` with ``violation(U) <= 0`` (vectorised over rows of ``U``), or None.

    Greedy: tighten one parameter a step (or to the next finer grade or class of its process) at a time, the one
    that removes the most violation per unit of cost. Returns ``(cost, opt, n)``."""
    opt, n = np.array(opt, int), np.array(n, int)
    for _ in range(max_steps):
        v0 = float(violation(cat.u_of(opt, n)[None])[0])
        if v0 <= 0:
            return cat.total_cost(opt, n), opt, n
        moves = []
        for a in range(cat.n_params):
            o = int(opt[a])
            if cat.stepped[o]:
                if n[a] > cat.n_lo[o]:
                    moves.append((a, o, n[a] - 1))
            else:
                finer = [q for q in range(cat.start[a], cat.start[a + 1]) if not cat.stepped[q]
                         and cat.group[q] == cat.group[o] and cat.t[q] < cat.t[o]]
                if finer:
                    moves.append((a, max(finer, key=lambda q: cat.t[q]), 0))
        if not moves:
            return None
        U = np.repeat(cat.u_of(opt, n)[None], len(moves), axis=0)
        dc = np.empty(len(moves))
        base = cat.costs_of(opt, n)
        for r, (a, o, k) in enumerate(moves):
            t = k * cat.step[o] if cat.stepped[o] else cat.t[o]
            U[r, a] = (t / cat.t_ref[a]) ** 2
            dc[r] = (float(cat.law[o].cost(t)) if cat.stepped[o] else cat.cost[o]) - base[a]
        gain = (v0 - violation(U)) / np.maximum(dc, 1e-12)
        a, o, k = moves[int(np.argmax(gain))]
        opt[a], n[a] = o, k
    return None
