"""Cross-validation folds of the effect selection: blocked in time and in joint space, random on request.

:func:`make_folds` partitions the poses (repeated measurements of one pose stay together); :func:`fold_count`
raises the requested count when the poses are few, so a held-out block never takes most of a fit's redundancy.
"""

from __future__ import annotations

import numpy as np

__all__ = ["CV_SCHEMES", "make_folds", "fold_count"]


CV_SCHEMES = ("blocked", "time", "joint", "random")


def make_folds(meas, k: int, scheme: str = "blocked", seed: int = 0) -> list:
    """Cross-validation folds (sorted index arrays partitioning the poses).

    ``time``: ``k`` contiguous blocks in row (time) order; ``joint``: ``k`` contiguous regions of joint space
    (k-means on the joint values scaled by their training range, seeded); ``random``: a random partition
    (only on request: neighbouring poses in time or joint space then sit on both sides of a split and flatter
    a model that interpolates). ``blocked`` is ``time`` here; :class:`_Context` adds the ``joint`` folds to it.
    Repeated measurements of one pose always fall in the same fold.
    """
    if scheme not in CV_SCHEMES:
        raise ValueError(f"cv: expected one of {', '.join(CV_SCHEMES)}, got {scheme!r}")
    groups = meas.pose_groups()
    G = int(groups.max()) + 1
    k = max(2, min(k, G))
    if scheme == "random":
        label = np.zeros(G, int)
        label[np.random.default_rng(seed).permutation(G)] = np.arange(G) % k
    elif scheme == "joint":
        first = np.unique(groups, return_index=True)[1]
        q = meas.q[first]
        z = (q - q.min(0)) / np.maximum(np.ptp(q, axis=0), 1e-12)
        label = _kmeans(z, k, seed)
    else:
        label = np.minimum(np.arange(G) * k // G, k - 1)  # groups are numbered in order of first appearance
    folds = [np.flatnonzero(label[groups] == i) for i in range(k)]
    return [f for f in folds if len(f)]


def fold_count(folds: int, n_rows: int, n_fixed: int) -> int:
    """Folds per CV scheme: at least ``folds``, more when the poses are few.

    A held-out block removes its rows from a fit that must still determine the registration, offset and
    geometric parameters (``n_fixed`` columns of ``n_rows`` rows). When a block takes more than half of the
    full training fit's redundancy ``n_rows - n_fixed``, every fold's fit is close to interpolating and the
    out-of-fold error measures its conditioning (it grows with every extra effect parameter) rather than
    the effect. So the blocks are made smaller: ``K`` is the smallest count >= ``folds`` with
    ``n_rows / K <= (n_rows - n_fixed) / 2`` (e.g. 22 UR10 poses, 66 rows, 27 fixed columns: 4 folds; at 90
    poses the requested 3 stand).
    """
    spare = max(n_rows - n_fixed, 1)
    return int(max(folds, np.ceil(2.0 * n_rows / spare)))


def _kmeans(z: np.ndarray, k: int, seed: int, iters: int = 30) -> np.ndarray:
    """Labels of a small seeded k-means (k-means++ start), shape (N,)."""
    rng = np.random.default_rng(seed)
    c = [z[rng.integers(len(z))]]
    for _ in range(1, k):
        d = np.min([np.sum((z - ci) ** 2, 1) for ci in c], axis=0)
        c.append(z[rng.choice(len(z), p=d / d.sum())] if d.sum() > 0 else z[rng.integers(len(z))])
    c = np.array(c)
    for _ in range(iters):
        lab = np.argmin(((z[:, None, :] - c[None]) ** 2).sum(-1), axis=1)
        c_new = np.array([z[lab == i].mean(0) if np.any(lab == i) else c[i] for i in range(k)])
        if np.allclose(c_new, c):
            break
        c = c_new
    return lab
