"""Link deflection: the arm segments bend and twist as cantilevers under the masses they carry and the payload.

A *segment* runs from a revolute joint to the next revolute joint (spanning prismatic strokes, so a telescopic
stage's lever arm grows with its joint) or to the flange (:func:`deflection_segments`). Every mass carried after
its first joint (the robot's mass model) and the payload at the target is a point load where it sits; the internal
moment ``M(s)`` at each section (its bending part about the axes across the segment, its torsion part about the
segment axis) turns the section by ``C M(s) ds``, ``C = (I - e e^T) / EI + e e^T / GJ``, and the turn of every
section moves all points beyond it (:func:`_load_integrals`, integrated in closed form). A load ``F`` at the end of
a horizontal cantilever gives the textbook ``F L^3 / 3EI``, a mass beyond the end its moment, a mass beside the axis
a twist. With the section and material of the robot file (:class:`~tolalloc.robot.components.LinkSection`)
:func:`beam_sag` gives the displacement in mm with no free parameter (the design's model, shear ``F / kGA``
included). Without them the diagnosis fits the compliances of the same load shapes (:func:`beam_columns`): ``tip``
(one ``k h^3`` drop per segment, ``h`` its horizontal overhang [m]), ``beam`` (``1/EI`` and ``1/GJ`` per segment),
``beam+w`` (also a distributed own weight the mass model lacks), ``beam+tip`` (also an unknown mass at the target).

What sits between the flange and the tool -- a force-torque sensor, a tool changer, a compliance device, a gripper on
flexures -- is itself a short compliant element (:func:`flange_columns`): the tool turns and shifts on it under the
load beyond the flange, compliance per axis of the tool frame.

A telescopic stage also tilts in its guide (:func:`guide_columns`): bearing compliance or clearance, by ``g M``
[rad per N m] with ``M`` the bending moment of the masses beyond the guide about the guide point.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.lie import cross
from tolalloc.robot.model import Robot
from tolalloc.physics.loads import G, mass_points, point_at

__all__ = ["MIN_OVERHANG_MM", "deflection_segments", "segment_geometry", "beam_columns", "flange_columns",
           "guide_joints", "guide_columns", "segment_section", "segment_loads", "beam_sag"]

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


def _load_integrals(start, e, L, loads, p, couples=(), height=None) -> dict:
    """End-displacement integrals of a cantilever segment (start (P, 3) [mm], unit axis ``e`` (P, 3), length ``L``
    (P,) [mm]) under point forces ``loads = [(F (P, 3) [N], at (P, 3) [mm], through_end)]``, at the points ``p``
    (P, 3) beyond it.

    The internal moment at station ``s`` is ``M(s) = sum (c - x(s)) x F`` over the loads the section carries
    (``x(s) = start + s e``): a load on the segment up to its projection ``a`` on the axis, a load attached beyond
    the segment's end (``through_end``: a later body, the payload) over the whole length, wherever it hangs (a folded
    arm's distal masses may project back over the segment). The section turns by ``C M(s) ds`` with the compliance
    ``C = b (I - e e^T) + t e e^T`` (bending ``b = 1/EI``, torsion ``t = 1/GJ``), which moves ``p`` by
    ``C M(s) ds x (p - x(s))``; shear moves everything beyond ``s`` by ``F_perp ds / kGA``. Integrated in closed form
    (``M`` linear in ``s``): ``{"bend": (P, 3) [N mm^3], "twist": ..., "shear": (P, 3) [N mm]}`` per unit
    ``b``, ``t`` and ``1/kGA``. ``couples``: moments (P, 3) [N m] applied beyond the segment's end (a process
    wrench's moment), constant along it. ``height``: a box's height direction (P, 3), unit and across ``e``; given,
    the bending part splits in two, ``C = b w w^T + b_side u u^T + t e e^T`` (``u`` the height, ``w = e x u`` the
    width axis: a moment about ``w`` bends the box in the plane of its height), and ``"bend_side"`` holds the
    integrals per unit ``b_side``."""
    out = {"bend": np.zeros_like(p), "twist": np.zeros_like(p), "shear": np.zeros_like(p)}
    p0 = p - start
    along = lambda a: (lambda v: a * np.einsum("pi,pi->p", a, v)[:, None])  # noqa: E731
    along_e = along(e)
    if height is None:
        parts = (("bend", lambda v: v - along_e(v)), ("twist", along_e))  # C's bending and torsion parts
    else:
        out["bend_side"] = np.zeros_like(p)
        parts = (("bend", along(cross(e, height))), ("bend_side", along(height)), ("twist", along_e))
    for F, c, through_end in loads:
        r = c - start
        a = (L if through_end else np.clip(np.einsum("pi,pi->p", r, e), 0.0, L))[:, None]
        m0, m1 = cross(r, F), cross(e, F)
        for key, C in parts:
            c0, c1 = C(m0), C(m1)
            out[key] += (a * cross(c0, p0) - a ** 2 / 2 * (cross(c0, e) + cross(c1, p0))
                         + a ** 3 / 3 * cross(c1, e))
        out["shear"] += a * (F - along_e(F))
    for M in couples:
        for key, C in parts:
            c0 = C(1000.0 * np.asarray(M, dtype=float))  # [N mm]
            out[key] += L[:, None] * cross(c0, p0) - L[:, None] ** 2 / 2 * cross(c0, e)
    return out


def segment_loads(robot: Robot, masses, j: int, p_t, kg_at_target=None, k: int | None = None,
                  payload_at=None, wrench=None) -> list:
    """Point loads ``[(F (P, 3) [N], at (P, 3) [mm], through_end)]`` the segment from joint ``j`` to joint ``k``
    (None: to the flange) carries: the weight of every mass after joint ``j`` (``through_end`` for those after joint
    ``k``), ``kg_at_target`` (P,) at ``payload_at`` (P, 3) (default the target points ``p_t``) and the force of a
    process ``wrench`` (P, 6) at ``p_t``, both carried through the end (the wrench's moment: ``couples`` of
    :func:`_load_integrals`)."""
    g = G * np.asarray(robot.gravity, dtype=float)
    loads = [(np.broadcast_to(m.mass_kg * g, c.shape), c, k is not None and m.body > k)
             for m, c in masses if m.body > j]
    if kg_at_target is not None:
        loads.append((np.asarray(kg_at_target, float).reshape(-1, 1) * g, p_t if payload_at is None else payload_at,
                      True))
    if wrench is not None:
        loads.append((np.asarray(wrench, float)[:, :3], p_t, True))
    return loads


def _weight_loads(robot: Robot, start, e, L) -> list:
    """A distributed weight of 1 kg/m along the segment as point loads at Gauss-Legendre nodes: the end displacement
    of a load at distance ``a`` is a cubic in ``a``, so the 2-node rule integrates it exactly (loads on the segment,
    as :func:`_load_integrals` takes them)."""
    g = G * np.asarray(robot.gravity, dtype=float)
    x, w = np.polynomial.legendre.leggauss(2)
    return [(np.broadcast_to(g, start.shape) * (L * wi / 2 / 1000.0)[:, None],
             start + e * (L * (1 + xi) / 2)[:, None], False) for xi, wi in zip(x, w)]


def beam_columns(robot: Robot, q, p_t, variant: str = "tip", payload_kg=None, wrench=None) -> tuple:
    """Target-displacement basis of link deflection, ``B`` (P, 3, M) per unit coefficient, and names.

    ``tip``: one ``k h^3`` drop per segment. ``beam``: per segment the bending ``e`` and torsion ``r`` of the robot's
    mass model and the logged payload (:func:`_load_integrals`: each mass a point load where it sits, its moment
    about every section), coefficients ``1/EI`` and ``1/GJ`` [1/(MN m^2)]; ``beam+w`` also the bending of a
    distributed own weight the mass model lacks (``w``, [1/(MN m^2)] per kg/m); ``beam+tip`` also the bending of an
    unknown mass at the target (``t``, [1/(MN m^2)] per kg). A logged process ``wrench`` (P, 6) at the target loads
    the ``beam`` variants beside the payload."""
    g = np.asarray(robot.gravity, dtype=float)
    cols, names = [], []
    masses = mass_points(robot, q)
    Pm = poe_prefix(robot.screws, q)
    for j, k, _ in deflection_segments(robot):
        end, h, u, L = segment_geometry(robot, q, j, k)
        nm = robot.joints[j].name
        if variant == "tip":
            hm = h / 1000.0
            cols.append(hm[:, None] ** 3 * g + (1.5e-3 * hm ** 2)[:, None] * np.cross(np.cross(u, g), p_t - end))
            names.append(f"k_{nm} [mm/m^3]")
            continue
        start = point_at(Pm[:, j], robot.joint_points_mm[j])
        e = (end - start) / np.maximum(L, 1e-9)[:, None]
        couples = () if wrench is None else (np.asarray(wrench, float)[:, 3:],)
        I = _load_integrals(start, e, L, segment_loads(robot, masses, j, p_t, payload_kg, k, wrench=wrench), p_t,
                            couples)
        terms = [("e", I["bend"]), ("r", I["twist"])]
        if variant == "beam+w":
            terms.append(("w", _load_integrals(start, e, L, _weight_loads(robot, start, e, L), p_t)["bend"]))
        if variant == "beam+tip":
            tip = [(G * np.broadcast_to(g, p_t.shape), p_t, True)]
            terms.append(("t", _load_integrals(start, e, L, tip, p_t)["bend"]))
        for lab, B in terms:
            cols.append(1e-12 * B)  # [N mm^3] x 1/(MN m^2) = 1e-12 / (N mm^2)
            names.append(f"{lab}_{nm} [1/(MN m^2)]")
    return (np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))), names


def flange_columns(robot: Robot, q, p_t, payload_kg=None, wrench=None) -> tuple:
    """A compliant element between the flange and the tool (module docstring), columns (P, 3, m) and names.

    The load beyond the flange -- the masses on the last body and the logged payload at the target (``known``), and a
    unit mass at the target (``tool``, a tool the mass model lacks) -- gives the force ``F`` and the moment ``M`` about
    the flange point (a logged process ``wrench`` (P, 6) at the target adds to the known load). In the tool frame (axes
    ``x, y, z``) the element turns by ``c_i M_i`` [urad per N m] and shifts by ``s_i F_i`` [um per N] along each axis; a
    turn moves the target about the flange point. Without known loads only the ``tool`` columns are given."""
    q = np.atleast_2d(q)
    g = np.asarray(robot.gravity, dtype=float)
    Pm = poe_prefix(robot.screws, q)
    n = robot.n_joints
    R = Pm[:, n, :3, :3] @ robot.tool_rotation
    pf = point_at(Pm[:, n], robot.home[:3, 3] - robot.tool_offset_mm)  # the flange point (the tool's root)
    F, M = np.zeros((len(q), 3)), np.zeros((len(q), 3))
    for Fk, at, _ in segment_loads(robot, mass_points(robot, q, Pm), n - 1, p_t, payload_kg, wrench=wrench):
        F, M = F + Fk, M + np.cross((at - pf) / 1000.0, Fk)  # beyond the last joint
    if wrench is not None:
        M = M + np.asarray(wrench, float)[:, 3:]
    unit_F = np.broadcast_to(G * g, (len(q), 3))
    loads = [("tool", unit_F, np.cross((p_t - pf) / 1000.0, unit_F))]
    if max(np.abs(F).max(initial=0.0), np.abs(M).max(initial=0.0)) > 0:
        loads.insert(0, ("known", F, M))
    cols, names = [], []
    for lab, Fl, Ml in loads:
        Mt, Ft = np.einsum("pji,pj->pi", R, Ml), np.einsum("pji,pj->pi", R, Fl)  # in the tool frame
        for i, ax in enumerate("xyz"):
            turn = 1e-6 * R[:, :, i] * Mt[:, i:i + 1]
            cols.append(np.cross(turn, p_t - pf))
            names.append(f"c{ax}_{lab} [urad/(N m)]")
        for i, ax in enumerate("xyz"):
            cols.append(1e-3 * R[:, :, i] * Ft[:, i:i + 1])
            names.append(f"s{ax}_{lab} [um/N]")
    return np.stack(cols, axis=-1), names


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


def beam_sag(robot: Robot, q, p_t, payload_kg=None, payload_at=None, wrench=None) -> np.ndarray:
    """Target displacement [mm] (P, 3) of the segments with a section in the robot file: bending (``EI``; a box with
    its ``height_direction``: ``EI`` in the plane of its height, ``EI_side`` in the plane of its width), torsion
    (``GJ``, the section's torsion constant ``torsion_mm4``) and shear (``kGA``) under every
    mass the segment carries as a point load where it sits and the payload at ``payload_at`` (P, 3) (default the
    target ``p_t``; :func:`_load_integrals`), plus the section's own weight where the robot file puts no mass on the
    segment, and a process ``wrench`` (P, 6) at ``p_t`` (its force a point load, its moment a couple, as
    :func:`beam_columns`). Segments without a section do not bend here."""
    masses = mass_points(robot, q)
    Pm = poe_prefix(robot.screws, q)
    out = np.zeros((len(q), 3))
    for j, k, _ in deflection_segments(robot):
        sec = segment_section(robot, j, k)
        if sec is None:
            continue
        end, _, _, L = segment_geometry(robot, q, j, k)
        start = point_at(Pm[:, j], robot.joint_points_mm[j])
        e = (end - start) / np.maximum(L, 1e-9)[:, None]
        loads = segment_loads(robot, masses, j, p_t, payload_kg, k, payload_at, wrench)
        if not any(m.body > j and (k is None or m.body <= k) for m, _ in masses):
            per_kg_m = sec.area_mm2 * sec.density_kg_per_mm3 * 1e3  # [kg/m]
            loads += [(F * per_kg_m, c, on) for F, c, on in _weight_loads(robot, start, e, L)]
        couples = () if wrench is None else (np.asarray(wrench, float)[:, 3:],)
        I = _load_integrals(start, e, L, loads, p_t, couples, _height(sec, Pm[:, j + 1, :3, :3], e))
        out += (I["bend"] / sec.EI_Nmm2 + I.get("bend_side", 0.0) / sec.EI_side_Nmm2 + I["twist"] / sec.GJ_Nmm2
                + I["shear"] / sec.shear_stiffness_N)
    return out


def _height(sec, R, e) -> np.ndarray | None:
    """The box's height direction at the poses, across the segment axis ``e`` (P, 3), or None (no orientation
    given). ``R`` (P, 3, 3): the segment body's rotation (its joints after the first are prismatic)."""
    if sec.height_direction is None:
        return None
    h = R @ np.asarray(sec.height_direction, float)
    u = h - e * np.einsum("pi,pi->p", e, h)[:, None]
    n = np.linalg.norm(u, axis=1)
    if n.min() < 0.5:
        raise ValueError(f"a box section's height_direction {list(sec.height_direction)} lies within 30 deg of its "
                         "segment's axis at some poses: give the direction of the box's height across the link")
    return u / n[:, None]
