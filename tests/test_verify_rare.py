"""A verification that reaches a verdict by itself at rare-event requirements (issue 46): importance sampling under
``auto``, zero-discordance pairs kept paired, and a correction loop that never asks for a target of 1 or more."""

from __future__ import annotations

import numpy as np
import pytest

from tolalloc import load_robot
from tolalloc.allocate import allocate, build_problem
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.estimate import fallback_text
from tolalloc.montecarlo.paired import PairedCounts, estimate_from_counts
from tolalloc.verify.correct import _cannot_tighten, imprecise_poses, needed_targets
from tolalloc.verify.designs import Verification, verify_design
from tolalloc.verify.verdicts import RequirementCheck

P5 = 0.99999


@pytest.fixture(scope="module")
def rare():
    """The exact design for p = 0.99999 at two ur10 working poses (P_lin = p at its binding pose)."""
    robot = load_robot("ur10")
    pr = build_problem(build_error_model(robot), robot.poses("working")[[0, 2]], prob=P5)
    return pr, allocate(pr, snap=False).design


def test_auto_verifies_a_rare_tail_by_importance_sampling_from_the_first_look(rare):
    pr, d = rare
    # n_max = n_mc: no second look; the tail 1 - p = 1e-5 is below RARE_TAIL, so auto runs importance sampling
    v = verify_design(pr, d, n_mc=2**13, n_max=2**13, seed=3, keep_samples=0)
    assert np.all(v.estimator == "importance") and (v.n_intervals, v.second_looks) == (2, 0)
    assert v.estimate.requested == "auto" and v.estimator_message().startswith("estimator: importance (requested "
                                                                                "auto)")
    # the interval resolves the tail: far narrower than the paired zero-count width z^2 / n = 6.1e-4
    assert np.all(v.ci_high - v.ci_low < 2e-6)
    # the same seed, the same numbers
    again = verify_design(pr, d, n_mc=2**13, n_max=2**13, seed=3, keep_samples=0)
    np.testing.assert_array_equal(v.p_mc, again.p_mc)


def test_a_pair_with_no_discordant_draw_is_not_called_a_poor_control():
    # P_lin = 1 - 1e-7 at pose 1, no discordant draw: the paired interval is the zero-count one; pose 2 has
    # discordant draws and a plain estimate that is better: plain Monte Carlo, the fallback says where
    n = 10**6
    counts = np.array([[[n, n, n]], [[n - 100, n - 100 + 40, n - 100 - 60]]], np.int64)  # nl in, lin in, both
    pc = PairedCounts(n, 0, counts, np.zeros(2))
    e = estimate_from_counts(pc, 0, 0.25, [1 - 1e-7, 0.9999], level=0.99)
    assert e.estimator.tolist() == ["paired", "plain"]
    assert e.fallback[0] == "" and e.fallback[1].startswith("poor control: variance reduction x")
    assert fallback_text(e.fallback).endswith("< 1, so plain Monte Carlo (pose 2)")
    assert "fallback to plain: poor control: variance reduction x" in e.message()


def _check(p_linear, p_mc, lo, hi):
    return RequirementCheck("position", P5, np.array(p_linear), np.array(p_mc), np.array(lo), np.array(hi))


def test_the_correction_target_is_never_one_or_more():
    # pose 1: estimate above p, interval too wide for any margin below 1 -> left alone (more samples decide it);
    # pose 2: estimate below p, same width -> halfway between p + shortfall and 1; pose 3: a narrow interval -> the
    # usual target p + shortfall + (z + 3) se
    chk = _check([0.99999, 0.999992, 0.99999], [0.999995, 0.999985, 0.9999899], [0.99997, 0.99996, 0.99998985],
                 [1.0, 0.99999, 0.99998995 + 2e-8])
    targets = needed_targets(chk, np.full(3, P5))
    assert np.all(targets < 1.0)
    assert targets[0] == P5
    assert targets[1] == pytest.approx(0.5 * (P5 + 7e-6 + 1.0))
    se = (chk.ci_high[2] - chk.ci_low[2]) / (2 * 1.959964)
    assert targets[2] == pytest.approx(P5 + 1e-7 + (1.959964 + 3) * se, abs=1e-12)
    assert imprecise_poses(chk, np.full(3, P5)).tolist() == [0]


def test_the_loop_says_when_only_more_samples_can_decide():
    n = np.full(1, 10**6)
    ver = Verification("exact", 0.25, P5, n, 0, np.array([P5]), np.array([0.999995]), np.array([0.99997]),
                       np.array([1.0]), np.array([True]), ("",), 0)
    targets = {"position": np.full(1, P5)}
    new = {"position": needed_targets(ver.requirements()[0], targets["position"])}
    assert _cannot_tighten(new, targets, ver, None) == (
        "position pose 1: the estimate 0.999995 is at or above p = 0.99999, but its interval (half-width 1.5e-05) is "
        "too wide to demonstrate it, and a target carrying that imprecision would be 1 or more; more samples "
        "(`n_mc`) or importance sampling (`estimator`) would decide it, tightening cannot")
