"""Requirement objects (tolalloc.acceptance.requirements): statements, records and refusals."""

import pytest

from tolalloc.exceptions import ArgumentError
from tolalloc.acceptance import (Conditions, DistanceAccuracy, OrientationRepeatability, PathAccuracy, PoseAccuracy,
                                 PoseRepeatability, PositionRequirement, check_requirements, split_requirements)


def test_texts_state_statistic_population_and_conditions():
    assert PoseRepeatability(limit_mm=0.05).text() == (
        "RP_l <= 0.05 mm for 95 % of built robots (ISO 9283 7.2.2; 100 % rated load, 100 % rated velocity)")
    r = PoseAccuracy(limit_mm=0.5, share=0.9, population="robot", conditions=Conditions(load_pct=10),
                     guard_band=True)
    assert r.text() == ("AP_P <= 0.5 mm for the robot, with probability 0.9 (ISO 9283 7.2.1; 10 % rated load, "
                        "100 % rated velocity; demonstrated with the measurement uncertainty)")
    assert DistanceAccuracy(limit_mm=0.2, poses=(3, 5)).text().startswith("|AD_P| (P3-P5) <= 0.2 mm")
    assert OrientationRepeatability(limit_deg=0.01).limit == pytest.approx(0.01 * 3.141592653589793 / 180)


def test_records_round_trip():
    r = PathAccuracy(limit_mm=0.4, points=7, conditions=Conditions(speed_pct=50))
    d = r.to_dict()
    assert d == {"kind": "path_accuracy", "share": 0.95, "population": "fleet", "load_pct": 100.0, "speed_pct": 50.0,
                 "guard_band": False, "limit_mm": 0.4, "points": 7}


@pytest.mark.parametrize("make, match", [
    (lambda: PoseAccuracy(limit_mm=-1), r"PoseAccuracy\.limit_mm: expected a finite number > 0 \[mm\]"),
    (lambda: PoseRepeatability(limit_mm=0.05, share=1.0), r"PoseRepeatability\.share: expected a probability"),
    (lambda: PoseAccuracy(limit_mm=0.5, population="all"), r"PoseAccuracy\.population: expected one of fleet, robot"),
    (lambda: Conditions(load_pct=150), r"Conditions\.load_pct: expected a percentage of the rated value in \[0, 100\]"),
    (lambda: DistanceAccuracy(limit_mm=0.2, poses=(2, 2)), r"DistanceAccuracy\.poses: expected two different"),
    (lambda: PathAccuracy(limit_mm=0.2, points=1), r"PathAccuracy\.points: expected a whole number of path points"),
])
def test_bad_fields_refused(make, match):
    with pytest.raises(ArgumentError, match=match):
        make()


def test_positional_limit_refused():
    with pytest.raises(TypeError):
        PoseAccuracy(0.5)  # keyword-only: a bare number would be ambiguous with the share


def test_check_and_split():
    reqs = [PoseRepeatability(limit_mm=0.05), PositionRequirement(radius_mm=0.3), PoseAccuracy(limit_mm=0.5)]
    pos, ori, iso = split_requirements(reqs)
    assert pos.radius_mm == 0.3 and ori is None and [r.kind for r in iso] == ["pose_accuracy", "pose_repeatability"]
    with pytest.raises(ArgumentError, match=r"requirement: expected at most one requirement of each kind, got 2 "
                                            r"pose_accuracy requirements"):
        check_requirements([PoseAccuracy(limit_mm=0.5), PoseAccuracy(limit_mm=0.4)])
    with pytest.raises(ArgumentError, match=r"requirement: expected a requirement or a list of them"):
        check_requirements(["AP <= 0.5"])
