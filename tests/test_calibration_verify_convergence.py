"""End-to-end Monte Carlo: the count of converged calibration fits (n_converged, converged_share) is consistent with
the per-fit iteration counts and with the convergence verdict and note, in the linear regime and at 100x errors."""

import numpy as np
import pytest

from tolalloc.calibration import make_plan, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io import load_robot
from tolalloc.verify.calibrated import verify_calibration
from tolalloc.verify.calibrated_fit import _MAX_ITER


@pytest.mark.parametrize("factor", [1.0, 100.0])
def test_converged_count_matches_iterations_and_note(factor):
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    split = split_errors(model.with_sigma(factor * model.sigma))
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    chk = verify_calibration(split, plan, robot.poses("working"), 0.25 * factor, n_robots=30, seed=7)
    assert 0 <= chk.n_converged <= chk.n_robots
    assert chk.converged_share == chk.n_converged / chk.n_robots
    # a fit that left the batch before the cap converged; one that did not converge ran to the cap
    assert chk.n_converged >= int(np.sum(chk.iterations < _MAX_ITER))
    assert chk.n_robots - chk.n_converged <= int(np.sum(chk.iterations == _MAX_ITER))
    assert chk.converged == (chk.n_converged == chk.n_robots)
    bad = chk.n_robots - chk.n_converged
    assert (f"{bad} of {chk.n_robots} fits NOT converged" in chk.fits_note()) == (bad > 0)
    if factor == 1.0:  # linear regime: every fit converges
        assert chk.converged_share == 1.0
