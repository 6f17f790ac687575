"""Optional compiled Monte Carlo kernel (numba): perturbed chains, error features and statistics in one pass.

:func:`block_stats` evaluates the *same* parameter draws as the numpy path of :mod:`tolalloc.montecarlo.blocks`
(same random stream, same blocks and sub-blocks, sub-block statistics merged in the same order) with a
fused, vectorised loop: per sub-block of :data:`~tolalloc.montecarlo.blocks.SUB_BLOCK` samples and per pose, the
chain's :class:`~tolalloc.errormodel.pose_program.PoseProgram` (the arrays :class:`~tolalloc.errormodel.chain.FastChain`
runs, built from the model's one :class:`~tolalloc.errormodel.chain.ChainProgram`) runs on L1-sized chunks, the
features of :class:`~tolalloc.errormodel.features.ErrorFeatures` are written to a buffer, and the buffer's moments (two-pass),
extrema, threshold counts and histogram cells are accumulated. ``sin``/``cos``/``atan2`` are inlined
polynomial kernels (fdlibm's sine/cosine kernels, Cephes' arctangent; about 1 ulp) instead of libm, so the
numbers equal the numpy path's to rounding (moments to ~1e-13 relative, extrema to a few ulps; counts and
histogram counts equal unless a sample lies within rounding of a threshold).

The normal draws of a block go through numba's port of numpy's ziggurat on the same PCG64 bit generator
(:func:`fill_standard_normal`: the same numbers in the same order, about twice as fast here), so the random
stream, the blocks and the reproducibility rules of :mod:`tolalloc.montecarlo.run` are unchanged.

numba is a core dependency; without it (a broken install), or with ``TOLALLOC_NUMBA=0`` or
``engine="numpy"``, everything runs on the numpy path. Compiled code is cached on disk (``cache=True``).
"""

from __future__ import annotations

import numpy as np

from tolalloc.errormodel.pose_program import FD

__all__ = ["compile_programs", "block_stats", "fill_standard_normal"]

_nb = None  # the compiled kernels' module, imported at the first use


def compile_programs(progs: list, feats: list, home: np.ndarray) -> tuple:
    """Stack the :class:`~tolalloc.errormodel.pose_program.PoseProgram` arrays (one per pose) and the
    :meth:`ErrorFeatures.constants <tolalloc.errormodel.features.ErrorFeatures.constants>` into the kernel's arrays.

    Returns ``(fi, fk, fcf, fd, endoff, pose_c, home)``: per pose ``p`` the pose program's ``fi, fk, fcf, fd``
    padded to the longest program (``fi[p, f, 0] = -1`` ends a shorter one), ``endoff (P, 3)``, the feature
    constants ``pose_c (P, 20)`` and the rows ``[R | p]`` of ``home`` (3, 4).
    """
    P = len(progs)
    nf = max(1, max(len(p) for p in progs))
    nc = max(p.fk.shape[1] for p in progs)
    fi = np.full((P, nf, 4), -1, np.int64)
    fk = np.zeros((P, nf, nc), np.int64)
    fcf = np.zeros((P, nf, nc))
    fd = np.zeros((P, nf, FD))
    endoff = np.zeros((P, 3))
    for p, prog in enumerate(progs):
        F, C = prog.fk.shape
        fi[p, :F], fk[p, :F, :C], fcf[p, :F, :C], fd[p, :F] = prog.fi, prog.fk, prog.fcf, prog.fd
        endoff[p] = prog.endoff
    pose_c = np.array([fe.constants() for fe in feats]).reshape(P, 20)
    return fi, fk, fcf, fd, endoff, pose_c, np.ascontiguousarray(np.asarray(home, float)[:3])


def block_stats(compiled: tuple, V: np.ndarray, sub: int, radii, aradii, hist, keep: int):
    """Statistics of one block of draws ``V`` (K, m) at every pose (see :func:`tolalloc.montecarlo.blocks._block`).

    Returns ``None`` when a sample's rotation error is near pi (the caller falls back to numpy), else
    ``(moments, extras, kept)`` with per pose ``(n, mean (11,), M2 (11, 11))`` and
    ``(max (11,), min (11,), counts (R,), hist (3, b+2, b+2) or None)``, and the features (11, keep) of
    pose 0's first ``keep`` samples.
    """
    fi, fk, fcf, fd, endoff, pose_c, home = compiled
    P = fi.shape[0]
    radii = np.asarray(radii, float)
    aradii = np.asarray(aradii, float)
    if hist is not None:
        lo, inv_w, nb = np.asarray(hist.lo_mm, float), 1.0 / np.asarray(hist.width_mm, float), hist.bins
        H = np.zeros((P, 3, (nb + 2) ** 2), np.int64)
    else:
        lo, inv_w, nb, H = np.zeros((P, 3)), np.ones((P, 3)), -1, np.zeros((P, 3, 1), np.int64)
    mean = np.zeros((P, 11))
    M2 = np.zeros((P, 11, 11))
    mx = np.empty((P, 11))
    mn = np.empty((P, 11))
    cnt = np.zeros((P, len(radii) + len(aradii)), np.int64)
    kept = np.empty((11, keep))
    ok = _call("block_kernel", V, sub, fi, fk, fcf, fd, endoff, pose_c, home, radii, aradii, lo, inv_w, nb, keep,
               mean, M2, mx, mn, cnt, H, kept)
    if not ok:
        return None
    m = V.shape[1]
    hs = [None] * P if nb < 0 else [H[p].reshape(3, nb + 2, nb + 2) for p in range(P)]
    return ([(m, mean[p], M2[p]) for p in range(P)], [(mx[p], mn[p], cnt[p], hs[p]) for p in range(P)], kept)


def fill_standard_normal(rng: np.random.Generator, out: np.ndarray) -> None:
    """Fill ``out`` (rows, m), C-contiguous, like ``rng.standard_normal(out=out)`` (same numbers), compiled."""
    _call("fill_standard_normal", rng, out)


#: The kernels this process has called once.
_READY: set = set()


def _call(name: str, *args):
    """Call the kernel ``name`` of :mod:`._kernel_nb`; its first call in a process (the compilation, or the load of the
    disk cache) runs under :func:`~tolalloc.engine.first_compile`, so processes that start together on an empty cache
    compile once."""
    global _nb
    if _nb is None:
        from tolalloc.montecarlo.engines import _kernel_nb as _nb
    if name in _READY:
        return getattr(_nb, name)(*args)
    from tolalloc.engine import first_compile

    with first_compile(_nb.__file__):
        out = getattr(_nb, name)(*args)
    _READY.add(name)
    return out
