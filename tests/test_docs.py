"""The documentation cannot rot: it builds without a warning, every tutorial runs, and what it quotes is checked.

* the README's docs-build command (``sphinx-build -W``) runs (skipped only where the ``docs`` extra is missing);
* every script under docs/tutorials and docs/howto runs with ``--quick`` and its results are checked;
* the pages that repeat the README (quick-start commands, Python example) repeat it verbatim;
* every public module is in the API reference, every relative link and included cell exists.
"""

from __future__ import annotations

import importlib.util
import pkgutil
import re
import runpy
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import tolalloc

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = (ROOT / "README.md").read_text()
PAGES = sorted(DOCS.rglob("*.md"))
SCRIPTS = sorted([*DOCS.glob("tutorials/*.py"), *DOCS.glob("howto/*.py")])
DOCS_EXTRA = ("sphinx", "myst_parser", "numpydoc", "furo", "sphinx-mathjax-offline")


def _section(text: str, title: str) -> str:
    return text.split(f"## {title}", 1)[1].split("\n## ", 1)[0]


def _bash_commands(section: str) -> list[str]:
    blocks = re.findall(r"```bash\n(.*?)```", section, flags=re.S)
    return [line for b in blocks for line in b.splitlines() if line.strip() and not line.startswith("#")]


def docs_build_command() -> str:
    """The README's documentation build command (Development section)."""
    lines = [c for c in _bash_commands(_section(README, "Development")) if "sphinx-build" in c]
    assert len(lines) == 1, "the README's Development section names one sphinx-build command"
    return lines[0]


def ur10_data() -> Path | None:
    """shared/data/ipa-ur10 in a folder above the repository (where the tutorial looks), or None."""
    for folder in ROOT.parents:
        if (folder / "shared" / "data" / "ipa-ur10").is_dir():
            return folder / "shared" / "data" / "ipa-ur10"
    return None


# ---------------------------------------------------------------------------------------------- the build
@pytest.mark.slow
def test_docs_build_strict_with_no_warning(tmp_path):
    missing = [m for m in DOCS_EXTRA if importlib.util.find_spec(m) is None]
    if missing:
        pytest.skip(f"the docs extra is not installed (missing {', '.join(missing)}): pip install -e '.[docs]'")
    argv = shlex.split(docs_build_command(), comments=True)
    assert Path(argv[0]).name == "sphinx-build" and "-W" in argv
    out = tmp_path / "html"
    argv = [sys.executable, "-m", "sphinx", *argv[1:-1], str(out), "-d", str(tmp_path / "doctrees")]
    run = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "WARNING" not in run.stderr and "ERROR" not in run.stderr, run.stderr[-3000:]
    cli = (out / "cli.html").read_text()
    for flag in ("--radius-mm", "--region", "--estimator", "--test-frame", "--n-poses"):  # generated from the parsers
        assert flag in cli, flag
    workflows = (out / "api" / "workflows.html").read_text()
    # numpydoc rendered the entries (docs/_ext/numpydoc_template_once.py replaces its per-object template set-up)
    entry = workflows.split('id="tolalloc.workflows.allocation.allocate_tolerances"', 1)[1][:20000]
    assert "Parameters" in entry and "Returns" in entry
    assert 'id="tolalloc.linear.covariance.LinearResult"' in (out / "api" / "linear.html").read_text()
    assert (out / "_static" / "mathjax" / "tex-chtml.js").is_file()  # formulas render without the network


# ---------------------------------------------------------------------------------------------- tutorials
def _run_script(path: Path, argv: list[str], monkeypatch) -> dict:
    monkeypatch.setattr(sys, "argv", [str(path), *argv])
    saved = list(sys.path)
    try:
        return runpy.run_path(str(path), run_name="__main__")
    finally:
        sys.path[:] = saved


def test_every_script_has_a_test():
    assert {p.stem for p in SCRIPTS} == {"allocate", "analyze", "simulate", "calibration", "diagnose", "ur10",
                                         "own_robot"}


