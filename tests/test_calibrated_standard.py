"""Standard grades for the calibration-aware design (tolalloc.allocate.calibrated.standard / _margin / _rounding).

Known answers: the fast post-calibration margin equals the reference posterior (tolalloc.calibration.posterior);
rounding down lowers the post-calibration covariance in the Loewner order at every pose (so P cannot fall), with
random-only parameters (clearances) in the calibration's noise; the local search ends feasible and never dearer than
its start; on a small chain the search's design is the cheapest of all enumerated standard designs; over a box the
standard design meets p on fresh poses (independent posterior); the end-to-end Monte Carlo runs on the standard design.
"""

import itertools
import json
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from tolalloc import TolallocError
from tolalloc.allocate import build_problem
from tolalloc.allocate.calibrated.design import allocate_with_calibration
from tolalloc.allocate.calibrated.exact import post_probabilities
from tolalloc.allocate.calibrated.margin import PostMargin
from tolalloc.allocate.calibrated.rounding import catalogue_range, coupled_round_down
from tolalloc.allocate.calibrated.standard import standardize_calibrated
from tolalloc.allocate.catalogue import build_catalogue
from tolalloc.allocate.discrete_exact import local_search
from tolalloc.allocate.region import box_region
from tolalloc.allocate.standards import IT_TABLE_UM, it_row
from tolalloc.calibration import make_plan, posterior, split_errors, write_plan
from tolalloc.cli import main
from tolalloc.errormodel import build_error_model
from tolalloc.linear.probability import p_within_radius
from tolalloc.robot.io import load_robot
from tolalloc.verify.calibrated_worst import verify_calibrated_design


@pytest.fixture(scope="module")
def tc():
    robot = load_robot("tool_changer")
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((12, 6)))
    return robot, plan


@pytest.fixture(scope="module")
def poses(tc):
    """Calibration-aware design at 6 of the working poses and its standard design."""
    robot, plan = tc
    pr = build_problem(build_error_model(robot), robot.poses("working")[:6])
    res = allocate_with_calibration(pr, plan, baseline=False)
    return res, standardize_calibrated(res)


@pytest.fixture(scope="module")
def clearance(tc):
    """A problem with random-only allocatable parameters (clearances: measurement noise of the calibration)."""
    robot, plan = tc
    model = build_error_model(robot, clearance=True)
    pr = build_problem(model, robot.poses("working")[:6])
    return pr, split_errors(model), plan


def _random_t(pr, rng, n):
    """``n`` designs (n, K), log-uniform between the process limits."""
    lo, hi = np.log(pr.t_min), np.log(pr.t_max)
    T = np.exp(lo + rng.random((n, len(lo))) * (hi - lo))
    T[:, pr.fixed] = np.asarray(pr.costs.fixed_tol)[pr.fixed]
    return T


def _cov(pr, split, plan, t):
    return posterior(split.with_model(pr.model_for(t)), plan).tool_covariance(pr.q)


def test_fast_margin_equals_reference_posterior(clearance):
    pr, split, plan = clearance
    assert any(not split.systematic[k] for k in pr.alloc)  # clearances enter the calibration as noise
    T = _random_t(pr, np.random.default_rng(3), 6)
    U = np.stack([pr.u_from_t(t) for t in T])
    m = PostMargin(pr, split, plan)
    ref = np.stack([post_probabilities(pr, split, plan, t)[0] for t in T])
    assert m.fast
    np.testing.assert_allclose(m.probabilities(U), ref, rtol=0, atol=1e-12)
    np.testing.assert_allclose(m(U), (ref - pr.prob).min(axis=1), rtol=0, atol=1e-12)
    # a plan that leaves systematic parts unestimated takes the reference path and agrees with it
    part = make_plan(pr.model.robot, plan.q, estimate=[pr.model.names[k] for k in split.sys_index[:10]])
    ms = PostMargin(pr, split, part)
    ref2 = np.stack([post_probabilities(pr, split, part, t)[0] for t in T[:2]])
    assert not ms.fast
    np.testing.assert_allclose(ms.probabilities(U[:2]), ref2, rtol=0, atol=1e-15)


