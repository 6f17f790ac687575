"""Verdicts of the diagnosis (diagnose/verdict.py, verdict_text.py): ambiguous, inconclusive, the safe model, and
the printed summary (report/diagnosis.py summary_lines).

Constructed evaluations (known out-of-fold residuals) test the decision rules without fitting; one small
synthetic diagnosis checks the whole printed summary and the JSON keys."""

import re
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.diagnose import VERDICTS, diagnose, generate, measurements_from_frame
from tolalloc.diagnose.scores import Candidate, Evaluation, Stage, clip_level, error_stats
from tolalloc.diagnose.synth import split_frame
from tolalloc.diagnose.verdict import (MAX_ERROR_RATIO, UNSTABLE_RATIO, compare_alternatives, inconclusive_reasons,
                                       safe_model)
from tolalloc.diagnose.verdict_text import verdict_of
from tolalloc.report.diagnosis import summary_lines


def _ev(effects, oof, test=None):
    names = tuple(f"{e}:p" for e in effects)
    return Evaluation("+".join(("geometric", *effects)), tuple(effects), None, names, np.arange(len(names)), oof,
                      test, None)


def _cand(e, sig=True):
    return Candidate(e, True, "", 1, 0.1, 0.1, 1e-9 if sig else 0.5, 30.0 if sig else 0.0, sig, 0.1, "v")


def _world(alt_scale, P=200, seed=0):
    """Geometric model: a systematic error; ``a`` removes it entirely; ``b`` in its place leaves ``alt_scale`` of
    it (0: as good as ``a``)."""
    rng = np.random.default_rng(seed)
    noise, sys_ = rng.normal(0, 0.03, (P, 3)), rng.normal(0, 0.1, (P, 3))
    evals = {"geometric": _ev((), noise + sys_), "geometric+a": _ev(("a",), noise),
             "geometric+b": _ev(("b",), noise + alt_scale * sys_ + rng.normal(0, 0.001, (P, 3)))}
    stages = [Stage((), 0.2, (_cand("a"), _cand("b"), _cand("c", sig=False)), "a")]
    return evals, stages


@pytest.mark.parametrize("alt_scale, separable", [(0.0, False), (0.8, True)])
def test_alternative_in_place_of_the_selected_effect(alt_scale, separable):
    evals, stages = _world(alt_scale)
    final = evals["geometric+a"]
    clip = clip_level(evals["geometric"].oof_mm)
    out = compare_alternatives(None, final, stages, evals, None, clip, 0.01, 0.02)
    assert [(c.effect, c.alternative) for c in out] == [("a", "b")]  # c was not significant: not compared
    assert out[0].separable is separable
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    v = verdict_of(ctx, stages, final, None, out, [], (), "geometric+a", None)
    assert v.verdict == ("effect" if separable else "ambiguous")
    assert v.candidates == (("a",) if separable else ("a", "b"))
    assert v.verdict in VERDICTS and v.headline().startswith(f"verdict: {v.verdict}")


def _models(base, geo_scale=0.5, final_scale=0.4, test=None, final_train_rms=None):
    """nominal / geometric / final evaluations whose out-of-fold residuals are multiples of ``base`` (the final
    model's training RMS equal to its out-of-fold RMS unless given)."""
    nominal = _ev((), base, None if test is None else test["nominal"])
    geometric = _ev((), geo_scale * base, None if test is None else test["geometric"])
    r = final_scale * float(np.sqrt(np.mean(np.sum(base ** 2, 1))))
    final = replace(_ev(("a",), final_scale * base, None if test is None else test["final"]),
                    fit=SimpleNamespace(rms_mm=r if final_train_rms is None else final_train_rms))
    return {"nominal": nominal, "geometric": geometric, "final": final}


def _cal(base, geo_scale=0.5):
    r = float(np.sqrt(np.mean(np.sum(base ** 2, 1))))
    return SimpleNamespace(nominal=SimpleNamespace(rms_mm=r), geometric=SimpleNamespace(rms_mm=geo_scale * r))


