"""Candidate unmodelled effects, each a small family of linear parametric corrections (its *variants*).

Every effect ``e`` in variant ``v`` contributes a displacement of the target point, linear in ``beta``::

    dx_i = B_e,v(q_i, covariates_i) @ beta      B : (P, 3, M) [mm per unit of beta], robot base frame

built to first order at the nominal geometry (effects are sub-millimetre; the second-order error is
~1e-3 mm). Joint-type effects move joint ``j`` by ``dq_j`` and displace the target by
``(v_j + omega_j x p) dq_j`` (space-Jacobian column ``j`` at the target point ``p``). Which variant an
effect uses is chosen on the training poses (:mod:`tolalloc.diagnose.select`); :func:`variants` lists
those the data can carry.

``joint_compliance``  ``dq_j = c_j tau_j(q)``, per-joint stiffness; ``tau_j`` the gravity torque [N m]
                      (force [N] for a prismatic joint) of the robot's masses, or of the default mass model
                      (:data:`DEFAULT_KG_PER_M` kg per metre of link at the link midpoints) when the robot
                      file has none, plus the logged ``payload_kg`` at the target point. Variants ``masses``
                      (``c_j``) and ``masses+tip`` (also ``d_j`` [rad/(N m)] per unit of a 1 kg point mass at
                      the target: an unknown tool mass or a mass distribution unlike the model's).
``link_deflection``   bending of each arm segment between consecutive revolute joints (spanning prismatic
                      strokes, so a telescopic stage's lever arm grows with its joint) whose horizontal
                      overhang can reach :data:`MIN_OVERHANG_MM`. ``tip``: drop ``k h^3`` [mm] along gravity
                      (``h`` horizontal overhang [m]), slope ``1.5 k h^2 / 1000`` [rad]; ``beam``: Euler-Bernoulli
                      cantilever under its own weight and a tip load, ``drop = (w L^4/8 + f L^3/3) cos(phi)``,
                      ``slope = (w L^3/6 + f L^2/2) cos(phi) / 1000`` (``L`` [m], ``phi`` the elevation).
``backlash``          ``dq_j = b_j s_j`` (half the backlash [rad or mm]); side ``s_j``: ``approach`` (needs
                      ``dir1..dirN``) or ``gravity`` (the sign of the gravity torque holds the gear on one flank).
``thermal``           every link length grows by ``alpha dT L``; ``alpha`` [1e-6/K]. ``dT``: ``temperature``
                      (logged ``temperature_c`` minus the training mean), ``lag_<tau>min`` (the log through a
                      first-order lag, time constant fitted on the grid :data:`LAG_MIN`; needs ``time_s``) or
                      ``warmup_<tau>min`` (``1 - exp(-(t - t0)/tau)`` per unit of growth [1e-6], time driven;
                      needs ``time_s``).
``transmission``      joint-side harmonics ``dq_j = sum_k a_jk sin(k q_j) + b_jk cos(k q_j)`` per revolute
                      joint, orders ``1x`` (once per revolution), ``1x2x``, ``2x3x``; ``motor`` adds the
                      motor-side once-per-motor-revolution term ``sin(N_j q_j), cos(N_j q_j)`` when the gear
                      ratios ``N`` are known (``ref["gear_ratio"]``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.errormodel import build_error_model
from tolalloc.robot.kinematics import poe_prefix
from tolalloc.robot.model import Mass, Robot
from tolalloc.diagnose.measurements import Measurements

__all__ = ["EFFECTS", "EffectBasis", "effect_basis", "effect_bases", "effect_reference", "applicable", "variants", "gravity_torques",
           "robot_masses", "deflection_segments", "joint_effect_dq", "target_points", "point_jacobian", "lagged"]

EFFECTS = ("joint_compliance", "link_deflection", "backlash", "thermal", "transmission")
DEFAULT_KG_PER_M = 10.0
MIN_OVERHANG_MM = 200.0
G = 9.81
LAG_MIN = (5.0, 7.5, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0, 90.0, 120.0, 180.0, 240.0)
HARMONICS = {"1x": (1,), "1x2x": (1, 2), "2x3x": (2, 3)}


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
    """

    effect: str
    names: tuple
    B: np.ndarray
    variant: str = ""


