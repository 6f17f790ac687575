"""Which effect: fit every candidate on training poses only, score it on held-out poses, select.

Held-out poses are the out-of-fold predictions of a *blocked* K-fold cross-validation within the training
file (every fit, including the registration, sees only the other folds; by default K contiguous blocks in
row/time order and, scored beside them, K contiguous regions of joint space -- random folds only on request,
see :func:`make_folds`) plus, when given, the separate test file (model fitted on the whole training file).
Each effect's variant (:func:`tolalloc.diagnose.effects.variants`) is chosen first on the training residual
(:func:`choose_variant`).

Scores are robust: 3-D held-out errors are clipped at 2.5 x the geometric model's median held-out error
(:func:`clip_level`). Significance: one-sided Wilcoxon signed-rank test on the per-pose differences of clipped
squared held-out error (base model - base + candidate). A candidate is *significant* when ``p < alpha / m``
(Bonferroni over the ``m`` applicable candidates) **and** it lowers the clipped held-out RMS
(:func:`robust_rms`) by at least ``min_gain`` (default 2 %). The significant candidate with the lowest clipped
held-out RMS is selected; the others are then tested on top of it (sequential forward selection, at most
``max_effects``: pairs where the data supports both), and every selected effect must finally still be significant
beside the others (backward elimination, :func:`_backward`). ``none`` when nothing is significant.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import wilcoxon

from tolalloc.diagnose.calibrate import Fit, fit_model, fixed_jacobian, select_columns
from tolalloc.diagnose.folds import CV_SCHEMES, fold_count, make_folds
from tolalloc.diagnose.effects import EFFECTS, applicable, effect_basis, effect_bases, effect_reference, variants
from tolalloc.diagnose.register import REGISTER_N, register_and_score, registration_split

__all__ = ["Candidate", "Stage", "Evaluation", "make_context", "make_folds", "fold_count", "choose_variant", "evaluate",
           "kept_basis", "score_test", "select_effects", "rms", "robust_rms", "clip_level", "error_stats", "CV_SCHEMES"]


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
    test_mm : array, shape (T, 3) or None  residuals on the test file (``refit``: scored poses only, (T - r, 3))
    test_pred_mm : array, shape (T, 3) or None  predictions on the test file (``refit``: in the re-registered frame)
    oof_joint_mm : array, shape (P, 3) or None  out-of-fold residuals of the joint-space blocks (``cv="blocked"``)
    """

    label: str
    effects: tuple
    fit: Fit
    param_names: tuple
    keep: np.ndarray
    oof_mm: np.ndarray
    test_mm: np.ndarray | None
    test_pred_mm: np.ndarray | None
    oof_joint_mm: np.ndarray | None = None

    @property
    def selection_mm(self) -> np.ndarray:
        """Residuals the selection scores: out-of-fold (time blocks, then joint-space blocks), then test."""
        parts = [self.oof_mm] + [a for a in (self.oof_joint_mm, self.test_mm) if a is not None]
        return np.concatenate(parts)

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
    robust_rms_mm: float = float("nan")
    variant: str = ""

    def to_dict(self) -> dict:
        return {"effect": self.effect, "heldout_rms_mm": self.heldout_rms_mm, "p_value": self.p_value,
                "cv_rms_mm": self.cv_rms_mm, "test_rms_mm": self.test_rms_mm, "gain_pct": self.gain_pct,
                "n_params": self.n_params, "significant": self.significant, "applicable": self.applicable,
                "reason": self.reason, "robust_rms_mm": self.robust_rms_mm, "variant": self.variant}


@dataclass(frozen=True, eq=False)
class Stage:
    """One step of the sequential selection: candidates tested on top of ``base``."""

    base: tuple
    base_rms_mm: float
    candidates: tuple
    selected: str | None
    removed: str | None = None  # backward step (:func:`_backward`): the effect dropped from ``base``, if any


def robust_rms(res: np.ndarray, clip_mm: float) -> float:
    """RMS of the 3-D error norms clipped at ``clip_mm`` [mm] (a Huber-type statistic outliers cannot dominate)."""
    d = np.minimum(np.linalg.norm(res, axis=1), clip_mm)
    return float(np.sqrt(np.mean(d ** 2))) if len(d) else float("nan")


def clip_level(res: np.ndarray) -> float:
    """Clip level of :func:`robust_rms`: 2.5 x the median 3-D error norm (~3.8 sigma for Gaussian noise) [mm]."""
    return float(max(2.5 * np.median(np.linalg.norm(res, axis=1)), 1e-6))


