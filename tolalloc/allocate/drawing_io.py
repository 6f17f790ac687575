"""The drawing exchange file: one CSV row per characteristic, written from a handover and read back for a review.

Why a CSV and not QIF 3: the QIF 3 schema (``QIFDocument.xsd`` of the Digital Metrology Standards Consortium) is
not distributed through a package registry, so neither a user's install nor CI could validate against it, and a
schema-valid QIF characteristic needs its feature's nominal geometry (a CAD model's faces and axes), which this
tool does not have. The CSV carries, per row, the QIF 3 characteristic type it maps to (``qif_characteristic``),
so a CAD, PLM or metrology importer maps the rows one to one.

Schema (version 2; columns in this order; units in the names; empty cells where a column does not apply)::

    id                  C1, C2 ... (callouts), P1, P2 ... (purchased parts), D1, D2 ... (datum features)
    feature             what is toleranced, the part, or what a datum letter stands for
    characteristic      perpendicularity | parallelism | angularity | coaxiality | position | size | fit |
                        purchased_part | datum_feature (a row naming one letter's feature; no parameters)
    qif_characteristic  the QIF 3 characteristic type (PerpendicularityCharacteristic ...); empty for a part
    symbol              ISO 1101 symbol (⊥ ∥ ∠ ◎ ⌖), ± for a size, "fit" for a fit
    zone_mm             zone width (or diameter) [mm]; a size: the full width 2 t; a fit: its largest clearance
    diameter_zone       true for a diameter zone (Ø), else false
    direction           the base axis a per-direction zone's tilt is about (x, y, z; that of the row's parameter),
                        else empty
    datum               datum letter, or datum system in order of precedence (``B|K``, ``H|B``); required for every
                        orientation, coaxiality and position zone
    length_mm           the zone's length (seat span) or the nominal size (a size, a position, a fit's diameter)
    grade               ISO 286 grade (IT7) or fit (H7/g6)
    tol_arcsec, tol_um  a purchased part's allowed (or, in a review, its actual) error as a half-width
    process, cost, cost_source, catalogue_source
    parameters          the error parameters the row bounds, space-separated (e1x e1y)
    z                   sigma = t / z of the design the zones were made for (every row the same)
    distribution        normal | uniform: the error distribution behind z (every row the same)

Version 1 files (without ``z`` and ``distribution``) are read with the z given to :func:`read_drawing`, else 3.

:func:`read_drawing` reads such a file (or a frame) back into a :class:`~tolalloc.allocate.drawing.FeatureMap`: a
size or position row may give its ``grade`` (IT7) and ``length_mm`` instead of ``zone_mm``; a fit row its
``grade`` (H7/g6) and ``length_mm`` (the seat diameter). Where a row gives both a zone and a grade they must agree
(the grade is the coarsest whose value at ``length_mm`` is within the zone; a fit's zone is its largest clearance).
Each characteristic bounds only parameters of the kinds in :data:`BOUNDS` (a tilt [rad] an orientation or
coaxiality zone, a length [mm] a size or position, a radial clearance a fit, a joint drive a purchased part).
"""

from __future__ import annotations

import re

from os import PathLike
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.allocate.datums import DATUM_PATTERN, datum_gaps, datum_letters
from tolalloc.robot.components_io import DATUM_LETTER
from tolalloc.allocate.drawing import SYMBOLS, Callout, FeatureMap, check_z, zone_factor
from tolalloc.allocate.purchase import PurchasedPart
from tolalloc.allocate.fits import parse_fit
from tolalloc.allocate.process_table import require_process
from tolalloc.allocate.standards import it_value_mm
from tolalloc.exceptions import TolallocError

__all__ = ["DRAWING_COLUMNS", "export_frame", "read_drawing", "read_rows", "recorded_z", "NEEDS_DATUM", "BOUNDS"]

DRAWING_COLUMNS = ("id", "feature", "characteristic", "qif_characteristic", "symbol", "zone_mm", "diameter_zone",
                   "direction", "datum", "length_mm", "grade", "tol_arcsec", "tol_um", "process", "cost",
                   "cost_source", "catalogue_source", "parameters", "z", "distribution")
