"""The verdict and its reasons in words (:func:`verdict_of`), from the selection's stages and the checks of
:mod:`.verdict`."""

from __future__ import annotations

from tolalloc.diagnose.thermal import time_problem
from tolalloc.diagnose.verdict import Verdict

__all__ = ["verdict_of", "input_notes"]


def input_notes(ctx, stages: list) -> list:
    """What could not be tested and why (bad or missing columns, too few rows), as reason lines."""
    out = []
    why_t = time_problem(ctx.train.time_s)
    if why_t is not None and "thermal" in ctx.bases:
        out.append(f"thermal: only the temperature-driven variant was tested; the time-driven ones (warm-up, motion "
                   f"history, lag of the temperature log) were skipped: {why_t}")
    if ctx.test is not None and ctx.test.time_s is not None and time_problem(ctx.test.time_s) is not None:
        out.append(f"test file: {time_problem(ctx.test.time_s)}")
    if stages:
        out += [f"{c.effect} not tested: {c.reason}" for c in stages[0].candidates if not c.applicable]
    return out


def _selected_line(stages: list, e: str) -> str:
    for st in stages:
        if st.selected == e:
            c = next(c for c in st.candidates if c.effect == e)
            base = "+".join(("geometric", *st.base))
            return (f"{e} ({c.variant}) lowers the out-of-fold RMS of the training file from {st.base_rms_mm:.4g} "
                    f"({base}) to {c.heldout_rms_mm:.4g} mm (clipped gain {c.gain_pct:+.1f} %, p = {c.p_value:.2g})")
    return f"{e} was selected"


def _best_line(stages: list) -> str:
    if not stages:
        return "no candidate was tested"
    cands = [c for c in stages[0].candidates if c.applicable]
    if not cands:
        return "no candidate effect could be tested"
    c = cands[0]
    return (f"no candidate lowers the out-of-fold RMS significantly; the best, {c.effect}, changes it by "
            f"{c.gain_pct:+.1f} % (p = {c.p_value:.2g})")


def _pair_line(c) -> str:
    return (f"{c.effect} and {c.alternative} explain the training file about equally well: out-of-fold RMS "
            f"{c.rms_mm:.4g} vs {c.alternative_rms_mm:.4g} mm, clipped gain {c.gain_pct:+.1f} % (p = {c.p_value:.2g}), "
            "below the selection's thresholds")


def verdict_of(ctx, stages: list, final, fallback, comparisons: tuple, inconclusive: list, fallback_msgs,
               safe: str, suggestions) -> Verdict:
    """The :class:`~tolalloc.diagnose.verdict.Verdict` (precedence: inconclusive, none, ambiguous, effect)."""
    notes = input_notes(ctx, stages)
    if inconclusive:
        picked = [f"the selection on the training file chose {'+'.join(final.effects)}; not claimed"] \
            if final.effects else []
        return Verdict("inconclusive", (), tuple(inconclusive + picked + notes), safe, comparisons)
    if not final.effects:
        first = list(fallback_msgs) if fallback else [_best_line(stages)]
        return Verdict("none", (), tuple(first + notes), safe, comparisons)
    amb = [c for c in comparisons if not c.separable]
    sel = [_selected_line(stages, e) for e in final.effects]
    if amb:
        names = []
        for e in final.effects:
            names += [x for x in (e, *[c.alternative for c in amb if c.effect == e]) if x not in names]
        lines = [_pair_line(c) for c in amb] + sel
        if suggestions is not None and len(suggestions):
            lines.append("poses that would separate them: suggested_poses (where the two fitted models' predictions "
                         f"differ most, up to {suggestions['predicted_difference_mm'].max():.3g} mm)")
        return Verdict("ambiguous", tuple(names), tuple(lines + notes), safe, comparisons, suggestions)
    sep = [f"{c.effect} beats {c.alternative} in its place (clipped gain {c.gain_pct:+.1f} %, p = {c.p_value:.2g})"
           for c in comparisons]
    return Verdict("effect", tuple(final.effects), tuple(sel + sep + notes), safe, comparisons)
