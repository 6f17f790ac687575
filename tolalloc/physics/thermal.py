"""Thermal growth of the links: what drives it (ambient log, warm-up time, motion history) and its basis.

Every link ``k`` grows by ``alpha_k dT_k L_k`` along itself; the target moves by ``J_k L_k alpha_k dT_k``
(``J_k`` the first-order displacement per mm of link ``k``, :func:`link_growth`). Variants of ``dT``:

* ``temperature``: the logged ``temperature_c`` minus the training mean; one ``alpha`` for all links.
* ``lag_<tau>min``: the log through a first-order lag (time constant ``tau`` on :data:`LAG_MIN`); one ``alpha``.
* ``warmup_<tau>min``: ``1 - exp(-(t - t0) / tau)``, a warm-up the ambient log does not show; one growth for all
  links [1e-6].
* ``links_warmup_<tau>min``: the same warm-up with its own growth per link (motors of different power sit at
  different links) [1e-6 per link].
* ``bow_<tau>min``: the same warm-up warming each link unevenly across its section (a motor flanged to one side,
  sun on one face): every link grows by its own amount and every link at least :data:`BOW_MIN_MM` long also bows
  about two axes across it fixed in the link (:func:`link_bow`) [1e-6 per link, urad per bow axis].
* ``activity_<tau>min``: motion history: per joint the joint speed between consecutive poses in time order
  (``|q_i - q_(i-1)| / (t_i - t_(i-1))``, rad/s or mm/s) through a first-order lag of time constant ``tau`` (the
  heat stored in its motor); link ``k`` grows with the lagged activity of the joints at its two ends, with its
  own coefficient [1e-6 per rad/s].
* ``motor_<tau>min``: the motors' losses as heat sources: per joint the friction losses of its motion (its speed)
  and the copper losses of the torque it holds (``I^2 R``, with the current proportional to the gravity load: the
  load squared, held over the interval before each pose), each through the first-order lag of heating and cooling
  (time constant ``tau``); the heat of joint ``j`` warms the links at its two ends, which grow along themselves --
  two coefficients per joint [1e-6 per rad/s, 1e-6 per (N m)^2]. The robot works for at most
  :data:`~tolalloc.physics.thermal_history.PAUSE_STEPS` median intervals of a gap between poses; the rest of a longer
  gap is a pause in which the links cool.

* ``held_<tau>min``: heat exchanged with what the robot holds: a gripped part warmer or colder than the arm (a
  casting from the die, a chilled or frozen part), a gripper's own heat source or sink (a solenoid, a vacuum ejector's
  expanding air) acting while it holds. The logged payload held over the interval before each pose (the previous
  pose's ``payload_kg`` in time order: the heat a part exchanges scales with its mass) through the first-order lag of
  heating and cooling (time constant ``tau``); the links grow or shrink each by its own coefficient (the heat enters
  at the wrist and spreads unevenly) [1e-6 per kg]. Needs a payload that varies; a held part that never changes is
  the warm-up's shape.

* ``tilt_<tau>min``: heat that tilts the joints' axes: a housing warmed on one side (the motor and its holding-brake
  coil flanged to it) grows more on that side, and the axis it carries tilts by ``alpha h dT / s`` (wall height ``h``,
  bearing spacing ``s``; Bryan, CIRP Annals 39(2), 1990; ISO 230-3). The heat flows while the robot works and stops
  in a pause (:func:`duty_warmup`), so the tilt rises over production and falls back in a pause. Every revolute
  joint's axis tilts about two axes across it fixed in the link that carries it (:func:`axis_tilt`) [urad per joint
  and axis].
* ``drift_<tau>min``: the measuring frame and the robot's base drift apart as the session goes on (a laser tracker
  warming up, its stand or the robot's pedestal settling): a translation common to every pose, ``1 - exp(-(t - t0)
  / tau)`` times three components (:func:`frame_drift`) [um]; ``tau`` at least :data:`DRIFT_MIN_MIN`. Relative to
  its own base the robot is unchanged: its columns (:data:`MEASUREMENT_PREFIX`, :func:`is_measurement_column`)
  move what the instrument sees, not the target in the base frame. (Turns are left out: a turn of the whole arm
  about its base is what a tilting first axis does.)
* ``scale``, ``scale_lag_<tau>min``: the joints' own position scales growing with the logged air, directly or
  through a lag, for the encoders the robot file declares a scale for (:mod:`.thermal_scale`) [1e-6/K per joint].
* ``<air>+<activity>``: an air-driven variant (``temperature`` or ``lag_<tau>min``) and an activity-driven one
  (``warmup``, ``links_warmup``, ``activity`` or ``motor``) together, their columns side by side: a workshop whose air
  drifts while the drives warm the arm (:func:`is_air_variant` tells the two kinds apart).

Time-driven variants need a usable ``time_s`` (:func:`~tolalloc.physics.thermal_history.time_problem`): present,
non-decreasing in row order (one session per file) and in seconds. Otherwise they are skipped and the reason is
reported. The training basis is built from the training rows alone; a test file's basis runs the lag filters over the
training and test rows together in time order (their joint values and times only -- what is known before a pose is
measured).
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Robot
from tolalloc.physics.loads import across_axes, gravity_torques, point_at
from tolalloc.physics.thermal_history import (activity, duty_warmup, held_heat, lagged, motor_heat, tau_s,
                                              through_history, time_problem)
from tolalloc.physics.thermal_scale import joint_scale, scale_joints

__all__ = ["LAG_MIN", "thermal_variants", "thermal_signal", "thermal_bases", "link_growth", "link_joint_matrix",
           "is_air_variant", "variant_parts", "link_bow", "BOW_MIN_MM", "axis_tilt", "frame_drift",
           "MEASUREMENT_PREFIX", "DRIFT_MIN_MIN", "is_measurement_column", "is_measurement_variant", "is_clock_variant"]

LAG_MIN = (5.0, 7.5, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0, 90.0, 120.0, 180.0, 240.0)
#: Links shorter than this [mm] do not bow measurably under a temperature difference across them.
BOW_MIN_MM = 200.0
#: Shortest warm-up [min] of the instrument's drift: a laser tracker settles over tens of minutes to hours (makers ask
#: for a warm-up before measuring); a faster transient at the start of a session is not the instrument's.
DRIFT_MIN_MIN = 20.0
#: Name prefix of the columns that move the measuring frame against the robot's base, not the robot's target.
MEASUREMENT_PREFIX = "drift_"
#: variants driven by the time since the session's start alone (a drift of the measuring frame is one too, kept apart)
CLOCK_VARIANTS = ("warmup", "links_warmup", "bow")


def thermal_variants(meas, robot: Robot | None = None) -> tuple:
    """Thermal variants the data can carry (first: the default), empty when none; ``scale`` and ``scale_lag_<tau>min``
    only for a ``robot`` whose file declares a scale (:func:`~.thermal_scale.scale_joints`)."""
    T, t, m_kg = meas.temperature_c, meas.time_s, meas.payload_kg
    air = T is not None and np.ptp(T) >= 0.05
    timed = time_problem(t) is None
    out = ["temperature"] if air else []
    if timed:
        if air:
            out += [f"lag_{m:g}min" for m in LAG_MIN]
        held = ("held",) if m_kg is not None and np.ptp(m_kg) > 0 else ()
        out += [f"{kind}_{m:g}min" for kind in ("warmup", "links_warmup", "bow", "activity", "motor", "tilt") + held
                for m in LAG_MIN]
        out += [f"drift_{m:g}min" for m in LAG_MIN if m >= DRIFT_MIN_MIN]
    if air and robot is not None and len(scale_joints(robot)):
        out += ["scale"] + ([f"scale_lag_{m:g}min" for m in LAG_MIN] if timed else [])
    return tuple(out)


def is_air_variant(variant: str) -> bool:
    """Whether ``variant`` is driven by the logged air temperature (``temperature``, ``lag_<tau>min``, ``scale``,
    ``scale_lag_<tau>min``)."""
    return variant == "temperature" or variant.startswith(("lag_", "scale"))


def is_measurement_column(name: str) -> bool:
    """Whether the effect column ``name`` moves the measuring frame against the robot's base (not the target relative
    to the base)."""
    return name.startswith(MEASUREMENT_PREFIX)


def is_measurement_variant(variant: str) -> bool:
    """Whether ``variant`` (or a part of a combined one) is a drift of the measuring frame (``drift_<tau>min``)."""
    return any(v.startswith("drift") for v in variant_parts(variant))


def is_clock_variant(variant: str) -> bool:
    """Whether ``variant`` is driven by the time since the session's start alone (``warmup``, ``links_warmup``,
    ``bow``): no logged temperature, motion or load enters it."""
    return all(v.startswith(CLOCK_VARIANTS) for v in variant_parts(variant))


def variant_parts(variant: str) -> tuple:
    """The single variants of a (possibly combined, ``a+b``) thermal variant."""
    return tuple(variant.split("+"))


def _history(meas, ref: dict, fn, key: str = "motion", values=None):
    """``fn(time_s, values)`` on the poses of ``meas`` run through after the training poses ``ref[key]`` (their times
    and values, default the joint values of ``ref["motion"]``; :func:`~.thermal_history.through_history`).
    ``values``: these poses' (default ``meas.q``)."""
    return through_history(fn, meas.time_s, meas.q if values is None else values, ref[key])


