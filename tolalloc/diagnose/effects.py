"""Candidate unmodelled effects, each a small family of linear parametric corrections (its *variants*).

Every effect ``e`` in variant ``v`` contributes a displacement of the target point, linear in ``beta``::

    dx_i = B_e,v(q_i, covariates_i) @ beta      B : (P, 3, M) [mm per unit of beta], robot base frame

built to first order at the nominal geometry (effects are sub-millimetre; the second-order error is
~1e-3 mm). Joint-type effects move joint ``j`` by ``dq_j`` and displace the target by
``(v_j + omega_j x p) dq_j`` (space-Jacobian column ``j`` at the target point ``p``). Which variant an
effect uses is chosen on the training poses (:mod:`tolalloc.diagnose.select`); :func:`variants` lists
those the data can carry. The gravity loads behind the gravity-driven effects (mass model, gravity torques) are
in :mod:`.gravity_loads`.

``joint_compliance``  ``dq_j = c_j tau_j(q)``, per-joint stiffness; ``tau_j`` the gravity torque [N m]
                      (force [N] for a prismatic joint) of the robot's masses, or of the default mass model
                      (:data:`.gravity_loads.DEFAULT_KG_PER_M` kg per metre of link at the link midpoints) when the
                      robot file has none, plus the logged ``payload_kg`` at the target point. Variants ``masses``
                      (``c_j``) and ``masses+tip`` (also ``d_j`` [rad/(N m)] per unit of a 1 kg point mass at
                      the target: an unknown tool mass or a mass distribution unlike the model's).
``link_deflection``   bending of each arm segment between consecutive revolute joints (spanning prismatic
                      strokes, so a telescopic stage's lever arm grows with its joint) whose horizontal
                      overhang can reach :data:`MIN_OVERHANG_MM`. ``tip``: drop ``k h^3`` [mm] along gravity
                      (``h`` horizontal overhang [m]), slope ``1.5 k h^2 / 1000`` [rad]; ``beam``: Euler-Bernoulli
                      cantilever under its own weight and a tip load, ``drop = (w L^4/8 + f L^3/3) cos(phi)``,
                      ``slope = (w L^3/6 + f L^2/2) cos(phi) / 1000`` (``L`` [m], ``phi`` the elevation).
                      Robots with a prismatic joint also get ``guide``: the telescopic stage tilts in its guide
                      (bearing compliance or clearance) about the axis perpendicular to the stage and to gravity,
                      by ``g M`` [rad per N m] with ``M`` the bending moment of the masses beyond the guide about the
                      guide point (robot masses + logged payload, and a 1 kg tip mass as a second column); the
                      target moves by ``omega x (p - p_guide)``. ``guide+overlap`` adds the same columns times the
                      extension ``s / stroke`` (the guide's bearing overlap shortens as the stage extends);
                      ``beam+guide`` both mechanisms.
``backlash``          ``dq_j = b_j s_j`` (half the backlash [rad or mm]); side ``s_j``: ``approach`` (needs
                      ``dir1..dirN``), ``gravity`` (the sign of the gravity torque holds the gear on one flank),
                      ``gravity_soft`` (``tanh(tau / (0.1 range))``: a preload that builds up with the torque) or
                      ``preload`` (gravity side where ``|tau|`` exceeds 10 % of its range, the approach direction
                      below: friction, not gravity, decides in the dead band; needs ``dir``).
``thermal``           link growth (:mod:`.thermal`): driven by the logged temperature (``temperature``,
                      ``lag_<tau>min``), by a warm-up with time (``warmup_<tau>min``, one growth;
                      ``links_warmup_<tau>min``, one per link) or by the motion history (``activity_<tau>min``:
                      per link the lagged speed of the joints at its ends). Time-driven variants need a usable
                      ``time_s`` (:func:`.thermal.time_problem`).
``transmission``      joint-side harmonics ``dq_j = sum_k a_jk sin(k q_j) + b_jk cos(k q_j)`` per revolute
                      joint, orders ``1x`` (once per revolution), ``1x2x``, ``2x3x``, ``series<K>`` (all orders
                      1..K: the output-side kinematic error of a strain-wave gear -- flexspline / circular-spline
                      runout and pitch errors -- and encoder eccentricity; only while its ``2 K n_rev`` columns
                      are at most two thirds of the file's coordinates, ``2 P``: the fitted prior keeps a long
                      series well-posed, the bound keeps its fits affordable); ``motor`` adds the once-per-motor-revolution term
                      ``sin(N_j q_j), cos(N_j q_j)`` when the gear ratios ``N`` are known (``ref["gear_ratio"]``).
                      Every transmission variant carries a Gaussian prior per joint (``groups``) whose scale is
                      fitted by marginal likelihood on the training residual (:mod:`.evidence`): a ridge, so a
                      long series does not fit noise (each cross-validation fold refits the scales on its own
                      training poses, :mod:`.select`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Robot
from tolalloc.diagnose.gravity_loads import G, _tip_load, gravity_torques, robot_masses
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.thermal import LAG_MIN, lagged, thermal_bases, thermal_variants, time_problem

__all__ = ["EFFECTS", "EffectBasis", "effect_basis", "effect_bases", "effect_reference", "applicable", "variants",
           "deflection_segments", "joint_effect_dq", "target_points", "point_jacobian", "lagged", "LAG_MIN",
           "SERIES_ORDERS", "guide_joints"]

EFFECTS = ("joint_compliance", "link_deflection", "backlash", "thermal", "transmission")
MIN_OVERHANG_MM = 200.0
HARMONICS = {"1x": (1,), "1x2x": (1, 2), "2x3x": (2, 3)}
#: Highest orders of the ``series<K>`` transmission variants.
SERIES_ORDERS = (6, 12, 24, 36)
#: Dead band of the ``preload`` backlash side and width of ``gravity_soft``, as a fraction of the torque's range.
PRELOAD_BAND = 0.1


@dataclass(frozen=True, eq=False)
class EffectBasis:
    """The displacement basis of one effect on a pose set.

    Attributes
    ----------
    effect : str
    names : tuple of str
        Parameter names with their unit, e.g. ``c_j2 [rad/(N m)]``.
    B : array, shape (P, 3, M) [mm per unit parameter], robot base frame.
    variant : str
    groups : array of int, shape (M,), or None
        Columns sharing one prior scale (transmission: per joint); None: no prior.
    prior_w : array, shape (M,), or None
        Ridge weights ``noise sd / prior sd`` fitted on the training residual (set by the variant choice).
    prior_dof : float or None
        Parameters the training data determine under that prior (``sum gamma`` of :mod:`.evidence`), set with
        ``prior_w``: what the columns cost in degrees of freedom.
    """

    effect: str
    names: tuple
    B: np.ndarray
    variant: str = ""
    groups: np.ndarray | None = None
    prior_w: np.ndarray | None = None
    prior_dof: float | None = None


def target_points(robot: Robot, q: np.ndarray, t_mm: np.ndarray) -> np.ndarray:
    """Nominal target position ``T(q) [t; 1]`` in the base frame [mm], shape (P, 3)."""
    T = robot.fk_internal(q)
    return T[:, :3, 3] + T[:, :3, :3] @ np.asarray(t_mm, dtype=float)


def point_jacobian(robot: Robot, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Velocity of the point ``p`` (P, 3) per unit joint rate, ``v_j + omega_j x p``, shape (P, 3, n)."""
    Js = robot.space_jacobian_internal(q)
    return Js[:, 3:, :] + np.cross(Js[:, :3, :], p[:, :, None], axis=1)


