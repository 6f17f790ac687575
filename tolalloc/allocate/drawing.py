"""From error screws to a drawing and a purchase list: the features that produce each error parameter.

Each error parameter of a design is mapped to what a drawing or a purchase order carries (ISO 1101, ISO 286):

``link_length``
    The distance between two joints: a *position* tolerance (``⌖``, a zone of two parallel planes ``2 t`` apart
    across the link, i.e. the IT value, at the theoretically exact distance) of what the link locates -- the next
    joint's axis where the link runs across it, else (along the next axis, a slide, the tool flange) the face that
    locates it along the link: the shoulder of the next joint's axially locating bearing seat, its guide's mounting
    face, the tool flange face. A step between two faces is no feature of size, so not a size ``±t`` (ISO 14405-2).
    A link along its datum axis is located in the datum system ``axis|shoulder face``. It carries the ISO 286 grade
    of the design.
``axis_deflection`` (two tilts per revolute joint)
    The axis of the joint's bearing-seat pair, its orientation to the datum of the joint before it (the first
    joint: the base mounting face, datum ``A``): *perpendicularity* ``⊥``, *parallelism* ``∥`` or *angularity*
    ``∠`` by the nominal geometry, over the seat span ``L``. An orientation zone of width ``t_zone`` over ``L``
    bounds the tilt in its direction to ``t_zone / L``: ``t_zone = L t`` (``t`` the allocated half-width [rad]).
    The two tilts with equal half-widths share one *diameter* zone bounding the tilt magnitude; it is placed at the
    two-dimensional coverage of the tolerance (for normal components the magnitude is Rayleigh distributed:
    ``Ø t_zone = L sigma sqrt(-2 ln(1 - p_c))`` with ``p_c = P(|N| < z)``, not ``z`` per component). Unequal
    tilts get a zone in each direction. To a datum *axis* at an angle a zone (two planes perpendicular to it) bounds
    only the tilt that changes the angle to it: each tilt gets its own zone, and a tilt about the datum axis' own
    direction -- and any zone the datum fixes only up to a turn about its direction (per-direction zones to a datum
    plane or a parallel axis, a Ø zone at an angle) -- is bounded in the datum system ``datum|locating feature`` (the
    locating pin hole or keyway of the datum joint's output flange, of the base's mounting face: it fixes the
    rotation about the datum; :mod:`tolalloc.allocate.datums`).
``clearance_tilt``
    The *coaxiality* ``◎`` of the joint's second bearing seat to the first over the span. A coaxiality zone is a
    cylinder centred on the datum axis, so a tilt of magnitude ``a`` (the second seat's radial offset ``L a``)
    needs a zone of diameter ``2 L a``: ``Ø t_zone = 2 L f t`` with the diameter factor ``f`` above.
``clearance_radial``
    An ISO 286 *fit* of the seats (:mod:`tolalloc.allocate.fits`): the loosest preferred clearance fit whose
    largest radial play ``c_max / 2`` is at most the design's radial bound ``sqrt(2) t`` (the ring's magnitude at
    the tolerance's coverage); the fit's ``c_max`` gives back ``sigma = c_max / (2 sqrt(2) z)``.
``clearance_axial``
    A *size* ``±t`` of the axial stack (spacer or shim) of the bearing arrangement. The robot file gives no nominal
    length of the stack: the seat span stands for it (for the ISO 286 grade's size range), stated as an
    assumption.
``joint_drive``
    A *purchased part*: the joint's reducer and encoder with their accuracy grade and catalogue source
    (:class:`~tolalloc.allocate.purchase.PurchasedPart`; the robot file's ``[components]``, or the chooser of
    :class:`HandoverSettings`).

Spans, datums and seat diameters come from the robot file's ``[components.joints.<joint>.bearing]`` (``span_mm``,
``datum``, ``locating_datum``, ``shoulder_datum``, ``seat_diameter_mm``; a table of its own or a catalogue slot's);
where it gives none, the stated defaults of :class:`HandoverSettings`, labelled
``assumed`` in every table.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import log, sqrt

import numpy as np
from scipy.special import log_ndtr

from tolalloc.allocate.datums import _Frame, _angle, _orientation, complete_datums, datum_gaps, datum_letters
from tolalloc.allocate.fits import FIT_MAX_SIZE_MM, PREFERRED_CLEARANCE_FITS, check_clearance_fits, clearance_fits
from tolalloc.allocate.purchase import drive_part
from tolalloc.allocate.standards import IT_SIZES_MM, IT_TABLE_UM, is_real_number, it_row
from tolalloc.exceptions import TolallocError

__all__ = ["Callout", "HandoverSettings", "FeatureMap", "feature_map", "diameter_factor", "zone_factor", "check_z",
           "datum_gaps", "SYMBOLS", "TILT_ZONES", "DISTRIBUTIONS"]

#: ISO 1101 symbols (and the drawing's sign for a size and a fit).
SYMBOLS = {"perpendicularity": "⊥", "parallelism": "∥", "angularity": "∠", "coaxiality": "◎", "position": "⌖",
           "size": "±", "fit": "fit"}
TILT_ZONES = ("auto", "diameter", "directions")
DISTRIBUTIONS = ("normal", "uniform")


def check_z(z, distribution: str, where: str) -> float:
    """``z`` of ``sigma = t / z`` as a float > 0 and ``distribution`` one of :data:`DISTRIBUTIONS`; TolallocError
    naming ``where`` otherwise."""
    if not (is_real_number(z) and np.isfinite(z) and z > 0):
        raise TolallocError(f"{where}: z expected a number > 0 (sigma = t / z, e.g. 3), got {z!r}.")
    if distribution not in DISTRIBUTIONS:
        raise TolallocError(f"{where}: distribution expected one of {', '.join(DISTRIBUTIONS)}, got "
                            f"{distribution!r}.")
    return float(z)


@dataclass(frozen=True)
class HandoverSettings:
    """How a design becomes a drawing: the defaults used where the robot file says nothing.

    Attributes
    ----------
    default_span_mm : float or None
        Axial distance between a joint's two bearing seats where the robot file gives no ``span_mm`` [mm]
        (None: a joint without one is an error).
    default_seat_diameter_mm : float or None
        Nominal seat diameter for a fit where the robot file gives no ``seat_diameter_mm`` [mm], within ISO 286's
        fit sizes (up to 500 mm).
    default_datums : bool
        Name datums where the robot file gives none: ``A`` the base mounting face, then ``B``, ``C`` ... the joints'
        seat axes in chain order. False: a callout without a datum keeps an empty one (the export refuses it).
    tilt_zone : {"auto", "diameter", "directions"}
        ``auto``: one diameter zone for two tilts of equal half-width, else a zone per direction; ``diameter``: one
        diameter zone at the smaller of the two (tighter than the design where they differ); ``directions``: always
        a zone per direction.
    fits : tuple of str
        Candidate fits of the radial clearance, ISO 286 clearance fits such as ``"H7/g6"`` (default: the preferred
        clearance fits).
    part_chooser : callable or None
        The per-joint choice of the bought part (:func:`tolalloc.allocate.purchase.drive_part`); None: the robot
        file's ``[components]``.
    """

    default_span_mm: float | None = 100.0
    default_seat_diameter_mm: float | None = 50.0
    default_datums: bool = True
    tilt_zone: str = "auto"
    fits: tuple = PREFERRED_CLEARANCE_FITS
    part_chooser: object = None

    def __post_init__(self):
        for name in ("default_span_mm", "default_seat_diameter_mm"):
            v = getattr(self, name)
            if v is not None and not (is_real_number(v) and np.isfinite(v) and v > 0):
                raise TolallocError(f"{name}: expected a length > 0 [mm] (a number) or None, got {v!r} "
                                    f"({type(v).__name__}).")
        d = self.default_seat_diameter_mm
        if d is not None and d > FIT_MAX_SIZE_MM:
            raise TolallocError(f"default_seat_diameter_mm: expected a seat diameter within ISO 286's fit sizes "
                                f"(0 < D <= {FIT_MAX_SIZE_MM:g} mm), got {d!r} mm.")
        if self.tilt_zone not in TILT_ZONES:
            raise TolallocError(f"tilt_zone: expected one of {', '.join(TILT_ZONES)}, got {self.tilt_zone!r}.")
        object.__setattr__(self, "fits", check_clearance_fits(self.fits, where="fits"))


@dataclass(frozen=True)
class Callout:
    """One drawing callout.

    Attributes
    ----------
    feature : str
        What is toleranced (``"j2 bearing-seat axis"``).
    characteristic : str
        Key of :data:`SYMBOLS`.
    zone_mm : float
        Zone width or diameter [mm]; a size: the full width ``2 t``; a fit: its largest clearance.
    diameter : bool
        A diameter zone (``Ø``).
    direction : str
        Base axis the bounded tilt is about (``x``, ``y``, ``z``; a zone per direction), else ``""``.
    datum : str
    length_mm : float
        Span of the zone (seat span) or nominal size.
    grade : str
        ``"IT9"``, a fit ``"H7/g6"`` or ``""``.
    parameters : tuple of str
        Error parameters it bounds.
    factor : float
        ``zone_mm = factor * t`` (``t`` the parameters' half-width [mm or rad]; a fit: ``2 sqrt(2)``, its largest
        clearance is twice the radial play bound ``sqrt(2) t``, so a fit gives back ``t`` at or below the design's).
    span_source : str
        ``"robot file"`` or ``"assumed default"`` (span, seat diameter); ``"nominal"`` for a link length.
    """

    feature: str
    characteristic: str
    zone_mm: float
    diameter: bool
    direction: str
    datum: str
    length_mm: float
    grade: str
    parameters: tuple
    factor: float
    span_source: str

    @property
    def symbol(self) -> str:
        return SYMBOLS[self.characteristic]


@dataclass(frozen=True)
class FeatureMap:
    """The drawing callouts and purchased parts of one design (:func:`feature_map`).

    Attributes
    ----------
    callouts : tuple of Callout
    parts : tuple of tolalloc.allocate.purchase.PurchasedPart
    z : float
        ``sigma = t / z``.
    distribution : {"normal", "uniform"}
    settings : HandoverSettings
    defaults_used : tuple of str
        The stated defaults this map relied on (for the assumptions).
    warnings : tuple of str
        Callouts looser than the design (a radial clearance finer than every candidate fit, with ``strict=False``).
    datum_gaps : tuple of str
        Callouts their datum cannot make bound what they stand for (:func:`datum_gaps`): a tilt about a datum axis'
        own direction, a location along a datum axis, where no letter names the feature that completes the datum
        system (``default_datums=False`` and none in the robot file). The drawing needs another datum there.
    datum_features : tuple of (str, str, str)
        ``(letter, feature, source)`` of every datum the callouts name, by letter; ``source`` is ``"robot file"``
        or ``"assumed letter"``.
    """

    callouts: tuple
    parts: tuple
    z: float
    distribution: str
    settings: HandoverSettings = field(default_factory=HandoverSettings)
    defaults_used: tuple = ()
    warnings: tuple = ()
    datum_gaps: tuple = ()
    datum_features: tuple = ()


def diameter_factor(z: float, distribution: str = "normal") -> float:
    """``f`` with ``Ø zone = L f t`` for two tilts of half-width ``t`` [rad] bounded by one diameter zone.

    Normal components: the magnitude is Rayleigh (scale ``sigma = t / z``); at the coverage ``p_c = P(|N| < z)`` of
    the one-dimensional tolerance its quantile is ``sigma sqrt(-2 ln(1 - p_c))``, so ``f = sqrt(-2 ln(1 - p_c)) / z``
    (1.1464 at z = 3). Uniform components (the square ``±t``): ``f = sqrt(2)``, the circle around the square.
    """
    if distribution == "uniform":
        return sqrt(2.0)
    log_tail = log(2.0) + float(log_ndtr(-z))  # ln(1 - p_c) = ln 2 Phi(-z), finite for any z
    return sqrt(-2.0 * log_tail) / z


def zone_factor(characteristic: str, diameter: bool, length_mm: float, z: float, distribution: str) -> float:
    """``factor`` with ``zone = factor * t`` of a tilt zone over ``length_mm``: ``L`` in one direction, ``L f`` for
    a diameter orientation zone (bounds the tilt magnitude ``f t``), ``2 L f`` for coaxiality (a cylinder centred on
    the datum axis: the second seat's radial offset ``L f t`` is its radius)."""
    if characteristic == "coaxiality":
        return 2.0 * length_mm * diameter_factor(z, distribution)
    return length_mm * diameter_factor(z, distribution) if diameter else length_mm


def feature_map(model, t, labels=(), *, z: float, distribution: str = "normal",
                settings: HandoverSettings | None = None, strict: bool = True) -> FeatureMap:
    """Drawing callouts and purchased parts of design ``t`` of ``model``.

    Parameters
    ----------
    model : ErrorModel
        Its robot's ``components`` give spans, datums, seat diameters and bought parts.
    t : array, shape (K,) [mm or rad]
        Half-width of every parameter.
    labels : sequence of str, optional
        Standard label per parameter (``"IT7"``, a class) of the design, shown as the grade.
    z : float
        ``sigma = t / z``.
    distribution : {"normal", "uniform"}
    settings : HandoverSettings, optional
    strict : bool
        Refuse a radial clearance finer than every candidate fit (False: the finest fit, listed in ``warnings``).
    """
    z = check_z(z, distribution, "feature_map")
    settings = settings or HandoverSettings()
    t = np.asarray(t, float)
    if t.shape != (len(model.params),):
        raise TolallocError(f"feature_map: expected {len(model.params)} half-widths > 0 [mm or rad], one per "
                            f"parameter of the model, got shape {t.shape}.")
    bad = np.flatnonzero(~(np.isfinite(t) & (t > 0)))
    if bad.size:
        k = int(bad[0])
        raise TolallocError(f"feature_map: the half-width of {model.params[k].name} is {float(t[k])!r} "
                            f"[{model.params[k].unit}]; every half-width must be a number > 0 ({bad.size} are not).")
    labels = list(labels) or [""] * len(t)
    fr = _Frame(model.robot, settings)
    fr.strict, fr.warnings = strict, []
    by_joint: dict = {}
    callouts, parts = [], []
    for k, p in enumerate(model.params):
        if p.kind == "link_length":
            callouts.append(_link_callout(model.robot, p, t[k], labels[k], fr))
        elif p.kind == "joint_drive":
            parts.append(drive_part(model.robot, p, t[k], settings.part_chooser))
        else:
            by_joint.setdefault((p.element, p.kind), []).append(k)
    for (joint, kind), ks in by_joint.items():
        j = [jt.name for jt in model.robot.joints].index(joint)
        if kind in ("axis_deflection", "clearance_tilt"):
            callouts += _tilt_callouts(model, j, kind, ks, t, fr, z, distribution)
        elif kind == "clearance_radial":
            callouts.append(_fit_callout(model, j, ks, t, fr, z))
        else:  # clearance_axial
            callouts.append(_stack_callout(model, j, ks[0], t, fr))
    callouts, gaps = complete_datums(model, callouts, fr)
    named = {x for c in callouts for x in datum_letters(c.datum)}
    return FeatureMap(tuple(callouts), tuple(parts), float(z), distribution, settings, tuple(fr.used),
                      tuple(fr.warnings), gaps, tuple((k, *fr.features[k]) for k in sorted(fr.features) if k in named))


def _stack_callout(model, j: int, k: int, t, fr: _Frame) -> Callout:
    """The axial stack's size: the robot file gives no nominal length of the spacer, so the seat span stands for
    it (the size ISO 286's grade is looked up at), stated in the feature and the assumptions."""
    joint = model.robot.joints[j].name
    span, src = fr.bearing_value(j, "span_mm", fr.settings.default_span_mm, "seat span")
    fr._note("axial stack (bearing spacer): nominal length taken as the seat span (assumed), the size its ISO 286 "
             "grade is looked up at")
    return Callout(f"{joint} axial stack (bearing spacer; nominal length = seat span {span:g} mm, assumed)", "size",
                   2 * t[k], False, "", fr.datum[joint], span, _grade_within(span, 2 * t[k]),
                   (model.params[k].name,), 2.0, f"{src} (seat span as the stack's nominal length, assumed)")


def _grade_within(size_mm: float, width_mm: float) -> str:
    """The coarsest IT grade whose value at ``size_mm`` is at most ``width_mm`` (``""`` if none or no size)."""
    if not 0 < size_mm <= IT_SIZES_MM[-1]:
        return ""
    ok = np.flatnonzero(IT_TABLE_UM[it_row(size_mm)] / 1000.0 <= width_mm * (1 + 1e-9))
    return f"IT{ok[-1] + 1}" if ok.size else ""


def _link_callout(robot, p, t: float, label: str, fr: _Frame) -> Callout:
    li = [lk.name for lk in robot.links].index(p.element)
    link, site = robot.links[li], int(robot.link_sites[li])
    datum = fr.previous(site)[0]
    nxt = robot.joints[site] if site < robot.n_joints else None
    grade = label if label.startswith("IT") else _grade_within(link.length_mm, 2 * t)
    if nxt is not None and nxt.is_revolute and _angle(link.direction, np.asarray(nxt.axis, float)) > 45.0:
        what = f"{nxt.name} axis"
    elif nxt is None:
        what = "tool flange face"
    else:
        what = (f"shoulder face of {nxt.name}'s axially locating bearing seat" if nxt.is_revolute
                else f"mounting face of {nxt.name}'s guide")
    return Callout(f"{what}, {link.length_mm:g} mm from the datum ({link.name})", "position", 2 * t, False, "",
                   datum, link.length_mm, grade, (p.name,), 2.0, "nominal")


def _tilt_callouts(model, j: int, kind: str, ks, t, fr: _Frame, z: float, distribution: str) -> list:
    jt = model.robot.joints[j]
    span, src = fr.bearing_value(j, "span_mm", fr.settings.default_span_mm, "seat span")
    plane = True
    if kind == "clearance_tilt":
        feature, char, datum = f"{jt.name} second bearing seat", "coaxiality", fr.datum[jt.name]
    else:
        datum, ddir, plane = fr.previous(j)
        feature, char = f"{jt.name} bearing-seat axis", _orientation(np.asarray(jt.axis, float), ddir, plane)
    names = tuple(model.params[k].name for k in ks)
    tk = t[list(ks)]
    mode = fr.settings.tilt_zone
    equal = len(ks) == 2 and abs(tk[0] - tk[1]) <= 1e-9 * max(tk)
    if kind == "axis_deflection" and not plane and char != "parallelism" and mode == "auto":
        equal = False  # to a datum axis a zone bounds one direction of tilt: a Ø zone is no ISO 1101 zone there
    if char == "coaxiality" or (len(ks) == 2 and (mode == "diameter" or (mode == "auto" and equal))):
        f = zone_factor(char, True, span, z, distribution)
        return [Callout(feature, char, f * float(tk.min()), True, "", datum, span, "", names, f, src)]
    out = []
    for k in ks:
        p = model.params[k]
        letter = p.name[-1]
        out.append(Callout(f"{feature}, tilt about {letter}", char, span * t[k],
                           False, letter, datum, span, "", (p.name,), span, src))
    return out


def _fit_callout(model, j: int, ks, t, fr: _Frame, z: float) -> Callout:
    jt = model.robot.joints[j]
    d, src = fr.bearing_value(j, "seat_diameter_mm", fr.settings.default_seat_diameter_mm, "seat diameter")
    names = tuple(model.params[k].name for k in ks)
    allowed = sqrt(2.0) * float(np.min(t[list(ks)]))  # largest radial play at the tolerance's coverage [mm]
    fits = [f for f in clearance_fits(d, fr.settings.fits, where=f"{jt.name} bearing seats (seat_diameter_mm)")
            if f.kind == "clearance"]
    ok = [f for f in fits if f.radial_play_max_mm <= allowed * (1 + 1e-9)]
    if not ok:
        fine = fits[0]
        text = (f"{jt.name} bearing seats (Ø{d:g} mm): the radial clearance allows a play of at most "
                f"{allowed * 1000:.3g} um, finer than every candidate fit; the finest, {fine.name}, has up to "
                f"{fine.radial_play_max_mm * 1000:.3g} um")
        if fr.strict:
            raise TolallocError(f"{text}. Give a finer fit (fits=...) or widen the clearance tolerance.")
        fr.warnings.append(f"{text}: the drawing carries {fine.name}, looser than the design")
        ok = [fine]
    fit = ok[-1]
    return Callout(f"{jt.name} bearing seats Ø{d:g} mm", "fit", fit.clearance_max_um / 1000.0, False, "",
                   fr.datum[jt.name], d, fit.name, names, 2.0 * sqrt(2.0), src)
