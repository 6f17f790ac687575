"""Upfront budgets of counts (issue 46): refused with the estimate and the largest count that fits, or announced."""

from __future__ import annotations

import warnings

import pytest

import tolalloc
from tolalloc import budget
from tolalloc.budget import LongRunWarning, check_count, duration_text, estimate_seconds
from tolalloc.exceptions import TolallocError


@pytest.fixture
def fixed_probe(monkeypatch):
    """A probe of exactly 10 ms: estimates are then plain arithmetic of the stated figures."""
    monkeypatch.setattr(budget, "probe_seconds", lambda: 0.01)
    monkeypatch.delenv(budget.TIME_BUDGET_ENV, raising=False)
    monkeypatch.delenv(budget.ANNOUNCE_ENV, raising=False)


def test_a_count_beyond_a_day_is_refused_with_the_largest_that_fits(fixed_probe):
    each = budget.WORK["mc"].probe_units * 0.01 / 2  # seconds per sample at one pose on 2 threads
    largest = int(86_400 // each)
    with pytest.raises(tolalloc.ArgumentError) as info:
        check_count(10**20, "n", "samples at 1 pose", "mc", threads=2, example="1000000")
    assert info.value.argument == "n"
    assert str(info.value) == (
        f"n 1e+20 samples at 1 pose would take about 269,349 years on 2 threads (1.7e-07 s per sample at one pose "
        f"(plain Monte Carlo) estimated for this machine), more than the time budget of a call, 24 h; expected at "
        f"most {largest:,} (e.g. 1000000), or raise the budget with TOLALLOC_TIME_BUDGET_S (seconds).")
    assert check_count(largest, "n", "samples", "mc", threads=2, announce=False).seconds <= 86_400


def test_several_kinds_of_work_and_a_fixed_part_add_up(fixed_probe):
    s = estimate_seconds(1000, {"mc": 12, "paired": 12}, scale=2.0, threads=4)
    assert s == pytest.approx(1000 * (1.7e-5 + 4.5e-5) * 12 * 0.01 * 2.0 / 4)
    # not parallel, with a fixed part: 140 probe units of set-up
    assert estimate_seconds(100, "candidate", threads=8) == pytest.approx(100 * 0.8 * 0.01 + 140 * 0.01)
    with pytest.raises(TolallocError, match=r"kind: expected keys of tolalloc.budget.WORK \(mc, paired, .*\), got "
                                            r"'nope'"):
        estimate_seconds(1, "nope")


def test_a_long_run_is_announced_before_it_starts(fixed_probe):
    with pytest.warns(LongRunWarning, match=r"^n = 1,000,000,000 samples at 1 pose: about 2.8 min \(1.7e-07 s per "
                                            r"sample at one pose \(plain Monte Carlo\) estimated for this machine\); "
                                            r"interrupt \(Ctrl-C\) to stop it, nothing is written\.$"):
        est = check_count(10**9, "n", "samples at 1 pose", "mc")
    assert est.seconds == pytest.approx(170.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_count(10**6, "n", "samples at 1 pose", "mc")  # 1.7 s: nothing said


def test_the_budget_and_the_announcement_are_set_by_environment_variables(fixed_probe, monkeypatch):
    monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", "10")
    with pytest.raises(tolalloc.ArgumentError, match=r"more than the time budget of a call, 10 s; expected at most "
                                                     r"58,823,529,? "):
        check_count(10**8, "n", "samples", "mc")
    monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", "inf")
    monkeypatch.setenv("TOLALLOC_ANNOUNCE_S", "inf")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_count(10**20, "n", "samples", "mc")
    for bad in ("-1", "soon", "nan", "0"):
        monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", bad)
        with pytest.raises(TolallocError, match=rf"^TOLALLOC_TIME_BUDGET_S: expected the time budget of a call in "
                                                rf"seconds, a number > 0 \(e.g. 86400 for a day\), got '{bad}'; fix or "
                                                r"unset the environment variable\.$"):
            budget.time_budget_s()


def test_the_count_must_be_a_whole_number(fixed_probe):
    with pytest.raises(tolalloc.ArgumentError, match=r"^n: expected a whole number, got 1.5\.$"):
        check_count(1.5, "n", "samples", "mc")


@pytest.mark.parametrize("seconds, text", [(3.14, "3.1 s"), (45, "45 s"), (600, "10 min"), (7200, "2 h"),
                                           (3 * 86400, "3 days"), (1e9, "32 years"), (1e12, "31,688 years"),
                                           (1e14, "3.2e+06 years"),
                                           (1e20, "3.2e+12 years")])
def test_durations_read_as_words(seconds, text):
    assert duration_text(seconds) == text


def test_the_probe_is_timed_once_per_process():
    budget.probe_seconds.cache_clear()
    first = budget.probe_seconds()
    assert 1e-4 <= first < 5.0 and budget.probe_seconds() == first


# ------------------------------------------------------------------------------------------------ the jobs
@pytest.fixture
def one_second(fixed_probe, monkeypatch):
    monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", "1")


@pytest.mark.parametrize("call, match", [
    (lambda: tolalloc.simulate_errors("tool_changer", 7e15),
     r"^n_mc 7e\+15 samples at 1 pose would take about [\d.e+,]+ years"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=10**15),
     r"^n_mc 1e\+15 samples per pose at 1 pose would take about [\d.e+,]+ years( on \d+ threads)? \(.*; one "
     r"verification, of up to 4 with the correction loop\), more than .* or switch the verification off\.$"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", region=tolalloc.Region(coverage_n=10**15),
                                          verification=False),
     r"^Region.coverage_n 1e\+15 coverage poses would take about [\d.,]+ years \(1.2e-05 s per coverage pose"),
])
def test_jobs_refuse_counts_that_cannot_finish_in_a_day(fixed_probe, call, match):
    with pytest.raises(tolalloc.ArgumentError, match=match):
        call()