def deflection_segments(robot: Robot) -> list:
    """Arm segments that may bend: ``(start_joint, end_joint or None for the flange, max overhang [mm])``.

    A segment runs from a revolute joint to the next revolute joint (spanning prismatic joints) or to the
    flange; it is kept when its horizontal overhang reaches :data:`MIN_OVERHANG_MM` on a fixed sample of
    400 poses within the joint limits (seed 0), so the list depends on the robot only.
    """
    rev = [j for j in range(robot.n_joints) if robot.joints[j].is_revolute]
    rng = np.random.default_rng(0)
    lo = np.where(robot.revolute_mask, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(robot.revolute_mask, np.minimum(robot.upper, np.pi), robot.upper)
    q = rng.uniform(lo, hi, (400, robot.n_joints))
    segs = []
    for a, j in enumerate(rev):
        k = rev[a + 1] if a + 1 < len(rev) else None
        h = _overhang(robot, q, j, k)[1]
        if h.max() >= MIN_OVERHANG_MM:
            segs.append((j, k, float(h.max())))
    return segs


def _overhang(robot: Robot, q, j, k):
    """Segment end points (P, 3), horizontal overhang [mm] (P,), unit horizontal direction (P, 3), length [mm] (P,)."""
    P = poe_prefix(robot.screws, q)
    g = np.asarray(robot.gravity, dtype=float)
    start = _point_at(P[:, j], robot.joint_points_mm[j])
    end = _point_at(P[:, k], robot.joint_points_mm[k]) if k is not None else robot.fk_internal(q)[:, :3, 3]
    L = end - start
    Lh = L - (L @ g)[:, None] * g
    h = np.linalg.norm(Lh, axis=1)
    return end, h, Lh / np.maximum(h, 1e-9)[:, None], np.linalg.norm(L, axis=1)


def _point_at(Pj, p_home):
    return Pj[:, :3, :3] @ p_home + Pj[:, :3, 3]


def _link_deflection(robot: Robot, q, p_t, variant="tip"):
    g = np.asarray(robot.gravity, dtype=float)
    cols, names = [], []
    for j, k, _ in deflection_segments(robot):
        end, h, u, L = _overhang(robot, q, j, k)
        axis = np.cross(u, g)
        arm = np.cross(axis, p_t - end)
        hm, Lm, cphi = h / 1000.0, L / 1000.0, h / np.maximum(L, 1e-9)
        if variant == "tip":
            terms = [("k", hm ** 3, 1.5e-3 * hm ** 2, "mm/m^3")]
        else:  # beam: own weight (w) and tip load (f), transverse gravity component cos(phi)
            terms = [("w", Lm ** 4 / 8 * cphi, 1e-3 * Lm ** 3 / 6 * cphi, "mm/m^4"),
                     ("f", Lm ** 3 / 3 * cphi, 1e-3 * Lm ** 2 / 2 * cphi, "mm/m^3")]
        for lab, drop, slope, unit in terms:
            cols.append(drop[:, None] * g + slope[:, None] * arm)
            names.append(f"{lab}_{robot.joints[j].name} [{unit}]")
    return np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0)), names


