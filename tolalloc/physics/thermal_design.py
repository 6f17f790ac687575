"""The design's thermal forward model: the links' temperatures over an ambient range and a duty cycle, and their growth.

The motors' copper losses at the held loads warm them by their thermal resistance (:func:`motor_rise`); a share of it
reaches the links at their ends (:func:`link_temperature`), which grow by their material's expansion coefficient
(:func:`link_cte`) along themselves (:func:`~tolalloc.physics.thermal.link_growth`, the field the diagnosis fits).
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.model import Robot
from tolalloc.physics.thermal import link_joint_matrix

__all__ = ["COPPER_LOSS_FACTOR", "link_cte", "motor_rise", "link_temperature"]

#: Copper loss per ``R_w I^2`` of a three-phase winding in star: three phases of ``R_w / 2`` each (``R_w`` the
#: line-to-line resistance, ``I`` the rms phase current of the torque constant).
COPPER_LOSS_FACTOR = 1.5


def link_cte(robot: Robot) -> np.ndarray:
    """Coefficient of thermal expansion [1/K] of every link of nonzero length (the order of
    :func:`~tolalloc.physics.thermal.link_growth`), from its section in the robot file; 0 where the file gives none
    (such a link does not grow)."""
    return np.array([robot.components.links[lk.name].cte_per_K if lk.name in robot.components.links else 0.0
                     for lk in robot.links if lk.length_mm > 0])


def motor_rise(robot: Robot, tau: np.ndarray, duty: float) -> np.ndarray:
    """Steady temperature rise [K] of every joint's motor, shape (P, n), holding the loads ``tau`` (P, n) [N m] for the
    fraction ``duty`` of the time: copper losses through the thermal resistance ``R_th``. The figures are a servo
    datasheet's: ``R_w`` the winding's line-to-line resistance, ``k_t`` per ampere rms, so a three-phase winding in
    star with the current ``I = tau / (N k_t)`` loses ``3 (R_w / 2) I^2`` (:data:`COPPER_LOSS_FACTOR`; ``N`` the
    reducer's ratio, 1 without one). Joints without complete motor figures, and prismatic joints, do not heat."""
    out = np.zeros_like(np.asarray(tau, float))
    for j, jt in enumerate(robot.joints):
        parts = robot.components.joint(jt.name)
        m = parts.motor
        if (not jt.is_revolute or m is None or None in (m.winding_resistance_ohm, m.torque_constant_Nm_per_A,
                                                          m.thermal_resistance_K_per_W)):
            continue
        ratio = parts.reducer.ratio if parts.reducer is not None and parts.reducer.ratio else 1.0
        current = tau[:, j] / (ratio * m.torque_constant_Nm_per_A)
        loss = COPPER_LOSS_FACTOR * m.winding_resistance_ohm * current ** 2
        out[:, j] = m.thermal_resistance_K_per_W * duty * loss
    return out


def link_temperature(robot: Robot, ambient_delta_c, rise: np.ndarray) -> np.ndarray:
    """Temperature of every link of nonzero length above the reference [K], shape (P, L): the ambient's departure
    ``ambient_delta_c`` (P,) plus, per motor at the link's ends, its ``link_coupling`` share of its rise ``rise``
    (P, n) (:func:`motor_rise`), averaged over those motors."""
    lj = link_joint_matrix(robot)  # (L, n)
    coup = np.array([getattr(robot.components.joint(jt.name).motor, "link_coupling", None) or 0.0
                     for jt in robot.joints])
    heat = (rise * coup) @ lj.T / np.maximum(lj.sum(axis=1), 1.0)
    return np.asarray(ambient_delta_c, float)[:, None] + heat
