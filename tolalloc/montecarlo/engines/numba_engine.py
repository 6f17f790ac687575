"""Optional compiled Monte Carlo kernel (numba): perturbed chains, error features and statistics in one pass.

:func:`block_stats` evaluates the *same* parameter draws as the numpy path of :mod:`tolalloc.montecarlo.blocks`
(same random stream, same blocks and sub-blocks, sub-block statistics merged in the same order) with a
fused, vectorised loop: per sub-block of :data:`~tolalloc.montecarlo.blocks.SUB_BLOCK` samples and per pose, the
chain :class:`~tolalloc.errormodel.chain.FastChain` program runs on L1-sized chunks, the features of
:class:`~tolalloc.errormodel.chain.ErrorFeatures` are written to a buffer, and the buffer's moments (two-pass),
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

from tolalloc.engine import NUMBA_AVAILABLE
from tolalloc.exceptions import TolallocError
from tolalloc.robot.lie import euler_xyz_fixed

__all__ = ["compile_programs", "block_stats", "fill_standard_normal"]

FD = 41  # floats per factor, see compile_programs
_jit = None


def compile_programs(progs: list, feats: list, home: np.ndarray) -> tuple:
    """Flatten :meth:`FastChain.program` lists (one per pose) and :class:`ErrorFeatures` into arrays.

    Returns ``(fi, fk, fcf, fd, endoff, pose_c, home)``: per pose ``p`` and factor ``f`` (right to left)
    ``fi[p, f] = (type, n_coefs, a, b)`` (type 0 translation, 1 rotation about a base axis mixing rows
    ``a, b``, 2 general rotation, -1 none), coefficient indices/values ``fk, fcf``, and ``fd[p, f]`` =
    ``[const, sg, shift(3), h*w(3), has_h, v or r0(3), sin/cos of const(2), A(9), B(9), C of const(9)]``;
    ``endoff (P, 3)`` is the final lazy shift of ``p``; ``pose_c (P, 20)`` holds the feature constants.
    """
    P = len(progs)
    nf = max(1, max(len(p) for p in progs))
    nc = max([1] + [len(c) for p in progs for _, _, c in p])
    fi = np.full((P, nf, 4), -1, np.int64)
    fk = np.zeros((P, nf, nc), np.int64)
    fcf = np.zeros((P, nf, nc))
    fd = np.zeros((P, nf, FD))
    endoff = np.zeros((P, 3))
    for p, prog in enumerate(progs):
        off = [0.0, 0.0, 0.0]
        for i, (f, const, coefs) in enumerate(prog):
            d = fd[p, i]
            d[0] = const
            for j, (k, cf) in enumerate(coefs):
                fk[p, i, j], fcf[p, i, j] = k, cf
            a = b = 0
            if f["kind"] == "trans":
                typ = 0
                d[9:12] = f["v"]
            else:
                d[12], d[13] = np.sin(const), np.cos(const)
                if f["h"] != 0.0:
                    d[8] = 1.0
                    d[5:8] = [(f["h"] * f["w"][r]) if f["w"][r] != 0.0 else 0.0 for r in range(3)]
                r0 = f["r0"]
                if f["axis"] is not None:
                    typ = 1
                    a, b, d[1] = f["axis"]
                    for r in (a, b):
                        if off[r] != r0[r]:
                            d[2 + r] = off[r] - r0[r]
                            off[r] = r0[r]
                else:
                    typ = 2
                    A = f["A"]
                    B = A @ A
                    for r in range(3):
                        d[2 + r] = off[r] - r0[r]
                        off[r] = 0.0
                    d[9:12] = r0
                    d[14:23], d[23:32] = A.ravel(), B.ravel()
                    C = [[(1.0 if r == j else 0.0) + B[r, j] + A[r, j] * d[12] - B[r, j] * d[13] for j in range(3)]
                         for r in range(3)]
                    d[32:41] = np.ravel(C)
            fi[p, i] = (typ, len(coefs), a, b)
        endoff[p] = off
    pose_c = np.zeros((P, 20))
    for p, fe in enumerate(feats):
        a0, _, g0 = euler_xyz_fixed(fe.R0)
        pose_c[p, :3] = fe.p0
        pose_c[p, 3], pose_c[p, 4] = fe.r0**2, fe.r0
        pose_c[p, 5:14] = fe.R0.ravel()
        pose_c[p, 14:19] = (np.cos(a0), np.sin(a0), np.cos(g0), np.sin(g0), fe.b0)
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
    ok = _kernel()(V, sub, fi, fk, fcf, fd, endoff, pose_c, home, radii, aradii, lo, inv_w, nb, keep,
                   mean, M2, mx, mn, cnt, H, kept)
    if not ok:
        return None
    m = V.shape[1]
    hs = [None] * P if nb < 0 else [H[p].reshape(3, nb + 2, nb + 2) for p in range(P)]
    return ([(m, mean[p], M2[p]) for p in range(P)], [(mx[p], mn[p], cnt[p], hs[p]) for p in range(P)], kept)


def fill_standard_normal(rng: np.random.Generator, out: np.ndarray) -> None:
    """Fill ``out`` (rows, m), C-contiguous, like ``rng.standard_normal(out=out)`` (same numbers), compiled."""
    _kernel()
    _jit[1](rng, out)


def _kernel():
    global _jit
    if _jit is None:
        from tolalloc.montecarlo.engines._kernel_nb import block_kernel, fill_standard_normal as fill

        _jit = (block_kernel, fill)
    return _jit[0]