def guide_joints(robot: Robot) -> list:
    """Prismatic joints that are telescopic stages: a revolute joint before them (the stage can swing)."""
    rev = robot.revolute_mask
    return [j for j in range(robot.n_joints) if not rev[j] and rev[:j].any()]


def _guide_deflection(robot: Robot, q, p_t, payload_kg=None, overlap: bool = False):
    """Tilt of every telescopic stage in its guide (module docstring), columns (P, 3, m) and names."""
    Pm = poe_prefix(robot.screws, q)
    g = np.asarray(robot.gravity, dtype=float)
    cols, names = [], []
    masses = robot_masses(robot)
    for j in guide_joints(robot):
        pg = _point_at(Pm[:, j], robot.joint_points_mm[j])
        u = Pm[:, j, :3, :3] @ robot.joints[j].axis
        loads = np.zeros((len(q), 3))
        for m in masses:
            if m.body > j:
                c = Pm[:, m.body, :3, :3] @ m.com_mm + Pm[:, m.body, :3, 3]
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
    return np.stack(cols, axis=-1) if cols else np.zeros((len(q), 3, 0)), names


def _one_joint(P, n, j, values):
    a = np.zeros((P, n))
    a[:, j] = values
    return a


def joint_effect_dq(effect: str, robot: Robot, q, direction=None, *, variant: str = "", tip_mm=None,
                    payload_kg=None, gear_ratio=None):
    """Joint-offset basis of a joint-type effect: ``dq = A @ beta``, ``A`` shape (P, n, M), with names.

    ``variant`` as in the module docstring (default: the first); ``tip_mm`` (P, 3) the target points and
    ``payload_kg`` (P,) the payload (compliance, gravity-held backlash); ``gear_ratio`` (n,) for ``motor``.
    """
    n, P = robot.n_joints, q.shape[0]
    cols, names = [], []
    unit = ["rad" if jt.is_revolute else "mm" for jt in robot.joints]
    if effect in ("joint_compliance", "backlash"):
        tau = gravity_torques(robot, q)
        tip = np.zeros_like(tau) if tip_mm is None else _tip_load(robot, q, tip_mm)
        if payload_kg is not None:
            tau = tau + np.asarray(payload_kg, float)[:, None] * tip
    if effect == "joint_compliance":
        for j in range(n):
            if np.abs(tau[:, j]).max() > 1e-9:
                cols.append(_one_joint(P, n, j, tau[:, j]))
                names.append(f"c_{robot.joints[j].name} [{unit[j]}/(N{' m' if unit[j] == 'rad' else ''})]")
            if variant == "masses+tip" and np.abs(tip[:, j]).max() > 1e-9:
                cols.append(_one_joint(P, n, j, tip[:, j]))
                names.append(f"d_{robot.joints[j].name} [{unit[j]}/kg]")
    elif effect == "backlash":
        scale = np.abs(tau).max(0, keepdims=True)
        span = np.maximum(np.ptp(tau, axis=0, keepdims=True), 1e-12)
        if variant == "gravity":
            side = np.where(np.abs(tau) > 1e-6 * scale, np.sign(tau), 0.0)
        elif variant == "gravity_soft":
            side = np.tanh(tau / (PRELOAD_BAND * span))
        elif variant == "preload":
            side = np.where(np.abs(tau) > PRELOAD_BAND * span, np.sign(tau), direction)
        else:
            side = direction
        for j in range(n):
            if np.any(side[:, j] != side[0, j]):
                cols.append(_one_joint(P, n, j, side[:, j]))
                names.append(f"b_{robot.joints[j].name} [{unit[j]}]")
    elif effect == "transmission":
        if variant.startswith("series"):
            orders = tuple(range(1, int(variant[6:]) + 1))
        else:
            orders = HARMONICS.get(variant or "2x3x", (1,))
        for j in range(n):
            if not robot.joints[j].is_revolute:
                continue
            ks = [(f"{k}x", float(k)) for k in orders]
            if variant == "motor" and gear_ratio is not None:
                ks.append(("m", float(gear_ratio[j])))
            for lab, k in ks:
                for fn, f in (("s", np.sin), ("c", np.cos)):
                    cols.append(_one_joint(P, n, j, f(k * q[:, j])))
                    names.append(f"{fn}{lab}_{robot.joints[j].name} [rad]")
    else:
        raise ValueError(effect)
    return (np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))), names


