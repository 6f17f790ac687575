"""Edges of the handover and the drawing review: the coaxiality zone (ISO 1101), ISO 286-2's N holes up to 3 mm,
the design's z recorded in drawing.csv, rows the reader refuses (no datum, a characteristic that cannot bound the
parameter, a zone that disagrees with its grade, a bad direction) and wrong-type inputs. Known answers: ISO 286-2's
tabulated deviations, ISO 286-1's IT values and the closed forms of the zones."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm, rayleigh

import tolalloc
from tolalloc import TolallocError
from tolalloc.allocate.drawing import Callout, HandoverSettings, feature_map
from tolalloc.allocate.drawing_io import DRAWING_COLUMNS, export_frame, read_drawing
from tolalloc.allocate.fits import tolerance_class
from tolalloc.allocate.handover import Handover, handover
from tolalloc.allocate.standards import snap_length
from tolalloc.allocate.tolerance_analysis import halfwidths_from_drawing
from tolalloc.errormodel import build_error_model
from tolalloc.workflows.settings import Costs

#: Rayleigh quantile at the coverage of +-3 sigma over 3: the diameter factor f at z = 3 (closed form).
F3 = rayleigh.ppf(2 * norm.cdf(3.0) - 1) / 3.0


@pytest.fixture(scope="module")
def job():
    return tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False, progress=False)


@pytest.fixture(scope="module")
def drawing_csv(job, tmp_path_factory):
    path = tmp_path_factory.mktemp("edges") / "drawing.csv"
    export_frame(job.handover()).to_csv(path, index=False, float_format="%.10g")
    return path


@pytest.fixture(scope="module")
def clearance_model():
    return build_error_model(tolalloc.load_robot("tool_changer"), clearance=True)


def _clearance_t(model):
    by_kind = {"clearance_tilt": 1e-4, "clearance_radial": 0.02, "clearance_axial": 0.03}
    return np.array([by_kind.get(p.kind, 1e-4 if p.unit == "rad" else 0.05) for p in model.params])


def _handover(fm) -> Handover:
    """A handover of feature map ``fm`` without processes or costs (enough for the export)."""
    n, m = len(fm.callouts), len(fm.parts)
    return Handover(fm, ("",) * n, ("",) * n, (True,) * n, (0.0,) * (n + m), ("",) * (n + m), ())


def _row(**cells) -> dict:
    out = {c: "" for c in DRAWING_COLUMNS}
    out.update(cells)
    return out


def _read(rows, model, **kw):
    return read_drawing(pd.DataFrame(rows, columns=list(DRAWING_COLUMNS)), model, **kw)


PERP = dict(characteristic="perpendicularity", zone_mm="0.01", direction="x", datum="A", length_mm="100",
            parameters="e1x")


# --- 3: coaxiality ------------------------------------------------------------------------------------------------

def test_coaxiality_zone_is_a_cylinder_around_the_datum_axis(clearance_model):
    model, t = clearance_model, _clearance_t(clearance_model)
    fm = feature_map(model, t, z=3.0, strict=False)
    coax = [c for c in fm.callouts if c.characteristic == "coaxiality"]
    assert coax
    for c in coax:
        # the second seat's radial offset at the tolerance's coverage is L f t; the zone's diameter is twice that
        span = {"j1": 250.0, "j2": 300.0, "j3": 250.0, "j5": 120.0, "j6": 100.0}[c.feature.split()[0]]
        assert c.length_mm == span  # the seat span of tool_changer.toml
        assert c.zone_mm == pytest.approx(2 * span * F3 * 1e-4, rel=1e-12)
        assert c.diameter and c.factor == pytest.approx(2 * span * F3, rel=1e-12)
    # the read-back turns the Ø into the same t
    frame = export_frame(_handover(fm))
    back = halfwidths_from_drawing(model, read_drawing(frame, model, check_processes=False))
    for c in coax:
        for p in c.parameters:
            assert back[model.index(p)] == pytest.approx(1e-4, rel=1e-9)
    row = frame[frame.characteristic == "coaxiality"].iloc[0]
    hand = _read([_row(characteristic="coaxiality", zone_mm=str(row.zone_mm), diameter_zone="true", datum="B",
                       length_mm=str(row.length_mm), parameters=row.parameters)], model, z=3.0, check_processes=False)
    assert hand.callouts[0].zone_mm / hand.callouts[0].factor == pytest.approx(1e-4, rel=1e-9)


# --- 4: ISO 286-2, K M N P holes up to 3 mm -------------------------------------------------------------------------

@pytest.mark.parametrize("name, upper, lower", [
    ("N9", -4, -29), ("N10", -4, -44), ("N11", -4, -64), ("N8", -4, -18), ("N7", -4, -14), ("N6", -4, -10),
    ("K8", 0, -14), ("K9", 0, -25), ("M8", -2, -16), ("M7", -2, -12), ("P9", -6, -31), ("P7", -6, -16),
    ("P6", -6, -12)])
def test_holes_up_to_3_mm_follow_iso_286_2(name, upper, lower):
    tc = tolerance_class(name, 2.5)
    assert (tc.upper_um, tc.lower_um) == (upper, lower)


# --- 6: z recorded in drawing.csv -----------------------------------------------------------------------------------

def test_drawing_records_z_and_the_review_uses_it(job, drawing_csv, tmp_path):
    frame = pd.read_csv(drawing_csv, dtype=str, keep_default_na=False)
    assert list(frame.columns) == list(DRAWING_COLUMNS)
    assert set(frame.z.astype(float)) == {job.problem.costs.z} and set(frame.distribution) == {"normal"}
    z2 = frame.assign(z="2")
    path = tmp_path / "z2.csv"
    z2.to_csv(path, index=False)
    model = job.problem.model
    assert read_drawing(z2, model).z == 2.0
    with pytest.raises(TolallocError, match=r"review's z = 3 differs from the drawing's z = 2"):
        read_drawing(z2, model, z=3.0)
    with pytest.raises(TolallocError, match=r"z2.csv: the review's z = 3 differs from the drawing's z = 2"):
        tolalloc.review_drawing("tool_changer", path, region="nominal", costs=Costs(z=3))
    with pytest.raises(TolallocError, match=r"distribution uniform differs from the drawing's normal"):
        tolalloc.review_drawing("tool_changer", path, region="nominal", costs=Costs(uniform=True))
    rev = tolalloc.review_drawing("tool_changer", path, region="nominal")
    assert rev.inputs["z"] == 2.0 and rev.inputs["z_source"] == "the drawing file"
    assert "z = 2 (normal, the drawing file)" in rev.text()
    with pytest.raises(TolallocError, match=r"column z records different values \(2, 3\)"):
        read_drawing(z2.assign(z=["2"] + ["3"] * (len(z2) - 1)), model)


def test_a_drawing_without_z_keeps_working(job, drawing_csv, tmp_path):
    old = pd.read_csv(drawing_csv, dtype=str, keep_default_na=False).drop(columns=["z", "distribution"])
    path = tmp_path / "v1.csv"
    old.to_csv(path, index=False)
    assert read_drawing(old, job.problem.model).z == 3.0
    assert read_drawing(old, job.problem.model, z=2.0).z == 2.0
    rev = tolalloc.review_drawing("tool_changer", path, region="nominal")
    assert rev.inputs["z"] == 3.0 and rev.inputs["z_source"] == "default (the drawing file records none)"
    rev = tolalloc.review_drawing("tool_changer", path, region="nominal", costs=Costs(z=2))
    assert rev.inputs["z"] == 2.0 and rev.inputs["z_source"] == "given (the drawing file records none)"


# --- 7, 8, 9: rows the reader refuses -------------------------------------------------------------------------------

def test_rows_without_datum_are_refused(job):
    model = job.problem.model
    with pytest.raises(TolallocError, match=r"row 1 \(j1\): column datum is empty; a perpendicularity zone"):
        _read([_row(**{**PERP, "feature": "j1", "datum": ""})], model)
    with pytest.raises(TolallocError, match=r"row 1 \(l2\): column datum is empty; a position zone"):
        _read([_row(feature="l2", characteristic="position", zone_mm="0.1", length_mm="210", parameters="dl2")],
              model)


def test_a_characteristic_must_bound_its_parameters_kind(job, clearance_model):
    model = job.problem.model
    with pytest.raises(TolallocError, match=r"'perpendicularity' cannot bound dl1 \(kind link_length, unit mm\); "
                                            r"parameters of kind link_length are bounded by: size, position"):
        _read([_row(**{**PERP, "parameters": "dl1", "direction": ""})], model)
    with pytest.raises(TolallocError, match=r"'position' cannot bound e1x \(kind axis_deflection, unit rad\); .*"
                                            r"perpendicularity, parallelism, angularity, coaxiality"):
        _read([_row(characteristic="position", zone_mm="0.1", datum="A", length_mm="210", parameters="e1x")], model)
    with pytest.raises(TolallocError, match=r"'fit' cannot bound dl1 \(kind link_length"):
        _read([_row(characteristic="fit", grade="H7/g6", length_mm="50", parameters="dl1")], clearance_model)
    with pytest.raises(TolallocError, match=r"'size' cannot bound dth1 \(kind joint_drive, unit rad\); .*: "
                                            r"purchased_part"):
        _read([_row(characteristic="size", zone_mm="0.1", length_mm="100", parameters="dth1")], model)


def test_zone_and_grade_must_agree(job, clearance_model):
    model = job.problem.model
    # ISO 286-1 at 250-315 mm: IT7 = 52 um, IT8 = 81 um
    with pytest.raises(TolallocError, match=r"zone_mm 1e-06 mm disagrees with grade IT7, 0.052 mm at 315 mm .* "
                                            r"next grade's 0.081 mm"):
        _read([_row(characteristic="size", grade="IT7", zone_mm="0.000001", length_mm="315", parameters="dl1")],
              model)
    with pytest.raises(TolallocError, match=r"zone_mm 0.09 mm disagrees with grade IT7"):
        _read([_row(characteristic="size", grade="IT7", zone_mm="0.09", length_mm="315", parameters="dl1")], model)
    ok = _read([_row(characteristic="size", grade="IT7", zone_mm="0.06", length_mm="315", parameters="dl1")], model)
    assert ok.callouts[0].zone_mm == 0.06
    # H7/g6 at 50 mm: ES = +25, ei = -25 um (ISO 286-2): largest clearance 0.050 mm
    with pytest.raises(TolallocError, match=r"zone_mm 0.04 mm disagrees with the fit H7/g6 at Ø50 mm, whose largest "
                                            r"clearance is 0.05 mm"):
        _read([_row(characteristic="fit", grade="H7/g6", zone_mm="0.04", length_mm="50", parameters="cr1x cr1y")],
              clearance_model)


def test_direction_is_the_tilt_axis_of_the_parameter(job, drawing_csv):
    model = job.problem.model
    with pytest.raises(TolallocError, match=r"direction 'q' does not match e1x, a tilt about the base x axis; "
                                            r"expected direction 'x'"):
        _read([_row(**{**PERP, "direction": "q"})], model)
    with pytest.raises(TolallocError, match=r"direction 'y' does not match e1x"):
        _read([_row(**{**PERP, "direction": "y"})], model)
    with pytest.raises(TolallocError, match=r"direction 'x' given for a perpendicularity diameter zone"):
        _read([_row(**{**PERP, "diameter_zone": "true", "parameters": "e1x e1y"})], model)
    # 11: the exported direction is the base axis the parameter's tilt is about, as the docstring says
    for c in read_drawing(drawing_csv, model).callouts:
        if c.direction:
            twist = model.params[model.index(c.parameters[0])].twist[:3]
            assert c.direction == "xyz"[int(np.argmax(np.abs(twist)))]
    assert "tilt is about" in Callout.__doc__ and "width is measured along" not in Callout.__doc__


# --- 10: wrong-type inputs ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("call, message", [
    (lambda: tolerance_class("H7", "40"), r"H7 size_mm: expected a nominal size 0 < D <= 500 mm .*got '40' \(str\)"),
    (lambda: tolerance_class("H7", None), r"H7 size_mm: expected .*got None \(NoneType\)"),
    (lambda: HandoverSettings(default_span_mm="80"), r"default_span_mm: expected a length > 0 .*got '80' \(str\)"),
    (lambda: HandoverSettings(default_seat_diameter_mm=600), r"default_seat_diameter_mm: .*0 < D <= 500 mm\), got 600"),
    (lambda: HandoverSettings(fits=("H7/x6",)), r"fits: 'H7/x6': 'x6': the fundamental deviation 'x'"),
    (lambda: HandoverSettings(fits=("H7/k6",)), r"fits: 'H7/k6' is not a clearance fit \(transition"),
    (lambda: HandoverSettings(fits="H7/g6"), r"fits: expected a non-empty tuple of ISO 286 fits"),
    (lambda: snap_length(0.0, 40), r"snap_length: t_mm expected a half-width > 0 \[mm\].*got 0.0"),
    (lambda: snap_length(-0.01, 40), r"t_mm expected .*got -0.01"),
    (lambda: snap_length(float("nan"), 40), r"t_mm expected .*got nan"),
    (lambda: tolalloc.review_drawing("tool_changer", 123), r"drawing: expected the path .*got 123 \(int\)"),
])
def test_wrong_inputs_name_the_field(call, message):
    with pytest.raises(TolallocError, match=message):
        call()


@pytest.mark.parametrize("z", [0, -3, float("nan"), "3"])
def test_feature_map_refuses_a_bad_z(z):
    model = build_error_model(tolalloc.load_robot("tool_changer"))
    with pytest.raises(TolallocError, match=r"feature_map: z expected a number > 0"):
        feature_map(model, model.sigma * 3, z=z)


def test_feature_map_names_the_half_width_that_is_not_positive():
    model = build_error_model(tolalloc.load_robot("tool_changer"))
    t = model.sigma * 3
    t[model.index("e2z")], t[model.index("dl3")] = 0.0, np.nan
    with pytest.raises(TolallocError, match=r"the half-width of dl3 is nan \[mm\]; every half-width must be a number "
                                            r"> 0 \(2 are not\)"):
        feature_map(model, t, z=3.0)
    with pytest.raises(TolallocError, match=r"one per parameter of the model, got shape \(3,\)"):
        feature_map(model, t[:3], z=3.0)


# --- 12: the axial stack's nominal ------------------------------------------------------------------------------------

def test_axial_stack_states_its_nominal(clearance_model):
    fm = feature_map(clearance_model, _clearance_t(clearance_model), z=3.0, strict=False)
    stack = [c for c in fm.callouts if "axial stack" in c.feature]
    assert stack
    # 2 t = 0.06 mm at the seat span taken as nominal (tool_changer.toml), ISO 286-1: 180-250 mm IT7 = 46 um,
    # IT8 = 72 um; 250-315 mm IT7 = 52 um, IT8 = 81 um; 80-120 mm IT8 = 54 um, IT9 = 87 um
    grade = {250.0: "IT7", 300.0: "IT7", 120.0: "IT8", 100.0: "IT8"}
    assert sorted(c.length_mm for c in stack) == [100.0, 120.0, 250.0, 250.0, 300.0]
    for c in stack:
        assert c.grade == grade[c.length_mm] and c.zone_mm == pytest.approx(0.06)
        assert f"nominal length = seat span {c.length_mm:g} mm, assumed" in c.feature
    assert any("nominal length taken as the seat span" in u for u in fm.defaults_used)


def _needs_second_datum(model, c) -> bool:
    """Whether callout ``c``'s zone is fixed by its datum only up to a turn about the datum's direction (checked
    here by turning the axis): a per-direction zone whose normal -- the direction a small tilt moves the axis -- is
    not along the datum's direction (an axis, or a plane's normal); a diameter zone at an angle to it."""
    from tolalloc.robot.lie import exp_so3

    names = [jt.name for jt in model.robot.joints]
    p = model.params[model.index(c.parameters[0])]
    j = names.index(p.element)
    d = np.array([0.0, 0.0, 1.0]) if j == 0 else np.asarray(model.robot.joints[j - 1].axis, float)
    a = np.asarray(model.robot.joints[j].axis, float)
    if c.diameter:
        return abs(d @ a) < 1 - 1e-6
    w = np.asarray(p.twist[:3], float) / np.linalg.norm(p.twist[:3])
    move = (exp_so3(1e-6 * w) @ a - a) / 1e-6
    return abs(d @ move) / np.linalg.norm(move) < 1 - 1e-4


@pytest.mark.parametrize("robot, tilts, positions", [
    ("tool_changer", {"e1x", "e1y", "e2z", "e3y", "e3z", "e5y", "e6x"}, {"dl2", "dl5"}),
    ("ur10", {"e2z", "e3x", "e3z", "e4x", "e4z", "e5y", "e6z"}, {"dd1", "dd4", "dd5", "dd6"}),
])
def test_a_callout_its_datum_fixes_only_up_to_a_turn_gets_the_datum_system_it_needs(robot, tilts, positions,
                                                                                      request):
    """A zone of two parallel planes is fixed by a datum axis or plane only up to a turn about its direction; so is a
    diameter zone at an angle to it (ISO 1101, ISO 5459). The orientation zones given a second datum are exactly those
    that turn would move (checked by turning the axis), with the locating pin hole or keyway of the datum joint's
    output flange (the base: of its mounting face; the slide j4: its anti-rotation guide) second; the positions of a
    link along its datum axis get the datum joint's shoulder face second. Nothing is left as DATUM NEEDED; each
    letter is listed among the datum features. Without default letters (``default_datums=False``; the robot files
    name no locating feature or shoulder face) the same callouts keep one datum and are listed as DATUM NEEDED."""
    res = (request.getfixturevalue("job") if robot == "tool_changer" else
           tolalloc.allocate_tolerances(robot, region="nominal", verification=False, progress=False))
    model, h = res.problem.model, res.handover()
    names = [jt.name for jt in model.robot.joints]
    systems = {c.parameters[0]: c.datum.split("|") for c in h.callouts if "|" in c.datum}
    for c in h.callouts:
        if c.characteristic in ("perpendicularity", "parallelism", "angularity"):
            assert _needs_second_datum(model, c) == (c.parameters[0] in systems), c.parameters
    assert set(systems) == tilts | positions and not h.features.datum_gaps
    assert not any(a.startswith("DATUM NEEDED") for a in h.assumptions)
    features = {k: what for k, what, _ in h.features.datum_features}
    assert set(features) == {x for c in h.callouts for x in c.datum.split("|") if x}
    for name, (first, second) in systems.items():
        p = model.params[model.index(name)]
        if name in tilts:   # the datum, then what fixes the turn about it, both of the joint before
            j = names.index(p.element)
            before = "base mounting face" if j == 0 else names[j - 1]
            assert before in features[first] and before in features[second]
            assert "pin hole" in features[second] or "anti-rotation guide" in features[second]
        else:               # the datum axis, then the face across it, both of the joint the link starts at
            before = names[model.robot.link_sites[[lk.name for lk in model.robot.links].index(p.element)] - 1]
            assert features[first].startswith(before) and before in features[second]
            assert "shoulder face" in features[second] or "carriage across its stroke" in features[second]
    bare = handover(res.result, settings=HandoverSettings(default_datums=False))
    gaps = bare.features.datum_gaps
    assert {c.parameters[0] for c in bare.callouts if any(g.startswith(c.feature + " (") for g in gaps)} == (
        tilts | positions)
    assert sum(a.startswith("DATUM NEEDED") for a in bare.assumptions) == len(tilts) + len(positions)
    assert all("secondary datum" in g for g in gaps)


def test_a_diameter_zone_at_an_angle_to_its_datum_axis_gets_the_locating_feature(job):
    """With ``tilt_zone="diameter"`` j2's two tilts share one Ø zone; j2's axis is perpendicular to its datum, j1's
    axis B: the cylinder can turn about B, so the zone is to B and j1's flange's pin hole or keyway. j1's Ø zone is
    along A's normal, which needs nothing more."""
    model = job.problem.model
    fm = feature_map(model, model.sigma * 3, z=3.0, settings=HandoverSettings(tilt_zone="diameter"))
    by = {c.parameters: c for c in fm.callouts}
    features = {k: what for k, what, _ in fm.datum_features}
    assert by[("e1x", "e1y")].diameter and by[("e1x", "e1y")].datum == "A"
    first, second = by[("e2y", "e2z")].datum.split("|")
    assert by[("e2y", "e2z")].diameter and first == "B" and features[second] == (
        "the locating pin hole or keyway of j1's output flange")
    assert not fm.datum_gaps


