"""ISO 286 fits: limit deviations against ISO 286-2's tabulated values, clearances, bad classes."""

import pytest

from tolalloc import TolallocError
from tolalloc.allocate.fits import PREFERRED_CLEARANCE_FITS, clearance_fits, parse_fit, tolerance_class

# ISO 286-2:2010 limit deviations [um] (upper, lower) at a nominal size inside the tabulated range
ISO_286_2 = [
    ("H7", 40, 25, 0), ("H7", 100, 35, 0), ("H7", 8, 15, 0), ("H8", 100, 54, 0), ("H6", 40, 16, 0),
    ("g6", 40, -9, -25), ("g6", 25, -7, -20), ("g5", 40, -9, -20), ("f7", 25, -20, -41), ("f7", 60, -30, -60),
    ("e8", 40, -50, -89), ("d9", 60, -100, -174), ("h6", 100, 0, -22), ("h5", 40, 0, -11), ("js6", 40, 8, -8),
    ("k6", 40, 18, 2), ("k6", 100, 25, 3), ("m6", 40, 25, 9), ("n6", 40, 33, 17), ("p6", 40, 42, 26),
    ("p6", 100, 59, 37), ("G7", 8, 20, 5), ("F8", 15, 43, 16), ("E9", 40, 112, 50), ("D10", 60, 220, 100),
    ("JS7", 40, 12.5, -12.5), ("K7", 40, 7, -18), ("K6", 60, 4, -15), ("K8", 40, 12, -27), ("M7", 40, 0, -25),
    ("M6", 300, -9, -41), ("N7", 25, -7, -28), ("N9", 40, 0, -62), ("P7", 25, -14, -35), ("P8", 40, -26, -65),
    ("K7", 2, 0, -10), ("N7", 2, -4, -14), ("M7", 2, -2, -12), ("P6", 40, -21, -37),
]


@pytest.mark.parametrize("name, size, upper, lower", ISO_286_2)
def test_limit_deviations_match_iso_286_2(name, size, upper, lower):
    c = tolerance_class(name, size)
    assert (c.upper_um, c.lower_um) == (pytest.approx(upper), pytest.approx(lower))
    assert c.is_hole == name[0].isupper()


def test_fit_clearances_and_kind():
    f = parse_fit("H7/g6", 50)
    assert (f.clearance_min_um, f.clearance_max_um) == (9, 50)  # ISO 286-2: H7/g6 over 30 up to 50 mm
    assert f.kind == "clearance" and f.radial_play_max_mm == pytest.approx(0.025)
    assert parse_fit("H7/k6", 50).kind == "transition"
    assert parse_fit("H7/p6", 50).kind == "interference" and parse_fit("H7/p6", 50).radial_play_max_mm == 0.0
    fits = clearance_fits(50)
    assert [f.clearance_max_um for f in fits] == sorted(f.clearance_max_um for f in fits)
    assert len(fits) == len(PREFERRED_CLEARANCE_FITS) and all(f.kind == "clearance" for f in fits)


@pytest.mark.parametrize("text, match", [
    ("H7-g6", r"not an ISO 286 fit; expected hole class / shaft class such as H7/g6"),
    ("g6/H7", r"expected the hole class first"),
    ("H7/x6", r"fundamental deviation 'x' is not implemented"),
    ("H7/g", r"'g' is not an ISO 286 tolerance class"),
    ("H19/g6", r"grade IT19 is not an ISO 286 grade"),
])
def test_bad_fits_are_refused(text, match):
    with pytest.raises(TolallocError, match=match):
        parse_fit(text, 50, where="joint j2 fit")


def test_size_out_of_range():
    with pytest.raises(TolallocError, match=r"0 < D <= 500 mm"):
        tolerance_class("H7", 600)
