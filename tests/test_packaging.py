"""The package as released: one version (pyproject.toml) shown by ``tolalloc --version`` and ``__version__``, PEP 639
licence metadata, the ``py.typed`` marker, the lazily loaded top-level names visible to type checkers, a cheap
``import tolalloc``, and a changelog in the agreed shape."""

from __future__ import annotations

import ast
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import tolalloc
from tolalloc.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_the_version_is_written_once_and_shown_everywhere(capsys):
    version = PYPROJECT["project"]["version"]
    assert tolalloc.__version__ == version
    assert main(["--version"]) == 0 and capsys.readouterr().out == f"tolalloc {version}\n"
    with pytest.raises(SystemExit) as stop:  # the full parser's --version (listed in --help) says the same
        build_parser().parse_args(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out == f"tolalloc {version}\n"
    literal = re.compile(r"""__version__\s*=\s*["']|^\s*version\s*=\s*["']\d""", re.M)  # not <?xml version="1.0"?>
    assert not [p for p in (ROOT / "tolalloc").rglob("*.py") if literal.search(p.read_text())]


def test_an_uninstalled_source_tree_reports_the_fallback(monkeypatch):
    import importlib.metadata

    from tolalloc.version import FALLBACK, package_version

    def missing(name):
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "version", missing)
    package_version.cache_clear()
    try:
        assert tolalloc.__version__ == FALLBACK == "0+unknown"
    finally:
        package_version.cache_clear()


def test_licence_metadata_and_typing_marker():
    project = PYPROJECT["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text().startswith("MIT License\n\nCopyright (c) 2026 the tolalloc developers\n")
    assert not [c for c in project["classifiers"] if c.startswith("License ::")]  # PEP 639: the expression only
    assert "setuptools>=77" in PYPROJECT["build-system"]["requires"]
    assert "py.typed" in PYPROJECT["tool"]["setuptools"]["package-data"]["tolalloc"]
    assert (ROOT / "tolalloc" / "py.typed").is_file()
    assert {"Homepage", "Source", "Issues", "Changelog"} <= set(project["urls"])


def test_type_checkers_see_every_lazily_loaded_name():
    tree = ast.parse((ROOT / "tolalloc" / "__init__.py").read_text())
    block = next(n for n in tree.body if isinstance(n, ast.If) and getattr(n.test, "id", "") == "TYPE_CHECKING")
    seen = {}
    for node in block.body:
        if isinstance(node, ast.ImportFrom):
            seen.update({a.asname or a.name: node.module for a in node.names})
    assert set(seen) == set(tolalloc.__all__)
    for name, module in seen.items():  # the same object the lazy loading gives
        assert getattr(__import__(module, fromlist=[name]), name) is getattr(tolalloc, name), name


def test_import_tolalloc_stays_cheap():
    code = "import sys, tolalloc; tolalloc.__version__; print(sorted({'numpy', 'scipy', 'pandas'} & set(sys.modules)))"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                         env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert run.stdout.strip() == "[]", run.stderr


def test_the_changelog_has_an_unreleased_section_in_the_agreed_shape():
    text = (ROOT / "CHANGELOG.md").read_text()
    unreleased = text.split("## [Unreleased]\n", 1)[1].split("\n## ", 1)[0]
    headings = re.findall(r"^### (\w+)$", unreleased, re.M)
    order = ["Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"]  # Keep a Changelog's kinds, in order
    assert headings and headings == sorted(set(headings), key=order.index), headings
    assert all(line.startswith(("- ", "  ", "### ")) for line in unreleased.strip().splitlines() if line), unreleased