def thermal_signal(meas, ref: dict, variant: str, link_joints: np.ndarray | None = None,
                   robot: Robot | None = None) -> np.ndarray:
    """The driving signal of ``variant`` on the poses of ``meas``: shape (P,) for the one-coefficient variants and
    ``links_warmup``, (P, L) for ``activity`` (``link_joints`` (L, n): :func:`link_joint_matrix`), (P, 2n) for
    ``motor`` (speeds, then squared loads; needs ``robot``)."""
    if variant in ("temperature", "scale"):
        return meas.temperature_c - ref["temperature_c"]
    tau, t = tau_s(variant), meas.time_s
    if variant.startswith((*CLOCK_VARIANTS, "drift")):
        return 1.0 - np.exp(-np.maximum(t - ref["time0_s"], 0.0) / tau)
    if variant.startswith("tilt"):
        return _history(meas, ref, lambda ts, qs: duty_warmup(ts, tau))
    if variant.startswith("activity"):
        return _history(meas, ref, lambda ts, qs: activity(ts, qs, tau)) @ link_joints.T
    if variant.startswith("motor"):
        return _history(meas, ref, lambda ts, qs: motor_heat(ts, qs, gravity_torques(robot, qs), tau))
    if variant.startswith("held"):
        return _history(meas, ref, lambda ts, ms: held_heat(ts, ms, tau), "payload_history", meas.payload_kg)
    ht, hT = ref["history"]  # lag of the temperature log
    allt, allT = np.concatenate([ht, t]), np.concatenate([hT, meas.temperature_c])
    y = lagged(allt, allT, tau)[len(ht):]
    return y - ref["temperature_c"]


