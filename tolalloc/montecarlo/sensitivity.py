"""Control-variable sensitivity curves and errors along a joint trajectory.

The control-variable method of the seed paper (Figs. 7-9, 13-16): every error
parameter is set, one at a time, to each value of a grid while all others are
zero, and the exact (nonlinear) tool-pose error is recorded. Along a joint
trajectory (Fig. 18) the same is done per time step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import ErrorModel
from tolalloc.montecarlo.run import FastChain, McResult, pose_errors

__all__ = ["SensitivityResult", "sensitivity", "TrajectoryResult", "trajectory_errors", "quintic_trajectory",
           "PAPER_LINK_GRID_MM", "PAPER_JOINT_GRID_DEG"]

#: The paper's control-variable grids: link errors ±0.02/0.04/0.06 mm, joint errors ±0.02 ... ±0.1 deg.
PAPER_LINK_GRID_MM = np.array([-0.06, -0.04, -0.02, 0.0, 0.02, 0.04, 0.06])
PAPER_JOINT_GRID_DEG = np.array([-0.1, -0.08, -0.06, -0.04, -0.02, 0.0, 0.02, 0.04, 0.06, 0.08, 0.1])


@dataclass(frozen=True)
class SensitivityResult:
    """Exact tool-pose errors with one parameter at a time set to grid values.

    Attributes
    ----------
    q : array, shape (n_joints,) [rad, mm]
    params : tuple of str
    units : tuple of str
        Internal unit of each parameter (``mm`` or ``rad``).
    grid : array, shape (P, G)
        Parameter values [mm or rad].
    dp_mm : array, shape (P, G, 3)
    norm_mm, reach_mm : array, shape (P, G)
    euler_rad : array, shape (P, G, 3)
        X-Y-Z fixed Euler-angle errors (alpha, beta, gamma).
    rot_rad : array, shape (P, G)
        Attitude error ``|rotvec(R' R^T)|``.
    labels : dict
    """

    q: np.ndarray
    params: tuple
    units: tuple
    grid: np.ndarray
    dp_mm: np.ndarray
    norm_mm: np.ndarray
    reach_mm: np.ndarray
    euler_rad: np.ndarray
    rot_rad: np.ndarray
    labels: dict

    def to_frame(self) -> pd.DataFrame:
        """Long table: one row per parameter and grid value (value in mm or deg as ``value_mm_or_deg``)."""
        rows = []
        for i, name in enumerate(self.params):
            f = 1.0 if self.units[i] == "mm" else 180 / np.pi
            for g in range(self.grid.shape[1]):
                rows.append({"parameter": name, "unit": "mm" if self.units[i] == "mm" else "deg",
                             "value_mm_or_deg": self.grid[i, g] * f,
                             "dx_mm": self.dp_mm[i, g, 0], "dy_mm": self.dp_mm[i, g, 1], "dz_mm": self.dp_mm[i, g, 2],
                             "norm_mm": self.norm_mm[i, g], "reach_mm": self.reach_mm[i, g],
                             "dalpha_rad": self.euler_rad[i, g, 0], "dbeta_rad": self.euler_rad[i, g, 1],
                             "dgamma_rad": self.euler_rad[i, g, 2], "rot_rad": self.rot_rad[i, g]})
        return pd.DataFrame(rows)


def _param_indices(model: ErrorModel, params) -> list[int]:
    if isinstance(params, str):
        params = [params]
    params = list(params)
    if not params:
        raise TolallocError("params: expected at least one error-parameter name.")
    return [model.index(p) for p in params]


def sensitivity(model: ErrorModel, q, params, grid) -> SensitivityResult:
    """Control-variable sensitivity: each parameter alone at each grid value.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (n_joints,) [rad, mm]
    params : sequence of str
        Parameter names (e.g. ``["dl1", ..., "dl6"]``).
    grid : array, shape (G,) or (P, G)
        Values [mm or rad, the parameters' internal unit]; one row per parameter, or one row for all.

    Returns
    -------
    SensitivityResult
    """
    idx = _param_indices(model, params)
    grid = np.asarray(grid, dtype=float)
    if grid.ndim == 1:
        grid = np.broadcast_to(grid, (len(idx), grid.size))
    if grid.ndim != 2 or grid.shape[0] != len(idx) or not np.all(np.isfinite(grid)):
        raise TolallocError(f"grid: expected finite values of shape (G,) or ({len(idx)}, G), got shape {grid.shape}.")
    P, G = grid.shape
    values = np.zeros((P * G, len(model.params)))
    for i, k in enumerate(idx):
        values[i * G:(i + 1) * G, k] = grid[i]
    err = pose_errors(model, q, values)
    return SensitivityResult(
        q=model.robot.check_q(q, "q"), params=tuple(model.names[k] for k in idx),
        units=tuple(model.params[k].unit for k in idx), grid=np.array(grid),
        dp_mm=err["dp_mm"].reshape(P, G, 3), norm_mm=err["norm_mm"].reshape(P, G),
        reach_mm=err["reach_mm"].reshape(P, G), euler_rad=err["euler_rad"].reshape(P, G, 3),
        rot_rad=np.linalg.norm(err["rotvec_rad"], axis=1).reshape(P, G), labels=model.labels)


def quintic_trajectory(q0, q1, duration_s: float = 10.0, steps: int = 51):
    """Rest-to-rest quintic joint trajectory from ``q0`` to ``q1``.

    Returns
    -------
    t_s : array, shape (T,)
    Q : array, shape (T, n) [rad, mm]
    """
    q0, q1 = np.asarray(q0, float), np.asarray(q1, float)
    t = np.linspace(0.0, duration_s, int(steps))
    u = t / duration_s
    s = 10 * u**3 - 15 * u**4 + 6 * u**5
    return t, q0 + s[:, None] * (q1 - q0)


@dataclass(frozen=True)
class TrajectoryResult:
    """Tool-position error along a joint trajectory (the paper's Fig. 18).

    Attributes
    ----------
    t_s : array, shape (T,)
    q : array, shape (T, n_joints) [rad, mm]
    params : tuple of str
    values : array, shape (P,)
        Value given to each parameter alone [mm or rad].
    dp_mm : array, shape (T, P, 3)
        Error with only parameter ``p`` at its value.
    mc : McResult or None
        Monte Carlo of the full model at every time step (std per direction over time).
    """

    t_s: np.ndarray
    q: np.ndarray
    params: tuple
    values: np.ndarray
    dp_mm: np.ndarray
    mc: McResult | None = None

    def to_frame(self) -> pd.DataFrame:
        rows = []
        for ti, t in enumerate(self.t_s):
            for pi, name in enumerate(self.params):
                rows.append({"t_s": t, "parameter": name, "dx_mm": self.dp_mm[ti, pi, 0],
                             "dy_mm": self.dp_mm[ti, pi, 1], "dz_mm": self.dp_mm[ti, pi, 2]})
        return pd.DataFrame(rows)


def trajectory_errors(model: ErrorModel, t_s, Q, params, values=None, *, mc: McResult | None = None) -> TrajectoryResult:
    """Error of each direction along a trajectory, one parameter at a time.

    Parameters
    ----------
    model : ErrorModel
    t_s : array, shape (T,)
    Q : array, shape (T, n_joints) [rad, mm]
    params : sequence of str
    values : array, shape (P,), optional
        Value of each parameter [mm or rad]; default its sigma (one standard deviation).
    mc : McResult, optional
        A Monte Carlo run at the same poses, stored alongside.
    """
    idx = _param_indices(model, params)
    Q = model.robot.check_q(np.atleast_2d(Q), "trajectory")
    vals = model.sigma[idx] if values is None else np.asarray(values, float)
    if vals.shape != (len(idx),) or not np.all(np.isfinite(vals)):
        raise TolallocError(f"values: expected {len(idx)} finite values, got {vals!r}.")
    V = np.zeros((len(idx), len(model.params)))
    V[np.arange(len(idx)), idx] = vals
    chain = FastChain(model)
    dp = np.stack([pose_errors(model, qi, V, chain=chain)["dp_mm"] for qi in Q])
    return TrajectoryResult(np.asarray(t_s, float), Q, tuple(model.names[k] for k in idx), vals, dp, mc)
