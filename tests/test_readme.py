"""The README's promises: two quick-start commands, the CI runs the test one; the robot-file and costs-file examples
(in the how-to pages the README links to) load."""

import re
import tomllib
from pathlib import Path

import numpy as np

from tolalloc import load_robot
from tolalloc.allocate.costs import load_costs
from tolalloc.errormodel import build_error_model
from tolalloc.robot.io import robot_from_dict

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()
#: the repository (pyproject's Source URL); the README links its files by absolute URLs, which work on a package index
REPO = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["urls"]["Source"]
REPO_FILES = f"{REPO}/blob/main/"
REPO_RAW = REPO.replace("https://github.com/", "https://raw.githubusercontent.com/") + "/main/"


def repo_file(url: str) -> Path | None:
    """The file of this checkout that a README link into the repository names (None: a link elsewhere)."""
    for prefix in (REPO_FILES, REPO_RAW):
        if url.startswith(prefix):
            return ROOT / url[len(prefix):]
    return None
#: the pages that hold the robot-file and costs-file examples (docs/howto, linked from the README)
EXAMPLE_PAGES = [ROOT / "docs" / "howto" / "own-robot.md", ROOT / "docs" / "howto" / "costs-file.md"]


def _quickstart_commands():
    section = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```bash\n(.*?)```", section, flags=re.S)
    return [line for b in blocks for line in b.splitlines() if line.strip() and not line.startswith("#")]


def _toml_blocks():
    text = README + "".join(page.read_text() for page in EXAMPLE_PAGES)
    return re.findall(r"```toml\n(.*?)```", text, flags=re.S)


def test_quickstart_has_exactly_two_commands_one_main_job_one_tests():
    cmds = _quickstart_commands()
    assert len(cmds) == 2
    assert "tolalloc allocate tool_changer" in cmds[0]
    assert "pytest" in cmds[1]
    for c in cmds:
        assert c.startswith("python3 -m venv .venv")


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text()
    assert _quickstart_commands()[1] in ci


def test_robot_file_example_loads_and_matches_hand_computation():
    block = next(b for b in _toml_blocks() if 'name = "demo_arm"' in b)
    robot = robot_from_dict(tomllib.loads(block), "README example")
    assert [j.name for j in robot.joints] == ["shoulder", "slide"]
    assert robot.poses("working").shape == (3, 2)
    # home: base (0,0,400) + upper arm (600,0,0) + forearm (250,0,0) + tool (0,0,-50)
    np.testing.assert_allclose(robot.home[:3, 3], [850, 0, 350], atol=1e-12)
    # at q = (0 deg, 100 mm) the slide adds 100 mm along x
    np.testing.assert_allclose(robot.fk_internal(np.array([0.0, 100.0]))[:3, 3], [950, 0, 350], atol=1e-9)
    model = build_error_model(robot, "shop")
    assert model.names == ["dbase", "dupper_arm", "dforearm", "dth1", "dd2", "e1x", "e1z"]
    np.testing.assert_allclose(model.sigma[3], np.deg2rad(0.005))


def test_costs_file_example_loads(tmp_path):
    block = next(b for b in _toml_blocks() if "[kinds.joint_drive]" in b)
    path = tmp_path / "costs.toml"
    path.write_text(block)
    model = build_error_model(load_robot("tool_changer"))
    costs = load_costs(path, model)
    assert costs.z == 3
    assert dict(zip(costs.names, costs.role))["dth6"] == "fixed"
    frame = costs.to_frame(model)
    assert len(frame) == len(model.names)


def test_python_example_is_the_tested_one():
    from test_workflows import PYTHON_EXAMPLE

    blocks = re.findall(r"```python\n(.*?)```", README, flags=re.S)
    assert PYTHON_EXAMPLE in blocks
    assert len(PYTHON_EXAMPLE.strip().splitlines()) <= 15


def test_example_pages_are_linked_from_the_readme():
    for page in EXAMPLE_PAGES:
        assert f"]({REPO_FILES}{page.relative_to(ROOT).as_posix()})" in README


def test_the_figure_is_shown_from_the_repository():
    figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", README)
    assert figures and all(f.startswith(REPO_RAW) and repo_file(f).is_file() for f in figures), figures
