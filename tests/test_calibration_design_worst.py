"""Plans for the allocation (tolalloc.calibration.design_worst, tolalloc.allocate.calibrated.plan).

Known answers: the exchange's rank-3 (Woodbury) update of the posterior equals the posterior module's square-root
form for the same plan; the designed plan is at least as good as its start and beats random plans of its size; the
all-candidates plan bounds every plan from above; the alternation never keeps a dearer plan.
"""

import numpy as np
import pytest

from tolalloc.allocate.calibrated.certified import allocate_calibrated
from tolalloc.allocate.calibrated.plan import compare_with_random_plans, design_plan_for_allocation
from tolalloc.allocate.problem import build_problem
from tolalloc.calibration import make_plan, posterior
from tolalloc.calibration.design import candidate_poses
from tolalloc.calibration.design_worst import _Objective, design_plan_worst, plan_worst_p, random_plan_worst_p
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io import load_robot


@pytest.fixture(scope="module")
def case():
    robot = load_robot("tool_changer")
    model = build_error_model(robot)
    pr = build_problem(model, robot.poses("working")[:4])
    cand = candidate_poses(robot, 160, seed=2)
    plan0 = make_plan(robot, cand[:10])
    cert = allocate_calibrated(pr, plan0)  # a design whose prior (loose calibrated parts) the plan is made for
    return robot, pr, cand, cert.post.split


def test_woodbury_update_equals_the_posterior(case):
    robot, pr, cand, sp = case
    q = robot.poses("working")[:4]
    obj = _Objective(sp, make_plan(robot, cand[:1]), cand, q, pr.radius_mm)
    chosen = list(range(10))
    rest = chosen[1:]
    c = 57  # swap candidate 0 for candidate 57
    Mi = obj.info(rest)
    Minv = np.linalg.inv(Mi)
    Gc = obj.G[c]
    Mnew_inv = Minv - Minv @ Gc.T @ np.linalg.solve(np.eye(3) + Gc @ Minv @ Gc.T, Gc @ Minv)
    cov_upd = obj.cov(np.linalg.inv(Mnew_inv))
    ref = posterior(sp, make_plan(robot, cand[rest + [c]])).tool_covariance(q)
    np.testing.assert_allclose(cov_upd, ref, rtol=1e-6, atol=1e-12)
    j, score = obj.best_swap(Mi, set(chosen))  # the batched update: the chosen candidate's own score agrees
    idx = rest + [j]
    assert score == pytest.approx(obj.score(posterior(sp, make_plan(robot, cand[idx])).tool_covariance(q)), rel=1e-6)


def test_designed_plan_beats_its_start_and_random_plans(case):
    robot, pr, cand, sp = case
    q = pr.q
    start = make_plan(robot, cand[20:30])
    w = design_plan_worst(sp, 10, cand, q, pr.radius_mm, start=start, a_optimal=False)
    assert w.worst_p >= plan_worst_p(sp, start, q, pr.radius_mm).min() - 1e-12
    assert w.worst_p == pytest.approx(plan_worst_p(sp, w.plan, q, pr.radius_mm).min(), abs=1e-12)
    rnd = random_plan_worst_p(sp, cand, 10, q, pr.radius_mm, count=40, seed=1)
    assert w.worst_p > np.quantile(rnd, 0.9)
    every = plan_worst_p(sp, make_plan(robot, cand), q, pr.radius_mm).min()
    assert every >= w.worst_p and every >= rnd.max()  # measuring every candidate bounds every plan
    with pytest.raises(TolallocError, match="n_poses: expected a whole number between 1 and the 160 candidates"):
        design_plan_worst(sp, 0, cand, q, pr.radius_mm)


def test_alternation_keeps_only_cheaper_plans(case):
    robot, pr, cand, sp = case
    res = design_plan_for_allocation(pr, 10, cand, rounds=1, exact=False, baseline=False, coverage_n=0,
                                     relaxation="frank-wolfe")
    costs = [h[1] for h in res.history]
    kept = [h for h in res.history if h[3]]
    assert res.result.cost == pytest.approx(kept[-1][1], rel=1e-9) and res.result.cost <= costs[0] + 1e-9
    assert res.start_cost == pytest.approx(costs[0])
    cmp = compare_with_random_plans(res.result, cand, count=20, seed=3)
    d = cmp.to_dict()
    assert d["random_p10"] <= d["random_median"] <= d["random_p90"] <= d["random_max"] <= d["all_candidates_worst_p"]
    assert d["designed_worst_p"] <= d["all_candidates_worst_p"] and "random 10-pose plans" in cmp.message()
    with pytest.raises(TolallocError, match="n_poses: expected a whole number between 8"):
        design_plan_for_allocation(pr, 5, cand)