def test_tutorial_allocate(tmp_path, monkeypatch):
    g = _run_script(DOCS / "tutorials" / "allocate.py", ["--quick", "--out", str(tmp_path)], monkeypatch)
    res = g["res"]
    assert res.status == "optimal" and res.ok and res.verdict == "demonstrated"
    assert res.region is not None and res.coverage.n_below == 0
    assert len(g["table"]) == 22 and set(g["table"]["unit"]) == {"mm", "deg"}
    assert "summary.json" in g["files"] and (tmp_path / "tolerances.csv").is_file()
    # every summary.json key that "Read the report" documents is in the summary of this real run
    page = (DOCS / "howto" / "read-report.md").read_text()
    table = _section(page, "The files").split("### summary.json", 1)[1].split("\n## ", 1)[0]
    documented = {k for row in re.findall(r"^\| (`.*?`(?:, `.*?`)*) \|", table, flags=re.M)
                  for k in re.findall(r"`(\w+)`", row)}
    assert len(documented) >= 25
    assert documented <= set(res.summary()), sorted(documented - set(res.summary()))
    # every kind of line of the printed excerpt is still printed (the numbers are the page's run's)
    excerpt = re.search(r"```text\n(.*?)```", _section(page, "What the allocation prints"), flags=re.S).group(1)
    text = res.text()
    labels = [m.group(1) for m in (re.match(r"([a-zA-Z][a-zA-Z ]*?)(:| \()", line.strip())
                                   for line in excerpt.splitlines()) if m]
    assert len(labels) >= 10
    for label in labels:
        assert label in text, label


def test_tutorial_analyze(tmp_path, monkeypatch):
    g = _run_script(DOCS / "tutorials" / "analyze.py", ["--quick", "--out", str(tmp_path)], monkeypatch)
    a = g["a"]
    assert a.linear.n_poses == 12
    # reports/tool_changer_allocation/README.md, section 2: at most 2.47e-05; r for p = 0.95 is 30.7-38.3 mm
    assert a.linear.p_within(0.25).max() == pytest.approx(2.47e-5, rel=0.01)
    r95 = a.linear.radius_for(0.95)
    assert r95.min() == pytest.approx(30.7, abs=0.05) and r95.max() == pytest.approx(38.3, abs=0.05)
    kinds = a.budget_frame(by="kind")
    assert kinds["share_norm_pct"].sum() == pytest.approx(100.0)
    assert set(kinds["kind"].iloc[:2]) == {"joint_drive", "axis_deflection"}   # what the page says dominates
    assert (tmp_path / "analyze.json").is_file()


def test_tutorial_simulate(tmp_path, monkeypatch):
    g = _run_script(DOCS / "tutorials" / "simulate.py", ["--quick", "--out", str(tmp_path)], monkeypatch)
    sim, lin = g["sim"], g["lin"]
    for r in (25.0, 35.0):  # the linear-Gaussian P lies in the seeded Monte Carlo's 95 % interval
        _, low, high = sim.mc.p_within[r][0]
        assert low <= lin.p_within(r)[0] <= high
    assert g["probs"]["radius_mm"].dropna().tolist() == [25.0, 35.0]   # the page's table: one row per radius
    with pytest.raises(tolalloc.TolallocError, match=r"^radius 0.3 mm was not simulated; simulated radii: 25 mm, 35 mm\. "
                                                     r"Simulate it with radius_mm=\[25, 35, 0.3\]"):  # as the page quotes
        sim.mc.p_within[0.3]
    ring, ring_lin = g["ring"], g["ring_lin"]
    for r in (0.5, 1.0):  # the ring: the linear-Gaussian P is far outside the Monte Carlo interval
        p, low, high = ring.mc.p_within[r][0]
        se = (high - low) / (2 * 1.96)
        assert abs(p - ring_lin.p_within(r)[0]) > 5 * se
    est = g["est"]
    assert est.estimator[0] == "paired"
    assert est.ci_high[0] - est.ci_low[0] < 0.2 * (est.plain_high[0] - est.plain_low[0])
    assert est.plain_low[0] <= est.p_hat[0] <= est.plain_high[0]   # the same draws: paired inside the plain interval


