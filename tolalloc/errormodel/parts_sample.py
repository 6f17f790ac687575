"""Physical draws of the bought parts' effects at one point, for the nonlinear Monte Carlo.

Each draw is one built robot (its systematic parts: stiffness factors, the phases of its gears', encoders' and
bearings' errors, its links' thermal and bending spread) making one move (its random parts: the flank its gears rest
on, the gear's repeatability). The effects are evaluated physically -- the catalogue's torque-torsion curve at the
drawn stiffness, the gear and encoder errors at the actual joint angle, the bearings' rotating eccentricities -- by the
physics stage's functions (the linear terms of :mod:`tolalloc.errormodel.parts` are their first-order moments). The
draws are parameter values of :func:`~tolalloc.errormodel.parts.parts_error_model` (joint offsets, link growth,
bearing displacements, which the exact perturbed chain carries) plus a direct tool displacement (beam sag, the
bearings' and the mount's tilt).
"""

from __future__ import annotations

import numpy as np

from tolalloc.errormodel.parts import (BEAM_SD, COMPENSATION_RESIDUAL, MOUNT_SD, THERMAL_SD, TILT_SD, PartEffects,
                                       encoder_harmonics, gear_harmonics, motor_side, residual_factors,
                                       stroke_of)
from tolalloc.physics.beams import beam_sag
from tolalloc.physics.bearings import runout_values
from tolalloc.physics.compliance import mount_tilt
from tolalloc.physics.thermal_design import link_cte
from tolalloc.physics.thermal_scale import scale_error
from tolalloc.physics.transmission import transmission_error

__all__ = ["sample_effects"]


def _sines(qj: float, orders, amps, rng, n: int) -> np.ndarray:
    """Sum of sines at angle ``qj`` with uniform random phases, shape (n,)."""
    phases = rng.uniform(0.0, 2 * np.pi, (n, len(orders)))
    return transmission_error(np.full(n, qj), orders, amps, phases)


def _joint_draws(fx: PartEffects, i: int, j: int, n: int, rng, f: dict) -> tuple:
    """Joint ``j``'s offset (systematic parts scaled by their effect's residual ``f``, random), shape (n,) each."""
    parts = fx.robot.components.joint(fx.robot.joints[j].name)
    red, enc = parts.reducer, parts.encoder
    qj, sys, rnd = fx.q[i, j], np.zeros(n), np.zeros(n)
    rev = fx.robot.joints[j].is_revolute
    if red is not None and motor_side(fx.robot, j):
        if red.stiffness:
            k = np.maximum(1.0 + (red.stiffness_sd or 0.0) * rng.standard_normal(n), 0.5)
            sys += f["compliance"] * red.deflection(np.full(n, fx.tau[i, j])) / k
        if red.lost_motion:
            side = rng.choice([-1.0, 1.0], (n, 1))[:, 0]  # the flank of a random approach, either side
            rnd += side * red.lost_motion / 2.0
        if red.transmission_accuracy:
            sys += f["transmission"] * _sines(qj, *gear_harmonics(red, rev, stroke_of(fx.robot, j)), rng, n)
        if red.repeatability:
            rnd += rng.uniform(-red.repeatability, red.repeatability, n)
    if enc is not None and (enc.accuracy or enc.eccentricity):
        orders, amps = encoder_harmonics(enc, getattr(red, "ratio", None), rev)
        # one sinusoid at a time: each its own phase
        sys += f["encoder"] * sum(_sines(qj, orders[k:k + 1], amps[k:k + 1], rng, n) for k in range(len(orders)))
    if enc is not None and enc.homing_repeatability:
        rnd += rng.uniform(-enc.homing_repeatability, enc.homing_repeatability, n)   # this power-up's zero
    if enc is not None and enc.scale_expansion is not None:
        grow = scale_error(enc.scale_expansion, qj, fx.ambient[i] - fx.conditions.reference_c)
        sys += f["thermal"] * grow * (1.0 + THERMAL_SD * rng.standard_normal(n))
    return sys, rnd


def sample_effects(fx: PartEffects, i: int, n: int, rng: np.random.Generator, *, after: str = "none",
                   residual=COMPENSATION_RESIDUAL) -> tuple:
    """``n`` physical draws of every effect at point ``i`` of ``fx``.

    Parameters
    ----------
    fx : PartEffects
    i : int
        The point (pose, payload, ambient).
    n : int
    rng : numpy Generator
    after : {"none", "compensation"}
    residual : float or dict
        ``compensation``: the compensation models leave this share of every systematic part (per effect with a dict;
        :func:`~tolalloc.errormodel.parts.residual_factors`, as
        :meth:`~tolalloc.errormodel.parts.EffectTerms.moments`).

    Returns
    -------
    values : array, shape (n, K)
        Parameter values of ``fx.pm.model`` [mm, rad] (the effects' only; add the geometric draws).
    direct : array, shape (n, 3)
        Tool displacement beside the chain (beam sag, bearing and mount tilt) [mm].
    """
    f = residual_factors(after, residual)
    r, pm = fx.robot, fx.pm
    values, direct = np.zeros((n, len(pm.model.params))), np.zeros((n, 3))
    for j in range(r.n_joints):
        sys, rnd = _joint_draws(fx, i, j, n, rng, f)
        values[:, pm.drive[j]] += sys + rnd
        bearing = r.components.joint(r.joints[j].name).bearing
        if bearing is not None and j in pm.bearing:
            values[:, pm.bearing[j]] += f["bearing"] * runout_values(bearing, rng.uniform(0.0, 2 * np.pi, (n, 2)))
    cte, dT = link_cte(r), fx.link_temperatures()[i]
    lengths = np.array([lk.length_mm for lk in r.links if lk.length_mm > 0])
    grow = cte * dT * lengths
    values[:, pm.link] += f["thermal"] * grow[None, :] * (1.0 + THERMAL_SD * rng.standard_normal((n, len(grow))))
    q1, p1 = fx.q[i:i + 1], fx.tool[i:i + 1]
    w_tool, w = (None if x is None else x[i:i + 1] for x in (fx.wrench_tool, fx.wrench))
    if r.components.links:
        sag = beam_sag(r, q1, p1, fx.payload[i:i + 1], fx.payload_point[i:i + 1], w_tool)[0]
        direct += f["beam"] * sag[None, :] * (1.0 + BEAM_SD * rng.standard_normal((n, 1)))
    theta, centre = (x[i] for x in fx.bearing_rotations)                   # (n_joints, 3) each
    if np.any(theta):
        spread = 1.0 + TILT_SD * rng.standard_normal((n, r.n_joints))
        direct += f["compliance"] * spread @ np.cross(theta, fx.tool[i] - centre)
    if r.components.mount.tilt_stiffness is not None:
        tilt = mount_tilt(r, q1, p1, fx.payload_point[i:i + 1], fx.payload[i:i + 1], w)[0]
        direct += f["mount"] * tilt[None, :] * (1.0 + MOUNT_SD * rng.standard_normal((n, 1)))
    return values, direct
