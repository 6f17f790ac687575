"""Blind cases from the independent physics of :mod:`physics`, and the truth-aware reference fit.

A case: random geometric errors on every parameter of the robot's description (sigma 0.3 mm / 0.05 deg
each; DH d, a, alpha, theta, beta for the UR10, link vectors and joint axis directions/positions/zeros for
the tool_changer), a random tracker frame (uniform rotation, translation within +-3 m), a probe offset of
50-200 mm, tracker noise sigma U(0.02, 0.05) mm per coordinate, in a quarter of the cases gross outliers
(2 % of the poses, at least one, 1-3 mm), random poses within the joint limits in time order (30 s apart),
a payload of 0-5 kg (constant per case), an ambient temperature log and one effect, two effects ("a+b",
each half the magnitude) or none. The effect's amplitudes are scaled so that it moves the probe by an
RMS ``U(0.15, 0.6)`` mm before calibration.

The **reference fit** knows the truth's structure but not its values: the diagnosis's calibration model
(registration, probe offset, identifiable geometry) plus the first-order displacement columns of the true
effect's own amplitudes (finite differences of :func:`physics.walk`, with the true lag, harmonic order,
backlash side rule and mass model), fitted on the training poses and scored on the test poses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from physics import _perturbed_ops, describe, gravity_torque, motion_temperatures, periodic_bumps, trans_links, walk

DT_S = 30.0


@dataclass
class Case:
    """One generated case: the measurement table, the truth, and the reference's effect columns."""

    frame: pd.DataFrame
    label: str
    magnitude_mm: float
    noise_mm: float
    outliers: int
    detail: str
    ref_B: np.ndarray  # (P, 3, M) [mm per unit amplitude], base frame, at the nominal geometry
    split: str = "random"  # "time": the first 75 % of the poses train (wrist-still sessions)
    variant: str = ""


def _limits(robot):
    return np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi)


