"""Datums of a drawing: the letters of the joints' seat axes and of the features that complete a datum system (the
robot file, else the stated defaults), the orientation characteristic of an axis to its datum, and the callouts one
datum cannot make bound what they stand for (:func:`complete_datums`, :func:`datum_gaps`). Used by
:mod:`tolalloc.allocate.drawing` and, for a drawing read back, :mod:`tolalloc.allocate.drawing_io`.

A zone of two parallel planes to a datum axis or plane, or a cylinder at an angle to it, is fixed by that datum
only up to a rotation about the datum's direction (ISO 1101, ISO 5459): it bounds the tilt it stands for only where
that rotation leaves it unchanged -- planes perpendicular to the datum axis (parallel to the datum plane), a
cylinder along the datum's direction. Elsewhere the datum system gains, as its secondary datum, a feature that fixes
that rotation: the locating pin hole or keyway of the datum joint's output flange (the base: of its mounting face; a
slide: its anti-rotation guide). A position along a datum axis, which locates nothing along itself, gains a face
across it: the shoulder of the datum joint's axially locating bearing seat. The datum features themselves are taken
as perfect relative to their axes (stated in the handover's assumptions).
"""

from __future__ import annotations

import re
from dataclasses import replace
from itertools import chain, product

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.robot.components_io import DATUM_LETTER

__all__ = ["datum_gaps", "complete_datums", "datum_letters", "DATUM_PATTERN"]

#: A datum letter (ISO 5459: capital letters; the defaults skip I, O and Q), a common datum (``B-C``), or a datum
#: system of up to three, in order of precedence, separated by ``|`` as in the feature control frame (``B|J``; spaces
#: around ``|`` allowed).
_ONE = f"{DATUM_LETTER}(-{DATUM_LETTER})?"
DATUM_PATTERN = re.compile(f"{_ONE}( *\\| *{_ONE}){{0,2}}")
_POOL = "BCDEFGHJKLMNPRSTUVWXYZ"
_KEYS = ("datum", "locating_datum", "shoulder_datum")
_PARALLEL = 1.0 - 1e-6


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
    """The feature of joint ``i`` (``-1``: the base) a ``kind`` datum is: the seat axis, the feature that fixes the
    rotation about it, or a face across it."""
    if i < 0:
        return "the base mounting face" if kind == "axis" else "the locating pin hole of the base mounting face"
    jt = robot.joints[i]
    if kind == "axis":
        return f"{jt.name} bearing-seat axis" if jt.is_revolute else f"{jt.name} guide axis"
    if kind == "locating":
        return (f"the locating pin hole or keyway of {jt.name}'s output flange" if jt.is_revolute
                else f"the anti-rotation guide of {jt.name}'s carriage")
    return (f"the shoulder face of {jt.name}'s axially locating bearing seat" if jt.is_revolute
            else f"a face of {jt.name}'s carriage across its stroke")


def _bearing(robot, name: str):
    """The joint's bearing figures: its own table, else its catalogue slot's seat geometry (the same for every
    option of the slot; the class of the option does not enter a drawing's datums, spans or seat diameters); a
    prismatic joint's guide letters."""
    parts = robot.components.joint(name)
    if parts.guide is not None:
        return parts.guide
    slot = robot.components.slots.get((name, "bearing"))
    return parts.bearing if parts.bearing is not None or slot is None else slot.seat()


def _letters():
    """Default letters: B ... Z without I, O, Q, then two-letter names (AA, AB ...)."""
    return chain(_POOL, ("".join(p) for p in product("A" + _POOL, repeat=2)))