def effect_reference(meas: Measurements, gear_ratio=None) -> dict:
    """Reference values taken from the training set (kept fixed for held-out poses)."""
    T, t = meas.temperature_c, meas.time_s
    return {"temperature_c": float(np.mean(T)) if T is not None else None,
            "time0_s": float(np.min(t)) if t is not None else None,
            "history": (t, T) if (t is not None and T is not None) else None,
            "motion": (t, meas.q) if t is not None else None,
            "gear_ratio": None if gear_ratio is None else np.asarray(gear_ratio, float), "variants": {}}


def variants(effect: str, meas: Measurements, ref: dict | None = None, robot: Robot | None = None) -> tuple:
    """The variants of ``effect`` the data can carry (first: the default), empty when none.

    ``robot``: adds the guide variants of ``link_deflection`` for robots with a telescopic stage."""
    ref = ref or {}
    if effect == "backlash":
        d = meas.direction
        both = d is not None and np.any((d > 0).any(0) & (d < 0).any(0))
        return ("approach", "gravity", "gravity_soft", "preload") if both else ("gravity", "gravity_soft")
    if effect == "thermal":
        return thermal_variants(meas)
    if effect == "transmission":
        n_rev = int(robot.revolute_mask.sum()) if robot is not None else meas.q.shape[1]
        series = tuple(f"series{K}" for K in SERIES_ORDERS if 2 * K * n_rev <= 2 * meas.n_poses)
        return ("2x3x", "1x", "1x2x") + series + (("motor",) if ref.get("gear_ratio") is not None else ())
    if effect == "joint_compliance":
        return ("masses", "masses+tip")
    guide = ("guide", "guide+overlap", "beam+guide") if robot is not None and guide_joints(robot) else ()
    return ("tip", "beam") + guide