def test_the_robot_files_letters_complete_the_datum_system():
    """``locating_datum`` and ``shoulder_datum`` of a bearing table (here a catalogue slot's) name the features; a
    letter given to two features, the base face's A, or one that is no letter, is refused naming the key."""
    import copy
    import tomllib

    from tolalloc.robot.io.load import _builtin_dir, robot_from_dict

    data = tomllib.loads((_builtin_dir() / "tool_changer.toml").read_text())
    data["components"]["joints"]["j1"]["bearing"].update(locating_datum="P", shoulder_datum="R")
    model = build_error_model(robot_from_dict(data))
    fm = feature_map(model, model.sigma * 3, z=3.0)
    by = {c.parameters[0]: c for c in fm.callouts}
    assert by["e2z"].datum == "B|P" and by["dl2"].datum == "B|R"  # both from j1's axis B
    listed = {k: (what, src) for k, what, src in fm.datum_features}
    assert listed["P"] == ("the locating pin hole or keyway of j1's output flange", "robot file")
    assert listed["R"] == ("the shoulder face of j1's axially locating bearing seat", "robot file")
    clash = copy.deepcopy(data)
    clash["components"]["joints"]["j3"]["bearing"]["locating_datum"] = "B"   # j1's axis; j3's pin is never used
    with pytest.raises(TolallocError, match=r"components.joints.j3.bearing.locating_datum = 'B': datum B already "
                                            r"names components.joints.j1.bearing.datum; give each datum feature its "
                                            r"own letter"):
        feature_map(build_error_model(robot_from_dict(clash)), model.sigma * 3, z=3.0)
    clash["components"]["joints"]["j3"]["bearing"]["locating_datum"] = "A"
    with pytest.raises(TolallocError, match=r"locating_datum = 'A': datum A already names the base mounting face "
                                            r"\(A is the base mounting face\)"):
        feature_map(build_error_model(robot_from_dict(clash)), model.sigma * 3, z=3.0)
    clash["components"]["joints"]["j3"]["bearing"]["locating_datum"] = "p1"
    with pytest.raises(TolallocError, match=r"j3.bearing.locating_datum: expected a datum letter \(one or two "
                                            r"capital letters, as B or AB\), got 'p1'"):
        robot_from_dict(clash)


