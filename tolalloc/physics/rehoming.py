"""Joint zeros homed anew at each power-up: incremental encoders (and the resolvers of older drives) know their zero
only after a homing run onto a reference switch or cam, which repeats to a few micrometres of the switch's travel --
arc-seconds of the joint's turn, hundredths of a millimetre of a linear axis -- so each power cycle sets every
homed joint's zero a little differently::

    dq_j,i = z_j,b(i)        the zero of joint j in the power cycle b of pose i [rad or mm]

Power cycles are read from ``time_s``: a pause longer than :data:`~.thermal_history.PAUSE_STEPS` median intervals
between two poses in time order may be a power-down (:func:`cycle_blocks`; a pause without one only costs the fit
columns the evidence does not want). The calibrated joint offsets are the mean zeros; each cycle departs from them by
contrasts (:func:`~.blocks.contrasts`), one prior scale per joint (a homing's spread differs between axes). A test
pose in a cycle with no training pose (the robot powered up again after the training poses) cannot be predicted
beyond the mean zeros. Absolute encoders keep their zero through a power cycle, and most arms have them: only the joints
whose encoder the robot file's components declare ``homing = "incremental"`` get columns (:func:`homed_joints`), as
a drift between the pauses of any other kind (heat, a settling base) is also constant-ish per block and would
otherwise be read as re-homing. Sources: IEC 60947-5-2 (repeatability of proximity switches); drive makers'
homing functions (reference-point approach: cam, switch edge, zero mark); Mooring, Roth & Driels, *Fundamentals of
Manipulator Calibration* (1991), ch. 2 (joint zero offsets).
"""

from __future__ import annotations

import numpy as np

from tolalloc.physics.blocks import block_problem, place, pose_contrasts, runs
from tolalloc.physics.thermal_history import PAUSE_STEPS, time_problem

__all__ = ["homed_joints", "cycle_gap_s", "cycle_blocks", "rehome_problem", "rehome_columns"]


def homed_joints(robot) -> np.ndarray:
    """Indices of the joints whose encoder is homed at each power-up (``homing = "incremental"`` in the robot file's
    components), shape (k,)."""
    return robot.components.encoder_joints([jt.name for jt in robot.joints], lambda enc: enc.homing == "incremental")


def cycle_gap_s(train_time_s: np.ndarray) -> float:
    """The pause that may be a power cycle [s]: :data:`~.thermal_history.PAUSE_STEPS` median intervals of the training
    poses in time order."""
    dt = np.diff(np.sort(np.asarray(train_time_s, float)))
    return PAUSE_STEPS * float(np.median(dt[dt > 0])) if np.any(dt > 0) else np.inf


def cycle_blocks(time_s: np.ndarray, train_time_s: np.ndarray) -> np.ndarray:
    """Training power cycle of every pose, shape (P,) int, -1 where its cycle holds no training pose
    (:func:`~.blocks.place`, the training file's pause)."""
    t = np.asarray(time_s, float)
    ht = np.asarray(train_time_s, float)
    return place(t, np.zeros(len(t)), ht, np.zeros(len(ht)), cycle_gap_s(ht))


def rehome_problem(time_s, robot=None) -> str | None:
    """Why the training poses cannot carry a zero per power cycle (None when they can); ``robot``: the joints must
    include one homed at power-up (:func:`homed_joints`)."""
    if robot is not None and not len(homed_joints(robot)):
        return "no joint's encoder is homed at power-up (the robot file's components declare no homing = incremental)"
    if time_s is None:
        return "needs time_s (the power cycles are read from the pauses)"
    t = np.asarray(time_s, float)
    why = time_problem(t)
    if why is not None:
        return why
    return block_problem(runs(t, np.zeros(len(t)), cycle_gap_s(t)), "power cycle")


def rehome_columns(Jp: np.ndarray, blocks: np.ndarray, counts: np.ndarray, joint_names, units) -> tuple:
    """Target displacement per unit departure of each joint's zero, ``(B (P, 3, n (K - 1)), names, groups)``.

    ``Jp`` (P, 3, n): the point Jacobian's columns of the homed joints at the target; ``blocks`` (P,) from
    :func:`cycle_blocks`; ``counts`` (K,) the training poses per cycle; ``joint_names``, ``units`` (n,) the joints'
    names and "rad" or "mm". The zero of joint ``j`` in cycle ``b`` is its calibrated offset plus ``C[b] @ z_j``
    (:func:`~.blocks.contrasts`); ``groups`` (n (K - 1),): the joint of each column (one prior scale per joint)."""
    w = pose_contrasts(blocks, counts)
    n = Jp.shape[2]
    B = np.einsum("pin,pk->pink", Jp, w).reshape(len(blocks), 3, -1)
    names = tuple(f"rehome_{joint_names[j]}_contrast{k + 1} [{units[j]}]" for j in range(n) for k in range(w.shape[1]))
    groups = np.repeat(np.arange(n), w.shape[1])
    return B, names, groups
