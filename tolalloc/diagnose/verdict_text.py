"""The verdict and its reasons in words (:func:`verdict_of`), from the selection's stages and the checks of
:mod:`.verdict`."""

from __future__ import annotations

import numpy as np

from tolalloc.physics.thermal import is_clock_variant, is_measurement_variant
from tolalloc.physics.thermal_history import time_problem
from tolalloc.diagnose.families import DECISIVE_BAYES_FACTOR, LEADING_BAYES_FACTOR
from tolalloc.diagnose.scores import poses_to_pass, scheme_text
from tolalloc.diagnose.verdict import PRACTICAL_MARGIN, Verdict, tied

__all__ = ["verdict_of", "input_notes", "further_ties"]


def input_notes(ctx, stages: list) -> tuple[list, list]:
    """What could not be tested and why: (reason lines, names of the effects or variants not tested).

    Bad or missing columns, too few rows, and selected effects the test file cannot carry (their displacement is
    left out of its predictions, so its figures do not judge them)."""
    out, untested = [], []
    out += list(getattr(ctx, "robust_notes", ()))
    out += [n.text for n in getattr(ctx, "ratio_notes", ()) if n.telling]
    why_t = time_problem(ctx.train.time_s)
    if why_t is not None and "thermal" in ctx.bases:
        out.append(f"thermal: only the temperature-driven variant was tested; the time-driven ones (warm-up, motion "
                   f"history, lag of the temperature log) were skipped: {why_t}")
        untested.append("thermal (time-driven)")
    if ctx.test is not None and ctx.test.time_s is not None and time_problem(ctx.test.time_s) is not None:
        out.append(f"test file: {time_problem(ctx.test.time_s)}")
    if stages:
        skipped = [c for c in stages[0].candidates if not c.applicable]
        out += [f"{c.effect} not tested: {c.reason}" for c in skipped]
        untested += [c.effect for c in skipped]
    for e, why in getattr(ctx, "untestable", {}).items():
        out.append(f"{e} ({ctx.bases[e].variant}) was judged on the training file only: {why}; on the test poses its "
                   "displacement is taken as 0, so the test figures do not judge it")
    return out, untested


def _selected_line(stages: list, e: str, effects: tuple, scheme: str = "time and joint-space blocks",
                   min_gain: float = 0.0) -> str:
    """Why ``e`` is in the final model ``effects``: its forward step or, when that step's base holds an effect the
    backward elimination removed since, the backward test of keeping it beside the others (or, for the last effect
    left, its out-of-fold RMS against the geometric model's)."""
    fwd, c = _forward(stages, e)
    if fwd is None:
        return f"{e} was selected"
    if set(fwd.base) <= set(effects):
        base = "+".join(("geometric", *fwd.base))
        led = (f"; tested alone, at alpha without the factor for {fwd.n_tests} candidates and with a "
               f"{100 * max(PRACTICAL_MARGIN, min_gain):.3g} % minimum gain: the model evidence singles it out, a Bayes "
               f"factor of at least {LEADING_BAYES_FACTOR:g} against no effect and every other family"
               ) if c.evidence_led else ""
        return (f"{e} ({c.variant}) lowers the out-of-fold RMS of the training file ({scheme}) from "
                f"{fwd.base_rms_mm:.4g} ({base}) to {c.heldout_rms_mm:.4g} mm (clipped gain {c.gain_pct:+.1f} %, "
                f"p = {c.p_value:.2g}{led})" + _instrument(c.variant) + _clock(e, c.variant))
    back = [st for st in stages if st.selected is None and st.removed is None and tuple(st.base) == tuple(effects)]
    if back and len(effects) > 1:
        st = back[-1]
        k = next(k for k in st.candidates if k.effect == e)
        rest = "+".join(("geometric", *(x for x in effects if x != e)))
        return (f"{e} ({c.variant}) lowers the out-of-fold RMS of the training file ({scheme}) from "
                f"{k.heldout_rms_mm:.4g} ({rest}) to {st.base_rms_mm:.4g} mm beside the others (clipped gain "
                f"{k.gain_pct:+.1f} %, p = {k.p_value:.2g})")
    removed = [st for st in stages if st.removed is not None]
    last = removed[-1]
    final_rms = next(k.heldout_rms_mm for k in last.candidates if k.effect == last.removed)
    return (f"{e} ({c.variant}) lowers the out-of-fold RMS of the training file ({scheme}) from "
            f"{stages[0].base_rms_mm:.4g} (geometric) to {final_rms:.4g} mm; the backward elimination removed "
            f"{', '.join(st.removed for st in removed)} (not significant beside it)")


