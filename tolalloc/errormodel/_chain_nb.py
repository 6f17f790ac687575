"""numba kernel of :meth:`tolalloc.errormodel.model.ErrorModel.perturbed_chain` (imported only when the compiled
engine is used).

The same walk over the chain program as the numpy path, one sample at a time: an ERROR factor multiplies the
running product ``C`` by ``exp([twist] amount)`` (the closed form of :func:`tolalloc.robot.lie.exp_se3_rp`, same
small-angle series), a JOINT factor takes the screw ``Ad_C twist`` and adds its amount to the joint offset; the
home pose is ``C M``. Equal to the numpy path to rounding (tests/test_chain_program.py). A diagnosis asks for one
chain per Levenberg-Marquardt pass, where the numpy path spends its time on per-call overhead.
"""

import numpy as np
from numba import njit

__all__ = ["perturbed_chain"]


@njit(nogil=True, cache=True, error_model="numpy")
def _exp_right(C, xi, T):
    """``C <- C exp([xi])`` for a twist ``xi`` (6,); ``T`` (3, 4) scratch."""
    w0, w1, w2 = xi[0], xi[1], xi[2]
    v0, v1, v2 = xi[3], xi[4], xi[5]
    t2 = w0 * w0 + w1 * w1 + w2 * w2
    theta = np.sqrt(t2)
    if theta < 1e-4:
        a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0
        b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0
        c = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0
    else:
        s = np.sin(theta)
        a = s / theta
        b = (1.0 - np.cos(theta)) / (theta * theta)
        c = (theta - s) / (theta * theta * theta)
    d = 1.0 - b * t2
    T[0, 0] = b * w0 * w0 + d
    T[0, 1] = b * w0 * w1 - a * w2
    T[0, 2] = b * w0 * w2 + a * w1
    T[1, 0] = b * w1 * w0 + a * w2
    T[1, 1] = b * w1 * w1 + d
    T[1, 2] = b * w1 * w2 - a * w0
    T[2, 0] = b * w2 * w0 - a * w1
    T[2, 1] = b * w2 * w1 + a * w0
    T[2, 2] = b * w2 * w2 + d
    wv = w0 * v0 + w1 * v1 + w2 * v2
    e = 1.0 - c * t2
    T[0, 3] = e * v0 + b * (w1 * v2 - w2 * v1) + c * wv * w0
    T[1, 3] = e * v1 + b * (w2 * v0 - w0 * v2) + c * wv * w1
    T[2, 3] = e * v2 + b * (w0 * v1 - w1 * v0) + c * wv * w2
    for r in range(3):
        c0, c1, c2 = C[r, 0], C[r, 1], C[r, 2]
        C[r, 3] += c0 * T[0, 3] + c1 * T[1, 3] + c2 * T[2, 3]
        for k in range(3):
            C[r, k] = c0 * T[0, k] + c1 * T[1, k] + c2 * T[2, k]


@njit(nogil=True, cache=True, error_model="numpy")
def perturbed_chain(kind, twist, joint, M, amounts, screws, home, dq):
    """Fill ``screws`` (N, n, 6), ``home`` (N, 4, 4) and ``dq`` (N, n, zeroed) for factor amounts (N, F).

    ``kind`` (F,) 0 = ERROR, 1 = JOINT; ``twist`` (F, 6); ``joint`` (F,); ``M`` (4, 4) the home pose.
    """
    C = np.empty((3, 4))
    T = np.empty((3, 4))
    xi = np.empty(6)
    for i in range(amounts.shape[0]):
        C[:] = 0.0
        C[0, 0] = C[1, 1] = C[2, 2] = 1.0
        for f in range(kind.shape[0]):
            if kind[f] == 1:
                j = joint[f]
                dq[i, j] += amounts[i, f]
                for r in range(3):  # Ad_C (w, v) = (R w, R v + p x R w)
                    screws[i, j, r] = C[r, 0] * twist[f, 0] + C[r, 1] * twist[f, 1] + C[r, 2] * twist[f, 2]
                for r in range(3):
                    r1, r2 = (r + 1) % 3, (r + 2) % 3
                    screws[i, j, 3 + r] = (C[r, 0] * twist[f, 3] + C[r, 1] * twist[f, 4] + C[r, 2] * twist[f, 5]
                                           + C[r1, 3] * screws[i, j, r2] - C[r2, 3] * screws[i, j, r1])
            else:
                for k in range(6):
                    xi[k] = amounts[i, f] * twist[f, k]
                _exp_right(C, xi, T)
        for r in range(3):
            for k in range(4):
                home[i, r, k] = C[r, 0] * M[0, k] + C[r, 1] * M[1, k] + C[r, 2] * M[2, k] + C[r, 3] * M[3, k]
        home[i, 3, :] = M[3, :]