class _Physics:
    """Draws of one case's effect physics; ``state(amps)`` gives (dq, growth, sag, guide) for amplitude vectors."""

    def __init__(self, robot, desc, effects, q, direction, temp, time_s, rng, t_mm, payload_kg, variant=""):
        self.payload, self.variant, self.guide = payload_kg, variant, None
        self.robot, self.desc, self.effects, self.q, self.t = robot, desc, effects, q, t_mm
        self.n = robot.n_joints
        ops0 = _perturbed_ops(desc, np.zeros(len(desc.geo_names)))
        x, joints, segs = walk(ops0, q, desc.tool_mm + t_mm)
        self.n_seg = len(segs)
        masses = {"rod_kg_per_m": rng.uniform(6, 14, len(segs)), "motor_kg": rng.uniform(1.5, 5, self.n),
                  "payload_kg": float(self.payload)}
        self.tau = gravity_torque(joints, segs, x, masses)
        self.details, self.size = [], {}
        if "backlash" in effects and variant == "preload":
            band = rng.uniform(0.05, 0.25)
            span = np.maximum(np.ptp(self.tau, axis=0), 1e-9)
            self.side = np.where(np.abs(self.tau) > band * span, np.sign(self.tau), direction)
            self.details.append(f"backlash friction band {band:.0%} of the torque range")
        elif "backlash" in effects:
            self.side_mode = rng.choice(["approach", "gravity"])
            if self.side_mode == "approach":
                self.side = direction
            else:
                span = np.maximum(np.ptp(self.tau, axis=0), 1e-9)
                self.side = np.tanh(self.tau / (0.02 * span))
            self.details.append(f"backlash side={self.side_mode}")
        if "transmission" in effects and variant == "bumps":
            arm = np.flatnonzero(robot.revolute_mask)[:3]
            nb = rng.integers(2, 5, len(arm))
            self.bump_joints = np.repeat(arm, nb)
            self.bump_c = rng.uniform(-np.pi, np.pi, len(self.bump_joints))
            self.bump_k = rng.uniform(20, 60, len(self.bump_joints))
            self.details.append(f"periodic bumps on joints {', '.join(str(j + 1) for j in arm)} "
                                f"(kappa {self.bump_k.min():.0f}-{self.bump_k.max():.0f})")
        elif "transmission" in effects:
            self.k = int(rng.choice([1, 2], p=[0.6, 0.4]))
            self.details.append(f"transmission {self.k}x/rev")
        if "thermal" in effects and variant == "motion":
            power = rng.uniform(0.5, 2.0, self.n)
            tau_m, tau_l = 60 * rng.uniform(10, 30), 60 * rng.uniform(20, 60)
            links = trans_links(ops0)  # link (joints before it) of every translation of the walk
            n_links = max(links) + 1
            ends = [[j for j in (k - 1, k) if 0 <= j < self.n] for k in range(n_links)]
            T = motion_temperatures(q, time_s, power, tau_m, tau_l, ends)
            alpha = rng.uniform(0.3, 1.0, n_links)
            self.dT_ops = (T * alpha)[:, links] / max(np.abs(T * alpha).max(), 1e-12) * 5.0
            self.details.append(f"thermal from motion history tau_motor={tau_m / 60:.0f} min, "
                                f"tau_link={tau_l / 60:.0f} min")
        elif "thermal" in effects:
            self.th_mode = rng.choice(["lag", "warmup"])
            tau_s = 60 * rng.uniform(15, 45)
            if self.th_mode == "lag":
                eff = np.empty_like(temp)
                eff[0] = temp[0]
                a = 1 - np.exp(-DT_S / tau_s)
                for i in range(1, len(temp)):
                    eff[i] = eff[i - 1] + a * (temp[i] - eff[i - 1])
                self.dT = eff - temp[0]
            else:
                self.dT = 5.0 * (1 - np.exp(-time_s / tau_s))
            self.details.append(f"thermal {self.th_mode} tau={tau_s / 60:.0f} min")
        if "link_deflection" in effects and variant == "guide":
            self._guide_shape(joints, x, q, rng)
        elif "link_deflection" in effects:
            self.r = rng.uniform(0.5, 2.0)
            self.details.append(f"beam sag r={self.r:.2f}")
        self.sag_mask = np.array([np.linalg.norm(b - a, axis=1).max() >= 250 for a, b, _ in segs])

    def _guide_shape(self, joints, x, q, rng):
        """Rotation vector per unit compliance of the telescopic stage in its guide (physics module docstring)."""
        j = next(k for k, (_, _, revo) in enumerate(joints) if not revo)
        pg, u, _ = joints[j]
        g = np.array([0.0, 0.0, -1.0])
        M = np.cross((x - pg) / 1000.0, 100.0 * 9.81 * g)  # 100 kg at the probe's lever arm [N m]
        M = M - np.einsum("pi,pi->p", M, u)[:, None] * u  # bending only
        m = np.linalg.norm(M, axis=1)
        hi = self.robot.upper[j]
        b0 = rng.uniform(80.0, 150.0)
        b = b0 + (hi - q[:, j])  # bearing overlap [mm]
        clear = rng.uniform(0.0, 1.0)
        size = m / b ** 2 * b0 ** 2 + clear * np.tanh(m / (0.2 * m.max())) * m.max() * b0 / b
        self.guide_j = j
        self.guide_dir = M / np.maximum(m, 1e-12)[:, None] * size[:, None] / max(size.max(), 1e-12)
        self.details.append(f"telescopic guide b0={b0:.0f} mm, clearance share {clear:.2f}")

    def n_amps(self, e):
        return {"joint_compliance": self.n, "backlash": self.n, "transmission": 2 * self.n, "thermal": 1,
                "link_deflection": self.n_seg}[e]

    def unit_amps(self, e, rng):
        """Random amplitudes with every column of comparable size (before the case's magnitude scaling)."""
        if e == "joint_compliance":
            rms = np.sqrt(np.mean(self.tau ** 2, 0))
            return rng.uniform(0.3, 1, self.n) / np.maximum(rms, 1e-9) * 1e-4 * (rms > 1e-6)  # 0 on unloaded joints
        if e == "backlash":
            return rng.uniform(0.3, 1, self.n) * 1e-4
        if e == "transmission" and self.variant == "bumps":
            return rng.normal(size=len(self.bump_joints)) * 1e-4
        if e == "link_deflection" and self.variant == "guide":
            return np.array([1e-4])
        if e == "transmission":
            a = rng.normal(size=2 * self.n) * 1e-4
            a[np.repeat(~self.robot.revolute_mask, 2)] = 0.0
            return a
        if e == "thermal":
            return np.array([10.0])
        return rng.uniform(0.3, 1, self.n_seg) * self.sag_mask

    def state(self, amps: dict):
        """(dq, growth, sag, guide) of the walk for amplitude vectors ``amps``."""
        P = len(self.q)
        dq, growth, sag, guide = np.zeros((P, self.n)), None, None, None
        for e, a in amps.items():
            if e == "joint_compliance":
                dq += self.tau * a
            elif e == "backlash":
                dq += self.side * a
            elif e == "transmission" and self.variant == "bumps":
                dq += periodic_bumps(self.q, self.bump_c, self.bump_k, a, self.bump_joints)
            elif e == "transmission":
                kq = self.k * self.q
                dq += (np.sin(kq) * a[0::2] + np.cos(kq) * a[1::2]) * self.robot.revolute_mask
            elif e == "thermal" and self.variant == "motion":
                growth = 1e-6 * a[0] * self.dT_ops
            elif e == "thermal":
                growth = 1e-6 * a[0] * self.dT
            elif e == "link_deflection" and self.variant == "guide":
                guide = (self.guide_j, a[0] * self.guide_dir)
            elif e == "link_deflection":
                sag = (a, self.r)
        return dq, growth, sag, guide


