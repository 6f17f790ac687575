"""report.html of the allocation, the calibration-aware allocation and the diagnosis.

The file is parsed (stdlib html.parser): every table with its columns and one row per parameter / pose, the cells
equal to the result's own numbers, every figure a data: URI, the verdict, inputs, versions and the command; nothing
loaded from outside (no http in any src / href / url(), no script, no stylesheet link). The allocation's command is
run again and must give the same tolerances. Where Chromium is installed, the report is rendered to a PNG.
"""

from __future__ import annotations

import ast
import base64
import inspect
import json
import shlex
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.report.html import pretty
from tolalloc.workflows import allocate_tolerances, diagnose_measurements

VOID = {"img", "meta", "br", "link", "input", "hr", "col", "source", "wbr"}
CHROMIUM = Path("/usr/bin/chromium")


class Page(HTMLParser):
    """What the tests look at: tables (id -> column keys and rows of cell texts), images, every URL-bearing
    attribute, the style sheet, the text under each element id, and the tags used."""

    def __init__(self, text: str):
        super().__init__(convert_charrefs=True)
        self.tables, self.images, self.urls, self.tags, self.texts = {}, [], [], set(), {}
        self.style = ""
        self.pairs = {}  # <dl id=...>: [(dt text, dd text)]
        self._stack, self._table, self._cell, self._in_style, self._dl = [], None, None, False, None
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.add(tag)
        self.urls += [(tag, k, v or "") for k, v in attrs if k in ("src", "href", "action", "data", "poster", "srcset")]
        if "style" in a:
            self.style += a["style"]
        if tag == "img":
            self.images.append(a)
        if tag == "style":
            self._in_style = True
        if tag == "dl" and a.get("id"):
            self._dl = self.pairs.setdefault(a["id"], [])
        elif tag == "dt" and self._dl is not None:
            self._dl.append(["", ""])
        if tag == "table":
            self._table = self.tables.setdefault(a.get("id"), {"keys": [], "labels": [], "rows": []})
        elif tag == "tr" and self._table is not None:
            self._row = []
        elif tag in ("th", "td") and self._table is not None:
            self._cell = ""
            if tag == "th":
                self._table["keys"].append(a.get("data-key"))
        if tag not in VOID:
            self._stack.append((tag, a.get("id")))

    def handle_endtag(self, tag):
        if tag == "style":
            self._in_style = False
        if tag == "th" and self._table is not None:
            self._table["labels"].append(self._cell.strip())
            self._cell = None
        elif tag == "td" and self._table is not None:
            self._row.append(self._cell.strip())
            self._cell = None
        elif tag == "tr" and self._table is not None and self._row:
            self._table["rows"].append(self._row)
            self._row = []
        elif tag == "table":
            self._table = None
        elif tag == "dl":
            self._dl = None
        while self._stack:
            t, _ = self._stack.pop()
            if t == tag:
                break

    def handle_data(self, data):
        inside = [t for t, _ in self._stack]
        if self._dl is not None and self._dl and inside and inside[-1] in ("dt", "dd"):
            self._dl[-1][inside[-1] == "dd"] += data
        if self._in_style:
            self.style += data
        if self._cell is not None:
            self._cell += data
        for _, ident in self._stack:
            if ident:
                self.texts[ident] = self.texts.get(ident, "") + data

    def text(self, ident: str) -> str:
        return " ".join(self.texts.get(ident, "").split())

    def kv(self, ident: str) -> dict:
        return {k.strip(): " ".join(v.split()) for k, v in self.pairs[ident]}

    def column(self, table: str, key: str) -> list[str]:
        t = self.tables[table]
        k = t["keys"].index(key)
        return [row[k] for row in t["rows"]]


