"""Sphinx extension: the API pages list every public module of a package, found when the documentation is built.

A page holds a marker ``<!-- api-modules: tolalloc.allocate -->`` (one or more package or module names); before
the page is parsed the marker is replaced by an ``automodule`` block for the package's own docstring and, for every
public submodule (no ``_`` in its name), a section with its ``automodule``. A module added to a stage appears in the
reference without editing any page; ``tests/test_docs.py`` checks that the markers cover every public module.
"""

from __future__ import annotations

import importlib
import pkgutil
import re

MARKER = re.compile(r"<!-- api-modules: ([\w. ]+?) -->")


def public_modules(name: str) -> list[str]:
    """``name`` and, for a package, its public submodules in name order (``cli`` and ``_private`` ones left out)."""
    module = importlib.import_module(name)
    out = [name]
    if hasattr(module, "__path__"):
        for info in pkgutil.walk_packages(module.__path__, name + "."):
            parts = info.name.split(".")
            if "cli" not in parts and not any(p.startswith("_") for p in parts[1:]):
                out.append(info.name)
    return out


def expand(names: str) -> str:
    """The MyST text that replaces one marker."""
    lines = []
    for root in names.split():
        is_package = hasattr(importlib.import_module(root), "__path__")
        for name in public_modules(root):
            if name == root and is_package:
                lines += ["```{eval-rst}", f".. automodule:: {name}", "   :no-members:", "```", ""]
            else:
                lines += [f"## `{name}`", "", "```{eval-rst}", f".. automodule:: {name}", "```", ""]
    return "\n".join(lines)


def _source_read(app, docname, source):
    source[0] = MARKER.sub(lambda m: expand(m.group(1)), source[0])


def setup(app):
    app.connect("source-read", _source_read)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