def test_linearisation_is_the_tangent_of_the_post_calibration_probability(clearance):
    pr, split, plan = clearance
    m = PostMargin(pr, split, plan)
    u = pr.u_from_t(_random_t(pr, np.random.default_rng(8), 1)[0])
    A, s = m.linearise(u, near=1.0)  # every pose
    assert A.shape == (pr.n_poses, len(u))
    base = m.probabilities(u)[0]
    d = u * np.random.default_rng(9).uniform(-1e-2, 1e-2, len(u))
    err, change = [], []
    for h in (1.0, 0.5):  # P_i(u) + grad . (h d) - target_i against the exact value: the error is second order
        lin = -(A @ (u + h * d)) + s
        exact = m.probabilities(u + h * d)[0]
        err.append(np.abs(exact - pr.prob - lin).max())
        change.append(np.abs(exact - base).max())
    assert err[0] < 0.01 * change[0] and err[1] < 0.3 * err[0]


def test_rounding_down_lowers_the_covariance_at_every_pose(clearance):
    pr, split, plan = clearance
    cat = build_catalogue(pr)
    lo, _ = catalogue_range(cat)
    rng = np.random.default_rng(11)
    T = _random_t(pr, rng, 12)
    T[:, pr.alloc] = np.maximum(T[:, pr.alloc], lo)  # above the finest value: the rounding goes down
    worst = np.inf
    for t in T:
        opt, n = coupled_round_down(cat, t[pr.alloc])
        tr = t.copy()
        tr[pr.alloc] = cat.t_of(opt, n)
        assert np.all(tr <= t * (1 + 1e-12)) and np.any(tr < t)
        C, Cr = _cov(pr, split, plan, t), _cov(pr, split, plan, tr)
        # Loewner order: C - Cr positive semi-definite at every pose (to rounding of the posterior)
        assert np.linalg.eigvalsh(C - Cr).min() >= -1e-12 * np.abs(C).max()
        gain = p_within_radius(Cr, pr.radius_mm) - p_within_radius(C, pr.radius_mm)
        worst = min(worst, float(gain.min()))
    assert worst >= -1e-14  # the post-calibration P never falls


def test_standard_design_meets_p_and_beats_rounding(poses):
    res, std = poses
    pr = std.problem
    assert std.ok and std.design.ok and std.design.solver == "discrete-exact"
    p = p_within_radius(_cov(pr, res.post.split, res.plan, std.design.t), pr.radius_mm)  # independent posterior
    assert p.min() >= pr.prob - 1e-12 and std.p_post.min() == pytest.approx(p.min(), abs=1e-14)
    assert std.rounded_meets and std.cost <= std.rounded_cost  # rounding down holds; the search only saves
    assert std.premium_pct == pytest.approx(100 * (std.cost / res.cost - 1))
    assert std.rounded_premium_pct == pytest.approx(100 * (std.rounded_cost / res.cost - 1))
    # link lengths carry ISO 286 values: +-IT/2 of their nominal size
    lengths = {lk.name: lk.length_mm for lk in pr.model.robot.links}
    for k, prm in enumerate(pr.model.params):
        if prm.kind == "link_length":
            g = int(std.grade[k][2:])
            assert std.design.t[k] == pytest.approx(IT_TABLE_UM[it_row(lengths[prm.element]), g - 1] / 2000.0)
    assert "not a proven one" in std.design.message and std.to_dict()["proven_optimal"] is False
    # the outer approximation starts from the local search's design: never dearer
    local = standardize_calibrated(res, outer_approximation=False, relax=False)
    assert local.design.ok and std.cost <= local.cost and std.outer_approximation == "converged"
    # the range-confined continuous design splits the premium into range and steps
    assert std.relaxed_label == "exact" and res.cost <= std.relaxed_cost
    assert std.range_premium_pct + std.step_premium_pct == pytest.approx(std.premium_pct, abs=0.05)


def test_local_search_never_breaks_the_requirement_nor_raises_the_cost(poses):
    res, _ = poses
    pr = res.problem
    cat = build_catalogue(pr)
    m = PostMargin(pr, res.post.split, res.plan)
    rng = np.random.default_rng(5)
    for scale in rng.uniform(0.5, 0.95, 3):  # tighter than the continuous design: feasible starts
        opt, n = coupled_round_down(cat, res.design.t[pr.alloc] * scale)
        assert m(cat.u_of(opt, n)[None])[0] >= 0
        costs = [cat.total_cost(opt, n)]
        for moves in range(1, 4):  # the first moves, one at a time: each feasible and cheaper
            o2, n2, done = local_search(cat, opt, n, m.violation, max_moves=moves, batch=16)
            assert m(cat.u_of(o2, n2)[None])[0] >= 0
            costs.append(cat.total_cost(o2, n2))
            if done < moves:
                break
        assert all(b < a for a, b in zip(costs, costs[1:]))


