"""ISO 286 IT grades and snapping."""

import numpy as np
import pytest

from tolalloc import TolallocError
from tolalloc.allocate.standards import IT_GRADES, IT_SIZES_MM, IT_TABLE_UM, it_value_mm, snap_angle, snap_length

LOWER = np.concatenate([[1.0], IT_SIZES_MM[:-1]])  # the first range is 0-3 mm; the standard uses D = sqrt(1*3)
D = np.sqrt(LOWER * IT_SIZES_MM)
UNIT = np.where(IT_SIZES_MM <= 500, 0.45 * np.cbrt(D) + 0.001 * D, 0.004 * D + 2.1)  # i or I [um]
MULT = {"IT5": 7, "IT6": 10, "IT7": 16, "IT8": 25, "IT9": 40, "IT10": 64, "IT11": 100, "IT12": 160, "IT13": 250,
        "IT14": 400, "IT15": 640, "IT16": 1000, "IT17": 1600, "IT18": 2500}


@pytest.mark.parametrize("grade", list(MULT))
def test_table_matches_the_standard_formulas(grade):
    # the standard rounds its values (and treats the first range, up to 3 mm, specially): within 10 %
    col = IT_TABLE_UM[1:, IT_GRADES.index(grade)]
    ref = MULT[grade] * UNIT[1:]
    assert np.all(np.abs(col / ref - 1) < 0.10), np.c_[IT_SIZES_MM[1:], col, ref]


def test_table_is_monotone():
    assert np.all(np.diff(IT_TABLE_UM, axis=1) > 0)   # coarser grade, wider zone
    assert np.all(np.diff(IT_TABLE_UM, axis=0) >= 0)  # larger size, wider zone
    assert IT_TABLE_UM.shape == (len(IT_SIZES_MM), 18)


def test_known_values_and_range_edges():
    assert it_value_mm(500, "IT7") == pytest.approx(0.063)
    assert it_value_mm(315, "IT7") == pytest.approx(0.052)   # "over 250 up to and including 315"
    assert it_value_mm(315.1, "IT7") == pytest.approx(0.057)
    assert it_value_mm(796, "IT6") == pytest.approx(0.050)
    with pytest.raises(TolallocError, match="3150"):
        it_value_mm(4000, "IT7")
    with pytest.raises(TolallocError, match="IT grade"):
        it_value_mm(100, "IT19")


def test_snap_length_at_or_below_and_process_limit():
    t, g = snap_length(0.1, 796.0)  # zone 0.2 mm at 630-800: IT9 = 0.200
    assert (t, g) == (pytest.approx(0.1), "IT9")
    t, g = snap_length(0.099, 796.0)
    assert g == "IT8" and t == pytest.approx(0.0625) and t <= 0.099
    t, g = snap_length(0.004, 796.0, t_min_mm=0.0)  # zone 0.008 < IT1 (0.010): kept
    assert g == "<IT1" and t == 0.004
    t, g = snap_length(0.0100, 796.0, t_min_mm=0.0095)  # IT3 (0.018/2 = 0.009) below t_min -> IT4 (0.0125)
    assert g == "IT4" and t == pytest.approx(0.0125)


def test_snap_angle():
    step = 1 / 3600
    assert snap_angle(np.deg2rad(0.0042), step) == pytest.approx(np.deg2rad(15 * step))
    assert snap_angle(np.deg2rad(0.0042), 0.001) == pytest.approx(np.deg2rad(0.004))
    assert snap_angle(np.deg2rad(0.0042), 0.001, t_min_rad=np.deg2rad(0.00415)) == pytest.approx(np.deg2rad(0.005))
    with pytest.raises(TolallocError, match="angle step"):
        snap_angle(0.01, 0.0)
