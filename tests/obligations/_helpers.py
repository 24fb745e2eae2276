"""Scaffolding shared by the obligation tests.

Each obligation is derived once per test module; a test alters the subject
(a flipped sign, a perturbed entry, a wrong constant …) and asserts that the
check reports failure and says why.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest
import sympy as sp


def obligation_fixture(cls: type) -> Any:
    """A module-scoped fixture giving ``(obligation, derived subject)`` for the obligation class ``cls``."""

    @pytest.fixture(scope="module")
    def fixture():
        ob = cls()
        return ob, ob.derive()

    return fixture


def subject_fixture(cls: type) -> Any:
    """A module-scoped fixture giving the derived subject of the obligation class ``cls``."""

    @pytest.fixture(scope="module")
    def fixture():
        return cls().derive()

    return fixture


def assert_fails(ob: Any, subject: Any, *fragments: str) -> Any:
    """Verify an altered ``subject``: the check must fail and its reason name every fragment.

    Returns the outcome, for further assertions.
    """
    out = ob.verify(subject)
    assert out.holds is False, f"the altered subject passed: {out.reason}"
    for fragment in fragments:
        assert fragment in out.reason, f"{fragment!r} is not in the reason {out.reason!r}"
    return out


def with_entry(matrix: Any, i: int, j: int, value: Any, *, symmetric: bool = False) -> sp.ImmutableMatrix:
    """A copy of ``matrix`` with entry ``(i, j)`` (and ``(j, i)`` if ``symmetric``) set to ``value``."""
    m = sp.Matrix(matrix)
    m[i, j] = value
    if symmetric:
        m[j, i] = value
    return sp.ImmutableMatrix(m)


def replace_key(subject: Any, field: str, key: Any, value: Any) -> Any:
    """``subject`` with entry ``key`` of its dict ``field`` (``sgn``, ``V``, ``f`` …) set to ``value``."""
    changed = dict(getattr(subject, field))
    changed[key] = value
    return dataclasses.replace(subject, **{field: changed})


def replace_item(subject: Any, field: str, attribute: str, match: Any, **changes: Any) -> Any:
    """``subject`` with the items of its tuple ``field`` whose ``attribute`` equals ``match`` altered by ``changes``."""
    items = tuple(
        dataclasses.replace(item, **changes) if getattr(item, attribute) == match else item for item in getattr(subject, field)
    )
    return dataclasses.replace(subject, **{field: items})


def assert_holds(ob: Any, subject: Any) -> Any:
    """Verify ``subject``: the check must hold (its reason is shown otherwise). Returns the outcome."""
    out = ob.verify(subject)
    assert out.holds, out.reason
    return out
