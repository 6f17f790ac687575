"""Tolerance tables: CSV round trip, Markdown and LaTeX formatting, one unit per column."""

import numpy as np
import pandas as pd
import pytest

from tolalloc import TolallocError
from tolalloc.report.tables import TABLE_COLUMNS, display_frame, format_text, tex_text, write_tables

NAN = np.nan


@pytest.fixture
def frame():
    return pd.DataFrame({
        "parameter": ["dl3", "dth1"], "kind": ["link_length", "joint_drive"], "element": ["l3", "j1"],
        "role": ["allocate", "fixed"], "unit": ["mm", "deg"], "nominal_mm": [796.0, NAN],
        "tol_mm": [0.0625, NAN], "tol_deg": [NAN, 0.00432712], "grade": ["IT8", ""], "process": ["turning", ""],
        "sigma_mm": [0.0208333, NAN], "sigma_deg": [NAN, 0.00144237], "cost": [2.01039, 3.31081],
        "variance_share_pct": [4.61, 7.9], "at_limit": ["", "fixed"], "t_min_mm": [0.005, NAN],
        "t_min_deg": [NAN, 0.0005], "tol_continuous_mm": [0.0989718, NAN], "tol_continuous_deg": [NAN, 0.00432712]})


def test_write_tables_round_trip(tmp_path, frame):
    paths = write_tables(frame, tmp_path, caption="Tolerances of tool_changer: P(|dP| < 0.25 mm) >= 0.95",
                         note="design: standard grades (discrete-exact), the design to build",
                         legend="Columns ending in _mm hold the length rows (mm), 5 %.")
    assert [p.name for p in paths] == ["tolerances.csv", "tolerances.md", "tolerances.tex"]
    back = pd.read_csv(paths[0], keep_default_na=False, na_values=[""])
    assert list(back.columns) == list(frame.columns)  # the table alone: no note column
    np.testing.assert_allclose(back["tol_mm"].iloc[:1], frame["tol_mm"].iloc[:1], rtol=1e-9)
    assert np.isnan(back["tol_mm"].iloc[1]) and back["grade"].fillna("").tolist() == ["IT8", ""]
    md = paths[1].read_text().splitlines()
    assert md[0] == "design: standard grades (discrete-exact), the design to build"
    assert md[2] == "**Tolerances of tool_changer: P(|dP| < 0.25 mm) >= 0.95**"
    assert "| role" in md[4] and "variance_share_pct" in md[4] and "tol_continuous" not in "\n".join(md)
    assert "±0.0625" in md[6] and "| fixed" in md[7] and md[-1].startswith("Columns ending in _mm")
    tex = paths[2].read_text()
    assert r"\toprule" in tex and r"$\pm$0.0625" in tex and r"tool\_changer" in tex and r"link\_length" in tex
    assert r"\caption{Tolerances of tool\_changer: P($|$dP$|$ $<$ 0.25 mm) $\geq$ 0.95. design: standard" in tex
    assert r"{\footnotesize Columns ending in \_mm hold the length rows (mm), 5 \%.}" in tex


def test_display_and_text(frame):
    d = display_frame(frame)
    assert list(d.columns) == [c for c in TABLE_COLUMNS if c in frame.columns]
    assert d.loc[1, "tol_mm"] == "" and d.loc[1, "tol_deg"] == "±0.004327" and d.loc[0, "variance_share_pct"] == "4.6"
    assert d.loc[0, "nominal_mm"] == "796" and d.loc[1, "nominal_mm"] == ""
    text = format_text(frame, ["parameter", "tol_deg"])
    assert "±0.004327" in text and "kind" not in text
    with pytest.raises(TolallocError, match="none of the columns"):
        display_frame(frame, ["nope"])


def test_empty_optional_columns_are_left_out(frame):
    bare = frame.assign(process="", grade="", nominal_mm=NAN)
    assert {"process", "grade", "nominal_mm"}.isdisjoint(display_frame(bare).columns)
    assert {"tol_mm", "tol_deg", "sigma_mm", "sigma_deg"} <= set(display_frame(bare).columns)


def test_tex_text_escapes_and_typesets():
    assert tex_text("a_b 5 % & #1 ±0.1 |x| <= 2 >= 1 tr Σ") == (
        r"a\_b 5 \% \& \#1 $\pm$0.1 $|$x$|$ $\leq$ 2 $\geq$ 1 tr $\Sigma$")


def test_markdown_table_leaves_the_other_unit_of_a_pair_blank():
    from tolalloc.report.tables import markdown_table

    df = pd.DataFrame({"parameter": ["dl1", "dth1"], "tol_mm": [0.1114, np.nan], "tol_deg": [np.nan, 0.004679]})
    rows = markdown_table(df).splitlines()
    assert "nan" not in "\n".join(rows)
    cells = [[c.strip() for c in r.strip("|").split("|")] for r in rows[2:]]
    assert cells == [["dl1", "0.1114", ""], ["dth1", "", "0.004679"]]
