"""Blind identification: the diagnosis never sees the label; >= 90 % correct on a small benchmark.

A smaller version of studies/sim2real_blind (2 robots x 6 labels, 100 poses, 3-fold CV).
"""

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose import LABELS, diagnose, generate, measurements_from_frame


@pytest.fixture(scope="module")
def results():
    out = []
    rng = np.random.default_rng(2024)
    for name in ("tool_changer", "ur10"):
        robot = tolalloc.load_robot(name)
        for label in LABELS:
            case = generate(robot, label, 100, rng)
            d = diagnose(robot, measurements_from_frame(case.frame, robot), folds=3)
            out.append((label, d))
    return out


@pytest.mark.slow
def test_blind_identification_rate(results):
    correct = sum(d.effect == label for label, d in results)
    assert correct / len(results) >= 0.9, [(label, d.effect) for label, d in results]


def test_heldout_shrinks_when_an_effect_is_found(results):
    for label, d in results:
        g, f = d.geometric.heldout_rms_mm, d.final.heldout_rms_mm
        if d.effect != "none":
            assert f < 0.9 * g
            top = d.ranking[0]
            assert top.effect == d.effect and top.p_value < 0.01 / 5
        else:
            assert f == g


def test_json_summary_keys(results):
    label, d = results[0]
    js = d.to_dict()
    assert js["effect"] in (*LABELS,)
    assert set(js["cv_rms_mm"]) == {"nominal", "geometric", "final"} and "rms_mm" not in js
    assert {"effect", "heldout_rms_mm", "p_value"} <= set(js["ranking"][0])
    assert len(js["ranking"]) == len(LABELS) - 1  # every effect family, applicable or not
