"""Link deflection: the arm segments bend as cantilevers under their own weight, the distal masses and the payload.

A *segment* runs from a revolute joint to the next revolute joint (spanning prismatic strokes, so a telescopic
stage's lever arm grows with its joint) or to the flange (:func:`deflection_segments`). Under the transverse part
of gravity (``cos(phi)`` of the weight, ``phi`` the segment's elevation) an Euler-Bernoulli cantilever of length
``L`` with a distributed load ``w`` and an end load ``F`` drops at its end by::

    drop = (w L^4 / 8 + F L^3 / 3) cos(phi) / (E I)  +  (w L^2 / 2 + F L) cos(phi) / (kappa G A)   (shear)
    slope = (w L^3 / 6 + F L^2 / 2) cos(phi) / (E I)

and the slope turns everything beyond it: the target moves by ``drop g + slope (axis x (p - end))``, ``axis`` the
horizontal bending axis. With the section and material of the robot file (:class:`~tolalloc.robot.components.LinkSection`)
:func:`beam_sag` gives the displacement in mm with no free parameter (the design's model). Without them the
diagnosis fits the coefficients of the load shapes (:func:`beam_columns`): ``tip`` (one ``k h^3`` drop per
segment, ``h`` its horizontal overhang [m]), ``beam`` (own weight ``w`` and end load ``f`` columns, plus ``fp``:
the end load of a logged payload that changes between poses).

A telescopic stage also tilts in its guide (:func:`guide_columns`): bearing compliance or clearance, by ``g M``
[rad per N m] with ``M`` the bending moment of the masses beyond the guide about the guide point.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Robot
from tolalloc.physics.loads import G, mass_points, point_at

__all__ = ["MIN_OVERHANG_MM", "deflection_segments", "segment_geometry", "beam_columns", "guide_joints",
           "guide_columns", "segment_section", "beam_sag"]

#: Segments whose horizontal overhang never reaches this [mm] do not bend measurably.
MIN_OVERHANG_MM = 200.0


@lru_cache(maxsize=32)
def deflection_segments(robot: Robot) -> tuple:
    """Arm segments that may bend: ``(start_joint, end_joint or None for the flange, max overhang [mm])``.

    Kept when the segment's horizontal overhang reaches :data:`MIN_OVERHANG_MM` on a fixed sample of 400 poses
    within the joint limits (seed 0), so the list depends on the robot only (and is computed once per robot).
    """
    rev = [j for j in range(robot.n_joints) if robot.joints[j].is_revolute]
    rng = np.random.default_rng(0)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    q = rng.uniform(lo, hi, (400, robot.n_joints))
    segs = []
    for a, j in enumerate(rev):
        k = rev[a + 1] if a + 1 < len(rev) else None
        h = segment_geometry(robot, q, j, k)[1]
        if h.max() >= MIN_OVERHANG_MM:
            segs.append((j, k, float(h.max())))
    return tuple(segs)


def segment_geometry(robot: Robot, q, j: int, k: int | None):
    """Segment end points (P, 3), horizontal overhang [mm] (P,), unit horizontal direction (P, 3), length [mm] (P,)."""
    P = poe_prefix(robot.screws, q)
    g = np.asarray(robot.gravity, dtype=float)
    start = point_at(P[:, j], robot.joint_points_mm[j])
    end = point_at(P[:, k], robot.joint_points_mm[k]) if k is not None else robot.fk_internal(q)[:, :3, 3]
    L = end - start
    Lh = L - (L @ g)[:, None] * g
    h = np.linalg.norm(Lh, axis=1)
    return end, h, Lh / np.maximum(h, 1e-9)[:, None], np.linalg.norm(L, axis=1)


def _move(drop, slope, g, arm):
    """Target displacement (P, 3) of a segment end dropping by ``drop`` [mm] and turning by ``slope`` [rad]."""
    return drop[:, None] * g + slope[:, None] * arm


def beam_columns(robot: Robot, q, p_t, variant: str = "tip", payload_kg=None) -> tuple:
    """Target-displacement basis of link deflection, ``B`` (P, 3, M) per unit coefficient, and names (module doc)."""
    g = np.asarray(robot.gravity, dtype=float)
    pay = None if payload_kg is None or np.ptp(payload_kg) <= 0 else np.asarray(payload_kg, float)
    cols, names = [], []
    for j, k, _ in deflection_segments(robot):
        end, h, u, L = segment_geometry(robot, q, j, k)
        arm = np.cross(np.cross(u, g), p_t - end)
        hm, Lm, cphi = h / 1000.0, L / 1000.0, h / np.maximum(L, 1e-9)
        if variant == "tip":
            terms = [("k", hm ** 3, 1.5e-3 * hm ** 2, "mm/m^3")]
        else:  # own weight (w) and end load (f); a logged payload's end load (fp) when it varies
            terms = [("w", Lm ** 4 / 8 * cphi, 1e-3 * Lm ** 3 / 6 * cphi, "mm/m^4"),
                     ("f", Lm ** 3 / 3 * cphi, 1e-3 * Lm ** 2 / 2 * cphi, "mm/m^3")]
            if pay is not None:
                terms.append(("fp", pay * Lm ** 3 / 3 * cphi, pay * 1e-3 * Lm ** 2 / 2 * cphi, "mm/(kg m^3)"))
        for lab, drop, slope, unit in terms:
            cols.append(_move(drop, slope, g, arm))
            names.append(f"{lab}_{robot.joints[j].name} [{unit}]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))), names


def guide_joints(robot: Robot) -> list:
    """Prismatic joints that are telescopic stages: a revolute joint before them (the stage can swing)."""
    rev = robot.revolute_mask
    return [j for j in range(robot.n_joints) if not rev[j] and rev[:j].any()]


def guide_columns(robot: Robot, q, p_t, payload_kg=None, overlap: bool = False) -> tuple:
    """Tilt of every telescopic stage in its guide (module docstring), columns (P, 3, m) and names."""
    Pm = poe_prefix(robot.screws, q)
    g = np.asarray(robot.gravity, dtype=float)
    cols, names = [], []
    masses = mass_points(robot, q, Pm)
    for j in guide_joints(robot):
        pg = point_at(Pm[:, j], robot.joint_points_mm[j])
        u = Pm[:, j, :3, :3] @ robot.joints[j].axis
        loads = np.zeros((len(q), 3))
        for m, c in masses:
            if m.body > j:
                loads += np.cross((c - pg) / 1000.0, m.mass_kg * G * g)
        tip = np.cross((p_t - pg) / 1000.0, G * g)  # per kg at the target
        if payload_kg is not None:
            loads = loads + np.asarray(payload_kg, float)[:, None] * tip
        ext = (q[:, j] - robot.lower[j]) / max(robot.upper[j] - robot.lower[j], 1e-9)
        terms = [("g", loads, "rad/(N m)"), ("gt", tip, "rad/kg")]
        if overlap:
            terms += [("gs", loads * ext[:, None], "rad/(N m)"), ("gts", tip * ext[:, None], "rad/kg")]
        for lab, M, unit in terms:
            Mb = M - np.einsum("pi,pi->p", M, u)[:, None] * u  # bending part (torsion about the stage excluded)
            cols.append(np.cross(Mb, p_t - pg))
            names.append(f"{lab}_{robot.joints[j].name} [{unit}]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))), names


def segment_section(robot: Robot, j: int, k: int | None):
    """The section of the segment from joint ``j`` to ``k`` (its longest link that has one), or None."""
    best, length = None, -1.0
    for lk, site in zip(robot.links, robot.link_sites):
        inside = site > j and (k is None or site <= k)
        sec = robot.components.links.get(lk.name)
        if inside and sec is not None and lk.length_mm > length:
            best, length = sec, lk.length_mm
    return best


def _segment_loads(j: int, k: int | None, masses, payload_kg) -> tuple:
    """Mass [kg] on the segment (the robot's masses between its joints) and beyond its end (with the payload)."""
    own = sum(m.mass_kg for m, _ in masses if m.body > j and (k is None or m.body <= k))
    distal = sum(m.mass_kg for m, _ in masses if k is not None and m.body > k)
    pay = 0.0 if payload_kg is None else np.asarray(payload_kg, float)
    return own, distal + pay


def beam_sag(robot: Robot, q, p_t, payload_kg=None) -> np.ndarray:
    """Target displacement [mm] (P, 3) of the segments with a section in the robot file, bending and shear under
    their own masses (spread along the segment), the distal masses and the payload at the target (module
    docstring). Segments without a section do not bend here."""
    g = np.asarray(robot.gravity, dtype=float)
    masses = mass_points(robot, q)
    out = np.zeros((len(q), 3))
    for j, k, _ in deflection_segments(robot):
        sec = segment_section(robot, j, k)
        if sec is None:
            continue
        end, h, u, L = segment_geometry(robot, q, j, k)
        own_kg, end_kg = _segment_loads(j, k, masses, payload_kg)
        # [N/mm]: the robot's masses on the segment spread along it, or the section's own weight without them
        w = own_kg * G / np.maximum(L, 1e-9) if own_kg > 0 else sec.area_mm2 * sec.density_kg_per_mm3 * G
        F = end_kg * G
        cphi = h / np.maximum(L, 1e-9)
        drop = ((w * L ** 4 / 8 + F * L ** 3 / 3) / sec.EI_Nmm2
                + (w * L ** 2 / 2 + F * L) / sec.shear_stiffness_N) * cphi
        slope = (w * L ** 3 / 6 + F * L ** 2 / 2) / sec.EI_Nmm2 * cphi
        out += _move(drop, slope, g, np.cross(np.cross(u, g), p_t - end))
    return out
