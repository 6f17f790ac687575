"""An independent physical simulation of a UR10-class arm's bought parts (its own code: no tolalloc.physics,
no tolalloc.errormodel, no tolalloc kinematics).

What it shares with the library is the *input*: the UR10 robot file (DH table, masses, link sections, payload,
mount, read here with tomllib), the catalogue figures of the chosen parts, and the modelling assumptions that are
part of the model's definition (the 70/15/15 share of a gear's transmission accuracy at orders 1, N, 2N; the
spreads of stiffness 10 %, thermal growth 10 %, bending 10 %, mount 20 %; lost motion by approach direction). What it
computes itself: forward kinematics from the standard DH matrices, the gravity loads by virtual work (central
differences of the masses' potential energy), the catalogue's three-band torque-torsion curve, the sums of sines,
the bearings' rotating eccentricities as rigid displacements after the joint's rotation, the links' thermal growth
as longer DH lengths, bending, torsion and shear of the two arm tubes by quadrature along them, and the
mount's tilt. It draws its own random numbers
and estimates P(|dP| < r) by plain Monte Carlo with a Wilson interval.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
from scipy.stats import norm

G = 9.81
ROBOT_FILE = Path(__file__).resolve().parents[2] / "tolalloc" / "data" / "robots" / "ur10.toml"
SHARES = (0.7, 0.15, 0.15)
SPREAD = {"thermal": 0.1, "beam": 0.1, "mount": 0.2}
SHEAR_FACTOR_TUBE = 0.5
ALUMINIUM = {"E": 70e3, "G": 26e3, "cte": 23.1e-6}  # MPa, MPa, 1/K (the robot file names the material)


def _rz(t):
    c, s = np.cos(t), np.sin(t)
    out = np.zeros(np.shape(t) + (4, 4))
    out[..., 0, 0], out[..., 0, 1], out[..., 1, 0], out[..., 1, 1] = c, -s, s, c
    out[..., 2, 2] = out[..., 3, 3] = 1.0
    return out


def _const(d, a, alpha):
    """Tz(d) Tx(a) Rx(alpha), broadcast over the arrays d, a."""
    d, a = np.broadcast_arrays(np.asarray(d, float), np.asarray(a, float))
    out = np.zeros(d.shape + (4, 4))
    c, s = np.cos(alpha), np.sin(alpha)
    out[..., 0, 0], out[..., 0, 3] = 1.0, a
    out[..., 1, 1], out[..., 1, 2] = c, -s
    out[..., 2, 1], out[..., 2, 2], out[..., 2, 3] = s, c, d
    out[..., 3, 3] = 1.0
    return out


def _small(t, w):
    """Rigid displacements (N, 4, 4): the rotation of rotation vector ``w`` (N, 3) (Rodrigues) and the translation
    ``t`` (N, 3) [mm]."""
    th = np.linalg.norm(w, axis=1)
    k = np.where(th[:, None] > 0, w / np.maximum(th, 1e-300)[:, None], 0.0)
    K = np.zeros((len(w), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 0] = -k[:, 2], k[:, 1], k[:, 2]
    K[:, 1, 2], K[:, 2, 0], K[:, 2, 1] = -k[:, 0], -k[:, 1], k[:, 0]
    R = np.eye(3) + np.sin(th)[:, None, None] * K + (1 - np.cos(th))[:, None, None] * (K @ K)
    out = np.zeros((len(w), 4, 4))
    out[:, :3, :3], out[:, :3, 3], out[:, 3, 3] = R, t, 1.0
    return out


class UR10Sim:
    """The UR10 file's arm with the catalogue parts ``parts`` ``{joint name: {"reducer": Reducer, "encoder": Encoder,
    "bearing": Bearing, "motor": Motor}}`` (figures in SI-mm-rad, as the catalogue gives them)."""

    def __init__(self, parts: dict, conditions, after="none", residual=None):
        data = tomllib.loads(ROBOT_FILE.read_text())
        self.names = [row["name"] for row in data["dh"]]
        self.d = np.array([1000.0 * row.get("d_m", 0.0) for row in data["dh"]])
        self.a = np.array([1000.0 * row.get("a_m", 0.0) for row in data["dh"]])
        self.alpha = np.array([row.get("alpha_rad", 0.0) for row in data["dh"]])
        comp = data["components"]
        self.payload_com = np.array(comp["payload"]["com_mm"], float)
        self.mount_k = float(comp["mount"]["tilt_stiffness_Nm_per_rad"])
        self.sections = {}
        for name, sec in comp["links"].items():
            D, t = sec["outer_diameter_mm"], sec["wall_mm"]
            di = D - 2 * t
            self.sections[name] = (np.pi / 64 * (D ** 4 - di ** 4), np.pi / 4 * (D ** 2 - di ** 2))
        body = {"d1": 1, "a2": 2, "a3": 3, "d4": 4, "d5": 5, "d6": 6}
        T0 = self.frames(np.zeros((1, 6)))
        self.masses = []  # (body, kg, com in the body's frame)
        for m in data["masses"]:
            b = body[m["link"]]
            local = np.linalg.solve(T0[b][0], np.append(m["com_mm"], 1.0))
            self.masses.append((b, m["mass_kg"], local))
        self.parts, self.cond = parts, conditions
        f = dict.fromkeys(("compliance", "transmission", "encoder", "bearing", "thermal", "beam", "mount"), 1.0)
        if after == "compensation":
            f = {e: (residual.get(e, 1.0) if isinstance(residual, dict) else residual) for e in f}
        self.f = f

    # ---- kinematics -------------------------------------------------------------------------------------------
    def frames(self, q, dq=None, scale=None, bearing=None) -> list:
        """DH frames 0..6 (each (N, 4, 4)) at joint values ``q + dq``, DH lengths of a2/a3 times ``scale`` (N, 2),
        a rigid displacement ``bearing[j]`` (N, 4, 4) after joint j's rotation."""
        q = np.atleast_2d(q)
        N = len(q)
        th = q + (0.0 if dq is None else dq)
        a = np.broadcast_to(self.a, (N, 6)).copy()
        if scale is not None:
            a[:, 1] *= scale[:, 0]
            a[:, 2] *= scale[:, 1]
        T = [np.broadcast_to(np.eye(4), (N, 4, 4))]
        for j in range(6):
            A = _rz(th[:, j])
            if bearing is not None and j in bearing:
                A = A @ bearing[j]
            T.append(T[-1] @ A @ _const(self.d[j], a[:, j], self.alpha[j]))
        return T

    def mass_points(self, q) -> list:
        """``(kg, position (N, 3))`` of the arm's masses and the payload (last, 1 kg placeholder) at ``q``."""
        T = self.frames(q)
        out = [(kg, (T[b] @ c)[:, :3]) for b, kg, c in self.masses]
        return out, (T[6] @ np.append(self.payload_com, 1.0))[:, :3], T

    def loads(self, q, payload_kg) -> np.ndarray:
        """Gravity loads on the joints by virtual work, shape (N, 6) [N m]: ``Q_j = sum F_i . dp_i/dq_j``."""
        q = np.atleast_2d(q)
        h = 1e-6
        out = np.zeros(q.shape)
        for j in range(6):
            e = np.zeros(6)
            e[j] = h
            Vp, Vm = self._potential(q + e, payload_kg), self._potential(q - e, payload_kg)
            out[:, j] = -(Vp - Vm) / (2 * h)
        return out

    def _potential(self, q, payload_kg):
        pts, pay, _ = self.mass_points(q)
        V = sum(kg * G * p[:, 2] / 1000.0 for kg, p in pts)
        return V + payload_kg * G * pay[:, 2] / 1000.0

    # ---- the parts ---------------------------------------------------------------------------------------------
    @staticmethod
    def _curve(red, tau):
        t, s = np.abs(tau), np.sign(tau)
        if len(red.stiffness) == 1:
            return tau / red.stiffness[0]
        (k1, k2, k3), (t1, t2) = red.stiffness, red.torque_bands
        return s * np.where(t <= t1, t / k1, np.where(t <= t2, t1 / k1 + (t - t1) / k2,
                                                     t1 / k1 + (t2 - t1) / k2 + (t - t2) / k3))

    def _sine(self, q, orders, amps, rng):
        ph = rng.uniform(0, 2 * np.pi, (len(q), len(orders)))
        return np.sum(np.array(amps) * np.sin(np.outer(q, orders) + ph), axis=1)

    def joint_offsets(self, q, tau, rng) -> np.ndarray:
        """Drawn joint offsets (N, 6) [rad] of every joint."""
        N = len(q)
        out = np.zeros((N, 6))
        for j, nm in enumerate(self.names):
            p = self.parts.get(nm, {})
            red, enc = p.get("reducer"), p.get("encoder")
            loop_motor = enc is None or enc.side == "motor"
            if red is not None and loop_motor:
                k = np.maximum(1 + (red.stiffness_sd or 0) * rng.standard_normal(N), 0.5)
                out[:, j] += self.f["compliance"] * self._curve(red, tau[:, j]) / k
                out[:, j] += rng.choice([-0.5, 0.5], N) * (red.lost_motion or 0.0)
                amps = 0.5 * (red.transmission_accuracy or 0.0) * np.array(SHARES)
                out[:, j] += self.f["transmission"] * self._sine(q[:, j], [1, red.ratio, 2 * red.ratio], amps, rng)
                rep = red.repeatability or 0.0
                out[:, j] += rng.uniform(-rep, rep, N)
            if enc is not None:
                if enc.side == "motor":
                    e = self._sine(q[:, j], [red.ratio], [enc.accuracy / 2 / red.ratio], rng)
                else:
                    e = self._sine(q[:, j], [1], [enc.accuracy / 2], rng)
                    if enc.eccentricity:
                        e = e + self._sine(q[:, j], [1], [enc.eccentricity / enc.scale_radius_mm], rng)
                out[:, j] += self.f["encoder"] * e
        return out

    def bearings(self, N, rng) -> dict:
        """Drawn bearing displacements ``{joint: (N, 4, 4)}``: the body's shift and tilt about the joint point."""
        out = {}
        for j, nm in enumerate(self.names):
            b = self.parts.get(nm, {}).get("bearing")
            if b is None:
                continue
            eps = b.radial_runout / 2
            ph = rng.uniform(0, 2 * np.pi, (N, 2))
            e1 = eps * np.stack([np.cos(ph[:, 0]), np.sin(ph[:, 0])], 1)
            e2 = eps * np.stack([np.cos(ph[:, 1]), np.sin(ph[:, 1])], 1)
            t, dd = (e1 + e2) / 2, (e2 - e1) / b.span_mm
            f = self.f["bearing"]
            out[j] = _small(f * np.column_stack([t, np.zeros(N)]),
                            f * np.column_stack([-dd[:, 1], dd[:, 0], np.zeros(N)]))
        return out

    def link_temperatures(self, tau, ambient_c) -> np.ndarray:
        """Temperature of the tubes a2 and a3 above the reference, shape (N, 2) [K]."""
        rise = np.zeros(tau.shape)
        for j, nm in enumerate(self.names):
            p = self.parts.get(nm, {})
            m, red = p.get("motor"), p.get("reducer")
            if m is None or red is None:
                continue
            cur = tau[:, j] / (red.ratio * m.torque_constant_Nm_per_A)    # rms phase current
            r_phase = m.winding_resistance_ohm / 2.0                         # star winding: half the line-to-line
            rise[:, j] = m.thermal_resistance_K_per_W * self.cond.duty * 3.0 * r_phase * cur ** 2
            rise[:, j] *= m.link_coupling or 0.0
        base = ambient_c - self.cond.reference_c
        return np.column_stack([base + (rise[:, 1] + rise[:, 2]) / 2, base + (rise[:, 2] + rise[:, 3]) / 2])

    def bending(self, q, payload_kg, nodes: int = 2000) -> np.ndarray:
        """Tip displacement (N, 3) [mm] of the two arm tubes as cantilevers from their proximal joint: every mass the
        tube carries (on the tube, beyond its section, or distal in the chain) and the payload as a point load where
        it sits; each section bends (1/EI) and twists (1/GJ, J = 2 I of a round tube) under the moment of the loads it
        carries, and shears (1/kGA) under their force across it; the distal arm turns rigidly with the section. By
        numerical quadrature along the tube (midpoint rule on ``nodes`` sections)."""
        pts, pay, T = self.mass_points(q)
        tip = T[6][:, :3, 3]
        out = np.zeros_like(tip)
        down = np.array([0.0, 0.0, -G])
        for (j, k, link) in ((1, 2, "a2"), (2, 3, "a3")):
            start, end = T[j][:, :3, 3], T[k][:, :3, 3]
            Ln = np.linalg.norm(end - start, axis=1)
            e = (end - start) / np.maximum(Ln, 1e-9)[:, None]
            I, A = self.sections[link]
            EI, GJ, GA = ALUMINIUM["E"] * I, ALUMINIUM["G"] * 2 * I, SHEAR_FACTOR_TUBE * ALUMINIUM["G"] * A
            loads = [(kg, p, b == k) for (b, kg, _), (_, p) in zip(self.masses, pts) if b >= k]
            loads.append((payload_kg, pay, False))
            for i in range(len(tip)):
                s = (np.arange(nodes) + 0.5) / nodes * Ln[i]
                x = start[i] + s[:, None] * e[i]  # (nodes, 3) section centres
                M, F = np.zeros((nodes, 3)), np.zeros((nodes, 3))
                for kg, p, on_tube in loads:
                    f = kg * down
                    carried = ((p[i] - start[i]) @ e[i] > s) if on_tube else np.ones(nodes, bool)
                    M += carried[:, None] * np.cross(p[i] - x, f)
                    F += carried[:, None] * f
                axial = M @ e[i]
                kappa = (M - axial[:, None] * e[i]) / EI + axial[:, None] * e[i] / GJ  # (nodes, 3) [1/mm]
                F_perp = F - (F @ e[i])[:, None] * e[i]
                ds = Ln[i] / nodes
                out[i] += (np.cross(kappa, tip[i] - x).sum(axis=0) + F_perp.sum(axis=0) / GA) * ds
        return out

    def tilt(self, q, payload_kg) -> np.ndarray:
        """Tip displacement (N, 3) [mm] of the mount tilting under the moment of the moving masses and payload."""
        pts, pay, T = self.mass_points(q)
        Fz = np.array([0.0, 0.0, -G])
        M = sum(np.cross(p / 1000.0, kg * Fz) for kg, p in pts) + np.cross(pay / 1000.0, payload_kg * Fz)
        M[:, 2] = 0.0
        return np.cross(M / self.mount_k, T[6][:, :3, 3])

    # ---- Monte Carlo ---------------------------------------------------------------------------------------------
    def errors(self, q, payload_kg, ambient_c, n: int, seed: int) -> np.ndarray:
        """``n`` drawn tool-position errors (n, 3) [mm] at one pose ``q`` (6,) [rad]."""
        rng = np.random.default_rng(seed)
        Q = np.repeat(np.atleast_2d(q), n, axis=0)
        tau = self.loads(Q[:1], payload_kg)
        tau = np.repeat(tau, n, axis=0)
        dq = self.joint_offsets(Q, tau, rng)
        dT = self.link_temperatures(tau[:1], ambient_c)[0]
        lengths = np.abs(self.a[1:3])
        grow = self.f["thermal"] * ALUMINIUM["cte"] * dT * lengths * (1 + SPREAD["thermal"] * rng.standard_normal((n, 2)))
        scale = 1 + grow / lengths
        T = self.frames(Q, dq, scale, self.bearings(n, rng))
        nominal = self.frames(Q[:1])[6][0, :3, 3]
        direct = (self.f["beam"] * self.bending(Q[:1], payload_kg)[0] * (1 + SPREAD["beam"] * rng.standard_normal((n, 1)))
                  + self.f["mount"] * self.tilt(Q[:1], payload_kg)[0] * (1 + SPREAD["mount"] * rng.standard_normal((n, 1))))
        return T[6][:, :3, 3] - nominal + direct


def wilson(k: int, n: int, level: float = 0.95) -> tuple:
    """Wilson score interval of a proportion ``k / n``: ``(p, low, high)``."""
    z = norm.ppf(0.5 + level / 2)
    p = k / n
    c = (p + z * z / (2 * n)) / (1 + z * z / n)
    h = z / (1 + z * z / n) * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return p, c - h, c + h