class _Context:
    """Training / test data, folds, chosen effect variants and effect bases shared by all evaluations."""

    def __init__(self, cal, train, test, folds, seed, test_frame, tol, cv="blocked", gear_ratio=None):
        self.cal, self.train, self.test, self.tol, self.test_frame = cal, train, test, tol, test_frame
        self.cv = cv
        self.J_fixed = fixed_jacobian(cal.geometric, train.q, train.xyz_mm)
        k = fold_count(folds, *self.J_fixed.shape)
        self.folds = make_folds(train, k, cv, seed)
        self.folds_joint = make_folds(train, k, "joint", seed) if cv == "blocked" else []
        self.bases, self.bases_test, self.reasons = {}, {}, {}
        t = cal.geometric.t_mm
        self.ref = effect_reference(train, gear_ratio)
        robot = cal.geometric.model.robot
        res = train.xyz_mm - cal.geometric.predict(train.q)  # the geometric fit's residual on these poses
        for e in EFFECTS:
            ok, why = applicable(e, train)
            names = [v for v in variants(e, train, self.ref) if test is None or _test_can_carry(e, v, test)]
            if ok and not names:
                ok, why = False, "the test file lacks the columns this effect needs (dir / temperature_c / time_s)"
            self.reasons[e] = why
            if ok:
                cands = effect_bases(e, robot, train, t, self.ref, names)
                self.bases[e] = choose_variant(cands, cal.geometric, self.J_fixed, res)
                self.ref["variants"][e] = self.bases[e].variant
                if test is not None:
                    self.bases_test[e] = align_basis(effect_basis(e, robot, test, t, self.ref), self.bases[e].names)


def align_basis(basis, names: tuple):
    """``basis`` with exactly the columns ``names`` of the training basis, in that order (zeros where the test poses
    do not excite a column, e.g. a joint whose gravity torque keeps its sign on the test file)."""
    pos = {nm: i for i, nm in enumerate(basis.names)}
    B = np.zeros(basis.B.shape[:2] + (len(names),))
    for i, nm in enumerate(names):
        if nm in pos:
            B[:, :, i] = basis.B[:, :, pos[nm]]
    return replace(basis, names=tuple(names), B=B)


def _test_can_carry(effect, variant, test) -> bool:
    if effect == "backlash" and variant == "approach":
        return test.direction is not None
    if effect == "thermal":
        need_T = not variant.startswith("warmup")
        need_t = variant != "temperature"
        return (not need_T or test.temperature_c is not None) and (not need_t or test.time_s is not None)
    return True


def choose_variant(cands: list, fit: Fit, J_fixed: np.ndarray, residual_mm: np.ndarray | None = None):
    """The variant whose columns best explain the geometric fit's training residual (BIC, winsorised residual).

    Linearised at the geometric fit: residual and effect columns are projected off the registration, offset
    and geometric columns ``J_fixed``; residual components beyond 3 robust sigma are clipped first, so a few
    outliers do not pick the variant. ``BIC = n log(RSS / (n - M)) + M log n`` with ``n`` the residual degrees
    of freedom (3P rows minus the fixed columns) and ``M`` the variant's columns: the noise variance is estimated
    from the degrees of freedom the variant leaves, so on few poses a many-column variant (e.g. two harmonics on
    every joint) cannot win by fitting the noise of a nearly interpolated residual.
    ``residual_mm`` (P, 3): the fit's residual on the poses of ``J_fixed`` (default ``fit.residual_mm``, when the
    fit was made on those very poses; a subsampled diagnosis passes the subsample's).
    """
    if len(cands) == 1:
        return cands[0]
    Q, _ = np.linalg.qr(J_fixed)
    r = (fit.residual_mm if residual_mm is None else residual_mm).ravel()
    r = r - Q @ (Q.T @ r)
    s = 1.4826 * np.median(np.abs(r - np.median(r)))
    r = np.clip(r, -3 * s, 3 * s)
    n = len(r) - Q.shape[1]  # residual degrees of freedom left by the fixed columns
    best, best_bic = cands[0], np.inf
    for c in cands:
        Jc = np.einsum("ij,pjm->pim", fit.R, c.B).reshape(len(r), -1)
        Jc = Jc - Q @ (Q.T @ Jc)
        beta, *_ = np.linalg.lstsq(Jc, r, rcond=1e-8)
        rss = float(np.sum((r - Jc @ beta) ** 2))
        M = np.linalg.matrix_rank(Jc, 1e-8 * max(1.0, np.abs(Jc).max()))
        bic = n * np.log(max(rss, 1e-300) / (n - M)) + M * np.log(n) if n - M > 0 else np.inf
        if bic < best_bic:
            best, best_bic = c, bic
    return best


