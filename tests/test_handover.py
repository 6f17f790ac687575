"""The handover (drawing callouts, purchase list, assumptions), the drawing exchange CSV and the reverse direction
(tolerance analysis of a drawing): closed forms, the round trip to 1e-6, the process table, bad input."""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm, rayleigh

import tolalloc
from tolalloc import TolallocError
from tolalloc.allocate.drawing import HandoverSettings, diameter_factor, feature_map
from tolalloc.allocate.drawing_io import DRAWING_COLUMNS, export_frame, read_drawing
from tolalloc.allocate.handover import handover
from tolalloc.allocate.process_table import COST_LAW_SOURCES, choose_process, require_process
from tolalloc.allocate.tolerance_analysis import analyze_drawing, halfwidths_from_drawing
from tolalloc.cli import main
from tolalloc.errormodel import build_error_model
from tolalloc.report.handover import handover_html, handover_markdown, write_handover
from tolalloc.robot.io.load import _builtin_dir, robot_from_dict

ARCSEC = np.pi / 648000.0


@pytest.fixture(scope="module")
def job():
    return tolalloc.allocate_tolerances("tool_changer", region="nominal", verification=False, progress=False)


@pytest.fixture(scope="module")
def drawing_csv(job, tmp_path_factory):
    path = tmp_path_factory.mktemp("drawing") / "drawing.csv"
    export_frame(job.handover()).to_csv(path, index=False, float_format="%.10g")
    return path


def _robot_data():
    return tomllib.loads((_builtin_dir() / "tool_changer.toml").read_text())


def test_diameter_factor_is_the_rayleigh_quantile_at_the_tolerance_coverage():
    pc = 2 * norm.cdf(3.0) - 1
    assert diameter_factor(3.0) == pytest.approx(rayleigh.ppf(pc) / 3.0, rel=1e-12)
    assert diameter_factor(3.0) == pytest.approx(1.14645, abs=1e-5)
    assert diameter_factor(np.sqrt(3), "uniform") == pytest.approx(np.sqrt(2))
    # seeded Monte Carlo: two normal tilts of sigma = t / 3 fall inside the diameter zone as often as one tilt in +-t
    x = np.random.default_rng(1).normal(size=(200_000, 2)) / 3.0
    inside = np.mean(np.hypot(x[:, 0], x[:, 1]) <= diameter_factor(3.0))
    assert inside == pytest.approx(pc, abs=5 * np.sqrt(pc * (1 - pc) / len(x)))


def test_every_row_has_a_callout_or_a_part_and_a_process(job):
    h = job.handover()
    assert h.rows_without_handover(job.problem.model.names) == []
    frame = job.to_frame()
    drives = frame["kind"] == "joint_drive"
    assert (frame.loc[drives, "process"] == "purchased part").all()
    assert (frame.loc[~drives, "process"] != "").all()
    assert frame["callout"].str.len().gt(0).all() and frame["cost_source"].str.contains("assumed").all()
    assert all(h.holds)
    draw = h.drawing_frame()
    # the tool_changer's geometry: j1 axis perpendicular to the base face A, j3 parallel to j2 (datum C)
    j1 = draw[draw.parameters.str.startswith("e1")]
    # (two zones of different widths: each is fixed only once the base's locating pin hole fixes the turn about A's
    # normal, the second datum of its system; j3's to C once j2's flange's pin hole or keyway fixes the turn about C)
    assert set(j1.characteristic) == {"perpendicularity"} and {d.split("|")[0] for d in j1.datum} == {"A"}
    j3 = draw[draw.parameters.str.startswith("e3")]
    assert set(j3.characteristic) == {"parallelism"} and {d.split("|")[0] for d in j3.datum} == {"C"}
    assert all(len(d.split("|")) == 2 for d in [*j1.datum, *j3.datum])
    # a step from the base face A to j1's seat shoulder: a position at the exact distance, not a size (ISO 14405-2)
    assert draw.set_index("parameters").loc["dl1", "characteristic"] == "position"
    assert draw.set_index("parameters").loc["dl1", "datum"] == "A"
    assert draw.set_index("parameters").loc["dl3", "characteristic"] == "position"
    # e6x and e6y sit at the same limit, but their datum is j5's axis F: a zone to a datum axis bounds one direction
    # of tilt (two planes perpendicular to it), so each tilt gets its own zone, not one diameter zone
    e6 = draw[draw.parameters.str.startswith("e6")].set_index("parameters")
    assert sorted(e6.index) == ["e6x", "e6y"] and not e6.diameter_zone.astype(str).eq("True").any()
    assert e6.zone_mm.astype(float).to_numpy() == pytest.approx(100.0 * np.deg2rad(0.5), rel=1e-3)


