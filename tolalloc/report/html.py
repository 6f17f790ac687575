"""Self-contained HTML reports (``report.html``): Jinja2 templates rendered from plain data.

The templates (``tolalloc/report/templates/``) receive tables as rows of formatted text (:func:`html_table`),
figures as ``data:`` URIs (:func:`figure_uri`, SVG or PNG) and lists of ``(label, value)`` pairs. Opening the file
loads nothing else: the style sheet is inline, there are no scripts, no web fonts and no external links. This module
formats and lays out; it takes every number from the caller and computes none.
"""

from __future__ import annotations

import base64
import datetime as _dt
import io
import math
import platform
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import pandas as pd

__all__ = ["Column", "html_table", "figure_uri", "figure_item", "file_figure_item", "writer_figure_item",
           "software_versions",
           "render_report", "write_html", "fmt_value", "pretty", "plot_calibrated_tolerances", "REPORT_FILE"]

#: file name of the report inside an output directory
REPORT_FILE = "report.html"

#: distributions whose versions the report lists (those that decide the numbers, then the ones that draw them)
VERSION_PACKAGES = ("tolalloc", "numpy", "scipy", "pandas", "cvxpy", "clarabel", "casadi", "numba", "matplotlib",
                    "jinja2")


# ---------------------------------------------------------------------------------------------- formatting
def _finite(x) -> bool:
    try:
        return x is not None and not isinstance(x, str) and math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def fmt_value(x, how: str = "g4") -> str:
    """One cell as text.

    ``how``: ``text``; ``g4`` (4 significant digits); ``f4`` / ``f3`` / ``f2`` / ``f1`` (fixed decimals); ``pm``
    (``±`` and 4 significant digits); ``pct`` (a share 0..1 shown in % with 1 decimal); ``pct1`` (already in %, 1
    decimal); ``int``; ``sci`` (2-digit scientific, p-values); ``bool`` (yes / no); ``ci`` (a pair ``[lo, hi]``
    with 4 decimals). Missing or non-finite numbers give an empty cell.
    """
    if how == "text":
        return "" if x is None or (isinstance(x, float) and math.isnan(x)) else str(x)
    if how == "bool":
        return "" if x is None else ("yes" if bool(x) else "no")
    if how == "ci":
        lo, hi = x
        return f"[{lo:.4f}, {hi:.4f}]" if _finite(lo) and _finite(hi) else ""
    if not _finite(x):
        return ""
    v = float(x)
    if how == "g4":
        return f"{v:.4g}"
    if how == "pm":
        return f"±{v:.4g}"
    if how == "pct":
        return f"{100 * v:.1f}"
    if how == "pct1":
        return f"{v:.1f}"
    if how == "int":
        return f"{int(round(v)):d}"
    if how == "sci":
        return f"{v:.2e}"
    m = re.fullmatch(r"f(\d)", how)
    if m:
        return f"{v:.{int(m.group(1))}f}"
    raise ValueError(f"unknown cell format {how!r}")


def pretty(text) -> str:
    """A message with typographic comparison signs (``>=`` as ``≥``, ``<=`` as ``≤``)."""
    return str(text).replace(">=", "≥").replace("<=", "≤")


@dataclass(frozen=True)
class Column:
    """One column of a report table.

    Attributes
    ----------
    key : str
        Column of the frame.
    label : str
        Header text (with its unit, e.g. ``"tolerance ± [mm or deg]"``).
    how : str
        Cell format (see :func:`fmt_value`).
    numeric : bool
        Right-aligned, tabular figures (default: every format but ``text`` and ``bool``).
    badge : bool
        Cells shown as a coloured label (verdicts, statuses); the cell's text is its CSS class too.
    optional : bool
        Left out when every cell is empty (e.g. a reason column where every pose passed).
    """

    key: str
    label: str
    how: str = "g4"
    numeric: bool | None = None
    badge: bool = False
    optional: bool = False

    @property
    def is_numeric(self) -> bool:
        return self.how not in ("text", "bool") if self.numeric is None else self.numeric


def _badge_class(text: str) -> str:
    return "badge b-" + re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")