def test_inconclusive_reasons_and_precedence():
    rng = np.random.default_rng(1)
    base = rng.normal(0, 0.1, (60, 3))
    evals, cal = _models(base), _cal(base)
    assert inconclusive_reasons(None, evals, cal, None) == []
    wild = dict(evals, nominal=_ev((), (UNSTABLE_RATIO + 1) * base))  # out-of-fold four times the training RMS
    assert "unstable out of fold" in inconclusive_reasons(None, wild, cal, None)[0]
    n = error_stats(base)
    test = {"nominal": base, "geometric": 1.1 * base, "final": 1.1 * base}
    msgs = inconclusive_reasons(None, _models(base, test=test), cal, {k: error_stats(v) for k, v in test.items()})
    assert len(msgs) == 1 and "does not transfer" in msgs[0]
    spike = 0.5 * base
    spike[0] = [0, 0, (MAX_ERROR_RATIO + 0.5) * n["max_mm"]]
    test = {"nominal": base, "geometric": spike, "final": spike}
    msgs = inconclusive_reasons(None, _models(base, test=test), cal, {k: error_stats(v) for k, v in test.items()})
    assert len(msgs) == 1 and "largest test error" in msgs[0]
    check = SimpleNamespace(names=("probe_offset_z",), status=("weak",), value=np.array([73.0]),
                            sd=np.array([54.0]), level=np.array([1.2]))
    assert "probe offset is weakly identified" in inconclusive_reasons(check, evals, cal, None)[0]
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    final = _ev(("a",), 0.5 * base)
    v = verdict_of(ctx, [Stage((), 0.1, (_cand("a"),), "a")], final, None, (), msgs, (), "geometric", None)
    assert v.verdict == "inconclusive" and v.candidates == () and "not claimed" in v.reasons[-1]
    assert v.selected == ("a",)


def test_geometric_model_that_interpolates_is_inconclusive():
    """Too few poses for the geometric parameters: the fits interpolate (training RMS far below out of fold)."""
    base = np.random.default_rng(3).normal(0, 0.1, (40, 3))
    msgs = inconclusive_reasons(None, _models(base), _cal(base, geo_scale=0.5 / (UNSTABLE_RATIO + 1)), None)
    assert len(msgs) == 1
    assert re.search(r"geometric model does not hold out of fold .* 4 x its training RMS", msgs[0])


@pytest.mark.parametrize("final_scale, fires", [(1.3, True), (1.005, False), (0.8, False)])
def test_effects_that_do_not_transfer_to_the_test_file(final_scale, fires):
    """The final model significantly worse than the geometric one on the sealed test poses: nothing is claimed."""
    rng = np.random.default_rng(4)
    base, t = rng.normal(0, 0.1, (60, 3)), rng.normal(0, 0.1, (120, 3))
    test = {"nominal": 2 * t, "geometric": t, "final": final_scale * t + rng.normal(0, 0.002, t.shape)}
    evals = _models(base, test=test)
    stats = {k: error_stats(v) for k, v in test.items()}
    msgs = inconclusive_reasons(None, evals, _cal(base), stats)
    assert any("do not transfer to the test file" in m for m in msgs) is fires
    assert inconclusive_reasons(None, evals, _cal(base), stats, untestable=("a",)) == []  # the test cannot judge a


def test_a_test_file_every_model_misses_is_named():
    rng = np.random.default_rng(6)
    base, t = rng.normal(0, 0.1, (60, 3)), rng.normal(0, 60.0, (30, 3))  # 60 mm: another robot or set-up
    test = {"nominal": t, "geometric": t, "final": t}
    msgs = inconclusive_reasons(None, _models(base, test=test), _cal(base), {k: error_stats(v) for k, v in test.items()})
    assert re.search(r"every model misses the test file: .* another robot, tool or set-up", msgs[0])


def test_safe_model_is_the_last_that_held():
    rng = np.random.default_rng(2)
    e = rng.normal(0, 0.1, (80, 3))
    nominal, geometric, final = _ev((), e), _ev((), 0.5 * e), _ev(("a",), 0.3 * e)
    nominal = Evaluation("nominal", (), None, (), np.zeros(0, int), e, None, None)
    st = {"nominal": error_stats(e), "geometric": error_stats(0.5 * e), "final": error_stats(0.3 * e)}
    assert safe_model(nominal, geometric, final, st, inconclusive=False) == "geometric+a"
    assert safe_model(nominal, geometric, final, st, inconclusive=True) == "geometric"  # effects not claimed
    st["final"] = error_stats(1.2 * e)  # the final model does not transfer to the test file
    assert safe_model(nominal, geometric, final, st, inconclusive=False) == "geometric"
    st["geometric"] = error_stats(1.1 * e)  # geometry alone does not hold on the test file ...
    assert safe_model(nominal, geometric, final, st, inconclusive=False) == "nominal"  # ... and the final does not
    st["final"] = error_stats(0.3 * e)
    assert safe_model(nominal, geometric, final, st, inconclusive=False) == "geometric+a"  # judged against nominal
    assert safe_model(nominal, geometric, final, st, inconclusive=True) == "nominal"
    assert safe_model(nominal, geometric, final, None, inconclusive=False) == "geometric+a"  # CV only


