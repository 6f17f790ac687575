"""A drawing's review holds the drawing to the rule the design was allocated by: P >= p at every pose, to within the
region search's tolerance (tolalloc.allocate.region.REGION_TOL), and says by how much the worst pose falls short."""

from types import SimpleNamespace

import numpy as np
import pytest

from tolalloc.allocate.region import REGION_TOL
from tolalloc.allocate.tolerance_analysis import DrawingAnalysis


def _analysis(p):
    p = np.asarray(p, float)
    return DrawingAnalysis(SimpleNamespace(callouts=(), parts=()), (), np.zeros(0), np.zeros(0),
                           np.zeros((len(p), 1)), p, 0.25, 0.95, int(np.argmin(p)), np.zeros(0))


@pytest.mark.parametrize("p_worst, ok, says", [
    (0.951, True, "the drawing meets it at 2 of 2 pose(s); worst pose 2: P = 0.951000\n"),
    (0.95 - 0.5 * REGION_TOL, True, "the drawing meets it within the allocation's tolerance of 0.0001 in P at 2 of 2 "
                                    "pose(s); worst pose 2: P = 0.949950 (5e-05 short)"),
    (0.95 - 2 * REGION_TOL, False, "the drawing does NOT meet it at 1 of 2 pose(s); worst pose 2: P = 0.949800 "
                                   "(0.0002 short)"),
])
def test_the_review_verdict_follows_the_allocations_tolerance_and_states_the_shortfall(p_worst, ok, says):
    a = _analysis([0.97, p_worst])
    assert a.ok is ok and a.shortfall == pytest.approx(max(0.95 - p_worst, 0.0))
    assert says in a.text() + "\n"
