"""Joint allocation of machining standard values and bought parts: the mixed-integer program against enumeration of
the part combinations (each solved by the standard-grade machinery alone), the region loop, the parts table, and
the errors for parts that cannot carry the load."""

import itertools
from dataclasses import replace

import numpy as np
import pytest

import tolalloc
from tolalloc.allocate.catalogue import build_catalogue
from tolalloc.allocate.discrete_rules import solve_discrete_rule
from tolalloc.allocate.parts import allocate_parts
from tolalloc.allocate.parts_discrete import parts_ratio, solve_parts_rule
from tolalloc.allocate.parts_problem import Points, option_blocks, parts_problem, signature_combos
from tolalloc.allocate.region import box_region
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.parts import Conditions
from tolalloc.robot.part_catalogue import builtin_catalogue

from parts_robot import CLASSES, arm

COND = Conditions((0.0, 1.0), (15.0, 30.0))
RADIUS = 1.5


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    robot = arm(tmp_path_factory.mktemp("arm"))
    model = build_error_model(robot)
    lo, hi = robot.regions["work"]
    points = Points.grid(np.array([0.5 * (lo + hi)]), COND.check(robot).corners())
    (combo,) = signature_combos(robot)
    ob = option_blocks(robot, model, points, combo, COND)
    pr = parts_problem(model, points, ob.fixed_cov, ob.bias_mm, radius_mm=RADIUS, prob=0.95, costs=CLASSES)
    return robot, model, points, ob, pr, build_catalogue(pr)


def test_joint_program_equals_enumeration_of_the_parts(setup):
    robot, model, points, ob, pr, cat = setup
    out = solve_parts_rule(pr, cat, ob, "trace")
    assert out.status == "optimal" and parts_ratio(pr, ob, "trace", cat.u_of(out.opt, out.n), out.part)[0] <= 1
    costs = {}
    per_slot = [np.flatnonzero(ob.slot == s) for s in range(len(ob.keys))]
    for part in itertools.product(*per_slot):  # each part combination: the machining alone, its covariance fixed
        fixed = parts_problem(model, points, ob.fixed_cov + ob.cov[list(part)].sum(0), ob.bias_mm, radius_mm=RADIUS,
                              prob=0.95, costs=CLASSES)
        r = solve_discrete_rule(fixed, build_catalogue(fixed), "trace")
        if r.status == "optimal":
            costs[part] = r.cost + ob.cost[list(part)].sum()
    best = min(costs, key=costs.get)
    assert len(costs) >= 2 and out.cost <= costs[best] * (1 + 1e-3) and costs[best] <= out.cost * (1 + 1e-3)
    assert ob.choice(out.part) == ob.choice(best) or abs(costs[tuple(out.part)] - costs[best]) <= 1e-3 * costs[best]


def test_region_loop_parts_table_and_budget(setup):
    robot, model = setup[0], setup[1]
    lo, hi = robot.regions["work"]
    res = allocate_parts(model, box_region(robot, lo, hi), conditions=COND, radius_mm=RADIUS, rules=("trace",),
                         costs=CLASSES, exact=False, n_seed=64, n_starts=1, seed=1)
    assert res.ok and res.worst.ratio <= 1 + 1e-3 and res.outcome.gap == pytest.approx(1e-3)
    tab = res.parts_table()
    assert list(tab.columns) == ["joint", "kind", "part", "family", "grade", "options", "cost", "cost_source",
                                 "figures", "source", "variance_share_pct"]
    assert set(tab["part"]) >= {res.choice[("j1", "reducer")], res.choice[("j2", "reducer")]}
    shares = res.variance_shares()
    assert shares["share_pct"].sum() == pytest.approx(100.0)
    assert res.cost == pytest.approx(res.machining_cost + tab["cost"].fillna(0).sum())
    w = res.worst.point
    assert COND.payload_kg[0] <= w.payload_kg[0] <= COND.payload_kg[1] and 15 <= w.ambient_c[0] <= 30


