"""Creep of a compliant mount: a support that keeps giving under the moment it holds, so the base's tilt follows the
history of the robot's poses, not only the pose it stands in.

An elastic mount (:func:`~.compliance.mount_columns`) tilts by ``c M_h`` at once. Many supports are viscoelastic or
viscous: elastomer pads and grout relax towards a larger steady tilt (a standard linear solid: Findley, Lai & Onaran,
*Creep and Relaxation of Nonlinear Viscoelastic Materials*, 1976, ch. 5), asphalt, soft soil and fresh concrete
flow without a bound while loaded (a Maxwell or Burgers body: Read & Whiteoak, *The Shell Bitumen Handbook*, 2003,
ch. 8). Two variants of the mount family, both needing ``time_s``:

* ``creep_<tau>min``: ``omega = c M_h + c_d y``, ``dy/dt = (M_h - y) / tau``: an instant compliance and a delayed one
  reached with the time constant ``tau`` (:data:`CREEP_MIN`). What the robot held before the session is not known;
  ``y`` starts at the mean moment of the training poses (a robot that worked the same cell before), not at the first
  pose's: a start at one pose would add a transient that depends on that pose alone and reads as a drift with time;
* ``flow``: ``omega = c M_h + f int M_h dt``: the tilt grows as long as a moment is held, about the axis of the
  moment's running integral. A support sinking evenly under the weight moves the robot along the vertical only in
  proportion to time -- any slow drift does that -- so it has no column here.

The moment is held at both poses of an interval (:func:`dwell_times`): half of the working time before a pose at the
previous pose and half at the new one, and a pause (longer than
:data:`~.thermal_history.PAUSE_STEPS` median intervals) at the previous pose. Both are linear in their compliances.
Over a held-out file the history runs through the training poses and then these, in time order (:func:`creep_signal`).
"""

from __future__ import annotations

import numpy as np

from tolalloc.physics.thermal_history import active_time, tau_s, through_history, time_problem

__all__ = ["CREEP_MIN", "CREEP_KINDS", "creep_variants", "is_creep_variant", "dwell_times", "creep_signal",
           "creep_columns"]

#: Time constants [min] of the delayed compliance the ``creep`` variants try.
CREEP_MIN = (10.0, 30.0, 90.0, 270.0)
#: Variant prefixes of a mount whose tilt depends on the history of its load.
CREEP_KINDS = ("creep", "flow")


def creep_variants(time_s) -> tuple:
    """The creep variants a file with these times can carry: none without a usable ``time_s``."""
    if time_problem(time_s) is not None:
        return ()
    return tuple(f"creep_{m:g}min" for m in CREEP_MIN) + ("flow",)


def is_creep_variant(variant: str) -> bool:
    """Whether a mount variant depends on the history of the load (needs ``time_s``)."""
    return variant.startswith(CREEP_KINDS)


def dwell_times(time_s: np.ndarray) -> tuple:
    """How long the robot stands at the previous pose and at the new one in the interval before each pose [s], each
    shape (P,) in the order of the poses (0 for the first in time): half the working time each (:func:`active_time`),
    and the rest of a pause at the previous pose."""
    on = active_time(time_s)
    order = np.argsort(time_s, kind="stable")
    dt = np.zeros(len(time_s))
    dt[order[1:]] = np.diff(time_s[order])
    return dt - 0.5 * on, 0.5 * on


def _held(time_s: np.ndarray, values: np.ndarray, tau: float | None, start: np.ndarray) -> np.ndarray:
    """Time integral [unit h] (``tau`` None) or first-order lag (time constant ``tau`` [s], starting at ``start``
    (m,)) of ``values`` (P, m) over the poses in time order."""
    order = np.argsort(time_s, kind="stable")
    prev, new = (d[order] for d in dwell_times(time_s))
    u = np.asarray(values, float)[order]
    if tau is None:
        step = np.zeros_like(u)
        step[1:] = (prev[1:, None] * u[:-1] + new[1:, None] * u[1:]) / 3600.0
        y = np.cumsum(step, axis=0)
    else:
        y = np.repeat(np.reshape(start, (1, -1)), len(u), axis=0)
        for i in range(1, len(u)):
            a, b = np.exp(-prev[i] / tau), np.exp(-new[i] / tau)
            y[i] = (y[i - 1] * a + (1.0 - a) * u[i - 1]) * b + (1.0 - b) * u[i]
    out = np.empty_like(y)
    out[order] = y
    return out


def creep_signal(time_s: np.ndarray, load: np.ndarray, variant: str, history: tuple | None = None) -> np.ndarray:
    """The held load of ``variant`` at each pose, shape of ``load`` (P, m): its lag (``creep_<tau>min``, started at
    the mean load of the training poses) or time integral [unit h] (``flow``). ``history`` ``(times (H,), loads
    (H, m))``: the training file's poses, run through with these in time order
    (:func:`~.thermal_history.through_history`); None: these poses are the training file."""
    tau = None if variant == "flow" else tau_s(variant)
    start = np.mean(load if history is None else history[1], axis=0)
    return through_history(lambda ts, vs: _held(ts, vs, tau, start), time_s, load, history)


def creep_columns(Mh: np.ndarray, held: np.ndarray, p: np.ndarray, variant: str) -> tuple:
    """Target-displacement basis of a creeping mount, ``B`` (P, 3, 2), and names.

    ``Mh`` (P, 3) the horizontal moment on the mount [N m] (:func:`~.compliance.mount_moment`); ``held`` (P, 3) its
    :func:`creep_signal` [N m, or N m h for ``flow``]; ``p`` (P, 3) the target points [mm]."""
    B = np.stack([np.cross(Mh, p), np.cross(held, p)], axis=-1)
    if variant == "flow":
        return B, ["c_mount [rad/(N m)]", "f_mount [rad/(N m h)]"]
    return B, ["c_mount [rad/(N m)]", "c_creep [rad/(N m)]"]
