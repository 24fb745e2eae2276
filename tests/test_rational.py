"""Exact parsing of user numbers."""

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symbolic_friction import format_rational, to_rational
from symbolic_friction.errors import InvalidNumberError, NonFiniteError


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("6.4", Fraction(32, 5)),
        ("32/5", Fraction(32, 5)),
        (" -0.66 ", Fraction(-33, 50)),
        ("1e-6", Fraction(1, 10**6)),
        (".5", Fraction(1, 2)),
        (7, Fraction(7)),
        (Fraction(3, 7), Fraction(3, 7)),
        (sp.Rational(3, 7), Fraction(3, 7)),
        (sp.Integer(4), Fraction(4)),
        (Decimal("0.08"), Fraction(2, 25)),
        (0.1, Fraction(1, 10)),
        (6.4, Fraction(32, 5)),
        (np.float64(0.66), Fraction(33, 50)),
        (np.int64(3), Fraction(3)),
    ],
)
def test_exact_values(value, expected):
    got = to_rational(value)
    assert got == expected and isinstance(got, Fraction)


def test_float_binary_only_on_request():
    assert to_rational(0.1) != Fraction(0.1)
    assert to_rational(0.1, binary=True) == Fraction(0.1)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf"), "nan", "inf", "-Infinity", Decimal("NaN"), sp.oo, sp.nan])
def test_non_finite(value):
    with pytest.raises(NonFiniteError, match="k_p must be finite"):
        to_rational(value, name="k_p")


@pytest.mark.parametrize("value", ["abc", "", "1/0", "6,4", True, None, [1], sp.Symbol("x"), sp.sqrt(2)])
def test_not_a_number(value):
    with pytest.raises(InvalidNumberError, match="k_i"):
        to_rational(value, name="k_i")


def test_zero_denominator_message():
    with pytest.raises(InvalidNumberError, match="zero denominator"):
        to_rational("3/0")


def test_sympy_float_goes_through_repr():
    assert to_rational(sp.Float(0.5)) == Fraction(1, 2)


def test_format_rational():
    assert format_rational(Fraction(32, 5)) == "32/5"
    assert format_rational(Fraction(-4)) == "-4"


def test_short_rational_keeps_messages_one_readable_line():
    from symbolic_friction._infra.rational import short_rational

    assert short_rational(Fraction(32, 5)) == "32/5"
    assert short_rational(Fraction(1, 10**300)) == "≈1e-300 (exact: a 301-digit denominator)"
    assert short_rational(Fraction(10**999)) == "≈1e+999 (exact: a 1000-digit numerator)"
    assert len(short_rational(Fraction(7**5000, 3**4000))) < 100  # beyond Python's 4300-digit str limit


def test_integers_beyond_the_str_limit_parse_and_print():
    from symbolic_friction._infra.rational import format_integer, parse_integer

    text = "9" * 12_345
    assert format_integer(parse_integer(text)) == text and parse_integer("-" + text) == -parse_integer(text)
