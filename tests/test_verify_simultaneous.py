"""The verification's intervals are simultaneous over the poses (Bonferroni): a design exactly at p everywhere is
called *failed* at some pose in at most about 1 - level of the runs, however many poses are verified; a possible
second look at a certified pose is one more interval of the family."""

from pathlib import Path

import numpy as np
import pytest

from tolalloc.montecarlo.intervals import family_size, simultaneous_level, z_of_level
from tolalloc.montecarlo.streaming import proportion_ci
from tolalloc.verify.resolution import resolvable_n
from tolalloc.verify.verdicts import (family_text, interval_words, overall_verdict, pose_verdicts,
                                      verification_family)

P_REQ, POSES, N, RUNS = 0.95, 18, 2000, 4000


def test_bonferroni_level():
    assert simultaneous_level(0.95, 1) == 0.95
    assert simultaneous_level(0.95, 18) == pytest.approx(1 - 0.05 / 18)
    assert simultaneous_level(0.95, 36) == pytest.approx(0.99861111)
    assert z_of_level(simultaneous_level(0.95, 18)) == pytest.approx(2.9913, abs=1e-4)
    # the sample size that can resolve p grows with z^2: 73 for one 95 % interval, 171 for one of 18
    assert resolvable_n(0.95) == 73 and resolvable_n(0.95, simultaneous_level(0.95, 18)) == 171
    assert interval_words(0.95, 1) == "95%" and interval_words(0.95, 18) == "simultaneous 95%"
    assert family_text(0.95, 36, 18, 2) == ("95% simultaneous over the 18 poses and 2 requirements (Bonferroni: 36 "
                                            "intervals at 99.86% each)")


def _false_failed_rate(level: float) -> float:
    """Share of runs in which a design with P = p at every pose is called failed, plain (Wilson) intervals at
    ``level`` each (the estimator itself simulated: binomial hit counts, no robot)."""
    rng = np.random.default_rng(2024)
    hits = rng.binomial(N, P_REQ, size=(RUNS, POSES))
    ci = proportion_ci(hits.ravel(), N, "wilson", level).reshape(RUNS, POSES, 3)
    failed = [overall_verdict(pose_verdicts(c[:, 1], c[:, 2], P_REQ)) == "failed" for c in ci]
    return float(np.mean(failed))


def test_family_wise_rate_of_a_false_failed_verdict():
    # 4000 runs of 18 poses: the rate's sd is about 0.0035 at 5 %, so 0.05 + 3 sd = 0.061 bounds the simultaneous
    # rule; per-pose 95 % intervals call a correct design failed in about 1 - 0.975^18 = 37 % of the runs
    simultaneous = _false_failed_rate(simultaneous_level(0.95, POSES))
    per_pose = _false_failed_rate(0.95)
    assert simultaneous <= 0.061, simultaneous
    assert per_pose > 0.30, per_pose


@pytest.mark.parametrize("level, m, match", [(0.95, 0, "m >= 1 .* got m = 0"), (0.95, 2.7, "got m = 2.7"),
                                             (0.95, True, "got m = True"), (1.0, 3, "in \\(0, 1\\) .* level = 1.0"),
                                             (0.0, 3, "level = 0.0"), ("0.95", 3, "level = '0.95'")])
def test_bonferroni_level_refuses_a_bad_count_or_level(level, m, match):
    from tolalloc import TolallocError

    with pytest.raises(TolallocError, match=f"simultaneous_level: expected .*{match}"):
        simultaneous_level(level, m)
    assert simultaneous_level(0.9, 4.0) == pytest.approx(0.975)


def test_family_counts_a_possible_second_look_at_each_certified_position_interval():
    # certified with n_max > n_mc: a straddling position interval is re-run, so each pose has one possible second look
    assert verification_family(18, 1, "certified", 2000, 8000) == (36, 18)
    assert verification_family(18, 2, "certified", 2000, 8000) == (54, 18)  # orientation: never re-run
    # no second look possible: certified with n_max = n_mc, or the exact criterion (whatever n_max)
    assert verification_family(18, 1, "certified", 2000, 2000) == (18, 0)
    assert verification_family(18, 2, "exact", 2000, 8000) == (36, 0)
    assert verification_family(1, 1, "certified", 2000, 8000) == (2, 1)
    assert simultaneous_level(0.95, family_size(18, 18)) == pytest.approx(1 - 0.05 / 36)
    assert simultaneous_level(0.95, family_size(18)) == simultaneous_level(0.95, 18)
    assert family_text(0.95, 36, 18, 1, 18) == ("95% simultaneous over the 18 poses (Bonferroni: 36 intervals at "
                                                "99.86% each, a possible second look at each position interval "
                                                "counted)")
    assert family_text(0.95, 54, 18, 2, 18).startswith("95% simultaneous over the 18 poses and 2 requirements "
                                                       "(Bonferroni: 54 intervals at 99.91% each, a possible second")
    assert family_text(0.95, 36, 18, 2) == ("95% simultaneous over the 18 poses and 2 requirements (Bonferroni: 36 "
                                            "intervals at 99.86% each)")


