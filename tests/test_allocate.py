"""Tolerance allocation: closed forms, solver agreement, the guard, infeasibility, snapping."""

import numpy as np
import pytest
from scipy.stats import chi2, norm

from tolalloc import TolallocError, load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.limits import check_process_limits
from tolalloc.allocate.convex import solve_rule
from tolalloc.allocate.exact import solve_exact
from tolalloc.errormodel import build_error_model
from tolalloc.linear.probability import p_within_radius

ALL = ["dl1", "dl2", "dl3", "dl4", "dl5", "dl6", "dth1", "dth2", "dth3", "dd4", "dth5", "dth6",
       "e1x", "e1y", "e2y", "e2z", "e3y", "e3z", "e5y", "e5z", "e6x", "e6y"]
WIDE = {"kinds": {k: {"t_min_mm": 1e-4, "t_max_mm": 5.0} for k in ("link_length", "joint_drive_prismatic")}
        | {k: {"t_min_deg": 1e-5, "t_max_deg": 2.0} for k in ("joint_drive", "axis_deflection")}}


@pytest.fixture(scope="module")
def robot():
    return load_robot("tool_changer")


def only(robot, keep):
    return build_error_model(robot, exclude=tuple(n for n in ALL if n not in keep))


def test_one_parameter_closed_form(robot):
    r, p, z = 0.25, 0.95, 3.0
    pr = build_problem(only(robot, ["dl3"]), robot.q_nominal, radius_mm=r, prob=p, costs=WIDE)
    t_exact = z * r / norm.ppf((1 + p) / 2)  # |J| = 1 mm/mm: P = 2 Phi(r / sigma) - 1
    t_lmi = z * r / np.sqrt(chi2.ppf(p, 3))
    tr, lmi = solve_rule(pr, "trace"), solve_rule(pr, "lmi")
    ex = solve_exact(pr, tr)
    assert tr.t[0] == pytest.approx(t_exact, rel=1e-6)   # rank one: the trace rule is exact
    assert lmi.t[0] == pytest.approx(t_lmi, rel=1e-6)
    assert ex.t[0] == pytest.approx(t_exact, rel=1e-5)
    assert ex.cost == pytest.approx(1.0 + 1.0 * 0.1 / t_exact, rel=1e-5)  # a + b t_ref / t
    assert ex.p_linear["position"][0] == pytest.approx(p, abs=1e-6)


def test_lagrange_closed_form_reciprocal_trace_rule(robot):
    keep = [n for n in ALL if n not in ("dth6", "e6x", "e6y")]  # no zero-influence parameters
    model = only(robot, keep)
    q = robot.poses("working")[5]
    r, p, z = 0.25, 0.95, 3.0
    pr = build_problem(model, q, radius_mm=r, prob=p, costs=WIDE)
    d = solve_rule(pr, "trace")
    # independent: min sum b_k u_k^-1/2  s.t. sum g_k u_k = 1  ->  u_k = (b_k/g_k)^(2/3) / sum_j g_j^(1/3) b_j^(2/3)
    J = model.jacobian(q)[:3]
    t_ref = np.array([m.t_ref for m in pr.costs.models])
    b = np.array([m.b for m in pr.costs.models])
    g = (J**2).sum(0) * (t_ref / z) ** 2 / (r**2 / chi2.ppf(p, 1))
    u = (b / g) ** (2 / 3) / np.sum(g ** (1 / 3) * b ** (2 / 3))
    np.testing.assert_allclose(d.t, t_ref * np.sqrt(u), rtol=2e-5)
    lam = 0.5 * b * u**-1.5 / g  # the same for every k
    assert d.pose_dual[0] == pytest.approx(lam[0], rel=1e-3)
    assert d.cost == pytest.approx(np.sum([m.a for m in pr.costs.models]) + np.sum(b / np.sqrt(u)), rel=1e-6)


