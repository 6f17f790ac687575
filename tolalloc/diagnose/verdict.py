"""The verdict of a diagnosis: ``effect``, ``none``, ``ambiguous`` or ``inconclusive``, with its reasons.

* ``ambiguous`` -- a selected effect ``e`` and another candidate ``a`` that was significant at the step ``e`` was
  selected in explain the training file equally well: the model with ``a`` in place of ``e`` is not beaten by the
  selection's own rule (one-sided Wilcoxon signed-rank test on the same out-of-fold poses, ``p < alpha``, and a
  clipped-RMS gain of at least ``min_gain``) -- :func:`compare_alternatives`. Both are named, and
  :func:`separating_poses` suggests poses where the two fitted models' predictions differ most.
* ``inconclusive`` -- no effect is claimed when the data cannot support one (:func:`inconclusive_reasons`): the
  probe offset is only weakly identified (the parameter check), the out-of-fold registration is unstable (the
  nominal model's out-of-fold RMS above :data:`UNSTABLE_RATIO` x its training RMS), or the final model does not
  transfer to the sealed test file (its RMS above the nominal model's, or its largest error above
  :data:`MAX_ERROR_RATIO` x the nominal model's).
* otherwise ``effect`` (one or more effects selected) or ``none``.

The model that is safe to use (:func:`safe_model`) is the last of nominal -> geometric -> final that held
(no worse than the one before it on cross-validation, :data:`~tolalloc.diagnose.guards.FALLBACK_MARGIN`, and --
with a test file -- no worse than nominal on it by the rules above); an ``inconclusive`` verdict stops at the
geometric model, since the effects are not claimed; ``none`` when even the nominal model does not transfer to the
test file (its test RMS above :data:`UNSTABLE_RATIO` x its out-of-fold RMS).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.diagnose.effects import effect_basis
from tolalloc.diagnose.guards import FALLBACK_MARGIN
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import align_basis
from tolalloc.diagnose.scores import error_stats, paired_pvalue, rms, robust_rms

__all__ = ["Verdict", "Comparison", "compare_alternatives", "separating_poses", "inconclusive_reasons", "safe_model",
           "VERDICTS", "UNSTABLE_RATIO", "MAX_ERROR_RATIO", "N_SUGGESTED", "N_SAMPLED", "scored_test_stats"]

VERDICTS = ("effect", "none", "ambiguous", "inconclusive")
#: Out-of-fold nominal RMS beyond this multiple of the training RMS: the registration does not hold across folds.
UNSTABLE_RATIO = 3.0
#: A final model whose largest test error exceeds this multiple of the nominal model's does not transfer.
MAX_ERROR_RATIO = 2.0
#: Poses suggested per ambiguous pair, and random poses searched for them.
N_SUGGESTED = 8
N_SAMPLED = 2000


@dataclass(frozen=True)
class Comparison:
    """A selected effect against an alternative in its place, on the same out-of-fold training poses.

    ``p_value``: one-sided Wilcoxon that the selected model has smaller clipped errors; ``gain_pct``: its clipped
    out-of-fold RMS gain over the swapped model; ``separable``: both beyond the selection's thresholds.
    """

    effect: str
    alternative: str
    p_value: float
    gain_pct: float
    rms_mm: float
    alternative_rms_mm: float
    separable: bool

    def to_dict(self) -> dict:
        return dict(self.__dict__)


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
    """

    verdict: str
    candidates: tuple
    reasons: tuple
    safe_model: str
    comparisons: tuple = ()
    suggestions: pd.DataFrame | None = field(default=None)

    def headline(self) -> str:
        """The first printed line."""
        if self.verdict == "effect":
            return f"verdict: effect -- {' + '.join(self.candidates)}"
        if self.verdict == "ambiguous":
            return f"verdict: ambiguous -- one of {', '.join(self.candidates)}; these poses cannot tell them apart"
        if self.verdict == "inconclusive":
            safe = ("no fitted model transfers to the test poses" if self.safe_model == "none"
                    else f"safe to use: the {self.safe_model} model")
            return f"verdict: inconclusive -- no effect claimed; {safe}"
        return "verdict: none -- no unmodelled effect lowers the held-out error significantly"

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "candidates": list(self.candidates), "reasons": list(self.reasons),
                "safe_model": self.safe_model, "comparisons": [c.to_dict() for c in self.comparisons],
                "suggested_poses": None if self.suggestions is None else self.suggestions.to_dict(orient="records")}


