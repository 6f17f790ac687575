"""Standard grades chosen by the optimiser (tolalloc.allocate.discrete*, catalogue, discretize, region_standard).

Known answers: brute-force enumeration of every standard design of a small chain (the certified rules'
MILP optimum and the exact search's design must equal the cheapest enumerated design), ISO 286 values,
and the rounding it replaces.
"""

import itertools

import numpy as np
import pytest

from tolalloc import TolallocError
from tolalloc.allocate import allocate, build_problem
from tolalloc.allocate.catalogue import build_catalogue
from tolalloc.allocate.costs import cost_set
from tolalloc.allocate.discrete import MIP_REL_GAP
from tolalloc.allocate.discrete_rules import rule_violation, solve_discrete_rule
from tolalloc.allocate.discrete_exact import exact_margin, screened_violation
from tolalloc.allocate.region import box_region, coverage
from tolalloc.allocate.region_standard import allocate_region_standard
from tolalloc.allocate.standards import IT_TABLE_UM
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io.robotfile import robot_from_chain_dict

PLANAR = {"name": "planar2", "chain": [
    {"joint": "j1", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l1", "vector_mm": [300, 0, 0]},
    {"joint": "j2", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90], "nominal_deg": 0},
    {"link": "l2", "vector_mm": [200, 0, 0]}]}
POSES = np.deg2rad([[10.0, 0.0], [0.0, 60.0]])
#: drives on a 0.001 deg step between 0.001 and 0.02 deg: 20 values each, 8 grades per link: 25600 designs
SMALL = {"kinds": {"joint_drive": {"t_min_deg": 0.001, "t_max_deg": 0.02, "step_deg": 0.001}}}


@pytest.fixture(scope="module")
def model():
    return build_error_model(robot_from_chain_dict(PLANAR), exclude=("axis_deflection",))


def enumerate_designs(cat):
    """Every choice of the catalogue: (opt (D, Ka), n (D, Ka), u (D, Ka), cost (D,))."""
    per = []
    for a in range(cat.n_params):
        lst = []
        for o in range(cat.start[a], cat.start[a + 1]):
            lst += [(o, k) for k in range(cat.n_lo[o], cat.n_hi[o] + 1)] if cat.stepped[o] else [(o, 0)]
        per.append(lst)
    combos = np.array(list(itertools.product(*per)))  # (D, Ka, 2)
    opt, n = combos[..., 0], combos[..., 1]
    t = np.where(cat.stepped[opt], n * np.nan_to_num(cat.step[opt]), cat.t[opt])
    u = (t / cat.t_ref[None]) ** 2
    cost = np.zeros(len(opt))
    for a in range(cat.n_params):
        for o in range(cat.start[a], cat.start[a + 1]):
            sel = opt[:, a] == o
            cost[sel] += cat.law[o].cost(t[sel, a]) if cat.stepped[o] else cat.cost[o]
    used = np.zeros((len(opt), len(cat.groups)), bool)
    for a in range(cat.n_params):
        g = cat.group[opt[:, a]]
        used[np.arange(len(opt))[g >= 0], g[g >= 0]] = True
    cost += used @ np.array([g[2] for g in cat.groups]) if cat.groups else 0.0
    ok = np.ones(len(opt), bool)  # a part uses one process
    for part in {g[0] for g in cat.groups}:
        ok &= used[:, [i for i, g in enumerate(cat.groups) if g[0] == part]].sum(axis=1) <= 1
    return opt, n, u, cost, ok


@pytest.fixture(scope="module")
def small(model):
    pr = build_problem(model, POSES, radius_mm=0.1, costs=SMALL)
    res = allocate(pr, discrete_certified=True)
    cat = build_catalogue(pr)
    return pr, res, cat, enumerate_designs(cat)


def test_catalogue_holds_the_iso_grades_and_the_step_multiples(small):
    pr, _, cat, (opt, *_rest) = small
    assert len(opt) == 8 * 8 * 20 * 20
    row = IT_TABLE_UM[10]  # 250 < D <= 315 mm (link l1, 300 mm)
    dl1 = slice(cat.start[0], cat.start[1])
    np.testing.assert_allclose(cat.t[dl1], row[4:12] / 2000.0)  # IT5..IT12, +-IT/2
    assert cat.label[dl1] == tuple(f"IT{g}" for g in range(5, 13))
    o = cat.start[2]
    assert cat.stepped[o] and (cat.n_lo[o], cat.n_hi[o]) == (1, 20)
    assert cat.step[o] == pytest.approx(np.deg2rad(0.001))