def test_solvers_agree_when_the_exact_constraint_acts_through_the_trace(robot):
    # at q = 0 every y-directed parameter moves the tool along y: rank-one covariance
    model = only(robot, ["dl3", "dl4", "dl5", "dl6", "dd4"])
    pr = build_problem(model, np.zeros(6), costs=WIDE)
    tr, lmi = solve_rule(pr, "trace"), solve_rule(pr, "lmi")
    ex = solve_exact(pr, tr)
    assert ex.solver == "exact"
    assert ex.cost == pytest.approx(tr.cost, rel=1e-5)
    np.testing.assert_allclose(ex.t, tr.t, rtol=1e-3)
    assert lmi.cost > tr.cost * 1.05


def _fd_position_jacobian(model, q, h=1e-5):
    """Position rows of the error Jacobian, (P, 3, K), by central differences of ``fk_poe`` on the perturbed chain."""
    from tolalloc.robot.kinematics import fk_poe

    K = len(model.params)
    vals = np.concatenate([h * np.eye(K), -h * np.eye(K)])  # (2K, K)
    screws, home, dq = model.perturbed_chain(vals)
    out = []
    for qi in np.atleast_2d(q):
        pos = fk_poe(screws, home, qi + dq)[:, :3, 3]  # (2K, 3)
        out.append(((pos[:K] - pos[K:]) / (2 * h)).T)
    return np.array(out)


def _quad_p_within(cov, r):
    """P(|x| < r), x ~ N(0, cov) in 3-D, by direct adaptive quadrature in the eigenframe.

    ``P = int int phi(z2) phi(z3) erf(sqrt((1 - l2 z2^2 - l3 z3^2) / (2 l1))) dz2 dz3`` over the ellipse where the
    argument is positive (``l1 >= l2 >= l3`` the eigenvalues over ``r^2``); independent of tolalloc.linear.
    """
    from scipy.integrate import quad
    from scipy.special import erf

    l1, l2, l3 = np.sort(np.clip(np.linalg.eigvalsh(cov), 0.0, None))[::-1] / r**2
    phi = lambda z: np.exp(-0.5 * z * z) / np.sqrt(2.0 * np.pi)  # norm.pdf without scipy's per-call overhead
    z2max = min(1 / np.sqrt(l2), 12.0) if l2 > 0 else 12.0

    def inner(z2):
        rem = 1 - l2 * z2**2
        if rem <= 0:
            return 0.0
        z3max = min(np.sqrt(rem / l3), 12.0) if l3 > 0 else 12.0
        g = lambda z3: phi(z3) * erf(np.sqrt(max(rem - l3 * z3**2, 0.0) / (2 * l1)))
        return 2 * quad(g, 0, z3max, epsabs=1e-10, epsrel=1e-9, limit=100)[0]

    return 2 * quad(lambda z2: phi(z2) * inner(z2), 0, z2max, epsabs=1e-10, epsrel=1e-9, limit=100)[0]


def test_independent_probability_and_jacobian_agree_with_closed_forms():
    # the two independent helpers above against closed forms: rank one 2 Phi(r/s) - 1, isotropic chi2_3
    assert _quad_p_within(np.diag([0.1**2, 0, 0]), 0.25) == pytest.approx(2 * norm.cdf(2.5) - 1, abs=1e-9)
    assert _quad_p_within(np.eye(3) * 0.1**2, 0.25) == pytest.approx(chi2.cdf(6.25, 3), abs=1e-9)


@pytest.fixture(scope="module")
def result(robot):
    pr = build_problem(build_error_model(robot))
    return allocate(pr)