def test_summary_lines_state_the_verdict_first_and_the_json_keys():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "joint_compliance", 60, np.random.default_rng(5))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    d = diagnose(robot, measurements_from_frame(tr, robot), measurements_from_frame(te, robot), folds=2,
                 max_effects=1)
    lines = summary_lines(d)
    assert lines[0] == d.verdict.headline() and lines[0].startswith("verdict: ")
    assert "reasons:" in lines and any(ln.startswith("safe to use: the ") for ln in lines)
    assert any(ln.startswith("ranking (by the clipped out-of-fold RMS of the training file") for ln in lines)
    js = d.to_dict()
    assert js["verdict"] in VERDICTS and isinstance(js["reasons"], list) and js["safe_model"]
    assert all("test_rms_mm" not in c for c in js["ranking"])  # candidates never see the test file
    assert js["settings"]["robust_loss"] == d.calibration.loss == "huber" and "outliers" in js  # auto, 45 poses


@pytest.mark.parametrize("excess, separable", [(0.03, False), (0.07, True)])
def test_alternative_is_judged_by_the_size_of_its_loss_not_its_p_value(monkeypatch, excess, separable):
    """An alternative whose clipped out-of-fold RMS is within the 5 % practical margin of the selected model's is tied,
    however small the p-value (here 1e-12); beyond the margin it is beaten, however large the p-value (0.5)."""
    import tolalloc.diagnose.verdict as verdict

    evals, stages = _world(0.0)
    evals["geometric+b"] = _ev(("b",), (1.0 + excess) * evals["geometric+a"].oof_mm)
    monkeypatch.setattr(verdict, "paired_pvalue", lambda *a: 1e-12 if not separable else 0.5)
    clip = 10.0  # no clipping: the excess is exactly the RMS ratio
    out = compare_alternatives(None, evals["geometric+a"], stages, evals, None, clip, 0.01, 0.02)
    assert out[0].separable is separable and out[0].excess_pct == pytest.approx(100 * excess)
    assert out[0].margin_pct == 100 * verdict.PRACTICAL_MARGIN


def test_at_most_two_tied_alternatives_are_named_the_closest_first():
    from tolalloc.diagnose.verdict import Comparison, Verdict, tied

    comps = tuple(Comparison("a", x, 0.5, 0.0, 0.1, 0.1, False, ex) for x, ex in (("c", 4.0), ("b", 1.0), ("d", 2.5)))
    assert [c.alternative for c in tied(comps)] == ["b", "d"]
    v = Verdict("ambiguous", ("a", "b", "d"), (), "x", comps, selected=("a",))
    assert v.headline().startswith("verdict: ambiguous -- a or b or d;")


def test_ambiguous_headline_keeps_the_model_structure():
    from tolalloc.diagnose.verdict import Comparison, Verdict

    amb = Comparison("backlash", "link_deflection", 0.2, 1.0, 0.1, 0.1, False)
    v = Verdict("ambiguous", ("joint_compliance", "backlash", "link_deflection"), (), "x", (amb,),
                selected=("joint_compliance", "backlash"))
    assert v.headline() == ("verdict: ambiguous -- joint_compliance + (backlash or link_deflection); these poses "
                            "cannot tell them apart")
    one = Verdict("ambiguous", ("backlash", "link_deflection"), (), "x", (amb,), selected=("backlash",))
    assert one.headline().startswith("verdict: ambiguous -- backlash or link_deflection;")


def test_none_says_which_effects_were_not_tested():
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    skipped = Candidate("thermal", False, "no temperature_c column, and no time_s column", 0, np.nan, np.nan,
                        1.0, 0.0, False)
    st = [Stage((), 0.1, (_cand("a", sig=False), skipped), None)]
    v = verdict_of(ctx, st, _ev((), np.zeros((5, 3))), None, (), [], (), "geometric", None)
    assert v.verdict == "none" and v.untested == ("thermal",)
    assert v.headline().startswith("verdict: none -- none of the tested effects") and "not tested: thermal" in v.headline()
    assert "thermal not tested: no temperature_c column" in v.reasons[-1]


