"""Selection on few poses and with overlapping effects (issue 15 item 6): the fold count and backward elimination."""

from types import SimpleNamespace

import numpy as np
import pytest

from tolalloc.diagnose.folds import fold_count
from tolalloc.diagnose.select import Evaluation, _backward, clip_level


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