#: Characteristics whose zone is located or oriented from a datum.
NEEDS_DATUM = ("perpendicularity", "parallelism", "angularity", "coaxiality", "position")
_ARCSEC = np.pi / 648000.0
_ORIENT = ("perpendicularity", "parallelism", "angularity", "coaxiality")
#: The characteristics that can bound each kind of error parameter.
BOUNDS = {"link_length": ("size", "position"), "axis_deflection": _ORIENT, "clearance_tilt": _ORIENT,
          "clearance_radial": ("fit",), "clearance_axial": ("size",), "joint_drive": ("purchased_part",)}


def export_frame(h) -> pd.DataFrame:
    """The exchange rows (:data:`DRAWING_COLUMNS`) of a :class:`~tolalloc.allocate.handover.Handover`.

    Raises TolallocError naming the feature when an orientation, coaxiality or position zone has no datum.
    """
    from tolalloc.allocate.handover import QIF_TYPES

    rows, design = [], {"z": h.features.z, "distribution": h.features.distribution}
    for i, c in enumerate(h.callouts):
        if c.characteristic in NEEDS_DATUM and not c.datum:
            raise TolallocError(f"export: {c.feature} ({c.characteristic}) has no datum; a {c.characteristic} zone is "
                                "located from one: give the joint's bearing datum in the robot file's [components] "
                                "or keep the default datums (default_datums=True).")
        rows.append({"id": f"C{i + 1}", "feature": c.feature, "characteristic": c.characteristic,
                     "qif_characteristic": QIF_TYPES[c.characteristic], "symbol": c.symbol, "zone_mm": c.zone_mm,
                     "diameter_zone": c.diameter, "direction": c.direction, "datum": c.datum,
                     "length_mm": c.length_mm, "grade": c.grade, "process": h.process[i], "cost": h.cost[i],
                     "cost_source": h.cost_source[i], "parameters": " ".join(c.parameters), **design})
    n = len(h.callouts)
    for i, p in enumerate(h.parts):
        tol = {"tol_arcsec": p.required / _ARCSEC} if p.unit == "rad" else {"tol_um": p.required * 1000.0}
        rows.append({"id": f"P{i + 1}", "feature": p.part, "characteristic": "purchased_part", **tol,
                     "grade": p.grade, "process": "purchased part", "cost": h.cost[n + i],
                     "cost_source": h.cost_source[n + i], "catalogue_source": p.source,
                     "parameters": " ".join(p.parameters), **design})
    for i, (letter, what, _) in enumerate(h.features.datum_features):
        rows.append({"id": f"D{i + 1}", "feature": what, "characteristic": "datum_feature", "datum": letter,
                     **design})
    return pd.DataFrame(rows, columns=list(DRAWING_COLUMNS))


def read_rows(path) -> pd.DataFrame:
    """The rows of a drawing exchange CSV as text (a byte-order mark is fine); clear errors for a missing or
    unreadable file."""
    from tolalloc.exceptions import InputFileError

    if not isinstance(path, (str, PathLike)):
        raise TolallocError(f"drawing file: expected a path (str or pathlib.Path) of a CSV with the columns "
                            f"{', '.join(DRAWING_COLUMNS)}, got {path!r} ({type(path).__name__}).")
    path = Path(path)
    if not path.is_file():
        raise InputFileError(f"drawing file {str(path)!r} not found; expected a CSV with the columns "
                             f"{', '.join(DRAWING_COLUMNS)} (the drawing.csv an allocation writes).")
    try:
        return pd.read_csv(path, dtype=str, keep_default_na=False, encoding="utf-8-sig")
    except (pd.errors.ParserError, UnicodeDecodeError, pd.errors.EmptyDataError) as exc:
        raise TolallocError(f"drawing file {path}: cannot be read as CSV ({exc}).") from None


def _num(row, key: str, where: str, positive: bool = True) -> float:
    v = row.get(key)
    try:
        x = float(v)
    except (TypeError, ValueError):
        x = np.nan
    if not np.isfinite(x) or (positive and x <= 0):
        raise TolallocError(f"{where}: {key} expected a number > 0, got {v!r}.")
    return x


def _bool(v) -> bool:
    return str(v).strip().lower() in ("true", "1", "yes")