def target_points(robot: Robot, q: np.ndarray, t_mm: np.ndarray) -> np.ndarray:
    """Nominal target position ``T(q) [t; 1]`` in the base frame [mm], shape (P, 3)."""
    T = robot.fk_internal(q)
    return T[:, :3, 3] + T[:, :3, :3] @ np.asarray(t_mm, dtype=float)


def point_jacobian(robot: Robot, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Velocity of the point ``p`` (P, 3) per unit joint rate, ``v_j + omega_j x p``, shape (P, 3, n)."""
    Js = robot.space_jacobian_internal(q)
    return Js[:, 3:, :] + np.cross(Js[:, :3, :], p[:, :, None], axis=1)


def robot_masses(robot: Robot) -> tuple:
    """The robot file's masses, or the default model (10 kg per metre of link, at link midpoints)."""
    if robot.masses:
        return robot.masses
    out, point = [], np.zeros(3)
    for link, site in zip(robot.links, robot.link_sites):
        if link.length_mm > 0:
            out.append(Mass(link.name, int(site), DEFAULT_KG_PER_M * link.length_mm / 1000.0, point + link.vector_mm / 2))
        point = point + link.vector_mm
    return tuple(out)


def _point_load(robot: Robot, P, c, F, below: int) -> np.ndarray:
    """Load of forces ``F`` (P, 3) [N] at points ``c`` (P, 3) [mm] on the joints ``j < below``, shape (P, n)."""
    tau = np.zeros((len(c), robot.n_joints))
    for j in range(min(below, robot.n_joints)):
        w = P[:, j, :3, :3] @ robot.joints[j].axis
        if robot.joints[j].is_revolute:
            pj = P[:, j, :3, :3] @ robot.joint_points_mm[j] + P[:, j, :3, 3]
            tau[:, j] = np.einsum("pi,pi->p", w, np.cross(c - pj, F)) / 1000.0
        else:
            tau[:, j] = np.einsum("pi,pi->p", w, F)
    return tau


def _tip_load(robot: Robot, q, tip_mm) -> np.ndarray:
    """Gravity load of a 1 kg point mass at ``tip_mm`` (P, 3) [mm] on every joint, shape (P, n) [N m / kg, N / kg]."""
    F = np.broadcast_to(G * np.asarray(robot.gravity, dtype=float), tip_mm.shape)
    return _point_load(robot, poe_prefix(robot.screws, np.atleast_2d(q)), tip_mm, F, robot.n_joints)


def gravity_torques(robot: Robot, q: np.ndarray, tip_mm: np.ndarray | None = None,
                    tip_kg: np.ndarray | float = 0.0) -> np.ndarray:
    """Gravity load at every joint, shape (P, n): torque about the axis [N m] (revolute), force [N] (prismatic).

    ``tip_mm`` (P, 3) [mm, base frame] and ``tip_kg`` (P,) or float: an extra point mass (the payload) at the target.
    """
    q = np.atleast_2d(q)
    P = poe_prefix(robot.screws, q)  # (P, n+1, 4, 4)
    g = np.asarray(robot.gravity, dtype=float)
    tau = np.zeros((q.shape[0], robot.n_joints))
    for m in robot_masses(robot):
        c = P[:, m.body, :3, :3] @ m.com_mm + P[:, m.body, :3, 3]
        tau += _point_load(robot, P, c, np.broadcast_to(m.mass_kg * G * g, c.shape), m.body)
    if tip_mm is not None:
        tau += np.broadcast_to(np.asarray(tip_kg, float), (len(q),))[:, None] * _tip_load(robot, q, tip_mm)
    return tau


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
        side = np.where(np.abs(tau) > 1e-6 * scale, np.sign(tau), 0.0) if variant == "gravity" else direction
        for j in range(n):
            if np.any(side[:, j] != side[0, j]):
                cols.append(_one_joint(P, n, j, side[:, j]))
                names.append(f"b_{robot.joints[j].name} [{unit[j]}]")
    elif effect == "transmission":
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
            "gear_ratio": None if gear_ratio is None else np.asarray(gear_ratio, float), "variants": {}}


