"""Sphinx extension: numpydoc renders every docstring with one template environment per builder.

numpydoc's ``get_doc_object`` builds a new Jinja environment and compiles its docstring template for every object
it documents (about 1,900 here), about a sixth of the documentation build. This extension, listed after
``numpydoc``, replaces the function numpydoc's Sphinx hooks call by one that compiles the template once per builder
and otherwise does exactly what numpydoc does (same loader, same template, same document classes): the HTML is
byte-for-byte the same. ``tests/test_docs.py`` checks that class and function entries are still rendered.
"""

from __future__ import annotations

import functools
from pathlib import Path


def setup(app):
    import numpydoc.numpydoc as hooks
    from numpydoc import docscrape
    from numpydoc import docscrape_sphinx as sphinx_doc

    @functools.lru_cache(maxsize=None)
    def template(builder):
        dirs = [str(Path(sphinx_doc.__file__).parent / "templates")]
        if builder is None:
            loader = sphinx_doc.FileSystemLoader(dirs)
        else:
            loader = sphinx_doc.BuiltinTemplateLoader()
            loader.init(builder, dirs=dirs)
        return sphinx_doc.SandboxedEnvironment(loader=loader).get_template("numpydoc_docstring.rst")

    def get_doc_object(obj, what=None, doc=None, config=None, builder=None):
        config = {} if config is None else config
        config["template"] = template(builder)
        return docscrape.get_doc_object(obj, what=what, doc=doc, config=config, class_doc=sphinx_doc.SphinxClassDoc,
                                        func_doc=sphinx_doc.SphinxFunctionDoc, obj_doc=sphinx_doc.SphinxObjDoc)

    hooks.get_doc_object = get_doc_object
    return {"parallel_read_safe": True, "parallel_write_safe": True}
