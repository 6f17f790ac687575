"""Sphinx extension: the API pages list every public module of a package, found when the documentation is built.

A page holds a marker ``<!-- api-modules: tolalloc.allocate -->`` (one or more package or module names); before
the page is parsed the marker is replaced by an ``automodule`` block for the package, documenting in full the names
it exports (its ``__all__``) under the package's name (``tolalloc.allocate.build_problem``), and, for every public
submodule (no ``_`` in its name), a section with its module docstring and a short entry for each other name it
exports: the first paragraph of its docstring (the stage's building blocks; ``help()`` shows the whole docstring),
still a target of cross-references. A module named in a marker itself (the foundation modules) is documented in
full. Names the top-level package exports (``tolalloc.allocate_tolerances``, the results and settings objects) are
left out here: the job pages document them under those names. A module added to a stage appears in the reference
without editing any page; ``tests/test_docs.py`` checks that the markers cover every public module.
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
            elif name == root:
                lines += [f"## `{name}`", "", "```{eval-rst}", f".. automodule:: {name}", *_excluded(top), "```", ""]
            else:
                lines += [f"## `{name}`", "", *_module_block(name), *_summary(name, at_package | top)]
    return "\n".join(lines)


def _module_block(name: str) -> list[str]:
    """A submodule's target (``py:module``) and its docstring as the section's text. The docstring is read from the
    imported module, not through autodoc, which would parse the module's source only to find its attribute comments
    (a third of the whole site's build over the stage pages' 200-odd submodules)."""
    import inspect

    doc = inspect.getdoc(importlib.import_module(name)) or ""
    return ["```{eval-rst}", f".. py:module:: {name}", "", *doc.splitlines(), "```", ""]


def _attribute_doc(module: str, name: str) -> str | None:
    """The ``#:`` comment above a module constant (what autodoc shows for it)."""
    from sphinx.pycode import ModuleAnalyzer

    try:
        docs = ModuleAnalyzer.for_module(module).find_attr_docs()
    except Exception:  # no source to read
        return None
    lines = docs.get(("", name))
    return "\n".join(lines).strip() if lines else None


def _summary(name: str, skip) -> list[str]:
    """Short entries for the names module ``name`` exports (its ``__all__``, less ``skip``): each a cross-reference
    target (``py:class``, ``py:function`` or ``py:data``) with the first paragraph of its docstring or ``#:``
    comment."""
    import inspect

    module = importlib.import_module(name)
    names = [n for n in getattr(module, "__all__", ()) if n not in skip]
    if not names:
        return []
    lines = ["```{eval-rst}", f".. py:currentmodule:: {name}", ""]
    for n in names:
        obj = getattr(module, n, None)
        kind = "class" if inspect.isclass(obj) else "function" if callable(obj) else "data"
        doc = inspect.getdoc(obj) if kind != "data" else _attribute_doc(name, n)
        first = (doc or f"A {type(obj).__name__}.").split("\n\n")[0]
        lines += [f".. py:{kind}:: {n}", "", *("   " + line for line in first.splitlines()), ""]
    return [*lines, "```", ""]


def _source_read(app, docname, source):
    source[0] = MARKER.sub(lambda m: expand(m.group(1)), source[0])


def setup(app):
    app.connect("source-read", _source_read)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
