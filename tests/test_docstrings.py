"""Every runnable example in the package's docstrings is correct.

One test per module of the package (found by walking it, so a new module is
covered without editing this file).  ``python -m pytest --doctest-modules``
would do the same but imports modules in a way that trips the lazy
``__init__``; ``doctest.testmod`` on the imported module does not.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import symbolic_friction

MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(symbolic_friction.__path__, prefix="symbolic_friction.")
    if not m.name.endswith("__main__")
)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0, f"{result.failed} failing example(s) in {name}"


def test_examples_exist_where_the_api_is():
    # The user-facing modules must carry runnable examples, not just prose.
    for name in ("symbolic_friction._infra.rational", "symbolic_friction._model.parameters", "symbolic_friction._model.lyapunov",
                 "symbolic_friction._simulation.affine", "symbolic_friction._certify.search"):
        tests = doctest.DocTestFinder().find(importlib.import_module(name))
        assert sum(len(t.examples) for t in tests) > 0, name
