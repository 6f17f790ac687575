"""A step at a pause against a course in time: when the final model names heat through a variant driven by the time
alone, would a single event at one pause between blocks explain the training file as well?

A thermal variant whose driver is the time since the session's start (``warmup``, ``links_warmup``, ``bow``), the
production time between pauses (``tilt_<tau>min``) or a drift of the measuring frame (``drift_<tau>min``) fits any
slow change in time. An event at a pause between blocks of
poses -- a joint slipping on its shaft at a stop, a collision shifting the base or the tracker, a screw loosening --
changes the errors once, and a course in time can take it roughly. :func:`step_check` puts in place of the thermal
basis, in turn, a single step after each pause of the training file (:func:`~tolalloc.physics.rehoming.cycle_blocks`:
a gap of :data:`~tolalloc.physics.thermal_history.PAUSE_STEPS` median intervals) of two kinds:

``frame``  the robot's base shifted against the tracker: a translation and a rotation of every later pose (6 columns);
``zeros``  the revolute joints' zeros stepped: ``J_p dq`` for every later pose (one column per revolute joint),

scores each by the selection's score (the clipped out-of-fold RMS of the training file) and compares the best with
the thermal model. The result is a finding -- it names neither an effect nor a verdict: a step within the practical
margin says an event at that pause fits as well (check the pause before compensating the course as heat); a step
worse by more says the change is gradual. The best of several steps is taken, so the comparison leans towards the
step; it is stated with the number tried.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np

from tolalloc.diagnose.effects import EffectBasis
from tolalloc.diagnose.scores import robust_rms, scheme_text
from tolalloc.physics.blocks import MIN_BLOCK_POSES
from tolalloc.physics.loads import point_jacobian, target_points
from tolalloc.physics.rehoming import cycle_blocks
from tolalloc.physics.thermal import is_clock_variant, is_measurement_variant, variant_parts
from tolalloc.physics.thermal_history import time_problem

__all__ = ["StepCheck", "step_check", "step_basis", "STEP_KINDS", "MAX_STEPS"]

STEP_KINDS = ("frame", "zeros")
#: At most this many pauses are tried (the first ones in time); more blocks are a process, not an event.
MAX_STEPS = 7

_WHAT = {"frame": "the robot's base shifted against the tracker (a translation and a rotation)",
         "zeros": "the joints' zeros stepped (a joint slipping on its shaft, a lost count)"}


@dataclass(frozen=True)
class StepCheck:
    """The best single step at a pause in place of a thermal variant driven by the time alone.

    Attributes
    ----------
    variant : str              the thermal variant of the final model
    kind : str                 ``frame`` or ``zeros`` (module docstring)
    after_block, n_blocks : int  the step lies after block ``after_block`` (0-based) of ``n_blocks``
    at_s : float               the time of the first pose after the pause [s]
    step_rms_mm, course_rms_mm : float  clipped out-of-fold RMS with the step, with the thermal variant [mm]
    n_tried : int              steps scored (pauses x kinds)
    margin : float             the practical margin the two are compared with
    scheme : str               the cross-validation scheme of the RMS
    """

    variant: str
    kind: str
    after_block: int
    n_blocks: int
    at_s: float
    step_rms_mm: float
    course_rms_mm: float
    n_tried: int
    margin: float
    scheme: str

    @property
    def fits_as_well(self) -> bool:
        """Whether the step is within the practical margin of the thermal model (or better)."""
        return self.step_rms_mm <= (1.0 + self.margin) * self.course_rms_mm

    def line(self) -> str:
        """The finding as one line."""
        where = (f"a single step at the pause before t = {self.at_s / 3600.0:.3g} h (after block {self.after_block + 1}"
                 f" of {self.n_blocks}; {_WHAT[self.kind]})")
        nums = (f"clipped out-of-fold RMS {self.step_rms_mm:.4g} against {self.course_rms_mm:.4g} mm ({self.scheme}; "
                f"the best of {self.n_tried} steps tried)")
        event = "an event at that pause (a slip at a stop, a collision, a loosening)"
        if self.step_rms_mm < (1.0 - self.margin) * self.course_rms_mm:
            return (f"finding: {where} in place of thermal ({self.variant}) explains the training file better, by "
                    f"more than the practical margin ({100 * self.margin:g} %): {nums} -- {event} is the likelier "
                    "reading, and the thermal effect may stand for it; check that pause before compensating heat")
        if self.fits_as_well:
            return (f"finding: {where} in place of thermal ({self.variant}) explains the training file within the "
                    f"practical margin ({100 * self.margin:g} %): {nums} -- {event} fits as well as a gradual course; "
                    "check that pause before compensating the course as heat")
        return (f"finding: no single step at a pause explains the training file as well as thermal ({self.variant}): "
                f"the best, {where}, {nums} -- the change is gradual, as heat or another slow process gives it")


def step_basis(robot, meas, t_mm: np.ndarray, after: np.ndarray, kind: str) -> EffectBasis:
    """Columns of a single step for the poses ``after`` (P,) bool, shape (P, 3, m) [mm per unit] (module docstring)."""
    q = meas.q
    p = target_points(robot, q, t_mm)
    on = after.astype(float)[:, None, None]
    if kind == "frame":
        rot = np.stack([np.cross(np.eye(3)[k], p) for k in range(3)], axis=-1)  # (P, 3, 3): e_k x p
        trans = np.broadcast_to(np.eye(3), (len(q), 3, 3))
        B = on * np.concatenate([trans, rot], axis=2)
        names = ("step_x [mm]", "step_y [mm]", "step_z [mm]", "step_rx [rad]", "step_ry [rad]", "step_rz [rad]")
    else:
        rev = np.flatnonzero(robot.revolute_mask)
        B = on * point_jacobian(robot, q, p)[:, :, rev]
        names = tuple(f"step_{robot.joints[j].name} [rad]" for j in rev)
    return EffectBasis("thermal", names, np.ascontiguousarray(B), f"step_{kind}")


def _pauses(meas) -> tuple:
    """Pause blocks of the training poses (P,) and the block indices a step may follow (enough poses each side)."""
    if meas.time_s is None or time_problem(meas.time_s) is not None:
        return None, ()
    block = cycle_blocks(meas.time_s, meas.time_s)
    counts = np.bincount(block)
    ok = [k for k in range(len(counts) - 1)
          if counts[:k + 1].sum() >= MIN_BLOCK_POSES and counts[k + 1:].sum() >= MIN_BLOCK_POSES]
    return block, tuple(ok[:MAX_STEPS])


def _time_only(variant: str) -> bool:
    """Whether the thermal ``variant`` is driven by the time alone: the clock variants, a drift of the measuring frame,
    or heat that tilts the axes (``tilt_<tau>min``: the production time between pauses)."""
    return bool(variant) and (is_clock_variant(variant) or is_measurement_variant(variant)
                              or all(v.startswith("tilt") for v in variant_parts(variant)))


def step_check(ctx, final, evaluate, clip: float, margin: float) -> StepCheck | None:
    """The best single step in place of the final model's thermal variant (module docstring), or None: no thermal
    effect, a variant with a logged driver, or no pause with enough poses on each side.

    ``evaluate``: :func:`tolalloc.diagnose.select.evaluate`; ``clip``: the selection's clip level [mm] (its ranking's
    figures); ``margin``: the practical margin."""
    basis = ctx.bases.get("thermal")
    if "thermal" not in final.effects or basis is None:
        return None
    variant = basis.variant
    if not _time_only(variant):
        return None
    block, after = _pauses(ctx.train)
    if not after:
        return None
    geometric = ctx.cal.geometric
    course = robust_rms(final.selection_mm, clip)
    best, n = None, 0
    for k in after:
        for kind in STEP_KINDS:
            alt = copy.copy(ctx)
            alt.bases = {**ctx.bases, "thermal": step_basis(geometric.model.robot, ctx.train, geometric.t_mm,
                                                            block > k, kind)}
            score = robust_rms(evaluate(alt, final.effects).selection_mm, clip)
            n += 1
            if best is None or score < best[0]:
                best = (score, k, kind)
    score, k, kind = best
    at = float(np.min(ctx.train.time_s[block == k + 1]))
    return StepCheck(variant, kind, int(k), int(block.max()) + 1, at, score, course, n, margin,
                     scheme_text(ctx.cv))
