"""The verdict of a diagnosis: ``effect``, ``none``, ``ambiguous`` or ``inconclusive``, with its reasons.

* ``ambiguous`` -- verdicts follow the *size* of the evidence. Every candidate family that explains part of the
  training residual at the step a selected effect ``e`` was chosen (clipped out-of-fold gain of at least ``min_gain``
  over that step's base) is fitted in place of ``e`` on the same out-of-fold poses (:func:`compare_alternatives`).
  An alternative whose clipped out-of-fold RMS is within the practical margin :data:`PRACTICAL_MARGIN` (5 %) of the
  selected model's is *tied*: the data cannot separate the two physics by what they predict. ``ambiguous`` names the
  selected effect and its (at most :data:`MAX_TIED` closest) tied alternatives, with the margin; an alternative
  worse by more than the margin is beaten, whatever its p-value, and the verdict stays ``effect``. A tie with the
  effect of the first step is also decided where the model evidence is strong: a Bayes factor of at least
  :data:`~.families.DECISIVE_BAYES_FACTOR` for the selected family over the alternative (:mod:`.families`; the
  first step has already selected the family the evidence favours, :func:`.families.evidence_pick`). The Wilcoxon
  p-value of each comparison is reported, not used. :func:`separating_poses` suggests poses where two tied models'
  predictions differ most. A tie on a later effect leaves the verdict ``effect`` when the first selected effect is
  clear (no tied alternative, a gain of at least the margin): the clear effects are named, and the tied one is a
  further effect whose family the data cannot tell, named with its alternatives (``Verdict.further``); so is a tie
  on a *minor* effect (its own gain below the margin) beside any clear effect, reported as not claimed
  (:func:`.verdict_text.further_ties`).
* ``inconclusive`` -- no effect is claimed when the data cannot support one (:func:`inconclusive_reasons`): the
  probe offset is only weakly identified (the parameter check); the out-of-fold registration is unstable (the
  nominal model's out-of-fold RMS above :data:`UNSTABLE_RATIO` x its training RMS); the geometric model or the final
  model does not hold out of fold (the same ratio: too few poses for its parameters, the fits interpolate); the
  selected effects do not lower the out-of-fold RMS by ``min_gain``; the final model does not transfer to the sealed test file (its RMS above the nominal model's, or its largest error above
  :data:`MAX_ERROR_RATIO` x the nominal model's); or the selected effects do not transfer (the final model
  significantly worse than the geometric model on the test poses: Wilcoxon ``p < alpha`` and a clipped-RMS loss of
  at least ``min_gain``).
* otherwise ``effect`` (one or more effects selected) or ``none``.

The model that is safe to use (:func:`safe_model`) is the last of nominal -> geometric -> final that held (no
worse on cross-validation than the last model before it that held, :data:`~tolalloc.diagnose.guards.FALLBACK_MARGIN`,
and -- with a test file -- no worse than nominal on it by the rules above): a geometric model that does not hold is
skipped, and the final model is then judged against the nominal one; an ``inconclusive`` verdict stops before the
final model, since the effects are not claimed; ``none`` when even the nominal model does not transfer to the test
file (its test RMS above :data:`UNSTABLE_RATIO` x its out-of-fold RMS).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.diagnose.effects import effect_basis, is_block_parameter
from tolalloc.diagnose.families import DECISIVE_BAYES_FACTOR, bayes_factor
from tolalloc.diagnose.guards import FALLBACK_MARGIN, extrapolation_flags, outside_range
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import align_basis
from tolalloc.diagnose.scores import clip_level, error_stats, paired_pvalue, rms, robust_rms

__all__ = ["Verdict", "Comparison", "compare_alternatives", "separating_poses", "inconclusive_reasons", "safe_model",
           "PRACTICAL_MARGIN", "MAX_TIED", "VERDICTS", "UNSTABLE_RATIO", "MAX_ERROR_RATIO", "N_SUGGESTED", "N_SAMPLED", "scored_test_stats"]

VERDICTS = ("effect", "none", "ambiguous", "inconclusive")
#: Out-of-fold nominal RMS beyond this multiple of the training RMS: the registration does not hold across folds.
UNSTABLE_RATIO = 3.0
#: A final model whose largest test error exceeds this multiple of the nominal model's does not transfer.
MAX_ERROR_RATIO = 2.0
#: Two families whose clipped out-of-fold RMS differ by less than this fraction of the better one's are tied.
PRACTICAL_MARGIN = 0.05
#: Tied alternatives named beside a selected effect (the closest first).
MAX_TIED = 2
#: Poses suggested per ambiguous pair, and random poses searched for them.
N_SUGGESTED = 8
N_SAMPLED = 2000


@dataclass(frozen=True)
class Comparison:
    """A selected effect against an alternative in its place, on the same out-of-fold training poses.

    ``excess_pct``: how much larger the alternative model's clipped out-of-fold RMS is than the selected model's
    (``100 (r_alt / r - 1)``); ``bayes_factor``: ``p(data | effect) / p(data | alternative)`` from the marginal
    likelihoods (the first step's effect only, NaN elsewhere); ``separable``: the excess beyond the practical margin,
    or a Bayes factor of at least :data:`~.families.DECISIVE_BAYES_FACTOR`; ``p_value``: one-sided Wilcoxon
    that the selected model has smaller clipped errors (reported, not used); ``gain_pct``: the selected model's clipped
    gain over the swapped one.
    """

    effect: str
    alternative: str
    p_value: float | None
    gain_pct: float | None
    rms_mm: float
    alternative_rms_mm: float
    separable: bool
    excess_pct: float = float("nan")
    margin_pct: float = 100.0 * PRACTICAL_MARGIN
    bayes_factor: float = float("nan")

    @property
    def alternative_label(self) -> str:
        """How the headline names the alternative."""
        return self.alternative

    @property
    def by_evidence(self) -> bool:
        """Separated by the model evidence, not by the held-out RMS (within the practical margin)."""
        return bool(self.separable and not self.excess_pct > self.margin_pct)

    def to_dict(self) -> dict:
        out = dict(self.__dict__)
        out["bayes_factor"] = self.bayes_factor if np.isfinite(self.bayes_factor) else None
        return out


@dataclass(frozen=True, eq=False)
class Verdict:
    """What the diagnosis concludes.

    Attributes
    ----------
    verdict : str           one of :data:`VERDICTS`
    candidates : tuple      the effects named (``effect``: the selected ones; ``ambiguous``: each selected effect
                            and its indistinguishable alternatives; empty for ``none`` / ``inconclusive``)
    reasons : tuple of str  why, in order of weight, then notes on effects that could not be tested
    safe_model : str        label of the model that is safe to use (:func:`safe_model`)
    comparisons : tuple of Comparison
    suggestions : DataFrame or None   poses separating the ambiguous pairs (interface units)
    selected : tuple of str the effects of the final model (also for ``inconclusive``, where they are not claimed)
    untested : tuple of str effects (or variants) the data could not test, each with its reason in ``reasons``
    further : tuple of str  (``effect``) selected effects after a clear first one whose family the data cannot tell
                            from a tied alternative: in the final model, named in the headline with the alternatives,
                            not claimed as a family (:func:`.verdict_text.further_ties`)
    """

    verdict: str
    candidates: tuple
    reasons: tuple
    safe_model: str
    comparisons: tuple = ()
    suggestions: pd.DataFrame | None = field(default=None)
    selected: tuple = ()
    untested: tuple = ()
    further: tuple = ()

    def headline(self) -> str:
        """The first printed line."""
        if self.verdict == "effect":
            if not self.further:
                return f"verdict: effect -- {' + '.join(self.candidates)}"
            return (f"verdict: effect -- {' + '.join(self.candidates)}; a further effect the data cannot attribute "
                    f"to one family: {self.further_terms()}")
        if self.verdict == "ambiguous":
            return f"verdict: ambiguous -- {self._ambiguous_terms()}; these poses cannot tell them apart"
        if self.verdict == "inconclusive":
            safe = ("no fitted model transfers to the test poses" if self.safe_model == "none"
                    else f"safe to use: the {self.safe_model} model")
            return f"verdict: inconclusive -- no effect claimed; {safe}"
        if self.untested:
            return ("verdict: none -- none of the tested effects lowers the held-out error significantly; not "
                    f"tested: {', '.join(self.untested)} (see the reasons)")
        return "verdict: none -- no unmodelled effect lowers the held-out error significantly"

    def _alternatives(self) -> dict:
        """``{effect: [its named tied alternatives]}`` (:func:`tied`)."""
        alts = {}
        for c in tied(self.comparisons):
            alts.setdefault(c.effect, []).append(c.alternative_label)
        return alts

    def further_terms(self) -> str:
        """The further effects with their tied alternatives, e.g. ``b or c`` (``and`` between two); empty without."""
        alts = self._alternatives()
        return " and ".join(" or ".join((e, *alts.get(e, ()))) for e in self.further)

    def _ambiguous_terms(self) -> str:
        """The selected effects with their indistinguishable alternatives, e.g. ``a + (b or c)``."""
        alts = self._alternatives()
        selected = self.selected or tuple(e for e in self.candidates if e in alts)
        terms = [" or ".join((e, *alts.get(e, ()))) for e in selected]
        if len(terms) == 1:
            return terms[0]
        return " + ".join(f"({t})" if e in alts else t for e, t in zip(selected, terms))

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "candidates": list(self.candidates), "reasons": list(self.reasons),
                "safe_model": self.safe_model, "selected": list(self.selected), "untested": list(self.untested),
                "further": list(self.further),
                "comparisons": [c.to_dict() for c in self.comparisons],
                "suggested_poses": None if self.suggestions is None else self.suggestions.to_dict(orient="records")}


def tied(comparisons) -> list:
    """The tied comparisons that are named: per selected effect its :data:`MAX_TIED` closest tied alternatives."""
    out, count = [], {}
    for c in sorted((c for c in comparisons if not c.separable), key=lambda c: c.excess_pct):
        if count.get(c.effect, 0) < MAX_TIED:
            out.append(c)
            count[c.effect] = count.get(c.effect, 0) + 1
    return out


def compare_alternatives(ctx, final, stages: list, evals: dict, evaluate, clip: float, alpha: float,
                         min_gain: float, margin: float = PRACTICAL_MARGIN, logml: dict | None = None) -> tuple:
    """:class:`Comparison` of every selected effect of ``final`` with every candidate that explains part of the residual
    at its step (clipped gain over the step's base of at least ``min_gain``), fitted in its place.

    ``evaluate(ctx, effects)`` fits a model not yet in ``evals`` (keys: evaluation labels). The alternative is tied
    (``separable`` False) when its clipped out-of-fold RMS exceeds the selected model's by at most ``margin``
    (:data:`PRACTICAL_MARGIN`) and the evidence does not separate them (``logml``: ``{family: log marginal
    likelihood}``, for the effect of the first step); ``alpha`` is kept for the reported p-value's context only.
    """
    out = []
    for e in final.effects:
        step = next((st for st in stages if st.selected == e), None)
        if step is None:
            continue
        for c in step.candidates:
            if c.effect == e or c.effect in final.effects or not c.applicable or not c.gain_pct >= 100.0 * min_gain:
                continue
            swapped = tuple(c.effect if x == e else x for x in final.effects)
            label = "+".join(("geometric", *swapped))
            ev = evals.get(label) or evaluate(ctx, swapped)
            evals[label] = ev
            p = paired_pvalue(ev.selection_stack, final.selection_stack, clip)
            r, r_alt = robust_rms(final.selection_mm, clip), robust_rms(ev.selection_mm, clip)
            excess = 100.0 * (r_alt / max(r, 1e-300) - 1.0)
            bf = bayes_factor(logml or {}, e, c.effect) if not step.base else float("nan")
            out.append(Comparison(e, c.effect, p, 100.0 * (1.0 - r / r_alt), rms(final.selection_mm),
                                  rms(ev.selection_mm), bool(excess > 100.0 * margin or bf >= DECISIVE_BAYES_FACTOR),
                                  excess, 100.0 * margin, bf))
    return tuple(out)


def _sample_poses(robot, q_train, n: int, seed: int) -> np.ndarray:
    """Random poses within the joint limits (revolute joints within one turn), shape (n, joints)."""
    rng = np.random.default_rng(seed)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    return rng.uniform(lo, hi, (n, robot.n_joints))


def _covariates_like(train: Measurements, q: np.ndarray) -> Measurements:
    """Measurements at poses ``q`` with the training file's median covariates (latest time; approach +1)."""
    P = len(q)
    med = (lambda a: None if a is None else np.full(P, float(np.median(a))))
    t = None if train.time_s is None else np.full(P, float(np.max(train.time_s)))
    d = None if train.direction is None else np.ones((P, q.shape[1]))
    return Measurements(q, np.zeros((P, 3)), med(train.temperature_c), d, med(train.payload_kg), t)


def separating_poses(ctx, pairs: list, evals: dict, *, n: int = N_SUGGESTED, n_sampled: int = N_SAMPLED,
                     seed: int = 0) -> pd.DataFrame | None:
    """Poses where the fitted models of each ambiguous pair predict most differently.

    ``pairs``: (Evaluation of the selected model, Evaluation of the model with the alternative, effect,
    alternative). Random poses within the joint limits (seeded), the covariates at the training file's median
    (time: its latest; approach directions +1); both models' predictions of the target point in the base
    frame (their own geometry and effects); the ``n`` poses of largest difference, each at least 10 % of the
    joint ranges (normalised distance) from those picked before. Returns one row per pose and pair: the pair,
    the joints in interface units, the predicted difference [mm].
    """
    if not pairs:
        return None
    robot = ctx.cal.geometric.model.robot
    q = _sample_poses(robot, ctx.train.q, n_sampled, seed)
    meas = _covariates_like(ctx.train, q)
    t = ctx.cal.geometric.t_mm
    cache = {}

    def predict(ev):
        if not ev.effects:
            return ev.fit.base_points(q)
        cols = []
        for e in ev.effects:
            if e not in cache:
                cache[e] = align_basis(effect_basis(e, robot, meas, t, ctx.ref), ctx.bases[e].names).B
            cols.append(cache[e])
        return ev.fit.base_points(q, np.concatenate(cols, axis=2)[:, :, ev.keep])

    span = np.maximum(np.ptp(q, axis=0), 1e-9)
    rows = []
    for ev_a, ev_b, e, a in pairs:
        diff = np.linalg.norm(predict(ev_a) - predict(ev_b), axis=1)
        picked = []
        for i in np.argsort(-diff):
            if all(np.linalg.norm((q[i] - q[j]) / span) > 0.1 for j in picked):
                picked.append(i)
            if len(picked) == n:
                break
        qi = robot.q_to_interface(q[picked])
        flags = extrapolation_flags(robot, ctx.train.q, q[picked])
        out_j = outside_range(robot, ctx.train.q, q[picked])
        for k, i in enumerate(picked):
            move = ", ".join(robot.joints[j].name for j in np.flatnonzero(out_j[k]))
            rows.append({"effect": e, "alternative": a,
                         **{f"q{j + 1}_{robot.joints[j].unit}": qi[k, j] for j in range(robot.n_joints)},
                         "predicted_difference_mm": float(diff[i]), "outside_training": bool(flags.flagged[k]),
                         "joints_outside_training_range": move})
    return pd.DataFrame(rows)


def _interpolation_oof(ev) -> tuple:
    """(out-of-fold RMS, its scheme's words) for the interpolation check: the time blocks', or the joint-space
    blocks' for a model with a seat per tool change (:mod:`tolalloc.physics.seating`) -- a time block holds out
    whole tool changes, whose seats no fit can know, which is the seats' scatter, not a fit that interpolates."""
    if ev.oof_joint_mm is not None and any(is_block_parameter(n) for n in ev.param_names):
        return rms(ev.oof_joint_mm), " (joint-space blocks: time blocks hold out whole tool changes)"
    return rms(ev.oof_mm), ""


def inconclusive_reasons(parameter_check, evals: dict, cal, test_stats: dict | None, *, alpha: float = 0.01,
                         min_gain: float = 0.02, untestable: tuple = ()) -> list:
    """Reasons to claim no effect (module docstring).

    ``evals``: the ``nominal``, ``geometric`` and ``final`` :class:`~tolalloc.diagnose.scores.Evaluation` (test
    residuals set when there is a test file); ``cal``: the :class:`~tolalloc.diagnose.calibrate.Calibration` (training
    fits); ``test_stats``: ``{"nominal": stats, "geometric": stats, "final": stats}`` of
    :func:`~tolalloc.diagnose.scores.error_stats` on the scored test poses, or None; ``untestable``: selected effects
    the test file cannot carry (their displacement is left out of its predictions, so it cannot judge them).
    """
    out = _probe_offset_reasons(parameter_check)
    nominal, geometric, final = evals["nominal"], evals["geometric"], evals["final"]
    checks = [(nominal, cal.nominal, "the registration is unstable out of fold: the nominal model's"),
              (geometric, cal.geometric, "the geometric model does not hold out of fold (too few poses for its "
                                         "parameters: the fits interpolate): its")]
    if final.effects and final is not geometric:
        checks.append((final, final.fit, f"the final model ({final.label}) does not hold out of fold (too few poses "
                                         f"for its {len(final.param_names)} effect parameters beside the geometry: the "
                                         "fits interpolate): its"))
    for ev, fit, what in checks:
        (oof, scheme), train = _interpolation_oof(ev), fit.rms_mm
        if oof > UNSTABLE_RATIO * train:
            out.append(f"{what} out-of-fold RMS {oof:.4g} mm{scheme} is {oof / max(train, 1e-300):.3g} x its training "
                       f"RMS {train:.4g} mm (limit {UNSTABLE_RATIO:g} x)")
    if final.effects and final is not geometric and rms(final.oof_mm) > (1 - min_gain) * rms(geometric.oof_mm):
        out.append(f"the selected effect(s) do not lower the out-of-fold RMS of the training file by {100 * min_gain:g} "
                   f"%: {rms(final.oof_mm):.4g} mm against the geometric model's {rms(geometric.oof_mm):.4g} mm (time "
                   "blocks)")
    if test_stats is None:
        return out
    n, f = test_stats["nominal"], test_stats["final"]
    probe = any(r.startswith("the probe offset") for r in out)  # explains a miss at other flange directions
    if n["rms_mm"] > UNSTABLE_RATIO * rms(nominal.oof_mm) and not probe:
        out.append(f"every model misses the test file: the nominal model's test RMS {n['rms_mm']:.4g} mm is "
                   f"{n['rms_mm'] / rms(nominal.oof_mm):.3g} x its out-of-fold RMS on the training file "
                   f"{rms(nominal.oof_mm):.4g} mm -- is the test file of another robot, tool or set-up, or another "
                   "session's tracker frame (test_frame='refit')?")
    if f["rms_mm"] > n["rms_mm"]:
        out.append(f"the final model does not transfer to the test file: RMS {f['rms_mm']:.4g} mm against the "
                   f"nominal model's {n['rms_mm']:.4g} mm")
    if f["max_mm"] > MAX_ERROR_RATIO * n["max_mm"]:
        out.append(f"the final model's largest test error {f['max_mm']:.4g} mm exceeds {MAX_ERROR_RATIO:g} x the "
                   f"nominal model's {n['max_mm']:.4g} mm")
    if final.effects and final is not geometric and not untestable:
        out += _effects_transfer(geometric, final, alpha, min_gain)
    return out


def _probe_offset_reasons(parameter_check) -> list:
    if parameter_check is None:
        return []
    return [f"the probe offset is weakly identified ({name} = {v:.3g} +- {sd:.2g} mm, more than the as-built level "
            f"{lev:.3g} mm): the flange hardly changed direction; pass target_offset_mm / target_offset_sd_mm from the "
            "tool definition, or turn the wrist more"
            for name, st, v, sd, lev in zip(parameter_check.names, parameter_check.status, parameter_check.value,
                                            parameter_check.sd, parameter_check.level)
            if name.startswith("probe_offset") and st == "weak"]


def _effects_transfer(geometric, final, alpha: float, min_gain: float) -> list:
    """A reason when the final model is significantly worse than the geometric one on the test poses: one-sided
    Wilcoxon on the clipped squared errors (clip level of the geometric model's test errors), ``p < alpha``, and a
    clipped-RMS loss of at least ``min_gain``."""
    clip = clip_level(geometric.test_mm)
    p = paired_pvalue(final.test_mm, geometric.test_mm, clip)
    loss = 1.0 - robust_rms(geometric.test_mm, clip) / max(robust_rms(final.test_mm, clip), 1e-300)
    if p < alpha and loss >= min_gain:
        return [f"the selected effect(s) do not transfer to the test file: the final model's test RMS "
                f"{rms(final.test_mm):.4g} mm is worse than the geometric model's {rms(geometric.test_mm):.4g} mm "
                f"(clipped loss {100 * loss:.1f} %, p = {p:.2g})"]
    return []


def _held(ev, base, test: dict | None, name: str) -> bool:
    """``ev`` no worse than ``base`` on CV (FALLBACK_MARGIN) and, with test figures, no worse than nominal."""
    cv = rms(ev.oof_mm) <= (1 + FALLBACK_MARGIN) * rms(base.oof_mm)
    if test is None or name not in test:
        return bool(cv)
    t, n = test[name], test["nominal"]
    return bool(cv and t["rms_mm"] <= n["rms_mm"] and t["max_mm"] <= MAX_ERROR_RATIO * n["max_mm"])


def safe_model(nominal, geometric, final, test_stats: dict | None, inconclusive: bool) -> str:
    """Label of the last model of nominal -> geometric -> final that held (module docstring); ``none`` when even
    the nominal model misses the test file by more than :data:`UNSTABLE_RATIO` x its out-of-fold RMS (e.g. a
    probe offset the training poses could not pin down, used at other flange directions)."""
    if test_stats is not None and test_stats["nominal"]["rms_mm"] > UNSTABLE_RATIO * rms(nominal.oof_mm):
        return "none"
    base = geometric if _held(geometric, nominal, test_stats, "geometric") else nominal
    if inconclusive or final is geometric or not final.effects:
        return base.label
    return final.label if _held(final, base, test_stats, "final") else base.label


def scored_test_stats(nominal, geometric, final) -> dict | None:
    """Error statistics of the three models on the scored test poses, or None without a test file."""
    if nominal.test_mm is None:
        return None
    return {k: error_stats(ev.test_mm) for k, ev in (("nominal", nominal), ("geometric", geometric), ("final", final))}
