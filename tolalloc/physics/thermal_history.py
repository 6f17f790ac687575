"""The driving signals of thermal growth over a session, in time order: the logged air through a first-order lag
(:func:`lagged`), interval inputs through heating and cooling (:func:`lag_filter`), the robot's work and pauses
(:func:`active_time`, :func:`duty_warmup`), the joints' motion (:func:`activity`), the motors' losses
(:func:`motor_heat`) and heat exchanged with what the robot holds (:func:`held_heat`); and the check that a
``time_s`` column can drive them (:func:`time_problem`). :mod:`tolalloc.physics.thermal` turns them into growth."""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_SPAN_S", "MAX_STEP_S", "PAUSE_STEPS", "time_problem", "tau_s", "through_history", "lagged",
           "lag_filter", "active_time", "duty_warmup", "activity", "motor_heat", "held_heat"]

#: A session longer than this [s] (2 days) is taken for a ``time_s`` column in another unit (ms).
MAX_SPAN_S = 2 * 86400.0
#: A median step between consecutive poses above this [s] (10 min) is taken for another unit (ms).
MAX_STEP_S = 600.0
#: An interval longer than this many median intervals between poses holds a pause (the motors idle, the links cool).
PAUSE_STEPS = 5.0


def time_problem(time_s) -> str | None:
    """Why ``time_s`` (P,) cannot drive time-dependent effects, or None when it can."""
    if time_s is None:
        return "no time_s column"
    t = np.asarray(time_s, float)
    if len(t) < 2 or np.ptp(t) <= 0:
        return "time_s does not advance"
    step = np.diff(t)
    if np.any(step < 0):
        i = int(np.flatnonzero(step < 0)[0])
        return (f"time_s is not increasing within the session (pose {i + 2}: {t[i + 1]:g} s after {t[i]:g} s); "
                "expected one session per file with time stamps in measurement order")
    pos = step[step > 0]
    med = float(np.median(pos)) if len(pos) else 0.0
    if np.ptp(t) > MAX_SPAN_S or med > MAX_STEP_S:
        return (f"time_s looks like another unit than seconds (span {np.ptp(t):.4g}, median step {med:.4g} between "
                f"poses; expected at most {MAX_SPAN_S:g} s and {MAX_STEP_S:g} s): convert it to seconds (ms / 1000)")
    return None


def tau_s(variant: str) -> float:
    """The time constant [s] a variant name ends with (``lag_7.5min``, ``creep_90min``)."""
    return 60.0 * float(variant.rsplit("_", 1)[1][:-3])


def through_history(fn, time_s: np.ndarray, values: np.ndarray, history: tuple | None = None) -> np.ndarray:
    """``fn(times, values)`` of these poses run through after ``history`` ``(times (H,), values (H, ...))`` -- the
    training file's poses: what is known before a pose is measured -- in time order, on these poses. A history that
    is these very poses (the training file itself), or None: over these poses alone."""
    if history is None:
        return fn(time_s, values)
    ht, hv = history
    if len(ht) == len(time_s) and np.array_equal(ht, time_s) and np.array_equal(hv, values):
        return fn(time_s, values)
    return fn(np.concatenate([ht, time_s]), np.concatenate([hv, values]))[len(ht):]


def lagged(time_s: np.ndarray, temp_c: np.ndarray, tau_s: float) -> np.ndarray:
    """First-order lag of a signal (time order), ``dy/dt = (T - y) / tau``, started at ``T[0]``, shape (P,).

    Exact for a log that runs linearly between its samples: over a step ``dt`` with slope ``k = dT / dt`` the state
    follows ``T - k tau`` with the difference decaying, ``y_i = T_i - k tau + (y_(i-1) - T_(i-1) + k tau) e^(-dt/tau)``
    (holding each sample's value over the step before it would run ahead of the lag by about half a step)."""
    order = np.argsort(time_s, kind="stable")
    ts, Ts = time_s[order], temp_c[order]
    y = np.empty_like(Ts)
    y[0] = Ts[0]
    dt = np.diff(ts)
    e = np.exp(-dt / tau_s)
    with np.errstate(divide="ignore", invalid="ignore"):
        ktau = np.where(dt > 0, np.diff(Ts) / np.where(dt > 0, dt, 1.0) * tau_s, 0.0)
    for i in range(1, len(Ts)):
        y[i] = (Ts[i] - ktau[i - 1] + (y[i - 1] - Ts[i - 1] + ktau[i - 1]) * e[i - 1] if dt[i - 1] > 0
                else y[i - 1])
    out = np.empty_like(y)
    out[order] = y
    return out