def _instrument(variant: str) -> str:
    """What a variant with a drift of the measuring frame means, or an empty string."""
    if not is_measurement_variant(variant):
        return ""
    return ("; its drift_ columns are a translation common to every pose: the measuring frame and the robot's base "
            "drift apart (the instrument warming up, its stand or the robot's pedestal settling), the robot relative "
            "to its own base unchanged -- base-frame predictions and compensation leave them out, tracker-frame "
            "predictions keep them")


def _clock(effect: str, variant: str) -> str:
    """What a thermal variant driven by the time alone can and cannot tell, or an empty string."""
    if effect != "thermal" or not variant or not is_clock_variant(variant):
        return ""
    return ("; its driver is the time since the session's start alone (no logged temperature, motion or load "
            "enters it): a warm-up or cool-down of the structure fits, and so would any slow process with the same "
            "time course (creep, a leak, a settling support), and, roughly, a step at a pause between blocks (a "
            "joint slipping at a stop, a base shifted by a collision, a screw loosening) -- check the cause before "
            "compensating it as heat")


def _best_line(stages: list, alpha: float, min_gain: float) -> str:
    """Why no candidate was selected, naming the criterion the best one failed."""
    if not stages:
        return "no candidate was tested"
    cands = [c for c in stages[0].candidates if c.applicable]
    if not cands:
        return "no candidate effect could be tested"
    c, level = cands[0], alpha / max(1, stages[0].n_tests)
    failed = []
    if c.reason:
        failed.append(c.reason)
    if not c.gain_pct >= 100.0 * min_gain:
        failed.append(f"its clipped gain {c.gain_pct:+.1f} % is below the minimum {100.0 * min_gain:.3g} %")
    if not c.p_value < level:
        failed.append(_p_line(c, stages[0], alpha, level, min_gain))
    return (f"no candidate effect is selected; the best, {c.effect} ({c.variant}), fails: " + "; ".join(failed)
            if failed else f"no candidate effect is selected; the best is {c.effect}")


def _p_line(c, stage, alpha: float, level: float, min_gain: float) -> str:
    """The p-value criterion the best candidate failed, with the level it was held to and, where its gain would count,
    roughly how many training poses would make it pass."""
    lead = c.effect == stage.leader and alpha > level
    out = (f"its p-value {c.p_value:.2g} is not below the level {level:.2g} (alpha {alpha:g} over {stage.n_tests} "
           "candidates)" + (f", nor below {alpha:g}, the level of the family the model evidence singles out"
                            if lead else ""))
    need = poses_to_pass(c.p_value, alpha if lead else level, stage.n_poses)
    if need is not None and c.gain_pct >= 100.0 * max(min_gain, PRACTICAL_MARGIN) and need > stage.n_poses:
        out += (f"; with the same gain per pose, about {need} training poses (now {stage.n_poses}) would pass it at "
                "80 % power (a rough extrapolation)")
    return out


def _pair_line(c) -> str:
    return (f"{c.effect} and {c.alternative} in its place explain the training file within the practical margin: "
            f"clipped out-of-fold RMS of {c.alternative} {c.excess_pct:+.1f} % against {c.effect} (margin "
            f"{c.margin_pct:g} %; unclipped {c.rms_mm:.4g} vs {c.alternative_rms_mm:.4g} mm)")


def _separated_line(c) -> str:
    if c.by_evidence:
        return (f"{c.effect} is named before {c.alternative} in its place: their clipped out-of-fold RMS lie within "
                f"the practical margin ({c.alternative} {c.excess_pct:+.1f} %, margin {c.margin_pct:g} %), but the "
                f"model evidence favours {c.effect} by a Bayes factor of {c.bayes_factor:.3g} (decisive from "
                f"{DECISIVE_BAYES_FACTOR:g})")
    return (f"{c.effect} beats {c.alternative} in its place: {c.alternative}'s clipped out-of-fold RMS is "
            f"{c.excess_pct:+.1f} % larger, beyond the practical margin of {c.margin_pct:g} %")


