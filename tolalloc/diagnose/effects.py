"""Candidate unmodelled effects: each a family of linear parametric corrections (its *variants*), built from the
physical effect models of :mod:`tolalloc.physics` (the same models the design samples).

Every effect ``e`` in variant ``v`` contributes a displacement of the target point, linear in ``beta``::

    dx_i = B_e,v(q_i, covariates_i) @ beta      B : (P, 3, M) [mm per unit of beta], robot base frame

built to first order at the nominal geometry (effects are sub-millimetre; the second-order error is ~1e-3 mm).
Joint-type effects move joint ``j`` by ``dq_j`` and displace the target by ``(v_j + omega_j x p) dq_j``
(:func:`~tolalloc.physics.loads.point_jacobian`). Which variant an effect uses is chosen on the training poses
(:mod:`tolalloc.diagnose.choice`); :func:`variants` lists those the data can carry. One family per physical
signature:

``joint_compliance``  the joints wind up under gravity, payload and a logged process wrench (``force_x_n`` ...,
                      :mod:`tolalloc.physics.compliance`): ``masses``
                      (linear, ``c_j = 1/K_j`` [rad/(N m)]), ``masses+tip`` (also ``d_j`` per kg at the target: an
                      unknown tool mass), ``masses+force`` (also ``d_j`` and ``h1_j``, ``h2_j`` per N of an
                      unknown constant force at the target, any direction: a hose, cable or balancer pulling one way),
                      ``hardening_<f>`` (a stiffness that rises with torque, smooth law with
                      ``T0 = f`` x the joint's largest load), ``catalogue`` (the reducer's K1/K2/K3 bands from the
                      robot file).
``mount_compliance``  the whole robot tilts on a compliant base under the moment of its masses, payload and wrench
                      (``isotropic``: one compliance; ``axes``: about base x and y; ``pivot``: one compliance
                      about a pivot below the base, its depth fitted) [rad/(N m)]; ``play``: a compliance and a
                      rocking in the moment's direction (a base standing within a clearance) [mrad]; ``tensor``: a
                      symmetric horizontal compliance (principal axes at any heading) about a pivot of fitted depth;
                      with ``time_s``, a support creeping under the moment it holds
                      (:mod:`tolalloc.physics.mount_creep`): ``creep_<tau>min`` (an instant and a delayed
                      compliance), ``flow`` (a viscous support: the tilt grows with the moment's time integral).
``link_deflection``   arm segments bend as beams under the mass model (each mass a point load where it sits, those
                      beyond by their moment), a logged payload and process wrench, and an own weight
                      (:mod:`tolalloc.physics.beams`):
                      ``tip``, ``beam`` (bending and torsion), ``beam+w``, ``beam+tip``; robots with a telescopic
                      stage also ``guide``,
                      ``guide+overlap``, ``beam+guide``; ``flange``: a compliant element between the flange and
                      the tool.
``backlash``          lost motion ``dq_j = s_j b_j / 2`` on the flank ``s_j`` (:mod:`tolalloc.physics.lost_motion`):
                      ``approach`` (needs ``dir1..dirN``), ``gravity``, ``gravity_soft``, ``preload``,
                      ``preload+hysteresis`` (a trailing hysteresis loss ``h_j`` beside the held flank);
                      ``clearance``: the joints' bearing play (axial, radial, tilt; a prismatic joint's roll) taken up
                      on the side the gravity load presses (:mod:`tolalloc.physics.clearance`); ``reseat``: the tool
                      re-seated within its coupling's clearance at each tool change, read from the logged payload in
                      time order (:mod:`tolalloc.physics.seating`).
``thermal``           link growth (:mod:`tolalloc.physics.thermal`): the logged temperature (``temperature``,
                      ``lag_<tau>min``), a warm-up with time (with links that also bow across their section:
                      ``bow_<tau>min``), the motion history (``activity_<tau>min``) or the motors' losses from
                      motion and holding torque (``motor_<tau>min``), heat exchanged with a held part
                      (``held_<tau>min``, the logged payload's history); the position scales the robot file
                      declares growing with the logged air (``scale``, ``scale_lag_<tau>min``,
                      :mod:`tolalloc.physics.thermal_scale`); heat that tilts the joints' axes
                      (``tilt_<tau>min``); a drift between the measuring frame and the base (``drift_<tau>min``).
``transmission``      kinematic error periodic in each revolute joint's angle (:mod:`tolalloc.physics.transmission`):
                      low orders (``1x``, ``1x2x``, ``2x3x``, ``series<K>``), and ``gear``: once per turn plus the
                      strain-wave orders ``N`` and ``2N`` of the gear ratio -- from the robot file's reducers, or
                      found by a frequency search on the training residual (:mod:`.ratio_search`) and used only for
                      the joints whose frequency the poses resolve; ``coupling``: each joint turning in proportion
                      to its own and the other joints' positions; ``stroke`` (a prismatic joint with a bounded
                      stroke): a linear axis' six error motions along its stroke
                      (:mod:`tolalloc.physics.error_motions`); ``rehome``: the zeros of joints with incremental encoders
                      (the robot file's ``homing``) homed anew at each power-up, read from the pauses in ``time_s``
                      (:mod:`tolalloc.physics.rehoming`). Every transmission variant carries a Gaussian prior per
                      joint (``groups``; ``stroke``: one for a joint's translations, one for its rotations) fitted by
                      marginal likelihood (:mod:`.evidence`): a ridge.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.robot.model import Robot
from tolalloc.physics.beams import beam_columns, flange_columns, guide_columns, guide_joints
from tolalloc.physics.clearance import clearance_columns
from tolalloc.physics.error_motions import stroke_columns, stroke_joints
from tolalloc.physics.compliance import HARDENING_FRACTIONS, catalogue_bands, compliance_columns, joint_loads, \
    mount_columns, mount_moment, side_loads, MOUNT_VARIANTS
from tolalloc.physics.mount_creep import creep_columns, creep_signal, creep_variants, is_creep_variant
from tolalloc.physics.loads import point_jacobian, target_points
from tolalloc.physics.lost_motion import GRAVITY_SIDES, SIDES, lost_motion_basis
from tolalloc.physics.rehoming import cycle_blocks, homed_joints, rehome_columns, rehome_problem
from tolalloc.physics.seating import seat_blocks, seat_columns, seat_problem
from tolalloc.physics.thermal import thermal_bases, thermal_variants
from tolalloc.physics.thermal_history import time_problem
from tolalloc.physics.transmission import SERIES_ORDERS, transmission_columns
from tolalloc.diagnose.measurements import Measurements

__all__ = ["EFFECTS", "EffectBasis", "effect_basis", "effect_bases", "effect_reference", "applicable", "variants",
           "joint_effect_dq", "target_points", "point_jacobian", "is_block_parameter"]

EFFECTS = ("joint_compliance", "mount_compliance", "link_deflection", "backlash", "thermal", "transmission")
#: Effects that move the joints (their basis is ``point_jacobian @ A``).
JOINT_EFFECTS = ("joint_compliance", "backlash", "transmission")


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


def joint_effect_dq(effect: str, robot: Robot, q, direction=None, *, variant: str = "", tip_mm=None,
                    payload_kg=None, gear_ratio=None, load_scale=None, wrench=None):
    """Joint-offset basis of a joint-type effect: ``dq = A @ beta``, ``A`` shape (P, n, M), with names.

    ``variant`` as in the module docstring (default: the first); ``tip_mm`` (P, 3) the target points and
    ``payload_kg`` (P,) the payload and ``wrench`` (P, 6) a logged process wrench at the target (compliance,
    gravity-held backlash); ``gear_ratio`` (n,) for ``gear`` and
    ``motor``; ``load_scale`` (n,) the torque scale of ``hardening`` (default: the largest load on these poses --
    pass the training file's for other poses).
    """
    if effect in ("joint_compliance", "backlash"):
        tau, tip = joint_loads(robot, q, tip_mm, payload_kg, wrench)
    if effect == "joint_compliance":
        law = "linear" if variant in ("", "masses", "masses+tip", "masses+force") else variant
        side = side_loads(robot, q, tip_mm) if variant == "masses+force" and tip_mm is not None else None
        return compliance_columns(robot, tau, tip, law, tip_mass=variant in ("masses+tip", "masses+force"),
                                  scale=load_scale, side=side)
    if effect == "backlash":
        return lost_motion_basis(robot, tau, direction, variant or "approach")
    if effect == "transmission":
        A, names, _ = transmission_columns(robot, q, variant or "2x3x", gear_ratio)
        return A, names
    raise ValueError(effect)


def effect_reference(meas: Measurements, gear_ratio=None, robot: Robot | None = None) -> dict:
    """Reference values taken from the training set (kept fixed for held-out poses): the temperature, time origin
    and histories of the thermal drivers, the gear ratios (n,) (NaN where unknown), and the torque scale of the
    hardening law (the training poses' largest gravity load per joint)."""
    T, t = meas.temperature_c, meas.time_s
    scale = None if robot is None else np.abs(joint_loads(robot, meas.q)[0]).max(0)
    return {"temperature_c": float(np.mean(T)) if T is not None else None,
            "time0_s": float(np.min(t)) if t is not None else None,
            "history": (t, T) if (t is not None and T is not None) else None,
            "motion": (t, meas.q) if t is not None else None,
            "payload_history": (t, meas.payload_kg) if (t is not None and meas.payload_kg is not None) else None,
            "load_history": (t, meas.q, meas.payload_kg, meas.wrench) if t is not None else None,
            "gear_ratio": None if gear_ratio is None else np.asarray(gear_ratio, float),
            "load_scale": scale, "variants": {}}


def variants(effect: str, meas: Measurements, ref: dict | None = None, robot: Robot | None = None) -> tuple:
    """The variants of ``effect`` the data can carry (first: the default), empty when none.

    ``robot``: adds the guide variants of ``link_deflection`` for robots with a telescopic stage and the
    ``catalogue`` compliance law for robots whose reducers give K1/K2/K3."""
    ref = ref or {}
    if effect == "backlash":
        d = meas.direction
        both = d is not None and np.any((d > 0).any(0) & (d < 0).any(0))
        reseat = ("reseat",) if seat_problem(meas.time_s, meas.payload_kg) is None else ()
        return (SIDES if both else GRAVITY_SIDES) + ("clearance",) + reseat
    if effect == "thermal":
        return thermal_variants(meas, robot)
    if effect == "transmission":
        n_rev = int(robot.revolute_mask.sum()) if robot is not None else meas.q.shape[1]
        series = tuple(f"series{K}" for K in SERIES_ORDERS if 2 * K * n_rev <= 2 * meas.n_poses)
        ratio = ref.get("gear_ratio")
        gear = ("gear",) if ratio is not None and np.any(np.isfinite(ratio)) else ()
        stroke = ("stroke",) if robot is not None and stroke_joints(robot) else ()
        rehome = ("rehome",) if robot is not None and rehome_problem(meas.time_s, robot) is None else ()
        return ("2x3x", "1x", "1x2x") + series + gear + ("coupling",) + stroke + rehome
    if effect == "joint_compliance":
        cat = ("catalogue",) if robot is not None and catalogue_bands(robot) else ()
        hardening = tuple(f"hardening_{f:g}" for f in HARDENING_FRACTIONS)
        return ("masses", "masses+tip", "masses+force") + hardening + cat
    if effect == "mount_compliance":
        return MOUNT_VARIANTS + creep_variants(meas.time_s)
    guide = ("guide", "guide+overlap", "beam+guide") if robot is not None and guide_joints(robot) else ()
    return ("tip", "beam", "beam+w", "beam+tip", "flange") + guide


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
    variant = variant or ref.get("variants", {}).get(effect) or (variants(effect, meas, ref, robot) or ("",))[0]
    q = meas.q
    p_t = target_points(robot, q, t_mm)
    groups = None
    if effect == "transmission" and variant == "rehome":
        B, names, groups = _rehome_basis(robot, meas, p_t, ref)
    elif effect == "transmission":
        B, names, groups = _transmission_basis(robot, q, p_t, variant, ref.get("gear_ratio"))
    elif effect == "backlash" and variant == "clearance":
        B, names, _ = clearance_columns(robot, q, p_t, p_t, meas.payload_kg)  # no prior: as the flank variants
    elif effect == "backlash" and variant == "reseat":  # the seats as random draws: one prior scale (a ridge)
        B, names = _seat_basis(robot, meas, ref)
        groups = np.zeros(len(names), int)
    elif effect in JOINT_EFFECTS:
        A, names = joint_effect_dq(effect, robot, q, meas.direction, variant=variant, tip_mm=p_t,
                                   payload_kg=meas.payload_kg, gear_ratio=ref.get("gear_ratio"),
                                   load_scale=ref.get("load_scale"), wrench=meas.wrench)
        B = np.einsum("pin,pnm->pim", point_jacobian(robot, q, p_t), A)
    elif effect == "mount_compliance" and is_creep_variant(variant):
        B, names = _creep_basis(robot, meas, p_t, t_mm, ref, variant)
    elif effect == "mount_compliance":
        B, names = mount_columns(robot, q, p_t, p_t, meas.payload_kg, variant, meas.wrench)
    elif effect == "link_deflection":
        parts = [flange_columns(robot, q, p_t, meas.payload_kg, meas.wrench)] if variant == "flange" else []
        if not variant.startswith(("guide", "flange")):
            parts.append(beam_columns(robot, q, p_t, "tip" if variant == "tip" else variant.replace("+guide", ""),
                                      meas.payload_kg, meas.wrench))
        if "guide" in variant:
            parts.append(guide_columns(robot, q, p_t, meas.payload_kg, overlap=variant == "guide+overlap"))
        B = np.concatenate([b for b, _ in parts], axis=2)
        names = [nm for _, nms in parts for nm in nms]
    else:
        return effect_bases("thermal", robot, meas, t_mm, ref, (variant,))[0]
    return EffectBasis(effect, tuple(names), np.asarray(B, dtype=float), variant, groups)


def is_block_parameter(name: str) -> bool:
    """Whether the fitted parameter ``name`` (``effect:column``) belongs to one block of a session -- a tool change
    (backlash ``reseat``) or a power cycle (transmission ``rehome``): poses of a block no fit has seen are predicted
    at the mean only."""
    return name.startswith(("backlash:seat_", "transmission:rehome_"))


def _rehome_basis(robot: Robot, meas: Measurements, p_t: np.ndarray, ref: dict) -> tuple:
    """``(B (P, 3, M), names, groups)`` of ``rehome``: the training file's power cycles, placed by time."""
    if meas.time_s is None:
        raise ValueError("the joint zeros per power cycle need time_s in every file (the training file has it): add "
                         "it to this file, or diagnose without the transmission variant 'rehome'")
    ht, homed = ref["motion"][0], homed_joints(robot)
    units = ["rad" if robot.joints[j].is_revolute else "mm" for j in homed]
    return rehome_columns(point_jacobian(robot, meas.q, p_t)[:, :, homed], cycle_blocks(meas.time_s, ht),
                          np.bincount(cycle_blocks(ht, ht)), [robot.joints[j].name for j in homed], units)


def _creep_basis(robot: Robot, meas: Measurements, p_t: np.ndarray, t_mm, ref: dict, variant: str) -> tuple:
    """``(B (P, 3, 2), names)`` of a creeping mount: the moment held over the training file's poses and these, in
    time order."""
    if meas.time_s is None:
        raise ValueError(f"the mount's creep (variant {variant}) needs time_s in every file (the training file has "
                         "it): add it to this file, or diagnose without the creep variants")
    here = mount_moment(robot, meas.q, p_t, meas.payload_kg, meas.wrench)
    history = None
    if ref.get("load_history") is not None:
        ht, hq, hkg, hw = ref["load_history"]
        history = (ht, mount_moment(robot, hq, target_points(robot, hq, t_mm), hkg, hw))
    return creep_columns(here, creep_signal(meas.time_s, here, variant, history), p_t, variant)


def _seat_basis(robot: Robot, meas: Measurements, ref: dict) -> tuple:
    """``(B (P, 3, M), names)`` of ``reseat``: the blocks of the training file's tool changes, placed by time."""
    ht, hm = ref["payload_history"]
    if meas.time_s is None or meas.payload_kg is None:
        raise ValueError("the re-seat of the tool needs time_s and payload_kg in every file (the training file has "
                         "them): add them to this file, or diagnose without the backlash variant 'reseat'")
    blocks = seat_blocks(meas.time_s, meas.payload_kg, ht, hm)
    return seat_columns(robot, meas.q, blocks, np.bincount(seat_blocks(ht, hm, ht, hm)))


def _transmission_basis(robot: Robot, q, p_t, variant: str, ratios) -> tuple:
    """``(B (P, 3, M), names, groups (M,))`` of transmission: the joints' kinematic error through the point Jacobian,
    one prior group per joint as :func:`~tolalloc.physics.transmission.transmission_columns` gives it, or a linear
    axis' error motions (``stroke``, :func:`~tolalloc.physics.error_motions.stroke_columns`)."""
    if variant == "stroke":
        return stroke_columns(robot, q, p_t)
    A, names, groups = transmission_columns(robot, q, variant or "2x3x", ratios)
    return np.einsum("pin,pnm->pim", point_jacobian(robot, q, p_t), A), names, groups


def effect_bases(effect: str, robot: Robot, meas: Measurements, t_mm, ref: dict, names) -> list:
    """:func:`effect_basis` for every variant in ``names`` (thermal: the link-growth field is computed once)."""
    if effect != "thermal":
        return [effect_basis(effect, robot, meas, t_mm, ref, v) for v in names]
    bases = thermal_bases(robot, meas, ref, names, target_points(robot, np.atleast_2d(meas.q), t_mm))
    return [EffectBasis(effect, labels, B, v) for v, (labels, B) in zip(names, bases)]
