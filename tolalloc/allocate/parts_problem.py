"""The allocation problem with bought parts: points (pose, payload, ambient), the parts' covariance and mean.

At every point ``i`` the tool error is the machining part ``J e`` (as in :mod:`tolalloc.allocate.problem`) plus the
bought parts' effects (:mod:`tolalloc.errormodel.parts`): a mean ``m_i`` and a covariance. The requirement
``P(|m_i + y_i| < r) >= p`` holds when ``P(|y_i| < r - |m_i|) >= p`` (the triangle inequality), which is the
requirement at radius ``r`` on the covariance scaled by ``s_i = (r / (r - |m_i|))^2``: so every solver and rule of
the machining allocation applies unchanged to the scaled blocks (:class:`PartsProblem`), and the probabilities it
reports are ``P(|y_i| < r - |m_i|)``, a lower bound on the probability with the mean.

The mean depends on the parts only through their stiffness, ratio and the side of the joint's encoder (the
wind-up, the motors' heating, the loop); those define a joint's *signature*. :func:`signature_combos` groups every
slot's options by it; within one combination every option adds a covariance (:class:`OptionBlocks`) and nothing
to the mean, which is what the mixed-integer program needs (:mod:`tolalloc.allocate.parts_discrete`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field, fields

import numpy as np

from tolalloc.allocate.problem import AllocationProblem, build_problem
from tolalloc.errormodel.parts import Conditions, EffectTerms, PartEffects, motor_side, with_parts
from tolalloc.exceptions import TolallocError

__all__ = ["PartsProblem", "Points", "OptionBlocks", "signature_combos", "parts_problem", "option_blocks",
           "compensation_advice", "MAX_COMBOS"]

#: Most combinations of joint signatures (stiffness, ratio, encoder side) the allocation enumerates.
MAX_COMBOS = 32


@dataclass(frozen=True)
class Points:
    """Points of the requirement: poses ``q`` (P, n) [rad, mm], payload ``payload_kg`` (P,), ambient ``ambient_c``
    (P,)."""

    q: np.ndarray
    payload_kg: np.ndarray
    ambient_c: np.ndarray

    def __len__(self) -> int:
        return len(self.q)

    def stack(self, other: "Points") -> "Points":
        return Points(np.vstack([self.q, other.q]), np.concatenate([self.payload_kg, other.payload_kg]),
                      np.concatenate([self.ambient_c, other.ambient_c]))

    @staticmethod
    def grid(q, corners) -> "Points":
        """Every pose of ``q`` (A, n) at every condition corner (C, 2) [kg, degC]."""
        q = np.atleast_2d(q)
        A, C = len(q), len(corners)
        return Points(np.repeat(q, C, axis=0), np.tile(corners[:, 0], A), np.tile(corners[:, 1], A))


@dataclass(frozen=True, eq=False)
class PartsProblem(AllocationProblem):
    """An :class:`~tolalloc.allocate.problem.AllocationProblem` at points, with the chosen parts' covariance
    ``extra_cov`` (P, 3, 3) [mm^2] and mean ``bias_mm`` (P, 3) folded in: blocks and covariances scaled by ``scale``
    (P,) = ``(r / (r - |bias|))^2`` (module docstring). ``points``: the points (``q`` is ``points.q``)."""

    extra_cov: np.ndarray = field(default=None, repr=False)
    bias_mm: np.ndarray = field(default=None, repr=False)
    scale: np.ndarray = field(default=None, repr=False)
    points: Points = field(default=None, repr=False)

    def covariances(self, t, rows=slice(0, 3)) -> np.ndarray:
        """Scaled position covariance (P, 3, 3) of half-widths ``t``: machining plus parts."""
        if rows != slice(0, 3):
            raise TolallocError("the allocation with bought parts has the position requirement only")
        return (super().covariances(t, rows) + self.extra_cov) * self.scale[:, None, None]


def compensation_advice(after: str) -> str:
    """What to advise about compensation where the parts' mean error is too large: turn it on (``after='none'``),
    or compensate more (a smaller residual)."""
    return ("compensate it (`after='compensation'`, or a smaller residual)" if after == "none"
            else "compensate more (a smaller residual)")


def parts_problem(model, points: Points, extra_cov, bias_mm, *, radius_mm: float, prob: float, costs,
                  after: str = "none") -> PartsProblem:
    """The machining problem at ``points`` with the parts' covariance and mean (raises where the mean alone reaches
    the radius: no covariance can meet the requirement there; ``after``, the compensation the mean is stated after,
    chooses the advice)."""
    base = build_problem(model, points.q, radius_mm=radius_mm, prob=prob, costs=costs)
    b = np.linalg.norm(bias_mm, axis=1)
    bad = np.flatnonzero(b >= radius_mm)
    if bad.size:
        i = int(bad[np.argmax(b[bad])])
        raise TolallocError(f"the bought parts' mean error alone is {b[i]:.4g} mm at point {i + 1} (payload "
                            f"{points.payload_kg[i]:g} kg, ambient {points.ambient_c[i]:g} degC), at or above the "
                            f"radius {radius_mm:g} mm: "
                            + compensation_advice(after) + ", choose stiffer parts, or relax the radius")
    s = (radius_mm / (radius_mm - b)) ** 2
    blk = dict(base.blocks[0])
    blk["A"] = blk["A"] * s[:, None, None, None]
    blk["C0"] = (blk["C0"] + extra_cov) * s[:, None, None]
    kw = {f.name: getattr(base, f.name) for f in fields(AllocationProblem)}
    kw["blocks"] = [blk]
    return PartsProblem(**kw, extra_cov=np.asarray(extra_cov, float), bias_mm=np.asarray(bias_mm, float), scale=s,
                        points=points)


def _signature(robot, key, part) -> tuple:
    """What of a slot option reaches the mean: a reducer's curve and ratio, an encoder's side, a motor itself."""
    spec = part.spec
    if key[1] == "reducer":
        return ("reducer", spec.stiffness, spec.torque_bands, spec.ratio, spec.stiffness_sd)
    if key[1] == "encoder":
        return ("encoder", spec.side)
    if key[1] == "motor":
        return ("motor", part.name)
    return ("bearing",)


def signature_combos(robot) -> list:
    """Combinations of the slots' signature groups: a list of ``{slot key: option names}`` (every slot of the robot,
    each with the options of one group). Raises beyond :data:`MAX_COMBOS`."""
    groups = []
    for key, slot in robot.components.slots.items():
        g: dict = {}
        for p in slot.options:
            g.setdefault(_signature(robot, key, p), []).append(p.name)
        groups.append([(key, tuple(v)) for v in g.values()])
    n = int(np.prod([len(g) for g in groups])) if groups else 1
    if n > MAX_COMBOS:
        many = [f"{g[0][0][0]}.{g[0][0][1]} ({len(g)})" for g in groups if len(g) > 1]
        raise TolallocError(f"the slots offer {n} combinations of stiffness, gear ratio and encoder side (slots with "
                            f"more than one: {', '.join(many)}); at most {MAX_COMBOS} are enumerated: fix some of "
                            "these slots to one stiffness or encoder side")
    return [dict(c) for c in itertools.product(*groups)] if groups else [{}]


@dataclass(frozen=True, eq=False)
class OptionBlocks:
    """One signature combination at P points: its fixed terms (mean and covariance) and every slot option's
    covariance.

    Attributes
    ----------
    keys : tuple of (joint, kind)            the slots, in order
    names : tuple of str, (Z,)               option names
    slot : array of int, (Z,)                the slot of each option
    cost : array, (Z,)                       option costs (0 where the catalogue gives none)
    cov : array, shape (Z, P, 3, 3) [mm^2]   covariance each option adds
    terms : tuple of EffectTerms, (Z,)       each option's terms
    fixed : EffectTerms                      terms every design of the combination carries
    fixed_cov, bias_mm : arrays (P, 3, 3), (P, 3)
    """

    keys: tuple
    names: tuple
    slot: np.ndarray
    cost: np.ndarray
    cov: np.ndarray
    terms: tuple
    fixed: EffectTerms
    fixed_cov: np.ndarray
    bias_mm: np.ndarray

    def choice(self, part) -> dict:
        """``{slot key: part name}`` of option indices ``part`` (one per slot)."""
        return {self.keys[self.slot[z]]: self.names[z] for z in part}

    def index(self, choice: dict) -> np.ndarray:
        """Option indices (one per slot) of a choice."""
        return np.array([next(z for z in range(len(self.names)) if self.slot[z] == s and self.names[z] == choice[k])
                         for s, k in enumerate(self.keys)])


def _option_terms(fx: PartEffects, robot, key, name) -> EffectTerms:
    j = [jt.name for jt in robot.joints].index(key[0])
    spec = robot.components.slots[key].resolve(name)
    if key[1] == "reducer":
        return fx.reducer_terms(j, spec, motor_side(fx.robot, j), ("lost_motion", "transmission"))
    if key[1] == "encoder":
        red = fx.robot.components.joint(key[0]).reducer
        return fx.encoder_terms(j, spec, getattr(red, "ratio", None))
    if key[1] == "bearing":   # the runout; the tilt under load is the slot's geometry, the same for every option
        return fx.bearing_terms(j, spec, ("bearing",))
    return EffectTerms.empty(fx.n_points)


def option_blocks(robot, model, points: Points, combo: dict, conditions: Conditions, after: str = "none",
                  residual=None) -> OptionBlocks:
    """The fixed terms and the options' covariances of one signature combination at ``points``."""
    from tolalloc.errormodel.parts import COMPENSATION_RESIDUAL

    residual = COMPENSATION_RESIDUAL if residual is None else residual
    rep = with_parts(robot, {k: v[0] for k, v in combo.items()})
    fx = PartEffects(rep, points.q, points.payload_kg, points.ambient_c, conditions, model)
    fixed = fx.body_terms()
    slotted = {k for k in robot.components.slots}
    for j, jt in enumerate(robot.joints):
        parts = rep.components.joint(jt.name)
        if (jt.name, "reducer") in slotted:
            fixed += fx.reducer_terms(j, parts.reducer, motor_side(rep, j), ("compliance",))
        else:
            fixed += fx.reducer_terms(j, parts.reducer, motor_side(rep, j))
        if (jt.name, "encoder") not in slotted:
            fixed += fx.encoder_terms(j, parts.encoder, getattr(parts.reducer, "ratio", None))
        if (jt.name, "bearing") in slotted:
            fixed += fx.bearing_terms(j, parts.bearing, ("compliance",))
        else:
            fixed += fx.bearing_terms(j, parts.bearing)
    keys = tuple(combo)
    names, slot, cost, cov, terms = [], [], [], [], []
    for s, key in enumerate(keys):
        for name in combo[key]:
            t = _option_terms(fx, robot, key, name)
            part = robot.components.slots[key].part(name)
            names.append(name), slot.append(s), cost.append(part.cost or 0.0), terms.append(t)
            cov.append(t.moments(after, residual)[1])
    mean, fcov = fixed.moments(after, residual)
    P = len(points)
    return OptionBlocks(keys, tuple(names), np.array(slot, int), np.array(cost, float),
                        np.array(cov).reshape(len(names), P, 3, 3), tuple(terms), fixed, fcov, mean)