class _Frame:
    """Spans, datums and seat diameters of the joints (robot file, else the stated defaults)."""

    def __init__(self, robot, settings):
        self.robot, self.settings, self.used = robot, settings, []
        self._bearings = [_bearing(robot, jt.name) for jt in robot.joints]
        self._mount = robot.components.mount
        given = self._check_letters()
        letters = (c for c in _letters() if c not in given)
        self.datum, self.features = {}, {}
        self.base_datum = self._mount.datum or ("A" if settings.default_datums else "")
        if self.base_datum:
            self.features[self.base_datum] = ("the base mounting face",
                                              "robot file" if self._mount.datum else "assumed letter")
        for i, (jt, b) in enumerate(zip(robot.joints, self._bearings)):
            own = b.datum if b is not None and b.datum else None
            self.datum[jt.name] = own or (next(letters) if settings.default_datums else "")
            if own is None and settings.default_datums:
                self._note("datums named A (base mounting face) and, where the robot file names none, the joint "
                           "axes B, C ... in chain order")
            if self.datum[jt.name]:
                self.features[self.datum[jt.name]] = (_what(robot, i, "axis"), "robot file" if own else "assumed letter")
        self._spare = (c for c in _letters() if c not in given and c not in self.datum.values())

    def _check_letters(self) -> set:
        """The robot file's letters, refused where one names two features (or the base face's A)."""
        m = self._mount
        seen = {x: f"components.mount.{k}" for k, x in (("datum", m.datum), ("locating_datum", m.locating_datum)) if x}
        if m.locating_datum and m.locating_datum == m.datum:
            raise TolallocError(f"components.mount.locating_datum = {m.datum!r}: the same letter as the base face's "
                                "datum; give each datum feature its own letter.")
        if not m.datum and self.settings.default_datums:
            seen.setdefault("A", "the base mounting face")
        for jt, b in zip(self.robot.joints, self._bearings):
            for key in _KEYS if b is not None else ():
                letter = getattr(b, key)
                if letter is None:
                    continue
                where = f"components.joints.{jt.name}.{'bearing' if jt.is_revolute else 'guide'}.{key}"
                if letter in seen:
                    raise TolallocError(f"{where} = {letter!r}: datum {letter} already names {seen[letter]}"
                                        f"{' (A is the base mounting face)' if letter == 'A' else ''}; give each "
                                        "datum feature its own letter.")
                seen[letter] = where
        return set(seen)

    def _note(self, text: str) -> None:
        if text not in self.used:
            self.used.append(text)

    def secondary(self, i: int, kind: str) -> str:
        """The letter of joint ``i``'s (``-1``: the base's) ``kind`` (``"locating"`` or ``"shoulder"``) datum
        feature: the robot file's ``locating_datum`` / ``shoulder_datum``, else the next free letter (with
        ``default_datums``), else ``""``."""
        b = self._bearings[i] if i >= 0 else self._mount
        own = getattr(b, f"{kind}_datum", None) if b is not None else None
        what = _what(self.robot, i, kind)
        for letter, (w, _) in self.features.items():
            if w == what:
                return letter
        if own is None and not self.settings.default_datums:
            return ""
        letter = own or next(self._spare)
        if own is None:
            self._note("the features that complete a datum system (a locating pin hole or keyway, a seat shoulder "
                       "face) named with the letters after the joint axes'")
        self.features[letter] = (what, "robot file" if own else "assumed letter")
        return letter

    def bearing_value(self, j: int, key: str, default, what: str) -> tuple[float, str]:
        jt = self.robot.joints[j]
        b = self._bearings[j]
        v = getattr(b, key, None)
        if v is not None:
            return float(v), "robot file"
        if key == "seat_diameter_mm" and getattr(b, "bore_mm", None) is not None:
            self._note("seat diameter taken as the bearing's bore where the robot file gives no seat diameter (the "
                       "shaft seat of the inner ring)")
            return float(b.bore_mm), "robot file (the bearing's bore)"
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


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _orientation_need(model, c) -> tuple | None:
    """``("locating", i, sentence)`` where the orientation zone of ``c`` can turn about its datum's direction."""
    robot = model.robot
    p = model.params[model.index(c.parameters[0])]
    j = [jt.name for jt in robot.joints].index(p.element)
    d, is_plane = _datum_feature(robot, j)
    a = _unit(robot.joints[j].axis)
    x = (datum_letters(c.datum) or ("(none)",))[0]
    kind = "plane" if is_plane else "axis"
    if c.diameter:
        if abs(float(a @ d)) >= _PARALLEL:
            return None
        why = (f"a diameter zone at an angle to datum {kind} {x} is fixed by {x} only up to a turn about {x}'s "
               "direction, which the tilt about that direction takes")
    else:
        m = np.cross(_unit(p.twist[:3]), a)  # the direction the tilt moves the axis: the zone's normal
        if np.linalg.norm(m) < 1e-12 or abs(float(_unit(m) @ d)) >= _PARALLEL:
            return None
        why = (f"a zone of two parallel planes {'across' if is_plane else 'along'} datum {kind} {x} is fixed by {x} "
               f"only up to a turn about {x}'s direction, so it bounds its tilt only once that turn is fixed")
    return ("locating", j - 1, f"{why} -- add a secondary datum that fixes the rotation about {x} "
                               f"({_what(robot, j - 1, 'locating')}) to the callout")