def applicable(effect: str, meas: Measurements) -> tuple[bool, str]:
    """Whether the data can carry ``effect`` at all, with the reason when not."""
    if effect == "thermal" and not variants(effect, meas):
        why_t = time_problem(meas.time_s)
        if meas.temperature_c is None:
            return False, f"no temperature_c column, and {why_t}"
        return False, f"temperature varies by only {np.ptp(meas.temperature_c):.3g} K, and {why_t}"
    return True, ""


def effect_basis(effect: str, robot: Robot, meas: Measurements, t_mm, ref: dict, variant: str | None = None) -> EffectBasis:
    """Displacement basis of ``effect`` on the poses of ``meas`` (target offset ``t_mm`` on the flange).

    ``variant``: see :func:`variants`; default ``ref["variants"][effect]`` or the first the data can carry.
    """
    if effect not in EFFECTS:
        raise ValueError(f"unknown effect {effect!r}; known: {', '.join(EFFECTS)}")
    variant = variant or ref.get("variants", {}).get(effect) or (variants(effect, meas, ref) or ("",))[0]
    q = meas.q
    p_t = target_points(robot, q, t_mm)
    groups = None
    if effect in ("joint_compliance", "backlash", "transmission"):
        A, names = joint_effect_dq(effect, robot, q, meas.direction, variant=variant, tip_mm=p_t,
                                   payload_kg=meas.payload_kg, gear_ratio=ref.get("gear_ratio"))
        B = np.einsum("pin,pnm->pim", point_jacobian(robot, q, p_t), A)
        if effect == "transmission":  # one prior scale per joint
            groups = np.array([int(np.flatnonzero(np.abs(A[:, :, m]).sum(0))[0]) if np.abs(A[:, :, m]).any() else 0
                               for m in range(A.shape[2])], int)
    elif effect == "link_deflection":
        parts = []
        if not variant.startswith("guide"):
            parts.append(_link_deflection(robot, q, p_t, "tip" if variant == "tip" else "beam"))
        if "guide" in variant:
            parts.append(_guide_deflection(robot, q, p_t, meas.payload_kg, overlap=variant == "guide+overlap"))
        B = np.concatenate([b for b, _ in parts], axis=2)
        names = [nm for _, nms in parts for nm in nms]
    else:
        return effect_bases("thermal", robot, meas, t_mm, ref, (variant,))[0]
    return EffectBasis(effect, tuple(names), np.asarray(B, dtype=float), variant, groups)


def effect_bases(effect: str, robot: Robot, meas: Measurements, t_mm, ref: dict, names) -> list:
    """:func:`effect_basis` for every variant in ``names`` (thermal: the link-growth field is computed once)."""
    if effect != "thermal":
        return [effect_basis(effect, robot, meas, t_mm, ref, v) for v in names]
    return [EffectBasis(effect, labels, B, v) for v, (labels, B) in zip(names, thermal_bases(robot, meas, ref, names))]