def recorded_z(frame, name: str = "drawing") -> tuple:
    """``(z, distribution)`` the file records (its ``z`` and ``distribution`` columns), ``(None, None)`` for a file
    without them (schema version 1) or with their cells empty; TolallocError for values that differ between rows
    or are not a number > 0 / normal or uniform."""
    out = []
    for col in ("z", "distribution"):
        cells = frame[col] if col in frame.columns else []
        values = sorted({str(v).strip() for v in cells if not pd.isna(v) and str(v).strip()})
        if len(values) > 1:
            raise TolallocError(f"{name}: column {col} records different values ({', '.join(values)}); a drawing "
                                "is made for one z and distribution.")
        out.append(values[0] if values else None)
    z, dist = out
    if z is None:
        return None, dist
    try:
        zf = float(z)
    except ValueError:
        zf = np.nan
    return check_z(zf, dist or "normal", f"{name} column z/distribution"), dist or "normal"


def _design_z(frame, name: str, z, distribution) -> tuple:
    """``(z, distribution)`` of a review: the file's, refused where a given one disagrees; a file recording none:
    the given ones, else z = 3 (normal) or sqrt(3) (uniform)."""
    if distribution is not None:
        check_z(1.0, distribution, name)
    if z is not None:
        check_z(z, distribution or "normal", name)
    z_file, dist_file = recorded_z(frame, name)
    if z_file is None:
        dist = distribution or dist_file or "normal"
        return (float(z) if z is not None else np.sqrt(3.0) if dist == "uniform" else 3.0), dist
    if distribution is not None and distribution != dist_file:
        raise TolallocError(f"{name}: the review's distribution {distribution} differs from the drawing's "
                            f"{dist_file} (column distribution); its zones were made for {dist_file}: review with "
                            "that distribution or leave it unset.")
    if z is not None and abs(float(z) - z_file) > 1e-6 * z_file:
        raise TolallocError(f"{name}: the review's z = {float(z):g} differs from the drawing's z = {z_file:.6g} "
                            "(column z); its zones were made for sigma = t / z with the drawing's z: review with "
                            "that z or leave it unset.")
    return z_file, dist_file


def read_drawing(source, model, *, z: float | None = None, distribution: str | None = None,
                 check_processes: bool = True, name: str | None = None) -> FeatureMap:
    """A drawing exchange file (path) or frame as a :class:`~tolalloc.allocate.drawing.FeatureMap` of ``model``.

    Every callout's ``factor`` (``zone = factor * t``) is derived from its characteristic, length and zone type
    (the file's own figures are not trusted for it). ``z`` and ``distribution`` (``sigma = t / z``): the file's
    (columns ``z``, ``distribution``); a given value that disagrees with them is refused; a file recording none
    takes the given ones, else z = 3, normal. ``check_processes``: refuse a zone or grade finer than any process of
    the built-in table holds (the error names the feature, the finest process and its cost). ``name``: how errors
    name the drawing (default: its path, ``drawing`` for a frame).
    Raises TolallocError naming the row for a missing or bad value, a span of zero, a fit that is not ISO 286, a
    zone without its datum, a zone that disagrees with its grade, a bad direction, a characteristic that cannot
    bound the row's parameters or a parameter the model does not have.
    """
    frame, own = (source, "drawing") if isinstance(source, pd.DataFrame) else (read_rows(source), str(source))
    name = name or own
    missing = [c for c in ("characteristic", "parameters") if c not in frame.columns]
    if missing:
        raise TolallocError(f"{name}: missing column(s) {', '.join(missing)}; expected {', '.join(DRAWING_COLUMNS)}.")
    z, distribution = _design_z(frame, name, z, distribution)
    known, callouts, parts, datums = set(model.names), [], [], {}
    for i, row in enumerate(frame.to_dict("records")):
        row = {k: ("" if v is None or (isinstance(v, float) and np.isnan(v)) else v) for k, v in row.items()}
        feature = str(row.get("feature") or f"row {i + 1}")
        where = f"{name} row {i + 1} ({feature})"
        if str(row["characteristic"]).strip() == "datum_feature":
            _datum_row(row, datums, where)
            continue
        params = tuple(str(row["parameters"]).split())
        bad = [p for p in params if p not in known]
        if not params or bad:
            raise TolallocError(f"{where}: parameters {' '.join(bad) or '(none)'} not in the error model; expected "
                                f"names among {', '.join(model.names)}.")
        char = str(row["characteristic"]).strip()
        if char not in SYMBOLS and char != "purchased_part":
            raise TolallocError(f"{where}: characteristic {char!r} unknown; expected one of "
                                f"{', '.join(SYMBOLS)}, purchased_part.")
        _check_bounds(char, params, model, where)
        if char == "purchased_part":
            parts.append(_part(row, params, model, where))
        else:
            callouts.append(_callout(row, char, params, feature, where, z, distribution, check_processes))
            _check_row(callouts[-1], params, model, where)
    return FeatureMap(tuple(callouts), tuple(parts), float(z), distribution,
                      datum_gaps=datum_gaps(model, callouts, datums),
                      datum_features=tuple((k, what, "drawing") for k, what in sorted(datums.items())))


