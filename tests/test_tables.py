"""Tolerance tables: CSV round trip, Markdown and LaTeX formatting."""

import numpy as np
import pandas as pd
import pytest

from tolalloc import TolallocError
from tolalloc.report.tables import TABLE_COLUMNS, display_frame, format_text, write_tables


@pytest.fixture
def frame():
    return pd.DataFrame({
        "parameter": ["dl3", "dth1"], "kind": ["link_length", "joint_drive"], "element": ["l3", "j1"],
        "unit": ["mm", "deg"], "role": ["allocate", "allocate"], "tolerance": [0.0989718, 0.00432712],
        "sigma": [0.0329906, 0.00144237], "tolerance_std": [0.0625, np.nan], "it_grade": ["IT8", ""],
        "grade": ["IT8", ""], "process": ["turning", ""],
        "cost": [2.01039, 3.31081], "variance_share": [0.0461, 0.079], "at_limit": ["", "t_min"],
        "t_min": [0.005, 0.0005], "t_max": [1.0, 0.5]})


def test_write_tables_round_trip(tmp_path, frame):
    paths = write_tables(frame, tmp_path, caption="tool_changer: P >= 0.95")
    assert [p.name for p in paths] == ["tolerances.csv", "tolerances.md", "tolerances.tex"]
    back = pd.read_csv(paths[0], keep_default_na=False, na_values=[""])
    assert list(back.columns) == list(frame.columns)
    np.testing.assert_allclose(back["tolerance"], frame["tolerance"], rtol=1e-9)
    assert back["it_grade"].fillna("").tolist() == ["IT8", ""]
    md = paths[1].read_text()
    assert "±0.09897" in md and "variance_share_pct" in md and "| dl3" in md
    tex = paths[2].read_text()
    assert r"\toprule" in tex and r"$\pm$0.0625" in tex and r"tool\_changer" in tex and r"link\_length" in tex


def test_display_and_text(frame):
    d = display_frame(frame)
    assert list(d.columns) == [c if c != "variance_share" else "variance_share_pct" for c in TABLE_COLUMNS]
    assert d.loc[1, "tolerance_std"] == "" and d.loc[0, "variance_share_pct"] == "4.6"
    text = format_text(frame, ["parameter", "tolerance"])
    assert "±0.004327" in text and "kind" not in text
    with pytest.raises(TolallocError, match="none of the columns"):
        display_frame(frame, ["nope"])
