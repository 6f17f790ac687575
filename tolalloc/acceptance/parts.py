"""The bought parts in the ISO 9283 acceptance test: :func:`parts_effects`, an
:class:`~tolalloc.acceptance.model.ErrorEffects` of a robot's resolved parts.

The parts model (:class:`tolalloc.errormodel.parts.PartEffects`) gives each effect at each pose a mean, a systematic
and a random part, one pose at a time. The test's statistics combine poses (the registration, a barycentre over the
cycles, two poses' distance), so they need more: how one built robot's effect at one pose goes with the same robot's
at another, and which parts a cycle of the test repeats. Per effect, with ``c_m`` the term's tool pose column at
pose ``m`` (position [mm] and rotation [rad] per unit value)::

    effect                      what one built robot keeps                       joint covariance over the poses
    compliance, thermal,        mean at the test load and temperature;           rank one: v_m = c_m s_m sign(mean_m)
    beam, mount                 a relative spread common to all its poses
    bearing                     a body displacement fixed in its link            rank one: v_m = c_m s
    transmission, encoder       sinusoids of the joint angle, random phases      sum_k a_k^2 / 2 cos(n_k (q_m - q_m'))
                                                                                 c_m c_m'^T
    lost motion                 the flank each pose is approached on             (b / 2)^2 c_m c_m^T per pose, none
                                                                                 between poses
    homing                      an incremental encoder's zero, set at power-up   rank one: v_m = c_m h / sqrt(3)
    gear repeatability          nothing: new at every move                       random, per pose

``s_m`` is the term's systematic sd at pose ``m``, ``a_k, n_k`` the amplitudes and orders of
:func:`~tolalloc.errormodel.parts.gear_harmonics` and :func:`~tolalloc.errormodel.parts.encoder_harmonics``. The
test approaches each pose the same way in every cycle (ISO 9283, 7.2.1: the poses visited in the same sequence),
so a gear rests on the same flank through the cycles: its lost motion is an offset of that pose, which an accuracy
sees and a repeatability does not; the flank at another pose is drawn independently (the approach directions are the
test path's, which the design does not know). The means enter the accuracies as the mean of the statistic's vector
(:meth:`~tolalloc.acceptance.model.StatisticModel.effect_mean`): every robot built to the design shares them. The
test runs in one power cycle, so the zero an incremental encoder was homed to holds through it: a robot keeps it at
every pose, like a systematic part (it changes at the next power-up, which no calibration follows). Over a small
cube it is nearly a rigid shift, which a registration on the cube's corners takes out: ``AP`` sees it where the test
measures in the robot's base frame (``registration="none"``). Where the test knows how a pose is approached
(``approach``: a multi-directional accuracy's visits, the tool moving along a base axis), a joint that moves into
the pose rests on its trailing flank, ``-dir b / 2``: every robot built with that gear has it, a mean of that visit
(the catalogue's lost motion taken whole, the conservative reading of a maximum); a compensation does not remove it.
A joint that hardly moves in the approach (direction 0) keeps the flank an earlier move left, drawn independently
per visit, as at the other poses (the moves before the approach are not known).

The load is the requirement's: ``load_pct`` of the rated payload (``[components.payload] rated_kg``) at its centre
of mass; the temperature the test room's (``ambient_c``, the reference temperature by default), with the motors'
heat at ``duty``. ``after="compensation"`` keeps ``residual`` of every mean and systematic part
(:func:`~tolalloc.errormodel.parts.residual_factors`), as the parts allocation does.
"""

from __future__ import annotations

import numpy as np

from tolalloc.acceptance.model import EffectCovariance
from tolalloc.errormodel.parts import (COMPENSATION_RESIDUAL, Conditions, PartEffects, encoder_harmonics,
                                       gear_harmonics, residual_factors, stroke_of)
from tolalloc.exceptions import TolallocError

__all__ = ["parts_effects", "effect_covariance"]

_RANK_ONE = ("compliance", "thermal", "beam", "mount", "bearing")


def parts_effects(*, after: str = "none", residual=COMPENSATION_RESIDUAL, ambient_c: float | None = None,
                  duty: float = 0.5):
    """The bought parts of the test's robot as an :class:`~tolalloc.acceptance.model.ErrorEffects` (module
    docstring): pass it as ``effects=`` to :func:`~tolalloc.acceptance.predict.predict_acceptance` or
    :func:`~tolalloc.acceptance.simulate.simulate_acceptance`. The robot's catalogue slots must be resolved
    (:func:`tolalloc.errormodel.parts.with_parts`, or the parts allocation's robot).

    Parameters
    ----------
    after : {"none", "compensation"}
    residual : float or dict
        With ``after="compensation"``: the share of every mean and systematic part the compensation leaves.
    ambient_c : float, optional
        The test room's temperature [degC] (default: the robot's reference, 20 degC).
    duty : float
        Fraction of time the motors carry the pose's load (their heat).
    """
    residual_factors(after, residual)
    if ambient_c is not None and not np.isfinite(float(ambient_c)):
        raise TolallocError(f"ambient_c: expected a temperature [degC], got {ambient_c!r}")
    if not 0.0 <= float(duty) <= 1.0:
        raise TolallocError(f"duty: expected a fraction of time in [0, 1], got {duty!r}")

    def effects(robot, q, conditions, approach=None) -> EffectCovariance:
        return effect_covariance(robot, q, conditions.load_pct, after=after, residual=residual, ambient_c=ambient_c,
                                 duty=duty, approach=approach)

    return effects