def test_zones_follow_the_design(job):
    h, t = job.handover(), dict(zip(job.problem.model.names, job.design.t))
    model = job.problem.model
    # the tool changer's bearings are catalogue slots: their seat spans (tool_changer.toml) are the zones' lengths
    spans = {"j1": 250.0, "j2": 300.0, "j3": 250.0, "j5": 120.0, "j6": 100.0}
    for c in h.callouts:
        if c.characteristic in ("size", "position"):
            assert c.zone_mm == pytest.approx(2 * t[c.parameters[0]], rel=1e-12)
        elif not c.diameter:
            span = spans[model.params[model.index(c.parameters[0])].element]
            assert c.length_mm == span and c.span_source == "robot file"
            assert c.zone_mm == pytest.approx(span * t[c.parameters[0]], rel=1e-12)  # t_zone = L alpha
    assert {c.grade for c in h.callouts if c.characteristic in ("size", "position")} <= set(job.result.grade)


def test_cost_source_and_assumptions_are_stated(job):
    h = job.handover()
    assert len(h.cost_source) == len(h.callouts) + len(h.parts)
    assert all("assumed" in s and "Chase & Greenwood (1988)" in s for s in h.cost_source)
    text = " ".join(h.assumptions)
    for word in ("Rigid links", "temperature", "normal (Gaussian)", "z = 3", "ASSUMED", "Rayleigh",
                 "Datum features: A the base mounting face (assumed letter); B j1 bearing-seat axis (robot file)"):
        assert word in text
    md = handover_markdown(h, "t")
    assert "## Assumptions behind the verdict" in md and "## Purchase list" in md and "⊥" in md
    html = handover_html(h)
    assert html["drawing"]["id"] == "drawing-table" and len(html["drawing"]["rows"]) == len(h.callouts)
    assert set(COST_LAW_SOURCES) == {"reciprocal", "reciprocal_power", "exponential", "michael_siddall"}


def test_round_trip_reproduces_the_allocated_probability(job, drawing_csv, tmp_path):
    pr = job.problem
    fmap = read_drawing(drawing_csv, pr.model, z=pr.costs.z)
    a = analyze_drawing(pr.model, fmap, pr.q, radius_mm=pr.radius_mm, prob=pr.prob)
    np.testing.assert_allclose(a.t, job.design.t, rtol=1e-8)
    np.testing.assert_allclose(a.p, job.design.p_linear["position"], atol=1e-6)
    assert a.feature_frame().variance_share_pct.sum() == pytest.approx(100.0)
    names = write_handover(job.handover(), tmp_path, "t")
    assert names == ["drawing.csv", "purchase_list.csv", "handover.md"]
    assert list(pd.read_csv(tmp_path / "drawing.csv").columns) == list(DRAWING_COLUMNS)


def test_review_command(capsys, drawing_csv, tmp_path):
    code = main(["review", "tool_changer", "--drawing", str(drawing_csv), "--region", "nominal", "--out",
                 str(tmp_path / "r")])
    out = capsys.readouterr().out
    assert code == 0 and "meets it at 1 of 1 pose(s)" in out and "purchased_part" in out
    written = sorted(p.name for p in (tmp_path / "r").iterdir() if p.name[0] != ".")
    assert written == ["review.json", "review_features.csv", "review_poses.csv"]
    code = main(["review", "tool_changer", "--drawing", str(tmp_path / "none.csv")])
    assert code == 2 and "drawing file" in capsys.readouterr().err


def test_components_give_spans_datums_fits_and_parts():
    data = _robot_data()
    data["components"] = {"joints": {
        "j1": {"bearing": {"span_mm": 80, "datum": "K", "seat_diameter_mm": 62},
               "reducer": {"type": "strain_wave", "ratio": 101, "transmission_accuracy_arcmin": 1.0,
                           "source": "Harmonic Drive CSG-32-100 catalogue"},
               "encoder": {"accuracy_arcsec": 20, "source": "assumed"}},
        "j2": {"bearing": {"span_mm": 120}}}}
    robot = robot_from_dict(data)
    assert robot.components.joint("j1").bearing.seat_diameter_mm == 62
    model = build_error_model(robot, clearance=True)
    t = np.where([p.kind == "clearance_radial" for p in model.params], 0.03, model.sigma * 3)
    fm = feature_map(model, t, z=3.0)
    by = {c.parameters: c for c in fm.callouts}
    assert by[("e1x", "e1y")].length_mm == 80 and by[("e1x", "e1y")].span_source == "robot file"
    # to datum axis K; e2z turns about K's own direction: its zone is to K and the pin or key of j1's output
    assert by[("e2y",)].datum == "K" and by[("e2z",)].datum.split("|")[0] == "K"
    assert all(by[(n,)].length_mm == 120 for n in ("e2y", "e2z"))
    fit = by[("cr1x", "cr1y")]
    assert fit.length_mm == 62 and fit.characteristic == "fit"
    assert fit.zone_mm / 2 <= np.sqrt(2) * 0.03 + 1e-12  # largest radial play within the design's bound
    part = fm.parts[0]
    assert part.source == "Harmonic Drive CSG-32-100 catalogue; assumed"
    assert part.part_halfwidth == pytest.approx((60 + 20) / 2 * ARCSEC)
    assert part.meets == ("yes" if part.part_halfwidth <= part.required else "no")
    # a fit gives back sigma at or below the design's: the drawing is never looser
    tb = halfwidths_from_drawing(model, fm)
    k = model.index("cr1x")
    assert tb[k] == pytest.approx(fit.zone_mm / (2 * np.sqrt(2))) and tb[k] <= 0.03


