"""claim1.cases: a stick branch's duration ``T`` must be *shown* positive (Claim 1 needs ``[0, T]``, ``T > 0``).

Row (iv) (``v̄ = 0, φ̄ = f_c, σ̄ = 0``, an equilibrium) is the input where only the duration can be wrong:
its friction selection is the constant ``w = 1`` and ``V = V_0`` holds at every time, so a finite ``T`` of
undecided sign, or ``T = 0``, is refused by the duration premise alone (an undecided sign never means proved).
"""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import pos
from symbolic_friction._obligations.claim1 import Claim1Cases, stick_duration_error

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_item

claim1 = obligation_fixture(Claim1Cases)


def _with_row_iv_duration(subject, T):
    row = next(r for r in subject.rows if r.label == "iv")
    return replace_item(subject, "rows", "label", "iv", stick=(dataclasses.replace(row.stick[0], T=T),))


def test_row_iv_with_a_long_positive_duration_still_holds(claim1):
    """The control: a finite ``T`` shown positive is accepted (the equilibrium holds on any ``[0, T]``)."""
    ob, subject = claim1
    assert_holds(ob, _with_row_iv_duration(subject, 2 * pos("a_dur") / pos("b_dur")))


@pytest.mark.parametrize("T", [pos("a_dur") - pos("b_dur"), sp.Symbol("T_dur", real=True), sp.Integer(0)],
                         ids=["a - b", "a real symbol", "zero"])
def test_a_stick_duration_not_shown_positive_fails(claim1, T):
    ob, subject = claim1
    out = assert_fails(ob, _with_row_iv_duration(subject, T), "not shown positive")
    assert out.reason.startswith("row (iv)")


def test_stick_duration_error_decides_the_sign_itself():
    a, b = pos("a_dur"), pos("b_dur")
    assert stick_duration_error(sp.oo) is None
    assert stick_duration_error(2 * a / b) is None
    for T in (a - b, sp.Integer(0), -a, sp.Symbol("T_dur", real=True)):
        assert "is not shown positive" in stick_duration_error(T)
