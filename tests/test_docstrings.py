"""Every runnable example in the package's docstrings is correct.

One test per module of the package (found by walking it, so a new module is
covered without editing this file).  ``python -m pytest --doctest-modules``
would do the same but imports modules in a way that trips the lazy
``__init__``; ``doctest.testmod`` on the imported module does not.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil

import pytest

import symbolic_friction

MODULES = ["symbolic_friction"] + sorted(
    m.name
    for m in pkgutil.walk_packages(symbolic_friction.__path__, prefix="symbolic_friction.")
    if not m.name.endswith("__main__")
)

# Curated names whose runnable examples live in the docstring of a public task module
# (their defining modules' docstrings are kept as they are): name -> that module.
EXAMPLES_ELSEWHERE = {
    "run_obligations": "symbolic_friction.obligations",
    "all_obligations": "symbolic_friction.obligations",
    "all_errata": "symbolic_friction.obligations",
    "verify_file": "symbolic_friction.certificates",
    "load_certificate": "symbolic_friction.certificates",
    "write_certificate": "symbolic_friction.certificates",
    "Certificate": "symbolic_friction.certificates",
    "VerificationReport": "symbolic_friction.certificates",
}


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


def _examples(obj, name) -> list:
    return [e for t in doctest.DocTestFinder(recurse=False).find(obj, name) for e in t.examples]


def test_the_curated_api_has_numpydoc_examples():
    # every function and class of __all__ shows how it is called, in an Examples section run above
    missing = []
    for name in symbolic_friction.__all__:
        obj = getattr(symbolic_friction, name)
        if name == "__version__" or inspect.ismodule(obj) or not callable(obj):
            continue
        if name in EXAMPLES_ELSEWHERE:
            home = importlib.import_module(EXAMPLES_ELSEWHERE[name])
            ok = f"{name}(" in home.__doc__ or f"sf.{name}" in home.__doc__
        else:
            ok = "Examples\n" in (inspect.getdoc(obj) or "") and bool(_examples(obj, name))
        if not ok:
            missing.append(name)
    assert missing == [], f"no numpydoc Examples for {missing}"


def test_the_examples_check_can_fail(monkeypatch):
    def bare():
        """No examples."""

    monkeypatch.setattr(symbolic_friction, "__all__", [*symbolic_friction.__all__, "bare"])
    monkeypatch.setattr(symbolic_friction, "bare", bare, raising=False)
    with pytest.raises(AssertionError, match=r"no numpydoc Examples for \['bare'\]"):
        test_the_curated_api_has_numpydoc_examples()
