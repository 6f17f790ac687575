"""Lost motion (backlash and hysteresis loss): a joint stops on one flank of its gear's play.

A joint with lost motion of full width ``b`` [rad or mm] sits at ``dq = s b / 2`` (output angle minus the
motor-side reading), ``s = +-1`` the flank it rests on (:func:`flank`). Which flank, by variant:

* ``approach``: against the direction of the joint's last motion before the pose (``dir1..dirN`` columns, +1 / -1),
  ``s = -dir`` -- the motor pushes the output from behind, so the output trails by ``b / 2``, and friction keeps
  it there;
* ``gravity``: the sign of the joint's gravity load, ``s = sign(tau)`` -- a loaded gear rests on the flank the
  load presses (a positive load turns the joint along +axis, :func:`~tolalloc.physics.loads.gravity_torques`);
* ``gravity_soft``: ``tanh(tau / (0.1 range))``: a preload that builds up with the load (hysteresis: the
  torque-torsion loop of a strain-wave gear);
* ``preload``: the gravity flank where ``|tau|`` exceeds :data:`PRELOAD_BAND` of its range, the approach flank
  inside that band (friction, not gravity, decides there);
* ``preload+hysteresis``: ``preload`` plus a hysteresis loss ``-h dir / 2`` that trails the motion whatever the
  load -- a strain-wave or cycloid gear's catalogue gives both, lost motion (the play the load takes up) and the
  hysteresis loss of its torque-torsion loop, which friction in the teeth and bearings leaves at every load.

The diagnosis fits ``b_j / 2`` (and ``h_j / 2``) per joint (:func:`lost_motion_basis`); the design samples the
flank (random by approach, or held by gravity) and the width from the reducer's catalogue figures.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.model import Robot

__all__ = ["SIDES", "FLANKS", "GRAVITY_SIDES", "DIRECTION_SIDES", "PRELOAD_BAND", "flank", "lost_motion_basis",
           "lost_motion_columns"]

SIDES = ("approach", "gravity", "gravity_soft", "preload", "preload+hysteresis")
#: The single flank rules of :func:`flank` (``preload+hysteresis`` joins two of them).
FLANKS = SIDES[:4]
#: Flank rules set by the gravity load alone.
GRAVITY_SIDES = ("gravity", "gravity_soft")
#: Flank rules that need the approach directions.
DIRECTION_SIDES = ("approach", "preload", "preload+hysteresis")
#: Dead band of the ``preload`` flank and width of ``gravity_soft``, as a fraction of the load's range.
PRELOAD_BAND = 0.1


def flank(tau: np.ndarray, direction: np.ndarray | None, variant: str) -> np.ndarray:
    """The flank ``s`` (P, n) each joint rests on (module docstring); ``tau`` (P, n) gravity loads, ``direction``
    (P, n) the approach directions (+1 / -1; needed by ``approach`` and ``preload``)."""
    if variant not in FLANKS:
        raise ValueError(f"unknown flank rule {variant!r}: expected one of {', '.join(FLANKS)}")
    # a load below 1e-9 of the largest on any joint is rounding (a vertical axis carries none): no flank from it
    tau = np.where(np.abs(tau) > 1e-9 * max(float(np.abs(tau).max(initial=0.0)), 1e-300), tau, 0.0)
    span = np.maximum(np.ptp(tau, axis=0, keepdims=True), 1e-300)
    if variant == "gravity":
        return np.sign(tau)
    if variant == "gravity_soft":
        return np.tanh(tau / (PRELOAD_BAND * span))
    if direction is None:
        raise ValueError(f"the {variant!r} flank needs the approach directions (dir1..dirN)")
    trailing = -np.asarray(direction, float)
    if variant == "preload":
        return np.where(np.abs(tau) > PRELOAD_BAND * span, np.sign(tau), trailing)
    return trailing


def lost_motion_basis(robot: Robot, tau: np.ndarray, direction: np.ndarray | None, variant: str) -> tuple:
    """Joint-offset basis ``A`` (P, n, M) and names of lost motion in ``variant`` (module docstring): the columns of
    :func:`lost_motion_columns` on the variant's flank, for ``preload+hysteresis`` followed by the trailing
    hysteresis loss (``h_<joint>``)."""
    if variant != "preload+hysteresis":
        return lost_motion_columns(robot, flank(tau, direction, variant))
    A, names = lost_motion_columns(robot, flank(tau, direction, "preload"))
    H, h_names = lost_motion_columns(robot, flank(tau, direction, "approach"), prefix="h")
    return np.concatenate([A, H], axis=-1), names + h_names


def lost_motion_columns(robot: Robot, side: np.ndarray, prefix: str = "b") -> tuple:
    """Joint-offset basis ``A`` (P, n, M) [per unit half-width] and names (``<prefix>_<joint> [unit]``): one column
    per joint whose flank changes between poses (a constant flank is a joint offset, which the geometric
    calibration takes)."""
    P, n = side.shape
    cols, names = [], []
    for j in range(n):
        if np.any(side[:, j] != side[0, j]):
            a = np.zeros((P, n))
            a[:, j] = side[:, j]
            cols.append(a)
            unit = "rad" if robot.joints[j].is_revolute else "mm"
            names.append(f"{prefix}_{robot.joints[j].name} [{unit}]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))), names