@pytest.mark.parametrize("rule", ["trace", "lmi"])
def test_certified_rule_milp_equals_brute_force(small, rule):
    pr, res, cat, (opt, n, u, cost, _) = small
    best = cost[rule_violation(pr, rule, u) <= 0].min()
    cont = res.certified if res.certified.solver == f"certified-{rule}" else res.certified_other
    out = solve_discrete_rule(pr, cat, rule, cont)
    assert out.status == "optimal"
    assert best <= out.cost <= best * (1 + MIP_REL_GAP)  # the proof's tolerance
    assert out.cost == pytest.approx(best, rel=1e-12)  # and here the MILP found the enumerated optimum itself
    assert out.bound <= best and cont.cost <= best  # both lower bounds are valid


def test_exact_search_equals_brute_force_and_beats_rounding(small):
    pr, res, cat, (opt, n, u, cost, _) = small
    std = res.standard
    assert std.solver == "discrete-exact" and std.ok
    # every enumerated design cheaper than the one found misses the requirement (the exact P of the others
    # need not be computed), and the one found is an enumerated design
    cheaper = cost < std.cost * (1 - 1e-12)
    assert cheaper.sum() > 100 and np.all(exact_margin(pr, u[cheaper]) < 0)
    assert np.min(np.abs(cost - std.cost)) < 1e-12 * std.cost
    assert std.p_linear["position"].min() >= pr.prob  # the exact Gaussian P, no tolerance
    # rounding down costs 14.8 % over the continuous design here, the chosen standard design 1.7 %
    assert res.rounded.cost > 1.1 * std.cost and std.cost < 1.02 * res.design.cost
    d = res.discrete
    assert d.gap_pct == pytest.approx(100 * (std.cost / res.design.cost - 1))
    assert [o.rule for o in d.outcomes] == ["trace", "lmi", "exact"] or [o.rule for o in d.outcomes] == ["lmi", "exact"]


@pytest.mark.parametrize("n_screen", [1, 3])
def test_screened_violation_accepts_exactly_the_designs_that_meet_the_requirement(model, n_screen):
    """The local search's screen (a few binding poses first) accepts the same designs as the full check, on 12
    poses and 800 catalogue designs, the first row setting the screen's poses."""
    rng = np.random.default_rng(5)
    poses = np.deg2rad(rng.uniform(-90, 90, (12, 2)))
    pr = build_problem(model, poses, radius_mm=0.1, costs=SMALL)
    _, _, u, _, _ = enumerate_designs(build_catalogue(pr))
    U = u[rng.choice(len(u), 800, replace=False)]
    full = -exact_margin(pr, U)
    screened = screened_violation(pr, U, n_screen)
    assert 40 < np.sum(full <= 0) < 760                          # both outcomes are well represented
    np.testing.assert_array_equal(screened <= 0, full <= 0)
    np.testing.assert_array_equal(screened[full <= 0], full[full <= 0])   # the accepted rows' values are the full ones
    assert np.all(screened[full > 0] <= full[full > 0])          # elsewhere a bound from fewer poses


def test_rounding_infeasible_where_the_discrete_design_is_not(model):
    # a coarse angle step (0.016 deg) rounds dth1 (0.0105 deg) up to one step: the rounded design misses p
    pr = build_problem(model, POSES, radius_mm=0.1)
    res = allocate(pr, angle_step_deg=0.016)
    assert res.rounded.status == "violated" and res.rounded.p_linear["position"].min() < 0.945
    std = res.standard
    assert std.ok and std.fallback_from is None and std.p_linear["position"].min() >= pr.prob
    steps = np.rad2deg(std.t[2:]) / 0.016
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-9)  # on the step
    # the links pay for it: finer grades than the continuous optimum's rounding
    assert all(g.startswith("IT") for g in res.grade[:2])


@pytest.mark.parametrize("solver", ["certified", "exact"])
def test_orientation_requirement_is_met_by_the_standard_design(model, solver):
    pr = build_problem(model, POSES, radius_mm=0.1, costs=SMALL, angle_radius_deg=0.004)
    res = allocate(pr, solver=solver)
    std = res.standard
    assert std.ok and std.solver in (("discrete-lmi", "discrete-trace") if solver == "certified" else ("discrete-exact",))
    for name, p in std.p_linear.items():
        assert p.min() >= (pr.prob if name == "position" else pr.angle_prob)
    assert res.design.p_linear["orientation"].min() < 0.96  # the angle requirement binds
    assert res.rounded is not None and std.cost <= res.rounded.cost


def test_no_standard_design_is_reported_as_such(model):
    pr = build_problem(model, POSES, radius_mm=0.1)
    res = allocate(pr, angle_step_deg=0.02)  # one step already exceeds what the links can make up for
    assert res.standard.status == "infeasible" and not res.standard.ok
    assert "even every parameter at its finest standard value" in res.standard.message


