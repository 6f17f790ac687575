"""The handover files of a design: ``drawing.csv`` (the exchange file), ``purchase_list.csv`` and ``handover.md``
(drawing callouts, purchase list, cost sources, assumptions), and the same tables for ``report.html``.

Everything is taken from a :class:`~tolalloc.allocate.handover.Handover`; nothing is recomputed here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tolalloc.allocate.drawing_io import export_frame

__all__ = ["HANDOVER_FILES", "write_handover", "handover_markdown", "handover_html"]

HANDOVER_FILES = ("drawing.csv", "purchase_list.csv", "handover.md")
_DRAWING = ["feature", "callout", "zone_um", "datum", "length_mm", "grade", "process", "cost", "parameters"]
_PARTS = ["part", "grade", "required_arcsec", "required_um", "catalogue_source", "meets", "cost", "parameters"]


def _md_table(frame) -> str:
    def cell(v):
        if isinstance(v, float):
            return "" if np.isnan(v) else f"{v:.4g}"
        return str(v).replace("|", "\\|")
    lines = ["| " + " | ".join(frame.columns) + " |", "|" + "---|" * len(frame.columns)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in frame.itertuples(index=False)]
    return "\n".join(lines)


def handover_markdown(h, title: str) -> str:
    """``handover.md``: drawing callouts, purchase list, cost sources and assumptions of handover ``h``."""
    draw, parts = h.drawing_frame(), h.purchase_frame()
    sources = sorted(set(h.cost_source))
    out = [f"# {title}", "",
           "## Drawing callouts (ISO 1101, ISO 286)", "",
           "Zones in mm as the drawing carries them, rounded down (never looser than the design); `zone_um` and "
           "`drawing.csv` carry the exact zone. Spans marked `assumed default` and datum letters marked `assumed "
           "letter` are stated defaults (see the assumptions, which list every datum feature); a datum system is "
           "read in order of precedence (`B|K`: axis B primary, then K).", "",
           _md_table(draw[_DRAWING]), "",
           "## Purchase list", "",
           "Allowed error of each joint drive (reducer + encoder) as a half-width: arcsec (revolute), um "
           "(prismatic).", "",
           _md_table(parts[_PARTS]), "",
           "## Cost sources", "",
           "Cost per row in relative cost units; every row's source is one of:", ""]
    out += [f"- {s}" for s in sources]
    out += ["", "## Assumptions behind the verdict", ""] + [f"- {a}" for a in h.assumptions] + [""]
    return "\n".join(out)


def write_handover(h, folder, title: str) -> list[str]:
    """Write :data:`HANDOVER_FILES` of handover ``h`` into the existing directory ``folder``; their names."""
    folder = Path(folder)
    export_frame(h).to_csv(folder / "drawing.csv", index=False, float_format="%.10g")
    h.purchase_frame().to_csv(folder / "purchase_list.csv", index=False, float_format="%.10g")
    (folder / "handover.md").write_text(handover_markdown(h, title), encoding="utf-8")
    return list(HANDOVER_FILES)


def handover_html(h) -> dict:
    """The report's handover section: the drawing and purchase tables (for ``m.table``) and the assumptions."""
    from tolalloc.report.html import Column, html_table

    draw, parts = h.drawing_frame(), h.purchase_frame()
    dcols = [Column("feature", "feature", "text"), Column("callout", "callout", "text"),
             Column("zone_um", "zone [µm]", "g4"), Column("datum", "datum", "text"),
             Column("length_mm", "length [mm]", "g4"), Column("grade", "grade or fit", "text"),
             Column("process", "process", "text"), Column("cost", "cost", "g4"),
             Column("cost_source", "cost source", "text"), Column("parameters", "error parameters", "text")]
    pcols = [Column("part", "part", "text"), Column("grade", "grade to order", "text"),
             Column("required_arcsec", "allowed ± [arcsec]", "g4", optional=True),
             Column("required_um", "allowed ± [µm]", "g4", optional=True),
             Column("catalogue_source", "catalogue source", "text"), Column("meets", "part meets it", "text"),
             Column("cost", "cost", "g4"), Column("cost_source", "cost source", "text"),
             Column("parameters", "error parameters", "text")]
    return {"drawing": html_table(draw, dcols, table_id="drawing-table", caption="Drawing callouts (ISO 1101, ISO 286)",
                                  note="Zones in mm as the drawing carries them (rounded down); the exact zone in µm. "
                                       "drawing.csv is the machine-readable export (one row per characteristic, with "
                                       "its QIF 3 characteristic type)."),
            "parts": html_table(parts, pcols, table_id="purchase-table", caption="Purchase list",
                                note="Allowed error of each joint drive (reducer + encoder) as a half-width."),
            "assumptions": list(h.assumptions)}
