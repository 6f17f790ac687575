"""The drawing exchange file: one CSV row per characteristic, written from a handover and read back for a review.

Why a CSV and not QIF 3: the QIF 3 schema (``QIFDocument.xsd`` of the Digital Metrology Standards Consortium) is
not distributed through a package registry, so neither a user's install nor CI could validate against it, and a
schema-valid QIF characteristic needs its feature's nominal geometry (a CAD model's faces and axes), which this
tool does not have. The CSV carries, per row, the QIF 3 characteristic type it maps to (``qif_characteristic``),
so a CAD, PLM or metrology importer maps the rows one to one.

Schema (version 1; columns in this order; units in the names; empty cells where a column does not apply)::

    id                  C1, C2 ... (callouts), P1, P2 ... (purchased parts)
    feature             what is toleranced, or the part
    characteristic      perpendicularity | parallelism | angularity | coaxiality | position | size | fit |
                        purchased_part
    qif_characteristic  the QIF 3 characteristic type (PerpendicularityCharacteristic ...); empty for a part
    symbol              ISO 1101 symbol (⊥ ∥ ∠ ◎ ⌖), ± for a size, "fit" for a fit
    zone_mm             zone width (or diameter) [mm]; a size: the full width 2 t; a fit: its largest clearance
    diameter_zone       true for a diameter zone (Ø), else false
    direction           the base axis a per-direction zone's tilt is about (x, y, z), else empty
    datum               datum letter (required for every orientation, coaxiality and position zone)
    length_mm           the zone's length (seat span) or the nominal size (a size, a position, a fit's diameter)
    grade               ISO 286 grade (IT7) or fit (H7/g6)
    tol_arcsec, tol_um  a purchased part's allowed (or, in a review, its actual) error as a half-width
    process, cost, cost_source, catalogue_source
    parameters          the error parameters the row bounds, space-separated (e1x e1y)

:func:`read_drawing` reads such a file (or a frame) back into a :class:`~tolalloc.allocate.drawing.FeatureMap`: a
size or position row may give its ``grade`` (IT7) and ``length_mm`` instead of ``zone_mm``; a fit row its
``grade`` (H7/g6) and ``length_mm`` (the seat diameter).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.allocate.drawing import SYMBOLS, Callout, FeatureMap, diameter_factor
from tolalloc.allocate.purchase import PurchasedPart
from tolalloc.allocate.fits import parse_fit
from tolalloc.allocate.process_table import require_process
from tolalloc.allocate.standards import it_value_mm
from tolalloc.exceptions import TolallocError

__all__ = ["DRAWING_COLUMNS", "export_frame", "read_drawing", "read_rows", "NEEDS_DATUM"]

DRAWING_COLUMNS = ("id", "feature", "characteristic", "qif_characteristic", "symbol", "zone_mm", "diameter_zone",
                   "direction", "datum", "length_mm", "grade", "tol_arcsec", "tol_um", "process", "cost",
                   "cost_source", "catalogue_source", "parameters")
#: Characteristics whose zone is located or oriented from a datum.
NEEDS_DATUM = ("perpendicularity", "parallelism", "angularity", "coaxiality", "position")
_ARCSEC = np.pi / 648000.0
_ORIENT = ("perpendicularity", "parallelism", "angularity", "coaxiality")


def export_frame(h) -> pd.DataFrame:
    """The exchange rows (:data:`DRAWING_COLUMNS`) of a :class:`~tolalloc.allocate.handover.Handover`.

    Raises TolallocError naming the feature when an orientation, coaxiality or position zone has no datum.
    """
    from tolalloc.allocate.handover import QIF_TYPES

    rows = []
    for i, c in enumerate(h.callouts):
        if c.characteristic in NEEDS_DATUM and not c.datum:
            raise TolallocError(f"export: {c.feature} ({c.characteristic}) has no datum; a {c.characteristic} zone is "
                                "located from one: give the joint's bearing datum in the robot file's [components] "
                                "or keep the default datums (default_datums=True).")
        rows.append({"id": f"C{i + 1}", "feature": c.feature, "characteristic": c.characteristic,
                     "qif_characteristic": QIF_TYPES[c.characteristic], "symbol": c.symbol, "zone_mm": c.zone_mm,
                     "diameter_zone": c.diameter, "direction": c.direction, "datum": c.datum,
                     "length_mm": c.length_mm, "grade": c.grade, "process": h.process[i], "cost": h.cost[i],
                     "cost_source": h.cost_source[i], "parameters": " ".join(c.parameters)})
    n = len(h.callouts)
    for i, p in enumerate(h.parts):
        tol = {"tol_arcsec": p.required / _ARCSEC} if p.unit == "rad" else {"tol_um": p.required * 1000.0}
        rows.append({"id": f"P{i + 1}", "feature": p.part, "characteristic": "purchased_part", **tol,
                     "grade": p.grade, "process": "purchased part", "cost": h.cost[n + i],
                     "cost_source": h.cost_source[n + i], "catalogue_source": p.source,
                     "parameters": " ".join(p.parameters)})
    return pd.DataFrame(rows, columns=list(DRAWING_COLUMNS))


def read_rows(path) -> pd.DataFrame:
    """The rows of a drawing exchange CSV as text (a byte-order mark is fine); clear errors for a missing or
    unreadable file."""
    from tolalloc.exceptions import InputFileError

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


def read_drawing(source, model, *, z: float = 3.0, distribution: str = "normal",
                 check_processes: bool = True) -> FeatureMap:
    """A drawing exchange file (path) or frame as a :class:`~tolalloc.allocate.drawing.FeatureMap` of ``model``.

    Every callout's ``factor`` (``zone = factor * t``) is derived from its characteristic, length and zone type
    (the file's own figures are not trusted for it). ``check_processes``: refuse a zone or grade finer than any
    process of the built-in table holds (the error names the feature, the finest process and its cost).
    Raises TolallocError naming the row for a missing or bad value, a span of zero, a fit that is not ISO 286 or
    a parameter the model does not have.
    """
    frame, name = (source, "drawing") if isinstance(source, pd.DataFrame) else (read_rows(source), str(source))
    missing = [c for c in ("characteristic", "parameters") if c not in frame.columns]
    if missing:
        raise TolallocError(f"{name}: missing column(s) {', '.join(missing)}; expected {', '.join(DRAWING_COLUMNS)}.")
    known, callouts, parts = set(model.names), [], []
    for i, row in enumerate(frame.to_dict("records")):
        row = {k: ("" if v is None or (isinstance(v, float) and np.isnan(v)) else v) for k, v in row.items()}
        feature = str(row.get("feature") or f"row {i + 1}")
        where = f"{name} row {i + 1} ({feature})"
        params = tuple(str(row["parameters"]).split())
        bad = [p for p in params if p not in known]
        if not params or bad:
            raise TolallocError(f"{where}: parameters {' '.join(bad) or '(none)'} not in the error model; expected "
                                f"names among {', '.join(model.names)}.")
        char = str(row["characteristic"]).strip()
        if char == "purchased_part":
            parts.append(_part(row, params, model, where))
        elif char in SYMBOLS:
            callouts.append(_callout(row, char, params, feature, where, z, distribution, check_processes))
        else:
            raise TolallocError(f"{where}: characteristic {char!r} unknown; expected one of "
                                f"{', '.join(SYMBOLS)}, purchased_part.")
    return FeatureMap(tuple(callouts), tuple(parts), float(z), distribution)


def _part(row, params, model, where) -> PurchasedPart:
    p = model.params[model.index(params[0])]
    if p.unit == "rad":
        t = _num(row, "tol_arcsec", where) * _ARCSEC
    else:
        t = _num(row, "tol_um", where) * 1e-3
    return PurchasedPart(str(row.get("feature", "")), p.element, params, str(row.get("grade", "")), t, p.unit,
                         str(row.get("catalogue_source", "")))


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
        if check:
            for cls in (fit.hole, fit.shaft):
                require_process(f"{where} {cls.name}", grade=cls.grade)
        return Callout(feature, char, zone, False, "", datum, d, fit.name, params, factor, "drawing")
    length = _num(row, "length_mm", where)  # a span of zero or none is refused here
    if char in ("size", "position"):
        zone = (float(_num(row, "zone_mm", where)) if str(row.get("zone_mm", "")).strip() else
                it_value_mm(length, grade) if grade.startswith("IT") else _num(row, "zone_mm", where))
        if check:
            kw = {"grade": int(grade[2:])} if grade.startswith("IT") else {"zone_mm": zone, "length_mm": length}
            require_process(where, **kw)
        return Callout(feature, char, zone, False, "", datum, length, grade, params, 2.0, "drawing")
    zone = _num(row, "zone_mm", where)
    if char not in _ORIENT:
        raise TolallocError(f"{where}: characteristic {char!r} unknown.")
    if diameter or char == "coaxiality":
        factor = length * diameter_factor(z, distribution)
    elif len(params) == 1:
        factor = length
    else:
        raise TolallocError(f"{where}: a zone in one direction bounds one tilt, got {len(params)} parameters; give "
                            "diameter_zone = true for a diameter zone or one row per direction.")
    if check:
        require_process(where, zone_mm=zone, length_mm=length)
    return Callout(feature, char, zone, diameter or char == "coaxiality", direction, datum, length, grade, params,
                   factor, "drawing")