def test_tilt_zone_modes():
    model = build_error_model(tolalloc.load_robot("tool_changer"))
    t = model.sigma * 3
    t[model.index("e1x")] *= 0.5
    zones = {m: [c for c in feature_map(model, t, z=3.0, settings=HandoverSettings(tilt_zone=m)).callouts
                 if c.parameters[0].startswith("e1")] for m in ("auto", "diameter", "directions")}
    assert len(zones["auto"]) == 2 and len(zones["directions"]) == 2 and len(zones["diameter"]) == 1
    # j1's seat span: 250 mm (tool_changer.toml)
    assert zones["diameter"][0].zone_mm == pytest.approx(250 * diameter_factor(3.0) * t[model.index("e1x")])


def test_process_table():
    assert choose_process(grade=6).process.name == "reaming"
    assert choose_process(grade=9).process.name == "turning"
    assert choose_process(grade=4).process.name == "honing"
    ch = choose_process(grade=3)
    assert not ch.holds and ch.label == "none holds it (finest: honing)"
    assert choose_process(zone_mm=0.004, length_mm=100).process.name == "honing"
    with pytest.raises(TolallocError, match=r"j2 seat: a zone of 0.0005 mm over 100 mm is finer than any process of "
                                            r"the table holds; the finest is lapping \(0.002 mm, relative cost 5\)"):
        require_process("j2 seat", zone_mm=0.0005, length_mm=100)


def _edit(path, row: int, **cells) -> pd.DataFrame:
    frame = pd.read_csv(path, dtype=str, keep_default_na=False)
    for k, v in cells.items():
        frame.loc[row, k] = v
    return frame


def test_bad_drawings_are_refused_naming_the_feature(job, drawing_csv):
    model = job.problem.model
    frame = pd.read_csv(drawing_csv, dtype=str, keep_default_na=False)
    i = frame.index[frame.parameters == "e1x"][0]
    with pytest.raises(TolallocError, match=r"row \d+ \(j1 bearing-seat axis, tilt about x\): length_mm expected a "
                                            r"number > 0, got '0'"):
        read_drawing(_edit(drawing_csv, i, length_mm="0"), model)
    with pytest.raises(TolallocError, match=r"j1 bearing-seat axis, tilt about x.*finer than any process.*lapping"):
        read_drawing(_edit(drawing_csv, i, zone_mm="0.0001"), model)
    fit = _edit(drawing_csv, i, characteristic="fit", grade="H7/g6", length_mm="50")
    with pytest.raises(TolallocError, match=r"tilt about x\): characteristic 'fit' cannot bound e1x \(kind "
                                            r"axis_deflection, unit rad\); .* perpendicularity, parallelism"):
        read_drawing(fit, model)
    with pytest.raises(TolallocError, match=r"no callout or part bounds e1x"):
        halfwidths_from_drawing(model, read_drawing(frame.drop(index=i), model))
    with pytest.raises(TolallocError, match=r"parameters zz9 not in the error model"):
        read_drawing(_edit(drawing_csv, i, parameters="zz9"), model)


def test_missing_span_and_datum():
    bare = copy.deepcopy(_robot_data())
    del bare["components"]
    model = build_error_model(robot_from_dict(bare))
    t = model.sigma * 3
    with pytest.raises(TolallocError, match=r"joint j1: no seat span \(span_mm\).*and no default given"):
        feature_map(model, t, z=3.0, settings=HandoverSettings(default_span_mm=None))
    with pytest.raises(TolallocError, match=r"default_span_mm: expected a length > 0"):
        HandoverSettings(default_span_mm=0)
    data = copy.deepcopy(_robot_data())
    data["components"] = {"joints": {"j1": {"bearing": {"span_mm": 0}}}}
    with pytest.raises(TolallocError, match=r"bearing.span_mm: expected positive values, got 0"):
        robot_from_dict(data)


def test_export_refuses_a_zone_without_datum(job):
    h = handover(job.result, settings=HandoverSettings(default_datums=False))
    # the robot file names the seat axes of j1-j3, j5, j6, not the base face (l1's position is located from it)
    with pytest.raises(TolallocError, match=r"export: shoulder face of j1's axially locating bearing seat, 315 mm from "
                                            r"the datum \(l1\) \(position\) has no datum"):
        export_frame(h)


def test_michael_siddall_law_is_convex_and_matches_its_expressions():
    import cvxpy as cp

    from tolalloc.allocate.costs import CostModel

    cm = CostModel("michael_siddall", 1.0, 2.0, 0.1, 0.01, 1.0, k=1.5)
    tau = np.array([0.3, 1.0, 2.0])
    np.testing.assert_allclose(cm.cost(0.1 * tau), 1.0 + 2.0 * tau**-1.5 * np.exp(-tau))
    u = cp.Variable(3, pos=True)
    expr = cm.cost_u(u, "cvxpy")
    assert expr.is_convex()
    u.value = tau**2
    np.testing.assert_allclose(expr.value, cm.cost(0.1 * tau), rtol=1e-10)