def verdict_of(ctx, stages: list, final, fallback, comparisons: tuple, inconclusive: list, fallback_msgs,
               safe: str, suggestions, alpha: float = 0.01, min_gain: float = 0.02) -> Verdict:
    """The :class:`~tolalloc.diagnose.verdict.Verdict` (precedence: inconclusive, none, ambiguous, effect)."""
    notes, untested = input_notes(ctx, stages)
    kw = dict(selected=tuple(final.effects), untested=tuple(untested))
    if inconclusive:
        picked = [f"the selection on the training file chose {'+'.join(final.effects)}; not claimed"] \
            if final.effects else []
        return Verdict("inconclusive", (), tuple(inconclusive + picked + notes), safe, comparisons, **kw)
    if not final.effects and stages and not any(c.applicable for c in stages[0].candidates):
        first = ["no candidate effect could be tested on this training file (reasons below): the data cannot tell "
                 "whether an unmodelled effect is present", *fallback_msgs]
        return Verdict("inconclusive", (), tuple(first + notes), safe, comparisons, **kw)
    if not final.effects:
        first = list(fallback_msgs) if fallback else [_best_line(stages, alpha, min_gain)]
        return Verdict("none", (), tuple(first + notes), safe, comparisons, **kw)
    amb = tied(comparisons)
    scheme = scheme_text(getattr(ctx, "cv", "blocked"))
    sel = [_selected_line(stages, e, final.effects, scheme, min_gain) for e in final.effects]
    further = further_ties(stages, final.effects, amb)
    if amb and len(further) < len(amb):
        names = []
        for e in final.effects:
            names += [x for x in (e, *[c.alternative for c in amb if c.effect == e]) if x not in names]
        lines = [_pair_line(c) for c in amb] + sel + _suggestion_lines(suggestions)
        return Verdict("ambiguous", tuple(names), tuple(lines + notes), safe, comparisons, suggestions, **kw)
    sep = [_separated_line(c) for c in comparisons if c.separable]
    unnamed = sorted({c.effect for c in further}, key=final.effects.index)
    big = tuple(e for e in unnamed if _gain_of(stages, e) >= further[0].margin_pct)
    lines = [_further_line(stages, e, [c for c in further if c.effect == e]) for e in unnamed]
    lines += _suggestion_lines(suggestions) if big else []
    named = tuple(e for e in final.effects if e not in unnamed)
    return Verdict("effect", named, tuple(sel + sep + lines + notes), safe, comparisons,
                   suggestions if big else None, further=big, **kw)


def _suggestion_lines(suggestions) -> list:
    """The line pointing at the poses that would separate tied families (none without suggestions)."""
    if suggestions is None or not len(suggestions):
        return []
    out_n = int(suggestions["outside_training"].sum())
    return ["poses that would separate them: suggested_poses (where the two fitted models' predictions differ most, "
            f"up to {suggestions['predicted_difference_mm'].max():.3g} mm)"
            + (f"; {out_n} of {len(suggestions)} lie outside the training data, where both fits extrapolate (column "
               "joints_outside_training_range: the joints to move beyond their training range)" if out_n else "")]


def _further_line(stages: list, e: str, ties: list) -> str:
    """Why the tied later effect ``e`` is kept in the final model without its family being claimed."""
    gain, margin = _gain_of(stages, e), ties[0].margin_pct
    alts = " or ".join(f"{c.alternative} ({c.excess_pct:+.1f} %)" for c in ties)
    if gain < margin:
        return (f"{e} adds a gain below the practical margin ({gain:+.1f} % < {margin:g} %) and the data cannot tell "
                f"it from {' or '.join(c.alternative for c in ties)} in its place: a minor further effect of an unnamed "
                f"family, kept in the final model, not claimed")
    return (f"{e} adds a further gain of {gain:+.1f} % after the clear first effect, but {alts} in its place explains "
            f"the training file within the practical margin of {margin:g} %: a further effect whose family the data "
            f"cannot tell, kept in the final model (as {e}), its family not claimed")


def _forward(stages: list, e: str) -> tuple:
    """The forward step that selected ``e`` and ``e``'s candidate there, or ``(None, None)``."""
    fwd = next((st for st in stages if st.selected == e), None)
    return fwd, None if fwd is None else next(c for c in fwd.candidates if c.effect == e)


def _gain_of(stages: list, e: str) -> float:
    """The clipped out-of-fold gain [%] of ``e`` at the forward step that selected it (inf when it has none)."""
    c = _forward(stages, e)[1]
    return np.inf if c is None else float(c.gain_pct)


def further_ties(stages: list, effects: tuple, amb: list) -> list:
    """The tied comparisons ``amb`` that leave the verdict ``effect``.

    A selected effect is *clear* when it has no tied alternative and a gain at its step of at least the practical
    margin. When the first selected effect of the final model (in the order of the forward steps) is clear, every tie
    is on a later effect: the clear effects are named and each tied one is a further effect whose family the data
    cannot tell. Otherwise, beside any clear effect, only the ties of *minor* effects (own gain below the margin, so
    that leaving them out is itself within the margin) leave the verdict ``effect``."""
    if not amb:
        return []
    margin = amb[0].margin_pct
    tied_effects = {c.effect for c in amb}
    clear = [e for e in effects if e not in tied_effects and _gain_of(stages, e) >= margin]
    if not clear:
        return []
    order = [st.selected for st in stages if st.selected in effects]
    if order and order[0] in clear:
        return list(amb)
    return [c for c in amb if _gain_of(stages, c.effect) < margin]
