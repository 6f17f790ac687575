"""End-to-end Monte Carlo of a calibration-aware design at its worst poses (tolalloc.verify.calibrated_worst)."""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.design import allocate_with_calibration
from tolalloc.allocate.problem import build_problem
from tolalloc.calibration import make_plan
from tolalloc.calibration.design import candidate_poses
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot
from tolalloc.verify.calibrated_worst import verify_calibrated_design
from tolalloc.verify.designs import pose_verdicts


@pytest.fixture(scope="module")
def res():
    robot = load_robot("tool_changer")
    pr = build_problem(build_error_model(robot), robot.poses("working")[:5])
    return allocate_with_calibration(pr, make_plan(robot, candidate_poses(robot, 12, seed=5)), baseline=False)


def test_worst_poses_of_each_design(res):
    from tolalloc.allocate.calibrated.exact import post_probabilities

    for which, design in (("chosen", res.design), ("certified", res.certified.design)):
        split = res.end_to_end_inputs(2, which)["split"]
        q = res.check_poses(2, which)
        p_all, _ = post_probabilities(res.problem, split, res.plan, design.t)
        np.testing.assert_allclose(q, res.problem.q[np.argsort(p_all)[:2]])
    with pytest.raises(TolallocError, match="which: expected 'chosen' or 'certified'"):
        res.check_poses(2, "best")


def test_verdicts_and_linear_agreement(res):
    e = verify_calibrated_design(res, n_robots=400, seed=2, k_worst=2)
    c = e.check
    assert e.design == "exact" and res.exact_accepted and len(c.q) == 2
    np.testing.assert_array_equal(e.verdicts, pose_verdicts(c.ci_low, c.ci_high, res.problem.prob))
    assert np.all(c.agree), e.message()  # the linear post-calibration P lies in the simultaneous interval
    assert e.passed == (bool(np.all(e.verdicts != "failed")) and not np.any(c.p_linear > c.ci_high))
    d = e.to_dict()
    assert d["n_robots"] == 400 and d["poses"] == 2 and d["verdict"] == e.verdict
    assert list(e.to_frame().columns)[-1] == "verdict" and "worst poses" in e.message()
    ec = verify_calibrated_design(res, which="certified", n_robots=200, seed=2, k_worst=1)
    assert ec.design == "certified" and ec.passed == bool(np.all(ec.verdicts == "demonstrated") and
                                                         np.all(ec.check.p_linear <= ec.check.ci_high))


def test_bad_arguments(res):
    with pytest.raises(TolallocError, match="n_robots: expected a whole number >= 10"):
        verify_calibrated_design(res, n_robots=5)
    with pytest.raises(TolallocError, match="which: expected"):
        verify_calibrated_design(res, which="exact")
