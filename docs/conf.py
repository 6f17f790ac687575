"""Sphinx configuration of the tolalloc documentation.

Build (from the repository root, with the ``docs`` extra installed)::

    sphinx-build -W --keep-going -b html docs build/docs

Pages are Markdown (MyST); the API reference is generated from the numpydoc docstrings (autodoc + numpydoc); the
command-line reference from the argparse parsers (``_ext/cli_reference.py``). The tutorials are the percent-format
scripts ``docs/tutorials/*.py`` themselves, read by jupytext and executed by myst-nb at every build, so their pages
show the output and the figures of the code they show. The build runs them with ``--quick`` (small sample counts);
``TOLALLOC_DOCS_FULL=1`` runs them with their full counts. Their result files go to ``_tutorial_output/<name>/`` of
the built site (the reports page shows the HTML reports written there; ``tests/test_docs.py`` checks the results).
"""

import os

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
    "myst_nb",                  # MyST pages, and the tutorials as notebooks executed at build time
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",   # MathJax served from the site itself: the formulas render offline
    "numpydoc",
    "numpydoc_template_once",   # after numpydoc: its docstring template compiled once, not once per object
    "cli_reference",
    "api_pages",
]
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**/__pycache__", "conf.py", "howto/*.py", "**/tutorial_output"]

# the tutorials: percent-format scripts read by jupytext, executed at every build; a failing cell fails the build
nb_custom_formats = {".py": ["jupytext.reads", {"fmt": "py:percent"}]}
nb_execution_mode = "force"
nb_execution_timeout = 1800
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_output_stderr = "remove"     # progress bars; the results are on stdout
nb_merge_streams = True
# the UR10 tutorial reads ../shared/data (never copied into the repository); where it is absent the page shows the
# code without output
_UR10_DATA = next((f for f in HERE.parents if (f / "shared" / "data" / "ipa-ur10").is_dir()), None)
nb_execution_excludepatterns = [] if _UR10_DATA is not None else ["tutorials/ur10.py"]

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


def _tutorial_environment(app):
    """The tutorials' arguments (``--quick`` unless TOLALLOC_DOCS_FULL=1; with it the numpy engine) and where they
    write their files; the notebook kernels inherit the environment."""
    quick = os.environ.get("TOLALLOC_DOCS_FULL") != "1"
    os.environ.setdefault("TOLALLOC_TUTORIAL_ARGS", "--quick" if quick else "")
    if quick:
        # --quick's sample counts are small enough that the numpy engine beats loading the compiled kernels (and,
        # in a fresh checkout, waiting for their first compile); both engines draw the same samples and agree to
        # rounding
        os.environ.setdefault("TOLALLOC_NUMBA", "0")
    os.environ.setdefault("TOLALLOC_TUTORIAL_OUT", str(Path(app.outdir) / "_tutorial_output"))


def setup(app):
    app.connect("builder-inited", _tutorial_environment)
