"""A nominal model that misses the measurements by far more than manufacturing errors can explain.

After the tracker frame and the target offset are registered, a real robot of the right kind, measured in the
right units, is off by a few millimetres at most (the UR10 data: about 1 mm RMS). Tens of millimetres or more
mean the data does not fit the robot as described: a joint column in radians instead of degrees, joints in
another order or with other zero positions, or another robot altogether. Fitting effects to such data gives a
confident, meaningless answer (e.g. a "transmission error" of hundreds of mm), so the diagnosis stops with one
clear error, naming the joint columns that look like radians when converting them explains the gap.
``--trust-units`` (:func:`tolalloc.units.trusting_units`) accepts the data as it is.
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Robot
from tolalloc.units import units_trusted
from tolalloc.diagnose.calibrate import Fit, kabsch
from tolalloc.diagnose.measurements import Measurements

__all__ = ["check_nominal_misfit", "MISFIT_MM"]

#: Nominal RMS [mm] (after registration and target offset) beyond which the data is taken not to fit the robot.
MISFIT_MM = 25.0


def _kabsch_rms(robot: Robot, q: np.ndarray, xyz: np.ndarray) -> float:
    """RMS [mm] of the rigid alignment of the nominal tool points at ``q`` (P, n) to ``xyz`` (P, 3)."""
    pts = robot.fk_internal(q)[:, :3, 3]
    R, p = kabsch(pts, xyz)
    return float(np.sqrt(np.mean(np.sum((pts @ R.T + p - xyz) ** 2, axis=1))))


def radian_columns(robot: Robot, meas: Measurements) -> list:
    """Revolute joint columns (0-based) whose values read as radians explain the data far better, as a list."""
    q, xyz = meas.q, meas.xyz_mm
    base = _kabsch_rms(robot, q, xyz)
    small = [j for j in np.flatnonzero(robot.revolute_mask) if np.abs(np.degrees(q[:, j])).max() <= 2 * np.pi + 1e-6
             and np.ptp(q[:, j]) > 0]
    found = []
    for j in small:
        q2 = q.copy()
        q2[:, j] = np.degrees(q[:, j])  # the file's numbers taken as radians
        if _kabsch_rms(robot, q2, xyz) < base / 3:
            found.append(int(j))
    if not found and len(small) > 1:
        q2 = q.copy()
        q2[:, small] = np.degrees(q[:, small])
        if _kabsch_rms(robot, q2, xyz) < base / 3:
            found = [int(j) for j in small]
    return found


def check_nominal_misfit(robot: Robot, meas: Measurements, nominal: Fit, limit_mm: float = MISFIT_MM) -> None:
    """Raise :class:`TolallocError` when the registered nominal model misses ``meas`` by more than ``limit_mm``."""
    rms = nominal.rms_mm
    if rms <= limit_mm or units_trusted():
        return
    cols = radian_columns(robot, meas)
    hint = ""
    if cols:
        names = ", ".join(f"q{j + 1}" for j in cols)
        hint = (f" Column(s) {names} look like radians (their values span less than one turn if read as degrees, and "
                "read as radians they explain the measurements): convert them to degrees.")
    raise TolallocError(
        f"{meas.source}: after registering the tracker frame and the target offset, the nominal robot misses the "
        f"measured points by {rms:.4g} mm RMS; manufacturing errors explain a few mm at most (limit {limit_mm:g} "
        f"mm).{hint} Check the joint columns (deg for revolute, mm for prismatic joints, in the robot's joint order "
        "and zero positions) and the robot (wrong robot?); pass --trust-units to diagnose the data as it is.")