def link_growth(robot: Robot, q: np.ndarray) -> tuple:
    """Displacement of the target per unit relative growth (1e-6) of every link of nonzero length, shape (P, 3, L),
    and the links' names: link ``k`` grows along its own vector, turned by the joints before it, and the
    translation moves every point downstream equally (so it is the same at the target)."""
    prefix = poe_prefix(robot.screws, np.atleast_2d(q))
    cols, names = [], []
    for lk, site in zip(robot.links, robot.link_sites):
        if lk.length_mm > 0:
            cols.append(prefix[:, site, :3, :3] @ lk.vector_mm)
            names.append(lk.name)
    grow = np.stack(cols, axis=-1) if cols else np.zeros((len(prefix), 3, 0))
    return 1e-6 * grow, tuple(names)


def link_joint_matrix(robot: Robot) -> np.ndarray:
    """(L, n) indicator of the joints at the two ends of every link of nonzero length (its motors)."""
    rows = []
    for lk, site in zip(robot.links, robot.link_sites):
        if lk.length_mm <= 0:
            continue
        r = np.zeros(robot.n_joints)
        for j in (site - 1, site):
            if 0 <= j < robot.n_joints:
                r[j] = 1.0
        rows.append(r)
    return np.array(rows).reshape(-1, robot.n_joints)