def _stack(bases: dict, effects) -> tuple:
    if not effects:
        return None, ()
    B = np.concatenate([bases[e].B for e in effects], axis=2)
    names = tuple(f"{e}:{nm}" for e in effects for nm in bases[e].names)
    return B, names


def kept_basis(bases: dict, ev: Evaluation):
    """The effect columns ``ev`` kept, on the poses of ``bases`` (``ctx.bases`` or ``ctx.bases_test``), shape
    (P, 3, m) [mm per unit]; None for a model without effects."""
    B, _ = _stack(bases, ev.effects)
    return None if B is None else B[:, :, ev.keep]


def evaluate(ctx: _Context, effects: tuple = (), nominal: bool = False) -> Evaluation:
    """Fit a model on all training poses and on every CV fold; residuals on the held-out poses."""
    cal, train = ctx.cal, ctx.train
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
    warm = replace(full, beta=np.zeros(0))  # folds start from the full fit (same optimum, fewer iterations)
    oof = _out_of_fold(warm, q, xyz, geo, B, names, ctx.folds)
    oof_joint = _out_of_fold(warm, q, xyz, geo, B, names, ctx.folds_joint) if ctx.folds_joint else None
    test_res, test_pred = score_test(ctx, full, effects, keep)
    label = "nominal" if nominal else "+".join(("geometric", *effects))
    return Evaluation(label, tuple(effects), full, names, keep, oof, test_res, test_pred, oof_joint)


def score_test(ctx: _Context, full: Fit, effects: tuple, keep: np.ndarray):
    """Residuals and predictions of ``full`` on the test file (None, None without one).

    ``refit``: registered on ``ctx.registration.register_index`` and scored on the rest (residuals (T - r, 3),
    predictions in the re-registered frame); else residuals and predictions (T, 3) in the measurement frame.
    """
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
        reg = register_and_score(full, test.q, test.xyz_mm, extra, ctx.registration)
        return reg.residual_mm, reg.pred_mm
    return test.xyz_mm - test_pred, test_pred


def _out_of_fold(start, q, xyz, geo, B, names, folds) -> np.ndarray:
    """Residuals of every fold's poses under the model fitted on the other folds, shape (P, 3)."""
    oof = np.zeros_like(xyz)
    for f in folds:
        tr = np.setdiff1d(np.arange(len(q)), f)
        ff = fit_model(start, q[tr], xyz[tr], geo_index=geo, B=None if B is None else B[tr], effect_names=names)
        oof[f] = xyz[f] - ff.predict(q[f], None if B is None else B[f])
    return oof


def _pvalue(base: np.ndarray, cand: np.ndarray, clip_mm: float) -> float:
    """One-sided Wilcoxon signed-rank p-value that ``cand`` has smaller clipped 3-D errors than ``base``."""
    d = np.minimum(np.sum(base ** 2, axis=1), clip_mm ** 2) - np.minimum(np.sum(cand ** 2, axis=1), clip_mm ** 2)
    if np.allclose(d, 0):
        return 1.0
    return float(wilcoxon(d, alternative="greater").pvalue)


def _score(ctx, chosen, e, current, clip, m, alpha, min_gain):
    """Evaluate candidate ``e`` on top of ``chosen``; returns (Candidate, Evaluation)."""
    ev = evaluate(ctx, (*chosen, e))
    n_new = sum(nm.startswith(e + ":") for nm in ev.param_names)
    base_r = robust_rms(current.selection_mm, clip)
    r = robust_rms(ev.selection_mm, clip)
    p = _pvalue(current.selection_mm, ev.selection_mm, clip) if n_new else 1.0
    gain = 100.0 * (1.0 - r / base_r)
    sig = bool(n_new and p < alpha / m and gain >= 100.0 * min_gain)
    t_rms = rms(ev.test_mm) if ev.test_mm is not None else None
    cand = Candidate(e, True, "" if n_new else "not identifiable beside the geometric parameters", n_new,
                     ev.heldout_rms_mm, rms(ev.oof_mm), t_rms, p, gain, sig, r, ctx.bases[e].variant)
    return cand, ev


