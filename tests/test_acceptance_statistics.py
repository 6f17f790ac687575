"""ISO 9283 statistics (tolalloc.acceptance.statistics) against hand-computed values, and the decision rule of
ISO 14253-1 (tolalloc.acceptance.decision) on each of its outcomes."""

import numpy as np
import pytest

from tolalloc.exceptions import TolallocError
from tolalloc.acceptance import statistics as st
from tolalloc.acceptance.decision import (ABOVE_LIMIT, CONFORMANCE, INSIDE_GUARD_BAND, NONCONFORMANCE, decide)


def test_pose_accuracy_is_distance_of_barycentre():
    att = np.array([[1.0, 0, 0], [3.0, 0, 0], [2.0, 3.0, 0], [2.0, -3.0, 4.0]])  # barycentre (2, 0, 1)
    assert st.pose_accuracy(att, [2.0, 0.0, -1.0]) == pytest.approx(2.0)
    assert st.pose_accuracy(att, [0.0, 0.0, 1.0]) == pytest.approx(2.0)


def test_pose_repeatability_by_hand():
    # four points at distance 1 from their barycentre: lb = 1, S_l = 0
    ring = np.array([[1.0, 0, 0], [-1.0, 0, 0], [0, 1.0, 0], [0, -1.0, 0]])
    assert st.pose_repeatability(ring) == pytest.approx(1.0)
    # points on a line at -3, -1, 1, 3: l = (3, 1, 1, 3), lb = 2, S_l = sqrt(4 / 3)
    line = np.array([[-3.0, 0, 0], [-1.0, 0, 0], [1.0, 0, 0], [3.0, 0, 0]])
    assert st.pose_repeatability(line + 5.0) == pytest.approx(2 + 3 * np.sqrt(4 / 3))


def test_orientation_statistics_by_hand():
    a = np.array([[0.1, 0.0, -0.2], [0.3, 0.0, -0.2], [0.2, 0.3, -0.2]])
    np.testing.assert_allclose(st.orientation_accuracy(a, [0.0, 0.1, 0.0]), [0.2, 0.0, -0.2], atol=1e-15)
    np.testing.assert_allclose(st.orientation_repeatability(a), [0.3, 3 * np.sqrt(0.03), 0.0], atol=1e-15)


def test_distance_statistics_by_hand():
    p1 = np.zeros((3, 3))
    p2 = np.array([[10.0, 0, 0], [0, 11.0, 0], [0, 0, 12.0]])  # distances 10, 11, 12
    assert st.distance_accuracy(p1, p2, [0, 0, 0], [10.5, 0, 0]) == pytest.approx(0.5)
    assert st.distance_repeatability(p1, p2) == pytest.approx(3.0)


def test_path_statistics_by_hand():
    cmd = np.array([[0.0, 0, 0], [10.0, 0, 0]])
    att = np.array([[[0, 1.0, 0], [10, 0, 0.5]], [[0, 3.0, 0], [10, 0, 0.5]]])  # 2 cycles, 2 points
    assert st.path_accuracy(att, cmd) == pytest.approx(2.0)
    assert st.path_repeatability(att) == pytest.approx(1 + 3 * 0.0)


def test_statistics_need_two_cycles():
    with pytest.raises(TolallocError, match=r"attained_mm \(number of cycles\): expected a whole number of cycles of "
                                            r"at least 2 .* got 1"):
        st.pose_repeatability(np.zeros((1, 3)))
    with pytest.raises(TolallocError, match=r"cycles: expected a whole number of cycles of at least 2"):
        st.check_cycles(1)
    with pytest.raises(TolallocError, match=r"expected the attained values of the cycles as an array of shape"):
        st.pose_accuracy(np.zeros((4, 2)), np.zeros(2))


@pytest.mark.parametrize("value, U, outcome, margin", [
    (0.040, 0.005, CONFORMANCE, 0.005),
    (0.048, 0.005, INSIDE_GUARD_BAND, -0.003),
    (0.052, 0.005, ABOVE_LIMIT, -0.007),
    (0.056, 0.005, NONCONFORMANCE, -0.011),
])
def test_decision_rule_iso_14253(value, U, outcome, margin):
    d = decide(value, 0.05, U)
    assert d.outcome == outcome
    assert d.margin == pytest.approx(margin)
    assert d.demonstrated == (outcome == CONFORMANCE)


def test_decision_text_says_by_how_much():
    assert decide(0.048, 0.05, 0.005).text() == (
        "not demonstrated: inside the limit, within U of it: 0.048 mm is 0.002 mm below the limit 0.05 mm but U = "
        "0.005 mm; conformance needs the value 0.003 mm lower, or U <= 0.002 mm")
    assert decide(0.04, 0.05, 0.005).text().startswith("conformance demonstrated: 0.04 mm + U 0.005 mm = 0.045 mm")
