"""An independent fleet generator for the fleet study: UR10-like robots built with known shifts and spreads of their
Denavit-Hartenberg parameters, measured by a laser tracker on one pose plan.

Shares no code with tolalloc's fit: its own standard-DH forward kinematics (numpy only), its own parameter errors
(``a``, ``d``, ``alpha``, ``theta`` offset per joint, plus a ``beta`` tilt about the joint's y axis -- Hayati's
parameter, for the parallel axes DH cannot perturb smoothly), its own tracker frames and noise. The nominal table is
the UR10's (``../shared/data/ipa-ur10/README.md``, the same one tolalloc's ur10 robot file holds); the tool frame is
the flange (DH frame 6) and the measured target sits at a fixed probe offset on it (one fixture for the whole fleet).

``truth_map`` gives the generator's own first-order Jacobian of the target in its parameters (central finite
differences of its forward kinematics): the study maps the known per-parameter shifts and spreads through it onto the
identifiable combinations the diagnosis estimates.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: Nominal standard DH table of the UR10 [mm, rad]: d, a, alpha per joint.
D_MM = np.array([127.3, 0.0, 0.0, 163.941, 115.7, 92.2])
A_MM = np.array([0.0, -612.0, -572.3, 0.0, 0.0, 0.0])
ALPHA = np.array([np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0])
#: Joint zero of tolalloc's ur10 file matches theta = q (no offsets in the nominal table).
KINDS = ("d", "a", "alpha", "theta", "beta")
UNITS = {"d": "mm", "a": "mm", "alpha": "rad", "theta": "rad", "beta": "rad"}
PROBE_MM = np.array([0.0, 60.0, 80.0])  # target offset on the flange (DH frame 6)


def names() -> list[str]:
    return [f"{k}{j + 1}" for j in range(6) for k in KINDS]


def _rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def target_points(q: np.ndarray, err: np.ndarray, probe_mm=PROBE_MM) -> np.ndarray:
    """Target positions in the base frame [mm], shape (P, 3), of a robot with parameter errors ``err`` (30,)."""
    e = np.asarray(err, float).reshape(6, 5)  # per joint: d, a, alpha, theta, beta
    out = np.empty((len(q), 3))
    for p, qp in enumerate(np.atleast_2d(q)):
        R, x = np.eye(3), np.zeros(3)
        for j in range(6):
            th = qp[j] + e[j, 3]
            c, s = np.cos(th), np.sin(th)
            Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            # T_j = Rz(theta) Tz(d) Tx(a) Rx(alpha) Ry(beta)
            x = x + R @ (Rz @ np.array([A_MM[j] + e[j, 1], 0.0, D_MM[j] + e[j, 0]]))
            R = R @ Rz @ _rx(ALPHA[j] + e[j, 2]) @ _ry(e[j, 4])
        out[p] = x + R @ probe_mm
    return out


def truth_map(q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """d(target points) / d(errors) at zero error, shape (3P, 30) [mm per mm or rad] (central differences)."""
    cols = []
    for k in range(30):
        e = np.zeros(30)
        e[k] = h
        cols.append(((target_points(q, e) - target_points(q, -e)) / (2 * h)).ravel())
    return np.array(cols).T


def pose_plan(n: int, seed: int = 0) -> np.ndarray:
    """One calibration pose plan for the whole fleet [rad], shape (n, 6): joints spread over +-170 deg (joint 2 over
    -170..-10 deg: the arm above the table)."""
    rng = np.random.default_rng(seed)
    q = rng.uniform(np.deg2rad(-170), np.deg2rad(170), (n, 6))
    q[:, 1] = rng.uniform(np.deg2rad(-170), np.deg2rad(-10), n)
    return q


def fleet_truth(seed: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Known per-parameter shift and spread [mm, rad] of the factory, (30,) each: spreads 0.02-0.1 mm / 0.0002-0.0006
    rad, shifts between -1.5 and +1.5 spreads on half of the parameters (a drifted process), 0 on the others."""
    rng = np.random.default_rng(seed)
    kinds = np.array([KINDS[k % 5] for k in range(30)])
    spread = np.where(np.isin(kinds, ("d", "a")), rng.uniform(0.02, 0.1, 30), rng.uniform(2e-4, 6e-4, 30))
    shifted = rng.uniform(size=30) < 0.5
    shift = np.where(shifted, rng.uniform(-1.5, 1.5, 30) * spread, 0.0)
    return shift, spread


def measure(q: np.ndarray, err: np.ndarray, rng, noise_mm: float = 0.01) -> pd.DataFrame:
    """A tracker measurement table of a robot: ``q1_deg..q6_deg, x_mm, y_mm, z_mm`` in a random tracker frame."""
    x = target_points(q, err)
    a, b, c = rng.uniform(-np.pi, np.pi, 3)
    R = _rx(a) @ _ry(b) @ _rx(c)
    p = rng.uniform(-2000, 2000, 3)
    xyz = x @ R.T + p + rng.normal(0, noise_mm, x.shape)
    df = pd.DataFrame(np.rad2deg(q), columns=[f"q{j + 1}_deg" for j in range(6)])
    df[["x_mm", "y_mm", "z_mm"]] = xyz
    return df


def make_fleet(n_robots: int, n_poses: int, seed: int = 2, noise_mm: float = 0.01) -> dict:
    """``{"q", "frames": [DataFrame per robot], "errors": (N, 30), "shift", "spread"}``."""
    shift, spread = fleet_truth()
    q = pose_plan(n_poses)
    rng = np.random.default_rng(seed)
    errors = shift + spread * rng.normal(size=(n_robots, 30))
    frames = [measure(q, e, rng, noise_mm) for e in errors]
    return {"q": q, "frames": frames, "errors": errors, "shift": shift, "spread": spread}
