"""Which effects: forward selection and backward elimination of the candidate effects on their held-out scores.

Every model is fitted and scored by :func:`.select.evaluate` (training file only, blocked cross-validation; the
test file stays sealed, see :mod:`.select`); this module decides on those scores.

Scores are robust: 3-D held-out errors are clipped at 2.5 x the geometric model's median held-out error
(:func:`.scores.clip_level`). Significance: one-sided Wilcoxon signed-rank test on the per-pose differences of clipped
squared held-out error (base model - base + candidate), one difference per pose (the mean over the two CV
schemes, which score the same poses). A candidate is *significant* when ``p < alpha / m``
(Bonferroni over the ``m`` applicable candidates) **and** it lowers the clipped held-out RMS
(:func:`.scores.robust_rms`) by at least ``min_gain`` (default 2 %; more on a small file:
:func:`.calibrate.small_file_min_gain`), and its unclipped out-of-fold RMS stays within
:data:`BLOWUP_RATIO` x the base model's (clipping must not hide held-out predictions that blow up). The significant
candidate with the lowest clipped held-out RMS is selected; the others are then tested on top of it (sequential
forward selection, at most ``max_effects``: pairs where the data supports both), and every selected effect must
finally still be significant beside the others (backward elimination, :func:`_backward`). ``none`` when nothing is
significant.

The Bonferroni factor pays for choosing among the ``m`` candidates on the data. At the first step, when no
candidate passes it and the model evidence singles one family out (:func:`.families.evidence_leader`), that family
is the one hypothesis left: it is significant at ``p < alpha`` alone when it also lowers the clipped held-out RMS by
the practical margin (:data:`.verdict.PRACTICAL_MARGIN`, 5 %) -- an effect that is decisive in the evidence and
clearly helpful out of fold, but not significant over six candidates, is named rather than called ``none``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from tolalloc.diagnose.effects import EFFECTS
from tolalloc.diagnose.families import evidence_leader, evidence_pick
from tolalloc.diagnose.scores import Candidate, Evaluation, Stage, clip_level, paired_pvalue, rms, robust_rms
from tolalloc.diagnose.select import _Context, evaluate, rows_problem
from tolalloc.diagnose.verdict import PRACTICAL_MARGIN

__all__ = ["select_effects", "BLOWUP_RATIO"]

#: A candidate whose unclipped out-of-fold RMS exceeds this multiple of the base model's is not significant, whatever
#: its clipped score: the clipping that keeps gross measurement errors from deciding would hide predictions that blow up.
BLOWUP_RATIO = 1.5


def _n_params(ctx, effects) -> tuple[int, int]:
    """Parameters a model with ``effects`` asks of the training data: (full fit, each fold's fit without the
    geometric and ridge-regularised ones) -- see :func:`.select.rows_problem`."""
    free = 9
    ridge = 0
    for e in effects:
        b = ctx.bases[e]
        w = np.zeros(b.B.shape[2]) if getattr(b, "prior_w", None) is None else np.asarray(b.prior_w)
        free += int(np.sum(w == 0))
        ridge += int(np.ceil(b.prior_dof or 0.0)) if w.any() else 0
    return free + len(ctx.cal.geometric.geo_index) + ridge, free


def _score(ctx, chosen, e, current, clip, m, alpha, min_gain):
    """Evaluate candidate ``e`` on top of ``chosen``; returns (Candidate, Evaluation or None)."""
    why = rows_problem(ctx, *_n_params(ctx, (*chosen, e)))
    if why is not None:
        return Candidate(e, False, why, 0, float("nan"), float("nan"), 1.0, 0.0, False), None
    ev = evaluate(ctx, (*chosen, e))
    n_new = sum(nm.startswith(e + ":") for nm in ev.param_names)
    base_r = robust_rms(current.selection_mm, clip)
    r = robust_rms(ev.selection_mm, clip)
    p = paired_pvalue(current.selection_stack, ev.selection_stack, clip) if n_new else 1.0
    gain = 100.0 * (1.0 - r / base_r)
    plain, base_plain = rms(ev.selection_mm), rms(current.selection_mm)
    reason = "" if n_new else "not identifiable beside the geometric parameters"
    if plain > BLOWUP_RATIO * base_plain:
        reason = (f"its unclipped out-of-fold RMS {plain:.4g} mm is {plain / base_plain:.3g} x the base model's "
                  f"{base_plain:.4g} mm: some held-out predictions blow up (a fit the poses do not hold)")
    sig = bool(n_new and not reason and p < alpha / m and gain >= 100.0 * min_gain)
    cand = Candidate(e, True, reason, n_new, ev.cv_rms_mm, rms(ev.oof_mm), p, gain, sig, r,
                     ctx.bases[e].variant)
    return cand, ev


def select_effects(ctx: _Context, base_eval: Evaluation, *, alpha: float = 0.01, min_gain: float = 0.02,
                   max_effects: int = 3, logml: dict | None = None):
    """Sequential forward selection; returns (stages, evaluations by label, final evaluation).

    ``logml``: ``{family: log marginal likelihood}`` of the geometric residual (:func:`.families.family_log_evidence`),
    which decides ties of the first step; None or empty: the lowest clipped held-out RMS alone.

    Scores use the training file's out-of-fold residuals (:attr:`Evaluation.selection_mm`); the gain and the Wilcoxon test use
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
                cands.append(Candidate(e, False, ctx.reasons[e], 0, float("nan"), float("nan"), 1.0, 0.0, False))
                continue
            cand, ev = _score(ctx, chosen, e, current, clip, m, alpha, min_gain)
            if ev is not None:
                evals[ev.label] = cand_evals[e] = ev
            cands.append(cand)
        cands.sort(key=lambda c: (not c.applicable, c.robust_rms_mm if np.isfinite(c.robust_rms_mm) else np.inf))
        leader = evidence_leader(logml or {})[0] if not chosen else None
        if not chosen and not any(c.significant for c in cands):
            cands = [_evidence_led(c, leader, alpha, min_gain) for c in cands]
        best = next((c for c in cands if c.significant), None)
        if not chosen:
            best = evidence_pick(cands, logml or {}, PRACTICAL_MARGIN) or best
        stages.append(Stage(chosen, current.cv_rms_mm, tuple(cands), best.effect if best else None, n_tests=m,
                            leader=leader, n_poses=len(current.oof_mm)))
        if best is None:
            break
        chosen = (*chosen, best.effect)
        current = cand_evals[best.effect]
    current = _backward(ctx, current, evals, stages, clip, alpha, min_gain)
    return stages, evals, current