def test_parts_that_cannot_carry_the_load_are_refused(tmp_path):
    model = build_error_model(arm(tmp_path, "", "a.toml"))
    heavy = arm(tmp_path, "", "b.toml")  # j1 offered a size 14 gear, rated 10 N m
    slots = dict(heavy.components.slots)
    slots[("j1", "reducer")] = replace(slots[("j1", "reducer")], options=builtin_catalogue().family("reducer",
                                                                                                  "HD-CSG-14-100"))
    object.__setattr__(heavy, "components", replace(heavy.components, slots=slots))
    with pytest.raises(tolalloc.TolallocError, match=r"joint j1: HD-CSG-14-100 is rated 10 N m, but the gravity load "
                                                     r"reaches 14.59 N m in the poses at the payload of 1 kg, .* "
                                                     r"above; drop it, or choose a reducer rated for at least .* "
                                                     r"\(in the built-in catalogue: HD-CSG-17-100 \(31 N m\)"):
        allocate_parts(build_error_model(heavy), conditions=COND, q=np.zeros((1, 3)))
    with pytest.raises(tolalloc.TolallocError, match=r"no design meets P\(\|dP\| < 0.01 mm\) >= 0.95 with these parts "
                                                     r"and process limits: the bought parts' mean error alone is "
                                                     r"0.9\d+ mm at point \d \(payload 1 kg, ambient 15 degC\), at or "
                                                     r"above the radius 0.01 mm: compensate it \(`after='compensation'`"):
        allocate_parts(model, conditions=COND, q=np.zeros((1, 3)), radius_mm=0.01, exact=False)
    # stated after compensation already, the advice is to compensate more, not to turn it on
    with pytest.raises(tolalloc.TolallocError, match=r"above the radius 0.001 mm: compensate more \(a smaller "
                                                     r"residual\), choose stiffer parts"):
        allocate_parts(model, conditions=COND, q=np.zeros((1, 3)), radius_mm=0.001, after="compensation", exact=False)
    # the mean below the radius but the finest parts' spread too wide: the same advice, one wording for both reasons
    with pytest.raises(tolalloc.TolallocError, match=r"the finest part of every slot the trace rule is exceeded by a "
                                                     r"factor 3.75\d; .* mean error is 0.963 mm: relax the radius, "
                                                     r"compensate it \(`after='compensation'`, or a smaller residual\), "
                                                     r"or offer finer parts"):
        allocate_parts(model, conditions=COND, q=np.zeros((1, 3)), radius_mm=1.1, exact=False)
    with pytest.raises(tolalloc.TolallocError, match=r"mean error is 0.0963 mm: relax the radius, compensate more "
                                                     r"\(a smaller residual\), or offer finer parts"):
        allocate_parts(model, conditions=COND, q=np.zeros((1, 3)), radius_mm=0.1, after="compensation", exact=False)


def test_calibration_aware_allocation_sees_the_parts(setup):
    from tolalloc.allocate.calibrated import allocate_calibrated
    from tolalloc.allocate.calibrated.certified import post_ratio
    from tolalloc.calibration import make_plan, split_errors

    robot, model, points = setup[0], setup[1], setup[2]
    res = allocate_parts(model, q=points.q[:1], conditions=COND, radius_mm=0.4, after="compensation", rules=("lmi",),
                         costs=CLASSES, exact=False)
    rng = np.random.default_rng(0)
    plan = make_plan(robot, robot.lower + (robot.upper - robot.lower) * rng.random((8, 3)))
    with_parts = allocate_calibrated(res.problem, plan)
    without = allocate_calibrated(replace(res.problem, extra_cov=0 * res.problem.extra_cov,
                                          scale=np.ones_like(res.problem.scale)), plan)
    assert with_parts.certified and without.certified
    assert with_parts.design.cost > without.design.cost  # what calibration cannot remove of the parts costs tolerance
    ratio, _ = post_ratio(res.problem, split_errors(res.problem.model), plan, with_parts.design.t)
    assert ratio <= 1.0
