"""Blocks of a session: runs of poses in time order between which something is set anew (a tool changed, the drives
powered up and homed), with one offset per block.

:func:`runs` cuts the poses in time order where a key changes (the logged payload: a tool change) or where the time
between two poses exceeds a gap (a pause: a power cycle). :func:`place` puts another file's poses into the training
file's blocks by time (``-1`` where a pose's block holds no training pose). :func:`contrasts` writes a per-block offset
as departures from the mean over the poses, so the calibrated constant is the mean and a pose in a block no fit has seen
is predicted at the mean. :func:`block_problem` says why a training file's blocks cannot carry an offset each. Used by
:mod:`.seating` (tool seats) and :mod:`.rehoming` (joint zeros homed anew).
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_BLOCKS", "MIN_BLOCK_POSES", "runs", "place", "contrasts", "pose_contrasts", "block_problem"]

#: At most this many blocks in the training poses: more are a quantity that varies pose by pose, not a setting that
#: holds for a block.
MAX_BLOCKS = 8
#: Every training block needs this many poses to fix its offsets.
MIN_BLOCK_POSES = 6


def runs(time_s: np.ndarray, key: np.ndarray, gap_s: float = np.inf) -> np.ndarray:
    """Run index of every pose, shape (P,): the poses in time order, a new run where ``key`` (P,) changes or where
    the time since the previous pose exceeds ``gap_s``."""
    order = np.argsort(time_s, kind="stable")
    k, t = np.asarray(key, float)[order], np.asarray(time_s, float)[order]
    cut = (np.abs(np.diff(k)) > 1e-9) | (np.diff(t) > gap_s)
    out = np.empty(len(k), dtype=int)
    out[order] = np.concatenate([[0], np.cumsum(cut)])
    return out


def place(time_s: np.ndarray, key: np.ndarray, train_time_s: np.ndarray, train_key: np.ndarray,
          gap_s: float = np.inf) -> np.ndarray:
    """Training block of every pose, shape (P,) int, -1 where its block holds no training pose.

    The poses are placed among the training poses in time order (a test file's poses between two training poses of
    one block share it); the training file itself passes its own poses twice."""
    t, k = np.asarray(time_s, float), np.asarray(key, float)
    ht, hk = np.asarray(train_time_s, float), np.asarray(train_key, float)
    if len(ht) == len(t) and np.array_equal(ht, t) and np.array_equal(hk, k):
        return runs(t, k, gap_s)
    merged = runs(np.concatenate([ht, t]), np.concatenate([hk, k]), gap_s)
    # a run of the merged poses holding training poses lies within one training block (a change between two training
    # blocks is still a change once other poses come between them)
    index = dict(zip(merged[:len(ht)].tolist(), runs(ht, hk, gap_s).tolist()))
    return np.array([index.get(int(r), -1) for r in merged[len(ht):]], dtype=int)


def contrasts(counts: np.ndarray) -> np.ndarray:
    """Contrasts of ``B`` blocks, shape (B, B - 1): columns orthogonal to the blocks' pose counts ``counts`` (B,)
    (``counts @ C = 0``) and orthonormal in their weight, scaled by the square root of the poses in all.

    An offset per block written as ``c + C d`` leaves the constant ``c`` the mean over the poses, so a pose in a block
    the fit has not seen is predicted at the mean, not at some reference block's."""
    n = np.asarray(counts, float)
    root = np.sqrt(n)
    Q, _ = np.linalg.qr(np.column_stack([root, np.eye(len(n))]))
    return np.sqrt(n.sum()) * Q[:, 1:len(n)] / root[:, None]


def pose_contrasts(blocks: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Every pose's row of :func:`contrasts`, shape (P, K - 1): ``blocks`` (P,) from :func:`place`, ``counts`` (K,) the
    training poses per block; a pose in no training block (-1) gets zeros (the mean)."""
    C = contrasts(counts)
    w = np.zeros((len(blocks), C.shape[1]))
    seen = blocks >= 0
    w[seen] = C[blocks[seen]]
    return w


def block_problem(block: np.ndarray, what: str) -> str | None:
    """Why the training poses' blocks (P,) cannot carry an offset each (None when they can); ``what`` names a block's
    boundary ("tool change", "power cycle")."""
    n = int(block.max()) + 1
    if n < 2:
        return f"no {what} in the training poses"
    if n > MAX_BLOCKS:
        return f"{n - 1} {what}s in the training poses (at most {MAX_BLOCKS - 1})"
    short = int(np.bincount(block).min())
    if short < MIN_BLOCK_POSES:
        return f"a block has {short} poses (at least {MIN_BLOCK_POSES} between {what}s)"
    return None