def _evidence_led(c: Candidate, leader: str | None, alpha: float, min_gain: float = 0.0) -> Candidate:
    """``c`` made significant when it is ``leader``, the family the evidence singles out
    (:func:`.families.evidence_leader`), and passes the uncorrected test (``p < alpha``, clipped gain of at least the
    practical margin and of the step's ``min_gain``, no other reason against it); else ``c``."""
    if (c.effect != leader or not c.applicable or c.reason or not c.n_params or not c.p_value < alpha
            or not c.gain_pct >= 100.0 * max(PRACTICAL_MARGIN, min_gain)):
        return c
    return replace(c, significant=True, evidence_led=True)


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
            p = paired_pvalue(ev.selection_stack, current.selection_stack, clip)
            gain = 100.0 * (1.0 - r / r_rest)
            keep = bool(p < alpha / m and gain >= 100.0 * min_gain)
            n_e = sum(nm.startswith(e + ":") for nm in current.param_names)
            why = "backward step: " + ("" if keep else "not ") + "significant beside the others"
            tests.append((gain, Candidate(e, True, why, n_e, ev.cv_rms_mm, rms(ev.oof_mm), p, gain, keep,
                                          r_rest, ctx.bases[e].variant), ev))
        gain, cand, ev = min(tests, key=lambda x: x[0])
        stages.append(Stage(current.effects, current.cv_rms_mm, tuple(c for _, c, _ in tests), None,
                            None if cand.significant else cand.effect, n_tests=m))
        if cand.significant:
            break
        current = ev
    return current