def test_a_slot_gives_the_seat_diameter_else_its_bore(clearance_model):
    """The fit of a joint's bearing seats is drawn at the slot's ``seat_diameter_mm``, else at its bearing's bore
    (the inner ring's shaft seat: tool_changer.toml's bores 200, 200, 160, 100, 90 mm), not the 50 mm default."""
    fm = feature_map(clearance_model, _clearance_t(clearance_model), z=3.0, strict=False)
    fits = {c.feature.split()[0]: c for c in fm.callouts if c.characteristic == "fit"}
    assert {j: c.length_mm for j, c in fits.items()} == {"j1": 200.0, "j2": 200.0, "j3": 160.0, "j5": 100.0,
                                                          "j6": 90.0}
    assert all(c.span_source == "robot file (the bearing's bore)" for c in fits.values())
    assert any("seat diameter taken as the bearing's bore" in u for u in fm.defaults_used)


def test_the_review_of_a_drawing_names_the_callouts_its_verdict_leans_on(job, drawing_csv, tmp_path):
    """The review's P takes every row as bounding its parameter. The tool changer's own drawing carries the datum
    systems its rows need, and its review lists no gap; the same drawing with those rows cut back to their first
    datum lists each of them under its verdict, in its text and its summary, with the datum it needs (j4 is the
    slide: its carriage, not a bearing seat). A datum written with spaces (as handover.md prints it) is read; one
    that names a datum twice, or is no letter or datum system, is refused."""
    assert tolalloc.review_drawing("tool_changer", drawing=drawing_csv, region="nominal").summary()["datum_gaps"] == []
    frame = pd.read_csv(drawing_csv, dtype=str, keep_default_na=False)
    systems = frame.datum.str.contains("|", regex=False)
    assert set(frame.parameters[systems]) == {"e1x", "e1y", "e2z", "e3y", "e3z", "e5y", "e6x", "dl2", "dl5"}
    spaced = frame.copy()
    spaced.loc[systems, "datum"] = spaced.datum[systems].str.replace("|", " | ", regex=False)
    spaced.to_csv(tmp_path / "spaced.csv", index=False)
    assert tolalloc.review_drawing("tool_changer", drawing=tmp_path / "spaced.csv",
                                   region="nominal").summary()["datum_gaps"] == []
    frame.loc[systems, "datum"] = frame.datum[systems].str.split("|").str[0]
    frame.to_csv(tmp_path / "cut.csv", index=False)
    rv = tolalloc.review_drawing("tool_changer", drawing=tmp_path / "cut.csv", region="nominal")
    gaps = rv.summary()["datum_gaps"]
    assert len(gaps) == 9 and sum(line.startswith("DATUM NEEDED: ") for line in rv.text().splitlines()) == 9
    assert "the verdict holds only once each has the datum it needs" in rv.text()
    assert any("j5 bearing-seat axis, tilt about y" in g and "anti-rotation guide of j4's carriage" in g for g in gaps)
    assert any("j5 axis, 240 mm" in g and "a face of j4's carriage" in g for g in gaps)
    assert any("j2 bearing-seat axis, tilt about z" in g and "pin hole or keyway of j1's output flange" in g
               for g in gaps)
    assert any("j1 bearing-seat axis, tilt about x" in g and "pin hole of the base mounting face" in g for g in gaps)
    for bad, match in (("C/K", r"column datum 'C/K' is no datum letter or datum system"),
                       ("B|B", r"column datum 'B\|B' names a datum twice")):
        frame.loc[frame.parameters == "e2z", "datum"] = bad
        frame.to_csv(tmp_path / "bad.csv", index=False)
        with pytest.raises(TolallocError, match=match):
            tolalloc.review_drawing("tool_changer", drawing=tmp_path / "bad.csv", region="nominal")




