"""Which effect: fit every candidate on training poses only, score it on held-out poses, select.

Held-out poses are the out-of-fold predictions of a K-fold cross-validation within the training file
(every fit, including the registration, sees only the other folds) plus, when given, the separate test
file (model fitted on the whole training file). A candidate's score is the RMS of the 3-D held-out error.

Significance: one-sided Wilcoxon signed-rank test on the per-pose differences of squared held-out error
(base model - base + candidate). A candidate is *significant* when ``p < alpha / m`` (Bonferroni over the
``m`` applicable candidates) **and** it lowers the held-out RMS by at least ``min_gain`` (default 2 %).
The significant candidate with the lowest held-out RMS is selected; the others are then tested on top of
it (sequential forward selection, at most ``max_effects``). ``none`` when nothing is significant.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import wilcoxon

from tolalloc.diagnose.calibrate import Fit, fit_model, fixed_jacobian, kabsch, select_columns
from tolalloc.diagnose.effects import EFFECTS, applicable, effect_basis, effect_reference

__all__ = ["Candidate", "Stage", "Evaluation", "make_context", "evaluate", "score_test", "select_effects", "rms",
           "error_stats"]


def rms(res: np.ndarray) -> float:
    """RMS of the 3-D error [mm] of residuals shape (P, 3)."""
    return float(np.sqrt(np.mean(np.sum(res ** 2, axis=1)))) if len(res) else float("nan")


def error_stats(res: np.ndarray) -> dict:
    """RMS, 95th percentile and max of the 3-D error norm [mm]."""
    d = np.linalg.norm(res, axis=1)
    return {"rms_mm": rms(res), "p95_mm": float(np.percentile(d, 95)), "max_mm": float(d.max()),
            "mean_mm": float(d.mean())}


@dataclass(frozen=True, eq=False)
class Evaluation:
    """One model (registration + offset [+ geometry] [+ effects]) fitted and scored on held-out poses.

    Attributes
    ----------
    label : str                  ``nominal``, ``geometric`` or ``geometric+effect+...``
    effects : tuple of str
    fit : Fit                    fitted on all training poses
    param_names : tuple of str   fitted (identifiable) effect parameters
    keep : array of int          their columns in the concatenated basis
    oof_mm : array, shape (P, 3)         out-of-fold residuals of the training poses (measured - predicted)
    test_mm : array, shape (T, 3) or None  residuals on the test file
    test_pred_mm : array, shape (T, 3) or None  predictions on the test file (measurement frame)
    """

    label: str
    effects: tuple
    fit: Fit
    param_names: tuple
    keep: np.ndarray
    oof_mm: np.ndarray
    test_mm: np.ndarray | None
    test_pred_mm: np.ndarray | None

    @property
    def heldout_mm(self) -> np.ndarray:
        """All held-out residuals: out-of-fold, then test, shape (P + T, 3)."""
        return self.oof_mm if self.test_mm is None else np.concatenate([self.oof_mm, self.test_mm])

    @property
    def heldout_rms_mm(self) -> float:
        return rms(self.heldout_mm)


@dataclass(frozen=True, eq=False)
class Candidate:
    """Score of one candidate effect on top of a base model."""

    effect: str
    applicable: bool
    reason: str
    n_params: int
    heldout_rms_mm: float
    cv_rms_mm: float
    test_rms_mm: float | None
    p_value: float
    gain_pct: float
    significant: bool

    def to_dict(self) -> dict:
        return {"effect": self.effect, "heldout_rms_mm": self.heldout_rms_mm, "p_value": self.p_value,
                "cv_rms_mm": self.cv_rms_mm, "test_rms_mm": self.test_rms_mm, "gain_pct": self.gain_pct,
                "n_params": self.n_params, "significant": self.significant, "applicable": self.applicable,
                "reason": self.reason}


@dataclass(frozen=True, eq=False)
class Stage:
    """One step of the sequential selection: candidates tested on top of ``base``."""

    base: tuple
    base_rms_mm: float
    candidates: tuple
    selected: str | None


class _Context:
    """Training / test data, folds and effect bases shared by all evaluations."""

    def __init__(self, cal, train, test, folds, seed, test_frame, tol):
        self.cal, self.train, self.test, self.tol, self.test_frame = cal, train, test, tol, test_frame
        P = train.n_poses
        perm = np.random.default_rng(seed).permutation(P)
        self.folds = [np.sort(f) for f in np.array_split(perm, min(folds, P))]
        self.bases, self.bases_test, self.reasons = {}, {}, {}
        t = cal.geometric.t_mm
        self.ref = effect_reference(train)
        robot = cal.geometric.model.robot
        for e in EFFECTS:
            ok, why = applicable(e, train)
            if ok and test is not None and e == "backlash" and test.direction is None:
                ok, why = False, "test file has no dir columns"
            if ok and test is not None and e == "thermal" and test.temperature_c is None:
                ok, why = False, "test file has no temperature_c column"
            self.reasons[e] = why
            if ok:
                self.bases[e] = effect_basis(e, robot, train, t, self.ref)
                if test is not None:
                    self.bases_test[e] = effect_basis(e, robot, test, t, self.ref)
        self.J_fixed = fixed_jacobian(cal.geometric, train.q, train.xyz_mm)


def _stack(bases: dict, effects) -> tuple:
    if not effects:
        return None, ()
    B = np.concatenate([bases[e].B for e in effects], axis=2)
    names = tuple(f"{e}:{nm}" for e in effects for nm in bases[e].names)
    return B, names


def _refit_frame(fit: Fit, q, xyz, extra, seed=0):
    """Two-fold re-registration on a test set in another frame: residuals of each half with the frame of the other."""
    res = np.zeros_like(xyz)
    halves = np.array_split(np.random.default_rng(seed).permutation(len(q)), 2)
    for a, b in ((halves[0], halves[1]), (halves[1], halves[0])):
        base = fit.base_points(q[b]) + extra[b]
        R, p = kabsch(base, xyz[b])
        start = replace(fit, R=R, p_mm=p)
        f = fit_model(start, q[b], xyz[b], geo_index=np.zeros(0, int), extra=extra[b])
        res[a] = xyz[a] - _points_with(f, q[a], extra[a])
    return res


def _points_with(f: Fit, q, extra):
    return (f.base_points(q) + extra) @ f.R.T + f.p_mm


def evaluate(ctx: _Context, effects: tuple = (), nominal: bool = False) -> Evaluation:
    """Fit a model on all training poses and on every CV fold; residuals on the held-out poses."""
    cal, train, test = ctx.cal, ctx.train, ctx.test
    q, xyz = train.q, train.xyz_mm
    start = cal.nominal if nominal else cal.geometric
    geo = np.zeros(0, int) if nominal else cal.geometric.geo_index
    B, names = _stack(ctx.bases, effects)
    keep = np.zeros(0, int)
    if B is not None:
        Jc = np.einsum("ij,pjm->pim", start.R, B).reshape(3 * len(q), -1)
        keep, *_ = select_columns(ctx.J_fixed, Jc, ctx.tol)
        B = B[:, :, keep]
        names = tuple(names[k] for k in keep)
    full = fit_model(start, q, xyz, geo_index=geo, B=B, effect_names=names)
    oof = np.zeros_like(xyz)
    for f in ctx.folds:
        tr = np.setdiff1d(np.arange(len(q)), f)
        ff = fit_model(start, q[tr], xyz[tr], geo_index=geo, B=None if B is None else B[tr], effect_names=names)
        oof[f] = xyz[f] - ff.predict(q[f], None if B is None else B[f])
    test_res, test_pred = score_test(ctx, full, effects, keep)
    label = "nominal" if nominal else "+".join(("geometric", *effects))
    return Evaluation(label, tuple(effects), full, names, keep, oof, test_res, test_pred)


def score_test(ctx: _Context, full: Fit, effects: tuple, keep: np.ndarray):
    """Residuals and predictions (T, 3) of ``full`` on the test file (None, None without one)."""
    test = ctx.test
    if test is None:
        return None, None
    Bt = None
    if effects:
        Bt, _ = _stack(ctx.bases_test, effects)
        Bt = Bt[:, :, keep]
    test_pred = full.predict(test.q, Bt)
    if ctx.test_frame == "refit":
        extra = np.zeros((test.n_poses, 3)) if Bt is None else Bt @ full.beta
        return _refit_frame(full, test.q, test.xyz_mm, extra), test_pred
    return test.xyz_mm - test_pred, test_pred


def _pvalue(base: np.ndarray, cand: np.ndarray) -> float:
    d = np.sum(base ** 2, axis=1) - np.sum(cand ** 2, axis=1)
    if np.allclose(d, 0):
        return 1.0
    return float(wilcoxon(d, alternative="greater").pvalue)


def select_effects(ctx: _Context, base_eval: Evaluation, *, alpha: float = 0.01, min_gain: float = 0.02,
                   max_effects: int = 3):
    """Sequential forward selection; returns (stages, evaluations by label, final evaluation)."""
    evals = {base_eval.label: base_eval}
    stages = []
    current = base_eval
    chosen: tuple = ()
    while len(chosen) < max_effects:
        cands, cand_evals = [], {}
        pool = [e for e in EFFECTS if e not in chosen]
        m = max(1, sum(e in ctx.bases for e in pool))
        base_rms = current.heldout_rms_mm
        for e in pool:
            if e not in ctx.bases:
                cands.append(Candidate(e, False, ctx.reasons[e], 0, float("nan"), float("nan"), None, 1.0, 0.0, False))
                continue
            ev = evaluate(ctx, (*chosen, e))
            evals[ev.label] = ev
            cand_evals[e] = ev
            n_new = sum(nm.startswith(e + ":") for nm in ev.param_names)
            h = ev.heldout_rms_mm
            p = _pvalue(current.heldout_mm, ev.heldout_mm) if n_new else 1.0
            gain = 100.0 * (1.0 - h / base_rms)
            sig = bool(n_new and p < alpha / m and gain >= 100.0 * min_gain)
            t_rms = rms(ev.test_mm) if ev.test_mm is not None else None
            cands.append(Candidate(e, True, "" if n_new else "not identifiable beside the geometric parameters",
                                   n_new, h, rms(ev.oof_mm), t_rms, p, gain, sig))
        cands.sort(key=lambda c: (not c.applicable, c.heldout_rms_mm if np.isfinite(c.heldout_rms_mm) else np.inf))
        best = next((c for c in cands if c.significant), None)
        stages.append(Stage(chosen, base_rms, tuple(cands), best.effect if best else None))
        if best is None:
            break
        chosen = (*chosen, best.effect)
        current = cand_evals[best.effect]
    return stages, evals, current


def make_context(cal, train, test=None, *, folds: int = 5, seed: int = 0, test_frame: str = "same",
                 tol: float = 1e-3) -> _Context:
    """Shared state of one diagnosis (folds, effect bases)."""
    return _Context(cal, train, test, folds, seed, test_frame, tol)

