"""Denavit-Hartenberg rows with units in their keys, read into internal units (mm, rad).

Shared by the DH loaders (:mod:`tolalloc.robot.io.dh`: TOML and CSV) and :meth:`Robot.from_dh
<tolalloc.robot.model.Robot.from_dh>` (a table given in Python, checked by :func:`rows_from_table`); imports nothing
of the robot model, so the model can use it.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, describe
from tolalloc.units import ALL_UNITS as _ALL_UNITS, ANGLE_UNITS, LENGTH_UNITS, unit_value

__all__ = ["check_limits", "parse_dh_rows", "row_from_cells", "rows_from_table", "CSV_COLUMNS"]

#: columns of a DH table (CSV file or DataFrame)
CSV_COLUMNS = ("name", "type", "d_mm", "d_m", "a_mm", "a_m", "alpha_deg", "alpha_rad", "theta_offset_deg",
               "theta_offset_rad", "lower_deg_mm", "upper_deg_mm", "nominal_deg_mm")


def _unit_value(data: dict, base: str, allowed: dict, default=None, check: bool = True):
    return unit_value(data, base, allowed, default, exclude=("d_offset",) if base == "d" else (), check=check)


def check_limits(lim, nom, revolute: bool) -> None:
    """Joint limits ``[lower, upper]`` and nominal value [rad or mm]: lower < upper, nominal inside (ValueError)."""
    shown = (lambda x: np.round(np.rad2deg(x), 9).tolist()) if revolute else (lambda x: np.asarray(x).tolist())
    unit = "deg" if revolute else "mm"
    if np.shape(lim) != (2,) or not lim[0] < lim[1]:
        raise ValueError(f"limits must be [lower, upper] with lower < upper, got {shown(lim)} {unit}")
    if np.shape(nom) != () or not lim[0] - 1e-12 <= float(nom) <= lim[1] + 1e-12:
        raise ValueError(f"nominal value {shown(nom)} {unit} lies outside the joint limits {shown(lim)} {unit}; "
                         "expected one number inside the limits")


def parse_dh_rows(dh: list[dict]) -> list[dict]:
    """DH rows with unit keys (``d_mm``, ``alpha_deg``, ``limits_deg`` ...) -> rows in internal units.

    Returns
    -------
    list of dict
        Keys ``name``, ``type``, ``d``, ``a`` [mm], ``alpha``, ``theta_offset`` [rad], ``lower``, ``upper``,
        ``nominal`` [rad or mm] (the input of :func:`tolalloc.robot.elements.chain_from_dh`).
    """
    rows = []
    for i, row in enumerate(dh):
        where = f"dh[{i}]"
        known = {"name", "type"}
        try:
            kind = row.get("type", "revolute")
            if kind not in ("revolute", "prismatic", "continuous"):
                raise ValueError(f"type must be 'revolute', 'prismatic' or 'continuous', got {kind!r}")
            for key in row:
                if key not in known and not any(key.startswith(b + "_") and key[len(b) + 1:] in _ALL_UNITS
                                                for b in ("d", "a", "alpha", "theta_offset", "limits", "nominal")):
                    raise ValueError(f"unknown key {key!r}; expected name, type, d_mm|d_m, a_mm|a_m, alpha_deg|alpha_rad, theta_offset_deg|theta_offset_rad, limits_*, nominal_*")
            d, _ = _unit_value(row, "d", LENGTH_UNITS, 0.0)
            a, _ = _unit_value(row, "a", LENGTH_UNITS, 0.0)
            alpha, _ = _unit_value(row, "alpha", ANGLE_UNITS, 0.0)
            th0, _ = _unit_value(row, "theta_offset", ANGLE_UNITS, 0.0)
            rev = kind != "prismatic"
            units = ANGLE_UNITS if rev else LENGTH_UNITS
            lim, _ = _unit_value(row, "limits", units, np.array([-2 * np.pi, 2 * np.pi]) if rev else np.array([-1000.0, 1000.0]))
            nom, _ = _unit_value(row, "nominal", units, 0.0)
            for key, val in (("d", d), ("a", a), ("alpha", alpha), ("theta_offset", th0)):
                if np.shape(val) != () or not np.isfinite(val):
                    raise ValueError(f"{key} must be one finite number, got {np.asarray(val).tolist()}")
            check_limits(lim, nom, rev)
        except ValueError as exc:
            raise TolallocError(f"{where}: {exc}") from None
        rows.append(dict(name=str(row.get("name", f"j{i + 1}")), type="revolute" if rev else "prismatic",
                         d=float(d), a=float(a), alpha=float(alpha), theta_offset=float(th0),
                         lower=float(lim[0]), upper=float(lim[1]), nominal=float(nom)))
    return rows


def row_from_cells(cells: dict, i: int, source: str) -> dict:
    """One row of a DH table (CSV columns, values as text or numbers) -> a row with unit keys (see
    :func:`parse_dh_rows`); ``lower_deg_mm`` / ``upper_deg_mm`` / ``nominal_deg_mm`` take the joint's unit."""
    given = dict(cells)
    cells = {k: ("" if v is None or (isinstance(v, float) and np.isnan(v)) else str(v).strip()) for k, v in cells.items()}
    row = {"name": cells["name"]}

    def number(col: str, text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise ValueError(f"{col}: expected a number, got {describe(given[col])}") from None

    kind = cells.get("type") or "revolute"
    row["type"] = kind
    unit = "mm" if kind == "prismatic" else "deg"
    try:
        for col, val in cells.items():
            if col in ("name", "type") or val == "":
                continue
            if col in ("lower_deg_mm", "upper_deg_mm"):
                continue
            key = f"nominal_{unit}" if col == "nominal_deg_mm" else col
            row[key] = number(col, val)
        lo, hi = cells.get("lower_deg_mm", ""), cells.get("upper_deg_mm", "")
        if (lo == "") != (hi == ""):
            raise ValueError("give both lower_deg_mm and upper_deg_mm, or neither")
        if lo != "":
            row[f"limits_{unit}"] = [number("lower_deg_mm", lo), number("upper_deg_mm", hi)]
    except ValueError as exc:
        raise TolallocError(f"{source}: dh[{i}] ({cells['name']}): {exc}; expected numbers in the unit of the column name.") from None
    return row


def _check_cells(records: list, frame: bool) -> None:
    """No NaN or inf given as a value (a DataFrame's NaN is an empty cell: its column's default), and no empty alpha
    in a DataFrame."""
    for i, r in enumerate(records):
        where = f"table: row {i + 1} ({r.get('name')})"
        for key, v in r.items():
            if isinstance(v, (float, np.floating)) and (np.isinf(v) or (np.isnan(v) and not frame)):
                raise TolallocError(f"{where}: {key} = {v}; expected a finite number in the unit of the column name "
                                    "(leave the key out for its default).")
        alpha = [r[k] for k in ("alpha_deg", "alpha_rad") if k in r]
        if frame and alpha and all(isinstance(v, float) and np.isnan(v) for v in alpha):
            raise TolallocError(f"{where}: alpha_deg / alpha_rad is empty; expected the twist of every row.")


def rows_from_table(table) -> list[dict]:
    """The rows of a DH table given in Python (:meth:`Robot.from_dh <tolalloc.robot.model.Robot.from_dh>`) in
    internal units (:func:`parse_dh_rows`); messages start with ``table``.

    Parameters
    ----------
    table : DataFrame or list of dict
        One row per joint with a ``name``, an ``alpha_deg`` or ``alpha_rad`` column and columns among
        :data:`CSV_COLUMNS`.

    Returns
    -------
    list of dict
        As :func:`parse_dh_rows`.
    """
    if isinstance(table, pd.DataFrame):
        records = table.to_dict(orient="records")
    else:
        records = list(table) if isinstance(table, (list, tuple)) else None
    if not records or not all(isinstance(r, dict) and isinstance(r.get("name"), (str, int, np.integer))
                              and str(r["name"]).strip() for r in records):
        raise TolallocError("table: expected a DataFrame or a list of dicts, one row per joint, each with a name "
                            f"(a string) and columns among {', '.join(CSV_COLUMNS)}, got {describe(table)}.")
    cols = sorted({str(k) for r in records for k in r})
    unknown = [c for c in cols if c not in CSV_COLUMNS]
    if "name" not in cols or unknown or not ({"alpha_deg", "alpha_rad"} & set(cols)):
        raise TolallocError(f"table: columns {cols}: expected a 'name' column, an alpha_deg or alpha_rad column and "
                            f"columns among {', '.join(CSV_COLUMNS)}" + (f"; unknown: {unknown}" if unknown else "") + ".")
    _check_cells(records, isinstance(table, pd.DataFrame))
    try:
        return parse_dh_rows([row_from_cells(r, i, "table") for i, r in enumerate(records)])
    except TolallocError as exc:
        raise TolallocError(str(exc) if str(exc).startswith("table") else f"table: {exc}") from None
