"""Selection on few poses and with overlapping effects (issue 15 item 6): the fold count and backward elimination."""

from types import SimpleNamespace

import numpy as np
import pytest

from tolalloc.diagnose.folds import fold_count
from tolalloc.diagnose.select import Evaluation, choose_variant, clip_level
from tolalloc.diagnose.stepwise import _backward


@pytest.mark.parametrize("folds, rows, fixed, expected", [
    (3, 66, 27, 4),    # 22 UR10 poses: a third of the rows would take 22 of the 39 spare rows, more than half
    (3, 66, 31, 4),    # 22 Panda poses: 66 / 4 = 16.5 <= 35 / 2
    (3, 66, 45, 7),    # 21 spare rows: blocks of at most 10.5 rows
    (3, 270, 27, 3),   # 90 poses: the requested count stands
    (5, 270, 27, 5),
    (2, 30, 29, 60),   # one spare row: the bound asks for more folds than rows (make_folds caps at the poses)
])
def test_fold_count_keeps_half_the_redundancy(folds, rows, fixed, expected):
    k = fold_count(folds, rows, fixed)
    assert k == expected
    assert rows / k <= (rows - fixed) / 2 or rows - fixed <= 1
    if k > folds:  # the smallest such count
        assert rows / (k - 1) > (rows - fixed) / 2


def _ev(effects, res):
    names = tuple(f"{e}:p" for e in effects)
    return Evaluation("+".join(("geometric", *effects)), tuple(effects), None, names, np.arange(len(names)),
                      res, None, None)


def _setup(redundant: bool, P=150, seed=0):
    """Three selected effects a, b, c: removing b or c doubles the error; removing a changes nothing when
    ``redundant`` (a stood in for b + c), else it adds a clear systematic error."""
    rng = np.random.default_rng(seed)
    noise = rng.normal(0, 0.03, (P, 3))
    sys = rng.normal(0, 0.05, (P, 3))
    evals = {"geometric": _ev((), noise + 3 * sys)}
    full = _ev(("a", "b", "c"), noise)
    for rest in (("b", "c"), ("a", "c"), ("a", "b")):
        res = noise + (0.0 if (redundant and rest == ("b", "c")) else 1.0) * sys
        evals[f"geometric+{'+'.join(rest)}"] = _ev(rest, res)
    for one in "abc":  # a single effect leaves a clear systematic error
        evals[f"geometric+{one}"] = _ev((one,), noise + 2 * sys)
    ctx = SimpleNamespace(bases={e: SimpleNamespace(variant="v") for e in "abc"})
    return ctx, full, evals


def test_backward_drops_the_effect_the_others_made_redundant():
    ctx, full, evals = _setup(redundant=True)
    stages = []
    final = _backward(ctx, full, evals, stages, clip_level(evals["geometric"].oof_mm), 0.01, 0.02)
    assert final.effects == ("b", "c")
    assert stages[0].removed == "a" and stages[0].base == ("a", "b", "c")
    kept = {c.effect: c.significant for c in stages[0].candidates}
    assert kept == {"a": False, "b": True, "c": True}
    assert stages[-1].removed is None  # b and c both still pay their way beside each other


def test_backward_keeps_effects_that_all_pay_their_way():
    ctx, full, evals = _setup(redundant=False)
    stages = []
    final = _backward(ctx, full, evals, stages, clip_level(evals["geometric"].oof_mm), 0.01, 0.02)
    assert final is full and len(stages) == 1 and stages[0].removed is None
    assert all(c.significant for c in stages[0].candidates)


def _variant_problem(extra_signal: float, P=22, f=31, seed=3):
    """Residual of P poses (3P rows) off ``f`` fixed columns: 14 columns of variant A carry a signal; variant B
    is A plus 16 more columns, which carry ``extra_signal`` [mm per unit]."""
    rng = np.random.default_rng(seed)
    J_fixed = rng.normal(size=(3 * P, f))
    A = rng.normal(size=(P, 3, 14))
    extra = rng.normal(size=(P, 3, 16))
    res = A @ rng.normal(0, 0.3, 14) + extra @ (extra_signal * np.ones(16)) + rng.normal(0, 0.03, (P, 3))
    fit = SimpleNamespace(R=np.eye(3), residual_mm=res)
    cands = [SimpleNamespace(B=A, variant="A"), SimpleNamespace(B=np.concatenate([A, extra], axis=2), variant="B")]
    return cands, fit, J_fixed


def test_variant_bic_counts_the_degrees_of_freedom_left():
    # 66 rows - 31 fixed = 35 degrees of freedom: B's 30 columns nearly interpolate the noise, which a BIC with
    # the variance RSS / 66 rewarded (it mostly chose B on pure noise); with the variance from the
    # degrees of freedom left, A wins on noise and B when its extra columns carry a signal. Fixed seeds 0-19,
    # tolerance: at least 16 of 20 right each way (chance level 10).
    right_noise = sum(choose_variant(*_variant_problem(0.0, seed=s)).variant == "A" for s in range(20))
    right_signal = sum(choose_variant(*_variant_problem(0.05, seed=s)).variant == "B" for s in range(20))
    assert right_noise >= 16 and right_signal >= 16, (right_noise, right_signal)