def select_effects(ctx: _Context, base_eval: Evaluation, *, alpha: float = 0.01, min_gain: float = 0.02,
                   max_effects: int = 3):
    """Sequential forward selection; returns (stages, evaluations by label, final evaluation).

    Scores use every held-out residual of :attr:`Evaluation.selection_mm`; the gain and the Wilcoxon test use
    3-D errors clipped at :func:`clip_level` of the geometric model's held-out errors (fixed for the whole
    selection), so a few gross outliers neither hide nor fake an effect.
    """
    evals = {base_eval.label: base_eval}
    stages = []
    current = base_eval
    chosen: tuple = ()
    clip = clip_level(base_eval.selection_mm)
    while len(chosen) < max_effects:
        cands, cand_evals = [], {}
        pool = [e for e in EFFECTS if e not in chosen]
        m = max(1, sum(e in ctx.bases for e in pool))
        for e in pool:
            if e not in ctx.bases:
                cands.append(Candidate(e, False, ctx.reasons[e], 0, float("nan"), float("nan"), None, 1.0, 0.0, False))
                continue
            cand, ev = _score(ctx, chosen, e, current, clip, m, alpha, min_gain)
            evals[ev.label] = cand_evals[e] = ev
            cands.append(cand)
        cands.sort(key=lambda c: (not c.applicable, c.robust_rms_mm if np.isfinite(c.robust_rms_mm) else np.inf))
        best = next((c for c in cands if c.significant), None)
        stages.append(Stage(chosen, current.heldout_rms_mm, tuple(cands), best.effect if best else None))
        if best is None:
            break
        chosen = (*chosen, best.effect)
        current = cand_evals[best.effect]
    current = _backward(ctx, current, evals, stages, clip, alpha, min_gain)
    return stages, evals, current


def _backward(ctx, current: Evaluation, evals: dict, stages: list, clip, alpha, min_gain) -> Evaluation:
    """Backward elimination after the forward steps: drop an effect the others have made redundant.

    Gravity-driven effects overlap (joint compliance ``c_j tau_j``, gravity-held backlash ``b_j sign(tau_j)``,
    beam sag): the first forward step may pick the one that best explains their *sum* as a proxy, and the
    true two are added after it. Each selected effect must therefore still pay its way beside the others:
    the full model has to beat the model without it by the forward rule (Wilcoxon ``p < alpha / m`` over the
    ``m`` selected effects, clipped gain >= ``min_gain``); else the weakest such effect is dropped (a
    :class:`Stage` with ``removed`` set), and the test is repeated on what is left. In such a stage each
    candidate's scores are those of the model *without* it, its gain what keeping it gains.
    """
    while len(current.effects) > 1:
        m, tests = len(current.effects), []
        for e in current.effects:
            rest = tuple(x for x in current.effects if x != e)
            label = "+".join(("geometric", *rest))
            ev = evals.get(label) or evaluate(ctx, rest)
            evals[label] = ev
            r, r_rest = robust_rms(current.selection_mm, clip), robust_rms(ev.selection_mm, clip)
            p = _pvalue(ev.selection_mm, current.selection_mm, clip)
            gain = 100.0 * (1.0 - r / r_rest)
            keep = bool(p < alpha / m and gain >= 100.0 * min_gain)
            n_e = sum(nm.startswith(e + ":") for nm in current.param_names)
            why = "backward step: " + ("" if keep else "not ") + "significant beside the others"
            t_rms = rms(ev.test_mm) if ev.test_mm is not None else None
            tests.append((gain, Candidate(e, True, why, n_e, ev.heldout_rms_mm, rms(ev.oof_mm), t_rms, p, gain, keep,
                                          r_rest, ctx.bases[e].variant), ev))
        gain, cand, ev = min(tests, key=lambda x: x[0])
        stages.append(Stage(current.effects, current.heldout_rms_mm, tuple(c for _, c, _ in tests), None,
                            None if cand.significant else cand.effect))
        if cand.significant:
            break
        current = ev
    return current


def make_context(cal, train, test=None, *, folds: int = 5, seed: int = 0, test_frame: str = "same",
                 tol: float = 1e-3, register_n: float = REGISTER_N, cv: str = "blocked",
                 gear_ratio=None) -> _Context:
    """Shared state of one diagnosis (folds, effect variants and bases; with ``test_frame='refit'`` the
    registration split).

    ``cv``: ``blocked`` (default: ``folds`` contiguous time blocks *and* ``folds`` joint-space blocks, both
    scored), ``time``, ``joint`` or ``random`` (see :func:`make_folds`). ``gear_ratio`` (n,): known gear
    ratios, enabling the motor-side transmission variant.
    """
    ctx = _Context(cal, train, test, folds, seed, test_frame, tol, cv, gear_ratio)
    ctx.registration = (registration_split(test.q, cal.geometric.model.robot.revolute_mask, register_n, seed)
                        if test is not None and test_frame == "refit" else None)
    return ctx

