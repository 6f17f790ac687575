"""The pose program: a chain program at one pose, as the flat arrays both Monte Carlo engines run.

:meth:`FastChain.program <tolalloc.errormodel.chain.FastChain.program>` specialises the model's
:class:`~tolalloc.errormodel.chain.ChainProgram` to one pose ``q``: the factors right to left with their constant
amounts folded in, identity factors dropped. :func:`_pose_program` flattens those factors into a
:class:`PoseProgram` (per factor ``fi = (type, n_coefs, a, b)``, coefficient indices/values ``fk, fcf`` and
:data:`FD` floats ``fd``), which the numpy evaluator :meth:`FastChain.run <tolalloc.errormodel.chain.FastChain.run>`
and the numba kernel (:mod:`tolalloc.montecarlo.engines`) both execute.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["PoseProgram", "FD"]

#: Floats per factor in :attr:`PoseProgram.fd`.
FD = 32


@dataclass(frozen=True, eq=False)
class PoseProgram:
    """A :class:`ChainProgram` at one pose, right to left, as the arrays both Monte Carlo engines run.

    Attributes
    ----------
    fi : array of int, shape (F', 4)
        ``(type, n_coefs, a, b)``: type 0 translation, 1 rotation about a base axis mixing rows ``a, b``,
        2 general rotation.
    fk, fcf : array of int / float, shape (F', C)
        Parameter indices and coefficients of the amount ``const + sum_j fcf[f, j] V[fk[f, j]]``.
    fd : array, shape (F', FD)
        ``[const, sign of the base axis, shift of p (3), h*w (3), has_h, v or r0 (3), sin/cos of const (2),
        A (9), A^2 (9)]`` (``A = [w]``; ``shift`` is the lazy move of ``p`` to the axis point before the factor).
    endoff : array, shape (3,)
        Lazy shift of ``p`` left after the last factor.
    """

    fi: np.ndarray
    fk: np.ndarray
    fcf: np.ndarray
    fd: np.ndarray
    endoff: np.ndarray

    def __len__(self) -> int:
        return len(self.fi)

    @cached_property
    def steps(self) -> list:
        """Per factor ``(type, coefs ((k, cf), ...), a, b, fd as floats)`` for the numpy evaluator."""
        out = []
        for (typ, ncf, a, b), ks, cfs, d in zip(self.fi.tolist(), self.fk.tolist(), self.fcf.tolist(), self.fd.tolist()):
            out.append((typ, tuple(zip(ks[:ncf], cfs[:ncf])), a, b, d))
        return out


def _pose_program(rows: list) -> PoseProgram:
    """Flatten ``(prepared factor, const, coefs)`` rows (right to left) into a :class:`PoseProgram`."""
    nf = len(rows)
    nc = max([1] + [len(c) for _, _, c in rows])
    fi = np.zeros((nf, 4), np.int64)
    fk = np.zeros((nf, nc), np.int64)
    fcf = np.zeros((nf, nc))
    fd = np.zeros((nf, FD))
    off = [0.0, 0.0, 0.0]
    for i, (f, const, coefs) in enumerate(rows):
        d = fd[i]
        d[0] = const
        for j, (k, cf) in enumerate(coefs):
            fk[i, j], fcf[i, j] = k, cf
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
                for r in range(3):
                    d[2 + r] = off[r] - r0[r]
                    off[r] = 0.0
                d[9:12] = r0
                d[14:23], d[23:32] = f["A"].ravel(), (f["A"] @ f["A"]).ravel()
        fi[i] = (typ, len(coefs), a, b)
    return PoseProgram(fi, fk, fcf, fd, np.array(off))