def thermal_bases(robot: Robot, meas, ref: dict, names, points_mm: np.ndarray | None = None) -> list:
    """(names, B (P, 3, M)) of every variant in ``names`` (the link-growth field is computed once), at the measured
    points ``points_mm`` (P, 3) (default the tool point; growth moves every point alike, a bow turns them)."""
    grow, links = link_growth(robot, meas.q)
    total = grow.sum(axis=2)  # (P, 3): every link by the same relative amount
    lj = link_joint_matrix(robot)
    bow = tilt = scale = None  # the bow, tilt and scale fields, computed once for all their variants
    out = []
    for v in names:
        if "+" in v:  # a combined variant: its parts' columns side by side
            parts = thermal_bases(robot, meas, ref, variant_parts(v), points_mm)
            out.append((sum((lab for lab, _ in parts), ()), np.concatenate([B for _, B in parts], axis=2)))
            continue
        s = thermal_signal(meas, ref, v, lj, robot)
        if v.startswith("motor"):
            out.append(_motor_basis(robot, grow, lj, s, v))
            continue
        if v.startswith("drift"):
            drift = frame_drift(len(s))
            out.append((tuple(f"{lab} ({v})" for lab in drift[1]), drift[0] * s[:, None, None]))
            continue
        if v.startswith("scale"):
            pts = robot.fk_internal(meas.q)[:, :3, 3] if points_mm is None else points_mm
            scale = joint_scale(robot, meas.q, pts) if scale is None else scale
            out.append((tuple(f"{lab} ({v})" for lab in scale[1]), scale[0] * s[:, None, None]))
            continue
        if v.startswith("tilt"):
            tilt = axis_tilt(robot, meas.q, points_mm) if tilt is None else tilt
            out.append((tuple(f"{lab} ({v})" for lab in tilt[1]), tilt[0] * s[:, None, None]))
            continue
        if v.startswith("bow"):
            bow = link_bow(robot, meas.q, points_mm) if bow is None else bow
            out.append(_bow_basis(grow, links, bow, s, v))
            continue
        if v.startswith(("links_warmup", "activity", "held")):
            per = s[:, None] if s.ndim == 1 else s
            B = grow * (per if per.shape[1] == grow.shape[2] else np.repeat(per, grow.shape[2], axis=1))[:, None, :]
            unit = {"links": "1e-6", "held": "1e-6 per kg"}.get(v.split("_")[0], "1e-6 per rad/s")
            labels = tuple(f"alpha_{nm} [{unit}] ({v})" for nm in links)
        else:
            B = (total * s[:, None])[:, :, None]
            labels = (f"alpha [1e-6/K] ({v})" if not v.startswith("warmup") else f"growth [1e-6] ({v})",)
        out.append((labels, np.asarray(B, dtype=float)))
    return out


def link_bow(robot: Robot, q: np.ndarray, points_mm: np.ndarray | None = None,
             min_length_mm: float = BOW_MIN_MM) -> tuple:
    """Displacement of the points ``points_mm`` (P, 3) carried by the flange (default the tool point) per 1e-6 rad of
    thermal bow of every link at least ``min_length_mm`` long, about two axes across it fixed in the link, shape
    (P, 3, 2L'), and the links' names.

    A temperature difference across a link's section bends it with a uniform curvature ``kappa`` (Timoshenko &
    Goodier: ``alpha dT / D``, ``D`` the depth): its far end turns by ``theta = kappa L`` and shifts by
    ``kappa L^2 / 2`` across it, which is the turn ``theta`` about an axis through the link's midpoint."""
    q = np.atleast_2d(q)
    prefix = poe_prefix(robot.screws, q)
    tip = robot.fk_internal(q)[:, :3, 3] if points_mm is None else np.asarray(points_mm, float)
    start = np.zeros(3)
    cols, names = [], []
    for lk, site in zip(robot.links, robot.link_sites):
        v = np.asarray(lk.vector_mm, float)
        if lk.length_mm >= min_length_mm:
            e = v / np.linalg.norm(v)
            mid = point_at(prefix[:, site], start + v / 2)
            for a0 in across_axes(e):
                cols.append(1e-6 * np.cross(prefix[:, site, :3, :3] @ a0, tip - mid))
            names.append(lk.name)
        start = start + v
    B = np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))
    return B, tuple(names)