LENGTH_PROCESSES = {
    "grinding": {"grades": "IT5-IT7", "cost": {"IT5": 4.0, "IT6": 3.0, "IT7": 2.6}, "setup": 0.3},
    "milling": {"grades": "IT7-IT12", "model": "reciprocal", "a": 1.0, "b": 1.2, "t_ref_mm": 0.1}}
DRIVE_PROCESSES = {  # stepped values: each process a range of step multiples with its own law
    "precision": {"applies_to": ["joint_drive"], "t_max_deg": 0.005, "model": "reciprocal", "a": 1.5, "b": 1.0,
                  "t_ref_deg": 0.01, "setup": 0.2},
    "standard": {"applies_to": ["joint_drive"], "t_min_deg": 0.004, "model": "reciprocal", "a": 1.0, "b": 1.0,
                 "t_ref_deg": 0.01}}


@pytest.mark.parametrize("processes, a", [(LENGTH_PROCESSES, 0), (DRIVE_PROCESSES, 2)])
def test_processes_milp_equals_brute_force(model, processes, a):
    costs = {**SMALL, "processes": processes}
    pr = build_problem(model, POSES, radius_mm=0.1, costs=cost_set(model, costs))
    cat = build_catalogue(pr)
    assert set(cat.process[cat.start[a]:cat.start[a + 1]]) == set(processes)
    opt, n, u, cost, ok = enumerate_designs(cat)
    res = allocate(pr, solver="certified")
    rule = str(res.certified.solver).split("-")[1]
    best = cost[ok & (rule_violation(pr, rule, u) <= 0)].min()
    out = solve_discrete_rule(pr, cat, rule, res.certified)
    assert out.status == "optimal" and best <= out.cost <= best * (1 + MIP_REL_GAP)
    assert res.standard.cost == pytest.approx(min(o.cost for o in res.discrete.outcomes))
    frame = res.to_frame()
    name = pr.costs.names[pr.alloc[a]]
    assert frame.loc[frame.parameter == name, "process"].item() in processes
    assert res.summary()["standard"]["processes"][name] in processes


BAD = [
    ({"kinds": {"link_length": {"grades": "IT5-IT20"}}}, r"\[kinds.link_length\].*grades: unknown grade 'IT20'"),
    ({"parameters": {"dl1": {"grades": "IT9-IT7"}}}, r"\[parameters.dl1\] grades: the grade range 'IT9-IT7' is empty"),
    ({"kinds": {"joint_drive": {"grades": "IT7"}}}, r"grades \(ISO 286\) apply to link_length parameters only"),
    ({"kinds": {"joint_drive": {"step_deg": -0.001}}}, r"step_deg expected a finite number > 0"),
    ({"kinds": {"joint_drive": {"classes_deg": {}}}}, r"classes_deg is empty"),
    ({"kinds": {"joint_drive": {"classes_mm": [0.01]}}}, r"classes_mm has the wrong unit"),
    ({"processes": {"grinding": {"grades": "IT5-IT7", "cost": {"IT5": 4.0, "IT6": -1.0, "IT7": 2.0}}}},
     r"\[processes.grinding\]: cost.IT6 expected a finite cost >= 0"),
    ({"processes": {"grinding": {"grades": "IT5-ITx", "cost": {"IT5": 4.0}}}},
     r"\[processes.grinding\] grades: unknown grade 'ITx'"),
    ({"processes": {"grinding": {"grades": "IT7-IT5", "cost": {"IT5": 4.0}}}}, r"grade range 'IT7-IT5' is empty"),
    ({"processes": {"grinding": {"grades": "IT5-IT6", "cost": {"IT9": 4.0}}}}, r"cost.IT9: not a grade of the process range"),
    ({"processes": {"grinding": {"grades": "IT5-IT6"}}}, r"give a cost per grade"),
    ({"processes": {"grinding": {"grades": "IT5-IT6", "cost": {"IT5": 1.0}, "setup": -2}}}, r"setup expected a finite cost >= 0"),
    ({"processes": {"grinding": {"applies_to": ["gearbox"], "cost": {"IT5": 1.0}}}}, r"applies_to: 'gearbox' is neither"),
    ({"processes": {"grinding": {"speed": 3, "cost": {"IT5": 1.0}}}}, r"unknown key 'speed'"),
    ({"processes": {"hob": {"applies_to": ["joint_drive"], "t_min_deg": 0.01, "t_max_deg": 0.001, "model": "reciprocal",
                            "b": 1.0, "t_ref_deg": 0.01}}}, r"attainable range is empty"),
]


