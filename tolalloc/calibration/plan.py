"""Calibration plan: measurement poses, what is measured, its noise, and what is estimated.

Plan CSV (what ``tolalloc calplan`` writes and ``tolalloc allocate --calibration`` reads)::

    # robot = ur10                     the robot the plan was written for (checked when read)
    # n_poses = 12                      the number of pose rows that follow (checked: a truncated file is refused)
    # measurement = position           (or: pose)
    # noise_mm = 0.02                   tracker noise sigma per coordinate [mm]
    # noise_deg = 0.001                 orientation noise sigma [deg] (pose measurements only)
    # estimate = all                    or a space-separated list of parameter names
    # registration = true               estimate the tracker registration (6) and tool offset (3)
    j1_deg,j2_deg,...                   one row per measurement pose, interface units (deg / mm)
    10.0,-20.0,...

The pose columns are written ``<joint name>_deg`` / ``_mm`` and read by the joint-column rule of every reader
(:mod:`tolalloc.robot.columns`: ``q1_deg`` / ``q4_mm``, ``<joint name>_deg`` / ``_mm`` or plain ``q1..qN``), so a
plan filled in with tracker readings (``x_mm, y_mm, z_mm``) is also a measurement file for the diagnosis, and
still a plan (columns other than the joints' are not read).
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.robot.columns import find_joint_columns
from tolalloc.robot.model import Robot

__all__ = ["CalibrationPlan", "make_plan", "read_plan", "write_plan"]


@dataclass(frozen=True, eq=False)
class CalibrationPlan:
    """A calibration plan.

    Attributes
    ----------
    q : array, shape (M, n) [rad, mm]
        Measurement poses (M may be 0: no calibration).
    measurement : {"position", "pose"}
    noise_mm : float
        Position noise sigma per coordinate [mm].
    noise_rad : float
        Orientation noise sigma per axis [rad] (``pose`` only).
    estimate : tuple of str or None
        Parameters estimated; ``None``: every systematic one.
    registration : bool
        Whether the tracker registration (6) and tool offset (3) are estimated too (nuisance, marginalised).
    robot : str or None
        Name of the robot the plan was made for (``None``: unknown, e.g. a plan file without the header line).
    """

    q: np.ndarray
    measurement: str = "position"
    noise_mm: float = 0.02
    noise_rad: float = np.deg2rad(0.001)
    estimate: tuple | None = None
    registration: bool = True
    robot: str | None = None

    @property
    def n_poses(self) -> int:
        return self.q.shape[0]

    @property
    def rows_per_pose(self) -> int:
        return 3 if self.measurement == "position" else 6

    def to_frame(self, robot: Robot) -> pd.DataFrame:
        """One row per pose, joint values in interface units (deg / mm)."""
        qi = robot.q_to_interface(self.q)
        return pd.DataFrame({f"{j.name}_{j.unit}": qi[:, k] for k, j in enumerate(robot.joints)})


def _check_noise(value, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = np.nan
    if isinstance(value, bool) or not np.isfinite(v) or v <= 0:
        raise TolallocError(f"{name}: expected a finite noise standard deviation > 0, got {value!r}; "
                            "a perfect measurement is the limit of a small one (e.g. 1e-6).")
    return v


def make_plan(robot: Robot, q, *, measurement: str = "position", noise_mm: float = 0.02, noise_deg: float = 0.001,
              estimate=None, registration: bool = True) -> CalibrationPlan:
    """Validated :class:`CalibrationPlan`.

    Parameters
    ----------
    robot : Robot
    q : array, shape (M, n) [rad, mm]
        Measurement poses, inside the joint limits (M = 0 allowed: an empty plan).
    measurement : {"position", "pose"}
    noise_mm, noise_deg : float
        Measurement noise sigma [mm] and [deg], > 0.
    estimate : iterable of str, optional
        Parameter names (checked against the error model where the plan is used); default all systematic.
    registration : bool
    """
    if measurement not in ("position", "pose"):
        raise TolallocError(f"measurement: expected 'position' or 'pose', got {measurement!r}.")
    q = (np.atleast_2d(robot.check_q(q, "calibration poses")) if np.size(q) else
         np.zeros((0, robot.n_joints)))
    est = None if estimate is None or estimate == "all" else tuple(estimate)
    return CalibrationPlan(q, measurement, _check_noise(noise_mm, "noise_mm"),
                           np.deg2rad(_check_noise(noise_deg, "noise_deg")), est, bool(registration), robot.name)


def write_plan(plan: CalibrationPlan, robot: Robot, path) -> None:
    """Write ``plan`` as CSV with its settings in ``#`` header lines."""
    est = "all" if plan.estimate is None else " ".join(plan.estimate)
    head = (f"# robot = {robot.name}\n# n_poses = {plan.n_poses}\n# measurement = {plan.measurement}\n# noise_mm = {plan.noise_mm:.12g}\n"
            f"# noise_deg = {np.rad2deg(plan.noise_rad):.12g}\n# estimate = {est}\n"
            f"# registration = {'true' if plan.registration else 'false'}\n")
    Path(path).write_text(head + plan.to_frame(robot).to_csv(index=False, float_format="%.10g"), encoding="utf-8")


