"""Guard on the fitted effect parameters: a joint compliance must not be negative.

A passive joint yields *along* its gravity load (``dq = c tau`` with ``c >= 0``, ``tau`` the load torque of
:func:`tolalloc.physics.loads.gravity_torques`). A compliance clearly below zero (more than ``N_SD`` standard
deviations) is a joint that leans into gravity: the named effect then stands in for something else (the mass
model, unmodelled geometry, another gravity-driven effect), and its name is not a physical diagnosis even if
it lowers the held-out error. Columns ``c_<joint>`` (per N m or N) and ``d_<joint>`` (per kg of payload at the
target) of ``joint_compliance`` are checked.
"""

from __future__ import annotations

import numpy as np

from tolalloc.diagnose.uncertainty import parameter_covariance

__all__ = ["compliance_sign_flags", "N_SD"]

#: Standard deviations below zero at which a compliance counts as negative.
N_SD = 3.0


def compliance_sign_flags(fit, q: np.ndarray, B: np.ndarray, names, n_sd: float = N_SD) -> tuple:
    """Guard messages for compliance parameters of ``fit`` more than ``n_sd`` standard deviations below zero.

    Parameters
    ----------
    fit : :class:`tolalloc.diagnose.calibrate.Fit`   the final fit (``fit.beta`` matches the columns of ``B``)
    q : array, shape (P, n) [rad, mm]                 its training poses
    B : array, shape (P, 3, m) [mm per unit]          its effect columns on those poses
    names : sequence of str, length m                 effect parameter names (``[effect:]c_<joint> [unit]``)
    """
    names = [n.split(":", 1)[-1] for n in names]  # "joint_compliance:c_elbow_joint [rad/(N m)]"
    if B is None or not B.shape[-1] or not any(n.startswith(("c_", "d_")) for n in names):
        return ()
    cov, _ = parameter_covariance(fit, q, B, unresolved="inflate")
    m = B.shape[-1]
    sd = np.sqrt(np.maximum(np.diag(cov)[-m:], 0.0))
    beta = np.asarray(fit.beta, float)[-m:]
    out = []
    for name, b, s in zip(names, beta, sd):
        if name.startswith(("c_", "d_")) and b < -n_sd * s:
            out.append(f"non-physical effect parameter: {name.split(' ')[0]} = {b:.3g} {name.partition(' ')[2]} "
                       f"is {abs(b) / s:.1f} sd below zero (a joint that yields against its gravity load); the "
                       "compliance effect is standing in for something else (mass model, unmodelled geometry, "
                       "another gravity-driven effect), not a measured stiffness")
    return tuple(out)