def lag_filter(time_s: np.ndarray, inputs: np.ndarray, tau_s: float, on_s: np.ndarray | None = None) -> np.ndarray:
    """First-order lag (heating and cooling) of interval inputs, shape (P, m): ``inputs[i]`` (P, m) acts over the
    interval before pose ``i`` (time order; the first pose's is ignored), the state starts at 0 (a cold robot).
    ``on_s`` (P,) [s]: how long of each interval the input acts (in time order, the rest of the interval cools; default
    the whole interval)."""
    order = np.argsort(time_s, kind="stable")
    ts, u = time_s[order], np.asarray(inputs, float)[order]
    dt = np.diff(ts)
    on = dt if on_s is None else np.minimum(np.asarray(on_s, float)[order][1:], dt)
    a, cool = 1.0 - np.exp(-on / tau_s), np.exp(-(dt - on) / tau_s)
    y = np.zeros_like(u)
    for i in range(1, len(ts)):
        y[i] = (y[i - 1] + a[i - 1] * (u[i] - y[i - 1])) * cool[i - 1]
    out = np.empty_like(y)
    out[order] = y
    return out


def active_time(time_s: np.ndarray) -> np.ndarray:
    """How long the robot works in the interval before each pose [s], shape (P,): the interval, at most
    :data:`PAUSE_STEPS` median intervals -- a longer gap is a pause (motors idle, the links cool) after that."""
    order = np.argsort(time_s, kind="stable")
    dt = np.diff(time_s[order])
    med = float(np.median(dt[dt > 0])) if np.any(dt > 0) else 0.0
    on = np.zeros(len(time_s))
    on[order[1:]] = np.minimum(dt, PAUSE_STEPS * med)
    return on


def duty_warmup(time_s: np.ndarray, tau_s: float) -> np.ndarray:
    """Warm-up of a heat source that is on while the robot works and off in its pauses (:func:`active_time`), shape
    (P,): 0 at the first pose (a cold start), 1 - exp(-t / tau) over uninterrupted work, decaying by exp(-t / tau)
    over a pause."""
    return lag_filter(time_s, np.ones((len(time_s), 1)), tau_s, on_s=active_time(time_s))[:, 0]


def _moves(time_s: np.ndarray, q: np.ndarray) -> tuple:
    """``(|q_i - q_(i-1)|`` (P, n), ``t_i - t_(i-1)`` (P,)): the move and the interval before each pose in time
    order (0 for the first), in the order of the poses."""
    order = np.argsort(time_s, kind="stable")
    step, dt = np.zeros(q.shape), np.zeros(len(time_s))
    step[order[1:]] = np.abs(np.diff(q[order], axis=0))
    dt[order[1:]] = np.diff(time_s[order])
    return step, dt


def _speed(time_s: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Joint speed over the interval before each pose in time order (0 for the first), shape (P, n)."""
    step, dt = _moves(time_s, q)
    return step / np.maximum(dt, 1e-9)[:, None]


def activity(time_s: np.ndarray, q: np.ndarray, tau_s: float) -> np.ndarray:
    """Lagged joint activity, shape (P, n): joint speed over the interval before each pose (time order; 0 for the
    first), through a first-order lag of time constant ``tau_s`` started at 0 (a cold robot)."""
    return lag_filter(time_s, _speed(time_s, q), tau_s)


def motor_heat(time_s: np.ndarray, q: np.ndarray, load: np.ndarray, tau_s: float) -> np.ndarray:
    """Lagged motor losses per joint, shape (P, 2n): the speed of the move (friction losses) and the squared load
    held over the interval before each pose (copper losses; the load of the previous pose in time order), each
    acting while the robot works (:func:`active_time`: a long gap is a pause that cools) through the first-order lag
    of time constant ``tau_s``."""
    on = active_time(time_s)
    held = _previous(time_s, load) ** 2
    speed = _moves(time_s, q)[0] / np.maximum(on, 1e-9)[:, None]  # the move over the time the robot works
    return lag_filter(time_s, np.concatenate([speed, held], axis=1), tau_s, on_s=on)


def held_heat(time_s: np.ndarray, payload_kg: np.ndarray, tau_s: float) -> np.ndarray:
    """Lagged heat of a held payload, shape (P,): the payload of the previous pose in time order held over the interval
    before each pose (0 before the first), through the first-order lag of time constant ``tau_s`` started at 0 [kg]."""
    return lag_filter(time_s, _previous(time_s, payload_kg)[:, None], tau_s)[:, 0]


def _previous(time_s: np.ndarray, values: np.ndarray) -> np.ndarray:
    """``values`` (P, ...) of the previous pose in time order, at each pose (0 at the first): what was held over the
    interval before it."""
    order = np.argsort(time_s, kind="stable")
    out = np.zeros(np.shape(values), dtype=float)
    out[order[1:]] = np.asarray(values, float)[order[:-1]]
    return out
