"""Sphinx extension: the API pages list every public module of a package, found when the documentation is built.

A page holds a marker ``<!-- api-modules: tolalloc.allocate -->`` (one or more package or module names); before
the page is parsed the marker is replaced by an ``automodule`` block for the package, documenting the names it
exports (its ``__all__``) under the package's name (``tolalloc.allocate.build_problem``), and, for every public
submodule (no ``_`` in its name), a section with its ``automodule`` and the members the package does not export.
Names the top-level package exports (``tolalloc.allocate_tolerances``, the results and settings objects) are left out
here: the job pages document them under those names. A module added to a stage appears in the reference without
editing any page; ``tests/test_docs.py`` checks that the markers cover every public module.
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


def _excluded(names) -> list[str]:
    return ["   :exclude-members: " + ", ".join(sorted(names))] if names else []


def expand(names: str) -> str:
    """The MyST text that replaces one marker."""
    import tolalloc

    top = set(tolalloc.__all__)
    lines = []
    for root in names.split():
        package = importlib.import_module(root)
        modules = public_modules(root)
        exported = set(getattr(package, "__all__", ())) if hasattr(package, "__path__") else set()
        # a name that is also a submodule's (tolalloc.allocate.discretize) is documented in that module
        at_package = exported - top - {m.rsplit(".", 1)[-1] for m in modules}
        for name in modules:
            if name == root and hasattr(package, "__path__"):
                lines += ["```{eval-rst}", f".. automodule:: {name}",
                          *(["   :members:", *_excluded(exported - at_package)] if at_package else ["   :no-members:"]),
                          "```", ""]
            else:
                lines += [f"## `{name}`", "", "```{eval-rst}", f".. automodule:: {name}", *_excluded(at_package | top),
                          "```", ""]
    return "\n".join(lines)


def _source_read(app, docname, source):
    source[0] = MARKER.sub(lambda m: expand(m.group(1)), source[0])


def setup(app):
    app.connect("source-read", _source_read)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
