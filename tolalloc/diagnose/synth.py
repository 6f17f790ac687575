"""Synthetic laser-tracker measurement sets with a withheld effect, for blind checks of the diagnosis.

A case is: random geometric errors (the robot's default sigma set, exact perturbed chain), an arbitrary
tracker frame (uniform random rotation, translation within +-3 m), a target offset of 50-200 mm on the
flange, isotropic tracker noise ``sigma ~ U(0.01, 0.03)`` mm and one effect of
:data:`tolalloc.diagnose.effects.EFFECTS` -- or ``none`` -- whose parameters are drawn at random and scaled
so that the effect displaces the target by an RMS ``magnitude_mm ~ U(0.15, 0.6)`` mm (before calibration).
Joint-type effects and thermal growth are applied exactly in the forward kinematics; link deflection
through its first-order displacement.

The table always has the same columns whatever the effect: ``q1..qN, x_mm, y_mm, z_mm, temperature_c,
dir1..dirN, payload_kg, time_s`` (temperature drifts by 2-8 K over the run; ``dir`` is the sign of each
joint's motion from the previous pose; payload 0). Only the data's shape reveals the effect.

Role: a **self-consistency** check only. Each effect is drawn from the default variant of the very basis
:mod:`tolalloc.diagnose.effects` fits, so a high identification rate here says the selection machinery works,
not that the physics is right. The blind benchmark (issue 15) uses the independent generator of
``studies/sim2real_blind`` (own kinematics, own effect physics, geometric errors on every DH/axis parameter).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel import build_error_model
from tolalloc.robot.kinematics import fk_poe
from tolalloc.robot.model import Robot
from tolalloc.diagnose.effects import EFFECTS, effect_basis, joint_effect_dq, target_points
from tolalloc.diagnose.measurements import Measurements

__all__ = ["SynthCase", "generate", "split_frame", "LABELS"]

LABELS = (*EFFECTS, "none")


@dataclass(frozen=True, eq=False)
class SynthCase:
    """A generated measurement table and what was put into it (never shown to the diagnosis).

    Attributes
    ----------
    frame : DataFrame   the measurement table (interface units)
    effect : str        the withheld label
    magnitude_mm : float  RMS target displacement of the effect before calibration
    noise_mm : float
    truth : dict        geometric values, registration, offset, effect parameters
    """

    frame: pd.DataFrame
    effect: str
    magnitude_mm: float
    noise_mm: float
    truth: dict


def _random_poses(robot: Robot, n: int, rng) -> np.ndarray:
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    return rng.uniform(lo, hi, (n, robot.n_joints))


def generate(robot: Robot, effect: str, n_poses: int = 200, rng: np.random.Generator | None = None, *,
             noise_mm: float | None = None, magnitude_mm: float | None = None) -> SynthCase:
    """Generate one synthetic measurement set.

    Parameters
    ----------
    robot : Robot
    effect : str, one of :data:`LABELS`
    n_poses : int
    rng : numpy Generator
    noise_mm, magnitude_mm : float, optional
        Fixed values instead of the random draws (see the module docstring).
    """
    if effect not in LABELS:
        raise TolallocError(f"effect: expected one of {', '.join(LABELS)}, got {effect!r}.")
    if isinstance(n_poses, bool) or not isinstance(n_poses, (int, np.integer)) or n_poses < 2:
        raise TolallocError(f"n_poses: expected a whole number of poses >= 2 (a measurement set to split into "
                            f"training and test rows), got {n_poses!r}.")
    rng = rng or np.random.default_rng()
    n = robot.n_joints
    noise = float(rng.uniform(0.01, 0.03) if noise_mm is None else noise_mm)
    mag = float(rng.uniform(0.15, 0.6) if magnitude_mm is None else magnitude_mm)
    q = _random_poses(robot, n_poses, rng)
    direction = np.sign(np.diff(q, axis=0, prepend=q[:1] - rng.choice([-1.0, 1.0], n)))
    direction[direction == 0] = 1.0
    time_s = 30.0 * np.arange(n_poses)
    drift = rng.uniform(2.0, 8.0)
    temperature = 20.0 + drift * (1 - np.exp(-time_s / (0.4 * time_s[-1] + 1))) + rng.normal(0, 0.05, n_poses)
    model = build_error_model(robot)
    values = np.repeat(model.sample(1, rng), n_poses, axis=0)
    R = Rotation.random(random_state=rng).as_matrix()
    p = rng.uniform(-3000, 3000, 3)
    t = rng.normal(size=3)
    t *= rng.uniform(50, 200) / np.linalg.norm(t)
    meas = Measurements(q, np.zeros((n_poses, 3)), temperature, direction, np.zeros(n_poses), time_s)
    dq = np.zeros((n_poses, n))
    extra = np.zeros((n_poses, 3))
    beta = np.zeros(0)
    if effect != "none":
        basis = effect_basis(effect, robot, meas, t, {"temperature_c": float(temperature.mean())})
        M = basis.B.shape[-1]
        if effect == "transmission":
            beta = rng.normal(size=M)
        else:
            beta = rng.uniform(0.3, 1.0, M)
        # equalise the columns' typical contributions so no single one dominates by units alone
        col_rms = np.sqrt(np.mean(np.sum(basis.B ** 2, axis=1), axis=0))
        beta = beta / np.where(col_rms > 0, col_rms, 1.0)
        rms = float(np.sqrt(np.mean(np.sum((basis.B @ beta) ** 2, axis=1))))
        if not rms > 0:
            raise TolallocError(f"effect: {effect!r} moves no target point of robot {robot.name!r} at these poses "
                                f"(its basis is zero, e.g. no link it can bend or no joint it can act on); "
                                f"generate another effect (one of {', '.join(LABELS)}).")
        scale = mag / rms
        beta = beta * scale
        if effect in ("joint_compliance", "backlash", "transmission"):
            A, _ = joint_effect_dq(effect, robot, q, direction)
            dq = A @ beta
        elif effect == "thermal":
            dT = temperature - temperature.mean()
            for k, prm in enumerate(model.params):
                if prm.kind == "link_length":
                    L = robot.links[[lk.name for lk in robot.links].index(prm.element)].length_mm
                    values[:, k] += beta[0] * 1e-6 * dT * L
        else:  # link_deflection, first order
            extra = basis.B @ beta
    screws, home, dq0 = model.perturbed_chain(values)
    T = fk_poe(screws, home, q + dq0 + dq)
    x = T[:, :3, 3] + T[:, :3, :3] @ t + extra
    xyz = x @ R.T + p + rng.normal(0, noise, (n_poses, 3))
    cols = {f"q{j + 1}": robot.q_to_interface(q)[:, j] for j in range(n)}
    cols.update({"x_mm": xyz[:, 0], "y_mm": xyz[:, 1], "z_mm": xyz[:, 2], "temperature_c": temperature})
    cols.update({f"dir{j + 1}": direction[:, j] for j in range(n)})
    cols.update({"payload_kg": np.zeros(n_poses), "time_s": time_s})
    truth = {"geometric": values[0], "R": R, "p_mm": p, "t_mm": t, "beta": beta,
             "nominal_points_mm": target_points(robot, q, t)}
    return SynthCase(pd.DataFrame(cols), effect, mag if effect != "none" else 0.0, noise, truth)


def split_frame(df: pd.DataFrame, test_fraction: float, rng: np.random.Generator):
    """Random split of a measurement table into (train, test), row order kept within each."""
    idx = rng.permutation(len(df))
    n_test = int(round(test_fraction * len(df)))
    test = np.sort(idx[:n_test])
    train = np.sort(idx[n_test:])
    return df.iloc[train].reset_index(drop=True), df.iloc[test].reset_index(drop=True)