def test_none_names_the_raised_minimum_gain_of_a_small_file():
    note = "minimum gain of a selected effect raised from 2 % to 7.45 %: 30 training poses for 25 parameters"
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={}, robust_notes=[note])
    weak = Candidate("a", True, "", 2, 0.1, 0.1, 3e-4, 6.8, False, 0.095, "v")
    st = [Stage((), 0.1, (weak,), None)]
    v = verdict_of(ctx, st, _ev((), np.zeros((5, 3))), None, (), [], (), "geometric", None, min_gain=1 / np.sqrt(180))
    assert v.verdict == "none"
    assert v.reasons[0] == ("no candidate effect is selected; the best, a (v), fails: its clipped gain +6.8 % is below "
                            "the minimum 7.45 %")
    assert note in v.reasons


def test_none_names_the_level_the_evidence_leader_failed_and_the_poses_it_would_take():
    """The best candidate, singled out by the model evidence, fails the uncorrected level too: the reason says both
    levels and how many poses would pass it at the same gain (z ~ sqrt(poses): 4x the poses where z must double)."""
    from scipy.stats import norm

    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    p = float(norm.sf(0.5 * (norm.isf(0.01) + norm.ppf(0.8))))  # half the z that passes 0.01 at 80 % power
    lead = Candidate("a", True, "", 2, 0.1, 0.1, p, 20.0, False, 0.095, "v")
    st = [Stage((), 0.1, (lead,), None, n_tests=5, leader="a", n_poses=30)]
    v = verdict_of(ctx, st, _ev((), np.zeros((5, 3))), None, (), [], (), "geometric", None)
    assert v.reasons[0] == (f"no candidate effect is selected; the best, a (v), fails: its p-value {p:.2g} is not "
                            "below the level 0.002 (alpha 0.01 over 5 candidates), nor below 0.01, the level of the "
                            "family the model evidence singles out; with the same gain per pose, about 120 training "
                            "poses (now 30) would pass it at 80 % power (a rough extrapolation)")
    other = verdict_of(ctx, [replace(st[0], leader="b")], _ev((), np.zeros((5, 3))), None, (), [], (), "geometric",
                       None)
    assert "nor below" not in other.reasons[0] and "training poses (now 30)" in other.reasons[0]
    small = verdict_of(ctx, [Stage((), 0.1, (replace(lead, gain_pct=1.0),), None, n_tests=5, leader="a", n_poses=30)],
                       _ev((), np.zeros((5, 3))), None, (), [], (), "geometric", None)
    assert "training poses" not in small.reasons[0]  # a gain below the margin: no count of poses


def test_poses_to_pass_extrapolates_the_signed_rank_test():
    """Closed form, and the Wilcoxon test's power at the poses it gives (seeded Monte Carlo)."""
    from scipy.stats import norm, wilcoxon

    from tolalloc.diagnose.scores import poses_to_pass

    assert poses_to_pass(float(norm.sf(1.0)), float(norm.sf(2.0)), 10, power=0.5) == 40
    assert poses_to_pass(0.6, 0.01, 10) is None and poses_to_pass(0.1, 0.01, 0) is None
    rng = np.random.default_rng(5)
    n0, mu, level = 25, 0.3, 0.01
    p0 = np.median([wilcoxon(rng.normal(mu, 1.0, n0), alternative="greater").pvalue for _ in range(301)])
    need = poses_to_pass(float(p0), level, n0)
    power = np.mean([wilcoxon(rng.normal(mu, 1.0, need), alternative="greater").pvalue < level for _ in range(400)])
    assert 60 < need < 300 and 0.7 <= power <= 0.92, (need, power)


def test_reason_lines_do_not_quote_a_model_the_backward_step_removed():
    """Forward: a, then b on top of a; backward: a removed. b's line compares with the geometric model, not a."""
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    back = Candidate("a", True, "backward step: not significant beside the others", 1, 0.15, 0.15, 0.3, 0.5,
                     False, 0.15, "v")  # heldout: the model without a, i.e. geometric+b
    stages = [Stage((), 0.30, (_cand("a"), _cand("b")), "a"), Stage(("a",), 0.20, (_cand("b"),), "b"),
              Stage(("a", "b"), 0.149, (back, _cand("b")), None, "a")]
    v = verdict_of(ctx, stages, _ev(("b",), np.zeros((5, 3))), None, (), [], (), "geometric+b", None)
    assert v.verdict == "effect" and v.candidates == ("b",)
    assert v.reasons[0].startswith("b (v) lowers the out-of-fold RMS of the training file (time and joint-space blocks) "
                                   "from 0.3 (geometric) to 0.15 mm")
    assert "removed a" in v.reasons[0] and "geometric+a" not in v.reasons[0]


