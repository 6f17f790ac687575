"""The perturbed-chain program: one description of ``G_0 E_1 G_1 ... E_n G_n M`` for every consumer.

The chain program
-----------------
An :class:`~tolalloc.errormodel.model.ErrorModel` inserts small displacements ``G_s`` (exponentials of its
parameters' twists) between the joint exponentials ``E_j = exp([S_j](q_j + dq_j))`` of the nominal chain.
:func:`chain_program` writes that product down *once*, left to right, as a frozen :class:`ChainProgram` of
plain arrays (``F`` factors, ``K`` parameters)::

    kind  (F,)    ERROR (0): an error displacement; JOINT (1): a joint exponential
    twist (F, 6)  the factor's twist (omega, v) in the base frame at home (a parameter's twist, or S_j)
    joint (F,)    joint index of a JOINT factor, -1 for an ERROR factor
    site  (F,)    joints before the factor (0..n; a JOINT factor j has site j)
    coef  (F, K)  the factor's amount is  coef[f] @ values  (+ q[joint[f]] for a JOINT factor)
    home  (4, 4)  M

so the factor is ``exp([twist_f] (q_joint + coef_f . e))``. A parameter appears with coefficient +1 at its
insertion site and, for ``axes_only`` links and ``tilt`` deflections, with -1 at its undo site (undos first among a
site's insertions); a joint drive is a +1 in its joint's row. Every consumer reads these arrays and nothing else of
the parameters: the generic path :meth:`ErrorModel.perturbed_chain` (+ ``fk_poe``; numpy, or the same walk compiled
in :mod:`tolalloc.errormodel._chain_nb`; used by the calibration simulations and the diagnosis), the first-order
:meth:`ErrorModel.jacobian` (numpy, and the compiled kernel of :mod:`tolalloc.robot._jacobian_nb` through
:meth:`ChainProgram.param_entries`), the numpy Monte Carlo engine :class:`FastChain` and the numba engine (through
:class:`~tolalloc.errormodel.pose_program.PoseProgram`). A change to the error model's insertion rules is a change
to :func:`chain_program` and reaches all of them.

The pose program and the numpy engine
-------------------------------------
:meth:`FastChain.program` specialises the chain program to one pose ``q`` (and optional per-parameter multipliers,
e.g. sigma for standard-normal draws) as a :class:`~tolalloc.errormodel.pose_program.PoseProgram`
(:mod:`tolalloc.errormodel.pose_program`): the factors right to left with their constant amounts folded in,
identity factors dropped, and per factor ``fi = (type, n_coefs, a, b)``, coefficient indices/values ``fk, fcf`` and
the floats ``fd`` (layout in :class:`~tolalloc.errormodel.pose_program.PoseProgram`). The numpy evaluator
:meth:`FastChain.run` and the numba kernel (:mod:`tolalloc.montecarlo.engines`) both run these same arrays on a
structure-of-arrays ``(3, 4, N)`` block (rows of ``[R | p]``) with closed-form exponentials: a rotation about a
base axis mixes only the two rows it touches, a pure translation only adds to ``p``, ``p`` is shifted lazily to the
rotation axis' point. In :meth:`FastChain.run` ``cos`` is taken as ``sqrt(1 - sin^2)`` when every angle of the
block lies in ``[-1, 1]`` rad (exact to rounding, a third of the cost). Both equal the generic ``fk_poe`` path to
rounding (tested to 1e-9, ``tests/test_chain_program.py``).

This module holds the chain program (:class:`ChainProgram`, :func:`chain_program`) and the numpy engine
(:class:`FastChain`); the pose program's arrays are built in :mod:`tolalloc.errormodel.pose_program`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from tolalloc.errormodel.pose_program import PoseProgram, _pose_program
from tolalloc.exceptions import TolallocError
from tolalloc.robot.lie import hat

__all__ = ["ChainProgram", "chain_program", "FastChain", "ERROR", "JOINT"]

ERROR, JOINT = 0, 1


@dataclass(frozen=True, eq=False)
class ChainProgram:
    """The perturbed chain ``G_0 E_1 G_1 ... E_n G_n M`` as ``F`` factors, left to right (see the module doc).

    Attributes
    ----------
    kind : array of int, shape (F,)
        :data:`ERROR` or :data:`JOINT`.
    twist : array, shape (F, 6)
        Twist ``(omega, v)`` of the factor in the base frame at home [rad, mm].
    joint : array of int, shape (F,)
        Joint index of a JOINT factor, -1 otherwise.
    site : array of int, shape (F,)
        Joints before the factor, ``0..n``.
    coef : array, shape (F, K)
        Amount of factor ``f`` per unit of each parameter (added to ``q[joint[f]]`` for a JOINT factor).
    home : array, shape (4, 4)
        Home pose ``M`` [mm].
    """

    kind: np.ndarray
    twist: np.ndarray
    joint: np.ndarray
    site: np.ndarray
    coef: np.ndarray
    home: np.ndarray

    @property
    def n_factors(self) -> int:
        return len(self.kind)

    @cached_property
    def _sources(self) -> tuple:
        """Per factor, ``(k, coef)`` of its nonzero coefficients in parameter order (read once, used per call)."""
        return tuple(tuple((int(k), float(self.coef[f, k])) for k in np.flatnonzero(self.coef[f]))
                     for f in range(self.n_factors))

    def sources(self, f: int) -> list[tuple[int, float]]:
        """``(k, coef)`` of the parameters that move factor ``f``, in parameter order."""
        return list(self._sources[f])

    @cached_property
    def _padded_sources(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:attr:`_sources` as arrays ``(k, coef, used)`` of shape (F, L), L the most sources of any factor."""
        L = max((len(s) for s in self._sources), default=0)
        F = self.n_factors
        k, cf, used = np.zeros((F, L), int), np.zeros((F, L)), np.zeros((F, L), bool)
        for f, src in enumerate(self._sources):
            for i, (kk, c) in enumerate(src):
                k[f, i], cf[f, i], used[f, i] = kk, c, True
        return k, cf, used

    def amounts(self, values: np.ndarray) -> np.ndarray:
        """Parameter part of every factor's amount, ``values @ coef.T`` summed in parameter order, shape (N, F).

        ``values`` (N, K) [mm, rad]; the joint value of a JOINT factor is not included. One vectorised step per
        source position, each adding a factor's next source (in parameter order) to its running sum.
        """
        k, cf, used = self._padded_sources
        out = np.zeros((values.shape[0], self.n_factors))
        for i in range(k.shape[1]):
            term = values[:, k[:, i]]
            term = np.where(cf[:, i] == 1.0, term, cf[:, i] * term)
            out = np.where(used[:, i], out + term, out)
        return out

    @cached_property
    def kernel_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``kind, twist, joint, home`` as contiguous int64 / float arrays (the compiled walk's arguments), built
        once per program."""
        f = np.ascontiguousarray
        return (f(self.kind, dtype=np.int64), f(self.twist, dtype=float), f(self.joint, dtype=np.int64),
                f(self.home, dtype=float))

    def param_entries(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Factors of each parameter (CSR by parameter, factors left to right) for first-order consumers.

        Returns
        -------
        ptr : array of int, shape (K + 1,)
            Parameter ``k``'s entries are ``ptr[k]:ptr[k + 1]``.
        site : array of int, shape (E,)
        coef : array, shape (E,)
        twist : array, shape (E, 6)

        Built once per program (the Jacobian kernel reads them at every call); callers must not modify them.
        """
        return self._param_entries

    @cached_property
    def _param_entries(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        f, k = np.nonzero(self.coef.T)[::-1]  # sorted by parameter, then factor
        ptr = np.searchsorted(k, np.arange(self.coef.shape[1] + 1))
        return ptr, self.site[f], self.coef[f, k], np.ascontiguousarray(self.twist[f])

    def site_groups(self) -> list[tuple[int, list, float, np.ndarray]]:
        """``(site, parameter indices, coef, twists (6, k))`` of the entries with coefficient +1 first, then -1,
        then any other coefficient, each by increasing site (at most one entry per parameter and group).
        Built once per program (the first-order Jacobian reads it at every call); callers must not modify it."""
        return self._site_groups

    @cached_property
    def _site_groups(self) -> list[tuple[int, list, float, np.ndarray]]:
        ptr, site, coef, twist = self.param_entries()
        k_of = np.repeat(np.arange(len(ptr) - 1), np.diff(ptr))
        out = []
        for cf in [1.0, -1.0] + sorted(set(coef.tolist()) - {1.0, -1.0}, reverse=True):
            for s in sorted(set(site[coef == cf].tolist())):
                sel = np.flatnonzero((coef == cf) & (site == s))
                out.append((s, k_of[sel].tolist(), cf, np.ascontiguousarray(twist[sel].T)))
        return out


def chain_program(model) -> ChainProgram:
    """Build the :class:`ChainProgram` of an :class:`~tolalloc.errormodel.model.ErrorModel` (the one insertion table).

    Parameter ``k`` of kind ``joint_drive`` adds to joint ``joint_index``'s value; any other is the factor
    ``exp([twist_k] e_k)`` at ``site`` and, with an ``undo_site``, ``exp(-[twist_k] e_k)`` first at that site.
    """
    robot, params = model.robot, model.params
    n, K = robot.n_joints, len(params)
    drives = [[] for _ in range(n)]
    inserts = [[] for _ in range(n + 1)]  # per site: (k, sign) in order, undos first
    for k, p in enumerate(params):
        if p.kind == "joint_drive":
            drives[p.joint_index].append(k)
            continue
        inserts[p.site].append((k, 1.0))
        if p.undo_site is not None:
            inserts[p.undo_site].insert(0, (k, -1.0))
    kind, twist, joint, site, coef = [], [], [], [], []
    for s in range(n + 1):
        rows = [(ERROR, np.asarray(params[k].twist, float), -1, {k: sign}) for k, sign in inserts[s]]
        if s < n:
            rows.append((JOINT, np.asarray(robot.screws[s], float), s, {k: 1.0 for k in drives[s]}))
        for kd, tw, j, src in rows:
            row = np.zeros(K)
            for k, cf in src.items():
                row[k] += cf
            kind.append(kd), twist.append(tw), joint.append(j), site.append(s), coef.append(row)
    return ChainProgram(np.array(kind, np.int64), np.array(twist, float).reshape(-1, 6), np.array(joint, np.int64),
                        np.array(site, np.int64), np.array(coef, float).reshape(-1, K),
                        np.asarray(robot.home, float).copy())


def check_joint_values(model, q: np.ndarray, *, batch: bool = True) -> None:
    """Refuse joint values ``q`` [rad, mm] unless shaped (n,) (or (..., n) with ``batch``), n the robot's joints."""
    n = model.robot.n_joints
    if q.ndim == 0 or q.shape[-1] != n or (not batch and q.ndim != 1):
        raise TolallocError(f"q: expected shape ({n},)" + (f" or (..., {n})" if batch else "") + f", got shape "
                            f"{q.shape}; one value per joint of robot {model.robot.name!r}, in rad and mm")


def check_parameter_values(model, values: np.ndarray, *, transposed: bool = False) -> None:
    """Refuse parameter values unless shaped (N, K) (or (K, N) with ``transposed``), K the model's parameters."""
    K = len(model.params)
    if values.ndim != 2 or values.shape[0 if transposed else 1] != K:
        raise TolallocError("values: expected shape " + (f"({K}, N) with transposed=True" if transposed else
                                                         f"(N, {K})") + f", got shape {values.shape}; one "
                            "value per error parameter in model order (ErrorModel.names): draw them with "
                            "ErrorModel.sample(n, rng)")


class FastChain:
    """The numpy evaluator of an :class:`ErrorModel`'s :class:`ChainProgram`, vectorised over samples.

    Parameters
    ----------
    model : ErrorModel
    """

    def __init__(self, model):
        self.model = model
        cp = model.program
        self.K = cp.coef.shape[1]
        self.factors = [self._prepare(cp.twist[f], int(cp.joint[f]) if cp.kind[f] == JOINT else None, cp.sources(f))
                        for f in range(cp.n_factors)]
        self.home = cp.home

    @staticmethod
    def _prepare(twist, joint, sources):
        w, v = twist[:3], twist[3:]
        nw = float(np.linalg.norm(w))
        if nw < 1e-15:
            nv = float(np.linalg.norm(v))
            return {"kind": "trans", "v": v / nv if nv > 0 else v, "scale": nv, "joint": joint, "src": sources}
        w, v = w / nw, v / nw
        axis = None
        big = int(np.argmax(np.abs(w)))
        if abs(abs(w[big]) - 1.0) < 1e-15:  # base axis x, y or z (sign sg): rows (a, b) rotate
            axis = ((big + 1) % 3, (big + 2) % 3, 1.0 if w[big] > 0 else -1.0)
        return {"kind": "rot", "w": w, "r0": np.cross(w, v), "h": float(w @ v), "scale": nw,
                "A": hat(w), "joint": joint, "src": sources, "axis": axis}

    # ------------------------------------------------------------- programs
    def program(self, q: np.ndarray, mult: np.ndarray | None = None) -> PoseProgram:
        """The chain program at pose ``q``: factors right to left, amounts ``const + sum(coef_k V[k])``.

        ``mult`` (K,) scales the value rows (e.g. sigma for standard-normal rows); a source
        with ``mult == 0`` is dropped, an identity factor is skipped.
        """
        rows = []
        for f in reversed(self.factors):
            const = float(q[f["joint"]]) * f["scale"] if f["joint"] is not None else 0.0
            coefs = []
            for k, sign in f["src"]:
                m = 1.0 if mult is None else float(mult[k])
                if m != 0.0:
                    coefs.append((k, sign * f["scale"] * m))
            if not coefs and const == 0.0:
                continue
            rows.append((f, const, tuple(coefs)))
        return _pose_program(rows)

    @staticmethod
    def _amount(const, coefs, V, th):
        if len(coefs) == 1 and const == 0.0 and coefs[0][1] == 1.0:
            return V[coefs[0][0]]
        k, cf = coefs[0]
        np.multiply(V[k], cf, out=th)
        for k, cf in coefs[1:]:
            th += V[k] * cf
        if const != 0.0:
            th += const
        return th

    def run(self, prog: PoseProgram, V: np.ndarray, X: np.ndarray, work: dict) -> np.ndarray:
        """Evaluate a :meth:`program` on values ``V`` (K, N) into ``X`` (3, 4, N), in place.

        ``work`` holds scratch arrays ``t1, t2`` (4, N) and ``th, s, c`` (N,) (see :meth:`workspace`).
        """
        N = X.shape[2]
        for i in range(3):
            X[i] = self.home[i, :, None]
        th_buf, s, c = work["th"][:N], work["s"][:N], work["c"][:N]
        for typ, coefs, a, b, d in prog.steps:
            th = self._amount(d[0], coefs, V, th_buf) if coefs else d[0]
            if typ == 0:
                for i in range(3):
                    vi = d[9 + i]
                    if vi == 0.0:
                        continue
                    if vi == 1.0 or not coefs:
                        X[i, 3] += th if vi == 1.0 else th * vi
                    else:
                        np.multiply(th, vi, out=c)
                        X[i, 3] += c
                continue
            if coefs:
                np.sin(th, out=s)
                if th.max() <= 1.0 and th.min() >= -1.0:
                    np.multiply(s, s, out=c)
                    np.subtract(1.0, c, out=c)
                    np.sqrt(c, out=c)
                else:
                    np.cos(th, out=c)
                ss, cc = s, c
            else:
                ss, cc = d[12], d[13]
            if typ == 1:
                self._rotate_base(X, a, b, d, ss, cc, work["t1"][:, :N], work["t2"][:, :N])
            else:
                self._rotate_general(X, d, ss, cc)
            if d[8] != 0.0:
                for i in range(3):
                    if d[5 + i] != 0.0:
                        X[i, 3] += d[5 + i] * th
        for i in range(3):
            if prog.endoff[i] != 0.0:
                X[i, 3] += prog.endoff[i]
        return X

    @staticmethod
    def _rotate_base(X, a, b, d, ss, cc, t1, t2):
        """Rotation about base axis ``a x b`` (sign ``d[1]``): rows a, b mix; p first shifted by ``d[2 + r]``."""
        Xa, Xb = X[a], X[b]
        for r in (a, b):
            if d[2 + r] != 0.0:
                X[r, 3] += d[2 + r]
        np.multiply(Xa, ss, out=t1)
        np.multiply(Xb, ss, out=t2)
        Xa *= cc
        Xb *= cc
        if d[1] > 0:
            Xa -= t2
            Xb += t1
        else:
            Xa += t2
            Xb -= t1

    @staticmethod
    def _rotate_general(X, d, ss, cc):
        """General axis: ``R = I + s A + (1 - c) A^2`` applied to the rows, ``p`` about the axis point ``r0``."""
        A, B, r0 = d[14:23], d[23:32], d[9:12]
        Y = X.copy()
        for j in range(3):
            Y[j, 3] += d[2 + j]
        for i in range(3):
            row = None
            for j in range(3):
                cij = (1.0 if i == j else 0.0) + B[3 * i + j] + A[3 * i + j] * ss - B[3 * i + j] * cc
                term = Y[j] * cij
                row = term if row is None else row + term
            X[i] = row
            X[i, 3] += r0[i]

    @staticmethod
    def workspace(N: int) -> dict:
        """Scratch arrays for :meth:`run` on up to ``N`` samples."""
        return {"th": np.empty(N), "s": np.empty(N), "c": np.empty(N), "t1": np.empty((4, N)), "t2": np.empty((4, N))}

    def pose(self, q: np.ndarray, values: np.ndarray, *, transposed: bool = False) -> np.ndarray:
        """Perturbed tool poses as rows of ``[R | p]``.

        Parameters
        ----------
        q : array, shape (n,) [rad, mm]
        values : array, shape (N, K) [mm, rad], or (K, N) if ``transposed``

        Returns
        -------
        X : array, shape (3, 4, N); ``X[i, j, m]`` is ``T'[i, j]`` of sample ``m``.
        """
        q, values = np.asarray(q, float), np.asarray(values, float)
        check_joint_values(self.model, q, batch=False)
        check_parameter_values(self.model, values, transposed=transposed)
        V = values if transposed else np.ascontiguousarray(values.T)
        N = V.shape[1]
        X = np.empty((3, 4, N))
        return self.run(self.program(q), V, X, self.workspace(N))
