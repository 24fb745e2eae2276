"""The runnable examples in the certificate modules' docstrings are correct."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "symbolic_friction._certify.certificate",
    "symbolic_friction._certify.search",
    "symbolic_friction._certify.rounding",
    "symbolic_friction._certify.verify",
    "symbolic_friction._certify.report",
    "symbolic_friction._certify.pipeline",
    "symbolic_friction._certify.sweep",
    "symbolic_friction._progress",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0, f"{result.failed} failing example(s) in {name}"