def test_no_testable_candidate_is_inconclusive_not_none():
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    why = "the model has 40 parameters; the training file's 12 poses give 36 coordinates, fewer than the 46 it needs"
    st = [Stage((), 0.1, tuple(Candidate(e, False, why, 0, np.nan, np.nan, 1.0, 0.0, False) for e in "ab"), None)]
    v = verdict_of(ctx, st, _ev((), np.zeros((5, 3))), None, (), [], (), "geometric", None)
    assert v.verdict == "inconclusive" and v.untested == ("a", "b")
    assert v.reasons[0].startswith("no candidate effect could be tested") and f"a not tested: {why}" in v.reasons


def test_printed_final_model_is_marked_not_claimed_when_inconclusive():
    """An inconclusive verdict claims no effect: the printed summary and report name the selected model as not
    claimed (the safe model is printed with the verdict); otherwise it is the final model."""
    from types import SimpleNamespace

    from tolalloc.report.diagnosis import _final_name

    def diag(verdict, effects):
        return SimpleNamespace(verdict=SimpleNamespace(verdict=verdict), effects=effects)

    assert "not claimed" in _final_name(diag("inconclusive", ("joint_compliance",)))
    assert _final_name(diag("inconclusive", ())) == "final model"  # nothing selected: the final model is geometric
    assert _final_name(diag("effect", ("joint_compliance",))) == "final model"
    assert _final_name(diag("ambiguous", ("a", "b"))) == "final model"


def test_safe_model_with_a_larger_largest_error_than_nominal_says_so():
    """A safe model held (RMS no higher, largest error within MAX_ERROR_RATIO x nominal's) but its largest test error
    is above the nominal model's: the 'safe to use' line says so with both figures; no note when it is not."""
    from types import SimpleNamespace

    from tolalloc.report.diagnosis import safe_max_note

    def diag(safe, final_max):
        t = pd.DataFrame({"model": ["nominal", "geometric", "final"], "label": ["nominal", "geometric", "geometric+a"],
                          "max_mm": [1.671, 1.5, final_max]})
        return SimpleNamespace(test=object(), verdict=SimpleNamespace(safe_model=safe), before_after=lambda which: t)

    note = safe_max_note(diag("geometric+a", 2.303))
    assert "2.303 mm" in note and "1.671 mm" in note and f"{MAX_ERROR_RATIO:g} x" in note
    assert safe_max_note(diag("geometric+a", 1.2)) == ""
    assert safe_max_note(diag("geometric", 2.303)) == ""  # the safe geometric model's largest error is below nominal's
    assert safe_max_note(diag("nominal", 2.303)) == ""
    assert safe_max_note(SimpleNamespace(test=None)) == ""


@pytest.mark.parametrize("gain_m, a_tied, verdict", [(2.3, False, "effect"), (8.0, False, "effect"),
                                                     (2.3, True, "ambiguous"), (8.0, True, "ambiguous")])
def test_a_tie_on_a_later_effect_leaves_the_clear_first_one_claimed(gain_m, a_tied, verdict):
    """a is selected first (gain 30 %), m on top of it; m is tied with j. a clearly ahead of b: the verdict names a
    alone; m stays in the final model, its family not claimed -- a minor effect (gain below the 5 % margin) reported
    as such, a larger one named in the headline with j as a further effect the data cannot attribute, with the poses
    that would separate them. a tied too: ambiguous, whatever m's gain."""
    from tolalloc.diagnose.verdict import Comparison

    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    m = Candidate("m", True, "", 1, 0.1, 0.1, 1e-4, gain_m, True, 0.1, "v")
    j = Candidate("j", True, "", 1, 0.1, 0.1, 1e-3, 2.0, True, 0.1, "v")
    stages = [Stage((), 0.30, (_cand("a"), _cand("b")), "a"), Stage(("a",), 0.20, (m, j), "m")]
    comps = (Comparison("a", "b", 1e-6, 20.0, 0.1, 0.12, not a_tied, 2.0 if a_tied else 20.0),
             Comparison("m", "j", 0.4, 1.0, 0.1, 0.101, False, 1.0))
    poses = pd.DataFrame({"outside_training": [True, False], "predicted_difference_mm": [0.05, 0.02]})
    v = verdict_of(ctx, stages, _ev(("a", "m"), np.zeros((5, 3))), None, comps, [], (), "geometric+a+m", poses)
    assert v.verdict == verdict and v.selected == ("a", "m")
    if verdict == "ambiguous":
        assert "m" in v.candidates and "j" in v.candidates and v.further == ()
        return
    assert v.candidates == ("a",) and v.to_dict()["further"] == list(v.further)
    if gain_m < 5.0:
        assert v.headline() == "verdict: effect -- a" and v.further == () and v.suggestions is None
        line = next(r for r in v.reasons if r.startswith("m adds a gain below the practical margin"))
        assert "(+2.3 % < 5 %)" in line and "from j in its place" in line and "not claimed" in line
    else:
        assert v.further == ("m",) and v.suggestions is poses
        assert v.headline() == "verdict: effect -- a; a further effect the data cannot attribute to one family: m or j"
        line = next(r for r in v.reasons if r.startswith("m adds a further gain of +8.0 %"))
        assert "j (+1.0 %) in its place" in line and "its family not claimed" in line
        assert any(r.startswith("poses that would separate them: suggested_poses") and "1 of 2 lie outside" in r
                   for r in v.reasons)