def test_tool_changer_allocation(result):
    pr = result.problem
    assert result.status == "optimal" and result.design.solver == "exact"
    assert result.exact.cost <= result.certified.cost  # the guard's promise
    assert result.certified.cost <= result.certified_other.cost
    for d in (result.certified, result.certified_other):  # certified rules imply the requirement
        assert d.p_linear["position"].min() >= pr.prob - 1e-9
    p = result.design.p_linear["position"]
    assert p.min() == pytest.approx(pr.prob, abs=1e-5)  # the exact constraint is active somewhere
    # independent probability of the design: Jacobian by central differences of the exact perturbed chain, and
    # P(|x| < r) by direct quadrature in the eigenframe (not the project's Jacobian or probability code)
    low = np.argsort(p)[:4]  # the binding poses (quadrature is slow: ~0.7 s a pose)
    J = _fd_position_jacobian(pr.model, pr.q[low])
    C = np.einsum("pik,k,pjk->pij", J, (result.design.t / 3) ** 2, J)
    np.testing.assert_allclose([_quad_p_within(c, 0.25) for c in C], p[low], atol=1e-7)
    assert min(_quad_p_within(c, 0.25) for c in C) >= 0.95 - 1e-5  # meets the requirement within FEAS_TOL
    # the paper's sigma (table2) misses the requirement by far; the design tightens the dominant ones
    assert (result.design.t / 3)[pr.model.index("dth2")] < pr.model.with_sigma(build_error_model(pr.model.robot).sigma).sigma[pr.model.index("dth2")] / 3
    frame = result.to_frame(result.design)
    assert list(frame.columns[:8]) == ["parameter", "kind", "element", "role", "unit", "nominal_mm", "tol_mm",
                                       "tol_deg"]
    assert frame["variance_share_pct"].sum() == pytest.approx(100.0)
    assert set(frame.loc[frame.parameter.isin(["dth6", "e6x", "e6y"]), "at_limit"]) == {"t_max"}
    # one unit per column: lengths in tol_mm (nothing in tol_deg), angles in tol_deg, with the right factor
    mm = (frame["unit"] == "mm").to_numpy()
    np.testing.assert_allclose(frame["tol_mm"][mm], result.design.t[mm], rtol=1e-12)
    np.testing.assert_allclose(frame["tol_deg"][~mm], np.rad2deg(result.design.t[~mm]), rtol=1e-12)
    assert frame["tol_deg"][mm].isna().all() and frame["tol_mm"][~mm].isna().all()
    assert (frame["grade"] == "").all()  # the continuous design carries no standard value
    lengths = {lk.name: lk.length_mm for lk in pr.model.robot.links}
    links = frame["kind"] == "link_length"
    assert frame.loc[links, "nominal_mm"].tolist() == [lengths[e] for e in frame.loc[links, "element"]]
    assert frame.loc[~links, "nominal_mm"].isna().all()
    s = result.summary()
    assert s["costs"]["saving"] == pytest.approx(result.certified.cost - result.exact.cost)
    assert len(s["poses"]) == 12 and s["poses"][0]["q_deg_mm"][0] == pytest.approx(15.0)
    assert "q" not in s["poses"][0]  # joint values only under their unit-carrying key


def test_snapping_tightens_and_rechecks(result):
    rnd, d, pr = result.rounded, result.design, result.problem
    assert rnd.status == "optimal" and "re-checked" in rnd.message
    assert np.all(rnd.t <= d.t * (1 + 1e-12))
    assert rnd.p_linear["position"].min() >= pr.prob
    grades = dict(zip(pr.costs.names, result.rounded_grade))
    assert grades["dl3"].startswith("IT") and grades["dth1"] == ""