# ---------------------------------------------------------------------------------------------- fixtures
@pytest.fixture(scope="module")
def allocation(tmp_path_factory):
    job = allocate_tolerances("tool_changer", region="nominal", verification=tolalloc.Verification(n_mc=2000, seed=3))
    out = tmp_path_factory.mktemp("alloc") / "res"
    names = [p.name for p in job.save(out, report=True)]
    return job, out, names, Page((out / "report.html").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    from tolalloc.calibration import make_plan, write_plan

    tc = tolalloc.load_robot("tool_changer")
    rng = np.random.default_rng(0)
    folder = tmp_path_factory.mktemp("calib")
    plan = folder / "plan.csv"
    write_plan(make_plan(tc, tc.lower + (tc.upper - tc.lower) * rng.random((12, 6))), tc, plan)
    job = allocate_tolerances("tool_changer", calibration=str(plan), region=tolalloc.Region(coverage_n=5000), n_mc=200)
    names = [p.name for p in job.save(folder / "res", report=True)]
    return job, folder / "res", names, Page((folder / "res" / "report.html").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def diagnosis(tmp_path_factory):
    from tolalloc.diagnose import generate
    from tolalloc.diagnose.synth import split_frame

    tc = tolalloc.load_robot("tool_changer")
    folder = tmp_path_factory.mktemp("diag")
    case = generate(tc, "backlash", 160, np.random.default_rng(5))
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(0))
    tr.to_csv(folder / "train.csv", index=False)
    te.to_csv(folder / "test.csv", index=False)
    job = diagnose_measurements(tc, folder / "train.csv", folder / "test.csv", folds=3, gap_split=True, seed=1)
    job.save(folder / "rep", report=True)
    return job, folder / "rep", Page((folder / "rep" / "report.html").read_text(encoding="utf-8"))


# ---------------------------------------------------------------------------------------------- one file
@pytest.mark.parametrize("which", ["allocation", "calibrated", "diagnosis"])
def test_one_file_nothing_fetched(which, request):
    fixture = request.getfixturevalue(which)
    page = fixture[-1]
    assert "script" not in page.tags and "link" not in page.tags and "iframe" not in page.tags
    assert page.urls, "expected the contents links and the figures"
    for tag, attr, url in page.urls:  # a data: URI's base64 payload is checked decoded, below
        assert url.startswith(("#", "data:image/")), (tag, attr, url[:80])
        assert "http" not in (url.split(",", 1)[0] if url.startswith("data:") else url).lower(), (tag, attr, url[:80])
    assert "@import" not in page.style and "@font-face" not in page.style
    assert "url(" not in page.style  # no background images or fonts to fetch
    assert page.images and all(img["src"].startswith(("data:image/svg+xml;base64,", "data:image/png;base64,"))
                               for img in page.images)
    for img in page.images:
        head, payload = img["src"].split(",", 1)
        data = base64.b64decode(payload, validate=True)
        if "svg" in head:
            svg = data.decode("utf-8")
            assert svg.lstrip().startswith("<svg") and svg.rstrip().endswith("</svg>")
            assert 'href="http' not in svg and "url(http" not in svg  # embedded rasters are data: too
        else:
            assert data[:8] == b"\x89PNG\r\n\x1a\n"
        assert img.get("alt")
    for section in ("summary", "figures", "reproduce"):  # the contents list points at sections that exist
        assert ("a", "href", f"#{section}") in page.urls and page.text(section)


# ---------------------------------------------------------------------------------------------- allocation
def test_allocation_files_and_verdict(allocation):
    job, out, names, page = allocation
    assert "report.html" in names and (out / "report.html").is_file()
    ver = job.verification
    assert page.text("requirement") == pretty(job.requirement())
    verdict = page.text("verdict")
    assert verdict.startswith(ver.verdict.upper()) and " ".join(pretty(ver.message()).split()) in verdict
    if job.correction is not None:
        assert " ".join(pretty(job.correction.message()).split()) in verdict
    assert " ".join(pretty(ver.message()).split()) in page.text("verification-message")
    assert {"fig-budget", "fig-poses", "fig-cloud"} <= set(page.texts) and len(page.images) == 3


def test_allocation_tolerance_table(allocation):
    job, _, _, page = allocation
    frame = job.to_frame()
    t = page.tables["tolerance-table"]
    assert {"parameter", "kind", "role", "nominal_mm", "tol_mm", "tol_deg", "grade", "sigma_mm", "sigma_deg", "cost",
            "variance_share_pct", "at_limit", "tol_continuous_mm", "tol_continuous_deg"} <= set(t["keys"])
    assert {"tolerance ± [mm]", "tolerance ± [deg]", "σ [mm]", "σ [deg]", "nominal [mm]"} <= set(t["labels"])
    assert t["keys"].index("tol_mm") < t["keys"].index("tol_continuous_mm")  # the design to build leads
    assert len(t["rows"]) == len(frame) == len(job.problem.model.params)
    assert page.column("tolerance-table", "parameter") == list(frame["parameter"])
    for key in ("tol_mm", "tol_deg", "tol_continuous_mm"):
        assert page.column("tolerance-table", key) == ["" if np.isnan(x) else f"±{x:.4g}" for x in frame[key]]
    assert page.column("tolerance-table", "grade") == list(frame["grade"])
    assert any(g.startswith("IT") for g in frame["grade"])
    assert page.column("tolerance-table", "variance_share_pct") == [f"{x:.1f}" for x in frame["variance_share_pct"]]
    # the table, the design note and the costs' bold row are the design to build: the standard one
    assert job.standard and page.text("design-note").startswith("Design: standard grades (discrete-exact), the design "
                                                                "to build; verified by nonlinear Monte Carlo")
    assert f"at the worst pose (pose {job.worst_pose + 1})" in page.text("tolerances")


def test_allocation_report_names_one_design_one_worst_pose(allocation):
    from tolalloc.report.html_allocation import allocation_context

    job, _, _, page = allocation
    ctx = allocation_context(job)
    rows = ctx["costs_table"]["rows"]
    bold = [r["cells"][0]["text"] for r in rows if r["cls"] == "chosen"]
    assert bold == ["standard grades"]
    s = job.summary()
    cards = {c["label"]: c for c in ctx["cards"]}
    assert cards["lowest linear P"]["note"].startswith(f"pose {s['worst_pose']},")
    assert s["worst_pose"] == job.worst_pose + 1 == int(np.argmin(job.design.p_linear["position"])) + 1
    assert f"(pose {job.worst_pose + 1})" in ctx["figures"][0]["caption"]
    # the pose table's legend names the interval of the estimator that ran: the nominal pose sits on p, so its paired
    # interval straddled p and the second look was importance sampling (Tango's interval, not Wilson's)
    assert set(job.verification.estimator) == {"importance"} and job.verification.second_looks == 1
    assert "importance sampling: Tango's score interval of the weighted discordant counts" in ctx["pose_table"]["note"]
    assert "Wilson" not in ctx["pose_table"]["note"]


def test_allocation_costs_and_poses(allocation):
    job, _, _, page = allocation
    s = job.summary()
    costs = page.column("costs", "cost")
    assert f"{s['costs']['certified']:.4f}" in costs and f"{s['costs']['exact']:.4f}" in costs
    assert f"{s['costs']['standard']:.4f}" in costs
    ver = job.verification.to_frame()
    t = page.tables["pose-table"]
    assert {"pose", "p_linear", "p_mc", "ci", "n", "verdict"} <= set(t["keys"]) and "q1" in t["keys"]
    assert len(t["rows"]) == len(ver) == job.problem.n_poses
    assert page.column("pose-table", "p_mc") == [f"{x:.4f}" for x in ver["p_mc"]]
    assert page.column("pose-table", "ci") == [f"[{lo:.4f}, {hi:.4f}]" for lo, hi in zip(ver["ci_low"], ver["ci_high"])]
    assert page.column("pose-table", "verdict") == list(ver["verdict"])
    assert page.column("pose-table", "n") == [str(int(n)) for n in ver["n"]]
    q = job.robot.q_to_interface(job.problem.q)
    assert page.column("pose-table", "q2") == [f"{x:.2f}" for x in q[:, 1]]


def test_allocation_inputs_versions(allocation):
    import casadi
    import cvxpy
    import scipy

    job, _, _, page = allocation
    inputs = page.kv("inputs")
    assert {k: inputs[k] for k in ("robot", "seed", "n_mc", "costs", "region", "radius_mm", "prob")} == {
        "robot": "tool_changer", "seed": "3", "n_mc": "2000", "costs": "defaults", "region": "nominal",
        "radius_mm": "0.25", "prob": "0.95"}
    assert inputs["sigma_set"] == job.problem.model.sigma_set and inputs["link_mode"] == "consistent"
    versions = page.kv("versions")
    for name, mod in (("numpy", np), ("scipy", scipy), ("cvxpy", cvxpy), ("casadi", casadi), ("pandas", pd)):
        assert versions[name] == mod.__version__
    assert versions["tolalloc"] == tolalloc.__version__


def test_allocation_command_reproduces_the_tables(allocation, tmp_path):
    from tolalloc.cli import main

    job, out, _, page = allocation
    cli = page.text("command-cli")
    args = shlex.split(cli)
    assert args[:3] == ["tolalloc", "allocate", "tool_changer"]
    assert {"--n-mc", "--seed", "--poses"} <= set(args) and args[args.index("--seed") + 1] == "3"
    args[args.index("DIR")] = str(tmp_path / "again")
    assert main(args[1:]) == 0
    assert (tmp_path / "again" / "report.html").is_file()
    again = pd.read_csv(tmp_path / "again" / "tolerances.csv")
    pd.testing.assert_frame_equal(again, pd.read_csv(out / "tolerances.csv"))
    s = json.loads((tmp_path / "again" / "summary.json").read_text())
    assert s["verification"]["verdicts"] == job.verification.verdicts.tolist()
    # the Python call names only keyword arguments of allocate_tolerances
    call = next(n for n in ast.walk(ast.parse(page.texts["command-python"])) if isinstance(n, ast.Call))
    params = inspect.signature(allocate_tolerances).parameters
    assert call.keywords and all(k.arg in params for k in call.keywords)


@pytest.mark.parametrize("kw, word", [(dict(verification=False), "NOT VERIFIED"),
                                      (dict(n_mc=2000, radius_mm=0.005), "INFEASIBLE")])
def test_allocation_without_verification_or_design(kw, word, tmp_path):
    """No Monte Carlo: the pose table holds the linear P only; no design: the verdict says so, nothing verified."""
    job = allocate_tolerances("tool_changer", region="nominal", **kw)
    job.save(tmp_path / "r", report=True)
    page = Page((tmp_path / "r" / "report.html").read_text(encoding="utf-8"))
    assert page.text("verdict").startswith(word)
    assert job.verification is None and "p_mc" not in page.tables["pose-table"]["keys"]
    s = job.summary()
    assert page.column("pose-table", "p_linear") == [f"{row['p_linear']:.4f}" for row in s["poses"]]
    assert page.column("tolerance-table", "parameter") == list(job.to_frame()["parameter"])
    assert len(page.images) == 1  # the error budget; no verification figures
    assert ("--no-verify" in page.text("command-cli")) == (kw.get("verification") is False)
    assert "verified" not in page.text("design-note").replace("NOT verified", "")  # nothing verified, nothing said so
    if word == "NOT VERIFIED":
        assert job.ok and not job.verified and not s["verified"] and "NOT verified by Monte Carlo" in s["tables_design"]


# ---------------------------------------------------------------------------------------------- calibrated
def test_calibrated_report(calibrated):
    job, out, names, page = calibrated
    assert "report.html" in names
    frame = job.to_frame()
    t = page.tables["tolerance-table"]
    assert {"parameter", "unit", "tol_mm", "tol_deg", "tol_no_calibration_mm", "sigma_post_calibration_deg", "status",
            "cost"} <= set(t["keys"])
    assert page.column("tolerance-table", "parameter") == list(frame["parameter"])
    assert page.column("tolerance-table", "status") == list(frame["status"])
    for key in ("tol_mm", "tol_deg"):
        assert page.column("tolerance-table", key) == ["" if np.isnan(x) else f"±{x:.4g}" for x in frame[key]]
    e2e = job.end_to_end
    chk = e2e.check
    assert len(page.tables["pose-table"]["rows"]) == len(chk.p_mc) >= 1  # the design's worst poses
    assert page.column("pose-table", "ci") == [f"[{lo:.4f}, {hi:.4f}]" for lo, hi in zip(chk.ci_low, chk.ci_high)]
    assert page.text("verdict").startswith(e2e.verdict.upper())
    assert " ".join(pretty(e2e.message()).split()) in page.text("verification-message")
    assert len(page.images) == 2
    assert f"{job.summary()['cost']:.4f}" in page.text("summary")
    args = shlex.split(page.text("command-cli"))
    assert "--calibration" in args and args[args.index("--region") + 1] == job.label
    # the plan cannot identify some parameters: the page does not call them all "must be held"
    unid = page.text("unidentifiable")
    assert "(must be held in manufacturing)" not in unid and ", ".join(job.summary()["unidentifiable"]) in unid


def test_calibrated_command_gives_back_the_call(calibrated, monkeypatch, tmp_path):
    """The box region's coverage sample size (coverage_n) is part of the command, with every other option."""
    from test_reproduce_command import assert_reproduced

    job = calibrated[0]
    assert job.region is not None and job.inputs["coverage_n"] == 5000
    assert_reproduced(job, dict(robot="tool_changer", calibration=job.plan_source, n_mc=200,
                                region=tolalloc.Region(coverage_n=5000)), monkeypatch, tmp_path)


# ---------------------------------------------------------------------------------------------- diagnosis
def test_diagnosis_report(diagnosis):
    from tolalloc.report.diagnosis import worst_test_poses

    job, out, page = diagnosis
    d = job.diagnosis
    assert (out / "report.md").is_file() and (out / "report.html").is_file()
    assert page.text("verdict").startswith(f"EFFECT: {d.effect}") and d.effect == "backlash"
    for table, which in (("test-table", "test"), ("cv-table", "cv")):
        ba = d.before_after(which)
        assert page.column(table, "model") == ["nominal", "geometric", "final"]
        assert page.column(table, "rms_mm") == [f"{x:.4f}" for x in ba["rms_mm"]]
        assert {"p95_mm", "max_mm", "rms_shrink_pct"} <= set(page.tables[table]["keys"])
    worst = worst_test_poses(d)
    assert page.column("worst-table", "row") == [str(r) for r in worst["row"]]
    assert page.column("worst-table", "q1_deg") == [f"{x:.2f}" for x in worst["q1_deg"]]
    seq = d.sequence_frame()
    assert page.column("ranking-table", "effect") == list(seq["effect"])
    assert page.column("ranking-table", "p_value") == [f"{x:.2e}" for x in seq["p_value"]]
    gap = job.gap.to_frame()
    assert page.column("gap-table", "part") == list(gap["part"])
    assert len(page.images) == 3
    assert "No guard fired." in page.text("guards") if not d.guards else all(
        " ".join(pretty(g).split()) in page.text("guards") for g in d.guards)


def test_diagnosis_inputs_and_command(diagnosis):
    from tolalloc.cli import build_parser

    job, out, page = diagnosis
    inputs = page.kv("inputs")
    assert (inputs["alpha"], inputs["seed"], inputs["folds"], inputs["gap_split"]) == ("0.01", "1", "3", "True")
    args = shlex.split(page.text("command-cli"))
    assert args[:3] == ["tolalloc", "diagnose", "tool_changer"]
    ns = build_parser().parse_args(args[1:])
    d = job.diagnosis
    assert (ns.train, ns.test, ns.folds, ns.seed, ns.alpha, ns.gap_split, ns.report) == (
        d.train.source, d.test.source, 3, 1, 0.01, True, "DIR")


# ---------------------------------------------------------------------------------------------- screenshot
@pytest.mark.skipif(not CHROMIUM.exists(), reason="no headless Chromium at /usr/bin/chromium")
def test_screenshot_of_the_report(allocation, tmp_path):
    from matplotlib.image import imread

    _, out, _, _ = allocation
    png = tmp_path / "shot.png"
    html = tmp_path / "report.html"
    shutil.copy(out / "report.html", html)  # the file alone: nothing beside it is needed
    subprocess.run([str(CHROMIUM), "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                    "--hide-scrollbars", "--window-size=1200,1800", f"--screenshot={png}", html.as_uri()],
                   check=True, capture_output=True, timeout=120)
    img = imread(png)
    assert img.shape[0] == 1800 and img.shape[1] == 1200
    rgb = img[..., :3]
    assert rgb.std() > 0.1  # text, tables and the header band: far from a blank page
    colours = np.unique((rgb.reshape(-1, 3) * 255).astype(np.uint8), axis=0)
    assert len(colours) > 50
    band = rgb[20:120, 200:1000].mean(axis=(0, 1))  # the header band is the accent blue (#1f4e79)
    assert band[2] > band[0] + 0.15


def test_diagnosis_report_states_an_inconclusive_verdict_with_its_reasons(diagnosis, tmp_path):
    """A test file every model misses (shifted by 30 mm): the banner says INCONCLUSIVE, gives the verdict's reasons
    and the model that is safe to use, as the text and the JSON do."""
    job, out, _ = diagnosis
    folder = out.parent
    te = pd.read_csv(folder / "test.csv")
    te["x_mm"] += 30.0
    te.to_csv(tmp_path / "shifted.csv", index=False)
    shifted = diagnose_measurements("tool_changer", folder / "train.csv", tmp_path / "shifted.csv", folds=3, seed=1)
    v = shifted.diagnosis.verdict
    assert v.verdict == "inconclusive"
    shifted.save(tmp_path / "rep", report=True)
    page = Page((tmp_path / "rep" / "report.html").read_text(encoding="utf-8"))
    banner = page.text("verdict")
    assert banner.startswith("INCONCLUSIVE") and "NO EFFECT FOUND" not in banner
    assert "every model misses the test file" in banner.lower() and "Safe to use: " in banner


def test_an_input_named_in_the_record_and_by_the_run_is_listed_once():
    """coverage_n is in the call's record and in what the run used: the Inputs list shows it once, as used."""
    from tolalloc.report.html_allocation import _inputs_pairs

    pairs = _inputs_pairs({"robot": "tool_changer", "coverage_n": 100000, "seed": 0}, [("coverage_n", 5000), ("z", "2")])
    assert [k for k, _ in pairs] == ["robot", "coverage_n", "seed", "z"]
    assert dict(pairs)["coverage_n"] == "5000"


def test_the_monte_carlo_card_says_how_a_paired_estimate_relates_to_the_linear_p():
    """A paired estimate equal to the linear P is not a missing Monte Carlo: the card gives the disagreeing samples."""
    from types import SimpleNamespace

    from tolalloc.report.html_allocation import _paired_note

    ver = SimpleNamespace(estimator=np.array(["paired", "plain"]), n=np.array([10**6, 10**6]),
                          p_mc=np.array([0.96, 0.97]), n_discordant=np.array([3.0, 0.0]))
    assert "disagree on 3 of 1,000,000 samples" in _paired_note(ver, 0)
    assert _paired_note(ver, 1) == ""


def test_a_figure_a_plotting_function_saves_itself_carries_no_date():
    """writer_figure_item (the diagnosis report's figures: the plotting function calls savefig) drops the SVG metadata
    block, whose date made two reports of one diagnosis differ."""
    import base64

    import matplotlib.pyplot as plt

    from tolalloc.report.html import writer_figure_item

    def write(f):
        fig, ax = plt.subplots()
        ax.plot([1, 2, 3])
        fig.savefig(f, format="svg")
        plt.close(fig)

    svg = base64.b64decode(writer_figure_item(write, figure_id="a", caption="c")["uri"].split(",", 1)[1])
    assert b"<metadata>" not in svg and b"dc:date" not in svg and svg.startswith(b"<svg")


def test_the_banner_names_a_further_effect_with_its_tied_families():
    """An `effect` verdict with a further effect whose family the data cannot tell: the banner's word names the clear
    effect and, in brackets, the further one with its alternatives; its first line is the verdict's headline."""
    from types import SimpleNamespace

    from tolalloc.diagnose.verdict import Comparison, Verdict
    from tolalloc.report.html_diagnosis import _verdict

    tie = Comparison("backlash", "joint_compliance", 0.6, 1.0, 0.1, 0.101, False, 1.0)
    v = Verdict("effect", ("mount_compliance",), ("why",), "geometric+mount_compliance+backlash", (tie,),
                selected=("mount_compliance", "backlash"), further=("backlash",))
    block = pd.DataFrame({"model": ["nominal", "geometric", "final"], "rms_mm": [1.0, 0.2, 0.1],
                          "rms_shrink_pct": [0.0, 80.0, 90.0]})
    card = _verdict(SimpleNamespace(verdict=v, fallback=None, guards=(), test=None), block, "test")
    assert card["word"] == "EFFECT: mount_compliance + (backlash or joint_compliance)"
    assert card["lines"][0] == ("Verdict: mount_compliance; a further effect the data cannot attribute to one family: "
                                "backlash or joint_compliance.")
    plain = _verdict(SimpleNamespace(verdict=Verdict("effect", ("backlash",), (), "x"), fallback=None, guards=(),
                                     test=None), block, "test")
    assert plain["word"] == "EFFECT: backlash"


def test_the_diagnosis_repr_names_a_further_effect_apart_from_the_claimed_one():
    """The result's headline (its ``repr`` and notebook card) lists a further effect whose family is not claimed apart
    from the candidates, with its tied alternatives."""
    from types import SimpleNamespace

    from tolalloc.diagnose.verdict import Comparison, Verdict
    from tolalloc.workflows.diagnosis import MeasurementDiagnosis

    tie = Comparison("backlash", "joint_compliance", 0.6, 1.0, 0.1, 0.101, False, 1.0)
    v = Verdict("effect", ("mount_compliance",), ("why",), "geometric+mount_compliance+backlash", (tie,),
                selected=("mount_compliance", "backlash"), further=("backlash",))
    block = pd.DataFrame({"model": ["nominal", "geometric", "final"], "rms_mm": [1.0, 0.2, 0.1]})
    d = SimpleNamespace(verdict=v, effect="mount_compliance", robot=SimpleNamespace(name="ur10"), guards=(),
                        train=SimpleNamespace(n_poses=40), test=None, before_after=lambda which: block)
    lines = MeasurementDiagnosis(d).headline()
    assert lines[1] == ("verdict: effect   effect: mount_compliance   candidates: mount_compliance   further, family not "
                        "claimed: backlash or joint_compliance")
    assert "further" not in MeasurementDiagnosis(SimpleNamespace(**{**vars(d), "verdict": Verdict(
        "effect", ("backlash",), (), "x")})).headline()[1]
