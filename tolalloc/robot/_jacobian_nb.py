"""numba kernels of the Jacobian stacks (imported only when the compiled engine is used).

For ``P`` poses of one chain whose screws have a unit (revolute) or zero (prismatic) angular part, one pass
per pose computes the prefix products ``P_j = exp([S_1] q_1) ... exp([S_j] q_j)`` (the closed form of
:func:`tolalloc.robot.kinematics._joint_exp_rp`, same operations) and from them

* :func:`space_jacobian` -- the columns ``Ad_{P_{j-1}} S_j`` of :func:`tolalloc.robot.kinematics.space_jacobian`;
* :func:`error_jacobian` -- the rows ``dp = V_v - p_tool x V_w``, ``dw = V_w`` of
  :meth:`tolalloc.errormodel.model.ErrorModel.jacobian`, with ``V_k = sum_e coef_e Ad_{P_site(e)} xi_e`` over the
  parameter's entries in the chain program (plain arrays: +1 at its site, -1 at an undo site) and
  ``p_tool = R_n home_p + p_n``.

The numpy functions stay the reference: the results equal theirs to rounding (tested to 1e-12 relative).
Compiled code is cached on disk (``cache=True``); the first call in a fresh environment compiles (~1-2 s).
"""

import math

import numpy as np
from numba import njit

__all__ = ["space_jacobian", "error_jacobian"]


@njit(nogil=True, cache=True, error_model="numpy")
def _prefix(S, q, R, p):
    """Prefix products of one pose: ``R`` (n + 1, 3, 3), ``p`` (n + 1, 3) [mm] for screws S (n, 6), q (n,)."""
    for a in range(3):
        p[0, a] = 0.0
        for b in range(3):
            R[0, a, b] = 1.0 if a == b else 0.0
    E = np.empty((3, 3))
    e = np.empty(3)
    for j in range(S.shape[0]):
        w0, w1, w2, v0, v1, v2 = S[j, 0], S[j, 1], S[j, 2], S[j, 3], S[j, 4], S[j, 5]
        ww = w0 * w0 + w1 * w1 + w2 * w2
        nw = math.sqrt(ww)
        th = q[j] * nw
        s, c = math.sin(th), math.cos(th)
        b = 1.0 - c
        d = 1.0 - b * nw * nw  # c I + s [w] + b w w^T (I for w = 0), as lie._rodrigues
        E[0, 0], E[0, 1], E[0, 2] = b * w0 * w0 + d, b * w0 * w1 - s * w2, b * w0 * w2 + s * w1
        E[1, 0], E[1, 1], E[1, 2] = b * w1 * w0 + s * w2, b * w1 * w1 + d, b * w1 * w2 - s * w0
        E[2, 0], E[2, 1], E[2, 2] = b * w2 * w0 - s * w1, b * w2 * w1 + s * w0, b * w2 * w2 + d
        u0, u1, u2 = w1 * v2 - w2 * v1, w2 * v0 - w0 * v2, w0 * v1 - w1 * v0  # w x v
        x0, x1, x2 = w1 * u2 - w2 * u1, w2 * u0 - w0 * u2, w0 * u1 - w1 * u0  # w x (w x v)
        wvq = (w0 * v0 + w1 * v1 + w2 * v2) * q[j]
        pq = (1.0 - ww) * q[j]  # v q for a prismatic joint
        e[0] = ((b * u0 - s * x0) + wvq * w0) + pq * v0
        e[1] = ((b * u1 - s * x1) + wvq * w1) + pq * v1
        e[2] = ((b * u2 - s * x2) + wvq * w2) + pq * v2
        for a in range(3):
            p[j + 1, a] = (R[j, a, 0] * e[0] + R[j, a, 1] * e[1] + R[j, a, 2] * e[2]) + p[j, a]
            for k in range(3):
                R[j + 1, a, k] = R[j, a, 0] * E[0, k] + R[j, a, 1] * E[1, k] + R[j, a, 2] * E[2, k]