@pytest.mark.parametrize("m, looks, match", [(0, 0, "n_intervals >= 1 .* got n_intervals = 0"),
                                             (18, -1, "second looks >= 0 .* got second_looks = -1"),
                                             (18, 1.5, "got second_looks = 1.5"), (True, 0, "n_intervals = True")])
def test_family_size_refuses_a_bad_count(m, looks, match):
    from tolalloc import TolallocError

    with pytest.raises(TolallocError, match=f"family_size: expected .*{match}"):
        family_size(m, looks)


def test_sample_size_rule_with_the_second_look_counted_is_the_pages():
    # the plain interval's resolvable n grows with z^2: 18 poses judged once (z 2.99), or with a possible second
    # look at each (36 intervals, z 3.20); the concepts page quotes both
    once = resolvable_n(0.95, simultaneous_level(0.95, 18))
    twice = resolvable_n(0.95, simultaneous_level(0.95, family_size(18, 18)))
    z_twice = z_of_level(simultaneous_level(0.95, family_size(18, 18)))
    assert (once, twice) == (171, 195) and round(z_twice, 2) == 3.2
    page = " ".join((Path(__file__).parents[1] / "docs" / "concepts" / "verification.md").read_text().split())
    assert (f"{once} samples at $p = 0.95$ over 18 poses judged once, {twice} with a possible second look at each "
            f"(36 intervals, $z = {z_twice:.2f}$)") in page


P_TWO, N_FIRST, N_MAX = 6, 2000, 8000  # the default n_max = 4 n_mc


def _two_look_rates(m: int, pooled: bool) -> tuple[float, float]:
    """Family-wise rates of the certified two-look decision for a design with P = p at ``P_TWO`` poses, every
    interval at ``simultaneous_level(0.95, m)``: ``(false demonstrated, some interval misses P)``.

    First look: ``N_FIRST`` binomial hits, Wilson interval; a pose whose interval straddles p (lower < p <= upper) is
    looked at again -- pooled with ``N_MAX - N_FIRST`` more hits (plain and paired runs) or ``N_MAX`` fresh ones
    (importance sampling) -- and judged by that interval. *False demonstrated*: some pose's deciding lower bound at
    or above p (a pass the design only just misses at P a hair below p); *misses*: some deciding interval excludes P.
    """
    rng = np.random.default_rng(2024)
    first = rng.binomial(N_FIRST, P_REQ, size=(RUNS, P_TWO))
    more = rng.binomial(N_MAX - N_FIRST if pooled else N_MAX, P_REQ, size=(RUNS, P_TWO))
    lvl = simultaneous_level(0.95, m)
    ci1 = proportion_ci(first, N_FIRST, "wilson", lvl)
    ci2 = proportion_ci(first + more, N_MAX, "wilson", lvl) if pooled else proportion_ci(more, N_MAX, "wilson", lvl)
    again = (ci1[..., 1] < P_REQ) & (ci1[..., 2] >= P_REQ)
    ci = np.where(again[..., None], ci2, ci1)
    demonstrated = np.mean((ci[..., 1] >= P_REQ).any(axis=1))
    misses = np.mean(((ci[..., 1] > P_REQ) | (ci[..., 2] < P_REQ)).any(axis=1))
    return float(demonstrated), float(misses)


def _pct(x: float) -> str:
    return f"{100 * x:.1f} %"


def test_family_wise_rates_of_the_two_look_certified_decision():
    """A design with P = p at 6 poses, 4000 runs of the certified decision (first look 2000 samples, a straddling
    pose looked at again with n_max = 8000), the rates over the runs (this test computes them and checks that these
    figures are its own):

    ============================= =========================== ==============================
    second look                   old rule: 6 intervals       second looks counted: 12
    ============================= =========================== ==============================
    pooled   (false demonstrated) 3.8 %                       2.1 %
    pooled   (an interval misses) 8.8 %                       4.9 %
    fresh    (false demonstrated) 3.8 %                       2.0 %
    fresh    (an interval misses) 9.6 %                       5.1 %
    ============================= =========================== ==============================

    The false "demonstrated" rate stays below 5 % under either rule (each two-sided interval spends only half its
    alpha below P); the claim the report prints -- all intervals cover their P at 95 % together -- fails in about
    twice 5 % of the runs when the second looks are not counted, and holds when they are (within the simulation's
    sd of 0.35 %; a Wilson interval's coverage far in the tail is a little below its nominal level).
    """
    sd = np.sqrt(0.05 * 0.95 / RUNS)
    rows = {}
    for pooled in (True, False):
        old, new = _two_look_rates(P_TWO, pooled), _two_look_rates(family_size(P_TWO, P_TWO), pooled)
        assert new[0] <= 0.05 and new[1] <= 0.05 + 3 * sd, (pooled, new)
        assert old[1] > 0.05 + 3 * sd, (pooled, old)  # the uncounted second look breaks the printed claim
        rows["pooled" if pooled else "fresh"] = (old, new)
    doc = " ".join(test_family_wise_rates_of_the_two_look_certified_decision.__doc__.split())
    for look, (old, new) in rows.items():
        assert f"{look} (false demonstrated) {_pct(old[0])} {_pct(new[0])}" in doc, (look, old, new)
        assert f"{look} (an interval misses) {_pct(old[1])} {_pct(new[1])}" in doc, (look, old, new)
