"""Datums of a drawing: the letters of the joints' seat axes and of the features that complete a datum system (the
robot file, else the stated defaults), the orientation characteristic of an axis to its datum, and the callouts one
datum axis cannot make bound what they stand for (:func:`complete_datums`, :func:`datum_gaps`). Used by
:mod:`tolalloc.allocate.drawing` and, for a drawing read back, :mod:`tolalloc.allocate.drawing_io`."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["datum_gaps", "complete_datums", "datum_letters", "DATUM_PATTERN"]

#: A datum letter (ISO 5459: capital letters; the defaults skip I, O and Q) or a datum system of up to three, in
#: order of precedence, separated by ``|`` as in the feature control frame (``B|J``).
DATUM_PATTERN = re.compile(r"[A-Z]{1,2}(\|[A-Z]{1,2}){0,2}")
_POOL = "BCDEFGHJKLMNPRSTUVWXYZ"


def datum_letters(datum: str) -> tuple:
    """The letters of a datum or datum system in order of precedence (``"B|J"`` -> ``("B", "J")``)."""
    return tuple(s.strip() for s in str(datum).split("|") if s.strip())


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


def _what(robot, i: int, kind: str) -> str:
    """The feature of joint ``i`` a ``kind`` datum is: the seat axis, the angular locating feature of its output or
    a face across its axis."""
    jt = robot.joints[i]
    if kind == "axis":
        return f"{jt.name} bearing-seat axis" if jt.is_revolute else f"{jt.name} guide axis"
    if kind == "locating":
        return (f"the angular locating feature, pin or key, of {jt.name}'s output" if jt.is_revolute
                else f"the anti-rotation guide of {jt.name}'s carriage")
    return f"the seat shoulder face of {jt.name}" if jt.is_revolute else f"a face of {jt.name}'s carriage across its stroke"


def _bearing(robot, name: str):
    """The joint's bearing figures: its own table, else its catalogue slot's seat geometry (the same for every
    option of the slot; the class of the option does not enter a drawing's datums, spans or seat diameters)."""
    b = robot.components.joint(name).bearing
    slot = robot.components.slots.get((name, "bearing"))
    return b if b is not None or slot is None else slot.resolve(slot.options[0].name)


class _Frame:
    """Spans, datums and seat diameters of the joints (robot file, else the stated defaults)."""

    def __init__(self, robot, settings):
        self.robot, self.settings, self.used = robot, settings, []
        self._bearings = [_bearing(robot, jt.name) for jt in robot.joints]
        given = {x for b in self._bearings if b is not None
                 for x in (b.datum, b.locating_datum, b.shoulder_datum) if x}
        letters = (c for c in _POOL if c not in given)
        self.datum, self.features = {}, {}
        self.base_datum = "A" if settings.default_datums else ""
        if self.base_datum:
            self.features["A"] = ("the base mounting face", "assumed letter")
        for i, (jt, b) in enumerate(zip(robot.joints, self._bearings)):
            own = b.datum if b is not None and b.datum else None
            self.datum[jt.name] = own or (next(letters) if settings.default_datums else "")
            if own is None and settings.default_datums:
                self._note("datums named A (base mounting face), then B, C ... per joint axis in chain order")
            if self.datum[jt.name]:
                self._feature(self.datum[jt.name], _what(robot, i, "axis"), "robot file" if own else "assumed letter")
        self._spare = (c for c in _POOL if c not in given and c not in self.datum.values())

    def _note(self, text: str) -> None:
        if text not in self.used:
            self.used.append(text)

    def _feature(self, letter: str, what: str, source: str) -> None:
        if letter in self.features and self.features[letter][0] != what:
            raise TolallocError(f"datum {letter} names two features: {self.features[letter][0]} and {what}; give "
                                "each datum feature its own letter in the robot file's [components.joints.<joint>."
                                "bearing] (datum, locating_datum, shoulder_datum).")
        self.features[letter] = (what, source)

    def secondary(self, i: int, kind: str) -> str:
        """The letter of joint ``i``'s ``kind`` (``"locating"`` or ``"shoulder"``) datum feature: the robot file's
        ``locating_datum`` / ``shoulder_datum``, else the next free letter (with ``default_datums``), else ``""``."""
        b = self._bearings[i]
        own = getattr(b, f"{kind}_datum") if b is not None else None
        what = _what(self.robot, i, kind)
        for letter, (w, _) in self.features.items():
            if w == what:
                return letter
        if own is None and not self.settings.default_datums:
            return ""
        letter = own or next(self._spare)
        if own is None:
            self._note("the features that complete a datum system (an output's angular locating feature, a seat "
                       "shoulder face) named with the letters after the joint axes'")
        self._feature(letter, what, "robot file" if own else "assumed letter")
        return letter

    def bearing_value(self, j: int, key: str, default, what: str) -> tuple[float, str]:
        jt = self.robot.joints[j]
        b = self._bearings[j]
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


def _need(model, c) -> tuple | None:
    """``(kind, i, sentence)`` where callout ``c``'s datum axis alone cannot bound what it stands for, else None.

    * An orientation zone to a datum *axis* (two planes perpendicular to it, ISO 1101) bounds the tilt that changes
      the angle between the feature's axis ``a`` and the datum's ``d``: the component about ``n = d x a``. A tilt
      about another direction (about ``d`` itself where ``a`` is perpendicular to it) leaves the angle unchanged:
      the zone needs a secondary datum that fixes the rotation about ``d`` (kind ``"locating"``: the angular
      locating feature of the datum joint ``i``'s output, a pin or a key).
    * A position zone measured from a datum axis locates the feature across that axis only: a link that runs along
      the datum axis needs a datum plane across it (kind ``"shoulder"``: the datum joint's seat shoulder face).
    """
    robot = model.robot
    names = [jt.name for jt in robot.joints]
    letters = datum_letters(c.datum) or ("(none)",)
    if c.characteristic in ("perpendicularity", "angularity") and c.direction:
        p = model.params[model.index(c.parameters[0])]
        j = names.index(p.element)
        d, is_plane = _datum_feature(robot, j)
        if is_plane:
            return None
        a = np.asarray(robot.joints[j].axis, float)
        n = np.cross(d, a) / np.linalg.norm(np.cross(d, a))
        w = np.asarray(p.twist[:3], float) / np.linalg.norm(p.twist[:3])
        share = abs(float(w @ n))
        if share >= 1.0 - 1e-6:
            return None
        part = "none of this one" if share < 1e-6 else f"{share:.0%} of this one"
        return ("locating", j - 1,
                f"a zone to datum axis {letters[0]} bounds only the tilt that changes the angle to it, {part}; "
                f"the rest turns the axis about {letters[0]}'s direction -- add a secondary "
                f"datum that fixes that rotation ({_what(robot, j - 1, 'locating')}) to the callout")
    if c.characteristic == "position":
        li = [lk.name for lk in robot.links].index(model.params[model.index(c.parameters[0])].element)
        link, site = robot.links[li], int(robot.link_sites[li])
        ddir, is_plane = _datum_feature(robot, site)
        if not is_plane and _angle(link.direction, ddir) < 45.0:
            return ("shoulder", site - 1,
                    f"{link.name} runs along datum axis {letters[-1]}, which locates nothing along "
                    f"itself -- the {link.length_mm:g} mm need a datum plane across that axis "
                    f"({_what(robot, site - 1, 'shoulder')}) in the callout's datum system")
    return None


def complete_datums(model, callouts, frame: _Frame) -> tuple:
    """``(callouts, gaps)``: each callout a datum axis alone cannot make bound its parameter (:func:`_need`) given
    the datum system it needs -- ``axis|locating`` for an orientation zone, ``shoulder|axis`` for a position -- where
    ``frame`` has the letter; the others' sentences in ``gaps``."""
    out, gaps = [], []
    for c in callouts:
        need = _need(model, c)
        letter = frame.secondary(need[1], need[0]) if need is not None and c.datum else ""
        if need is None:
            out.append(c)
        elif not letter:
            out.append(c)
            gaps.append(f"{c.feature} ({c.symbol} | {c.datum}): {need[2]}")
        else:
            out.append(replace(c, datum=f"{c.datum}|{letter}" if need[0] == "locating" else f"{letter}|{c.datum}"))
    return tuple(out), tuple(gaps)


def datum_gaps(model, callouts) -> tuple:
    """The callouts whose datum cannot bound what they stand for, one sentence each: those :func:`_need` names
    whose datum is a single letter (a datum system of two or more letters is taken to carry the feature named)."""
    out = []
    for c in callouts:
        need = _need(model, c)
        if need is not None and len(datum_letters(c.datum)) < 2:
            out.append(f"{c.feature} ({c.symbol} | {c.datum}): {need[2]}")
    return tuple(out)
