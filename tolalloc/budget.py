"""Upfront budgets of every count a call is given: the time (and memory) it would take, said before the work starts.

A count (Monte Carlo samples, coverage poses, calibration candidates, random plans, Sobol' samples ...) is checked
by :func:`check_count` before any of its work runs:

* refused, with an :class:`~tolalloc.exceptions.ArgumentError` naming the argument, when its estimated time exceeds
  the time budget of a call (:func:`time_budget_s`: 24 h, or ``TOLALLOC_TIME_BUDGET_S`` seconds) or its memory the
  memory budget (:func:`~tolalloc.exceptions.check_memory`); the message gives the estimate and the largest count
  that fits;
* announced, by a :class:`LongRunWarning` (one ``warning:`` line of the command line, before the work starts), when
  the estimate is above :func:`announce_s` seconds (a minute, or ``TOLALLOC_ANNOUNCE_S``);
* let through silently otherwise.

Throughput figures
------------------
Each kind of work has a stated cost per unit (:data:`WORK`) in *probe units*: the time one unit takes over the
time of a fixed numpy workload (:func:`probe_seconds`, a short calibration run of 10 to 20 ms, timed once per
process, best of three). The estimate on this machine is that ratio times the probe's time here, so it follows the
machine's speed and its current load. The ratios were measured by ``benchmarks/bench_budget.py``, which also prints,
for every kind, the measured time beside the estimate. Estimates are good to a factor of about 2: enough to refuse a
count that could not finish in a day, or to say a run takes minutes rather than hours.
"""

from __future__ import annotations

import math
import os
import time
import warnings
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from tolalloc.exceptions import ArgumentError, TolallocError, check_memory, describe

__all__ = ["Work", "WORK", "Estimate", "LongRunWarning", "check_count", "estimate_seconds", "time_budget_s",
           "announce_s", "probe_seconds", "duration_text", "chain_scale", "DEFAULT_TIME_BUDGET_S", "TIME_BUDGET_ENV",
           "ANNOUNCE_S", "ANNOUNCE_ENV"]

#: Time budget of one call [s] (a day), unless ``TOLALLOC_TIME_BUDGET_S`` says otherwise.
DEFAULT_TIME_BUDGET_S = 86_400.0
#: Estimates above this many seconds are announced (:class:`LongRunWarning`) before the work starts, unless
#: ``TOLALLOC_ANNOUNCE_S`` says otherwise.
ANNOUNCE_S = 60.0
#: Environment variables of the time budget of a call and of the announcement threshold [s] (``inf``: none).
TIME_BUDGET_ENV, ANNOUNCE_ENV = "TOLALLOC_TIME_BUDGET_S", "TOLALLOC_ANNOUNCE_S"


class LongRunWarning(UserWarning):
    """A call is estimated to run longer than :data:`ANNOUNCE_S`; said before its work starts."""


@dataclass(frozen=True)
class Work:
    """The cost of one unit of a kind of work.

    Attributes
    ----------
    unit : str
        What one unit is, for messages (``"sample at one pose"``).
    probe_units : float
        Time of one unit over the time of the probe workload (:func:`probe_seconds`), one thread.
    parallel : bool
        The work spreads over the call's threads.
    fixed_probe_units : float
        Time of a call that does not grow with the count (set-up, solves), in probe units.
    """

    unit: str
    probe_units: float
    parallel: bool = True
    fixed_probe_units: float = 0.0


#: Stated costs in probe units, measured by ``benchmarks/bench_budget.py`` on the development machine (the probe
#: took 10 to 20 ms there: a sample at one pose, plain, about 0.2 to 0.3 us) with the tool_changer's error model (22
#: parameters, 6 joints; chain work scales with :func:`chain_scale`). ``random_plan`` is per evaluation pose.
WORK = {
    "mc": Work("sample at one pose (plain Monte Carlo)", 1.7e-5),
    "paired": Work("sample at one pose (paired Monte Carlo)", 4.5e-5),
    "importance": Work("sample at one pose (importance sampling)", 9.0e-5),
    "sobol": Work("chain evaluation (Sobol' indices)", 4.0e-5, parallel=False),
    "coverage": Work("coverage pose (linear probability)", 1.2e-3, parallel=False),
    "candidate": Work("candidate pose of a calibration design", 0.8, parallel=False, fixed_probe_units=140.0),
    "random_plan": Work("random plan at one evaluation pose", 0.035, parallel=False),
}