def test_standard_design_is_chosen_not_rounded(result):
    # the standard design meets the requirement (exact Gaussian P, no tolerance) and costs less than the rounding
    std, rnd, pr = result.standard, result.rounded, result.problem
    assert std.solver == "discrete-exact" and std.ok and std.fallback_from is None
    assert std.p_linear["position"].min() >= pr.prob
    assert result.design.cost < std.cost < rnd.cost
    grades = dict(zip(pr.costs.names, result.it_grade))
    assert grades["dl3"].startswith("IT") and grades["dth1"] == ""
    s = result.summary()
    assert s["costs"]["standard"] == pytest.approx(std.cost) and s["costs"]["rounded"] == pytest.approx(rnd.cost)
    # the standard design is the one to build: the table, the summary's cost, solver and worst pose are its own
    assert result.built is std and s["standard_built"] and s["cost"] == pytest.approx(std.cost)
    assert s["solver"] == "discrete-exact" and s["cost_continuous"] == pytest.approx(result.design.cost)
    assert s["worst_pose"] == int(np.argmin(std.p_linear["position"])) + 1
    assert [r["p_linear"] for r in s["poses"]] == pytest.approx(std.p_linear["position"].tolist())
    assert [r["p_linear_continuous"] for r in s["poses"]] == pytest.approx(result.design.p_linear["position"].tolist())
    frame = result.to_frame()
    mm = (frame["unit"] == "mm").to_numpy()
    np.testing.assert_allclose(np.where(mm, frame["tol_mm"], frame["tol_deg"]), std.t * [p.to_interface for p in
                                                                                           pr.model.params])
    np.testing.assert_allclose(np.where(mm, frame["tol_continuous_mm"], frame["tol_continuous_deg"]),
                               result.design.t * [p.to_interface for p in pr.model.params])
    assert frame["cost"].sum() == pytest.approx(std.cost) and frame["cost_continuous"].sum() == pytest.approx(
        result.design.cost)
    assert frame["grade"].tolist() == list(result.grade) and "it_grade" not in frame
    assert frame["variance_share_pct"].tolist() == pytest.approx((100 * result.variance_share(std)).tolist())
    assert s["costs"]["standard_premium_pct"] == pytest.approx(100 * (std.cost / result.design.cost - 1))
    assert s["discrete"]["proven_optimal"] is False and s["standard"]["grades"]["dl3"] == grades["dl3"]


def test_guard_falls_back_to_certified(result):
    d = solve_exact(result.problem, result.certified, max_rounds=0)  # no IPOPT run: must fall back
    assert d.solver == result.certified.solver and d.solver.certified and d.fallback_from == "exact"
    assert d.label == f"{result.certified.solver} (fallback from exact)"
    assert d.cost == result.certified.cost and "guard" in d.message and "max_rounds = 0" in d.message


def test_infeasible_limits_are_stated(robot):
    costs = {"kinds": {"axis_deflection": {"t_min_deg": 0.01}}}
    pr = build_problem(build_error_model(robot), costs=costs)
    res = allocate(pr)
    assert res.status == "infeasible" and res.design.status == "infeasible"
    msg = res.message
    assert "infeasible within the process limits" in msg and "radius achievable at p = 0.95" in msg
    assert "t_min = 0.01 deg" in msg
    diag = res.diagnosis
    i = diag.worst_pose["position"]
    t = pr.t_min
    J = pr.model.jacobian(pr.q[i])[:3]
    C = J @ np.diag((t / 3) ** 2) @ J.T
    assert diag.p_best["position"][i] == pytest.approx(float(p_within_radius(C, 0.25)), abs=1e-10)
    assert diag.p_best["position"][i] < 0.95
    assert float(p_within_radius(C, diag.radius_best["position"][i])) == pytest.approx(0.95, abs=1e-8)
    assert diag.binding[0][0].startswith("e")  # a deflection limit binds first
    assert res.certified.status == "infeasible"


def test_certified_only_and_orientation_requirement(robot):
    pr = build_problem(build_error_model(robot), robot.poses("working")[:4], angle_radius_deg=0.01)
    res = allocate(pr, solver="certified", snap=False)  # the standard design with an angle requirement: test_discrete
    assert res.design.solver.startswith("certified") and res.exact is None
    assert res.design.p_linear["orientation"].min() >= 0.95 - 1e-9
    assert check_process_limits(pr).feasible


@pytest.mark.parametrize("kw, match", [({"prob": 1.5}, "prob"), ({"radius_mm": -1}, "radius_mm"),
                                       ({"angle_radius_deg": 0.01, "angle_prob": 0}, "angle_prob")])
def test_bad_requirements(robot, kw, match):
    with pytest.raises(TolallocError, match=match):
        build_problem(build_error_model(robot), **kw)


def test_bad_solver_name(result):
    with pytest.raises(TolallocError, match="solver"):
        allocate(result.problem, solver="magic")