def _need(model, c) -> tuple | None:
    """``(kind, i, sentence)`` where callout ``c``'s one datum cannot make it bound what it stands for, else None:
    kind ``"locating"`` (an orientation zone that can turn about its datum's direction, module docstring) or
    ``"shoulder"`` (a position along a datum axis), ``i`` the datum joint (``-1``: the base)."""
    robot = model.robot
    if c.characteristic in ("perpendicularity", "parallelism", "angularity"):
        return _orientation_need(model, c)
    if c.characteristic == "position":
        li = [lk.name for lk in robot.links].index(model.params[model.index(c.parameters[0])].element)
        link, site = robot.links[li], int(robot.link_sites[li])
        ddir, is_plane = _datum_feature(robot, site)
        if not is_plane and _angle(link.direction, ddir) < 45.0:
            x = (datum_letters(c.datum) or ("(none)",))[0]
            return ("shoulder", site - 1,
                    f"{link.name} runs along datum axis {x}, which locates nothing along itself -- the "
                    f"{link.length_mm:g} mm need a datum plane across that axis "
                    f"({_what(robot, site - 1, 'shoulder')}) as the secondary datum")
    return None


def _gap(c, sentence: str) -> str:
    frame = f"{c.symbol} | {c.datum}" if c.datum else f"{c.symbol}, no datum"
    return f"{c.feature} ({frame}): {sentence}"


def complete_datums(model, callouts, frame: _Frame) -> tuple:
    """``(callouts, gaps)``: each callout its one datum cannot make bound its parameter (:func:`_need`) given the
    datum system it needs -- the datum, then the feature that fixes the rotation about it or the face across it --
    where ``frame`` has the letter; the others' sentences in ``gaps``."""
    out, gaps = [], []
    for c in callouts:
        need = _need(model, c)
        letter = frame.secondary(need[1], need[0]) if need is not None and c.datum else ""
        if need is not None and not letter:
            gaps.append(_gap(c, need[2]))
        out.append(replace(c, datum=f"{c.datum}|{letter}") if letter else c)
    return tuple(out), tuple(gaps)


def _mismatch(robot, need: tuple, letters: tuple, features: dict) -> str:
    """Why a callout's datum system does not name the features ``need`` asks for (the drawing's ``features``:
    letter -> what it stands for), ``""`` where it does or the drawing does not say what its letters stand for."""
    kind, i, _ = need
    for letter, want in ((letters[0], _what(robot, i, "axis")), (letters[1], _what(robot, i, kind))):
        said = features.get(letter)
        if said is not None and said != want:
            return (f"its datum {letter} is {said}, where the zone needs {want} -- name that feature in the datum "
                    "system")
    return ""


def datum_gaps(model, callouts, features: dict | None = None) -> tuple:
    """The callouts whose datum cannot bound what they stand for, one sentence each: those :func:`_need` names
    whose datum is a single letter, or whose datum system names other features than the zone needs where the
    drawing says what its letters stand for (``features``: letter -> feature, its ``datum_feature`` rows, as
    :func:`complete_datums` words them). A system whose letters the drawing does not explain is taken to carry the
    features needed."""
    out = []
    for c in callouts:
        need = _need(model, c)
        if need is None:
            continue
        letters = datum_letters(c.datum)
        why = need[2] if len(letters) < 2 else _mismatch(model.robot, need, letters, features or {})
        if why:
            out.append(_gap(c, why))
    return tuple(out)