def _small(tc, grades):
    """dl1, dl2 on ``grades`` and dth1 on 0.001 deg steps allocatable, every other parameter fixed."""
    robot, plan = tc
    model = build_error_model(robot)
    free = {"dl1", "dl2", "dth1"}
    params = {p.name: {"fixed": True, ("tol_mm" if p.unit == "mm" else "tol_deg"): 0.05 if p.unit == "mm" else 0.003}
              for p in model.params if p.name not in free}
    params["dth1"] = {"t_min_deg": 0.001, "t_max_deg": 0.006, "step_deg": 0.001}
    costs = {"kinds": {"link_length": {"grades": grades}}, "parameters": params}
    pr = build_problem(model, robot.poses("working")[:6], radius_mm=0.175, costs=costs)
    return allocate_with_calibration(pr, plan, baseline=False)


def test_small_case_equals_brute_force(tc):
    robot, plan = tc
    res = _small(tc, "IT8-IT12")
    std = standardize_calibrated(res, relax=False)
    cat = build_catalogue(res.problem)
    per = [[(o, k) for o in range(cat.start[a], cat.start[a + 1])
            for k in (range(cat.n_lo[o], cat.n_hi[o] + 1) if cat.stepped[o] else (0,))] for a in range(cat.n_params)]
    combos = np.array(list(itertools.product(*per)))  # (D, 3, 2): 5 grades x 5 grades x 6 steps
    opt, n = combos[..., 0], combos[..., 1]
    U = np.stack([cat.u_of(o, k) for o, k in zip(opt, n)])
    cost = np.array([cat.total_cost(o, k) for o, k in zip(opt, n)]) + (std.cost - cat.total_cost(
        *coupled_round_down(cat, std.design.t[res.problem.alloc])))
    ok = PostMargin(res.problem, res.post.split, plan)(U) >= 0
    assert len(combos) == 150 and 0 < ok.sum() < len(combos)
    assert std.cost == pytest.approx(cost[ok].min(), rel=1e-12)  # the enumerated optimum itself
    assert std.rounded_cost > std.cost * (1 + 1e-3)  # and rounding alone would not reach it
    local = standardize_calibrated(res, relax=False, outer_approximation=False)  # the local search alone, here too
    assert local.cost == pytest.approx(cost[ok].min(), rel=1e-12)


def test_rounding_up_misses_p_where_the_search_does_not(tc):
    # IT11 is coarser than the continuous dl1, dl2: "rounding down" goes up to the finest grade and misses p
    res = _small(tc, "IT11-IT12")
    std = standardize_calibrated(res, relax=False)
    assert res.design.ok and not std.rounded_meets and std.rounded_p_min < res.problem.prob
    assert std.ok and std.p_post.min() >= res.problem.prob - 1e-12
    assert "misses p" in std.message_line()
    # IT12 only: no standard design meets p (every tolerance at its finest value fails); said, nothing built
    res = _small(tc, "IT12-IT12")
    std = standardize_calibrated(res, relax=False)
    assert std.design.status == "infeasible" and not std.ok and "standard grades: none" in std.message_line()
    assert std.to_dict()["cost"] is None
    with pytest.raises(TolallocError, match="^standard: the standard-grade design has no design to check"):
        verify_calibrated_design(res, standard=std, n_robots=40)


@pytest.fixture(scope="module")
def box(tc):
    robot, plan = tc
    pr = build_problem(build_error_model(robot), robot.poses("working")[:4])
    lo, hi = robot.regions["working"]
    mid, half = 0.5 * (lo + hi), 0.25 * (hi - lo)
    region = box_region(robot, mid - half, mid + half, "small")
    kw = dict(coverage_n=2000, seed=1, n_seed=128, n_starts=3)
    res = allocate_with_calibration(pr, plan, region=region, baseline=False, **kw)
    return res, standardize_calibrated(res, relax=False, **kw)


def test_box_standard_design_holds_on_fresh_poses(box):
    res, std = box
    assert std.region_kind == "box" and std.search.converged and std.coverage.ok and std.ok
    assert len(std.search.active_q) >= len(res.problem.q)  # the continuous active set, grown if needed
    rng = np.random.default_rng(77)
    q = res.region.q_min + rng.random((3000, 6)) * (res.region.q_max - res.region.q_min)
    post = posterior(res.post.split.with_model(std.problem.model_for(std.design.t)), res.plan)
    p = p_within_radius(post.tool_covariance(q), res.problem.radius_mm)
    assert p.min() >= res.problem.prob - 1e-4  # the search's tolerance
    Q = std.check_poses(2)
    np.testing.assert_allclose(Q[0], std.search.worst_q)


