"""Verdicts of the diagnosis (diagnose/verdict.py, verdict_text.py): ambiguous, inconclusive, the safe model, and
the printed summary (report/diagnosis.py summary_lines).

Constructed evaluations (known out-of-fold residuals) test the decision rules without fitting; one small
synthetic diagnosis checks the whole printed summary and the JSON keys."""

from types import SimpleNamespace

import numpy as np
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
    return Candidate(e, True, "", 1, 0.1, 0.1, None, 1e-9 if sig else 0.5, 30.0 if sig else 0.0, sig, 0.1, "v")


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


def test_inconclusive_reasons_and_precedence():
    rng = np.random.default_rng(1)
    base = rng.normal(0, 0.1, (60, 3))
    nominal = _ev((), base)
    cal_nominal = SimpleNamespace(rms_mm=float(np.sqrt(np.mean(np.sum(base ** 2, 1)))))
    assert inconclusive_reasons(None, nominal, cal_nominal, None) == []
    wild = _ev((), (UNSTABLE_RATIO + 1) * base)  # out-of-fold four times the training RMS
    assert "unstable out of fold" in inconclusive_reasons(None, wild, cal_nominal, None)[0]
    n, f = error_stats(base), error_stats(1.1 * base)
    msgs = inconclusive_reasons(None, nominal, cal_nominal, {"nominal": n, "final": f})
    assert len(msgs) == 1 and "does not transfer" in msgs[0]
    spike = 0.5 * base
    spike[0] = [0, 0, (MAX_ERROR_RATIO + 0.5) * n["max_mm"]]
    msgs = inconclusive_reasons(None, nominal, cal_nominal, {"nominal": n, "final": error_stats(spike)})
    assert len(msgs) == 1 and "largest test error" in msgs[0]
    check = SimpleNamespace(names=("probe_offset_z",), status=("weak",), value=np.array([73.0]),
                            sd=np.array([54.0]), level=np.array([1.2]))
    assert "probe offset is weakly identified" in inconclusive_reasons(check, nominal, cal_nominal, None)[0]
    ctx = SimpleNamespace(train=SimpleNamespace(time_s=None), test=None, bases={})
    final = _ev(("a",), 0.5 * base)
    v = verdict_of(ctx, [Stage((), 0.1, (_cand("a"),), "a")], final, None, (), msgs, (), "geometric", None)
    assert v.verdict == "inconclusive" and v.candidates == () and "not claimed" in v.reasons[-1]


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
    st["geometric"] = error_stats(1.1 * e)
    assert safe_model(nominal, geometric, final, st, inconclusive=False) == "nominal"
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
    assert any(ln.startswith("ranking (out-of-fold RMS of the training file") for ln in lines)
    js = d.to_dict()
    assert js["verdict"] in VERDICTS and isinstance(js["reasons"], list) and js["safe_model"]
    assert all(c["test_rms_mm"] is None for c in js["ranking"])  # candidates never see the test file
    assert js["settings"]["robust_loss"] == "tukey" and "outliers" in js