@pytest.mark.parametrize("call, argument", [
    (lambda: tolalloc.analyze_errors("tool_changer", sobol_n=1_000_000), "sobol_n"),
    (lambda: tolalloc.plan_calibration("tool_changer", 10, n_candidates=1000), "n_candidates"),
    (lambda: tolalloc.plan_calibration("tool_changer", 10, n_candidates=100, for_allocation=True,
                                       random_plans=10_000), "random_plans"),
])
def test_jobs_check_their_other_counts_against_the_budget(one_second, call, argument):
    with pytest.raises(tolalloc.ArgumentError, match=r"would take about .* more than the time budget of a call, "
                                                     r"1 s; expected at most") as info:
        call()
    assert info.value.argument == argument


def test_the_command_line_refuses_by_the_flag(fixed_probe, capsys):
    from tolalloc.cli import main

    assert main(["mc", "tool_changer", "--n", "1e20"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --n-mc 1e+20 samples at 1 pose would take about ")  # --n is its alias
    assert main(["allocate", "tool_changer", "--coverage-n", "1e15", "--no-verify"]) == 2
    assert capsys.readouterr().err.startswith("error: --coverage-n 1e+15 coverage poses would take about ")


def test_a_registration_count_beyond_the_test_file_says_what_fits():
    from tolalloc.diagnose.register import register_count

    with pytest.raises(TolallocError, match=r"^register_n 1e\+15 asks for 1,000,000,000,000,000 registration poses, "
                                            r"but the 20 test poses leave at most \d+ after the \d+ scored ones; "
                                            r"expected a count from 5 to \d+ or a fraction below 1"):
        register_count(20, 1e15)


def test_the_estimators_refuse_counts_that_cannot_finish(fixed_probe):
    from tolalloc.errormodel import build_error_model
    from tolalloc.montecarlo.importance import importance_probability
    from tolalloc.montecarlo.paired import paired_counts

    model = build_error_model(tolalloc.load_robot("ur10"))
    q = model.robot.q_nominal
    with pytest.raises(tolalloc.ArgumentError, match=r"^n 1e\+20 samples at 1 pose would take about [\d,.e+]+ years"):
        paired_counts(model, q, 10**20, radii_mm=(0.25,))
    with pytest.raises(tolalloc.ArgumentError, match=r"\(.* s per sample at one pose \(importance sampling\) "):
        importance_probability(model, q, 10**20, radius_mm=0.25)
