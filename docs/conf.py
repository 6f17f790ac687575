"""Sphinx configuration of the tolalloc documentation.

Build (from the repository root, with the ``docs`` extra installed)::

    sphinx-build -W --keep-going -b html docs build/docs

Pages are Markdown (MyST); the API reference is generated from the numpydoc docstrings (autodoc + numpydoc); the
command-line reference from the argparse parsers (``_ext/cli_reference.py``); tutorials include the scripts in
``docs/tutorials/`` that the test suite runs (``tests/test_docs.py``).
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent))

import tolalloc  # noqa: E402

project = "tolalloc"
author = "the tolalloc authors"
copyright = "tolalloc authors, MIT licence"
release = version = tolalloc.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",   # MathJax served from the site itself: the formulas render offline
    "numpydoc",
    "numpydoc_template_once",   # after numpydoc: its docstring template compiled once, not once per object
    "cli_reference",
    "api_pages",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**/__pycache__"]

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

autodoc_member_order = "bysource"
# The pages' own contents list their headings (one per module on the API pages), not every documented function and
# class: those lists made each page's navigation copy thousands of entries (a sixth of the build).
toc_object_entries = False
autodoc_typehints = "none"
autodoc_default_options = {"members": True, "show-inheritance": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# quotes and ellipses only: "--flag" in help texts and docstrings stays two hyphens
smartquotes_action = "qe"

html_theme = "furo"
html_title = f"tolalloc {release}"
html_show_sourcelink = False
