"""Table I: the printed roots."""

from __future__ import annotations

import dataclasses
from decimal import ROUND_HALF_EVEN, Decimal
from fractions import Fraction as F

import mpmath
import pytest
import sympy as sp

from symbolic_friction import Parameters
from symbolic_friction._obligations.table1 import PRINTED_ROOTS, TableI, parse_printed_root

from ._helpers import assert_fails, assert_holds, replace_item, subject_fixture


subject = subject_fixture(TableI)


def _with_printed(subject, label, printed):
    return replace_item(subject, "cases", "label", label, printed=printed)


def _fails(altered, pattern):
    assert_fails(TableI(), altered, pattern)


def test_holds(subject):
    out = assert_holds(TableI(), subject)
    details = dict(out.details)
    assert "(the printed values are exact)" in details["\\text{case (b): rational roots}"]
    assert "\\left(2 s + 1\\right) \\left(5 s + 1\\right) \\left(5 s + 4\\right)" in "".join(details.values())


@pytest.mark.parametrize(
    "label, printed",
    [
        ("a", ("-6.02", "-0.19+0.79i", "-0.19-0.79i")),
        ("a", ("-6.01", "-0.19+0.80i", "-0.19-0.80i")),
        ("a", ("-6.01", "-0.20+0.79i", "-0.20-0.79i")),
        ("a", ("-6.01", "-0.19+0.79i", "-0.19+0.79i")),
        ("b", ("-0.8", "-0.5", "-0.3")),
        ("b", ("-0.8", "-0.8", "-0.2")),
    ],
)
def test_perturbed_digits_fail(subject, label, printed):
    _fails(_with_printed(subject, label, printed), f"case ({label}): the roots")


def test_more_digits_than_printed_still_decided(subject):
    # the true root −6.011649… does not round to −6.0117 but does to −6.0116
    _fails(_with_printed(subject, "a", ("-6.0117", "-0.19+0.79i", "-0.19-0.79i")), "do not round")
    assert TableI().verify(_with_printed(subject, "a", ("-6.0116", "-0.1942+0.7923i", "-0.1942-0.7923i"))).holds


def test_wrong_count_and_unreadable(subject):
    _fails(_with_printed(subject, "b", ("-0.8", "-0.5")), "2 printed roots for a degree-3 polynomial")
    _fails(_with_printed(subject, "b", ("-0.8", "-0.5", "minus 0.2")), "cannot read the printed root 'minus 0.2'")


def test_polynomial_must_be_the_characteristic_polynomial(subject):
    s = subject.s
    a = subject.cases[0]
    wrong = sp.Poly(s**3 + 7 * s**2 + 3 * s + 4, s)
    cases = (dataclasses.replace(a, polynomial=wrong),) + subject.cases[1:]
    _fails(dataclasses.replace(subject, cases=cases), "is not s³ + k_v s² + k_p s + k_i")
    # consistent but different gains: the printed roots no longer match
    cases = (dataclasses.replace(a, polynomial=wrong, k_v=sp.Integer(7)),) + subject.cases[1:]
    _fails(dataclasses.replace(subject, cases=cases), "case (a): the roots")


def test_parse_printed_root():
    assert parse_printed_root("-6.01") == (F(-601, 100), 2, F(0), 0)
    assert parse_printed_root("-0.19 + 0.79i") == (F(-19, 100), 2, F(79, 100), 2)
    with pytest.raises(ValueError, match="cannot read the printed root '1i'"):
        parse_printed_root("1i")
    with pytest.raises(ValueError, match="cannot read the printed root 'x'"):
        parse_printed_root("x")


@pytest.mark.parametrize("label", ["a", "b"])
def test_printed_digits_against_mpmath(label):
    """Independent reference: mpmath's polyroots at 50 digits, rounded half-even to the printed places."""
    p = Parameters.table_i(label)
    mpmath.mp.dps = 50
    coeffs = [1] + [mpmath.mpf(q.numerator) / q.denominator for q in (p.k_v, p.k_p, p.k_i)]
    roots = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200)
    got = []
    for r, printed in zip(sorted(roots, key=lambda z: (float(z.real), float(z.imag))), sorted(PRINTED_ROOTS[label], key=_key)):
        re_p, re_d, im_p, im_d = parse_printed_root(printed)
        q = lambda x, d: Decimal(mpmath.nstr(x, 45)).quantize(Decimal(1).scaleb(-d), rounding=ROUND_HALF_EVEN)
        got.append((q(r.real, re_d), q(r.imag, im_d)))
        assert (F(got[-1][0]), F(got[-1][1])) == (re_p, im_p), (r, printed)
    assert len(got) == 3


def _key(text):
    re_p, _, im_p, _ = parse_printed_root(text)
    return (float(re_p), float(im_p))
