"""The workspace-allocation study's building blocks against known answers (issue 13, item 5).

The coverage statement failing for a pose-set design on a region it does not cover is tested in
tests/test_allocate_region.py (test_coverage_fails_for_a_pose_set_design_on_a_region_it_does_not_cover);
here: the worst-pose search's batched gradient (it must find the closed-form worst pose by itself when the
seed sample is too small to land near it) and the study's P slice (the figure) against the allocation
problem's own probabilities at the same poses.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.problem import make_design
from tolalloc.allocate.region import box_region, coverage, worst_pose
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io.robotfile import robot_from_chain_dict

from test_allocate_region import PLANAR

STUDY = Path(__file__).resolve().parents[1] / "studies" / "workspace_allocation"


@pytest.fixture(scope="module")
def planar():
    # in-plane errors only: the error grows with the reach, so the worst pose of a box containing q2 = 0 is the
    # stretched arm q2 = 0 (any q1, rotation symmetry); a design allocated at the folded pose q2 = 60 deg
    robot = robot_from_chain_dict(PLANAR)
    model = build_error_model(robot, exclude=("axis_deflection",))
    box = box_region(robot, np.deg2rad([0, -40]), np.deg2rad([20, 60]), "box")
    pr = build_problem(model, np.deg2rad([[10.0, 60.0]]))
    return robot, model, box, pr, allocate(pr, snap=False).design


def test_gradient_search_reaches_the_stretched_pose_from_poor_seeds(planar):
    robot, model, box, pr, d = planar
    # 2 seeds, none within 5 deg of q2 = 0: only the local search can get there
    seeds = box.sample(2, 5)
    assert np.all(np.abs(np.rad2deg(seeds[:, 1])) > 5)
    q, p, n_eval = worst_pose(pr, d.t, box, n_seed=2, n_starts=2, seed=5)
    assert abs(np.rad2deg(q[1])) < 0.01
    stretched = build_problem(model, np.array([[q[0], 0.0]]))
    # P is quadratic in q2 around the stretched pose: within 0.01 deg it equals the value there to ~1e-8
    assert p == pytest.approx(make_design(stretched, "standard", d.t).p_linear["position"][0], abs=1e-8)
    assert n_eval > 2  # the local search spent evaluations (5 poses per step for 2 free joints)


def test_study_slice_matches_the_problem_probabilities_and_the_coverage(planar, monkeypatch):
    monkeypatch.syspath_prepend(str(STUDY))
    sys.modules.pop("compute", None)
    from compute import DesignRun, RobotStudy, p_slice, slice_joints

    robot, model, box, pr, d = planar
    res = allocate(pr, snap=False)
    cov = coverage(pr, d.t, box, n=4000, seed=3)
    run = DesignRun("pose set", res, 0.0, 0.0, pr.q, cov, None, pr.q)
    study = RobotStudy("planar2", robot, model, box, "", (run,))
    centre = cov.worst_q[0]
    assert slice_joints(study, centre, run) == (0, 1)
    s = p_slice(study, run, centre, (0, 1), n_grid=9)
    X, Y = np.meshgrid(s["x"], s["y"])
    grid = np.column_stack([X.ravel(), Y.ravel()])
    ref = make_design(build_problem(model, grid), "standard", d.t).p_linear["position"].reshape(X.shape)
    np.testing.assert_allclose(s["P"], ref, rtol=0, atol=1e-12)
    # the slice passes through the worst sampled pose: its centre value is the coverage minimum
    assert s["x"][0] <= centre[0] <= s["x"][-1] and s["y"][0] <= centre[1] <= s["y"][-1]
    at_centre = make_design(build_problem(model, centre[None]), "standard", d.t).p_linear["position"][0]
    assert at_centre == pytest.approx(cov.min_p, abs=1e-12)
    # and the folded design leaves the stretched side of the slice below p (the slice shows the failure)
    assert s["P"].min() < 0.95 - 1e-4 and cov.n_below > 0