@njit(nogil=True, cache=True, error_model="numpy", inline="always")
def _ad(R, p, t, out):
    """``Ad_{(R, p)} t`` = ``(R w, R v + p x R w)`` of a twist ``t`` (6,) into ``out`` (6,)."""
    for a in range(3):
        out[a] = R[a, 0] * t[0] + R[a, 1] * t[1] + R[a, 2] * t[2]
        out[3 + a] = R[a, 0] * t[3] + R[a, 1] * t[4] + R[a, 2] * t[5]
    out[3] += p[1] * out[2] - p[2] * out[1]
    out[4] += p[2] * out[0] - p[0] * out[2]
    out[5] += p[0] * out[1] - p[1] * out[0]


@njit(nogil=True, cache=True, error_model="numpy")
def _space_kernel(S, Q, J):
    n = S.shape[0]
    R = np.empty((n + 1, 3, 3))
    p = np.empty((n + 1, 3))
    col = np.empty(6)
    for i in range(Q.shape[0]):
        _prefix(S, Q[i], R, p)
        for j in range(n):
            _ad(R[j], p[j], S[j], col)
            for r in range(6):
                J[i, r, j] = col[r]


@njit(nogil=True, cache=True, error_model="numpy")
def _error_kernel(S, home_p, Q, ptr, site, coef, X, J):
    n = S.shape[0]
    R = np.empty((n + 1, 3, 3))
    p = np.empty((n + 1, 3))
    V = np.empty(6)
    U = np.empty(6)
    for i in range(Q.shape[0]):
        _prefix(S, Q[i], R, p)
        Rn, pn = R[n], p[n]
        t0 = (Rn[0, 0] * home_p[0] + Rn[0, 1] * home_p[1] + Rn[0, 2] * home_p[2]) + pn[0]
        t1 = (Rn[1, 0] * home_p[0] + Rn[1, 1] * home_p[1] + Rn[1, 2] * home_p[2]) + pn[1]
        t2 = (Rn[2, 0] * home_p[0] + Rn[2, 1] * home_p[1] + Rn[2, 2] * home_p[2]) + pn[2]
        for k in range(ptr.shape[0] - 1):
            for r in range(6):
                V[r] = 0.0
            for e in range(ptr[k], ptr[k + 1]):  # V = sum_e coef_e Ad_{P_site_e} X_e
                _ad(R[site[e]], p[site[e]], X[e], U)
                c = coef[e]
                for r in range(6):
                    V[r] = V[r] + c * U[r]
            J[i, 0, k] = V[3] - (t1 * V[2] - t2 * V[1])
            J[i, 1, k] = V[4] - (t2 * V[0] - t0 * V[2])
            J[i, 2, k] = V[5] - (t0 * V[1] - t1 * V[0])
            J[i, 3, k], J[i, 4, k], J[i, 5, k] = V[0], V[1], V[2]


def space_jacobian(screws: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Space Jacobians, shape (P, 6, n), of screws (n, 6) (unit or zero angular parts) at q (P, n) [rad, mm]."""
    S = np.ascontiguousarray(screws, dtype=float)
    Q = np.ascontiguousarray(q, dtype=float)
    J = np.empty((Q.shape[0], 6, S.shape[0]))
    _space_kernel(S, Q, J)
    return J


def error_jacobian(screws, home_p, q, ptr, site, coef, twists) -> np.ndarray:
    """Error Jacobians, shape (P, 6, K), from a chain program's entries (CSR by parameter, see
    :meth:`tolalloc.errormodel.chain.ChainProgram.param_entries`): ``ptr`` (K + 1,), per entry its site in 0..n,
    coefficient and twist (E, 6)."""
    S = np.ascontiguousarray(screws, dtype=float)
    Q = np.ascontiguousarray(q, dtype=float)
    X = np.ascontiguousarray(twists, dtype=float)
    J = np.empty((Q.shape[0], 6, len(ptr) - 1))
    _error_kernel(S, np.ascontiguousarray(home_p, dtype=float), Q, np.asarray(ptr, np.int64),
                  np.asarray(site, np.int64), np.ascontiguousarray(coef, dtype=float), X, J)
    return J