def test_a_robot_file_that_names_every_datum_feature_needs_no_default_letter():
    """With the base face's letters (``[components.mount]``), the slide's (``[components.joints.j4.guide]``) and
    every bearing's locating and shoulder letters in the robot file, ``default_datums=False`` gives a complete drawing:
    every callout has the datum (system) it needs, each letter from the file, and the export takes it."""
    import tomllib

    from tolalloc.robot.io.load import _builtin_dir, robot_from_dict

    data = tomllib.loads((_builtin_dir() / "tool_changer.toml").read_text())
    comps = data["components"]
    comps["mount"].update(datum="W", locating_datum="X")
    comps["joints"]["j4"]["guide"] = {"datum": "E", "locating_datum": "U", "shoulder_datum": "V"}
    for j, (pin, face) in {"j1": ("P", "R"), "j2": ("S", "T"), "j3": ("H", "J"), "j5": ("K", "L")}.items():
        comps["joints"][j]["bearing"].update(locating_datum=pin, shoulder_datum=face)
    model = build_error_model(robot_from_dict(data))
    t = model.sigma * 3
    t[[model.index("e1x"), model.index("e3y")]] *= 0.5   # unequal tilts: a zone per direction
    fm = feature_map(model, t, z=3.0, settings=HandoverSettings(default_datums=False))
    by = {c.parameters[0]: c.datum for c in fm.callouts}
    assert (by["e1x"], by["dl1"], by["e2z"], by["dl2"], by["e3y"]) == ("W|X", "W", "B|P", "B|R", "C|S")
    assert (by["e5y"], by["dl5"], by["e6x"]) == ("E|U", "E|V", "F|K")
    assert not fm.datum_gaps and all(src == "robot file" for _, _, src in fm.datum_features)
    assert len(export_frame(_handover(fm))) == len(fm.callouts) + len(fm.parts) + len(fm.datum_features)
    bad = tomllib.loads((_builtin_dir() / "tool_changer.toml").read_text())
    bad["components"]["joints"]["j1"]["guide"] = {"datum": "Q"}
    with pytest.raises(TolallocError, match=r"j1.guide: j1 is a revolute joint; its drawing letters go in its bearing"):
        robot_from_dict(bad)
    bad = tomllib.loads((_builtin_dir() / "tool_changer.toml").read_text())
    bad["components"]["joints"]["j4"]["guide"] = {"datum": "E", "span_mm": 3}
    with pytest.raises(TolallocError, match=r"j4.guide: unknown key 'span_mm'; expected datum, locating_datum"):
        robot_from_dict(bad)


