"""Capability-aware allocation (issue 45, part 3): mean shifts, Cpk targets, a fleet's spread factors.

Known answers: with the default capability (Cpk 1, no shift) the problem is the centred one, and the cone program
with bounded shifts, with a vanishing shift, reproduces the centred certified design of :func:`solve_rule`; a design
with bounded shifts holds its requirement for shifts drawn at the bound with the worst signs (seeded Monte Carlo);
explicit shifts are judged by the exact non-centred ball probability, which the uniform widening of
:func:`rescale_exact` brings down to the target.
"""

import numpy as np
import pytest

import tolalloc
from tolalloc.allocate.capability import (Capability, capable_covariances, capable_probabilities, pose_means,
                                          rescale_exact, shift_bounds, solve_capable)
from tolalloc.allocate.convex import solve_rule
from tolalloc.allocate.problem import build_problem
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError


@pytest.fixture(scope="module")
def problem():
    return build_problem(build_error_model(tolalloc.load_robot("tool_changer")), radius_mm=0.25, prob=0.95)


@pytest.mark.parametrize("rule", ["trace", "lmi"])
def test_default_and_vanishing_shift_reproduce_the_centred_design(problem, rule):
    ref = solve_rule(problem, rule)
    same = solve_capable(problem, Capability(), rule)
    np.testing.assert_allclose(same.design.t, ref.design.t if hasattr(ref, "design") else ref.t, rtol=1e-12)
    cone = solve_capable(problem, Capability(shift_sigma=1e-12), rule)  # the bounded-shift cone program in v
    assert cone.design.ok and cone.kind == "lower bound"
    assert cone.design.cost == pytest.approx(ref.cost, rel=1e-6)
    np.testing.assert_allclose(cone.design.t, ref.t, rtol=1e-3)


def test_bounded_shift_holds_for_worst_signed_shifts(problem):
    cap = Capability(cpk=1.33, shift_sigma=1.5)
    res = solve_capable(problem, cap, "lmi")
    centred = solve_rule(problem, "lmi")
    assert res.design.ok and res.design.cost > centred.cost  # drifting processes cost more
    assert np.all(res.probability >= 0.95 - 1e-9)
    t = res.design.t
    sig = t / (problem.costs.z * 1.33)
    shift = 1.5 * t / (problem.costs.z * 1.33 + 1.5)
    rng = np.random.default_rng(3)
    J = problem.J[:, :3, :]
    for i in range(problem.n_poses):  # shifts at the bound, signs along the pose's first principal direction
        d = np.linalg.svd(J[i])[0][:, 0]
        mu = shift * np.sign(d @ J[i])
        x = (J[i] @ mu) + (rng.normal(size=(20000, len(t))) * sig) @ J[i].T
        p = np.mean(np.linalg.norm(x, axis=1) < problem.radius_mm)
        assert p >= 0.95 - 3 * np.sqrt(0.05 * 0.95 / 20000)
    assert np.all(shift_bounds(problem, t, cap) > 0)


def test_explicit_shift_exact_probability_and_rescale(problem):
    K = len(problem.costs.names)
    mean = np.where([p.unit == "mm" for p in problem.model.params], 0.004, 2e-5)
    cap = Capability(mean=mean, spread_factor=np.full(K, 1.2))
    res = solve_capable(problem, cap, "lmi")
    assert res.design.ok and res.kind == "exact"
    from tolalloc.linear.probability import p_within_radius

    C = capable_covariances(problem, res.design.t, cap)
    np.testing.assert_allclose(res.probability, p_within_radius(C, 0.25, mean=pose_means(problem, cap)))
    assert res.probability.min() >= 0.95
    wider = rescale_exact(problem, res)
    assert wider.design.cost <= res.design.cost and wider.probability.min() >= 0.95 - 1e-9
    assert wider.probability.min() < res.probability.min()
    p, kind = capable_probabilities(problem, wider.design.t, cap)
    assert kind == "exact" and p.min() == pytest.approx(wider.probability.min())
    with pytest.raises(TolallocError, match="bounded shifts, whose exact worst-case probability is not computed"):
        rescale_exact(problem, solve_capable(problem, Capability(shift_sigma=1.5), "trace"))


def test_capability_bad_input(problem):
    K = len(problem.costs.names)
    with pytest.raises(TolallocError, match=r"cpk expected finite values > 0, got 0 for dl1, dl2, dl3 \.\.\."):
        solve_capable(problem, Capability(cpk=0.0))
    with pytest.raises(TolallocError, match=f"spread_factor expected one value or {K}"):
        solve_capable(problem, Capability(spread_factor=[1.0, 2.0]))
    with pytest.raises(TolallocError, match="the mean error alone is .* at or beyond the required radius 0.25 mm"):
        solve_capable(problem, Capability(pose_mean_mm=np.tile([0.3, 0.0, 0.0], (problem.n_poses, 1))))
    with pytest.raises(TolallocError, match="rule: expected 'trace' or 'lmi', got 'exact'"):
        solve_capable(problem, Capability(), "exact")
    angled = build_problem(problem.model, radius_mm=0.25, prob=0.95, angle_radius_deg=0.05)
    with pytest.raises(TolallocError, match="handles the position requirement only"):
        solve_capable(angled, Capability())
