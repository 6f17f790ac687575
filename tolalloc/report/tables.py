"""Tolerance tables as CSV, Markdown and LaTeX.

The table of an allocation (:meth:`tolalloc.allocate.result.AllocationResult.to_frame`) has one row per
parameter. A quantity in mm or deg has two columns, ``<name>_mm`` for the length rows and ``<name>_deg`` for
the angle rows (the other one empty), so that every column holds one unit and says which: ``tol_mm`` /
``tol_deg`` (± half-width), ``sigma_mm`` / ``sigma_deg``, ``t_min_*``, ``t_max_*``, ``tol_continuous_*``,
``tol_rounded_*``; ``variance_share_pct`` is in %, ``cost`` in the relative units of the cost laws. CSV keeps
every column at full precision; Markdown and LaTeX (the hand-over) show :data:`TABLE_COLUMNS` with 4 significant
digits and a ``±`` on the tolerances, the note (which design, what was checked) on their first line / in their
caption and a legend below. LaTeX uses ``pandas.io.formats.style.Styler.to_latex`` (needs jinja2).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

__all__ = ["TABLE_COLUMNS", "UNIT_PAIRS_LEGEND", "display_frame", "write_tables", "format_text", "tex_text",
           "markdown_table"]

#: Columns of the printed / Markdown / LaTeX table (CSV has every column of ``to_frame``).
TABLE_COLUMNS = ["parameter", "kind", "role", "nominal_mm", "tol_mm", "tol_deg", "grade", "process", "sigma_mm",
                 "sigma_deg", "cost", "variance_share_pct", "at_limit", "callout"]

#: The legend's sentence on the column pairs, shared by every tolerance table.
UNIT_PAIRS_LEGEND = ("Columns ending in _mm hold the length rows (mm), those ending in _deg the angle rows (deg); the "
                     "other one of each pair is empty. nominal_mm: the link's nominal length, the size its ISO 286 "
                     "grade applies to.")

#: Columns left out of the printed tables when no row has a value (no processes, no link lengths, no grades).
OPTIONAL_COLUMNS = ("nominal_mm", "grade", "process", "callout")

_TOLERANCE_PREFIXES = ("tol_",)


def markdown_table(df: pd.DataFrame, floatfmt: str = ".4g") -> str:
    """A DataFrame as a Markdown table; a missing value (a row of the other unit of a ``_mm`` / ``_deg`` pair, a figure
    that does not apply) is a blank cell."""
    return df.astype(object).where(df.notna(), None).to_markdown(index=False, floatfmt=floatfmt, missingval="")


def _g(x, digits=4) -> str:
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return ""
    return f"{x:.{digits}g}"


def _empty(s: pd.Series) -> bool:
    if pd.api.types.is_float_dtype(s):
        return not np.isfinite(s.to_numpy(float)).any()
    return not s.astype(str).str.strip().any()


def display_frame(frame: pd.DataFrame, columns=None) -> pd.DataFrame:
    """A string-formatted copy for humans: ``±`` tolerances, 4 significant digits, empty cells for the other
    unit's column; optional columns with no value left out."""
    cols = [c for c in (columns or TABLE_COLUMNS) if c in frame.columns
            and not (c in OPTIONAL_COLUMNS and _empty(frame[c]))]
    if not cols:
        raise TolallocError(f"table: none of the columns {columns or TABLE_COLUMNS} is in the frame ({list(frame.columns)}).")
    out = pd.DataFrame(index=frame.index)
    for c in cols:
        s = frame[c]
        if c.startswith(_TOLERANCE_PREFIXES) and pd.api.types.is_float_dtype(s):
            out[c] = ["" if not np.isfinite(x) else "±" + _g(x) for x in s]
        elif c.endswith("_pct"):
            out[c] = ["" if not np.isfinite(x) else f"{x:.1f}" for x in s]
        elif c.startswith("cost"):
            out[c] = ["" if not np.isfinite(x) else f"{x:.3f}" for x in s]
        elif pd.api.types.is_float_dtype(s):
            out[c] = [_g(x) for x in s]
        else:
            out[c] = s.astype(str)
    return out


def format_text(frame: pd.DataFrame, columns=None) -> str:
    """The table as fixed-width text for the terminal."""
    return display_frame(frame, columns).to_string(index=False)


_TEX = {"\\": r"\textbackslash{}", "_": r"\_", "%": r"\%", "&": r"\&", "#": r"\#", "$": r"\$", "{": r"\{",
        "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "±": r"$\pm$", "<": r"$<$", ">": r"$>$",
        "|": r"$|$", "≥": r"$\geq$", "≤": r"$\leq$", "Σ": r"$\Sigma$", "σ": r"$\sigma$"}


def tex_text(text: str) -> str:
    """Plain text as LaTeX text: special characters escaped, ``>=`` / ``<=`` / ``±`` / ``|`` as math."""
    text = str(text).replace(">=", "≥").replace("<=", "≤")
    return "".join(_TEX.get(ch, ch) for ch in text)


def write_tables(frame: pd.DataFrame, out_dir, stem: str = "tolerances", *, caption: str | None = None,
                 note: str | None = None, legend: str | None = None) -> list[Path]:
    """Write ``<stem>.csv`` (all columns, full precision), ``.md`` and ``.tex`` (formatted) into ``out_dir``.

    ``note`` (which design the table holds and what was checked) is the first line of the Markdown file and
    the start of the LaTeX caption; ``caption`` (robot, requirement, where) follows it; ``legend`` (what the
    columns hold, their units) is written below both tables. The CSV holds the table alone.

    Returns
    -------
    list of Path
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [out_dir / f"{stem}.csv", out_dir / f"{stem}.md", out_dir / f"{stem}.tex"]
    frame.to_csv(paths[0], index=False, float_format="%.10g")
    disp = display_frame(frame)
    head = [x for x in (note, None if caption is None else f"**{caption}**") if x]
    paths[1].write_text("".join(f"{x}\n\n" for x in head) + disp.to_markdown(index=False) + "\n"
                        + ("" if legend is None else f"\n{legend}\n"))
    tex = disp.copy()
    tex.columns = [tex_text(c) for c in tex.columns]
    for c in tex.columns:
        tex[c] = [tex_text(x) for x in tex[c]]
    styler = tex.style.hide(axis="index")
    full = ". ".join(x for x in (caption, note) if x) or None
    body = styler.to_latex(caption=None if full is None else tex_text(full), hrules=True,
                           column_format="l" * tex.shape[1])
    if legend:
        body = body.replace("\\end{table}", f"\\par\\smallskip{{\\footnotesize {tex_text(legend)}}}\n\\end{{table}}")
    paths[2].write_text(body + "\n")
    return paths