def axis_tilt(robot: Robot, q: np.ndarray, points_mm: np.ndarray | None = None) -> tuple:
    """Displacement of the points ``points_mm`` (P, 3) carried by the flange (default the tool point) per 1e-6 rad of
    tilt of every revolute joint's axis, about two axes across it fixed in the link that carries the joint and
    through a point of the axis, shape (P, 3, 2R), and the columns' names (``tilt_<joint>_u [urad]``, ``_v``)."""
    q = np.atleast_2d(q)
    prefix = poe_prefix(robot.screws, q)
    tip = robot.fk_internal(q)[:, :3, 3] if points_mm is None else np.asarray(points_mm, float)
    cols, names = [], []
    for j, jt in enumerate(robot.joints):
        if not jt.is_revolute:
            continue
        w = robot.screws[j, :3]
        p = point_at(prefix[:, j], robot.joint_points_mm[j])
        for a0, ax in zip(across_axes(w), "uv"):
            cols.append(1e-6 * np.cross(prefix[:, j, :3, :3] @ a0, tip - p))
            names.append(f"tilt_{jt.name}_{ax} [urad]")
    B = np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0))
    return B, tuple(names)


def frame_drift(n_poses: int) -> tuple:
    """Apparent displacement of every measured point per micrometre of drift between the measuring frame and the
    robot's base along the base axes x, y, z, shape (P, 3, 3), and the columns' names (``drift_x [um]`` ..,
    :data:`MEASUREMENT_PREFIX`)."""
    return (np.broadcast_to(1e-3 * np.eye(3), (n_poses, 3, 3)).copy(),
            tuple(f"{MEASUREMENT_PREFIX}{a} [um]" for a in "xyz"))


def _bow_basis(grow: np.ndarray, links: tuple, bow_field: tuple, s: np.ndarray, variant: str) -> tuple:
    """(names, B (P, 3, M)) of ``bow``: every link grows (``grow``, ``links``: :func:`link_growth`), and every link
    long enough bows (``bow_field``: :func:`link_bow`), by its own amount times the warm-up ``s`` (P,)."""
    bow, bowed = bow_field
    labels = [f"alpha_{nm} [1e-6] ({variant})" for nm in links]
    labels += [f"bow_{nm}_{ax} [urad] ({variant})" for nm in bowed for ax in ("u", "v")]
    return tuple(labels), np.concatenate([grow, bow], axis=2) * s[:, None, None]


def _motor_basis(robot: Robot, grow: np.ndarray, lj: np.ndarray, heat: np.ndarray, variant: str) -> tuple:
    """(names, B (P, 3, M)) of ``motor``: joint ``j``'s lagged losses ``heat`` (P, 2n) grow the links at its ends."""
    n = robot.n_joints
    cols, labels = [], []
    for part, unit in ((0, "1e-6 per rad/s"), (1, "1e-6 per (N m)^2")):
        for j in range(n):
            h = heat[:, part * n + j]
            links = np.flatnonzero(lj[:, j])
            if np.ptp(h) <= 0 or not len(links):
                continue
            cols.append(grow[:, :, links].sum(axis=2) * h[:, None])
            labels.append(f"{'h' if part == 0 else 'hl'}_{robot.joints[j].name} [{unit}] ({variant})")
    B = np.stack(cols, axis=-1) if cols else np.zeros((grow.shape[0], 3, 0))
    return tuple(labels), B
