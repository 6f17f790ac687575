"""Tolerance tables as CSV, Markdown and LaTeX.

The table of an allocation (:meth:`tolalloc.allocate.problem.AllocationResult.to_frame`) has one row per
parameter; ``unit`` (mm or deg) is the unit of ``tolerance`` (± half-width), ``sigma``,
``tolerance_std`` (snapped to the standard grade), ``t_min`` and ``t_max``. CSV keeps full
precision; Markdown and LaTeX show 4 significant digits and a ``±`` on the tolerances.
LaTeX uses ``pandas.io.formats.style.Styler.to_latex`` (needs jinja2).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

__all__ = ["TABLE_COLUMNS", "display_frame", "write_tables", "format_text"]

#: Columns of the printed / Markdown / LaTeX table (CSV has every column of ``to_frame``).
TABLE_COLUMNS = ["parameter", "kind", "unit", "tolerance", "sigma", "tolerance_std", "grade", "process", "cost",
                 "variance_share", "at_limit"]


def _g(x, digits=4) -> str:
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return ""
    return f"{x:.{digits}g}"


def display_frame(frame: pd.DataFrame, columns=None) -> pd.DataFrame:
    """A string-formatted copy for humans: ``±`` tolerances, 4 significant digits, shares in %."""
    cols = [c for c in (columns or TABLE_COLUMNS) if c in frame.columns
            and not (c == "process" and not frame[c].astype(str).str.strip().any())]  # no processes in the costs
    if not cols:
        raise TolallocError(f"table: none of the columns {columns or TABLE_COLUMNS} is in the frame ({list(frame.columns)}).")
    out = pd.DataFrame(index=frame.index)
    for c in cols:
        s = frame[c]
        if c in ("tolerance", "tolerance_std"):
            out[c] = ["" if not np.isfinite(x) else "±" + _g(x) for x in s]
        elif c == "variance_share":
            out["variance_share_pct"] = [f"{100 * x:.1f}" for x in s]
        elif c == "cost":
            out[c] = [f"{x:.3f}" for x in s]
        elif pd.api.types.is_float_dtype(s):
            out[c] = [_g(x) for x in s]
        else:
            out[c] = s.astype(str)
    return out


def format_text(frame: pd.DataFrame, columns=None) -> str:
    """The table as fixed-width text for the terminal."""
    return display_frame(frame, columns).to_string(index=False)


def write_tables(frame: pd.DataFrame, out_dir, stem: str = "tolerances", *, caption: str | None = None,
                 note: str | None = None) -> list[Path]:
    """Write ``<stem>.csv`` (all columns, full precision), ``.md`` and ``.tex`` (formatted) into ``out_dir``.

    ``note`` (e.g. which design the table holds: its solver label, fallback, non-convergence, correction) is
    written as a line above the Markdown table and appended to the LaTeX caption.

    Returns
    -------
    list of Path
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [out_dir / f"{stem}.csv", out_dir / f"{stem}.md", out_dir / f"{stem}.tex"]
    frame.to_csv(paths[0], index=False, float_format="%.10g")
    disp = display_frame(frame)
    paths[1].write_text(("" if note is None else f"{note}\n\n") + disp.to_markdown(index=False) + "\n")
    tex = disp.copy()
    tex.columns = [c.replace("_", r"\_") for c in tex.columns]
    for c in tex.columns:
        tex[c] = [str(x).replace("_", r"\_").replace("±", r"$\pm$").replace("%", r"\%") for x in tex[c]]
    styler = tex.style.hide(axis="index")
    if note:
        caption = f"{caption}. {note}" if caption else note
    if caption:
        caption = caption.replace("_", r"\_").replace("%", r"\%").replace(">=", r"$\geq$").replace("<", r"$<$")
    paths[2].write_text(styler.to_latex(caption=caption, hrules=True, column_format="l" * tex.shape[1]) + "\n")
    return paths
