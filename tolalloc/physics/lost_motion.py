"""Lost motion (backlash and hysteresis loss): a joint stops on one flank of its gear's play.

A joint with lost motion of full width ``b`` [rad or mm] sits at ``dq = s b / 2``, ``s = +-1`` the flank it rests on
(:func:`flank`). Which flank, by variant:

* ``approach``: the direction of the joint's last motion before the pose (``dir1..dirN`` columns, +1 / -1) -- the
  play is taken up in the direction of travel and friction keeps it there;
* ``gravity``: the sign of the joint's gravity load -- a loaded gear rests on the flank the load presses;
* ``gravity_soft``: ``tanh(tau / (0.1 range))``: a preload that builds up with the load (hysteresis: the
  torque-torsion loop of a strain-wave gear);
* ``preload``: the gravity flank where ``|tau|`` exceeds :data:`PRELOAD_BAND` of its range, the approach flank
  inside that band (friction, not gravity, decides there).

The diagnosis fits ``b_j / 2`` per joint (:func:`lost_motion_columns`); the design samples the flank (random by
approach, or held by gravity) and the width from the reducer's catalogue figures.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.model import Robot

__all__ = ["SIDES", "GRAVITY_SIDES", "PRELOAD_BAND", "flank", "lost_motion_columns"]

SIDES = ("approach", "gravity", "gravity_soft", "preload")
#: Flank rules set by the gravity load alone.
GRAVITY_SIDES = ("gravity", "gravity_soft")
#: Dead band of the ``preload`` flank and width of ``gravity_soft``, as a fraction of the load's range.
PRELOAD_BAND = 0.1


def flank(tau: np.ndarray, direction: np.ndarray | None, variant: str) -> np.ndarray:
    """The flank ``s`` (P, n) each joint rests on (module docstring); ``tau`` (P, n) gravity loads, ``direction``
    (P, n) the approach directions (+1 / -1; needed by ``approach`` and ``preload``)."""
    scale = np.abs(tau).max(0, keepdims=True)
    span = np.maximum(np.ptp(tau, axis=0, keepdims=True), 1e-12)
    if variant == "gravity":
        return np.where(np.abs(tau) > 1e-6 * scale, np.sign(tau), 0.0)
    if variant == "gravity_soft":
        return np.tanh(tau / (PRELOAD_BAND * span))
    if direction is None:
        raise ValueError(f"the {variant!r} flank needs the approach directions (dir1..dirN)")
    if variant == "preload":
        return np.where(np.abs(tau) > PRELOAD_BAND * span, np.sign(tau), direction)
    return np.asarray(direction, float)


def lost_motion_columns(robot: Robot, side: np.ndarray) -> tuple:
    """Joint-offset basis ``A`` (P, n, M) [per unit half-width] and names: one column per joint whose flank changes
    between poses (a constant flank is a joint offset, which the geometric calibration takes)."""
    P, n = side.shape
    cols, names = [], []
    for j in range(n):
        if np.any(side[:, j] != side[0, j]):
            a = np.zeros((P, n))
            a[:, j] = side[:, j]
            cols.append(a)
            unit = "rad" if robot.joints[j].is_revolute else "mm"
            names.append(f"b_{robot.joints[j].name} [{unit}]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))), names