def compare_alternatives(ctx, final, stages: list, evals: dict, evaluate, clip: float, alpha: float,
                         min_gain: float) -> tuple:
    """:class:`Comparison` of every selected effect of ``final`` with every candidate significant at its step.

    ``evaluate(ctx, effects)`` fits a model not yet in ``evals`` (keys: evaluation labels).
    """
    out = []
    for i, e in enumerate(final.effects):
        step = next((st for st in stages if st.selected == e), None)
        if step is None:
            continue
        for c in step.candidates:
            if c.effect == e or c.effect in final.effects or not c.significant:
                continue
            swapped = tuple(c.effect if x == e else x for x in final.effects)
            label = "+".join(("geometric", *swapped))
            ev = evals.get(label) or evaluate(ctx, swapped)
            evals[label] = ev
            p = paired_pvalue(ev.selection_stack, final.selection_stack, clip)
            r, r_alt = robust_rms(final.selection_mm, clip), robust_rms(ev.selection_mm, clip)
            gain = 100.0 * (1.0 - r / r_alt)
            out.append(Comparison(e, c.effect, p, gain, rms(final.selection_mm), rms(ev.selection_mm),
                                  bool(p < alpha and gain >= 100.0 * min_gain)))
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
        for k, i in enumerate(picked):
            rows.append({"effect": e, "alternative": a,
                         **{f"q{j + 1}_{robot.joints[j].unit}": qi[k, j] for j in range(robot.n_joints)},
                         "predicted_difference_mm": float(diff[i])})
    return pd.DataFrame(rows)


def inconclusive_reasons(parameter_check, nominal, cal_nominal, test_stats: dict | None) -> list:
    """Reasons to claim no effect (module docstring); ``test_stats``: ``{"nominal": stats, "final": stats}`` of
    :func:`~tolalloc.diagnose.scores.error_stats` on the scored test poses, or None."""
    out = []
    if parameter_check is not None:
        for name, st, v, sd, lev in zip(parameter_check.names, parameter_check.status, parameter_check.value,
                                        parameter_check.sd, parameter_check.level):
            if name.startswith("probe_offset") and st == "weak":
                out.append(f"the probe offset is weakly identified ({name} = {v:.3g} +- {sd:.2g} mm, more than the "
                           f"as-built level {lev:.3g} mm): the flange hardly changed direction; pass "
                           "target_offset_mm / target_offset_sd_mm from the tool definition, or turn the wrist more")
    oof, train = rms(nominal.oof_mm), cal_nominal.rms_mm
    if oof > UNSTABLE_RATIO * train:
        out.append(f"the registration is unstable out of fold: the nominal model's out-of-fold RMS {oof:.4g} mm is "
                   f"{oof / train:.1f} x its training RMS {train:.4g} mm (limit {UNSTABLE_RATIO:g} x)")
    if test_stats is not None:
        n, f = test_stats["nominal"], test_stats["final"]
        if f["rms_mm"] > n["rms_mm"]:
            out.append(f"the final model does not transfer to the test file: RMS {f['rms_mm']:.4g} mm against the "
                       f"nominal model's {n['rms_mm']:.4g} mm")
        if f["max_mm"] > MAX_ERROR_RATIO * n["max_mm"]:
            out.append(f"the final model's largest test error {f['max_mm']:.4g} mm exceeds {MAX_ERROR_RATIO:g} x the "
                       f"nominal model's {n['max_mm']:.4g} mm")
    return out


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
    safe = nominal.label
    if not _held(geometric, nominal, test_stats, "geometric"):
        return safe
    safe = geometric.label
    if inconclusive or final is geometric or not final.effects:
        return safe
    return final.label if _held(final, geometric, test_stats, "final") else safe


def scored_test_stats(nominal, geometric, final) -> dict | None:
    """Error statistics of the three models on the scored test poses, or None without a test file."""
    if nominal.test_mm is None:
        return None
    return {k: error_stats(ev.test_mm) for k, ev in (("nominal", nominal), ("geometric", geometric), ("final", final))}
