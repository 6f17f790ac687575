"""Bought parts: the purchase-list row of a joint drive (reducer and encoder, their grade and catalogue source).

A joint-drive error parameter becomes a :class:`PurchasedPart`: what to buy, the accuracy the order must name (the
allowed transmission + encoder error as a half-width), the catalogue source and, where the part's own figures are
known, whether it meets the requirement. :func:`drive_part` fills it from the robot file's ``[components]`` today;
its ``chooser`` argument (``HandoverSettings.part_chooser``) is the hook for a component catalogue's per-joint
choice of part and grade.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PurchasedPart", "drive_part"]

_ARCSEC = np.pi / 648000.0


@dataclass(frozen=True)
class PurchasedPart:
    """A bought part that bounds a joint-drive error.

    Attributes
    ----------
    part : str
        Part name (catalogue designation, or what to buy).
    joint : str
    parameters : tuple of str
    grade : str
        The accuracy the order must name.
    required : float
        Allowed half-width [rad or mm].
    unit : {"rad", "mm"}
    source : str
        Catalogue source, or ``""`` (none given: the part is to be chosen).
    part_halfwidth : float
        The part's own figure as a half-width [rad or mm] (NaN where unknown).
    """

    part: str
    joint: str
    parameters: tuple
    grade: str
    required: float
    unit: str
    source: str = ""
    part_halfwidth: float = float("nan")

    @property
    def meets(self) -> str:
        """``"yes"``, ``"no"`` or ``""`` (the part's figure is unknown)."""
        if not np.isfinite(self.part_halfwidth):
            return ""
        return "yes" if self.part_halfwidth <= self.required * (1 + 1e-9) else "no"


def drive_part(robot, p, t: float, chooser=None) -> PurchasedPart:
    """The bought part that bounds joint drive ``p`` (an ErrorParameter) of allowed half-width ``t`` [rad or mm].

    ``chooser(joint_name, joint_components, t, unit) -> PurchasedPart or None`` is the hook for a catalogue's
    per-joint choice (part name, grade, source); without one, or where it answers None, the robot file's
    ``[components]`` (reducer and encoder: their figures and sources), else a part to be chosen.
    """
    jt = robot.joints[p.joint_index]
    comps = robot.components.joint(jt.name)
    if chooser is not None:
        chosen = chooser(jt.name, comps, t, p.unit)
        if chosen is not None:
            return chosen
    rev = p.unit == "rad"
    need = (f"transmission error + encoder error within ±{t / _ARCSEC:.4g} arcsec ({2 * t / _ARCSEC:.4g} arcsec "
            "peak-to-peak) at the joint output") if rev else f"positioning error within ±{t * 1000:.4g} um"
    red, enc = comps.reducer, comps.encoder
    names, srcs, half = [], [], 0.0
    if red is not None:
        names.append(f"{red.type.replace('_', ' ')} reducer" + (f" 1:{red.ratio:g}" if red.ratio else ""))
        srcs.append(red.source)
        half = half + red.transmission_accuracy / 2 if red.transmission_accuracy is not None else np.nan
    if enc is not None:
        names.append(f"{enc.side}-side encoder")
        srcs.append(enc.source)
        half = half + enc.accuracy / 2 if enc.accuracy is not None else np.nan
    if not names:
        return PurchasedPart(f"{jt.name} drive (reducer and encoder, to be chosen)", jt.name, (p.name,), need, t,
                             p.unit)
    return PurchasedPart(f"{jt.name} " + " + ".join(names), jt.name, (p.name,), need, t, p.unit,
                         "; ".join(s for s in srcs if s) or "robot file [components] (no source given)", float(half))