def html_table(frame: pd.DataFrame, columns, *, table_id: str, caption: str, note: str | None = None,
               row_classes=None, compact: bool = False) -> dict:
    """A table for the templates: header cells and rows of formatted text, one row per frame row, in order.

    Columns whose ``key`` is not in ``frame`` are left out, and optional columns with no text. ``row_classes``:
    a CSS class per row (``hl`` highlighted, ``bad`` failing, ``chosen`` bold). ``compact``: as wide as its content
    instead of the full page.
    """
    cols = [c for c in columns if c.key in frame.columns]
    text = {c.key: [fmt_value(v, c.how) for v in frame[c.key]] for c in cols}
    cols = [c for c in cols if not (c.optional and not any(text[c.key]))]
    rows = []
    for i in range(len(frame)):
        cells = []
        for c in cols:
            t = text[c.key][i]
            cls = ("num" if c.is_numeric else "txt") + (f" {_badge_class(t)}" if c.badge and t else "")
            cells.append({"text": t, "cls": cls})
        rows.append({"cells": cells, "cls": "" if row_classes is None else str(row_classes[i] or "")})
    return {"id": table_id, "caption": caption, "note": note, "cls": "compact" if compact else "",
            "columns": [{"label": c.label, "key": c.key, "cls": "num" if c.is_numeric else "txt"} for c in cols],
            "rows": rows}


# ---------------------------------------------------------------------------------------------- figures
_SVG_PROLOGUE = re.compile(rb"<\?xml[^>]*\?>\s*(<!DOCTYPE[^>]*>\s*)?", re.S)
_SVG_METADATA = re.compile(rb"\s*<metadata>.*?</metadata>", re.S)


def _data_uri(payload: bytes, fmt: str) -> str:
    if fmt == "svg":
        payload = _SVG_PROLOGUE.sub(b"", payload, count=1)  # the DOCTYPE names an external DTD; not needed
        payload = _SVG_METADATA.sub(b"", payload, count=1)  # its date: the same figure gives the same bytes
    mime = "image/svg+xml" if fmt == "svg" else "image/png"
    return f"data:{mime};base64,{base64.b64encode(payload).decode('ascii')}"


def _savefig_options(fmt: str) -> tuple[dict, dict]:
    """``(rcParams, savefig keyword arguments)`` for reproducible figure bytes without metadata (an SVG's metadata
    block, with its date, is dropped by :func:`_data_uri`, also where a plotting function saves the figure itself)."""
    if fmt == "svg":
        return {"svg.hashsalt": "tolalloc", "savefig.format": "svg"}, {}
    if fmt == "png":
        return {"savefig.format": "png"}, {"metadata": {"Software": None}}
    raise ValueError(f"figure format: expected 'svg' or 'png', got {fmt!r}")


def figure_uri(fig, fmt: str = "svg", dpi: int = 110) -> str:
    """A matplotlib figure as a ``data:`` URI (SVG: vector, for charts; PNG: for dense point clouds); closes it."""
    import matplotlib
    import matplotlib.pyplot as plt

    if not hasattr(fig, "savefig"):  # the Axes (or array of Axes) a result's plot_* method returns
        import numpy as np

        fig = np.ravel(np.asarray(fig, dtype=object))[0].figure
    rc, kw = _savefig_options(fmt)
    buf = io.BytesIO()
    try:
        with matplotlib.rc_context(rc):
            fig.savefig(buf, format=fmt, dpi=dpi, **kw)
    finally:
        plt.close(fig)
    return _data_uri(buf.getvalue(), fmt)


def figure_item(fig, *, figure_id: str, caption: str, fmt: str = "svg", dpi: int = 110) -> dict:
    """A figure for the templates: ``{"id", "caption", "uri", "fmt"}`` from a matplotlib figure (closed)."""
    return {"id": figure_id, "caption": caption, "uri": figure_uri(fig, fmt, dpi), "fmt": fmt}


def file_figure_item(path, *, figure_id: str, caption: str) -> dict:
    """A figure for the templates from a PNG or SVG file already drawn (e.g. the copy saved beside the report)."""
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ("png", "svg"):
        raise ValueError(f"figure file: expected a .png or .svg file, got {path.name!r}")
    return {"id": figure_id, "caption": caption, "uri": _data_uri(path.read_bytes(), fmt), "fmt": fmt}