def test_end_to_end_checks_the_standard_design(poses):
    res, std = poses
    e = verify_calibrated_design(res, standard=std, n_robots=40, seed=3, k_worst=2)
    assert e.design == "standard" and e.to_dict()["design"] == "standard"
    np.testing.assert_allclose(e.check.q, std.check_poses(2))
    # the linear prediction beside the Monte Carlo is the standard design's post-calibration P
    p_std = p_within_radius(std.post.tool_covariance(e.check.q), res.problem.radius_mm)
    np.testing.assert_allclose(e.check.p_linear, p_std, rtol=0, atol=1e-10)
    with pytest.raises(TolallocError, match="^standard: expected the CalibratedStandard of this allocation"):
        verify_calibrated_design(res, standard=res.certified, n_robots=40)
    other = make_plan(res.problem.model.robot, res.plan.q[:8])
    with pytest.raises(TolallocError, match="of another allocation"):
        verify_calibrated_design(res, standard=replace(std, plan=other), n_robots=40)


def test_bad_arguments_name_the_keyword(poses):
    res, _ = poses
    with pytest.raises(TolallocError, match=r"^tol: expected a probability tolerance"):
        standardize_calibrated(res, tol=0.5)
    with pytest.raises(TolallocError, match=r"^res: expected the CalibratedDesign"):
        standardize_calibrated(res.certified)
    with pytest.raises(TolallocError, match=r"^max_moves: expected a whole number >= 0"):
        standardize_calibrated(res, max_moves=-1)


def test_processes_round_to_one_process_per_part(tc):
    robot, _ = tc
    model = build_error_model(robot)
    procs = {"precision": {"applies_to": ["joint_drive", "axis_deflection"], "t_max_deg": 0.005,
                           "model": "reciprocal", "a": 1.5, "b": 1.0, "t_ref_deg": 0.01, "setup": 0.2},
             "standard": {"applies_to": ["joint_drive", "axis_deflection"], "t_min_deg": 0.004,
                          "model": "reciprocal", "a": 1.0, "b": 1.0, "t_ref_deg": 0.01}}
    pr = build_problem(model, robot.poses("working")[:2], costs={"processes": procs})
    cat = build_catalogue(pr)
    t = pr.t_max[pr.alloc].copy()
    names = [model.names[k] for k in pr.alloc]
    t[names.index("dth1")] = np.deg2rad(0.003)  # only 'precision' reaches it; e1x, e1y loose: 'standard' is cheaper
    opt, _ = cat.round_down(t)
    assert not cat.coupled(opt)  # plain rounding mixes the processes of joint j1
    opt, n = coupled_round_down(cat, t)
    assert cat.coupled(opt)
    j1 = [names.index(x) for x in ("dth1", "e1x", "e1y")]
    assert {cat.process[opt[a]] for a in j1} == {"precision"}  # the one that holds every value at or below t
    assert np.all(cat.t_of(opt, n)[j1] <= t[j1] * (1 + 1e-12))


def test_cli_writes_the_standard_grades(tc, tmp_path, capsys):
    from tolalloc.report.html import pretty
    from tolalloc.workflows import allocate_tolerances
    from tolalloc.report.html_calibrated import calibrated_context

    robot, plan = tc
    path = tmp_path / "plan.csv"
    write_plan(plan, robot, path)
    out = tmp_path / "res"
    rc = main(["allocate", "tool_changer", "--calibration", str(path), "--region", "nominal", "--no-verify",
               "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 0 and "standard grades (discrete-exact): cost" in text and "rounding down would cost" in text
    frame = pd.read_csv(out / "tolerances.csv", keep_default_na=False)
    assert {"tol_mm", "tol_deg", "tol_continuous_mm", "grade", "cost", "cost_continuous"} <= set(frame.columns)
    assert frame.loc[frame.parameter == "dl1", "grade"].item().startswith("IT")
    s = json.loads((out / "summary.json").read_text())
    assert s["built"]["standard"] and s["cost_standard"] == pytest.approx(s["standard"]["cost"])
    assert s["cost"] == s["cost_standard"] == s["built"]["cost"] and s["cost_rounded"] >= s["cost_standard"]
    assert s["standard_premium_pct"] == pytest.approx(100 * (s["cost_standard"] / s["cost_continuous"] - 1))
    job = allocate_tolerances("tool_changer", calibration=str(path), region="nominal", verification=False)
    assert job.cost == pytest.approx(s["cost_standard"]) and job.built is job.standard
    note = job.grade_note()
    assert "standard values" in note and "holds at p at every pose" in note and "not a proven one" in note
    assert calibrated_context(job)["grade_note"] == pretty(note)
