"""Datums of a drawing: the letters of the joints' seat axes (robot file, else the stated defaults), the
orientation characteristic of an axis to its datum, and the callouts a datum cannot make bound what they stand for
(:func:`datum_gaps`). Used by :mod:`tolalloc.allocate.drawing`."""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["datum_gaps"]


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.degrees(np.arccos(np.clip(abs(float(a @ b)), 0.0, 1.0))))


def _orientation(axis: np.ndarray, datum_dir: np.ndarray, datum_is_plane: bool) -> str:
    """Perpendicularity, parallelism or angularity of ``axis`` to a datum axis (or plane of normal ``datum_dir``)."""
    ang = _angle(axis, datum_dir)
    if datum_is_plane:
        ang = 90.0 - ang
    if ang < 1e-6:
        return "parallelism"
    return "perpendicularity" if abs(ang - 90.0) < 1e-6 else "angularity"


class _Frame:
    """Spans, datums and seat diameters of the joints (robot file, else the stated defaults)."""

    def __init__(self, robot, settings):
        self.robot, self.settings, self.used = robot, settings, []
        comps = robot.components
        letters = iter("BCDEFGHJKLMNPRSTUVWXYZ")
        self.datum = {}
        for jt in robot.joints:
            b = comps.joint(jt.name).bearing
            own = b.datum if b is not None and b.datum else None
            self.datum[jt.name] = own or (next(letters) if settings.default_datums else "")
            if own is None and settings.default_datums:
                self._note("datums named A (base mounting face), then B, C ... per joint axis in chain order")
        self.base_datum = "A" if settings.default_datums else ""

    def _note(self, text: str) -> None:
        if text not in self.used:
            self.used.append(text)

    def bearing_value(self, j: int, key: str, default, what: str) -> tuple[float, str]:
        jt = self.robot.joints[j]
        b = self.robot.components.joint(jt.name).bearing
        v = getattr(b, key) if b is not None else None
        if v is not None:
            return float(v), "robot file"
        if default is None:
            raise TolallocError(f"joint {jt.name}: no {what} ({key}) in the robot file's [components.joints."
                                f"{jt.name}.bearing] and no default given; add {key} there or pass a default "
                                f"(default_{key}).")
        self._note(f"{what} {default:g} mm where the robot file gives none (assumed default)")
        return float(default), "assumed default"

    def previous(self, j: int):
        """``(datum letter, direction, is_plane)`` of the feature joint ``j``'s seats are located from."""
        letter = self.base_datum if j == 0 else self.datum[self.robot.joints[j - 1].name]
        return (letter, *_datum_feature(self.robot, j))


def _datum_feature(robot, j: int) -> tuple:
    """``(direction, is_plane)`` of the feature joint ``j``'s seats are located from: the base mounting face (normal
    base z) for the first joint, else the axis of the joint before."""
    if j == 0:
        return np.array([0.0, 0.0, 1.0]), True
    return np.asarray(robot.joints[j - 1].axis, float), False


def datum_gaps(model, callouts) -> tuple:
    """The callouts whose datum cannot bound what they stand for, one sentence each.

    * An orientation zone to a datum *axis* (two planes perpendicular to it, ISO 1101) bounds the tilt that changes
      the angle between the feature's axis ``a`` and the datum's ``d``: the component about ``n = d x a``. A tilt
      about another direction (about ``d`` itself where ``a`` is perpendicular to it) leaves the angle unchanged: the
      zone needs a secondary datum that fixes the rotation about ``d`` (the angular locating feature of the datum
      joint's output, a pin or a key).
    * A position zone measured from a datum axis locates the feature across that axis only: a link that runs along
      the datum axis needs a datum plane across it (the datum joint's seat shoulder face).
    """
    robot, out = model.robot, []
    names = [jt.name for jt in robot.joints]
    for c in callouts:
        if c.characteristic in ("perpendicularity", "angularity") and c.direction:
            p = model.params[model.index(c.parameters[0])]
            j = names.index(p.element)
            d, is_plane = _datum_feature(robot, j)
            if is_plane:
                continue
            a = np.asarray(robot.joints[j].axis, float)
            n = np.cross(d, a) / np.linalg.norm(np.cross(d, a))
            w = np.asarray(p.twist[:3], float) / np.linalg.norm(p.twist[:3])
            share = abs(float(w @ n))
            if share < 1.0 - 1e-6:
                part = "none of this one" if share < 1e-6 else f"{share:.0%} of this one"
                fix = (f"the angular locating feature, pin or key, of {names[j - 1]}'s output"
                       if robot.joints[j - 1].is_revolute else f"the anti-rotation guide of {names[j - 1]}'s carriage")
                out.append(f"{c.feature} ({c.symbol} | {c.datum}): a zone to datum axis {c.datum} bounds only the "
                           f"tilt that changes the angle to it, {part}; the rest turns the axis about "
                           f"{c.datum}'s direction -- add a secondary datum that fixes that rotation ({fix}) to the "
                           "callout")
        elif c.characteristic == "position":
            li = [lk.name for lk in robot.links].index(model.params[model.index(c.parameters[0])].element)
            link, site = robot.links[li], int(robot.link_sites[li])
            ddir, is_plane = _datum_feature(robot, site)
            if not is_plane and _angle(link.direction, ddir) < 45.0:
                face = (f"the seat shoulder face of {names[site - 1]}" if robot.joints[site - 1].is_revolute
                        else f"a face of {names[site - 1]}'s carriage across its stroke")
                out.append(f"{c.feature} (⌖ | {c.datum}): {link.name} runs along datum axis {c.datum}, which locates "
                           f"nothing along itself -- the {link.length_mm:g} mm need a datum plane across that axis "
                           f"({face}) in the callout's datum system")
    return tuple(out)
