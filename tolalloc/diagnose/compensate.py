"""Compensation: the joint values that put the target point on given positions under an identified model.

Position targets ``x`` (P, 3) [mm] and seed joint values ``q0`` (P, n) -- the program's nominal joint values, or
the nominal robot's inverse kinematics of the targets -- are solved row by row for ``f(q) = x``, ``f`` the
identified model's target point (:class:`~tolalloc.diagnose.model_use.IdentifiedModel`), by damped least squares
(Levenberg-Marquardt): ``dq = J^T (J J^T + lambda^2 I)^-1 (x - f(q))`` with the identified geometry's Jacobian
``J`` (3, n); ``lambda`` grows tenfold on a step that does not reduce the error and shrinks on one that does. With
more joints than 3 the step is the smallest joint change, so the solution stays next to the seed (the tool
orientation the program taught is kept as far as a position correction allows). The effects' own slope in the
joints is left out of ``J``; their displacement is re-evaluated at every step, so the fixed point is exact.

Rows are refused, never silently kept: ``unreachable`` (the error stays above ``tol_mm`` after ``max_iter`` steps
-- the row's distance from the target at the closest joint values found says how far) or ``joint_limits`` (the
solution leaves a joint's limits; which joints and by how much). Rows that are not finite (a NaN target or seed)
are an input error, raised before any solving.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.model_use import IdentifiedModel

__all__ = ["Compensation", "solve_targets", "compensate", "nominal_targets", "TOL_MM", "MAX_ITER", "STATUSES"]

#: Distance [mm] below which a target counts as reached.
TOL_MM = 1e-6
#: Damped least-squares steps at most.
MAX_ITER = 100
STATUSES = ("ok", "unreachable", "joint_limits")
#: Damping at which a row counts as stuck (no step reduces its error any more).
STALL_DAMPING = 1e4
#: Random starts of the nominal inverse kinematics for a target its nominal joint values do not reach.
IK_STARTS = 8


@dataclass(frozen=True, eq=False)
class Compensation:
    """Compensated joint values of a set of targets.

    Attributes
    ----------
    robot : Robot
    q_seed : array, shape (P, n) [rad, mm]   where each row started (the program's joint values)
    q : array, shape (P, n) [rad, mm]        compensated joint values (the closest found on refused rows)
    targets_mm : array, shape (P, 3)         the targets, in ``frame``
    predicted_mm : array, shape (P, 3)       the identified model's target point at ``q``
    status : tuple of str                    per row: ``ok``, ``unreachable`` or ``joint_limits``
    reason : tuple of str                    per row: empty, or why it was refused
    iterations : array of int, shape (P,)
    frame : str                              ``base`` or ``tracker``
    tol_mm : float
    """

    robot: object
    q_seed: np.ndarray
    q: np.ndarray
    targets_mm: np.ndarray
    predicted_mm: np.ndarray
    status: tuple
    reason: tuple
    iterations: np.ndarray
    frame: str = "base"
    tol_mm: float = TOL_MM

    @property
    def error_mm(self) -> np.ndarray:
        """Distance of the model's target point at ``q`` from the target [mm], shape (P,)."""
        return np.linalg.norm(self.predicted_mm - self.targets_mm, axis=1)

    @property
    def ok(self) -> np.ndarray:
        return np.array([s == "ok" for s in self.status], bool)

    def to_frame(self, columns: list | None = None) -> pd.DataFrame:
        """One row per target (``row`` from 1): compensated joint values and their change from the seed in interface
        units (deg / mm; ``columns``: the joint column names, default ``q1_deg``...), the target, the model's point,
        the remaining error, the status and the reason. Refused rows keep empty joint values."""
        rob = self.robot
        names = columns or [f"q{j + 1}_{'deg' if r else 'mm'}" for j, r in enumerate(rob.revolute_mask)]
        qi, dqi = rob.q_to_interface(self.q), rob.q_to_interface(self.q - self.q_seed)
        ok = self.ok
        out = {"row": np.arange(1, len(self.q) + 1)}
        for j, nm in enumerate(names):
            out[nm] = np.where(ok, qi[:, j], np.nan)
        for j, nm in enumerate(names):
            base, unit = nm.rsplit("_", 1) if "_" in nm else (nm, "deg" if rob.revolute_mask[j] else "mm")
            out[f"d{base}_{unit}"] = np.where(ok, dqi[:, j], np.nan)
        for i, a in enumerate("xyz"):
            out[f"target_{a}_mm"] = self.targets_mm[:, i]
        for i, a in enumerate("xyz"):
            out[f"model_{a}_mm"] = self.predicted_mm[:, i]
        out["error_mm"] = self.error_mm
        out["status"] = list(self.status)
        out["reason"] = list(self.reason)
        return pd.DataFrame(out)


def _limit_reason(robot, q: np.ndarray) -> str:
    """Which joints ``q`` (n,) leaves the limits of, by how much (interface units), or empty."""
    lo, hi = robot.lower, robot.upper
    parts = []
    for j, jt in enumerate(robot.joints):
        over = max(lo[j] - q[j], q[j] - hi[j])
        if over > 0:
            unit = "deg" if jt.is_revolute else "mm"
            amount = float(np.rad2deg(over)) if jt.is_revolute else float(over)
            parts.append(f"{jt.name} by {amount:.4g} {unit}")
    return ("the compensated joint values leave the joint limits: " + ", ".join(parts)) if parts else ""


def _finite_rows(values, width: int, name: str, what: str) -> np.ndarray:
    """``values`` as finite rows of ``width`` numbers, shape (P, width); a clear error otherwise."""
    try:
        a = np.atleast_2d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise TolallocError(f"{name}: expected rows of {width} {what}, got {type(values).__name__}.") from None
    if a.ndim != 2 or a.shape[1] != width:
        raise TolallocError(f"{name}: expected rows of {width} {what}, got shape {a.shape}.")
    bad = np.flatnonzero(~np.isfinite(a).all(axis=1))
    if len(bad):
        raise TolallocError(f"{name}: row {int(bad[0])} is not finite ({a[bad[0]].tolist()}); {len(bad)} such row(s) "
                            "in all -- drop or fill them before compensating.")
    return a


def solve_targets(model: IdentifiedModel, targets_mm, q_seed, meas: Measurements | None = None, *, frame: str = "base",
                  tol_mm: float = TOL_MM, max_iter: int = MAX_ITER, clamp: bool = False) -> Compensation:
    """Damped least squares for the joint values that put ``model``'s target point on ``targets_mm`` (module docstring).

    Parameters
    ----------
    model : IdentifiedModel
    targets_mm : array, shape (P, 3) [mm], in ``frame``
    q_seed : array, shape (P, n) [rad, mm]
    meas : Measurements, optional
        The covariates of the rows (payload, temperature, time, directions; :meth:`IdentifiedModel.measurements`);
        its joint values are replaced at every step.
    clamp : bool
        Keep every step inside the joint limits (projected onto them): the nominal inverse kinematics of
        :func:`compensate`; the compensation itself does not clamp, it refuses a row that leaves the limits.
    """
    q = _finite_rows(q_seed, model.robot.n_joints, "q_seed", "joint values [rad, mm]").copy()
    x = _finite_rows(targets_mm, 3, "targets_mm", "x, y, z targets [mm]")
    if len(x) != len(q):
        raise TolallocError(f"targets_mm: expected one x, y, z target [mm] per seed row ({len(q)}), got {len(x)} "
                            "rows.")
    base = meas if meas is not None else model.measurements(q)

    def at(qq):
        return model.points(Measurements(qq, base.xyz_mm, base.temperature_c, base.direction, base.payload_kg,
                                         base.time_s, wrench=base.wrench), frame)

    err = x - at(q)
    norm = np.linalg.norm(err, axis=1)
    lam = np.full(len(q), 1e-6)
    it = np.zeros(len(q), int)
    for _ in range(max_iter):
        live = (norm > tol_mm) & (lam < STALL_DAMPING)  # a row whose damping ran away no longer moves
        if not live.any():
            break
        J = model.joint_jacobian(q, frame)
        scale = np.linalg.norm(J, axis=(1, 2))
        A = J @ np.swapaxes(J, 1, 2) + ((lam * scale) ** 2)[:, None, None] * np.eye(3)
        step = np.einsum("pin,pi->pn", J, np.linalg.solve(A, err[:, :, None])[:, :, 0])
        q_new = np.where(live[:, None], q + step, q)
        if clamp:
            q_new = np.clip(q_new, model.robot.lower, model.robot.upper)
        err_new = x - at(q_new)
        norm_new = np.linalg.norm(err_new, axis=1)
        better = live & (norm_new < norm)
        q[better], err[better], norm[better] = q_new[better], err_new[better], norm_new[better]
        lam = np.where(better, np.maximum(lam / 10, 1e-9), np.where(live, lam * 10, lam))
        it += live
    status, reason = [], []
    for i in range(len(q)):
        lim = _limit_reason(model.robot, q[i])
        if not norm[i] <= tol_mm:
            why = (f"the step limit ({max_iter}) was reached" if it[i] >= max_iter else
                   "no step reduced the error any more")
            status.append("unreachable")
            reason.append(f"target not reached: {norm[i]:.4g} mm away at the closest joint values found, {why} "
                          "(outside the reachable space, or too far from the seed for the local solver)")
        elif lim:
            status.append("joint_limits")
            reason.append(lim)
        else:
            status.append("ok")
            reason.append("")
    return Compensation(model.robot, np.atleast_2d(np.asarray(q_seed, float)), q, x, x - err, tuple(status),
                        tuple(reason), it, frame, tol_mm)


def nominal_targets(model: IdentifiedModel, q, frame: str = "base") -> np.ndarray:
    """Where the nominal robot puts the target point (the identified probe offset) at ``q`` (P, n) [mm]: the positions
    a program taught on the nominal model means."""
    return model.nominal().points(Measurements(np.atleast_2d(q), np.zeros((len(np.atleast_2d(q)), 3))), frame)


def _nominal_ik(model: IdentifiedModel, x: np.ndarray, frame, tol_mm, max_iter) -> np.ndarray:
    """Seeds for targets without joint values: the nominal robot's inverse kinematics within the joint limits, from
    its nominal joint values, then from up to :data:`IK_STARTS` seeded random starts for the rows not reached."""
    nominal, robot = model.nominal(), model.robot
    q = np.repeat(robot.q_nominal[None, :], len(x), axis=0)
    rng = np.random.default_rng(0)
    for k in range(IK_STARTS + 1):
        rows = np.arange(len(x)) if k == 0 else np.flatnonzero(~done)
        if not len(rows):
            break
        start = q[rows] if k == 0 else robot.random_q(rng, len(rows))
        res = solve_targets(nominal, x[rows], start, None, frame=frame, tol_mm=tol_mm, max_iter=max_iter, clamp=True)
        q[rows] = np.where(res.ok[:, None] | (k == 0), res.q, q[rows])
        done = np.zeros(len(x), bool) if k == 0 else done
        done[rows] = res.ok
    return q


def compensate(model: IdentifiedModel, q_program=None, targets_mm=None, meas: Measurements | None = None, *,
               frame: str = "base", tol_mm: float = TOL_MM, max_iter: int = MAX_ITER) -> Compensation:
    """Compensated joint values of a program.

    ``q_program`` (P, n) [rad, mm]: the program's joint values (the seeds; without ``targets_mm`` the targets are the
    positions the nominal robot reaches there, :func:`nominal_targets`). ``targets_mm`` (P, 3) without
    ``q_program``: the seeds are the nominal robot's inverse kinematics from its nominal joint values (give the
    program's joint values whenever there are some: a position has many joint solutions), and the compensated
    solution is kept inside the joint limits -- the tool chose the joint values, so a seed on a limit (where the
    nominal solution lies) must not leave it by the compensation's few thousandths of a degree; a taught program's
    row that would leave them is refused instead.
    """
    if q_program is None and targets_mm is None:
        raise TolallocError("compensate: expected the program's joint values and / or targets, got neither.")
    chosen = q_program is None
    if chosen:
        q_program = _nominal_ik(model, _finite_rows(targets_mm, 3, "targets_mm", "x, y, z targets [mm]"), frame,
                                tol_mm, max_iter)
    q_program = _finite_rows(q_program, model.robot.n_joints, "q_program", "joint values [rad, mm]")
    x = nominal_targets(model, q_program, frame) if targets_mm is None else targets_mm
    return solve_targets(model, x, q_program, meas, frame=frame, tol_mm=tol_mm, max_iter=max_iter, clamp=chosen)