#: chain factors (parameters + joints) of the model the stated costs were measured on
_REFERENCE_FACTORS = 28.0


def chain_scale(n_params: int, n_joints: int) -> float:
    """Cost of one chain evaluation relative to the tool_changer model's (22 parameters, 6 joints)."""
    return max(0.25, (int(n_params) + int(n_joints)) / _REFERENCE_FACTORS)


def _probe_workload(A: np.ndarray, B: np.ndarray) -> float:
    """The fixed workload: batched 4 x 4 products and transcendental functions, as a kinematic chain does."""
    total = 0.0
    for _ in range(40):
        C = np.einsum("ijn,jkn->ikn", A, B)
        A = np.tanh(C)
        total += float(A[0, 0, 0])
    return total


@lru_cache(maxsize=1)
def probe_seconds() -> float:
    """Time of the probe workload on this machine now [s]: the best of three runs (timed once per process)."""
    rng = np.random.default_rng(0)
    A, B = rng.standard_normal((4, 4, 4096)), rng.standard_normal((4, 4, 4096))
    best = math.inf
    for _ in range(3):
        t = time.perf_counter()
        _probe_workload(A, B)
        best = min(best, time.perf_counter() - t)
    return max(best, 1e-4)


def time_budget_s() -> float:
    """The time budget of a call [s]: ``TOLALLOC_TIME_BUDGET_S`` if set (a number > 0), else a day."""
    return _seconds_from_env(TIME_BUDGET_ENV, DEFAULT_TIME_BUDGET_S, "the time budget of a call", "86400 for a day")


def announce_s() -> float:
    """Estimates above this many seconds are announced: ``TOLALLOC_ANNOUNCE_S`` if set (a number > 0, ``inf``: never),
    else a minute."""
    return _seconds_from_env(ANNOUNCE_ENV, ANNOUNCE_S, "the run time above which a call says its estimate",
                             "60, or inf for never")


def _seconds_from_env(name: str, default: float, what: str, example: str) -> float:
    text = os.environ.get(name, "").strip()
    if not text:
        return default
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (value > 0 and not math.isnan(value)):
        raise TolallocError(f"{name}: expected {what} in seconds, a number > 0 (e.g. {example}), got {text!r}; fix or "
                            "unset the environment variable.")
    return value


def duration_text(seconds: float) -> str:
    """``"40 s"``, ``"3.2 min"``, ``"5.1 h"``, ``"12 days"``, ``"2.4e+05 years"``."""
    s = float(seconds)
    if s < 60:
        return f"{s:.2g} s" if s < 10 else f"{s:.0f} s"
    for unit, size, below in (("min", 60.0, 3600.0), ("h", 3600.0, 2 * 86400.0), ("days", 86400.0, 365.25 * 86400)):
        if s < below:
            v = s / size
            return f"{v:.2g} {unit}" if v < 10 else f"{v:.0f} {unit}"
    v = s / (365.25 * 86400)
    return f"{v:.2g} years" if v < 10 or v >= 1e6 else f"{v:,.0f} years"


def _kinds(kind) -> dict:
    """``{kind: units per count}`` from a key of :data:`WORK` or such a mapping."""
    kinds = {kind: 1.0} if isinstance(kind, str) else dict(kind)
    unknown = [k for k in kinds if k not in WORK]
    if unknown or not kinds:
        raise TolallocError(f"kind: expected keys of tolalloc.budget.WORK ({', '.join(WORK)}), got {kind!r}.")
    return kinds


def estimate_seconds(count: float, kind, *, per_count: float = 1.0, scale: float = 1.0, threads: int = 1,
                     fixed_s: float = 0.0) -> float:
    """Estimated time [s] of ``count`` x ``per_count`` units of work ``kind`` on this machine, with the work's fixed
    part. ``kind``: a key of :data:`WORK`, or a mapping of keys to units per count (work of several kinds per counted
    item); ``scale``: the cost of a unit relative to the stated one; ``threads``: for parallel work; ``fixed_s``: more
    time that does not grow with the count."""
    each, fixed = _per_count_and_fixed(_kinds(kind), per_count, scale, threads, fixed_s)
    return float(count) * each + fixed