def _check_resolved(robot) -> None:
    comps = robot.components
    open_slots = [f"{j}.{kind}" for (j, kind), slot in comps.slots.items()
                  if getattr(comps.joint(j), kind) is None and len(slot.options) > 1]
    if open_slots:
        raise TolallocError(f"robot {robot.name!r}: the catalogue slots {', '.join(sorted(open_slots))} hold no "
                            "chosen part; choose them first (tolalloc.errormodel.parts.with_parts(robot, {(joint, "
                            "kind): part}), or the parts allocation's robot)")


def effect_covariance(robot, q, load_pct: float, *, after: str = "none", residual=COMPENSATION_RESIDUAL,
                      ambient_c: float | None = None, duty: float = 0.5, approach=None) -> EffectCovariance:
    """The parts' mean and covariances at the evaluation poses ``q`` (M, n) [rad, mm] under ``load_pct`` of the
    rated payload (module docstring); ``approach`` (M, n): each joint's direction of motion into the pose (+1 / -1,
    0 or None unknown)."""
    _check_resolved(robot)
    rated = robot.components.payload.rated_kg
    if rated is None and load_pct > 0:
        raise TolallocError(f"robot {robot.name!r}: the test load is {load_pct:g} % of the rated payload, which the "
                            "robot file does not give; add [components.payload] rated_kg, or test at load_pct = 0")
    payload = (rated or 0.0) * load_pct / 100.0
    ref = Conditions().reference_c
    amb = ref if ambient_c is None else float(ambient_c)
    fx = PartEffects(robot, q, payload, amb, Conditions((payload, payload), (amb, amb), ref, duty), rotations=True)
    terms = fx.terms()
    f = residual_factors(after, residual)
    ft = np.array([f.get(e, 1.0) for e in terms.effect])
    col = np.concatenate([terms.columns, terms.rotation], axis=1)          # (M, 6, T)
    M = len(fx.q)
    mean = np.einsum("mat,mt->ma", col, terms.mean * ft).ravel()
    sys, rnd = np.zeros((M * 6, M * 6)), np.zeros((M, 6, 6))
    blocks = sys.reshape(M, 6, M, 6)             # a view: pose m's block is blocks[m, :, m, :]
    poses = np.arange(M)
    known = np.zeros((M, robot.n_joints)) if approach is None else np.asarray(approach, float)
    for t, effect in enumerate(terms.effect):
        c, r = col[:, :, t], terms.rnd_sd[:, t]
        if effect in _RANK_ONE:
            v = (c * (terms.sys_sd[:, t] * np.where(terms.mean[:, t] < 0, -1.0, 1.0) * ft[t])[:, None]).ravel()
            sys += np.outer(v, v)
        elif effect in ("transmission", "encoder"):
            K = _periodic_kernel(robot, terms.joint[t], effect, fx.q) * ft[t] ** 2
            sys += np.einsum("mn,ma,nb->manb", K, c, c).reshape(M * 6, M * 6)
        # the part the parts model calls random: a zero kept through the power cycle (homing), a flank kept through
        # the cycles at each pose (lost motion), else new at every move
        per_pose = r[:, None, None] ** 2 * np.einsum("ma,mb->mab", c, c)
        if effect == "homing":
            v = (c * r[:, None]).ravel()
            sys += np.outer(v, v)
        elif effect == "lost_motion":
            side = -known[:, terms.joint[t]]                   # the trailing flank, 0 where the approach is unknown
            mean += (c * (r * side)[:, None]).ravel()
            blocks[poses, :, poses, :] += per_pose * (side == 0)[:, None, None]
        else:
            rnd += per_pose
    return EffectCovariance(0.5 * (sys + sys.T), rnd, mean)


def _periodic_kernel(robot, j: int, effect: str, q: np.ndarray) -> np.ndarray:
    """``sum_k a_k^2 / 2 cos(n_k (q_m - q_m'))``, shape (M, M): the covariance over the poses of joint ``j``'s gear
    or encoder error at random phases."""
    parts = robot.components.joint(robot.joints[j].name)
    rev = robot.joints[j].is_revolute
    if effect == "transmission":
        orders, amps = gear_harmonics(parts.reducer, rev, stroke_of(robot, j))
    else:
        orders, amps = encoder_harmonics(parts.encoder, getattr(parts.reducer, "ratio", None), rev)
    d = q[:, j][:, None] - q[:, j][None, :]
    return np.einsum("k,kmn->mn", amps ** 2 / 2, np.cos(orders[:, None, None] * d[None]))