def _datum_row(row, datums: dict, where: str) -> None:
    """A ``datum_feature`` row into ``datums`` (letter -> what it stands for): one letter, a feature, no parameter."""
    letter, what = str(row.get("datum", "")).strip(), str(row.get("feature", "")).strip()
    if not re.fullmatch(DATUM_LETTER, letter) or not what:
        raise TolallocError(f"{where}: a datum_feature row names one datum letter (column datum, as B) and what it "
                            f"stands for (column feature); got datum {letter!r}, feature {what!r}.")
    if str(row.get("parameters", "")).strip():
        raise TolallocError(f"{where}: a datum_feature row bounds no parameter; leave column parameters empty.")
    if letter in datums and datums[letter] != what:
        raise TolallocError(f"{where}: datum {letter} is already {datums[letter]!r}; a letter names one feature.")
    datums[letter] = what


def _check_bounds(char: str, params, model, where: str) -> None:
    """TolallocError where ``char`` cannot bound one of ``params`` (:data:`BOUNDS`)."""
    for p in params:
        kind, unit = model.params[model.index(p)].kind, model.params[model.index(p)].unit
        can = BOUNDS.get(kind)
        if can is not None and char not in can:
            raise TolallocError(f"{where}: characteristic {char!r} cannot bound {p} (kind {kind}, unit {unit}); "
                                f"parameters of kind {kind} are bounded by: {', '.join(can)}.")


def _check_row(c: Callout, params, model, where: str) -> None:
    """A callout's datum and direction: a located or oriented zone names its datum; a direction is that of the
    one tilt a per-direction orientation zone bounds, else empty."""
    if c.characteristic in NEEDS_DATUM and not c.datum:
        raise TolallocError(f"{where}: column datum is empty; a {c.characteristic} zone is located or oriented from "
                            "a datum: give its letter (A, B ...).")
    if c.datum and not DATUM_PATTERN.fullmatch(c.datum):
        raise TolallocError(f"{where}: column datum {c.datum!r} is no datum letter or datum system; expected capital "
                            "letters, a common datum (B-C), a system of up to three in order of precedence separated "
                            "by | (B, B|K).")
    letters = datum_letters(c.datum)
    if len(set(letters)) < len(letters):
        raise TolallocError(f"{where}: column datum {c.datum!r} names a datum twice; a datum system names each datum "
                            "feature once, in order of precedence (B|K).")
    if not c.direction:
        return
    if c.characteristic not in _ORIENT or c.diameter or c.characteristic == "coaxiality":
        raise TolallocError(f"{where}: column direction {c.direction!r} given for a {c.characteristic} "
                            f"{'diameter ' if c.diameter else ''}zone; only a zone per direction of an orientation "
                            "tolerance names one (leave it empty).")
    # the export writes the tilt's letter (e2z -> z: the base axis its twist was built from), which is also the
    # largest component of the twist's rotation except near a tie
    twist = np.asarray(model.params[model.index(params[0])].twist[:3], float)
    axis = params[0][-1] if params[0][-1] in "xyz" else "xyz"[int(np.argmax(np.abs(twist)))]
    if c.direction != axis:
        raise TolallocError(f"{where}: column direction {c.direction!r} does not match {params[0]}, a tilt about "
                            f"the base {axis} axis; expected direction {axis!r} (valid directions: x, y, z, that "
                            "of the row's parameter).")


