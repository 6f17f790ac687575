"""Memory is bounded on every path of the API as on the command line: a sample count of 1e12 is streamed (memory
does not grow with it) or refused by its argument with the memory it would need -- never a MemoryError."""

from __future__ import annotations

import signal
import threading
import tracemalloc

import numpy as np
import pytest

import tolalloc
from tolalloc.exceptions import Interrupted, clear_interrupt, memory_budget_bytes, note_interrupt

HUGE = 10**12


def test_a_streamed_sample_count_runs_in_bounded_memory(monkeypatch):
    """simulate_errors(n_mc=1e12) streams its samples: stopped after a moment (the CLI's interrupt checkpoint), it
    has held well under 300 MB -- a dense draw of 1e12 samples would need 10^5 GB."""
    monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", "inf")  # hours of work: the time budget would refuse it
    monkeypatch.setenv("TOLALLOC_ANNOUNCE_S", "inf")
    clear_interrupt()
    timer = threading.Timer(0.5, note_interrupt, [signal.SIGINT])
    tracemalloc.start()
    timer.start()
    try:
        with pytest.raises(Interrupted):
            tolalloc.simulate_errors("tool_changer", monte_carlo=tolalloc.MonteCarlo(n_mc=HUGE, keep_samples=0))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
        timer.cancel()
        clear_interrupt()
    assert peak < 300e6, peak


@pytest.mark.parametrize("call, argument", [
    (lambda: tolalloc.simulate_errors("tool_changer", monte_carlo=tolalloc.MonteCarlo(n_mc=HUGE, keep_samples=HUGE)),
     "MonteCarlo.keep_samples"),
    (lambda: tolalloc.simulate_errors("tool_changer", monte_carlo=tolalloc.MonteCarlo(n_mc=100, hist_bins=HUGE)),
     "MonteCarlo.hist_bins"),
    (lambda: tolalloc.simulate_errors("tool_changer", monte_carlo=tolalloc.MonteCarlo(n_mc=100, jobs=HUGE)),
     "MonteCarlo.jobs"),
    (lambda: tolalloc.plan_calibration("tool_changer", 10, n_candidates=HUGE), "n_candidates"),
    (lambda: tolalloc.plan_calibration("tool_changer", HUGE, n_candidates=2000), "n_poses"),
    (lambda: tolalloc.load_robot("tool_changer").random_q(np.random.default_rng(0), HUGE), "n"),
    (lambda: tolalloc.analyze_errors("tool_changer", sobol_n=HUGE), "sobol_n"),
    (lambda: tolalloc.allocate_tolerances("tool_changer", verification=tolalloc.Verification(correction_rounds=HUGE)),
     "Verification.correction_rounds"),
])
def test_counts_whose_arrays_cannot_be_streamed_are_refused_by_name(call, argument):
    with pytest.raises(tolalloc.ArgumentError) as info:
        call()
    assert info.value.argument == argument
    assert str(HUGE) in str(info.value) or "1e+12" in str(info.value)


def test_the_memory_refusal_says_how_much_and_what_fits():
    budget = memory_budget_bytes()
    with pytest.raises(tolalloc.ArgumentError, match=r"^n_candidates 1e\+12 candidate poses would hold about "
                                                     r"[\d.,]+ [TGM]iB in memory at once, more than the [\d.]+ [TGM]iB "
                                                     r"a call may use on this machine; expected at most [\d,]+ "):
        tolalloc.plan_calibration("tool_changer", 10, n_candidates=HUGE)
    largest = budget // 65536
    assert largest > 2000  # the default number of candidates fits on any machine this runs on