@pytest.mark.slow
def test_tutorial_calibration(tmp_path, monkeypatch):
    g = _run_script(DOCS / "tutorials" / "calibration.py", ["--quick", "--out", str(tmp_path)], monkeypatch)
    plan, res, table = g["plan"], g["res"], g["table"]
    assert plan.plan.n_poses == 12 and "# measurement = position" in (tmp_path / "plan.csv").read_text()
    assert {"dth1", "e1x", "e1y"} <= set(plan.unidentifiable)         # the page names them
    assert {"calibrated away", "must be held"} <= set(table["status"])
    s = res.summary()
    assert res.ok and s["cost"] < s["cost_no_calibration"]
    # the page's account of what runs and of the unidentifiable parameters
    assert res.stages() == "certified -> exact -> standard grades" and s["design"] == "exact"
    assert s["unidentifiable_held"] == ["dl1", "dl2", "dth1", "dth5", "e1x", "e1y", "e2z"]
    assert s["unidentifiable_loose"] == ["dl4", "dl5", "dd4", "dth6", "e6x", "e6y"]
    assert g["files"] == ["tolerances.csv", "tolerances.md", "tolerances.tex", "summary.json", "verification.csv"]
    # every column and summary key the calibrated part of "Read the report" names is in this run's output
    page = _section((DOCS / "howto" / "read-report.md").read_text(), "The calibration-aware allocation")
    tables = re.findall(r"^\| (`.*?`(?:, `.*?`)*) \|", page, flags=re.M)
    documented = {k for row in tables for k in re.findall(r"`(\w+)`", row)}
    assert len(documented) >= 20
    assert documented <= set(res.to_frame().columns) | set(s), sorted(documented - set(s))


def test_tutorial_diagnose(tmp_path, monkeypatch):
    g = _run_script(DOCS / "tutorials" / "diagnose.py", ["--quick", "--out", str(tmp_path)], monkeypatch)
    d, case = g["d"], g["case"]
    assert d.effect == case.effect == "joint_compliance"
    rms = d.to_frame().set_index("model")["rms_mm"]
    assert rms["final"] < rms["geometric"] < 0.1 * rms["nominal"]
    assert (tmp_path / "report" / "report.md").is_file() and (tmp_path / "predictions.csv").is_file()


@pytest.mark.slow
def test_tutorial_ur10_real_data(tmp_path, monkeypatch):
    data = ur10_data()
    if data is None:
        pytest.skip(f"the UR10 data folder shared/data/ipa-ur10 is absent above {ROOT} (read-only shared data, "
                    "never copied into the repository)")
    g = _run_script(DOCS / "tutorials" / "ur10.py", ["--quick", "--data", str(data), "--out", str(tmp_path)],
                    monkeypatch)
    within = g["within"].to_frame().set_index("model")["rms_mm"]
    # the data set's README: a geometric fit on one session roughly halves the held-out error
    assert 0.5 < within["nominal"] < 1.3 and within["geometric"] < 0.75 * within["nominal"]
    across = g["across"]
    assert across.diagnosis.test_frame == "refit" and any("extrapolation" in x for x in across.diagnosis.guards)
    assert not list(tmp_path.rglob("measurements_*.csv"))     # results only, never a copy of the data


def test_costs_file_page_examples_load(tmp_path):
    from tolalloc.allocate.costs import load_costs
    from tolalloc.errormodel import build_error_model
    from tolalloc.workflows.calibrated import split_from_costs

    model = build_error_model(tolalloc.load_robot("tool_changer"))
    blocks = re.findall(r"```toml\n(.*?)```", (DOCS / "howto" / "costs-file.md").read_text(), flags=re.S)
    assert len(blocks) == 4
    for i, block in enumerate(blocks):
        path = tmp_path / f"costs_{i}.toml"
        path.write_text(block)
        costs = load_costs(path, model)                 # every block is a valid costs file on its own
        split = split_from_costs(model, path)
        if "[processes." in block:
            assert {p.name for p in costs.spec(model.index("dl1")).processes} == {"grinding", "milling"}
        if "repeatability_deg = 0.0005" in block:       # the kind's repeatability, a parameter's own, e2y random
            assert split.random_sigma[model.index("dth2")] == pytest.approx(np.deg2rad(0.0005))
            assert split.random_sigma[model.index("dth6")] == pytest.approx(np.deg2rad(0.001))
            assert not split.systematic[model.index("e2y")] and split.systematic[model.index("e2z")]