def test_a_mount_about_a_pivot_below_the_base_is_one_more_column_whose_ratio_is_the_depth():
    """The pivot variant's columns reproduce a rigid tilt omega = c M_h about a point h below the base origin."""
    from tolalloc.physics.compliance import mount_columns
    from tolalloc.physics.loads import base_moment, target_points

    robot = tolalloc.load_robot("ur10")
    q = np.random.default_rng(3).uniform(-2, 2, (6, robot.n_joints))
    p = target_points(robot, q, np.zeros(3))
    c, h = 2e-7, 350.0
    B, names = mount_columns(robot, q, p, p, None, "pivot")
    assert B.shape == (6, 3, 2) and names == ["c_mount [rad/(N m)]", "c_mount_depth [rad mm/(N m)]"]
    g = np.asarray(robot.gravity, float)
    M = base_moment(robot, q, p, 0.0)
    omega = c * (M - (M @ g)[:, None] * g)
    expected = np.cross(omega, p - h * g)
    np.testing.assert_allclose(B @ np.array([c, c * h]), expected, rtol=1e-12, atol=1e-15)
    iso, _ = mount_columns(robot, q, p, p, None, "isotropic")
    np.testing.assert_allclose(B[..., 0], iso[..., 0])


def test_a_base_rocking_about_one_horizontal_axis_is_the_tensor_variant_with_the_sole_depth():
    """A base rocking on a sole bowed along one heading e (omega = e (e . M_h) / (W R), about the sole's crest h below
    the base): a rank-one symmetric compliance the isotropic and base-axes variants cannot hold; the tensor variant's
    six columns reproduce it exactly, and its first two are the base-axes variant's."""
    from tolalloc.physics.compliance import mount_columns
    from tolalloc.physics.loads import base_moment, target_points

    robot = tolalloc.load_robot("ur10")
    q = np.random.default_rng(4).uniform(-2, 2, (40, robot.n_joints))
    p = target_points(robot, q, np.zeros(3))
    g = np.asarray(robot.gravity, float)
    M = base_moment(robot, q, p, 0.0)
    Mh = M - (M @ g)[:, None] * g
    e, k, h = np.array([np.cos(0.6), np.sin(0.6), 0.0]), 3e-7, 450.0
    expected = np.cross(k * (Mh @ e)[:, None] * e, p - h * g)
    B, names = mount_columns(robot, q, p, p, None, "tensor")
    assert B.shape == (40, 3, 6) and names[:3] == ["c_mount_xx [rad/(N m)]", "c_mount_yy [rad/(N m)]",
                                                   "c_mount_xy [rad/(N m)]"]
    C = k * np.outer(e, e)
    np.testing.assert_allclose(B @ np.r_[C[0, 0], C[1, 1], C[0, 1], h * C[0, 0], h * C[1, 1], h * C[0, 1]], expected,
                               rtol=1e-10, atol=1e-15)
    axes, _ = mount_columns(robot, q, p, p, None, "axes")
    np.testing.assert_allclose(B[..., :2], axes)
    for variant in ("isotropic", "axes", "pivot"):  # a least-squares fit of the others leaves most of it
        A, _ = mount_columns(robot, q, p, p, None, variant)
        A = A.reshape(-1, A.shape[-1])
        r = expected.ravel() - A @ np.linalg.lstsq(A, expected.ravel(), rcond=None)[0]
        assert np.linalg.norm(r) > 0.3 * np.linalg.norm(expected), variant


