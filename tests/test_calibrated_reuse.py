"""The calibration-aware allocation's convex step (tolalloc.allocate.calibrated.step): the compiled, re-solved (DPP)
problem gives the same step as a freshly built one; the exact per-pose check agrees with the posterior module; the
working set of poses gives the design of the full set of pose LMIs."""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.certified import _grades, allocate_calibrated
from tolalloc.allocate.calibrated.step import StepData, information, pose_ratios, solve_step
from tolalloc.allocate.problem import build_problem
from tolalloc.calibration import make_plan, posterior, split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io import load_robot

GRADE = dict(model="reciprocal", a=0.2, b=0.3, t_ref_deg=0.001, t_min_deg=0.0003, t_max_deg=0.01)


def _plan(robot, n=12):
    rng = np.random.default_rng(0)
    return make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((n, robot.n_joints)))


@pytest.fixture(scope="module")
def full_case():
    """tool_changer with clearances (random-only allocatable parts) and repeatability grades: every parameter kind."""
    robot = load_robot("tool_changer")
    model = build_error_model(robot, clearance=True)
    pr = build_problem(model, robot.poses("working")[:5])
    split = split_errors(model, {"kinds": {"joint_drive": {"grade": GRADE}}})
    return pr, split, _plan(robot)


def _start(pr, split):
    gr = _grades(pr, split)
    E = split.sys_index
    a_pos = {k: i for i, k in enumerate(pr.alloc)}
    om0 = np.array([1.0 / pr.u_max[a_pos[k]] if k in a_pos else 1.0 for k in E])
    return gr, E, om0


def test_reused_problem_gives_the_same_step_as_a_fresh_one(full_case):
    pr, split, plan = full_case
    gr, E, om0 = _start(pr, split)
    data = StepData(pr, split, E, gr, start_share=0.0)
    om1, u1, v1 = solve_step(data, gr.split_at(split, gr.v_max), plan, om0, pr.u_max.copy(), gr.v_max)
    assert len(data.compiled) == 1
    lmi = next(iter(data.compiled.values()))
    assert lmi.problem.is_dcp(dpp=True) and lmi.problem.parameters()
    # second MM step: new tangent point, whitening and upper limits -- re-solved on the same compiled problem
    u_rand_max = np.where(np.isin(pr.alloc, split.sys_index), pr.u_max, u1)
    args = (gr.split_at(split, v1), plan, np.maximum(om1, 1e-12), u_rand_max, v1)
    reused = solve_step(data, *args)
    assert len(data.compiled) == 1 and next(iter(data.compiled.values())) is lmi
    fresh_data = StepData(pr, split, E, gr, start_share=0.0)
    fresh = solve_step(fresh_data, *args)
    assert next(iter(fresh_data.compiled.values())) is not lmi
    for a, b in zip(reused, fresh):
        np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12)
    # the step moved: the parameters did change the problem
    assert np.max(np.abs(reused[0] - om1) / om1) > 1e-3


def test_pose_ratios_match_the_posterior_module(full_case):
    """The step's information-form check against the square-root posterior of tolalloc.calibration (independent)."""
    pr, split, plan = full_case
    gr, E, _ = _start(pr, split)
    res = allocate_calibrated(pr, plan, split=split)
    assert res.certified
    t, v = res.design.t, (res.grade_t[gr.idx] / gr.t_ref) ** 2
    u = pr.u_from_t(t)
    sp = gr.split_at(split, v)
    data = StepData(pr, sp, E, gr)
    om = np.array([1.0 / u[data.a_pos[k]] if k in data.a_pos else data.om_out[i] for i, k in enumerate(E)])
    ratio = pose_ratios(data, np.arange(len(E)), information(data, sp, plan, u), om, u, v)
    post = posterior(sp.with_model(pr.model_for(t)), plan)
    ref = np.linalg.eigvalsh(post.tool_covariance(pr.q))[:, -1] / pr.blocks[0]["eig_bound"]
    np.testing.assert_allclose(ratio, ref, rtol=1e-8)
    assert ref.max() == pytest.approx(res.ratio, rel=1e-12)


@pytest.mark.parametrize("name, grades", [("ur10", False), ("tool_changer", True)])
def test_working_set_gives_the_design_of_all_pose_lmis(name, grades):
    robot = load_robot(name)
    model = build_error_model(robot)
    pr = build_problem(model, robot.poses("working"))
    split = split_errors(model, {"kinds": {"joint_drive": {"grade": GRADE}}} if grades else None)
    plan = _plan(robot)
    fast = allocate_calibrated(pr, plan, split=split)
    full = allocate_calibrated(pr, plan, split=split, pose_screening=False)
    assert fast.certified and full.certified
    assert len(full.lmi_poses) == pr.n_poses and len(fast.lmi_poses) < pr.n_poses
    assert fast.summary()["cost"] == pytest.approx(full.summary()["cost"], rel=1e-6)
    # the poses left out of the LMIs hold with the design (the final re-check is over all poses)
    assert fast.ratio <= 1.0
