"""The measuring instrument of the acceptance test (a laser tracker) and the registration of its frame.

**Tracker.** A laser tracker's maximum permissible error is stated as ``MPE = A + B L`` (ISO 10360-10; of the order
of 15 um + 6 um/m, ``L`` the distance from the tracker). It is read here as the half-width of a uniform error of
each coordinate of each measured point (GUM, ISO/IEC Guide 98-3 4.3.7): standard uncertainty ``MPE / sqrt(3)`` per
coordinate, independent between measurements. A 6-DoF probe's orientation error likewise from ``angle_mpe_deg``.
Expanded uncertainties use the coverage factor ``k`` (default 2, about 95 %).

**Registration** (ISO 9283 6.4: the attained poses are expressed in the base coordinate system; the relation
between the measuring system's frame and the base frame is established by measurement, at poses other than the
test poses): ``"corners"`` fits the rigid transform (rotation ``theta``, translation ``delta``) of least squares
between the measured and the command positions at the cube's eight corners, each measured ``visits`` times;
every measured pose is then expressed through it. The fit absorbs the rigid-body part of the robot's own errors
at those poses (as in a real test) and adds the tracker's noise there. ``"none"``: the base frame is known (base
targets measured beforehand); the robot's base errors then count in full.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.exceptions import ArgumentError

__all__ = ["Tracker", "REGISTRATIONS", "registration_map"]

REGISTRATIONS = ("corners", "none")


def _nonneg(value, name, unit, example):
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if isinstance(value, bool) or not np.isfinite(v) or v < 0:
        raise ArgumentError(f"Tracker.{name}", f"expected a number >= 0 [{unit}] (e.g. {example}), got {value!r}.")
    return v


@dataclass(frozen=True)
class Tracker:
    """A laser tracker: ``MPE = mpe_a_mm + mpe_b_mm_per_m * distance_m`` per coordinate, read as a uniform error.

    Attributes
    ----------
    mpe_a_mm : float
        Constant part of the MPE [mm] (default 0.015).
    mpe_b_mm_per_m : float
        Part proportional to the distance [mm per m] (default 0.006).
    distance_m : float
        Distance from the tracker to the test poses [m] (default 2).
    angle_mpe_deg : float
        MPE of each orientation angle of the 6-DoF probe [deg] (default 0.01).
    k : float
        Coverage factor of the expanded uncertainty (default 2).
    """

    mpe_a_mm: float = 0.015
    mpe_b_mm_per_m: float = 0.006
    distance_m: float = 2.0
    angle_mpe_deg: float = 0.01
    k: float = 2.0

    def __post_init__(self):
        _nonneg(self.mpe_a_mm, "mpe_a_mm", "mm", "0.015")
        _nonneg(self.mpe_b_mm_per_m, "mpe_b_mm_per_m", "mm/m", "0.006")
        _nonneg(self.distance_m, "distance_m", "m", "2")
        _nonneg(self.angle_mpe_deg, "angle_mpe_deg", "deg", "0.01")
        if _nonneg(self.k, "k", "-", "2") <= 0:
            raise ArgumentError("Tracker.k", f"expected a coverage factor > 0 (e.g. 2), got {self.k!r}.")

    @property
    def mpe_mm(self) -> float:
        """MPE at :attr:`distance_m` [mm]."""
        return float(self.mpe_a_mm + self.mpe_b_mm_per_m * self.distance_m)

    @property
    def sigma_mm(self) -> float:
        """Standard uncertainty of each coordinate [mm]: ``MPE / sqrt(3)``."""
        return self.mpe_mm / np.sqrt(3.0)

    @property
    def sigma_rad(self) -> float:
        """Standard uncertainty of each orientation angle [rad]."""
        return float(np.deg2rad(self.angle_mpe_deg) / np.sqrt(3.0))

    def covariance(self) -> np.ndarray:
        """Covariance of one measured pose's error, shape (6, 6): position [mm^2] then rotation [rad^2], the order of
        the error Jacobian's rows."""
        return np.diag(np.r_[np.full(3, self.sigma_mm**2), np.full(3, self.sigma_rad**2)])

    def text(self) -> str:
        return (f"laser tracker, MPE {1000 * self.mpe_a_mm:g} um + {1000 * self.mpe_b_mm_per_m:g} um/m at "
                f"{self.distance_m:g} m = {1000 * self.mpe_mm:.3g} um (u = {1000 * self.sigma_mm:.3g} um per "
                f"coordinate), angles {self.angle_mpe_deg:g} deg")


def registration_map(p_reg_mm: np.ndarray) -> np.ndarray:
    """Least-squares map from the position errors at the registration points to the registration's rotation and
    translation.

    With ``e_r`` (3R,) the measured-minus-command positions at the registration points ``p_r`` (R, 3), the rigid
    correction ``(theta, delta)`` minimising ``sum_r |e_r - (delta + theta x p_r)|^2`` is ``H @ e_r``.

    Returns
    -------
    H : array, shape (6, 3R): rows (theta [rad], delta [mm]).
    """
    p = np.asarray(p_reg_mm, float)
    A = np.zeros((3 * len(p), 6))
    for r, pr in enumerate(p):
        A[3 * r:3 * r + 3, :3] = -_skew(pr)  # theta x p = -[p]x theta
        A[3 * r:3 * r + 3, 3:] = np.eye(3)
    return np.linalg.pinv(A)


def _skew(v) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], float)