@pytest.mark.parametrize("log_bf, verdict", [(np.log(30.0), "effect"), (np.log(10.0), "ambiguous"),
                                             (-np.log(30.0), "ambiguous")])
def test_a_tie_in_held_out_rms_is_decided_by_strong_evidence_only(log_bf, verdict):
    """Two families tied on the held-out RMS (``b`` in place of ``a`` as good): a Bayes factor of 30 for the selected
    family separates them (named alone, the reason states the factor); 10 (below Kass and Raftery's 20) or a factor
    for the alternative leaves the verdict ambiguous."""
    from tolalloc.diagnose.families import DECISIVE_BAYES_FACTOR, bayes_factor

    evals, stages = _world(0.0)
    logml = {"none": -50.0, "a": 10.0 + log_bf, "b": 10.0}
    out = compare_alternatives(None, evals["geometric+a"], stages, evals, None, clip_level(evals["geometric"].oof_mm),
                               0.01, 0.02, logml=logml)
    assert out[0].bayes_factor == pytest.approx(np.exp(log_bf)) == bayes_factor(logml, "a", "b")
    assert abs(out[0].excess_pct) < out[0].margin_pct                  # tied by what the two predict
    assert out[0].separable is bool(np.exp(log_bf) >= DECISIVE_BAYES_FACTOR) is out[0].by_evidence
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    v = verdict_of(ctx, stages, evals["geometric+a"], None, out, [], (), "geometric+a", None)
    assert v.verdict == verdict
    if verdict == "effect":
        assert v.candidates == ("a",) and any("Bayes factor of 30 (decisive from 20)" in r for r in v.reasons)
    # a comparison at a later step (a base of other effects) has no single-family evidence: the margin rule alone
    later = [Stage(("x",), 0.2, stages[0].candidates, "a")]
    assert not compare_alternatives(None, evals["geometric+a"], later, evals, None, 1.0, 0.01, 0.02,
                                    logml=logml)[0].separable


def test_the_first_step_selects_the_family_the_evidence_favours_among_those_tied_with_the_best():
    """evidence_pick: among the significant candidates within the practical margin of the best clipped held-out RMS,
    the one with a Bayes factor of at least 20 over each other; none when the factor is weaker, when one of the
    tied candidates is not favoured against, or when no other candidate is within the margin."""
    from tolalloc.diagnose.families import evidence_pick

    def cand(e, r, sig=True):
        return replace(_cand(e, sig), robust_rms_mm=r)

    cands = [cand("a", 0.100), cand("b", 0.103), cand("c", 0.104), cand("d", 0.200), cand("e", 0.101, sig=False)]
    strong = {"a": 0.0, "b": 10.0, "c": 5.0, "d": 100.0, "e": 100.0}   # d: better evidence, beaten on RMS
    assert evidence_pick(cands, strong, 0.05).effect == "b"             # BF e^5 over c, e^10 over a
    assert evidence_pick(cands, {**strong, "c": 8.0}, 0.05) is None     # BF e^2 = 7.4 over c: not decisive
    assert evidence_pick(cands, strong, 0.02) is None                   # only a within 2 %: no tie
    assert evidence_pick(cands, {}, 0.05) is None                       # no evidence stated
    assert evidence_pick(cands[:3], {"a": 4.0, "b": 0.0, "c": 0.0}, 0.05).effect == "a"