@pytest.mark.parametrize("z", [3.0, np.sqrt(3.0)])
def test_certified_rules_hold_exactly(robot, z):
    from tolalloc.allocate.convex import rule_ratio
    from tolalloc.allocate.costs import cost_set

    model = build_error_model(robot)
    pr = build_problem(model, costs=cost_set(model, None, z=z))
    for rule in ("trace", "lmi"):
        d = solve_rule(pr, rule)
        assert d.status == "optimal"
        assert rule_ratio(pr, rule, pr.u_from_t(d.t)) <= 1.0
        assert rule_ratio(pr, rule, pr.u_from_t(d.t)) > 1 - 1e-6  # active: nothing left on the table


def test_a_requirement_the_loosest_design_meets_is_answered_without_a_solve(robot, monkeypatch):
    """Every cost law decreases in its tolerance: when the design with every tolerance at t_max meets the rule, it
    is the optimum. It is returned as certified without a conic solve (Clarabel ended ``optimal_inaccurate`` on such
    slack problems); a requirement one step tighter than that corner still goes to the solver."""
    import cvxpy as cp

    from tolalloc.allocate.convex import rule_ratio

    model = build_error_model(robot)
    q = robot.poses("working")
    calls = []
    solve = cp.Problem.solve
    monkeypatch.setattr(cp.Problem, "solve", lambda self, *a, **k: calls.append(1) or solve(self, *a, **k))
    pr = build_problem(model, q, radius_mm=30.0)
    for rule in ("trace", "lmi"):
        d = solve_rule(pr, rule)
        assert d.status == "optimal" and d.ok and calls == []
        assert np.array_equal(d.t, pr.t_max) and rule_ratio(pr, rule, pr.u_max) <= 1.0
        assert d.message == f"every tolerance at its process limit t_max meets the {rule} rule"
        assert d.cost == pytest.approx(sum(m.cost(t) for m, t in zip(pr.costs.models, pr.t_max)), rel=1e-12)
    # the radius at which the corner's trace ratio is 1.01: the rule is not met there, so the solver decides
    corner = rule_ratio(pr, "trace", pr.u_max)
    tight = build_problem(model, q, radius_mm=30.0 * np.sqrt(corner / 1.01))  # ratios scale with 1 / r^2
    d = solve_rule(tight, "trace")
    assert calls and d.status == "optimal" and rule_ratio(tight, "trace", tight.u_from_t(d.t)) <= 1.0
    assert np.any(d.t < tight.t_max * (1 - 1e-6))


def test_exact_tolerances_at_t_max_sit_on_it_and_snap_to_it(result):
    # regression: IPOPT left dth6, e6x, e6y a hair below t_max = 0.5 deg and snapping took 0.4997 deg (1799")
    pr, d = result.problem, result.exact
    at = np.array([a == "t_max" for a in d.at_limit])
    assert at.sum() == 3
    assert np.all(d.t[at] == pr.t_max[at])
    np.testing.assert_allclose(result.rounded.t[at], pr.t_max[at], rtol=1e-12)
    np.testing.assert_allclose(result.standard.t[at], pr.t_max[at], rtol=1e-12)


def test_diagnosis_message_and_summary_units(robot):
    # regressions: the message said P(|dpos| < ...); summary radius_best_max had no unit (orientation in rad)
    res = allocate(build_problem(build_error_model(robot), radius_mm=0.01, angle_radius_deg=1e-4))
    assert res.status == "infeasible"
    assert "P(|dP| < 0.01 mm)" in res.message and "P(|dw| < 0.0001 deg)" in res.message
    rb = res.summary()["diagnosis"]["radius_best_max"]
    assert rb["position_mm"] == pytest.approx(res.diagnosis.radius_best["position"].max())
    assert rb["orientation_deg"] == pytest.approx(np.rad2deg(res.diagnosis.radius_best["orientation"].max()))


def test_uniform_costs_make_the_design_errors_uniform(robot):
    pr = build_problem(build_error_model(robot), robot.poses("nominal"), costs={"distribution": "uniform"})
    assert pr.costs.z == pytest.approx(np.sqrt(3))
    assert {p.distribution for p in pr.model.params} == {"uniform"}
    assert {p.distribution for p in pr.model_for(pr.t_max).params} == {"uniform"}  # what the Monte Carlo samples