def test_howto_own_robot_python_chain_is_the_toml_example(monkeypatch):
    g = _run_script(DOCS / "howto" / "own_robot.py", ["--quick"], monkeypatch)
    from tolalloc.robot.io import robot_from_dict

    page = (DOCS / "howto" / "own-robot.md").read_text()
    block = next(b for b in re.findall(r"```toml\n(.*?)```", page, flags=re.S) if 'name = "demo_arm"' in b)
    toml_robot = robot_from_dict(tomllib.loads(block), "own-robot.md example")
    demo = g["demo"]
    for q in ([0, 0], [20, 100], [45, 300], [-60, 250]):
        np.testing.assert_allclose(demo.fk(q), toml_robot.fk(q), atol=1e-9)
    ur10 = tolalloc.load_robot("ur10")
    for q in ([0, -90, 0, -90, 0, 0], [10, -60, 45, 20, -30, 90]):   # the DH rows are the built-in UR10's table
        np.testing.assert_allclose(g["arm"].fk(q)[:3, 3], ur10.fk(q)[:3, 3], atol=1e-6)
    assert g["res"].ok


# ---------------------------------------------------------------------------------------------- consistency
def test_getting_started_repeats_the_readme():
    from test_workflows import PYTHON_EXAMPLE

    page = (DOCS / "getting-started.md").read_text()
    assert _bash_commands(_section(page, "The two quick-start commands")) == _bash_commands(_section(README, "Quick start"))
    assert PYTHON_EXAMPLE in re.findall(r"```python\n(.*?)```", page, flags=re.S)


def test_readme_is_a_front_page():
    """Short, and every link and figure works on a package index page too: absolute URLs into the repository
    (pyproject's ``Source``), each naming a file that exists here."""
    from test_readme import REPO_FILES, repo_file

    assert len(README.splitlines()) <= 150
    assert docs_build_command()
    targets = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README)
    assert len(targets) > 30
    for target in targets:
        assert target.startswith(("http://", "https://")), f"relative link {target!r}: use {REPO_FILES}{target}"
        path = repo_file(target)
        assert path is None or path.exists(), target


def test_every_public_module_is_in_the_api_reference():
    spec = importlib.util.spec_from_file_location("api_pages", DOCS / "_ext" / "api_pages.py")
    api_pages = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(api_pages)
    text = "".join(p.read_text() for p in (DOCS / "api").glob("*.md"))
    documented = set(re.findall(r"\.\. automodule:: ([\w.]+)", text))
    for names in api_pages.MARKER.findall(text):
        documented |= set(re.findall(r"\.\. automodule:: ([\w.]+)", api_pages.expand(names)))
    public = {"tolalloc"}
    for info in pkgutil.walk_packages(tolalloc.__path__, "tolalloc."):
        parts = info.name.split(".")
        if parts[1] != "cli" and not any(p.startswith("_") for p in parts[1:]):
            public.add(info.name)
    assert public <= documented, f"add to a marker of docs/api/*.md: {sorted(public - documented)}"
    assert documented <= public, sorted(documented - public)
    index = (DOCS / "api" / "index.md").read_text()
    assert all(f"`{name}`" in index or f"`tolalloc.{name}`" in index for name in tolalloc.__all__), \
        [n for n in tolalloc.__all__ if f"`{n}`" not in index and f"`tolalloc.{n}`" not in index]


def test_relative_links_and_included_cells_exist():
    for page in PAGES:
        text = page.read_text()
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text):
            if not target.startswith(("http://", "https://", "mailto:")):
                assert (page.parent / target).exists(), f"{page.relative_to(ROOT)}: {target}"
        for script, options in re.findall(r"```\{literalinclude\} (\S+)\n(.*?)```", text, flags=re.S):
            source = (page.parent / script).read_text()
            for marker in re.findall(r':(?:start-after|end-before): "(.*?)"', options):
                assert marker in source, f"{page.relative_to(ROOT)}: {script} has no {marker!r}"