def _part(row, params, model, where) -> PurchasedPart:
    p = model.params[model.index(params[0])]
    if p.unit == "rad":
        t = _num(row, "tol_arcsec", where) * _ARCSEC
    else:
        t = _num(row, "tol_um", where) * 1e-3
    return PurchasedPart(str(row.get("feature", "")), p.element, params, str(row.get("grade", "")), t, p.unit,
                         str(row.get("catalogue_source", "")))


def _check_grade(zone: float, grade: str, length: float, where: str) -> None:
    """A size or position row's zone and IT grade agree: the grade is the coarsest whose value at ``length`` is
    within the zone (as the export writes it)."""
    it = it_value_mm(length, grade)  # refuses a grade that is not IT1..IT18 or a size beyond 3150 mm
    g = int(grade[2:])
    coarser = it_value_mm(length, f"IT{g + 1}") if g < 18 else np.inf
    if not it * (1 - 1e-9) <= zone < coarser * (1 - 1e-9):
        raise TolallocError(f"{where}: zone_mm {zone:g} mm disagrees with grade {grade}, {it:g} mm at {length:g} mm "
                            f"(a zone of {grade} lies from {it:g} mm up to the next grade's "
                            f"{coarser:g} mm); correct one of them or leave zone_mm empty.")


def _callout(row, char, params, feature, where, z, distribution, check) -> Callout:
    grade, datum = str(row.get("grade", "")).strip(), str(row.get("datum", "")).strip()
    diameter, direction = _bool(row.get("diameter_zone", "")), str(row.get("direction", "")).strip()
    if char == "fit":
        d = _num(row, "length_mm", where)
        fit = parse_fit(grade, d, where=where)
        if fit.clearance_max_um <= 0:
            raise TolallocError(f"{where}: {fit.name} at Ø{d:g} mm is an interference fit (no radial play); the "
                                "radial clearance model needs a clearance or transition fit.")
        zone, factor = fit.clearance_max_um / 1000.0, 2.0 * np.sqrt(2.0)
        given = _num(row, "zone_mm", where) if str(row.get("zone_mm", "")).strip() else zone
        if abs(given - zone) > 1e-6 * zone:
            raise TolallocError(f"{where}: zone_mm {given:g} mm disagrees with the fit {fit.name} at Ø{d:g} mm, "
                                f"whose largest clearance is {zone:g} mm (ES - ei); give one or make them agree.")
        if check:
            for cls in (fit.hole, fit.shaft):
                require_process(f"{where} {cls.name}", grade=cls.grade)
        return Callout(feature, char, zone, False, "", datum, d, fit.name, params, factor, "drawing")
    length = _num(row, "length_mm", where)  # a span of zero or none is refused here
    if char in ("size", "position"):
        zone = (float(_num(row, "zone_mm", where)) if str(row.get("zone_mm", "")).strip() else
                it_value_mm(length, grade) if grade.startswith("IT") else _num(row, "zone_mm", where))
        if grade:
            _check_grade(zone, grade, length, where)
        if check:
            kw = {"grade": int(grade[2:])} if grade.startswith("IT") else {"zone_mm": zone, "length_mm": length}
            require_process(where, **kw)
        return Callout(feature, char, zone, False, "", datum, length, grade, params, 2.0, "drawing")
    zone = _num(row, "zone_mm", where)
    if char not in _ORIENT:
        raise TolallocError(f"{where}: characteristic {char!r} unknown.")
    if diameter or char == "coaxiality" or len(params) == 1:
        factor = zone_factor(char, diameter, length, z, distribution)
    else:
        raise TolallocError(f"{where}: a zone in one direction bounds one tilt, got {len(params)} parameters; give "
                            "diameter_zone = true for a diameter zone or one row per direction.")
    if check:
        require_process(where, zone_mm=zone, length_mm=length)
    return Callout(feature, char, zone, diameter or char == "coaxiality", direction, datum, length, grade, params,
                   factor, "drawing")
