"""Tool seating: what the flange carries re-seats within its coupling's clearance each time it is changed.

A tool changer or quick-change coupling locates the tool on pins in bushes with a clearance fit (ISO 286: a 6 mm
pin in H7/g6 leaves 4-24 um, worn bushes more; the coupling's face and its clamping balls settle within their own
play). At every change the tool comes to rest at a new place within that clearance: a small translation and turn of
the tool against the flange, which at the target is a constant displacement in the flange frame for as long as the
tool stays on::

    dx_i = R_i d_b          R_i the flange's orientation at pose i, d_b the offset of block b [mm]

(a turn ``theta`` of the tool moves a target at ``r`` from the coupling by ``theta x r``, also constant in the
flange frame). The same holds for a gripped part measured on the part: it seats anew at each pick. The changes are
read from the logged payload (:func:`seat_blocks`): a change of ``payload_kg`` between consecutive poses in time
order starts a block. The payload must carry the tool's own mass, so it never drops to zero: a payload that does is
a gripper picking and releasing parts (its blocks are held parts, not seats), and no block is formed
(:func:`seat_problem`). The geometric calibration's tool offset is the mean seat; the blocks' departures from it are
``B - 1`` contrasts of three columns each (:func:`~.blocks.contrasts`, :func:`seat_columns`). A pose in a block with no
training pose (a tool put on again after the training poses) cannot be predicted beyond the mean seat: its columns
are zero. Sources: Slocum, *Precision Machine Design* (1992), ch. 7 (kinematic and clearance couplings,
repeatability of re-seating); ISO 9409-1 (flange and coupling locating pins).
"""

from __future__ import annotations

import numpy as np

from tolalloc.physics.blocks import block_problem, place, pose_contrasts, runs
from tolalloc.physics.thermal_history import time_problem
from tolalloc.robot.model import Robot

__all__ = ["seat_blocks", "seat_columns", "seat_problem"]


def seat_problem(time_s, payload_kg) -> str | None:
    """Why the training poses cannot carry a re-seat per block (None when they can)."""
    if time_s is None or payload_kg is None:
        return "needs time_s and payload_kg (the tool changes are read from the payload in time order)"
    why = time_problem(np.asarray(time_s, float))
    if why is not None:
        return why
    if np.min(payload_kg) <= 0:
        return ("the payload drops to zero: an empty gripper between picks, not a tool change (a tool's mass stays "
                "in the payload)")
    if np.ptp(payload_kg) == 0:
        return "the payload never changes"
    return block_problem(runs(np.asarray(time_s, float), payload_kg), "tool change")


def seat_blocks(time_s: np.ndarray, payload_kg: np.ndarray, train_time_s: np.ndarray,
                train_payload_kg: np.ndarray) -> np.ndarray:
    """Training block of every pose, shape (P,) int, -1 where its block holds no training pose: the runs of the
    payload in time order (:func:`~.blocks.place`)."""
    return place(time_s, payload_kg, train_time_s, train_payload_kg)


def seat_columns(robot: Robot, q: np.ndarray, blocks: np.ndarray, counts: np.ndarray) -> tuple:
    """Target displacement per mm of each seat contrast, ``(B (P, 3, 3 (K - 1)), names)``, ``K = len(counts)``.

    ``blocks`` (P,) from :func:`seat_blocks`, ``counts`` (K,) the training poses per block: the seat of block ``b``
    is the calibrated tool offset (the mean seat) plus ``C[b] @ d`` on the flange (:func:`~.blocks.contrasts`); poses in
    no training block (-1) get no column (the mean seat)."""
    q = np.atleast_2d(q)
    w = pose_contrasts(blocks, counts)
    R = robot.fk_internal(q)[:, :3, :3]  # (P, 3, 3): the flange's axes, what an offset on the flange turns by
    B = np.einsum("pia,pk->pika", R, w).reshape(len(q), 3, -1)
    names = tuple(f"seat_{ax}_contrast{k + 1} [mm]" for k in range(w.shape[1]) for ax in "xyz")
    return B, names