def lagged(time_s: np.ndarray, temp_c: np.ndarray, tau_s: float) -> np.ndarray:
    """First-order lag of a temperature log (time order), ``dy/dt = (T - y) / tau``, started at ``T[0]``, shape (P,)."""
    order = np.argsort(time_s, kind="stable")
    ts, Ts = time_s[order], temp_c[order]
    y = np.empty_like(Ts)
    y[0] = Ts[0]
    a = 1.0 - np.exp(-np.diff(ts) / tau_s)
    for i in range(1, len(Ts)):
        y[i] = y[i - 1] + a[i - 1] * (Ts[i] - y[i - 1])
    out = np.empty_like(y)
    out[order] = y
    return out


def _temperature_signal(meas: Measurements, ref: dict, variant: str) -> np.ndarray:
    """The ``dT`` driving thermal growth for ``variant`` on the poses of ``meas``, shape (P,)."""
    if variant == "temperature":
        return meas.temperature_c - ref["temperature_c"]
    tau_s = 60.0 * float(variant.split("_")[1][:-3])
    t = meas.time_s
    if variant.startswith("warmup"):
        return 1.0 - np.exp(-np.maximum(t - ref["time0_s"], 0.0) / tau_s)
    # lag: run the filter over the training log and these poses together, in time order
    ht, hT = ref["history"]
    allt, allT = np.concatenate([ht, t]), np.concatenate([hT, meas.temperature_c])
    y = lagged(allt, allT, tau_s)[len(ht):]
    return y - ref["temperature_c"]


def variants(effect: str, meas: Measurements, ref: dict | None = None) -> tuple:
    """The variants of ``effect`` the data can carry (first: the default), empty when none."""
    ref = ref or {}
    T, t = meas.temperature_c, meas.time_s
    if effect == "backlash":
        d = meas.direction
        both = d is not None and np.any((d > 0).any(0) & (d < 0).any(0))
        return ("approach", "gravity") if both else ("gravity",)
    if effect == "thermal":
        out = ["temperature"] if T is not None and np.ptp(T) >= 0.05 else []
        if t is not None and np.ptp(t) > 0:
            if out:
                out += [f"lag_{m:g}min" for m in LAG_MIN]
            out += [f"warmup_{m:g}min" for m in LAG_MIN]
        return tuple(out)
    if effect == "transmission":
        return ("2x3x", "1x", "1x2x") + (("motor",) if ref.get("gear_ratio") is not None else ())
    if effect == "joint_compliance":
        return ("masses", "masses+tip")
    return ("tip", "beam")


def applicable(effect: str, meas: Measurements) -> tuple[bool, str]:
    """Whether the data can carry ``effect`` at all, with the reason when not."""
    if effect == "thermal" and not variants(effect, meas):
        if meas.temperature_c is None:
            return False, "no temperature_c or time_s column"
        return False, f"temperature varies by only {np.ptp(meas.temperature_c):.3g} K and no time_s column"
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
    if effect in ("joint_compliance", "backlash", "transmission"):
        A, names = joint_effect_dq(effect, robot, q, meas.direction, variant=variant, tip_mm=p_t,
                                   payload_kg=meas.payload_kg, gear_ratio=ref.get("gear_ratio"))
        B = np.einsum("pin,pnm->pim", point_jacobian(robot, q, p_t), A)
    elif effect == "link_deflection":
        B, names = _link_deflection(robot, q, p_t, variant)
    else:
        return effect_bases("thermal", robot, meas, t_mm, ref, (variant,))[0]
    return EffectBasis(effect, tuple(names), np.asarray(B, dtype=float), variant)


def effect_bases(effect: str, robot: Robot, meas: Measurements, t_mm, ref: dict, names) -> list:
    """:func:`effect_basis` for every variant in ``names`` (thermal: the link-growth field is computed once)."""
    if effect != "thermal":
        return [effect_basis(effect, robot, meas, t_mm, ref, v) for v in names]
    model = build_error_model(robot, "generic", exclude=("joint_drive", "axis_deflection"))
    J = model.jacobian(meas.q)[:, :3, :]  # (P, 3, L) per mm of each link (a translation: same at the target)
    L = np.array([lk.length_mm for lk in robot.links if lk.length_mm > 0])
    grow = 1e-6 * (J @ L)  # (P, 3) per unit of relative growth 1e-6
    out = []
    for v in names:
        B = (grow * _temperature_signal(meas, ref, v)[:, None])[:, :, None]
        label = f"alpha [1e-6/K] ({v})" if not v.startswith("warmup") else f"growth [1e-6] ({v})"
        out.append(EffectBasis(effect, (label,), np.asarray(B, dtype=float), v))
    return out
