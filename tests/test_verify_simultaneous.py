"""The verification's intervals are simultaneous over the poses (Bonferroni): a design exactly at p everywhere is
called *failed* at some pose in at most about 1 - level of the runs, however many poses are verified."""

import numpy as np
import pytest

from tolalloc.montecarlo.intervals import simultaneous_level, z_of_level
from tolalloc.montecarlo.streaming import proportion_ci
from tolalloc.verify.resolution import resolvable_n
from tolalloc.verify.verdicts import family_text, interval_words, overall_verdict, pose_verdicts

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