@pytest.mark.parametrize("data, match", BAD)
def test_costs_file_standard_values_and_processes_are_validated(model, data, match):
    with pytest.raises(TolallocError, match=match):
        cost_set(model, data)


def test_no_candidate_within_the_limits_names_the_parameter(model):
    costs = {"kinds": {"joint_drive": {"t_min_deg": 0.0015, "t_max_deg": 0.0019, "step_deg": 0.001}}}
    pr = build_problem(model, POSES, costs=costs)
    with pytest.raises(TolallocError, match=r"standard values of dth1: none of its multiples of the step 0.001 deg"):
        build_catalogue(pr)


def test_bad_costs_file_gives_one_error_line(tmp_path, capsys):
    from tolalloc.cli import main

    path = tmp_path / "c.toml"
    path.write_text('[processes.grinding]\ngrades = "IT5-IT7"\ncost = { IT5 = 4.0, IT6 = -1.0, IT7 = 2.0 }\n')
    assert main(["allocate", "tool_changer", "--no-verify", "--costs", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and "cost.IT6" in err[0]


def test_discrete_off_keeps_the_rounding_and_flags_are_checked(model):
    pr = build_problem(model, POSES, radius_mm=0.1, costs=SMALL)
    res = allocate(pr, discrete=False)
    assert res.standard is res.rounded and res.discrete is None and res.standard.solver == "standard"
    with pytest.raises(TolallocError, match="discrete: expected True or False"):
        allocate(pr, discrete="yes")
    with pytest.raises(TolallocError, match="time_limit_s"):
        allocate(pr, time_limit_s=0)


def test_table_and_summary_carry_grades_processes_and_costs(small):
    pr, res, cat, _ = small
    frame = res.to_frame()
    for col in ("tol_mm", "tol_deg", "grade", "process", "cost", "tol_continuous_mm", "cost_continuous",
                "tol_rounded_mm", "tol_rounded_deg"):
        assert col in frame.columns
    assert frame["cost"].sum() == pytest.approx(res.standard.cost)  # the standard design, set-ups included
    assert frame.loc[frame.parameter == "dl1", "grade"].item().startswith("IT")
    c = res.summary()["costs"]
    assert c["continuous"] == pytest.approx(res.design.cost) and c["rounded"] == pytest.approx(res.rounded.cost)
    assert c["rounded_premium_pct"] == pytest.approx(100 * (res.rounded.cost / res.design.cost - 1))
    s = res.summary()["discrete"]
    assert s["solver"] == "discrete-exact" and s["gap_pct"] == pytest.approx(c["standard_premium_pct"])
    assert {o["rule"] for o in s["solves"]} >= {"lmi", "exact"}


def test_standard_design_holds_over_a_region(model):
    robot = model.robot
    box = box_region(robot, np.deg2rad([0, -40]), np.deg2rad([20, 60]), "box")
    ra = allocate_region_standard(model, box, radius_mm=0.1)
    assert ra.converged and ra.continuous.converged
    std = ra.result.standard
    assert std.ok and std.solver == "discrete-exact" and ra.worst_p >= 0.95 - 1e-4
    cov = coverage(ra.result.problem, std.t, box, n=5000, seed=3)
    assert cov.min_p >= 0.95 - 1e-4
    assert ra.time_s >= ra.continuous.time_s and len(ra.active_q) >= len(ra.continuous.active_q)


@pytest.mark.parametrize("solver", ["exact", "certified"])
def test_a_program_stopped_by_its_time_limit_is_not_called_optimal(model, solver):
    pr = build_problem(model, POSES, radius_mm=0.1, costs=SMALL)
    res = allocate(pr, solver=solver, time_limit_s=1e-4)  # HiGHS stops at once
    std = res.standard
    assert std.status == "not_converged" and not std.ok and "user_limit" in std.message
    assert std.p_linear["position"].min() >= pr.prob  # the design kept still meets the requirement
    assert res.summary()["discrete"]["proven_optimal"] is False


def test_a_part_the_costs_file_fixes_is_in_the_standard_design_cost(tmp_path):
    """The standard design's cost counts the fixed part's cost as the continuous design's does: the premium over
    the continuous optimum is then the few tenths of a percent of the grade steps, not minus the fixed part."""
    import tolalloc

    path = tmp_path / "costs.toml"
    path.write_text("[parameters.e1x]\nfixed = true\ntol_deg = 0.002\n")
    res = tolalloc.allocate_tolerances("tool_changer", region="nominal", costs=path, verification=False)
    frame = res.to_frame()
    assert frame.loc[frame.parameter == "e1x", "role"].item() == "fixed"
    assert res.cost == pytest.approx(frame["cost"].sum(), rel=1e-12)
    assert 0.0 <= res.summary()["discrete"]["gap_pct"] < 2.0