def read_plan(path, robot: Robot) -> CalibrationPlan:
    """Read a plan CSV (see the module docstring); poses must lie inside the robot's limits."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise TolallocError(f"calibration plan {str(path)!r}: cannot read it ({exc.strerror}); give an existing CSV "
                            "written by tolalloc calplan / tolalloc.plan_calibration.") from None
    settings = {}
    for line in text.splitlines():
        if line.startswith("#") and "=" in line:
            key, _, val = line[1:].partition("=")
            settings[key.strip()] = val.strip()
    known = {"robot", "n_poses", "measurement", "noise_mm", "noise_deg", "estimate", "registration"}
    bad = set(settings) - known
    if bad:
        raise TolallocError(f"calibration plan {path.name}: unknown setting(s) {', '.join(sorted(bad))}; "
                            f"expected {', '.join(sorted(known))}.")
    if settings.get("robot", robot.name) != robot.name:
        raise TolallocError(f"calibration plan {path.name}: written for the robot {settings['robot']!r} (its header), "
                            f"but the allocation is for {robot.name!r}; design a plan for this robot "
                            f"(tolalloc calplan {robot.name} / tolalloc.plan_calibration({robot.name!r}, n_poses)).")
    cols = [f"{j.name}_{j.unit}" for j in robot.joints]
    try:
        df = pd.read_csv(io.StringIO(text), comment="#", skipinitialspace=True)
    except (pd.errors.EmptyDataError, pd.errors.ParserError) as exc:
        raise TolallocError(f"calibration plan {path.name}: cannot be read as CSV ({str(exc).strip()}); expected the "
                            f"columns {', '.join(cols)} (a plan written by tolalloc calplan / "
                            "tolalloc.plan_calibration).") from None
    qcols = find_joint_columns(robot, df.columns, f"calibration plan {path.name}")  # other columns: not read
    try:
        qi = df.set_axis([str(c).strip() for c in df.columns], axis=1)[qcols].to_numpy(dtype=float)
    except ValueError:
        raise TolallocError(f"calibration plan {path.name}: joint values must be numbers (deg / mm).") from None
    if "n_poses" in settings and settings["n_poses"] != str(len(qi)):
        raise TolallocError(f"calibration plan {path.name}: its header says n_poses = {settings['n_poses']}, but the "
                            f"file has {len(qi)} pose row(s) (truncated or edited?); write the plan again (tolalloc "
                            "calplan / tolalloc.plan_calibration), or correct the n_poses line.")
    q = robot.check_q(qi, f"calibration plan {path.name}", interface=True) if len(qi) else np.zeros((0, len(cols)))
    reg = settings.get("registration", "true").lower()
    if reg not in ("true", "false"):
        raise TolallocError(f"calibration plan {path.name}: registration expected true or false, got {reg!r}.")
    est = settings.get("estimate", "all")
    return make_plan(robot, q, measurement=settings.get("measurement", "position"),
                     noise_mm=settings.get("noise_mm", 0.02), noise_deg=settings.get("noise_deg", 0.001),
                     estimate=None if est == "all" else est.split(), registration=reg == "true")
