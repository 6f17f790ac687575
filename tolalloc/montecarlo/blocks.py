"""Monte Carlo work units: parameter sampling and the statistics of one random-number block.

A block (:data:`BLOCK_SIZE` samples, its own generator ``SeedSequence(seed)`` child ``b``) is the unit
of reproducibility; it is processed in sub-blocks of :data:`SUB_BLOCK` samples (cache-sized) whose
statistics are merged in order. :func:`run_blocks` is the task that every scheduler runs
(:mod:`tolalloc.montecarlo.parallel`); :func:`tolalloc.montecarlo.run.run_mc` merges the results in block order.
With ``McSpec.engine == "numba"`` a block's normals are drawn by numba's port of the same generator and
its statistics come from the compiled kernel of :mod:`tolalloc.montecarlo.engines.numba_engine` (same draws, same block and
sub-block structure, same merge order; equal to the numpy path to rounding).
"""

from __future__ import annotations

import threading

import numpy as np

from tolalloc.engine import NUMBA_AVAILABLE
from tolalloc.montecarlo.engines import numba_engine as kernel_mod
from tolalloc.errormodel.sampling import draw_rows
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.features import N_BUF, ErrorFeatures, features_to_dict
from tolalloc.montecarlo.streaming import Extras, HistSpec, Moments

__all__ = ["BLOCK_SIZE", "SUB_BLOCK", "KernelSpec", "McSpec", "run_blocks"]

#: Samples per random-number block (the unit of reproducibility).
BLOCK_SIZE = 2**16
#: Samples per kinematics/statistics sub-block (cache-sized; part of the definition of the numbers).
SUB_BLOCK = 8192


# ----------------------------------------------------------------- block task
class KernelSpec:
    """A picklable task specification whose prepared kernel (chain programs per pose ...) is built once per
    process, on first use, under a lock (threads of one process share it); pickling leaves it out."""

    _kernel = None
    _lock = None

    def _build(self):  # pragma: no cover - every spec defines it
        raise NotImplementedError

    def __getstate__(self):
        return {k: v for k, v in self.__dict__.items() if k not in ("_kernel", "_lock")}

    def __setstate__(self, state):
        self.__dict__.update(state)

    def kernel(self):
        lock = self.__dict__.setdefault("_lock", threading.Lock())
        with lock:
            if self._kernel is None:
                self._kernel = self._build()
            return self._kernel

    def _chain_and_programs(self):
        """The fast chain and its program at every pose (multipliers of standard-normal rows)."""
        chain = FastChain(self.model)
        mult = draw_rows(self.model, 1, np.random.default_rng(0), np.empty((len(self.model.params), 1)))
        return chain, mult, [chain.program(qi, mult) for qi in self.q]


class McSpec(KernelSpec):
    """Everything a block needs (picklable; the prepared kernel is rebuilt once per process)."""

    def __init__(self, model, q, n, seed, radii, aradii, hist: HistSpec | None, keep: int, engine: str = "numpy"):
        self.model, self.q, self.n, self.seed = model, q, n, seed
        self.radii, self.aradii, self.hist, self.keep = radii, aradii, hist, keep
        self.engine = engine  # "numba" (tolalloc.kernel) or "numpy"; resolved by the caller
        self._lock = threading.Lock()

    def _build(self):
        chain, _, progs = self._chain_and_programs()
        feats = [ErrorFeatures(self.model.robot.fk_internal(qi)) for qi in self.q]
        compiled = None
        if self.engine == "numba" and NUMBA_AVAILABLE:  # a worker without numba: numpy
            compiled = kernel_mod.compile_programs(progs, feats, chain.home)
        return chain, progs, feats, compiled


_local = threading.local()


def _workspace(K: int) -> dict:
    ws = getattr(_local, "ws", None)
    if ws is None or ws["K"] != K or ws["tmp"].shape[1] != SUB_BLOCK:
        ws = {"K": K, "V": np.empty(K * BLOCK_SIZE), "X": np.empty(12 * SUB_BLOCK), "buf": np.empty((N_BUF, SUB_BLOCK)),
              "tmp": np.empty((2, SUB_BLOCK)), "cells": np.empty((3, BLOCK_SIZE), dtype=np.intp),
              "chain": FastChain.workspace(SUB_BLOCK)}
        _local.ws = ws
    return ws


def _block(spec: McSpec, b: int):
    """Statistics of block ``b``: per pose Moments and Extras, and kept samples of pose 0."""
    chain, progs, feats, compiled = spec.kernel()
    m = min(BLOCK_SIZE, spec.n - b * BLOCK_SIZE)
    ws = _workspace(len(spec.model.params))
    V = ws["V"][: len(spec.model.params) * m].reshape(-1, m)
    draw_rows(spec.model, m, np.random.default_rng(np.random.SeedSequence(spec.seed, spawn_key=(b,))), V,
              fill_normal=kernel_mod.fill_standard_normal if compiled is not None else None)
    keep = max(0, min(m, spec.keep - b * BLOCK_SIZE))
    if compiled is not None:
        out = kernel_mod.block_stats(compiled, V, SUB_BLOCK, spec.radii, spec.aradii, spec.hist, keep)
        if out is not None:  # None: a rotation error near pi, which the numpy path handles
            moms, exts, F = out
            kept = [features_to_dict(F)] if keep else []
            return (m, [Moments(*mo) for mo in moms],
                    [Extras(mx, mn, c, h) for mx, mn, c, h in exts], kept)
    moments, extras, kept = [], [], []
    for i, prog in enumerate(progs):
        mom, ext = Moments(), None
        for s0 in range(0, m, SUB_BLOCK):
            s1 = min(m, s0 + SUB_BLOCK)
            N = s1 - s0
            X = ws["X"][: 12 * N].reshape(3, 4, N)
            chain.run(prog, V[:, s0:s1], X, ws["chain"])
            F = feats[i].compute(X, ws["buf"], ws["tmp"])
            ang = ErrorFeatures.angle_row(ws["buf"], N)
            norm = F[6]
            cnt = np.array([np.count_nonzero(norm < r) for r in spec.radii]
                           + [np.count_nonzero(ang < r) for r in spec.aradii], dtype=np.int64)
            e = Extras(F.max(axis=1), F.min(axis=1), cnt)
            ext = e if ext is None else ext.merge(e)
            if spec.hist is not None:
                spec.hist.cell_index(F[0:3], i, ws["cells"][:, s0:s1], ws["tmp"][0])
            if i == 0 and s0 < keep:
                kept.append({k: v[: keep - s0] for k, v in features_to_dict(F).items()})
            mom.merge(Moments.of(F))
        if spec.hist is not None:
            ext.hist = spec.hist.count(ws["cells"][:, :m])
        moments.append(mom)
        extras.append(ext)
    return m, moments, extras, kept


def run_blocks(spec: McSpec, blocks: tuple[int, int]):
    """Blocks ``b0 <= b < b1``: per-block moments (merged later in block order), summed exact extras."""
    out_m, ext, kept, ns = [], None, [], []
    for b in range(*blocks):
        m, moments, extras, k = _block(spec, b)
        ns.append(m)
        out_m.append(moments)
        ext = extras if ext is None else [a.merge(x) for a, x in zip(ext, extras)]
        kept += k
    return ns, out_m, ext, kept
