"""The SMT encoder's Horner text: its shortcuts (one monomial, integer numerals) write what the plain steps write."""

from __future__ import annotations

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symbolic_friction._obligations._smt import _encode


def _plain(terms, names, var=0):
    """The Horner form by its definition alone (the encoder before its shortcuts): the reference."""
    if not terms:
        return "0"
    while var < len(names) and all(m[var] == 0 for m, _ in terms):
        var += 1
    if var == len(names):
        return _number(sp.Integer(sum(c for _, c in terms)))
    groups = {}
    for m, c in terms:
        groups.setdefault(m[var], []).append((m, c))
    x, out, prev = names[var], "", 0
    for d in sorted(groups, reverse=True):
        coeff = _plain(groups[d], names, var + 1)
        out = coeff if not out else f"(+ {coeff} {_encode._app('*', [x] * (prev - d) + [out])})"
        prev = d
    return _encode._app("*", [x] * prev + [out]) if prev else out


def _number(q):
    """A rational's SMT-LIB text, as the encoder wrote it on sympy numbers (the reference)."""
    p, d = abs(int(q.p)), int(q.q)
    text = str(p) if d == 1 else f"(/ {p} {d})"
    return f"(- {text})" if q < 0 else text


_polynomials = st.integers(1, 4).flatmap(lambda n: st.dictionaries(
    st.tuples(*[st.integers(0, 4)] * n), st.integers(-10**30, 10**30).filter(bool), max_size=12))


@settings(max_examples=300, deadline=None)
@given(_polynomials)
def test_horner_writes_what_its_definition_writes(poly):
    n = len(next(iter(poly))) if poly else 2
    names = [f"x{i}" for i in range(n)]
    terms = sorted(poly.items())
    assert _encode._horner(terms, names) == _plain(terms, names)


def test_numbers_are_written_as_sympy_rationals_were():
    for p, q in [(0, 1), (5, 1), (-5, 1), (3, 7), (-3, 7), (-(10**40), 3)]:
        text = _encode._number(sp.Rational(p, q))
        assert text == _encode._ratio(p, q) == _number(sp.Rational(p, q))
        assert sp.Rational(p, q) == _value(text)


def test_a_monomial_keeps_its_variables_innermost_last():
    assert _encode._horner([((2, 0, 1), -3)], ["x", "y", "z"]) == "(* x x (* z (- 3)))"
    assert _encode._horner([((0, 0, 0), 4)], ["x", "y", "z"]) == "4"


def _value(text):
    text = text.replace("(- ", "(-1 * ").replace("(/ ", "(Rational ")
    import re

    m = re.fullmatch(r"\(-1 \* (.*)\)", text)
    sign, text = (-1, m.group(1)) if m else (1, text)
    m = re.fullmatch(r"\(Rational (\d+) (\d+)\)", text)
    return sign * (sp.Rational(int(m.group(1)), int(m.group(2))) if m else sp.Integer(int(text)))