def test_the_drawing_says_what_its_letters_stand_for_and_the_review_checks_them(job, drawing_csv, tmp_path):
    """drawing.csv carries a ``datum_feature`` row per letter it uses (what the letter stands for). The review reads
    them back and checks each datum system against them: a system whose second letter stands for another feature
    than its zone needs (j2's tilt about B located by j1's shoulder face instead of its flange's pin hole or keyway)
    is listed as DATUM NEEDED, naming both. A drawing without such rows is read as before; a bad row is refused."""
    frame = pd.read_csv(drawing_csv, dtype=str, keep_default_na=False)
    rows = frame[frame.characteristic == "datum_feature"]
    h = job.handover()
    assert list(zip(rows.datum, rows.feature)) == [(k, what) for k, what, _ in h.features.datum_features]
    assert (rows.parameters == "").all() and rows.id.str.startswith("D").all()
    model = job.problem.model
    back = read_drawing(drawing_csv, model)
    assert [k for k, _, _ in back.datum_features] == [k for k, _, _ in h.features.datum_features]
    assert not back.datum_gaps
    letter = dict(zip(rows.feature, rows.datum))
    face = letter["the shoulder face of j1's axially locating bearing seat"]
    wrong = frame.copy()
    wrong.loc[wrong.parameters == "e2z", "datum"] = f"B|{face}"
    gaps = read_drawing(wrong, model).datum_gaps
    assert len(gaps) == 1 and gaps[0].startswith("j2 bearing-seat axis, tilt about z")
    assert (f"its datum {face} is the shoulder face of j1's axially locating bearing seat, where the zone needs the "
            "locating pin hole or keyway of j1's output flange") in gaps[0]
    assert not read_drawing(frame[frame.characteristic != "datum_feature"], model).datum_gaps
    common = frame.copy()   # a common datum (ISO 5459: the axis common to two features) is read
    common.loc[common.parameters == "e2z", "datum"] = "B-C|" + frame.datum[frame.parameters == "e2z"].iloc[0][2:]
    assert read_drawing(common, model).callouts
    bad = frame.copy()
    bad.loc[bad.index[bad.characteristic == "datum_feature"][0], "parameters"] = "e1x"
    with pytest.raises(TolallocError, match=r"a datum_feature row bounds no parameter"):
        read_drawing(bad, model)
    bad = frame.copy()
    bad.loc[bad.index[bad.characteristic == "datum_feature"][0], "datum"] = "B|C"
    with pytest.raises(TolallocError, match=r"a datum_feature row names one datum letter"):
        read_drawing(bad, model)