def writer_figure_item(write: Callable, *, figure_id: str, caption: str, fmt: str = "svg") -> dict:
    """A figure for the templates from a plotting function that saves to a path: ``write(file_object)``."""
    import matplotlib

    rc, _ = _savefig_options(fmt)
    buf = io.BytesIO()
    with matplotlib.rc_context(rc):
        write(buf)
    return {"id": figure_id, "caption": caption, "uri": _data_uri(buf.getvalue(), fmt), "fmt": fmt}


# ---------------------------------------------------------------------------------------------- provenance
def software_versions() -> list[tuple[str, str]]:
    """``[(name, version)]``: Python, the packages that decide and draw the numbers, and the platform."""
    from importlib.metadata import PackageNotFoundError, version

    out = [("python", platform.python_version())]
    for name in VERSION_PACKAGES:
        try:
            out.append((name, version(name)))
        except PackageNotFoundError:
            out.append((name, "not installed"))
    out.append(("platform", f"{platform.system()} {platform.machine()}"))
    return out


# ---------------------------------------------------------------------------------------------- rendering
def _environment():
    import jinja2

    env = jinja2.Environment(loader=jinja2.PackageLoader("tolalloc.report", "templates"),
                             autoescape=jinja2.select_autoescape(default=True, default_for_string=True),
                             undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    env.filters["fmt"] = fmt_value
    return env


def generated_at() -> str:
    """The report's date: now, or ``SOURCE_DATE_EPOCH`` when set (the reproducible-builds convention, so that two
    runs of the same job write the same bytes)."""
    import os

    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    when = (_dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc) if epoch.isdigit()
            else _dt.datetime.now(_dt.timezone.utc))
    return when.strftime("%Y-%m-%d %H:%M UTC")


def render_report(template: str, context: dict) -> str:
    """Render ``template`` (``allocation.html.j2``, ``calibrated.html.j2``, ``diagnosis.html.j2``) with ``context``.

    The context supplies ``title``, ``subtitle``, ``sections`` (``[{"id", "title"}]``, the contents list),
    ``verdict``, ``inputs``, ``reproduce`` and the job's tables and figures; ``versions`` and ``generated`` are
    added when missing.
    """
    versions = software_versions()
    ctx = {"versions": versions, "tolalloc_version": dict(versions).get("tolalloc", "unknown"),
           "generated": generated_at()} | dict(context)
    return _environment().get_template(template).render(**ctx)


def write_html(text: str, folder) -> Path:
    """Write ``report.html`` (UTF-8) into the existing directory ``folder``; returns its path."""
    path = Path(folder) / REPORT_FILE
    path.write_text(text, encoding="utf-8")
    return path


def plot_calibrated_tolerances(table: pd.DataFrame):
    """Tolerance per parameter with and without calibration (log scale); returns the figure.

    ``table``: :meth:`CalibratedToleranceAllocation.to_frame` (columns parameter, unit, tol_mm / tol_deg,
    tol_no_calibration_mm / _deg, status).
    """
    import matplotlib.pyplot as plt

    from tolalloc.report.plots import fit_layout
    from tolalloc.units import in_row_unit

    y = np.arange(len(table))[::-1]
    fig, ax = plt.subplots(figsize=(8, 0.26 * len(table) + 1.4))
    held = table["status"].str.startswith("must be held").to_numpy()
    ax.barh(y + 0.2, in_row_unit(table, "tol_no_calibration"), height=0.4, color="#9aa7b4", label="without calibration")
    ax.barh(y - 0.2, in_row_unit(table, "tol"), height=0.4, color=np.where(held, "#c44e52", "#4c72b0"),
            label="with the plan (red: must be held)")
    ax.set_xscale("log")
    ax.set_yticks(y, [f"{p} [{u}]" for p, u in zip(table["parameter"], table["unit"])], fontsize=8)
    ax.set_xlabel("tolerance ± (mm or deg, log scale)")
    ax.legend(fontsize=8, loc="lower right")
    fit_layout(fig)
    return fig
