"""Checks of a calibration plan against the allocation that uses it: robot, size, header.

* **Robot.** A plan records the robot it was made for (:attr:`CalibrationPlan.robot`, the ``# robot`` header line);
  it must be the allocation's robot, with one joint value per joint inside the joint limits.
* **Size.** With registration and tool offset estimated, a calibration must identify every combination of the
  estimated parameters and the 9 nuisance parameters that a measurement of this robot can see anywhere in its joint
  limits (the generic rank of the stacked identification Jacobian, :func:`identifiable_count`). A plan with fewer
  measurement rows than that leaves some of them to the prior alone, whatever its poses: it is refused, with the
  smallest number of poses that can do it.
* **Header.** Settings passed by the caller (measurement, noise, registration) must agree with the plan's.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.stats import qmc

from tolalloc.calibration.plan import CalibrationPlan
from tolalloc.calibration.posterior import nuisance_columns
from tolalloc.calibration.split import ErrorSplit
from tolalloc.exceptions import TolallocError

__all__ = ["check_plan", "identifiable_count", "min_plan_poses"]

#: Relative singular-value threshold of the generic rank (the gap on both robots is ~1e14).
RANK_TOL = 1e-9


def identifiable_count(split: ErrorSplit, plan: CalibrationPlan, *, n_probe: int = 64, seed: int = 0) -> tuple:
    """Generic rank of the identification problem: ``(total, of the error model, of the nuisance)``.

    The stacked Jacobian of the estimated systematic parameters (columns scaled by their prior sigma) and, with
    registration, the 9 registration / tool-offset columns, at ``n_probe`` scrambled-Sobol poses of the joint limits,
    columns normalised; its numerical rank (:data:`RANK_TOL`) is the number of parameter combinations any plan of
    this robot can identify.
    """
    model = split.model
    robot = model.robot
    rows = plan.rows_per_pose
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # Sobol balance needs a power of 2; any n probes the limits
        q = robot.lower + (robot.upper - robot.lower) * qmc.Sobol(robot.n_joints, scramble=True, seed=seed).random(
            n_probe)
    E = np.array([k for k in split.sys_index if model.sigma[k] > 0], int)
    cols = [model.jacobian(q)[:, :rows, E] * np.sqrt(split.prior_var_of(E))]
    n_nui = 0
    if plan.registration:
        N = nuisance_columns(model, q, rows)
        cols.append(N)
        n_nui = int(_rank(N.reshape(-1, 9)))
    A = np.concatenate(cols, axis=2).reshape(len(q) * rows, -1)
    total = _rank(A)
    return total, total - n_nui, n_nui


def _rank(A: np.ndarray) -> int:
    norm = np.linalg.norm(A, axis=0)
    A = A[:, norm > 0] / norm[norm > 0]
    if not A.size:
        return 0
    s = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(s > RANK_TOL * s[0]))


def min_plan_poses(split: ErrorSplit, plan: CalibrationPlan) -> int:
    """Smallest number of poses whose measurement rows can identify every identifiable combination."""
    return math.ceil(identifiable_count(split, plan)[0] / plan.rows_per_pose)


def check_plan(plan: CalibrationPlan, split: ErrorSplit, *, measurement: str | None = None,
               noise_mm: float | None = None, registration: bool | None = None, where: str = "plan") -> None:
    """Refuse a plan that does not fit the allocation (module docstring); one message per fault.

    Parameters
    ----------
    plan : CalibrationPlan
    split : ErrorSplit
        Of the allocation's error model (its robot is the allocation's robot).
    measurement, noise_mm, registration : optional
        What the caller asks for; each given one must agree with the plan's setting.
    where : str
        Named in the messages (the keyword argument or flag that carried the plan).
    """
    if not isinstance(plan, CalibrationPlan):
        raise TolallocError(f"{where}: expected a CalibrationPlan (tolalloc.calibration.read_plan or make_plan), got "
                            f"{type(plan).__name__}.")
    robot = split.model.robot
    if plan.robot is not None and plan.robot != robot.name:
        raise TolallocError(f"{where}: the plan was written for the robot {plan.robot!r}, but the allocation is for "
                            f"{robot.name!r}; design a plan for this robot (`tolalloc calplan {robot.name} "
                            "--n-poses N --out PLAN.csv`).")
    if plan.q.ndim != 2 or plan.q.shape[1] != robot.n_joints:
        raise TolallocError(f"{where}: the plan's poses have {plan.q.shape[-1]} joint values each, but "
                            f"{robot.name} has {robot.n_joints} joints; it was written for another robot.")
    if plan.n_poses:
        robot.check_q(plan.q, f"{where} (poses of the plan)")
    for key, want in (("measurement", measurement), ("noise_mm", noise_mm), ("registration", registration)):
        have = getattr(plan, key)
        if want is not None and (have != want if key != "noise_mm" else not np.isclose(have, float(want))):
            raise TolallocError(f"{where}: the plan's header says {key} = {_fmt(have)}, but {key}={_fmt(want)} was "
                                f"asked for; use a plan written with {key} = {_fmt(want)}, or drop the {key} argument "
                                "to use the plan's.")
    if plan.estimate is not None:
        raise TolallocError(f"{where}: the allocation needs a plan that estimates every systematic parameter "
                            f"(estimate = all); its header lists {' '.join(plan.estimate)}.")
    total, n_model, n_nui = identifiable_count(split, plan)
    need = math.ceil(total / plan.rows_per_pose)
    if plan.n_poses < need:
        nui = f" and {n_nui} of the tracker registration and tool offset" if n_nui else ""
        raise TolallocError(f"{where}: {plan.n_poses} {plan.measurement} measurement pose(s) give "
                            f"{plan.n_poses * plan.rows_per_pose} measurement rows, fewer than the {total} parameter "
                            f"combinations a calibration of {robot.name} must identify ({n_model} of the error "
                            f"model{nui}); give a plan of at least {need} poses (`tolalloc calplan {robot.name} "
                            f"--n-poses {need} --out PLAN.csv`).")


def _fmt(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return f"{v:g}" if isinstance(v, float) else str(v)
