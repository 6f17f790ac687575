"""numba kernel of :func:`tolalloc.diagnose.scale.point_kinematics` (imported only when the compiled engine is used).

Per pose the prefix products of :func:`tolalloc.robot.kinematics.compiled_prefix` (the closed form of the numpy
path, same operations), then the flange rotation ``R_n home_R`` and the
target point ``R_n home_p + p_n + R_f t``. Equal to the numpy path to rounding (tests/test_diagnose_scale.py).
"""

import numpy as np
from numba import njit

from tolalloc.robot.kinematics import compiled_prefix

_prefix = compiled_prefix()

__all__ = ["point_kinematics"]


@njit(nogil=True, cache=True, error_model="numpy")
def point_kinematics(S, home, Q, t, pts, rots):
    """Fill ``pts`` (P, 3) and ``rots`` (P, 3, 3) for screws S (n, 6), home (4, 4), Q (P, n), t (3,)."""
    n = S.shape[0]
    R = np.empty((n + 1, 3, 3))
    p = np.empty((n + 1, 3))
    for i in range(Q.shape[0]):
        _prefix(S, Q[i], R, p)
        for a in range(3):
            for b in range(3):
                rots[i, a, b] = R[n, a, 0] * home[0, b] + R[n, a, 1] * home[1, b] + R[n, a, 2] * home[2, b]
        for a in range(3):
            pts[i, a] = (R[n, a, 0] * home[0, 3] + R[n, a, 1] * home[1, 3] + R[n, a, 2] * home[2, 3] + p[n, a]
                         + rots[i, a, 0] * t[0] + rots[i, a, 1] * t[1] + rots[i, a, 2] * t[2])