def _wrist_still(robot, q, rng):
    """The flange keeps its direction (tool pointing one way; the wrist joints follow the arm), +-0.03 deg."""
    jitter = rng.normal(0, np.deg2rad(0.03), (len(q), 2))
    if robot.name == "ur10":  # wrist 1 cancels shoulder + elbow, wrist 2 at -90 deg: tool down
        q[:, 3] = np.angle(np.exp(1j * (-q[:, 1] - q[:, 2] - np.pi / 2))) + jitter[:, 0]  # within one turn
        q[:, 4] = -np.pi / 2 + jitter[:, 1]
    else:  # tool_changer: joints 2, 3 and 5 turn about x; their sum fixes the flange direction
        q[:, 4] = -q[:, 1] - q[:, 2] + jitter[:, 0]
    return q


def generate(robot, label: str, n_poses: int, rng: np.random.Generator, variant: str = "") -> Case:
    """One blind case (see the module docstring); ``label`` one effect name, ``a+b`` or ``none``.

    ``variant`` (issue 25): ``motion`` (thermal from the motion history), ``guide`` (telescopic-guide
    deflection), ``preload`` (friction-banded backlash), ``bumps`` (periodic bumps), ``outliers`` (2 % gross
    outliers, always), ``wrist_still`` (the first 75 % of the poses -- the training part, split in time -- keep
    the flange direction; the rest are random); ``beam``: the issue-15 physics (a tag only). Without a variant
    the draws are those of the issue-15 cases.
    """
    desc = describe(robot)
    n = robot.n_joints
    effects = [] if label == "none" else label.split("+")
    lo, hi = _limits(robot)
    q = rng.uniform(lo, hi, (n_poses, n))
    if variant == "wrist_still":
        n_still = int(round(0.75 * n_poses))
        q[:n_still] = _wrist_still(robot, q[:n_still], rng)
    direction = np.sign(np.diff(q, axis=0, prepend=q[:1] - rng.choice([-1.0, 1.0], n)))
    direction[direction == 0] = 1.0
    time_s = DT_S * np.arange(n_poses)
    temp = 20.0 + rng.uniform(0.3, 3.0) * (1 - np.exp(-time_s / (60 * rng.uniform(20, 90)))) + rng.normal(0, 0.03, n_poses)
    geo = rng.normal(size=len(desc.geo_scale)) * desc.geo_scale
    ops = _perturbed_ops(desc, geo)
    R = Rotation.random(random_state=rng).as_matrix()
    p = rng.uniform(-3000, 3000, 3)
    t = rng.normal(size=3)
    t *= rng.uniform(50, 200) / np.linalg.norm(t)
    payload = float(rng.uniform(0, 5))
    phys = _Physics(robot, desc, effects, q, direction, temp, time_s, rng, t, payload, variant)
    mag = float(rng.uniform(0.15, 0.6))
    x0 = walk(ops, q, desc.tool_mm + t)[0]
    amps = {}
    for e in effects:
        a = phys.unit_amps(e, rng)
        dq, growth, sag, guide = phys.state({e: a})
        x1 = walk(ops, q + dq, desc.tool_mm + t, growth=growth, sag=sag, guide=guide)[0]
        r = np.sqrt(np.mean(np.sum((x1 - x0) ** 2, axis=1)))
        amps[e] = a * (mag / len(effects)) / max(r, 1e-12)
    dq, growth, sag, guide = phys.state(amps)
    x = walk(ops, q + dq, desc.tool_mm + t, growth=growth, sag=sag, guide=guide)[0]
    noise = float(rng.uniform(0.02, 0.05))
    xyz = x @ R.T + p + rng.normal(0, noise, x.shape)
    n_out = 0
    if rng.random() < 0.25 or variant == "outliers":
        n_out = max(1 if variant != "outliers" else 2, int(round(0.02 * n_poses)))
        idx = rng.choice(n_poses, n_out, replace=False)
        v = rng.normal(size=(n_out, 3))
        xyz[idx] += v / np.linalg.norm(v, axis=1)[:, None] * rng.uniform(1, 3, (n_out, 1))
    ref_B = _reference_columns(phys, desc, q, t, amps)
    cols = {f"q{j + 1}": robot.q_to_interface(q)[:, j] for j in range(n)}
    cols.update({"x_mm": xyz[:, 0], "y_mm": xyz[:, 1], "z_mm": xyz[:, 2], "temperature_c": temp})
    cols.update({f"dir{j + 1}": direction[:, j] for j in range(n)})
    cols.update({"payload_kg": np.full(n_poses, payload), "time_s": time_s})
    detail = "; ".join(phys.details + ([variant.replace("_", " ")] if variant in ("wrist_still", "outliers") else []))
    return Case(pd.DataFrame(cols), label, mag if effects else 0.0, noise, n_out, detail, ref_B,
                "time" if variant == "wrist_still" else "random", variant)


def _reference_columns(phys, desc, q, t, amps) -> np.ndarray:
    """Displacement per unit of every true amplitude (finite differences at the nominal geometry), (P, 3, M)."""
    ops0 = _perturbed_ops(desc, np.zeros(len(desc.geo_names)))
    x0 = walk(ops0, q, desc.tool_mm + t)[0]
    cols = []
    for e, a in amps.items():
        nz = np.abs(a[a != 0])
        for k in range(len(a)):
            if a[k] == 0 and e != "transmission":
                continue
            # step: the amplitude's own size (one global step let a huge amplitude on a joint without load --
            # the base joint's compliance -- make the other columns' finite differences nonlinear garbage)
            ek = np.zeros_like(a)
            ek[k] = abs(a[k]) if a[k] != 0 else (np.median(nz) if len(nz) else 1.0)
            h = ek[k]
            dq, growth, sag, guide = phys.state({e: ek})
            x1 = walk(ops0, q + dq, desc.tool_mm + t, growth=growth, sag=sag, guide=guide)[0]
            if np.abs(x1 - x0).max() > 1e-9:
                cols.append((x1 - x0) / h)
    return np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))