def _per_count_and_fixed(kinds: dict, per_count: float, scale: float, threads: int, fixed_s: float) -> tuple:
    """Seconds per counted item and seconds of the fixed part, on this machine."""
    probe = probe_seconds()
    each = sum(WORK[k].probe_units * u / (max(1, int(threads)) if WORK[k].parallel else 1) for k, u in kinds.items())
    fixed = sum(WORK[k].fixed_probe_units for k in kinds) * probe + float(fixed_s)
    return each * probe * float(scale) * float(per_count), fixed


@dataclass(frozen=True)
class Estimate:
    """The estimate of one count: ``seconds`` (all of its work), with the words of its messages."""

    argument: str
    count: int
    what: str
    seconds: float
    seconds_each: float
    threads: int
    unit: str
    note: str = ""

    def text(self) -> str:
        """``n = 1,000,000,000 samples at 1 pose: about 2.5 min on 2 threads (1.6e-07 s per sample at one pose (plain
        Monte Carlo) estimated for this machine)``, with the note."""
        on = f" on {self.threads} threads" if self.threads > 1 else ""
        note = f"; {self.note}" if self.note else ""
        return (f"{self.argument} = {self.count:,} {self.what}: about {duration_text(self.seconds)}{on}{note} "
                f"({self.seconds_each:.2g} s per {self.unit} estimated for this machine)")


def check_count(count, argument: str, what: str, kind, *, per_count: float = 1.0, scale: float = 1.0,
                threads: int = 1, fixed_s: float = 0.0, bytes_each: float = 0.0, example: str = "",
                announce: bool = True, remedy: str = "", note: str = "") -> Estimate:
    """Refuse a count that cannot finish within the budget; announce a long one; return its :class:`Estimate`.

    Parameters
    ----------
    count : int
        The count as the caller checked it (a whole number >= 0).
    argument : str
        Its keyword argument (the command line shows the flag).
    what : str
        What is counted, for messages (``"samples at 12 poses"``).
    kind : str or dict
        Key of :data:`WORK`, or a mapping of keys to units per count (see :func:`estimate_seconds`); the first
        names the unit in messages.
    per_count, scale, threads, fixed_s
        See :func:`estimate_seconds`.
    bytes_each : float
        Memory one counted item holds at once (0: streamed); checked by :func:`~tolalloc.exceptions.check_memory`.
    example : str
        A count that would work, for the message.
    remedy : str
        Another way out, appended to the refusal (``"or switch the verification off"``).
    note : str
        More about the estimate, for the announcement (``"per verification; ..."``).
    """
    if not isinstance(count, (int, np.integer)) or isinstance(count, bool):
        raise ArgumentError(argument, f"expected a whole number, got {describe(count)}.")
    count = int(count)
    if bytes_each:
        check_memory(count, bytes_each, argument, what, example or "1000")
    kinds = _kinds(kind)
    work = WORK[next(iter(kinds))]
    threads = max(1, int(threads)) if any(WORK[k].parallel for k in kinds) else 1
    each, fixed = _per_count_and_fixed(kinds, per_count, scale, threads, fixed_s)
    seconds = count * each + fixed
    unit_s = work.probe_units * probe_seconds() * float(scale)
    est = Estimate(argument, count, what, seconds, unit_s, threads, work.unit, note)
    budget = time_budget_s()
    if seconds > budget:
        largest = max(0, int((budget - fixed) // max(each, 1e-300)))
        on = f" on {threads} threads" if threads > 1 else ""
        why = f"{unit_s:.2g} s per {work.unit} estimated for this machine" + (f"; {note}" if note else "")
        raise ArgumentError(argument, f"{count:g} {what} would take about {duration_text(seconds)}{on} ({why}), more "
                            f"than the time budget of a call, {duration_text(budget)}; expected at most {largest:,}"
                            + (f" (e.g. {example})" if example else "") + f", or raise the budget with "
                            f"{TIME_BUDGET_ENV} (seconds){', ' + remedy if remedy else ''}.")
    if announce and seconds > announce_s():
        warnings.warn(f"{est.text()}; interrupt (Ctrl-C) to stop it, nothing is written.", LongRunWarning,
                      stacklevel=3)
    return est