def test_a_family_too_wide_for_the_residual_is_left_out_of_the_evidence_not_the_others():
    """family_log_evidence on a constructed residual (P = 40 poses, 120 coordinates, 6 fixed columns): the family
    that made it (``a``, 2 columns) gets a decisive factor over one that did not (``b``); a 60-column family (more
    than a third of the 114 degrees of freedom) is left out instead of silencing every probability; the ``none``
    evidence is the Gaussian likelihood at the ML noise level."""
    from tolalloc.diagnose.choice import projected_residual
    from tolalloc.diagnose.families import bayes_factor, family_log_evidence, posterior_probabilities

    rng = np.random.default_rng(3)
    P = 40
    J_fixed = rng.normal(size=(3 * P, 6))
    Ba, Bb, Bwide = rng.normal(size=(P, 3, 2)), rng.normal(size=(P, 3, 2)), rng.normal(size=(P, 3, 60))
    res = (Ba @ np.array([0.3, -0.2]) + rng.normal(0, 0.02, (P, 3)))
    fit = SimpleNamespace(R=np.eye(3), residual_mm=res)
    ctx = SimpleNamespace(cal=SimpleNamespace(geometric=fit), J_fixed=J_fixed, geo_residual=res,
                          bases={"a": SimpleNamespace(B=Ba, groups=None), "b": SimpleNamespace(B=Bb, groups=None),
                                 "wide": SimpleNamespace(B=Bwide, groups=None)})
    logml = family_log_evidence(ctx)
    assert set(logml) == {"none", "a", "b"}                           # 3 x 60 > 114: wide is not weighed
    _, r, n = projected_residual(fit, J_fixed, res)
    assert n == 3 * P - 6
    assert logml["none"] == pytest.approx(-0.5 * n * (np.log(2 * np.pi * (r @ r) / n) + 1.0))
    assert bayes_factor(logml, "a", "b") > 1e6 and posterior_probabilities(logml)["a"] > 0.999
    ctx.bases = {"wide": ctx.bases["wide"]}
    assert family_log_evidence(ctx) == {} and posterior_probabilities({}) == {}


def test_the_evidence_leader_beats_no_effect_and_every_other_family_by_a_very_strong_factor():
    """evidence_leader: the family whose Bayes factor against ``none`` and each other family is at least 150 (Kass
    and Raftery's *very strong*, 2 ln B > 10); none when a rival or the noise alone comes closer, or when ``none``
    is not weighed."""
    from tolalloc.diagnose.families import LEADING_BAYES_FACTOR, evidence_leader

    assert LEADING_BAYES_FACTOR == 150.0
    e = np.log(LEADING_BAYES_FACTOR)
    assert evidence_leader({"none": 0.0, "a": e + 0.1, "b": 0.0})[0] == "a"
    assert evidence_leader({"none": 0.0, "a": e + 0.1, "b": 0.0})[1] == pytest.approx(np.exp(e + 0.1))
    assert evidence_leader({"none": 0.0, "a": e + 0.1, "b": 0.2})[0] is None      # b within a factor 150
    assert evidence_leader({"none": 1.0, "a": e + 0.5, "b": -9.0})[0] is None     # no effect within a factor 150
    assert evidence_leader({"a": 50.0, "b": 0.0})[0] is None                      # no effect not weighed
    assert evidence_leader({})[0] is None


@pytest.mark.parametrize("p, gain, leader, led, step_gain", [
    (0.004, 9.0, "a", True, 0.02),     # not below 0.01 / 6, below 0.01; gain above the 5 % margin: named
    (0.02, 9.0, "a", False, 0.02),     # not below alpha
    (0.004, 3.0, "a", False, 0.02),    # gain below the practical margin
    (0.004, 9.0, "b", False, 0.02),    # the evidence singles out another family
    (0.004, 6.0, "a", False, 0.0745),  # above the margin, below a small file's raised minimum gain
    (0.004, 9.0, "a", True, 0.0745),   # above both
])
def test_the_family_the_evidence_singles_out_is_tested_at_the_uncorrected_level(p, gain, leader, led, step_gain):
    """_evidence_led: where no candidate passes alpha / m, the family the evidence singles out is significant at
    p < alpha with a clipped gain of at least the practical margin; its reason line says so."""
    from tolalloc.diagnose.families import evidence_leader
    from tolalloc.diagnose.stepwise import _evidence_led

    c = replace(_cand("a", sig=False), p_value=p, gain_pct=gain)
    logml = {"none": 0.0, leader: 20.0, "a" if leader == "b" else "b": 1.0}
    out = _evidence_led(c, evidence_leader(logml)[0], 0.01, step_gain)
    assert out.significant is led and out.evidence_led is led and out.to_dict()["evidence_led"] is led
    if led:
        ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
        v = verdict_of(ctx, [Stage((), 0.3, (out, _cand("b", sig=False)), "a", n_tests=6)],
                       _ev(("a",), np.zeros((5, 3))), None, (), [], (), "geometric+a", None, min_gain=step_gain)
        assert v.verdict == "effect" and v.candidates == ("a",)
        bar = max(5.0, 100 * step_gain)
        assert (f"tested alone, at alpha without the factor for 6 candidates and with a {bar:.3g} % minimum gain"
                in v.reasons[0])
        assert "Bayes factor of at least 150 against no effect and every other family" in v.reasons[0]
