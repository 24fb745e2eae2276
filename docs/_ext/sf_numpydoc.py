"""numpydoc with its docstring template compiled once per build, not once per docstring.

numpydoc renders every docstring it reads (about 700 in this site: once for the text, once for the
signature) through one Jinja template, ``numpydoc_docstring.rst``; its ``get_doc_object`` makes a new
Jinja environment and compiles that template on each call, about a tenth of the whole build's time.
This extension hands numpydoc the same function with the compiled template kept: one per kind of loader
(Sphinx's, when numpydoc passes the builder; a plain file loader otherwise), built exactly as numpydoc
builds it, so every page is byte for byte what numpydoc alone writes.  Where numpydoc's module no
longer has the pieces this relies on, numpydoc is left as it is (slower, the same pages).
"""

from __future__ import annotations

import os
from typing import Any

__all__ = ["setup"]


def _cached_get_doc_object():
    """numpydoc's ``get_doc_object`` with the template kept across calls; None if numpydoc changed shape."""
    from numpydoc import docscrape_sphinx as sphinx_doc
    from numpydoc import numpydoc as extension

    names = ("get_doc_object_orig", "SphinxClassDoc", "SphinxFunctionDoc", "SphinxObjDoc", "BuiltinTemplateLoader",
             "FileSystemLoader", "SandboxedEnvironment")
    if not all(hasattr(sphinx_doc, name) for name in names) or not hasattr(extension, "get_doc_object"):
        return None
    templates: dict[Any, Any] = {}

    def template(builder):
        key = id(builder) if builder is not None else None
        if key not in templates:
            dirs = [os.path.join(os.path.dirname(sphinx_doc.__file__), "templates")]
            if builder is not None:
                loader = sphinx_doc.BuiltinTemplateLoader()
                loader.init(builder, dirs=dirs)
            else:
                loader = sphinx_doc.FileSystemLoader(dirs)
            templates[key] = (builder, sphinx_doc.SandboxedEnvironment(loader=loader).get_template("numpydoc_docstring.rst"))
        return templates[key][1]

    def get_doc_object(obj, what=None, doc=None, config=None, builder=None):
        if config is None:
            config = {}
        config["template"] = template(builder)
        return sphinx_doc.get_doc_object_orig(obj, what=what, doc=doc, config=config, class_doc=sphinx_doc.SphinxClassDoc,
                                              func_doc=sphinx_doc.SphinxFunctionDoc, obj_doc=sphinx_doc.SphinxObjDoc)

    return get_doc_object


def setup(app):
    app.setup_extension("numpydoc")
    cached = _cached_get_doc_object()
    if cached is not None:
        from numpydoc import numpydoc as extension

        extension.get_doc_object = cached  # the name numpydoc's event handlers call
    return {"parallel_read_safe": True, "parallel_write_safe": True}
